"""Kik-Piotrowski's method error against the exact half-space solution on one gap.

KP (``wheel_rail/nonhertz.py``, Piotrowski & Kik, VSD 46 (2008) 27-48) and the exact
solution (``wheel_rail/exact_normal.py``, checked against Hertz in
tests/test_exact_normal.py) solve the same undeformed gap ``g(t) + A x^2``; the difference
of their approaches at one force is KP's method error alone (validation/normal_vs_contact.md
gives it on CONTACT's cases: -5.8 ... -0.2 %).  Measured here before the bounds were set,
at 20 / 40 / 80 / 160 elements across the KP patch (the grid error of the exact solution):

- flat face 25 mm wide with 5 mm corner radii (the check-rail face of issue 22):
  +2.6 / +4.1 / +4.9 / +4.6 % (KP needs more approach than exact);
- a wedge (gap slopes 0.042 and 0.009 either side, the nose corner of CONTACT's
  cross+wing case in our geometry): -6.30 / -6.24 / -6.28 / -6.27 %;
- two radii (B = 2 and 20 1/m either side): -5.08 / -5.11 / -5.11 / -5.11 %.

The bounds hold the converged value +-1.5 % (grid error and margin): a change to either
method that moves the error by more than that is a change of its physics.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_turnout.wheel_rail.exact_normal import solve_on_lateral_gap
from exudyn_turnout.wheel_rail.hertz import effective_modulus
from exudyn_turnout.wheel_rail.nonhertz import kik_piotrowski

MODULUS = effective_modulus()  # steel, 210 GPa, 0.3
STEP = 2e-5  # m
T = np.arange(-1500, 1501) * STEP  # +-30 mm
DELTA = 2e-5  # m, KP's penetration
#: 1/m, cos(84 deg) / (2 r), r = 0.46 m: flange back against a check-rail face (issue 22)
A_FACE = math.cos(math.radians(84.0)) / (2 * 0.46)

CASES = {
    # name: (gap, A, elements across the KP patch, (lower, upper) bound of KP / exact - 1)
    "flat face": (
        np.where(np.abs(T) < 0.0125, 0.0, (np.abs(T) - 0.0125) ** 2 / 0.01),
        A_FACE,
        80,
        (0.032, 0.062),
    ),
    "wedge": (np.where(T < 0.0, -0.042 * T, 0.009 * T), 1.087, 20, (-0.078, -0.048)),
    "two radii": (np.where(T < 0.0, 2.0 * T**2, 20.0 * T**2), 1.087, 20, (-0.066, -0.036)),
}


@pytest.mark.parametrize("name", list(CASES))
def test_kp_method_error_against_the_exact_solution(name):
    gap, a_sum, elements, (lower, upper) = CASES[name]
    kp = kik_piotrowski(gap, STEP, a_sum, DELTA, MODULUS)
    dx = 2.0 * float(kp.half_length[0]) / elements
    ds = float(kp.t_high[0] - kp.t_low[0]) / elements
    exact = solve_on_lateral_gap(
        gap, STEP, a_sum, float(kp.normal_force[0]), MODULUS, dx, ds, level=DELTA
    )
    assert exact.converged
    assert lower < DELTA / exact.approach - 1.0 < upper
    # the exact contact on the face stays on the face: inside the interpenetration
    # region of its approach (surface displacements only open the gap), which reaches
    # sqrt(R delta) into the 5 mm corner radii; and it spans the face
    if name == "flat face":
        inside = exact.y[np.any(exact.pressure > 0.0, axis=0)]
        edge = 0.0125 + math.sqrt(0.01 * exact.approach) + 0.5 * ds
        assert -edge < inside.min() < -0.0125 + ds and 0.0125 - ds < inside.max() < edge
