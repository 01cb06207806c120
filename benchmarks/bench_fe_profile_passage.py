"""Benchmark: the FE track under the one vehicle and contact vs the co-running tracks.

Run: ``python benchmarks/bench_fe_profile_passage.py [--x-start X] [--x-end X] [--full]``
(default: the README's case, the through route's 65 m at 100 km/h, h = 1e-4 s). Rows,
each run once in this one process (the 2-core machine may be shared: ratios within one run
are what counts):

- 3-layer co-running track, profile contact (Exudyn; the README's main job);
- FE track, profile contact, vertical and lateral planes with rail torsion, co-simulated
  (``passage/fe_track/``), with the split of its wall time;
- with ``--full``: the full vehicle (4 wheelsets) on the FE track and on 3-layer tracks.
"""

from __future__ import annotations

import argparse
import time

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage.results import PassageSettings
from exudyn_turnout.passage.run import simulate_passage


def _timed(run) -> tuple[float, object]:
    t0 = time.perf_counter()
    result = run()
    return time.perf_counter() - t0, result


def main(argv=None) -> None:
    """Print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--x-start", type=float, default=None)
    parser.add_argument("--x-end", type=float, default=None)
    parser.add_argument("--full", action="store_true", help="also the full vehicle")
    args = parser.parse_args(argv)
    turnout = load_turnout()
    settings = PassageSettings(x_start=args.x_start, x_end=args.x_end)
    simulate_passage(turnout, PassageSettings(x_start=-5.0, x_end=-4.9))  # tables, numba
    rows = []
    wall_3l, co = _timed(lambda: simulate_passage(turnout, settings, track="3-layer"))
    sim = co.summary["simulated_time_s"]
    rows.append(("3-layer co-running, profile contact (Exudyn)", wall_3l, co))
    wall_fe, fe = _timed(lambda: simulate_passage(turnout, settings, track="fe"))
    rows.append(("FE, profile contact, vertical + lateral (co-simulation)", wall_fe, fe))
    if args.full:
        for track in ("3-layer", "fe"):
            wall, r = _timed(
                lambda track=track: simulate_passage(turnout, settings, "manchester", track=track)
            )
            rows.append((f"full vehicle, {track}", wall, r))
    print(
        f"x {settings.x_start or turnout.x_min:g}..{settings.x_end or turnout.x_max:g} m, "
        f"100 km/h, h = 1e-4 s, {sim:.3f} s simulated"
    )
    print(f"{'case':<58}{'wall s':>9}{'x real':>9}{'vs 3L':>8}{'DOFs':>8}")
    for name, wall, r in rows:
        n_dof = r.summary.get("n_dof", "")
        print(f"{name:<58}{wall:>9.1f}{wall / sim:>9.1f}{wall / wall_3l:>8.1f}{n_dof!s:>8}")
    parts = fe.summary["wall_time_parts_s"]
    steps = fe.summary["n_steps"]
    print(f"\nFE (profile): {steps} steps, {1e3 * parts['steps'] / steps:.2f} ms per step:")
    for key in ("build", "factorise", "static", "predict", "coupling", "complete", "steps"):
        print(f"  {key:<10}{parts[key]:>8.1f} s")


if __name__ == "__main__":
    main()
