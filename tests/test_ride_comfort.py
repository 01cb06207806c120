"""EN 12299 frequency weightings Wb (vertical) and Wd (lateral) against their published gains,
and the ride-comfort columns and summary of a run (issue 25); the digital filters (written
in numpy, without scipy.signal) against scipy.signal's."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest

from exudyn_turnout.passage.ride_comfort import (
    MIN_SAMPLING_RATE,
    WB,
    WD,
    bilinear_zpk,
    comfort_columns,
    comfort_summary,
    second_order_sections,
    sections_filter,
    sections_steady_state,
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


def test_an_output_step_of_exactly_1e_3_s_is_filtered():
    # 1 / (t[1] - t[0]) of such a grid lies a few ulp below 1000 Hz: comfort_columns
    # accepted it, weighted raised (a full-vehicle study at output_step 1e-3 failed)
    assert weighted(np.ones(100), MIN_SAMPLING_RATE * (1.0 - 1e-12), WB).shape == (100,)
    t = np.arange(3000) * 1e-3  # its uniform grid's rate: 999.9999999999991 Hz
    columns = {"t_s": t, "ay_floor_car_centre_mps2": np.sin(t), "az_car_centre_mps2": np.cos(t)}
    assert set(comfort_columns(columns)) == {"awd_y_car_centre_mps2", "awb_z_car_centre_mps2"}
    with pytest.raises(ValueError, match="got 999 Hz"):
        weighted(np.zeros(100), 999.0, WB)


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


def _digital_gain(sos: np.ndarray, f, fs: float) -> np.ndarray:
    """|H(e^{j 2 pi f / fs})| of cascaded second-order sections."""
    z = np.exp(-2j * np.pi * np.asarray(f, float) / fs)[:, None]  # z^-1
    b = sos[:, 0] + sos[:, 1] * z + sos[:, 2] * z**2
    a = sos[:, 3] + sos[:, 4] * z + sos[:, 5] * z**2
    return np.abs(np.prod(b / a, axis=1))


@pytest.mark.parametrize("fs", [1000.0, 9950.2, 10_000.0])
@pytest.mark.parametrize("weighting", [WB, WD])
def test_filter_steps_equal_scipy_signal(weighting, fs):
    """The package's bilinear transform, sections, steady state and recursion against
    scipy.signal's bilinear_zpk, zpk2sos, sosfilt_zi and sosfilt (which the weighting used
    before; scipy is the reference here only)."""
    sp = pytest.importorskip("scipy.signal")
    z, p, k = weighting_zpk(weighting)
    ours = bilinear_zpk(z, p, k, fs)
    theirs = sp.bilinear_zpk(z, p, k, fs)
    for mine, ref in zip(ours, theirs, strict=True):
        np.testing.assert_allclose(mine, ref, rtol=1e-14, atol=0.0)
    sos = second_order_sections(*ours)
    sos_ref = sp.zpk2sos(*theirs)
    np.testing.assert_allclose(sos, sos_ref, rtol=1e-13, atol=1e-16)
    zi = sections_steady_state(sos)
    np.testing.assert_allclose(zi, sp.sosfilt_zi(sos_ref), rtol=1e-12, atol=1e-15)
    rng = np.random.default_rng(12299)
    x = 0.3 + np.cumsum(rng.normal(size=20_000)) * 0.01 + rng.normal(size=20_000)
    y = sections_filter(sos, x, zi * x[0])
    y_ref, _ = sp.sosfilt(sos_ref, x, zi=sp.sosfilt_zi(sos_ref) * x[0])
    np.testing.assert_allclose(y, y_ref, rtol=1e-12, atol=1e-12 * np.max(np.abs(y_ref)))
    np.testing.assert_allclose(weighted(x, fs, weighting), y_ref, rtol=1e-12,
                               atol=1e-12 * np.max(np.abs(y_ref)))  # fmt: skip


def test_digital_filter_gain_at_the_tabulated_frequencies():
    """The sections' gain at 10 kHz (the passage's output rate) against ISO 2631-1:1997
    Table 3 (Wd, to its rounding; the bilinear transform adds < 2e-4 relative at 63 Hz) and
    ISO 8041:2005's values at 100 rad/s (Wb 0.8126, Wd 0.1261)."""
    fs = 10_000.0
    sos_d = second_order_sections(*bilinear_zpk(*weighting_zpk(WD), fs))
    f = np.array(list(WD_TABLE))
    gain = 1000.0 * _digital_gain(sos_d, f, fs)
    tolerance = np.array([0.5 if v >= 100 else 0.05 for v in WD_TABLE.values()])
    assert np.all(np.abs(gain - np.array(list(WD_TABLE.values()))) <= tolerance + 1e-9)
    sos_b = second_order_sections(*bilinear_zpk(*weighting_zpk(WB), fs))
    for sos, value in ((sos_b, 0.8126), (sos_d, 0.1261)):
        assert _digital_gain(sos, [REFERENCE_HZ], fs)[0] == pytest.approx(value, abs=5e-5)


def test_sections_need_complex_pole_pairs():
    with pytest.raises(ValueError, match="complex pole pairs"):
        second_order_sections(np.array([1.0, -1.0]), np.array([0.5, 0.25]), 1.0)


def test_weighting_needs_no_scipy_signal():
    """scipy.signal costs 0.5-1.3 s to import: the weighting of a run does without it."""
    code = (
        "import sys\n"
        "import numpy as np\n"
        "from exudyn_turnout.passage.ride_comfort import comfort_columns\n"
        "t = np.arange(3000) * 1e-4\n"
        "cols = comfort_columns({'t_s': t, 'ay_floor_car_centre_mps2': np.sin(9 * t),\n"
        "                        'az_car_centre_mps2': np.cos(40 * t)})\n"
        "print(sorted(cols), 'scipy.signal' in sys.modules)\n"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert run.stdout.split("]")[-1].strip() == "False"
    assert "awb_z_car_centre_mps2" in run.stdout
