"""Reading input files: TOML parsing and a field reader whose errors name file and field.

:func:`read_toml` parses a file (UTF-8, no NaN or infinite number anywhere);
:class:`FieldReader` reads its fields by dotted name and raises one
:class:`TurnoutFileError` per bad field, e.g. ``uic60.toml: sleeper.spacing must be > 0,
got -0.6``. The turnout file (:mod:`.turnout`), its routes (:mod:`.routes`) and the
single-wheelset vehicle file (:mod:`.vehicle`) are read with them.
"""

from __future__ import annotations

import difflib
import math
import tomllib
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from exudyn_turnout.inputs.turnout_data import Table1D

__all__ = [
    "TurnoutFileError",
    "FieldReader",
    "X_LIMIT",
    "read_toml",
    "did_you_mean",
]


def did_you_mean(name: str, known: Iterable[str]) -> str:
    """``" (did you mean 'x'?)"`` for the closest of ``known`` to ``name``, else the list.

    Parameters
    ----------
    name : str
        The unknown name.
    known : iterable of str
        The names allowed there.

    Returns
    -------
    str
        A suffix for a message: the close match (:func:`difflib.get_close_matches`), or the
        allowed names when none is close.
    """
    names = sorted(known)
    close = difflib.get_close_matches(name, names, n=1, cutoff=0.6)
    if close:
        return f" (did you mean {close[0]!r}?)"
    return f" (known: {', '.join(names)})"


class TurnoutFileError(ValueError):
    """A turnout file is missing a field or holds a value that cannot be right."""


#: m, largest |x| of any position in a turnout file (a turnout is not 10 km long).
X_LIMIT = 1e4


class FieldReader:
    """Reads fields of a parsed TOML file and raises one clear error per bad field.

    Parameters
    ----------
    filename : str
        Name of the file, for messages.
    data : Mapping
        The parsed file (or one of its tables, see :meth:`sub`).
    prefix : str
        Fields under this dotted prefix are looked up in ``data`` itself.
    """

    def __init__(self, filename: str, data: Mapping[str, Any], prefix: str = ""):
        self.filename = filename
        self.data = data
        self.prefix = prefix  # fields under this dotted prefix are looked up in data itself

    def sub(self, prefix: str, data: Any) -> FieldReader:
        """A reader of ``data`` (e.g. one list item) whose fields are named ``prefix.field``.

        Parameters
        ----------
        prefix : str
            Dotted name of ``data`` in the file, e.g. ``zones[2]``.
        data : Any
            The table (anything else reads as an empty table).

        Returns
        -------
        FieldReader
            A reader of the same file.
        """
        return FieldReader(self.filename, data if isinstance(data, Mapping) else {}, prefix)

    def fail(self, field: str, problem: str) -> TurnoutFileError:
        """The error of one field: ``<file>: <field> <problem>``.

        Parameters
        ----------
        field : str
            Dotted field name.
        problem : str
            What is wrong, e.g. ``must be > 0, got -1``.

        Returns
        -------
        TurnoutFileError
            The error (to raise).
        """
        return TurnoutFileError(f"{self.filename}: {field} {problem}")

    def keys(self, field: str, known: Iterable[str]) -> None:
        """Refuse a key of table ``field`` that is not in ``known`` (one line, did you mean).

        Parameters
        ----------
        field : str
            Dotted name of the table (``""``: the file's top level). A missing table or a
            value that is not a table is left to the field's own check.
        known : iterable of str
            The keys allowed in the table.

        Raises
        ------
        TurnoutFileError
            The first unknown key, named with the closest known one.
        """
        table = self.get(field, None) if field else self.data
        if not isinstance(table, Mapping):
            return
        allowed = set(known)
        for key in table:
            if key not in allowed:
                name = f"{field}.{key}" if field else f"[{key}]"
                what = "key" if field else "section"
                raise self.fail(name, f"is not a {what} of this file{did_you_mean(key, allowed)}")

    def get(self, field: str, default: Any = ...) -> Any:
        """The value of a dotted field.

        Parameters
        ----------
        field : str
            Dotted field name, e.g. ``sleeper.spacing``.
        default : Any, optional
            Returned when the field is missing; without it a missing field is an error.

        Returns
        -------
        Any
            The parsed value.
        """
        node: Any = self.data
        path = (
            field[len(self.prefix) + 1 :]
            if self.prefix and field.startswith(self.prefix + ".")
            else field
        )
        for part in path.split("."):
            if not isinstance(node, Mapping) or part not in node:
                if default is not ...:
                    return default
                raise self.fail(field, "is missing")
            node = node[part]
        return node

    def number(
        self,
        field: str,
        positive: bool = True,
        default: Any = ...,
        upper: float | None = None,
        lower: float | None = None,
    ) -> float:
        """Field ``field`` as a float (> 0 if ``positive``, <= ``upper`` if given).

        Parameters
        ----------
        field : str
            Dotted field name.
        positive : bool
            The value must be > 0.
        default : Any, optional
            Value of a missing field; without it a missing field is an error.
        upper : float, optional
            Plausibility bound on the magnitude.
        lower : float, optional
            Smallest value allowed (e.g. 0 for a damping, which may be zero).

        Returns
        -------
        float
            The value.
        """
        return self.check(field, self.get(field, default), positive, upper, lower)

    def check(
        self,
        field: str,
        value: Any,
        positive: bool = True,
        upper: float | None = None,
        lower: float | None = None,
    ) -> float:
        """``value`` as a float, or an error naming ``field`` if it is not a (positive) number.

        Parameters
        ----------
        field : str
            Dotted field name, for the message.
        value : Any
            The value to check.
        positive : bool
            The value must be > 0.
        upper : float, optional
            A plausibility bound (see ``turnout.BOUNDS``); larger magnitudes are an error.
        lower : float, optional
            Smallest value allowed; smaller values are an error.

        Returns
        -------
        float
            The value.
        """
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.fail(field, f"must be a number, got {value!r}")
        if not math.isfinite(value):
            raise self.fail(field, f"must be finite, got {value!r}")
        if positive and value <= 0:
            raise self.fail(field, f"must be > 0, got {value:g}")
        if lower is not None and value < lower:
            raise self.fail(field, f"must be >= {lower:g}, got {value:g}")
        if upper is not None and abs(value) > upper:
            raise self.fail(
                field, f"must be <= {upper:g} (physically plausible bound), got {value:g}"
            )
        return float(value)

    def integer(self, field: str, lo: int, hi: int, default: Any = ...) -> int:
        """Field ``field`` as an integer in [lo, hi] (a float such as 2.5 is an error).

        Parameters
        ----------
        field : str
            Dotted field name.
        lo, hi : int
            Allowed range, ends included.
        default : Any, optional
            Value of a missing field; without it a missing field is an error.

        Returns
        -------
        int
            The value.
        """
        value = self.get(field, default)
        return self.check_integer(field, value, lo, hi)

    def check_integer(self, field: str, value: Any, lo: int, hi: int) -> int:
        """``value`` as an int in [lo, hi], or an error naming ``field``.

        Parameters
        ----------
        field : str
            Dotted field name, for the message.
        value : Any
            The value to check.
        lo, hi : int
            Allowed range, ends included.

        Returns
        -------
        int
            The value.
        """
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.fail(field, f"must be an integer, got {value!r}")
        if not lo <= value <= hi:
            raise self.fail(field, f"must be in {lo}..{hi}, got {value}")
        return int(value)

    def choice(self, field: str, options: tuple, default: Any = ...) -> Any:
        """Field ``field``, which must be one of ``options``.

        Parameters
        ----------
        field : str
            Dotted field name.
        options : tuple
            Allowed values.
        default : Any, optional
            Value of a missing field; without it a missing field is an error.

        Returns
        -------
        Any
            The value (one of ``options``).
        """
        value = self.get(field, default)
        if value not in options:
            raise self.fail(field, f"must be one of {', '.join(map(str, options))}, got {value!r}")
        return value

    def table(self, field: str, upper: float | None = None) -> Table1D:
        """A number or ``{x = [...], value = [...]}`` (values > 0 and <= upper, x increasing).

        Parameters
        ----------
        field : str
            Dotted field name.
        upper : float, optional
            Plausibility bound on the values.

        Returns
        -------
        Table1D
            The quantity along x (a single value: a one-point table at x = 0).
        """
        value = self.get(field)
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            return Table1D((0.0,), (self.number(field, upper=upper),))
        if not isinstance(value, Mapping):
            raise self.fail(field, "must be a number or a table {x = [...], value = [...]}")
        xs, vs = self.get(field + ".x"), self.get(field + ".value")
        if not isinstance(xs, list) or not isinstance(vs, list) or len(xs) != len(vs) or not xs:
            raise self.fail(field, "needs lists x and value of the same, non-zero length")
        for i, v in enumerate(vs):
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not v > 0:
                raise self.fail(f"{field}.value[{i}]", f"must be > 0, got {v!r}")
            self.check(f"{field}.value[{i}]", v, upper=upper)
        for i, a in enumerate(xs):
            self.check(f"{field}.x[{i}]", a, positive=False, upper=X_LIMIT)
        if any(b <= a for a, b in zip(xs, xs[1:])):
            raise self.fail(field + ".x", f"must be increasing numbers, got {xs}")
        return Table1D(tuple(map(float, xs)), tuple(map(float, vs)))


def _non_finite(node: Any, field: str) -> str | None:
    """Dotted name of the first NaN or infinite number in a parsed TOML tree, None if all finite."""
    if isinstance(node, float) and not math.isfinite(node):
        return field
    items = (
        node.items()
        if isinstance(node, Mapping)
        else (((f"[{i}]", v) for i, v in enumerate(node)) if isinstance(node, list) else ())
    )
    for key, value in items:
        name = f"{field}{key}" if key.startswith("[") else (f"{field}.{key}" if field else key)
        found = _non_finite(value, name)
        if found:
            return found
    return None


def read_toml(path: Path) -> dict:
    """Parse a TOML file; TurnoutFileError naming the file if it cannot be read or parsed.

    Also an error: a file that is not UTF-8, or a NaN or infinite number anywhere in it
    (TOML allows ``nan`` and ``inf``; no quantity of a turnout or vehicle may be either).

    Parameters
    ----------
    path : Path
        The file.

    Returns
    -------
    dict
        The parsed file.

    Raises
    ------
    TurnoutFileError
        The file cannot be read, is not UTF-8, is not valid TOML, or holds a NaN or
        infinite number (the message names the file, and the field for the last).
    """
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except IsADirectoryError:
        raise TurnoutFileError(f"{path.name}: is a directory, not a file") from None
    except OSError as err:
        raise TurnoutFileError(f"{path.name}: cannot be read ({err.strerror or err})") from None
    except UnicodeDecodeError as err:
        raise TurnoutFileError(
            f"{path.name}: is not UTF-8 text (byte {err.start}: "
            f"{err.object[err.start : err.start + 1]!r})"
        ) from None
    except tomllib.TOMLDecodeError as err:
        raise TurnoutFileError(f"{path.name}: is not valid TOML ({err})") from None
    bad = _non_finite(data, "")
    if bad:
        raise TurnoutFileError(f"{path.name}: {bad} must be finite, got nan or inf")
    return data
