"""Benchmark: receptance of the co-running model, and Exudyn time steps of the track alone.

Run: ``python benchmarks/bench_receptance.py [--repeat N] [--steps N]``. Prints one table;
every ratio is of two timings from this same run. Targets: a 2000-frequency
three-layer receptance in <= 50 ms; the scan of one rail every 0.6 m from -5 to 60 m in
a few seconds. The yardstick (``benchmarks/yardstick.py``) runs before, between and after
the two groups of timings; the "yardstick" column gives each time in its units (against
the yardstick runs around its group), which carry over between machines and loads.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from functools import partial

import numpy as np
from yardstick import Yardstick, machine_line


def best_of(fn: Callable[[], object], repeat: int) -> float:
    """Shortest wall time (s) of ``repeat`` calls."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def receptance_rows(turnout, repeat: int) -> list[tuple[str, float, str, str]]:
    from exudyn_turnout.corunning.modal import (
        assemble_track_matrices,
        co_running_receptance,
        receptance_from_matrices,
    )
    from exudyn_turnout.corunning.parameters import co_running_parameters
    from exudyn_turnout.receptance import log_frequencies

    f = log_frequencies(1.0, 2000.0, 2000)
    t = {
        layers: best_of(
            partial(
                co_running_receptance, turnout, layers, "r2", "vertical", x=47.0, frequencies=f
            ),
            repeat,
        )
        for layers in (2, 3)
    }
    matrices = assemble_track_matrices(co_running_parameters(turnout, x=47.0, layers=3), 47.0)
    t_modal = best_of(lambda: receptance_from_matrices(matrices, "z_m0_r2", f, "modal"), repeat)
    t_direct = best_of(lambda: receptance_from_matrices(matrices, "z_m0_r2", f, "direct"), repeat)
    xs = np.arange(-5.0, 60.0 + 1e-9, 0.6)
    t_scan = best_of(
        lambda: [
            co_running_receptance(turnout, 3, "r1", "vertical", x=x, frequencies=f) for x in xs
        ],
        max(1, repeat // 5),
    )
    return [
        (
            "3-layer receptance, 2000 frequencies (params + M,K,D + modes + H)",
            t[3] * 1e3,
            "ms",
            "<= 50",
        ),
        ("2-layer receptance, 2000 frequencies", t[2] * 1e3, "ms", ""),
        ("  ratio 3-layer / 2-layer", t[3] / t[2], "-", ""),
        ("3-layer H only, modal state-space, 2000 frequencies", t_modal * 1e3, "ms", ""),
        ("3-layer H only, direct solve per frequency", t_direct * 1e3, "ms", ""),
        ("  ratio direct / modal", t_direct / t_modal, "-", ""),
        (
            f"scan r1 vertical 3-layer, {len(xs)} positions -5..60 m every 0.6 m, 2000 freq.",
            t_scan,
            "s",
            "a few s",
        ),
    ]


def exudyn_rows(turnout, steps: int) -> list[tuple[str, float, str, str]]:
    import exudyn as exu
    from exudyn.itemInterface import LoadForceVector

    from exudyn_turnout.corunning.parameters import co_running_parameters
    from exudyn_turnout.corunning.track import (
        MECHANISMS,
        add_co_running_track,
        linearized_matrices,
        simulation_settings,
    )

    exu.config.printToConsole = False
    h = 5e-5

    def build(layers: int, mechanism: str):
        mbs = exu.SystemContainer().AddSystem()
        params = co_running_parameters(turnout, zone=1, layers=layers)
        handles = add_co_running_track(mbs, params, 2.0, 50.0, mechanism=mechanism)
        mbs.AddLoad(
            LoadForceVector(markerNumber=handles.wheel_markers["r2"], loadVector=[2e4, -1e5, 0.0])
        )
        mbs.Assemble()
        return mbs, handles

    def linearize():
        mbs, handles = build(3, "symbolic")
        linearized_matrices(mbs, handles)

    t_lin = best_of(linearize, 5)
    per_step, iterations = {}, {}
    for layers in (2, 3):
        for mechanism in MECHANISMS:
            mbs, _ = build(layers, mechanism)
            solver = exu.MainSolverImplicitSecondOrder()
            t0 = time.perf_counter()
            solver.SolveSystem(mbs, simulation_settings(steps * h, h))
            per_step[layers, mechanism] = (time.perf_counter() - t0) / steps
            iterations[layers, mechanism] = solver.it.newtonStepsCount / steps
    rows = [
        (
            "Exudyn: build 3-layer track (symbolic) + Assemble + ComputeLinearizedSystem",
            t_lin * 1e3,
            "ms",
            "",
        )
    ]
    for (layers, mechanism), t in per_step.items():
        rows.append(
            (
                f"time step, {layers}-layer, {mechanism} springs (h = 5e-5 s, x = 2 m + 50 m/s t)",
                t * 1e6,
                "us",
                f"{iterations[layers, mechanism]:.2f} Newton it/step",
            )
        )
    rows += [
        (
            "  ratio python / symbolic (3-layer)",
            per_step[3, "python"] / per_step[3, "symbolic"],
            "-",
            "",
        ),
        (
            "  ratio symbolic / constant (3-layer)",
            per_step[3, "symbolic"] / per_step[3, "constant"],
            "-",
            "",
        ),
        (
            "  ratio 3-layer / 2-layer (symbolic)",
            per_step[3, "symbolic"] / per_step[2, "symbolic"],
            "-",
            "paper ~1.10",
        ),
        (
            "  real-time factor, 3-layer symbolic (simulated s per wall s)",
            1.0 / (per_step[3, "symbolic"] / h),
            "-",
            ">= 1",
        ),
    ]
    return rows


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--repeat", type=int, default=10, help="repetitions of each receptance timing"
    )
    parser.add_argument("--steps", type=int, default=10000, help="time steps per Exudyn timing")
    args = parser.parse_args(argv)
    from exudyn_turnout.inputs.turnout import load_turnout

    turnout = load_turnout()
    stick = Yardstick()
    stick.run()
    rows = [(*r, stick.run()) for r in receptance_rows(turnout, args.repeat)]
    rows += [(*r, stick.run()) for r in exudyn_rows(turnout, args.steps)]
    seconds = {"s": 1.0, "ms": 1e-3, "us": 1e-6}
    width = max(len(r[0]) for r in rows)
    print(f"{'quantity':<{width}}  {'value':>10}  unit  {'yardstick':>10}  target / note")
    for name, value, unit, target, after in rows:
        units = f"{value * seconds[unit] / after:>10.3g}" if unit in seconds else f"{'':>10}"
        print(f"{name:<{width}}  {value:>10.3g}  {unit:<4}  {units}  {target}")
    print(f"yardstick median {stick.median:.3f} s; {machine_line()}")


if __name__ == "__main__":
    main()
