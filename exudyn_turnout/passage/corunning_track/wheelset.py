"""A wheelset passing through the turnout on a co-running track (paper Section 4).

The wheelset (:mod:`~exudyn_turnout.inputs.vehicle`) runs at constant speed along a route
(:mod:`~exudyn_turnout.inputs.routes`) over a two- or three-layer co-running track
(:mod:`~exudyn_turnout.corunning.track`) whose position-dependent stiffness and damping
follow the wheelset's x, coupled by the penalty wheel/rail contact of
:mod:`~exudyn_turnout.passage.contact.height_table`.

The run starts from static equilibrium at ``x_start`` or, where the route is curved there,
in steady curving at speed: from the static state, a dynamic relaxation with x frozen (the
contact's creep at speed v, the track's springs at x_start, the curving load on) until the
vehicle is at rest in the track-following frame (``summary["start"]``,
``summary["start_residual"]``; :mod:`~exudyn_turnout.passage.vehicle.start`, which also
warns when a region of the turnout begins before the vehicle has settled). On straight
track the static state is kept (the steady state up to what the lateral hold carries: the
straight-track results do not change). The run is then split at the zone boundaries
(Table 3): in each zone a new Exudyn system is built with that zone's masses and active
rails, and the state of everything that continues (vehicle, sleeper, rails present in
both zones, or a rail slot that a route says continues another) is carried over. A zone
where a check-rail contact carried load at a step coarser than
``settings.check_rail_time_step`` runs again from its start at that step to the load's end
(:class:`~exudyn_turnout.passage.check_rail_steps.CheckRailSteps`, as the full vehicle's segments):
a zone predicted to load it (the wheelset displaced towards it by half its clearance at the
zone's start; the profile contact only) runs at that step directly, the fine stepping ended
during the run; one not predicted that loads it runs at its step first, then again (the
safety net). The progress never goes back. The diverging route at 80 km/h, 2 layers,
20..55 m: the same windows and peaks as the after-the-fact method's, every column within
1.7e-9 of its largest value, for 0.90x its CPU time (4 rounds alternating in fresh
processes, medians 0.575 -> 0.518 s).
"""

from __future__ import annotations

import functools
import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from exudyn_turnout.corunning.parameters import CoRunningParameters, co_running_parameters
from exudyn_turnout.inputs.routes import Route
from exudyn_turnout.inputs.turnout import Turnout, Zone
from exudyn_turnout.inputs.vehicle import Vehicle
from exudyn_turnout.passage.check_rail_steps import CheckRailSteps, CheckRailStop
from exudyn_turnout.passage.common import (
    NEWTON_ABSOLUTE_TOLERANCE,
    QuietExudyn,
    join_segments,
    monotone_progress,
    progress_function,
    zones_of_run,
)
from exudyn_turnout.passage.contact.profile import STATIC_LATERAL_STIFFNESS
from exudyn_turnout.passage.contact.protocol import Contact
from exudyn_turnout.passage.corunning_track.carry_over import (
    dof_of,
    rebase_track,
    set_named_state,
    vehicle_shift,
)
from exudyn_turnout.passage.corunning_track.relax import relax_frozen
from exudyn_turnout.passage.results import PassageResult
from exudyn_turnout.passage.safety import limits_for_friction
from exudyn_turnout.passage.settings import PassageError, PassageFailure, PassageSettings
from exudyn_turnout.passage.summary import check_plausible, passage_summary
from exudyn_turnout.passage.vehicle.start import (
    RELAX_CHUNK,
    FrozenPosition,
    record_start,
    steady_description,
)
from exudyn_turnout.passage.vehicle.wheelset import add_vehicle, element_matrices, initial_guess

__all__ = ["simulate_wheelset", "build_zone_system", "ZoneSystem"]


def _profile_columns(
    element: Any, t: np.ndarray, q: np.ndarray, q_t: np.ndarray, rails: Mapping[str, int]
) -> dict[str, np.ndarray]:
    """Columns of one zone's run with profile contact, from stored coordinates and velocities."""
    cols: dict[str, np.ndarray] = {"t_s": t, "x_m": element.x0 + element.v * t}
    cols.update(element.columns(t, q, q_t))
    for i, name in enumerate(
        (
            "y_wheelset_m",
            "z_wheelset_m",
            "roll_wheelset_rad",
            "yaw_wheelset_rad",
            "spin_wheelset_rad",
        )
    ):
        cols[name] = q[:, i]
    for slot, i in rails.items():
        cols[f"y_rail_{slot}_m"], cols[f"z_rail_{slot}_m"] = q[:, i], q[:, i + 1]
    return cols


@dataclass
class ZoneSystem:
    """One zone's Exudyn system and what the passage needs of it."""

    container: Any  #: exudyn.SystemContainer
    mbs: Any  #: exudyn.MainSystem
    zone: Zone
    element: Any  #: WheelRailElement or ProfileContactElement
    names: dict  #: node name ("wheelset", "yaw", "sprung", "sleeper", "rail_r1", "m0_r1") -> node
    rails: dict  #: rail slot touched by a wheel -> index of its y in the element
    sensors: list  #: sensors of the coordinates of the element's nodes, in element order
    params: CoRunningParameters  #: the zone's set, with the route's cross-section
    #: stores the contact element's generalised forces every step (-1: profile contact,
    #: whose outputs come from the stored coordinates and velocities)
    force_sensor: int

    @property
    def sleeper_y(self) -> float:
        """m, lateral position of the zone's sleeper reference point."""
        return self.params.zone.sleeper_y


def build_zone_system(
    turnout: Turnout,
    route: Route,
    vehicle: Vehicle,
    zone: Zone,
    settings: PassageSettings,
    x0: float,
    v: float,
    contact: Contact,
    frozen: bool = False,
) -> ZoneSystem:
    """One zone's Exudyn system: the co-running track of the zone under the wheelset, the
    vehicle, and the contact element coupling them.

    ::

        sprung mass ---- primary suspension ---- wheelset (y, z, roll, yaw [, spin])
                                                    |  contact element (penalty)
        rail bodies m_r (y, z) per active rail slot  --- [3 layers: m0 bodies] ---
        sleeper (y_t, z_t, phi_t) --- ballast/ground (co-running springs at x0 + v t)

    Parameters
    ----------
    turnout : Turnout
    route : Route
    vehicle : Vehicle
    zone : Zone
        The zone (Table 3) whose parameters and active rails the track has.
    settings : PassageSettings
        Layers, parameter source, spring mechanism, irregularity.
    x0, v : float
        m, m/s: the wheelset's position at t = 0 and speed (0: static).
    contact : Contact
        Makes the zone's contact element.
    frozen : bool
        The wheelset stays at x0 whatever t (the steady-state start at speed: the contact
        has the creep of speed v, the track its springs at x0).

    Returns
    -------
    ZoneSystem
        The assembled system and what the passage reads of it.
    """
    import exudyn as exu
    from exudyn.itemInterface import ObjectGenericODE2, SensorBody, SensorNode

    from exudyn_turnout.corunning.track import add_co_running_track

    container = exu.SystemContainer()
    mbs = container.AddSystem()
    params = co_running_parameters(
        turnout, zone=zone.index, layers=settings.layers, source=settings.source
    )
    params = replace(params, zone=route.zone(params.zone))
    v_track = 0.0 if frozen else v
    track = add_co_running_track(mbs, params, x0, v_track, mechanism=settings.track_mechanism)
    profile = contact.profile
    element: Any
    try:
        element, slots = contact.element(vehicle, route, zone, x0, v, settings.irregularity)
    except ValueError as err:
        raise PassageError(str(err)) from None
    if frozen:  # the element's position: x0 at every t (an instance attribute shadows x_at)
        element.x_at = FrozenPosition(element.x0)
    if profile:
        z_w, z_s = initial_guess(vehicle)
        z_touch, roll = element.touching_position(x0, -z_w / 3.0)
        veh = add_vehicle(
            mbs, vehicle, track.ground, z_touch, z_touch + z_s - z_w, spin=True, roll0=roll
        )
    else:
        veh = add_vehicle(mbs, vehicle, track.ground, *initial_guess(vehicle))
    rails = {r: element.n_vehicle + 2 * i for i, r in enumerate(slots)}
    nodes = [veh.wheelset_node, veh.yaw_node, veh.sprung_node] + [
        track.wheel_nodes[r] for r in slots
    ]
    M, K = element_matrices(vehicle, element.n, profile)
    contact_object = mbs.AddObject(
        ObjectGenericODE2(
            nodeNumbers=nodes, massMatrix=M, stiffnessMatrix=K, forceUserFunction=element
        )
    )
    force_sensor = -1
    if not profile:  # the profile element's outputs are computed from stored states
        force_sensor = mbs.AddSensor(
            SensorBody(
                bodyNumber=contact_object,
                storeInternal=True,
                writeToFile=False,
                outputVariableType=exu.OutputVariableType.Force,
            )
        )
    sensors = [
        mbs.AddSensor(
            SensorNode(
                nodeNumber=n,
                storeInternal=True,
                writeToFile=False,
                outputVariableType=kind,
            )
        )
        for kind in (
            (exu.OutputVariableType.Coordinates, exu.OutputVariableType.Coordinates_t)
            if profile
            else (exu.OutputVariableType.Coordinates,)
        )
        for n in nodes
    ]
    names = {
        "wheelset": veh.wheelset_node,
        "yaw": veh.yaw_node,
        "sprung": veh.sprung_node,
        "sleeper": track.sleeper_node,
    }
    names.update({f"rail_{r}": n for r, n in track.rail_nodes.items()})
    names.update({f"m0_{r}": n for r, n in track.layer_nodes.items()})
    mbs.Assemble()
    return ZoneSystem(container, mbs, zone, element, names, rails, sensors, params, force_sensor)


def _node_state(system: ZoneSystem) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    import exudyn as exu

    data = system.mbs.systemData
    q = np.asarray(data.GetODE2Coordinates(exu.ConfigurationType.Current))
    q_t = np.asarray(data.GetODE2Coordinates_t(exu.ConfigurationType.Current))
    out = {}
    for name, node in system.names.items():
        i = system.mbs.GetNodeODE2Index(node)
        k = np.atleast_1d(system.mbs.GetNodeOutput(node, exu.OutputVariableType.Coordinates)).size
        out[name] = (q[i : i + k].copy(), q_t[i : i + k].copy())
    return out


def _track_vector(state: dict, system: ZoneSystem, index: int) -> dict[str, float]:
    """Track coordinates (index 0) or velocities (1) of ``state`` by coordinate name."""
    out: dict[str, float] = {}
    for name in system.names:
        if name in ("wheelset", "yaw", "sprung"):
            continue
        out.update(zip(dof_of(name), state[name][index]))
    return out


def _wheel_rail_loads(
    system: ZoneSystem, state: dict, layers: int
) -> dict[str, tuple[float, float]]:
    """Total (vertical, lateral) force on each rail slot touched, from the element at ``state``."""
    q = np.concatenate([state[n][0] for n in _element_nodes(system, layers)])
    q_t = np.concatenate([state[n][1] for n in _element_nodes(system, layers)])
    el = system.element
    return el.rail_loads(el.x_at(system.mbs.systemData.GetTime()), q, q_t)


def _carry_over(
    state: dict,
    old: ZoneSystem,
    new: ZoneSystem,
    continues: Mapping[str, str],
    layers: int,
    x: float,
) -> None:
    """Set the new zone's initial state from the old zone's final ``state``.

    The static part of the track's deflection is re-based: the old zone's static deflection
    under the current wheel loads is replaced by the new zone's (its parameters differ),
    and the wheelset and sprung mass move with the rails they stand on, so that no wheel
    load jumps; the dynamic deviation from static equilibrium and all velocities carry
    over. A rail that appears starts with the sleeper's motion under it.
    """
    loads_old = _wheel_rail_loads(old, state, layers)
    lateral = old.element.lateral_static_loads
    q_old, v_old = _track_vector(state, old, 0), _track_vector(state, old, 1)
    q_new, v_new, u_old, u_new, source = rebase_track(
        old.params, new.params, x, x, loads_old, continues, q_old, v_old, layers, lateral
    )
    moved = vehicle_shift(old.element, u_old, u_new, loads_old, source, layers)
    values = {}
    for name in new.names:
        if name in ("wheelset", "yaw", "sprung"):
            values[name] = (state[name][0] + moved[name], state[name][1])
        else:
            dofs = dof_of(name)
            values[name] = (np.array([q_new[d] for d in dofs]), np.array([v_new[d] for d in dofs]))
    set_named_state(new.mbs, new.names, values)


def _element_nodes(system: ZoneSystem, layers: int) -> list[str]:
    body = "m0" if layers == 3 else "rail"
    return ["wheelset", "yaw", "sprung"] + [f"{body}_{r}" for r in system.rails]


def _wheel_loads(system: ZoneSystem, state: dict, layers: int) -> dict[str, float]:
    """Total normal force (N) on each wheel in ``state``."""
    q = np.concatenate([state[n][0] for n in _element_nodes(system, layers)])
    el = system.element
    return el.wheel_loads(el.x0, q)


def _solve_static(system: ZoneSystem) -> None:
    import exudyn as exu

    from exudyn_turnout.corunning.track import simulation_settings

    sim = simulation_settings(1.0, 1.0)
    sim.staticSolver.newton.absoluteTolerance = 1e-4
    try:
        system.mbs.SolveStatic(sim, updateInitialValues=True)
    except (exu.SolverError, RuntimeError) as err:
        raise PassageFailure(
            f"static equilibrium not found at x = {system.element.x0:g} m "
            f"(zone {system.zone.index}): {err}"
        ) from None


def _relax(system: ZoneSystem, vehicle: Vehicle) -> float:
    """Relax the frozen ``system`` to the steady state at speed
    (:func:`~exudyn_turnout.passage.corunning_track.relax.relax_frozen`, at least two
    chunks); return the residual (N): the largest mass x lateral acceleration left on the
    wheelset and the sprung mass."""
    mbs = system.mbs
    ws, yaw, sprung = (mbs.GetNodeODE2Index(system.names[n]) for n in ("wheelset", "yaw", "sprung"))
    where = f"at x = {system.element.x0:g} m (zone {system.zone.index})"
    residual, _ = relax_frozen(
        mbs,
        # the vehicle's coordinates but the spin (its rate is steady, not zero)
        [ws, ws + 1, ws + 2, yaw, sprung, sprung + 1],
        [(ws, vehicle.m_w), (sprung, vehicle.m_s)],
        where,
        settle_after=RELAX_CHUNK,
    )
    return residual


def _run(
    system: ZoneSystem,
    duration: float,
    settings: PassageSettings,
    t_offset: float,
    total: float,
    progress: Callable | None,
    stop: CheckRailStop | None = None,
) -> dict[str, np.ndarray]:
    """Integrate one zone for ``duration`` s; return its columns (time shifted by t_offset);
    ``stop`` (the predicted check rail's fine piece, ``CheckRailSteps.run_predicted``) may
    end the run early."""
    import exudyn as exu

    from exudyn_turnout.corunning.track import simulation_settings

    h = settings.time_step
    sim = simulation_settings(
        duration, h, 0.999 * (settings.output_step or h)
    )  # every step: no rounding skips
    sim.timeIntegration.numberOfSteps = max(1, int(math.ceil(duration / h - 1e-9)))
    sim.timeIntegration.generalizedAlpha.spectralRadius = settings.spectral_radius
    # 1 N residual: 2e-5 of a wheel load; peaks equal those at 1e-4 N to 0.2 N, with half
    # the iterations
    sim.timeIntegration.newton.absoluteTolerance = NEWTON_ABSOLUTE_TOLERANCE
    el = system.element
    pre_step = None
    if progress is not None:
        pre_step = progress_function(progress, t_offset, total, el.x0, el.v)
    if stop is not None:
        watch, report = stop, pre_step
        check_force = _check_force(el, stop.pairs)
        state = functools.partial(_node_state, system)

        def pre_step(mbs, t):
            if report is not None:
                report(mbs, t)
            return watch(check_force, state)

    if pre_step is not None:
        system.mbs.SetPreStepUserFunction(pre_step)
    try:
        system.mbs.SolveDynamic(sim)
    except (exu.SolverError, RuntimeError) as err:
        t = system.mbs.systemData.GetTime()
        raise PassageFailure(
            f"solver failed at t = {t_offset + t:.5f} s, x = {el.x_at(t):.3f} m "
            f"(zone {system.zone.index}, {system.zone.name}): {str(err).strip()}"
        ) from None
    stored = [system.mbs.GetSensorStoredData(sensor) for sensor in system.sensors]
    t = stored[0][:, 0]
    q = np.hstack([a[:, 1:] for a in stored])
    if int(system.force_sensor) >= 0:
        force = system.mbs.GetSensorStoredData(system.force_sensor)[:, 1:]
    else:
        force = np.zeros((len(t), 1))
    finite = np.all(np.isfinite(q), axis=1) & np.all(np.isfinite(force), axis=1)
    if not finite.all():
        bad = t[~finite][0]
        raise PassageFailure(
            f"solution diverged at t = {t_offset + bad:.5f} s, x = {el.x_at(bad):.3f} m "
            f"(zone {system.zone.index}): reduce the time step"
        )
    if int(system.force_sensor) >= 0:
        cols = el.force_columns(t, q, force, system.rails)
    else:
        n = q.shape[1] // 2
        cols = _profile_columns(el, t, q[:, :n], q[:, n:], system.rails)
    cols["t_s"] = t + t_offset
    return cols


def _check_force(element: Any, pairs: tuple[tuple[str, str], ...]) -> Callable[[], float]:
    """A function giving the check rails' largest contact force (N, |(Fy, Fz)|, as
    ``check_rail_window`` takes it from the columns) at the element's last evaluation."""
    picks = []
    for wheel, slot in pairs:
        seen = {
            (b.i_y, b.i_z)
            for b in element.bodies
            if b.rail == slot and element.wheel_of.get(slot) == wheel
        }
        if seen:
            iy, iz = zip(*sorted(seen))
            picks.append((np.array(iy), np.array(iz)))

    def force() -> float:
        f = element.last_forces()
        return max(
            (math.hypot(float(f[iy].sum()), float(f[iz].sum())) for iy, iz in picks),
            default=0.0,
        )

    return force


def simulate_wheelset(
    turnout: Turnout,
    settings: PassageSettings,
    vehicle: Vehicle,
    contact: Contact,
    route: Route,
    x_range: tuple[float, float],
    progress: Callable[[float, float], None] | None = None,
    options: None = None,
) -> PassageResult:
    """Run the single wheelset through the turnout on the co-running track of
    ``settings.layers`` layers (the door is :func:`exudyn_turnout.passage.run.simulate_passage`).

    Parameters
    ----------
    turnout : Turnout
        From :func:`~exudyn_turnout.inputs.turnout.load_turnout`.
    settings : PassageSettings
        The scenario: route, speed, x range, layers, parameter source, time step, output
        step, spring mechanism.
    vehicle : Vehicle
        The single wheelset with its sprung mass.
    contact : Contact
        The route's wheel/rail contact (:class:`~exudyn_turnout.passage.contact.protocol.Contact`):
        it makes each zone's contact element.
    route : Route
        ``settings.route`` of the turnout.
    x_range : tuple of float
        m, start and end of the run (checked by the door).
    progress : callable(fraction, x), optional
        Called about every 2 % of the run.
    options : None
        The co-running track has no options (the FE track's interface has them).

    Returns
    -------
    PassageResult
        ``columns``: ``t_s``, ``x_m``; per wheel and rail ``Fz_<wheel>_<rail>_N`` (normal force
        pressing the rail down) and ``Fy_<wheel>_<rail>_N`` (lateral force on the rail, positive
        left); per wheel ``Fz_<wheel>_N``, ``Fy_<wheel>_N``; wheelset ``y``, ``z``, ``roll``,
        ``yaw``; per rail touched, the contact body's ``y_rail_<rail>_m``, ``z_rail_<rail>_m``
        (NaN where that rail is not part of the zone). ``summary``: peaks (see
        :func:`~exudyn_turnout.passage.summary.passage_summary`).

    Raises
    ------
    PassageFailure
        A solver failure (time and position) or an absurd static state.
    """
    del options
    x_a, x_b = x_range
    zones = zones_of_run(turnout, x_a, x_b)
    wall = time.perf_counter()
    with QuietExudyn():
        return _simulate(
            turnout, settings, vehicle, route, zones, x_a, x_b, progress, wall, contact
        )


def _simulate(
    turnout: Turnout,
    settings: PassageSettings,
    vehicle: Vehicle,
    route: Route,
    zones: list[Zone],
    x_a: float,
    x_b: float,
    progress: Callable | None,
    wall: float,
    contact: Contact,
) -> PassageResult:
    v = settings.v
    static = build_zone_system(turnout, route, vehicle, zones[0], settings, x_a, 0.0, contact)
    _solve_static(static)
    state = _node_state(static)
    static_loads = _wheel_loads(static, state, settings.layers)
    _check_static(state, static_loads, x_a, vehicle)
    W = 0.5 * (static_loads["left"] + static_loads["right"])
    curvature = float(route.curvature(x_a))
    if curvature != 0.0:  # in a curve: the steady curving state at speed
        static = build_zone_system(
            turnout, route, vehicle, zones[0], settings, x_a, v, contact, frozen=True
        )
        set_named_state(static.mbs, static.names, state)
        residual = _relax(static, vehicle)
        state = _node_state(static)
        start = steady_description(settings.speed_kmh, curvature)
    else:  # straight: at rest is the steady state up to what the holds carry
        # the lateral hold's force; the spin hold's torque is released in ~1 ms (spin
        # inertia over the creep's damping 2 r0^2 f11 / v), not counted
        residual = STATIC_LATERAL_STIFFNESS * abs(float(state["wheelset"][0][0]))
        start = "static at rest"
    segments, x, t_offset, previous, total = [], x_a, 0.0, static, (x_b - x_a) / v
    # the height-table contact has no per-contact columns: no check rail seen
    check = CheckRailSteps(settings, route, W)
    progress = monotone_progress(progress)  # a zone run again reports its times again
    for k, zone in enumerate(zones):
        continues = route.continues.get(zone.index, {}) if k else {}
        duration = (min(zone.x_end, x_b) - x) / v
        where = f"zone {zone.index}, {zone.name}"
        limits = limits_for_friction(vehicle.contact.mu)
        #: the pieces' start states by their start time (s from the zone's start): a piece
        #: run again starts where it started before, a new one where the last ended
        begun: dict[float, list] = {}
        carried: list[Any] = [state, previous]

        def run_piece(
            t_from, length, x_p, step_settings, stop=None, zone=zone, t0=t_offset,
            carried=carried, begun=begun, continues=continues, where=where, limits=limits,
        ):  # fmt: skip
            origin = begun.setdefault(t_from, list(carried))
            system = build_zone_system(turnout, route, vehicle, zone, settings, x_p, v, contact)
            # the first piece continues the zone before; the others their own zone
            went_on = continues if t_from == 0.0 else {}
            _carry_over(*origin, system, went_on, settings.layers, x_p)
            piece = _run(system, length, step_settings, t0 + t_from, total, progress, stop)
            check_plausible(piece, W, where, limits)
            if stop is not None and stop.state is not None:  # the fine piece ends at stop.end
                carried[:] = [stop.state, system]
            else:
                carried[:] = [_node_state(system), system]
            return piece

        # predicted to load a check rail (the profile contact: the height table has no
        # check-rail contact): the fine step directly
        y = [float(state["wheelset"][0][0])]
        fine_from = check.predict(x, x + v * duration, (0.0,), y) if contact.profile else None
        if fine_from is not None:
            cols, _ = check.run_predicted(duration, t_offset, x, fine_from, run_piece)
        else:
            cols = run_piece(0.0, duration, x, settings)
            window = check.window(cols)
            if window is not None and check.step is not None:  # again, the window finer
                cols, _ = check.rerun_unpredicted(cols, window, duration, t_offset, x, run_piece)
            elif window is not None:
                check.unrefined(window, cols)
        system = carried[1]
        segments.append(cols if k == 0 else {n: c[1:] for n, c in cols.items()})
        state, previous = _node_state(system), system
        x, t_offset = min(zone.x_end, x_b), t_offset + duration
    columns = join_segments(segments)
    summary = passage_summary(
        columns,
        turnout,
        settings,
        static_loads,
        time.perf_counter() - wall,
        limits_for_friction(vehicle.contact.mu),
    )
    record_start(summary, turnout, x_a, v, start, residual, stacklevel=4)
    check.record(summary, stacklevel=4)
    return PassageResult(settings, columns, summary, tuple(max(z.x_start, x_a) for z in zones))


def _check_static(
    state: Mapping[str, tuple[np.ndarray, np.ndarray]],
    loads: Mapping[str, float],
    x: float,
    vehicle: Vehicle,
) -> None:
    """Stop on an absurd static state: deflections beyond :data:`PLAUSIBLE`, or wheel loads
    that do not carry the vehicle (their sum off the weight by more than 20 %)."""
    cols = {
        "t_s": np.zeros(1),
        "x_m": np.full(1, x),
        "z_wheelset_m": state["wheelset"][0][1:2],
        "y_wheelset_m": state["wheelset"][0][0:1],
    }
    for name, (q, _) in state.items():
        if name.startswith("rail_"):
            cols[f"z_{name}_m"] = q[1:2]
    try:
        check_plausible(cols, vehicle.static_wheel_load, "static equilibrium")
    except PassageFailure as err:
        message = str(err).replace("implausible run stopped", "absurd static state")
        raise PassageFailure(message) from None
    total = loads["left"] + loads["right"]
    if not abs(total - 2.0 * vehicle.static_wheel_load) <= 0.2 * 2.0 * vehicle.static_wheel_load:
        raise PassageFailure(
            f"absurd static state at x = {x:g} m: the wheel loads sum to {total:.4g} N, "
            f"the vehicle weighs {2.0 * vehicle.static_wheel_load:.4g} N"
        )
