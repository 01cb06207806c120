"""The full vehicle's body outputs: motion and acceleration at named points, suspension forces.

Pure numpy, from the coordinates of the linear vehicle
(:func:`~exudyn_turnout.passage.vehicle.builder.add_vehicle_model`, ``"linear"``: one
NodeGenericODE2 per body, car body and bogie frames with y, z, roll, pitch, yaw; wheelsets
with y, z, roll, yaw, spin) over a run: q, q_t and q_tt of the suspension element's
coordinates (the bodies in :meth:`~exudyn_turnout.passage.vehicle.handles.VehicleBuild.bodies`
order), as :mod:`~exudyn_turnout.passage.vehicle.body_sensors` records them.

Points (:func:`body_points`; EN 12299:2009 clause 6.5.2 puts the accelerometers on the floor
at the car body's centre and above each bogie centre):

- ``car_front``, ``car_centre``, ``car_rear``: the car body's floor on its centre line above
  bogie 1's pivot, midway, above bogie 2's pivot, :data:`FLOOR_HEIGHT` above the rail top;
- ``bogie1``, ``bogie2``: the bogie frames' centres (their CoG).

Columns (:func:`body_columns`), all in the track-following frame of the run (lateral y
positive left, vertical z up; each body's frame is the track's tangent at the body's own x,
so a car-body point's lateral displacement is measured from the tangent at the car body's
CoG: in a curve it includes the chord offset of the unstrained vehicle, ~59 mm above the
bogies in the 760 m curve):

- per point: ``y_<point>_m``, ``z_<point>_m`` (displacement from the vehicle's static
  equilibrium on rigid track, ``VehicleBuild.static_state``), ``ay_<point>_mps2``,
  ``az_<point>_mps2`` (acceleration: the integrator's q_tt, generalized-alpha's own
  accelerations, transformed to the point with the same small-angle kinematics; not a
  differentiated displacement);
- car-body points: ``ay_floor_<point>_mps2``, what a lateral accelerometer on the floor
  reads in car-body axes: ``ay`` + v^2 kappa(x_car) + d v^2 dkappa/ds(x_car) + g roll: the
  point's acceleration relative to the car body's frame, plus that frame's own at the point
  (its centripetal acceleration, the one the run applies to the car body as its curving
  load, and its angular acceleration times the point's distance d ahead of the CoG: the
  frame's Euler term, :mod:`~exudyn_turnout.passage.vehicle.track_frame`; the frame follows
  the centreline smoothed over 0.5 m, so both are continuous), plus gravity's share along
  the rolled floor; the input of the ride comfort
  (:mod:`exudyn_turnout.passage.ride_comfort`). Left out (module docstring of
  ``track_frame``): Omega^2 y, ~2e-5 m/s^2;
- per body (``car_body``, ``bogie1``...): ``roll_<body>_rad``, ``pitch_<body>_rad``,
  ``yaw_<body>_rad`` from the static state;
- suspension forces (:func:`suspension_forces`): per axlebox ``F<x|y|z>_primary_ws<k>_<side>_N``
  (what the primary spring and damper carry from the wheelset up to the bogie frame: z the
  load carried, positive up; y positive left; x forward), per bogie side
  ``F<x|y|z>_secondary_b<j>_<side>_N`` (bogie frame to car body), per bogie
  ``Mz_secondary_yaw_b<j>_Nm`` and ``Mx_anti_roll_b<j>_Nm`` (torques on the car body) and
  ``Fy_bumpstop_b<j>_N`` (on the car body).

Each spring-damper's force is its stiffness and damping (the vehicle file's k and c per
element) times the relative displacement and velocity of its two attachment points
(t + theta x r, the builder's small-angle kinematics), of the coordinates relative to the
unstrained vehicle in the track-following frame, q - q_geo (in a curve the frame's own
geometry q_geo strains nothing; :class:`~exudyn_turnout.passage.vehicle.track_frame.BodyLoads`).
The reference configuration (all coordinates zero) is every element's force-free state, as
in the rigid model the linear one is linearised from; at the static state the forces carry
the bodies' weights (tested).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from exudyn_turnout.inputs.vehicle_data import full_vehicle_parts
from exudyn_turnout.inputs.vehicle_model import GRAVITY
from exudyn_turnout.passage.vehicle.handles import (
    BodyHandles,
    VehicleBuild,
    WheelsetHandles,
    point_transform,
)

__all__ = [
    "FLOOR_HEIGHT",
    "CAR_POINTS",
    "BodyPoint",
    "body_points",
    "coordinate_slices",
    "point_motion",
    "suspension_forces",
    "body_columns",
]

#: m above the rail top: the car body's floor, where EN 12299 measures. Not in the
#: Manchester benchmark's data (ASSUMED: a main-line coach's floor is 1.1-1.3 m high).
FLOOR_HEIGHT = 1.2

#: Names of the car-body floor points: above bogie 1's pivot, the centre, above bogie 2's.
CAR_POINTS = ("car_front", "car_centre", "car_rear")


@dataclass(frozen=True)
class BodyPoint:
    """A named point of a body whose motion is an output."""

    name: str  #: e.g. "car_centre", "bogie1"
    body: str  #: the body's name ("car_body", "bogie1", ...)
    #: m, position relative to the body's reference (Exudyn X lateral, Y vertical, Z forward)
    offset: tuple[float, float, float]
    x: float  #: m, longitudinal position relative to the front wheelset


def body_points(build: VehicleBuild, floor_height: float = FLOOR_HEIGHT) -> tuple[BodyPoint, ...]:
    """The car body's floor points and the bogie frames' centres (module docstring).

    Parameters
    ----------
    build : VehicleBuild
        A full vehicle (car body on two bogies).
    floor_height : float
        m above the rail top.

    Returns
    -------
    tuple of BodyPoint
        ``car_front``, ``car_centre``, ``car_rear``, then ``bogie1``, ``bogie2``...; empty
        without a car body.
    """
    car = build.car_body
    if car is None or len(build.bogies) < 2:
        return ()
    height = floor_height - car.reference[1]
    xs = (build.bogies[0].x, car.x, build.bogies[-1].x)
    out = [
        BodyPoint(name, car.name, (0.0, height, x - car.x), x) for name, x in zip(CAR_POINTS, xs)
    ]
    out += [BodyPoint(b.name, b.name, (0.0, 0.0, 0.0), b.x) for b in build.bogies]
    return tuple(out)


def coordinate_slices(build: VehicleBuild) -> dict[str, slice]:
    """Where each body's coordinates are in the suspension element's coordinate vector.

    Parameters
    ----------
    build : VehicleBuild
        Linear representation.

    Returns
    -------
    dict
        Body name (``car_body``, ``bogie1``, ``wheelset1``...) -> slice.
    """
    out, k = {}, 0
    for handles in build.bodies():
        out[handles.name] = slice(k, k + len(handles.dof))
        k += len(handles.dof)
    return out


def _handles(build: VehicleBuild, name: str) -> BodyHandles | WheelsetHandles:
    for handles in build.bodies():
        if handles.name == name:
            return handles
    raise KeyError(name)


def point_motion(
    build: VehicleBuild, body: str, offset: Sequence[float], q: np.ndarray
) -> np.ndarray:
    """Small-angle displacement of a body point over a run: t + theta x r.

    Parameters
    ----------
    build : VehicleBuild
        Linear representation.
    body : str
        The body's name.
    offset : sequence of 3 float
        m, the point relative to the body's reference (Exudyn X, Y, Z).
    q : numpy.ndarray
        (samples, coordinates) of the suspension element (or one row).

    Returns
    -------
    numpy.ndarray
        (samples, 3): m, lateral (X), vertical (Y), longitudinal (Z).
    """
    return _motion(_handles(build, body), coordinate_slices(build)[body], offset, q)


def _motion(handles, where: slice, offset, q: np.ndarray) -> np.ndarray:
    """:func:`point_motion` of the body of ``handles``, its coordinates at ``where``."""
    return np.atleast_2d(q)[:, where] @ point_transform(list(handles.dof), offset).T


def _relative(slices, parent, child, point, q):
    """Displacement of the child's attachment point minus the parent's (samples, 3);
    ``slices``: :func:`coordinate_slices` (:func:`point_motion`'s operations, the bodies
    looked up once per call of the caller)."""

    def local(handles):
        return tuple(p - r for p, r in zip(point, handles.reference))

    child_motion = _motion(child, slices[child.name], local(child), q)
    return child_motion - _motion(parent, slices[parent.name], local(parent), q)


def _bumpstop_forces(stop, u: np.ndarray) -> np.ndarray:
    """``stop.lateral_force`` of every sample of u (m), N: the same operations in the same
    order, on arrays (bit for bit; one Python call per sample cost ~0.2 s a passage)."""
    points, increments = stop.ramps()
    a = np.abs(u)
    total = np.zeros_like(a)  # as sum(): 0 + the first term, then term by term
    for point, increment in zip(points, increments):
        total = total + increment * np.maximum(a - point, 0.0)
    return np.copysign(total, u)


def suspension_forces(
    build: VehicleBuild, q: np.ndarray, q_t: np.ndarray | None = None
) -> dict[str, np.ndarray]:
    """Primary and secondary spring-damper forces, yaw and anti-roll torques, bumpstop forces.

    Parameters
    ----------
    build : VehicleBuild
        A full vehicle, linear representation.
    q : numpy.ndarray
        (samples, coordinates): m and rad relative to the unstrained vehicle (q - q_geo in
        a curve; module docstring).
    q_t : numpy.ndarray, optional
        The same rates (m/s, rad/s); None: springs only (a static state).

    Returns
    -------
    dict
        Columns (N, N m), names in the module docstring.
    """
    model = build.model
    q = np.atleast_2d(q)
    q_t = np.zeros_like(q) if q_t is None else np.atleast_2d(q_t)
    out: dict[str, np.ndarray] = {}
    axes = ("x", "y", "z")
    order = (2, 0, 1)  # Exudyn Z (forward), X (lateral), Y (vertical) -> x, y, z
    primary = model.primary
    wheelset_data = model.wheelset
    sides = ((-1.0, "right"), (1.0, "left"))
    sl = coordinate_slices(build)
    for ws in build.wheelsets:
        j = wheelset_data.bogie[ws.index]
        if j < 0:
            continue
        bogie = build.bogies[j]
        for side, label in sides:
            point = (side * primary.semi_spacing, primary.height, ws.x)
            u = _relative(sl, bogie, ws, point, q)  # wheelset minus frame
            u_t = _relative(sl, bogie, ws, point, q_t)
            k = (primary.k_x, primary.k_y, primary.k_z)
            c = (primary.c_x, primary.c_y, primary.c_z)
            for a, i, kk, cc in zip(axes, order, k, c):
                out[f"F{a}_primary_ws{ws.index + 1}_{label}_N"] = kk * u[:, i] + cc * u_t[:, i]
    car = build.car_body
    if car is None:
        return out
    _, _, secondary = full_vehicle_parts(model)
    for j, bogie in enumerate(build.bogies):
        tag = f"b{j + 1}"
        for side, label in sides:
            point = (side * secondary.semi_spacing, secondary.height, bogie.x)
            u = _relative(sl, car, bogie, point, q)  # frame minus car body
            u_t = _relative(sl, car, bogie, point, q_t)
            k = (secondary.k_x, secondary.k_y, secondary.k_z)
            c = (secondary.c_x, secondary.c_y, secondary.c_z)
            for a, i, kk, cc in zip(axes, order, k, c):
                out[f"F{a}_secondary_{tag}_{label}_N"] = kk * u[:, i] + cc * u_t[:, i]
        rel = q[:, sl[bogie.name]] - q[:, sl[car.name]]  # frame minus car body, same dofs
        out[f"Mz_secondary_yaw_{tag}_Nm"] = model.secondary_yaw_stiffness * rel[:, car.dof["yaw"]]
        out[f"Mx_anti_roll_{tag}_Nm"] = model.anti_roll_stiffness * rel[:, car.dof["roll"]]
        if model.bumpstop is not None:
            stop = model.bumpstop
            point = (0.0, stop.height, bogie.x)
            u = _relative(sl, bogie, car, point, q)[:, 0]  # car body minus frame
            # the force on the car body opposes its displacement relative to the frame
            out[f"Fy_bumpstop_{tag}_N"] = 0.0 - _bumpstop_forces(stop, u)
    return out


def body_columns(
    build: VehicleBuild,
    q: np.ndarray,
    q_t: np.ndarray,
    q_tt: np.ndarray,
    *,
    q_geo: np.ndarray | None = None,
    q_geo_t: np.ndarray | None = None,
    centripetal: np.ndarray | None = None,
    frame_yaw_acceleration: np.ndarray | None = None,
    floor_height: float = FLOOR_HEIGHT,
) -> dict[str, np.ndarray]:
    """Every body output of a run (module docstring): points, rotations, suspension forces.

    Parameters
    ----------
    build : VehicleBuild
        A full vehicle, linear representation (``static_state`` set).
    q, q_t, q_tt : numpy.ndarray
        (samples, coordinates) of the suspension element: m, rad and their rates.
    q_geo, q_geo_t : numpy.ndarray, optional
        The unstrained vehicle in the track-following frame and its rate (a curve); None:
        straight track (zero).
    centripetal : numpy.ndarray, optional
        v^2 kappa at the car body's x (m/s^2, positive to the left) per sample, the
        acceleration of its frame; None: zero (straight track).
    frame_yaw_acceleration : numpy.ndarray, optional
        v^2 dkappa/ds at the car body's x (rad/s^2, positive turning left) per sample, the
        angular acceleration of its frame; None: zero.
    floor_height : float
        m, the car body's floor above the rail top.

    Returns
    -------
    dict
        Name -> array (samples,).
    """
    q, q_t, q_tt = (np.atleast_2d(np.asarray(a, float)) for a in (q, q_t, q_tt))
    static = np.asarray(build.static_state, float)
    dq = q - static
    out: dict[str, np.ndarray] = {}
    slices = coordinate_slices(build)
    bodies: dict = {}
    for handles in build.bodies():  # the first of a name, as point_motion
        bodies.setdefault(handles.name, handles)
    for point in body_points(build, floor_height):
        handles, where = bodies[point.body], slices[point.body]
        u = _motion(handles, where, point.offset, dq)
        a = _motion(handles, where, point.offset, q_tt)
        out[f"y_{point.name}_m"], out[f"z_{point.name}_m"] = u[:, 0], u[:, 1]
        out[f"ay_{point.name}_mps2"], out[f"az_{point.name}_mps2"] = a[:, 0], a[:, 1]
    car = build.car_body
    if car is not None:
        roll = dq[:, slices[car.name]][:, car.dof["roll"]]
        extra = 0.0 if centripetal is None else np.asarray(centripetal, float)
        turning = 0.0 if frame_yaw_acceleration is None else np.asarray(frame_yaw_acceleration)
        for point in body_points(build, floor_height)[: len(CAR_POINTS)]:
            frame = extra + point.offset[2] * turning  # offset[2]: m ahead of the CoG
            ay = out[f"ay_{point.name}_mps2"]
            out[f"ay_floor_{point.name}_mps2"] = ay + frame + GRAVITY * roll
    for handles in ([car] if car is not None else []) + list(build.bogies):
        part = dq[:, slices[handles.name]]
        for angle in ("roll", "pitch", "yaw"):
            out[f"{angle}_{handles.name}_rad"] = part[:, handles.dof[angle]]
    strain = q if q_geo is None else q - q_geo
    strain_t = q_t if q_geo_t is None else q_t - q_geo_t
    out.update(suspension_forces(build, strain, strain_t))
    return out
