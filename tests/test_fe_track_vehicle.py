"""The full vehicle on the FE track (passage/fe_track/vehicle.py).

References: the vehicle's weight, 44 482 kg x 9.81 m/s^2 / 8 = 54 546 N per wheel
(data/manchester_vehicle.toml, Iwnicki 1998), issue 14's "static wheel loads on the FE track
equal the co-running ones within 0.1 %", and the one-step compliance between wheelsets
(2.56 m apart) against a wheelset's own, which the coupling leaves out: it must be
negligible (the FE track's step response decays within centimetres).
"""

import numpy as np
import pytest

from exudyn_turnout.inputs.vehicle_model import load_vehicle_model
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageError, PassageSettings

SETTINGS = PassageSettings(route="through", speed_kmh=100.0, x_start=-5.0, x_end=-4.9)


@pytest.fixture(scope="module")
def fe_run(turnout):
    return simulate_passage(turnout, SETTINGS, load_vehicle_model(), track="fe")


@pytest.mark.slow
def test_static_wheel_loads_carry_the_vehicle(fe_run):
    weight_share = 44482.0 * 9.81 / 8.0
    for k in range(1, 5):
        for wheel in ("left", "right"):
            load = fe_run.summary[f"static_wheel_load_ws{k}_{wheel}_N"]
            assert load == pytest.approx(weight_share, rel=1e-3)


@pytest.mark.slow
def test_static_wheel_loads_equal_the_co_running_ones(turnout, fe_run):
    co = simulate_passage(turnout, SETTINGS, load_vehicle_model(), track="3-layer")
    for k in range(1, 5):
        for wheel in ("left", "right"):
            key = f"static_wheel_load_ws{k}_{wheel}_N"
            assert fe_run.summary[key] == pytest.approx(co.summary[key], rel=1e-3)


@pytest.mark.slow
def test_wheelsets_do_not_couple_within_a_step(fe_run):
    assert 0.0 <= fe_run.summary["cross_compliance"] < 1e-6


@pytest.mark.slow
def test_every_wheel_stays_loaded_on_plain_track(fe_run):
    W = 44482.0 * 9.81 / 8.0
    for k in range(1, 5):
        for wheel in ("left", "right"):
            force = fe_run.columns[f"Fz_ws{k}_{wheel}_N"]
            assert np.all(np.isfinite(force))
            assert np.all(np.abs(force / W - 1.0) < 0.05)  # sleeper passing: a few per cent


def test_unknown_track_is_refused(turnout):
    with pytest.raises(PassageError, match="track must be one of"):
        simulate_passage(turnout, SETTINGS, load_vehicle_model(), track="4-layer")
