"""Kalker's FASTSIM (wheel_rail/fastsim.py): linear limit, saturation, convergence, bound.

References:

- Kalker's linear theory, ``F_x = -G a b C11 xi``, ``F_y = -G a b (C22 eta + sqrt(a b) C23
  phi)``, coefficients of J.J. Kalker, *Three-dimensional elastic bodies in rolling
  contact*, Kluwer 1990, Table E3, for a circle at nu = 0.25: C11 = 4.12, C22 = 3.67,
  C23 = 1.47 (the same digits as CONTACT's copy, ``src/m_hertz.f90``, ``linrol``), written
  here, not taken from the package's table.  FASTSIM's flexibilities are made from these
  coefficients, so this limit is built in; it checks the discretisation (and the three
  flexibilities with all creepages at once).
- The saturation of a pure creepage: Vermeulen & Johnson's curve, ``F / (mu N) = 1 -
  (1 - k)^3`` for k < 1, ``k = G a b C11 |xi| / (3 mu N)`` (P.J. Vermeulen, K.L. Johnson,
  "Contact of nonspherical elastic bodies transmitting tangential forces", J. Appl. Mech.
  31 (1964) 338-340; in this normalisation as in Kalker 1982 and Polach 1999).  Not built
  in: FASTSIM on an ellipse follows it within 1.2 % of mu N (measured 0.0108 at k = 0.5);
  each strip of the ellipse saturates from its own trailing edge, so the curve is not
  reproduced exactly.
- Spin, not built in: the lateral force of pure spin saturates and then falls (in full
  slip the slip directions of a pure spin cancel across the patch), and a longitudinal
  creepage with spin gives a lateral force, the coupling Polach's method approximates.
"""

import math

import numpy as np
import pytest

from exudyn_turnout.wheel_rail.creep import kalker_coefficients, polach_creep_forces
from exudyn_turnout.wheel_rail.fastsim import (
    fastsim_ellipse,
    fastsim_solver,
    fastsim_strips,
    kalker_flexibilities,
)

G = 8.1e10  # Pa
MU = 0.3
LOAD = 1e4  # N
A, B = 6e-3, 4e-3  # m


def test_linear_limit_is_kalker_for_every_combination():
    a = b = 5e-3  # a circle: Kalker 1990 Table E3, nu = 0.25 (module docstring)
    c11, c22, c23 = 4.12, 3.67, 1.47
    xi, eta, phi = 1e-8, -2e-8, 3e-6
    forces = fastsim_ellipse(xi, eta, phi, a, b, LOAD, MU, G, poisson=0.25)
    assert float(forces.longitudinal) == pytest.approx(-G * a * b * c11 * xi, rel=1e-3)
    lateral = -G * a * b * (c22 * eta + math.sqrt(a * b) * c23 * phi)
    assert float(forces.lateral) == pytest.approx(lateral, rel=1e-3)


@pytest.mark.parametrize("k", [0.1, 0.3, 0.5, 0.8, 0.95, 1.5])
def test_pure_creepage_follows_vermeulen_johnson(k):
    c11 = float(kalker_coefficients(A, B).c11)
    xi = k * 3.0 * MU * LOAD / (G * A * B * c11)
    ratio = -float(fastsim_ellipse(xi, 0.0, 0.0, A, B, LOAD, MU, G).longitudinal) / (MU * LOAD)
    vermeulen_johnson = 1.0 - (1.0 - min(k, 1.0)) ** 3
    assert abs(ratio - vermeulen_johnson) <= 0.012  # measured at most 0.0108 (docstring)
    # Polach's law against the same curve (reported, measured): 0.289 / 0.692 / 0.866 /
    # 0.953 / 0.970 / 0.991 at these k; it rises faster, then saturates more slowly
    polach = -float(polach_creep_forces(xi, 0.0, 0.0, A, B, LOAD, MU, G).longitudinal)
    assert abs(polach / (MU * LOAD) - vermeulen_johnson) <= 0.04


@pytest.mark.parametrize(
    "state", [(1.5e-3, -1e-3, 0.8), (3e-4, 1e-4, 0.3), (0.0, 0.0, 2.0), (1e-3, 0.0, 0.0)]
)
def test_converged_in_the_number_of_elements(state):
    """Strips x elements 10 x 15 ... 160 x 240, partly saturated states with spin.

    Measured (lateral force of state 1 over mu N): -0.1008 / -0.0999 / -0.0994 / -0.0993
    / -0.0993; without the extrapolation the default grid was 0.014 mu N off for pure
    spin (first order)."""
    grid = [(10, 15), (20, 30), (40, 60), (80, 120), (160, 240)]
    values = np.array(
        [
            [float(v) for v in (f.longitudinal, f.lateral)]
            for f in (
                fastsim_ellipse(*state, A, B, LOAD, MU, G, n_strips=s, n_x=n) for s, n in grid
            )
        ]
    ) / (MU * LOAD)
    # the package's default (40 x 60) within 1e-3 mu N of the finest grid (measured <= 5e-4)
    assert np.abs(values[2] - values[-1]).max() < 1e-3
    assert np.abs(values[3] - values[-1]).max() < 4e-4


def test_resultant_never_exceeds_mu_n_for_random_inputs():
    rng = np.random.default_rng(3)
    n = 20_000

    def log_uniform(lo, hi):
        return 10.0 ** rng.uniform(math.log10(lo), math.log10(hi), n)

    def signed(lo, hi):
        return rng.choice([-1.0, 1.0], n) * log_uniform(lo, hi)

    a = log_uniform(5e-4, 2e-2)
    b = a / log_uniform(0.03, 30.0)
    load = log_uniform(1e2, 3e5)
    friction = rng.uniform(0.05, 0.8, n)
    forces = fastsim_ellipse(
        signed(1e-6, 0.3), signed(1e-6, 0.3), signed(1e-3, 30.0), a, b, load, friction, G,
        n_strips=12, n_x=16,
    )  # fmt: skip
    ratio = np.hypot(forces.longitudinal, forces.lateral) / (friction * load)
    assert np.all(np.isfinite(ratio))
    assert ratio.max() <= 1.0 + 1e-12
    assert ratio.max() > 0.999  # the bound is reached, not trivially far


def test_spin_lateral_force_rises_then_falls():
    """Pure spin: the lateral force peaks and tends to 0 in full slip (not built in)."""
    spins = np.array([1e-3, 0.1, 1.0, 3.0, 10.0, 100.0, 1e4])
    lateral = fastsim_ellipse(0.0, 0.0, spins, A, B, LOAD, MU, G).lateral / (MU * LOAD)
    assert np.all(lateral < 0.0)  # opposing the spin (Kalker's sign)
    peak = int(np.argmin(lateral))
    assert 0 < peak < len(spins) - 1
    assert abs(lateral[-1]) < 0.05 * abs(lateral[peak])


def test_longitudinal_creepage_with_spin_gives_a_lateral_force():
    """xi and phi together: a lateral force, and |F| still within mu N (not built in)."""
    forces = fastsim_ellipse(2e-3, 0.0, np.array([-2.0, 0.0, 2.0]), A, B, LOAD, MU, G)
    assert forces.lateral[1] == pytest.approx(0.0, abs=1e-9)
    assert forces.lateral[0] == pytest.approx(-forces.lateral[2], rel=1e-9)  # mirror
    assert forces.lateral[2] < -0.05 * MU * LOAD


def test_strips_of_an_ellipse_reproduce_the_ellipse():
    """The strip form, given an ellipse's strips with parabolic pressure (uniform strips
    in y, so a different quadrature), converges to the elliptic result."""
    n = 400
    y = B * ((np.arange(n) + 0.5) / n * 2.0 - 1.0)
    width = np.full(n, 2.0 * B / n)
    half = A * np.sqrt(1.0 - (y / B) ** 2)
    p0 = 2.0 * LOAD / (math.pi * A * B)
    load = p0 * (half / A) ** 2 * 4.0 * half / 3.0
    flex = tuple(float(f) for f in kalker_flexibilities(A, B, G))
    for state in [(1e-4, 0.0, 0.0), (1e-3, -5e-4, 0.5), (0.0, 0.0, 5.0)]:
        strips = fastsim_strips(*state, y, width, half, load, flex, MU, n_x=60)
        ellipse = fastsim_ellipse(*state, A, B, LOAD, MU, G)
        assert strips[0] == pytest.approx(float(ellipse.longitudinal), abs=5e-3 * MU * LOAD)
        assert strips[1] == pytest.approx(float(ellipse.lateral), abs=5e-3 * MU * LOAD)


def test_solver_signature_and_pressure_choice():
    fx, fy = fastsim_solver(A, B, 1e-3, 0.0, 0.0, LOAD, MU, G, 0.28)
    assert fx < 0.0 and fy == pytest.approx(0.0, abs=1e-9)
    with pytest.raises(ValueError, match="pressure"):
        fastsim_strips(0, 0, 0, [0.0], [1.0], [1.0], [1.0], (1.0, 1.0, 1.0), MU, pressure="x")
