"""The full vehicle's body outputs: named points, suspension forces, the run's body columns
(issue 25, "the full vehicle's outputs")."""

from __future__ import annotations

import exudyn as exu
import numpy as np
import pytest

from exudyn_turnout.inputs.vehicle_model import GRAVITY, load_vehicle_model
from exudyn_turnout.passage.results import write_passage
from exudyn_turnout.passage.settings import PassageSettings
from exudyn_turnout.passage.vehicle.body_outputs import (
    CAR_POINTS,
    FLOOR_HEIGHT,
    body_columns,
    body_points,
    coordinate_slices,
    point_motion,
    suspension_forces,
)
from exudyn_turnout.passage.vehicle.builder import add_vehicle_model


@pytest.fixture(scope="module")
def model():
    return load_vehicle_model()


@pytest.fixture(scope="module")
def build(model):
    mbs = exu.SystemContainer().AddSystem()
    return add_vehicle_model(
        mbs, model, representation="linear", wheelset_spin=True, bumpstop="none"
    )


def test_points_of_the_manchester_vehicle(build):
    points = {p.name: p for p in body_points(build)}
    assert list(points) == [*CAR_POINTS, "bogie1", "bogie2"]
    # data/manchester_vehicle.toml: bogie centres at -1.28 and -20.28 m, car body at -10.78 m
    assert [points[n].x for n in CAR_POINTS] == [-1.28, -10.78, -20.28]
    # the floor FLOOR_HEIGHT above the rail, the car body's CoG 1.8 m (the vehicle file)
    assert points["car_centre"].offset == pytest.approx((0.0, FLOOR_HEIGHT - 1.8, 0.0))
    assert points["bogie2"].offset == (0.0, 0.0, 0.0) and points["bogie2"].body == "bogie2"


def test_small_angle_kinematics_of_a_floor_point(build):
    """A car-body roll lifting the left side moves a point below the CoG to the left, and
    a pitch (about the lateral axis, Exudyn X) lifts a point behind the centre."""
    q = np.zeros(sum(s.stop - s.start for s in coordinate_slices(build).values()))
    car = build.car_body
    start = coordinate_slices(build)["car_body"].start
    q[start + car.dof["roll"]] = 1e-3
    q[start + car.dof["pitch"]] = 2e-4
    u = point_motion(build, "car_body", (0.0, -0.6, -9.5), q)[0]
    assert u == pytest.approx([0.6e-3, 2e-4 * 9.5, -2e-4 * 0.6])


def test_every_suspension_element_force_free_in_the_reference(build):
    n = sum(s.stop - s.start for s in coordinate_slices(build).values())
    forces = suspension_forces(build, np.zeros((1, n)), np.zeros((1, n)))
    assert len(forces) == 4 * 2 * 3 + 2 * 2 * 3 + 2 * 3
    assert all(v[0] == 0.0 for v in forces.values())


def test_bumpstop_column_is_the_scalar_law_bit_for_bit(build, model):
    # the bumpstop column (computed on arrays) equals BumpStop.lateral_force sample by
    # sample: inside the clearance (zero), on its edge, in the table and beyond it (the
    # last slope extrapolated), both directions
    stop = model.bumpstop
    n = sum(s.stop - s.start for s in coordinate_slices(build).values())
    car = build.car_body
    start = coordinate_slices(build)["car_body"].start
    y = np.array([0.0, 0.01, stop.clearance, 0.026, 0.03, 0.04, 0.08])
    y = np.concatenate([y, -y])
    q = np.zeros((len(y), n))
    q[:, start + car.dof["y"]] = y  # the car body to the side, the bogies centred
    force = suspension_forces(build, q)["Fy_bumpstop_b1_N"]
    expected = np.array([0.0 - stop.lateral_force(u) for u in y])
    assert np.array_equal(force.view(np.int64), expected.view(np.int64))
    assert np.count_nonzero(force) == 8  # beyond the 25 mm clearance only (4 each side)
    assert np.all(np.sign(force[y > stop.clearance]) == -1.0)  # pushes the car body back


def test_static_forces_carry_the_body_weights(build, model):
    """At the vehicle's static equilibrium on rigid track the primary springs carry car body
    and bogie frames, the secondary ones the car body (masses: data/manchester_vehicle.toml)."""
    forces = suspension_forces(build, np.asarray(build.static_state))
    primary = sum(v[0] for k, v in forces.items() if k.startswith("Fz_primary_"))
    secondary = sum(v[0] for k, v in forces.items() if k.startswith("Fz_secondary_"))
    car, bogie = model.car_body.mass, model.bogie.mass
    assert primary == pytest.approx((car + 2 * bogie) * GRAVITY, rel=1e-9)
    assert secondary == pytest.approx(car * GRAVITY, rel=1e-9)
    lateral = [v[0] for k, v in forces.items() if k.startswith(("Fy_", "Fx_", "M"))]
    assert np.max(np.abs(lateral)) < 1e-6  # N, N m: a symmetric vehicle at rest


def test_frame_geometry_strains_nothing(build):
    """In a curve the coordinates of the unstrained vehicle (q_geo) carry no force."""
    rng = np.random.default_rng(3)
    n = len(build.static_state)
    q, q_geo = rng.normal(size=(4, n)) * 1e-3, rng.normal(size=(4, n)) * 1e-2
    zero = np.zeros((4, n))
    shifted = body_columns(build, q + q_geo, zero, zero, q_geo=q_geo, q_geo_t=zero)
    plain = body_columns(build, q, zero, zero)
    for name in plain:
        if name.startswith(("F", "M")):
            np.testing.assert_allclose(shifted[name], plain[name], atol=1e-6)


def test_floor_acceleration_adds_centripetal_and_gravity(build):
    n = len(build.static_state)
    q = np.tile(np.asarray(build.static_state), (2, 1))
    car = build.car_body
    q[:, coordinate_slices(build)["car_body"].start + car.dof["roll"]] += 0.01
    zero = np.zeros((2, n))
    centripetal = np.array([0.5, 0.5])
    cols = body_columns(build, q, zero, zero, centripetal=centripetal)
    assert cols["ay_floor_car_centre_mps2"] == pytest.approx([0.5 + GRAVITY * 0.01] * 2)
    assert cols["ay_car_centre_mps2"] == pytest.approx([0.0, 0.0])


def test_floor_acceleration_adds_the_frames_angular_acceleration(build):
    """The car body's frame turning at Omega_t moves a floor point d ahead of the CoG
    laterally at d Omega_t (track_frame module docstring; bogie pivots at d = +-9.5 m,
    data/manchester_vehicle.toml)."""
    n = len(build.static_state)
    q = np.tile(np.asarray(build.static_state), (2, 1))
    zero = np.zeros((2, n))
    turning = np.array([0.2, -0.1])  # rad/s^2
    cols = body_columns(build, q, zero, zero, frame_yaw_acceleration=turning)
    assert cols["ay_floor_car_front_mps2"] == pytest.approx(9.5 * turning)
    assert cols["ay_floor_car_rear_mps2"] == pytest.approx(-9.5 * turning)
    assert cols["ay_floor_car_centre_mps2"] == pytest.approx([0.0, 0.0], abs=1e-12)


@pytest.mark.slow
def test_run_on_plain_track_has_body_columns_at_rest(tmp_path):
    """All wheelsets on plain track (behind the turnout's start): a steady straight run."""
    from exudyn_turnout.inputs.turnout import load_turnout
    from exudyn_turnout.passage.run import simulate_passage

    settings = PassageSettings(x_start=-5.0, x_end=-4.5)
    result = simulate_passage(load_turnout(), settings, "manchester")
    c = result.columns
    for name in ("az_car_centre_mps2", "ay_floor_car_front_mps2", "az_bogie2_mps2"):
        assert np.max(np.abs(c[name])) < 1e-3, name  # m/s^2
    model = load_vehicle_model()
    primary = sum(v for k, v in c.items() if k.startswith("Fz_primary_"))
    car, bogie = model.car_body.mass, model.bogie.mass
    weight = (car + 2 * bogie) * GRAVITY
    # Newton on the sprung bodies, vertically: the primary forces carry the weights and the
    # (integrator's) accelerations; the car body's centre point has its CoG's vertical
    inertia = car * c["az_car_centre_mps2"] + bogie * (c["az_bogie1_mps2"] + c["az_bogie2_mps2"])
    assert np.max(np.abs(primary - weight - inertia)) < 1e-3  # N (measured 1e-9 N)
    for name in ("roll_car_body_rad", "Fy_bumpstop_b1_N", "Mz_secondary_yaw_b2_Nm"):
        assert name in c
    assert result.summary["Fz_secondary_min_N"] == pytest.approx(
        model.car_body.mass * GRAVITY / 4, rel=1e-6
    )
    assert "N_MV" in result.summary["ride_comfort_note"]
    assert "awb_z_car_rear_mps2" in c
    paths = write_passage(result, tmp_path, "csv")
    header = open(paths["timeseries"]).readline().strip().split(",")
    assert header == list(c)


@pytest.mark.slow
def test_fe_track_run_has_the_same_body_columns():
    """The full vehicle on the FE track records the same body columns (its run loop calls
    the same sensors); Newton on the sprung bodies as on the co-running track."""
    from exudyn_turnout.inputs.turnout import load_turnout
    from exudyn_turnout.passage.run import simulate_passage

    settings = PassageSettings(x_start=-5.0, x_end=-4.95)
    result = simulate_passage(load_turnout(), settings, "manchester", track="fe")
    c = result.columns
    model = load_vehicle_model()
    car, bogie = model.car_body.mass, model.bogie.mass
    primary = sum(v for k, v in c.items() if k.startswith("Fz_primary_"))
    inertia = car * c["az_car_centre_mps2"] + bogie * (c["az_bogie1_mps2"] + c["az_bogie2_mps2"])
    residual = primary - (car + 2 * bogie) * GRAVITY - inertia
    assert np.max(np.abs(residual)) < 1e-3  # N
    assert len(c["y_car_front_m"]) == len(c["t_s"])
