"""How an output was made: versions, input files (name and SHA-256), settings, command, date.

Every file the package writes carries this record: ``summary.json`` of ``simulate`` and
``fe simulate`` under the key ``provenance``, the CSV outputs of ``frf``, ``fe frf`` and
``fe stiffness`` in a sidecar ``<stem>.meta.json`` (the CSV stays a plain table), the
``params`` CSV/JSON as extra rows/keys, ``metrics.json`` of ``validate`` under
``provenance``. No absolute path of the machine that ran it is recorded: files by name
(with the SHA-256 of their content), the command line with absolute paths reduced to
file names. Floats are rounded to 9 significant digits (:func:`round_floats`).
"""

from __future__ import annotations

import datetime
import hashlib
import json
import math
import os
import platform
from collections.abc import Mapping, Sequence
from importlib import metadata
from pathlib import Path
from typing import Any

__all__ = [
    "provenance",
    "file_record",
    "reduce_argv",
    "round_floats",
    "write_json",
    "sidecar_path",
    "SIGNIFICANT_DIGITS",
]

#: Significant digits kept by :func:`round_floats` (9: no 2.3399999999999808, and below the
#: solvers' tolerances by orders of magnitude).
SIGNIFICANT_DIGITS = 9


def round_floats(value: Any, digits: int = SIGNIFICANT_DIGITS) -> Any:
    """``value`` with every float (in dicts, lists, tuples too) rounded to ``digits`` digits.

    Non-finite floats become None (JSON has no NaN); numpy scalars become Python numbers.

    Parameters
    ----------
    value : any
        A number, string, mapping or sequence (nested).
    digits : int
        Significant digits.

    Returns
    -------
    any
        The same structure with rounded floats (tuples become lists).
    """
    if isinstance(value, bool) or value is None or isinstance(value, str):
        return value
    if isinstance(value, Mapping):
        return {str(k): round_floats(v, digits) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [round_floats(v, digits) for v in value]
    if hasattr(value, "item") and hasattr(value, "dtype"):  # numpy scalar / 0-d array
        return round_floats(
            value.item() if getattr(value, "ndim", 0) == 0 else value.tolist(), digits
        )
    if isinstance(value, int):
        return value
    if isinstance(value, float):
        if not math.isfinite(value):
            return None
        return float(f"{value:.{digits}g}") + 0.0  # + 0.0: no "-0.0"
    return value


def file_record(path: str | Path | None) -> dict[str, str] | None:
    """``{"name": file name, "sha256": hex digest of its content}``; None without a path.

    Parameters
    ----------
    path : str or Path or None
        The input file.

    Returns
    -------
    dict or None
        Its name (no directory) and the SHA-256 of its bytes ("unreadable" if it cannot be
        read).
    """
    if path is None:
        return None
    file = Path(str(path))
    try:
        digest = hashlib.sha256(file.read_bytes()).hexdigest()
    except OSError:
        digest = "unreadable"
    return {"name": file.name, "sha256": digest}


def reduce_argv(argv: Sequence[str]) -> list[str]:
    """The command line with absolute paths reduced to their file names.

    ``--out=/home/me/run`` becomes ``--out=run``; relative paths are kept as given.

    Parameters
    ----------
    argv : sequence of str
        Arguments (without the program name).

    Returns
    -------
    list of str
        The arguments, absolute paths (also after ``--option=``) replaced by their names.
    """
    out = []
    for arg in argv:
        arg = str(arg)
        key, eq, value = (
            arg.partition("=") if arg.startswith("--") and "=" in arg else ("", "", arg)
        )
        if value and (os.path.isabs(value) or value.startswith("~")):
            value = Path(os.path.expanduser(value)).name or value
        out.append(f"{key}{eq}{value}" if eq else value)
    return out


def _version(distribution: str) -> str:
    try:
        return metadata.version(distribution)
    except metadata.PackageNotFoundError:
        return "not installed"


def _source_of(item: Any) -> Any:
    """A path from a path, or from an object with a ``source`` attribute (Turnout, Vehicle)."""
    return getattr(item, "source", item)


def provenance(
    settings: Mapping[str, Any] | None = None,
    *,
    turnout: Any = None,
    vehicle: Any = None,
    argv: Sequence[str] | None = None,
    files: Mapping[str, Any] | None = None,
    command: str = "exudyn-turnout",
) -> dict[str, Any]:
    """The record of how an output was made (JSON-ready, floats rounded).

    Parameters
    ----------
    settings : mapping, optional
        Every setting of the run (route, speed, layers, source, profiles, x range, time
        step, output step, ...); stored as given, floats rounded.
    turnout, vehicle : Turnout, Vehicle, str or Path, optional
        The input files (an object with a ``source`` path, or a path): recorded by name
        and SHA-256 of their content.
    argv : sequence of str, optional
        The command line's arguments (without the program name); absolute paths are
        reduced to file names.
    files : mapping, optional
        Further input files, name -> path.
    command : str
        Program name put in front of ``argv`` in ``command_line``.

    Returns
    -------
    dict
        ``package``, ``package_version``, ``exudyn_version``, ``python_version``,
        ``platform``, ``inputs`` ({"turnout": {"name", "sha256"}, ...}), ``settings``,
        ``argv``, ``command_line``, ``date_utc`` (ISO 8601, seconds).

    Examples
    --------
    In the report code: ``metrics["provenance"] = provenance({"quick": config.quick},
    turnout=turnout)``.
    """
    from exudyn_turnout import __version__

    inputs = {
        "turnout": file_record(_source_of(turnout)) if turnout is not None else None,
        "vehicle": file_record(_source_of(vehicle)) if vehicle is not None else None,
    }
    for name, path in (files or {}).items():
        inputs[name] = file_record(_source_of(path))
    record: dict[str, Any] = {
        "package": "exudyn_turnout",
        "package_version": __version__,
        "exudyn_version": _version("exudyn"),
        "python_version": platform.python_version(),
        "platform": platform.system(),
        "inputs": {k: v for k, v in inputs.items() if v is not None},
        "settings": dict(settings or {}),
    }
    if argv is not None:
        reduced = reduce_argv(argv)
        record["argv"] = reduced
        record["command_line"] = " ".join([command] + reduced)
    record["date_utc"] = datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")
    return round_floats(record)


def sidecar_path(path: str | Path) -> Path:
    """``<dir>/<stem>.meta.json`` next to an output file ``<dir>/<stem>.<ext>``.

    Parameters
    ----------
    path : str or Path
        The output file.

    Returns
    -------
    Path
        The sidecar file's path (in the output file's directory).
    """
    output = Path(path)
    return output.with_name(output.stem + ".meta.json")


def write_json(path: str | Path, data: Mapping[str, Any]) -> None:
    """Write ``data`` (floats rounded) as JSON, atomically: a temporary file, then renamed.

    Parameters
    ----------
    path : str or Path
        Target file; never left partially written.
    data : mapping
        JSON-ready content.
    """
    target = Path(path)
    tmp = target.with_name(f".{target.name}.{os.getpid()}.tmp")
    try:
        tmp.write_text(json.dumps(round_floats(data), indent=1) + "\n", encoding="utf-8")
        os.replace(tmp, target)
    finally:
        if tmp.exists():
            tmp.unlink()
