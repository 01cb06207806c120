"""Every spring-damper the package builds is force-free in its reference configuration.

A connector that carries force with all coordinates at their reference values is a
modelling error (a pretension nobody asked for): the primary suspension once carried
k_y d = 3.884 MN of lateral tension per axlebox that way, which turned the wheelset's roll
stiffness negative. The checks below build every Exudyn model of the package (the
co-running track of every zone, both layer counts, both routes' passage systems with the
vehicle) and read each connector's force with every coordinate and velocity at zero.
"""

from __future__ import annotations

from dataclasses import replace

import exudyn as exu
import numpy as np
import pytest

from exudyn_turnout.corunning.parameters import co_running_parameters
from exudyn_turnout.corunning.track import add_co_running_track
from exudyn_turnout.inputs.routes import load_route
from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.inputs.vehicle import load_vehicle
from exudyn_turnout.passage.contact.height_table import HeightTableContact
from exudyn_turnout.passage.contact.profile import route_contact
from exudyn_turnout.passage.corunning_track.wheelset import build_zone_system
from exudyn_turnout.passage.settings import PassageSettings
from exudyn_turnout.passage.vehicle.wheelset import add_vehicle

#: Exudyn connector types that carry a force law; all the package uses are listed here.
CONNECTOR_TYPES = tuple(
    "Connector" + kind
    for kind in (
        "CartesianSpringDamper",
        "SpringDamper",
        "RigidBodySpringDamper",
        "TorsionalSpringDamper",
        "LinearSpringDamper",
        "CoordinateSpringDamper",
    )
)


def _connector_forces(mbs) -> dict[int, np.ndarray]:
    """Force of every spring-damper of ``mbs`` with all coordinates and velocities zero."""
    data = mbs.systemData
    n = data.GetODE2Coordinates().__len__()
    data.SetODE2Coordinates(np.zeros(n), exu.ConfigurationType.Current)
    data.SetODE2Coordinates_t(np.zeros(n), exu.ConfigurationType.Current)
    out = {}
    for i in range(mbs.systemData.NumberOfObjects()):
        kind = mbs.GetObject(i)["objectType"]
        if kind in CONNECTOR_TYPES:
            out[i] = np.atleast_1d(mbs.GetObjectOutput(i, exu.OutputVariableType.Force))
    return out


def _assert_force_free(mbs, what: str) -> int:
    forces = _connector_forces(mbs)
    assert forces, f"{what}: no connectors found"
    for i, f in forces.items():
        assert np.max(np.abs(f)) < 1e-6, f"{what}: connector {i} carries {f} N at rest"
    return len(forces)


@pytest.fixture(scope="module")
def turnout():
    return load_turnout()


@pytest.mark.parametrize("layers", [2, 3])
def test_track_springs_force_free_every_zone(turnout, layers):
    for zone in turnout.zones:
        params = co_running_parameters(turnout, zone=zone.index, layers=layers)
        mbs = exu.SystemContainer().AddSystem()
        x_mid = 0.5 * (zone.x_start + zone.x_end)
        add_co_running_track(mbs, params, x_mid, 0.0, mechanism="constant")
        mbs.Assemble()
        _assert_force_free(mbs, f"zone {zone.index}, {layers} layers")


def test_vehicle_springs_force_free():
    vehicle = load_vehicle()
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(exu.itemInterface.ObjectGround())
    add_vehicle(mbs, vehicle, ground)
    mbs.Assemble()
    assert _assert_force_free(mbs, "vehicle") == 2  # two axlebox springs


@pytest.mark.parametrize("contact", ["height-table", "profile"])
@pytest.mark.parametrize("route_name", ["through", "diverging"])
@pytest.mark.parametrize("layers", [2, 3])
def test_passage_systems_force_free(turnout, route_name, layers, contact):
    vehicle = load_vehicle()
    route = load_route(turnout, route_name)
    settings = replace(PassageSettings(), route=route_name, layers=layers, contact=contact)
    made = (
        HeightTableContact()
        if contact == "height-table"
        else route_contact(turnout, route_name, vehicle)
    )
    for zone in turnout.zones:
        system = build_zone_system(turnout, route, vehicle, zone, settings, zone.x_start, 0.0, made)
        _assert_force_free(
            system.mbs, f"{route_name} zone {zone.index} {layers} layers, {contact} contact"
        )


def test_wheelset_roll_and_lateral_stiffness_by_hand():
    """Linearised primary suspension against its hand values 2 k_z d^2 and 2 k_y.

    Hand values from the vehicle file (Iwnicki 1998, Manchester benchmark): k_z = 1.22 MN/m,
    k_y = 3.884 MN/m per axlebox, d = 1.0 m: roll 2 k_z d^2 = 2.44 MN m/rad (the pretension
    bug gave 2 (k_z - k_y) d^2 = -5.33 MN m/rad), lateral 2 k_y = 7.768 MN/m.
    """
    vehicle = load_vehicle()
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(exu.itemInterface.ObjectGround())
    handles = add_vehicle(mbs, vehicle, ground)
    mbs.Assemble()
    sim = exu.SimulationSettings()
    _, K, _ = mbs.ComputeLinearizedSystem(sim)
    K = np.asarray(K)
    i = mbs.GetNodeODE2Index(handles.wheelset_node)
    assert K[i + 2, i + 2] == pytest.approx(2.0 * 1.22e6 * 1.0**2, rel=1e-9)
    assert K[i + 2, i + 2] == pytest.approx(vehicle.k_roll, rel=1e-9)
    assert K[i, i] == pytest.approx(2.0 * 3.884e6, rel=1e-9)
    assert K[i + 1, i + 1] == pytest.approx(2.0 * 1.22e6, rel=1e-9)
