"""The tables' contact position is Kik-Piotrowski's force centre; the one normal law of the
kernel and the lookup (their equality: tests/test_wheel_rail_kernel.py).

References: CONTACT's reference outputs (E.A.H. Vollebregt, github eve70a/CONTACT d431cdb,
Apache-2.0, packaged under data/wheel_rail/reference_outputs/): the contact reference
point YCP(R), ZCP(R) of each case, and the force centre that
``references.contact_at_reference`` computes by Kik-Piotrowski at CONTACT's FN
(validation/contact_vs_contact.md: within 0.5 mm of CONTACT in 5/5 cases).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from exudyn_turnout.wheel_rail.data import data_dir, s1002_wheel
from exudyn_turnout.wheel_rail.geometry import (
    FLANGE_DIRECTION,
    prepare_rail,
    prepare_wheel,
    search_candidates,
    surface_derivatives,
)
from exudyn_turnout.wheel_rail.node_laws import (
    DELTA_REF,
    centre_point,
    node_centre,
    node_normal_force,
    node_normal_forces,
    node_offset,
)
from exudyn_turnout.wheel_rail.nonhertz import (
    PATCH_FIELDS,
    force_centre,
    kik_piotrowski,
    patch_law_fields,
)
from exudyn_turnout.wheel_rail.profiles import read_slices
from exudyn_turnout.wheel_rail.references import (
    REFERENCE_FILES,
    contact_at_reference,
    read_reference_output,
)
from exudyn_turnout.wheel_rail.sections import (
    lateral_grid,
    slice_sections,
    wheel_drop,
    wheel_envelope,
)

CASES = [
    (name, case)
    for name in REFERENCE_FILES
    for case in read_reference_output(data_dir() / "reference_outputs" / f"{name}.ref_out")
]


def _table_node(case, wheel):
    """What a table node at the case's section and shift holds (zero lift, as the tables)."""
    slices = read_slices(data_dir() / "profiles" / Path(case.rail_file).name)
    grid = lateral_grid(-0.08, 0.30, wheel.s[1] - wheel.s[0])
    offsets = np.arange(-0.1, 0.1 + 1.25e-4, 2.5e-4)
    sections = slice_sections(slices, grid, x=case.s + offsets, interpolation="auto")
    enveloped = wheel_envelope(sections, np.array([case.s]), 0.46, reach=0.1, step=2.5e-4)
    derivatives = surface_derivatives(enveloped)
    rail = prepare_rail(enveloped.z[0], derivatives.slope[0], derivatives.curvature[0], grid)
    prepared = prepare_wheel(wheel, 0.0, 0.0, (FLANGE_DIRECTION,))
    found = search_candidates(rail, prepared, shift=case.y)
    law = patch_law_fields(rail, prepared, [case.y], [found])[0]
    index = np.round((found.y_rail - grid[0]) / (grid[1] - grid[0])).astype(int)
    assert enveloped.x_offset is not None
    return found, law, enveloped.x_offset[0, index]


@pytest.mark.parametrize("name, case", CASES, ids=[f"{n}#{c.case}" for n, c in CASES])
def test_table_force_centre_is_contacts_reference_point(name, case):
    """At the node of each CONTACT case the stored force centre (zero lift, as the tables),
    taken at our KP approach for CONTACT's FN, puts the contact within 0.5 mm of CONTACT's
    YCP, ZCP (issue 22's tolerance) and within 0.1 mm of the KP force centre that the
    validation script computes there (from the same gap function, at 20 um sampling)."""
    wheel = s1002_wheel()
    found, law, x_offset = _table_node(case, wheel)
    patch = case.patches[0]
    k = int(np.argmin(np.abs(found.y_rail - patch.y_contact_rail)))
    result = contact_at_reference(case, wheel, data_dir() / "profiles")
    centre = node_centre(
        law[k, PATCH_FIELDS.index("patch_centre")],
        law[k, PATCH_FIELDS.index("patch_centre_exponent")],
        result.semi_hertz.approach,
    )
    offset = node_offset(
        law[k, PATCH_FIELDS.index("patch_offset_c2")],
        law[k, PATCH_FIELDS.index("patch_offset_c3")],
        centre,
    )
    along, up = centre_point(centre, offset, np.sin(found.angle[k]), np.cos(found.angle[k]))
    y = found.y_rail[k] + along  # the point of the rail on the force's line of action
    # the envelope's height is met x_offset ahead (the tables' x_offset): the rail point
    # there lies dx^2 / (2 r) higher in the wheel's plane (as references.geometry_at_reference)
    dx = x_offset[k]
    z = found.z_rail[k] + up + wheel_drop(dx, 0.46)
    assert abs(y - patch.y_contact_rail) <= 0.5e-3
    assert abs(z - patch.z_contact_rail) <= 0.5e-3
    # the validation's KP centre is the tangent point (same line of action, the normal)
    tangent_y = found.y_rail[k] + centre * np.cos(found.angle[k])
    assert abs(tangent_y - result.semi_hertz.y_contact_rail) <= 0.1e-3


def test_force_centre_equals_kik_piotrowskis():
    """force_centre is KP's t_centre (one formula), and 0 for a symmetric (Hertz) gap."""
    step = 1e-4
    t = (np.arange(301) - 150) * step
    lopsided = np.where(t < 0.0, 40.0 * t * t, 4.0 * t * t)  # 1/m: steep flank, flat top
    symmetric = 20.0 * t * t
    gaps = np.stack((lopsided, symmetric))
    centre = force_centre(gaps, step, 5e-5)
    patch = kik_piotrowski(gaps, step, 1.0, 5e-5, 1.15e11)
    np.testing.assert_allclose(centre, patch.t_centre, atol=1e-15)
    assert centre[0] > 5e-4  # towards the flat side
    assert abs(centre[1]) < 1e-12


def test_node_law_is_hertz_for_hertz_nodes():
    """n = 1.5: N_ref (delta / DELTA_REF)^1.5 = C_H delta^1.5 with C_H = N_ref /
    DELTA_REF^1.5; no force without penetration."""
    constant = 1.0e11  # N/m^1.5
    reference = constant * DELTA_REF**1.5
    for delta in (1e-6, 5e-5, 3e-4):
        assert node_normal_force(reference, 1.5, delta) == pytest.approx(
            constant * delta**1.5, rel=1e-12
        )
    assert node_normal_force(reference, 1.5, 0.0) == 0.0
    assert node_normal_force(reference, 1.5, -1e-5) == 0.0
    deltas = np.array([[1e-5, -1e-5], [2e-4, 0.0]])
    forces = node_normal_forces(
        np.full(4, reference), np.array([1.5, 1.5, 1.2, 1.5]), deltas.ravel()
    )
    assert forces[1] == 0.0 and forces[3] == 0.0
    assert forces[2] == pytest.approx(reference * (2e-4 / DELTA_REF) ** 1.2, rel=1e-12)
