"""The turnout layout of the FE model ([layout] of the turnout file) and its consistency.

Reference values and their sources:
- a circle of radius R + 0.75 m tangent at the toe (R = 760 m, the turnout's name) is
  at y = 0.75 - ((R + 0.75) - sqrt((R + 0.75)^2 - x^2)): hand values -0.540 m at
  44.29 m (start of the crossing panel, paper Section 2) and -0.750 m at 47.749 m, the
  rail-centre crossing point (inside the crossing panel 44.29-51.52 m); the right rail
  (radius R - 0.75) is at -0.816 m at 10 m and -2.253 m at 47.749 m;
- the file's [[zones]] rail_y (cross-sections of the co-running model: zone 1 r1 = -0.75
  m where the wheel runs on it, checked at 3 m before the load transfer; zone 2
  r1 = -2.25 m, r2 = -0.75 m, r3 = 0.68 m, r4 = 0.75 m, sleeper_y = -0.75 m)
  and rail_types per slot (Table 3): the layout must agree with them;
- sleeper length table of the file (2.5 m plain track, 4.06 m crossing panel, Table 1).
"""

import copy
import dataclasses

import numpy as np
import pytest

from exudyn_turnout.fe.layout import load_layout
from exudyn_turnout.fe.mesh import build_mesh
from exudyn_turnout.inputs.turnout import TurnoutFileError


@pytest.fixture(scope="module")
def layout(turnout):
    return load_layout(turnout)


@pytest.mark.parametrize(
    "rail,x,y",
    [
        ("curved", 44.29, -0.540),
        ("curved", 47.749, -0.750),
        ("stock_right", 10.0, -0.816),
        ("stock_right", 47.749, -2.253),
        ("stock_right", -3.0, -0.75),
        ("stock_left", 30.0, 0.75),
        ("check_through", 47.0, 0.68),
    ],
)
def test_rail_positions(layout, rail, x, y):
    assert layout.rail_y(rail, x) == pytest.approx(y, abs=0.001)


@pytest.mark.parametrize("zone_index,x", [(1, 3.0), (2, 47.749), (3, 55.0)])
def test_slots_agree_with_zones(turnout, layout, zone_index, x):
    """Every active slot's rail sits at the zone's rail_y (10 mm) and has its rail type."""
    zone = turnout.zone(zone_index)
    for slot in zone.active_rails:
        rail = layout.slot_rail(slot, x)
        assert layout.rail_y(rail, x) == pytest.approx(zone.rail_y[slot], abs=0.01), slot
        assert layout.rail(rail).segment_at(x).rail_type == zone.rail_types[slot], slot


def test_bearers_follow_the_sleeper_table(turnout, layout):
    mesh = build_mesh(turnout, layout)
    not_bearer = np.array(mesh.sleeper_track) != "turnout"

    def bearer_near(x):
        """Index of the turnout bearer nearest to x (other tracks' sleepers penalised)."""
        return int(np.argmin(np.abs(mesh.sleeper_x - x) + not_bearer))

    plain, crossing = bearer_near(-3.0), bearer_near(47.7)
    assert mesh.sleeper_length[plain] == pytest.approx(2.5) and mesh.sleeper_centre[
        plain
    ] == pytest.approx(0.0)
    assert mesh.sleeper_length[crossing] == pytest.approx(4.06)
    assert mesh.sleeper_centre[crossing] == pytest.approx(turnout.zone(2).sleeper_y, abs=0.05)
    assert (
        "diverging" in mesh.sleeper_track
    )  # the diverging track's own sleepers after the crossing


@pytest.mark.parametrize(
    "slot,x,message",
    [
        ("r2", -2.0, "rail r2 is not present at x = -2 m"),
        ("r3", 30.0, "rail r3 is not present"),
        ("r1", 70.0, "outside the FE model"),
    ],
)
def test_slot_errors(layout, slot, x, message):
    with pytest.raises(ValueError, match=message):
        layout.slot_rail(slot, x)


def _broken(turnout, edit):
    raw = copy.deepcopy(dict(turnout.raw))
    edit(raw["layout"])
    return dataclasses.replace(turnout, raw=raw)


@pytest.mark.parametrize(
    "edit,field",
    [
        (lambda s: s["rails"][2].update(route="divergent"), "layout.rails[3].route must be one of"),
        (
            lambda s: s["rails"][0]["segments"][0].update(type="steel"),
            "layout.rails[1].segments[1].type",
        ),
        (lambda s: s["rails"][3].update(end_joins="nowhere"), "layout.rails[4].end_joins"),
        (
            lambda s: s["slots"]["through"].update(r2=[{"rail": "straight", "x": [-3.0, 10.0]}]),
            "layout.slots.through.r2[1].x",
        ),
        (lambda s: s["diverging"].pop("radius"), "layout.diverging.radius is missing"),
        (lambda s: s["fits"]["K_sw"].update(rail="nope"), "layout.fits.K_sw.rail"),
    ],
)
def test_file_errors_name_file_and_field(turnout, edit, field):
    with pytest.raises(
        TurnoutFileError,
        match="uic60_760_1_15.toml: " + field.replace("[", r"\[").replace("]", r"\]"),
    ):
        load_layout(_broken(turnout, edit))


def test_missing_section(turnout):
    raw = {k: v for k, v in turnout.raw.items() if k != "layout"}
    with pytest.raises(TurnoutFileError, match="layout is missing"):
        load_layout(dataclasses.replace(turnout, raw=raw))


def test_too_short_sleeper_is_an_error(turnout, layout):
    sleeper = dataclasses.replace(
        turnout.sleeper, length=dataclasses.replace(turnout.sleeper.length, value=(2.5,) * 7)
    )
    with pytest.raises(TurnoutFileError, match="sleeper.length = 2.5 m at x = .* is too short"):
        build_mesh(dataclasses.replace(turnout, sleeper=sleeper), layout)
