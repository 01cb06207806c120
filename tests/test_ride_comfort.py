"""EN 12299 frequency weightings Wb (vertical) and Wd (lateral) against their published gains,
and the ride-comfort columns and summary of a run (issue 25)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_turnout.passage.ride_comfort import (
    MIN_SAMPLING_RATE,
    WB,
    WD,
    comfort_columns,
    comfort_summary,
    weighted,
    weighting_response,
    weighting_zpk,
)

#: ISO 2631-1:1997 Table 3, weighting factors x 1000 of Wd at one-third-octave centre
#: frequencies (Hz -> factor), the horizontal weighting EN 12299:2009 Annex A uses.
WD_TABLE = {
    0.5: 853.0,
    1.0: 1011.0,
    2.0: 890.0,
    4.0: 512.0,
    8.0: 253.0,
    16.0: 125.0,
    31.5: 63.2,
    63.0: 29.5,
}

#: ISO 8041:2005: each weighting's value at its reference frequency 100 rad/s (15.915 Hz):
#: Wb 0.8126, Wd 0.1261.
REFERENCE_HZ = 100.0 / (2.0 * math.pi)


def test_wd_against_iso_2631_table():
    f = np.array(list(WD_TABLE))
    gain = 1000.0 * np.abs(weighting_response(WD, f))
    # the table rounds to 3 significant figures: half a unit of its last digit
    tolerance = np.array([0.5 if v >= 100 else 0.05 for v in WD_TABLE.values()])
    assert np.all(np.abs(gain - np.array(list(WD_TABLE.values()))) <= tolerance + 1e-9)


@pytest.mark.parametrize("weighting,value", [(WB, 0.8126), (WD, 0.1261)])
def test_value_at_reference_frequency_iso_8041(weighting, value):
    assert abs(weighting_response(weighting, REFERENCE_HZ)) == pytest.approx(value, abs=5e-5)


@pytest.mark.parametrize("weighting", [WB, WD])
def test_zeros_and_poles_are_the_transfer_function(weighting):
    f = np.logspace(-1, 2.5, 50)
    z, p, k = weighting_zpk(weighting)
    s = 2j * np.pi * f
    h = k * np.prod(s[:, None] - z, axis=1) / np.prod(s[:, None] - p, axis=1)
    np.testing.assert_allclose(h, weighting_response(weighting, f), rtol=1e-12)


@pytest.mark.parametrize("weighting,f", [(WB, 4.0), (WB, 10.0), (WD, 1.0), (WD, 4.0)])
def test_time_domain_filter_gain_on_a_sine(weighting, f):
    fs = 10_000.0  # the passage's default output rate (time step 1e-4 s)
    t = np.arange(0.0, 12.0, 1.0 / fs)
    y = weighted(np.sin(2 * np.pi * f * t), fs, weighting)
    tail = y[t > 6.0]  # the 0.4 Hz band limit has settled
    rms = np.sqrt(np.mean(tail**2)) * math.sqrt(2.0)
    # the bilinear transform at 10 kHz: |H| off by < 0.03 % up to 100 Hz
    assert rms == pytest.approx(abs(weighting_response(weighting, f)), rel=1e-3)


def test_constant_input_gives_no_output():
    """Started in the steady state of its first sample: a steady curving acceleration at the
    start of a run is no transient (a weighting passes no constant)."""
    y = weighted(np.full(5000, 0.65), 10_000.0, WD)
    assert np.max(np.abs(y)) < 1e-9


def test_sampling_rate_too_low():
    with pytest.raises(ValueError, match="ride comfort needs >= 1000 Hz samples"):
        weighted(np.zeros(100), 500.0, WB)
    t = np.arange(200) * 0.01  # output step 0.01 s
    columns = {"t_s": t, "ay_floor_car_centre_mps2": np.zeros(200), "az_car_centre_mps2": t}
    assert comfort_columns(columns) == {}
    note = comfort_summary(columns)["ride_comfort_note"]
    assert note.startswith("not computed: EN 12299 filters need samples at >= 1000 Hz")


def test_summary_of_a_sine_and_why_no_n_mv():
    fs = 2000.0
    t = np.arange(0.0, 8.0, 1.0 / fs)
    lateral = 0.1 * np.sin(2 * np.pi * 1.0 * t) * np.minimum(t, 1.0)  # ramped in
    columns = {
        "t_s": t,
        "ay_floor_car_centre_mps2": lateral,
        "az_car_centre_mps2": 0.2 * np.sin(2 * np.pi * 8.0 * t) * np.minimum(t, 1.0),
    }
    weighted_cols = comfort_columns(columns)
    assert set(weighted_cols) == {"awd_y_car_centre_mps2", "awb_z_car_centre_mps2"}
    summary = comfort_summary(columns)
    # steady part dominates: rms ~ amplitude |W(f)| / sqrt 2 (Wd(1 Hz) 1.011, Wb(8 Hz) 1.025)
    assert summary["ride_awd_y_rms_car_centre_mps2"] == pytest.approx(
        0.1 * 1.011 / math.sqrt(2), rel=0.08
    )
    assert summary["ride_awb_z_rms_car_centre_mps2"] == pytest.approx(
        0.2 * 1.025 / math.sqrt(2), rel=0.08
    )
    assert abs(summary["ride_awb_z_peak_car_centre_mps2"]) == pytest.approx(0.2 * 1.025, rel=0.02)
    assert "N_MV" in summary["ride_comfort_note"] and summary["ride_duration_s"] > 7.9
    assert MIN_SAMPLING_RATE == 1000.0


def test_run_of_segments_with_different_steps_is_filtered_on_a_uniform_grid():
    """Zone boundaries split a run into segments with their own step (~0.5 % apart)."""
    t = np.concatenate([np.arange(0, 1.0, 1e-4), 1.0 + np.arange(0, 1.0, 0.995e-4)])
    f = 2.0
    columns = {"t_s": t, "ay_floor_car_centre_mps2": np.sin(2 * np.pi * f * t)}
    y = comfort_columns(columns)["awd_y_car_centre_mps2"]
    assert y.shape == t.shape
    tail = y[t > 1.5]
    # Wd(2 Hz) = 0.890 (ISO 2631-1:1997 Table 3); the 0.4 Hz band limit not yet settled
    assert np.max(np.abs(tail)) == pytest.approx(0.890, rel=0.05)
