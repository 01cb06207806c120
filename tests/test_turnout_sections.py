"""The turnout's rail bodies from its design data: sections per route, transfer, tables.

Packaged turnout UIC60-760-1:15 (its plan: nose tip 46.90 m, 1:16.26) with the S1002 wheel
and UIC60 1:40 rail of the Manchester benchmark, standard gauge 1435 mm, back to back
1360 mm (``WheelsetSetup()``).
"""

from dataclasses import replace

import numpy as np
import pytest

from exudyn_turnout.inputs.geometry import turnout_plan
from exudyn_turnout.inputs.routes import load_route
from exudyn_turnout.inputs.turnout import TurnoutFileError, default_turnout_path, load_turnout
from exudyn_turnout.wheel_rail.data import s1002_wheel, standard_track
from exudyn_turnout.wheel_rail.geometry import WheelsetSetup
from exudyn_turnout.wheel_rail.handovers import handover_windows, route_transfers, table_rest_path
from exudyn_turnout.wheel_rail.sections import sections_at
from exudyn_turnout.wheel_rail.tables import TableSettings, build_contact_table, lookup
from exudyn_turnout.wheel_rail.turnout_design import rail_geometry
from exudyn_turnout.wheel_rail.turnout_sections import (
    envelope_sections,
    route_contact_tables,
    route_rail_bodies,
)

SETUP = WheelsetSetup()
ROUTES = ("through", "diverging")


@pytest.fixture(scope="module")
def turnout():
    return load_turnout()


@pytest.fixture(scope="module")
def bodies(turnout):
    return {route: route_rail_bodies(turnout, route) for route in ROUTES}


@pytest.fixture(scope="module")
def wheel():
    return s1002_wheel(SETUP)


def _with_raw(turnout, **sections):
    raw = dict(turnout.raw)
    raw.update(sections)
    return replace(turnout, raw=raw)


@pytest.mark.parametrize("route", ROUTES)
def test_every_body_has_rail_over_its_contact_range(turnout, bodies, route):
    pairs = load_route(turnout, route).pairs
    assert len(bodies[route]) == len(pairs)
    for body, pair in zip(bodies[route], pairs):
        grid = body.sections
        assert grid.x[0] == body.x_from and grid.x[-1] == body.x_to
        assert np.all(np.diff(grid.x) > 0.0) and len(grid.x) <= 300  # memory budget
        # where the file's height table or check range says the wheel can touch the body,
        # there is rail within 16 mm of the top (a tread or a check-rail face)
        lo, hi = (pair.x[0], pair.x[-1]) if pair.x else pair.check
        x = np.linspace(lo, hi, 50)
        if "nose" in body.name:
            x = x[x >= rail_geometry(turnout).crossing.nose_tip]
        z = sections_at(grid, x)
        assert np.all(np.nanmax(z, axis=1) > -0.016), body.name
        assert body.back_of_flange == (pair.check is not None)


def test_constant_stretches_have_two_nodes_and_changes_have_more(bodies):
    through = {body.name: body for body in bodies["through"]}
    assert len(through["left wheel on left stock rail"].sections.x) == 2
    nose = through["right wheel on crossing nose"].sections.x
    # min_step 10 mm, down to 1 mm where nose and wing rail share the wheel (transfer
    # nodes, section_nodes.TRANSFER_MIN_STEP; the wing rail's nodes kept 0.5 mm apart)
    assert len(nose) > 20 and np.min(np.diff(nose)) >= 0.5e-3 - 1e-9


def test_diverging_route_uses_the_same_design_in_its_own_frame(bodies):
    # mirrored cross-section: the diverging route's left wheel sees what the through
    # route's right wheel sees (a tangential switch and a straight crossing, see the module
    # docstring of turnout_sections for what this neglects)
    for a, b in zip(bodies["through"], bodies["diverging"]):
        assert {a.wheel, b.wheel} == {"left", "right"} or a.wheel == b.wheel
    blade_t, blade_d = bodies["through"][1].sections, bodies["diverging"][1].sections
    np.testing.assert_array_equal(blade_t.x, blade_d.x)
    np.testing.assert_array_equal(blade_t.z, blade_d.z)


@pytest.fixture(scope="module")
def transfers(turnout, bodies, wheel):
    tip = turnout_plan(turnout).nose_tip_x
    return route_transfers(
        turnout,
        "through",
        wheel,
        SETUP,
        shifts=(-0.003, 0.0, 0.003),
        step=0.01,
        bodies=bodies["through"],
        x_ranges={"switch": (3.3, 4.3), "crossing": (tip - 0.15, tip + 0.35)},
    )


def test_load_passes_from_stock_rail_to_blade_after_the_toe(turnout, transfers):
    switch = next(t for t in transfers if t.place == "switch")
    centred = switch.paths[1]
    # the window's ends: the stock rail carries the wheel at its start, the blade at its end
    assert centred.carrier[0] == 1 and centred.carrier[-1] == 0
    design = rail_geometry(turnout).switch
    for summary in switch.summaries:
        # after the toe (plan: toe_x = 0) and before the blade's top is at full height
        assert turnout_plan(turnout).toe_x < summary.transfer_x < design.lowering_length
        # a dip, not a step: the stock rail falls away under the cone while the blade rises
        assert 1e-4 < summary.depth < design.toe_lowering


def test_load_passes_from_wing_rail_to_nose_after_its_tip(turnout, transfers):
    crossing = next(t for t in transfers if t.place == "crossing")
    design = rail_geometry(turnout).crossing
    tip = turnout_plan(turnout).nose_tip_x
    assert design.nose_tip == tip  # the crossing's nose tip is the plan's
    centred = crossing.paths[1]
    assert centred.carrier[0] == 1 and centred.carrier[-1] == 0
    transfer = [summary.transfer_x for summary in crossing.summaries]
    for x in transfer:
        # the 12 mm tip is 3 mm low: the nose takes the wheel after its tip, before it
        # reaches full height
        assert tip < x < tip + design.lowering_length
    # towards the field side the tread meets the widening nose earlier (as on the UK
    # crossing, tests/test_wheel_rail_transfer.py)
    assert transfer[2] < transfer[1] <= transfer[0]
    assert all(s.dip_angle > 1e-3 for s in crossing.summaries)


@pytest.fixture(scope="module")
def small_route(turnout):
    # the through route with only its plain left stock rail and its check rail: the two
    # bodies the next checks need, built in ~2 s
    raw = {k: v for k, v in turnout.raw["routes"]["through"].items()}
    contacts = raw["contacts"]
    raw["contacts"] = [c for c in contacts if c.get("rail") in ("r4", "r3")]
    raw.pop("continues", None)
    routes = dict(turnout.raw["routes"])
    routes["through"] = raw
    return _with_raw(turnout, routes=routes)


@pytest.fixture(scope="module")
def small_tables(small_route, wheel, tmp_path_factory):
    cache = tmp_path_factory.mktemp("tables")
    first = route_contact_tables(small_route, "through", wheel, SETUP, cache_dir=cache)
    second = route_contact_tables(small_route, "through", wheel, SETUP, cache_dir=cache)
    return first, second


def test_tables_are_cached_on_disk(small_tables):
    first, second = small_tables
    for (_body, built), (_, loaded) in zip(first, second):
        assert built.build_seconds > 0.0 and loaded.build_seconds == 0.0
        assert built.key == loaded.key
        np.testing.assert_array_equal(built.values, loaded.values)


def test_plain_body_reproduces_the_plain_track_table(small_tables, wheel, tmp_path):
    body, table = small_tables[0][0]
    assert not body.back_of_flange
    reference = build_contact_table(
        wheel, standard_track(SETUP), SETUP.taping_line, cache_dir=tmp_path
    )
    np.testing.assert_allclose(table.shift, reference.shift)
    # the same profile and grid (up to the grid origin's last bit), so the same numbers
    np.testing.assert_allclose(table.values[0], reference.values[0], rtol=1e-9, atol=1e-12)


def test_check_rail_face_stands_at_the_clearance_from_the_flange_back(small_route, small_tables):
    body, table = small_tables[0][1]
    geometry = rail_geometry(small_route)
    clearance = geometry.check_rail.clearance  # [check_rail] clearance, 4 mm
    assert body.back_of_flange
    middle = 0.5 * (body.x_from + body.x_to)  # away from the flared ends
    z = sections_at(body.sections, np.array([middle]))[0]
    top = np.nanmax(z)
    face = body.sections.y[np.isfinite(z) & (z >= top - 0.014)].max()
    # face (14 mm below its top) = back of the flange of a centred wheelset - clearance
    assert face == pytest.approx(0.5 * geometry.back_to_back - clearance, abs=2e-4)
    centred = lookup(table, [middle], [0.0])
    touching = lookup(table, [middle], [-clearance])
    # the S1002 file's back of the flange is at -69.6 mm from the taping line (not -70) and
    # not quite vertical: 0.5 mm allowed on the normal gap
    assert centred.gap[0, 0] == pytest.approx(clearance, abs=5e-4)
    assert touching.gap[0, 0] == pytest.approx(0.0, abs=5e-4)
    assert np.degrees(centred.angle[0, 0]) < -60.0  # back of the flange: towards the field


@pytest.mark.parametrize(
    "section, field",
    [
        ({"inclination": "steep"}, "wheel_rail.inclination"),
        ({"gauge": -1.435}, "wheel_rail.gauge"),
        ({"switch": {"toe_lowering": 0.5}}, "wheel_rail.switch.toe_lowering"),
        ({"crossing": {"flangeway": "wide"}}, "wheel_rail.crossing.flangeway"),
        ({"check_rail": {"colour": 1}}, "wheel_rail.check_rail.colour"),
        ({"profile": "no_such_rail.prr"}, "wheel_rail.profile"),
    ],
)
def test_bad_wheel_rail_values_name_the_field(turnout, section, field):
    with pytest.raises(TurnoutFileError) as err:
        rail_geometry(_with_raw(turnout, wheel_rail=section))
    message = str(err.value)
    assert "\n" not in message and field in message and "uic60_760_1_15.toml" in message


@pytest.mark.parametrize(
    "sections, problem",
    [
        ([{"kind": "bogus", "x": [-5.0, 60.0]}], "kind"),
        ([{"kind": "plain", "x": [-5.0, 10.0]}, {"kind": "plain", "x": [11.0, 60.0]}], "start"),
        ([{"kind": "plain", "x": [0.0, 60.0]}], "cover"),
        ([{"kind": "plain", "x": ["nose_top", 60.0]}], "feature"),
    ],
)
def test_bad_sections_name_the_contact(turnout, sections, problem):
    routes = dict(turnout.raw["routes"])
    through = dict(routes["through"])
    contacts = [dict(c) for c in through["contacts"]]
    contacts[4]["sections"] = sections  # the left stock rail, -5..60 m
    through["contacts"] = contacts
    routes["through"] = through
    with pytest.raises(TurnoutFileError) as err:
        route_rail_bodies(_with_raw(turnout, routes=routes), "through")
    message = str(err.value)
    assert "\n" not in message and "routes.through.contacts[4].sections" in message
    assert problem in message


def test_geometry_figures_are_written(transfers, bodies, wheel, tmp_path):
    from exudyn_turnout.plotting.wheel_rail import (
        plot_body_sections,
        plot_contact_band_along_x,
        plot_dip,
    )

    crossing = next(t for t in transfers if t.place == "crossing")
    centred = crossing.paths[1]
    band = plot_contact_band_along_x(
        centred.x,
        centred.y_rail,
        centred.y_rail - SETUP.taping_line,
        np.where(centred.carrier == 0, "nose", "wing rail"),
        tmp_path / "band.png",
        x_ranges=[(centred.x[0], centred.x[-1])],
    )
    dip = plot_dip(list(crossing.paths), list(crossing.summaries), tmp_path / "dip.png")
    nose = bodies["through"][2]
    sections = plot_body_sections(
        [nose.sections],
        [nose.name],
        [nose.x_from + 0.2],
        wheel,
        SETUP.taping_line,
        tmp_path / "sections.png",
    )
    for path in (band, dip, sections):
        assert path.exists() and path.stat().st_size > 10_000


# --- no geometry step where one rail body hands the wheel to the next ---------------------

#: m, x step of the rest-height check
STEP = 0.005
#: m, largest step allowed: a change of the rest height over one 5 mm step that differs
#: from the changes over both neighbouring steps by more than this.  A slope (the wheel's
#: fall along the wing rail: up to 9 mrad, 0.045 mm per step, on the 1:9 crossing) or a
#: kink (a dip's bottom) changes neighbouring steps alike and passes; a step does not.
#: 0.02 mm: 1/14 of the step the upright nose made where the inclined plain rail took over
#: (0.28 mm from the tables, 0.36 mm from the sections, without the twist), and above what
#: the tables leave inside the twist, where the contact point jumps in a cell they hold
#: (0.017 mm with nodes every 1/1200 of tilt, turnout_sections._TWIST_STEP)
STEP_TOLERANCE = 2e-5
#: m, lateral shifts of the check: the centred wheel, queried in the middle of the tables'
#: two 0.2 mm shift cells next to zero (exactly at zero a query falls into either cell by
#: the last bit of the shift grid, and the two cells may blend differently)
SHIFTS = (-1e-4, 1e-4)
PACKAGED = (
    ("uic60_760_1_15.toml", "through"),
    ("uic60_760_1_15.toml", "diverging"),
    ("ew54_190_1_9.toml", "main"),
    ("ew54_190_1_9.toml", "branch"),
)


def packaged_path(name):
    return default_turnout_path().parent / name


def _steps(height):
    """Per 5 mm step: how much its change differs from both neighbouring steps' (m)."""
    d = np.diff(height)
    inner = np.minimum(np.abs(d[1:-1] - d[:-2]), np.abs(d[1:-1] - d[2:]))
    return np.concatenate(([0.0], inner, [0.0]))


def _window_tables(bodies, geometry, wheel, side, lo, hi, cache):
    """(body, table) of every running-rail body of a wheel, built on its x nodes over [lo, hi].

    The same enveloped sections at the same nodes as :func:`route_contact_tables`, with the
    shifts -1..1 mm of the full table's 0.2 mm grid: at zero shift its cells are the full
    table's cells (a table's values at a node do not depend on the other nodes).
    """
    settings = TableSettings(shift_min=-0.001, shift_max=0.001)
    pairs = []
    for body in bodies:
        if body.wheel != side or body.back_of_flange:
            continue
        a, b = max(lo, body.x_from), min(hi, body.x_to)
        if a > b:
            continue
        nodes = body.sections.x
        first = max(int(np.searchsorted(nodes, a, side="right")) - 1, 0)
        last = min(int(np.searchsorted(nodes, b, side="left")), len(nodes) - 1)
        part = envelope_sections(
            body, geometry, SETUP.nominal_radius, nodes[first : max(last, first + 1) + 1]
        )
        table = build_contact_table(wheel, part, SETUP.taping_line, settings, cache)
        pairs.append((body, table))
    return pairs


def _largest_steps(turnout, route, wheel, cache):
    """Per wheel and hand-over window: (window, largest step (m), its x)."""
    geometry = rail_geometry(turnout)
    bodies = route_rail_bodies(turnout, route)
    out = []
    for side in ("left", "right"):
        for lo, hi in handover_windows(bodies, side, geometry):
            x = np.round(np.arange(lo, hi + 0.5 * STEP, STEP), 9)
            pairs = _window_tables(bodies, geometry, wheel, side, lo, hi, cache)
            for shift in SHIFTS:
                path = table_rest_path(pairs, side, x, shift)
                assert np.all(np.isfinite(path.height)), (route, side, lo, hi)  # rail under it
                steps = _steps(path.height)
                i = int(np.argmax(steps))
                out.append((side, (lo, hi), float(steps[i]), float(x[i])))
    return out


@pytest.fixture(scope="module")
def table_cache(tmp_path_factory):
    return tmp_path_factory.mktemp("handover_tables")


@pytest.mark.parametrize("name, route", PACKAGED)
def test_no_rest_height_step_where_a_body_hands_over(name, route, wheel, table_cache):
    turnout = load_turnout(packaged_path(name))
    found = _largest_steps(turnout, route, wheel, table_cache)
    # the wheel that runs over blade and nose has its hand-overs: plain -> stock rail, toe,
    # stock rail's end, blade -> closure -> wing rail, nose's start, wing rail's end, the
    # nose's twist and its end where the plain rail takes over
    assert len(found) >= 6 * len(SHIFTS)
    for side, window, step, x in found:
        assert step <= STEP_TOLERANCE, f"{name} {route} {side} {window}: {step:.2e} m at {x}"


def test_the_check_finds_the_step_without_the_twist(turnout, wheel, table_cache):
    # inclination_transition = 0: the upright nose ends, the inclined plain rail begins
    raw = dict(turnout.raw["wheel_rail"])
    raw["crossing"] = {**raw.get("crossing", {}), "inclination_transition": 0.0}
    stepped = _with_raw(turnout, wheel_rail=raw)
    found = _largest_steps(stepped, "through", wheel, table_cache)
    end = [step for _side, (lo, hi), step, _x in found if lo < 51.0 < hi]
    assert end and min(end) > 10 * STEP_TOLERANCE  # 0.28 mm measured from the tables


@pytest.mark.parametrize("name, route", PACKAGED)
def test_nose_ends_with_the_plain_rails_section(name, route):
    turnout = load_turnout(packaged_path(name))
    bodies = route_rail_bodies(turnout, route)
    noses = [b for b in bodies if b.segments[-1].kind == "nose"]
    plain = {(b.wheel, b.x_from): b for b in bodies if b.segments[0].kind == "plain"}
    assert noses
    for nose in noses:
        after = plain[(nose.wheel, nose.x_to)]  # the plain rail that takes the wheel over
        np.testing.assert_array_equal(nose.sections.z[-1], after.sections.z[0])
        # and the nose is upright until its twist begins (the section at the tip region
        # differs from the inclined rail's)
        start = nose.x_to - rail_geometry(turnout).crossing.inclination_transition
        before = sections_at(nose.sections, np.array([start - 0.01]))[0]
        assert not np.allclose(before, after.sections.z[0], equal_nan=True)


def test_twist_longer_than_the_nose_names_the_field(turnout):
    raw = dict(turnout.raw["wheel_rail"])
    raw["crossing"] = {**raw.get("crossing", {}), "inclination_transition": 5.0}
    with pytest.raises(TurnoutFileError) as err:
        route_rail_bodies(_with_raw(turnout, wheel_rail=raw), "through")
    message = str(err.value)
    assert "\n" not in message and "wheel_rail.crossing.inclination_transition" in message
