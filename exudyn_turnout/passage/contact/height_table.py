"""Wheel/rail contact as a user-defined penalty load on an Exudyn ``ObjectGenericODE2``.

One element couples the wheelset (y, z, roll), its yaw coordinate, the sprung mass
(y, z; for the curving load) and the contact body of every rail the route lets a wheel
touch in the current zone (the rail mass for two layers, m_0 for three). Its Python force
function evaluates, at the wheelset's position x = x0 + v t, for every wheel/rail pair:

- the normal force, Hertz C_H delta^1.5, one-sided (loss of contact allowed), with delta
  the rail height profile of the route plus the rail's displacement minus the wheel's
  contact-point height (wheelset z, roll times b, and the conical tread's radius change);
- the creep forces, linear Kalker (f11, f22 scaled with N^(2/3)) with Johnson-Vermeulen
  saturation at mu N, from the longitudinal and lateral creepages of a conical wheelset;
- the lateral component gamma N of the normal force on the conical tread;
- flange and check-rail contact, stiff one-sided lateral springs beyond their clearance;
- the curving load -m v^2 kappa on wheelset and sprung mass (track-following frame).

Every force acts on the wheelset and, with opposite sign, on the rail body it touches.
Coordinates of the element: ``[y_w, z_w, phi, psi, y_s, z_s, y_r1, z_r1, ...]``.
"""

from __future__ import annotations

import math
from bisect import bisect_right
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from exudyn_turnout.inputs.routes import ContactPair, Route
from exudyn_turnout.inputs.vehicle import Vehicle
from exudyn_turnout.passage.contact.protocol import ContactElement
from exudyn_turnout.passage.settings import PassageError
from exudyn_turnout.wheel_rail.laws import (
    creep_coefficient,
    flange_force,
    hertz_force,
    lateral_creepage,
    longitudinal_creepage,
    saturation_factor,
)

__all__ = [
    "BoundPair",
    "PairForces",
    "WheelRailElement",
    "HeightTableContact",
    "STATIC_LATERAL_STIFFNESS",
]

#: N/m: holds the wheelset's lateral position in the static solve only, where creep
#: (a velocity effect) gives no lateral stiffness; the symmetric equilibrium has y = 0.
STATIC_LATERAL_STIFFNESS = 1e7


@dataclass(frozen=True)
class BoundPair:
    """A contact pair bound to the element's coordinates."""

    pair: ContactPair  #: the route's wheel/rail pair (side, rail height profile, flange)
    i_y: int  #: index of the rail body's lateral coordinate in the element
    i_z: int  #: index of its vertical coordinate


@dataclass(frozen=True)
class PairForces:
    """Forces of one wheel/rail pair at one instant, on the rail (N)."""

    N: float  #: normal (vertical) force on the rail, positive pressing it down
    F_y: float  #: lateral force on the rail, positive to the left
    F_x: float  #: longitudinal creep force on the wheel
    delta: float  #: m, normal penetration (negative: separated)
    in_contact: bool  #: True while the normal force is positive


def _interp(xs: tuple, zs: tuple, x: float) -> float:
    """Piecewise-linear interpolation of the table (xs, zs) at x, constant beyond its ends."""
    i = bisect_right(xs, x)
    if i <= 0:
        return zs[0]
    if i >= len(xs):
        return zs[-1]
    x0, x1 = xs[i - 1], xs[i]
    return zs[i - 1] + (zs[i] - zs[i - 1]) * (x - x0) / (x1 - x0)


class WheelRailElement(ContactElement):
    """Force function of the wheel/rail contact element (see the module docstring).

    Parameters
    ----------
    vehicle : Vehicle
        Wheelset geometry (b, r0), masses for the curving load and the contact law.
    route : Route
        The route: its curvature and check-rail clearances.
    pairs : sequence of BoundPair
        The route's pairs in this zone, bound to rail coordinates of the element.
    x0 : float
        Position (m) of the wheelset at t = 0.
    v : float
        Speed (m/s); 0 for the static solve (no creep, lateral position held).
    """

    n_vehicle = 6  #: vehicle coordinates at the head of the element: y_w, z_w, phi, psi, y_s, z_s
    #: m, how far a roll moves the wheels' running surfaces sideways per rad: 0 here (the
    #: conical tread's contact ignores roll sideways; see the profile element)
    running_surface_depth = 0.0
    #: whether its lateral loads at rest are real (re-based at zone boundaries): not on the
    #: conical tread (see passage.corunning_track.carry_over.static_deflection)
    lateral_static_loads = False

    def __init__(self, vehicle: Vehicle, route: Route, pairs, x0: float, v: float):
        self.vehicle, self.route, self.pairs = vehicle, route, tuple(pairs)
        self.wheel_of = {bp.pair.rail: bp.pair.wheel for bp in self.pairs}
        self.x0, self.v = float(x0), float(v)
        self.n = 6 + 2 * len({(p.i_y, p.i_z) for p in self.pairs})
        self._cached_t = math.nan
        self._geometry: tuple = ()

    def force_columns(
        self, t: np.ndarray, q: np.ndarray, force: np.ndarray, rails: Mapping[str, int]
    ) -> dict[str, np.ndarray]:
        """Forces and displacements of one zone's run.

        Parameters
        ----------
        t : numpy.ndarray
            s, sample times from the zone's start.
        q : numpy.ndarray
            Stored element coordinates (samples x n).
        force : numpy.ndarray
            The element's stored generalised forces, the left-hand side K q - f_user of its
            equations: the force a wheel puts on a rail is +force[z] (pressing down) and
            -force[y] (lateral, on the rail).
        rails : mapping
            Rail slot -> index of its y in the element.

        Returns
        -------
        dict
            The passage's columns (see :func:`exudyn_turnout.passage.run.simulate_passage`).
        """
        cols: dict[str, np.ndarray] = {"t_s": t, "x_m": self.x0 + self.v * t}
        wheel_of = {bp.pair.rail: bp.pair.wheel for bp in self.pairs}
        for wheel in ("right", "left"):
            for name in ("Fz", "Fy"):
                cols[f"{name}_{wheel}_N"] = np.zeros_like(t)
        for slot, i in rails.items():
            key = f"{wheel_of[slot]}_{slot}"
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

    def geometry(self, x: float) -> tuple:
        """Track geometry the pairs see at position x, and the route's curvature there.

        Parameters
        ----------
        x : float
            m, position along the route.

        Returns
        -------
        tuple
            ``(rows, kappa)``: one row per pair (in ``self.pairs`` order),
            ``(rail height in m or None off the tread, flange contact possible,
            check-rail clearance in m or None)``; ``kappa`` the curvature (1/m).
        """
        rows = []
        for bound in self.pairs:
            pair = bound.pair
            rail_height = _interp(pair.x, pair.z, x) if pair.tread_active(x) else None
            rows.append(
                (
                    rail_height,
                    bool(pair.flange and pair.flange[0] <= x <= pair.flange[1]),
                    self.route.check_clearance_at(pair, x),
                )
            )
        curvature = self.route.curvature
        return tuple(rows), _interp(curvature.x, curvature.value, x)

    def _geometry_at(self, t: float) -> tuple:
        if t != self._cached_t:  # Newton iterations of one step share t
            self._cached_t, self._geometry = t, self.geometry(self.x_at(t))
        return self._geometry

    def pair_forces(self, bp: BoundPair, x: float, q, q_t) -> PairForces:
        """Forces of one pair at position x for element coordinates q, q_t.

        Parameters
        ----------
        bp : BoundPair
            One of ``self.pairs``.
        x : float
            m, position of the wheelset along the route.
        q, q_t : sequence of float
            Element coordinates (m, rad) and velocities, in the order of the module docstring.

        Returns
        -------
        PairForces
            Normal, lateral and longitudinal force, penetration and contact state.
        """
        return self.all_pair_forces(x, q, q_t)[self.pairs.index(bp)]

    def all_pair_forces(self, x: float, q, q_t) -> list[PairForces]:
        """Forces of every pair (in ``self.pairs`` order) at position x.

        Parameters
        ----------
        x : float
            m, position of the wheelset along the route.
        q, q_t : sequence of float
            Element coordinates (m, rad) and velocities, in the order of the module docstring.

        Returns
        -------
        list of PairForces
            One per pair, in ``self.pairs`` order.
        """
        rows, kappa = self.geometry(x)
        return [
            PairForces(*self._forces(bp, row, kappa, q, q_t)) for bp, row in zip(self.pairs, rows)
        ]

    def rail_loads(self, x: float, q, q_t) -> dict[str, tuple[float, float]]:
        """Total (vertical, lateral) force on each rail slot touched.

        Parameters
        ----------
        x : float
            m, wheelset position.
        q, q_t : sequence of float
            Element coordinates and velocities.

        Returns
        -------
        dict
            Slot -> (vertical force pressing it down, lateral force on it, positive left), N.
        """
        loads: dict[str, list[float]] = {}
        for bp, pf in zip(self.pairs, self.all_pair_forces(x, q, q_t)):
            acc = loads.setdefault(bp.pair.rail, [0.0, 0.0])
            acc[0], acc[1] = acc[0] + pf.N, acc[1] + pf.F_y
        return {r: (v[0], v[1]) for r, v in loads.items()}

    def wheel_loads(self, x: float, q) -> dict[str, float]:
        """Total normal force (N) on each wheel at rest (velocities zero).

        Parameters
        ----------
        x : float
            m, wheelset position.
        q : sequence of float
            Element coordinates.

        Returns
        -------
        dict
            "left", "right" -> N.
        """
        loads = {"left": 0.0, "right": 0.0}
        for bp, pf in zip(self.pairs, self.all_pair_forces(x, q, [0.0] * len(q))):
            loads[bp.pair.wheel] += pf.N
        return loads

    def _forces(self, bp: BoundPair, row: tuple, kappa: float, q, q_t) -> tuple:
        """(N, F_y on the rail, F_x on the wheel, delta, in contact) of one pair."""
        law = self.vehicle.contact
        s, b, gamma = bp.pair.side, self.vehicle.b, law.conicity
        height, flange_on, check_clearance = row
        dy, dy_t = q[0] - q[bp.i_y], q_t[0] - q_t[bp.i_y]
        N = F_y = F_x = 0.0
        delta = -math.inf
        if height is not None:
            delta = q[bp.i_z] + height - (q[1] + s * b * q[2] - s * gamma * dy)
            if delta > 0.0:
                delta_t = q_t[bp.i_z] - (q_t[1] + s * b * q_t[2] - s * gamma * dy_t)
                N = max(hertz_force(delta, law.C_H) + law.damping * delta_t, 0.0)
            if N > 0.0 and self.v > 0.0:
                F_x, F_y = self._creep(s, N, dy, dy_t, q[3], q_t[3], kappa)
            F_y -= s * gamma * N  # the conical tread's normal leans towards the track centre
        if flange_on:
            F_y -= s * flange_force(
                s * dy - law.flange_clearance, s * dy_t, law.flange_stiffness, law.flange_damping
            )
        if check_clearance is not None:
            F_y += s * flange_force(
                -s * dy - check_clearance, -s * dy_t, law.flange_stiffness, law.flange_damping
            )
        return N, -F_y, F_x, delta, N > 0.0

    def _creep(
        self, s: int, N: float, dy: float, dy_t: float, psi: float, psi_t: float, kappa: float
    ) -> tuple[float, float]:
        """Saturated creep forces (F_x, F_y) on the wheel of side s (N)."""
        vehicle, law = self.vehicle, self.vehicle.contact
        xi_x = longitudinal_creepage(
            s, dy, psi_t, self.v, vehicle.b, vehicle.r0, law.conicity, kappa
        )
        xi_y = lateral_creepage(dy_t, psi, self.v)
        F_x = -creep_coefficient(law.f11_ref, N, law.N_ref) * xi_x
        F_y = -creep_coefficient(law.f22_ref, N, law.N_ref) * xi_y
        saturation = saturation_factor(math.hypot(F_x, F_y), law.mu * N)
        return saturation * F_x, saturation * F_y

    def __call__(self, mbs, t, item_number, q, q_t):
        """Exudyn ``forceUserFunction``: generalised forces on the element's coordinates."""
        rows, kappa = self._geometry_at(t)
        forces = [0.0] * self.n
        vehicle = self.vehicle
        b, r0 = vehicle.b, vehicle.r0
        for bp, row in zip(self.pairs, rows):
            N, F_y, F_x = self._forces(bp, row, kappa, q, q_t)[:3]
            s = bp.pair.side
            forces[0] -= F_y
            forces[1] += N
            forces[2] += s * b * N - r0 * F_y
            forces[3] -= s * b * F_x
            forces[bp.i_y] += F_y
            forces[bp.i_z] -= N
        if self.v > 0.0:
            a_y = self.v**2 * kappa
            forces[0] -= vehicle.m_w * a_y
            forces[4] -= vehicle.m_s * a_y
        else:
            forces[0] -= STATIC_LATERAL_STIFFNESS * q[0]
        return forces


class HeightTableContact:
    """The height-table contact of a route: makes each zone's :class:`WheelRailElement`.

    A documented baseline (the contact of the package's first passages: rail heights and
    contact angles from tables, linear Kalker creep with saturation, a flange spring). Only
    :mod:`exudyn_turnout.passage.run` imports it (``PassageSettings.contact =
    "height-table"``); the drivers see it through
    :class:`~exudyn_turnout.passage.contact.protocol.Contact`. It runs on the co-running
    tracks under the single wheelset only.
    """

    #: no spin coordinate; outputs from the element's stored generalised forces
    profile = False

    def element(
        self, vehicle: Vehicle, route: Route, zone, x0: float, v: float, irregularity=None
    ) -> tuple[WheelRailElement, list[str]]:
        """The zone's contact element and the rail slots it couples to.

        Parameters
        ----------
        vehicle : Vehicle
        route : Route
        zone : Zone
            The zone (its active rails).
        x0, v : float
            m, m/s: position at t = 0 and speed.
        irregularity : None
            Not supported by this contact (checked by the passage's settings).

        Returns
        -------
        element : WheelRailElement
        slots : list of str
            The rail slots the element couples to, in coordinate order.

        Raises
        ------
        PassageError
            Both wheels touch one rail slot in the zone.
        """
        del irregularity
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
        return element, slots
