"""A small TOML writer and dotted-path access, for the modified files of a study's cases.

Writes what :mod:`tomllib` reads: tables, arrays of tables, inline tables inside arrays,
strings, integers, floats (``inf``, ``nan``), booleans and arrays. Comments and layout of
the original file are not kept (the case's file is data, the original stays the reference).
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Mapping
from typing import Any

__all__ = ["dumps", "get_dotted", "set_dotted"]

_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")


def _key(key: str) -> str:
    return key if _BARE_KEY.fullmatch(key) else json.dumps(key)


def _value(value: Any) -> str:
    """A TOML value on one line (inline tables and arrays for nested data)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, Mapping):
        return "{ " + ", ".join(f"{_key(k)} = {_value(v)}" for k, v in value.items()) + " }"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_value(v) for v in value) + "]"
    raise TypeError(f"cannot write {type(value).__name__} to TOML")


def _is_table_array(value: Any) -> bool:
    return (
        isinstance(value, (list, tuple))
        and len(value) > 0
        and all(isinstance(v, Mapping) for v in value)
    )


def _table(lines: list[str], path: list[str], table: Mapping[str, Any]) -> None:
    for k, v in table.items():
        if not isinstance(v, Mapping) and not _is_table_array(v):
            lines.append(f"{_key(k)} = {_value(v)}")
    for k, v in table.items():
        name = ".".join(_key(p) for p in path + [k])
        if isinstance(v, Mapping):
            lines.append("")
            lines.append(f"[{name}]")
            _table(lines, path + [k], v)
        elif _is_table_array(v):
            for item in v:
                lines.append("")
                lines.append(f"[[{name}]]")
                _table(lines, path + [k], item)


def dumps(data: Mapping[str, Any]) -> str:
    """TOML text of a nested dict (as :func:`tomllib.loads` returns it).

    Parameters
    ----------
    data : mapping
        Tables (mappings), arrays of tables (lists of mappings), and values.

    Returns
    -------
    str
        TOML that ``tomllib.loads`` reads back into an equal dict.
    """
    lines: list[str] = []
    _table(lines, [], data)
    return "\n".join(lines).lstrip("\n") + "\n"


def _step(node: Any, part: str, done: str) -> Any:
    if isinstance(node, Mapping):
        if part not in node:
            keys = ", ".join(str(k) for k in node) or "nothing"
            where = done or "the file"
            raise KeyError(f"no field {part!r} in {where} (it has: {keys})")
        return node[part]
    if isinstance(node, list):
        if not part.isdigit() or int(part) >= len(node):
            raise KeyError(f"{done} is a list of {len(node)}: {part!r} is not an index 0..")
        return node[int(part)]
    raise KeyError(f"{done} is a value, it has no field {part!r}")


def get_dotted(data: Mapping[str, Any], path: str) -> Any:
    """The value at a dotted path (``rail_types.stock.pad.k_z``; list items by index).

    Parameters
    ----------
    data : mapping
        Nested dict of a TOML file.
    path : str
        Keys joined by dots; an integer selects an item of an array (``zones.0.x_end``).

    Returns
    -------
    any

    Raises
    ------
    KeyError
        A key that is not there (the message lists the keys that are).
    """
    node: Any = data
    done = ""
    for part in path.split("."):
        node = _step(node, part, done)
        done = f"{done}.{part}" if done else part
    return node


def set_dotted(data: dict[str, Any], path: str, value: Any) -> None:
    """Set the value at a dotted path that exists (in place).

    Parameters
    ----------
    data : dict
        Nested dict of a TOML file.
    path : str
        See :func:`get_dotted`.
    value : any
        The new value; a number may replace a number only, a string a string only.

    Raises
    ------
    KeyError
        The path is not there.
    TypeError
        The new value's kind differs from the old one's.
    """
    parent_path, _, last = path.rpartition(".")
    parent = get_dotted(data, parent_path) if parent_path else data
    old = _step(parent, last, parent_path)
    numeric = (int, float)
    same = (
        isinstance(old, numeric) and not isinstance(old, bool) and isinstance(value, numeric)
    ) or type(old) is type(value)
    if not same or isinstance(value, bool) != isinstance(old, bool):
        raise TypeError(
            f"{path} holds a {type(old).__name__}, cannot set a {type(value).__name__} ({value!r})"
        )
    if isinstance(parent, list):
        parent[int(last)] = value
    else:
        parent[last] = value
