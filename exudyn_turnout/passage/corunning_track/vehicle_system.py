"""The full vehicle's run segment: its Exudyn system and the state carried between segments.

A run of :mod:`~exudyn_turnout.passage.corunning_track.vehicle` is cut into segments where
any wheelset crosses x_min, a zone boundary or x_max; each segment is one Exudyn system
(:func:`build_segment`: the vehicle, one co-running track per wheelset in the zone of
:func:`place_of`, the contacts' object), and the next one starts from the last one's final
state (:func:`named_state`, :func:`carry_over_state`: vehicle bodies unchanged, a wheelset's
track re-based where its zone changed, the other tracks copied). The run itself, its start
and the check rail's re-run are in :mod:`~exudyn_turnout.passage.corunning_track.vehicle`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from exudyn_turnout.corunning.parameters import co_running_parameters
from exudyn_turnout.inputs.routes import Route
from exudyn_turnout.inputs.turnout import RAIL_SLOTS, Turnout, Zone
from exudyn_turnout.inputs.vehicle import Vehicle
from exudyn_turnout.inputs.vehicle_model import VehicleModel
from exudyn_turnout.passage.contact.profile import RouteContact
from exudyn_turnout.passage.contact.vehicle_contacts import (
    VehicleContacts,
    WheelsetContactElement,
)
from exudyn_turnout.passage.corunning_track.carry_over import (
    dof_of,
    inside_zone,
    rebase_track,
    set_named_state,
    vehicle_shift,
)
from exudyn_turnout.passage.settings import PassageError, PassageSettings
from exudyn_turnout.passage.vehicle.body_sensors import add_body_sensors
from exudyn_turnout.passage.vehicle.track_frame import (
    DUMMY_MASS,
    DUMMY_STIFFNESS,
    BodyLoads,
    add_vehicle_loads,
    set_initial_vehicle,
)

__all__ = [
    "VARIABLES_KEY",
    "WheelsetPlace",
    "SegmentSystem",
    "place_of",
    "build_segment",
    "named_state",
    "element_vector",
    "track_vector",
    "carry_over_state",
]

#: ``mbs.variables`` key of a built system's (contacts, body loads, kept objects)
VARIABLES_KEY = "exudyn_turnout.corunning_track.vehicle"


@dataclass(frozen=True)
class WheelsetPlace:
    """Where one wheelset's track and contact are in a run segment.

    Parameters
    ----------
    zone : Zone
        The zone whose parameters its track and contact take.
    clamped : bool
        Behind the turnout's start: zone 1 at x_min.
    beyond : bool
        Past the turnout's end: the last zone at x_max.
    """

    zone: Zone
    clamped: bool  #: behind the turnout's start: zone 1 at x_min
    beyond: bool = False  #: past the turnout's end: the last zone at x_max


@dataclass
class SegmentSystem:
    """One run segment's Exudyn system (:func:`build_segment`).

    Parameters
    ----------
    container : exudyn.SystemContainer
        Keeps ``mbs`` alive.
    mbs : exudyn.MainSystem
        The assembled system; ``mbs.variables[VARIABLES_KEY]`` its (contacts, body loads,
        kept objects).
    places : tuple of WheelsetPlace
        Per wheelset, where its track and contact are.
    elements : list of WheelsetContactElement
        Per wheelset, its contact element.
    params : list of CoRunningParameters
        Per wheelset, its track's parameters.
    slots : list of tuple of str
        Per wheelset, the rail slots of its element in coordinate order.
    names : dict
        Node name -> node (``"car_body"``, ``"bogie1"``, ``"ws1"``, ``"t1:sleeper"``,
        ``"t1:m0_r1"`` ...).
    sensors : list
        Per wheelset, (coordinate sensors, velocity sensors) of its element's nodes.
    body_loads : BodyLoads
        The car body's and bogies' loads in the track-following frame.
    x_front : float
        m, the front wheelset's position at t = 0.
    """

    container: Any
    mbs: Any
    places: tuple[WheelsetPlace, ...]
    elements: list  #: per wheelset, its WheelsetContactElement
    params: list  #: per wheelset, its track's CoRunningParameters
    slots: list  #: per wheelset, rail slots of its element in coordinate order
    names: dict  #: node name -> node ("car_body", "bogie1", "ws1", "t1:sleeper", "t1:m0_r1")
    sensors: list  #: per wheelset, (coordinate sensors, velocity sensors) of its element nodes
    body_loads: BodyLoads
    x_front: float  #: m, front wheelset's position at t = 0


def place_of(turnout: Turnout, x: float) -> WheelsetPlace:
    """The zone of a wheelset at x: behind x_min zone 1 (clamped), past x_max the last zone.

    Parameters
    ----------
    turnout : Turnout
    x : float
        m, the wheelset's position.

    Returns
    -------
    WheelsetPlace
    """
    if x < turnout.x_min - 1e-9:
        return WheelsetPlace(turnout.zones[0], True)
    if x > turnout.x_max + 1e-9:
        return WheelsetPlace(turnout.zones[-1], False, True)
    for zone in turnout.zones:
        if zone.x_start - 1e-9 <= x < zone.x_end - 1e-9:
            return WheelsetPlace(zone, False)
    return WheelsetPlace(turnout.zones[-1], False)


def build_segment(
    turnout: Turnout,
    route: Route,
    model: VehicleModel,
    vehicle: Vehicle,
    contact: RouteContact,
    settings: PassageSettings,
    places: tuple[WheelsetPlace, ...],
    x_front: float,
    v: float,
    frozen: bool,
    x_range: tuple[float, float],
    tables: dict | None = None,
    parameters: dict | None = None,
) -> SegmentSystem:
    """Build one run segment's Exudyn system: the vehicle, every wheelset's co-running track
    in its zone and its contact element (the module docstring of
    :mod:`~exudyn_turnout.passage.corunning_track.vehicle`)::

        car body -- bogies -- wheelsets (linear suspension, bumpstops on the contacts' object)
                                 |  contact element (profile contact, dummy sprung mass)
                       rails -- [layers] -- sleeper   one co-running track per wheelset

    Parameters
    ----------
    turnout : Turnout
    route : Route
    model : VehicleModel
        The full vehicle.
    vehicle : Vehicle
        The contact's vehicle (sprung mass 0:
        :func:`~exudyn_turnout.passage.vehicle.track_frame.contact_vehicle`).
    contact : RouteContact
        The route's profile contact.
    settings : PassageSettings
        Layers, source, track mechanism, irregularity.
    places : tuple of WheelsetPlace
        Per wheelset (:func:`place_of`).
    x_front : float
        m, the front wheelset's position at t = 0.
    v : float
        m/s, the speed.
    frozen : bool
        x held (the static solves and the relaxation at speed).
    x_range : (float, float)
        m, the run's range (the body loads' table).
    tables : dict, optional
        The running loads' table, shared by the segments.
    parameters : dict, optional
        Zone index -> its co-running parameters, filled and shared by the builds.

    Returns
    -------
    SegmentSystem
        Assembled, the vehicle at its initial state.
    """
    import exudyn as exu
    from exudyn.itemInterface import NodeGenericODE2, ObjectGenericODE2, SensorNode

    from exudyn_turnout.corunning.track import add_co_running_track
    from exudyn_turnout.corunning.track_kernel import TrackPlacement, track_force
    from exudyn_turnout.passage.vehicle import builder as vehicle_builder
    from exudyn_turnout.passage.vehicle.builder import add_vehicle_model

    container = exu.SystemContainer()
    mbs = container.AddSystem()
    build = add_vehicle_model(
        mbs, model, representation="linear", wheelset_spin=True, bumpstop="none"
    )
    names: dict[str, int] = {b.name: b.node for b in build.bodies() if b.name[:5] != "wheel"}
    elements, params_all, slots_all, sensors = [], [], [], []
    contact_nodes: list[int] = []
    compiled = settings.track_mechanism == "compiled"
    placements = []  #: per track (compiled): (params, x, v, {coordinate: (node, local)})
    for i, (ws, place) in enumerate(zip(build.wheelsets, places)):
        x_i = x_front + ws.x
        # a wheelset placed on a zone boundary by round-off (x0 + v t) builds its track at the
        # boundary itself: the zone's parameters are defined on [x_start, x_end] only
        x_track = (
            turnout.x_min
            if place.clamped
            else turnout.x_max
            if place.beyond
            else inside_zone(place.zone, x_i)
        )
        # a zone's parameters, derived once per run (``parameters``: zone index -> them)
        params = None if parameters is None else parameters.get(place.zone.index)
        if params is None:
            params = co_running_parameters(
                turnout, zone=place.zone.index, layers=settings.layers, source=settings.source
            )
            params = replace(params, zone=route.zone(params.zone))
            if parameters is not None:
                parameters[place.zone.index] = params
        v_track = 0.0 if (place.clamped or place.beyond or frozen) else v
        track = add_co_running_track(
            mbs, params, x_track, v_track, mechanism=settings.track_mechanism, force_object=False
        )
        if compiled:
            placements.append((params, x_track, v_track, _coordinate_nodes(track)))
        try:
            raw, slots = contact.element(vehicle, route, place.zone, x_i, v, settings.irregularity)
        except ValueError as err:
            raise PassageError(str(err)) from None
        element = WheelsetContactElement.of(raw, turnout.x_min, turnout.x_max)
        element.frozen = frozen
        dummy = int(
            mbs.AddNode(
                NodeGenericODE2(
                    referenceCoordinates=[0.0, 0.0],
                    initialCoordinates=[0.0, 0.0],
                    initialCoordinates_t=[0.0, 0.0],
                    numberOfODE2Coordinates=2,
                )
            )
        )
        rail_nodes = [track.wheel_nodes[r] for r in slots]
        contact_nodes += [ws.node, dummy] + rail_nodes
        sensors.append(
            tuple(
                [
                    mbs.AddSensor(
                        SensorNode(
                            nodeNumber=n,
                            storeInternal=True,
                            writeToFile=False,
                            outputVariableType=kind,
                        )
                    )
                    for n in [ws.node] + rail_nodes
                ]
                for kind in (
                    exu.OutputVariableType.Coordinates,
                    exu.OutputVariableType.Coordinates_t,
                )
            )
        )
        names[f"ws{i + 1}"] = ws.node
        names[f"dummy{i + 1}"] = dummy
        names[f"t{i + 1}:sleeper"] = track.sleeper_node
        names.update({f"t{i + 1}:rail_{r}": n for r, n in track.rail_nodes.items()})
        names.update({f"t{i + 1}:m0_{r}": n for r, n in track.layer_nodes.items()})
        elements.append(element)
        params_all.append(params)
        slots_all.append(slots)
    stiffness = mbs.GetObjectParameter(build.items["suspension"], "stiffnessMatrix")
    stiffness = np.asarray(stiffness.GetPythonObject(), float)
    damping = mbs.GetObjectParameter(build.items["suspension"], "dampingMatrix")
    damping = np.asarray(damping.GetPythonObject(), float)
    loads = BodyLoads(build, stiffness, damping, route, x_front, v, *x_range)
    loads.frozen = frozen
    add_body_sensors(mbs, build, loads)  # car body, bogies: columns after the run
    if tables is not None:
        loads.tabulate(tables)
    stops = None
    car = build.car_body
    # the bumpstops ride on the contacts' object, and in a curve the curving loads too
    fold = model.bumpstop is not None and car is not None
    if fold and car is not None:
        size, (stop_force, stop_jacobian) = vehicle_builder.linear_bumpstop_functions(
            model, car, build.bogies
        )
        arrays = vehicle_builder.linear_bumpstop_arrays(model, car, build.bogies)
        stops = (size, stop_force, stop_jacobian, arrays)
        contact_nodes += [car.node] + [b.node for b in build.bogies]
    forces, n_track = None, 0
    if compiled:  # the tracks' springs ride on the contacts' object (module docstring)
        offsets, size = {}, 0
        for node in contact_nodes:
            offsets[node] = size
            size += len(mbs.GetNode(node)["referenceCoordinates"])
        n_shared = size
        for *_, coordinates in placements:
            for node, _ in coordinates.values():
                if node not in offsets:
                    offsets[node] = size
                    size += len(mbs.GetNode(node)["referenceCoordinates"])
                    contact_nodes.append(node)
        n_track = size - n_shared
        forces = track_force(
            [
                TrackPlacement(p, x, v_p, {d: offsets[n] + j for d, (n, j) in c.items()})
                for p, x, v_p, c in placements
            ]
        )
    body_loads = None
    if fold and loads.curved:  # the loads' coordinates (every body's) in the object's vector
        at, size = {}, 0
        for node in contact_nodes:
            at[node] = size
            size += len(mbs.GetNode(node)["referenceCoordinates"])
        index = [
            at[b.node] + j
            for b in build.bodies()
            for j in range(len(mbs.GetNode(b.node)["referenceCoordinates"]))
        ]
        body_loads = (loads, np.array(index, dtype=np.int64))
    contacts = VehicleContacts(elements, stops, forces, n_track, body_loads)
    dummies = [names[f"dummy{i + 1}"] for i in range(len(elements))]
    n_dummy = 2 * len(dummies)
    mbs.AddObject(  # the dummy sprung masses, decoupled
        ObjectGenericODE2(
            nodeNumbers=dummies,
            massMatrix=DUMMY_MASS * np.eye(n_dummy),
            stiffnessMatrix=DUMMY_STIFFNESS * np.eye(n_dummy),
        )
    )
    mbs.AddObject(
        ObjectGenericODE2(
            nodeNumbers=contact_nodes,
            forceUserFunction=contacts.force_function(),
            jacobianUserFunction=contacts.jacobian_function,
        )
    )
    keep = add_vehicle_loads(mbs, build, loads) if (loads.curved and not fold) else ()
    mbs.variables[VARIABLES_KEY] = (contacts, loads, keep)
    mbs.Assemble()
    system = SegmentSystem(
        container, mbs, places, elements, params_all, slots_all, names, sensors, loads, x_front
    )
    set_initial_vehicle(system, build)
    return system


def _coordinate_nodes(track: Any) -> dict[str, tuple[int, int]]:
    """A track's coordinates (dof names) as (node, local index)."""
    pairs = [(track.sleeper_node, j) for j in range(3)]
    for group in (track.rail_nodes, track.layer_nodes):
        pairs += [(group[r], j) for r in RAIL_SLOTS if r in group for j in (0, 1)]
    return dict(zip(track.dof, pairs))


def named_state(system: SegmentSystem) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """The system's current coordinates and velocities per named node.

    Parameters
    ----------
    system : SegmentSystem

    Returns
    -------
    dict
        Node name (``system.names``) -> (coordinates, velocities).
    """
    import exudyn as exu

    data, mbs = system.mbs.systemData, system.mbs
    q = np.asarray(data.GetODE2Coordinates(exu.ConfigurationType.Current))
    q_t = np.asarray(data.GetODE2Coordinates_t(exu.ConfigurationType.Current))
    out = {}
    for name, node in system.names.items():
        i = mbs.GetNodeODE2Index(node)
        k = np.atleast_1d(mbs.GetNodeOutput(node, exu.OutputVariableType.Coordinates)).size
        out[name] = (q[i : i + k].copy(), q_t[i : i + k].copy())
    return out


def element_vector(system: SegmentSystem, state: Mapping, i: int, index: int) -> np.ndarray:
    """Element coordinates (index 0) or velocities (1) of wheelset i (0-based) in ``state``.

    Parameters
    ----------
    system : SegmentSystem
        The system ``state`` is of.
    state : mapping
        :func:`named_state`'s.
    i : int
        The wheelset (0-based).
    index : {0, 1}
        Coordinates or velocities.

    Returns
    -------
    numpy.ndarray
        Wheelset, dummy sprung mass, then the element's rail slots (contact bodies).
    """
    body = "m0" if system.params[i].layers == 3 else "rail"
    parts = [state[f"ws{i + 1}"][index], state[f"dummy{i + 1}"][index]]
    parts += [state[f"t{i + 1}:{body}_{r}"][index] for r in system.slots[i]]
    return np.concatenate(parts)


def track_vector(state: Mapping, system: SegmentSystem, i: int, index: int) -> dict[str, float]:
    """Coordinates (index 0) or velocities (1) of wheelset i's track by dof name.

    Parameters
    ----------
    state : mapping
        :func:`named_state`'s.
    system : SegmentSystem
        The system ``state`` is of.
    i : int
        The wheelset (0-based).
    index : {0, 1}
        Coordinates or velocities.

    Returns
    -------
    dict
        Dof name (:func:`~exudyn_turnout.passage.corunning_track.carry_over.dof_of`) ->
        value.
    """
    out: dict[str, float] = {}
    prefix = f"t{i + 1}:"
    for name in system.names:
        if name.startswith(prefix):
            out.update(zip(dof_of(name[len(prefix) :]), state[name][index]))
    return out


def carry_over_state(
    state: Mapping,
    old: SegmentSystem,
    new: SegmentSystem,
    route: Route,
    layers: int,
    x_front: float,
    t_old: float,
) -> None:
    """Set ``new``'s initial state from ``old``'s final ``state`` (module docstring).

    Parameters
    ----------
    state : mapping
        ``old``'s final state (:func:`named_state`).
    old, new : SegmentSystem
        The segment ending and the one starting.
    route : Route
        Its zones' continuing rails.
    layers : int
        The tracks' layers.
    x_front : float
        m, the front wheelset's position at the boundary (unused; kept for the callers).
    t_old : float
        s, the old segment's duration (its elements' x at its end).
    """
    values: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    for name in new.names:
        if not name.startswith("t"):
            values[name] = (state[name][0].copy(), state[name][1].copy())
    for i, (p_old, p_new) in enumerate(zip(old.places, new.places)):
        prefix = f"t{i + 1}:"
        if p_old.zone.index == p_new.zone.index:  # same zone (or leaving the clamp): copy
            for name in new.names:
                if name.startswith(prefix):
                    values[name] = state[name]
            continue
        el = old.elements[i]
        x = el.x_at(t_old)
        q_el, v_el = element_vector(old, state, i, 0), element_vector(old, state, i, 1)
        loads_old = el.rail_loads(x, q_el, v_el)
        continues = route.continues.get(p_new.zone.index, {})
        q_old, v_old = track_vector(state, old, i, 0), track_vector(state, old, i, 1)
        # the boundary itself, in each zone's own range (x0 + v t carries round-off)
        q_new, v_new, u_old, u_new, source = rebase_track(
            old.params[i],
            new.params[i],
            inside_zone(old.params[i].zone, x),
            inside_zone(new.params[i].zone, x),
            loads_old,
            continues,
            q_old,
            v_old,
            layers,
            True,
        )
        for name in new.names:
            if name.startswith(prefix):
                dofs = dof_of(name[len(prefix) :])
                values[name] = (
                    np.array([q_new[d] for d in dofs]),
                    np.array([v_new[d] for d in dofs]),
                )
        moved = vehicle_shift(el, u_old, u_new, loads_old, source, layers)
        q_ws = values[f"ws{i + 1}"][0]
        q_ws[:3] = q_ws[:3] + moved["wheelset"]
    set_named_state(new.mbs, new.names, values)
