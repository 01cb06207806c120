"""The FE single wheelset starts in steady curving inside a curve (issue 23).

Reference values and their sources:
- steady curving: the lateral forces on the rails balance the d'Alembert load
  (m_w + m_s) v^2 / R of the single wheelset (R = 760 m, no cant: the packaged diverging
  route; paper Section 4), 7.23 kN at 80 km/h; the old FE start (static at rest) left all
  of it unbalanced (its ``start_residual`` was that load);
- the start tolerance and its meaning: :mod:`exudyn_turnout.passage.vehicle.start`;
- measured (this change, 80 km/h from x = 30 m): first-sample sum Fy 7228 N (+0.04 %),
  residual 0.24 N, wheelset y 5.352 -> 5.349 mm over the first 0.5 m. The 1 % and 0.05 mm
  tolerances stand for "balanced" and "settled" (the FE rail's discrete supports move the
  forces by ~2 % along a bay).
"""

import warnings

import pytest

from exudyn_turnout.inputs.vehicle import load_vehicle
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings
from exudyn_turnout.passage.vehicle.start import START_TOLERANCE, StartWarning

V = 80.0 / 3.6  #: m/s, the diverging route's permitted speed (turnout file)
R = 760.0  #: m, the diverging route's radius (UIC60-760-1:15)


@pytest.mark.slow
def test_fe_wheelset_inside_the_curve_starts_in_steady_curving(turnout):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = simulate_passage(
            turnout,
            PassageSettings(route="diverging", speed_kmh=80.0, x_start=30.0, x_end=30.5),
            "wheelset",
            track="fe",
        )
    s, c = result.summary, result.columns
    assert s["start"].startswith("steady curving at 80 km/h, R = 760 m (relaxed")
    assert s["start_residual"] < START_TOLERANCE
    assert not [w for w in caught if issubclass(w.category, StartWarning)]
    veh = load_vehicle()
    centrifugal = (veh.m_w + veh.m_s) * V**2 / R
    assert c["Fy_left_N"][0] + c["Fy_right_N"][0] == pytest.approx(centrifugal, rel=0.01)
    y = c["y_wheelset_m"]
    assert y[0] > 0.004  # flanging outwards (curve to the right: +y), not centred at rest
    assert abs(y[-1] - y[0]) < 5e-5
