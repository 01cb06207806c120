"""Polach's creep forces with spin: Coulomb's bound, Kalker's linear limit, full slip.

Coulomb's law holds at every point of the contact patch, |tau| <= mu p, so the resultant
creep force can never exceed mu Q (Kalker's exact theory and FASTSIM never do).  Polach's
method (O. Polach, VSD 33 Suppl. (1999) 728-739) keeps it when the translational force is
saturated with, and divided by, the resultant creepage s_C that includes spin; adding the
spin force to a force saturated with the creepage without spin gave up to 1.47 mu Q on the
grid below (issue 22).  The tests check the closed form itself (``bound_resultant=False``)
as well as the guarded function and the compiled kernel.

Small-creepage references: Kalker's linear theory, ``F_x = -G a b C11 xi``,
``F_y = -G a b (C22 eta + sqrt(a b) C23 phi)``, with the coefficients of a circular patch at
nu = 0.25 from J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*, Kluwer
1990, Table E3 (C11 = 4.12, C22 = 3.67, C23 = 1.47; the same digits as CONTACT's copy,
``src/m_hertz.f90``, subroutine ``linrol``).  Those numbers are written here, not taken
from the package's table.
"""

import math

import numpy as np
import pytest

from exudyn_turnout.wheel_rail import kernel, packed_tables
from exudyn_turnout.wheel_rail.creep import kalker_coefficients, polach_creep_forces

G = 8.1e10  # Pa, steel
MU = 0.4
ROUND_OFF = 1e-9  # relative


def _grid():
    creep = np.r_[-np.logspace(-5, -1, 9), 0.0, np.logspace(-5, -1, 9)]
    spin = np.r_[-np.logspace(-2, 1, 7), 0.0, np.logspace(-2, 1, 7)]
    a = np.array([2e-3, 4e-3, 5.5e-3, 7e-3, 10e-3])
    b = np.array([1.5e-3, 2.5e-3, 5e-3, 8e-3, 15e-3])
    load = np.array([1e4, 6e4, 1.6e5])
    return np.meshgrid(creep, creep, spin, a, b, load, indexing="ij")


def _random(n, seed):
    rng = np.random.default_rng(seed)

    def log_uniform(lo, hi):
        return 10.0 ** rng.uniform(math.log10(lo), math.log10(hi), n)

    def signed(lo, hi, zero_fraction):
        return rng.choice([-1.0, 1.0], n) * log_uniform(lo, hi) * (rng.random(n) > zero_fraction)

    return (
        signed(1e-6, 0.3, 0.2),  # xi
        signed(1e-6, 0.3, 0.2),  # eta
        signed(1e-3, 30.0, 0.1),  # spin, 1/m
        log_uniform(5e-4, 2e-2),  # a, m
        log_uniform(5e-4, 2e-1),  # b, m (flat flange faces give long, narrow patches)
        log_uniform(1e2, 3e5),  # Q, N
    )


def _ratio(forces, load):
    return np.hypot(forces.longitudinal, forces.lateral) / (MU * load)


@pytest.mark.parametrize("bounded", [False, True])
def test_resultant_never_exceeds_mu_q_on_a_grid(bounded):
    xi, eta, spin, a, b, load = _grid()
    ratio = _ratio(
        polach_creep_forces(xi, eta, spin, a, b, load, MU, G, bound_resultant=bounded), load
    )
    assert np.all(np.isfinite(ratio))
    assert ratio.max() <= 1.0 + ROUND_OFF
    # the grid reaches full slip: the bound is approached, not trivially far
    assert ratio.max() > 0.999


@pytest.mark.parametrize("seed", [1, 2])
def test_resultant_never_exceeds_mu_q_for_random_inputs(seed):
    xi, eta, spin, a, b, load = _random(200_000, seed)
    ratio = _ratio(
        polach_creep_forces(xi, eta, spin, a, b, load, MU, G, bound_resultant=False), load
    )
    assert np.all(np.isfinite(ratio))
    assert ratio.max() <= 1.0 + ROUND_OFF


def test_issue_case_flange_root_spin():
    """Issue 22: phi = -1.02 1/m, a x b = 4-7 x 2.5-8 mm gave 1.01-1.29 mu N."""
    creep = np.r_[-np.logspace(-5, -1, 13), 0.0, np.logspace(-5, -1, 13)]
    xi, eta, a, b = np.meshgrid(
        creep, creep, np.linspace(4e-3, 7e-3, 7), np.linspace(2.5e-3, 8e-3, 7), indexing="ij"
    )
    load = 57.2e3
    forces = polach_creep_forces(xi, eta, -1.02, a, b, load, MU, G, bound_resultant=False)
    assert _ratio(forces, load).max() <= 1.0 + ROUND_OFF


def test_compiled_kernel_keeps_the_bound_and_equals_numpy():
    xi, eta, spin, a, b, load = _random(20_000, 3)
    coefficients = kalker_coefficients(a, b, 0.28)
    reference = polach_creep_forces(xi, eta, spin, a, b, load, MU, G, 0.28)
    for i in range(xi.size):
        fx, fy = kernel.polach_scalar(
            xi[i], eta[i], spin[i], a[i], b[i], load[i], MU, G,
            coefficients.c11[i], coefficients.c22[i], coefficients.c23[i],
        )  # fmt: skip
        assert math.hypot(fx, fy) <= MU * load[i] * (1.0 + ROUND_OFF)
        # round-off: K_M is a difference of nearly equal terms at large eps_M
        tolerance = 1e-9 * MU * load[i]
        assert fx == pytest.approx(reference.longitudinal[i], rel=1e-10, abs=tolerance)
        assert fy == pytest.approx(reference.lateral[i], rel=1e-10, abs=tolerance)


# Kalker (1990) Table E3, a/b = 1, nu = 0.25 (module docstring)
C11, C22, C23 = 4.12, 3.67, 1.47
A = B = 5e-3
LOAD = 8e4  # N; with these creepages eps < 1e-3: linear within 1e-6


def _polach(xi, eta, spin):
    forces = polach_creep_forces(xi, eta, spin, A, B, LOAD, MU, G, poisson=0.25)
    return float(forces.longitudinal), float(forces.lateral)


@pytest.mark.parametrize(
    "xi, eta, spin",
    [
        (1e-7, 0.0, 0.0),
        (0.0, -1e-7, 0.0),
        (0.0, 0.0, 2e-5),
        (0.0, 1e-7, 2e-5),  # eta and phi a of the same sign
        (0.0, 1e-7, -2e-5),  # phi a = -eta: s_yC = eta
        (0.0, 1e-7, -1e-4),  # phi a = -5 eta: s_yC = eta + phi a
    ],
)
def test_small_creepage_is_kalkers_linear_theory(xi, eta, spin):
    fx, fy = _polach(xi, eta, spin)
    kalker_x = -G * A * B * C11 * xi
    kalker_y = -G * A * B * (C22 * eta + math.sqrt(A * B) * C23 * spin)
    assert fx == pytest.approx(kalker_x, rel=1e-5, abs=1e-9)
    assert fy == pytest.approx(kalker_y, rel=1e-5, abs=1e-9)


def test_small_combined_creepage_has_kalkers_magnitude():
    xi, eta = 1e-7, -2e-7
    fx, fy = _polach(xi, eta, 0.0)
    kalker = G * A * B * math.hypot(C11 * xi, C22 * eta)
    assert math.hypot(fx, fy) == pytest.approx(kalker, rel=1e-5)
    # Polach's direction is that of the creepage (Kalker's: of (C11 xi, C22 eta))
    assert fy / fx == pytest.approx(eta / xi, rel=1e-12)


def test_full_slip_is_coulomb_with_and_without_spin():
    for spin in (0.0, 1.0, -3.0):
        fx, fy = _polach(0.2, 0.1, spin)
        assert math.hypot(fx, fy) == pytest.approx(MU * LOAD, rel=0.01)
        # the force opposes the creepage
        assert fx < 0.0 and fy < 0.0


def test_spin_uses_up_adhesion():
    """At the same longitudinal creepage, spin never increases the longitudinal force."""
    xi = np.logspace(-5, -1, 30)
    plain = polach_creep_forces(xi, 0.0, 0.0, A, B, LOAD, MU, G).longitudinal
    for spin in (0.5, 2.0, -2.0):
        spun = polach_creep_forces(xi, 0.0, spin, A, B, LOAD, MU, G).longitudinal
        assert np.all(np.abs(spun) <= np.abs(plain) * (1.0 + 1e-12))


@pytest.mark.parametrize("creep_law", ["fastsim", "polach"])
def test_every_contact_of_the_compiled_kernel_keeps_the_bound(tmp_path, creep_law):
    """Property test through the whole kernel (issue 22: 1.31 mu N at a flange root in a
    full-vehicle curving run): random wheelset states on plain track and on a crossing
    (two-point contact, rows blended from several table nodes), every contact row
    |(F_x, F_t)| <= mu N, with the kernel's creep law (the FASTSIM table) and Polach's."""
    from exudyn_turnout.wheel_rail.data import s1002_wheel, standard_track, uic60_rail
    from exudyn_turnout.wheel_rail.geometry import WheelsetSetup
    from exudyn_turnout.wheel_rail.sections import (
        CrossingDesign,
        SectionGrid,
        crossing_sections,
        lateral_grid,
    )
    from exudyn_turnout.wheel_rail.tables import build_contact_table

    setup = WheelsetSetup()
    wheel = s1002_wheel(setup)
    plain = build_contact_table(
        wheel, standard_track(setup, np.array([-10.0, 70.0])), setup.taping_line, cache_dir=tmp_path
    )
    grid = lateral_grid(setup.taping_line - 0.11, setup.taping_line + 0.09, setup.grid_step)
    x = np.linspace(-0.2, 0.6, 9)
    rails = crossing_sections(
        CrossingDesign(nose_tip=0.0), uic60_rail(setup), x, grid, gauge=setup.gauge
    )
    crossing = SectionGrid(x=x, y=grid, z=np.fmax(rails["wing"].z, rails["nose"].z), name="x")
    crossing_table = build_contact_table(wheel, crossing, setup.taping_line, cache_dir=tmp_path)
    packed = packed_tables.pack_tables(
        [plain, crossing_table], [1, -1], [(7, 8), (9, 10)], [(-10.0, 70.0), (-0.2, 0.6)],
        creep_law=creep_law,
    )  # fmt: skip
    rng = np.random.default_rng(11)
    n_q, columns = 11, kernel.DETAIL_FIELDS
    normal, fx, ft = (columns.index(c) for c in ("normal", "Fx", "Ft"))
    loaded = 0
    for _ in range(3000):
        q = np.zeros(n_q)
        q[0] = rng.uniform(-0.011, 0.011)  # lateral: tread to flange on either side
        q[1] = rng.uniform(-3e-4, 0.0)  # down: penetrations up to a heavy load's
        q[2], q[3] = rng.normal(0.0, 2e-3), rng.normal(0.0, 0.01)  # roll, yaw
        q_t = np.zeros(n_q)
        q_t[0], q_t[2], q_t[3], q_t[4] = rng.normal(0.0, [0.3, 0.05, 0.3, 3.0])
        speed, friction = rng.uniform(1.0, 40.0), rng.uniform(0.1, 0.6)
        curvature = rng.uniform(-1.0 / 150.0, 1.0 / 150.0)
        constants = np.array([speed, 0.46, friction, G, 0.0, curvature])
        forces = np.zeros(n_q)
        details = np.zeros((packed.n_bodies * packed.n_candidates, len(columns)))
        kernel.contact_forces(
            rng.uniform(-0.2, 0.6), q, q_t, np.zeros(4), packed.values, packed.blendable,
            packed.x, packed.layout, packed.bounds, constants, forces, details,
        )  # fmt: skip
        rows = details[details[:, normal] > 0.0]
        loaded += len(rows)
        resultant = np.hypot(rows[:, fx], rows[:, ft])
        assert np.all(resultant <= friction * rows[:, normal] * (1.0 + ROUND_OFF) + 1e-9)
    assert loaded > 3000  # most states load one or two contacts per wheel
