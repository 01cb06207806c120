"""A route's packed contact kept on disk beside the contact tables (issue 24).

Reference values: ``route_contact`` building the packed tables itself (the disk entry must
give exactly what it builds, bit for bit, and a passage on it exactly the same columns).
Each test puts the route's entry in ``tmp_path`` (the tables themselves stay in the user's
cache, where the other tests keep them) and starts with nothing in memory.
"""

from __future__ import annotations

import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.inputs.vehicle import load_vehicle
from exudyn_turnout.passage.contact import profile, route_cache
from exudyn_turnout.wheel_rail import turnout_sections

ARRAYS = ("values", "blendable", "x", "layout", "bounds")


@pytest.fixture(scope="module")
def turnout():
    return load_turnout()


@pytest.fixture(scope="module")
def vehicle():
    return load_vehicle()


@pytest.fixture
def entry(tmp_path, monkeypatch):
    """The route's disk entry in ``tmp_path``; counts the builds of the route's tables."""
    folder = tmp_path / "cache"
    monkeypatch.setattr(
        route_cache, "_packed_cache_path", lambda key, cache_dir=None: folder / f"rc_{key[:8]}.npz"
    )
    builds: list[str] = []
    original = turnout_sections.route_contact_tables

    def counted(*args, **kwargs):
        builds.append(args[1])
        return original(*args, **kwargs)

    monkeypatch.setattr(turnout_sections, "route_contact_tables", counted)
    return folder, builds


def _fresh(turnout, vehicle, monkeypatch, route="through"):
    """``route_contact`` in a process with nothing in memory (disk entry or build)."""
    monkeypatch.setattr(route_cache, "_RECENT", route_cache._RecentContacts())
    return profile.route_contact(turnout, route, vehicle)


def _same(a, b) -> None:
    """Equal to the bit: dtype, shape, memory layout and bytes of every array, and texts."""
    for name in ARRAYS:
        left, right = getattr(a.tables, name), getattr(b.tables, name)
        assert left.dtype == right.dtype and left.shape == right.shape, name
        # the compiled kernel is typed by these: a read-only or strided copy recompiles
        assert right.flags.c_contiguous and right.flags.writeable, name
        assert left.tobytes() == right.tobytes(), name
    assert a.tables.names == b.tables.names and a.wheels == b.wheels and a.rails == b.rails
    assert all(type(s) is str for s in a.tables.names + a.wheels + a.rails)


@pytest.mark.parametrize("route", ["through", "diverging"])
def test_loaded_contact_equals_the_built_one(turnout, vehicle, monkeypatch, entry, route):
    folder, builds = entry
    built = _fresh(turnout, vehicle, monkeypatch, route)
    assert builds == [route] and len(list(folder.glob("rc_*.npz"))) == 1
    loaded = _fresh(turnout, vehicle, monkeypatch, route)
    assert builds == [route]  # not built again
    _same(loaded, built)
    assert profile.route_contact(turnout, route, vehicle) is loaded  # kept in memory


@pytest.mark.slow  # two passages with their start: 8-12 s on a busy core
def test_a_passage_on_the_loaded_contact_has_the_same_columns(turnout, monkeypatch, entry):
    from exudyn_turnout.passage.run import simulate_passage
    from exudyn_turnout.passage.settings import PassageSettings

    folder, builds = entry
    settings = replace(PassageSettings(x_start=-5.0, x_end=-4.9), contact="profile")
    runs = []
    for _ in range(2):  # built, then loaded
        monkeypatch.setattr(route_cache, "_RECENT", route_cache._RecentContacts())
        runs.append(simulate_passage(turnout, settings, "wheelset"))
    assert len(builds) == 1 and len(list(folder.glob("rc_*.npz"))) == 1
    built, loaded = runs
    assert built.columns.keys() == loaded.columns.keys()
    assert any(name.startswith("cp_") for name in built.columns)  # contact points in it
    for name, values in built.columns.items():
        np.testing.assert_array_equal(loaded.columns[name], values, err_msg=name)


def _damage(path: Path, how: str) -> None:
    if how in ("tampered", "foreign"):
        with np.load(path, allow_pickle=False) as data:
            content = {k: data[k] for k in data.files}
        if how == "tampered":  # key kept, one value changed: the checksum finds it
            content["values"] = content["values"].copy()
            content["values"][12345] += 1e-3
        else:  # a sound entry of other code or inputs under this name
            content["key"] = np.array("0" * 64)
        np.savez(path, **content)
    elif how == "short-header":  # the array's shape edited: reads fewer bytes, no zip CRC
        data = bytearray(path.read_bytes())
        at = data.index(b"'shape': (") + len(b"'shape': (")
        data[at] = ord("1") if data[at] != ord("1") else ord("2")
        path.write_bytes(bytes(data))
    else:
        data = path.read_bytes()
        path.write_bytes(data[: len(data) // 2] if how == "truncated" else b"x" * 999)


@pytest.mark.parametrize("how", ["truncated", "garbage", "tampered", "foreign", "short-header"])
def test_a_damaged_or_foreign_entry_is_built_again_and_overwritten(
    turnout, vehicle, monkeypatch, entry, how
):
    folder, builds = entry
    built = _fresh(turnout, vehicle, monkeypatch)
    (path,) = folder.glob("rc_*.npz")
    _damage(path, how)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")  # no traceback: built again
        again = _fresh(turnout, vehicle, monkeypatch)
    messages = [str(w.message) for w in caught if "route contact cache" in str(w.message)]
    if how == "foreign":  # another code's or input's entry under this name: quietly replaced
        assert messages == []
    else:  # a damaged entry: one warning naming the file and what is wrong
        assert len(messages) == 1, messages
        assert path.name in messages[0] and "built again" in messages[0]
        assert all(w.category is RuntimeWarning for w in caught if str(w.message) in messages)
    assert len(builds) == 2
    _same(again, built)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the overwritten entry is whole: read quietly
        _same(_fresh(turnout, vehicle, monkeypatch), built)
    assert len(builds) == 2


def test_an_unusable_cache_location_builds_with_one_warning(
    turnout, vehicle, monkeypatch, entry, tmp_path
):
    _, builds = entry
    blocker = tmp_path / "not_a_directory"
    blocker.write_text("a file where the cache should be")
    monkeypatch.setattr(
        route_cache, "_packed_cache_path", lambda key, cache_dir=None: blocker / "rc.npz"
    )
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        first = _fresh(turnout, vehicle, monkeypatch)
        second = _fresh(turnout, vehicle, monkeypatch)
    messages = [str(w.message) for w in caught]
    assert len(messages) == 1 and "running without a cache" in messages[0], messages
    assert len(builds) == 2
    _same(second, first)


def test_the_entry_key_covers_the_code_and_numpy(monkeypatch):
    base = route_cache._packed_key("a" * 64)
    assert route_cache._packed_key("b" * 64) != base  # route_contact_key: inputs, route, wheel
    files = {f"{p.parent.name}/{p.name}" for p in route_cache._packed_sources()}
    for name in (  # the modules that build and pack (issue 24's list) and the loaders
        "wheel_rail/turnout_sections.py",
        "wheel_rail/section_nodes.py",
        "wheel_rail/sections.py",
        "wheel_rail/tables.py",  # with the table format version
        "wheel_rail/packed_tables.py",  # pack_tables
        "wheel_rail/kernel.py",
        "wheel_rail/nonhertz.py",
        "wheel_rail/creep_table.py",
        "inputs/routes.py",
        "inputs/turnout.py",
        "contact/profile.py",
    ):
        assert name in files, name
    monkeypatch.setattr(np, "__version__", "0.0.0")
    assert route_cache._packed_key("a" * 64) != base
