"""The normal law of a contact whose gap along x is truncated (along_x.patch_along_x).

Reference: the exact half-space solution (wheel_rail/exact_normal.solve_normal, Kalker's
normal problem solved by Polonsky & Keer's conjugate gradients) on the gap
``h(x, y) = g(x) + (x - x0)^2 / (2 R_x) + B y^2`` of a cylinder-like wheel against a flat
face that flares 1:67 behind a kink at x = 0 (g = 0.0148 max(-x, 0), the packaged check
rail's flare times sin(81 deg); R_x = 2.93 m, r / cos(gamma) of its flange back; B = 70 /m
gives the flange back's a / b ~ 40, packed_tables.hertz_axes_per_root).  Both the kinked and the
plain parabola's gap are solved and their ratio compared with the model's.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_turnout.wheel_rail import along_x, kernel, packed_tables
from exudyn_turnout.wheel_rail.exact_normal import solve_normal
from exudyn_turnout.wheel_rail.hertz import effective_modulus

R_X = 2.93  #: m, r / cos(gamma) of the flange back at the kink (validation/check_rail_kink)
FLARE = 0.0148  #: the gap's slope behind the kink (1:67 times sin(81 deg))
B_SUM = 70.0  #: 1/m, lateral relative curvature (a / b ~ 40 with R_X)
MODULUS = effective_modulus(2.1e11, 0.3)
DX, DY = 0.5e-3, 0.04e-3  #: m, elements of the exact solution
X = np.arange(-0.06, 0.06 + 1e-9, DX)
Y = np.arange(-0.9e-3, 0.9e-3 + 1e-9, DY)


def _exact(gap_x: np.ndarray, delta: float) -> tuple[float, float]:
    """Exact normal force (N) and force centre along x (m) at approach delta."""
    h = gap_x[:, None] + B_SUM * Y[None, :] ** 2
    solved = solve_normal(h - h.min(), DX, DY, MODULUS, approach=delta)
    per_x = solved.pressure.sum(axis=1)
    return solved.normal_force, float(np.sum(per_x * X) / per_x.sum())


def _table(slope_behind: float) -> tuple[np.ndarray, np.ndarray]:
    """A packed slot's gaps along x (nodes 62.5 mm apart, the kink at 0) and its x nodes."""
    xs = np.arange(-0.5, 0.5 + 1e-9, 0.0625)
    values = np.zeros(xs.size * 25)
    values[0::25] = slope_behind * np.maximum(-xs, 0.0)
    return xs, values


def _model(xs, values, x_yaw, delta, quartic=0.0):
    """along_x.patch_along_x at the deepest point of the gap along x (Hertz's a, b)."""
    a_root, b_root = packed_tables.hertz_axes_per_root(
        np.array([0.5 / R_X]), np.array([B_SUM]), MODULUS
    )
    a, b = a_root[0] * math.sqrt(delta), b_root[0] * math.sqrt(delta)
    xi = np.linspace(-0.2, 0.2, 400001)
    total = np.interp(xi, xs, values[0::25]) + (xi - x_yaw) ** 2 / (2 * R_X) + quartic * xi**4
    deepest = float(xi[np.argmin(total)])
    k0 = int(np.searchsorted(xs, 0.0)) - 1
    level = a * a / (2.0 * R_X)
    return along_x.patch_along_x(
        values, xs, 25 * k0, k0, False, xs.size, 25, 0, 0.0, 0.0, x_yaw, R_X, quartic,
        deepest, delta, level, level / delta, 0.5 * math.exp(-0.5) * b, 0.5, FLARE, 0.118,
        np.empty(128 + 4 * along_x.PATCH_CELLS),
    )  # fmt: skip


@pytest.mark.parametrize("delta", [40e-6, 93.6e-6])
@pytest.mark.parametrize("where", [0.05, 0.2, 0.5])
def test_truncated_patch_force_against_the_exact_solution(delta, where):
    """The wheel's parabola's vertex behind the kink by ``where FLARE R_X``: the deepest
    point is the kink, the flare truncates the patch behind it.  Exact force ratios 0.31 ...
    0.60 (the node law's error was 1 / ratio); the model within 2 % of them (measured
    0.2-0.8 %), the force centre within 0.3 mm (measured 0.1 mm)."""
    x_yaw = -where * FLARE * R_X
    plain, _ = _exact(X**2 / (2.0 * R_X), delta)
    kinked, centre = _exact(FLARE * np.maximum(-X, 0.0) + (X - x_yaw) ** 2 / (2.0 * R_X), delta)
    xs, values = _table(FLARE)
    ratio, rate, length, model_centre = _model(xs, values, x_yaw, delta)
    assert kinked / plain < 0.65  # a strongly truncated patch
    assert ratio == pytest.approx(kinked / plain, rel=0.02)
    assert model_centre == pytest.approx(centre, abs=3e-4)
    assert 0.0 < length < 0.65
    # the rate d ln(ratio) / d ln(delta) against a difference of the model
    a_ratio, *_ = _model(xs, values, x_yaw, delta * 1.001)
    assert rate == pytest.approx(math.log(a_ratio / ratio) / math.log(1.001), abs=0.03)


def test_one_slope_is_the_parabola():
    """One slope over the whole patch and no profile term: the gap along x is the parabola
    moved, the model's patch its reference: ratio 1, length 1, the centre the deepest."""
    xs, values = _table(0.0)
    values[0::25] = 0.004 * xs  # the same slope everywhere
    ratio, rate, length, centre = _model(xs, values, 0.0, 80e-6)
    assert ratio == pytest.approx(1.0, abs=1e-9)
    assert rate == pytest.approx(0.0, abs=1e-9)
    assert length == pytest.approx(1.0, abs=1e-9)
    assert centre == pytest.approx(-0.004 * R_X, abs=1e-5)


def test_prismatic_table_keeps_the_node_law():
    """A prismatic table (equal gaps along x: slope bound 0, no search along x): the kernel's
    normal force is the node law exactly and the contact at the yaw's lead."""
    from exudyn_turnout.wheel_rail.node_laws import DELTA_REF

    values = np.zeros(2 * 2 * 1 * 25)
    xs = np.array([0.0, 1.0])
    fields = values.reshape(2, 2, 1, 25)
    fields[..., 0] = -1e-4  # gap: 0.1 mm into the rail at zero lift
    fields[..., 4] = math.radians(70.0)
    fields[..., 5] = 0.46
    fields[..., 6], fields[..., 7] = 3e4, 1.5  # N at DELTA_REF, Hertz's exponent
    fields[..., 10], fields[..., 11] = math.sin(math.radians(70)), math.cos(math.radians(70))
    fields[..., 12], fields[..., 13], fields[..., 17], fields[..., 18] = 6e-3, 4e-3, 0.5, 0.5
    fields[..., 24] = 30.0
    creep_law = np.array([float(values.size), 0.0])  # Polach's law behind the nodes
    packed_values = np.concatenate([values, creep_law])
    layout = np.array([[0, 0, 0, 2, 2, 1, 1, 5, 6]], dtype=np.int64)
    bounds = np.array([[-1e-3, 2e-3, -1.0, 2.0, 0.0, 0.0]])
    q = np.zeros(7)
    q[3] = 4e-3  # yaw
    details = np.zeros((1, len(kernel.DETAIL_FIELDS)))
    kernel.contact_forces(
        0.5, q, np.zeros(7), np.zeros(4), packed_values, np.ones(4, np.uint8), xs, layout,
        bounds, np.array([0.0, 0.46, 0.3, 8e10, 0.0, 0.0]), np.zeros(7), details,
    )  # fmt: skip
    row = details[0]
    delta = row[kernel.DETAIL_FIELDS.index("delta")]
    assert delta > 0.0
    assert row[kernel.DETAIL_FIELDS.index("normal")] == 3e4 * (delta / DELTA_REF) ** 1.5
    lead = 0.46 * math.tan(math.radians(70)) * math.tan(4e-3)
    assert row[kernel.DETAIL_FIELDS.index("x_offset")] == pytest.approx(lead, rel=1e-9)
