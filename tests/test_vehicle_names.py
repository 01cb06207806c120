"""inputs/vehicle_names.py: the packaged vehicle files by name."""

from __future__ import annotations

import pytest

from exudyn_turnout.inputs.toml_fields import TurnoutFileError
from exudyn_turnout.inputs.vehicle_names import (
    FULL_VEHICLE,
    PACKAGED_VEHICLES,
    SINGLE_WHEELSET,
    packaged_vehicle_kind,
    packaged_vehicle_path,
)


def test_names_and_files():
    assert set(PACKAGED_VEHICLES) == {"wheelset", "manchester"}
    assert packaged_vehicle_path("wheelset").name == "manchester_wheelset.toml"
    assert packaged_vehicle_path("manchester").name == "manchester_vehicle.toml"
    for name in PACKAGED_VEHICLES:
        assert packaged_vehicle_path(name).is_file()
    assert packaged_vehicle_kind("wheelset") == SINGLE_WHEELSET
    assert packaged_vehicle_kind("manchester") == FULL_VEHICLE


@pytest.mark.parametrize("call", [packaged_vehicle_path, packaged_vehicle_kind])
def test_unknown_name_fails_in_one_line_listing_the_names(call):
    with pytest.raises(TurnoutFileError) as err:
        call("Manchester ")
    message = str(err.value)
    assert "\n" not in message
    assert message == "unknown packaged vehicle 'Manchester ' (packaged: wheelset, manchester)"
