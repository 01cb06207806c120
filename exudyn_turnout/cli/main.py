"""Command line: ``exudyn-turnout SUBCOMMAND ...``.

Exit codes: 0 success (also ``--help``, ``--version`` and no arguments at all, which print
the help); 2 bad input (option, turnout or vehicle file, zone, position, output path):
one line on stderr naming the problem, no traceback; 3 a run that failed, diverged or
left every physical state (one line with the time, x and what went wrong). A closed
stdout (``exudyn-turnout params ... | head -1``) ends the command quietly with exit 0.
"""

from __future__ import annotations

import argparse
import csv
import importlib
import io
import json
import math
import os
import sys
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import NoReturn

from exudyn_turnout.corunning.parameters import SOURCES, CoRunningParameters, co_running_parameters
from exudyn_turnout.inputs.turnout import Turnout, TurnoutFileError, load_turnout
from exudyn_turnout.inputs.vehicle_model import VehicleModelError
from exudyn_turnout.passage.settings import PassageError, PassageFailure
from exudyn_turnout.wheel_rail.profiles import ProfileFormatError

__all__ = [
    "main",
    "UsageError",
    "RunFailure",
    "unit_of",
    "add_turnout_options",
    "add_position_options",
    "number",
    "turnout_from_args",
    "kilonewtons",
    "check_out_dir",
    "check_out_file",
    "check_plot_file",
    "write_output",
    "write_sidecar",
    "EXIT_USAGE",
    "EXIT_RUN_FAILED",
]

#: Exit code of bad input (option, file, value, output path).
EXIT_USAGE = 2
#: Exit code of a run that failed, diverged or was stopped as implausible.
EXIT_RUN_FAILED = 3


class UsageError(Exception):
    """Bad input from the command line; the message is printed as one line, exit 2."""


class RunFailure(Exception):
    """A run that failed or was stopped (time, x and what went wrong); one line, exit 3."""


def _writable_place(path: Path, option: str) -> None:
    """The nearest existing ancestor of ``path`` must be a directory we may write into."""
    parent = path.parent
    while not parent.exists() and parent != parent.parent:
        parent = parent.parent
    if not parent.is_dir():
        raise UsageError(f"{option} {path}: {parent} is a file, not a directory")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise UsageError(f"{option} {path}: cannot write into {parent} (permission denied)")


def check_out_dir(path: str, option: str = "--out") -> Path:
    """An output directory: an existing directory, or a place where one can be made.

    Parameters
    ----------
    path : str
        The directory (not created here).
    option : str
        Option name for the message.

    Returns
    -------
    Path

    Raises
    ------
    UsageError
        ``path`` is an existing file, lies under a file, or in an unwritable directory.
    """
    p = Path(path)
    if p.exists() and not p.is_dir():
        raise UsageError(f"{option} {path}: is an existing file, not a directory")
    if p.is_dir():
        if not os.access(p, os.W_OK | os.X_OK):
            raise UsageError(
                f"{option} {path}: cannot write into this directory (permission denied)"
            )
        return p
    _writable_place(p, option)
    return p


#: Figure formats ``--plot`` accepts (matplotlib picks the format from the suffix).
PLOT_SUFFIXES = (
    ".png",
    ".pdf",
    ".svg",
    ".svgz",
    ".jpg",
    ".jpeg",
    ".eps",
    ".ps",
    ".tif",
    ".tiff",
    ".webp",
)


def check_plot_file(path: str, option: str = "--plot") -> Path:
    """A figure file: as :func:`check_out_file`, with a suffix of :data:`PLOT_SUFFIXES`.

    Parameters
    ----------
    path : str
        The figure file.
    option : str
        Option name for the message.

    Returns
    -------
    Path
    """
    if Path(path).suffix.lower() not in PLOT_SUFFIXES:
        raise UsageError(
            f"{option} {path}: the file name must end in one of {', '.join(PLOT_SUFFIXES)}"
        )
    return check_out_file(path, option)


def check_out_file(path: str, option: str = "--out") -> Path:
    """An output file: not a directory, in a directory that exists (or can be made) and is writable.

    An existing file is overwritten (a re-run replaces its own output).

    Parameters
    ----------
    path : str
        The file.
    option : str
        Option name for the message.

    Returns
    -------
    Path

    Raises
    ------
    UsageError
        ``path`` is a directory, lies under a file, or in an unwritable directory.
    """
    p = Path(path)
    if p.is_dir() or str(path).endswith(("/", os.sep)):
        raise UsageError(f"{option} {path}: is a directory, a file name is needed")
    if p.exists() and not os.access(p, os.W_OK):
        raise UsageError(
            f"{option} {path}: the existing file cannot be overwritten (permission denied)"
        )
    _writable_place(p, option)
    return p


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:  # one line, exit 2 (argparse: usage too)
        raise UsageError(f"{self.prog}: {message}")


def write_output(path: str, write, option: str = "--out") -> None:
    """Call ``write(tmp_path)`` and rename the result to ``path`` (never a partial file there).

    The temporary file keeps the extension (plotting picks the format from it).

    Parameters
    ----------
    path : str
        Target file.
    write : callable(str)
        Writes the content to the path it is given.
    option : str
        Option name for the message.

    Raises
    ------
    UsageError
        The file cannot be written.
    """
    p = Path(path)
    tmp = p.with_name(f".{p.stem}.partial-{os.getpid()}{p.suffix}")
    try:
        p.parent.mkdir(parents=True, exist_ok=True)
        write(str(tmp))
        os.replace(tmp, p)
    except OSError as err:
        raise UsageError(f"{option} {path}: cannot write: {err.strerror or err}") from None
    finally:
        if tmp.exists():
            tmp.unlink()


def write_sidecar(path: str, record: dict) -> str:
    """Write the provenance ``record`` of output file ``path`` to ``<stem>.meta.json``.

    Parameters
    ----------
    path : str
        The output file the record describes.
    record : dict
        From :func:`exudyn_turnout.provenance.provenance`.

    Returns
    -------
    str
        Path of the sidecar.
    """
    from exudyn_turnout.provenance import sidecar_path, write_json

    meta = sidecar_path(path)
    try:
        write_json(meta, record)
    except OSError as err:
        raise UsageError(f"--out {path}: cannot write {meta.name}: {err.strerror or err}") from None
    return str(meta)


def unit_of(name: str) -> str:
    """SI unit of a parameter-set entry, from its name.

    Parameters
    ----------
    name : str
        Entry name (``k_rt1_z``, ``m_t``, ...).

    Returns
    -------
    str
    """
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


def kilonewtons(force: float) -> str:
    """A force (N) as "12.3 kN", or "n/a (region not in the run)" where it is not finite.

    Parameters
    ----------
    force : float
        N.

    Returns
    -------
    str
    """
    return f"{force / 1e3:.1f} kN" if math.isfinite(force) else "n/a (region not in the run)"


def number(text: str) -> float:
    """argparse type: a finite float.

    Parameters
    ----------
    text : str
        The option's value.

    Returns
    -------
    float
    """
    value = float(text)
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"must be a finite number, got {text!r}")
    return value


def add_turnout_options(p: argparse.ArgumentParser) -> None:
    """--turnout, --source, --parameters and --profiles, shared by the co-running commands.

    Parameters
    ----------
    p : argparse.ArgumentParser
    """
    p.add_argument(
        "--turnout", metavar="FILE", help="turnout file (default: packaged UIC60-760-1:15)"
    )
    p.add_argument(
        "--source",
        choices=SOURCES,
        default="derived",
        help="derived: Eqs 1-19 on Table 1; published: the paper's Table 2; fitted: fitted "
        "to the FE receptance, from --parameters FILE (exudyn-turnout fit) (default: derived)",
    )
    p.add_argument(
        "--parameters",
        metavar="FILE",
        help="fitted parameter file written by exudyn-turnout fit (for --source fitted)",
    )
    p.add_argument(
        "--profiles",
        choices=("paper", "fe-fit"),
        default="paper",
        help="K_sw(x), K_sh(x) behind Delta_z, Delta_y: the paper's Eqs 10, 14 (default) or "
        "polynomials fitted to our FE reference's static stiffness (computed, ~5 s)",
    )


def turnout_from_args(args: argparse.Namespace) -> Turnout:
    """The turnout of ``--turnout``, with FE-fitted K_sw, K_sh if ``--profiles fe-fit``.

    ``--source published`` on a file without any ``[published.zoneN]`` is an error, and so
    is ``--source fitted`` without ``--parameters FILE`` (the fitted set is read from FILE and
    attached to the turnout, :func:`exudyn_turnout.corunning.fitted.load_fitted`).

    Parameters
    ----------
    args : argparse.Namespace

    Returns
    -------
    Turnout
    """
    turnout = load_turnout(args.turnout)
    if getattr(args, "source", "derived") == "published" and not turnout.published:
        raise UsageError(
            f"--source published: {Path(turnout.source).name} has no published parameter "
            "set ([published.zoneN] sections); use --source derived"
        )
    source, parameters = getattr(args, "source", "derived"), getattr(args, "parameters", None)
    if source == "fitted" and not parameters:
        raise UsageError(
            "--source fitted needs --parameters FILE (a file written by exudyn-turnout fit)"
        )
    if parameters and source != "fitted":
        raise UsageError(f"--parameters {parameters}: only used with --source fitted")
    if parameters:
        from exudyn_turnout.corunning.fitted import load_fitted

        turnout = load_fitted(turnout, parameters)
    if getattr(args, "profiles", "paper") == "fe-fit":
        from exudyn_turnout.fe.fits import fit_turnout_profiles, with_fitted_profiles
        from exudyn_turnout.fe.stiffness import static_stiffness_profile

        turnout = with_fitted_profiles(
            turnout, fit_turnout_profiles(static_stiffness_profile(turnout), turnout)
        )
    return turnout


def add_position_options(p: argparse.ArgumentParser) -> None:
    """--zone N or --x METRES (one of them, required).

    Parameters
    ----------
    p : argparse.ArgumentParser
    """
    where = p.add_mutually_exclusive_group(required=True)
    where.add_argument("--zone", type=int, metavar="N", help="simulation zone (Table 3), 1-based")
    where.add_argument(
        "--x", type=number, metavar="METRES", help="position from the switch toe (m)"
    )


def _parameter_set(args: argparse.Namespace, turnout: Turnout) -> CoRunningParameters:
    try:
        return co_running_parameters(
            turnout, zone=args.zone, x=args.x, layers=args.layers, source=args.source
        )
    except (KeyError, ValueError) as err:
        message = str(err).strip("'\"").replace(turnout.source, Path(turnout.source).name)
        raise UsageError(message) from None


def _zone_rows(p: CoRunningParameters) -> dict[str, object]:
    out: dict[str, object] = {
        "zone": p.zone.index,
        "x_start_m": p.zone.x_start,
        "x_end_m": p.zone.x_end,
        "source": p.source,
        "layers": p.layers,
        "active_rails": " ".join(p.active_rails),
    }
    for name, e in p.entries.items():
        out[name] = e.a
        if e.kind == "ramp":
            out[name + "_end"] = e.b
        if e.kind != "const":
            out[name + "_factor"] = e.kind if e.kind != "ramp" else "linear in x over the zone"
    out.update(p.constants)
    return out


def _x_rows(p: CoRunningParameters, x: float) -> dict[str, object]:
    out: dict[str, object] = {
        "x_m": x,
        "zone": p.zone.index,
        "source": p.source,
        "layers": p.layers,
        "active_rails": " ".join(p.active_rails),
    }
    out.update(p.at(x))
    return out


def _format(rows: dict[str, object], fmt: str) -> str:
    if fmt == "json":
        from exudyn_turnout.provenance import round_floats

        return json.dumps(round_floats(rows), indent=1)
    if fmt == "csv":
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(["name", "value", "unit"])
        for k, v in rows.items():
            w.writerow(
                [
                    k,
                    f"{v:.6g}" if isinstance(v, float) else v,
                    unit_of(k) if isinstance(v, float) else "",
                ]
            )
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


def _provenance_rows(args: argparse.Namespace, turnout: Turnout) -> dict[str, object]:
    """How the set was made, as flat rows: versions, turnout file and SHA-256, command, date."""
    from exudyn_turnout.provenance import provenance

    rec = provenance({"profiles": args.profiles}, turnout=turnout, argv=getattr(args, "argv", None))
    rows: dict[str, object] = {
        "profiles": args.profiles,
        "turnout_file": rec["inputs"]["turnout"]["name"],
        "turnout_sha256": rec["inputs"]["turnout"]["sha256"],
    }
    for key in ("package_version", "exudyn_version", "python_version", "command_line", "date_utc"):
        if key in rec:
            rows[key] = rec[key]
    return rows


def _cmd_params(args: argparse.Namespace) -> int:
    turnout = turnout_from_args(args)
    p = _parameter_set(args, turnout)
    rows = _zone_rows(p) if args.zone is not None else _x_rows(p, args.x)
    if args.format != "table":
        rows.update(_provenance_rows(args, turnout))
    print(_format(rows, args.format))
    return 0


def _build_params(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "params",
        help="equivalent co-running parameters (Eqs 1-19 / Table 2)",
        description="Print the co-running parameter set of a zone (Table 2 form: "
        "coefficients with their Delta factor) or at a position x (numbers).",
    )
    add_turnout_options(p)
    add_position_options(p)
    p.add_argument(
        "--layers", type=int, choices=(2, 3), default=3, help="track model layers (default 3)"
    )
    p.add_argument("--format", choices=("table", "csv", "json"), default="table")
    p.set_defaults(run=_cmd_params)


#: Modules defining further subcommands, each with ``build(subparsers)``. A subcommand
#: module must not import exudyn or matplotlib at import time (import inside its run
#: function) so that every command starts fast.
_COMMAND_MODULES: tuple[str, ...] = (
    "exudyn_turnout.cli.track",
    "exudyn_turnout.cli.passage",
    "exudyn_turnout.cli.validate",
    "exudyn_turnout.cli.fe",
    "exudyn_turnout.cli.draw",
    "exudyn_turnout.cli.study",
    "exudyn_turnout.cli.fit",
)


def _version_text() -> str:
    from exudyn_turnout import __version__
    from exudyn_turnout.provenance import provenance

    rec = provenance()
    return (
        f"exudyn-turnout {__version__} (exudyn {rec['exudyn_version']}, "
        f"Python {rec['python_version']})"
    )


def _parser() -> _Parser:
    parser = _Parser(
        prog="exudyn-turnout",
        description="Co-running turnout track models on Exudyn (Shih, Ambur & Dixon 2023).",
        epilog="Exit codes: 0 done, 2 bad input (one line on stderr), 3 a run that "
        "failed or was stopped as implausible.",
    )
    parser.add_argument("--version", action="version", version=_version_text())
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    _build_params(sub)
    for name in _COMMAND_MODULES:
        importlib.import_module(name).build(sub)
    return parser


def _quiet_stdout() -> None:
    """After a closed pipe: send what is left of stdout to /dev/null (no error at exit)."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):  # stdout without a file descriptor (tests)
        pass


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``exudyn-turnout``; returns the exit code.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments without the program name (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        0 done (also help, version, no arguments: the help), 2 bad input, 3 a failed or
        stopped run (see the module docstring).
    """
    argv = list(sys.argv[1:] if argv is None else argv)
    with warnings.catch_warnings():
        warnings.showwarning = _one_line_warning
        return _main(argv)


def _one_line_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """Print a warning as one line ``warning: ...`` on stderr (no source line)."""
    print(f"warning: {message}", file=sys.stderr)


def _main(argv: list[str]) -> int:
    try:
        parser = _parser()
        if not argv:
            parser.print_help()
            return 0
        try:
            args = parser.parse_args(argv)
        except SystemExit as exit_:  # --help, --version
            return int(exit_.code or 0)
        args.argv = argv
        code = args.run(args)
        sys.stdout.flush()
        return code
    except (RunFailure, PassageFailure) as err:
        print(f"error: {err}", file=sys.stderr)
        return EXIT_RUN_FAILED
    except (
        UsageError,
        TurnoutFileError,
        VehicleModelError,
        ProfileFormatError,
        PassageError,
    ) as err:  # every command: a bad input file is one line, whichever stage finds it
        print(f"error: {err}", file=sys.stderr)
        return EXIT_USAGE
    except BrokenPipeError:
        _quiet_stdout()
        return 0


if __name__ == "__main__":
    sys.exit(main())
