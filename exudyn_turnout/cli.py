"""Command line: ``exudyn-turnout SUBCOMMAND ...``.

Every bad input (option, turnout file, zone, position) ends with one line on stderr
naming the problem and exit code 2; no traceback.
"""
from __future__ import annotations

import argparse
import csv
import importlib
import io
import json
import math
import sys
from typing import Sequence

from .parameters import SOURCES, CoRunningParameters, co_running_parameters
from .turnout import Turnout, TurnoutFileError, load_turnout

__all__ = ["main", "UsageError", "unit_of", "add_turnout_options", "add_position_options", "number",
           "turnout_from_args", "kilonewtons", "progress_bar"]


class UsageError(Exception):
    """Bad input from the command line; the message is printed as one line, exit 2."""


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # one line, exit 2 (argparse prints usage too)
        raise UsageError(f"{self.prog}: {message}")


def unit_of(name: str) -> str:
    """SI unit of a parameter-set entry, from its name."""
    if name.startswith(("k_", "K_st")):
        return "N/m"
    if name.startswith("c_"):
        return "N s/m"
    if name.startswith("m_"):
        return "kg"
    if name == "J_t":
        return "kg m^2"
    if name.startswith("L_eff_r") or name.endswith("_m"):
        return "m"
    return "-"


def progress_bar(stream):
    """A one-line progress bar on a terminal; nothing when output is not a terminal."""
    if not stream.isatty():
        return None

    def show(fraction: float, x: float) -> None:
        n = int(30 * fraction)
        stream.write(f"\r[{'#' * n}{'.' * (30 - n)}] {100 * fraction:5.1f} %  x = {x:7.2f} m")
        stream.flush()
    return show


def kilonewtons(force: float) -> str:
    """A force (N) as "12.3 kN", or "n/a (region not in the run)" where it is not finite."""
    return f"{force / 1e3:.1f} kN" if math.isfinite(force) else "n/a (region not in the run)"


def number(text: str) -> float:
    value = float(text)
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"must be a finite number, got {text!r}")
    return value


def add_turnout_options(p: argparse.ArgumentParser) -> None:
    """--turnout, --source and --profiles, shared by the co-running commands."""
    p.add_argument("--turnout", metavar="FILE", help="turnout file (default: packaged UIC60-760-1:15)")
    p.add_argument("--source", choices=SOURCES, default="derived",
                   help="derived: Eqs 1-19 on Table 1; published: the paper's Table 2 (default: derived)")
    p.add_argument("--profiles", choices=("paper", "fe-fit"), default="paper",
                   help="K_sw(x), K_sh(x) behind Delta_z, Delta_y: the paper's Eqs 10, 14 (default) or "
                        "polynomials fitted to our FE reference's static stiffness (computed, ~5 s)")


def turnout_from_args(args: argparse.Namespace) -> Turnout:
    """The turnout of ``--turnout``, with FE-fitted K_sw, K_sh if ``--profiles fe-fit``."""
    turnout = load_turnout(args.turnout)
    if getattr(args, "profiles", "paper") == "fe-fit":
        from .fe.fits import fit_turnout_profiles, with_fitted_profiles
        from .fe.stiffness import static_stiffness_profile
        turnout = with_fitted_profiles(turnout, fit_turnout_profiles(static_stiffness_profile(turnout), turnout))
    return turnout


def add_position_options(p: argparse.ArgumentParser) -> None:
    where = p.add_mutually_exclusive_group(required=True)
    where.add_argument("--zone", type=int, metavar="N", help="simulation zone (Table 3), 1-based")
    where.add_argument("--x", type=number, metavar="METRES", help="position from the switch toe (m)")


def _parameter_set(args: argparse.Namespace, turnout: Turnout) -> CoRunningParameters:
    try:
        return co_running_parameters(turnout, zone=args.zone, x=args.x, layers=args.layers, source=args.source)
    except (KeyError, ValueError) as err:
        raise UsageError(str(err).strip("'\"")) from None


def _zone_rows(p: CoRunningParameters) -> dict[str, object]:
    out: dict[str, object] = {"zone": p.zone.index, "x_start_m": p.zone.x_start, "x_end_m": p.zone.x_end,
                              "source": p.source, "layers": p.layers, "active_rails": " ".join(p.active_rails)}
    for name, e in p.entries.items():
        out[name] = e.a
        if e.kind == "ramp":
            out[name + "_end"] = e.b
        if e.kind != "const":
            out[name + "_factor"] = e.kind if e.kind != "ramp" else "linear in x over the zone"
    out.update(p.constants)
    return out


def _x_rows(p: CoRunningParameters, x: float) -> dict[str, object]:
    out: dict[str, object] = {"x_m": x, "zone": p.zone.index, "source": p.source, "layers": p.layers,
                              "active_rails": " ".join(p.active_rails)}
    out.update(p.at(x))
    return out


def _format(rows: dict[str, object], fmt: str) -> str:
    if fmt == "json":
        return json.dumps(rows, indent=1)
    if fmt == "csv":
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(["name", "value", "unit"])
        for k, v in rows.items():
            w.writerow([k, f"{v:.6g}" if isinstance(v, float) else v, unit_of(k) if isinstance(v, float) else ""])
        return buf.getvalue().rstrip("\n")
    lines = []
    for k, v in rows.items():
        if k.endswith(("_factor", "_end")):
            continue
        text = f"{v:.4g}" if isinstance(v, float) else str(v)
        factor = rows.get(k + "_factor")
        if factor == "linear in x over the zone":
            text = f"{v:.4g} -> {rows[k + '_end']:.4g} (linear in x)"
        elif factor:
            text += f" * {factor}"
        lines.append(f"{k:<12} {text:<34} {unit_of(k) if isinstance(v, float) else ''}")
    return "\n".join(lines)


def _cmd_params(args: argparse.Namespace) -> int:
    turnout = turnout_from_args(args)
    p = _parameter_set(args, turnout)
    rows = _zone_rows(p) if args.zone is not None else _x_rows(p, args.x)
    print(_format(rows, args.format))
    return 0


def _build_params(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("params", help="equivalent co-running parameters (Eqs 1-19 / Table 2)",
                       description="Print the co-running parameter set of a zone (Table 2 form: "
                                   "coefficients with their Delta factor) or at a position x (numbers).")
    add_turnout_options(p)
    add_position_options(p)
    p.add_argument("--layers", type=int, choices=(2, 3), default=3, help="track model layers (default 3)")
    p.add_argument("--format", choices=("table", "csv", "json"), default="table")
    p.set_defaults(run=_cmd_params)


#: Modules defining further subcommands, each with ``build(subparsers)``. A subcommand
#: module must not import exudyn or matplotlib at import time (import inside its run
#: function) so that every command starts fast.
_COMMAND_MODULES: tuple[str, ...] = ("exudyn_turnout.cli_track", "exudyn_turnout.cli_passage", "exudyn_turnout.cli_validate",
                                      "exudyn_turnout.cli_fe")


def _parser() -> _Parser:
    parser = _Parser(prog="exudyn-turnout",
                     description="Co-running turnout track models on Exudyn (Shih, Ambur & Dixon 2023).")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    _build_params(sub)
    for name in _COMMAND_MODULES:
        importlib.import_module(name).build(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``exudyn-turnout``; returns the exit code."""
    try:
        args = _parser().parse_args(argv)
        return args.run(args)
    except (UsageError, TurnoutFileError) as err:
        print(f"error: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
