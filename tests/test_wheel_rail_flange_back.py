"""The back of the flange as EN 13715 draws it (geometry.flange_back_arc, prepare_wheel).

Reference: EN 13715 (as UIC 510-2) defines S1002's flange back as section H, depth below the
taping circle ``F(S) = AH + sqrt(BH^2 - (S + CH)^2)`` for S from -70 to -62.764705882 mm with
AH = 9.519259302 mm, BH = 20.5 mm, CH = 49.5 mm (S from the taping line, negative towards
the flange back): a circle of 20.5 mm with a vertical tangent at S = -70 mm, the wheel's
inner face.  ``MBench_S1002_v3.prw`` comments out that tangent point (``!7.0000000E+01
9.5192593E+00``) and starts at S = -69.61 mm.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_turnout.wheel_rail.data import s1002_wheel
from exudyn_turnout.wheel_rail.geometry import (
    CHECK_RAIL_DIRECTION,
    FLANGE_BACK,
    FLANGE_BACK_RADIUS,
    find_candidates,
    flange_back_arc,
    prepare_wheel,
    rail_row,
    surface_derivatives,
)
from exudyn_turnout.wheel_rail.profile_grid import WheelsetSetup
from exudyn_turnout.wheel_rail.profiles import Profile
from exudyn_turnout.wheel_rail.sections import SectionGrid, lateral_grid, surface_on_grid

#: mm, EN 13715 / UIC 510-2 S1002 section H coefficients (module docstring)
AH, BH, CH = 9.519259302, 20.5, 49.5


def _section_h_depth(s_mm: np.ndarray) -> np.ndarray:
    return AH + np.sqrt(np.maximum(BH**2 - (s_mm + CH) ** 2, 0.0))


def test_constants_are_the_standards():
    """Radius and face position are section H's (BH, and CH + BH = 70 mm)."""
    assert FLANGE_BACK_RADIUS * 1e3 == pytest.approx(BH)
    assert FLANGE_BACK * 1e3 == pytest.approx(CH + BH)
    assert WheelsetSetup().flange_back == pytest.approx(FLANGE_BACK)


def test_arc_is_section_h_down_to_the_inner_face():
    """From the file's first point the arc follows section H within 0.02 mm (the grid's first
    point is linearly interpolated between file points 0.39 mm apart) and ends at the
    vertical tangent S = -70 mm, depth AH."""
    wheel = s1002_wheel()
    finite = np.isfinite(wheel.z)
    s0, z0 = float(wheel.s[finite][0]), float(wheel.z[finite][0])
    assert s0 * 1e3 == pytest.approx(-69.6, abs=0.06)  # the file stops short of the face
    s, z = flange_back_arc(s0, z0, 1e-4)
    assert len(s) > 10
    assert s[0] == pytest.approx(-FLANGE_BACK, abs=1e-9)
    assert -z[0] * 1e3 == pytest.approx(AH, abs=0.02)
    assert np.all(np.diff(s) > 0.0) and s[-1] < s0
    np.testing.assert_allclose(-z * 1e3, _section_h_depth(s * 1e3), atol=0.02)
    steps = np.hypot(np.diff(s), np.diff(z))
    assert np.max(steps) <= 1e-4 + 1e-12


def test_no_arc_when_the_profile_reaches_the_face():
    """A profile that already starts on the face gets no arc (the face starts there)."""
    s, z = flange_back_arc(-FLANGE_BACK, -0.01, 1e-4)
    assert s.size == 0 and z.size == 0
    s, z = flange_back_arc(-0.040, -0.02, 1e-4)  # beyond the circle's reach
    assert s.size == 0


def test_no_corner_at_the_flange_back():
    """In the check-rail search direction the wheel's curvature from the inner face down the
    flange back stays below 2 / 20.5 mm; before the arc the corner at the file's first point
    read 288 1/m (validation/check_rail_patch.py at the previous table format).  Bound 2/R,
    not 1/R: the file's own points on section H, 0.39 mm apart and gridded linearly, read
    3-78 1/m on the 1.5 mm filter further down the flange back (s = -69.5 ... -68.5 mm,
    asserted below), and the join to the arc shows the same polyline noise."""
    wheel = s1002_wheel()
    prepared = prepare_wheel(wheel, 0.75, 0.0, (CHECK_RAIL_DIRECTION,))
    _theta, _v, lower, s_at, curvature, height = prepared.directions[0]
    back = np.isfinite(lower) & (height < -0.005) & (s_at < -0.0694)
    assert np.sum(back) > 10
    assert np.max(curvature[back]) < 2.0 / FLANGE_BACK_RADIUS
    polyline = np.isfinite(lower) & (s_at > -0.0695) & (s_at < -0.0685)
    assert np.max(curvature[polyline]) > 1.5 / FLANGE_BACK_RADIUS  # the file's own noise
    on_arc = back & (s_at > -0.06999) & (s_at < -0.0697)
    assert np.median(curvature[on_arc]) == pytest.approx(1.0 / FLANGE_BACK_RADIUS, rel=0.05)


@pytest.mark.parametrize("top", [-0.004, 0.010])
def test_radius_of_an_inner_face_contact_is_from_its_height(top):
    """A check-rail block (vertical face 0.1 mm from the wheel's inner face, its top 4 mm
    below or 10 mm above the tread) touches the inner face: the contact's rolling radius is
    that point's distance from the axle, r0 - z (z: its height above the taping circle's
    lowest point), below r0 + AH; before, every inner-face contact had the radius of the
    profile's first point, r0 + 13.5 mm."""
    wheel = s1002_wheel()
    setup = WheelsetSetup()
    # m from the track centre, 0.1 mm from the inner face (0.680 m): near touching, where the
    # wheel point at the rail point's coordinate along the search direction is the one on
    # its normal (5 mm away they differ by 1.8 mm in height)
    face = 0.6799
    block = Profile(
        y=np.array([face - 0.04, face - 0.04, face - 0.002, face, face]),
        z=np.array([-0.05, top, top, top - 0.002, -0.05]),
        kind="rail",
        source="check rail block",
    )
    grid = lateral_grid(0.60, 0.84)
    check = SectionGrid(x=np.array([0.0]), y=grid, z=surface_on_grid(block, grid)[None, :])
    found = find_candidates(
        *rail_row(check, surface_derivatives(check)),
        wheel,
        setup.taping_line,
        directions=(CHECK_RAIL_DIRECTION,),
    )
    k = int(np.argmin(np.abs(found.angle + math.pi / 2)))
    assert math.degrees(found.angle[k]) == pytest.approx(-90.0, abs=3.0)
    assert found.s_wheel[k] == pytest.approx(-FLANGE_BACK, abs=1e-4)
    assert -AH * 1e-3 - 1e-4 <= found.z_rail[k] <= top
    assert found.radius[k] == pytest.approx(setup.nominal_radius - found.z_rail[k], abs=2e-4)
    assert found.radius[k] <= setup.nominal_radius + AH * 1e-3 + 1e-4
