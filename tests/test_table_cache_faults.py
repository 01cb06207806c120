"""A damaged or unusable contact-table cache: named in one warning, rebuilt or skipped.

Issue 25: a truncated, empty, random, all-NaN cache file, one with wrong keys or shapes,
and an unusable cache location (XDG_CACHE_HOME a file, the cache directory a file, a home
that cannot be written) each gave a traceback, a numpy message naming no file or "static
equilibrium not found". Each must give one warning naming the file (or directory) and a
table equal to a fresh build.
"""

import warnings

import numpy as np
import pytest

from exudyn_turnout.wheel_rail import tables
from exudyn_turnout.wheel_rail.data import s1002_wheel, standard_track
from exudyn_turnout.wheel_rail.geometry import WheelsetSetup
from exudyn_turnout.wheel_rail.tables import TableSettings, build_contact_table

SETUP = WheelsetSetup()
#: a coarse table (41 shifts over +-8 mm): seconds to build
SETTINGS = TableSettings(shift_min=-0.008, shift_max=0.008, shift_step=4e-4)


@pytest.fixture(scope="module")
def inputs():
    return s1002_wheel(SETUP), standard_track(SETUP)


@pytest.fixture(scope="module")
def fresh(inputs, tmp_path_factory):
    wheel, track = inputs
    cache = tmp_path_factory.mktemp("fresh")
    return build_contact_table(wheel, track, SETUP.taping_line, SETTINGS, cache_dir=cache)


def _build(inputs, cache):
    wheel, track = inputs
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        table = build_contact_table(wheel, track, SETUP.taping_line, SETTINGS, cache_dir=cache)
    return table, [str(w.message) for w in caught]


def _damage_by(kind, path):
    if kind == "truncated":
        data = path.read_bytes()
        path.write_bytes(data[: len(data) // 2])
    elif kind == "empty":
        path.write_bytes(b"")
    elif kind == "random bytes":
        path.write_bytes(np.random.default_rng(1).bytes(4096))
    else:
        with np.load(path) as f:
            arrays = {k: f[k] for k in f.files}
        if kind == "wrong keys":
            arrays["valuez"] = arrays.pop("values")
        elif kind == "wrong shape":
            arrays["values"] = arrays["values"][:, :-1]
        elif kind == "all NaN":
            arrays["values"] = np.full_like(arrays["values"], np.nan)
        elif kind == "bit flip":  # same shapes, finite, one value changed: the checksum
            arrays["values"] = arrays["values"].copy()
            arrays["values"].flat[7] += 1e-3
        np.savez(path, **arrays)


@pytest.mark.parametrize(
    "kind, problem",
    [
        ("truncated", "cannot be read"),
        ("empty", "cannot be read"),
        ("random bytes", "cannot be read"),
        ("wrong keys", "misses values"),
        ("wrong shape", "has values of shape"),
        ("all NaN", "checksum"),
        ("bit flip", "checksum"),
    ],
)
def test_damaged_cache_file_is_named_and_rebuilt(inputs, fresh, tmp_path, kind, problem):
    first, messages = _build(inputs, tmp_path)
    assert messages == []
    (path,) = tmp_path.glob("contact_table_*.npz")
    _damage_by(kind, path)
    table, messages = _build(inputs, tmp_path)
    assert len(messages) == 1 and "\n" not in messages[0], messages
    assert path.name in messages[0] and problem in messages[0] and "rebuilt" in messages[0]
    assert table.build_seconds > 0.0  # built again, equal to a fresh build
    np.testing.assert_array_equal(table.values, fresh.values)
    again, messages = _build(inputs, tmp_path)  # the rebuilt file is good again
    assert messages == [] and again.build_seconds == 0.0
    np.testing.assert_array_equal(again.values, fresh.values)


def test_xdg_cache_home_a_file_runs_without_cache(inputs, fresh, tmp_path, monkeypatch):
    a_file = tmp_path / "not_a_dir"
    a_file.write_text("x")
    monkeypatch.setenv("XDG_CACHE_HOME", str(a_file))
    monkeypatch.setattr(tables, "_UNUSABLE", set())
    table, messages = _build(inputs, None)
    assert len(messages) == 1 and "running without a cache" in messages[0]
    assert str(a_file) in messages[0]
    np.testing.assert_array_equal(table.values, fresh.values)
    _, messages = _build(inputs, None)  # once per directory and process
    assert messages == []


def test_cache_directory_a_file_runs_without_cache(inputs, tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    monkeypatch.setattr(tables, "_UNUSABLE", set())
    (tmp_path / "exudyn_turnout").mkdir()
    (tmp_path / "exudyn_turnout" / "wheel_rail").write_text("a file where the cache goes")
    table, messages = _build(inputs, None)
    assert len(messages) == 1 and "wheel_rail: cannot be written" in messages[0]
    assert table.build_seconds > 0.0


def test_unwritable_home_runs_without_cache(inputs, tmp_path, monkeypatch):
    """A home that cannot be written (as root permissions do not bite: savez refuses)."""
    monkeypatch.delenv("XDG_CACHE_HOME", raising=False)
    monkeypatch.setenv("HOME", str(tmp_path))
    monkeypatch.setattr(tables, "_UNUSABLE", set())

    def refuse(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(tables.np, "savez", refuse)
    table, messages = _build(inputs, None)
    assert len(messages) == 1 and "Permission denied" in messages[0]
    assert "running without a cache" in messages[0] and str(tmp_path) in messages[0]
    assert not list(tmp_path.rglob("*.npz"))  # no partial file left
