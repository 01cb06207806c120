"""The model drawings: cross-section geometry as built by Exudyn, its figure, the passage GIF."""

import matplotlib

matplotlib.use("Agg")

import exudyn as exu
import matplotlib.pyplot as plt
import numpy as np
import pytest
from PIL import Image

from exudyn_turnout.corunning import track
from exudyn_turnout.corunning.cross_section import cross_section_springs
from exudyn_turnout.corunning.parameters import co_running_parameters
from exudyn_turnout.inputs.routes import load_route
from exudyn_turnout.inputs.vehicle import load_vehicle
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings
from exudyn_turnout.plotting.model import (
    animate_passage,
    cross_section_geometry,
    draw_cross_section,
    entry_symbol,
    format_damping,
    format_stiffness,
    passage_frames,
    spring_label,
)

CASES = [(zone, layers) for zone in (1, 2, 3) for layers in (2, 3)]


def _x_in(turnout, zone):
    z = turnout.zone(zone)
    return 0.5 * (z.x_start + z.x_end) + 0.123


def _marker_y(mbs, marker):
    """Model lateral position (m) of a marker: body reference + local position, or the node's."""
    m = mbs.GetMarker(marker)
    if "localPosition" in m:
        body = mbs.GetObject(m["bodyNumber"])
        ref = (
            body["referencePosition"][0]
            if body["objectType"] == "Ground"
            else mbs.GetNode(body["nodeNumber"])["referenceCoordinates"][0]
        )
        return float(ref + m["localPosition"][0])
    return float(mbs.GetNode(m["nodeNumber"])["referenceCoordinates"][0])


def _built(params, x):
    """Exudyn system of the co-running track as the passage builds it (constant springs)."""
    mbs = exu.SystemContainer().AddSystem()
    handles = track.add_co_running_track(mbs, params, x, 0.0, mechanism="constant")
    mbs.Assemble()
    return mbs, handles


@pytest.mark.parametrize("zone,layers", CASES)
def test_geometry_lists_the_springs_exudyn_builds(turnout, zone, layers):
    x = _x_in(turnout, zone)
    params = co_running_parameters(turnout, zone=zone, layers=layers)
    geo = cross_section_geometry(params, x)
    mbs, handles = _built(params, x)
    n_objects = mbs.systemData.NumberOfObjects()
    springs = [
        i
        for i in range(n_objects)
        if mbs.GetObject(i)["objectType"] == "ConnectorCartesianSpringDamper"
    ]
    assert (
        geo.connectors
        == tuple(s.name for s in cross_section_springs(params))
        == tuple(handles.connectors)
    )
    assert len(geo.connectors) == len(springs)
    for spring in geo.springs:  # stiffness, damping and attachment points of the built object
        obj = mbs.GetObject(handles.connectors[spring.name])
        axis = {"y": 0, "z": 1}[spring.direction]
        assert obj["stiffness"][axis] == pytest.approx(spring.k, rel=1e-12)
        assert obj["damping"][axis] == pytest.approx(spring.c, rel=1e-12)
        assert spring.attach_y == pytest.approx(
            tuple(_marker_y(mbs, m) for m in obj["markerNumbers"])
        )
    for name in geo.connectors:  # every direction the object acts in is drawn, and no other
        obj = mbs.GetObject(handles.connectors[name])
        built = {d for d, axis in (("y", 0), ("z", 1)) if obj["stiffness"][axis] > 0}
        assert {s.direction for s in geo.springs if s.name == name} == built
    rails = tuple(r for r in ("r1", "r2", "r3", "r4") if r in params.active_rails)
    names = {b.name for b in geo.bodies}
    assert names == {
        "ground",
        "sleeper",
        *rails,
        *([f"m0_{r}" for r in rails] if layers == 3 else []),
    }


@pytest.mark.parametrize("zone,layers", [(2, 3), (1, 2)])
def test_labels_carry_the_values_at_x(turnout, zone, layers):
    x = _x_in(turnout, zone)
    params = co_running_parameters(turnout, zone=zone, layers=layers)
    values = params.at(x)
    vehicle = load_vehicle()
    geo = cross_section_geometry(params, x, route="through", vehicle=vehicle)
    ax = draw_cross_section(params, x, route="through", vehicle=vehicle)
    text = "\n".join(t.get_text() for t in ax.texts)
    for s in geo.springs:
        assert s.k == values[s.k_name] and s.c == values[s.c_name]
        assert f"{entry_symbol(s.k_name)} = {format_stiffness(values[s.k_name])}" in text
        assert f"{entry_symbol(s.c_name)} = {format_damping(values[s.c_name])}" in text
        assert format_stiffness(s.k) in spring_label(s) and format_damping(s.c) in spring_label(s)
    for r in params.active_rails:
        assert f"{entry_symbol('m_' + r)} = {values['m_' + r]:.4g} kg" in text
        assert f"y = {params.zone.rail_y[r]:.3g} m" in text
    assert f"{values['m_t']:.4g} kg" in text and f"{values['J_t']:.4g} kg m$^2$" in text
    assert f"{format_stiffness(vehicle.k_z)}" in text and f"{vehicle.m_s:.4g} kg" in text
    title = ax.get_title()
    for part in (
        turnout.name,
        f"zone {zone}",
        f"x = {x:g} m",
        f"{layers}-layer",
        "derived",
        "through",
    ):
        assert part in title
    plt.close(ax.figure)


def test_value_formats():
    assert format_stiffness(3.69426e8) == "369 MN/m"
    assert format_stiffness(1.0767e9) == "1077 MN/m"
    assert format_damping(76963.8) == "77 kN s/m"
    assert format_damping(1345749.07) == "1346 kN s/m"
    assert entry_symbol("k_rt2_z") == "$k_{rt2,z}$" and entry_symbol("k_tg_y") == "$k_{tg,y}$"
    assert entry_symbol("m_0") == "$m_{0}$"


def test_close_rails_are_drawn_apart_at_their_model_positions(turnout):
    params = co_running_parameters(turnout, zone=1, layers=3)
    geo = cross_section_geometry(params, 3.0, min_gap=1.0)
    r1, r2, r4 = (geo.body(r) for r in ("r1", "r2", "r4"))
    assert r1.y == r2.y == -0.75 and r4.y == 0.75  # model positions kept
    assert r2.y_drawn - r1.y_drawn == pytest.approx(1.0) and r4.y_drawn - r2.y_drawn >= 1.0 - 1e-9
    assert set(geo.spread_rails) == {"r1", "r2"} and r4.y_drawn == 0.75
    pad = next(s for s in geo.springs if s.name == "pad_r2" and s.direction == "z")
    assert pad.from_point[0] == pad.to_point[0] == r2.y_drawn  # vertical spring under its rail
    ballast = [s for s in geo.springs if s.name.startswith("ballast_z")]
    assert [s.attach_y[0] for s in ballast] == list(params.zone.ballast_y)


def test_route_positions_and_contacts(turnout):
    params = co_running_parameters(turnout, zone=2, layers=3)
    route = load_route(turnout, "diverging")
    geo = cross_section_geometry(params, 47.5, route=route, vehicle=load_vehicle())
    assert geo.route == "diverging" and geo.body("r3").y == route.rail_y["r3"]
    assert {(c.wheel, c.rail, c.body) for c in geo.contacts} == {
        ("left", "r2", "m0_r2"),
        ("right", "r1", "m0_r1"),
    }
    assert {s.name for s in geo.suspension} == {"primary_left", "primary_right"}


def test_cross_section_figure_saves_as_png(turnout, tmp_path):
    params = co_running_parameters(turnout, zone=2, layers=3)
    ax = draw_cross_section(params, 47.0, route="through", vehicle=load_vehicle())
    path = tmp_path / "cross_section.png"
    ax.figure.savefig(path, dpi=60)
    plt.close(ax.figure)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_passage_frames():
    assert list(passage_frames(361, every=60)) == [0, 60, 120, 180, 240, 300, 360]
    default = passage_frames(23402)
    assert len(default) <= 150 and default[0] == 0 and len(default) > 140
    with pytest.raises(ValueError):
        passage_frames(0)


@pytest.mark.slow
def test_passage_gif(turnout, tmp_path):
    result = simulate_passage(
        turnout, PassageSettings(x_start=-5.0, x_end=-4.0), vehicle="wheelset"
    )
    n = len(result.columns["t_s"])
    path = animate_passage(result, tmp_path / "passage.gif", every=60, turnout=turnout)
    assert path.read_bytes()[:4] == b"GIF8"
    with Image.open(path) as gif:
        assert gif.n_frames == len(passage_frames(n, every=60)) == int(np.ceil(n / 60))
