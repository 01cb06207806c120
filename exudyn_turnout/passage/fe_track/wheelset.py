"""The single wheelset through the turnout on the FE track, vertical and lateral.

The same vehicle (:func:`~exudyn_turnout.passage.vehicle.wheelset.add_vehicle`) and the same profile
contact (:class:`~exudyn_turnout.passage.contact.profile.ProfileContactElement`) as the
co-running passage of :mod:`~exudyn_turnout.passage.corunning_track.wheelset`, on the FE
turnout track
coupled by the exact one-step co-simulation of :mod:`~exudyn_turnout.passage.fe_track.coupling`
(read its docstring for the scheme and why). The run is one Exudyn solve over the whole x
range: the FE track has no zones; every rail body of the route is coupled to the FE rail
of its slot wherever the wheelset is in its reach.

The run starts from the static equilibrium at ``x_start`` (lateral position and spin held)
or, where the route is curved there, in steady curving at speed, as the FE full vehicle
(:mod:`~exudyn_turnout.passage.fe_track.vehicle`): from the static state a dynamic
relaxation with x frozen, the FE track stepped alongside (:data:`RELAX_TIME`);
``summary["start"]`` and ``summary["start_residual"]`` say how it started
(:mod:`~exudyn_turnout.passage.vehicle.start`).

::

      sprung mass m_s (y, z)              Exudyn
        |k_y, k_z, c_z at +-d|
     ===o=====wheelset=====o===           y, z, roll, yaw, spin
        |  profile contact  |             ProfileContactElement (per rail body y, z)
     ---+-------------------+---          FE rail heads: r = r_free + C F  (co-simulation)
     FE vertical plane (w) + lateral plane (v, roll, warping), pads, sleepers, ballast
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
from exudyn_turnout.inputs.vehicle import Vehicle
from exudyn_turnout.passage.common import QuietExudyn
from exudyn_turnout.passage.contact.profile import RouteContact
from exudyn_turnout.passage.fe_track.common import (
    StepGrid,
    check_rail_plan,
    check_rail_steps,
    coupled_run_settings,
    failure_reason,
    fe_columns,
    fe_contact_element,
    fe_summary,
    solve_in_pieces,
    two_run_progress,
)
from exudyn_turnout.passage.fe_track.coupling import FEContactElement, FECoSimulation, run_progress
from exudyn_turnout.passage.fe_track.options import FEPassageOptions
from exudyn_turnout.passage.fe_track.planes import FETrackPlanes, build_fe_planes
from exudyn_turnout.passage.results import PassageResult
from exudyn_turnout.passage.safety import limits_for_friction
from exudyn_turnout.passage.settings import PassageError, PassageFailure, PassageSettings
from exudyn_turnout.passage.summary import check_plausible, passage_summary
from exudyn_turnout.passage.vehicle.start import (
    RELAX_STEP,
    FrozenPosition,
    record_start,
    steady_description,
)

__all__ = [
    "simulate_wheelset",
    "fe_contact_element",
    "static_equilibrium",
    "FEStaticState",
    "coupled_run_settings",
    "start_state",
    "RELAX_TIME",
]

#: s, the dynamic relaxation to steady curving at speed of a run that starts in a curve (x
#: frozen, the FE track stepped alongside at the start module's ``RELAX_STEP``): as the
#: co-running single wheelset's relaxation (passage/corunning_track/wheelset.py), which
#: settles below the start tolerance within its first two 1 s chunks; 3 s leaves a margin.
RELAX_TIME = 3.0

#: Vehicle coordinates in the element: wheelset (y, z, roll), yaw and spin, sprung (y, z).
_VEHICLE_NODES = ("wheelset", "yaw", "sprung")


@dataclass
class _System:
    """One Exudyn system of the FE passage: vehicle, coupled element, coordinate indices."""

    mbs: Any  #: exudyn.MainSystem
    container: Any  #: exudyn.SystemContainer
    coupled: FEContactElement
    index: np.ndarray  #: global ODE2 indices of the element's 7 vehicle coordinates
    nodes: dict  #: "wheelset", "yaw", "sprung" -> node number


def _build(vehicle: Vehicle, coupled: FEContactElement, z_w: float, z_s: float, roll: float):
    import exudyn as exu
    from exudyn.itemInterface import ObjectGenericODE2, ObjectGround

    from exudyn_turnout.passage.vehicle.wheelset import add_vehicle, element_matrices

    container = exu.SystemContainer()
    mbs = container.AddSystem()
    ground = mbs.AddObject(ObjectGround())
    veh = add_vehicle(mbs, vehicle, ground, z_w, z_s, spin=True, roll0=roll)
    nodes = dict(zip(_VEHICLE_NODES, (veh.wheelset_node, veh.yaw_node, veh.sprung_node)))
    M, K = element_matrices(vehicle, coupled.n, True)
    mbs.AddObject(
        ObjectGenericODE2(
            nodeNumbers=list(nodes.values()),
            massMatrix=M,
            stiffnessMatrix=K,
            forceUserFunction=coupled,
        )
    )
    mbs.Assemble()
    index = np.concatenate(
        [
            mbs.GetNodeODE2Index(nodes["wheelset"]) + np.arange(3),
            mbs.GetNodeODE2Index(nodes["yaw"]) + np.arange(2),
            mbs.GetNodeODE2Index(nodes["sprung"]) + np.arange(2),
        ]
    )
    return _System(mbs, container, coupled, index, nodes)


def _coordinates(system: _System, initial: bool = False) -> tuple[np.ndarray, np.ndarray]:
    import exudyn as exu

    kind = exu.ConfigurationType.Initial if initial else exu.ConfigurationType.Current
    data = system.mbs.systemData
    q = np.asarray(data.GetODE2Coordinates(kind))
    q_t = np.asarray(data.GetODE2Coordinates_t(kind))
    return q[system.index].copy(), q_t[system.index].copy()


def _solve_static(system: _System, x: float) -> None:

    from exudyn_turnout.corunning.track import simulation_settings

    sim = simulation_settings(1.0, 1.0)
    sim.staticSolver.newton.absoluteTolerance = 1e-4
    try:
        system.mbs.SolveStatic(sim, updateInitialValues=True)
    except Exception as err:  # Exudyn's SolverError, or ModelError from a user function
        raise PassageFailure(
            f"static equilibrium on the FE track not found at x = {x:g} m: {failure_reason(err)}"
        ) from None


class _Recorder:
    """The full element coordinates (vehicle and rail bodies) at the output times (every
    ``every``-th step, or where ``grid`` says in a run in pieces)."""

    def __init__(self, every: int, grid: StepGrid | None = None):
        self.every, self.count, self.grid = every, 0, grid
        self.t: list[float] = []
        self.q: list[np.ndarray] = []
        self.q_t: list[np.ndarray] = []

    def add(self, t: float, coupled: FEContactElement, last: bool = False) -> None:
        sample = self.grid.step(last) if self.grid is not None else None
        if sample if sample is not None else (self.count % self.every == 0 or last):
            self.t.append(t)
            self.q.append(coupled.q.copy())
            self.q_t.append(coupled.q_t.copy())
        self.count += 1


def simulate_wheelset(
    turnout: Turnout,
    settings: PassageSettings,
    vehicle: Vehicle,
    contact: RouteContact,
    route: Route,
    x_range: tuple[float, float],
    progress: Callable[[float, float], None] | None = None,
    options: FEPassageOptions | None = None,
    *,
    planes: FETrackPlanes | None = None,
) -> PassageResult:
    """Run the wheelset over the FE track with the profile contact (module docstring); the
    door is :func:`exudyn_turnout.passage.run.simulate_passage`, which checks the settings.

    Parameters
    ----------
    turnout : Turnout
    settings : PassageSettings
        Route, speed, time step, output step, ``spectral_radius`` (of Exudyn's
        generalized-alpha, used by the FE side too), ``irregularity``; ``layers``,
        ``source`` and ``track_mechanism`` do not apply.
    vehicle : Vehicle
        The single wheelset with its sprung mass.
    contact : RouteContact
        The route's profile contact for this vehicle.
    route : Route
        ``settings.route`` of the turnout.
    x_range : tuple of float
        m, start and end of the run (checked by the door).
    progress : callable(fraction, x), optional
        Called about every 2 % of the run.
    options : FEPassageOptions, optional
        Mesh and ``loss_reference_hz``
        (:class:`~exudyn_turnout.passage.fe_track.options.FEPassageOptions`).
    planes : FETrackPlanes, optional
        FE planes from :func:`~exudyn_turnout.passage.fe_track.planes.build_fe_planes` to
        reuse.

    Returns
    -------
    PassageResult
        The columns of :func:`~exudyn_turnout.passage.run.simulate_passage` with the
        profile contact (vertical and lateral forces per wheel and slot, contact points);
        ``y_rail_<slot>_m``, ``z_rail_<slot>_m`` are the FE rail head's displacement under
        the wheel. Summary: :func:`~exudyn_turnout.passage.summary.passage_summary` plus
        ``model`` "FE", DOF counts, time integration and wall time of each part.

    Raises
    ------
    PassageError
        The x range outside the FE layout, or a solver failure (time and position).
    """
    wall = time.perf_counter()
    options = options or FEPassageOptions()
    x_a, x_b = x_range
    planes = planes or build_fe_planes(turnout, options)
    lay = planes.layout
    if not (lay.x_start <= x_a and x_b <= lay.x_end):
        raise PassageError(
            f"x range {x_a:g}..{x_b:g} m must lie within the FE layout "
            f"({lay.x_start:g}..{lay.x_end:g} m)"
        )
    with QuietExudyn():
        return _simulate(
            turnout, settings, vehicle, route, contact, planes, x_a, x_b, progress, wall, options
        )


def _simulate(
    turnout, settings, vehicle, route, contact, planes, x_a, x_b, progress, wall, options
):
    v = settings.v
    duration = (x_b - x_a) / v
    n_steps = max(1, math.ceil(duration / settings.time_step - 1e-9))
    h = duration / n_steps
    every = max(1, round((settings.output_step or h) / h))
    track = FECoSimulation(planes, route.name, h, settings.spectral_radius, options)
    irr = settings.irregularity
    t0 = time.perf_counter()
    rest = static_equilibrium(track, contact, vehicle, route, x_a, irr)
    q0, loads = rest.vehicle_q, rest.wheel_loads
    q0_t = np.zeros_like(q0)
    curvature = float(route.curvature(x_a))
    if curvature != 0.0:  # in a curve: steady curving at speed, relaxed with x frozen
        start_element, forces, q0, q0_t, residual = _relax(
            planes, route, contact, vehicle, x_a, v, irr, options, rest
        )
        start = steady_description(settings.speed_kmh, curvature) + (
            f" (relaxed {RELAX_TIME:g} s with x frozen, FE track stepped alongside)"
        )
    else:
        start_element, forces = rest.element, rest.rail_forces
        start, residual = start_state(vehicle, route, x_a, v)
    track.start([start_element], [forces], v)
    static_s = time.perf_counter() - t0
    start_args = (q0, q0_t)
    t1 = time.perf_counter()

    def run(track, progress, pieces):
        """The run from the start state on ``track`` (``pieces``: the finer windows)."""
        return _run(
            settings, vehicle, route, contact, track, x_a, v, irr, duration, n_steps, every,
            start_args, progress, pieces, options,
        )  # fmt: skip

    progress, second = two_run_progress(progress, settings, route)
    moving, recorder = run(track, progress, None)
    steps_s = time.perf_counter() - t1
    W = 0.5 * (loads["left"] + loads["right"])
    columns = fe_columns(moving, recorder.t, recorder.q, recorder.q_t, x_a, v)
    pieces = check_rail_plan(settings, route, W, columns, n_steps, h)
    refined: list[tuple[float, float, float]] = []
    first_s = 0.0
    if pieces is not None:  # a loaded check rail: the run again, finer through it
        first_s = steps_s
        track = FECoSimulation(planes, route.name, h, settings.spectral_radius, options)
        track.start([start_element], [forces], v)
        t1 = time.perf_counter()
        moving, recorder = run(track, second, pieces)
        steps_s = time.perf_counter() - t1
        columns = fe_columns(moving, recorder.t, recorder.q, recorder.q_t, x_a, v)
        refined = [(a * h, b * h, h / m) for a, b, m in pieces if m > 1]
    elif second is not None:  # no second run after all: the line to its end
        second(1.0, x_b)
    check_plausible(columns, W, "FE track", limits_for_friction(vehicle.contact.mu))
    summary = passage_summary(
        columns,
        turnout,
        settings,
        loads,
        time.perf_counter() - wall,
        limits_for_friction(vehicle.contact.mu),
    )
    summary.update(fe_summary(planes, settings, track, h, n_steps, static_s, steps_s, first_s))
    record_start(summary, turnout, x_a, v, start, residual, stacklevel=5)
    check_rail_steps(settings, route, W, columns, summary, stacklevel=5, refined=refined)
    return PassageResult(replace(settings, x_start=x_a, x_end=x_b), columns, summary, (x_a,))


def _run(
    settings,
    vehicle,
    route,
    contact,
    track,
    x_a,
    v,
    irr,
    duration,
    n_steps,
    every,
    start,
    progress,
    pieces,
    options,
):
    """One run at speed from the start state: at the run's step throughout (``pieces``
    None: one SolveDynamic) or in pieces (:func:`~exudyn_turnout.passage.fe_track.common.
    solve_in_pieces`). Returns the moving contact element and the recorder."""
    import exudyn as exu

    from exudyn_turnout.passage.common import NEWTON_ABSOLUTE_TOLERANCE

    q0, q0_t = start
    h = duration / n_steps
    moving = fe_contact_element(contact, vehicle, route, x_a, v, irr)
    coupled = FEContactElement(moving, track)
    system = _build(vehicle, coupled, 0.0, 0.0, 0.0)
    data = system.mbs.systemData
    q_init = np.asarray(data.GetODE2Coordinates(exu.ConfigurationType.Initial)).copy()
    q_init[system.index] = q0
    data.SetODE2Coordinates(q_init, exu.ConfigurationType.Initial)
    q_t_init = np.asarray(data.GetODE2Coordinates_t(exu.ConfigurationType.Initial)).copy()
    q_t_init[system.index] = q0_t
    data.SetODE2Coordinates_t(q_t_init, exu.ConfigurationType.Initial)
    grid = None if pieces is None else StepGrid(every, options.check_rail_every_step)
    recorder = _Recorder(every, grid)
    report = run_progress(progress, duration, x_a, v)

    def pre_step(mbs, t):
        track.predict(t, [coupled])
        report(t)
        return True

    def post_step(mbs, t):
        if t != track.t_next and recorder.t:  # a piece's first call: its start, done
            return True
        q, q_t = _coordinates(system)
        if t == track.t_next:
            F = coupled.solve(t, q, q_t)
            track.complete([(coupled, F)])
        else:  # t = 0: the start state
            coupled.solve(t, q, q_t)
        recorder.add(t, coupled, last=abs(t - duration) < 0.5 * track.h)
        return True

    system.mbs.SetPreStepUserFunction(pre_step)
    system.mbs.SetPostStepUserFunction(post_step)
    sim = coupled_run_settings(duration, n_steps, settings, NEWTON_ABSOLUTE_TOLERANCE)
    try:
        if pieces is None:
            system.mbs.SolveDynamic(sim)
        else:
            solver: Any = exu.MainSolverImplicitSecondOrder()  # (its stubs leave out self)
            solve_in_pieces(solver, system.mbs, sim, pieces, h, duration, track.set_step, grid)
    except Exception as err:  # Exudyn's SolverError, or ModelError from a user function
        t = track.t_next if math.isfinite(track.t_next) else data.GetTime()
        raise PassageFailure(
            f"FE passage failed at t = {t:.5f} s, x = {x_a + v * t:.3f} m: {failure_reason(err)}"
        ) from None
    return moving, recorder


def start_state(vehicle: Vehicle, route: Route, x: float, v: float) -> tuple[str, float]:
    """The static start's ``summary["start"]`` and residual (a run on straight track).

    A run that starts on straight track starts from the static equilibrium at rest (lateral
    position and spin held): the steady state at speed up to what the holds carry (the
    creep forces at speed settle within centimetres). A run that starts in a curve is
    relaxed to steady curving instead (:func:`simulate_wheelset`); were it started at rest,
    what it left unbalanced would be the lateral curving load of the wheelset and its
    sprung mass, (m_w + m_s) v^2 |kappa|, which this returns there.

    Parameters
    ----------
    vehicle : Vehicle
    route : Route
    x : float
        m, start.
    v : float
        m/s, speed.

    Returns
    -------
    start : str
        "static at rest".
    residual : float
        N, the unbalanced lateral curving load.
    """
    kappa = abs(float(route.curvature(x)))
    return "static at rest", (vehicle.m_w + vehicle.m_s) * v * v * kappa


def _relax(planes, route, contact, vehicle, x, v, irr, options, rest):
    """Relax the wheelset at speed with x frozen from its static state, the FE track stepped
    alongside (its own track at the start module's ``RELAX_STEP``, rho_inf 0, field not
    moving), for :data:`RELAX_TIME`: as the FE full vehicle's relaxation
    (:mod:`~exudyn_turnout.passage.fe_track.vehicle`), whose static solve at speed fails in
    a curve (saturated creep). Returns the coupled element (frozen at x), its rail forces,
    the vehicle's coordinates and velocities, and the residual (N: the largest mass x
    lateral acceleration left on the wheelset or the sprung mass)."""
    import exudyn as exu

    from exudyn_turnout.passage.common import NEWTON_ABSOLUTE_TOLERANCE

    relax_track = FECoSimulation(planes, route.name, RELAX_STEP, 0.0, options)
    element = fe_contact_element(contact, vehicle, route, x, v, irr)
    element.x_at = FrozenPosition(x)  # an instance attribute shadows the method
    coupled = FEContactElement(element, relax_track)
    relax_track.start([coupled], [rest.rail_forces], 0.0)
    system = _build(vehicle, coupled, 0.0, 0.0, 0.0)
    data = system.mbs.systemData
    q_init = np.asarray(data.GetODE2Coordinates(exu.ConfigurationType.Initial)).copy()
    q_init[system.index] = rest.vehicle_q
    data.SetODE2Coordinates(q_init, exu.ConfigurationType.Initial)
    forces = [rest.rail_forces]

    def pre_step(mbs, t):
        relax_track.predict(t, [coupled])
        return True

    def post_step(mbs, t):
        q, q_t = _coordinates(system)
        F = coupled.solve(t, q, q_t)
        if t == relax_track.t_next:
            relax_track.complete([(coupled, F)])
        forces[0] = F
        return True

    system.mbs.SetPreStepUserFunction(pre_step)
    system.mbs.SetPostStepUserFunction(post_step)
    n_steps = round(RELAX_TIME / RELAX_STEP)
    sim = coupled_run_settings(
        RELAX_TIME, n_steps, PassageSettings(spectral_radius=0.0), NEWTON_ABSOLUTE_TOLERANCE
    )
    try:
        system.mbs.SolveDynamic(sim)
    except Exception as err:  # Exudyn's SolverError, or ModelError from a user function
        raise PassageFailure(
            f"steady curving at speed on the FE track not found at x = {x:g} m: "
            f"{failure_reason(err)}"
        ) from None
    q, q_t = _coordinates(system)
    a = np.asarray(data.GetODE2Coordinates_tt(exu.ConfigurationType.Current))[system.index]
    residual = max(vehicle.m_w * abs(float(a[0])), vehicle.m_s * abs(float(a[5])))
    return coupled, forces[0], q, q_t, residual


@dataclass(frozen=True)
class FEStaticState:
    """Static equilibrium of the vehicle on the FE track at one position."""

    x: float  #: m, wheelset position
    element: FEContactElement  #: the static element (its ``last`` holds bodies and r)
    vehicle_q: np.ndarray  #: the vehicle's 7 coordinates (m, rad)
    rail_forces: np.ndarray  #: N, forces on the coupled rail coordinates (y, z per body)
    rail_displacements: np.ndarray  #: m, the rail heads' (y, z) per coupled body
    wheel_loads: dict  #: N, "left", "right": total normal force on each wheel


def static_equilibrium(
    track: FECoSimulation, contact, vehicle: Vehicle, route: Route, x: float, irregularity=None
) -> FEStaticState:
    """The vehicle at rest on the FE track: Exudyn's static solve, rails on K^-1.

    The element's rail coordinates obey r = C_s F with the FE's static compliance
    C_s = G^T K^-1 G (lateral position and spin held, as on the co-running track).

    Parameters
    ----------
    track : FECoSimulation
        The FE track (its state is not changed).
    contact : RouteContact
        The route's rail bodies and tables.
    vehicle : Vehicle
    route : Route
    x : float
        m, wheelset position.
    irregularity : Irregularity, optional

    Returns
    -------
    FEStaticState

    Raises
    ------
    PassageFailure
        No equilibrium, or wheel loads that do not carry the vehicle.
    """
    from exudyn_turnout.passage.vehicle.wheelset import initial_guess

    rest = fe_contact_element(contact, vehicle, route, x, 0.0, irregularity)
    coupled = FEContactElement(rest, track)
    z_w, z_s = initial_guess(vehicle)
    z_touch, roll = rest.touching_position(x, -z_w / 3.0)
    track.begin_static([coupled])
    try:
        static = _build(vehicle, coupled, z_touch, z_touch + z_s - z_w, roll)
        _solve_static(static, x)
        q0, _ = _coordinates(static, initial=True)
        F0 = coupled.solve(0.0, q0, np.zeros_like(q0))
    finally:
        track.end_static()
    loads = rest.wheel_loads(x, coupled.q)
    _check_static(loads, vehicle, x)
    return FEStaticState(x, coupled, q0, F0, coupled.last[1].copy(), loads)


def _check_static(loads: dict, vehicle: Vehicle, x: float) -> None:
    total = loads["left"] + loads["right"]
    weight = 2.0 * vehicle.static_wheel_load
    if not abs(total - weight) <= 0.2 * weight:
        raise PassageFailure(
            f"absurd static state on the FE track at x = {x:g} m: the wheel loads sum to "
            f"{total:.4g} N, the vehicle weighs {weight:.4g} N"
        )
