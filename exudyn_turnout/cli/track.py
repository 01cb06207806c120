"""``exudyn-turnout frf``: point receptance of a rail of the co-running track model.

Writes ``frequency_hz,real,imag,magnitude`` (m/N) and optionally a log-log plot; prints
one summary line with the first eigenfrequencies. Plots (with --plot) through
:mod:`exudyn_turnout.plotting.curves`.
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from typing import cast

from exudyn_turnout.cli.main import (
    UsageError,
    add_position_options,
    add_turnout_options,
    check_out_file,
    check_plot_file,
    number,
    turnout_from_args,
    write_output,
    write_sidecar,
)
from exudyn_turnout.inputs.turnout import RAIL_SLOTS
from exudyn_turnout.receptance import DIRECTIONS, log_frequencies

__all__ = ["build"]


def build(sub: argparse._SubParsersAction) -> None:
    """Register the command on the ``exudyn-turnout`` subcommand parsers.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subcommand parsers of ``exudyn-turnout``; ``frf`` is added to them.
    """
    parser = sub.add_parser(
        "frf",
        help="receptance (FRF) of a rail of the co-running track model",
        description="Point receptance H = displacement / force (m/N) of one rail of the two- "
        "or three-layer co-running model (paper Section 3.3), at x or at a "
        "zone's midpoint.",
    )
    add_turnout_options(parser)
    add_position_options(parser)
    parser.add_argument(
        "--layers", type=int, choices=(2, 3), required=True, help="track model layers"
    )
    parser.add_argument(
        "--rail",
        choices=RAIL_SLOTS,
        required=True,
        help="rail slot: r1 stock, r2 switch rail / crossing, r3 check, r4 stock",
    )
    parser.add_argument("--direction", choices=DIRECTIONS, required=True)
    parser.add_argument(
        "--fmin", type=number, default=1.0, metavar="HZ", help="lowest frequency (default 1 Hz)"
    )
    parser.add_argument(
        "--fmax",
        type=number,
        default=2000.0,
        metavar="HZ",
        help="highest frequency (default 2000 Hz)",
    )
    parser.add_argument(
        "--n", type=int, default=400, help="number of log-spaced frequencies (default 400)"
    )
    parser.add_argument("--out", required=True, metavar="FILE.csv", help="CSV file to write")
    parser.add_argument("--plot", metavar="FILE.png", help="also save a log-log plot of |H|")
    parser.set_defaults(run=_run)


def _run(args: argparse.Namespace) -> int:
    from exudyn_turnout.corunning.modal import co_running_receptance
    from exudyn_turnout.provenance import provenance

    check_out_file(args.out)
    if args.plot:
        check_plot_file(args.plot)
    try:
        frequencies = log_frequencies(args.fmin, args.fmax, args.n)
    except ValueError as err:
        raise UsageError(f"frf: {err}") from None
    turnout = turnout_from_args(args)
    try:
        receptance = co_running_receptance(
            turnout,
            args.layers,
            args.rail,
            args.direction,
            x=args.x,
            zone=args.zone,
            source=args.source,
            frequencies=frequencies,
        )
    except (KeyError, ValueError) as err:
        raise UsageError(f"frf: {str(err).strip(chr(39))}") from None
    settings = {
        "model": f"co-running, {args.layers} layers",
        "source": args.source,
        "profiles": args.profiles,
        "zone": args.zone,
        "x_m": receptance.x,
        "layers": args.layers,
        "rail": args.rail,
        "direction": args.direction,
        "fmin_hz": args.fmin,
        "fmax_hz": args.fmax,
        "n": args.n,
    }
    write_output(args.out, receptance.to_csv)
    write_sidecar(args.out, provenance(settings, turnout=turnout, argv=getattr(args, "argv", None)))
    if args.plot:
        _plot(receptance, args.plot)
    # co_running_receptance's metadata: tuples of floats (Hz)
    eigenfrequencies = cast(Sequence[float], receptance.metadata["eigenfrequencies_hz"])
    damped_frequencies = cast(Sequence[float], receptance.metadata["damped_frequencies_hz"])
    undamped = ", ".join(f"{f:.0f}" for f in eigenfrequencies[:4])
    damped = ", ".join(f"{f:.0f}" for f in damped_frequencies[:4])
    print(
        f"wrote {args.out}: {receptance.model} {receptance.rail} {receptance.direction} "
        f"at x = {receptance.x:g} m (zone {receptance.metadata['zone']}, "
        f"{args.source}), {len(frequencies)} frequencies {args.fmin:g}-{args.fmax:g} Hz; "
        f"1/|H({frequencies[0]:g} Hz)| = {receptance.static_stiffness:.4g} N/m; "
        f"first undamped eigenfrequencies {undamped} Hz; oscillating modes (damped) {damped} Hz"
    )
    return 0


def _plot(receptance, path: str) -> None:
    from exudyn_turnout.plotting.curves import plot_receptance, save_figure

    zone, source = receptance.metadata["zone"], receptance.metadata["source"]
    fig, _ = plot_receptance(
        receptance, title=f"{receptance.model} co-running track, zone {zone}, {source} parameters"
    )
    write_output(path, lambda tmp: save_figure(fig, tmp, dpi=120), "--plot")
