"""The co-running check rail derived from the FE bracket (corunning/check_rail.py)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from exudyn_turnout.corunning import check_rail as cr
from exudyn_turnout.corunning.modal import assemble_track_matrices, co_running_receptance
from exudyn_turnout.corunning.parameters import co_running_parameters
from exudyn_turnout.fe.check_rail_receptance import (
    check_rail_lateral_points,
    check_rail_positions,
)
from exudyn_turnout.inputs.check_rail import CheckRailLateral, lateral_from_section
from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage.common import lightest_rail_mass

EW54 = "exudyn_turnout/data/ew54_190_1_9.toml"


def test_pad_stiffness_series_springs():
    # 1/K = 1/k_tg + (1 + r)/k_rt: with k_tg = 100, K = 50 -> k_rt = (1 + r) * 100 (hand)
    assert cr.check_rail_pad_stiffness(50e6, 100e6) == pytest.approx(100e6)
    assert cr.check_rail_pad_stiffness(50e6, 100e6, 0.2) == pytest.approx(120e6)
    with pytest.raises(ValueError, match="not below"):
        cr.check_rail_pad_stiffness(100e6, 100e6)


def test_mass_and_damping_of_a_resonance():
    # a 30 kg mass on 106.6 MN/m resonates at sqrt(k/m)/2pi = 300.0 Hz (hand)
    k = 30.0 * (2 * math.pi * 300.0) ** 2
    assert cr.check_rail_mass(k, 300.0) == pytest.approx(30.0)
    assert cr.check_rail_mass(k, 300.0, layers=3, m_0=2.5) == pytest.approx(27.5)
    assert cr.check_rail_pad_damping(2 * math.pi * 300.0 * 20e3, 300.0) == pytest.approx(20e3)
    with pytest.raises(ValueError, match="not positive"):
        cr.check_rail_mass(1.0, 300.0, layers=3, m_0=2.5)


def test_section_is_checked():
    good = {
        "rail": "c",
        "x": [1.0, 2.0],
        "static_stiffness": [1.0, 2.0],
        "resonance_frequency": [1.0, 2.0],
        "resonance_stiffness": [1.0, 2.0],
    }
    assert lateral_from_section({"co_running": good}).x == (1.0, 2.0)
    assert lateral_from_section({}) is None
    with pytest.raises(ValueError, match="x must increase"):
        lateral_from_section({"co_running": {**good, "x": [2.0, 1.0]}})
    with pytest.raises(ValueError, match="static_stifness is not a field.*static_stiffness"):
        lateral_from_section({"co_running": {"static_stifness": [1.0], **good}})
    with pytest.raises(ValueError, match="one value per x"):
        lateral_from_section({"co_running": {**good, "resonance_stiffness": [1.0]}})


@pytest.mark.parametrize("layers", [2, 3])
def test_static_stiffness_is_the_fe_one_at_every_table_position(layers):
    """The derived check rail's static lateral stiffness equals the file's FE value."""
    turnout = load_turnout()
    lateral = cr.check_rail_lateral(turnout)
    assert lateral is not None
    zone = turnout.zone_at(46.0)
    params = co_running_parameters(turnout, zone=zone.index, layers=layers)
    for x, K_fe in zip(lateral.x, lateral.static_stiffness):
        if not zone.x_start <= x <= zone.x_end:
            continue
        m = assemble_track_matrices(params, x)
        i = m.index("y_m0_r3" if layers == 3 else "y_r3")
        assert 1.0 / np.linalg.inv(m.K)[i, i] == pytest.approx(K_fe, rel=1e-9)


def test_resonance_of_the_derived_rail_is_near_the_fe_one():
    """The 3-layer r3 receptance peaks within 10 % of the FE's resonance (median x)."""
    turnout = load_turnout()
    lateral = cr.check_rail_lateral(turnout)
    i = len(lateral.x) // 2
    x, f_r = lateral.x[i], lateral.resonance_frequency[i]
    f = np.geomspace(60.0, 500.0, 200)
    H = co_running_receptance(turnout, 3, "r3", "lateral", x=x, frequencies=f).H
    assert f[np.argmax(np.abs(H))] == pytest.approx(f_r, rel=0.10)


def test_table1_path_kept_and_bracket_default():
    turnout = load_turnout()
    table1 = co_running_parameters(turnout, x=46.0, check_rail="table1").at(46.0)
    bracket = co_running_parameters(turnout, x=46.0).at(46.0)
    # Table 1 values of the check rail (validation/check_rail_support.md, before): 109.4 kg
    assert table1["m_r3"] == pytest.approx(109.4, abs=0.1)
    assert bracket["m_r3"] < 0.5 * table1["m_r3"]
    assert bracket["k_rt3_y"] < table1["k_rt3_y"]
    # the running rails are untouched
    for name in ("k_rt1_y", "k_rt2_y", "m_r2", "k_tg_y", "m_t", "k_rt3_z"):
        assert bracket[name] == table1[name]
    with pytest.raises(ValueError, match="check_rail must be one of"):
        co_running_parameters(turnout, x=46.0, check_rail="fe")
    no_data = dataclasses.replace(turnout, raw={**turnout.raw, "check_rail": {"clearance": 0.004}})
    assert co_running_parameters(no_data, x=46.0).at(46.0)["m_r3"] == table1["m_r3"]
    with pytest.raises(ValueError, match="no \\[check_rail.co_running\\]"):
        co_running_parameters(no_data, x=46.0, check_rail="bracket")


def test_second_turnout_derives_too():
    turnout = load_turnout(EW54)
    assert cr.check_rail_model(turnout, None) == "bracket"
    zone = next(z for z in turnout.zones if "r3" in z.active_rails)
    x = 0.5 * (zone.x_start + zone.x_end)
    values = co_running_parameters(turnout, x=x, layers=3).at(x)
    assert values["m_r3"] > 0 and values["k_rt3_y"] > 0 and values["c_rt3_y"] > 0


def test_lightest_rail_mass_is_the_derived_check_rail():
    """The lightest rail mass of a crossing run is the derived check rail's (stated)."""
    turnout = load_turnout()
    m = lightest_rail_mass(turnout, 44.5, 50.0, 3, "derived")
    assert m == pytest.approx(co_running_parameters(turnout, x=46.0).at(46.0)["m_r3"])


def test_lateral_dataclass_rejects_bad_values():
    with pytest.raises(ValueError, match="finite and > 0"):
        CheckRailLateral("c", (1.0,), (0.0,), (1.0,), (1.0,))


def test_positions_are_sleepers_and_overhang():
    turnout = load_turnout()
    xs = check_rail_positions(turnout, "check_diverging")
    # check rail 44.29-51.52 m (layout), sleepers at 0.3 + 0.6 i m ([layout] sleeper_x0)
    assert xs[0] == pytest.approx(44.30) and xs[-1] == pytest.approx(51.51)
    sleepers = [x for x in xs if abs((x - 0.3) / 0.6 - round((x - 0.3) / 0.6)) < 1e-6]
    assert sleepers[0] == pytest.approx(44.7) and sleepers[-1] == pytest.approx(51.3)
    assert len(sleepers) == 12


@pytest.mark.slow
def test_file_values_are_the_fe_ones():
    """[check_rail.co_running] of the packaged file reproduces from the FE (4 digits)."""
    turnout = load_turnout()
    stored = cr.check_rail_lateral(turnout)
    i = stored.x.index(46.5)
    fe = check_rail_lateral_points(turnout, stored.rail, [46.5])
    assert fe.static_stiffness[0] == pytest.approx(stored.static_stiffness[i], rel=1e-3)
    assert fe.resonance_frequency[0] == pytest.approx(stored.resonance_frequency[i], rel=1e-3)
    assert fe.resonance_stiffness[0] == pytest.approx(stored.resonance_stiffness[i], rel=1e-3)
