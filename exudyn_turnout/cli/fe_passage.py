"""``exudyn-turnout fe simulate``: the wheelset passage over the FE turnout track.

:func:`add_simulate` adds the ``simulate`` sub-command to the ``fe`` group of
:mod:`exudyn_turnout.cli.fe` (pass it that group's sub-parsers). numpy/scipy only at
import; matplotlib is imported only to draw ``forces.png``.
"""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from exudyn_turnout.cli.main import UsageError, check_out_dir, number
from exudyn_turnout.cli.passage import (
    add_passage_options,
    route_from_args,
    run_passage_command,
    settings_from_args,
)

if TYPE_CHECKING:
    from exudyn_turnout.passage.fe_track.options import FEPassageOptions

__all__ = ["add_simulate"]


def _options(args: argparse.Namespace) -> FEPassageOptions:
    """FE passage options from ``--element-length``; a bad value is exit 2."""
    from exudyn_turnout.fe.mesh import FEOptions
    from exudyn_turnout.passage.fe_track.options import FEPassageOptions

    try:
        return FEPassageOptions(mesh=FEOptions(element_length=args.element_length))
    except ValueError as err:
        raise UsageError(str(err)) from None


def _run(args: argparse.Namespace) -> int:
    from dataclasses import asdict

    from exudyn_turnout.inputs.turnout import load_turnout
    from exudyn_turnout.inputs.vehicle import load_vehicle
    from exudyn_turnout.passage.run import simulate_passage

    check_out_dir(args.out)
    turnout = load_turnout(args.turnout)
    vehicle = load_vehicle(args.vehicle)
    args.route = route_from_args(args, turnout)
    options = _options(args)
    settings = settings_from_args(args)
    return run_passage_command(
        args,
        lambda bar: simulate_passage(
            turnout, settings, vehicle, bar, track="fe", fe_options=options
        ),
        f"FE track, {turnout.name}, {args.route} route, {args.speed:g} km/h",
        "FE track, ",
        turnout=turnout,
        vehicle=vehicle,
        extra_settings={
            "model": "FE",
            "fe_options": asdict(options.mesh),
            "loss_reference_hz": options.loss_reference_hz,
        },
    )


def add_simulate(fe_sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Add ``simulate`` to the ``fe`` group.

    Parameters
    ----------
    fe_sub : argparse._SubParsersAction
        The ``fe`` group's sub-parsers.

    Returns
    -------
    argparse.ArgumentParser
        The ``simulate`` parser.
    """
    parser = fe_sub.add_parser(
        "simulate",
        help="wheelset passage over the FE turnout track",
        description="Run one wheelset (Manchester benchmark) over the FE model of the turnout "
        "(vertical and lateral planes, rail torsion) with the profile contact of "
        "`exudyn-turnout simulate`, co-simulated with Exudyn's vehicle (exact one-step "
        "coupling); the same as `exudyn-turnout simulate --track fe`. Write "
        "timeseries.csv, summary.json, forces.png and contact_band.png into --out.",
    )
    parser.add_argument(
        "--turnout",
        metavar="FILE",
        help="turnout file with a [layout] section (default: packaged UIC60-760-1:15)",
    )
    parser.add_argument(
        "--route",
        metavar="NAME",
        help="route of the turnout file (default: through, or the file's first route)",
    )
    parser.add_argument(
        "--time-step",
        type=number,
        default=1e-4,
        metavar="S",
        help="s (default 1e-4: halving it moves the switch and crossing peaks <= 0.15 %%, "
        "validation/fe_profile_convergence.md)",
    )
    parser.add_argument(
        "--element-length",
        type=number,
        default=0.2,
        metavar="M",
        help="longest rail element (m), order 4 (default 0.2)",
    )
    add_passage_options(parser)
    parser.set_defaults(run=_run)
    return parser
