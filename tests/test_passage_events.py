"""Events taken from the geometry: the crossing nose and the check rail (passage/events.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_turnout.inputs.geometry import turnout_plan
from exudyn_turnout.inputs.routes import load_route, route_names
from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage.events import (
    NOSE_AFTER,
    NOSE_BEFORE,
    check_rail_event,
    event_line,
    event_summary,
    nose_region,
)

TURNOUTS = ("uic60_760_1_15.toml", "ew54_190_1_9.toml")


def _turnout(name):
    from exudyn_turnout.inputs.turnout import default_turnout_path

    return load_turnout(default_turnout_path().parent / name)


@pytest.mark.parametrize("name", TURNOUTS)
def test_check_rail_entry_is_not_inside_the_nose_region(name):
    # Issue 23: the diverging "crossing" peak of the report was the check rail's entry
    # impact, 1.7 m before the nose tip, inside the file's crossing region.  The nose event
    # must not hold any check rail's entry flare.
    turnout = _turnout(name)
    lo, hi = nose_region(turnout)
    tip = turnout_plan(turnout).nose_tip_x
    assert hi == pytest.approx(tip + NOSE_AFTER)
    assert tip - NOSE_BEFORE <= lo < tip
    for route in route_names(turnout):
        event = check_rail_event(turnout, route)
        assert event is not None  # both packaged turnouts have a check rail on each route
        entry = event["entry_m"]
        assert entry[1] <= lo, (route, entry, lo)
        pair = [p for p in load_route(turnout, route).pairs if p.check][0]
        assert event["wheel"] == pair.wheel and event["rail"] == pair.rail


def _columns(x, t, fy_check, fz_check, fz_wheel):
    zero = np.zeros_like(x)
    return {
        "t_s": t,
        "x_m": x,
        "Fz_right_N": fz_wheel,
        "Fy_right_N": fy_check,
        "Fz_left_N": 50e3 + zero,
        "Fy_left_N": zero,
        "Fy_right_r3_N": fy_check,
        "Fz_right_r3_N": fz_check,
    }


def test_check_rail_event_on_a_known_pulse():
    turnout = _turnout(TURNOUTS[0])  # diverging: right wheel against r3, 44.29-51 m
    v = 80 / 3.6
    x = np.linspace(40.0, 50.0, 20001)
    t = (x - x[0]) / v
    # a triangular pulse of 60 kN on the check rail, 0.2 m long (9 ms), peak at 45.2 m:
    # impulse = 0.5 * 60e3 * 0.2 / v N s
    fy = np.clip(1.0 - np.abs(x - 45.2) / 0.1, 0.0, None) * 60e3
    fz_check = 0.1 * fy
    fz_wheel = 55e3 - 0.9 * fy + fz_check  # the tread unloads to 1 kN at the peak
    s = event_summary(
        _columns(x, t, fy, fz_check, fz_wheel), turnout, "diverging", {"left": 55e3, "right": 55e3}
    )
    assert s["check_rail_wheel"] == "right" and s["check_rail_rail"] == "r3"
    assert s["peak_Fy_check_rail_N"] == pytest.approx(60e3, rel=1e-3)
    assert s["peak_Fy_check_rail_x_m"] == pytest.approx(45.2, abs=1e-3)
    assert s["check_rail_impulse_Ns"] == pytest.approx(0.5 * 60e3 * 0.2 / v, rel=1e-3)
    assert s["check_rail_min_tread_Fz_N"] == pytest.approx(1e3, rel=1e-2)
    assert s["check_rail_tread_unloaded"] is False  # 1 kN > 1 % of 55 kN
    line = event_line(s)
    assert line is not None and "peak Fy +60.0 kN at x = 45.20 m" in line
    # the tread fully unloaded
    s = event_summary(
        _columns(x, t, fy, fz_check, fz_wheel - 1e3),
        turnout,
        "diverging",
        {"left": 55e3, "right": 55e3},
    )
    assert s["check_rail_tread_unloaded"] is True
    assert "tread unloaded" in event_line(s)
    # the nose region's peaks are taken within it only (the check-rail pulse is outside)
    assert s["peak_Fy_nose_N"] == pytest.approx(0.0, abs=1e-6)


def test_event_outside_the_run_is_nan():
    turnout = _turnout(TURNOUTS[0])
    x = np.linspace(0.0, 10.0, 101)
    t = x / 20.0
    s = event_summary(
        _columns(x, t, 0 * x, 0 * x, 50e3 + 0 * x),
        turnout,
        "diverging",
        {"left": 5e4, "right": 5e4},
    )
    assert math.isnan(s["peak_Fy_check_rail_N"]) and math.isnan(s["peak_Fz_nose_N"])
    assert event_line(s) is None
    # a run through the check rail that never touches it
    x = np.linspace(40.0, 50.0, 101)
    s = event_summary(
        _columns(x, x / 20.0, 0 * x, 0 * x, 50e3 + 0 * x),
        turnout,
        "diverging",
        {"left": 5e4, "right": 5e4},
    )
    assert event_line(s) == "check rail (right wheel, r3, 44.29-51 m): no contact"
