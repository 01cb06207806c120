"""Benchmark: the full vehicle (4 wheelsets, a co-running track under each) vs one wheelset.

Run: ``python benchmarks/bench_vehicle_passage.py [--route R] [--x-start X] [--x-end X]
[--speed V]`` (default: the whole turnout, through route, 100 km/h). Each case runs once
(profile contact, h = 1e-4 s): the single-wheelset passage
(:func:`exudyn_turnout.passage.simulate.simulate_passage`) and the full Manchester vehicle
(:func:`exudyn_turnout.passage.full_vehicle_passage.simulate_vehicle_passage`), on the
2-layer and the 3-layer track, plus a short run (0.5 m) of each to separate the fixed cost
(building the systems, static solves) from the cost per step: "marginal us/step" is
(wall - wall_short) / (steps - steps_short). The contact tables are loaded and the compiled
contact kernel warmed up before, untimed. The 2-core machine is shared: expect noise.
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.inputs.vehicle_model import load_vehicle_model
from exudyn_turnout.passage.full_vehicle_passage import simulate_vehicle_passage
from exudyn_turnout.passage.results import PassageSettings
from exudyn_turnout.passage.simulate import simulate_passage


def _timed(run, settings) -> tuple[float, int]:
    wall = time.perf_counter()
    result = run(settings)
    return time.perf_counter() - wall, len(result.columns["t_s"]) - 1


def main() -> None:
    """Print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--route", default="through")
    parser.add_argument("--x-start", type=float, default=None, help="front wheelset start (m)")
    parser.add_argument("--x-end", type=float, default=None, help="front wheelset end (m)")
    parser.add_argument("--speed", type=float, default=100.0, help="km/h")
    args = parser.parse_args()
    turnout, model = load_turnout(), load_vehicle_model()
    x_a = turnout.x_min if args.x_start is None else args.x_start
    x_b = turnout.x_max if args.x_end is None else args.x_end
    base = PassageSettings(route=args.route, speed_kmh=args.speed, x_start=x_a, x_end=x_b)
    warm = replace(base, x_end=x_a + 0.05)
    simulate_passage(turnout, warm)  # contact tables, compiled kernel: untimed
    simulate_vehicle_passage(turnout, warm, model)
    simulated = (x_b - x_a) / base.v
    print(f"{args.route} route, front wheelset x {x_a:g} .. {x_b:g} m, {args.speed:g} km/h, ")
    print(f"h = 1e-4 s, {simulated:.3f} s simulated")
    print(
        f"{'case':<36}{'steps':>7}{'wall s':>8}{'us/step':>9}{'marginal us/step':>18}"
        f"{'x real time':>13}"
    )
    cases = (
        ("1 wheelset", lambda s: simulate_passage(turnout, s)),
        ("4 wheelsets (full vehicle)", lambda s: simulate_vehicle_passage(turnout, s, model)),
    )
    for layers in (2, 3):
        settings = replace(base, layers=layers)
        for label, run in cases:
            wall_0, steps_0 = _timed(run, replace(settings, x_end=x_a + 0.5))
            wall, steps = _timed(run, settings)
            marginal = 1e6 * (wall - wall_0) / max(steps - steps_0, 1)
            print(
                f"{label + f', {layers} layers':<36}{steps:>7}{wall:>8.2f}"
                f"{1e6 * wall / steps:>9.1f}{marginal:>18.1f}{wall / simulated:>13.1f}"
            )


if __name__ == "__main__":
    main()
