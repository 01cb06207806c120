"""Frozen dataclasses read from and written to JSON by their field types.

A :class:`Record` subclass declares the keys of one JSON object as typed fields (in the
JSON's order); :meth:`Record.from_dict` builds it from the parsed JSON, recursing into
fields that are records, ``dict[str, X]``, ``list[X]`` and ``X | None``, and
:meth:`Record.to_dict` gives the JSON object back. Values are taken as they are (no
conversion of numbers), so ``from_dict(d).to_dict() == d``. A key that is not a valid
Python name (e.g. ``co-running``) is named by the field's metadata ``{"key": ...}``; a key
that may be absent is a field made by :func:`optional`: None when absent, and then not
written back (a key present with null is written back as null; a record made in code writes
every key). An unknown or a missing key is an error: the schema never drifts silently.

A float read from ``metrics.json`` is None where the report computed NaN (JSON null).
"""

from __future__ import annotations

import dataclasses
import types
import typing
from collections.abc import Mapping
from typing import Any, TypeVar, get_args, get_origin, get_type_hints

__all__ = ["Record", "optional", "json_key"]

R = TypeVar("R", bound="Record")


def optional(key: str | None = None) -> Any:
    """A field whose JSON key may be absent (then the field is None and no key is written back).

    Parameters
    ----------
    key : str, optional
        The JSON key when it is not the field's name.

    Returns
    -------
    dataclasses.Field
        Default None.
    """
    metadata = {"optional": True} | ({"key": key} if key else {})
    return dataclasses.field(default=None, metadata=metadata)


def _fields(record: Any) -> list[dataclasses.Field]:
    """The fields of a record that are JSON keys (not its bookkeeping)."""
    return [f for f in dataclasses.fields(record) if not f.metadata.get("internal")]


def json_key(f: dataclasses.Field) -> str:
    """The JSON key of a record's field: its metadata ``key`` or its name.

    Parameters
    ----------
    f : dataclasses.Field

    Returns
    -------
    str
    """
    return f.metadata.get("key", f.name)


def _load(tp: Any, value: Any, where: str) -> Any:
    """``value`` of the parsed JSON as type ``tp`` (records built, containers recursed)."""
    if value is None or tp is Any:
        return value
    origin = get_origin(tp)
    if origin in (types.UnionType, typing.Union):
        args = [a for a in get_args(tp) if a is not type(None)]
        return _load(args[0], value, where) if len(args) == 1 else value
    if isinstance(tp, type) and issubclass(tp, Record):
        return tp.from_dict(value, where)
    if isinstance(tp, type) and dataclasses.is_dataclass(tp):
        return tp(**value)
    if origin in (dict, Mapping):
        item = get_args(tp)[1]
        return {k: _load(item, v, f"{where}.{k}") for k, v in value.items()}
    if origin in (list, tuple) and get_args(tp):
        item = get_args(tp)[0]
        return [_load(item, v, f"{where}[{i}]") for i, v in enumerate(value)]
    return value


def _dump(value: Any) -> Any:
    """The JSON form of a field's value (records and dataclasses as dicts)."""
    if isinstance(value, Record):
        return value.to_dict()
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return dataclasses.asdict(value)
    if isinstance(value, Mapping):
        return {k: _dump(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_dump(v) for v in value]
    return value


@dataclasses.dataclass(frozen=True)
class Record:
    """Base of the typed JSON objects (see the module docstring)."""

    #: JSON keys of optional fields that the parsed object did not have (not written back)
    absent_keys: frozenset[str] = dataclasses.field(
        default=frozenset(), repr=False, compare=False, kw_only=True, metadata={"internal": True}
    )

    @classmethod
    def from_dict(cls: type[R], data: Mapping[str, Any], where: str = "") -> R:
        """The record of a parsed JSON object.

        Parameters
        ----------
        data : mapping
            The object's keys and values.
        where : str
            Where the object lies in the document (for error messages).

        Returns
        -------
        Record
            An instance of the class it is called on.

        Raises
        ------
        ValueError
            A key the record does not know, or a required key that is missing.
        """
        where = where or cls.__name__
        if not isinstance(data, Mapping):
            raise ValueError(f"{where}: expected an object, got {type(data).__name__}")
        hints = get_type_hints(cls)
        fields = _fields(cls)
        unknown = set(data) - {json_key(f) for f in fields}
        if unknown:
            raise ValueError(f"{where}: unknown keys {sorted(unknown)} for {cls.__name__}")
        values: dict[str, Any] = {}
        absent = set()
        for f in fields:
            key = json_key(f)
            if key in data:
                values[f.name] = _load(hints[f.name], data[key], f"{where}.{key}")
            elif f.metadata.get("optional"):
                absent.add(key)
            else:
                raise ValueError(f"{where}: missing key {key!r} of {cls.__name__}")
        return cls(**values, absent_keys=frozenset(absent))

    def to_dict(self) -> dict[str, Any]:
        """The JSON object (keys in field order; optional keys the parsed object had not left out).

        Returns
        -------
        dict
        """
        return {
            json_key(f): _dump(getattr(self, f.name))
            for f in _fields(self)
            if json_key(f) not in self.absent_keys
        }
