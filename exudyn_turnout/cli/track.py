"""``exudyn-turnout frf``: point receptance of a rail of the co-running track model.

Writes ``frequency_hz,real,imag,magnitude`` (m/N) and optionally a log-log plot; prints
one summary line with the first eigenfrequencies. ``--with-fe`` also computes the FE
reference's receptance at the same x, rail and direction (``<stem>_fe.csv``, overlaid in
the plot: the comparison of the paper's Figs 5 and 6). Plots (with --plot) through
:mod:`exudyn_turnout.plotting.curves`.
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from pathlib import Path
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

__all__ = ["build", "fe_csv_path"]


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
    parser.add_argument(
        "--with-fe",
        action="store_true",
        help="also the FE reference's receptance at the same x, rail and direction (the "
        "rail of the slot on the through route, or the file's first route; as fe frf: 400 "
        "frequencies took 6 s vertical, 29 s lateral): written to <stem>_fe.csv and overlaid "
        "in --plot",
    )
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
    fe = _fe_receptance(args, turnout, receptance.x, frequencies) if args.with_fe else None
    write_output(args.out, receptance.to_csv)
    write_sidecar(args.out, provenance(settings, turnout=turnout, argv=getattr(args, "argv", None)))
    if fe is not None:
        fe_path = str(fe_csv_path(args.out))
        fe_settings = dict(
            settings, model="FE", rail_id=fe.metadata["rail_id"], n_dof=fe.metadata["n_dof"]
        )
        write_output(fe_path, fe.to_csv)
        write_sidecar(
            fe_path, provenance(fe_settings, turnout=turnout, argv=getattr(args, "argv", None))
        )
    if args.plot:
        _plot(receptance, args.plot, fe)
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
    if fe is not None:
        print(
            f"wrote {fe_csv_path(args.out)}: FE {args.rail} ({fe.metadata['rail_id']}) "
            f"{args.direction} at x = {receptance.x:g} m, {fe.metadata['n_dof']} DOFs; "
            f"1/|H({frequencies[0]:g} Hz)| = {fe.static_stiffness:.4g} N/m "
            f"({receptance.model}/FE = {receptance.static_stiffness / fe.static_stiffness:.3f})"
        )
    return 0


def fe_csv_path(out: str) -> Path:
    """The FE receptance's CSV of ``frf --with-fe``: ``<stem>_fe.csv`` beside ``--out``.

    Parameters
    ----------
    out : str
        ``--out`` (the co-running receptance's CSV).

    Returns
    -------
    Path
    """
    p = Path(out)
    return p.with_name(f"{p.stem}_fe{p.suffix or '.csv'}")


def _fe_receptance(args: argparse.Namespace, turnout, x: float, frequencies):
    """The FE receptance at x of the same rail slot and direction (the default route)."""
    from exudyn_turnout.cli.passage import route_from_args
    from exudyn_turnout.fe.frf import fe_receptance
    from exudyn_turnout.fe.layout import load_layout

    check_out_file(str(fe_csv_path(args.out)))
    args.route = None  # frf has no --route: the default route's slot mapping
    route = route_from_args(args, turnout)
    try:
        return fe_receptance(
            turnout,
            args.rail,
            args.direction,
            x,
            frequencies,
            route=route,
            layout=load_layout(turnout),
        )
    except (KeyError, ValueError) as err:
        raise UsageError(f"frf --with-fe: {str(err).strip(chr(39))}") from None


def _plot(receptance, path: str, fe=None) -> None:
    from exudyn_turnout.plotting.curves import plot_receptance, save_figure

    zone, source = receptance.metadata["zone"], receptance.metadata["source"]
    curves = [receptance] if fe is None else [fe, receptance]
    title = f"{receptance.model} co-running track, zone {zone}, {source} parameters"
    if fe is not None:
        title = f"FE reference and {title}"
    fig, _ = plot_receptance(curves, title=title)
    write_output(path, lambda tmp: save_figure(fig, tmp, dpi=120), "--plot")
