"""inputs/vehicles.py: packaged_vehicle(name) loads the single wheelset or the full vehicle."""

from __future__ import annotations

import pytest

import exudyn_turnout.inputs as inputs
from exudyn_turnout.inputs.toml_fields import TurnoutFileError
from exudyn_turnout.inputs.vehicle import Vehicle, load_vehicle
from exudyn_turnout.inputs.vehicle_model import (
    VehicleModel,
    VehicleModelError,
    load_vehicle_model,
)
from exudyn_turnout.inputs.vehicles import packaged_vehicle, packaged_vehicle_names


def test_wheelset_is_the_single_wheelset_vehicle():
    vehicle = packaged_vehicle("wheelset")
    assert isinstance(vehicle, Vehicle)
    assert vehicle == load_vehicle()


def test_manchester_is_the_full_vehicle():
    model = packaged_vehicle("manchester")
    assert isinstance(model, VehicleModel)
    assert model == load_vehicle_model()
    assert model.n_wheelsets == 4 and model.n_bogies == 2
    assert load_vehicle_model("manchester") == model


def test_names():
    assert packaged_vehicle_names() == ("wheelset", "manchester")
    assert inputs.packaged_vehicle is packaged_vehicle


def test_unknown_name():
    with pytest.raises(TurnoutFileError, match=r"unknown packaged vehicle 'tgv' \(packaged: "):
        packaged_vehicle("tgv")


def test_full_vehicle_loader_refuses_the_wheelset_file_in_one_line():
    with pytest.raises(VehicleModelError) as err:
        load_vehicle_model("wheelset")
    message = str(err.value)
    assert "\n" not in message
    assert message.startswith("manchester_wheelset.toml: is a single-wheelset vehicle file")
    assert "load_vehicle" in message
