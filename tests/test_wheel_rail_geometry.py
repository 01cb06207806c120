"""Wheelset-on-track contact geometry (exudyn_turnout.wheel_rail.geometry).

S1002 wheel / UIC60 rail inclined 1:40 (Manchester benchmark profiles, CONTACT's copies),
gauge 1435 mm, back-to-back 1360 mm, flange back 70 mm from the taping line (EN 13715),
gauge point 14 mm below the top of rail (EN 15302).
"""

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import IntegrationWarning, quad

from exudyn_turnout.wheel_rail.data import s1002_wheel, standard_track
from exudyn_turnout.wheel_rail.geometry import (
    WheelsetSetup,
    equivalent_conicity,
    equivalent_conicity_klingel,
    find_candidates,
    flange_angle,
    grid_wheel,
    nadal_limit,
    rail_row,
    solve_wheelset,
    surface_derivatives,
)
from exudyn_turnout.wheel_rail.profiles import Profile
from exudyn_turnout.wheel_rail.sections import (
    CrossingDesign,
    crossing_sections,
    lateral_grid,
    place_rail,
    plain_rail_sections,
)

SETUP = WheelsetSetup()


@pytest.fixture(scope="module")
def s1002_on_uic60():
    wheel = s1002_wheel(SETUP)
    track = standard_track(SETUP)
    row = rail_row(track, surface_derivatives(track))
    y = np.round(np.arange(-6.0, 6.01, 0.25), 2) * 1e-3
    return wheel, row, solve_wheelset(y, wheel, row, row, SETUP)


def test_centred_wheelset_is_symmetric_and_on_the_tread(s1002_on_uic60):
    _wheel, _row, result = s1002_on_uic60
    centre = int(np.argmin(np.abs(result.y)))
    assert result.delta_r[centre] == pytest.approx(0.0, abs=1e-7)
    assert result.roll[centre] == pytest.approx(0.0, abs=1e-7)
    # Delta r is odd in y (symmetric track and wheelset)
    np.testing.assert_allclose(result.delta_r, -result.delta_r[::-1], atol=2e-6)
    # tread contact near the taping line; S1002 is designed for 1:40 rails, so the contact
    # angle is close to the inclination: atan(1/40) = 1.43 deg (hand value)
    assert abs(result.s_left[centre]) < 0.006
    assert math.degrees(result.angle_left[centre]) == pytest.approx(1.43, abs=0.3)


def test_contact_angle_equals_both_profile_slopes_at_the_contact_point(s1002_on_uic60):
    """Independent check: the surfaces are tangent at a rigid contact point."""
    wheel, row, result = s1002_on_uic60
    rail_z, _slope, _curvature, grid = row
    for i in range(0, len(result.y), 4):
        angle = result.angle_left[i] - result.roll[i]  # left wheel, rolled with the wheelset
        s = result.s_left[i]
        raw_wheel_slope = np.interp(s, wheel.s, np.gradient(np.nan_to_num(wheel.z), wheel.s))
        y = result.y_rail_left[i]
        raw_rail_slope = np.interp(y, grid, np.gradient(np.nan_to_num(rail_z), grid))
        if abs(result.y[i]) < 0.004:  # tread: slopes within 0.3 deg of each other
            assert math.degrees(math.atan(raw_wheel_slope) - angle) == pytest.approx(0.0, abs=0.3)
            assert math.degrees(math.atan(raw_rail_slope) - result.angle_left[i]) == pytest.approx(
                0.0, abs=0.3
            )


def test_rolling_radius_difference_jumps_to_the_flange_root(s1002_on_uic60):
    _wheel, _row, result = s1002_on_uic60
    small = np.abs(result.y) <= 0.003
    # on the tread Delta r is a few tenths of a mm per mm of shift ...
    assert np.all(np.abs(result.delta_r[small]) < 1.2e-3)
    # ... and S1002 on UIC60 1:40 jumps to flange-root contact (contact angle > 15 deg)
    # before the flange touches: the well-known Delta r jump of this pair
    jump = result.y[np.argmax(np.degrees(result.angle_left) > 15.0)]
    assert 0.004 <= jump <= 0.006
    assert result.delta_r[result.y == jump][0] > 2.5e-3


def test_equivalent_conicity_en15302_at_3_mm(s1002_on_uic60):
    """EN 15302 regression method, amplitude 3 mm.

    No published number for S1002 / UIC60 1:40 / 1435 / 1360 could be found (searched
    2026-11: EN 15302 / UIC 519 texts, Polach's papers, the Manchester benchmark; EN
    15302's Annex E uses other wheel treads, see ANNEX_E_DELTA_R below), so the value is
    checked by an independent computation of the same definition (first Fourier
    coefficient by adaptive quadrature of the Delta r function) and reported; it is
    printed by validation/contact_geometry.py.
    """
    _wheel, _row, result = s1002_on_uic60
    conicity = equivalent_conicity(result.y, result.delta_r, 0.003)

    def integrand(theta):
        y = 0.003 * math.sin(theta)
        return np.interp(y, result.y, result.delta_r) * math.sin(theta)

    with warnings.catch_warnings():  # Delta r is piecewise linear: quad notes the kinks
        warnings.simplefilter("ignore", IntegrationWarning)
        first_harmonic = quad(integrand, 0.0, 2.0 * math.pi, limit=400)[0] / math.pi
    assert conicity == pytest.approx(first_harmonic / (2.0 * 0.003), rel=2e-3)
    assert 0.10 < conicity < 0.30  # tread conicity of a new S1002 on 1:40 rails


# EN 15302:2008+A1:2010, Annex E: reference Delta r functions (mm, y = 0, 0.1, ... 6.8 mm;
# odd in y) and reference equivalent conicities, cases E1 (wheels A / A on rail A) and E2
# (wheels B / B on rail A), as transcribed in github.com/criogenox/
# B_ECC-Equivalent-Conicity-Calculation (commit 6e33d43), files
# src/main/resources/eqcon/mvnver/data/dr_ce_E1.dat, dr_ce_E2.dat, ben_E1.dat, ben_E2.dat;
# y grid from its Select.java.  Wheel A / B are S1002 flanges with other treads, so these
# check the conicity methods, not our S1002 / UIC60 geometry.
ANNEX_E_DELTA_R = {
    "E1": (
        0.0,
        0.032,
        0.051,
        0.071,
        0.092,
        0.116,
        0.142,
        0.167,
        0.197,
        0.227,
        0.257,
        0.292,
        0.328,
        0.361,
        0.402,
        0.443,
        0.481,
        0.527,
        0.574,
        0.616,
        0.667,
        0.719,
        0.766,
        0.822,
        0.879,
        0.931,
        0.992,
        1.055,
        1.111,
        1.177,
        1.236,
        1.299,
        1.346,
        1.407,
        1.471,
        1.539,
        1.598,
        1.673,
        1.752,
        1.834,
        1.906,
        1.995,
        2.088,
        2.185,
        2.286,
        2.373,
        2.481,
        2.593,
        2.709,
        2.808,
        2.931,
        3.058,
        3.189,
        3.324,
        3.44,
        3.582,
        3.729,
        3.879,
        4.008,
        4.166,
        4.328,
        4.494,
        4.636,
        5.064,
        5.692,
        6.521,
        7.597,
        9.01,
        10.954,
    ),
    "E2": (
        0.0,
        0.005,
        0.01,
        0.015,
        0.02,
        0.025,
        0.03,
        0.035,
        0.04,
        0.045,
        0.05,
        0.055,
        0.06,
        0.065,
        0.07,
        0.075,
        0.08,
        0.085,
        0.09,
        0.095,
        0.1,
        0.105,
        0.11,
        0.115,
        0.12,
        0.125,
        0.13,
        0.135,
        0.14,
        0.145,
        1.95,
        2.003,
        2.057,
        2.112,
        2.167,
        2.224,
        2.281,
        2.339,
        2.397,
        2.457,
        2.517,
        2.578,
        2.64,
        2.702,
        2.766,
        2.83,
        2.895,
        2.961,
        3.027,
        3.095,
        3.163,
        3.232,
        3.302,
        3.372,
        3.444,
        3.516,
        3.589,
        3.663,
        3.737,
        3.813,
        3.889,
        3.966,
        4.044,
        4.123,
        5.392,
        6.111,
        7.05,
        8.27,
        9.895,
    ),
}
ANNEX_E_CONICITY = {  # amplitude (mm): reference tan(gamma_e)
    "E1": {1.0: 0.125, 2.0: 0.155, 3.0: 0.188, 4.0: 0.216, 5.0: 0.254, 6.0: 0.303},
    "E2": {1.0: 0.025, 2.0: 0.025, 3.0: 0.058, 3.5: 0.189, 4.0: 0.241, 5.0: 0.283, 6.0: 0.302},
}


def _annex_e(case):
    half = np.array(ANNEX_E_DELTA_R[case])
    y = np.round(np.arange(-6.8, 6.81, 0.1), 1)
    return y, np.concatenate((-half[:0:-1], half))


@pytest.mark.parametrize("case", ["E1", "E2"])
def test_klingel_conicity_reproduces_en15302_annex_e(case):
    """EN 15302's acceptance band is +-min(0.05, 0.5 tan gamma_e) (Annex F); the integration
    of the kinematic motion should be far better than that, since Annex E's references are
    that method's results.  The 0.002 below was fixed after the first run showed
    agreement within 0.001 (it guards against regressions, it was not predicted)."""
    y, delta_r = _annex_e(case)
    for amplitude, reference in ANNEX_E_CONICITY[case].items():
        assert equivalent_conicity_klingel(y, delta_r, amplitude) == pytest.approx(
            reference, abs=0.002
        ), amplitude


def test_regression_conicity_overshoots_when_the_amplitude_just_reaches_a_jump():
    # documents the limitation stated in equivalent_conicity's Notes: E2 jumps from 0.145
    # to 1.95 mm at y = 3.0 mm; at 3 mm the regression gives 0.090, the reference is 0.058
    y, delta_r = _annex_e("E2")
    assert equivalent_conicity(y, delta_r, 3.0) == pytest.approx(0.090, abs=0.002)
    # where Delta r is smooth over the motion the two methods agree (E1, 3 mm: 0.188)
    y, delta_r = _annex_e("E1")
    assert equivalent_conicity(y, delta_r, 3.0) == pytest.approx(0.188, abs=0.002)


def test_klingel_conicity_of_s1002_on_uic60_agrees_with_the_regression(s1002_on_uic60):
    """At 3 mm the S1002 / UIC60 Delta r has no jump inside the motion (the flange-root
    jump is at 4.5-5 mm), so the two EN 15302 methods should agree to well within the
    standard's band; 0.005 (about 3 %) was chosen from that argument.  (A 0.1 mm-grid run
    made while investigating, before this test was written, gave 0.1853 / 0.1838.)"""
    _wheel, _row, result = s1002_on_uic60
    regression = equivalent_conicity(result.y, result.delta_r, 0.003)
    integration = equivalent_conicity_klingel(result.y, result.delta_r, 0.003)
    assert integration == pytest.approx(regression, abs=0.005)


def test_conicity_of_a_cone_on_circular_crowns_matches_the_closed_form():
    """Hand derivation for a cone (slope g) on rails with a circular crown (radius R,
    inclination e), wheelset radius r0, contact points b' from the centre line:

    - rolling the wheelset by phi moves each wheel's bottom by r0 phi (left outwards,
      right inwards) and the contact points on the crowns by R phi the same way, so
      Delta r = g (2 y + 2 (r0 + R) phi);
    - the axle's roll follows from the radii and the contact heights on the crowns,
      phi (2 b' + 2 R (g - e)) = Delta r;
    - hence gamma_e = g / (1 - g (r0 + R) / (b' + R (g - e))) = 0.05266 for g = 1/20,
      R = 0.3 m, e = 1/40, r0 = 0.46 m, b' = 0.7457 m (slightly above g: roll).
    """
    s = np.linspace(-0.065, 0.065, 1301)
    cone = Profile(y=s, z=s / 20.0, kind="wheel", source="cone 1:20")
    wheel = grid_wheel(cone, nominal_radius=0.46)
    y = np.linspace(-0.036, 0.036, 721)
    head = np.concatenate(([-0.036], y, [0.036]))
    crown = np.concatenate(([-0.040], -(0.3 - np.sqrt(0.3**2 - y**2)), [-0.040]))
    rail = place_rail(
        Profile(y=head, z=crown, kind="rail", source="R300 crown"), inclination=1 / 40
    )
    grid = lateral_grid(0.66, 0.84)
    track = plain_rail_sections(rail, np.array([0.0]), grid)
    row = rail_row(track, surface_derivatives(track))
    shifts = np.linspace(-0.004, 0.004, 17)
    result = solve_wheelset(shifts, wheel, row, row, SETUP)
    g, radius, e, r0 = 1 / 20, 0.3, 1 / 40, 0.46
    b_prime = result.y_rail_left[8]  # centred wheelset (0.7457 m)
    expected = g / (1 - g * (r0 + radius) / (b_prime + radius * (g - e)))
    assert expected == pytest.approx(0.05266, abs=1e-4)
    assert equivalent_conicity(result.y, result.delta_r, 0.003) == pytest.approx(expected, rel=2e-3)
    # the contact angle is the cone's, turned by the roll
    np.testing.assert_allclose(np.tan(result.angle_left - result.roll), g, atol=1e-3)


def test_flange_angle_and_nadal_limit():
    wheel = s1002_wheel(SETUP)
    angle = flange_angle(wheel)
    # S1002 flange flank at 70 deg (EN 13715 profile definition)
    assert math.degrees(angle) == pytest.approx(70.0, abs=0.5)
    # Nadal Y/Q = (tan g - mu)/(1 + mu tan g); hand value for 70 deg, mu = 0.3: 1.342
    assert nadal_limit(math.radians(70.0), 0.3) == pytest.approx(1.342, abs=1e-3)
    assert nadal_limit(angle, 0.3) == pytest.approx(1.342, abs=0.02)


def test_two_rail_heads_give_two_candidates_each_with_its_own_gap():
    """Crossing section with wing rail and nose both under the tread."""
    wheel = s1002_wheel(SETUP)
    design = CrossingDesign()
    base = place_rail(wheel_rail_base(), inclination=0.0)
    grid = lateral_grid(0.66, 0.86)
    x = np.array([design.nose_tip + 0.3])
    sections = crossing_sections(design, base, x, grid)
    merged = np.fmax(sections["wing"].z, sections["nose"].z)
    from exudyn_turnout.wheel_rail.sections import SectionGrid

    both = SectionGrid(x=x, y=grid, z=merged)
    row = rail_row(both, surface_derivatives(both))
    found = find_candidates(*row, wheel, SETUP.taping_line, max_gap=0.003)
    assert len(found.gap) >= 2
    nose_edge = 0.7175 + design.tip_width + 0.3 / design.crossing_number
    on_nose = found.y_rail < nose_edge
    assert on_nose.any() and (~on_nose).any()
    # lowering the wheel by the smaller gap closes exactly that candidate
    lowest = int(np.argmin(found.gap))
    vertical = found.gap[lowest] / math.cos(found.angle[lowest])
    again = find_candidates(*row, wheel, SETUP.taping_line, lift=-vertical, max_gap=0.003)
    assert np.min(np.abs(again.gap)) < 2e-6


def wheel_rail_base():
    """The benchmark UIC60 turned back upright (crossings are not inclined)."""
    from exudyn_turnout.wheel_rail.data import profile_path
    from exudyn_turnout.wheel_rail.profiles import read_simpack_profile
    from exudyn_turnout.wheel_rail.sections import incline_profile

    return incline_profile(read_simpack_profile(profile_path("MBench_UIC60_v3.prr")), -1 / 40)


def test_back_of_flange_against_a_check_rail_is_found_along_its_own_direction():
    """A check rail (vertical face 5 mm from the wheel's inner face) is touched by the back
    of the flange: contact angle -90 deg (normal on the wheel towards the field side), normal
    gap closing one to one with the wheel's shift towards the track centre.  The inner face
    is where EN 13715 puts it, 70 mm from the taping line: at 1360 / 2 = 680 mm from the
    track centre (EN 13260's back-to-back distance)."""
    from exudyn_turnout.wheel_rail.geometry import CHECK_RAIL_DIRECTION, FLANGE_DIRECTION
    from exudyn_turnout.wheel_rail.sections import SectionGrid, surface_on_grid

    wheel = s1002_wheel(SETUP)
    face = 0.675  # m from the track centre; the wheel's inner face is at 0.680 m
    block = Profile(
        y=np.array([face - 0.04, face - 0.04, face - 0.002, face, face]),
        z=np.array([-0.05, 0.010, 0.010, 0.008, -0.05]),
        kind="rail",
        source="check rail block",
    )
    grid = lateral_grid(0.60, 0.84)
    check = SectionGrid(x=np.array([0.0]), y=grid, z=surface_on_grid(block, grid)[None, :])
    row = rail_row(check, surface_derivatives(check))
    gaps = []
    for shift in (0.0, -0.003):
        found = find_candidates(
            *row,
            wheel,
            SETUP.taping_line,
            shift=shift,
            lift=-1.8e-4,
            directions=(FLANGE_DIRECTION, CHECK_RAIL_DIRECTION),
        )
        assert math.degrees(found.angle[0]) == pytest.approx(-90.0, abs=1.0)
        gaps.append(found.gap[0])
    assert gaps[0] == pytest.approx(0.680 - face, abs=2e-4)
    assert gaps[0] - gaps[1] == pytest.approx(0.003, abs=1e-4)
    vertical_only = find_candidates(*row, wheel, SETUP.taping_line, shift=0.0, directions=())
    assert len(vertical_only.gap) == 0 or abs(math.degrees(vertical_only.angle[0])) < 80
