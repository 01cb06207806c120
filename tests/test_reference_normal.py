"""The exact normal solution on our 3-D surfaces against CONTACT's reference outputs.

References: CONTACT's APPROACH, FN, PMAX, XCP(TR), the extent of its contact map and its
reference location YCP(R) in the packaged ``reference_outputs/*.ref_out`` (E.A.H.
Vollebregt, CONTACT open-source version, github eve70a/CONTACT at d431cdb, Apache-2.0;
read by ``wheel_rail.references.read_reference_output``).  Measured on the first (linear)
surfaces before the bounds were set (validation/normal_vs_contact.md at 4d2f2d4):
approach at CONTACT's FN -0.7, +0.6, +1.2, +1.6, -0.8 %; patch length 9.6 / 9.8,
9.8 / 9.4, 9.4 / 9.0, 9.4 / 9.2, 5.2 / 5.0 mm; width equal or one element (0.05 mm)
wider; force centre -0.003 ... -0.170 mm from YCP(R).  On the spline surfaces (the
default since; validation/detailed_vs_contact.md): approach -0.7, +1.6, -0.0, -0.0,
-1.8 %, lengths equal or one element longer, widths equal or one element off.  Bounds:
issue 22's 5 % for the approach and 0.5 mm for the position; the length within 0.5 mm
(CONTACT and we count whole elements of 0.2 mm), the width within two elements.
"""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_turnout.wheel_rail.data import data_dir, s1002_wheel
from exudyn_turnout.wheel_rail.exact_normal import solve_on_lateral_gap
from exudyn_turnout.wheel_rail.hertz import effective_modulus
from exudyn_turnout.wheel_rail.profiles import Profile
from exudyn_turnout.wheel_rail.reference_normal import (
    GAP_SAMPLE_STEP,
    case_geometry,
    contact_pitch,
    exact_on_surface,
    spline_profile,
    surface_gap,
)
from exudyn_turnout.wheel_rail.references import REFERENCE_FILES, read_reference_output

FOLDER = data_dir()
PROFILES = FOLDER / "profiles"


def _cases():
    return [
        (name, case)
        for name in REFERENCE_FILES
        for case in read_reference_output(FOLDER / "reference_outputs" / f"{name}.ref_out")
    ]


def _modulus(case) -> float:
    return effective_modulus(2.0 * case.shear_modulus * (1.0 + case.poisson), case.poisson)


def _check(case) -> None:
    patch = case.patches[0]
    geometry = case_geometry(case, s1002_wheel(), PROFILES)
    found = exact_on_surface(
        case, geometry, PROFILES, patch.normal_force, _modulus(case), case.dx, case.ds
    )
    solved = found.solution
    assert solved.converged
    assert solved.approach == pytest.approx(patch.approach, rel=0.05)
    assert abs(solved.length - patch.length) <= 0.5e-3 + 1e-12
    assert abs(solved.width - patch.width) <= 2 * case.ds + 1e-12
    y_centre = geometry.y_rail + solved.y_centre * np.cos(geometry.angle)
    assert abs(y_centre - patch.y_contact_rail) <= 0.5e-3
    if case.prescribed == "position":
        # CONTACT's approach is the undeformed interpenetration at its wheel position;
        # ours measured -0.5, +2.2, -0.1, +0.0 % (cross_brute's 0.75 um unexplained)
        assert found.interpenetration == pytest.approx(patch.approach, rel=0.03)


def test_wing_rail_case_against_contact():
    name, case = _cases()[0]
    assert name == "wing_brute"
    _check(case)


@pytest.mark.slow
@pytest.mark.parametrize("index", range(1, 5))
def test_other_cases_against_contact(index):
    _check(_cases()[index][1])


def test_interrupted_rail_is_what_the_2d_slice_misses():
    # cw_interrupt case 2: the rail ends along x inside the patch.  CONTACT's patch is
    # 5.0 mm long; on the 2-D slice (g(t) + A x^2) the exact solution's is 9.0 mm and its
    # approach 20 % short of CONTACT's (validation/normal_vs_contact.md)
    name, case = _cases()[-1]
    assert (name, case.case) == ("cw_interrupt", 2)
    patch = case.patches[0]
    geometry = case_geometry(case, s1002_wheel(), PROFILES)
    flat = solve_on_lateral_gap(
        geometry.gap, GAP_SAMPLE_STEP, geometry.a_sum, patch.normal_force, _modulus(case),
        case.dx, case.ds,
    )  # fmt: skip
    assert flat.length > 1.5 * patch.length
    assert flat.approach < 0.85 * patch.approach
    # the 3-D gap has no rail beyond the interruption: no surface, no contact
    x = geometry.x_offset + (np.arange(-40, 41)) * case.dx
    gap = surface_gap(case, geometry, PROFILES, x, np.zeros(1))[:, 0]
    assert np.any(gap >= 1.0)  # 1 m: no rail


def _min_gap(case, geometry, surface: str) -> float:
    """Deepest undeformed interpenetration of the 3-D surfaces around the contact."""
    pitch = contact_pitch(geometry.x_offset) if surface == "spline" else 0.0
    x = geometry.x_offset + np.arange(-40, 41) * 5e-5
    t = np.arange(-50, 51) * 1e-5
    return -float(np.min(surface_gap(case, geometry, PROFILES, x, t, surface, pitch)))


def test_linear_surfaces_match_the_2d_slice():
    # the slice's envelope (sections.wheel_envelope) and the "linear+revolution" surfaces
    # take the wheel's drop as a circle and the profiles as the same polygons: their
    # deepest interpenetrations agree (1 um: the lateral grids differ, 0.1 and 0.01 mm,
    # and the envelope's circle has the nominal radius, the surface's the point's own)
    for index in (0, 1):
        _name, case = _cases()[index]
        geometry = case_geometry(case, s1002_wheel(), PROFILES)
        assert _min_gap(case, geometry, "linear+revolution") == pytest.approx(
            geometry.interpenetration, abs=1e-6
        )
    # with the parabola ("linear") cross_brute's contact 46 mm ahead sits 5.7 um deeper
    # (x^4 / (8 r^3), closed form): what the envelope did before it took the circle
    _name, case = _cases()[1]
    geometry = case_geometry(case, s1002_wheel(), PROFILES)
    extra = _min_gap(case, geometry, "linear") - geometry.interpenetration
    assert extra == pytest.approx(0.046**4 / (8 * 0.46**3), abs=1e-6)


def test_the_wheel_circle_is_the_cross_brute_geometry_error():
    # cross_brute: CONTACT's contact lies 45.76 mm ahead of the axle (XCP(TR)), its
    # approach at the prescribed position is 0.03368 mm (cross_brute.ref_out).  The
    # parabola x^2 / (2 r) lowers the wheel there by x^4 / (8 r^3) = 5.7 um against the
    # circle: 0.0402 mm (+19 %); the body of revolution on the pitched normal 0.0344 mm
    name, case = _cases()[1]
    assert name == "cross_brute"
    geometry = case_geometry(case, s1002_wheel(), PROFILES)
    assert geometry.x_offset == pytest.approx(case.x_contact, abs=0.5e-3)
    assert _min_gap(case, geometry, "linear") > 1.15 * case.approach
    assert _min_gap(case, geometry, "spline") == pytest.approx(case.approach, rel=0.03)


def test_spline_profile_follows_a_circle_and_keeps_its_kinks():
    # points of a circle of 10 mm radius every 0.2 mm of arc (the spacing of CONTACT's
    # slices): the polygon's chords sag by h^2 / (8 R) = 0.5 um, the spline by < 1 nm
    radius = 0.01
    angle = np.arange(-40, 41) * 2e-4 / radius
    circle = Profile(y=radius * np.sin(angle), z=radius * np.cos(angle), kind="rail", source="")
    dense = spline_profile(circle, step=1e-5)
    assert np.max(np.abs(np.hypot(dense.y, dense.z) - radius)) < 1e-9
    midpoints = 0.5 * (circle.y[1:] + circle.y[:-1]), 0.5 * (circle.z[1:] + circle.z[:-1])
    assert radius - np.min(np.hypot(*midpoints)) > 4e-7
    # a V (a 90 deg turn) is a kink: both legs stay straight, no overshoot at the corner
    vee = Profile(
        y=np.linspace(-1e-3, 1e-3, 11), z=np.abs(np.linspace(-1e-3, 1e-3, 11)), kind="rail",
        source="",
    )  # fmt: skip
    kinked = spline_profile(vee, step=1e-5)
    assert np.max(np.abs(kinked.z - np.abs(kinked.y))) < 1e-12


def test_spline_pmax_converges_where_the_polygon_did_not():
    # cw_interrupt case 1 (CONTACT PMAX 3388 MPa, cw_interrupt.ref_out): on the polygons
    # PMAX grows by 20 % with half the element size (7083 -> 8494 MPa); on the splines
    # it changes by 0.1 % (3363 -> 3365 MPa, within 1 % of CONTACT's)
    name, case = _cases()[3]
    assert (name, case.case) == ("cw_interrupt", 1)
    patch = case.patches[0]
    geometry = case_geometry(case, s1002_wheel(), PROFILES)
    pmax = {}
    for surface in ("linear", "spline"):
        for scale in (1.0, 0.5):
            found = exact_on_surface(
                case, geometry, PROFILES, patch.normal_force, _modulus(case),
                scale * case.dx, scale * case.ds, surface=surface,
            )  # fmt: skip
            pmax[surface, scale] = found.solution.p_max
    assert pmax["linear", 0.5] > 1.1 * pmax["linear", 1.0]
    assert pmax["spline", 0.5] == pytest.approx(pmax["spline", 1.0], rel=0.01)
    assert pmax["spline", 1.0] == pytest.approx(patch.p_max, rel=0.05)


def test_unknown_surface_is_named():
    _name, case = _cases()[0]
    geometry = case_geometry(case, s1002_wheel(), PROFILES)
    with pytest.raises(ValueError, match="surface 'cubic'"):
        surface_gap(case, geometry, PROFILES, np.zeros(1), np.zeros(1), surface="cubic")
