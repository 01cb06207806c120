"""The kernel puts a yawed wheel's contact where the wheel's distance along x, a parabola
about the yaw's lead, plus the rail's gap at that x is smallest (along_x.lead_along_x).

Reference: the same kernel without yaw, evaluated at x + xi on a grid of xi (the rail's gap
along x as the tables give it), plus the parabola ``(xi - x_yaw)^2 / (2 r / cos(gamma))``
and less the yaw's closing (lead.contact_lead, closed form; the parabola and the minimum
checked against a 3-D search in tests/test_wheel_rail_lead.py), minimised by brute force.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_turnout.wheel_rail import kernel, packed_tables
from exudyn_turnout.wheel_rail.data import s1002_wheel, uic60_rail
from exudyn_turnout.wheel_rail.geometry import WheelsetSetup
from exudyn_turnout.wheel_rail.lead import contact_lead
from exudyn_turnout.wheel_rail.sections import SectionGrid, lateral_grid, surface_on_grid
from exudyn_turnout.wheel_rail.tables import build_contact_table, lookup_values

SETUP = WheelsetSetup()
FLARE = 1.0 / 100.0  # the rail moves towards the flange by 1 mm per 100 mm along x ...
KINK = 0.15  # m, ... up to here, straight beyond (a check rail's flare meeting its line)
N_Q = 9  # y_w, z_w, phi, psi, beta, y_s, z_s, then the rail's lateral and vertical (7, 8)


def _offset(x):
    """m, the rail's move towards the field side at x (the flare, then the straight)."""
    return -FLARE * np.minimum(np.asarray(x, float) - KINK, 0.0)


@pytest.fixture(scope="module")
def kinked(tmp_path_factory):
    rail = uic60_rail(SETUP)
    grid = lateral_grid(SETUP.taping_line - 0.11, SETUP.taping_line + 0.09, SETUP.grid_step)
    x = np.arange(0.0, 0.3 + 1e-9, 0.025)
    z = np.stack([surface_on_grid(rail, grid, y_offset=float(_offset(xi))) for xi in x])
    sections = SectionGrid(x=x, y=grid, z=z, name="kinked rail")
    return build_contact_table(
        s1002_wheel(SETUP),
        sections,
        SETUP.taping_line,
        cache_dir=tmp_path_factory.mktemp("tables"),
    )


def _details(packed, x, shift, lift, yaw):
    q = np.zeros(N_Q)
    q[0], q[1], q[3] = shift, lift, yaw  # left wheel: shift = y_w (rail at 0)
    details = np.zeros((packed.n_candidates, len(kernel.DETAIL_FIELDS)))
    kernel.contact_forces(
        x, q, np.zeros(N_Q), np.zeros(4), packed.values, packed.blendable, packed.x,
        packed.layout, packed.bounds, np.array([0.0, SETUP.nominal_radius, 0.4, 8.1e10, 0.0,
        0.0]), np.zeros(N_Q), details,
    )  # fmt: skip
    return details


def _column(name: str) -> int:
    return kernel.DETAIL_FIELDS.index(name)


def _slide(table, x: float, shift: float, c: int) -> float:
    """1 / (rho_w + rho_r) of slot c at (x, shift) as the kernel has it: per node from the
    table's lateral curvatures (both convex, else 0), bilinear between the cell's nodes."""
    names = list(table.fields)
    k_w = np.nan_to_num(table.values[..., c, names.index("curvature_wheel")])
    k_r = np.nan_to_num(table.values[..., c, names.index("curvature_rail")])
    convex = (table.values[..., c, 0] < 0.5) & (k_w > 0.0) & (k_r > 0.0)
    node = np.where(convex, k_w * k_r / np.where(convex, k_w + k_r, 1.0), 0.0)
    ix = min(max(int(np.searchsorted(table.x, x, side="right")) - 1, 0), len(table.x) - 2)
    tx = min(max((x - table.x[ix]) / (table.x[ix + 1] - table.x[ix]), 0.0), 1.0)
    position = (shift - table.shift[0]) / (table.shift[1] - table.shift[0])
    js = int(position)
    ts = position - js
    v00, v10, v01, v11 = node[ix, js], node[ix + 1, js], node[ix, js + 1], node[ix + 1, js + 1]
    return float(v00 + tx * (v10 - v00) + ts * ((v01 - v00) + tx * (v11 - v10 - v01 + v00)))


@pytest.mark.parametrize(
    "x, where",
    [(0.11, "on the flare"), (0.135, "on the kink"), (0.16, "beyond the kink")],
)
def test_flange_contact_is_the_minimum_along_a_kinked_flare(kinked, x, where):
    """A left wheel 3 mm into the gauge face of a rail flaring 1:100 towards it up to a kink
    at 0.15 m, yawed 6 mrad (flange at ~70 deg, the yaw's lead 7.7 mm): the kernel's
    penetration is the largest over xi of the table's (tables.lookup_values at x + xi, the
    query's shift, in the cells 0.1 ... 0.3 m that hold one point along x) less the
    parabola and the profile term (along_x.lead_along_x), plus the closing, and its lead
    that xi.  On the flare the contact lies
    ``FLARE sin(gamma) r / cos(gamma)`` ~ 12.5 mm ahead of the yaw's lead (and the first
    order along x misses ~60 um of penetration), within that of the kink on the kink,
    beyond it at the yaw's lead.  The xi grid (20 um) holds the table's nodes: within 1 nm
    of penetration, 20 um of lead."""
    packed = packed_tables.pack_tables([kinked], [1], [(7, 8)], [(-1.0, 2.0)])
    yaw, shift = 6e-3, 0.0054 + float(_offset(x)) + 0.003
    yawed = _details(packed, x, shift, 0.0, yaw)
    rows = [
        c
        for c in range(packed.n_candidates)
        if yawed[c, _column("found")] > 0.0 and yawed[c, _column("angle")] > math.radians(45.0)
    ]
    assert len(rows) == 1  # the flange (the tread's point, if any, is another slot)
    c = rows[0]
    row = yawed[c]
    angle, radius = row[_column("angle")], row[_column("radius")]
    assert math.degrees(angle) == pytest.approx(70.0, abs=1.0)
    x_yaw, closing = (float(v) for v in contact_lead(radius, angle, 1, yaw))
    lo, hi = max(-0.03, 0.1 - x), min(0.05, 0.3 - x)
    offsets = np.union1d(np.arange(lo, hi, 2e-5), kinked.x[(kinked.x > x + lo)] - x)
    offsets = offsets[offsets <= hi]
    gaps = lookup_values(kinked, x + offsets, np.full(offsets.size, shift))[:, c, 0]
    quartic = math.sin(angle) ** 2 * _slide(kinked, x, shift, c) / (8.0 * radius**2)
    candidates = (
        -gaps - (offsets - x_yaw) ** 2 / (2.0 * radius / math.cos(angle)) - quartic * offsets**4
    )
    best = int(np.argmax(candidates))
    assert 0 < best < offsets.size - 1  # a minimum inside the search
    assert row[_column("delta")] == pytest.approx(candidates[best] + closing, abs=1e-9)
    # the kernel's x_offset is the force centre (along_x.patch_along_x): within the patch's
    # semi-axis of the deepest point, which the penetration above pins to offsets[best]
    assert abs(row[_column("x_offset")] - offsets[best]) < row[_column("a")]
    lead = float(offsets[best])
    here, ahead = lookup_values(kinked, [x, x + 1e-3], [shift, shift])[:, c, 0]
    first_order = -(here + (ahead - here) / 1e-3 * x_yaw - closing)
    if where == "on the flare":
        assert lead - x_yaw == pytest.approx(12.5e-3, rel=0.05)
        assert row[_column("delta")] - first_order > 4e-5
    elif where == "on the kink":
        assert lead == pytest.approx(KINK - x, abs=2e-5)
    else:
        assert lead == pytest.approx(x_yaw, abs=2e-5)
        assert row[_column("delta")] == pytest.approx(first_order, abs=1e-12)
