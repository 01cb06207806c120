"""The compiled time stepper (passage/corunning_track/stepper.py) against Exudyn's
generalized-alpha solver and closed forms.

1. The scheme alone on a linear 2-DOF oscillator: equal to Exudyn's GeneralizedAlpha (same
   h, same rho, Exudyn's default Newton tolerance) to round-off, and second-order
   convergent to the exact modal solution as h halves.
2. The full vehicle's passage: every output column (forces, contact details, wheelset and
   body coordinates, the columns derived from them) of ``solver="compiled"`` against
   ``solver="exudyn"``, on the through route across a segment boundary (a wheelset entering
   the turnout: rebuild and carry-over) and on the diverging route into its curve (body
   loads, curvature) across one. The tolerance comes from Newton's: both solvers stop at
   ||r|| <= eps (eps = NEWTON_TOLERANCE_FACTOR x newton_tolerance(4) = 5 N), so their
   results may differ by what that tolerance itself moves them. Measured per column
   against Exudyn run with eps / 100 (B): every column of the compiled run (C) must be as
   close to Exudyn's at eps (A) as A is to B, |C - A| <= |A - B| + 1e-9 max|B| (round-off
   floor); and every force column (N) within 2 eps (each run's contact force within eps of
   the exactly converged one).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
import scipy.linalg

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.inputs.vehicle_model import load_vehicle_model
from exudyn_turnout.passage.common import newton_tolerance
from exudyn_turnout.passage.corunning_track import stepper
from exudyn_turnout.passage.corunning_track import vehicle as full_vehicle
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageError, PassageFailure, PassageSettings

#: kg, N/m: a 2-DOF chain (masses 2 and 1 kg, springs 200 and 100 N/m): omega 5.8, 14.1 rad/s
MASS = np.diag([2.0, 1.0])
STIFFNESS = np.array([[300.0, -100.0], [-100.0, 100.0]])
Q0 = np.array([0.01, -0.005])  #: m, initial displacement (at rest)
RHO = 0.8  #: the passages' default spectral radius


def _exudyn_oscillator(damping: np.ndarray, steps: int) -> np.ndarray:
    """Exudyn's GeneralizedAlpha on M q'' + D q' + K q = 0 over 1 s: (samples, 2)."""
    import exudyn as exu
    from exudyn.itemInterface import NodeGenericODE2, ObjectGenericODE2, SensorNode

    container = exu.SystemContainer()
    mbs = container.AddSystem()
    node = mbs.AddNode(
        NodeGenericODE2(
            referenceCoordinates=[0.0, 0.0],
            initialCoordinates=list(Q0),
            initialCoordinates_t=[0.0, 0.0],
            numberOfODE2Coordinates=2,
        )
    )
    mbs.AddObject(
        ObjectGenericODE2(
            nodeNumbers=[node], massMatrix=MASS, stiffnessMatrix=STIFFNESS, dampingMatrix=damping
        )
    )
    sensor = mbs.AddSensor(
        SensorNode(
            nodeNumber=node,
            storeInternal=True,
            writeToFile=False,
            outputVariableType=exu.OutputVariableType.Coordinates,
        )
    )
    mbs.Assemble()
    sim = exu.SimulationSettings()
    sim.timeIntegration.endTime = 1.0
    sim.timeIntegration.numberOfSteps = steps
    sim.timeIntegration.verboseMode = 0
    sim.timeIntegration.generalizedAlpha.spectralRadius = RHO
    sim.solution.file.write = False
    sim.solution.sensors.writePeriod = 0.999 / steps
    mbs.SolveDynamic(sim)
    return np.asarray(mbs.GetSensorStoredData(sensor))[:, 1:]


@pytest.mark.parametrize(
    "damped, tolerance",
    [
        # undamped: the same operations up to the order of sums, round-off only (measured
        # 2e-15 m on 0.01 m after 500 steps)
        (False, 1e-12),
        # damped: Exudyn's one Newton iteration a step stops at its relative tolerance
        # 1e-8 with a residual that differs from ours in the last digits of the damping
        # term: each step may differ by up to 1e-8 of its correction (measured 1.3e-12 m
        # on 0.01 m after 500 steps, growing linearly)
        (True, 1e-9),
    ],
)
def test_oscillator_equals_exudyn(damped, tolerance):
    damping = (1e-3 * STIFFNESS + 0.1 * MASS) if damped else np.zeros((2, 2))  # Rayleigh
    reference = _exudyn_oscillator(damping, 500)
    run = stepper.integrate_linear(MASS, STIFFNESS, damping, Q0, np.zeros(2), 1.0, 500, RHO)
    assert run.q.shape == reference.shape
    assert run.iterations == 500 and run.jacobians == 1  # linear: one iteration a step
    assert np.max(np.abs(run.q - reference)) <= tolerance * np.max(np.abs(Q0))


def test_oscillator_second_order():
    # exact: q(t) = sum_i phi_i cos(omega_i t) phi_i^T M q0 (mass-normalised modes, at rest)
    omega2, phi = scipy.linalg.eigh(STIFFNESS, MASS)
    errors = []
    for steps in (200, 400, 800):
        run = stepper.integrate_linear(
            MASS, STIFFNESS, np.zeros((2, 2)), Q0, np.zeros(2), 1.0, steps, RHO
        )
        exact = (np.cos(np.outer(run.times, np.sqrt(omega2))) * (phi.T @ MASS @ Q0)) @ phi.T
        errors.append(np.max(np.abs(run.q - exact)))
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    assert errors[0] < 1e-2 * np.max(np.abs(Q0))
    assert np.all((ratios > 3.6) & (ratios < 4.4)), ratios  # second order: 4 per halving


def test_alpha_constants_closed_form():
    # rho = 1: the trapezoidal rule (alpha_m = alpha_f = 1/2, beta = 1/4, gamma = 1/2)
    assert stepper.alpha_constants(1.0) == pytest.approx((0.5, 0.5, 0.25, 0.5))
    # rho = 0.8 (Chung-Hulbert): alpha_m = 0.6/1.8, alpha_f = 0.8/1.8, gamma = 1/2 + 0.2/1.8
    alpha_m, alpha_f, beta, gamma = stepper.alpha_constants(0.8)
    assert (alpha_m, alpha_f) == pytest.approx((1 / 3, 4 / 9))
    assert gamma == pytest.approx(0.5 + 1 / 9)
    assert beta == pytest.approx(0.25 * (1 + 1 / 9) ** 2)


def test_sample_rows_every_step_and_period():
    times, sizes = stepper.step_times(1e-3, 10)
    assert len(times) == 11 and times[-1] == pytest.approx(1e-3)
    assert stepper.sample_rows(times, sizes, 0.999e-4).all()
    rows = stepper.sample_rows(times, sizes, 0.999 * 3e-4)  # every third step, and the end
    assert list(np.nonzero(rows)[0]) == [0, 3, 6, 9, 10]


@pytest.fixture(scope="module")
def scene():
    return load_turnout(), load_vehicle_model()


def _columns(scene, settings, factor=None):
    turnout, model = scene
    saved = full_vehicle.NEWTON_TOLERANCE_FACTOR
    if factor is not None:
        full_vehicle.NEWTON_TOLERANCE_FACTOR = factor
    try:
        return simulate_passage(turnout, settings, model)
    finally:
        full_vehicle.NEWTON_TOLERANCE_FACTOR = saved


@pytest.mark.parametrize(
    "route, speed, x_range, output_step",
    [("through", 100.0, (-5.0, -1.0), None), ("diverging", 80.0, (-3.0, 1.5), 3e-4)],
)
def test_vehicle_passage_equals_exudyn(scene, monkeypatch, route, speed, x_range, output_step):
    calls = []
    integrate = stepper.integrate
    monkeypatch.setattr(stepper, "integrate", lambda *a, **k: calls.append(1) or integrate(*a, **k))
    case = PassageSettings(
        route=route,
        speed_kmh=speed,
        x_start=x_range[0],
        x_end=x_range[1],
        output_step=output_step,
        solver="exudyn",  # the references A and B: Exudyn's integrator, asked for
    )
    a = _columns(scene, case)
    reported = []
    c = simulate_passage(
        scene[0], replace(case, solver="compiled"), scene[1], lambda f, x: reported.append(f)
    )
    assert len(calls) == len(c.zone_starts) >= 2  # every segment stepped here; a rebuild
    assert len(reported) > 20 and reported == sorted(reported)  # progress about every 2 %
    assert c.zone_starts == a.zone_starts
    b = _columns(scene, case, full_vehicle.NEWTON_TOLERANCE_FACTOR / 100).columns
    eps = full_vehicle.NEWTON_TOLERANCE_FACTOR * newton_tolerance(4)
    a, c = a.columns, c.columns
    assert set(c) == set(a) and len(c["t_s"]) == len(a["t_s"])
    checked = 0
    for name in a:
        ref, mine, tight = (np.asarray(x[name], float) for x in (a, c, b))
        assert np.array_equal(np.isnan(mine), np.isnan(ref)), name
        if np.all(np.isnan(ref)):
            continue
        own = np.nanmax(np.abs(ref - tight))  # what Newton's tolerance moves this column
        floor = 1e-9 * np.nanmax(np.abs(tight))
        difference = np.nanmax(np.abs(mine - ref))
        assert difference <= own + floor, (name, difference, own)
        if name.startswith(("Fz_", "Fy_")) and name.endswith("_N"):
            assert difference <= 2 * eps, name
        checked += 1
    assert checked > 150  # every wheelset's and body's columns, not a few


def test_compiled_is_the_default_and_ignored_elsewhere(scene, monkeypatch):
    turnout, model = scene
    assert PassageSettings().solver == "compiled"
    with pytest.raises(PassageError, match="solver must be"):
        simulate_passage(turnout, PassageSettings(solver="fast"), "wheelset")
    # the single wheelset steps in Exudyn whatever the solver says: the default's run is
    # the one asking for Exudyn, bit for bit, and the stepper is never called
    monkeypatch.setattr(stepper, "integrate", lambda *a, **k: pytest.fail("stepper called"))
    case = PassageSettings(x_start=-5.0, x_end=-4.9)
    default = simulate_passage(turnout, case, "wheelset").columns
    exudyn = simulate_passage(turnout, replace(case, solver="exudyn"), "wheelset").columns
    for name, values in exudyn.items():
        np.testing.assert_array_equal(default[name], values, err_msg=name)


def test_failed_step_names_time_and_position(scene, monkeypatch):
    # a step whose Newton fails (not retried smaller, unlike Exudyn's adaptive step): the
    # run stops with the same PassageFailure as Exudyn's solver error, time and position
    integrate = stepper.integrate

    def failing(*args, **kwargs):
        return replace(integrate(*args, **kwargs), failed_at=0.01)

    monkeypatch.setattr(stepper, "integrate", failing)
    turnout, model = scene
    case = PassageSettings(x_start=-5.0, x_end=-4.5, solver="compiled")
    x = -5.0 + case.v * 0.01
    with pytest.raises(PassageFailure, match=rf"t = 0\.01000 s, front wheelset at x = {x:.3f} m"):
        simulate_passage(turnout, case, model)


def test_anything_else_acting_goes_to_exudyn(scene, monkeypatch):
    turnout, model = scene
    case = PassageSettings(x_start=-5.0, x_end=-4.8)  # the default solver: compiled
    seen = []
    integrate = stepper.integrate

    def spy(mbs, contacts, *args, **kwargs):
        seen.append((mbs, contacts))
        return integrate(mbs, contacts, *args, **kwargs)

    monkeypatch.setattr(stepper, "integrate", spy)
    assert simulate_passage(turnout, case, model).summary["stepping"] == "compiled"
    mbs, contacts = seen[0]
    assert stepper.unsupported(mbs, contacts) is None
    from exudyn.itemInterface import LoadCoordinate, MarkerNodeCoordinate

    marker = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=0, coordinate=0))
    mbs.AddLoad(LoadCoordinate(markerNumber=marker, load=1.0))
    mbs.Assemble()
    assert stepper.unsupported(mbs, contacts) == "the system has loads"
    # a segment the stepper does not serve runs in Exudyn: Exudyn's results, bit for bit
    monkeypatch.setattr(stepper, "unsupported", lambda mbs, contacts: "a load")
    seen.clear()
    fallback = simulate_passage(turnout, case, model)
    asked = simulate_passage(turnout, replace(case, solver="exudyn"), model)
    assert not seen
    # the default (compiled) falls back, and the summary says why
    assert fallback.summary["stepping"] == "exudyn (compiled stepper: a load)"
    assert asked.summary["stepping"] == "exudyn"
    fallback, exudyn = fallback.columns, asked.columns
    for name, values in exudyn.items():
        np.testing.assert_array_equal(fallback[name], values, err_msg=name)
