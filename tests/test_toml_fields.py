"""inputs/toml_fields.py: the public field reader; every error is one line naming file and field."""

from __future__ import annotations

import math

import pytest

from exudyn_turnout.inputs import turnout
from exudyn_turnout.inputs.toml_fields import FieldReader, TurnoutFileError, read_toml
from exudyn_turnout.inputs.turnout_data import Table1D

DATA = {
    "a": {"k": 2.0, "n": 3, "flag": True, "kind": "edge", "t": {"x": [0.0, 1.0], "value": [1, 2]}},
    "items": [{"y": -1.0}],
}


def _error(call) -> str:
    with pytest.raises(TurnoutFileError) as err:
        call()
    message = str(err.value)
    assert "\n" not in message and message.startswith("f.toml: "), message
    return message


def test_reads_fields():
    r = FieldReader("f.toml", DATA)
    assert r.number("a.k") == 2.0 and r.integer("a.n", 1, 5) == 3
    assert r.choice("a.kind", ("edge", "middle")) == "edge"
    assert r.table("a.t") == Table1D((0.0, 1.0), (1.0, 2.0))
    assert r.table("a.k") == Table1D((0.0,), (2.0,))
    assert r.get("a.missing", None) is None and r.number("a.missing", default=4.0) == 4.0
    item = r.sub("items[0]", DATA["items"][0])
    assert item.number("items[0].y", positive=False) == -1.0


def test_errors_name_file_and_field():
    r = FieldReader("f.toml", DATA)
    assert "a.missing is missing" in _error(lambda: r.number("a.missing"))
    assert "a.flag must be a number" in _error(lambda: r.number("a.flag"))
    assert "a.k must be <= 1" in _error(lambda: r.number("a.k", upper=1.0))
    assert "a.n must be in 4..5" in _error(lambda: r.integer("a.n", 4, 5))
    assert "a.k must be an integer" in _error(lambda: r.integer("a.k", 0, 5))
    assert "a.kind must be one of middle" in _error(lambda: r.choice("a.kind", ("middle",)))
    assert "x must be finite" in _error(lambda: r.check("x", math.nan))


def test_read_toml_refuses_nan(tmp_path):
    path = tmp_path / "f.toml"
    path.write_text("[a]\nk = nan\n", encoding="utf-8")
    assert _error(lambda: read_toml(path)) == "f.toml: a.k must be finite, got nan or inf"


def test_old_names_stay_importable_from_turnout():
    assert turnout.TurnoutFileError is TurnoutFileError
    assert turnout.read_toml is read_toml
    assert turnout.FieldReader is FieldReader
