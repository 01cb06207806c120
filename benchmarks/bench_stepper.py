"""Benchmark: the full vehicle's passage with Exudyn's integrator and the compiled stepper.

Run: ``python benchmarks/bench_stepper.py [--repeats N] [--x-start X] [--x-end X] [--route
R] [--speed KMH] [--layers N]`` (default: the README's full-vehicle case, 3-layer, through
route, 100 km/h, front wheelset x -5..60 m, 2.34 s simulated, one run of each solver per
round; the diverging route's check rail: ``--route diverging --speed 80 --x-start 20 --x-end
55``, the predicted fine pieces stopped by each solver's own stop). Each round runs the
yardstick, the passage with ``solver="exudyn"``, the yardstick, the passage with
``solver="compiled"``, the yardstick (``benchmarks/yardstick.py``): per solver the whole
passage's CPU seconds (median over the rounds), x real time, yardstick units (its CPU time
over the mean of the two yardstick runs around it, median), the CPU seconds of the stepping
alone (Exudyn's ``SolveDynamic`` or the compiled stepper, every segment, median), and of the
stepping: steps, Newton iterations per step, residual calls per step (Exudyn: calls of the
force object's function during ``SolveDynamic``, its initial accelerations included;
compiled: the same count from the stepper) and iteration matrices (Jacobians). Then the
largest difference between the two solvers' peaks: |Fz| and |Fy| of every wheel of every
wheelset at the switch (that wheelset's x 5..15 m) and at the crossing (x 44..50 m), in
percent of Exudyn's peak. The contact tables are loaded and the kernels warmed up before,
untimed.

Measured (2 cores shared with other jobs, load 6-7; three runs of ``--repeats 3`` during the
work, the last on the final code; the seconds scatter: compare the units and the ratios):

========  ==============  =================  ==============  ===========================
solver    CPU s           yardstick units    stepping CPU s  it/step, calls/step, Jacs
========  ==============  =================  ==============  ===========================
exudyn    2.08/2.79/2.13  18.82/16.47/18.48  1.67/2.30/1.78  1.308, 2.308, 15
compiled  1.57/1.54/1.25  11.37/10.15/10.73  1.13/1.03/0.85  1.308, 2.308, 15
========  ==============  =================  ==============  ===========================

The whole passage -40 % (units 0.58-0.62 of Exudyn's), its stepping 1.5-2.2x faster (the
rest, set-up, columns and summary, ~0.45 s, is the same code); the same Newton iterations,
residual calls and Jacobians as Exudyn's, every one of the 24 switch and crossing peaks of
|Fz| within 0.01 N and of |Fy| within 0.22 N (0.012 %).

Issue 24, the compiled stepper the default (its stop for the check rail's fine piece; its
record of the contacts used, no longer given up at the start), load 1.3-1.8, medians:

==========================================  =========  =========  ==============  ========
case (``--repeats``)                        exudyn     compiled   ratio (units)   peaks
==========================================  =========  =========  ==============  ========
README case, through 100 km/h, 3-layer (5)  0.488 x    0.321 x    0.628           0.017 %
diverging 80 km/h, 2-layer, 20..55 m (3)    1.037 x    0.862 x    0.849           4e-12
diverging 80 km/h, 3-layer, 20..55 m (3)    1.102 x    0.948 x    0.843           1e-11
==========================================  =========  =========  ==============  ========

(x real time of the whole passage; peaks: the largest relative difference of the wheel-region
peaks, on the diverging route the check rail's Fy peak; the same refined, predicted and
re-run windows.) On the diverging route the shares both solvers pay alike are larger: the
start's dynamic relaxation in the curve (Exudyn's ``SolveDynamic``, counted as stepping
here) and the body loads of every time, interpolated in Python (~24 us a time under cProfile,
4x the times in the fine pieces).
"""

from __future__ import annotations

import argparse
import statistics
import time
from dataclasses import replace

import exudyn as exu
import numpy as np
from yardstick import Yardstick, machine_line

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.inputs.vehicle_model import load_vehicle_model
from exudyn_turnout.passage.contact.vehicle_contacts import VehicleContacts
from exudyn_turnout.passage.corunning_track import stepper
from exudyn_turnout.passage.corunning_track import vehicle as full_vehicle_passage
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings

#: m, the regions of the peaks compared (each wheelset's own x)
REGIONS = {"switch": (5.0, 15.0), "crossing": (44.0, 50.0)}


class _Counts:
    """Steps, Newton iterations, Jacobians and residual calls of every run segment."""

    def __init__(self):
        self.steps = self.iterations = self.jacobians = self.calls = 0
        self.stepping = 0.0  #: s, CPU time in SolveDynamic or the stepper
        self._run = full_vehicle_passage._run
        self._solve = exu.MainSystem.SolveDynamic
        self._integrate = stepper.integrate
        self._function = VehicleContacts.force_function
        self._live = [0]

    def __enter__(self):
        live = self._live

        def function(contacts):
            force = self._function(contacts)

            def counted(*args):
                live[0] += 1
                return force(*args)

            return counted

        def counted_run(system, *args, **kwargs):
            before = live[0]
            cols = self._run(system, *args, **kwargs)
            run = system.mbs.variables.get(full_vehicle_passage.STEPPER_KEY)
            if run is not None:
                self.steps += run.steps
                self.iterations += run.iterations
                self.jacobians += run.jacobians
                self.calls += run.residuals
            else:
                it = system.mbs.sys["dynamicSolver"].it
                self.steps += it.currentStepIndex - 1
                self.iterations += it.newtonStepsCount
                self.jacobians += it.newtonJacobiCount
                self.calls += live[0] - before
            return cols

        def timed(function):
            def call(*args, **kwargs):
                t0 = time.process_time()
                try:
                    return function(*args, **kwargs)
                finally:
                    self.stepping += time.process_time() - t0

            return call

        full_vehicle_passage._run = counted_run
        VehicleContacts.force_function = function
        exu.MainSystem.SolveDynamic = timed(self._solve)
        stepper.integrate = timed(self._integrate)
        return self

    def __exit__(self, *exc):
        full_vehicle_passage._run = self._run
        VehicleContacts.force_function = self._function
        exu.MainSystem.SolveDynamic = self._solve
        stepper.integrate = self._integrate


def peaks(columns, n_wheelsets: int = 4) -> dict[str, float]:
    """Peak |Fz|, |Fy| of every wheel (N) in each region of :data:`REGIONS`.

    Parameters
    ----------
    columns : mapping
        A full-vehicle passage's columns.
    n_wheelsets : int

    Returns
    -------
    dict
        ``"<region> F<z|y>_ws<k>_<wheel>"`` -> N.
    """
    out = {}
    for k in range(1, n_wheelsets + 1):
        x = np.asarray(columns[f"x_ws{k}_m"])
        for region, (lo, hi) in REGIONS.items():
            inside = (x >= lo) & (x <= hi)
            for force in ("Fz", "Fy"):
                for wheel in ("left", "right"):
                    values = np.asarray(columns[f"{force}_ws{k}_{wheel}_N"])[inside]
                    if values.size:
                        out[f"{region} {force}_ws{k}_{wheel}"] = float(np.nanmax(np.abs(values)))
    return out


def main() -> None:
    """Print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=1, help="rounds (medians)")
    parser.add_argument("--x-start", type=float, default=-5.0, help="front wheelset start (m)")
    parser.add_argument("--x-end", type=float, default=60.0, help="front wheelset end (m)")
    parser.add_argument("--route", default="through", help="through or diverging")
    parser.add_argument("--speed", type=float, default=100.0, help="km/h")
    parser.add_argument("--layers", type=int, default=3, help="co-running track layers")
    args = parser.parse_args()
    turnout, model = load_turnout(), load_vehicle_model()
    case = PassageSettings(
        route=args.route,
        speed_kmh=args.speed,
        layers=args.layers,
        x_start=args.x_start,
        x_end=args.x_end,
    )
    for solver in ("exudyn", "compiled"):  # tables, kernels: untimed
        simulate_passage(turnout, replace(case, x_end=case.x_start + 0.1, solver=solver), model)
    simulated = (case.x_end - case.x_start) / case.v
    stick = Yardstick()
    stick.run()
    cpu: dict[str, list[float]] = {"exudyn": [], "compiled": []}
    stepping: dict[str, list[float]] = {"exudyn": [], "compiled": []}
    units: dict[str, list[float]] = {"exudyn": [], "compiled": []}
    counts, results = {}, {}
    for _ in range(args.repeats):
        for solver in ("exudyn", "compiled"):
            with _Counts() as count:
                t0 = time.process_time()
                results[solver] = simulate_passage(turnout, replace(case, solver=solver), model)
                seconds = time.process_time() - t0
            stick.run()
            cpu[solver].append(seconds)
            stepping[solver].append(count.stepping)
            units[solver].append(seconds / (0.5 * sum(stick.cpu_times[-2:])))
            counts[solver] = count
    print(
        f"full Manchester vehicle, {case.layers}-layer, {case.route}, {case.speed_kmh:g} km/h, "
        f"x {case.x_start:g}..{case.x_end:g} m "
        f"({simulated:.2f} s simulated), median of {args.repeats} round(s), CPU time of the "
        "whole passage"
    )
    print(
        f"{'solver':<10}{'CPU s':>8}{'x real':>8}{'units':>8}{'stepping s':>12}{'steps':>8}"
        f"{'it/step':>9}{'calls/step':>12}{'Jacobians':>11}"
    )
    for solver in ("exudyn", "compiled"):
        c = counts[solver]
        seconds = statistics.median(cpu[solver])
        print(
            f"{solver:<10}{seconds:>8.3f}{seconds / simulated:>8.3f}"
            f"{statistics.median(units[solver]):>8.2f}"
            f"{statistics.median(stepping[solver]):>12.3f}{c.steps:>8d}"
            f"{c.iterations / c.steps:>9.3f}{c.calls / c.steps:>12.3f}{c.jacobians:>11d}"
        )
    ratios = [c / e for c, e in zip(units["compiled"], units["exudyn"])]
    print(
        f"compiled / exudyn per round (units): median {statistics.median(ratios):.3f}, "
        f"rounds {' '.join(f'{r:.3f}' for r in ratios)}"
    )
    summaries = results["exudyn"].summary, results["compiled"].summary
    print(f"stepping: exudyn {summaries[0]['stepping']!r}, compiled {summaries[1]['stepping']!r}")
    for key in ("check_rail_predicted", "check_rail_refined", "check_rail_rerun"):
        print(f"{key}: {'the same' if summaries[0][key] == summaries[1][key] else 'DIFFERENT'}")
    check = [abs(s.get("peak_Fy_check_rail_N") or 0.0) for s in summaries]
    if check[0] > 0.0:
        print(
            f"check-rail Fy peak: exudyn {check[0]:.3f} N, compiled {check[1]:.3f} N "
            f"(relative {abs(check[1] - check[0]) / check[0]:.2e})"
        )
    a, b = peaks(results["exudyn"].columns), peaks(results["compiled"].columns)
    if not a:
        print("no wheel in the peaks' regions")
        return
    worst = max(a, key=lambda k: abs(b[k] - a[k]) / a[k])
    print(
        f"largest peak difference (|Fz|, |Fy| of {len(a)} wheel-region peaks): "
        f"{100 * abs(b[worst] - a[worst]) / a[worst]:.4f} % ({worst}: exudyn {a[worst]:.1f} N, "
        f"compiled {b[worst]:.1f} N)"
    )
    for force in ("Fz", "Fy"):
        keys = [k for k in a if f" {force}_" in k]
        print(
            f"  {force}: largest {max(100 * abs(b[k] - a[k]) / a[k] for k in keys):.4f} %, "
            f"largest absolute {max(abs(b[k] - a[k]) for k in keys):.2f} N"
        )
    print(f"yardstick CPU median {stick.cpu_median:.3f} s; {machine_line()}")


if __name__ == "__main__":
    main()
