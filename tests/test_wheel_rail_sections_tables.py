"""Rail sections along x, the rigid-wheel envelope, design sections, cached contact tables."""

import math

import numpy as np
import pytest

from exudyn_turnout.wheel_rail.data import profile_path, s1002_wheel, standard_track
from exudyn_turnout.wheel_rail.geometry import (
    WheelsetSetup,
    find_candidates,
    rail_row,
    surface_derivatives,
)
from exudyn_turnout.wheel_rail.node_laws import DELTA_REF, centre_point, node_offset
from exudyn_turnout.wheel_rail.profiles import read_simpack_profile, read_slices
from exudyn_turnout.wheel_rail.sections import (
    CrossingDesign,
    SectionGrid,
    SwitchDesign,
    crossing_sections,
    incline_profile,
    lateral_grid,
    place_rail,
    section_at,
    sections_at,
    slice_heights,
    slice_sections,
    slice_surface,
    switch_sections,
    wheel_drop,
    wheel_envelope,
)
from exudyn_turnout.wheel_rail.tables import (
    TableSettings,
    build_contact_table,
    lookup,
    lookup_values,
    normal_force,
    table_key,
)

SETUP = WheelsetSetup()


def upright_uic60():
    rail = read_simpack_profile(profile_path("MBench_UIC60_v3.prr"))
    return place_rail(incline_profile(rail, -1 / 40))


def test_slices_are_interpolated_linearly_between_positions():
    slices = read_slices(profile_path("cross_nose.slcs"))
    grid = lateral_grid(-0.02, 0.08)
    sections = slice_sections(slices, grid)
    np.testing.assert_array_equal(section_at(sections, slices.u[4]), sections.z[4])
    middle = section_at(sections, 0.5 * (slices.u[4] + slices.u[5]))
    both = np.isfinite(sections.z[4]) & np.isfinite(sections.z[5])
    np.testing.assert_allclose(middle[both], 0.5 * (sections.z[4] + sections.z[5])[both])
    # CONTACT's artificial nose rises at 1:10 (the slice file's comment): 1 mm per 10 mm
    top = np.nanmax(sections.z, axis=1)
    assert np.median(np.diff(top[5:15]) / np.diff(slices.u[5:15])) == pytest.approx(0.1, rel=0.02)


@pytest.mark.parametrize(
    "name", ["cross_nose.slcs", "wing_rail.slcs", "cross+wing_extd.slcs", "uk_crossing.slcs"]
)
def test_slice_surface_passes_through_its_slices(name):
    slices = read_slices(profile_path(name))
    grid = lateral_grid(-0.05, 0.13)
    own = slice_sections(slices, grid)  # each slice's own profile, gridded
    surface = slice_surface(slices, grid)
    # CONTACT's data (packaged) with features are aligned by them, the UK crossing has none
    assert surface.alignment == ("lateral" if name == "uk_crossing.slcs" else "features")
    heights = slice_heights(surface, slices.u[:25])
    np.testing.assert_array_equal(np.isnan(heights), np.isnan(own.z[:25]))
    # resampled by arc length every 0.1 mm: corners of the polyline cut by < 5 um
    assert np.nanmax(np.abs(heights - own.z[:25])) < 5e-6


def test_linear_slice_interpolation_is_the_gridded_blend():
    slices = read_slices(profile_path("cross_nose.slcs"))
    grid = lateral_grid(-0.02, 0.08)
    x = np.concatenate((slices.u, slices.u[:-1] + 0.3 * np.diff(slices.u)))
    linear = slice_heights(slice_surface(slices, grid, interpolation="linear"), x)
    blend = sections_at(slice_sections(slices, grid), x)
    np.testing.assert_array_equal(np.isnan(linear), np.isnan(blend))
    np.testing.assert_allclose(linear, blend, atol=1e-15)


def test_a_rail_shifting_sideways_stays_its_shape_between_slices():
    """CONTACT's wing rail shifts sideways at 1:10 (its slice file's comment; the features
    move 1 mm per 10 mm slice): midway between slices the section is the slice shifted by
    0.5 mm.  The feature-aligned surface reproduces it; the linear blend at constant y
    cuts the moving flank (0.6 mm within 16 mm of the top, 0.1 mm within 5 mm)."""
    slices = read_slices(profile_path("wing_rail.slcs"))
    grid = lateral_grid(-0.03, 0.08)  # 0.1 mm: the 0.5 mm shift is 5 grid steps
    middle = 0.5 * (slices.u[8] + slices.u[9])
    errors = {}
    for method in ("auto", "linear"):
        surface = slice_surface(slices, grid, interpolation=method)
        before, half = slice_heights(surface, [slices.u[8], middle])
        shifted = np.full_like(before, np.nan)
        shifted[5:] = before[:-5]
        touchable = np.isfinite(shifted) & np.isfinite(half) & (shifted > np.nanmax(before) - 0.016)
        errors[method] = float(np.max(np.abs(half - shifted)[touchable]))
    assert errors["auto"] < 1e-6
    assert errors["linear"] > 0.4e-3


def test_uk_crossing_wing_rail_falls_smoothly_between_slices():
    """The wing rail of the UK crossing (S&C benchmark slices, packaged) falls steeply after
    u = 239 mm: 1.458 / 1.237 / 0.248 mm at y = 38.6 mm in the slices at u = 228.7 / 248.4 /
    268.0 mm (read from the files through the surface).  Midway between the last two the
    default (PCHIP at constant y) and CONTACT's feature-aligned cubic agree within 0.03 mm
    (0.879 / 0.872 mm) and lie 0.13 mm above the linear blend (0.743 mm); a not-a-knot cubic
    at constant y rings there (1.587 mm above the higher neighbouring slice, 0.044 mm below
    the lower), so it is not the default."""
    slices = read_slices(profile_path("uk_crossing.slcs"))
    grid = lateral_grid(0.0, 0.06)
    column = int(round(0.0386 / 1e-4))
    u = np.array([0.22871, 0.23854, 0.24836, 0.25819, 0.26801])
    at = {
        key: slice_heights(slice_surface(slices, grid, interpolation=m, alignment=a), u)[:, column]
        for key, m, a in [
            ("auto", "auto", "auto"),
            ("contact", "spline", "features"),
            ("linear", "linear", "auto"),
            ("cubic_y", "spline", "lateral"),
        ]
    }
    np.testing.assert_allclose(at["auto"][[0, 2, 4]], [1.458e-3, 1.237e-3, 0.248e-3], atol=2e-6)
    assert abs(at["auto"][3] - at["contact"][3]) < 0.03e-3
    assert at["auto"][3] - at["linear"][3] > 0.1e-3
    for value, lo, hi in [(at["auto"][1], 1.237e-3, 1.458e-3), (at["auto"][3], 0.248e-3, 1.237e-3)]:
        assert lo <= value <= hi  # shape-preserving: within its neighbouring slices
    assert at["cubic_y"][1] > 1.458e-3 and at["cubic_y"][3] < 0.248e-3  # beyond both


def test_uk_crossing_needs_lateral_alignment_where_the_nose_appears():
    """Without features CONTACT joins points by their fraction of the slice's length; where
    the nose appears (u = 113.95 -> 118.94 mm, the profile 107 -> 218 mm long) that joins
    the wing rail's head to the flangeway and the surface rises far above both slices."""
    slices = read_slices(profile_path("uk_crossing.slcs"))
    grid = lateral_grid(-0.05, 0.12)
    x = np.linspace(0.0808, 0.1189, 20)
    neighbours = slice_heights(slice_surface(slices, grid), slices.u[44:49])
    ceiling = np.nanmax(neighbours)
    contact = slice_surface(slices, grid, interpolation="spline", alignment="features")
    by_length = slice_heights(contact, x)
    auto = slice_heights(slice_surface(slices, grid), x)
    assert np.nanmax(by_length) > ceiling + 5e-3
    assert np.nanmax(auto) <= ceiling + 1e-9


def test_wheel_envelope_meets_a_rising_nose_ahead_and_a_flat_rail_under_the_centre():
    grid = lateral_grid(-0.02, 0.02, 1e-3)
    x = np.linspace(-0.2, 0.2, 41)
    flat = SectionGrid(x=x, y=grid, z=np.zeros((len(x), len(grid))))
    enveloped = wheel_envelope(flat, np.array([0.0]), 0.46, reach=0.1, step=0.005)
    np.testing.assert_allclose(enveloped.z, 0.0, atol=1e-15)
    np.testing.assert_allclose(enveloped.x_offset, 0.0, atol=1e-12)
    # a ramp z = x / 10 (x > 0): the circle r = 0.46 m touches where its slope is 1/10,
    # dx = r sin(atan(0.1)) = 45.8 mm ahead (hand value; CONTACT's cross_brute: 45.76 mm)
    ramp = SectionGrid(x=x, y=grid, z=np.maximum(x, 0.0)[:, None] / 10 + 0 * grid)
    met = wheel_envelope(ramp, np.array([0.0]), 0.46, reach=0.1, step=0.0005)
    assert met.x_offset[0, 0] == pytest.approx(0.46 * math.sin(math.atan(0.1)), abs=6e-4)
    # and the height met there is the circle's, r (sqrt(1 + s^2) - 1) = 2.2943 mm (closed
    # form, s = 1/10); the parabola dx^2 / (2 r) used before gave r s^2 / 2 = 2.3000 mm
    circle = 0.46 * (math.sqrt(1.0 + 0.01) - 1.0)
    assert met.z[0, 0] == pytest.approx(circle, abs=2e-7)
    assert abs(met.z[0, 0] - 0.46 * 0.01 / 2) > 5e-6


def test_wheel_drop_is_the_circle_and_the_envelope_rejects_a_reach_beyond_the_radius():
    dx = np.array([0.0, 0.01, 0.046, 0.12])
    r = 0.46
    drop = wheel_drop(dx, r)
    # closed form: the circle's height above its lowest point, r (1 - cos(asin(dx / r)))
    np.testing.assert_allclose(drop, r * (1.0 - np.cos(np.arcsin(dx / r))), rtol=1e-12)
    # the parabola lies below it by dx^4 / (8 r^3) to leading order: 5.7 um at 46 mm
    # (CONTACT's cross_brute contact, validation/detailed_vs_contact.md)
    assert drop[2] - 0.046**2 / (2 * r) == pytest.approx(0.046**4 / (8 * r**3), rel=0.02)
    grid = lateral_grid(-0.01, 0.01, 1e-3)
    flat = SectionGrid(x=np.array([-1.0, 1.0]), y=grid, z=np.zeros((2, len(grid))))
    with pytest.raises(ValueError, match="reach"):
        wheel_envelope(flat, np.array([0.0]), 0.46, reach=0.5)


def test_switch_blade_planed_and_lowered_near_the_toe():
    design = SwitchDesign()
    grid = lateral_grid(0.70, 0.92)
    sections = switch_sections(design, upright_uic60(), np.array([0.0, 2.5, 5.0, 8.0]), grid)
    blade, stock = sections["blade"], sections["stock"]
    unlowered = switch_sections(
        SwitchDesign(toe_lowering=0.0), upright_uic60(), np.array([0.0, 2.5, 5.0, 8.0]), grid
    )["blade"]
    lowering = np.nanmax(unlowered.z - blade.z, axis=1)
    # 3 mm low at the toe, rising linearly to full height at 5 m (SwitchDesign defaults)
    np.testing.assert_allclose(lowering, [0.003, 0.0015, 0.0, 0.0], atol=1e-9)
    # a 3 mm wide blade tip is the rail's gauge corner: its top is far below the crown
    assert np.nanmax(blade.z[0]) < -0.006
    widths = [np.ptp(grid[np.isfinite(row)]) for row in blade.z]
    assert widths[0] < widths[1] < widths[2]

    # the stock rail curves away: its gauge face moves x^2 / 2R + entry angle
    def gauge_face(row):
        return grid[np.argmax(row > -0.014)]

    moved = gauge_face(stock.z[3]) - gauge_face(stock.z[0])
    expected = design.entry_tangent * 8.0 + 64.0 / (2 * design.radius)
    assert moved == pytest.approx(expected, abs=3e-4)


def test_crossing_nose_widens_at_1_in_n_and_is_low_at_its_tip():
    design = CrossingDesign()
    grid = lateral_grid(0.70, 0.90)
    x = design.nose_tip + np.array([-0.1, 0.0, 0.25, 0.75])
    sections = crossing_sections(design, upright_uic60(), x, grid)
    nose = sections["nose"].z
    assert np.all(np.isnan(nose[0]))
    top = np.nanmax(nose[1:], axis=1)
    # tip: 3 mm design lowering plus the narrow head's own drop; full height 0.5 m after
    assert top[0] < -0.003 and top[0] < top[1] < top[2]
    assert top[2] == pytest.approx(0.0, abs=2e-4)
    # the wing rail's gauge face has left the running line by (x - throat) / N
    wing = sections["wing"].z
    throat = design.nose_tip - design.crossing_number * (design.tip_width + design.flangeway)
    face = grid[np.argmax(wing[3] > -0.014)] - grid[np.argmax(wing[0] > -0.014)]
    assert face == pytest.approx((x[3] - x[0]) / design.crossing_number, abs=3e-4)
    assert throat < x[0]


@pytest.fixture(scope="module")
def plain_table(tmp_path_factory):
    settings = TableSettings(shift_min=-0.008, shift_max=0.008, shift_step=4e-4)
    cache = tmp_path_factory.mktemp("tables")
    wheel = s1002_wheel(SETUP)
    track = standard_track(SETUP)
    table = build_contact_table(wheel, track, SETUP.taping_line, settings, cache_dir=cache)
    return wheel, track, settings, cache, table


def test_table_cache_is_keyed_by_the_inputs(plain_table):
    wheel, track, settings, cache, table = plain_table
    assert table.build_seconds > 0.0
    again = build_contact_table(wheel, track, SETUP.taping_line, settings, cache_dir=cache)
    assert again.build_seconds == 0.0
    np.testing.assert_array_equal(again.values, table.values)
    assert len(list(cache.glob("*.npz"))) == 1
    other = TableSettings(shift_min=-0.008, shift_max=0.008, shift_step=4e-4, young=2.0e11)
    assert table_key(wheel, track, SETUP.taping_line, other) != table.key
    assert table_key(wheel, track, SETUP.taping_line + 1e-4, settings) != table.key


def test_lookup_matches_the_direct_search_on_and_between_nodes(plain_table):
    wheel, track, _settings, _cache, table = plain_table
    row = rail_row(track, surface_derivatives(track))
    shifts = np.array([0.0, 0.0012, 0.0031, -0.0027, 0.0049])
    lifts = np.array([-3e-4, -2.5e-4, 0.0, -2e-4, -3e-4])  # touching at about -0.18 mm
    found = lookup(table, np.full(len(shifts), 0.5), shifts, lifts)
    for k, (shift, lift) in enumerate(zip(shifts, lifts)):
        direct = find_candidates(
            *row, wheel, SETUP.taping_line, shift=shift, lift=lift, max_gap=0.005
        )
        first = int(np.argmin(found.gap[k]))
        # normal gap within 3 micrometres, contact point within 0.5 mm, angle 0.5 deg
        assert found.gap[k, first] == pytest.approx(direct.gap[0], abs=3e-6)
        # (the lookup's positions are the force centre's on the rail surface; its deepest
        # point, the centre's law moved back along the tangent and normal, is compared)
        index = {name: i for i, name in enumerate(table.fields)}
        node = lookup_values(table, [0.5], [shift], [lift])[0, first]
        centre = found.centre[k, first]
        offset = node_offset(node[index["patch_offset_c2"]], node[index["patch_offset_c3"]], centre)
        gamma = found.angle[k, first]
        along, _up = centre_point(centre, offset, np.sin(gamma), np.cos(gamma))
        deepest = found.y_rail[k, first] - along
        assert deepest == pytest.approx(direct.y_rail[0], abs=5e-4)
        assert math.degrees(found.angle[k, first]) == pytest.approx(
            math.degrees(direct.angle[0]), abs=0.5
        )
    forces = normal_force(found)
    # the nodes' law N_ref (delta / DELTA_REF)^n (nonhertz), Hertz's C_H delta^1.5 where n
    # is 1.5 at all four nodes
    penetration = np.maximum(-found.gap, 0.0)
    expected = found.patch_force * (penetration / DELTA_REF) ** found.force_exponent
    np.testing.assert_allclose(forces, np.where(found.valid, expected, 0.0), rtol=1e-12)
    hertz = found.valid & (found.force_exponent == 1.5)
    assert np.any(hertz & (penetration > 0.0))
    np.testing.assert_allclose(
        forces[hertz], (found.hertz_constant * penetration**1.5)[hertz], rtol=1e-9
    )
    assert forces[0].sum() > 0.0 and np.all(forces[~found.valid] == 0.0)
