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

from exudyn_turnout.inputs.vehicle import GRAVITY, Vehicle

__all__ = ["VehicleHandles", "add_vehicle"]


@dataclass(frozen=True)
class VehicleHandles:
    """Exudyn indices of the vehicle items."""

    wheelset_node: int  #: NodeRigidBody2D (y, z, roll)
    wheelset_body: int
    sprung_node: int  #: NodePoint2D (y, z)
    sprung_body: int
    yaw_node: int  #: NodeGenericODE2, one coordinate; its inertia sits in the contact element
    gravity_loads: tuple[int, ...]


def add_vehicle(
    mbs, vehicle: Vehicle, ground_body: int, z_w0: float = 0.0, z_s0: float = 0.0
) -> VehicleHandles:
    """Add the wheelset, its sprung mass, the primary suspension and gravity.

    Parameters
    ----------
    mbs : exudyn.MainSystem
    vehicle : Vehicle
    ground_body : int
        Unused for now (the sprung mass is free); kept so a car body can be attached later.
    z_w0, z_s0 : float
        Initial vertical displacements (m) of wheelset and sprung mass (a guess for the
        static solver: the Hertz springs need closed contact to have stiffness).
    """
    from exudyn import itemInterface as ii

    del ground_body
    n_w = mbs.AddNode(
        ii.NodeRigidBody2D(
            referenceCoordinates=[0.0, 0.0, 0.0], initialCoordinates=[0.0, z_w0, 0.0]
        )
    )
    o_w = mbs.AddObject(
        ii.ObjectRigidBody2D(mass=vehicle.m_w, inertia=vehicle.J_roll, nodeNumber=n_w)
    )
    n_s = mbs.AddNode(
        ii.NodePoint2D(referenceCoordinates=[0.0, 0.0], initialCoordinates=[0.0, z_s0])
    )
    o_s = mbs.AddObject(ii.ObjectMassPoint2D(mass=vehicle.m_s, nodeNumber=n_s))
    n_yaw = mbs.AddNode(
        ii.NodeGenericODE2(
            referenceCoordinates=[0.0],
            initialCoordinates=[0.0],
            initialCoordinates_t=[0.0],
            numberOfODE2Coordinates=1,
        )
    )
    m_s = mbs.AddMarker(ii.MarkerNodePosition(nodeNumber=n_s))
    for side in (1.0, -1.0):
        # Force-free at rest: the axlebox marker sits at y = side * d, the sprung point at
        # y = 0, so the spring's unstretched offset is p_sprung - p_box = (-side * d, 0).
        # Without it each spring would carry k_y d of lateral tension, which acts on the
        # wheelset as a roll stiffness of -2 k_y d^2 instead of the intended +2 k_z d^2.
        m_box = mbs.AddMarker(
            ii.MarkerBodyPosition(bodyNumber=o_w, localPosition=[side * vehicle.d, 0.0, 0.0])
        )
        mbs.AddObject(
            ii.CartesianSpringDamper(
                markerNumbers=[m_box, m_s],
                stiffness=[vehicle.k_y, vehicle.k_z, 0.0],
                damping=[vehicle.c_y, vehicle.c_z, 0.0],
                offset=[-side * vehicle.d, 0.0, 0.0],
            )
        )
    loads = tuple(
        mbs.AddLoad(
            ii.LoadMassProportional(
                markerNumber=mbs.AddMarker(ii.MarkerBodyMass(bodyNumber=o)),
                loadVector=[0.0, -GRAVITY, 0.0],
            )
        )
        for o in (o_w, o_s)
    )
    return VehicleHandles(n_w, o_w, n_s, o_s, n_yaw, loads)
