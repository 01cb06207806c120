"""The full vehicle's run segment module
(:mod:`exudyn_turnout.passage.corunning_track.vehicle_system`): which zone a wheelset is in,
and the state vectors read by name. The segment's system itself is built in
tests/test_corunning_track_vehicle.py and run in every full-vehicle passage test.

Reference values: the packaged turnout (exudyn_turnout/data/uic60_760_1_15.toml, [[zones]]):
zone 1 -5..44.29 m, zone 2 44.29..51 m, zone 3 51..60 m.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage.corunning_track import vehicle_system
from exudyn_turnout.passage.corunning_track.vehicle_system import (
    element_vector,
    place_of,
    track_vector,
)


@pytest.fixture(scope="module")
def turnout():
    return load_turnout()


@pytest.mark.parametrize(
    "x, zone, clamped, beyond",
    [
        (-5.5, 1, True, False),  # behind x_min = -5 m: zone 1, clamped
        (-5.0, 1, False, False),
        (44.28, 1, False, False),
        (44.29, 2, False, False),  # a boundary belongs to the zone it starts
        (50.99, 2, False, False),
        (51.0, 3, False, False),
        (60.0, 3, False, False),  # x_max itself: the last zone, not beyond
        (61.0, 3, False, True),
    ],
)
def test_place_of_gives_the_zone_containing_x(turnout, x, zone, clamped, beyond):
    assert turnout.x_min == -5.0 and turnout.x_max == 60.0  # the file's zones (docstring)
    place = place_of(turnout, x)
    assert (place.zone.index, place.clamped, place.beyond) == (zone, clamped, beyond)


def _fake_system(layers: int) -> SimpleNamespace:
    """What element_vector and track_vector read of a system: params, slots, names."""
    names = {"ws1": 0, "dummy1": 1, "t1:sleeper": 2, "t1:rail_r1": 3, "t1:rail_r2": 4}
    names.update({"t1:m0_r1": 5, "t1:m0_r2": 6})
    return SimpleNamespace(
        params=[SimpleNamespace(layers=layers)], slots=[("r2", "r1")], names=names
    )


def _state() -> dict[str, tuple[np.ndarray, np.ndarray]]:
    def pair(*q):
        return np.array(q, float), -np.array(q, float)

    return {
        "ws1": pair(1, 2, 3, 4, 5),
        "dummy1": pair(6, 7),
        "t1:sleeper": pair(8, 9, 10),
        "t1:rail_r1": pair(11, 12),
        "t1:rail_r2": pair(13, 14),
        "t1:m0_r1": pair(15, 16),
        "t1:m0_r2": pair(17, 18),
    }


@pytest.mark.parametrize("layers, r2, r1", [(2, (13, 14), (11, 12)), (3, (17, 18), (15, 16))])
def test_element_vector_is_wheelset_dummy_then_the_contact_bodies_in_slot_order(layers, r2, r1):
    # the contact bodies: the rails on 2 layers, the rails' top masses m0 on 3
    system, state = _fake_system(layers), _state()
    expected = [1, 2, 3, 4, 5, 6, 7, *r2, *r1]
    np.testing.assert_array_equal(element_vector(system, state, 0, 0), expected)
    np.testing.assert_array_equal(element_vector(system, state, 0, 1), -np.array(expected))


def test_track_vector_names_every_track_coordinate():
    q = track_vector(_state(), _fake_system(3), 0, 0)
    assert q["y_r1"] == 11 and q["z_r2"] == 14 and q["y_m0_r1"] == 15 and q["z_m0_r2"] == 18
    assert len(q) == 3 + 4 + 4  # sleeper's three, two rails and two m0, (y, z) each


def test_every_public_name_is_listed():
    public = {n for n in vars(vehicle_system) if not n.startswith("_")}
    assert set(vehicle_system.__all__) <= public
    assert {"build_segment", "carry_over_state", "named_state"} <= set(vehicle_system.__all__)
