"""The contact element's force function, evaluated directly (no solver).

Reference values: Hertz F = C_H delta^1.5; a wheelset displaced to the left by y on a
conical tread gets a yaw moment that turns it right (Wickens 2003, ch. 3: the kinematic
oscillation of Klingel); flange forces only push; curving load m v^2 / R.
"""

import pytest

from exudyn_turnout.inputs.routes import load_route
from exudyn_turnout.inputs.vehicle import load_vehicle
from exudyn_turnout.passage.contact.height_table import BoundPair, WheelRailElement


@pytest.fixture(scope="module")
def through(turnout):
    return load_route(turnout, "through")


def _element(route, x0, v, rails=("r1", "r2", "r4")):
    index = {r: 6 + 2 * i for i, r in enumerate(rails)}
    pairs = [BoundPair(p, index[p.rail], index[p.rail] + 1) for p in route.pairs if p.rail in index]
    return WheelRailElement(load_vehicle(), route, pairs, x0, v)


def test_static_normal_force_is_hertz(through):
    el = _element(through, -2.0, 0.0)
    q = [0.0] * el.n
    q[1] = -1e-4  # wheelset 0.1 mm into both rails
    f = el(None, 0.0, 0, q, [0.0] * el.n)
    assert f[1] == pytest.approx(2 * 9e10 * 1e-4**1.5)
    assert f[2] == pytest.approx(0.0, abs=1e-9)  # symmetric: no roll moment


def test_conical_wheelset_steers_back_to_the_centre(through):
    el = _element(through, -2.0, 27.8)
    q, q_t = [0.0] * el.n, [0.0] * el.n
    q[1], q[0] = -1e-4, 0.003  # 3 mm to the left
    f = el(None, 0.0, 0, q, q_t)
    assert f[3] < 0  # yaw moment turns the front to the right


def test_flange_pushes_back_only_beyond_clearance(through):
    el = _element(through, -2.0, 27.8)
    q, q_t = [0.0] * el.n, [0.0] * el.n
    q[1] = -1e-4
    gamma, b = el.vehicle.contact.conicity, el.vehicle.b
    q[0], q[2] = (
        0.004,
        gamma * 0.004 / b,
    )  # within the 6 mm clearance, with the cone's kinematic roll
    inside = el(None, 0.0, 0, q, q_t)[0]
    q[0], q[2] = 0.008, gamma * 0.008 / b  # 2 mm into the left flange
    beyond = el(None, 0.0, 0, q, q_t)[0]
    assert beyond - inside == pytest.approx(-2e8 * 0.002, rel=1e-6)


def test_curving_load(turnout):
    div = load_route(turnout, "diverging")
    el = _element(div, 20.0, 27.8)
    q = [0.0] * el.n
    f = el(None, 0.0, 0, q, [0.0] * el.n)  # no contact: only the curving load remains
    veh = load_vehicle()
    assert f[0] == pytest.approx(
        veh.m_w * 27.8**2 / 760, rel=1e-6
    )  # curve to the right: load to the left
    assert f[4] == pytest.approx(veh.m_s * 27.8**2 / 760, rel=1e-6)


def test_load_transfer_comes_from_the_profiles(through):
    """At x = 1 m the right wheel stands on the stock rail r1, at 6 m on the blade r2."""
    el = _element(through, 0.0, 0.0)
    q = [0.0] * el.n
    q[1] = -1e-4
    for x, on, off in ((1.0, "r1", "r2"), (6.0, "r2", "r1")):
        forces = {"r1": 0.0, "r2": 0.0}
        for bp in el.pairs:
            if bp.pair.wheel == "right":
                forces[bp.pair.rail] += el.pair_forces(bp, x, q, [0.0] * el.n).N
        assert forces[on] > 0 and forces[off] == 0
