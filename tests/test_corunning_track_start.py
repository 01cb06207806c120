"""Co-running runs start where they are (issue 23): in steady curving inside a curve.

Reference values and their sources:
- steady curving: the lateral forces on the rails balance the d'Alembert load
  (m_w + m_s) v^2 / R of the single wheelset (R = 760 m, no cant: the packaged diverging
  route; paper Section 4); the old start (at rest) began with 0.08 kN of the 7.2 kN;
- a window started at 40 m and a run started at 30 m are at the same x in the same steady
  state: the same y and lateral forces before the check rail (measured 2-layer, 80 km/h:
  y 5.228 / 5.228 mm at 44 m, check-rail peak Fy 120.60 / 120.63 kN at 45.26 m; before
  the change 5.060 / 2.150 mm and 121.3 / -1.9 kN, commit 13f0f7d); tolerances of 1 % and
  10 um stand for "the same state" well above the step's round-off;
- on straight track the static state at rest is the start (its residual: what the static
  solve's lateral and spin holds carry), as before the change;
- the warning's criterion: :mod:`exudyn_turnout.passage.vehicle.start` (residual above
  START_TOLERANCE and a region within SETTLING_TIME x v of the start).
"""

import warnings

import numpy as np
import pytest

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.inputs.vehicle import load_vehicle
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings
from exudyn_turnout.passage.vehicle.start import (
    SETTLING_TIME,
    START_TOLERANCE,
    StartWarning,
    unsettled_warning,
)

V = 80.0 / 3.6  #: m/s, the diverging route's permitted speed (turnout file)
R = 760.0  #: m, the diverging route's radius (UIC60-760-1:15)


def _run(turnout, x_start, x_end, layers=2, route="diverging"):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = simulate_passage(
            turnout,
            PassageSettings(
                route=route, speed_kmh=80.0, layers=layers, x_start=x_start, x_end=x_end
            ),
            "wheelset",
            track=f"{layers}-layer",
        )
    return result, [w for w in caught if issubclass(w.category, StartWarning)]


@pytest.mark.parametrize("layers", [2, 3])
def test_a_run_inside_the_curve_starts_in_steady_curving(turnout, layers):
    result, caught = _run(turnout, 40.0, 40.3, layers)
    s, c = result.summary, result.columns
    assert s["start"] == "steady curving at 80 km/h, R = 760 m"
    assert isinstance(s["start_residual"], float) and s["start_residual"] < START_TOLERANCE
    assert not caught
    veh = load_vehicle()
    centrifugal = (veh.m_w + veh.m_s) * V**2 / R  # 7225 N
    first = c["Fy_right_N"][0] + c["Fy_left_N"][0]
    assert first == pytest.approx(centrifugal, rel=0.01)
    # already at rest in the track-following frame: y moves by less than 10 um in 0.3 m
    y = c["y_wheelset_m"]
    assert y[0] > 1e-3  # flanging outwards (to the left of the right-hand curve)
    assert np.max(np.abs(y - y[0])) < 1e-5


@pytest.mark.slow
def test_window_at_40_m_matches_a_run_from_30_m(turnout):
    """Through the check-rail entry (x ~ 45.26 m, the right wheel's back of flange)."""
    early, _ = _run(turnout, 30.0, 45.8)
    late, _ = _run(turnout, 40.0, 45.8)
    for name in ("y_wheelset_m", "yaw_wheelset_rad", "Fy_right_N", "Fy_left_N"):
        x = late.columns["x_m"]
        before = x < 44.2  # the curve ends at 44.29 m
        mine = late.columns[name][before]
        theirs = np.interp(x[before], early.columns["x_m"], early.columns[name])
        scale = np.max(np.abs(theirs))
        assert np.max(np.abs(mine - theirs)) < 0.01 * scale, name
    a, b = early.summary, late.summary
    assert b["max_Fy_crossing_wheel"] == a["max_Fy_crossing_wheel"] == "right"
    assert b["max_Fy_crossing_x_m"] == pytest.approx(a["max_Fy_crossing_x_m"], abs=0.01)
    assert b["max_Fy_crossing_N"] == pytest.approx(a["max_Fy_crossing_N"], rel=0.01)
    assert b["contact_losses"] == a["contact_losses"]


def test_straight_track_starts_static_and_the_switch_start_warns(turnout):
    """At x = 2 m of the through route (inside the switch region, 0-10 m) the static holds
    carry ~420 N (the switch rails are not symmetric): the run warns, naming the region."""
    result, caught = _run(turnout, 2.0, 2.05, route="through")
    s = result.summary
    assert s["start"] == "static at rest"
    assert s["start_residual"] > START_TOLERANCE
    assert len(caught) == 1
    message = str(caught[0].message)
    assert "switch region" in message and "\n" not in message


def test_plain_straight_start_is_settled(turnout):
    result, caught = _run(turnout, 52.0, 52.05, route="through")
    assert result.summary["start"] == "static at rest"
    assert result.summary["start_residual"] < START_TOLERANCE
    assert not caught


def test_warning_criterion():
    turnout = load_turnout()  # regions: switch 0-10 m, crossing 44.29-51 m
    v = 10.0  # m/s: settles 20 m after the start
    assert unsettled_warning(turnout, 40.0, v, "static at rest", START_TOLERANCE / 2) is None
    text = unsettled_warning(turnout, 40.0, v, "static at rest", 10 * START_TOLERANCE)
    assert text is not None and "crossing region" in text
    # the crossing begins 44.29 - x_start after the start: warned only within SETTLING_TIME v
    far = 44.29 - SETTLING_TIME * v - 0.1
    assert unsettled_warning(turnout, far, v, "static at rest", 10 * START_TOLERANCE) is None
    assert unsettled_warning(turnout, 52.0, v, "static at rest", 1e6) is None  # none ahead


@pytest.mark.slow
def test_full_vehicle_starts_in_steady_curving(turnout):
    """The Manchester vehicle at 40 m of the diverging route: relaxed until every body
    settles (measured: 18 s of relaxation, residual 3 N; after the old 8 s the car body
    still moved at 1.4 mm/s), so its wheelsets hold their positions from the first step."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = simulate_passage(
            turnout,
            PassageSettings(route="diverging", speed_kmh=80.0, layers=2, x_start=40.0, x_end=40.3),
            "manchester",
            track="2-layer",
        )
    s, c = result.summary, result.columns
    assert s["start"].startswith("steady curving at 80 km/h, R = 760 m")
    assert s["start_residual"] < START_TOLERANCE
    assert not [w for w in caught if issubclass(w.category, StartWarning)]
    for k in (1, 2, 3, 4):
        y = c[f"y_ws{k}_m"]
        assert np.max(np.abs(y - y[0])) < 1e-5, k
    # the leading wheelset flanges outwards (issue 23: y = 6.3 mm in steady curving)
    assert c["y_ws1_m"][0] > 5e-3
