"""``exudyn-turnout frf``: point receptance of a rail of the co-running track model.

Writes ``frequency_hz,real,imag,magnitude`` (m/N) and optionally a log-log plot; prints
one summary line with the first eigenfrequencies. Plots (with --plot) through exudyn_turnout.plotting.curves.
"""

from __future__ import annotations

import argparse

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
    """
    p = sub.add_parser(
        "frf",
        help="receptance (FRF) of a rail of the co-running track model",
        description="Point receptance H = displacement / force (m/N) of one rail of the two- "
        "or three-layer co-running model (paper Section 3.3), at x or at a "
        "zone's midpoint.",
    )
    add_turnout_options(p)
    add_position_options(p)
    p.add_argument("--layers", type=int, choices=(2, 3), required=True, help="track model layers")
    p.add_argument(
        "--rail",
        choices=RAIL_SLOTS,
        required=True,
        help="rail slot: r1 stock, r2 switch rail / crossing, r3 check, r4 stock",
    )
    p.add_argument("--direction", choices=DIRECTIONS, required=True)
    p.add_argument(
        "--fmin", type=number, default=1.0, metavar="HZ", help="lowest frequency (default 1 Hz)"
    )
    p.add_argument(
        "--fmax",
        type=number,
        default=2000.0,
        metavar="HZ",
        help="highest frequency (default 2000 Hz)",
    )
    p.add_argument(
        "--n", type=int, default=400, help="number of log-spaced frequencies (default 400)"
    )
    p.add_argument("--out", required=True, metavar="FILE.csv", help="CSV file to write")
    p.add_argument("--plot", metavar="FILE.png", help="also save a log-log plot of |H|")
    p.set_defaults(run=_run)


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
        r = co_running_receptance(
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
        "x_m": r.x,
        "layers": args.layers,
        "rail": args.rail,
        "direction": args.direction,
        "fmin_hz": args.fmin,
        "fmax_hz": args.fmax,
        "n": args.n,
    }
    write_output(args.out, r.to_csv)
    write_sidecar(args.out, provenance(settings, turnout=turnout, argv=getattr(args, "argv", None)))
    if args.plot:
        _plot(r, args.plot)
    undamped = ", ".join(f"{f:.0f}" for f in r.metadata["eigenfrequencies_hz"][:4])
    damped = ", ".join(f"{f:.0f}" for f in r.metadata["damped_frequencies_hz"][:4])
    print(
        f"wrote {args.out}: {r.model} {r.rail} {r.direction} at x = {r.x:g} m (zone {r.metadata['zone']}, "
        f"{args.source}), {len(frequencies)} frequencies {args.fmin:g}-{args.fmax:g} Hz; "
        f"1/|H({frequencies[0]:g} Hz)| = {r.static_stiffness:.4g} N/m; first undamped eigenfrequencies "
        f"{undamped} Hz; oscillating modes (damped) {damped} Hz"
    )
    return 0


def _plot(r, path: str) -> None:
    from exudyn_turnout.plotting.curves import plot_receptance, save_figure

    zone = r.metadata["zone"]
    fig, _ = plot_receptance(
        r, title=f"{r.model} co-running track, zone {zone}, {r.metadata['source']} parameters"
    )
    write_output(path, lambda tmp: save_figure(fig, tmp, dpi=120), "--plot")
