"""Exudyn builder of the single-wheelset vehicle (:class:`~exudyn_turnout.inputs.vehicle.Vehicle`).

The model lives in the track's cross-section plane, Exudyn's global X-Y plane: X = lateral
y (positive left), Y = vertical z (up), rotation about Z = roll (positive lifts the left
wheel); yaw is one more coordinate owned by the contact element.

::

              sprung mass m_s (y, z)            share of car body and bogie frame
             |             |
         k_y,k_z,c_z   k_y,k_z,c_z              primary suspension, per axlebox,
             |             |                    at +-d from the wheelset centre
        ==o==+=============+==o==               wheelset m_w, J_roll (y, z, roll), J_yaw
          |<------ 2 b ------>|                 contact points at +-b
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from exudyn_turnout.inputs.vehicle import GRAVITY, Vehicle
from exudyn_turnout.passage.settings import PassageError

__all__ = ["VehicleHandles", "add_vehicle"]


@dataclass(frozen=True)
class VehicleHandles:
    """Exudyn indices of the vehicle items."""

    wheelset_node: int  #: NodeRigidBody2D (y, z, roll)
    wheelset_body: int  #: ObjectRigidBody2D of the wheelset
    sprung_node: int  #: NodePoint2D (y, z)
    sprung_body: int  #: ObjectMassPoint2D of the sprung mass
    #: NodeGenericODE2: yaw (and spin perturbation); their inertia sits in the contact element
    yaw_node: int
    gravity_loads: tuple[int, ...]  #: LoadMassProportional on (wheelset, sprung mass)


def add_vehicle(
    mbs,
    vehicle: Vehicle,
    ground_body: int,
    z_w0: float = 0.0,
    z_s0: float = 0.0,
    spin: bool = False,
    roll0: float = 0.0,
) -> VehicleHandles:
    """Add the wheelset, its sprung mass, the primary suspension and gravity.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        System to add to (not yet assembled).
    vehicle : Vehicle
        Masses, inertias and primary suspension of the single-wheelset model.
    ground_body : int
        Unused for now (the sprung mass is free); kept so a car body can be attached later.
    z_w0, z_s0 : float
        Initial vertical displacements (m) of wheelset and sprung mass (a guess for the
        static solver: the Hertz springs need closed contact to have stiffness).
    roll0 : float
        rad, initial roll of the wheelset (a guess for the static solver).
    spin : bool
        The yaw node gets a second coordinate, the wheelset's spin perturbation beta about
        its axle (profile contact's longitudinal creepages need it); its inertia, like the
        yaw inertia, sits in the contact element.

    Returns
    -------
    VehicleHandles
        Exudyn indices of the nodes, bodies and gravity loads added.
    """
    from exudyn import itemInterface as ii

    del ground_body
    wheelset_node = mbs.AddNode(
        ii.NodeRigidBody2D(
            referenceCoordinates=[0.0, 0.0, 0.0], initialCoordinates=[0.0, z_w0, roll0]
        )
    )
    wheelset_body = mbs.AddObject(
        ii.ObjectRigidBody2D(mass=vehicle.m_w, inertia=vehicle.J_roll, nodeNumber=wheelset_node)
    )
    sprung_node = mbs.AddNode(
        ii.NodePoint2D(referenceCoordinates=[0.0, 0.0], initialCoordinates=[0.0, z_s0])
    )
    sprung_body = mbs.AddObject(ii.ObjectMassPoint2D(mass=vehicle.m_s, nodeNumber=sprung_node))
    n_yaw = 2 if spin else 1
    yaw_node = mbs.AddNode(
        ii.NodeGenericODE2(
            referenceCoordinates=[0.0] * n_yaw,
            initialCoordinates=[0.0] * n_yaw,
            initialCoordinates_t=[0.0] * n_yaw,
            numberOfODE2Coordinates=n_yaw,
        )
    )
    sprung_marker = mbs.AddMarker(ii.MarkerNodePosition(nodeNumber=sprung_node))
    for side in (1.0, -1.0):
        # Force-free at rest: the axlebox marker sits at y = side * d, the sprung point at
        # y = 0, so the spring's unstretched offset is p_sprung - p_box = (-side * d, 0).
        # Without it each spring would carry k_y d of lateral tension, which acts on the
        # wheelset as a roll stiffness of -2 k_y d^2 instead of the intended +2 k_z d^2.
        axlebox_marker = mbs.AddMarker(
            ii.MarkerBodyPosition(
                bodyNumber=wheelset_body, localPosition=[side * vehicle.d, 0.0, 0.0]
            )
        )
        mbs.AddObject(
            ii.CartesianSpringDamper(
                markerNumbers=[axlebox_marker, sprung_marker],
                stiffness=[vehicle.k_y, vehicle.k_z, 0.0],
                damping=[vehicle.c_y, vehicle.c_z, 0.0],
                offset=[-side * vehicle.d, 0.0, 0.0],
            )
        )
    loads = tuple(
        mbs.AddLoad(
            ii.LoadMassProportional(
                markerNumber=mbs.AddMarker(ii.MarkerBodyMass(bodyNumber=body)),
                loadVector=[0.0, -GRAVITY, 0.0],
            )
        )
        for body in (wheelset_body, sprung_body)
    )
    return VehicleHandles(wheelset_node, wheelset_body, sprung_node, sprung_body, yaw_node, loads)


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


def initial_guess(vehicle: Vehicle) -> tuple[float, float]:
    """Wheelset and sprung-mass z (m) with the contacts closed, so Hertz springs have stiffness."""
    W = vehicle.static_wheel_load
    z_w = -3.0 * (W / vehicle.contact.C_H) ** (2.0 / 3.0)
    return z_w, z_w - 0.5 * vehicle.m_s * 9.81 / vehicle.k_z
