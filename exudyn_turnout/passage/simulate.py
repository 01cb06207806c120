"""A wheelset passing through the turnout on a co-running track (paper Section 4).

The wheelset (:mod:`~exudyn_turnout.inputs.vehicle`) runs at constant speed along a route
(:mod:`~exudyn_turnout.inputs.routes`) over a two- or three-layer co-running track
(:mod:`~exudyn_turnout.corunning.track`) whose position-dependent stiffness and damping
follow the wheelset's x, coupled by the penalty wheel/rail contact of
:mod:`~exudyn_turnout.passage.contact_element`.

The run starts from static equilibrium at ``x_start`` and is split at the zone boundaries
(Table 3): in each zone a new Exudyn system is built with that zone's masses and active
rails, and the state of everything that continues (vehicle, sleeper, rails present in
both zones, or a rail slot that a route says continues another) is carried over.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from exudyn_turnout.corunning.parameters import CoRunningParameters, co_running_parameters
from exudyn_turnout.inputs.routes import Route, SpeedWarning, load_route, speed_warnings
from exudyn_turnout.inputs.turnout import Turnout, Zone
from exudyn_turnout.inputs.vehicle import Vehicle, load_vehicle
from exudyn_turnout.passage.contact_element import BoundPair, WheelRailElement
from exudyn_turnout.passage.results import (
    DEFAULT_SETTINGS,
    TRACKS,
    PassageError,
    PassageFailure,
    PassageResult,
    PassageSettings,
    check_plausible,
    passage_summary,
)
from exudyn_turnout.passage.vehicle import add_vehicle

if TYPE_CHECKING:
    from exudyn_turnout.passage.profile_contact import RouteContact

__all__ = [
    "simulate_passage",
    "compare_layers",
    "max_time_step",
    "contact_resonance",
    "lightest_rail_mass",
    "element_matrices",
]


#: Wheel/rail contact models of a passage (``PassageSettings.contact``).
CONTACT_MODELS = ("profile", "height-table")

#: N: Newton's absolute residual tolerance in a passage (see benchmarks/bench_passage.py).
NEWTON_ABSOLUTE_TOLERANCE = 1.0


def contact_resonance(vehicle: Vehicle, m_contact: float) -> float:
    """Wheel-on-rail resonance (Hz): half the wheelset on the linear Hertz spring over m_contact.

    Parameters
    ----------
    vehicle : Vehicle
    m_contact : float
        kg, the mass of rail under the wheel.

    Returns
    -------
    float
        Hz.
    """
    W = vehicle.static_wheel_load
    k_H = 1.5 * vehicle.contact.C_H ** (2.0 / 3.0) * W ** (1.0 / 3.0)  # dF/d delta at F = W
    m_w = 0.5 * vehicle.m_w
    return math.sqrt(k_H * (1.0 / m_w + 1.0 / m_contact)) / (2.0 * math.pi)


def max_time_step(vehicle: Vehicle, m_rail: float) -> float:
    """Largest time step (s) that resolves the wheel/rail contact: 10 steps per period.

    Parameters
    ----------
    vehicle : Vehicle
    m_rail : float
        kg, the lightest rail mass of the run (:func:`lightest_rail_mass`).

    Returns
    -------
    float
        s.
    """
    return 1.0 / (10.0 * contact_resonance(vehicle, m_rail))


def lightest_rail_mass(
    turnout: Turnout, x_a: float, x_b: float, layers: int = 3, source: str = "derived"
) -> float:
    """Lightest co-running rail mass m_r (kg) of the active rails between x_a and x_b.

    Evaluated from the actual parameter set (``layers``, ``source``) at both ends of each
    zone's part of the range; it sets the time-step limit (:func:`max_time_step`).

    Parameters
    ----------
    turnout : Turnout
    x_a, x_b : float
        Range of the run (m).
    layers : {2, 3}
    source : {"derived", "published"}

    Returns
    -------
    float
        kg.

    Raises
    ------
    PassageError
        The parameter set does not exist (e.g. ``source="published"`` without Table 2 for a zone).
    """
    masses = []
    for zone in _zones_of_run(turnout, x_a, x_b):
        try:
            p = co_running_parameters(turnout, zone=zone.index, layers=layers, source=source)
        except (KeyError, ValueError) as err:
            name = turnout.source.replace("\\", "/").rsplit("/", 1)[-1]
            raise PassageError(
                f"--source {source}: {name} has no parameter set for zone {zone.index} "
                f"({str(err).rsplit(': ', 1)[-1]})"
            ) from None
        for x in (max(zone.x_start, x_a), min(zone.x_end, x_b)):
            values = p.at(x)
            masses += [values[f"m_r{slot[1:]}"] for slot in zone.active_rails]
    return float(min(masses))


def _check(settings: PassageSettings, turnout: Turnout, vehicle: Vehicle) -> tuple[float, float]:
    s = settings
    if s.contact not in CONTACT_MODELS:
        raise PassageError(f"contact must be one of {', '.join(CONTACT_MODELS)}, got {s.contact!r}")
    if s.irregularity is not None and s.contact != "profile":
        raise PassageError("track irregularities need the profile contact (contact='profile')")
    if not (math.isfinite(s.speed_kmh) and 0 < s.speed_kmh <= 400):
        raise PassageError(f"speed must be > 0 and <= 400 km/h, got {s.speed_kmh:g} km/h")
    x_a = turnout.x_min if s.x_start is None else s.x_start
    x_b = turnout.x_max if s.x_end is None else s.x_end
    if not (turnout.x_min <= x_a < x_b <= turnout.x_max):
        raise PassageError(
            f"x range {x_a:g}..{x_b:g} m must lie within the turnout "
            f"({turnout.x_min:g}..{turnout.x_max:g} m) with x_start < x_end"
        )
    m_rail = lightest_rail_mass(turnout, x_a, x_b, s.layers, s.source)
    h_max = max_time_step(vehicle, m_rail)
    if not (math.isfinite(s.time_step) and 0 < s.time_step <= h_max):
        raise PassageError(
            f"time step {s.time_step:g} s is too large to resolve the wheel/rail contact "
            f"(~{contact_resonance(vehicle, m_rail):.0f} Hz with the lightest rail, "
            f"{m_rail:.4g} kg): use a step <= {h_max:.2g} s"
        )
    _check_output_step(s, (x_b - x_a) / s.v)
    return x_a, x_b


def _check_output_step(s: PassageSettings, duration: float) -> None:
    if s.output_step is None:
        return
    if not (math.isfinite(s.output_step) and s.time_step <= s.output_step <= duration):
        raise PassageError(
            f"output step {s.output_step:g} s must be >= the time step "
            f"({s.time_step:g} s) and <= the run's duration ({duration:.4g} s)"
        )


def _pair_key(wheel: str, rail: str) -> str:
    return f"{wheel}_{rail}"


def _segment_columns(
    element: WheelRailElement,
    t: np.ndarray,
    q: np.ndarray,
    force: np.ndarray,
    rails: Mapping[str, int],
) -> dict[str, np.ndarray]:
    """Forces and displacements of one zone's run.

    ``q``: stored element coordinates (samples x n); ``force``: the element's stored
    generalised forces, the left-hand side K q - f_user of its equations, so that the force
    a wheel puts on a rail is +force[z] (pressing down) and -force[y] (lateral, on the
    rail); ``rails``: slot -> index of its y in the element.
    """
    cols: dict[str, np.ndarray] = {"t_s": t, "x_m": element.x0 + element.v * t}
    wheel_of = {bp.pair.rail: bp.pair.wheel for bp in element.pairs}
    for wheel in ("right", "left"):
        for name in ("Fz", "Fy"):
            cols[f"{name}_{wheel}_N"] = np.zeros_like(t)
    for slot, i in rails.items():
        key = _pair_key(wheel_of[slot], slot)
        cols[f"Fz_{key}_N"], cols[f"Fy_{key}_N"] = force[:, i + 1].copy(), -force[:, i]
        cols[f"Fz_{wheel_of[slot]}_N"] += cols[f"Fz_{key}_N"]
        cols[f"Fy_{wheel_of[slot]}_N"] += cols[f"Fy_{key}_N"]
    for i, name in enumerate(
        ("y_wheelset_m", "z_wheelset_m", "roll_wheelset_rad", "yaw_wheelset_rad")
    ):
        cols[name] = q[:, i]
    for slot, i in rails.items():
        cols[f"y_rail_{slot}_m"], cols[f"z_rail_{slot}_m"] = q[:, i], q[:, i + 1]
    return cols


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


def _join(segments: list[dict[str, np.ndarray]]) -> dict[str, np.ndarray]:
    """Concatenate zone segments; a column missing in a segment is NaN there (rail not present)."""
    names: list[str] = []
    for seg in segments:
        names += [n for n in seg if n not in names]
    out = {}
    for n in names:
        out[n] = np.concatenate([seg.get(n, np.full(len(seg["t_s"]), np.nan)) for seg in segments])
    return out


@dataclass
class _ZoneSystem:
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
        return self.params.zone.sleeper_y


def element_matrices(vehicle: Vehicle, n: int, spin: bool) -> tuple[np.ndarray, np.ndarray]:
    """Mass and stiffness matrices of the contact element's own coordinates.

    The wheelset's yaw inertia and yaw stiffness (coordinate 3) and, with profile contact,
    its spin inertia (coordinate 4) sit in the contact element (their nodes are generic).

    Parameters
    ----------
    vehicle : Vehicle
    n : int
        Number of the element's coordinates.
    spin : bool
        The element has the spin perturbation (profile contact).

    Returns
    -------
    M, K : numpy.ndarray
        (n, n), kg (kg m^2) and N/m (N m/rad).
    """
    M, K = np.zeros((n, n)), np.zeros((n, n))
    M[3, 3], K[3, 3] = vehicle.J_yaw, vehicle.k_yaw
    if spin:
        if vehicle.J_spin is None:
            raise PassageError("the vehicle has no spin inertia: the profile contact needs it")
        M[4, 4] = vehicle.J_spin
    return M, K


def _initial_guess(vehicle: Vehicle) -> tuple[float, float]:
    """Wheelset and sprung-mass z (m) with the contacts closed, so Hertz springs have stiffness."""
    W = vehicle.static_wheel_load
    z_w = -3.0 * (W / vehicle.contact.C_H) ** (2.0 / 3.0)
    return z_w, z_w - 0.5 * vehicle.m_s * 9.81 / vehicle.k_z


def _build(
    turnout: Turnout,
    route: Route,
    vehicle: Vehicle,
    zone: Zone,
    settings: PassageSettings,
    x0: float,
    v: float,
    route_contact: RouteContact | None = None,
) -> _ZoneSystem:
    from dataclasses import replace

    import exudyn as exu
    from exudyn.itemInterface import ObjectGenericODE2, SensorBody, SensorNode

    from exudyn_turnout.corunning.track import add_co_running_track

    container = exu.SystemContainer()
    mbs = container.AddSystem()
    params = co_running_parameters(
        turnout, zone=zone.index, layers=settings.layers, source=settings.source
    )
    params = replace(params, zone=route.zone(params.zone))
    track = add_co_running_track(mbs, params, x0, v, mechanism=settings.track_mechanism)
    profile = route_contact is not None
    element: Any
    if profile:
        assert route_contact is not None
        try:
            element, slots = route_contact.element(
                vehicle, route, zone, x0, v, settings.irregularity
            )
        except ValueError as err:
            raise PassageError(str(err)) from None
        z_w, z_s = _initial_guess(vehicle)
        z_touch, roll = element.touching_position(x0, -z_w / 3.0)
        veh = add_vehicle(
            mbs, vehicle, track.ground, z_touch, z_touch + z_s - z_w, spin=True, roll0=roll
        )
    else:
        veh = add_vehicle(mbs, vehicle, track.ground, *_initial_guess(vehicle))
        pairs = [p for p in route.pairs_in(zone) if p.rail in zone.active_rails]
        slots = [r for r in zone.active_rails if any(p.rail == r for p in pairs)]
        for r in slots:
            if len({p.wheel for p in pairs if p.rail == r}) > 1:
                raise PassageError(
                    f"route {route.name}: rail {r} is touched by both wheels in zone {zone.index}"
                )
        rails_of = {r: 6 + 2 * i for i, r in enumerate(slots)}
        element = WheelRailElement(
            vehicle,
            route,
            [BoundPair(p, rails_of[p.rail], rails_of[p.rail] + 1) for p in pairs],
            x0,
            v,
        )
    rails = {r: element.n_vehicle + 2 * i for i, r in enumerate(slots)}
    nodes = [veh.wheelset_node, veh.yaw_node, veh.sprung_node] + [
        track.wheel_nodes[r] for r in slots
    ]
    M, K = element_matrices(vehicle, element.n, profile)
    contact = mbs.AddObject(
        ObjectGenericODE2(
            nodeNumbers=nodes, massMatrix=M, stiffnessMatrix=K, forceUserFunction=element
        )
    )
    force_sensor = -1
    if not profile:  # the profile element's outputs are computed from stored states
        force_sensor = mbs.AddSensor(
            SensorBody(
                bodyNumber=contact,
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
    return _ZoneSystem(container, mbs, zone, element, names, rails, sensors, params, force_sensor)


def _node_state(system: _ZoneSystem) -> dict[str, tuple[np.ndarray, np.ndarray]]:
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


_NODE_DOF = {"sleeper": ("y_t", "z_t", "phi_t")}


def _dof_of(name: str) -> tuple[str, ...]:
    """Coordinate names (corunning.modal) of a track node ("rail_r1", "m0_r1", "sleeper")."""
    if name in _NODE_DOF:
        return _NODE_DOF[name]
    kind, _, slot = name.partition("_")
    return (f"y_{slot}", f"z_{slot}") if kind == "rail" else (f"y_m0_{slot}", f"z_m0_{slot}")


def _track_vector(state: dict, system: _ZoneSystem, index: int) -> dict[str, float]:
    """Track coordinates (index 0) or velocities (1) of ``state`` by coordinate name."""
    out: dict[str, float] = {}
    for name in system.names:
        if name in ("wheelset", "yaw", "sprung"):
            continue
        out.update(zip(_dof_of(name), state[name][index]))
    return out


def _wheel_rail_loads(
    system: _ZoneSystem, state: dict, layers: int
) -> dict[str, tuple[float, float]]:
    """Total (vertical, lateral) force on each rail slot touched, from the element at ``state``."""
    q = np.concatenate([state[n][0] for n in _element_nodes(system, layers)])
    q_t = np.concatenate([state[n][1] for n in _element_nodes(system, layers)])
    el = system.element
    return el.rail_loads(el.x_at(system.mbs.systemData.GetTime()), q, q_t)


def _static_deflection(
    params,
    x: float,
    loads: Mapping[str, tuple[float, float]],
    layers: int,
    lateral: bool = False,
) -> dict[str, float]:
    """u = K^-1 f of the co-running track (by coordinate name) under the wheel loads.

    Vertical loads always; lateral loads only with ``lateral`` (the profile contact, whose
    lateral forces at rest are the real N tan(gamma) of each contact point, so that the new
    zone starts in lateral equilibrium too). For the height-table contact lateral loads are
    left out on purpose: the two rails' lateral deflections change in opposite directions at
    a zone boundary, which a rigid wheelset cannot follow, and on its conical tread that
    would turn into a vertical load step; lateral states carry over.
    """
    from exudyn_turnout.corunning.modal import assemble_track_matrices, wheel_dof

    m = assemble_track_matrices(params, x)
    f = np.zeros(len(m.dof))
    for rail, (N, F_y) in loads.items():
        if rail in params.active_rails:
            f[m.index(wheel_dof(rail, "vertical", layers))] -= N
            if lateral:
                f[m.index(wheel_dof(rail, "lateral", layers))] += F_y
    return dict(zip(m.dof, np.linalg.solve(m.K, f)))


def _carry_over(
    state: dict,
    old: _ZoneSystem,
    new: _ZoneSystem,
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
    import exudyn as exu

    loads_old = _wheel_rail_loads(old, state, layers)
    source = {slot: continues.get(slot, slot) for slot in new.params.active_rails}
    loads_new = {slot: loads_old[src] for slot, src in source.items() if src in loads_old}
    lateral = old.element.lateral_static_loads
    u_old = _static_deflection(old.params, x, loads_old, layers, lateral)
    u_new = _static_deflection(new.params, x, loads_new, layers, lateral)
    q_old, v_old = _track_vector(state, old, 0), _track_vector(state, old, 1)
    dyn = {n: q_old[n] - u_old[n] for n in q_old}
    shift = new.sleeper_y - old.sleeper_y  # the sleeper's reference point moved with the zone
    dyn["z_t"] += shift * dyn["phi_t"]
    v_old["z_t"] += shift * v_old["phi_t"]
    q_new, v_new = {}, {}
    for name in u_new:
        axis, _, rest = name.partition("_")
        slot = rest.rsplit("_", 1)[-1]
        src = (
            name.replace(slot, source[slot]) if slot in source else name
        )  # sleeper names have no slot
        if src in dyn:
            q_new[name], v_new[name] = u_new[name] + dyn[src], v_old[src]
        else:  # a rail that appears: the sleeper's motion under it
            arm = new.params.zone.rail_y[slot] - new.sleeper_y
            k = 0 if axis == "y" else 1
            q_new[name] = u_new[name] + (dyn["y_t"] if k == 0 else dyn["z_t"] + arm * dyn["phi_t"])
            v_new[name] = v_old["y_t"] if k == 0 else v_old["z_t"] + arm * v_old["phi_t"]
    vehicle_shift = _vehicle_shift(old, u_old, u_new, loads_old, source, layers)
    mbs, data = new.mbs, new.mbs.systemData
    q = np.asarray(data.GetODE2Coordinates(exu.ConfigurationType.Initial)).copy()
    q_t = np.zeros_like(q)
    for name, node in new.names.items():
        i = mbs.GetNodeODE2Index(node)
        if name in ("wheelset", "yaw", "sprung"):
            values, rates = state[name][0] + vehicle_shift[name], state[name][1]
        else:
            dofs = _dof_of(name)
            values, rates = np.array([q_new[d] for d in dofs]), np.array([v_new[d] for d in dofs])
        q[i : i + len(values)], q_t[i : i + len(values)] = values, rates
    data.SetODE2Coordinates(q, exu.ConfigurationType.Initial)
    data.SetODE2Coordinates_t(q_t, exu.ConfigurationType.Initial)


def _vehicle_shift(
    old: _ZoneSystem,
    u_old: dict,
    u_new: dict,
    loads: Mapping,
    source: Mapping[str, str],
    layers: int,
) -> dict[str, np.ndarray]:
    """Move wheelset and sprung mass with the change of static rail deflection under each wheel."""
    from exudyn_turnout.corunning.modal import wheel_dof

    b = old.element.vehicle.b
    dz: dict[str, list[float]] = {"left": [], "right": []}
    dy: dict[str, list[float]] = {"left": [], "right": []}
    new_slot = {
        src: slot for slot, src in source.items()
    }  # source holds the new zone's active slots only
    for rail, wheel in old.element.wheel_of.items():
        N = loads.get(rail, (0.0, 0.0))[0]
        if N <= 0.0 or rail not in new_slot:
            continue
        for axis, acc in (("vertical", dz), ("lateral", dy)):
            a, b_ = wheel_dof(rail, axis, layers), wheel_dof(new_slot[rail], axis, layers)
            if a in u_old and b_ in u_new:
                acc[wheel].append(u_new[b_] - u_old[a])
    mean = {
        w: (float(np.mean(dz[w])) if dz[w] else 0.0, float(np.mean(dy[w])) if dy[w] else 0.0)
        for w in dz
    }
    z, y = 0.5 * (mean["left"][0] + mean["right"][0]), 0.5 * (mean["left"][1] + mean["right"][1])
    roll = (mean["left"][0] - mean["right"][0]) / (2.0 * b)
    # profile contact: a roll moves the running surfaces sideways by r0 roll; move the
    # wheelset back by as much so the wheels stay where they touch
    y -= old.element.running_surface_depth * roll
    n_yaw = old.element.n_vehicle - 5  # yaw (and spin) coordinates
    return {"wheelset": np.array([y, z, roll]), "yaw": np.zeros(n_yaw), "sprung": np.array([y, z])}


def _element_nodes(system: _ZoneSystem, layers: int) -> list[str]:
    body = "m0" if layers == 3 else "rail"
    return ["wheelset", "yaw", "sprung"] + [f"{body}_{r}" for r in system.rails]


def _wheel_loads(system: _ZoneSystem, state: dict, layers: int) -> dict[str, float]:
    """Total normal force (N) on each wheel in ``state``."""
    q = np.concatenate([state[n][0] for n in _element_nodes(system, layers)])
    el = system.element
    return el.wheel_loads(el.x0, q)


def _solve_static(system: _ZoneSystem) -> None:
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


def _progress_function(
    progress: Callable[[float, float], None], t_offset: float, total: float, x0: float, v: float
) -> Callable:
    due = [0.0]

    def pre_step(mbs, t):
        if t >= due[0]:
            due[0] = t + 0.02 * total
            progress(min((t_offset + t) / total, 1.0), x0 + v * t)
        return True

    return pre_step


def _run(
    system: _ZoneSystem,
    duration: float,
    settings: PassageSettings,
    t_offset: float,
    total: float,
    progress: Callable | None,
) -> dict[str, np.ndarray]:
    """Integrate one zone for ``duration`` s; return its columns (time shifted by t_offset)."""
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
    if progress is not None:
        system.mbs.SetPreStepUserFunction(
            _progress_function(progress, t_offset, total, el.x0, el.v)
        )
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
        cols = _segment_columns(el, t, q, force, system.rails)
    else:
        n = q.shape[1] // 2
        cols = _profile_columns(el, t, q[:, :n], q[:, n:], system.rails)
    cols["t_s"] = t + t_offset
    return cols


def _zones_of_run(turnout: Turnout, x_a: float, x_b: float) -> list[Zone]:
    return [z for z in turnout.zones if min(z.x_end, x_b) - max(z.x_start, x_a) > 1e-9]


def simulate_passage(
    turnout: Turnout,
    settings: PassageSettings = DEFAULT_SETTINGS,
    vehicle: Vehicle | None = None,
    progress: Callable[[float, float], None] | None = None,
    *,
    track: str | None = None,
    fe_options=None,
) -> PassageResult:
    """Run the vehicle through the turnout on a co-running track or on the FE track.

    One entry point whatever the track: ``track="2-layer"`` or ``"3-layer"`` (the paper's
    co-running models, Figs 2, 3) or ``"fe"`` (the FE reference, vertical and lateral, with
    the same vehicle and profile contact:
    :func:`~exudyn_turnout.passage.fe_passage.simulate_fe_profile_passage`; with
    ``settings.contact = "height-table"`` the older vertical-only FE passage
    :func:`~exudyn_turnout.passage.fe_track.simulate_fe_passage`).

    Parameters
    ----------
    turnout : Turnout
        From :func:`~exudyn_turnout.inputs.turnout.load_turnout`.
    settings : PassageSettings
        The scenario: route, speed, x range, time step, output step; for the co-running
        tracks also the parameter source and the spring mechanism.
    vehicle : Vehicle, optional
        Default: the packaged Manchester benchmark wheelset.
    progress : callable(fraction, x), optional
        Called about every 2 % of the run.
    track : {"2-layer", "3-layer", "fe"}, optional
        Default: ``settings.layers`` layers of co-running track.
    fe_options : FEPassageOptions, optional
        Mesh and solver options of the FE track (``track="fe"`` only).

    Returns
    -------
    PassageResult
        ``columns``: ``t_s``, ``x_m``; per wheel and rail ``Fz_<wheel>_<rail>_N`` (normal force
        pressing the rail down) and ``Fy_<wheel>_<rail>_N`` (lateral force on the rail, positive
        left); per wheel ``Fz_<wheel>_N``, ``Fy_<wheel>_N``; wheelset ``y``, ``z``, ``roll``,
        ``yaw``; per rail touched, the contact body's ``y_rail_<rail>_m``, ``z_rail_<rail>_m``
        (NaN where that rail is not part of the zone). ``summary``: peaks (see
        :func:`passage_summary`).

    Raises
    ------
    PassageError
        Bad settings (one line naming the problem) or a solver failure (time and position).
    """
    if track is not None and track not in TRACKS:
        raise PassageError(f"track must be one of {', '.join(TRACKS)}, got {track!r}")
    if track == "fe" and settings.contact == "profile":
        from exudyn_turnout.passage.fe_passage import simulate_fe_profile_passage

        return simulate_fe_profile_passage(
            turnout, settings, vehicle, fe_options, progress=progress
        )
    if track == "fe":  # the vertical FE passage with its own height-table contact
        from exudyn_turnout.passage.fe_track import simulate_fe_passage

        return simulate_fe_passage(turnout, settings, vehicle, fe_options, progress=progress)
    if track is not None:
        settings = replace(settings, layers=int(track[0]))
    vehicle = vehicle or load_vehicle()
    x_a, x_b = _check(settings, turnout, vehicle)
    route = load_route(turnout, settings.route)
    for text in speed_warnings(route, settings.speed_kmh, x_a, x_b):
        warnings.warn(text, SpeedWarning, stacklevel=2)
    zones = _zones_of_run(turnout, x_a, x_b)
    wall = time.perf_counter()
    with _QuietExudyn():
        return _simulate(turnout, settings, vehicle, route, zones, x_a, x_b, progress, wall)


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
) -> PassageResult:
    v = settings.v
    contact = None
    if settings.contact == "profile":
        from exudyn_turnout.passage.profile_contact import route_contact

        try:
            contact = route_contact(turnout, route.name, vehicle)
        except ValueError as err:
            raise PassageError(str(err)) from None
    static = _build(turnout, route, vehicle, zones[0], settings, x_a, 0.0, contact)
    _solve_static(static)
    state = _node_state(static)
    static_loads = _wheel_loads(static, state, settings.layers)
    _check_static(state, static_loads, x_a, vehicle)
    W = 0.5 * (static_loads["left"] + static_loads["right"])
    segments, x, t_offset, previous, total = [], x_a, 0.0, static, (x_b - x_a) / v
    for k, zone in enumerate(zones):
        system = _build(turnout, route, vehicle, zone, settings, x, v, contact)
        _carry_over(
            state,
            previous,
            system,
            route.continues.get(zone.index, {}) if k else {},
            settings.layers,
            x,
        )
        duration = (min(zone.x_end, x_b) - x) / v
        cols = _run(system, duration, settings, t_offset, total, progress)
        check_plausible(cols, W, f"zone {zone.index}, {zone.name}")
        segments.append(cols if k == 0 else {n: c[1:] for n, c in cols.items()})
        state, previous = _node_state(system), system
        x, t_offset = min(zone.x_end, x_b), t_offset + duration
    columns = _join(segments)
    summary = passage_summary(columns, turnout, settings, static_loads, time.perf_counter() - wall)
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


class _QuietExudyn:
    """Silence Exudyn's console warnings (e.g. on user-function memory use) during a solve."""

    def __enter__(self):
        import exudyn as exu

        self._saved = exu.config.suppressWarnings, exu.config.printToConsole
        exu.config.suppressWarnings, exu.config.printToConsole = True, False

    def __exit__(self, *exc):
        import exudyn as exu

        exu.config.suppressWarnings, exu.config.printToConsole = self._saved
        return False


def compare_layers(
    turnout: Turnout, settings: PassageSettings = DEFAULT_SETTINGS, vehicle: Vehicle | None = None
) -> dict[int, PassageResult]:
    """The same passage on the two-layer and the three-layer track.

    Parameters
    ----------
    turnout : Turnout
    settings : PassageSettings
        ``layers`` is replaced.
    vehicle : Vehicle, optional

    Returns
    -------
    dict
        {2: PassageResult, 3: PassageResult}.
    """
    from dataclasses import replace

    return {
        layers: simulate_passage(turnout, replace(settings, layers=layers), vehicle)
        for layers in (2, 3)
    }
