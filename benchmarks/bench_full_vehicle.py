"""Benchmark: time per step of the vehicle alone on rigid-track springs (printed table).

Run: ``python benchmarks/bench_full_vehicle.py [--time S] [--repeat N]``. Each case starts
from the static equilibrium with the car body displaced 30 mm laterally (so the 25 mm
bumpstops engage) and wheelset 1 by 2 mm, and integrates ``--time`` seconds with
generalized-alpha (``vehicle_builder.dynamic_settings``: spectral radius 0.8, modified
Newton, relative tolerance 1e-8, absolute 1e-4 N as the package's passage) at h = 1e-4 s,
the passage's step.
Cases: the full Manchester vehicle (4 wheelsets) with each node parametrization and
bumpstop law in both representations of ``vehicle_builder`` (linear: one
``ObjectGenericODE2``; rigid: rigid bodies and connectors), and the single-wheelset model
(1 wheelset) through the same builder. The runs of a case alternate with the yardstick
(``benchmarks/yardstick.py``): the median solve time is printed in seconds and in
yardstick units (which carry over between machines and loads).
"""

from __future__ import annotations

import argparse
import time

import exudyn as exu
import numpy as np
from yardstick import Yardstick, machine_line

from exudyn_turnout.inputs.vehicle_model import load_vehicle_model, single_wheelset_share
from exudyn_turnout.passage.vehicle.builder import (
    RigidTrack,
    add_vehicle_model,
    dynamic_settings,
    rigid_track_support,
    solve_static,
)


def _perturb(mbs, build) -> None:
    """Static state + 30 mm car-body and 2 mm wheelset-1 lateral offsets as initial state."""
    q = np.array(mbs.systemData.GetODE2Coordinates(exu.ConfigurationType.Initial))
    for handles, dy in ((build.car_body, 0.03), (build.wheelsets[0], 0.002)):
        if handles is not None:
            q[mbs.GetNodeODE2Index(handles.node) + handles.dof["y"]] += dy
    mbs.systemData.SetODE2Coordinates(q, exu.ConfigurationType.Initial)


def _case(model, end_time, step, relative_tolerance=None, **options):
    """Wall time (s), ODE2 coordinates and Newton iterations per step of one run."""
    mbs = exu.SystemContainer().AddSystem()
    build = add_vehicle_model(mbs, model, **options)
    rigid_track_support(mbs, build, RigidTrack(k_x=1e7 if options.get("wheelset_spin") else 0.0))
    mbs.Assemble()
    solve_static(mbs)
    _perturb(mbs, build)
    settings = dynamic_settings(end_time, step)
    if relative_tolerance is not None:
        settings.timeIntegration.newton.relativeTolerance = relative_tolerance
    solver = exu.MainSolverImplicitSecondOrder()
    previous, exu.config.printToConsole = exu.config.printToConsole, False
    try:
        t0 = time.perf_counter()
        solver.SolveSystem(mbs, settings)
        wall = time.perf_counter() - t0
    finally:
        exu.config.printToConsole = previous
    steps = settings.timeIntegration.numberOfSteps
    return wall, len(mbs.systemData.GetODE2Coordinates()), solver.it.newtonStepsCount / steps


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--time", type=float, default=2.0, help="simulated time per case, s")
    parser.add_argument("--step", type=float, default=1e-4, help="time step, s")
    parser.add_argument("--repeat", type=int, default=3, help="runs per case, median taken")
    args = parser.parse_args(argv)
    full = load_vehicle_model()
    single = single_wheelset_share(full)
    rigid = {"representation": "rigid"}
    cases = [
        ("4 wheelsets, linear (default)", full, {}),
        ("4 wheelsets, linear, Newton rel. tol. 1e-6", full, {"relative_tolerance": 1e-6}),
        ("4 wheelsets, linear, no bumpstop", full, {"bumpstop": "none"}),
        ("4 wheelsets, linear, spin free", full, {"wheelset_spin": True}),
        ("4 wheelsets, rigid Rxyz, symbolic bumpstop", full, rigid),
        ("4 wheelsets, rigid Rxyz, Python bumpstop", full, {**rigid, "bumpstop": "python"}),
        ("4 wheelsets, rigid Rxyz, no bumpstop", full, {**rigid, "bumpstop": "none"}),
        ("4 wheelsets, rigid RotVecLG", full, {**rigid, "rotation": "RotVecLG"}),
        ("1 wheelset + sprung point, linear", single, {}),
        ("1 wheelset + sprung point, rigid Rxyz", single, rigid),
    ]
    steps = int(round(args.time / args.step))
    print(
        f"vehicle alone on rigid-track springs, h = {args.step:g} s, {steps} steps, median of "
        f"{args.repeat}"
    )
    print(
        f"{'case':<44}{'ODE2':>6}{'Newton/step':>12}{'wall s':>9}{'yardstick':>10}"
        f"{'us/step':>9}{'x real time':>13}"
    )
    stick = Yardstick()
    for name, model, options in cases:
        timing = stick.measure(
            lambda model=model, options=options: _case(model, args.time, args.step, **options),
            args.repeat,
            warm_up=False,
            inner=lambda run: run[0],  # the solve, not the build
        )
        wall = timing.seconds
        _, n, its = timing.result
        print(
            f"{name:<44}{n:>6}{its:>12.2f}{wall:>9.3f}{timing.units:>10.2f}"
            f"{1e6 * wall / steps:>9.1f}{wall / args.time:>13.3f}"
        )
    print(f"yardstick median {stick.median:.3f} s; {machine_line()}")


if __name__ == "__main__":
    main()
