"""Semi-Hertzian (Kik-Piotrowski) normal contact, wheel_rail/nonhertz.py.

References:
- the strip integral J(L, t) against its definition, integrated numerically
  (``scipy.integrate.quad``);
- Hertz (Johnson 1985, Eqs 4.39-4.41, :mod:`exudyn_turnout.wheel_rail.hertz`) for gaps that
  are exactly ``B y^2``: KP (Piotrowski & Kik, VSD 46 (2008) 27-48) is not exact there.
  Measured before the tolerance was set: force 0.7-4.9 % above Hertz for B / A = 0.28-28
  at 0.02-0.2 mm; the tolerance, 6 %, is that approximation of the method (not a
  numerical error);
- a flat face 25 mm wide with 5 mm corner radii (the check-rail face of issue 22): the
  patch must lie on the face (the Hertz ellipse of the floored curvature sum is > 100 mm
  wide there).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from exudyn_turnout.wheel_rail import node_laws, nonhertz
from exudyn_turnout.wheel_rail.hertz import (
    MIN_CURVATURE_SUM,
    effective_modulus,
    hertz_constant,
    hertz_contact,
)

MODULUS = effective_modulus()  # steel, E = 210 GPa, nu = 0.3
STEP = 2e-5  # m
T = np.arange(-1500, 1501) * STEP  # +-30 mm
#: 1/m, cos(84 deg) / (2 r), r = 0.46 m: flange back against a check-rail face (issue 22)
A_FACE = math.cos(math.radians(84.0)) / (2 * 0.46)
FACE = np.where(np.abs(T) < 0.0125, 0.0, (np.abs(T) - 0.0125) ** 2 / 0.01)


@pytest.mark.parametrize(("length", "t"), [(1e-3, 1e-4), (5e-3, 2e-3), (1e-3, 4e-3)])
def test_strip_integral_matches_its_definition(length, t):
    def integrand(x):
        return math.sqrt(length**2 - x * x) / math.sqrt(x * x + t * t)

    expected = quad(integrand, -length, length, points=[0.0], limit=200)[0]
    assert float(nonhertz.strip_integral(length, t)) == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize("b_sum", [0.3, 1.087, 5.0, 30.0])
@pytest.mark.parametrize("delta", [2e-5, 2e-4])
def test_kp_on_a_hertz_gap_is_close_to_hertz(b_sum, delta):
    a_sum = 1.087  # 1/m, wheel of 0.46 m on a straight rail
    patch = nonhertz.kik_piotrowski(b_sum * T**2, STEP, a_sum, delta, MODULUS)
    force = float(hertz_constant(a_sum, b_sum, MODULUS)) * delta**1.5
    assert patch.normal_force[0] == pytest.approx(force, rel=0.06)
    assert patch.normal_force[0] > force  # KP lies above Hertz over this range (measured)


def test_kp_patch_on_a_flat_face_stays_on_the_face():
    for delta in (2e-5, 6.3e-5, 2e-4):
        patch = nonhertz.kik_piotrowski(FACE, STEP, A_FACE, delta, MODULUS)
        # face 25 mm; its 5 mm corner radii add sqrt(2 R epsilon delta) per side
        edge = 0.0125 + math.sqrt(0.01 * nonhertz.EPSILON * delta)
        assert -edge - STEP < patch.t_low[0] < -0.0125
        assert 0.0125 < patch.t_high[0] < edge + STEP
        # equivalent ellipse (same area, same length/width): at most 2/sqrt(pi) times the
        # half-width, the ratio of a rectangle
        assert patch.b[0] < 2.0 / math.sqrt(math.pi) * edge
        hertz = hertz_contact(
            A_FACE, MIN_CURVATURE_SUM, patch.normal_force[0], MODULUS
        )  # what the tables gave before
        assert hertz.b > 0.1  # > 100 mm on a 25 mm face
        assert patch.p_max[0] > 0.0


def test_flat_face_is_softer_than_its_floored_hertz():
    law = nonhertz.patch_law(FACE[None, ::5], 5 * STEP, A_FACE, 0.0, MODULUS)[0]
    assert law[6] == 1.0  # semi-Hertzian
    hertz = float(hertz_constant(A_FACE, MIN_CURVATURE_SUM, MODULUS)) * node_laws.DELTA_REF**1.5
    assert law[0] < 0.3 * hertz  # measured 0.18


def test_power_law_between_and_beyond_its_two_points():
    """The per-node power law against KP itself over 0.01-0.4 mm (flat face): measured
    within 3.7 %; tolerance 5 %."""
    gap, step = FACE[None, ::5], 5 * STEP
    law = nonhertz.patch_law(gap, step, A_FACE, 0.0, MODULUS)[0]
    for delta in (1e-5, 4e-5, node_laws.DELTA_REF, 1e-4, 4e-4):
        exact = nonhertz.kik_piotrowski(gap, step, A_FACE, delta, MODULUS)
        ratio = delta / node_laws.DELTA_REF
        assert law[0] * ratio ** law[1] == pytest.approx(exact.normal_force[0], rel=0.05)
        assert law[4] * ratio ** law[5] == pytest.approx(exact.b[0], rel=0.05)


def test_hertz_law_where_hertz_fits_is_exactly_hertz():
    a_sum, b_sum = 1.087, 1 / 0.6
    law = nonhertz.patch_law((b_sum * T**2)[None], STEP, a_sum, b_sum, MODULUS)[0]
    constant = float(hertz_constant(a_sum, b_sum, MODULUS))
    assert law[6] == 0.0
    assert law[1] == 1.5 and law[3] == 0.5 and law[5] == 0.5
    assert law[0] == pytest.approx(constant * node_laws.DELTA_REF**1.5, rel=1e-12)
    ellipse = hertz_contact(a_sum, b_sum, law[0], MODULUS)
    assert (law[2], law[4]) == pytest.approx((float(ellipse.a), float(ellipse.b)), rel=1e-12)


def test_hertz_does_not_fit_a_narrow_face_or_floored_curvature():
    a_sum, b_sum = 1.087, 1 / 0.6
    parabola = b_sum * T**2
    narrow = np.where(np.abs(T) < 2e-3, parabola, 1.0)  # surfaces end 2 mm either side
    fits = nonhertz.hertz_fits(np.stack((parabola, narrow)), STEP, a_sum, b_sum, MODULUS)
    assert fits.tolist() == [True, False]
    assert not nonhertz.hertz_fits(parabola[None], STEP, a_sum, 1e-4, MODULUS)[0]


def test_separate_patch_is_not_counted():
    """Only the run of interpenetration around the contact point belongs to its patch."""
    a_sum, b_sum = 1.087, 5.0
    single = b_sum * T**2
    double = np.minimum(single, b_sum * (T - 0.01) ** 2 + 1e-6)  # a second minimum 10 mm away
    both = nonhertz.kik_piotrowski(np.stack((single, double)), STEP, a_sum, 2e-5, MODULUS)
    assert both.normal_force[1] == pytest.approx(both.normal_force[0], rel=1e-9)
    assert both.t_high[1] < 0.005
