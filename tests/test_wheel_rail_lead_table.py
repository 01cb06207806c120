"""The kernel takes the rail at x + x_lead (the lead of a yawed wheel's contact), to first
order along x.

Reference: the table itself, evaluated at x + x_lead by tables.lookup_values; on a rail that
moves sideways linearly along x the tables' gap is linear in x within a cell, so the
kernel's first-order correction is exact there up to round-off.  The lead and the gap it
closes are lead.contact_lead's (closed form, checked against a 3-D search in
tests/test_wheel_rail_lead.py).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_turnout.wheel_rail import kernel
from exudyn_turnout.wheel_rail.data import s1002_wheel, uic60_rail
from exudyn_turnout.wheel_rail.geometry import WheelsetSetup
from exudyn_turnout.wheel_rail.lead import contact_lead
from exudyn_turnout.wheel_rail.sections import SectionGrid, lateral_grid, surface_on_grid
from exudyn_turnout.wheel_rail.tables import build_contact_table, lookup_values

SETUP = WheelsetSetup()
FLARE = 1.0 / 50.0  # the rail moves towards the field side by 1 mm per 50 mm along x
N_Q = 9  # y_w, z_w, phi, psi, beta, y_s, z_s, then the rail's lateral and vertical (7, 8)


@pytest.fixture(scope="module")
def flaring(tmp_path_factory):
    rail = uic60_rail(SETUP)
    grid = lateral_grid(SETUP.taping_line - 0.11, SETUP.taping_line + 0.09, SETUP.grid_step)
    x = np.linspace(0.0, 0.4, 5)
    z = np.stack([surface_on_grid(rail, grid, y_offset=FLARE * xi) for xi in x])
    sections = SectionGrid(x=x, y=grid, z=z, name="flaring rail")
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


def test_flange_gap_is_the_rails_at_the_lead(flaring):
    """A left wheel in flange contact, yawed 6 mrad: the kernel's penetration of the flange
    contact is that of the same kernel without yaw at x + x_lead, less the gap the lead
    closes (within a cell both are linear in x); in cells whose nodes hold the same points
    also that of the table's lookup at x + x_lead.  At x they differ by about
    x_lead FLARE sin(gamma) ~ 0.06 mm here."""
    table = flaring
    packed = kernel.pack_tables([table], [1], [(7, 8)], [(-1.0, 2.0)])
    # at zero lift: the gap carried to a lift uses each point's own cos(gamma), and the
    # flange's angle changes along the flare (0.8 rad per 0.1 m cell here)
    yaw, lift = 6e-3, 0.0
    checked = blended = 0
    for x in (0.02, 0.07, 0.12, 0.17):  # shifts within the table (to 11 mm)
        shift = 0.0054 + FLARE * x + 0.002  # the flange 2 mm into the moving gauge face
        yawed = _details(packed, x, shift, lift, yaw)
        for c in range(packed.n_candidates):
            row = yawed[c]
            angle, radius = row[_column("angle")], row[_column("radius")]
            if row[_column("found")] <= 0.0 or angle < math.radians(45.0):
                continue
            x_lead = row[_column("x_offset")]
            lead, closing = contact_lead(radius, angle, 1, yaw)
            assert x_lead == pytest.approx(float(lead), rel=1e-9)
            assert x_lead > 2e-3
            ahead = _details(packed, x + x_lead, shift, lift, 0.0)[c]
            here = _details(packed, x, shift, lift, 0.0)[c]
            delta = row[_column("delta")]
            assert delta == pytest.approx(ahead[_column("delta")] + float(closing), abs=1e-8)
            # without the lead's x the penetration would be off by far more
            assert abs(here[_column("delta")] - ahead[_column("delta")]) > 3e-5
            checked += 1
            ix = int(np.searchsorted(table.x, x, side="right") - 1)
            js = int((shift - table.shift[0]) / (table.shift[1] - table.shift[0]))
            if table.blendable[ix, js]:
                values = lookup_values(table, [x + x_lead], [shift], [lift])[0]
                gap = values[int(np.argmin(np.abs(values[:, 4] - angle))), 0]
                assert delta == pytest.approx(-(gap - float(closing)), abs=2e-7)
                blended += 1
    assert checked >= 3
