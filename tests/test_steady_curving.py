"""Steady-state (quasi-static) curving without time integration (issue 23)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.inputs.vehicle_model import load_vehicle_model
from exudyn_turnout.passage.vehicle.steady_curving import (
    build_rigid_curve,
    conical_wheelset_residual,
    newton_steady,
    pure_rolling_offset,
    solve_steady_state,
)

# Manchester wheelset (Iwnicki (ed.) 1998, Veh. Syst. Dyn. 30(3-4) 295-313): 1813 kg,
# r0 = 0.46 m; b = 0.75 m; creep coefficients of the order of Kalker's for a 55 kN wheel
# (the closed form does not depend on them)
WHEELSET = dict(mass=1813.0, r0=0.46, b=0.75, conicity=0.15, f11=8e6, f22=7e6)


@pytest.mark.parametrize("radius, kmh", [(760.0, 80.0), (-300.0, 40.0)])
def test_conical_wheelset_rolls_at_the_pure_rolling_offset(radius, kmh):
    v, kappa = kmh / 3.6, 1.0 / radius
    p = WHEELSET

    def f(u):
        return conical_wheelset_residual(u, v, kappa, **p)

    result = newton_steady(f, np.zeros(3), np.array([1e-7, 1e-7, 1e-5]), tolerance=1e-6)
    assert result.converged
    y, psi, omega = result.u
    # Wickens 2003 sec. 2.3: y0 = r0 b / (lambda R), towards the outer rail (-sign(kappa))
    y0 = pure_rolling_offset(p["r0"], p["b"], p["conicity"], abs(radius))
    assert y == pytest.approx(-math.copysign(y0, kappa), rel=1e-6)
    # lateral balance: the creep forces carry the centrifugal load, sum F_y = m v^2 / R
    assert 2 * p["f22"] * psi == pytest.approx(p["mass"] * v**2 * kappa, rel=1e-6)
    assert abs(omega) < 1e-3 * v / p["r0"]


def test_pure_rolling_offset_closed_form():
    # Iwnicki (ed.) 2006, Handbook of Railway Vehicle Dynamics, ch. 9: 0.46 * 0.75 / (0.15 * 760)
    assert pure_rolling_offset(0.46, 0.75, 0.15, 760.0) == pytest.approx(3.0263e-3, rel=1e-4)


@pytest.fixture(scope="module")
def steady():
    turnout = load_turnout()
    model = load_vehicle_model()
    system = build_rigid_curve(turnout, "diverging", model, 80.0 / 3.6, 40.0)
    return system, solve_steady_state(system), model


def test_full_vehicle_steady_state_balances_the_centrifugal_load(steady):
    system, result, model = steady
    v = system.v
    # in a steady state the suspension forces are internal: sum of H = M v^2 |kappa|
    target = model.total_mass * v**2 * abs(system.kappa[0])
    assert result.total_lateral == pytest.approx(target, rel=1e-5)
    # every wheelset outwards (left, in this right-hand curve), the leading ones at the
    # flange root (validation/quasi_static_curving.md: 6.1 mm, contact angle ~27 deg)
    assert np.all(result.y > 0.0)
    assert 5e-3 < result.y[0] < 7e-3
    assert math.degrees(result.contact_angle[0, 1]) > 15.0


def test_steady_state_is_at_rest_under_the_time_integration(steady):
    import exudyn as exu

    from exudyn_turnout.passage.vehicle.builder import dynamic_settings

    system, result, _ = steady
    mbs, build = system.mbs, system.build
    q_t = np.zeros_like(result.q)
    for ws, omega in zip(build.wheelsets, result.spin_rate):
        q_t[mbs.GetNodeODE2Index(ws.node) + ws.dof["spin"]] = omega
    mbs.systemData.SetODE2Coordinates(result.q.tolist(), exu.ConfigurationType.Initial)
    mbs.systemData.SetODE2Coordinates_t(q_t.tolist(), exu.ConfigurationType.Initial)
    previous = exu.config.printToConsole
    exu.config.printToConsole = False
    sim = dynamic_settings(0.1, 5e-4)
    # the frozen curving loads ramp up over t in [0, 1] (static solves): start at t = 1
    sim.timeIntegration.startTime, sim.timeIntegration.endTime = 1.0, 1.1
    try:
        mbs.SolveDynamic(sim)
    finally:
        exu.config.printToConsole = previous
    q = np.array(mbs.systemData.GetODE2Coordinates())
    for ws in build.wheelsets:
        i = mbs.GetNodeODE2Index(ws.node)
        assert abs(q[i + ws.dof["y"]] - result.q[i + ws.dof["y"]]) < 1e-6
        assert abs(q[i + ws.dof["yaw"]] - result.q[i + ws.dof["yaw"]]) < 1e-6
