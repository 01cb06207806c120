"""Eqs 1-19 against the paper's numbers and closed forms.

Reference values and their sources:
- Table 2 of Shih, Ambur & Dixon (2023), plain-track (stock rail) entries, zone 1;
- the paper's text below Eq 11: "K_st is the stock rail continuous support stiffness,
  which is approximately 6.4 x 10^7 N/m based on Equation (2)";
- Delta_z, Delta_y: hand values from Eqs 10, 11, 14, 15 with K_st from Eq 2 worked out
  below (K_st,z = 6.3694e7 N/m, K_st,y = 2.79986e7 N/m);
- Eq 2 is the point stiffness of an infinite beam on a Winkler foundation, 8 EI beta^3
  with beta^4 = k_s / (4 EI) (Hetenyi, Beams on Elastic Foundation, 1946, ch. 2).
"""

import math

import pytest

from exudyn_turnout.corunning import equations as eq
from exudyn_turnout.corunning.parameters import (
    co_running_parameters,
    delta_y,
    delta_z,
    rail_support,
)

#: Table 2, zone 1 ("Simulation-1"), stock-rail (plain-track) entries; Delta-dependent
#: entries by their coefficient. Table 2 prints 2-3 significant digits: 2 % tolerance.
PLAIN_TRACK_TABLE2 = {
    "k_rt1_z": 369e6,
    "c_rt1_z": 77e3,
    "k_rt4_z": 369e6,
    "c_rt4_z": 77e3,
    "k_tg2_z": 77e6,
    "c_tg2_z": 77e4,
    "k_01_z": 369e6,
    "k_04_z": 369e6,
    "k_rt1_y": 56e6,
    "c_rt1_y": 22e3,
    "k_rt4_y": 56e6,
    "c_rt4_y": 22e3,
    "k_tg_y": 56e6,
    "c_tg_y": 56e4,
    "k_01_y": 280e6,
    "k_04_y": 280e6,
    "m_r1": 111.0,
    "m_r4": 111.0,
    "m_t": 500.0,
    "J_t": 265.0,
    "m_0": 2.5,
    # the switch rail's entries are the stock values times Delta_z (Section 3.1.1)
    "k_rt2_z": 369e6,
    "c_rt2_z": 77e3,
    "k_tg1_z": 77e6,
    "c_tg1_z": 77e4,
}


@pytest.mark.parametrize("name,published", sorted(PLAIN_TRACK_TABLE2.items()))
def test_plain_track_entry_reproduces_table2(turnout, name, published):
    derived = co_running_parameters(turnout, zone=1).entries[name].a
    assert derived == pytest.approx(published, rel=0.02)


def test_stock_rail_static_stiffness_is_about_6_4e7(turnout):
    """Paper text below Eq 11: K_st approximately 6.4e7 N/m (two significant digits)."""
    assert rail_support(turnout, "stock").K_st_z == pytest.approx(6.4e7, rel=0.01)


def test_eq2_hand_values():
    """k_b = 20e6 * 2.5 / 2 = 25e6 N/m (Eq 4).

    k_s = 120e6 * 25e6 / (0.6 * 145e6) = 34.483e6 N/m^2 (Eq 2).
    """
    k_s = eq.continuous_support_stiffness(120e6, 25e6, 0.6)
    assert k_s == pytest.approx(34.4828e6, rel=1e-5)
    assert eq.static_track_stiffness(207e9 * 3.03e-5, k_s) == pytest.approx(6.3694e7, rel=1e-4)


@pytest.mark.parametrize("EI,k_s", [(6.2721e6, 34.48e6), (1.06e6, 2e7), (1.88e7, 5e7)])
def test_eq2_equals_winkler_point_stiffness(EI, k_s):
    beta = (k_s / (4 * EI)) ** 0.25
    assert eq.static_track_stiffness(EI, k_s) == pytest.approx(8 * EI * beta**3, rel=1e-12)


@pytest.mark.parametrize(
    "x,expected_dz,expected_dy",
    [
        (0.0, 0.65940, 1.03577),  # 4.2e7 / 6.3694e7 ; 2.9e7 / 2.79986e7
        (10.0, 0.96712, 1.07505),  # 6.16e7 / 6.3694e7 ; 3.01e7 / 2.79986e7
        (22.0, 1.23691, 1.12220),  # 7.8784e7 / 6.3694e7 ; 3.142e7 / 2.79986e7
        (30.0, 1.23691, 1.15363),  # K_sw held at its 22 m value (Section 3.1.1); 3.23e7
        (44.0, 1.23691, 1.20863),  # ; 3.384e7 / 2.79986e7
    ],
)
def test_delta_factors_hand_values(turnout, x, expected_dz, expected_dy):
    assert delta_z(turnout, x) == pytest.approx(expected_dz, rel=1e-4)
    assert delta_y(turnout, x) == pytest.approx(expected_dy, rel=1e-4)


def test_lateral_check_rail_and_crossing_rail_reproduce_table2(turnout):
    """Table 2: k_rt3,y = 215e6 (check, L-brackets), zone 2 k_rt2,y = 53e6, k_tg,y = 86e6.

    Eqs 1-19 on Table 1 (``check_rail="table1"``, the paper's path; the default derives the
    check rail from the FE bracket instead, tests/test_corunning_check_rail.py)."""
    zone2 = co_running_parameters(turnout, zone=2, check_rail="table1").entries
    assert zone2["k_rt3_y"].a == pytest.approx(215e6, rel=0.02)
    assert zone2["k_rt2_y"].a == pytest.approx(53e6, rel=0.02)
    assert zone2["k_tg_y"].a == pytest.approx(86e6, rel=0.02)


def test_crossing_rail_reproduces_table2_only_with_reciprocal_eq5(turnout):
    """Table 2 zone 2: k_rt2,z 453e6 (range end), m_r2 409 kg, m_t 881 kg."""
    from exudyn_turnout.corunning.parameters import AS_PRINTED

    derived = co_running_parameters(turnout, zone=2).entries
    printed = co_running_parameters(turnout, zone=2, readings=AS_PRINTED).entries
    assert derived["k_rt2_z"].a == pytest.approx(453e6, rel=0.02)
    assert derived["m_r2"].a == pytest.approx(409, rel=0.02)
    assert derived["m_t"].a == pytest.approx(881, rel=0.02)
    assert printed["k_rt2_z"].a / 453e6 > 1.2  # as printed: 579e6


def test_eq12_textbook_shear_modulus_value():
    """c_0 = 2 A sqrt(0.4 G rho), G = 207e9 / 2.6 = 79.6 GPa.

    Hand value: 2 * 0.0076668 * sqrt(0.4 * 79.6e9 * 7850).
    """
    G = eq.shear_modulus(207e9, 0.3)
    assert G == pytest.approx(79.615e9, rel=1e-4)
    assert eq.extra_layer_damping(0.0076668, G, 7850) == pytest.approx(
        2 * 0.0076668 * math.sqrt(0.4 * 207e9 / 2.6 * 7850), rel=1e-12
    )
    assert eq.extra_layer_damping(
        0.0076668, eq.shear_modulus(207e9, 0.3, "E(1+nu)/2"), 7850
    ) == pytest.approx(315e3, rel=0.005)


def test_unknown_reading_is_refused():
    with pytest.raises(ValueError, match="Eq 5"):
        eq.sleeper_effective_length(4.06, 20e6, 8.4e6, reading="other")
    with pytest.raises(ValueError, match="Eq 16"):
        eq.rail_mass(0.0077, 7850, 1.8, 0.6, reading="other")
