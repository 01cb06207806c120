"""FE static stiffness along the turnout (paper Fig. 1(b,c)), its fits, the FE receptance.

Reference values and their sources (Shih, Ambur & Dixon 2023):
- Eq 10, K_sw = -2.4e4 x^2 + 2.2e6 x + 4.2e7 N/m (switch rail, vertical): 6.16e7 N/m at
  10 m, 7.88e7 N/m at 22 m; our FE must be within 10% there (the paper's FE model is
  not ours: same Table 1, our own layout);
- Eq 14, K_sh = 1.1e5 x + 2.9e7 N/m (lateral): 2.9e7 at 0 m, 3.38e7 at 44 m; within 5%;
- Eq 2 for the stock rail: 6.3694e7 N/m vertical, 2.7999e7 N/m lateral; the discrete
  Timoshenko FE in plain track is 5-10% lower vertically (shear 4.3%, discrete supports,
  see test_fe_plain_track.py) and within 5% laterally;
- Section 2: the switch-rail stiffness at the toe is lower than the stock rail's and
  grows; the crossing nose region is much stiffer; the check rails, on stiff L-brackets,
  are laterally much stiffer than the running rails (Table 1: k_p,y 120e6 vs 25e6 N/m).
"""

import csv

import numpy as np
import pytest

from exudyn_turnout.corunning.parameters import delta_z, reference_support
from exudyn_turnout.fe.fits import fit_turnout_profiles, with_fitted_profiles
from exudyn_turnout.fe.frf import fe_receptance
from exudyn_turnout.fe.stiffness import CSV_COLUMNS, static_stiffness_profile
from exudyn_turnout.receptance import CSV_COLUMNS as RECEPTANCE_COLUMNS


@pytest.fixture(scope="module")
def profile(turnout):
    return static_stiffness_profile(turnout)


@pytest.fixture(scope="module")
def fits(profile, turnout):
    return fit_turnout_profiles(profile, turnout)


def test_every_rail_is_in_the_profile(profile):
    assert set(profile.rails) == {
        "stock_left",
        "stock_right",
        "straight",
        "curved",
        "diverging_left",
        "check_through",
        "check_diverging",
    }
    assert profile.n_dof["vertical"] > profile.n_dof["lateral"] > 10000


def test_plain_track_against_eq2(profile, turnout):
    ref = reference_support(turnout)
    _, K_z, K_y = profile.at("stock_left", -3.0)
    assert 0.90 * ref.K_st_z < K_z < 0.95 * ref.K_st_z
    assert K_y == pytest.approx(ref.K_st_y, rel=0.05)


@pytest.mark.parametrize("x", [10.0, 22.0])
def test_switch_rail_vertical_near_eq10(profile, turnout, x):
    assert profile.at("straight", x)[1] == pytest.approx(turnout.K_sw(x), rel=0.10)


def test_section_2_statements(profile):
    toe, stock_toe = profile.at("straight", 0.0)[1], profile.at("stock_left", 0.0)[1]
    assert toe < 0.8 * stock_toe < profile.at("straight", 22.0)[1]
    assert profile.at("straight", 47.7)[1] > 1.2 * profile.at("straight", 40.0)[1]  # crossing
    assert profile.at("check_through", 47.7)[2] > 1.5 * profile.at("stock_left", 47.7)[2]


def test_fits(fits, turnout):
    assert (
        fits.K_sw.rail == "straight"
        and len(fits.K_sw.coefficients) == 3
        and fits.K_sw.r_squared > 0.9
    )
    assert (
        fits.K_sh.rail == "stock_left"
        and len(fits.K_sh.coefficients) == 2
        and fits.K_sh.r_squared > 0.9
    )
    for x in (10.0, 22.0):
        assert fits.K_sw(x) == pytest.approx(turnout.K_sw(x), rel=0.10)
    for x in (0.0, 44.0):
        assert fits.K_sh(x) == pytest.approx(turnout.K_sh(x), rel=0.05)


def test_fitted_turnout_drives_delta(fits, turnout):
    fitted = with_fitted_profiles(turnout, fits)
    assert (
        fitted.K_sw.coefficients == fits.K_sw.coefficients
        and fitted.K_sh.coefficients == fits.K_sh.polynomial.coefficients
    )
    assert delta_z(fitted, 10.0) == pytest.approx(
        fits.K_sw(10.0) / reference_support(turnout).K_st_z
    )
    assert delta_z(fitted, 30.0) == pytest.approx(
        delta_z(fitted, 22.0)
    )  # held beyond the fit range


def test_fitted_turnout_keeps_plain_track_ahead_of_the_toe(fits, turnout):
    """The file's plain_track_end survives the fit: Delta_z = 1 on plain track, then blends.

    Reference: the packaged file's K_sw.plain_track_end (-1.8 m) and parameters.delta_z's
    rule (1 at and before it, linear to the toe value at x_min); before the fix the fitted
    turnout held the fitted toe value on plain track.
    """
    fitted = with_fitted_profiles(turnout, fits)
    end = turnout.K_sw.plain_track_end
    assert end is not None and fitted.K_sw.plain_track_end == end
    assert fitted.K_sh.plain_track_end == turnout.K_sh.plain_track_end
    assert delta_z(fitted, end - 1.0) == 1.0
    x0 = fitted.K_sw.x_min
    at_toe = delta_z(fitted, x0)
    assert at_toe != pytest.approx(1.0, abs=1e-3)
    assert delta_z(fitted, 0.5 * (end + x0)) == pytest.approx(0.5 * (1.0 + at_toe))


def test_profile_csv(profile, tmp_path):
    path = tmp_path / "k.csv"
    profile.to_csv(path)
    rows = list(csv.reader(open(path)))
    assert tuple(rows[0]) == CSV_COLUMNS == ("x_m", "rail", "K_z_N_per_m", "K_y_N_per_m")
    assert len(rows) == len(profile.x) + 1


def test_receptance_object_and_static_value(turnout, profile, tmp_path):
    """The FE receptance at a sleeper, 1 Hz first: 1/|H| equals the profile's value."""
    x = profile.at("straight", 47.7)[0]
    r = fe_receptance(turnout, "r2", "vertical", x, [1.0, 500.0, 1000.0])
    assert (r.model, r.rail, r.metadata["rail_id"]) == ("FE", "r2", "straight")
    assert r.static_stiffness == pytest.approx(profile.at("straight", x)[1], rel=1e-6)
    r.to_csv(tmp_path / "h.csv")
    assert tuple(open(tmp_path / "h.csv").readline().strip().split(",")) == RECEPTANCE_COLUMNS
    assert np.all(np.isfinite(r.H))
