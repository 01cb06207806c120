"""The full Manchester vehicle through the turnout, a co-running track under every wheelset
(issue 13; :mod:`exudyn_turnout.passage.corunning_track.vehicle`)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.inputs.vehicle_model import load_vehicle_model
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageError, PassageSettings
from exudyn_turnout.passage.vehicle.track_frame import curve_geometry

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
    return simulate_passage(turnout, s, model)


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

    from exudyn_turnout.passage.vehicle.builder import add_vehicle_model

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
    result = simulate_passage(turnout, s, model)
    assert result.zone_starts == pytest.approx((44.2, 44.29))
    cols = result.columns
    i = int(np.searchsorted(cols["x_m"], 44.29))
    single = simulate_passage(turnout, s, vehicle="wheelset")
    j = int(np.searchsorted(single.columns["x_m"], 44.29))
    for wheel in ("right", "left"):
        jump = abs(np.diff(cols[f"Fz_ws1_{wheel}_N"])[i - 1 : i + 1]).max()
        jump_single = abs(np.diff(single.columns[f"Fz_{wheel}_N"])[j - 1 : j + 1]).max()
        # Tolerance: 1.5 % of the wheel load. The single-wheelset passage (the same
        # re-basing, simulate._carry_over) jumps by 589 N (right) / 459 N (left) here
        # (measured with Hertz contact everywhere): the full vehicle must not add to it.
        # One-sided since the semi-Hertzian law on the wing rail and nose (issue 22): the
        # two runs' start transients then differ, single 647 N, vehicle 600 N (right).
        assert jump < 0.015 * STATIC_WHEEL_LOAD, wheel
        assert jump <= 1.05 * jump_single + 20.0, wheel
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
    result = simulate_passage(turnout, s, model)
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
    s = simulate_passage(turnout, settings, model).summary
    W = 44482 * 9.81 / 8
    for k in (3, 4):
        assert s[f"peak_Fz_crossing_ws{k}_right_N"] > 1.5 * W  # the crossing impact
    assert np.isnan(s["peak_Fz_crossing_ws1_right_N"])  # the front ones are past it
    # the largest per region names a contact of the front wheelset (wheel, rail slot), never
    # a rear wheelset's total (it read "ws3 wheel on right" before)
    assert s["max_Fz_crossing_wheel"] is None and np.isnan(s["max_Fz_crossing_N"])
    too_far = PassageSettings(layers=2, x_start=80.0, x_end=82.0)
    with pytest.raises(PassageError, match="end plus the vehicle's length"):
        simulate_passage(turnout, too_far, model)


def _segment(turnout, model, x_front, v, frozen=False, route_name="through", mechanism="compiled"):
    """One run segment's Exudyn system of the full vehicle (3 layers), its contact function
    and a state with every wheel pressed into its rails and moving a little."""
    from exudyn_turnout.inputs.routes import load_route
    from exudyn_turnout.inputs.vehicle import load_vehicle
    from exudyn_turnout.passage.contact.profile import route_contact
    from exudyn_turnout.passage.corunning_track import vehicle_system as fvp
    from exudyn_turnout.passage.vehicle.track_frame import contact_vehicle

    route, base = load_route(turnout, route_name), load_vehicle()
    settings = PassageSettings(
        route=route_name, speed_kmh=100.0, layers=3, track_mechanism=mechanism
    )
    places = tuple(fvp.place_of(turnout, x_front + o) for o in model.wheelset.x)
    args = (turnout, route, model, contact_vehicle(base, model))
    args += (route_contact(turnout, route_name, base), settings, places, x_front, v, frozen)
    system = fvp.build_segment(*args, (x_front - 20.0, x_front + 10.0))
    contacts = system.mbs.variables[fvp.VARIABLES_KEY][0]
    rng = np.random.default_rng(13)
    q = 1e-5 * rng.standard_normal(contacts.n)
    q_t = 1e-2 * rng.standard_normal(contacts.n)
    for el, (a, _) in zip(contacts.elements, contacts.spans):
        # 0.1 mm into the rails (the static Hertz penetration is ~0.1 mm)
        q[a + 1], q[a + 2] = el.touching_position(el.x_at(0.0), 1e-4)
    return system, contacts, q, q_t


@pytest.mark.parametrize(
    "v, hold_spin, route",
    [
        (100.0 / 3.6, False, "through"),
        (100.0 / 3.6, False, "diverging"),  # x = 20 m: in the 760 m curve, curving loads
        (100.0 / 3.6, True, "through"),
        (0.0, False, "through"),
    ],
)
def test_one_contact_function_for_all_wheelsets_gives_each_elements_forces(
    turnout, model, v, hold_spin, route
):
    # the merged force function (one Exudyn call for the four wheelsets) must return, bit
    # for bit, what each wheelset's own element returns: running (curving load), the solve
    # at speed (spin held) and at rest (lateral position and spin held)
    x = 46.5 if route == "through" else 20.0
    # symbolic track springs: the object's forces are the contacts' alone
    _, contacts, q, q_t = _segment(turnout, model, x, v, route_name=route, mechanism="symbolic")
    t = 0.0123
    expected = []
    for el, (a, b) in zip(contacts.elements, contacts.spans):
        el.hold_spin = hold_spin
        expected.append(np.array(el(None, t, 0, list(q[a:b]), list(q_t[a:b]))))
    forces = np.array(contacts(None, t, 0, list(q), list(q_t)))
    c, e = contacts.n_contacts, contacts.n_stops_end
    # in a curve the body loads (K q_geo, curving loads) ride on the object too
    curved = contacts.body_loads is not None
    assert curved == (route == "diverging" and v > 0.0)
    loads = contacts._loads if curved else np.zeros(contacts.n)
    assert np.array_equal(forces[:c], np.concatenate(expected) + loads[:c])
    assert np.max(np.abs(forces)) > 1e4  # the wheels do carry load (N)
    # the curving loads were applied (the elements' own forces include -m v^2 kappa)
    assert any(el._kappa != 0.0 for el in contacts.elements) == (route == "diverging")
    # the bumpstops ride along after the contacts (car body, bogies), on q - q_geo
    shift = contacts.body_loads[0].geometry_at(t)[: e - c] if curved else 0.0
    stop = contacts.stops[1](None, t, 0, list(q[c:e] - shift), list(q_t[c:e]))
    assert np.array_equal(forces[c:e], np.array(stop) + loads[c:e])


@pytest.mark.parametrize("route", ["through", "diverging"])
@pytest.mark.parametrize("mechanism", ["compiled", "symbolic"])
def test_compiled_residual_equals_the_python_path(turnout, model, route, mechanism):
    # the hot path (contacts, bumpstops on straight track, the tracks' springs when
    # compiled: one numba call) returns, bit for bit, what the Python path returns
    x = 46.5 if route == "through" else 20.0
    _, contacts, q, q_t = _segment(
        turnout, model, x, 100.0 / 3.6, route_name=route, mechanism=mechanism
    )
    assert contacts._compiled is not None
    assert (contacts.track is not None) == (mechanism == "compiled")
    c, e = contacts.n_contacts, contacts.n_stops_end
    if route == "through":  # the car body 27.5 mm to the side: the bumpstops (clearance
        q[c] += 0.0275  # 25 mm) engaged
        assert np.any(contacts.stops[1](None, 0.0, 0, list(q[c:e]), list(q_t[c:e])))
    t = 0.0123
    fast = np.array(contacts(None, t, 0, list(q), list(q_t)))
    assert contacts._fast
    contacts._compiled, contacts._t_fast = None, math.nan
    slow = np.array(contacts(None, t, 0, list(q), list(q_t)))
    assert not contacts._fast
    assert np.array_equal(fast, slow)
    assert np.max(np.abs(fast[:c])) > 1e4  # the wheels carry load (N)
    assert np.max(np.abs(fast[c:e])) > 1e2  # stops (and in the curve the body loads)
    if mechanism == "compiled":  # the track's own coordinates feel their springs
        assert np.max(np.abs(fast[e:])) > 1e2


def test_compiled_residual_recomputes_the_track_laws_at_a_new_time(turnout, model):
    # the compiled path evaluates the springs' K(x), D(x) once per time (the Newton
    # iterations of a step share t): a call at a new t must use the new x. At x = 46.5 m
    # (the crossing) the support stiffness changes along the track: 0.1 s later the
    # wheelsets are 2.8 m further and the forces differ; each time's forces equal the
    # Python path's bit for bit, called first or after the other time.
    _, contacts, q, q_t = _segment(turnout, model, 46.5, 100.0 / 3.6)
    compiled = contacts._compiled
    e = contacts.n_stops_end
    fast = {}
    for t in (0.0123, 0.1123, 0.0123):
        fast[t] = np.array(contacts(None, t, 0, list(q), list(q_t)))
        assert contacts._fast
    contacts._compiled, contacts._t_fast = None, math.nan
    for t, forces in fast.items():
        slow = np.array(contacts(None, t, 0, list(q), list(q_t)))
        assert np.array_equal(forces, slow)
    assert not np.array_equal(fast[0.0123][e:], fast[0.1123][e:])  # the springs did change
    contacts._compiled = compiled
    assert isinstance(contacts(None, 0.2, 0, list(q), list(q_t)), list)  # Exudyn's fast type


def test_contact_jacobian_equals_central_differences(turnout, model):
    # -df/dq and -df/dq_t of the contact function (forward differences per wheelset) against
    # central differences of the whole function (definition of the derivative). Tolerance:
    # 1e-4 of the largest entry (forward differences with steps of 1e-9 against central ones
    # of 1e-8 m / 1e-6 m/s; measured: 2.4e-6 of it at x = 20, 46.5 and 47 m).
    _, contacts, q, q_t = _segment(turnout, model, 20.0, 100.0 / 3.6)
    t = 0.0
    jac_q = contacts.jacobian_function(None, t, 0, q, q_t, 1.0, 0.0)  # with the track springs
    jac_q_t = contacts.jacobian_function(None, t, 0, q, q_t, 0.0, 1.0)
    for vector, jac, step in ((q, jac_q, 1e-8), (q_t, jac_q_t, 1e-6)):
        central = np.zeros_like(jac)
        for j in range(contacts.n):
            up, down = vector.copy(), vector.copy()
            up[j] += step
            down[j] -= step
            if vector is q:
                f_up = np.array(contacts(None, t, 0, list(up), list(q_t)))
                f_down = np.array(contacts(None, t, 0, list(down), list(q_t)))
            else:
                f_up = np.array(contacts(None, t, 0, list(q), list(up)))
                f_down = np.array(contacts(None, t, 0, list(q), list(down)))
            central[:, j] = (f_down - f_up) / (2.0 * step)
        scale = np.max(np.abs(central))
        assert scale > 0.0
        assert np.max(np.abs(jac - central)) < 1e-4 * scale
    # the wheelsets do not couple: off-diagonal blocks are zero
    (a, b), (c, d) = contacts.spans[0], contacts.spans[1]
    assert not np.any(jac_q[a:b, c:d]) and not np.any(jac_q[c:d, a:b])


def test_exudyn_takes_the_contact_jacobian_as_its_own_numerical_one(turnout, model):
    # the system Jacobian assembled with the contacts' jacobianUserFunction equals the one
    # Exudyn differentiates numerically without it (same steps: relative 1e-7, minimum
    # coordinate 0.01): the sign, the factors f_ODE2 / f_ODE2_t and the object's own
    # stiffness (the dummies' springs, added by Exudyn) are right.
    import exudyn as exu

    from exudyn_turnout.corunning.track import simulation_settings

    jacobians = []
    for user in (True, False):
        system, contacts, _, _ = _segment(turnout, model, 46.5, 100.0 / 3.6)
        mbs = system.mbs
        data = mbs.systemData
        q_t = np.zeros(data.ODE2Size())
        q_t[::7] = 0.01  # m/s: creepages
        data.SetODE2Coordinates_t(q_t, exu.ConfigurationType.Initial)
        # the car body 27.5 mm to the side: the bumpstops (clearance 25 mm, next kink at
        # 30 mm; on the contacts' object on straight track) are engaged
        q = np.array(data.GetODE2Coordinates(exu.ConfigurationType.Initial))
        q[mbs.GetNodeODE2Index(system.names["car_body"])] += 0.0275
        data.SetODE2Coordinates(q, exu.ConfigurationType.Initial)
        u = []
        for name in ("car_body", "bogie1", "bogie2"):  # the bumpstops' coordinates
            node = system.names[name]
            i = mbs.GetNodeODE2Index(node)
            k = np.atleast_1d(mbs.GetNodeOutput(node, exu.OutputVariableType.Coordinates)).size
            u += list(q[i : i + k])
        assert len(u) == contacts.n_stops_end - contacts.n_contacts
        assert np.any(contacts.stops[1](None, 0.0, 0, u, [0.0] * len(u)))  # engaged
        if not user:
            for i in range(data.NumberOfObjects()):
                if mbs.GetObject(i)["objectType"] == "GenericODE2":
                    if mbs.GetObject(i)["forceUserFunction"] is contacts:
                        mbs.SetObjectParameter(i, "jacobianUserFunction", 0)
        solver = exu.MainSolverImplicitSecondOrder()
        solver.InitializeSolver(mbs, simulation_settings(0.01, 1e-4))
        blocks = []
        for f_q, f_q_t in ((1.0, 0.0), (0.0, 1.0)):
            solver.ComputeJacobianODE2RHS(
                mbs, scalarFactor_ODE2=f_q, scalarFactor_ODE2_t=f_q_t, scalarFactor_ODE1=0.0
            )
            blocks.append(np.array(solver.GetSystemJacobian()))
        jacobians.append(blocks)
    for user, numerical in zip(*jacobians):
        assert np.max(np.abs(numerical)) > 1e5
        assert np.allclose(user, numerical, rtol=0.0, atol=1e-9 * np.max(np.abs(numerical)))


def test_newton_tolerance_per_wheelset():
    # sqrt(n) times the single wheelset's: the L2 residual of n wheelsets with each
    # wheelset's share at the single wheelset's tolerance
    from exudyn_turnout.passage.common import NEWTON_ABSOLUTE_TOLERANCE, newton_tolerance

    assert newton_tolerance(1) == NEWTON_ABSOLUTE_TOLERANCE
    assert newton_tolerance(4) == pytest.approx(2.0 * NEWTON_ABSOLUTE_TOLERANCE)


@pytest.mark.slow
def test_rear_wheelset_enters_a_zone_exactly_at_its_boundary(turnout, model):
    # The rear wheelset (21.56 m behind the front one on the Manchester vehicle) reaches the
    # diverging route's zone-2 start, 44.29 m, with the front at 65.85 m; x0 + v t lands there
    # by round-off a hair short of the boundary, and the track must be built at the boundary
    # (it raised "x = 44.29 m is outside zone 2 (44.29 m to 51 m)" before).
    s = PassageSettings(route="diverging", speed_kmh=80.0, layers=3, x_start=65.6, x_end=66.1)
    result = simulate_passage(turnout, s, model)
    x = result.columns["x_m"]
    assert x[-1] >= 66.1 - 1e-3
    for side in ("right", "left"):  # the wheel's total (per-rail columns are NaN off-rail)
        fz = result.columns[f"Fz_ws4_{side}_N"]
        assert np.all(np.isfinite(fz)) and np.all(fz > 0.5 * STATIC_WHEEL_LOAD)


def test_the_objects_force_function_equals_the_call(turnout, model):
    # the function Exudyn gets (compiled path bound once, the path chosen once per time)
    # returns what __call__ returns, bit for bit, at a new time, back at an old one, and on
    # the Python path (spin held: the steady-state solve)
    _, contacts, q, q_t = _segment(turnout, model, 46.5, 100.0 / 3.6)
    force = contacts.force_function()
    for t in (0.0123, 0.1123, 0.0123):
        forces = force(None, t, 0, list(q), list(q_t))
        assert isinstance(forces, list)  # Exudyn's fast type
        assert forces == contacts(None, t, 0, list(q), list(q_t))
    assert contacts._fast
    for el in contacts.elements:
        el.hold_spin = True
    held = force(None, 0.2, 0, list(q), list(q_t))
    assert not contacts._fast
    assert held == contacts(None, 0.2, 0, list(q), list(q_t))
    for el in contacts.elements:
        el.hold_spin = False
    assert held != force(None, 0.3, 0, list(q), list(q_t))  # the holds did act


def test_the_force_function_follows_a_frozen_flag(turnout, model):
    # the compiled path reads the elements' frozen flags once per time (one C loop where
    # every element has the flag): at one time, a wheelset frozen at x0 gets other forces
    # than moving (a fresh function: the flags are read anew), equal to __call__'s, and the
    # moving ones again once released
    _, contacts, q, q_t = _segment(turnout, model, 46.5, 100.0 / 3.6)
    t, a, b = 0.061, *contacts.spans[0]
    moving = contacts.force_function()(None, t, 0, list(q), list(q_t))
    contacts.elements[0].frozen = True
    frozen = contacts.force_function()(None, t, 0, list(q), list(q_t))
    assert contacts._fast
    assert frozen[a:b] != moving[a:b]
    assert frozen == contacts(None, t, 0, list(q), list(q_t))
    contacts.elements[0].frozen = False
    assert contacts.force_function()(None, t, 0, list(q), list(q_t)) == moving


def test_recorded_contact_columns_equal_the_ones_evaluated_after_the_run(
    turnout, model, monkeypatch
):
    # the compiled residual records every time's contact forces and details at Newton's last
    # call (the accepted state); the columns made of them equal, to round-off (the curvature
    # and the irregularity at x are evaluated by other code after the run), those evaluated
    # again from the stored coordinates, at the crossing where contacts jump between rails
    from exudyn_turnout.passage.contact.vehicle_contacts import VehicleContacts

    s = PassageSettings(layers=3, x_start=46.6, x_end=47.0)
    used = []
    recorded = VehicleContacts.recorded

    def spy(self, t):
        out = recorded(self, t)
        used.append(out is not None)
        return out

    monkeypatch.setattr(VehicleContacts, "recorded", spy)
    fast = simulate_passage(turnout, s, model).columns
    assert used and all(used)
    monkeypatch.setattr(VehicleContacts, "start_record", lambda self, times: None)
    used.clear()
    slow = simulate_passage(turnout, s, model).columns
    assert used and not any(used)  # nothing recorded: evaluated after the run
    assert fast.keys() == slow.keys()
    for name, column in slow.items():
        assert np.allclose(fast[name], column, rtol=1e-12, atol=1e-9, equal_nan=True), name
    assert np.max(np.abs(slow["Fz_ws1_right_N"])) > 1e4  # the wheel carries load (N)


def test_the_record_keeps_the_last_call_of_each_time_and_rewinds_a_step_tried_again(turnout, model):
    _, contacts, q, q_t = _segment(turnout, model, 46.5, 100.0 / 3.6)
    force = contacts.force_function()
    other = q + 1e-6  # another state (a Newton iterate)
    contacts.start_record(4)
    for t, state in ((0.0, q), (1e-4, other), (1e-4, q), (2e-4, q), (1.5e-4, other)):
        force(None, t, 0, list(state), list(q_t))
    # the step to 2e-4 failed and was tried again to 1.5e-4: 2e-4 is gone
    assert contacts.recorded(np.array([0.0, 1e-4, 2e-4])) is None
    contacts.start_record(4)
    for t, state in ((0.0, q), (1e-4, other), (1e-4, q), (2e-4, q), (1.5e-4, other)):
        force(None, t, 0, list(state), list(q_t))
    got = contacts.recorded(np.array([0.0, 1e-4, 1.5e-4]))
    assert got is not None
    for k, (el, (a, b)) in enumerate(zip(contacts.elements, contacts.spans)):
        forces, details = got[k]
        for row, (t, state) in enumerate(((0.0, q), (1e-4, q), (1.5e-4, other))):
            expected, expected_details = el.evaluate(el.x_at(t), state[a:b], q_t[a:b])
            assert np.array_equal(forces[row], expected)
            assert np.array_equal(details[row], expected_details)
    assert contacts.recorded(np.array([0.0])) is None  # recording stopped
    contacts.start_record(1)  # more times than rows: given up
    for t in (0.0, 1e-4):
        force(None, t, 0, list(q), list(q_t))
    assert contacts.recorded(np.array([0.0])) is None
