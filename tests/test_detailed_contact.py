"""Our detailed contact (exact normal on our 3-D surfaces, then Kalker's exact steady
rolling on that pressure) against closed forms and CONTACT's reference outputs.

References:

* Hertz (K.L. Johnson, *Contact mechanics*, CUP 1985, eq. 4.22 for a circle):
  ``a = (3 N R / (4 E*))^(1/3)`` for the gap ``(x^2 + y^2) / (2 R)``.
* Kalker's linear theory: C11 = 4.12, C22 = 3.67 for a circle at nu = 0.25 (J.J. Kalker,
  *Three-dimensional elastic bodies in rolling contact*, Kluwer 1990, Table E3).
* Coulomb's law: in full slip every element carries mu p against its slip, so a pure
  longitudinal creepage far beyond saturation gives ``F_x = -mu N``.
* CONTACT's reference outputs (E.A.H. Vollebregt, github eve70a/CONTACT at d431cdb,
  Apache-2.0, packaged in exudyn_turnout/data/wheel_rail): FX, FS and NCON of each case.
  Measured before the bounds were set (validation/detailed_vs_contact.md): FX +1.0,
  -0.0, +1.0, +0.4, +4.3 %, FS +6.2, -0.0, -2.3, +6.3, +5.2 %; elements in contact
  630 / 624, 724 / 723, 1281 / 1283, 469 / 467, 1009 / 991.  Bound: issue 22's 10 %
  for the creep forces; the element count within 3 % (measured at most 1.8 %).
"""

import dataclasses
import math

import numpy as np
import pytest

from exudyn_turnout.wheel_rail.data import data_dir, s1002_wheel
from exudyn_turnout.wheel_rail.detailed_contact import detailed_contact, rolling_on_normal
from exudyn_turnout.wheel_rail.exact_normal import solve_normal
from exudyn_turnout.wheel_rail.hertz import effective_modulus
from exudyn_turnout.wheel_rail.reference_normal import case_geometry
from exudyn_turnout.wheel_rail.references import REFERENCE_FILES, read_reference_output

FOLDER = data_dir()
PROFILES = FOLDER / "profiles"
G = 8.2e10  # Pa, CONTACT's steel
N = 1.0e4  # N


def _hertz_circle(nu: float, elements: int = 40):
    """The exact normal solution on a Hertz circle's gap, about `elements` across."""
    modulus = effective_modulus(2.0 * G * (1.0 + nu), nu)
    radius = 0.3  # m, relative radius of curvature
    a = (3.0 * N * radius / (4.0 * modulus)) ** (1.0 / 3.0)
    h = 2.0 * a / elements
    x = (np.arange(elements + 9) - 0.5 * (elements + 8)) * h
    gap = (x[:, None] ** 2 + x[None, :] ** 2) / (2.0 * radius)
    return solve_normal(gap, h, h, modulus, force=N), a


def test_linear_creep_on_a_hertz_circle_is_kalkers():
    nu = 0.25
    normal, a = _hertz_circle(nu)
    assert normal.length == pytest.approx(2.0 * a, abs=2.0 * normal.dx)
    fx = rolling_on_normal(normal, 1e-6, 0.0, 0.0, 1e3, G, nu).fx
    fy = rolling_on_normal(normal, 0.0, 1e-6, 0.0, 1e3, G, nu).fy
    # the grid's contact area against Hertz's: c^2 = area / pi
    c2 = normal.area / math.pi
    assert -fx / (G * c2 * 1e-6) == pytest.approx(4.12, rel=0.03)
    assert -fy / (G * c2 * 1e-6) == pytest.approx(3.67, rel=0.03)


def test_full_slip_gives_coulombs_force():
    normal, _a = _hertz_circle(0.28, elements=20)
    solved = rolling_on_normal(normal, 0.05, 0.0, 0.0, 0.3, G, 0.28)
    assert solved.converged
    assert solved.slip[solved.contact].all()
    assert solved.fx == pytest.approx(-0.3 * N, rel=1e-3)
    assert abs(solved.fy) < 1e-3 * N


def test_no_pressure_is_named():
    normal, _a = _hertz_circle(0.28, elements=10)
    empty = dataclasses.replace(normal, pressure=np.zeros_like(normal.pressure))
    with pytest.raises(ValueError, match="carries no pressure"):
        rolling_on_normal(empty, 1e-3, 0.0, 0.0, 0.3, G, 0.28)


def _cases():
    return [
        (name, case)
        for name in REFERENCE_FILES
        for case in read_reference_output(FOLDER / "reference_outputs" / f"{name}.ref_out")
    ]


def _check(case) -> None:
    patch = case.patches[0]
    geometry = case_geometry(case, s1002_wheel(), PROFILES)
    found = detailed_contact(case, geometry, PROFILES, case.dx, case.ds)
    assert found.rolling.converged
    assert found.fx == pytest.approx(patch.fx, rel=0.10)
    assert found.fs == pytest.approx(patch.fs, rel=0.10)
    assert int(found.rolling.contact.sum()) == pytest.approx(patch.n_elements, rel=0.03)


def test_wing_rail_creep_forces_against_contact():
    name, case = _cases()[0]
    assert name == "wing_brute"
    _check(case)


@pytest.mark.slow
@pytest.mark.parametrize("index", range(1, 5))
def test_other_creep_forces_against_contact(index):
    _check(_cases()[index][1])
