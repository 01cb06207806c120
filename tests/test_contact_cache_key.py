"""The key of a route's contact tables in memory: what the tables depend on, nothing else.

A study varying the track (pad stiffness, ballast, masses) must reuse the route's tables; a
change of what the tables are built from (rail profile, route geometry, layout, wheel) must
not. The last test guards the key's list of sections: it records which parts of the turnout
``route_contact`` reads while it builds the tables, so that a new input of the tables that
the key does not cover fails here.
"""

from __future__ import annotations

import shutil
import tomllib
from collections.abc import Mapping
from pathlib import Path

import pytest

from exudyn_turnout.inputs.turnout import default_turnout_path, load_turnout
from exudyn_turnout.inputs.vehicle import default_vehicle_path, load_vehicle
from exudyn_turnout.passage.contact import profile, route_cache
from exudyn_turnout.studies.toml_writer import dumps, set_dotted
from exudyn_turnout.wheel_rail.data import profile_path


def _turnout_with(tmp_path: Path, name: str, edits: Mapping[str, object]):
    """The packaged turnout with ``edits`` (dotted path -> value), written as ``name``."""
    data = tomllib.loads(default_turnout_path().read_text(encoding="utf-8"))
    for path, value in edits.items():
        set_dotted(data, path, value)
    folder = tmp_path / name
    folder.mkdir()
    (folder / "turnout.toml").write_text(dumps(data), encoding="utf-8")
    return load_turnout(folder / "turnout.toml")


def _key(turnout, vehicle=None, route="through"):
    return route_cache.route_contact_key(turnout, route, vehicle or load_vehicle())


def test_track_parameters_do_not_change_the_key(tmp_path):
    base = _key(_turnout_with(tmp_path, "base", {}))
    track = {
        "rail_types.stock.pad.k_z": 96e6,
        "rail_types.crossing.pad.c_z": 30e3,
        "ballast.s_b_z": 25e6,
        "sleeper.density": 2500.0,
        "extra_layer.m_0": 3.0,
        "turnout.description": "another description",
    }
    for path, value in track.items():  # each in another folder: the file's place is not in it
        assert _key(_turnout_with(tmp_path, path, {path: value})) == base, path


def test_geometry_changes_the_key(tmp_path):
    base = _key(_turnout_with(tmp_path, "base", {}))
    geometry = {
        "routes.through.contacts.0.z": [0.0, 0.0, -0.004],  # a rail's height profile
        "wheel_rail.gauge_depth": 0.015,
        "wheel_rail.switch.toe_width": 0.004,
        "layout.nose_tip_width": 0.013,
        "check_rail.clearance": 0.042,
        "zones.2.x_end": 61.0,  # the turnout's x range
    }
    keys = {path: _key(_turnout_with(tmp_path, path, {path: v})) for path, v in geometry.items()}
    assert base not in keys.values()
    assert len(set(keys.values())) == len(keys)
    assert _key(_turnout_with(tmp_path, "base-2", {})) == base
    assert route_cache.route_contact_key(load_turnout(), "diverging", load_vehicle()) != _key(
        load_turnout()
    )


def test_rail_profile_file_content_changes_the_key(tmp_path):
    """A rail profile beside the turnout file replaces the packaged one of that name."""
    turnout = _turnout_with(tmp_path, "local", {})
    base = _key(turnout)
    name = "MBench_UIC60_v3.prr"
    local = Path(turnout.source).parent / name
    shutil.copyfile(profile_path(name), local)
    copied = _key(turnout)  # same content, another file: another key (the path is in it)
    assert copied != base
    lines = local.read_text(encoding="utf-8").splitlines()
    local.write_text("\n".join(lines[:-1] + [lines[-1] + " "]) + "\n", encoding="utf-8")
    assert _key(turnout) not in (base, copied)
    local.unlink()
    assert _key(turnout) == base


def test_wheel_changes_the_key(tmp_path):
    turnout = load_turnout()
    vehicle = load_vehicle()
    base = _key(turnout, vehicle)
    data = tomllib.loads(default_vehicle_path().read_text(encoding="utf-8"))
    data["wheelset"]["mass"] = float(data["wheelset"]["mass"]) * 1.1  # a mass: same tables
    (tmp_path / "heavier.toml").write_text(dumps(data), encoding="utf-8")
    assert _key(turnout, load_vehicle(tmp_path / "heavier.toml")) == base
    data["wheelset"]["back_to_back"] = float(data["wheelset"]["back_to_back"]) + 0.002
    (tmp_path / "wider.toml").write_text(dumps(data), encoding="utf-8")
    assert _key(turnout, load_vehicle(tmp_path / "wider.toml")) != base


def test_a_pad_stiffness_study_reuses_the_tables_in_memory(tmp_path):
    softer = _turnout_with(tmp_path, "softer", {"rail_types.stock.pad.k_z": 96e6})
    stiffer = _turnout_with(tmp_path, "stiffer", {"rail_types.stock.pad.k_z": 144e6})
    vehicle = load_vehicle()
    first = profile.route_contact(softer, "through", vehicle)
    assert profile.route_contact(stiffer, "through", vehicle) is first
    raised = {"routes.through.contacts.0.z": [0.0, 0.0, -0.004]}
    assert route_cache.route_contact_key(
        _turnout_with(tmp_path, "raised", raised), "through", vehicle
    ) != route_cache.route_contact_key(stiffer, "through", vehicle)


class _Recorder(Mapping):
    """A read-only view of a nested mapping that notes the top-level keys read through it."""

    def __init__(self, data, seen, top=None):
        self.data, self.seen, self.top = data, seen, top

    def __getitem__(self, key):
        self.seen.add(self.top or key)
        value = self.data[key]
        return _wrap(value, self.seen, self.top or key)

    def __iter__(self):
        self.seen.add(self.top or "<every section>")
        return iter(self.data)

    def __len__(self):
        return len(self.data)


def _wrap(value, seen, top):
    if isinstance(value, Mapping):
        return _Recorder(value, seen, top)
    if isinstance(value, list):
        return [_wrap(v, seen, top) for v in value]
    return value


class _RecordingTurnout:
    """A turnout whose attribute reads (and raw sections read) are noted."""

    def __init__(self, turnout, attributes, sections):
        self._turnout, self._attributes, self._sections = turnout, attributes, sections

    def __getattr__(self, name):
        self._attributes.add(name)
        value = getattr(self._turnout, name)
        return _Recorder(value, self._sections) if name == "raw" else value


@pytest.mark.parametrize("route", ["through", "diverging"])
def test_the_key_covers_what_the_tables_are_built_from(monkeypatch, tmp_path, route):
    """Build the route's tables (from the disk cache) and note what of the turnout is read."""
    monkeypatch.setattr(route_cache, "_RECENT", route_cache._RecentContacts())  # nothing in memory
    # no packed route on disk either: the tables are built (each from its disk cache)
    monkeypatch.setattr(route_cache, "_packed_cache_path", lambda key, d=None: tmp_path / "r.npz")
    attributes: set[str] = set()
    sections: set[str] = set()
    turnout = _RecordingTurnout(load_turnout(), attributes, sections)
    profile.route_contact(turnout, route, load_vehicle())
    assert sections and sections <= set(route_cache.CONTACT_SECTIONS), sections
    # the zones (raw "zones" is in the key) and the file's place (its design files are)
    assert attributes <= {"raw", "source", "zones", "zone", "x_min", "x_max"}, attributes
