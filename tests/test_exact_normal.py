"""Exact half-space normal contact on a grid, wheel_rail/exact_normal.py.

References: Hertz's closed forms (Johnson, *Contact mechanics*, CUP 1985, eqs 4.39-4.44,
as :mod:`exudyn_turnout.wheel_rail.hertz` evaluates them with complete elliptic
integrals) for a circle (A = B) and an ellipse of a / b = 3 (B / A found here).  Grid
errors measured before the tolerances were set (20 / 40 / 80 elements across each axis):
approach -0.023 / -0.007 / -0.002 % (circle), -0.017 / -0.006 / -0.002 % (ellipse); peak
pressure +0.06 / +0.01 / +0.003 %; contact extent one element more than 2a, 2b (element
centres inside the ellipse; the error is one element, shrinking as 1 / n); area
+3.5 / +1.3 / +0.6 %.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from exudyn_turnout.wheel_rail import exact_normal
from exudyn_turnout.wheel_rail.hertz import effective_modulus, hertz_constant, hertz_contact
from exudyn_turnout.wheel_rail.nonhertz import kik_piotrowski

MODULUS = effective_modulus()  # steel, 210 GPa, 0.3
FORCE = 1e4  # N
A_SUM = 1.087  # 1/m, a 0.46 m wheel on a straight rail


def _b_for_ratio(ratio: float) -> float:
    """Lateral curvature B giving Hertz semi-axes a / b = ratio with A = A_SUM."""

    def excess(b_sum):
        ellipse = hertz_contact(A_SUM, b_sum, FORCE, MODULUS)
        return float(ellipse.a / ellipse.b) - ratio

    return brentq(excess, A_SUM * 1.0001, A_SUM * 100.0)


def _hertz_grid(b_sum: float, n: int):
    ellipse = hertz_contact(A_SUM, b_sum, FORCE, MODULUS)
    dx, dy = 2.0 * float(ellipse.a) / n, 2.0 * float(ellipse.b) / n
    size = int(1.4 * n) | 1
    x = (np.arange(size) - 0.5 * (size - 1)) * dx
    y = (np.arange(size) - 0.5 * (size - 1)) * dy
    gap = A_SUM * x[:, None] ** 2 + b_sum * y[None, :] ** 2
    return ellipse, gap, dx, dy


def _errors(b_sum: float, n: int) -> dict[str, float]:
    ellipse, gap, dx, dy = _hertz_grid(b_sum, n)
    solved = exact_normal.solve_normal(gap, dx, dy, MODULUS, force=FORCE)
    assert solved.converged
    delta = (FORCE / float(hertz_constant(A_SUM, b_sum, MODULUS))) ** (2.0 / 3.0)
    return {
        "approach": solved.approach / delta - 1.0,
        "p0": solved.p_max / float(ellipse.p0) - 1.0,
        "length": solved.length / (2.0 * float(ellipse.a)) - 1.0,
        "width": solved.width / (2.0 * float(ellipse.b)) - 1.0,
        "area": solved.area / (math.pi * float(ellipse.a * ellipse.b)) - 1.0,
        "force": solved.normal_force / FORCE - 1.0,
    }


@pytest.mark.parametrize("ratio", [1.0, 3.0])
def test_hertz_closed_forms_within_the_grid_error(ratio):
    b_sum = A_SUM if ratio == 1.0 else _b_for_ratio(ratio)
    coarse, fine = _errors(b_sum, 20), _errors(b_sum, 40)
    assert abs(coarse["force"]) < 1e-9  # the force constraint holds exactly
    # approach and peak pressure: 0.1 % at 20 elements across (measured 0.02, 0.07 %)
    assert abs(coarse["approach"]) < 1e-3 and abs(coarse["p0"]) < 1e-3
    # the extent counts whole elements: within one element (1 / 20) of 2a and 2b
    for key in ("length", "width"):
        assert abs(coarse[key]) <= 1.0 / 20 + 1e-9 and abs(fine[key]) <= 1.0 / 40 + 1e-9
    # every error shrinks when the grid is refined
    for key in ("approach", "p0", "area"):
        assert abs(fine[key]) < abs(coarse[key])
    # at 40 elements: the area within 2 % (measured 1.3 %)
    assert abs(fine["area"]) < 0.02


def test_prescribed_approach_gives_hertz_force():
    b_sum = _b_for_ratio(3.0)
    _ellipse, gap, dx, dy = _hertz_grid(b_sum, 40)
    delta = (FORCE / float(hertz_constant(A_SUM, b_sum, MODULUS))) ** (2.0 / 3.0)
    solved = exact_normal.solve_normal(gap, dx, dy, MODULUS, approach=delta)
    assert solved.converged
    assert solved.approach == delta
    assert solved.normal_force == pytest.approx(FORCE, rel=2e-4)  # measured 0.9e-4


def test_signorini_conditions_hold():
    b_sum = _b_for_ratio(3.0)
    _ellipse, gap, dx, dy = _hertz_grid(b_sum, 30)
    solved = exact_normal.solve_normal(gap, dx, dy, MODULUS, force=FORCE)
    coefficients = exact_normal.boussinesq_coefficients(dx, dy, *gap.shape, MODULUS)
    nx, ny = gap.shape
    u = np.zeros(gap.shape)
    for i, j in zip(*np.nonzero(solved.pressure), strict=True):  # direct sum, no FFT
        u += solved.pressure[i, j] * coefficients[nx - 1 - i : 2 * nx - 1 - i,
                                                  ny - 1 - j : 2 * ny - 1 - j]  # fmt: skip
    deformed = gap + u - solved.approach
    contact = solved.pressure > 0.0
    assert np.all(solved.pressure >= 0.0)
    assert np.max(np.abs(deformed[contact])) < 1e-6 * solved.approach
    assert np.min(deformed[~contact]) > -1e-6 * solved.approach
    assert solved.x_centre == pytest.approx(0.0, abs=1e-9)  # symmetric gap
    assert solved.y_centre == pytest.approx(0.0, abs=1e-9)


def test_boussinesq_coefficient_of_a_square_element():
    # centre of a uniformly loaded square of side c: 1/(pi E*) * 4 c asinh(1) (Johnson
    # 1985, eq. 3.25 at the centre; both bodies together)
    side = 1e-4
    value = exact_normal.boussinesq_coefficients(side, side, 1, 1, MODULUS)[0, 0]
    assert value == pytest.approx(4.0 * side * math.asinh(1.0) / (math.pi * MODULUS), rel=1e-12)


def test_lateral_gap_grows_its_grid_and_matches_hertz():
    b_sum = _b_for_ratio(3.0)
    step = 2e-5
    t = np.arange(-1000, 1001) * step
    ellipse = hertz_contact(A_SUM, b_sum, FORCE, MODULUS)
    delta = (FORCE / float(hertz_constant(A_SUM, b_sum, MODULUS))) ** (2.0 / 3.0)
    # first guess far too small: the grid must grow until it holds the patch
    solved = exact_normal.solve_on_lateral_gap(
        b_sum * t**2, step, A_SUM, FORCE, MODULUS, float(ellipse.a) / 15,
        float(ellipse.b) / 15, level=1e-6,
    )  # fmt: skip
    assert solved.approach == pytest.approx(delta, rel=2e-3)
    assert solved.y_centre == pytest.approx(0.0, abs=step)


def test_kp_against_the_exact_solution_on_a_hertz_gap():
    # Kik-Piotrowski on a Hertz gap is not exact (tests/test_wheel_rail_nonhertz.py: force
    # 0.7-4.9 % above Hertz): the exact solver must see the same deviation
    b_sum = _b_for_ratio(3.0)
    step = 2e-5
    t = np.arange(-1000, 1001) * step
    delta = 2e-5
    kp = kik_piotrowski(b_sum * t**2, step, A_SUM, delta, MODULUS)
    ellipse = hertz_contact(A_SUM, b_sum, FORCE, MODULUS)
    solved = exact_normal.solve_on_lateral_gap(
        b_sum * t**2, step, A_SUM, float(kp.normal_force[0]), MODULUS,
        float(ellipse.a) / 20, float(ellipse.b) / 20,
    )  # fmt: skip
    assert 0.0 < 1.0 - delta / solved.approach < 0.05


@pytest.mark.parametrize(
    "kwargs", [{}, {"force": 1.0, "approach": 1e-5}, {"force": -1.0}, {"force": 0.0}]
)
def test_bad_input_is_named(kwargs):
    with pytest.raises(ValueError, match="solve_normal"):
        exact_normal.solve_normal(np.zeros((3, 3)), 1e-4, 1e-4, MODULUS, **kwargs)


def test_non_finite_gap_is_named():
    with pytest.raises(ValueError, match="finite"):
        exact_normal.solve_normal(np.full((3, 3), np.nan), 1e-4, 1e-4, MODULUS, force=1.0)
