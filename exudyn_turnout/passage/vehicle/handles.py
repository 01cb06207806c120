"""The vehicle build's data: representations, coordinate names and the handles of the
Exudyn items :func:`~exudyn_turnout.passage.vehicle.builder.add_vehicle_model` adds.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from exudyn_turnout.inputs.vehicle_model import (
    VehicleModel,
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
]

#: "linear": small-angle linear model (one ObjectGenericODE2), "rigid": rigid bodies + connectors.
REPRESENTATIONS = ("linear", "rigid")


#: Rotation parametrizations of the rigid-body nodes ("rigid" representation).
ROTATIONS = ("Rxyz", "RotVecLG")


#: Lateral bumpstop force law: "auto" (symbolic on "rigid", Python on "linear"), or one of them,
#: or "none" (left out).
BUMPSTOP_LAWS = ("auto", "symbolic", "python", "none")


#: Coordinates of a rigid-body node (X, Y, Z, rotation about X, Y, Z) by name.
RIGID_DOF = {"y": 0, "z": 1, "x": 2, "pitch": 3, "yaw": 4, "roll": 5}


#: ... of a wheelset's rigid-body node: the rotation about its axle is the spin.
WHEELSET_DOF = {"y": 0, "z": 1, "x": 2, "spin": 3, "yaw": 4, "roll": 5}


#: ... of a sprung point (NodePoint).
POINT_DOF = {"y": 0, "z": 1, "x": 2}


#: Free coordinates of each body kind in the linear representation, in node order.
LINEAR_DOF = {
    "body": ("y", "z", "roll", "pitch", "yaw"),
    "wheelset": ("y", "z", "roll", "yaw"),
    "sprung": ("y", "z"),
}


KEEPALIVE_KEY = "exudyn_turnout.passage.vehicle.builder.user_functions"  # mbs.variables key


@dataclass(frozen=True)
class RigidTrack:
    """Linear wheel supports of rigid track, for static loads and eigen-analysis.

    Defaults: vertical k_z = the linearised Hertz spring 1.5 C_H^(2/3) N^(1/3) = 1.14e9 N/m
    (C_H = 9e10 N/m^1.5, data/manchester_wheelset.toml; N = 54.55 kN) in series with the
    plain-track support K_st,z = 6.37e7 N/m (paper Eq 2, README) = 6.03e7 N/m; lateral
    k_y = the plain-track lateral support K_st,y = 2.80e7 N/m (``exudyn-turnout params
    --zone 1``; creep forces, a velocity effect, are not in it). No longitudinal support
    (the longitudinal coordinates are held) and no damping unless given.
    """

    k_z: float = 6.03e7  #: N/m, vertical, per wheel
    k_y: float = 2.80e7  #: N/m, lateral, per wheel
    k_x: float = 0.0  #: N/m, longitudinal, per wheel (needed if the wheelset spin is free)
    c_z: float = 0.0  #: N s/m, vertical damping per wheel
    c_y: float = 0.0  #: N s/m, lateral damping per wheel


@dataclass(frozen=True)
class BodyHandles:
    """Exudyn items of a car body, bogie frame or sprung point."""

    name: str  #: "car_body", "bogie1", "sprung1", ...
    node: int  #: its node (rigid: NodeRigidBodyRxyz/RotVecLG or NodePoint; linear: NodeGenericODE2)
    body: int  #: rigid: ObjectRigidBody / ObjectMassPoint; linear: -1 (mass in the element)
    x: float  #: m, longitudinal position relative to the vehicle reference
    reference: tuple[float, float, float]  #: m, reference position (Exudyn X, Y, Z)
    dof: Mapping[str, int]  #: coordinate name -> index in the node (held ones too)


@dataclass(frozen=True)
class WheelsetHandles:
    """Exudyn items of one wheelset, for a contact element and the track under it.

    Linear representation: ``node`` is a NodeGenericODE2 with (y, z, roll, yaw[, spin]), the
    coordinates the package's contact element reads; ``body`` is -1, ``wheel_markers`` is
    empty and ``centre_marker`` a MarkerNodeCoordinates. Rigid representation: a rigid-body
    node and body, MarkerBodyPosition at the wheels' nominal contact points, a
    MarkerBodyRigid at the centre.
    """

    index: int  #: 0-based, front first
    name: str  #: "wheelset1", ...
    x: float  #: m, offset from the vehicle reference (front wheelset 0, others < 0)
    node: int
    body: int
    centre_marker: int
    wheel_markers: tuple[int, ...]  #: (right, left) contact-point markers (rigid only)
    wheel_positions: tuple[tuple[float, float, float], ...]  #: m, (right, left) contact
    #: points relative to the wheelset centre (Exudyn X, Y, Z): (-+b, -r0, 0)
    reference: tuple[float, float, float]  #: m, reference position of the centre
    dof: Mapping[str, int]  #: coordinate name -> index in the node (held ones too)


@dataclass(frozen=True)
class VehicleBuild:
    """Handles of a vehicle built by :func:`add_vehicle_model`."""

    model: VehicleModel
    representation: str  #: one of REPRESENTATIONS
    rotation: str  #: rigid-body node parametrization (rigid representation)
    ground: int  #: ObjectGround
    wheelsets: tuple[WheelsetHandles, ...]
    bogies: tuple[BodyHandles, ...]
    car_body: BodyHandles | None
    sprung: tuple[BodyHandles, ...]  #: sprung points (single-wheelset layout)
    #: name -> object: connectors ("primary_ws1_left", "secondary_b2_right", "torsion_b1",
    #: "bumpstop_b1") or, linear, "suspension" and "bumpstops" (ObjectGenericODE2)
    items: Mapping[str, int]
    constraints: tuple[int, ...]  #: coordinate constraints holding x (and spin), rigid only
    held: tuple[tuple[int, int], ...]  #: (node, local coordinate) held at its reference
    gravity_loads: tuple[int, ...]  #: rigid: LoadMassProportional; linear: -
    #: linear: the static equilibrium of the rigid model it was linearised at (free coords)
    static_state: tuple[float, ...] = ()
    keepalive: tuple[Any, ...] = field(default=(), repr=False)  #: user functions

    def bodies(self) -> tuple[BodyHandles | WheelsetHandles, ...]:
        """All bodies in node order: car body, bogies, sprung points, wheelsets.

        Returns
        -------
        tuple of BodyHandles or WheelsetHandles
            The handles, the car body first (if any), the wheelsets last.
        """
        out: list = [] if self.car_body is None else [self.car_body]
        return tuple(out + list(self.bogies) + list(self.sprung) + list(self.wheelsets))


@dataclass(frozen=True)
class TrackSupport:
    """Rigid-track wheel supports added by :func:`rigid_track_support`."""

    track: RigidTrack
    items: tuple[int, ...]  #: rigid: connectors (right, left per wheelset); linear: one element
    build: VehicleBuild = field(repr=False)


@dataclass(frozen=True)
class VehicleMode:
    """One vibration mode of the linearised vehicle."""

    frequency_hz: float  #: Hz, undamped natural frequency (eig of K, M)
    damped_frequency_hz: float  #: Hz, |lambda| / 2 pi of the matching damped mode
    damping_ratio: float  #: -, -Re(lambda) / |lambda| of the matching damped mode
    body: str  #: body with the largest share of kinetic energy, e.g. "car_body"
    direction: str  #: its dominant direction: "y", "z", "roll", "pitch", "yaw", "spin"
    share: float  #: -, that coordinate's share of the mode's kinetic energy
    participation: Mapping[str, float]  #: "body.direction" -> energy share (>= 1 %)


def point_transform(dof: Sequence[str], r: Sequence[float]) -> np.ndarray:
    """3 x n matrix: small-angle displacement (X, Y, Z) of a body point at offset r (Exudyn
    axes) from the body's coordinates ``dof``: u = t + theta x r, theta = (pitch, yaw, roll)."""
    rx, ry, rz = r
    cols = {
        "y": (1.0, 0.0, 0.0),
        "z": (0.0, 1.0, 0.0),
        "x": (0.0, 0.0, 1.0),
        "roll": (-ry, rx, 0.0),
        "pitch": (0.0, -rz, ry),
        "spin": (0.0, -rz, ry),
        "yaw": (rz, 0.0, -rx),
    }
    return np.array([cols[d] for d in dof]).T
