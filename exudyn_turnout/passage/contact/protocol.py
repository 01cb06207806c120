"""What a passage's driver asks of a wheel/rail contact: the written protocol.

A *contact* (:class:`Contact`) belongs to a route and makes, for each zone (or for the
whole run on the FE track), the *contact element* (:class:`ContactElement`) that Exudyn
calls as the force function of an ``ObjectGenericODE2`` on the wheelset's coordinates
(y, z, roll, yaw [, spin], the sprung mass's y, z) and the (y, z) of every rail body it
couples to. Implementations: :class:`~exudyn_turnout.passage.contact.profile.RouteContact`
(profile contact, the default) and
:class:`~exudyn_turnout.passage.contact.height_table.HeightTableContact` (the baseline).
The members listed are those the drivers use today.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, Protocol

import numpy as np

from exudyn_turnout.inputs.routes import Route
from exudyn_turnout.inputs.turnout import Zone
from exudyn_turnout.inputs.vehicle import Vehicle

__all__ = ["Contact", "ContactElement"]


class ContactElement(Protocol):
    """A wheelset's contact element: Exudyn's force function and what the drivers read.

    The package's elements subclass it and inherit :meth:`x_at` (constant speed)."""

    vehicle: Vehicle  #: the wheelset whose contact it is
    x0: float  #: m, position at t = 0
    v: float  #: m/s, speed
    n: int  #: number of the element's coordinates
    n_vehicle: int  #: of which the vehicle's (the rails' (y, z) pairs follow)
    wheel_of: Mapping[str, str]  #: rail slot -> wheel ("left" / "right") touching it
    #: lateral forces at rest are real (N tan gamma): the zone carry-over balances them
    lateral_static_loads: bool
    running_surface_depth: float  #: m, roll moves the running surfaces sideways by this x roll

    def __call__(self, mbs: Any, t: float, item_number: int, q: Any, q_t: Any) -> Any:
        """Exudyn ``forceUserFunction``: the generalised forces on the coordinates."""

    def x_at(self, t: float) -> float:
        """The wheelset's position at time t: x0 + v t (the implementations inherit it).

        Parameters
        ----------
        t : float
            s.

        Returns
        -------
        float
            m.
        """
        return self.x0 + self.v * t

    def wheel_loads(self, x: float, q: np.ndarray) -> dict[str, float]:
        """The normal force on each wheel.

        Parameters
        ----------
        x : float
            m, position.
        q : numpy.ndarray
            The element's coordinates.

        Returns
        -------
        dict
            "left", "right" -> N.
        """

    def rail_loads(
        self, x: float, q: np.ndarray, q_t: np.ndarray
    ) -> dict[str, tuple[float, float]]:
        """The (vertical, lateral) force on each rail slot touched.

        Parameters
        ----------
        x : float
            m, position.
        q, q_t : numpy.ndarray
            The element's coordinates and velocities.

        Returns
        -------
        dict
            Rail slot -> (N, N).
        """


class Contact(Protocol):
    """A route's wheel/rail contact: it makes each zone's contact element."""

    #: True: profile contact (spin coordinate; outputs from stored coordinates and
    #: velocities); False: outputs from the element's stored generalised forces
    profile: bool

    def element(
        self,
        vehicle: Vehicle,
        route: Route,
        zone: Zone,
        x0: float,
        v: float,
        irregularity: Any = None,
    ) -> tuple[Any, list[str]]:
        """The zone's contact element and the rail slots it couples to.

        Parameters
        ----------
        vehicle : Vehicle
            The wheelset whose contact it is.
        route : Route
        zone : Zone
            The zone the element serves (its active rails).
        x0, v : float
            m, m/s: position at t = 0 and speed (0: static).
        irregularity : Irregularity, optional
            Track irregularity under the wheels (profile contact only).

        Returns
        -------
        element : ContactElement
        slots : list of str
            Rail slots in the element's coordinate order.
        """
