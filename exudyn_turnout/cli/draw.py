"""``exudyn-turnout draw``: see the model.

- ``draw section``: the co-running cross-section as it is built for a zone or position
  (sleeper, rails, m_0 layer, every spring-damper with its name and value, the wheelset
  above), like the paper's Figs 2 and 3;
- ``draw passage``: a GIF of a passage's cross-section (wheelset and rails moving,
  displacements exaggerated, contact forces as arrows).
"""

from __future__ import annotations

import argparse
from pathlib import Path

from exudyn_turnout.cli.main import (
    RunFailure,
    UsageError,
    add_position_options,
    add_turnout_options,
    check_out_file,
    number,
    turnout_from_args,
)

__all__ = ["build"]


def _check_file(path: str, suffix: str) -> Path:
    if Path(path).suffix.lower() != suffix:
        raise UsageError(f"--out {path}: must end in {suffix}")
    out = check_out_file(path, "--out")
    out.parent.mkdir(parents=True, exist_ok=True)
    return out


def _run_section(args: argparse.Namespace) -> int:
    from exudyn_turnout.corunning.parameters import co_running_parameters
    from exudyn_turnout.inputs.routes import load_route
    from exudyn_turnout.inputs.vehicle import load_vehicle
    from exudyn_turnout.plotting.model import draw_cross_section

    out = _check_file(args.out, ".png")
    turnout = turnout_from_args(args)
    try:
        params = co_running_parameters(
            turnout, zone=args.zone, x=args.x, layers=args.layers, source=args.source
        )
    except (KeyError, ValueError) as err:
        raise UsageError(str(err).strip("'\"")) from None
    zone = params.zone
    x = args.x if args.x is not None else 0.5 * (zone.x_start + zone.x_end)
    route = load_route(turnout, args.route) if args.route else None
    vehicle = None if args.no_vehicle else load_vehicle(args.vehicle)
    ax = draw_cross_section(params, x, route=route, vehicle=vehicle)
    ax.figure.savefig(out, dpi=110, bbox_inches="tight")  # the process ends: no close needed
    print(f"wrote {out}: zone {zone.index}, x = {x:g} m, {params.layers} layers")
    return 0


def _check_passage_options(args: argparse.Namespace, turnout) -> None:
    """``--scale`` and the x range, before the passage runs (bad input: exit 2, not 3)."""
    if not args.scale > 0.0:
        raise UsageError(f"--scale must be > 0 (a magnification), got {args.scale:g}")
    x_start = turnout.x_min if args.x_start is None else args.x_start
    x_end = turnout.x_max if args.x_end is None else args.x_end
    if not turnout.x_min <= x_start < x_end <= turnout.x_max:
        raise UsageError(
            f"--x-start {x_start:g} --x-end {x_end:g}: the x range must lie within the "
            f"turnout ({turnout.x_min:g} to {turnout.x_max:g} m) with --x-start < --x-end"
        )


def _run_passage(args: argparse.Namespace) -> int:
    from exudyn_turnout.cli.passage import route_from_args, settings_from_args
    from exudyn_turnout.inputs.vehicle import load_vehicle
    from exudyn_turnout.passage.run import simulate_passage
    from exudyn_turnout.passage.settings import PassageError
    from exudyn_turnout.plotting.model import animate_passage

    out = _check_file(args.out, ".gif")
    turnout = turnout_from_args(args)
    _check_passage_options(args, turnout)
    vehicle = load_vehicle(args.vehicle)
    args.route = route_from_args(args, turnout)
    settings = settings_from_args(args, layers=args.layers, source=args.source)
    try:
        result = simulate_passage(turnout, settings, vehicle)
    except PassageError as err:
        raise RunFailure(str(err)) from None
    animate_passage(result, out, scale=args.scale, turnout=turnout, vehicle=vehicle)
    print(f"wrote {out}: {result}")
    return 0


def build(sub: argparse._SubParsersAction) -> None:
    """Register ``draw section`` and ``draw passage`` on the subcommand parsers.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The ``exudyn-turnout`` subcommand parsers.
    """
    draw = sub.add_parser("draw", help="draw the model: cross-section (PNG) or passage (GIF)")
    kinds = draw.add_subparsers(dest="what", required=True, parser_class=type(draw))

    section = kinds.add_parser("section", help="the co-running cross-section of a zone (PNG)")
    add_turnout_options(section)
    add_position_options(section)
    section.add_argument("--layers", type=int, choices=(2, 3), default=3)
    section.add_argument(
        "--route", metavar="NAME", help="route whose rail positions to draw (default: zone's)"
    )
    section.add_argument("--vehicle", metavar="FILE", help="vehicle file drawn above the track")
    section.add_argument("--no-vehicle", action="store_true", help="draw the track only")
    section.add_argument("--out", required=True, metavar="FILE.png")
    section.set_defaults(run=_run_section)

    passage = kinds.add_parser("passage", help="a GIF of a passage's cross-section")
    add_turnout_options(passage)
    passage.add_argument("--layers", type=int, choices=(2, 3), default=3)
    passage.add_argument(
        "--route", metavar="NAME", help="route (default: through, or the file's first route)"
    )
    passage.add_argument("--vehicle", metavar="FILE", help="vehicle file")
    passage.add_argument("--speed", type=number, default=100.0, metavar="KMH")
    passage.add_argument("--x-start", type=number, metavar="M")
    passage.add_argument("--x-end", type=number, metavar="M")
    passage.add_argument(
        "--scale",
        type=number,
        default=200.0,
        metavar="S",
        help="displacement magnification (default 200)",
    )
    passage.add_argument("--out", required=True, metavar="FILE.gif")
    passage.set_defaults(run=_run_passage)
