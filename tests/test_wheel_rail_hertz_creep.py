"""Hertz constant and ellipse; Kalker coefficients; Polach's creep forces."""

import math

import numpy as np
import pytest

from exudyn_turnout.wheel_rail.creep import kalker_coefficients, polach_creep_forces
from exudyn_turnout.wheel_rail.hertz import (
    curvature_sums,
    effective_modulus,
    ellipse_parameter,
    hertz_constant,
    hertz_contact,
)

STEEL = effective_modulus(2.1e11, 0.3)  # E* = E / (2 (1 - nu^2)) = 115.4 GPa


def test_sphere_on_plane_is_hertz_exactly():
    # Hertz: F = (4/3) E* sqrt(R) delta^1.5, a = sqrt(R delta) (Johnson 1985, Eq. 4.22-4.23)
    radius = 0.02
    curvature = 1.0 / (2.0 * radius)
    assert hertz_constant(curvature, curvature, STEEL) == pytest.approx(
        4.0 / 3.0 * STEEL * math.sqrt(radius), rel=1e-8
    )
    delta = 1e-5
    force = 4.0 / 3.0 * STEEL * math.sqrt(radius) * delta**1.5
    contact = hertz_contact(curvature, curvature, force, STEEL)
    assert contact.a == pytest.approx(math.sqrt(radius * delta), rel=1e-6)
    assert contact.b == pytest.approx(contact.a, rel=1e-6)


def test_wheel_046_on_uic60_crown():
    """About 9e10 N/m^1.5 (the value the packaged vehicle file uses for a 0.46 m wheel on a
    UIC60 crown; it is not a measured number, so the band is +-10 %)."""
    a_sum, b_sum = curvature_sums(0.46, 0.0, 0.0, 1.0 / 0.3)
    constant = float(hertz_constant(a_sum, b_sum, STEEL))
    assert 8.1e10 < constant < 9.9e10
    # the same with the wheel and rail swapped in the ellipse is symmetric
    assert float(hertz_constant(b_sum, a_sum, STEEL)) == pytest.approx(constant, rel=1e-10)


def test_ellipse_shape_against_greenwood_approximation():
    """Greenwood (1997): b/a ~ (A/B)^(2/3) within a few per cent for moderate ratios."""
    for ratio in (1.5, 3.0, 10.0):
        m = float(ellipse_parameter(ratio))
        assert math.sqrt(1.0 - m) == pytest.approx(ratio ** (-2.0 / 3.0), rel=0.04)


def test_kalker_table_values_and_asymptotes():
    # Kalker (1990) Table E3, circular contact, nu = 0.25: 4.12, 3.67, 1.47, 1.17 (the first
    # three as in CONTACT's copy, see PUBLISHED_E3; C33 = 1.17 not checked against print)
    c = kalker_coefficients(1.0, 1.0, 0.25)
    assert (float(c.c11), float(c.c22), float(c.c23), float(c.c33)) == (4.12, 3.67, 1.47, 1.17)
    # Kalker (1967): for a/b -> 0, C11 -> pi^2 / (4 (1 - nu)), C22 -> pi^2 / 4
    for nu in (0.0, 0.25, 0.5):
        narrow = kalker_coefficients(0.1, 1.0, nu)
        assert float(narrow.c11) == pytest.approx(math.pi**2 / (4 * (1 - nu)), rel=0.03)
        assert float(narrow.c22) == pytest.approx(math.pi**2 / 4, rel=0.03)
    # Kalker (1967) asymptotes for g = a/b -> 0: C23 = pi sqrt(g) / 3 at nu = 0,
    # C33 = pi^2 / (16 (1 - nu) g)
    assert float(kalker_coefficients(0.1, 1.0, 0.0).c23) == pytest.approx(
        math.pi * math.sqrt(0.1) / 3.0, rel=0.03
    )
    assert float(kalker_coefficients(0.1, 1.0, 0.25).c33) == pytest.approx(
        math.pi**2 / (16 * 0.75 * 0.1), rel=0.03
    )
    # for nu = 0 longitudinal and lateral coefficients are equal (Kalker's table columns)
    ratios = np.array([0.2, 0.7, 1.0, 1.6, 5.0])
    at_zero = kalker_coefficients(ratios, 1.0, 0.0)
    np.testing.assert_allclose(at_zero.c11, at_zero.c22)
    # monotone in the ellipse ratio (a/b up: longitudinal stiffer)
    assert np.all(np.diff(kalker_coefficients(ratios, 1.0, 0.28).c11) > 0)


# Kalker (1990) Table E3 as copied in CONTACT (E.A.H. Vollebregt, Apache-2.0):
# https://github.com/eve70a/CONTACT/blob/master/src/m_hertz.f90, subroutine linrol
# (commit e60b3acc667dea5e9f85e320a3e98d3649106bef, "Table E.3 of [4]", [4] = Kalker 1990).
# (a/b, nu, coefficient, published value); b/a rows written as a/b = 1 / (b/a).
PUBLISHED_E3 = (
    (0.3, 0.5, "c11", 4.80),
    (0.8, 0.25, "c23", 1.25),  # CONTACT's usetab_table.f90 has a typo here (1.15)
    (0.5, 0.25, "c22", 3.01),
    (1.0, 0.0, "c23", 1.33),
    (1.0 / 0.7, 0.0, "c11", 3.82),
    (1.0 / 0.4, 0.5, "c22", 6.31),
    (1.0 / 0.2, 0.25, "c11", 7.78),
    (1.0 / 0.1, 0.5, "c23", 18.0),
)


@pytest.mark.parametrize("ratio, nu, name, published", PUBLISHED_E3)
def test_kalker_table_matches_the_published_table(ratio, nu, name, published):
    # on the table's nodes the interpolation must return the published number itself
    value = float(getattr(kalker_coefficients(ratio, 1.0, nu), name))
    assert value == pytest.approx(published, rel=1e-9)


def test_polach_small_creepage_is_kalker_linear_and_large_is_coulomb():
    a, b, load, mu, shear = 6e-3, 5e-3, 1e5, 0.3, 8.1e10
    coeff = kalker_coefficients(a, b, 0.28)
    small = polach_creep_forces(1e-6, 0.0, 0.0, a, b, load, mu, shear)
    assert float(small.longitudinal) == pytest.approx(-shear * a * b * coeff.c11 * 1e-6, rel=1e-4)
    lateral = polach_creep_forces(0.0, 1e-6, 0.0, a, b, load, mu, shear)
    assert float(lateral.lateral) == pytest.approx(-shear * a * b * coeff.c22 * 1e-6, rel=1e-4)
    spin = polach_creep_forces(0.0, 0.0, 1e-4, a, b, load, mu, shear)
    assert float(spin.lateral) == pytest.approx(
        -shear * (a * b) ** 1.5 * coeff.c23 * 1e-4, rel=1e-3
    )
    big = polach_creep_forces(0.3, 0.0, 0.0, a, b, load, mu, shear)
    assert -float(big.longitudinal) == pytest.approx(mu * load, rel=0.01)
    combined = polach_creep_forces(0.05, 0.05, 0.0, a, b, load, mu, shear)
    assert math.hypot(float(combined.longitudinal), float(combined.lateral)) <= mu * load
    unloaded = polach_creep_forces(0.01, 0.01, 0.1, a, b, 0.0, mu, shear)
    assert float(unloaded.longitudinal) == 0.0 and float(unloaded.lateral) == 0.0
