"""Figures of a full vehicle's passage: per-wheelset forces and the bodies (issue 25)."""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_turnout.passage.results import PassageResult
from exudyn_turnout.passage.settings import DEFAULT_SETTINGS
from exudyn_turnout.plotting.curves import save_figure
from exudyn_turnout.plotting.vehicle import envelope, plot_vehicle_bodies, plot_wheelset_forces

N = 5000


def _vehicle_result() -> PassageResult:
    t = np.arange(N) * 1e-4
    x = 40.0 + 27.78 * t
    cols: dict[str, np.ndarray] = {"t_s": t, "x_m": x}
    for k, offset in enumerate((0.0, -2.56, -19.0, -21.56)):
        label = f"ws{k + 1}"
        cols[f"x_{label}_m"] = x + offset
        for wheel in ("right", "left"):
            cols[f"Fz_{label}_{wheel}_N"] = 5.45e4 + 1e3 * np.sin(40 * t + k)
            cols[f"Fy_{label}_{wheel}_N"] = 1e2 * np.cos(30 * t)
    for point in ("car_front", "car_centre", "car_rear", "bogie1", "bogie2"):
        cols[f"y_{point}_m"], cols[f"z_{point}_m"] = 1e-4 * np.sin(t), -1e-4 * t
        cols[f"ay_{point}_mps2"], cols[f"az_{point}_mps2"] = 0.1 * np.sin(9 * t), 0.1 * t
    for point in ("car_front", "car_centre", "car_rear"):
        cols[f"ay_floor_{point}_mps2"] = 0.2 * np.sin(12 * t)
    cols["Fz_primary_ws1_right_N"] = 4.56e4 + 10 * t
    cols["Fz_secondary_b1_left_N"] = 7.85e4 + 10 * t
    cols["Fy_secondary_b1_left_N"] = 10 * t
    cols["Fy_bumpstop_b1_N"] = 0 * t
    summary = {
        "static_wheel_load_N": 5.45e4,
        "static_wheel_load_left_N": 5.45e4,
        "crossing_region_m": [44.29, 51.0],
    }
    return PassageResult(DEFAULT_SETTINGS, cols, summary)


def test_envelope_keeps_every_extreme_and_order():
    rng = np.random.default_rng(2)
    x = np.arange(100_000, dtype=float)
    y = rng.normal(size=x.size)
    y[31_337] = 9.0  # a lone peak
    ex, ey = envelope(x, y, bins=1000)
    assert ex.size <= 2 * 1000 + 100
    assert ey.max() == 9.0 and ey.min() == y.min()
    assert np.all(np.diff(ex) >= 0)
    short_x, short_y = envelope(x[:100], y[:100], bins=1000)
    assert short_x.size == 100  # short curves unchanged


def test_result_gets_weighted_floor_accelerations():
    cols = _vehicle_result().columns
    assert {"awd_y_car_centre_mps2", "awb_z_car_rear_mps2"} <= set(cols)


def test_wheelset_figure_one_row_per_wheelset(tmp_path):
    fig, axes = plot_wheelset_forces(_vehicle_result())
    assert axes.shape == (4, 2)
    # each row against its own wheelset's x: the rear wheelset 21.56 m behind
    assert axes[3, 0].get_xlim()[0] == pytest.approx(40.0 - 21.56, abs=1e-6)
    save_figure(fig, str(tmp_path / "w.png"))
    assert (tmp_path / "w.png").read_bytes()[:4] == b"\x89PNG"


def test_body_figure(tmp_path):
    result = _vehicle_result()
    fig, axes = result.plot_bodies(title="bodies")
    assert axes.shape == (3, 2)
    labels = [t.get_text() for t in axes[1, 0].get_legend().get_texts()]
    assert "car_centre Wd" in labels
    save_figure(fig, str(tmp_path / "b.png"))
    assert (tmp_path / "b.png").stat().st_size > 10_000


def test_single_wheelset_result_is_refused():
    cols = {"t_s": np.zeros(3), "x_m": np.zeros(3)}
    for q in ("Fz", "Fy"):
        for wheel in ("right", "left"):
            cols[f"{q}_{wheel}_N"] = np.zeros(3)
    result = PassageResult(DEFAULT_SETTINGS, cols, {})
    with pytest.raises(ValueError, match="no per-wheelset columns"):
        plot_wheelset_forces(result)
    with pytest.raises(ValueError, match="no body columns"):
        plot_vehicle_bodies(result)


@pytest.mark.slow
def test_cli_full_vehicle_writes_the_vehicle_figures(tmp_path):
    from exudyn_turnout.cli.main import main

    out = tmp_path / "run"
    argv = ["simulate", "--vehicle", "manchester", "--x-start", "20", "--x-end", "20.3"]
    assert main([*argv, "--out", str(out)]) == 0
    for name in ("wheelsets.png", "bodies.png", "forces.png"):
        assert (out / name).read_bytes()[:4] == b"\x89PNG", name
