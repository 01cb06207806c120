"""Benchmark: the full vehicle (4 wheelsets, a co-running track under each) vs one wheelset.

Run: ``python benchmarks/bench_vehicle_passage.py [--route R] [--x-start X] [--x-end X]
[--speed V] [--layers 2 3]`` (default: the whole turnout, through route, 100 km/h, 2 and 3
layers). Each case runs once (profile contact, h = 1e-4 s): the single-wheelset passage
(:func:`exudyn_turnout.passage.run.simulate_passage`) and the full Manchester vehicle
(:func:`exudyn_turnout.passage.run.simulate_passage`), plus a short
run (0.5 m) of each to separate the fixed cost (building the systems, static solves) from the
cost per step: "marginal us/step" is (wall - wall_short) / (steps - steps_short). "cpu s" is
the process's CPU time of the run (less sensitive than wall time to other processes on a
shared machine). For the full vehicle: Newton iterations per step and Jacobian evaluations
of the whole run (Exudyn's solver statistics, summed over the run's segments). The contact
tables are loaded and the compiled contact kernel warmed up before, untimed. Issue 13's
target: the 3-layer full vehicle at most 1.0 x real time. Every run alternates with the
yardstick (``benchmarks/yardstick.py``); "yardstick" is the whole run's wall time in its
units, the number that carries over between machines and loads.

``--phases`` measures instead the README's full-vehicle case (issue 24: 3-layer, through
route, 100 km/h, front wheelset -5..60 m, 2.34 s simulated; ``--repeats`` runs, medians)
in three parts, each in CPU seconds, x real time and yardstick units (its CPU time over
the yardstick runs' around it): the set-up (from the call to the first time step: the
Exudyn systems, the static solves of the four tracks, the start at speed), the stepping
(every segment's ``SolveDynamic``, with the compiled residual calls inside), and the rest
(the segments' rebuilds and carry-overs, the columns, the summary); with residual
calls, Newton iterations per step and Jacobian evaluations.

Measured (issue 24; 2 cores shared with five other jobs, load 5-7, so CPU seconds scatter
by +-30 %: compare the yardstick units of runs made side by side). Commit 4e6e5d3 and
this code alternately, three rounds of ``--phases --repeats 3`` each, medians per round:

==========  ======================  ======================
part        4e6e5d3 (yardstick)     now (yardstick)
==========  ======================  ======================
set-up      0.37 / 0.33 / 0.40      0.33 / 0.28 / 0.32
stepping    15.16 / 14.33 / 13.83   15.99 / 13.88 / 16.74
rest        4.60 / 4.38 / 4.24      3.13 / 2.68 / 3.20
total       20.29 / 19.00 / 18.66   19.40 / 17.17 / 20.31
==========  ======================  ======================

Residual calls per step 2.48 -> 2.30, Newton iterations per step 1.482 -> 1.296, Jacobians
47 -> 42. Instructions (callgrind, which the load does not change; front wheelset -5..16 m,
7,560 steps): whole passage 5.81e9 -> 5.15e9 (-11 %), stepping 4.46e9 -> 4.23e9 (-5 %), of
it the residual evaluations 3.85e9 -> 3.66e9, everything else but the solves 1.23e9 ->
0.80e9 (-35 %: the output columns' contacts are recorded during the run instead of
evaluated again). On a quiet machine the case cost 1.05 x real time at 4e6e5d3 (set-up
0.04 s, stepping 1.84 s, rest 0.55 s); the issue's goal, 0.5 x, is not reached: the
residual evaluations are ~86 % of the stepping, and one of them (~30 us) is ~5 us of
Exudyn's own, ~6 us passing Exudyn's two 103-coordinate lists to Python and back, ~5.5 us
packing them into the kernel's buffer and returning a list, ~8.5 us the numba residual.

Later (issue 24, the residual's views, recording and Python frame, the safety checks'
sliding means; forces and summary bit-identical): 3273b6f and the new code alternately in
fresh processes, ``--phases --repeats 1`` each, 7 rounds, medians (load 3-4), CPU s:
stepping 1.123 -> 1.044, rest 0.225 -> 0.173, total 1.377 -> 1.246 (0.588 -> 0.532 x real
time; 18.0 -> 17.1 yardstick units, the yardstick itself bimodal that day: 0.074 or
0.116 s). The goal, 0.5 x real time on a quiet machine, is within reach but not shown.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time
from dataclasses import replace

import exudyn as exu
from yardstick import Yardstick, machine_line

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.inputs.vehicle_model import load_vehicle_model
from exudyn_turnout.passage.contact.vehicle_contacts import VehicleContacts
from exudyn_turnout.passage.corunning_track import vehicle as full_vehicle_passage
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings


class _NewtonCount:
    """Sums Exudyn's Newton statistics over the full vehicle's run segments."""

    def __init__(self):
        self.steps = self.iterations = self.jacobians = 0
        self._run = full_vehicle_passage._run

    def __enter__(self):
        def counted(system, *args, **kwargs):
            cols = self._run(system, *args, **kwargs)
            it = system.mbs.sys["dynamicSolver"].it
            self.steps += it.currentStepIndex
            self.iterations += it.newtonStepsCount
            self.jacobians += it.newtonJacobiCount
            return cols

        full_vehicle_passage._run = counted
        return self

    def __exit__(self, *exc):
        full_vehicle_passage._run = self._run


def _timed(stick, run, settings) -> tuple[float, float, int, _NewtonCount, float]:
    with _NewtonCount() as count:
        timing = stick.measure(lambda: run(settings), repeats=1, warm_up=False)
    result = timing.result
    return timing.seconds, timing.cpu_seconds, len(result.columns["t_s"]) - 1, count, timing.units


class _Phases:
    """CPU time of the set-up, the stepping and the rest of a full-vehicle passage."""

    def __init__(self):
        self.start = self.first_step = math.nan
        self.stepping = 0.0
        self.calls = 0
        self._solve = exu.MainSystem.SolveDynamic
        self._function = VehicleContacts.force_function

    def __enter__(self):
        def solve(mbs, *args, **kwargs):
            t0 = time.process_time()
            if math.isnan(self.first_step):
                self.first_step = t0
            try:
                return self._solve(mbs, *args, **kwargs)
            finally:
                self.stepping += time.process_time() - t0

        def function(contacts):
            force = self._function(contacts)

            def counted(*args):
                self.calls += 1
                return force(*args)

            return counted

        exu.MainSystem.SolveDynamic = solve
        VehicleContacts.force_function = function
        return self

    def __exit__(self, *exc):
        exu.MainSystem.SolveDynamic = self._solve
        VehicleContacts.force_function = self._function


def phases(repeats: int) -> None:
    """Print the full-vehicle case's set-up, stepping and rest (module docstring)."""
    turnout, model = load_turnout(), load_vehicle_model()
    # Exudyn's integrator (its solver's timers and counters; the compiled stepper, the
    # default since issue 24: benchmarks/bench_stepper.py)
    case = PassageSettings(
        route="through", speed_kmh=100.0, x_start=-5.0, x_end=60.0, solver="exudyn"
    )
    simulate_passage(turnout, replace(case, x_end=-4.9), model)  # tables, kernels: untimed
    simulated = (case.x_end - case.x_start) / case.v
    stick = Yardstick()
    stick.run()
    rows: dict[str, list[float]] = {"set-up": [], "stepping": [], "rest": [], "total": []}
    units: dict[str, list[float]] = {k: [] for k in rows}
    counts = []
    for _ in range(repeats):
        with _NewtonCount() as newton, _Phases() as part:
            t0 = time.process_time()
            simulate_passage(turnout, case, model)
            total = time.process_time() - t0
        stick.run()
        cpu = {
            "set-up": part.first_step - t0,
            "stepping": part.stepping,
            "rest": total - (part.first_step - t0) - part.stepping,
            "total": total,
        }
        scale = 0.5 * sum(stick.cpu_times[-2:])
        for key, value in cpu.items():
            rows[key].append(value)
            units[key].append(value / scale)
        counts.append(
            (part.calls / newton.steps, newton.iterations / newton.steps, newton.jacobians)
        )
    print(
        f"full Manchester vehicle, 3-layer, through, 100 km/h, x -5..60 m ({simulated:.2f} s "
        f"simulated), median of {repeats} runs, CPU time"
    )
    print(f"{'part':<10}{'CPU s':>8}{'x real time':>13}{'yardstick':>11}")
    for key, values in rows.items():
        cpu = statistics.median(values)
        print(f"{key:<10}{cpu:>8.3f}{cpu / simulated:>13.3f}{statistics.median(units[key]):>11.2f}")
    calls, iterations, jacobians = counts[-1]
    print(
        f"residual calls per step {calls:.2f}, Newton iterations per step {iterations:.3f}, "
        f"Jacobians {jacobians}"
    )
    print(f"yardstick CPU median {stick.cpu_median:.3f} s; {machine_line()}")


def main() -> None:
    """Print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--route", default="through")
    parser.add_argument("--x-start", type=float, default=None, help="front wheelset start (m)")
    parser.add_argument("--x-end", type=float, default=None, help="front wheelset end (m)")
    parser.add_argument("--speed", type=float, default=100.0, help="km/h")
    parser.add_argument("--layers", type=int, nargs="+", default=[2, 3], choices=[2, 3])
    parser.add_argument("--phases", action="store_true", help="set-up, stepping, rest")
    parser.add_argument("--repeats", type=int, default=3, help="runs of --phases")
    args = parser.parse_args()
    if args.phases:
        phases(args.repeats)
        return
    turnout, model = load_turnout(), load_vehicle_model()
    x_a = turnout.x_min if args.x_start is None else args.x_start
    x_b = turnout.x_max if args.x_end is None else args.x_end
    base = PassageSettings(  # Exudyn's integrator (its counters; bench_stepper.py: both)
        route=args.route, speed_kmh=args.speed, x_start=x_a, x_end=x_b, solver="exudyn"
    )
    warm = replace(base, x_end=x_a + 0.05)
    simulate_passage(turnout, warm, "wheelset")  # contact tables, compiled kernel: untimed
    simulate_passage(turnout, warm, model)
    stick = Yardstick()
    simulated = (x_b - x_a) / base.v
    print(f"{args.route} route, front wheelset x {x_a:g} .. {x_b:g} m, {args.speed:g} km/h, ")
    print(f"h = 1e-4 s, {simulated:.3f} s simulated")
    print(
        f"{'case':<30}{'steps':>7}{'wall s':>8}{'cpu s':>7}{'us/step':>9}{'marginal':>10}"
        f"{'x real time':>12}{'yardstick':>10}{'Newton/step':>12}{'Jacobians':>10}"
    )
    cases = (
        ("1 wheelset", lambda s: simulate_passage(turnout, s, "wheelset")),
        ("4 wheelsets (full vehicle)", lambda s: simulate_passage(turnout, s, model)),
    )
    for layers in args.layers:
        settings = replace(base, layers=layers)
        for label, run in cases:
            wall_0, _, steps_0, _, _ = _timed(stick, run, replace(settings, x_end=x_a + 0.5))
            wall, cpu, steps, count, units = _timed(stick, run, settings)
            marginal = 1e6 * (wall - wall_0) / max(steps - steps_0, 1)
            newton = (
                f"{count.iterations / count.steps:>12.2f}{count.jacobians:>10d}"
                if count.steps
                else f"{'-':>12}{'-':>10}"
            )
            print(
                f"{label + f', {layers}L':<30}{steps:>7}{wall:>8.2f}{cpu:>7.2f}"
                f"{1e6 * wall / steps:>9.1f}{marginal:>10.1f}{wall / simulated:>12.2f}"
                f"{units:>10.2f}{newton}"
            )
    print(f"yardstick median {stick.median:.3f} s; {machine_line()}")


if __name__ == "__main__":
    main()
