"""inputs/vehicle.py: load_vehicle by path or packaged name; a full-vehicle file is refused
in one line naming the loader to use."""

from __future__ import annotations

import pytest

import exudyn_turnout as et
from exudyn_turnout.inputs.toml_fields import TurnoutFileError
from exudyn_turnout.inputs.vehicle import (
    Vehicle,
    default_vehicle_path,
    load_vehicle,
    resolve_vehicle_path,
)
from exudyn_turnout.inputs.vehicle_model import default_vehicle_model_path


def test_packaged_name_is_the_default_file():
    assert resolve_vehicle_path("wheelset") == default_vehicle_path()
    assert resolve_vehicle_path(None) == default_vehicle_path()
    assert load_vehicle("wheelset") == load_vehicle()


def test_a_path_stays_a_path(tmp_path):
    target = tmp_path / "wheelset"
    assert resolve_vehicle_path(target) == target
    assert resolve_vehicle_path(str(tmp_path / "v.toml")) == tmp_path / "v.toml"


@pytest.mark.parametrize("given", ["manchester", str(default_vehicle_model_path())])
def test_full_vehicle_file_is_refused_in_one_line(given):
    with pytest.raises(TurnoutFileError) as err:
        et.load_vehicle(given)
    message = str(err.value)
    assert "\n" not in message
    assert message.startswith("manchester_vehicle.toml: is a full-vehicle file")
    assert "load_vehicle_model" in message
    assert "contact.C_H" not in message


def test_single_wheelset_model_file_is_refused(tmp_path):
    path = tmp_path / "ws.toml"
    path.write_text("[vehicle]\nwheelsets = 1\nbogies = 0\n[sprung_mass]\nmass = 1.0\n")
    expected = r"ws.toml: is a vehicle-model file.*load_vehicle_model"
    with pytest.raises(TurnoutFileError, match=expected):
        load_vehicle(path)


def test_unknown_name_lists_the_packaged_names():
    with pytest.raises(TurnoutFileError) as err:
        load_vehicle("tram")
    message = str(err.value)
    assert "\n" not in message and "'tram'" in message
    assert "wheelset" in message and "manchester" in message


def test_missing_file_still_says_cannot_be_read(tmp_path):
    with pytest.raises(TurnoutFileError, match="none.toml: cannot be read"):
        load_vehicle(tmp_path / "none.toml")


def test_packaged_wheelset_loads():
    vehicle = load_vehicle("wheelset")
    assert isinstance(vehicle, Vehicle)
    assert vehicle.source.endswith("manchester_wheelset.toml")
