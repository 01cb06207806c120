"""``exudyn-turnout fe ...``: the FE reference model of the turnout.

``fe frf``        point receptance of a rail at x (CSV: frequency_hz,real,imag,magnitude)
``fe stiffness``  static stiffness at every sleeper for every rail (CSV:
                  x_m,rail,K_z_N_per_m,K_y_N_per_m), with the Eq 10 / 14 analogue fits

numpy/scipy only; matplotlib is imported only when ``--plot`` is given.
"""

from __future__ import annotations

import argparse
import time

from exudyn_turnout.cli.fe_passage import add_simulate
from exudyn_turnout.cli.main import (
    UsageError,
    check_out_file,
    check_plot_file,
    number,
    write_output,
    write_sidecar,
)
from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.receptance import DIRECTIONS, log_frequencies

__all__ = ["build"]


def _turnout_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--turnout",
        metavar="FILE",
        help="turnout file with a [layout] section (default: packaged UIC60-760-1:15)",
    )


def _check_outputs(args: argparse.Namespace) -> None:
    check_out_file(args.out)
    if args.plot:
        check_plot_file(args.plot)


def _save_plot(fig, path: str) -> None:
    from exudyn_turnout.plotting.curves import save_figure

    write_output(path, lambda tmp: save_figure(fig, tmp, dpi=120), "--plot")
    print(f"plot -> {path}")


def _cmd_frf(args: argparse.Namespace) -> int:
    from exudyn_turnout.cli.passage import route_from_args
    from exudyn_turnout.fe.frf import fe_receptance
    from exudyn_turnout.fe.layout import load_layout
    from exudyn_turnout.provenance import provenance

    _check_outputs(args)
    turnout = load_turnout(args.turnout)
    route = route_from_args(args, turnout)
    layout = load_layout(turnout)
    try:
        frequencies = log_frequencies(args.fmin, args.fmax, args.n)
        t0 = time.perf_counter()
        receptance = fe_receptance(
            turnout, args.rail, args.direction, args.x, frequencies, route=route, layout=layout
        )
    except ValueError as err:
        raise UsageError(str(err)) from None
    write_output(args.out, receptance.to_csv)
    settings = {
        "model": "FE",
        "rail": args.rail,
        "rail_id": receptance.metadata["rail_id"],
        "direction": args.direction,
        "x_m": args.x,
        "route": route,
        "fmin_hz": args.fmin,
        "fmax_hz": args.fmax,
        "n": args.n,
        "n_dof": receptance.metadata["n_dof"],
    }
    write_sidecar(args.out, provenance(settings, turnout=turnout, argv=getattr(args, "argv", None)))
    rail_id, n_dof = receptance.metadata["rail_id"], receptance.metadata["n_dof"]
    print(
        f"FE receptance {args.rail} ({rail_id}) {args.direction} at x = {args.x:g} m: "
        f"{len(frequencies)} frequencies {args.fmin:g}-{args.fmax:g} Hz, {n_dof} DOFs, "
        f"{time.perf_counter() - t0:.1f} s; static stiffness "
        f"1/|H({frequencies[0]:g} Hz)| = {receptance.static_stiffness:.4g} N/m -> {args.out}"
    )
    if args.plot:
        from exudyn_turnout.plotting.curves import plot_receptance

        fig, _ = plot_receptance(
            receptance, title=f"FE {args.rail} ({rail_id}) {args.direction}, x = {args.x:g} m"
        )
        _save_plot(fig, args.plot)
    return 0


def _cmd_stiffness(args: argparse.Namespace) -> int:
    from exudyn_turnout.fe.fits import fit_turnout_profiles
    from exudyn_turnout.fe.layout import load_layout
    from exudyn_turnout.fe.stiffness import static_stiffness_profile
    from exudyn_turnout.provenance import provenance

    _check_outputs(args)
    turnout = load_turnout(args.turnout)
    layout = load_layout(turnout)
    t0 = time.perf_counter()
    profile = static_stiffness_profile(turnout, layout)
    fits = fit_turnout_profiles(profile, turnout, layout)
    write_output(args.out, profile.to_csv)
    settings = {
        "model": "FE",
        "quantity": "static stiffness 1/|H(1 Hz)| at every sleeper, every rail",
        "n_dof": dict(profile.n_dof),
        "fits": {
            name: {
                "rail": fit.rail,
                "direction": fit.direction,
                "x_min_m": fit.x_min,
                "x_max_m": fit.x_max,
                "coefficients": list(fit.coefficients),
                "r_squared": fit.r_squared,
            }
            for name, fit in (("K_sw", fits.K_sw), ("K_sh", fits.K_sh))
        },
    }
    write_sidecar(args.out, provenance(settings, turnout=turnout, argv=getattr(args, "argv", None)))
    print(
        f"FE static stiffness 1/|H(1 Hz)|: {len(profile.x)} rail positions, "
        f"{len(profile.rails)} rails, "
        f"DOFs {profile.n_dof['vertical']} vertical / {profile.n_dof['lateral']} lateral, "
        f"{time.perf_counter() - t0:.1f} s -> {args.out}"
    )
    for name, fit, paper, eq in (
        ("K_sw", fits.K_sw, turnout.K_sw, "Eq 10"),
        ("K_sh", fits.K_sh, turnout.K_sh, "Eq 14"),
    ):
        terms = " + ".join(
            f"{c:.4g} x^{i}" if i else f"{c:.4g}" for i, c in enumerate(fit.coefficients)
        )
        paper_terms = " + ".join(
            f"{c:.4g} x^{i}" if i else f"{c:.4g}" for i, c in enumerate(paper.coefficients)
        )
        print(
            f"{name} ({fit.direction}, rail {fit.rail}, {fit.x_min:g}-{fit.x_max:g} m): "
            f"{terms} N/m, R^2 = {fit.r_squared:.3f}; paper {eq}: {paper_terms}"
        )
    if args.plot:
        from exudyn_turnout.plotting.curves import plot_stiffness_profile

        fig, _ = plot_stiffness_profile(profile, fits, turnout)
        _save_plot(fig, args.plot)
    return 0


def build(sub: argparse._SubParsersAction) -> None:
    """Register the command on the ``exudyn-turnout`` subcommand parsers.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subcommand parsers of ``exudyn-turnout``; ``fe`` with its subcommands ``frf``,
        ``stiffness`` and ``simulate`` is added to them.
    """
    fe = sub.add_parser(
        "fe",
        help="FE reference model of the turnout (receptance, static stiffness)",
        description="Timoshenko rails on discrete pads, sleepers as beams on ballast, "
        "the turnout layout of the file's [layout] section.",
    )
    fe_sub = fe.add_subparsers(dest="fe_command", required=True, parser_class=type(fe))
    frf_parser = fe_sub.add_parser(
        "frf", help="point receptance of a rail at x (direct frequency-domain solve)"
    )
    frf_parser.add_argument(
        "--rail",
        required=True,
        metavar="RAIL",
        help="co-running slot r1|r2|r3|r4 (layout.slots of the route) or a layout rail id",
    )
    frf_parser.add_argument("--direction", required=True, choices=DIRECTIONS)
    frf_parser.add_argument(
        "--x", required=True, type=number, metavar="METRES", help="position from the switch toe (m)"
    )
    frf_parser.add_argument(
        "--route",
        metavar="NAME",
        help="route of the turnout file: which slot mapping (default: through, or the first route)",
    )
    frf_parser.add_argument(
        "--fmin", type=number, default=1.0, help="lowest frequency (Hz, default 1)"
    )
    frf_parser.add_argument(
        "--fmax", type=number, default=2000.0, help="highest frequency (Hz, default 2000)"
    )
    frf_parser.add_argument(
        "--n", type=int, default=400, help="number of log-spaced frequencies (default 400)"
    )
    frf_parser.add_argument("--out", required=True, metavar="FILE.csv")
    frf_parser.add_argument("--plot", metavar="FILE.png")
    _turnout_option(frf_parser)
    frf_parser.set_defaults(run=_cmd_frf)
    stiffness_parser = fe_sub.add_parser(
        "stiffness",
        help="static stiffness 1/|H(1 Hz)| at every sleeper, every rail "
        "(paper Fig. 1(b,c)) and the Eq 10 / 14 analogue fits",
    )
    stiffness_parser.add_argument("--out", required=True, metavar="FILE.csv")
    stiffness_parser.add_argument("--plot", metavar="FILE.png")
    _turnout_option(stiffness_parser)
    stiffness_parser.set_defaults(run=_cmd_stiffness)
    add_simulate(fe_sub)
