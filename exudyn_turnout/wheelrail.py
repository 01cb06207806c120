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
from dataclasses import dataclass

from .contact import creep_coefficient, flange_force, hertz_force, lateral_creepage, longitudinal_creepage, \
    saturation_factor
from .routes import ContactPair, Route
from .vehicle import Vehicle

__all__ = ["BoundPair", "PairForces", "WheelRailElement", "STATIC_LATERAL_STIFFNESS"]

#: N/m: holds the wheelset's lateral position in the static solve only, where creep
#: (a velocity effect) gives no lateral stiffness; the symmetric equilibrium has y = 0.
STATIC_LATERAL_STIFFNESS = 1e7


@dataclass(frozen=True)
class BoundPair:
    """A contact pair bound to the element's coordinates."""

    pair: ContactPair
    i_y: int  #: index of the rail body's lateral coordinate in the element
    i_z: int  #: index of its vertical coordinate


@dataclass(frozen=True)
class PairForces:
    """Forces of one wheel/rail pair at one instant, on the rail (N)."""

    N: float  #: normal (vertical) force on the rail, positive pressing it down
    F_y: float  #: lateral force on the rail, positive to the left
    F_x: float  #: longitudinal creep force on the wheel
    delta: float  #: m, normal penetration (negative: separated)
    in_contact: bool


def _interp(xs: tuple, zs: tuple, x: float) -> float:
    i = bisect_right(xs, x)
    if i <= 0:
        return zs[0]
    if i >= len(xs):
        return zs[-1]
    x0, x1 = xs[i - 1], xs[i]
    return zs[i - 1] + (zs[i] - zs[i - 1]) * (x - x0) / (x1 - x0)


class WheelRailElement:
    """Force function of the wheel/rail contact element (see the module docstring).

    Parameters
    ----------
    vehicle : Vehicle
    route : Route
    pairs : sequence of BoundPair
        The route's pairs in this zone, bound to rail coordinates of the element.
    x0 : float
        Position (m) of the wheelset at t = 0.
    v : float
        Speed (m/s); 0 for the static solve (no creep, lateral position held).
    """

    def __init__(self, vehicle: Vehicle, route: Route, pairs, x0: float, v: float):
        self.vehicle, self.route, self.pairs = vehicle, route, tuple(pairs)
        self.x0, self.v = float(x0), float(v)
        self.n = 6 + 2 * len({(p.i_y, p.i_z) for p in self.pairs})

    def x_at(self, t: float) -> float:
        return self.x0 + self.v * t

    def pair_forces(self, bp: BoundPair, x: float, q, q_t) -> PairForces:
        """Forces of one pair at position x for element coordinates q, q_t."""
        veh, law, pair = self.vehicle, self.vehicle.contact, bp.pair
        s, b, gamma = pair.side, veh.b, law.conicity
        dy, dy_t = q[0] - q[bp.i_y], q_t[0] - q_t[bp.i_y]
        N = F_y = F_x = 0.0
        delta = -math.inf
        if pair.tread_active(x):
            delta = q[bp.i_z] + _interp(pair.x, pair.z, x) - (q[1] + s * b * q[2] - s * gamma * dy)
            if delta > 0.0:
                delta_t = q_t[bp.i_z] - (q_t[1] + s * b * q_t[2] - s * gamma * dy_t)
                N = max(hertz_force(delta, law.C_H) + law.damping * delta_t, 0.0)
            if N > 0.0 and self.v > 0.0:
                F_x, F_y = self._creep(s, N, dy, dy_t, q[3], q_t[3], x)
            F_y -= s * gamma * N  # the conical tread's normal leans towards the track centre
        if pair.flange and pair.flange[0] <= x <= pair.flange[1]:
            F_y -= s * flange_force(s * dy - law.flange_clearance, s * dy_t, law.flange_stiffness, law.flange_damping)
        if pair.check and pair.check[0] <= x <= pair.check[1]:
            F_y += s * flange_force(-s * dy - self.route.check_clearance, -s * dy_t, law.flange_stiffness,
                                    law.flange_damping)
        return PairForces(N, -F_y, F_x, delta, N > 0.0)

    def _creep(self, s: int, N: float, dy: float, dy_t: float, psi: float, psi_t: float, x: float):
        veh, law = self.vehicle, self.vehicle.contact
        xi_x = longitudinal_creepage(s, dy, psi_t, self.v, veh.b, veh.r0, law.conicity, self.route.curvature(x))
        xi_y = lateral_creepage(dy_t, psi, self.v)
        F_x = -creep_coefficient(law.f11_ref, N, law.N_ref) * xi_x
        F_y = -creep_coefficient(law.f22_ref, N, law.N_ref) * xi_y
        k = saturation_factor(math.hypot(F_x, F_y), law.mu * N)
        return k * F_x, k * F_y

    def __call__(self, mbs, t, item_number, q, q_t):
        """Exudyn ``forceUserFunction``: generalised forces on the element's coordinates."""
        x = self.x_at(t)
        f = [0.0] * self.n
        veh = self.vehicle
        for bp in self.pairs:
            pf = self.pair_forces(bp, x, q, q_t)
            s = bp.pair.side
            f[0] -= pf.F_y
            f[1] += pf.N
            f[2] += s * veh.b * pf.N - veh.r0 * pf.F_y
            f[3] -= s * veh.b * pf.F_x
            f[bp.i_y] += pf.F_y
            f[bp.i_z] -= pf.N
        if self.v > 0.0:
            a_y = self.v**2 * self.route.curvature(x)
            f[0] -= veh.m_w * a_y
            f[4] -= veh.m_s * a_y
        else:
            f[0] -= STATIC_LATERAL_STIFFNESS * q[0]
        return f
