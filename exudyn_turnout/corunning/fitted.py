"""Fitted co-running parameter sets: entries as functions of x, and their TOML file.

A fitted set (:mod:`exudyn_turnout.corunning.fit`) holds, per zone, the co-running entries
whose values were chosen to match the FE receptance. Entries that were fitted at several
positions of a zone are :class:`TableEntry` objects: piecewise linear in the relative zone
position s = (x - x_start) / (x_end - x_start), held at the end values outside the fitted
positions (the analogue of the paper's Eqs 10 and 14, which are polynomials in x). Masses
are constant per zone, as in the paper.

The file (``exudyn-turnout fit --out fitted.toml``) is plain TOML::

    [fitted]                     # provenance: turnout file and its SHA-256, layers, route,
    format = 2                   # frequency range, FE options, optimiser, weights, date
    turnout = "UIC60-760-1:15"
    turnout_sha256 = "..."       # the turnout file's bytes (provenance only)
    turnout_model_sha256 = "..." # what the fit depends on: turnout_model_sha256(turnout)
    layers = 3
    band_centres_hz = [...]      # 1/3-octave centres of the residuals below
    [fitted.fe_options]
    element_order = 4
    [zone1]
    s = [0.05, 0.5, 0.95]        # relative zone positions of the fits
    x_m = [...]
    [zone1.entries]
    k_rt2_z = [1.1e8, 1.3e8, 1.2e8]   # N/m, one value per s (a table), or
    m_r2 = 171.0                      # kg, one number (constant over the zone), or
    c_02_y = { s = [0.0, 1.0], values = [2e5, 3e5] }  # N s/m, a table on its own s
    [[zone1.residuals]]          # per position, rail and direction: band RMS (dB) of
    x_m = 3.9                    # 20 log10(|H_model| / |H_FE|), derived and fitted
    rail = "r2"
    direction = "vertical"
    derived_db = [...]
    fitted_db = [...]

:func:`read_fitted` checks the whole file and raises
:class:`~exudyn_turnout.inputs.turnout.TurnoutFileError` naming the file and the field;
:func:`with_fitted` returns the turnout carrying the set, which
``co_running_parameters(..., source="fitted")`` then uses.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import tomllib
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from exudyn_turnout.inputs.turnout import PARAMETER_NAMES, Entry, Turnout, TurnoutFileError

__all__ = [
    "TableEntry",
    "FittedSet",
    "FITTED_FORMAT",
    "file_sha256",
    "MODEL_SECTIONS",
    "turnout_model_sha256",
    "fitted_toml",
    "write_fitted",
    "read_fitted",
    "with_fitted",
    "load_fitted",
]

#: Version of the fitted-file format written by :func:`write_fitted` (2: with
#: ``fitted.turnout_model_sha256``; 1, without it, is still read, with a warning).
FITTED_FORMAT = 2

#: Sections of a turnout file that a fitted set depends on (the FE model it was fitted to
#: and the co-running model it starts from): rails, pads, sleepers, ballast, the support
#: polynomials, the third layer, the zones, the layout, the check rail's L-bracket in the
#: FE (``check_rail.support``) and the co-running check rail (``check_rail.co_running``).
#: A dotted name is a sub-table; it enters the hash only when the file has it (a turnout
#: without it keeps the hash it had before it was added here). Comments, formatting and the
#: other sections (routes, regions, the check rail's clearance and flares, wheel/rail
#: design, report, Table 2) do not enter :func:`turnout_model_sha256`, so editing them keeps
#: a fitted file valid.
MODEL_SECTIONS = (
    "rail_types",
    "sleeper",
    "ballast",
    "stiffness_profiles",
    "extra_layer",
    "zones",
    "layout",
    "check_rail.support",
    "check_rail.co_running",
)

#: SI upper bounds of fitted values (those of the turnout file, ``inputs.turnout.BOUNDS``).
_UPPER = {"k": 1e12, "c": 1e10, "m": 1e5, "J": 1e5}


@dataclass(frozen=True)
class TableEntry(Entry):
    """An entry piecewise linear in the relative zone position s (kind ``"table"``).

    ``a`` holds the first value (what ``params --zone`` prints), ``b`` the last. Outside
    ``[s_points[0], s_points[-1]]`` the value is held at the end values.
    """

    s_points: tuple[float, ...] = ()  #: -, relative zone positions, increasing
    values: tuple[float, ...] = ()  #: SI, the entry's value at each s

    @classmethod
    def of(cls, s_points: Sequence[float], values: Sequence[float]) -> TableEntry:
        """A table entry from its points.

        Parameters
        ----------
        s_points : sequence of float
            Relative zone positions (-), strictly increasing.
        values : sequence of float
            Values (SI), one per position.

        Returns
        -------
        TableEntry
            kind ``"table"``, ``a`` and ``b`` the first and last value.
        """
        s, v = tuple(float(x) for x in s_points), tuple(float(x) for x in values)
        if len(s) != len(v) or not s:
            raise ValueError(f"a table needs as many values as positions, got {len(s)}, {len(v)}")
        if any(b <= a for a, b in zip(s, s[1:])):
            raise ValueError(f"table positions must increase, got {s}")
        return cls("table", v[0], v[-1], s, v)

    def value(self, delta_z: float, delta_y: float, s: float) -> float:
        """Value at relative zone position s (Delta_z, Delta_y are not used).

        Parameters
        ----------
        delta_z, delta_y : float
            Ignored (a fitted value is absolute).
        s : float
            Relative position in the zone (-).

        Returns
        -------
        float
            Linear interpolation of the table, held at its end values.
        """
        return float(np.interp(s, self.s_points, self.values))

    def ramps(self) -> tuple[float, tuple[tuple[float, float, float], ...]]:
        """The table as a start value plus clamped ramps (for min/max-only evaluation).

        value(s) = v_0 + sum_i (v_{i+1} - v_i) clamp((s - s_i) / (s_{i+1} - s_i), 0, 1).

        Returns
        -------
        v0 : float
            The first value (SI).
        ramps : tuple of (s_i, 1 / (s_{i+1} - s_i), v_{i+1} - v_i)
            One ramp per table segment.
        """
        s, v = self.s_points, self.values
        return v[0], tuple(
            (s[i], 1.0 / (s[i + 1] - s[i]), v[i + 1] - v[i]) for i in range(len(s) - 1)
        )

    def describe(self) -> str:
        """The entry in words: its range over the table.

        Returns
        -------
        str
            "fitted 1.2e+08 .. 1.4e+08 (table of 5 points)" or the constant value.
        """
        if len(self.values) == 1:
            return f"{self.a:.4g} (fitted)"
        return (
            f"fitted {min(self.values):.4g} .. {max(self.values):.4g} "
            f"(table of {len(self.values)} points)"
        )


@dataclass(frozen=True)
class FittedSet:
    """A fitted co-running parameter set of a turnout with its provenance and residuals."""

    layers: int  #: 2 or 3
    entries: Mapping[int, Mapping[str, Entry]]  #: zone index -> fitted entries
    #: zone index -> (s, x in m) of the fit positions
    positions: Mapping[int, tuple[tuple[float, ...], tuple[float, ...]]]
    provenance: Mapping[str, Any] = field(default_factory=dict)  #: turnout hash, options...
    band_centres_hz: tuple[float, ...] = ()  #: Hz, centres of the residual bands
    #: per zone, one dict per (x, rail, direction): x_m, rail, direction, derived_db, fitted_db
    residuals: Mapping[int, tuple[Mapping[str, Any], ...]] = field(default_factory=dict)
    source: str = ""  #: file the set was read from ("" when computed)


def file_sha256(path: str | Path) -> str:
    """SHA-256 (hex) of a file's content.

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    str
        64 hex digits.
    """
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def turnout_model_sha256(turnout: Turnout) -> str:
    """SHA-256 (hex) of the turnout's :data:`MODEL_SECTIONS`, as parsed (canonical JSON).

    Parameters
    ----------
    turnout : Turnout
        A loaded turnout (its ``raw`` sections are hashed, keys sorted).

    Returns
    -------
    str
        64 hex digits; the same for two files that differ only in comments, layout of the
        text or sections outside :data:`MODEL_SECTIONS`.
    """
    model: dict[str, Any] = {}
    for name in MODEL_SECTIONS:
        head, _, sub = name.partition(".")
        value = turnout.raw.get(head)
        if not sub:
            model[name] = value
        elif isinstance(value, Mapping) and sub in value:
            model[name] = value[sub]
    text = json.dumps(model, sort_keys=True, separators=(",", ":"), default=repr)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"cannot write a non-finite number ({value!r}) to a fitted file")
        return repr(float(value))
    if isinstance(value, str):
        escaped = value.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")
        return f'"{escaped}"'
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if value is None:
        return '"none"'
    raise TypeError(f"cannot write {type(value).__name__} to TOML")


def _key(name: str) -> str:
    return name if name.replace("_", "").isalnum() else _toml_value(name)


def fitted_toml(fitted: FittedSet) -> str:
    """The fitted set as TOML text (floats written with all their digits: exact round trip).

    Parameters
    ----------
    fitted : FittedSet
        The set to write.

    Returns
    -------
    str
        The file content (see the module docstring for the layout).
    """
    lines = [
        "# Co-running parameters fitted to the FE receptance (exudyn-turnout fit).",
        "# SI units. Written by exudyn_turnout.corunning.fitted: values of the fit, do not edit.",
        *(
            [f"# FE reference: {fitted.provenance['fe_reference']}."]
            if "fe_reference" in fitted.provenance
            else []
        ),
        "[fitted]",
        f"format = {FITTED_FORMAT}",
        f"layers = {fitted.layers}",
        f"band_centres_hz = {_toml_value(list(fitted.band_centres_hz))}",
    ]
    nested = {k: v for k, v in fitted.provenance.items() if isinstance(v, Mapping)}
    for key, value in fitted.provenance.items():
        if key not in nested and key not in ("format", "layers", "band_centres_hz"):
            lines.append(f"{_key(key)} = {_toml_value(value)}")
    for key, table in nested.items():
        lines += ["", f"[fitted.{_key(key)}]"]
        lines += [f"{_key(k)} = {_toml_value(v)}" for k, v in table.items()]
    for zone in sorted(fitted.entries):
        s, x = fitted.positions[zone]
        lines += [
            "",
            f"[zone{zone}]",
            f"s = {_toml_value(list(s))}",
            f"x_m = {_toml_value(list(x))}",
            "",
            f"[zone{zone}.entries]",
        ]
        for name, entry in fitted.entries[zone].items():
            if not isinstance(entry, TableEntry):
                text = _toml_value(entry.a)
            elif tuple(entry.s_points) == tuple(s):
                text = _toml_value(list(entry.values))
            else:  # a table on its own positions
                text = (
                    f"{{ s = {_toml_value(list(entry.s_points))}, "
                    f"values = {_toml_value(list(entry.values))} }}"
                )
            lines.append(f"{name} = {text}")
        for row in fitted.residuals.get(zone, ()):
            lines += ["", f"[[zone{zone}.residuals]]"]
            lines += [f"{_key(k)} = {_toml_value(v)}" for k, v in row.items()]
    return "\n".join(lines) + "\n"


def write_fitted(path: str | Path, fitted: FittedSet) -> None:
    """Write a fitted set to a TOML file.

    Parameters
    ----------
    path : str or Path
        The file (replaced if it exists).
    fitted : FittedSet
        The set.
    """
    Path(path).write_text(fitted_toml(fitted), encoding="utf-8")


class _Check:
    """One clear error per bad field of a fitted file."""

    def __init__(self, filename: str):
        self.filename = filename

    def fail(self, field_name: str, problem: str) -> TurnoutFileError:
        return TurnoutFileError(f"{self.filename}: {field_name} {problem}")

    def number(self, field_name: str, value: Any, upper: float | None = None) -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.fail(field_name, f"must be a number, got {value!r}")
        if not math.isfinite(value):
            raise self.fail(field_name, f"must be finite, got {value!r}")
        if value <= 0:
            raise self.fail(field_name, f"must be > 0, got {value:g}")
        if upper is not None and value > upper:
            raise self.fail(
                field_name, f"must be <= {upper:g} (physically plausible bound), got {value:g}"
            )
        return float(value)

    def table(self, field_name: str, value: Any, n: int) -> tuple[float, ...]:
        if not isinstance(value, list) or len(value) != n:
            raise self.fail(field_name, f"must be a list of {n} numbers (one per s), got {value!r}")
        return tuple(self.number(f"{field_name}[{i}]", v) for i, v in enumerate(value))


def _upper(name: str) -> float:
    return _UPPER[name[0] if name[0] in "kcm" else "J"]


def _positions(check: _Check, where: str, s_raw: Any) -> list[float]:
    """Relative zone positions: a non-empty, increasing list of numbers in [0, 1]."""
    if not isinstance(s_raw, list) or not s_raw:
        raise check.fail(where, f"must be a non-empty list of numbers, got {s_raw!r}")
    s: list[float] = []
    for i, v in enumerate(s_raw):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not 0.0 <= v <= 1.0:
            raise check.fail(f"{where}[{i}]", f"must be a number in [0, 1], got {v!r}")
        if s and v <= s[-1]:
            raise check.fail(where, f"must increase, got {s_raw!r}")
        s.append(float(v))
    return s


def _x_positions(check: _Check, where: str, raw: Any, n: int) -> tuple[float, ...]:
    """The fit positions (m): empty, or one finite number per s, strictly increasing."""
    if not isinstance(raw, list):
        raise check.fail(where, f"must be a list of positions (m), got {raw!r}")
    if not raw:
        return ()
    if len(raw) != n:
        raise check.fail(where, f"must hold one position per s ({n}), got {len(raw)}")
    x: list[float] = []
    for i, v in enumerate(raw):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise check.fail(f"{where}[{i}]", f"must be a finite number (m), got {v!r}")
        if x and v <= x[-1]:
            raise check.fail(where, f"must increase (as s does), got {raw!r}")
        x.append(float(v))
    return tuple(x)


def _read_zone(
    check: _Check, turnout: Turnout | None, zone_key: str, data: Any, layers: int
) -> tuple[int, dict[str, Entry], tuple[tuple[float, ...], tuple[float, ...]], tuple]:
    index = int(zone_key[4:])
    if not isinstance(data, Mapping):
        raise check.fail(zone_key, "must be a table")
    if turnout is not None and not 1 <= index <= len(turnout.zones):
        raise check.fail(
            zone_key, f"names no zone of {turnout.name} (zones 1..{len(turnout.zones)})"
        )
    s = _positions(check, f"{zone_key}.s", data.get("s"))
    x = _x_positions(check, f"{zone_key}.x_m", data.get("x_m", []), len(s))
    if turnout is not None and x:
        zone = turnout.zone(index)
        if x[0] < zone.x_start - 1e-6 or x[-1] > zone.x_end + 1e-6:
            raise check.fail(
                f"{zone_key}.x_m",
                f"must lie inside zone {index} ({zone.x_start:g}..{zone.x_end:g} m), "
                f"got {x[0]:g}..{x[-1]:g}",
            )
    entries_raw = data.get("entries")
    if not isinstance(entries_raw, Mapping) or not entries_raw:
        raise check.fail(f"{zone_key}.entries", "is missing or empty")
    entries: dict[str, Entry] = {}
    for name, value in entries_raw.items():
        where = f"{zone_key}.entries.{name}"
        if name not in PARAMETER_NAMES:
            raise check.fail(where, "is not a co-running parameter name")
        if layers == 2 and name.startswith(("k_0", "c_0", "m_0")):
            raise check.fail(where, "belongs to the three-layer model, but fitted.layers = 2")
        if isinstance(value, (list, Mapping)):
            points = s
            if isinstance(value, Mapping):  # { s = [...], values = [...] }
                points = _positions(check, f"{where}.s", value.get("s"))
                value = value.get("values")
            table = TableEntry.of(points, check.table(where, value, len(points)))
            for v in table.values:
                if v > _upper(name):
                    raise check.fail(where, f"must be <= {_upper(name):g}, got {v:g}")
            entries[name] = table
        else:
            entries[name] = Entry("const", check.number(where, value, _upper(name)))
    if layers == 3 and "m_0" not in entries:
        raise check.fail(f"{zone_key}.entries.m_0", "is missing (fitted.layers = 3)")
    residuals = data.get("residuals", [])
    if not isinstance(residuals, list):
        raise check.fail(f"{zone_key}.residuals", "must be an array of tables")
    return index, entries, (tuple(s), x), tuple(dict(r) for r in residuals)


def _check_turnout(check: _Check, head: Mapping[str, Any], turnout: Turnout) -> str | None:
    """The set must have been fitted to this turnout (its name and model hash).

    Returns the warning for a file without the hash (given once the rest is checked).
    """
    source = Path(str(turnout.source)).name
    name = head.get("turnout")
    if isinstance(name, str) and name != turnout.name:
        raise check.fail(
            "fitted.turnout",
            f"= {name!r}: the set was fitted to another turnout, not to {turnout.name} "
            f"({source}); fit this one with exudyn-turnout fit --turnout {source}",
        )
    sha = head.get("turnout_model_sha256")
    if sha is None:
        return (
            f"{check.filename} has no fitted.turnout_model_sha256 (written before format 2): "
            f"whether it was fitted to this {source} cannot be checked; refit with "
            "exudyn-turnout fit"
        )
    if sha != turnout_model_sha256(turnout):
        raise check.fail(
            "fitted.turnout_model_sha256",
            f"does not match {source}: the set was fitted to a turnout whose rails, pads, "
            "sleepers, ballast, zones, layout or check rail's support differ; refit with "
            f"exudyn-turnout fit --turnout {source}",
        )
    return None


def read_fitted(path: str | Path, turnout: Turnout | None = None) -> FittedSet:
    """Read and check a fitted parameter file.

    Parameters
    ----------
    path : str or Path
        The TOML file written by :func:`write_fitted`.
    turnout : Turnout, optional
        The turnout the set is for: its zones bound the zone numbers and the fit
        positions; the file's ``fitted.turnout`` must be its name and
        ``fitted.turnout_model_sha256`` its :func:`turnout_model_sha256` (a file without
        the hash, format 1, gives a warning).

    Returns
    -------
    FittedSet
        The set, ``source`` the file's path.

    Raises
    ------
    TurnoutFileError
        The file cannot be read, is not TOML, or a field is missing or out of range (an
        unknown ``format``, fit positions that do not increase); it was fitted to another
        turnout. The message names the file and the field.
    """
    path = Path(path)
    check = _Check(path.name)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise check.fail("", "does not exist") from None
    except (OSError, UnicodeDecodeError) as err:
        raise check.fail("", f"cannot be read ({err})") from None
    except tomllib.TOMLDecodeError as err:
        raise check.fail("", f"is not valid TOML ({err})") from None
    head = data.get("fitted")
    if not isinstance(head, Mapping):
        raise check.fail("[fitted]", "is missing (not a fitted parameter file)")
    version = head.get("format", 1)  # hand-written files may leave it out: format 1
    if isinstance(version, bool) or not isinstance(version, int):
        raise check.fail("fitted.format", f"must be an integer, got {version!r}")
    if not 1 <= version <= FITTED_FORMAT:
        raise check.fail(
            "fitted.format",
            f"= {version} is not a format this version reads (1..{FITTED_FORMAT}); "
            "refit with exudyn-turnout fit or update exudyn_turnout",
        )
    layers = head.get("layers")
    if layers not in (2, 3) or isinstance(layers, bool):
        raise check.fail("fitted.layers", f"must be 2 or 3, got {layers!r}")
    centres = head.get("band_centres_hz", [])
    entries, positions, residuals = {}, {}, {}
    zone_keys = [k for k in data if k.startswith("zone") and k[4:].isdigit()]
    unknown = [k for k in data if k != "fitted" and k not in zone_keys]
    if unknown:
        raise check.fail(unknown[0], "is not a section of a fitted file ([fitted], [zoneN])")
    if not zone_keys:
        raise check.fail("[zoneN]", "is missing: the file holds no fitted zone")
    unchecked = None  # first: another turnout's zones would not fit either
    if turnout is not None:
        unchecked = _check_turnout(check, head, turnout)
    for key in zone_keys:
        index, zone_entries, where, rows = _read_zone(check, turnout, key, data[key], layers)
        entries[index], positions[index], residuals[index] = zone_entries, where, rows
    if unchecked:
        warnings.warn(unchecked, stacklevel=2)
    provenance = {k: v for k, v in head.items() if k not in ("layers", "band_centres_hz")}
    return FittedSet(
        layers,
        entries,
        positions,
        provenance,
        tuple(float(c) for c in centres),
        residuals,
        str(path),
    )


def with_fitted(turnout: Turnout, fitted: FittedSet) -> Turnout:
    """The turnout carrying a fitted set (``co_running_parameters(..., source="fitted")``).

    Parameters
    ----------
    turnout : Turnout
        The turnout the set was fitted to.
    fitted : FittedSet
        From :func:`read_fitted` or :func:`exudyn_turnout.corunning.fit.fitted_set`.

    Returns
    -------
    Turnout
        A copy with ``fitted`` set (zone index -> entries).
    """
    return dataclasses.replace(turnout, fitted={k: dict(v) for k, v in fitted.entries.items()})


def load_fitted(turnout: Turnout, path: str | Path) -> Turnout:
    """Read a fitted file and attach it to the turnout.

    Parameters
    ----------
    turnout : Turnout
        The turnout.
    path : str or Path
        The fitted parameter file.

    Returns
    -------
    Turnout
        :func:`with_fitted` of :func:`read_fitted`.
    """
    return with_fitted(turnout, read_fitted(path, turnout))
