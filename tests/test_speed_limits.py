"""Permitted speed and cant deficiency of a route: warnings, not errors.

Reference: cant deficiency D = G v^2 / (g R) - cant with G = 1.5 m (EN 13803, standard
gauge): R = 760 m, no cant, 100 km/h: 1.5 x 27.778^2 / (9.81 x 760) = 0.15524 m; 80 km/h:
0.09935 m (the diverging route's limits in the packaged file: 80 km/h, 100 mm).
"""

import pytest

from exudyn_turnout.inputs.routes import cant_deficiency, load_route, speed_warnings


def test_cant_deficiency_by_hand():
    assert cant_deficiency(100.0, -1.0 / 760.0) == pytest.approx(0.15524, abs=1e-5)
    assert cant_deficiency(80.0, 1.0 / 760.0) == pytest.approx(0.09935, abs=1e-5)
    assert cant_deficiency(80.0, 1.0 / 760.0, cant=0.05) == pytest.approx(0.04935, abs=1e-5)


def test_diverging_route_warns_above_its_limits(turnout):
    route = load_route(turnout, "diverging")
    assert speed_warnings(route, 80.0, -5.0, 60.0) == []
    text = speed_warnings(route, 100.0, -5.0, 60.0)
    assert len(text) == 2
    assert "above the permitted 80 km/h" in text[0] and "155 mm" in text[1]
    # the curve ends at 44.29 m: a run after it has no cant deficiency
    assert len(speed_warnings(route, 100.0, 52.0, 60.0)) == 1


def test_through_route_has_no_limits(turnout):
    assert speed_warnings(load_route(turnout, "through"), 300.0, -5.0, 60.0) == []
