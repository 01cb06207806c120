"""One plan geometry for the co-running routes and the FE layout.

Reference values (hand calculation from the file's [layout]: a 760 m circle leaving the
through route tangentially at the toe, standard gauge 1.435 m, gauge lines at +-0.7175 m):
- the diverging left gauge line, a circle of radius R + 0.7175 centred at (0, -R), meets
  the through right gauge line y = -0.7175 where (R + 0.7175)^2 - x^2 = (R - 0.7175)^2,
  i.e. x = sqrt(4 R 0.7175) = sqrt(2181.2) = 46.703 m;
- the crossing angle there: dy/dx = x / sqrt((R + 0.7175)^2 - x^2) = 1 / 16.26;
- a 12 mm nose tip lies about 0.012 x 16.26 = 0.195 m after the crossing point.
"""

from __future__ import annotations

import math

import pytest

from exudyn_turnout.fe.layout import load_layout
from exudyn_turnout.inputs.geometry import resolve_position, turnout_plan
from exudyn_turnout.inputs.routes import load_route


def test_crossing_point_and_angle_by_hand(turnout):
    plan = turnout_plan(turnout)
    x_cp = math.sqrt(4.0 * 760.0 * 0.7175)
    assert plan.crossing_point_x == pytest.approx(x_cp, abs=1e-6)
    slope = x_cp / math.sqrt((760.0 + 0.7175) ** 2 - x_cp**2)
    assert plan.crossing_angle_n == pytest.approx(1.0 / slope, rel=1e-4)
    assert plan.nose_tip_x - plan.crossing_point_x == pytest.approx(0.012 / slope, rel=0.01)
    assert plan.toe_x == 0.0


@pytest.mark.parametrize("route,wheel", [("through", "right"), ("diverging", "left")])
def test_routes_put_the_nose_where_the_layout_does(turnout, route, wheel):
    """The nose profile starts at the plan's nose tip, on the FE crossing rail, in the zone
    whose slot r2 is the crossing type."""
    plan = turnout_plan(turnout)
    layout = load_layout(turnout)
    nose_pairs = [
        p
        for p in load_route(turnout, route).pairs
        if p.wheel == wheel
        and p.rail == "r2"
        and p.x
        and p.z[0] < 0 < p.z[1] + 1e-12
        and p.x[0] > 10.0
    ]
    assert len(nose_pairs) == 1
    assert nose_pairs[0].x[0] == pytest.approx(plan.nose_tip_x, abs=1e-9)
    zone = turnout.zone_at(plan.nose_tip_x)
    assert zone.rail_types["r2"] == "crossing"
    fe_rail = layout.slot_rail("r2", plan.nose_tip_x, route)
    assert layout.rail(fe_rail).segment_at(plan.nose_tip_x).rail_type == "crossing"
    # the FE rail in slot r2 passes through the through route's inner gauge line there
    assert abs(layout.rail_y(fe_rail, plan.nose_tip_x)) == pytest.approx(0.75, abs=0.01)


def test_position_expressions(turnout):
    plan = turnout_plan(turnout)
    assert resolve_position(3.5, plan) == 3.5
    assert resolve_position("nose_tip - 0.2", plan) == pytest.approx(plan.nose_tip_x - 0.2)
    assert resolve_position("crossing_point", plan) == plan.crossing_point_x
    with pytest.raises(ValueError, match="feature of toe, crossing_point, nose_tip"):
        resolve_position("heel + 1", plan)
    with pytest.raises(ValueError, match="no \\[layout\\]"):
        resolve_position("nose_tip", None)
