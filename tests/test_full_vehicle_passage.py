"""The full Manchester vehicle through the turnout, a co-running track under every wheelset
(issue 13; :mod:`exudyn_turnout.passage.full_vehicle_passage`)."""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.inputs.vehicle_model import load_vehicle_model
from exudyn_turnout.passage.full_vehicle_passage import curve_geometry, simulate_vehicle_passage
from exudyn_turnout.passage.results import PassageError, PassageSettings
from exudyn_turnout.passage.simulate import simulate_passage

#: N, Iwnicki 1998: total mass 32 000 + 2 x 2 615 + 4 x 1 813 = 44 482 kg on 8 wheels.
STATIC_WHEEL_LOAD = 44482.0 * 9.81 / 8.0


@pytest.fixture(scope="module")
def turnout():
    return load_turnout()


@pytest.fixture(scope="module")
def model():
    return load_vehicle_model()


@pytest.fixture(scope="module")
def plain(turnout, model):
    """All four wheelsets on plain track: the front at x = -4 m, the rear ones behind the
    turnout's start (zone 1 clamped to x_min)."""
    s = PassageSettings(route="through", speed_kmh=60.0, layers=2, x_start=-4.0, x_end=-3.8)
    return simulate_vehicle_passage(turnout, s, model)


def test_static_wheel_loads_on_plain_track(plain):
    # Iwnicki 1998 masses, car body midway between the bogies: every wheel carries 1/8
    for i in range(1, 5):
        for wheel in ("right", "left"):
            load = plain.summary[f"static_wheel_load_ws{i}_{wheel}_N"]
            assert load == pytest.approx(STATIC_WHEEL_LOAD, rel=1e-3), (i, wheel)
    # the front wheelset's summary keeps the single-wheelset names
    assert plain.summary["static_wheel_load_N"] == plain.summary["static_wheel_load_ws1_right_N"]


def test_running_on_plain_track_stays_at_the_static_loads(plain):
    # straight plain track, design geometry, steady state at speed: nothing excites the vehicle
    for i in range(1, 5):
        for wheel in ("right", "left"):
            fz = plain.columns[f"Fz_ws{i}_{wheel}_N"]
            assert np.allclose(fz, STATIC_WHEEL_LOAD, rtol=2e-3), (i, wheel)
    assert np.array_equal(plain.columns["Fz_right_N"], plain.columns["Fz_ws1_right_N"])


def test_curve_geometry_closed_form():
    # constant curvature: offset kappa d^2 / 2 from the tangent, heading change kappa d
    kappa = -1.0 / 760.0
    x = np.linspace(-30.0, 30.0, 6001)
    d = np.array([-10.78, -1.28, 0.0, 9.5])
    e, theta = curve_geometry(x, np.full_like(x, kappa), d, 0.0)
    assert np.allclose(e, kappa * d**2 / 2.0, atol=1e-9)
    assert np.allclose(theta, kappa * d, atol=1e-12)


def test_suspension_has_no_stiffness_against_rigid_motion(model):
    # the curve term K q_geo relies on K q = 0 for a lateral shift and a yaw of the whole
    # unstrained vehicle (no spring changes length); gravity's roll terms do not enter.
    import exudyn as exu

    from exudyn_turnout.passage.vehicle_builder import add_vehicle_model

    mbs = exu.SystemContainer().AddSystem()
    build = add_vehicle_model(mbs, model, representation="linear", wheelset_spin=True)
    k = np.asarray(
        mbs.GetObjectParameter(build.items["suspension"], "stiffnessMatrix").GetPythonObject()
    )
    shift, yaw = [], []
    for b in build.bodies():
        for name in b.dof:
            shift.append(1.0 if name == "y" else 0.0)
            yaw.append(b.x if name == "y" else (1.0 if name == "yaw" else 0.0))
    for q in (np.array(shift), np.array(yaw)):
        assert np.max(np.abs(k @ q)) < 1e-6 * np.max(np.abs(k))


def test_zone_crossing_of_the_front_wheelset(turnout, model):
    # the front wheelset crosses zone 1 -> 2 (crossing panel, x = 44.29 m) on the through
    # route; the others stay in zone 1 and their tracks are copied.
    s = PassageSettings(route="through", speed_kmh=60.0, layers=2, x_start=44.2, x_end=44.4)
    result = simulate_vehicle_passage(turnout, s, model)
    assert result.zone_starts == pytest.approx((44.2, 44.29))
    cols = result.columns
    i = int(np.searchsorted(cols["x_m"], 44.29))
    single = simulate_passage(turnout, s)
    j = int(np.searchsorted(single.columns["x_m"], 44.29))
    for wheel in ("right", "left"):
        jump = abs(np.diff(cols[f"Fz_ws1_{wheel}_N"])[i - 1 : i + 1]).max()
        jump_single = abs(np.diff(single.columns[f"Fz_{wheel}_N"])[j - 1 : j + 1]).max()
        # Tolerance: 1.5 % of the wheel load. The single-wheelset passage (the same
        # re-basing, simulate._carry_over) jumps by 589 N (right) / 459 N (left) here
        # (measured): the full vehicle must not add to it.
        assert jump < 0.015 * STATIC_WHEEL_LOAD, wheel
        assert jump == pytest.approx(jump_single, rel=0.05, abs=20.0), wheel
        # wheelsets that do not cross: no jump beyond their step-to-step change (< 5 N)
        for k in (2, 3, 4):
            assert abs(np.diff(cols[f"Fz_ws{k}_{wheel}_N"])[i - 1 : i + 1]).max() < 5.0


def test_steady_curving_lateral_balance(turnout, model):
    # Diverging route, 760 m radius without cant (uic60_760_1_15: curvature -1/760 1/m from
    # x = 0 to 44.29 m). With the front wheelset at 30 m the rear one is at 8.44 m: all four
    # in the curve. In steady curving the lateral contact forces of all wheels carry the
    # whole vehicle's centrifugal load, M v^2 / R (Newton's second law in the
    # track-following frame): 44 482 kg x (60 / 3.6 m/s)^2 / 760 m = 16.26 kN (issue 13).
    s = PassageSettings(route="diverging", speed_kmh=60.0, layers=2, x_start=30.0, x_end=30.1)
    result = simulate_vehicle_passage(turnout, s, model)
    cols = result.columns
    total = sum(cols[f"Fy_ws{i}_{w}_N"] for i in range(1, 5) for w in ("right", "left"))
    expected = 44482.0 * (60.0 / 3.6) ** 2 / 760.0
    assert np.all(np.abs(total / expected - 1.0) < 0.02)
    # the rear wheelset is in the curve over the whole window
    assert cols["x_ws4_m"].min() > 0.0
    # lateral forces point outward (positive, left) on the rails in this right-hand curve
    assert total.min() > 0.0


def test_cli_runs_the_full_vehicle(tmp_path, capsys):
    """``simulate --vehicle`` with a full-vehicle file runs the full vehicle; outputs carry
    every wheelset (issue 13, CLI)."""
    import json

    from exudyn_turnout.cli.main import main
    from exudyn_turnout.inputs.vehicle_model import default_vehicle_model_path

    out = tmp_path / "run"
    argv = ["simulate", "--vehicle", str(default_vehicle_model_path()), "--layers", "2"]
    argv += ["--x-start", "52", "--x-end", "52.3", "--no-plot", "--out", str(out)]
    assert main(argv) == 0
    header = (out / "timeseries.csv").read_text().splitlines()[0].split(",")
    for k in (1, 2, 3, 4):
        assert f"Fz_ws{k}_right_N" in header and f"Fy_ws{k}_left_N" in header
    summary = json.loads((out / "summary.json").read_text())
    # the rear wheelsets stand on the switch panel's track (x = 30.4 m, 33 m), the front
    # ones on plain track: the loads differ a little, together they carry the vehicle
    # (44 482 kg, Iwnicki 1998)
    loads = [
        summary[f"static_wheel_load_ws{k}_{wheel}_N"]
        for k in (1, 2, 3, 4)
        for wheel in ("left", "right")
    ]
    assert sum(loads) == pytest.approx(44482 * 9.81, rel=1e-6)
    assert "front wheelset" in capsys.readouterr().out
    assert main(argv + ["--contact", "height-table"]) == 2
    assert "profile contact only" in capsys.readouterr().err


def test_rear_wheelsets_pass_the_crossing_beyond_the_turnout_end(turnout, model):
    """The front wheelset may run past the turnout's end (plain track: the last zone at x_max)
    by up to the vehicle's length, so the rear wheelsets cross the nose (46.9 m) too."""
    settings = PassageSettings(layers=2, x_start=66.0, x_end=70.0)  # rear: 44.4 -> 48.4 m
    s = simulate_vehicle_passage(turnout, settings, model).summary
    W = 44482 * 9.81 / 8
    for k in (3, 4):
        assert s[f"peak_Fz_crossing_ws{k}_right_N"] > 1.5 * W  # the crossing impact
    assert np.isnan(s["peak_Fz_crossing_ws1_right_N"])  # the front ones are past it
    too_far = PassageSettings(layers=2, x_start=80.0, x_end=82.0)
    with pytest.raises(PassageError, match="end plus the vehicle's length"):
        simulate_vehicle_passage(turnout, too_far, model)
