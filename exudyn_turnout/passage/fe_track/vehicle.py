"""The full vehicle through the turnout on the FE track (every wheelset on the one FE model).

The vehicle of :mod:`~exudyn_turnout.passage.corunning_track.vehicle` (car body, bogies,
wheelsets; the same build, the same body loads and bumpstops, the same contact element
per wheelset) runs over the FE turnout track of :mod:`~exudyn_turnout.passage.fe_track.coupling`
instead of a co-running track per wheelset: all wheelsets load the one FE model, which
carries each wheelset's deflection basin to its neighbours (the wheelsets of a bogie,
2.56 m apart, deflect each other's rails).

::

        car body                         Exudyn (as the co-running full vehicle)
     ___|_______|___
    |  bogie 1      |  bogie 2 ...
    o-------o           o-------o         wheelsets ws1..ws4, profile contact each
   =|=======|===========|=======|======   one FE track: r_i = r_free,i + C_ii F_i per step
      FE vertical + lateral planes, rail torsion; plain-track extensions beyond the turnout

Coupling per step: every wheelset's contact element solves its rail coordinates from its
own one-step compliance C_ii; the cross terms C_ij (i != j) of the one-step compliance are
left out: a step's response of the rail decays within centimetres (h = 1e-4 s: the rail's
bending waves travel ~1-10 cm), the wheelsets are >= 2.5 m apart (the run records the
largest |C_ij| / |C_ii| at the start to show it). Everything earlier steps did reaches the
other wheelsets through the FE state (r_free). In the static solves the cross terms are in
(K^-1 reaches metres).

Wheelsets beyond the turnout's ends (the rear ones while the front is at the switch, the
front ones after x_max) touch the plain rail's section at the end (the contact tables'
range) and load the FE model's plain-track extension at their own x: the extension is
lengthened to the vehicle's length plus 3 m where the default is shorter.

The start is the co-running full vehicle's: static equilibrium at rest (lateral position
and spin held), then the static solve with the creep forces at speed (spin held), all with
the FE's static compliance; the FE field then moves with the vehicle (convected velocity).
Where the static solve at speed fails (in a curve: saturated creep; the coupling's Newton on
the static compliance diverges where creep forces push a flexible blade), a dynamic
relaxation with x frozen (:data:`RELAX_TIME` s at :data:`RELAX_STEP` s, the FE track stepped
alongside with rho_inf 0) reaches the steady curving state, as on the co-running track.
``summary["start"]`` says which, ``summary["start_residual"]`` (N) what is left unbalanced;
a :class:`~exudyn_turnout.passage.vehicle.start.StartWarning` is issued when the first
region begins before an unsettled start has settled.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from exudyn_turnout.inputs.routes import Route
from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.inputs.vehicle import load_vehicle
from exudyn_turnout.inputs.vehicle_model import VehicleModel
from exudyn_turnout.passage.common import QuietExudyn
from exudyn_turnout.passage.contact.profile import STATIC_SPIN_STIFFNESS, RouteContact
from exudyn_turnout.passage.fe_track.coupling import FEContactElement, FECoSimulation, run_progress
from exudyn_turnout.passage.fe_track.options import FEPassageOptions
from exudyn_turnout.passage.fe_track.planes import build_fe_planes
from exudyn_turnout.passage.results import PassageResult
from exudyn_turnout.passage.safety import limits_for_friction
from exudyn_turnout.passage.settings import PassageFailure, PassageSettings
from exudyn_turnout.passage.summary import check_plausible
from exudyn_turnout.passage.vehicle.body_sensors import add_body_sensors, recorded_body_columns
from exudyn_turnout.passage.vehicle.start import record_start, steady_description

__all__ = ["simulate_vehicle", "EXTENSION_MARGIN"]

#: m, the FE model's plain-track extension reaches this far beyond the vehicle's length.
EXTENSION_MARGIN = 3.0
#: s, the dynamic relaxation to the steady state at speed where the static solve fails (in a
#: curve): as the co-running full vehicle's (the car body's lateral mode, ~0.7 Hz, damping
#: ratio ~0.45, settles in it; curving loads ramped up over the first second)
RELAX_TIME = 8.0
#: s, its time step (implicit, numerically damped: only the end state matters)
RELAX_STEP = 5e-3


@dataclass
class _Vehicle:
    """One Exudyn system of the vehicle with its coupled contact elements."""

    mbs: Any  #: exudyn.MainSystem
    container: Any  #: exudyn.SystemContainer
    build: Any  #: VehicleBuild
    elements: list  #: per wheelset, its WheelsetContactElement
    coupled: list  #: per wheelset, its FEContactElement
    index: list  #: per wheelset, global ODE2 indices of the element's 7 vehicle coordinates
    keep: tuple  #: user functions to keep alive


#: N, the static solves' Newton tolerance (the start residual after the solve at speed)
STATIC_TOLERANCE = 1e-4


def _fe_position(element) -> Callable[[float], float]:
    """The wheelset's own x on the FE track (not clamped to the tables' range)."""

    def position(t: float) -> float:
        return element.x0 if element.frozen else element.x0 + element.v * t

    return position


def _build(turnout, route, model, vehicle, contact, settings, track, x_range, x_front, v, frozen):
    import exudyn as exu
    from exudyn.itemInterface import NodeGenericODE2, ObjectGenericODE2

    from exudyn_turnout.passage.contact.vehicle_contacts import WheelsetContactElement
    from exudyn_turnout.passage.fe_track.common import fe_contact_element
    from exudyn_turnout.passage.vehicle.builder import add_vehicle_model
    from exudyn_turnout.passage.vehicle.track_frame import (
        DUMMY_MASS,
        DUMMY_STIFFNESS,
        BodyLoads,
        add_vehicle_loads,
        set_initial_vehicle,
    )

    container = exu.SystemContainer()
    mbs = container.AddSystem()
    build = add_vehicle_model(
        mbs, model, representation="linear", wheelset_spin=True, bumpstop="none"
    )
    elements, coupled, nodes = [], [], []
    for ws in build.wheelsets:
        raw = fe_contact_element(contact, vehicle, route, x_front + ws.x, v, settings.irregularity)
        element = WheelsetContactElement.of(raw, turnout.x_min, turnout.x_max)
        element.frozen = frozen
        wrapper = FEContactElement(element, track, _fe_position(element))
        dummy = mbs.AddNode(
            NodeGenericODE2(
                referenceCoordinates=[0.0, 0.0],
                initialCoordinates=[0.0, 0.0],
                initialCoordinates_t=[0.0, 0.0],
                numberOfODE2Coordinates=2,
            )
        )
        m, k = np.zeros((7, 7)), np.zeros((7, 7))
        for j in (5, 6):  # the dummy sprung-mass coordinates
            m[j, j], k[j, j] = DUMMY_MASS, DUMMY_STIFFNESS
        mbs.AddObject(
            ObjectGenericODE2(
                nodeNumbers=[ws.node, dummy],
                massMatrix=m,
                stiffnessMatrix=k,
                forceUserFunction=wrapper,
            )
        )
        elements.append(element)
        coupled.append(wrapper)
        nodes.append((ws.node, dummy))
    suspension = build.items["suspension"]
    stiffness = np.asarray(
        mbs.GetObjectParameter(suspension, "stiffnessMatrix").GetPythonObject(), float
    )
    damping = np.asarray(
        mbs.GetObjectParameter(suspension, "dampingMatrix").GetPythonObject(), float
    )
    loads = BodyLoads(build, stiffness, damping, route, x_front, v, *x_range)
    loads.frozen = frozen
    add_body_sensors(mbs, build, loads)  # car body, bogies: columns after the run
    keep = add_vehicle_loads(mbs, build, loads)
    mbs.Assemble()
    index = [
        np.concatenate(
            [mbs.GetNodeODE2Index(ws_node) + np.arange(5), mbs.GetNodeODE2Index(d) + np.arange(2)]
        )
        for ws_node, d in nodes
    ]
    system = _Vehicle(mbs, container, build, elements, coupled, index, keep + (loads,))
    set_initial_vehicle(system, build)
    return system


def _all_coordinates(system: _Vehicle) -> list[tuple[np.ndarray, np.ndarray]]:
    """Every wheelset element's 7 current coordinates and velocities (one read of each)."""
    data = system.mbs.systemData
    q = np.asarray(data.GetODE2Coordinates())
    q_t = np.asarray(data.GetODE2Coordinates_t())
    return [(q[index].copy(), q_t[index].copy()) for index in system.index]


def _coordinates(system: _Vehicle, i: int, initial: bool = False):
    import exudyn as exu

    kind = exu.ConfigurationType.Initial if initial else exu.ConfigurationType.Current
    data = system.mbs.systemData
    q = np.asarray(data.GetODE2Coordinates(kind))
    q_t = np.asarray(data.GetODE2Coordinates_t(kind))
    return q[system.index[i]].copy(), q_t[system.index[i]].copy()


def _static(system: _Vehicle, track: FECoSimulation, what: str, x: float, load_steps: int = 1):
    """Exudyn's static solve with the FE's static compliance; per wheelset the rail forces."""
    from exudyn_turnout.corunning.track import simulation_settings
    from exudyn_turnout.passage.fe_track.common import failure_reason

    sim = simulation_settings(1.0, 1.0)
    sim.staticSolver.numberOfLoadSteps = load_steps
    sim.staticSolver.newton.absoluteTolerance = STATIC_TOLERANCE
    sim.staticSolver.newton.maxIterations = 50
    track.begin_static(system.coupled)
    try:
        system.mbs.SolveStatic(sim, updateInitialValues=True)
        forces: list[np.ndarray] = []
        for _ in range(3):  # the cross terms: the others' final forces, to round-off
            forces = []
            for i, c in enumerate(system.coupled):
                q, _ = _coordinates(system, i, initial=True)
                forces.append(c.solve(0.0, q, np.zeros_like(q)))
    except Exception as err:  # Exudyn's SolverError, or ModelError from a user function
        raise PassageFailure(
            f"{what} on the FE track not found with the front wheelset at x = {x:g} m: "
            f"{failure_reason(err)}"
        ) from None
    finally:
        track.end_static()
    return forces


def _copy(source: _Vehicle, target: _Vehicle, current: bool = False) -> None:
    import exudyn as exu

    data_s, data_t = source.mbs.systemData, target.mbs.systemData
    kind = exu.ConfigurationType.Current if current else exu.ConfigurationType.Initial
    q = np.asarray(data_s.GetODE2Coordinates(kind)).copy()
    data_t.SetODE2Coordinates(q, exu.ConfigurationType.Initial)
    data_t.SetODE2Coordinates_t(np.zeros_like(q), exu.ConfigurationType.Initial)


def _held_spin_torque(system: _Vehicle) -> float:
    """N m: the largest torque the static solve's spin holds carry (what the run releases)."""
    torque = 0.0
    for i in range(len(system.coupled)):
        q, _ = _coordinates(system, i, initial=True)
        torque = max(torque, STATIC_SPIN_STIFFNESS * abs(float(q[4])))
    return torque


def _relax(system: _Vehicle, track: FECoSimulation, model: VehicleModel, x: float) -> tuple:
    """Integrate the vehicle with x frozen, coupled to the FE track stepped alongside (rho_inf
    0, step :data:`RELAX_STEP`), until it is at rest in the track-following frame (the
    steady state at speed); the rail forces per wheelset and the residual (N: the largest
    mass x acceleration left on a body). The FE track settles to the static field of the
    steady forces; its one-step compliance, unlike the static one, keeps the coupling's
    Newton well conditioned where creep forces push a flexible blade."""
    from exudyn_turnout.passage.common import NEWTON_ABSOLUTE_TOLERANCE
    from exudyn_turnout.passage.fe_track.common import coupled_run_settings, failure_reason

    n_steps = round(RELAX_TIME / RELAX_STEP)
    relax_settings = PassageSettings(spectral_radius=0.0)
    sim = coupled_run_settings(RELAX_TIME, n_steps, relax_settings, NEWTON_ABSOLUTE_TOLERANCE)
    forces: list = []

    def pre_step(mbs, t):
        track.predict(t, system.coupled)
        return True

    def post_step(mbs, t):
        states = _all_coordinates(system)
        done = [(c, c.solve(t, q, q_t)) for c, (q, q_t) in zip(system.coupled, states)]
        if t == track.t_next:
            track.complete(done)
        forces[:] = [F for _, F in done]
        return True

    system.mbs.SetPreStepUserFunction(pre_step)
    system.mbs.SetPostStepUserFunction(post_step)
    try:
        system.mbs.SolveDynamic(sim)
    except Exception as err:  # Exudyn's SolverError, or ModelError from a user function
        raise PassageFailure(
            f"steady state at speed on the FE track not found with the front wheelset at "
            f"x = {x:g} m: {failure_reason(err)}"
        ) from None
    a = np.asarray(system.mbs.systemData.GetODE2Coordinates_tt())
    residual = 0.0
    build = system.build
    for body in build.bodies():
        if body.name == "car_body" and model.car_body is not None:
            mass = model.car_body.mass
        elif body.name.startswith("bogie") and model.bogie is not None:
            mass = model.bogie.mass
        elif body.name.startswith("wheelset"):
            mass = model.wheelset.mass
        else:
            continue
        start = system.mbs.GetNodeODE2Index(body.node)
        dof = getattr(body, "dof", {"y": 0, "z": 1})  # a wheelset's node: y, z, roll, ...
        for name in ("y", "z"):
            if name in dof:
                residual = max(residual, mass * abs(float(a[start + dof[name]])))
    _copy(system, system, current=True)
    return forces, residual


def _cross_compliance(track: FECoSimulation, elements: list) -> float:
    """Largest |C_ij| / max |C_ii| of the one-step compliance between wheelsets at t = h."""
    track.predict(track.h, elements)
    own, cross = 0.0, 0.0
    points = [track.points(c.element, *c.positions(track.h)) for c in elements]
    for i, p_i in enumerate(points):
        for j, p_j in enumerate(points):
            for a in p_i.points:
                for b in p_j.points:
                    x_y, x_z = track._influence(b)
                    value = abs(a.weights @ x_z[a.w_dofs])
                    if i == j:
                        own = max(own, value)
                    else:
                        cross = max(cross, value)
    track.t_next = math.nan
    return cross / own if own > 0 else 0.0


def _run(system, track, settings, duration, n_steps, every, progress, x_a, pieces, fine=False):
    """One run at speed of the built system from its start state: at the run's step
    throughout (``pieces`` None: one SolveDynamic) or in pieces
    (:func:`~exudyn_turnout.passage.fe_track.common.solve_in_pieces`). Returns the sample
    times and per wheelset its element's (q, q_t) per sample."""
    import exudyn as exu

    from exudyn_turnout.passage.common import newton_tolerance
    from exudyn_turnout.passage.fe_track.common import (
        StepGrid,
        coupled_run_settings,
        failure_reason,
        solve_in_pieces,
    )

    v = settings.v
    h = duration / n_steps
    records: list[list] = [[] for _ in system.coupled]
    times: list[float] = []
    report = run_progress(progress, duration, x_a, v)
    count = [0]
    grid = None if pieces is None else StepGrid(every, fine)

    def pre_step(mbs, t):
        track.predict(t, system.coupled)
        report(t)
        return True

    def post_step(mbs, t):
        if t != track.t_next and times:  # a piece's first call: its start, done
            return True
        states = _all_coordinates(system)
        if t == track.t_next:
            done = [(c, c.solve(t, q, q_t)) for c, (q, q_t) in zip(system.coupled, states)]
            track.complete(done)
        else:  # t = 0: the start state
            for c, (q, q_t) in zip(system.coupled, states):
                c.solve(t, q, q_t)
        last = abs(t - duration) < 0.5 * track.h
        sample = grid.step(last) if grid is not None else count[0] % every == 0 or last
        if sample:
            times.append(t)
            for rec, c in zip(records, system.coupled):
                rec.append((c.q.copy(), c.q_t.copy()))
        count[0] += 1
        return True

    system.mbs.SetPreStepUserFunction(pre_step)
    system.mbs.SetPostStepUserFunction(post_step)
    tolerance = newton_tolerance(len(system.coupled))
    sim = coupled_run_settings(duration, n_steps, settings, tolerance)
    try:
        if pieces is None:
            system.mbs.SolveDynamic(sim)
        else:
            solver: Any = exu.MainSolverImplicitSecondOrder()  # (its stubs leave out self)
            solve_in_pieces(solver, system.mbs, sim, pieces, h, duration, track.set_step, grid)
    except Exception as err:  # Exudyn's SolverError, or ModelError from a user function
        t = track.t_next if math.isfinite(track.t_next) else system.mbs.systemData.GetTime()
        raise PassageFailure(
            f"FE passage failed at t = {t:.5f} s, front wheelset at x = {x_a + v * t:.3f} m: "
            f"{failure_reason(err)}"
        ) from None
    return np.array(times), records


def _wheelset_force_columns(system, times, records, v) -> dict[str, np.ndarray]:
    """``t_s`` and every wheelset's ``Fy_ws<i>_<wheel>_<slot>_N``, ``Fz_...`` of a run."""
    from exudyn_turnout.passage.contact.vehicle_contacts import wheelset_columns

    t = np.asarray(times, float)
    columns: dict[str, np.ndarray] = {"t_s": t}
    for i, (el, rec) in enumerate(zip(system.elements, records)):
        q = np.array([a for a, _ in rec])
        q_t = np.array([b for _, b in rec])
        columns.update(wheelset_columns(el, t, q, q_t, f"ws{i + 1}"))
    return columns


def simulate_vehicle(
    turnout: Turnout,
    settings: PassageSettings,
    model: VehicleModel,
    contact: RouteContact,
    route: Route,
    x_range: tuple[float, float],
    progress: Callable[[float, float], None] | None = None,
    options: FEPassageOptions | None = None,
) -> PassageResult:
    """Run the full vehicle over the FE track (module docstring).

    The door, :func:`~exudyn_turnout.passage.run.simulate_passage`, checks the settings.

    Parameters
    ----------
    turnout : Turnout
    settings : PassageSettings
        As for the co-running full vehicle; ``layers``, ``source`` and ``track_mechanism``
        do not apply.
    model : VehicleModel
        A full vehicle.
    contact : RouteContact
        The route's profile contact, made for the single-wheelset file's contact law and
        wheel profile.
    route : Route
        ``settings.route`` of the turnout.
    x_range : tuple of float
        m, the front wheelset's start and end (checked by the door).
    progress : callable(fraction, x), optional
    options : FEPassageOptions, optional
        FE mesh and damping (the extension is lengthened to the vehicle's length + 3 m).

    Returns
    -------
    PassageResult
        The columns and summary of the co-running full vehicle's passage; the summary also
        has ``model`` "FE", DOF counts and ``cross_compliance`` (the largest one-step
        compliance between wheelsets over a wheelset's own).

    Raises
    ------
    PassageError
        Bad settings.
    PassageFailure
        A solver failure (time and position), or no steady start.
    """
    with QuietExudyn():
        return _simulate(turnout, settings, model, contact, route, x_range, progress, options)


def _simulate(turnout, settings, model, contact, route, x_range, progress, options):
    """:func:`simulate_vehicle` with Exudyn silenced."""
    from exudyn_turnout.passage.contact.vehicle_contacts import wheelset_columns
    from exudyn_turnout.passage.fe_track.common import (
        check_rail_plan,
        check_rail_steps,
        fe_columns,
        fe_summary,
        two_run_progress,
    )
    from exudyn_turnout.passage.fe_track.options import FEPassageOptions
    from exudyn_turnout.passage.summary import vehicle_summary
    from exudyn_turnout.passage.vehicle.track_frame import contact_vehicle

    wall = time.perf_counter()
    options = options or FEPassageOptions()
    length = -min(model.wheelset.x)
    if options.mesh.extension < length + EXTENSION_MARGIN:
        options = replace(options, mesh=replace(options.mesh, extension=length + EXTENSION_MARGIN))
    vehicle = contact_vehicle(load_vehicle(), model)
    x_a, x_b = x_range
    v = settings.v
    duration = (x_b - x_a) / v
    n_steps = max(1, math.ceil(duration / settings.time_step - 1e-9))
    h = duration / n_steps
    planes = build_fe_planes(turnout, options)
    track = FECoSimulation(planes, route.name, h, settings.spectral_radius, options)
    covered = (x_a + min(model.wheelset.x), x_b)
    args = (turnout, route, model, vehicle, contact, settings, track, covered, x_a)
    t0 = time.perf_counter()
    rest = _build(*args, 0.0, True)
    forces = _static(rest, track, "static equilibrium at rest", x_a)
    static_loads = [el.wheel_loads(el.x_at(0.0), c.q) for el, c in zip(rest.elements, rest.coupled)]
    moving = _build(*args, v, True)
    _copy(rest, moving)
    for el in moving.elements:
        el.hold_spin = True
    curvature = max(abs(float(route.curvature(el.x_at(0.0)))) for el in moving.elements)
    start = steady_description(settings.speed_kmh, curvature)
    try:
        forces = _static(moving, track, "steady state at speed", x_a, 10)
        # converged: the lateral forces balance within the solve's tolerance; the spin holds'
        # torque is released in ~1 ms (spin inertia over the creep's damping), as on the
        # co-running track (passage/vehicle/start.py: the residual is lateral, in N)
        residual = STATIC_TOLERANCE
        start += f" (static solve, spin holds release {_held_spin_torque(moving):.3g} N m)"
    except PassageFailure:  # in a curve (saturated creep): relax dynamically with x frozen
        relax_track = FECoSimulation(planes, route.name, RELAX_STEP, 0.0, options)
        relax_args = (turnout, route, model, vehicle, contact, settings, relax_track, covered)
        moving = _build(*relax_args, x_a, v, True)
        _copy(rest, moving)
        relax_track.start(moving.coupled, forces, 0.0)
        forces, residual = _relax(moving, relax_track, model, x_a)
        start += f" (relaxed {RELAX_TIME:g} s with x frozen, FE track stepped alongside)"
    system = _build(*args, v, False)
    _copy(moving, system)
    track.start(system.coupled, forces, v)
    cross = _cross_compliance(track, system.coupled)
    static_s = time.perf_counter() - t0
    every = max(1, round((settings.output_step or h) / h))
    t1 = time.perf_counter()
    progress, second = two_run_progress(progress, settings, route)
    times, records = _run(system, track, settings, duration, n_steps, every, progress, x_a, None)
    steps_s = time.perf_counter() - t1
    first_s = 0.0
    refined: list[tuple[float, float, float]] = []
    n_ws = len(system.elements)
    pieces = check_rail_plan(
        settings,
        route,
        model.static_wheel_load,
        _wheelset_force_columns(system, times, records, v),
        n_steps,
        h,
        n_ws,
    )
    if pieces is not None:  # a loaded check rail: the run again, finer through it
        first_s = steps_s
        track = FECoSimulation(planes, route.name, h, settings.spectral_radius, options)
        args = (turnout, route, model, vehicle, contact, settings, track, covered, x_a)
        system = _build(*args, v, False)
        _copy(moving, system)
        track.start(system.coupled, forces, v)
        t1 = time.perf_counter()
        fine = options.check_rail_every_step
        times, records = _run(
            system, track, settings, duration, n_steps, every, second, x_a, pieces, fine
        )
        steps_s = time.perf_counter() - t1
        refined = [(a * h, b * h, h / m) for a, b, m in pieces if m > 1]
    elif second is not None:  # no second run after all: the line to its end
        second(1.0, x_a + v * duration)
    t = np.array(times)
    columns: dict[str, np.ndarray] = {"t_s": t, "x_m": x_a + v * t}
    for i, (el, rec) in enumerate(zip(system.elements, records)):
        q = np.array([a for a, _ in rec])
        q_t = np.array([b for _, b in rec])
        label = f"ws{i + 1}"
        own = wheelset_columns(el, t, q, q_t, label)
        own[f"x_{label}_m"] = el.x0 + v * t
        if i == 0:
            columns.update(fe_columns(el, t, q, q_t, x_a, v))
        plausible = {
            "t_s": t,
            "x_m": el.x0 + v * t,
            "y_wheelset_m": q[:, 0],
            "z_wheelset_m": q[:, 1],
            "Fz_right_N": own[f"Fz_{label}_right_N"],
            "Fz_left_N": own[f"Fz_{label}_left_N"],
            "Fy_right_N": own[f"Fy_{label}_right_N"],
            "Fy_left_N": own[f"Fy_{label}_left_N"],
        }
        limits = limits_for_friction(vehicle.contact.mu)
        check_plausible(plausible, model.static_wheel_load, f"wheelset {i + 1}", limits)
        columns.update(own)
    columns.update(recorded_body_columns(system.mbs, t))
    summary = vehicle_summary(
        turnout,
        settings,
        model,
        columns,
        static_loads,
        wall,
        limits_for_friction(vehicle.contact.mu),
    )
    summary.update(fe_summary(planes, settings, track, h, n_steps, static_s, steps_s, first_s))
    summary["cross_compliance"] = cross
    record_start(summary, turnout, x_a, v, start, residual, stacklevel=4)
    check_rail_steps(
        settings, route, model.static_wheel_load, columns, summary, n_ws, 4, refined=refined
    )
    return PassageResult(replace(settings, x_start=x_a, x_end=x_b), columns, summary, (x_a,))
