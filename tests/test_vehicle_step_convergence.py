"""The table builder of ``validation/vehicle_step_convergence.py`` on synthetic peaks.

The passages themselves take minutes (the page); here the arithmetic the page's
conclusions rest on: changes in percent, the observed order of convergence, the peak
picking from a summary, the largest step within a limit, against closed forms.
"""

from __future__ import annotations

import importlib.util
import math
import sys
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[1] / "validation" / "vehicle_step_convergence.py"


@pytest.fixture(scope="module")
def study():
    spec = importlib.util.spec_from_file_location("vehicle_step_convergence", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclasses look their module up by name
    try:
        spec.loader.exec_module(module)
        yield module
    finally:
        sys.modules.pop(spec.name, None)


@pytest.mark.parametrize("p", [1.0, 1.5, 2.0, 3.0])
def test_order_of_a_power_law(study, p):
    # P(h) = P0 + C h^p: (P(4h) - P(2h)) / (P(2h) - P(h)) = 2^p exactly (closed form)
    steps = (2.5e-5, 5e-5, 1e-4)
    values = [150e3 + 3e9 * h**p for h in steps]
    assert study.order(steps, values) == pytest.approx(p, rel=1e-6)


def test_order_not_in_the_asymptotic_range(study):
    steps = (2.5e-5, 5e-5, 1e-4)
    assert math.isnan(study.order(steps, [1.0, 2.0, 1.5]))  # differences change sign
    assert math.isnan(study.order(steps, [1.0, 1.0, 1.5]))  # no change at the finest
    assert math.isnan(study.order(steps, [1.0, math.nan, 1.5]))
    with pytest.raises(ValueError, match="constant ratio"):
        study.order((2.5e-5, 5e-5, 1.5e-4), [1.0, 2.0, 3.0])


def test_percent(study):
    assert study.percent(101.0, 100.0) == pytest.approx(1.0)
    assert study.percent(-20.9, -21.0) == pytest.approx(100.0 * (20.9 / 21.0 - 1.0))
    assert math.isnan(study.percent(1.0, 0.0))
    assert math.isnan(study.percent(math.nan, 1.0))


def _runs(study, failed=(), beyond=()):
    # P(h) = P0 (1 + c h^2): changes against h_a are 100 ((1 + c h^2) / (1 + c h_a^2) - 1)
    runs = {}
    for h in study.STEPS:
        if h in failed:
            runs[h] = study.Run({}, 0.0, 0, math.nan, "refused for the test")
            continue
        peaks = {"ws1 Fz right crossing": 150e3 * (1 + 2e5 * h**2), "check rail Fy": 0.0}
        runs[h] = study.Run(peaks, 1.0, int(0.1 / h), 1.2, beyond_limit=h in beyond)
    return runs


def test_case_tables_changes_and_order(study):
    runs = _runs(study, failed=(2e-4,), beyond=(1.5e-4,))
    text, vs_default, vs_reference = study.case_tables(runs)
    c = 2e5
    for h in (5e-5, 1.25e-4):
        expected_def = 100.0 * ((1 + c * h**2) / (1 + c * 1e-4**2) - 1.0)
        expected_ref = 100.0 * ((1 + c * h**2) / (1 + c * 2.5e-5**2) - 1.0)
        assert vs_default[h]["ws1 Fz right crossing"] == pytest.approx(expected_def, rel=1e-9)
        assert vs_reference[h]["ws1 Fz right crossing"] == pytest.approx(expected_ref, rel=1e-9)
    assert 2e-4 not in vs_default  # the failed step: listed with its reason, no column
    assert "h = 0.0002 s not run: refused for the test" in text
    assert "h = 0.00015 s*" in text  # run beyond the package's limit: marked
    assert "(left out): check rail Fy" in text  # zero at every step
    rows = [line for line in text.splitlines() if line.startswith("| ws1 Fz right crossing |")]
    row = rows[-1]  # the changes table's (the values table's comes first)
    # both order columns (from 1.25e-5 and from the reference 2.5e-5) give p = 2
    assert row.rstrip(" |").endswith("2.00 | 2.00")


def test_within_stops_at_the_first_step_over_the_limit(study):
    worst = {5e-5: 0.3, 1.1e-4: 0.05, 1.25e-4: 0.3, 1.5e-4: 0.08, 2e-4: math.nan}
    assert study.within(worst, 0.1) == 1.1e-4  # 1.5e-4 is within, but 1.25e-4 is not
    assert study.within(worst, 0.5) == 1.5e-4  # 2e-4 did not run
    assert study.within({1.1e-4: 0.2}, 0.1) == study.DEFAULT


def test_summary_peaks_picks_the_largest_magnitude(study):
    summary = {"wheelsets": 2, "peak_Fy_check_rail_N": 88e3}
    for region in ("switch", "crossing"):
        for q in ("Fz", "Fy"):
            for k, wheel, value in ((1, "right", 10e3), (1, "left", -12e3), (2, "right", 11e3)):
                summary[f"peak_{q}_{region}_ws{k}_{wheel}_N"] = value
            summary[f"peak_{q}_{region}_ws2_left_N"] = math.nan  # not reached
    for k, wheel, value in ((1, "right", 0.4), (1, "left", 0.5), (2, "right", 0.9)):
        summary[f"dQ_Q0_max_run_ws{k}_{wheel}"] = value
    summary["dQ_Q0_max_run_ws2_left"] = None  # JSON's missing value
    peaks = study.summary_peaks(summary)
    assert peaks["vehicle Fy crossing"] == -12e3  # largest magnitude, with its sign
    assert peaks["ws1 Fy right switch"] == 10e3
    assert peaks["check rail Fy"] == 88e3
    assert peaks["ws1 dQ/Q0"] == 0.5
    assert peaks["vehicle dQ/Q0"] == 0.9


def test_ringing_frequency_of_a_decaying_oscillation(study):
    # F = -F0 exp(-t / tau) (1 + cos(2 pi f t)) / 2 sampled every 2.5e-5 s at 80 km/h: the
    # maxima are one period 1 / f apart (closed form), the sign is the peak's
    import numpy as np

    v, f = 80 / 3.6, 950.0
    t = np.arange(0.0, 0.01, 2.5e-5)
    force = -100e3 * np.exp(-t / 3e-3) * 0.5 * (1.0 + np.cos(2.0 * np.pi * f * (t - 1e-3)))
    x = 45.0 + v * t
    x_peak = float(x[np.argmax(np.abs(force))])
    assert study.ringing_frequency(x, force, v, x_peak) == pytest.approx(f, rel=0.02)
    assert math.isnan(study.ringing_frequency(x, np.zeros_like(x), v, x_peak))


def test_conclusion_table_per_group(study):
    vs_default = {
        "a": {1.1e-4: {"p": 0.05}, 1.25e-4: {"p": 0.2}, 1.5e-4: {"p": 0.4}},
        "b": {1.1e-4: {"p": 0.3}, 1.25e-4: {"p": 0.3}, 1.5e-4: {"p": 0.6}},
    }
    vs_reference = {"a": {1e-4: {"p": -0.08}}, "b": {1e-4: {"p": 0.9}}}
    text = study.conclusion_table(
        {"all": ["a", "b"], "only a": ["a"]}, vs_default, vs_reference, [1.25e-4, 1.5e-4], 1e-4
    )
    rows = {line.split(" | ")[0].strip("| "): line for line in text.splitlines()[2:]}
    # within 0.1 %: none for both (b moves 0.3 % at 1.1e-4); a alone: 1.1e-4 (the limit);
    # within 0.5 %: both up to 1.25e-4 lifted (b: 0.6 % at 1.5e-4), a alone up to 1.5e-4
    assert "| 0.0001 / 0.0001 | 0.00011 / 0.000125 | 0.900 (b: p) |" in rows["all"]
    assert "| 0.00011 / 0.00011 | 0.00011 / 0.00015 | 0.080 (a: p) |" in rows["only a"]
