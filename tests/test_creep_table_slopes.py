"""The creep table's slopes where a linearisation reads them (issue 22; wheel_rail/creep_table.py).

A linearised vehicle at free rolling (passage/hunting.py) reads the creep forces' slopes
at zero translational creepage with the contact's spin, by forward differences of
~1e-11.  References: direct FASTSIM (:func:`.fastsim.fastsim_ellipse`, 40 strips x 60
elements, converged: tests/test_wheel_rail_fastsim.py) and Kalker's linear theory
(coefficients :func:`.creep.kalker_coefficients`, Kalker 1990 Table E3).
"""

import math

import numpy as np
import pytest

from exudyn_turnout.wheel_rail import creep_table as ct
from exudyn_turnout.wheel_rail.creep import kalker_coefficients
from exudyn_turnout.wheel_rail.fastsim import fastsim_ellipse

G = 8.1e10  # Pa
#: The Manchester vehicle's tread contact on S1002 / UIC60 1:40 at the centred position
#: (passage/hunting.py, tests/test_wheel_rail_creep_table.py): a, b, N, mu, spin
TREAD = (4.6868e-3, 8.8868e-3, 54535.0, 0.4, 0.052453)


@pytest.fixture(scope="module")
def table():
    return ct.creep_table()


def _forces(law, a, b, load, mu):
    def call(xi, eta, phi):
        f = law(xi, eta, phi, a, b, load, mu)
        return np.array([float(f.longitudinal), float(f.lateral)])

    return call


def _slopes(call, phi, step, f11, f22, f23):
    """dFx/dxi / -f11, dFy/deta / -f22, dFy/dxi / f11, dFx/deta / f22, dFy/dphi / -f23 at
    (0, 0, phi), forward differences."""
    base = call(0.0, 0.0, phi)
    d_xi = (call(step, 0.0, phi) - base) / step
    d_eta = (call(0.0, step, phi) - base) / step
    d_phi = (call(0.0, 0.0, phi * (1.0 + 1e-5)) - base) / (phi * 1e-5)
    return np.array([-d_xi[0] / f11, -d_eta[1] / f22, d_xi[1] / f11, d_eta[0] / f22,
                     -d_phi[1] / f23])  # fmt: skip


def _coefficients(a, b):
    c = kalker_coefficients(a, b)
    return G * a * b * c.c11, G * a * b * c.c22, G * (a * b) ** 1.5 * c.c23


def test_slopes_at_the_hunting_linearisation_point_are_fastsims(table):
    """Measured: table 0.9127 / 0.9493 / 0 / 0 / 0.9877, direct FASTSIM 0.9136 / 0.9534 /
    0 / 0 / 0.9876 (within 0.5 %; linear in rho 0.9114 / 0.9492 / 0 / 0 / 0.9921).  Before
    the spin angle was measured in the normalised creepages at small size and interpolated
    with Catmull-Rom (creep-table-4): 0.81 / 0.82 (1.04 on the other wheel) / 0.22 / 0 /
    0.99 -- the secant over the first spin-angle cell, which raised the linear critical
    speed from ~315 to 342 km/h."""
    a, b, load, mu, phi = TREAD
    f = _coefficients(a, b)
    law_t = _forces(lambda *args: ct.table_creep_forces(table, *args, G), a, b, load, mu)
    law_d = _forces(lambda *args: fastsim_ellipse(*args, G, 0.28, 40, 60), a, b, load, mu)
    for sign in (1.0, -1.0):  # left and right wheel: spin of either sign, the same slopes
        direct = _slopes(law_d, sign * phi, 1e-8, *f)
        for step in (1e-11, 1e-7):  # Exudyn's creepage steps and a larger one
            ours = _slopes(law_t, sign * phi, step, *f)
            np.testing.assert_allclose(ours[[0, 1, 4]], direct[[0, 1, 4]], rtol=0.01)
            assert np.all(np.abs(ours[[2, 3]]) < 1e-3)  # no cross slope (symmetry)
        assert direct[0] < 0.95  # the spin's nonlinearity the table must keep: not Kalker's 1


@pytest.mark.parametrize("ratio", [0.2, 0.53, 1.0, 5.0, 20.0])
@pytest.mark.parametrize("spin_size", [0.002, 0.02, 0.2])
def test_slopes_at_pure_spin_over_patches_and_spins(table, ratio, spin_size):
    """Pure spin of normalised size phi' (module docstring of creep_table), sqrt(a b) =
    5 mm.  Measured |table - direct| (in units of Kalker's linear slope): up to 0.020 on
    a / b = 0.2, 0.0073 on 0.53, 0.0061 on 1, 0.027 on 5 (the lateral slope at phi' =
    0.2), 0.049 on 20 (the same); a / b = 0.05 (flange patches, not here): up to 0.063 (the
    spin slope at phi' = 0.2).  Linear in rho: 0.031, 0.006, 0.015, 0.032, 0.051, 0.058."""
    a, b, load, mu = 5e-3 * math.sqrt(ratio), 5e-3 / math.sqrt(ratio), 1e4, 0.3
    f = _coefficients(a, b)
    c = kalker_coefficients(a, b)
    phi = spin_size * 3.0 * mu * load / (G * (a * b) ** 1.5 * c.c23)
    law_t = _forces(lambda *args: ct.table_creep_forces(table, *args, G), a, b, load, mu)
    law_d = _forces(lambda *args: fastsim_ellipse(*args, G, 0.28, 40, 60), a, b, load, mu)
    error = np.abs(_slopes(law_t, phi, 1e-11, *f) - _slopes(law_d, phi, 1e-8, *f))
    assert error.max() < 0.06
    assert np.all(error[[2, 3]] < 1e-3)


@pytest.mark.parametrize("ratio", [0.05, 0.5, 1.0, 5.0, 20.0])
def test_kalker_coefficients_at_the_origin(table, ratio):
    """Slopes at zero creepage and zero spin are Kalker's C11, C22, C23 (measured within
    0.04 %: the first size node lies at rho ~ 1e-3, where FASTSIM is 0.04 % below linear)."""
    a, b, load, mu = 5e-3 * math.sqrt(ratio), 5e-3 / math.sqrt(ratio), 1e4, 0.3
    f11, f22, f23 = _coefficients(a, b)
    call = _forces(lambda *args: ct.table_creep_forces(table, *args, G), a, b, load, mu)
    step = 1e-9
    assert -call(step, 0.0, 0.0)[0] / step == pytest.approx(f11, rel=2e-3)
    assert -call(0.0, step, 0.0)[1] / step == pytest.approx(f22, rel=2e-3)
    assert -call(0.0, 0.0, 100 * step)[1] / (100 * step) == pytest.approx(f23, rel=2e-3)
    assert abs(call(step, 0.0, 0.0)[1]) < 1e-6 * f11 * step  # no cross term


def test_slope_is_continuous_in_the_spin_angle(table):
    """C1 in beta: dF/dxi along xi = 0.1 ... 25 micro-strain at the tread's spin crosses
    three spin-angle nodes (rho stays in one size cell).  Measured largest jump between
    neighbouring slopes (xi steps of 6e-8): 2e-4 f11 with Catmull-Rom; 0.034 f11 (dFx/dxi)
    and 0.10 f11 (dFy/dxi) when interpolated linearly (the packed header's flag)."""
    a, b, load, mu, phi = TREAD
    f11 = _coefficients(a, b)[0]
    linear = ct.CreepTable(**{**table.__dict__, "settings": ct.CreepTableSettings(
        cubic_beta=False)})  # fmt: skip
    jumps = []
    for t in (table, linear):
        xi = np.linspace(1e-7, 2.5e-5, 400)
        f = ct.table_creep_forces(t, xi, 0.0, phi, a, b, load, mu, G)
        g = ct.table_creep_forces(t, xi + 1e-10, 0.0, phi, a, b, load, mu, G)
        slopes = np.stack(((g.longitudinal - f.longitudinal), (g.lateral - f.lateral))) / 1e-10
        jumps.append(np.abs(np.diff(slopes, axis=1)).max() / f11)
    assert jumps[0] < 2e-3
    assert jumps[1] > 0.02  # the test can tell: linear interpolation has kinks here


def test_spin_length_limits():
    """At small creepage the spin angle is that of the normalised creepages (l = sqrt(a b)
    C23 / C11 along x, / C22 along y); with blend 0, the patch's (b along x, a along y)."""
    a, b = 3e-3, 6e-3
    c = kalker_coefficients(a, b)
    args = (a, b, c.c11, c.c22, c.c23)
    root = math.sqrt(a * b) * c.c23
    assert ct.spin_length(1.0, 0.0, *args, 0.0, 0.3) == pytest.approx(root / c.c11, rel=1e-12)
    assert ct.spin_length(0.0, 2.0, *args, 0.0, 0.3) == pytest.approx(root / c.c22, rel=1e-12)
    assert ct.spin_length(0.0, 0.0, *args, 0.0, 0.3) == pytest.approx(root / c.c11, rel=1e-12)
    assert ct.spin_length(1.0, 0.0, *args, 0.5, 0.0) == pytest.approx(b, rel=1e-12)
    assert ct.spin_length(0.0, 1.0, *args, 0.5, 0.0) == pytest.approx(a, rel=1e-12)
    # half way (w = 1/2 at rho = blend): the geometric mean of the two
    half = ct.spin_length(1.0, 0.0, *args, 0.3, 0.3)
    assert half == pytest.approx(math.sqrt(b * root / c.c11), rel=1e-12)


def test_slope_is_continuous_in_the_size(table):
    """C1 in rho: along a ray of creepages (xi, eta, phi) = s (1, 0.5, 200 1/m), s = 1e-5
    ... 3e-4, rho runs from 0.0022 to 0.066 across 7 size nodes.  Measured largest jump
    between neighbouring slopes: 0.0012 f11 with the cubic in rho, 0.050 f11 when
    interpolated linearly (the packed header's flag)."""
    a, b, load, mu = TREAD[:4]
    f11 = _coefficients(a, b)[0]
    linear = ct.CreepTable(**{**table.__dict__, "settings": ct.CreepTableSettings(
        cubic_size=False)})  # fmt: skip
    jumps = []
    for t in (table, linear):
        s = np.linspace(1e-5, 3e-4, 600)
        f = ct.table_creep_forces(t, s, 0.5 * s, 200.0 * s, a, b, load, mu, G)
        s2 = s + 1e-11
        g = ct.table_creep_forces(t, s2, 0.5 * s2, 200.0 * s2, a, b, load, mu, G)
        slopes = np.stack(((g.longitudinal - f.longitudinal), (g.lateral - f.lateral))) / 1e-11
        jumps.append(np.abs(np.diff(slopes, axis=1)).max() / f11)
    assert jumps[0] < 5e-3
    assert jumps[1] > 0.02
