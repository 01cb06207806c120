"""The vehicle of a :class:`~exudyn_turnout.inputs.vehicle_model.VehicleModel` in Exudyn.

Axes (compatible with the co-running track, ``corunning/track.py``, and the single wheelset
of ``passage/vehicle.py``): Exudyn X = lateral y (positive left), Y = vertical z (up), Z =
longitudinal x (forward); (y, z, x) is right-handed. Rotation about Z = roll (positive lifts
the left wheel), about X = pitch (for a wheelset: spin), about Y = yaw. Heights are above
the rail top: a body's reference position is (0, CoG height, x), its reference rotation
zero; the vehicle reference (x = 0) is the front wheelset. The vehicle runs at constant
speed in a moving frame: no body has a longitudinal coordinate (rigid representation: it is
held by a coordinate constraint).

::

    side view (x forward, to the right of the page)

                      car body (CoG G at 1.8 m)               secondary, per bogie side:
     +-------------------------------------------------+     k_x k_y k_z c_y c_z at +-b2,
     |                        G                        |     0.8275 m; per bogie: yaw and
     +-------------------------------------------------+     anti-roll torsion, lateral
          S [B] S                         S [B] S             bumpstop [B] (+-25 mm free)
      +-------------+  bogie 2         +-------------+  bogie 1 (CoG 0.6 m)
      |  P       P  |                  |  P       P  |   primary, per axlebox: k_x k_y
      +-------------+                  +-------------+   k_z c_z at +-b1, axle height
        (O)     (O)   wheelsets          (O)     (O)     axles at r0 = 0.46 m
     ====*=======*=========================*=======*====  rail top, z = 0
      -21.56   -19.0                    -2.56     0.0    x of the wheelsets (m)

    end view (looking forward: +y, the left side, is on the left of the page)

        +y <--+                                     z ^
               +---------------------------------------+
               |               car body  G             |
               +---------------------------------------+
                  S               [B]               S      secondary springs at +-b2 = 1 m
               +---------------------------------------+
               |               bogie frame             |
               +---------------------------------------+
                  P                                 P      axlebox springs at +-b1 = 1 m
            ( wheel )===============o=============( wheel )   wheelset, axle at r0
                  *                                 *      contact points at +-b = 0.75 m
         ===========                               ===========   rails (rigid_track_support:
                                                                 k_y, k_z to ground at *)

A single-wheelset model (``bogies = 0``) is one wheelset under a point mass (its sprung
share) on the same primary springs, the point free in y, z (as ``passage/vehicle.py``).

Two representations (``add_vehicle_model(..., representation=...)``):

- ``"rigid"``: NodeRigidBodyRxyz + ObjectRigidBody per body; every suspension element a
  ``CartesianSpringDamper`` between body markers at its real position (per axlebox, per
  bogie side; axes fixed in the frame, which the moving-frame vehicle's small rotations
  allow); secondary yaw and anti-roll stiffness one ``RigidBodySpringDamper`` per bogie;
  the bumpstop a ``CartesianSpringDamper`` with a symbolic force function (the table as a
  sum of ramps, ``BumpStop.ramps``). Longitudinal coordinates and wheelset spin held by
  ``CoordinateConstraint``. The reference: force-free at rest (tested), preload effects
  (gravity on springs below/above a CoG) come out of Exudyn's geometry.
- ``"linear"`` (default): the rigid model linearised at its static equilibrium on rigid
  track, as one ``ObjectGenericODE2`` over one ``NodeGenericODE2`` per body with just its
  free coordinates (car body, bogies: y, z, roll, pitch, yaw; wheelsets: y, z, roll, yaw,
  the coordinates the package's contact element reads, + spin optionally); the bumpstops
  a second ObjectGenericODE2 with a Python force function and its analytic Jacobian. Same
  static equilibrium (to 1e-17 m) and modes (to 0.1 %) as the rigid one (tested).

Chosen by measurement (``python benchmarks/bench_full_vehicle.py``: vehicle alone on
rigid-track springs, generalized-alpha h = 1e-4 s, modified Newton, car body released 30
mm off centre so that the bumpstops work; 2 cores shared with other jobs, load 2-8, so
the ranges are two runs; us per step):

=============================================================  =======  ============
case                                                            ODE2    us per step
=============================================================  =======  ============
4 wheelsets, linear, bumpstop engaged (1.9 Newton it./step)       31     80 - 134
4 wheelsets, linear, without bumpstop (1.0 it./step)              31     17 - 23
4 wheelsets, rigid Rxyz, symbolic bumpstop (2.9 it./step)         42    330 - 410
4 wheelsets, rigid Rxyz, Python bumpstop                          42    380 - 440
4 wheelsets, rigid Rxyz, no bumpstop                              42    350 - 365
4 wheelsets, rigid RotVecLG, symbolic bumpstop (2.0 it./step)     42    310 - 325
1 wheelset + sprung point, linear                                  6      5
1 wheelset + sprung point, rigid Rxyz                              9     40 - 49
=============================================================  =======  ============

The rigid model spends ~75 % in Exudyn's ODE2 right-hand side (~75 us per evaluation for 24
connectors on rigid-body markers, measured with ``show.computationTime``); a full Newton
Jacobian costs ~0.6 ms. The runtime requirement for a full-vehicle passage (4 wheelsets with
their co-running tracks at <= 1x real time, i.e. ~100 us per step in all) rules it out for
passages; the linear model costs ~20 us per step plus the bumpstop's Python call (~10 us
free, ~20 us engaged) when it engages. RotVecLG was no faster than Rxyz within the noise.
The linear model leaves out what the rigid one has beyond small angles: finite rotations,
and the wheel-load preload's geometric roll term (-2 r0 Q), which the contact element
supplies.

The data of a build (representations, handles) are in
:mod:`~exudyn_turnout.passage.vehicle.handles`; the vehicle on rigid track (support, static
state, connector forces, linearisation, modes) in
:mod:`~exudyn_turnout.passage.vehicle.analysis`; both are re-exported here.
"""

from __future__ import annotations

import functools
import math
import operator
from collections.abc import Callable, Sequence
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.advancedUtilities import CreateSymbolicUserFunction
from exudyn.itemInterface import (
    CartesianSpringDamper,
    CoordinateConstraint,
    LoadMassProportional,
    MarkerBodyMass,
    MarkerBodyPosition,
    MarkerBodyRigid,
    MarkerNodeCoordinate,
    MarkerNodeCoordinates,
    MarkerNodePosition,
    MassPoint,
    NodeGenericODE2,
    NodePoint,
    NodePointGround,
    NodeRigidBodyRotVecLG,
    NodeRigidBodyRxyz,
    ObjectGenericODE2,
    ObjectGround,
    RigidBody,
    RigidBodySpringDamper,
)

from exudyn_turnout.inputs.vehicle_data import full_vehicle_parts
from exudyn_turnout.inputs.vehicle_model import (
    GRAVITY,
    BumpStop,
    VehicleModel,
)
from exudyn_turnout.passage.vehicle.analysis import (
    connector_forces_at_reference,
    dynamic_settings,
    linearized_matrices,
    rigid_track_support,
    solve_static,
    static_settings,
    support_wheel_loads,
    vehicle_modes,
)
from exudyn_turnout.passage.vehicle.handles import (
    BUMPSTOP_LAWS,
    KEEPALIVE_KEY,
    LINEAR_DOF,
    POINT_DOF,
    REPRESENTATIONS,
    RIGID_DOF,
    ROTATIONS,
    WHEELSET_DOF,
    BodyHandles,
    RigidTrack,
    TrackSupport,
    VehicleBuild,
    VehicleMode,
    WheelsetHandles,
    point_transform,
)

__all__ = [
    "REPRESENTATIONS",
    "ROTATIONS",
    "BUMPSTOP_LAWS",
    "RigidTrack",
    "BodyHandles",
    "WheelsetHandles",
    "VehicleBuild",
    "TrackSupport",
    "VehicleMode",
    "add_vehicle_model",
    "rigid_track_support",
    "support_wheel_loads",
    "static_settings",
    "dynamic_settings",
    "solve_static",
    "connector_forces_at_reference",
    "vehicle_modes",
    "linear_bumpstop_arrays",
]


# ------------------------------------------------------------------------------ geometry
def _bumpstop_of(model: VehicleModel) -> BumpStop:
    """The model's lateral bumpstop; ValueError if it has none."""
    if model.bumpstop is None:
        raise ValueError(f"{model.name}: has no lateral bumpstop (use bumpstop='none')")
    return model.bumpstop


def _offset(point: Sequence[float], reference: Sequence[float]) -> list[float]:
    return [float(a - b) for a, b in zip(point, reference)]


def _bumpstop_slope(stop: BumpStop) -> Callable[[float], float]:
    points, increments = stop.ramps()
    pairs = tuple(zip(points, increments))

    def slope(u: float) -> float:
        a = abs(u)
        return sum(s for p, s in pairs if a > p)

    return slope


def _bumpstop_connector_function(stop: BumpStop, symbolic: bool) -> Callable:
    points, increments = stop.ramps()
    pairs = list(zip(points, increments))
    law = stop.lateral_force

    def springForceUserFunction(
        mbs, t, itemNumber, displacement, velocity, stiffness, damping, offset
    ):
        u = displacement[0] - offset[0]
        if symbolic:
            lib = exu.symbolic
            a = lib.abs(u)
            f = 0.0
            for p, s in pairs:
                f = f + s * lib.max(a - p, 0.0)
            return [lib.sign(u) * f, 0.0, 0.0]
        return [law(u), 0.0, 0.0]

    return springForceUserFunction


# ------------------------------------------------------------------------------ builders
def add_vehicle_model(
    mbs: exu.MainSystem,
    model: VehicleModel,
    *,
    representation: str = "linear",
    rotation: str = "Rxyz",
    wheelset_spin: bool = False,
    bumpstop: str = "auto",
    gravity: bool = True,
) -> VehicleBuild:
    """Add the vehicle (bodies, suspensions, bumpstops, gravity) to ``mbs``.

    ``"rigid"``: rigid bodies, every suspension element a 3-D spring-damper connector at its
    real position, force-free in the reference configuration (all coordinates zero: both
    markers at the same point, or an offset equal to their reference distance); gravity is
    a load; the longitudinal coordinate of every body (and each wheelset's spin unless
    ``wheelset_spin``) is held by a coordinate constraint. ``"linear"`` (default, ~15x
    faster, see the module docstring): that rigid model linearised at its static
    equilibrium on rigid track (Exudyn's ComputeLinearizedSystem, held coordinates
    removed; preload effects included), one NodeGenericODE2 per body with its free
    coordinates and one ObjectGenericODE2 with M, K, D and the constant force
    F0 = K q_s - f_wheels(q_s), so that the rigid model's static equilibrium q_s under its
    wheel loads is the linear one's too; the lateral bumpstops are a second
    ObjectGenericODE2 with a Python force function of the relative lateral displacement.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        System to add to (not yet assembled).
    model : VehicleModel
        A full vehicle or a single-wheelset model.
    representation : str
        One of :data:`REPRESENTATIONS`.
    rotation : str
        Rigid-body node parametrization, one of :data:`ROTATIONS` ("rigid"; "linear" uses it
        for the model it linearises).
    wheelset_spin : bool
        True: each wheelset's spin perturbation (rotation about its axle) is a free
        coordinate (the contact's longitudinal creep forces must then hold it).
    bumpstop : str
        Force law of the lateral bumpstops, one of :data:`BUMPSTOP_LAWS`.
    gravity : bool
        Include gravity (rigid: LoadMassProportional per body; linear: in F0).

    Returns
    -------
    VehicleBuild
        Handles of the nodes, bodies, markers and items added.
    """
    if representation not in REPRESENTATIONS:
        raise ValueError(f"representation must be one of {REPRESENTATIONS}, got {representation!r}")
    if rotation not in ROTATIONS:
        raise ValueError(f"rotation must be one of {ROTATIONS}, got {rotation!r}")
    if bumpstop not in BUMPSTOP_LAWS:
        raise ValueError(f"bumpstop must be one of {BUMPSTOP_LAWS}, got {bumpstop!r}")
    if representation == "rigid":
        law = "symbolic" if bumpstop == "auto" else bumpstop
        return _add_rigid(mbs, model, rotation, wheelset_spin, law, gravity)
    if bumpstop == "symbolic":
        raise ValueError("bumpstop 'symbolic' needs representation 'rigid'")
    return _add_linear(mbs, model, rotation, wheelset_spin, bumpstop != "none", gravity)


def _add_rigid(
    mbs: exu.MainSystem,
    model: VehicleModel,
    rotation: str,
    wheelset_spin: bool,
    bumpstop: str,
    gravity: bool,
) -> VehicleBuild:
    ground = int(mbs.AddObject(ObjectGround()))
    ground_node = int(mbs.AddNode(NodePointGround()))
    ground_coordinate = int(
        mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground_node, coordinate=0))
    )
    wheelset_data, primary = model.wheelset, model.primary
    held: list[tuple[int, int]] = []
    items: dict[str, int] = {}

    def rigid(name, mass, inertia, ref, dof):
        node_type = NodeRigidBodyRxyz if rotation == "Rxyz" else NodeRigidBodyRotVecLG
        node = int(mbs.AddNode(node_type(referenceCoordinates=list(ref) + [0.0, 0.0, 0.0])))
        body = int(
            mbs.AddObject(
                RigidBody(mass=mass, inertia=list(inertia) + [0.0, 0.0, 0.0], nodeNumber=node)
            )
        )
        held.append((node, dof["x"]))
        return node, body

    car: BodyHandles | None = None
    bogies: list[BodyHandles] = []
    sprung: list[BodyHandles] = []
    wheelsets: list[WheelsetHandles] = []
    if model.car_body is not None:
        car_body, bogie_kind, _ = full_vehicle_parts(model)
        ref = (0.0, car_body.cog_height, car_body.x[0])
        node, body = rigid(
            "car_body",
            car_body.mass,
            (car_body.pitch_inertia, car_body.yaw_inertia, car_body.roll_inertia),
            ref,
            RIGID_DOF,
        )
        car = BodyHandles("car_body", node, body, car_body.x[0], ref, dict(RIGID_DOF))
        for j, x_bogie in enumerate(bogie_kind.x):
            ref = (0.0, bogie_kind.cog_height, x_bogie)
            node, body = rigid(
                f"bogie{j + 1}",
                bogie_kind.mass,
                (bogie_kind.pitch_inertia, bogie_kind.yaw_inertia, bogie_kind.roll_inertia),
                ref,
                RIGID_DOF,
            )
            bogies.append(BodyHandles(f"bogie{j + 1}", node, body, x_bogie, ref, dict(RIGID_DOF)))
    for i, x_wheelset in enumerate(wheelset_data.x):
        ref = (0.0, wheelset_data.wheel_radius, x_wheelset)
        node, body = rigid(
            f"wheelset{i + 1}",
            wheelset_data.mass,
            (wheelset_data.spin_inertia, wheelset_data.yaw_inertia, wheelset_data.roll_inertia),
            ref,
            WHEELSET_DOF,
        )
        if not wheelset_spin:
            held.append((node, WHEELSET_DOF["spin"]))
        local = tuple(
            (side * wheelset_data.contact_semi_spacing, -wheelset_data.wheel_radius, 0.0)
            for side in (-1, 1)
        )
        markers = tuple(
            int(mbs.AddMarker(MarkerBodyPosition(bodyNumber=body, localPosition=list(q))))
            for q in local
        )
        centre = int(mbs.AddMarker(MarkerBodyRigid(bodyNumber=body, localPosition=[0.0, 0.0, 0.0])))
        wheelsets.append(
            WheelsetHandles(
                i,
                f"wheelset{i + 1}",
                x_wheelset,
                node,
                body,
                centre,
                markers,
                local,
                ref,
                dict(WHEELSET_DOF),
            )
        )
        if model.sprung_mass is not None:
            ref = (0.0, model.sprung_mass.height, x_wheelset)
            node = int(mbs.AddNode(NodePoint(referenceCoordinates=list(ref))))
            body = int(mbs.AddObject(MassPoint(mass=model.sprung_mass.mass, nodeNumber=node)))
            sprung.append(
                BodyHandles(f"sprung{i + 1}", node, body, x_wheelset, ref, dict(POINT_DOF))
            )
            held.append((node, POINT_DOF["x"]))

    def position_marker(handles, point):
        local = _offset(point, handles.reference)
        return int(mbs.AddMarker(MarkerBodyPosition(bodyNumber=handles.body, localPosition=local)))

    # primary suspension, per axlebox: bogie frame (or the sprung point) -> wheelset
    for ws in wheelsets:
        j = wheelset_data.bogie[ws.index]
        for side, label in ((-1.0, "right"), (1.0, "left")):
            point = (side * primary.semi_spacing, primary.height, ws.x)
            if j >= 0:
                m_parent, offset = position_marker(bogies[j], point), [0.0, 0.0, 0.0]
            else:  # the sprung point: its marker is at the point, the offset makes it force-free
                parent = sprung[ws.index]
                m_parent = int(mbs.AddMarker(MarkerNodePosition(nodeNumber=parent.node)))
                offset = _offset(point, parent.reference)
            items[f"primary_ws{ws.index + 1}_{label}"] = int(
                mbs.AddObject(
                    CartesianSpringDamper(
                        markerNumbers=[m_parent, position_marker(ws, point)],
                        stiffness=[primary.k_y, primary.k_z, primary.k_x],
                        damping=[primary.c_y, primary.c_z, primary.c_x],
                        offset=offset,
                    )
                )
            )

    # secondary suspension, torsion (yaw, anti-roll), bumpstop: bogie frame -> car body
    keep: list[Any] = []
    if car is not None:
        _, _, secondary = full_vehicle_parts(model)
        for j, bogie in enumerate(bogies):
            for side, label in ((-1.0, "right"), (1.0, "left")):
                point = (side * secondary.semi_spacing, secondary.height, bogie.x)
                items[f"secondary_b{j + 1}_{label}"] = int(
                    mbs.AddObject(
                        CartesianSpringDamper(
                            markerNumbers=[
                                position_marker(bogie, point),
                                position_marker(car, point),
                            ],
                            stiffness=[secondary.k_y, secondary.k_z, secondary.k_x],
                            damping=[secondary.c_y, secondary.c_z, secondary.c_x],
                        )
                    )
                )
            torsion_centre = (0.0, secondary.height, bogie.x)
            k6 = np.zeros((6, 6))
            k6[4, 4] = model.secondary_yaw_stiffness  # about Y: yaw
            k6[5, 5] = model.anti_roll_stiffness  # about Z: roll
            torsion_markers = [
                int(
                    mbs.AddMarker(
                        MarkerBodyRigid(
                            bodyNumber=handles.body,
                            localPosition=_offset(torsion_centre, handles.reference),
                        )
                    )
                )
                for handles in (bogie, car)
            ]
            items[f"torsion_b{j + 1}"] = int(
                mbs.AddObject(
                    RigidBodySpringDamper(
                        markerNumbers=torsion_markers,
                        stiffness=k6.tolist(),
                        damping=np.zeros((6, 6)).tolist(),
                    )
                )
            )
            if bumpstop != "none":
                stop = _bumpstop_of(model)
                point = (0.0, stop.height, bogie.x)
                item = int(
                    mbs.AddObject(
                        CartesianSpringDamper(
                            markerNumbers=[
                                position_marker(bogie, point),
                                position_marker(car, point),
                            ],
                            stiffness=[0.0, 0.0, 0.0],
                            damping=[0.0, 0.0, 0.0],
                        )
                    )
                )
                law = _bumpstop_connector_function(stop, bumpstop == "symbolic")
                if bumpstop == "symbolic":
                    # exudyn's stub imports ObjectIndex without re-exporting it; it exists
                    object_index = exu.ObjectIndex(item)  # type: ignore[attr-defined]
                    law = CreateSymbolicUserFunction(
                        mbs, law, "springForceUserFunction", object_index
                    )
                keep.append(law)
                mbs.SetObjectParameter(item, "springForceUserFunction", law)
                items[f"bumpstop_b{j + 1}"] = item
    if keep:
        mbs.variables.setdefault(KEEPALIVE_KEY, []).extend(keep)

    constraints = tuple(
        int(
            mbs.AddObject(
                CoordinateConstraint(
                    markerNumbers=[
                        ground_coordinate,
                        int(mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=n, coordinate=k))),
                    ]
                )
            )
        )
        for n, k in held
    )
    loads: tuple[int, ...] = ()
    if gravity:
        bodies = ([car] if car else []) + bogies + sprung + wheelsets
        loads = tuple(
            int(
                mbs.AddLoad(
                    LoadMassProportional(
                        markerNumber=int(mbs.AddMarker(MarkerBodyMass(bodyNumber=handles.body))),
                        loadVector=[0.0, -GRAVITY, 0.0],
                    )
                )
            )
            for handles in bodies
        )
    return VehicleBuild(
        model,
        "rigid",
        rotation,
        ground,
        tuple(wheelsets),
        tuple(bogies),
        car,
        tuple(sprung),
        items,
        constraints,
        tuple(held),
        loads,
        (),
        tuple(keep),
    )


def _free_names(build: VehicleBuild, spin: bool) -> list[tuple[Any, str]]:
    """(body, coordinate name) of the linear representation's coordinates, in node order."""
    out = []
    for handles in build.bodies():
        if isinstance(handles, WheelsetHandles):
            names = LINEAR_DOF["wheelset"] + (("spin",) if spin else ())
        elif handles.name.startswith("sprung"):
            names = LINEAR_DOF["sprung"]
        else:
            names = LINEAR_DOF["body"]
        out += [(handles, name) for name in names]
    return out


@functools.lru_cache(maxsize=16)
def _linearised(model: VehicleModel, rotation: str, wheelset_spin: bool, gravity: bool) -> tuple:
    """The rigid model's static equilibrium on rigid track and its linearisation there:
    (rigid build, M, K, D and q_s on its free coordinates, wheel loads), arrays read-only.

    Deterministic in its arguments (a frozen model), so kept: the full vehicle's passage
    builds the same vehicle for every segment (~4 ms each)."""
    ref_mbs = exu.SystemContainer().AddSystem()
    rigid = _add_rigid(ref_mbs, model, rotation, wheelset_spin, "none", gravity)
    support = rigid_track_support(ref_mbs, rigid, RigidTrack(k_x=1e7 if wheelset_spin else 0.0))
    ref_mbs.Assemble()
    solve_static(ref_mbs)
    loads = support_wheel_loads(ref_mbs, support)
    for item in support.items:
        ref_mbs.SetObjectParameter(item, "activeConnector", False)
    m, k, d = linearized_matrices(ref_mbs)
    q_rigid = np.array(ref_mbs.systemData.GetODE2Coordinates())
    held = {ref_mbs.GetNodeODE2Index(n) + c for n, c in rigid.held}
    names = _free_names(rigid, wheelset_spin)
    index = [
        ref_mbs.GetNodeODE2Index(handles.node) + handles.dof[dname] for handles, dname in names
    ]
    assert not held.intersection(index)
    m, k, d = (np.array(np.asarray(a)[np.ix_(index, index)]) for a in (m, k, d))
    q_s = q_rigid[index]
    for a in (m, k, d, q_s):
        a.setflags(write=False)
    return rigid, m, k, d, q_s, loads


def _add_linear(
    mbs: exu.MainSystem,
    model: VehicleModel,
    rotation: str,
    wheelset_spin: bool,
    bumpstop: bool,
    gravity: bool,
) -> VehicleBuild:
    # 1. the rigid model, its static equilibrium on rigid track and its linearisation there
    rigid, m, k, d, q_s, loads = _linearised(model, rotation, wheelset_spin, gravity)

    # 2. the same bodies as generic nodes of their free coordinates
    spin = ("spin",) if wheelset_spin else ()

    def generic_node(n):
        return int(
            mbs.AddNode(
                NodeGenericODE2(
                    referenceCoordinates=[0.0] * n,
                    initialCoordinates=[0.0] * n,
                    initialCoordinates_t=[0.0] * n,
                    numberOfODE2Coordinates=n,
                )
            )
        )

    def body(handles, dof):
        return BodyHandles(
            handles.name,
            generic_node(len(dof)),
            -1,
            handles.x,
            handles.reference,
            {dname: i for i, dname in enumerate(dof)},
        )

    car = None if rigid.car_body is None else body(rigid.car_body, LINEAR_DOF["body"])
    bogies = tuple(body(handles, LINEAR_DOF["body"]) for handles in rigid.bogies)
    sprung = tuple(body(handles, LINEAR_DOF["sprung"]) for handles in rigid.sprung)
    wheelsets = []
    for handles in rigid.wheelsets:
        dof = LINEAR_DOF["wheelset"] + spin
        node = generic_node(len(dof))
        wheelsets.append(
            WheelsetHandles(
                handles.index,
                handles.name,
                handles.x,
                node,
                -1,
                int(mbs.AddMarker(MarkerNodeCoordinates(nodeNumber=node))),
                (),
                handles.wheel_positions,
                handles.reference,
                {dname: i for i, dname in enumerate(dof)},
            )
        )
    ground = int(mbs.AddObject(ObjectGround()))
    partial = VehicleBuild(
        model,
        "linear",
        rotation,
        ground,
        tuple(wheelsets),
        bogies,
        car,
        sprung,
        {},
        (),
        (),
        (),
        tuple(q_s),
    )
    nodes = [handles.node for handles in partial.bodies()]

    # 3. F0 = K q_s - f_wheels: the rigid model's equilibrium under its wheel loads
    f_wheels = np.zeros(len(q_s))
    offsets = _node_offsets(partial)
    for ws, pair in zip(partial.wheelsets, loads):
        coordinate_names = list(ws.dof)
        for wheel_load, r in zip(pair, ws.wheel_positions):
            t = point_transform(coordinate_names, r)
            start = offsets[ws.node]
            f_wheels[start : start + len(coordinate_names)] += t.T @ np.array(
                [0.0, wheel_load, 0.0]
            )
    force = k @ q_s - f_wheels if gravity else np.zeros(len(q_s))
    items = {
        "suspension": int(
            mbs.AddObject(
                ObjectGenericODE2(
                    nodeNumbers=nodes,
                    massMatrix=m,
                    stiffnessMatrix=k,
                    dampingMatrix=d,
                    forceVector=list(force),
                )
            )
        )
    }
    keep: tuple[Any, ...] = ()
    if bumpstop and car is not None:
        items["bumpstops"], keep = _add_linear_bumpstops(mbs, model, car, bogies)
    return VehicleBuild(
        model,
        "linear",
        rotation,
        ground,
        tuple(wheelsets),
        bogies,
        car,
        sprung,
        items,
        (),
        (),
        (),
        tuple(q_s),
        keep,
    )


def _node_offsets(build: VehicleBuild) -> dict[int, int]:
    """Linear representation: first index of each body node's coordinates in the element."""
    out, k = {}, 0
    for handles in build.bodies():
        out[handles.node] = k
        k += len(handles.dof)
    return out


def _gather(indices: Sequence[int]) -> Callable[[Sequence[float]], tuple[float, ...]]:
    """A function returning the entries of a sequence at ``indices`` as a tuple."""
    if len(indices) == 1:
        i = indices[0]
        return lambda q: (q[i],)
    return operator.itemgetter(*indices)


def _linear_bumpstop_rows(
    model: VehicleModel, car: BodyHandles, bogies: Sequence[BodyHandles]
) -> tuple[int, list[np.ndarray], BumpStop]:
    """Per bogie the row c of c^T q (car body - bogie at the bumpstop); the size of q."""
    stop = _bumpstop_of(model)
    n_car = len(car.dof)
    size = n_car + sum(len(b.dof) for b in bogies)
    rows = []
    start = n_car
    for bogie in bogies:
        point = (0.0, stop.height, bogie.x)
        c = np.zeros(size)
        c[:n_car] = point_transform(list(car.dof), _offset(point, car.reference))[0]
        c[start : start + len(bogie.dof)] = -point_transform(
            list(bogie.dof), _offset(point, bogie.reference)
        )[0]
        rows.append(c)
        start += len(bogie.dof)
    return size, rows, stop


def linear_bumpstop_arrays(
    model: VehicleModel, car: BodyHandles, bogies: Sequence[BodyHandles]
) -> dict[str, np.ndarray]:
    """The bumpstops of :func:`linear_bumpstop_functions` as arrays (for compiled code).

    Parameters
    ----------
    model : VehicleModel
        A vehicle with a lateral bumpstop.
    car : BodyHandles
    bogies : sequence of BodyHandles

    Returns
    -------
    dict of numpy.ndarray
        ``index``, ``coefficient`` (bogie x non-zero entries of its row c, in index order,
        padded), ``count`` (non-zero entries per row), ``points`` (m) and ``increments``
        (N/m) of the force law's ramps (``BumpStop.ramps``): F(u) = sign(u) sum over
        the points p < |u| of increment (|u| - p), zero up to the first point.
    """
    _, rows, stop = _linear_bumpstop_rows(model, car, bogies)
    nonzero = [np.flatnonzero(c) for c in rows]
    width = max((len(i) for i in nonzero), default=0)
    index = np.zeros((len(rows), width), dtype=np.int64)
    coefficient = np.zeros((len(rows), width))
    for r, (c, i) in enumerate(zip(rows, nonzero)):
        index[r, : len(i)], coefficient[r, : len(i)] = i, c[i]
    points, increments = stop.ramps()
    return {
        "index": index,
        "coefficient": coefficient,
        "count": np.array([len(i) for i in nonzero], dtype=np.int64),
        "points": np.array(points, dtype=float),
        "increments": np.array(increments, dtype=float),
    }


def linear_bumpstop_functions(
    model: VehicleModel, car: BodyHandles, bogies: Sequence[BodyHandles]
) -> tuple[int, tuple[Any, ...]]:
    """Force and Jacobian functions on (car body, bogies): F = -c F_stop(c^T q) per bogie,
    with c^T q the relative lateral displacement car body - bogie at the bumpstop (small
    angles); and their number of coordinates."""
    size, rows, stop = _linear_bumpstop_rows(model, car, bogies)
    c_matrix = np.array(rows)
    # plain Python on the few non-zero entries: numpy's per-call overhead on 15-vectors was
    # ~50 us per force evaluation, this is a few us
    sparse = tuple(tuple((int(i), float(c[i])) for i in np.flatnonzero(c)) for c in rows)
    points, increments = stop.ramps()
    pairs = tuple(zip(points, increments))
    slope = _bumpstop_slope(stop)

    # per row, its coefficients and an itemgetter of its coordinates: u = sum(map(mul, ...))
    # adds the same products in the same order as a loop, in C (~1 us a row)
    gathered = tuple((tuple(v for _, v in row), _gather([i for i, _ in row])) for row in sparse)
    clearance = pairs[0][0]
    zeros = [0.0] * size  # returned while no bumpstop touches (Exudyn copies it)

    def forceUserFunction(mbs, t, itemNumber, q, q_t):
        out = zeros
        for row, (values, take) in zip(sparse, gathered):
            u = sum(map(operator.mul, values, take(q)))
            a = abs(u)
            if a > clearance:
                f = math.copysign(sum(s * (a - p) for p, s in pairs if a > p), u)
                if out is zeros:
                    out = [0.0] * size
                for i, v in row:
                    out[i] -= v * f
        return out

    def jacobianUserFunction(mbs, t, itemNumber, q, q_t, fODE2, fODE2_t):
        # d(left-hand side)/dq = c^T diag(dF/du) c: the bumpstop's tangent stiffness
        u = c_matrix @ np.asarray(q)
        return fODE2 * (c_matrix.T * np.array([slope(v) for v in u])) @ c_matrix

    return size, (forceUserFunction, jacobianUserFunction)


def _add_linear_bumpstops(
    mbs: exu.MainSystem, model: VehicleModel, car: BodyHandles, bogies: Sequence[BodyHandles]
) -> tuple[int, tuple[Any, ...]]:
    """One ObjectGenericODE2 on (car body, bogies) with :func:`linear_bumpstop_functions`."""
    size, functions = linear_bumpstop_functions(model, car, bogies)
    forceUserFunction, jacobianUserFunction = functions
    zero = np.zeros((size, size))
    item = int(
        mbs.AddObject(
            ObjectGenericODE2(
                nodeNumbers=[car.node] + [b.node for b in bogies],
                massMatrix=zero,
                stiffnessMatrix=zero,
                dampingMatrix=zero,
                forceUserFunction=forceUserFunction,
                jacobianUserFunction=jacobianUserFunction,
            )
        )
    )
    mbs.variables.setdefault(KEEPALIVE_KEY, []).extend(functions)
    return item, functions
