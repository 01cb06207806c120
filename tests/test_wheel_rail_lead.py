"""Lead of the contact point of a yawed wheel (wheel_rail/lead.py) and its use in the kernel.

References:
- an independent 3-D search written here: the surface of revolution of a coned wheel,
  yawed about the vertical, sampled over its angle and axial position, against a prismatic
  rail (a circular gauge corner of 13 mm radius touching the cone), the touching point
  found as the smallest vertical distance on 201 x 201 grids of angle and axial position,
  from +-0.2 rad and +-4 mm, each around the last one's minimum and 10x finer (5 passes);
- the lateral creepage of a flanging wheel with its contact taken where it lies,
  ``-psi / cos(gamma)`` for r = r0 (derived in lead.py's docstring; the 1 / cos form as
  in Garg & Dukkipati 1984).
"""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_turnout.wheel_rail import along_x, kernel
from exudyn_turnout.wheel_rail.data import s1002_wheel, standard_track
from exudyn_turnout.wheel_rail.geometry import (
    WheelsetSetup,
    rail_row,
    solve_wheelset,
    surface_derivatives,
)
from exudyn_turnout.wheel_rail.lead import MAX_LEAD_SINE, contact_lead

SETUP = WheelsetSetup()
N_Q = 11  # y_w, z_w, phi, psi, beta, y_s, z_s, then left rail (7, 8), right rail (9, 10)
G = 8.1e10  # Pa, steel
RADIUS = 0.46  # m
CORNER = 0.013  # m, radius of the rail's gauge corner in the brute-force search


def _touch(
    gamma: float, yaw: float, side: int, thetas, axial, towards=None, rise=None, curvature=0.0
) -> tuple[float, float, float, float]:
    """Smallest vertical gap of the yawed cone over a grid: (gap, lead, theta, axial).

    ``towards(X)`` and ``rise(X)`` (m, default 0) move the rail's section at track X
    towards the wheel (laterally) and up: a flaring face, a ramp.  ``curvature`` (1/m, > 0)
    makes the wheel's profile a circle of that curvature through the contact point,
    convex towards the rail, ``axial`` then its angle (rad) from the contact point; and
    the gap the distance to the corner's circle (normal), not the vertical one."""
    slope = np.tan(gamma)
    normal = np.array([-side * np.sin(gamma), np.cos(gamma)])  # rail normal, (Y, Z)
    centre = np.array([0.0, -RADIUS]) - CORNER * normal
    theta, e = np.meshgrid(thetas, axial, indexing="ij")
    if curvature:  # (axial, radius) of the profile's circle; its outward normal at e = 0
        beta = np.arctan2(side * np.sin(gamma), np.cos(gamma))  # is (sin beta, cos beta)
        rho = 1.0 / curvature
        radius = RADIUS - rho * np.cos(beta) + rho * np.cos(beta + e)
        along = -rho * np.sin(beta) + rho * np.sin(beta + e)
    else:  # the cone: the flange side has the larger radius
        radius, along = RADIUS - side * slope * e, e
    x_wheel, z = radius * np.sin(theta), -radius * np.cos(theta)
    y = x_wheel * np.sin(yaw) + along * np.cos(yaw)
    x_track = x_wheel * np.cos(yaw) - along * np.sin(yaw)
    centre_y = centre[0] + (np.sign(normal[0]) * towards(x_track) if towards else 0.0)
    centre_z = centre[1] + (rise(x_track) if rise else 0.0)
    d = y - centre_y
    if curvature:
        gap = np.hypot(d, z - centre_z) - CORNER
    else:
        rail = np.where(np.abs(d) < CORNER, centre_z + np.sqrt(np.abs(CORNER**2 - d**2)), -np.inf)
        gap = z - rail
    i = np.unravel_index(np.argmin(gap), gap.shape)
    return float(gap[i]), float(x_track[i]), float(theta[i]), float(e[i])


def _search(
    gamma, yaw, side, towards=None, rise=None, span_t=0.2, curvature=0.0, span_e=4e-3
) -> tuple[float, float]:
    """Gap and track X of the touching point, from grids 10x finer each pass."""
    theta, e = 0.0, 0.0
    for _ in range(5):
        thetas = np.linspace(theta - span_t, theta + span_t, 201)
        axial = np.linspace(e - span_e, e + span_e, 201)
        gap, lead, theta, e = _touch(gamma, yaw, side, thetas, axial, towards, rise, curvature)
        span_t, span_e = span_t / 10.0, span_e / 10.0
    return gap, lead


def brute_force(gamma: float, yaw: float, side: int) -> tuple[float, float]:
    """Lead (m) and normal gap closed (m) by the yaw, from the 3-D search."""
    gap0, _ = _search(gamma, 0.0, side)
    gap1, lead1 = _search(gamma, yaw, side)
    return lead1, (gap0 - gap1) * np.cos(gamma)  # vertical lift closes cos(gamma) of it


@pytest.mark.parametrize(
    "gamma_deg, yaw, side",
    [(70.0, 0.005, 1), (70.0, -0.005, 1), (70.0, 0.005, -1), (-84.0, 0.004, -1), (30.0, 0.01, 1)],
)
def test_lead_and_closing_match_a_3d_search(gamma_deg, yaw, side):
    """Flange (70 deg), back of the flange against a check rail (-84 deg), flange root."""
    gamma = np.radians(gamma_deg)
    lead, closing = contact_lead(RADIUS, gamma, side, yaw)
    lead_3d, closing_3d = brute_force(gamma, yaw, side)
    assert abs(lead) > 1e-3  # a millimetre or more: worth having
    assert float(lead) == pytest.approx(lead_3d, rel=5e-3, abs=2e-5)
    assert float(closing) == pytest.approx(closing_3d, rel=0.02, abs=2e-7)


FLARE = 1.0 / 67.0  # the check rail's flare at the packaged turnout's crossing
RAMP = 1.0 / 20.0  # a steep ramp of a rail's top (a nose rising), for a clear effect


@pytest.mark.parametrize(
    "case, kink",
    [
        ("flare", -0.03), ("flare", 0.0), ("flare", 0.05), ("flare", 0.10),
        ("ramp", -0.02), ("ramp", 0.01), ("ramp", 0.05),
    ],
)  # fmt: skip
def test_lead_along_a_flare_and_a_ramp_matches_a_3d_search(case, kink):
    """The rail varies along x up to a kink at ``kink`` (m from the axle), constant beyond:
    a check rail's face flaring 1:67 towards the back of the flange (-84 deg, yaw 4 mrad,
    lead 17.5 mm on a prismatic rail) that meets its check line, and a rail's top rising
    1:20 under the tread (5 deg, yaw 10 mrad, lead 0.4 mm) to a plateau.  The kernel's
    minimum along x (along_x.lead_along_x on the rail's gap at three x nodes, the exact
    normal gap of the cone's line against the corner's circle moved by the rail, with
    R_x = r / cos(gamma)) against the 3-D search on the moving rail: behind the lead the
    kink changes nothing, ahead of it within |a| R_x the contact sits on the kink, further
    ahead at x_yaw - a R_x (the flare: 83 mm, the ramp: 23 mm).  Tolerances: 0.5 mm of lead
    and 1 % of the gap (the parabola stands for the wheel's circle: at theta = 0.18 rad the
    two differ by theta^2 / 12 ~ 0.3 %); the first-order lead (the rail's slope at the axle
    times the yaw's lead) is off by 30 ... 430 % of the gap where the kink matters."""
    if case == "flare":
        gamma, yaw, side = np.radians(-84.0), 0.004, -1
        towards, rise = (lambda x: FLARE * np.minimum(x - kink, 0.0)), None
        normal_gap = lambda x: -abs(np.sin(gamma)) * FLARE * np.minimum(x - kink, 0.0)  # noqa: E731
    else:
        gamma, yaw, side = np.radians(5.0), 0.01, 1
        towards, rise = None, (lambda x: RAMP * np.minimum(x - kink, 0.0))
        normal_gap = lambda x: -np.cos(gamma) * RAMP * np.minimum(x - kink, 0.0)  # noqa: E731
    gap0, _ = _search(gamma, 0.0, side)
    gap_3d, lead_3d = _search(gamma, yaw, side, towards, rise, span_t=0.3)
    # the rail's normal gap at three x nodes (gap, position on the rail interleaved)
    xs = np.array([kink - 1.0, kink, kink + 1.0])
    values = np.zeros(6)
    values[0::2] = normal_gap(xs)
    ix = 0 if kink > 0.0 else 1
    x_yaw, closing = (float(v) for v in contact_lead(RADIUS, gamma, side, yaw))
    limit = MAX_LEAD_SINE * RADIUS
    lead, change = along_x.lead_along_x(
        values, xs, 2 * ix, ix, True, 3, 2, 0, 0.0, 0.0, x_yaw, RADIUS / np.cos(gamma), 0.0,
        -limit, limit,
    )  # fmt: skip
    vertical = (normal_gap(0.0) + change - closing) / np.cos(gamma)
    assert lead == pytest.approx(lead_3d, abs=5e-4)
    assert vertical == pytest.approx(gap_3d - gap0, rel=0.01, abs=1e-6)
    slope = (values[2 * ix + 2] - values[2 * ix]) / (xs[ix + 1] - xs[ix])
    first_order = (normal_gap(0.0) + x_yaw * slope - closing) / np.cos(gamma)
    if 0.0 < kink:  # the kink ahead of the axle: the first-order lead misses it
        assert abs(first_order - (gap_3d - gap0)) > 0.3 * abs(gap_3d - gap0)
        assert abs(lead - x_yaw) > 9e-3
    else:  # behind: the rail is prismatic where the contact lies, nothing changes
        assert lead == x_yaw and change == 0.0


def _fine_search(gamma, yaw, side, towards, curvature) -> tuple[float, float]:
    """Gap and track X of the touching point: a dense first grid over the wheel's angle
    (-0.01 ... 0.2 rad, 0.2 mrad) and the profile's (+-0.3 rad, 1 mrad), then two grids
    10x finer around its minimum (the coarse first grid of ``_search`` can settle in the
    wrong valley of a curved profile)."""
    thetas, angles = np.linspace(-0.01, 0.2, 1051), np.linspace(-0.3, 0.3, 601)
    gap, lead, theta, e = _touch(gamma, yaw, side, thetas, angles, towards, None, curvature)
    span_t, span_e = 2e-3, 1e-2
    for _ in range(2):
        thetas = np.linspace(theta - span_t, theta + span_t, 101)
        angles = np.linspace(e - span_e, e + span_e, 101)
        gap, lead, theta, e = _touch(gamma, yaw, side, thetas, angles, towards, None, curvature)
        span_t, span_e = span_t / 10.0, span_e / 10.0
    return gap, lead


@pytest.mark.parametrize("kink", [0.03, 0.05, 0.10])
def test_profile_term_on_a_curved_flange_back_matches_a_3d_search(kink):
    """The flare of the test above against a flange back whose profile is curved (20 mm,
    convex, against the corner's 13 mm): the wheel's point xi ahead lies xi^2 / (2 r)
    higher, millimetres at these leads, and slides the two curved profiles along their
    tangent; the parabola alone (cone) closes the gap by up to 0.5 mm too much here, with
    the profile term (``quartic = sin(gamma)^2 / (8 r^2 (rho_w + rho_r))``) the kernel's
    minimum is within 2 % (+ 2 um) of the normal gap of the 3-D search and 1 mm of its
    lead."""
    gamma, yaw, side, curvature = np.radians(-84.0), 0.004, -1, 50.0
    towards = lambda x: FLARE * np.minimum(x - kink, 0.0)  # noqa: E731
    normal_gap = lambda x: -abs(np.sin(gamma)) * FLARE * np.minimum(x - kink, 0.0)  # noqa: E731
    gap0, _ = _fine_search(gamma, 0.0, side, None, curvature)
    gap_3d, lead_3d = _fine_search(gamma, yaw, side, towards, curvature)
    xs = np.array([kink - 1.0, kink, kink + 1.0])
    values = np.zeros(6)
    values[0::2] = normal_gap(xs)
    x_yaw, closing = (float(v) for v in contact_lead(RADIUS, gamma, side, yaw))
    limit = MAX_LEAD_SINE * RADIUS
    quartic = np.sin(gamma) ** 2 / (8.0 * RADIUS**2 * (1.0 / curvature + CORNER))
    results = {}
    for term in (0.0, quartic):
        lead, change = along_x.lead_along_x(
            values, xs, 0, 0, True, 3, 2, 0, 0.0, 0.0, x_yaw, RADIUS / np.cos(gamma), term,
            -limit, limit,
        )  # fmt: skip
        results[term] = (lead, normal_gap(0.0) + change - closing)
    lead, gap = results[quartic]
    assert abs(gap0) < 1e-7  # the surfaces touch without yaw and flare
    assert gap == pytest.approx(gap_3d - gap0, rel=0.02, abs=2e-6)
    assert lead == pytest.approx(lead_3d, abs=1e-3)
    assert abs(results[0.0][1] - (gap_3d - gap0)) > 5 * abs(gap - (gap_3d - gap0))


def test_lead_sign_and_cap():
    # left wheel (s = +1) against its flange (gamma > 0), wheelset turned left (psi > 0):
    # ahead; the right wheel's flange (s = -1) behind; no yaw, no lead
    assert contact_lead(RADIUS, 1.2, 1, 0.005)[0] > 0.0 > contact_lead(RADIUS, 1.2, -1, 0.005)[0]
    assert contact_lead(RADIUS, 1.2, 1, 0.0) == (0.0, 0.0)
    capped, _ = contact_lead(RADIUS, np.radians(89.0), 1, 0.1)
    assert float(capped) == pytest.approx(RADIUS * MAX_LEAD_SINE)


@pytest.fixture(scope="module")
def plain(plain_packed):
    """S1002 on plain UIC60 track, packed (conftest.py)."""
    return plain_packed


def _evaluate(packed, q, constants):
    forces = np.zeros(N_Q)
    details = np.zeros((packed.n_bodies * packed.n_candidates, len(kernel.DETAIL_FIELDS)))
    kernel.contact_forces(
        5.0,
        np.asarray(q, float),
        np.zeros(N_Q),
        np.zeros(4),
        packed.values,
        packed.blendable,
        packed.x,
        packed.layout,
        packed.bounds,
        np.asarray(constants, float),
        forces,
        details,
    )
    return forces, details


def _column(name: str) -> int:
    return kernel.DETAIL_FIELDS.index(name)


def test_kernel_flange_contact_of_a_yawed_wheelset(plain):
    """Left wheel on its flange (S1002 on UIC60 1:40, shift 7 mm: contact angle 70 deg),
    pressed 50 um without yaw, then yawed by 5 mrad at 80 km/h: the contact leads by
    contact_lead's x, is pressed in further by its closing, the lateral creepage is
    -psi cos(gamma) - (r / r0) tan(psi) tan(gamma) sin(gamma) (within 3 % of -psi / cos(gamma),
    r / r0 = 1.028 there) and the spin creepage is unchanged."""
    v, r0, yaw = 80.0 / 3.6, 0.46, 0.005
    constants = (v, r0, 0.4, G, 0.0, 0.0)
    q = np.zeros(N_Q)
    q[0] = 0.007
    _, details = _evaluate(plain, q, (0.0, r0, 0.4, G, 0.0, 0.0))
    left = details[: plain.n_candidates]
    deepest = left[
        np.argmax(np.where(left[:, _column("found")] > 0, left[:, _column("delta")], -1))
    ]
    q[1] = (deepest[_column("delta")] - 5e-5) / np.cos(deepest[_column("angle")])
    rows = {}
    for psi in (0.0, yaw):
        q[3] = psi
        _, details = _evaluate(plain, q, constants)
        loaded = details[: plain.n_candidates]
        loaded = loaded[loaded[:, _column("normal")] > 0]
        assert len(loaded) == 1
        rows[psi] = loaded[0]
    straight, yawed = rows[0.0], rows[yaw]
    gamma, r = yawed[_column("angle")], yawed[_column("radius")]
    assert np.degrees(gamma) == pytest.approx(70.0, abs=1.0)
    lead, closing = contact_lead(r, gamma, 1, yaw)
    assert straight[_column("x_offset")] == 0.0 and straight[_column("eta")] == 0.0
    assert yawed[_column("x_offset")] == pytest.approx(float(lead), rel=1e-12)
    assert 6e-3 < yawed[_column("x_offset")] < 7e-3
    assert yawed[_column("delta")] - straight[_column("delta")] == pytest.approx(
        float(closing), rel=1e-9
    )
    expected = -yaw * np.cos(gamma) - r / r0 * np.tan(yaw) * np.tan(gamma) * np.sin(gamma)
    assert yawed[_column("eta")] == pytest.approx(expected, rel=1e-9)
    assert yawed[_column("eta")] == pytest.approx(-yaw / np.cos(gamma), rel=0.03)
    assert yawed[_column("spin")] == pytest.approx(straight[_column("spin")], rel=1e-12)


def test_rigid_wheelset_yawed_in_flange_contact():
    """S1002 on UIC60 1:40 (Manchester benchmark profiles), wheelset 6.5 mm to the left (the
    left flange against its rail at 67 deg, the wheelset rolled by 4.3 mrad) and yawed by 5
    mrad: the left contact leads by
    contact_lead's x, the right one (tread, ~0.02 rad) by < 0.1 mm; both wheels still touch
    (vertical gaps 0); the flange reaches nearer its rail, so the wheelset rolls further
    (left side up) than without yaw."""
    wheel = s1002_wheel(SETUP)
    track = standard_track(SETUP)
    row = rail_row(track, surface_derivatives(track))
    results = {
        yaw: solve_wheelset(np.array([0.0065]), wheel, row, row, SETUP, yaw=yaw)
        for yaw in (0.0, 0.005)
    }
    straight, yawed_result = results[0.0], results[0.005]
    assert straight.x_lead_left[0] == 0.0 and straight.x_lead_right[0] == 0.0
    gamma = yawed_result.angle_left[0]
    assert np.degrees(gamma) == pytest.approx(67.0, abs=1.5)
    lead, _ = contact_lead(yawed_result.radius_left[0], gamma, 1, 0.005)
    assert yawed_result.x_lead_left[0] == pytest.approx(float(lead), rel=1e-12)
    assert 5e-3 < yawed_result.x_lead_left[0] < 6.5e-3
    assert abs(yawed_result.x_lead_right[0]) < 1e-4
    for side in ("left", "right"):
        found = getattr(yawed_result, f"candidates_{side}")[0]
        # the roll is solved on the vertical search; the flange's point from the 60 deg
        # search lies within 1 um of touching (0.81 um without yaw, 0.45 um with)
        assert found.gap[0] / np.cos(found.angle[0]) == pytest.approx(0.0, abs=1e-6)
    assert yawed_result.roll[0] > straight.roll[0]
