"""The FE track under the one vehicle and contact: co-simulation (passage/fe_track/coupling.py).

References: Exudyn's own time integration (the coupling must use its constants), the FE
model's static solution computed independently (scipy spsolve on the assembled planes with
the load vectors of fe/rail_head.py), the vehicle's weight (44 482 kg x 9.81 / 8 per wheel
is the full vehicle's; the single wheelset carries (m_w + m_s) g / 2 per wheel), and the
co-running passage's static wheel loads (issue 14: equal within 0.1 %).
"""

from types import SimpleNamespace

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as sla

from exudyn_turnout.fe.rail_head import rail_head_point
from exudyn_turnout.fe.timoshenko import lagrange_shape_functions
from exudyn_turnout.inputs.vehicle import GRAVITY, load_vehicle
from exudyn_turnout.passage.fe_track.planes import (
    PlaneStepper,
    build_fe_planes,
    generalized_alpha,
    lagrange_weights,
)
from exudyn_turnout.passage.fe_track.wheelset import simulate_wheelset
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings

X0 = -3.0  # m, plain track before the toe (the FE layout starts at -6 m)


@pytest.fixture(scope="module")
def planes(turnout):
    return build_fe_planes(turnout)


@pytest.fixture(scope="module")
def short_run(turnout, planes):
    """0.15 m of plain track at 100 km/h on the FE track (54 steps)."""
    settings = PassageSettings(route="through", speed_kmh=100.0, x_start=X0, x_end=X0 + 0.15)
    return _fe_wheelset(turnout, settings, planes)


def _fe_wheelset(turnout, settings, planes):
    """The FE track's wheelset run with prebuilt FE planes (the door builds them anew)."""
    from exudyn_turnout.inputs.routes import load_route
    from exudyn_turnout.inputs.vehicle import load_vehicle
    from exudyn_turnout.passage.contact.profile import route_contact

    vehicle = load_vehicle()
    contact = route_contact(turnout, settings.route, vehicle)
    route = load_route(turnout, settings.route)
    x_range = (settings.x_start, settings.x_end)
    return simulate_wheelset(turnout, settings, vehicle, contact, route, x_range, planes=planes)


def test_generalized_alpha_update_is_exudyns(turnout):
    """The FE side's step equals Exudyn's generalized-alpha on a forced damped oscillator.

    Reference: Exudyn 1.13's implicit solver on the same oscillator (ObjectGenericODE2 with
    a force user function); exactness of the co-simulation rests on this equality.
    """
    import exudyn as exu
    from exudyn.itemInterface import NodeGenericODE2, ObjectGenericODE2, SensorNode

    rho, h, n, k, c, q0 = 0.8, 1e-3, 200, (2 * np.pi * 50) ** 2, 3.0, 0.01

    def force(t):
        return 100.0 * np.sin(300.0 * t)

    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    node = mbs.AddNode(
        NodeGenericODE2(
            referenceCoordinates=[0.0],
            initialCoordinates=[q0],
            initialCoordinates_t=[0.0],
            numberOfODE2Coordinates=1,
        )
    )
    mbs.AddObject(
        ObjectGenericODE2(
            nodeNumbers=[node],
            massMatrix=np.eye(1),
            stiffnessMatrix=k * np.eye(1),
            dampingMatrix=c * np.eye(1),
            forceUserFunction=lambda mbs, t, i, q, q_t: [force(t)],
        )
    )
    sensor = mbs.AddSensor(
        SensorNode(
            nodeNumber=node,
            storeInternal=True,
            writeToFile=False,
            outputVariableType=exu.OutputVariableType.Coordinates,
        )
    )
    mbs.Assemble()
    sim = exu.SimulationSettings()
    ti = sim.timeIntegration
    ti.numberOfSteps, ti.endTime, ti.verboseMode = n, n * h, 0
    ti.generalizedAlpha.spectralRadius = rho
    ti.adaptiveStep = False
    ti.newton.relativeTolerance = ti.newton.absoluteTolerance = 1e-12
    sim.solution.file.write = False
    sim.solution.sensors.writePeriod = 0.999 * h
    exu.config.printToConsole = False
    mbs.SolveDynamic(sim)
    exudyn_q = mbs.GetSensorStoredData(sensor)[:, 1]

    ga = generalized_alpha(rho)
    model = SimpleNamespace(M=sp.csc_matrix([[1.0]]), K=sp.csc_matrix([[k]]), n_dof=1)
    plane = PlaneStepper(model, sp.csc_matrix([[c]]), h, ga)
    plane.u[:] = q0
    plane.qdd[:] = plane.a[:] = force(0.0) - k * q0
    ours = [q0]
    for step in range(1, n + 1):
        plane.predict()
        plane.complete(plane.factor.solve(np.array([force(step * h)])))
        ours.append(plane.u[0])
    assert np.max(np.abs(exudyn_q - np.array(ours))) < 1e-12 * np.max(np.abs(ours))


def test_lagrange_weights_equal_the_elements_shape_functions():
    for p in (1, 2, 4):
        for xi in (0.0, 0.137, 0.5, 1.0):
            reference = lagrange_shape_functions(p, [xi])[0][0]
            assert np.allclose(lagrange_weights(p, xi), reference, atol=1e-14)


def test_generalized_alpha_refuses_a_bad_radius():
    with pytest.raises(ValueError, match="spectral radius"):
        generalized_alpha(1.5)


def test_static_wheel_loads_equal_the_co_running_ones(turnout, short_run):
    """Issue 14: same vehicle, FE vs co-running static wheel loads within 0.1 %."""
    vehicle = load_vehicle()
    weight_share = 0.5 * (vehicle.m_w + vehicle.m_s) * GRAVITY
    settings = PassageSettings(route="through", speed_kmh=100.0, x_start=X0, x_end=X0 + 0.05)
    co_running = simulate_passage(turnout, settings, vehicle="wheelset")
    for wheel in ("left", "right"):
        key = "static_wheel_load_N" if wheel == "right" else "static_wheel_load_left_N"
        fe = short_run.summary[key]
        ref = co_running.summary[key]
        assert abs(fe - ref) <= 1e-3 * ref
        assert abs(fe - weight_share) <= 1e-3 * weight_share


def test_static_deflection_is_the_fe_static_solution(turnout, planes):
    """Issue 14: the wheels' static rail deflection equals K^-1 f of the FE planes.

    Reference: the static field of the wheels' forces (vertical and lateral, from the
    static equilibrium) solved independently with scipy's spsolve on each plane, with the
    load vectors and head displacements of fe/rail_head.py (not the coupling's own).
    """
    from exudyn_turnout.inputs.routes import load_route
    from exudyn_turnout.passage.contact.profile import route_contact
    from exudyn_turnout.passage.fe_track.coupling import FECoSimulation
    from exudyn_turnout.passage.fe_track.wheelset import static_equilibrium

    vehicle = load_vehicle()
    route = load_route(turnout, "through")
    track = FECoSimulation(planes, "through", 1e-4, 0.8)
    rest = static_equilibrium(track, route_contact(turnout, "through", vehicle), vehicle, route, X0)
    coupled = rest.element.last[0]
    f_ver = np.zeros(planes.vertical.n_dof)
    f_lat = np.zeros(planes.lateral.n_dof)
    points = []
    for j, k in enumerate(coupled.bodies):
        slot = rest.element.element.bodies[k].rail
        rail_id = planes.layout.slot_rail(slot, X0, "through")
        point = rail_head_point(planes.vertical, planes.lateral, rail_id, X0)
        fv, fl = point.loads(rest.rail_forces[2 * j], rest.rail_forces[2 * j + 1])
        f_ver += fv
        f_lat += fl
        points.append(point)
    assert len(points) == 2  # the two stock rails on plain track
    u_ver = sla.spsolve(planes.vertical.K.tocsc(), f_ver)
    u_lat = sla.spsolve(planes.lateral.K.tocsc(), f_lat)
    for j, point in enumerate(points):
        u_y, u_z = point.displacement(u_ver, u_lat)
        assert rest.rail_displacements[2 * j] == pytest.approx(u_y, rel=1e-6)
        assert rest.rail_displacements[2 * j + 1] == pytest.approx(u_z, rel=1e-6)
        assert u_z < -5e-4  # about a millimetre under a wheel load
        assert abs(u_y) > 1e-5  # the rail heads are pushed apart by N tan(gamma)
    total = rest.wheel_loads["left"] + rest.wheel_loads["right"]
    assert total == pytest.approx((vehicle.m_w + vehicle.m_s) * GRAVITY, rel=1e-6)


def test_coupling_is_consistent_with_the_fe_state(short_run, turnout, planes):
    """The rail coordinates the contact solved for are where the completed FE step put the
    rail head (to 1e-12 m): r = r_free + C F and the FE update agree (no lag, no sign slip).
    The forces stay near the static load on plain track (sleeper passing: < 5 %)."""
    from exudyn_turnout.inputs.routes import load_route
    from exudyn_turnout.passage.contact.profile import route_contact
    from exudyn_turnout.passage.fe_track.common import fe_contact_element
    from exudyn_turnout.passage.fe_track.coupling import (
        FEContactElement,
        FECoSimulation,
    )
    from exudyn_turnout.passage.fe_track.wheelset import static_equilibrium

    cols = short_run.columns
    W = short_run.summary["static_wheel_load_N"]
    assert np.all(np.abs(cols["Fz_right_N"] / W - 1.0) < 0.05)
    assert np.all(np.abs(cols["Fz_left_N"] / W - 1.0) < 0.05)
    # one step by hand with the pieces of the passage, from the static state
    vehicle = load_vehicle()
    route = load_route(turnout, "through")
    contact = route_contact(turnout, "through", vehicle)
    track = FECoSimulation(planes, "through", 1e-4, 0.8)
    rest = static_equilibrium(track, contact, vehicle, route, X0)
    v = 27.0
    element = FEContactElement(fe_contact_element(contact, vehicle, route, X0, v, None), track)
    track.start([element], [rest.rail_forces], v)
    track.predict(1e-4, [element])
    q = rest.vehicle_q.copy()
    q[1] -= 1e-5  # the wheelset pressed 10 um further down
    F = element.solve(1e-4, q, np.zeros(7))
    track.complete([(element, F)])
    r_fe = track.rail_displacements(track.points(element.element, X0 + v * 1e-4))
    assert np.max(np.abs(element.last[1] - r_fe)) < 1e-12
    assert -(F[1] + F[3]) > 2.0 * 1.05 * W  # pressed further in: larger loads
