"""Benchmark: the FE track under the one vehicle and contact vs the co-running tracks.

Run: ``python benchmarks/bench_fe_profile_passage.py [--x-start X] [--x-end X] [--full]
[--full-fe-only]``
(default: the single wheelset over the crossing, 44-49 m of the through route at 100 km/h,
h = 1e-4 s: issue 24's case). Every row is run in this one process after a warm-up and
costed in CPU time and in units of the yardstick, the 3-layer co-running run of the same
case measured alongside (its first row; the machine may be shared: the ratios are what
carries over):

- 3-layer co-running track, profile contact (Exudyn; the yardstick);
- FE track, profile contact, vertical and lateral planes with rail torsion, co-simulated
  (``passage/fe_track/``): the default moving window and the whole model, with the split
  of the window run's wall time;
- with ``--full``: the full vehicle (4 wheelsets) on 3-layer tracks and on the FE track;
- with ``--full-fe-only``: the unit and the full vehicle on the FE track only (issue 24's
  "full vehicle on FE over the through route": ``--x-start -5 --x-end 60 --full-fe-only``).

Every run also alternates with the shared yardstick (``benchmarks/yardstick.py``, a fixed
workload independent of this package): the "yardstick" column is the run's wall time in
its units.
"""

from __future__ import annotations

import argparse

from yardstick import Yardstick, machine_line

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage.fe_track.options import FEPassageOptions
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings


def _timed(stick, run) -> tuple[float, float, object, float]:
    t = stick.measure(run, repeats=1, warm_up=False)
    return t.cpu_seconds, t.seconds, t.result, t.units


def main(argv=None) -> None:
    """Print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--x-start", type=float, default=44.0)
    parser.add_argument("--x-end", type=float, default=49.0)
    parser.add_argument("--full", action="store_true", help="also the full vehicle")
    parser.add_argument(
        "--full-fe-only", action="store_true", help="the unit and the full vehicle on FE only"
    )
    args = parser.parse_args(argv)
    turnout = load_turnout()
    settings = PassageSettings(x_start=args.x_start, x_end=args.x_end)
    warm = PassageSettings(x_start=-5.0, x_end=-4.9)
    simulate_passage(turnout, warm, "wheelset")  # tables, numba
    simulate_passage(turnout, PassageSettings(x_start=-5.0, x_end=-4.99), "wheelset", track="fe")
    stick = Yardstick()
    rows = []
    cpu_3l, wall_3l, co, units = _timed(
        stick, lambda: simulate_passage(turnout, settings, "wheelset", track="3-layer")
    )
    sim = co.summary["simulated_time_s"]
    rows.append(("3-layer co-running, profile contact (the unit)", cpu_3l, wall_3l, co, units))
    window = FEPassageOptions()
    cases = (
        (f"FE, window {window.window_length:g} m (default)", window),
        ("FE, whole model", FEPassageOptions(window_length=None)),
    )
    tracks = ("3-layer", "fe") if args.full else ()
    if args.full_fe_only:
        cases, tracks = (), ("fe",)
    fe = None
    for name, options in cases:
        cpu, wall, r, units = _timed(
            stick,
            lambda options=options: simulate_passage(
                turnout, settings, "wheelset", track="fe", fe_options=options
            ),
        )
        fe = fe or r
        rows.append((name, cpu, wall, r, units))
    for track in tracks:
        cpu, wall, r, units = _timed(
            stick,
            lambda track=track: simulate_passage(turnout, settings, "manchester", track=track),
        )
        rows.append((f"full vehicle, {track}", cpu, wall, r, units))
        fe = r if track == "fe" and fe is None else fe
    print(
        f"x {settings.x_start:g}..{settings.x_end:g} m, 100 km/h, h = 1e-4 s, "
        f"{sim:.3f} s simulated; cost in units of the 3-layer run (same process)"
    )
    print(
        f"{'case':<50}{'x 3L':>8}{'CPU s':>9}{'wall s':>9}{'yardstick':>10}{'x real':>9}{'DOFs':>8}"
    )
    for name, cpu, wall, r, units in rows:
        n_dof = r.summary.get("n_dof", "")
        print(
            f"{name:<50}{cpu / cpu_3l:>8.1f}{cpu:>9.2f}{wall:>9.2f}{units:>10.2f}"
            f"{cpu / sim:>9.1f}{n_dof!s:>8}"
        )
    print(f"yardstick median {stick.median:.3f} s; {machine_line()}")
    assert fe is not None
    parts = fe.summary["wall_time_parts_s"]
    steps = fe.summary["n_steps"]
    print(f"\nFE window ({fe.summary['fe_window']}): {steps} steps, wall s:")
    for key in ("build", "factorise", "window", "static", "predict", "coupling", "complete"):
        print(f"  {key:<10}{parts[key]:>8.2f}")
    print(f"  {'steps':<10}{parts['steps']:>8.2f} ({1e3 * parts['steps'] / steps:.2f} ms a step)")


if __name__ == "__main__":
    main()
