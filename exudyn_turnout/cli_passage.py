"""``exudyn-turnout simulate``: a wheelset passage through the turnout (paper Section 4)."""
from __future__ import annotations

import argparse
import sys

from .cli import UsageError, add_turnout_options, kilonewtons, number, progress_bar, turnout_from_args

__all__ = ["build", "run_passage_command"]


def _run(args: argparse.Namespace) -> int:
    from .passage import PassageSettings, simulate_passage

    turnout = turnout_from_args(args)
    settings = PassageSettings(route=args.route, speed_kmh=args.speed, layers=args.layers, source=args.source,
                               x_start=args.x_start, x_end=args.x_end, time_step=args.time_step)
    return run_passage_command(args, lambda bar: simulate_passage(turnout, settings, progress=bar),
                               f"{turnout.name}, {args.route} route, {args.speed:g} km/h")


def run_passage_command(args: argparse.Namespace, simulate, title: str, what: str = "") -> int:
    """Run ``simulate(progress)`` with a progress bar; write the files, forces.png and one summary line.

    Shared by ``simulate`` and ``fe simulate``; a PassageError becomes one line and exit 2.
    """
    from .passage import PassageError, write_passage

    bar = progress_bar(sys.stderr)
    try:
        result = simulate(bar)
    except PassageError as err:
        raise UsageError(str(err)) from None
    finally:
        if bar:
            sys.stderr.write("\n")
    paths = write_passage(result, args.out)
    if not args.no_plot:
        from .plotting import plot_passage_forces, save_figure
        fig, _ = plot_passage_forces([result], wheel="right", title=title)
        save_figure(fig, f"{args.out}/forces.png", dpi=120)
    s = result.summary
    if "n_dof" in s:
        what = f"{what.rstrip(', ')} ({s['n_dof']} DOFs), "
    print(f"wrote {paths['timeseries']}, {paths['summary']}: {what}right wheel peak Fz "
          f"{kilonewtons(s['peak_Fz_switch_N'])} at the switch, {kilonewtons(s['peak_Fz_crossing_N'])} at the "
          f"crossing (static {kilonewtons(s['static_wheel_load_N'])}); {s['simulated_time_s']:.2f} s simulated "
          f"in {s['wall_time_s']:.1f} s")
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
