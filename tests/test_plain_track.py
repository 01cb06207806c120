"""Plain track before the switch toe behaves as plain track.

References:
- Eq 2 of the paper, K_st = 2 sqrt(2) (EI)^(1/4) k_s^(3/4), for the reference (stock)
  rail: 6.369e7 N/m vertically (paper: "approximately 6.4e7 N/m", Section 3.1.1);
- three layers: k_0,z = k_rt,z in series with the two-layer track (Section 3.1.1, "k_0j,z
  equal to the rail pad stiffness"), so 1/K = 1/K_st + 1/k_0,z;
- a symmetric vehicle on symmetric straight track: both static wheel loads are
  (m_w + m_s) g / 2 = (1813 + 9307.5) 9.81 / 2 = 54 546.05 N (Manchester wheelset file).
"""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_turnout.corunning.modal import assemble_track_matrices, wheel_dof
from exudyn_turnout.corunning.parameters import (
    co_running_parameters,
    delta_y,
    delta_z,
    reference_support,
)
from exudyn_turnout.corunning.track import EntryLaw
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings


def _static_stiffness(params, x: float, rail: str, direction: str) -> float:
    m = assemble_track_matrices(params, x)
    i = m.index(wheel_dof(rail, direction, params.layers))
    f = np.zeros(len(m.dof))
    f[i] = 1.0
    return 1.0 / np.linalg.solve(m.K, f)[i]


@pytest.mark.parametrize("x", [-5.0, -3.0, -1.8])
def test_delta_is_one_on_plain_track(turnout, x):
    assert delta_z(turnout, x) == 1.0
    assert delta_y(turnout, x) == 1.0


def test_delta_blends_continuously_into_eqs_10_14(turnout):
    """1 at plain_track_end, Eq 10 / Eq 14 at the toe, no jump at either end."""
    ref = reference_support(turnout)
    assert delta_z(turnout, 0.0) == pytest.approx(4.2e7 / ref.K_st_z, rel=1e-12)
    assert delta_y(turnout, 0.0) == pytest.approx(2.9e7 / ref.K_st_y, rel=1e-12)
    for fun in (delta_z, delta_y):
        for x in (-1.8, 0.0):
            assert fun(turnout, x - 1e-9) == pytest.approx(fun(turnout, x + 1e-9), abs=1e-6)
        assert min(fun(turnout, -1.0), 1.0) <= fun(turnout, -1.0) <= max(fun(turnout, 0.0), 1.0)


@pytest.mark.parametrize("x", [-4.0, -1.8, -0.9, 0.0, 3.0, 30.0])
def test_track_position_law_equals_parameters(turnout, x):
    """The expressions the Exudyn track evaluates give the same Delta as parameters.py."""
    params = co_running_parameters(turnout, x=x, layers=3)
    law = EntryLaw.of(params)
    values = params.at(x)
    for name, entry in params.entries.items():
        assert law.value(entry, x) == pytest.approx(values[name], rel=1e-12), name


@pytest.mark.parametrize("rail", ["r1", "r2", "r4"])
@pytest.mark.parametrize("x", [-5.0, -3.0])
def test_static_stiffness_is_eq2_on_plain_track(turnout, rail, x):
    ref = reference_support(turnout)
    two = co_running_parameters(turnout, x=x, layers=2)
    assert _static_stiffness(two, x, rail, "vertical") == pytest.approx(ref.K_st_z, rel=1e-9)
    assert _static_stiffness(two, x, rail, "lateral") == pytest.approx(ref.K_st_y, rel=1e-9)
    assert ref.K_st_z == pytest.approx(6.4e7, rel=0.01)  # the paper's "approximately 6.4e7"
    three = co_running_parameters(turnout, x=x, layers=3)
    k_0 = three.at(x)[f"k_0{rail[1]}_z"]
    series = 1.0 / (1.0 / ref.K_st_z + 1.0 / k_0)
    assert _static_stiffness(three, x, rail, "vertical") == pytest.approx(series, rel=1e-9)


@pytest.mark.parametrize("route", ["through", "diverging"])
@pytest.mark.parametrize("layers", [2, 3])
def test_static_wheel_loads_equal_before_the_toe(turnout, route, layers):
    settings = PassageSettings(route=route, layers=layers, x_start=-5.0, x_end=-4.95)
    summary = simulate_passage(turnout, settings, vehicle="wheelset").summary
    right, left = summary["static_wheel_load_N"], summary["static_wheel_load_left_N"]
    assert right == pytest.approx(left, rel=1e-3)
    # 1e-7: the static solve stops at a residual of 1e-4 N per coordinate
    assert right + left == pytest.approx((1813.0 + 9307.5) * 9.81, rel=1e-7)


def test_zone_one_cross_section_symmetric_before_the_toe(turnout):
    """The rails a wheel runs on before the toe stand symmetric about the centreline."""
    zone = turnout.zone_at(-3.0)
    assert zone.rail_y["r1"] == pytest.approx(-zone.rail_y["r4"], abs=1e-12)
    assert zone.ballast_y[0] == pytest.approx(-zone.ballast_y[1], abs=1e-12)
    assert zone.sleeper_y == 0.0
