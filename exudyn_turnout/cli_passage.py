"""``exudyn-turnout simulate``: a wheelset passage through the turnout (paper Section 4)."""
from __future__ import annotations

import argparse
import sys

from .cli import UsageError, progress_bar, add_turnout_options, kilonewtons, number, turnout_from_args

__all__ = ["build"]


def _run(args: argparse.Namespace) -> int:
    from .passage import PassageError, PassageSettings, simulate_passage, write_passage

    turnout = turnout_from_args(args)
    settings = PassageSettings(route=args.route, speed_kmh=args.speed, layers=args.layers, source=args.source,
                               x_start=args.x_start, x_end=args.x_end, time_step=args.time_step)
    bar = progress_bar(sys.stderr)
    try:
        result = simulate_passage(turnout, settings, progress=bar)
    except PassageError as err:
        if bar:
            sys.stderr.write("\n")
        raise UsageError(str(err)) from None
    if bar:
        sys.stderr.write("\n")
    paths = write_passage(result, args.out)
    if not args.no_plot:
        from .plotting import plot_passage_forces
        fig, _ = plot_passage_forces([result], wheel="right",
                                     title=f"{turnout.name}, {args.route} route, {args.speed:g} km/h")
        fig.savefig(f"{args.out}/forces.png", dpi=120)
    s = result.summary
    print(f"wrote {paths['timeseries']}, {paths['summary']}: right wheel peak Fz {kilonewtons(s['peak_Fz_switch_N'])} "
          f"at the switch, {kilonewtons(s['peak_Fz_crossing_N'])} at the crossing (static "
          f"{kilonewtons(s['static_wheel_load_N'])}); {s['simulated_time_s']:.2f} s simulated in {s['wall_time_s']:.1f} s")
    return 0


def build(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("simulate", help="wheelset passage on the co-running track",
                       description="Run one wheelset (Manchester benchmark) through the turnout on a 2- or 3-layer "
                                   "co-running track with penalty wheel/rail contact; write timeseries.csv, "
                                   "summary.json and forces.png into --out.")
    add_turnout_options(p)
    p.add_argument("--layers", type=int, choices=(2, 3), default=3)
    p.add_argument("--route", choices=("through", "diverging"), default="through")
    p.add_argument("--speed", type=number, default=100.0, metavar="KMH", help="km/h (default 100)")
    p.add_argument("--x-start", type=number, metavar="M", help="start position (m), default: turnout start")
    p.add_argument("--x-end", type=number, metavar="M", help="end position (m), default: turnout end")
    p.add_argument("--time-step", type=number, default=1e-4, metavar="S", help="s (default 1e-4, converged)")
    p.add_argument("--out", required=True, metavar="DIR", help="output directory")
    p.add_argument("--no-plot", action="store_true", help="skip forces.png")
    p.set_defaults(run=_run)
