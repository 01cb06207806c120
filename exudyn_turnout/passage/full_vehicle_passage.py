"""The full vehicle through the turnout, a co-running track under every wheelset (issue 13).

The vehicle of a :class:`~exudyn_turnout.inputs.vehicle_model.VehicleModel` (car body,
bogies, wheelsets; :func:`~exudyn_turnout.passage.vehicle_builder.add_vehicle_model`,
linear representation, wheelset spin free) runs at constant speed along a route. Every
wheelset has

- its own co-running track (``settings.layers``), evaluated at that wheelset's x and built
  with the parameters of the zone containing it;
- its own profile contact element: the same
  :class:`~exudyn_turnout.passage.profile_contact.ProfileContactElement` as the single
  wheelset's passage, given a Vehicle whose sprung mass ``m_s`` is 0 (the car body and the
  bogies get their own curving load here, so the element applies -m_w v^2 kappa to its
  wheelset only). The element's two sprung-mass coordinates sit on a decoupled dummy node
  (1 kg on 1e6 N/m) that stays at rest.

Track-following frame: every body's lateral coordinate and yaw are relative to the track
centreline and tangent at that body's own x. A vehicle whose suspension is unstrained in a
curve then has y_i = -e_i, psi_i = -theta_i, where e_i is the centreline's offset at x_i
from the tangent at the car body's x and theta_i the change of heading (both integrals of
the route's curvature): the suspension gets the extra force K q_geo (K its stiffness
matrix), which gives the wheelsets' geometric angle of attack in the bogie and the bogies'
offset under the car body. Car body and bogies get -m v^2 kappa(x) at their CoG
(d'Alembert in the track-following frame); while q_geo changes (entering a curve) the
suspension dampers see D q_geo_t as well. Left out: the yaw inertia terms J v^2 dkappa/dx
of the frame's changing yaw rate, and for the wheelsets everything the single wheelset's
element leaves out.

Zones: a wheelset's track and contact are in the zone containing its x. When any wheelset
crosses a zone boundary the system is rebuilt with the new zone for that wheelset and the
state carried over: vehicle bodies unchanged, that wheelset's track re-based as
``simulate._carry_over`` does (the old zone's static deflection under the current wheel
loads replaced by the new zone's, the dynamic part and velocities kept; the wheelset moved
with the static deflection under its wheels so that no wheel load jumps), the other
tracks copied. Wheelsets behind the turnout's x_min are on plain track: zone 1's parameters
and the contact at x clamped to x_min (the plain-track blend of zone 1 at its start is
plain track; the rail sections there are the plain rail). Likewise past x_max: the last
zone and the contact at x clamped to x_max (plain track in the packaged files), so the
front wheelset may run up to x_max plus the vehicle's length and the rear wheelsets pass
the whole turnout.

Exudyn objects of the user functions (speed, benchmarks/bench_vehicle_passage.py): the four
contact elements are one ObjectGenericODE2 (one Python call per residual evaluation) with a
forward-difference Jacobian per wheelset (Exudyn's own steps, a block each instead of the
whole object's numerical one); on straight track the bumpstops ride on it and the curving
loads (zero there) are left out; in a curve the curving loads and the bumpstops share one
object, the loads tabulated along the run. A run's Newton tolerance is
:func:`newton_tolerance`.

The run starts in the steady state at speed (at rest in the track-following frame): first
the static equilibrium at rest (lateral position and spin held, as the single wheelset's),
then a static solve with the creep forces of speed v (spin held); where that fails (in a
curve: saturated creep) a dynamic relaxation with x frozen (:data:`RELAX_TIME` s at
:data:`RELAX_STEP` s, curving loads ramped up over the first second) reaches it.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from types import SimpleNamespace
from typing import Any

import numpy as np

from exudyn_turnout.corunning.parameters import co_running_parameters
from exudyn_turnout.inputs.routes import Route, SpeedWarning, load_route, speed_warnings
from exudyn_turnout.inputs.turnout import Turnout, Zone
from exudyn_turnout.inputs.vehicle import Vehicle, load_vehicle
from exudyn_turnout.inputs.vehicle_model import VehicleModel
from exudyn_turnout.passage.profile_contact import (
    STATIC_LATERAL_STIFFNESS,
    STATIC_SPIN_STIFFNESS,
    ProfileContactElement,
    RouteContact,
)
from exudyn_turnout.passage.results import (
    TRACKS,
    PassageError,
    PassageFailure,
    PassageResult,
    PassageSettings,
    _peak,
    check_plausible,
    passage_summary,
)
from exudyn_turnout.passage.simulate import (
    NEWTON_ABSOLUTE_TOLERANCE,
    _check,
    _dof_of,
    _join,
    _progress_function,
    _QuietExudyn,
    _static_deflection,
    _vehicle_shift,
)

__all__ = [
    "simulate_vehicle_passage",
    "contact_vehicle",
    "wheelset_columns",
    "curve_geometry",
    "DUMMY_MASS",
    "DUMMY_STIFFNESS",
    "newton_tolerance",
    "vehicle_summary",
    "WheelsetContactElement",
    "BodyLoads",
    "add_vehicle_loads",
    "set_initial_vehicle",
]

#: kg, mass of each of the contact element's two unused sprung-mass coordinates.
DUMMY_MASS = 1.0
#: N/m, stiffness holding them at rest (nothing loads them: m_s = 0).
DUMMY_STIFFNESS = 1e6
#: s, time of the dynamic relaxation to the steady state at speed (where the static solve
#: fails, e.g. in a curve): the car body's lateral mode (~0.7 Hz, damping ratio ~0.45)
#: settles in it
RELAX_TIME = 8.0
#: s, its time step (implicit, numerically damped: only the end state matters)
RELAX_STEP = 5e-3
#: m, grid step of the route's integrated curvature (heading and lateral offset).
_GEOMETRY_STEP = 0.01
#: Exudyn's ``modifiedNewtonContractivity`` in a run: the Jacobian is recomputed when a
#: Newton iteration reduces the residual by less than this factor (Exudyn's default 0.5).
#: Where contact points move fast (switch, crossing) the kept Jacobian converges slowly;
#: the contact Jacobian is cheap (~1 ms): recomputing it sooner saves iterations
#: (benchmarks/bench_vehicle_passage.py: Newton iterations per step).
_NEWTON_CONTRACTIVITY = 0.1
#: relative step of the contact Jacobian's forward differences (Exudyn's default
#: ``numericalDifferentiation.relativeEpsilon``)
_JACOBIAN_EPSILON = 1e-7
#: smallest coordinate size scaling that step (Exudyn's ``minimumCoordinateSize``)
_JACOBIAN_MINIMUM_SIZE = 0.01


def contact_vehicle(base: Vehicle, model: VehicleModel) -> Vehicle:
    """The Vehicle a wheelset's contact element gets: the model's wheelset, no sprung mass.

    Parameters
    ----------
    base : Vehicle
        Contact law, wheel profile and back-to-back (the single-wheelset file).
    model : VehicleModel
        The full vehicle: wheelset mass, inertias, radius and contact semi-spacing.

    Returns
    -------
    Vehicle
        ``base`` with the model's wheelset data and ``m_s = 0`` (the bodies above carry their
        own curving load).
    """
    ws = model.wheelset
    return replace(
        base,
        m_w=ws.mass,
        J_roll=ws.roll_inertia,
        J_yaw=ws.yaw_inertia,
        J_spin=ws.spin_inertia,
        r0=ws.wheel_radius,
        b=ws.contact_semi_spacing,
        m_s=0.0,
    )


def curve_geometry(
    x: np.ndarray, kappa: np.ndarray, x_points: np.ndarray, x_ref: float
) -> tuple[np.ndarray, np.ndarray]:
    """Centreline offset e and heading change theta at x_points from the tangent at x_ref.

    e(x_i) = int_{x_ref}^{x_i} (x_i - s) kappa(s) ds, theta(x_i) = int_{x_ref}^{x_i} kappa ds
    (plane curve, small angles; positive kappa curves to the left, +y).

    Parameters
    ----------
    x, kappa : numpy.ndarray
        m, 1/m: the curvature on a fine increasing grid.
    x_points : numpy.ndarray
        m, where e and theta are wanted.
    x_ref : float
        m, the reference point (tangent).

    Returns
    -------
    e : numpy.ndarray
        m, lateral offset of the centreline (positive left).
    theta : numpy.ndarray
        rad, heading of the centreline relative to the tangent at x_ref.
    """
    return _offsets(x, *_integrated(x, kappa), x_points, x_ref)


def _integrated(x: np.ndarray, kappa: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Heading int kappa and lateral offset int heading from x[0] (trapezoidal rule)."""
    heading = np.concatenate(([0.0], np.cumsum(0.5 * (kappa[1:] + kappa[:-1]) * np.diff(x))))
    lateral = np.concatenate(([0.0], np.cumsum(0.5 * (heading[1:] + heading[:-1]) * np.diff(x))))
    return heading, lateral


def _offsets(
    x: np.ndarray, heading: np.ndarray, lateral: np.ndarray, x_points: np.ndarray, x_ref: float
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`curve_geometry` from the integrated curvature (:func:`_integrated`)."""
    h_ref, l_ref = np.interp(x_ref, x, heading), np.interp(x_ref, x, lateral)
    h, lat = np.interp(x_points, x, heading), np.interp(x_points, x, lateral)
    return lat - l_ref - h_ref * (x_points - x_ref), h - h_ref


class WheelsetContactElement(ProfileContactElement):
    """The profile contact element with its position clamped to the turnout's start and,
    for a solve at speed, frozen (x = x0 whatever t)."""

    x_clamp = -math.inf
    x_clamp_end = math.inf  #: m, largest position (the turnout's end: plain track beyond)
    frozen = False
    hold_spin = False

    def x_at(self, t: float) -> float:
        """Position (m) of the wheelset at time t, at least ``x_clamp``; x0 if frozen.

        Parameters
        ----------
        t : float
            s.

        Returns
        -------
        float
            m.
        """
        x = self.x0 if self.frozen else self.x0 + self.v * t
        return min(max(x, self.x_clamp), self.x_clamp_end)

    def columns(self, t: np.ndarray, q: np.ndarray, q_t: np.ndarray) -> dict[str, np.ndarray]:
        """Output columns (see the parent), at the clamped position.

        Parameters
        ----------
        t : numpy.ndarray
            s.
        q, q_t : numpy.ndarray
            Stored element coordinates and velocities.

        Returns
        -------
        dict
        """
        x = np.clip(self.x0 + self.v * np.asarray(t, float), self.x_clamp, self.x_clamp_end)
        return super().columns((x - self.x0) / self.v, q, q_t)

    def __call__(self, mbs, t, item_number, q, q_t):
        """Exudyn ``forceUserFunction`` (the parent's); frozen at speed (the steady-state
        solve, velocities zero) the spin perturbation is held by a spring, as at rest."""
        forces = super().__call__(mbs, t, item_number, q, q_t)
        if self.hold_spin and self.v > 0.0:
            forces[4] -= STATIC_SPIN_STIFFNESS * q[4]
        return forces

    def _generalised_forces(self, x: float, q: np.ndarray, q_t: np.ndarray) -> np.ndarray:
        """:meth:`__call__`'s forces at x, after ``_prepare(x)``: q, q_t float arrays; the
        element's buffer is returned (overwritten by the next call)."""
        self._call(x, q, q_t)
        forces = self._forces
        if self.v > 0.0:
            a_y = self.v**2 * self._kappa
            forces[0] -= self.vehicle.m_w * a_y
            forces[5] -= self.vehicle.m_s * a_y
            if self.hold_spin:
                forces[4] -= STATIC_SPIN_STIFFNESS * q[4]
        else:
            forces[0] -= STATIC_LATERAL_STIFFNESS * q[0]
            forces[4] -= STATIC_SPIN_STIFFNESS * q[4]
        return forces

    @classmethod
    def of(
        cls, element: ProfileContactElement, x_clamp: float, x_clamp_end: float = math.inf
    ) -> WheelsetContactElement:
        """The element ``element`` as a wheelset's contact, clamped to [x_clamp, x_clamp_end].

        Parameters
        ----------
        element : ProfileContactElement
            The wheelset's contact element (its state is shared, not copied).
        x_clamp, x_clamp_end : float
            m, the turnout's start and end: the contact tables' range.

        Returns
        -------
        WheelsetContactElement
        """
        out = cls.__new__(cls)
        out.__dict__.update(element.__dict__)
        out.x_clamp = x_clamp
        out.x_clamp_end = x_clamp_end
        return out


class _Contacts:
    """All wheelsets' contact elements as one Exudyn force function (one ObjectGenericODE2).

    One Python call per residual evaluation instead of one per wheelset; positions,
    curvature, irregularity and the curving loads -m_w v^2 kappa prepared once per time (the
    Newton iterations of a step share t). The forces are those of each element's own
    ``__call__``, bit for bit; the wheelsets' blocks do not couple (the numerical Jacobian
    is block diagonal).

    ``stops``: on straight track the vehicle's bumpstops (``vehicle_builder``'s force and
    Jacobian functions on car body and bogies, ``size`` coordinates) ride along on the
    object's last coordinates: one Python call fewer per residual evaluation.
    """

    def __init__(self, elements: list[WheelsetContactElement], stops: tuple | None = None):
        self.elements = list(elements)
        ends = np.cumsum([el.n for el in self.elements])
        self.spans = [(int(b - el.n), int(b)) for el, b in zip(self.elements, ends)]
        self.n_contacts = int(ends[-1])  #: coordinates of the contact elements, first
        self.stops = stops  #: (size, force, jacobian) of the bumpstops, or None
        self.n = self.n_contacts + (int(stops[0]) if stops is not None else 0)
        self._out = np.zeros(self.n)
        self._bias = np.zeros(self.n)  #: N, the curving loads (subtracted as in __call__)
        self._t = math.nan
        self._x = [0.0] * len(self.elements)
        self._moving = False  #: all at speed without holds: forces = kernel + bias
        self._a_y = [0.0] * len(self.elements)  #: m/s^2, the curving accelerations in _bias
        self._biased = False  #: any curving load (x + 0.0 == x: skipped on straight track)

    def _new_time(self, t: float) -> None:
        self._t = t
        self._moving = True
        for k, (el, (a, _)) in enumerate(zip(self.elements, self.spans)):
            x = el.x_at(t)
            el._prepare(x)
            el._cached_t = t
            self._x[k] = x
            if el.v > 0.0 and not el.hold_spin:
                a_y = el.v**2 * el._kappa
                if a_y != self._a_y[k]:  # changes in curves only
                    self._a_y[k] = a_y
                    self._bias[a] = -(el.vehicle.m_w * a_y)
                    self._bias[a + 5] = -(el.vehicle.m_s * a_y)
                    self._biased = bool(np.any(self._bias))
            else:
                self._moving = False

    def __call__(self, mbs, t, item_number, q_list, q_t_list):
        q, q_t = np.array(q_list, dtype=float), np.array(q_t_list, dtype=float)
        if t != self._t:
            self._new_time(t)
        out = self._out
        if self._moving:  # the hot path: x - c == x + (-c) exactly
            for el, x, (a, b) in zip(self.elements, self._x, self.spans):
                el._call(x, q[a:b], q_t[a:b])
                out[a:b] = el._forces
            if self._biased:
                out += self._bias
        else:
            for el, x, (a, b) in zip(self.elements, self._x, self.spans):
                out[a:b] = el._generalised_forces(x, q[a:b], q_t[a:b])
        if self.stops is not None:
            c = self.n_contacts
            out[c:] = self.stops[1](mbs, t, item_number, q_list[c:], q_t_list[c:])
        return out

    def jacobian(self, t: float, q: np.ndarray, q_t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """-df/dq and -df/dq_t of the contact forces f (the left-hand side's Jacobians), by
        forward differences per wheelset (its block; the blocks do not couple).

        The steps are Exudyn's own numerical differentiation's (relative 1e-7 of the
        coordinate, at least 1e-7 x 0.01). The dummy sprung-mass columns (5, 6) are zero:
        nothing acts on them (m_s = 0).

        Parameters
        ----------
        t : float
            s.
        q, q_t : numpy.ndarray
            The object's coordinates and velocities.

        Returns
        -------
        jac_q, jac_q_t : numpy.ndarray
            (n, n), N/m and N s/m.
        """
        if t != self._t:
            self._new_time(t)
        jac_q, jac_q_t = np.zeros((self.n, self.n)), np.zeros((self.n, self.n))
        for el, x, (a, b) in zip(self.elements, self._x, self.spans):
            u, u_t = np.array(q[a:b], dtype=float), np.array(q_t[a:b], dtype=float)
            f0 = el._generalised_forces(x, u, u_t).copy()
            for vector, jac in ((u, jac_q), (u_t, jac_q_t)):
                for j in range(b - a):
                    if j in (5, 6):
                        continue
                    value = vector[j]
                    eps = _JACOBIAN_EPSILON * max(abs(value), _JACOBIAN_MINIMUM_SIZE)
                    vector[j] = value + eps
                    f1 = el._generalised_forces(x, u, u_t)
                    vector[j] = value
                    jac[a:b, a + j] = (f0 - f1) / eps
        if self.stops is not None:  # their tangent stiffness; no damping
            c = self.n_contacts
            jac_q[c:, c:] = self.stops[2](None, t, 0, q[c:], q_t[c:], 1.0, 0.0)
        return jac_q, jac_q_t

    def jacobian_function(self, mbs, t, item_number, q, q_t, f_q, f_q_t):
        """Exudyn ``jacobianUserFunction``: f_q (-df/dq) + f_q_t (-df/dq_t); the object's
        own stiffness (the dummies' springs) Exudyn adds itself."""
        jac_q, jac_q_t = self.jacobian(t, np.asarray(q, float), np.asarray(q_t, float))
        return f_q * jac_q + f_q_t * jac_q_t


class BodyLoads:
    """Force function on the vehicle's nodes: K q_geo + D q_geo_t, -m v^2 kappa on car body
    and bogies (module docstring).

    The force depends on t only; it is computed once per time (Newton iterations share t).
    """

    def __init__(self, build, stiffness, damping, route: Route, x_f0: float, v: float, x_lo, x_hi):
        self.x_f0, self.v, self.frozen = float(x_f0), float(v), False
        self.d = np.asarray(damping)
        curvature = route.curvature
        self.x = np.arange(x_lo - 1.0, x_hi + 1.0 + _GEOMETRY_STEP, _GEOMETRY_STEP)
        self.kappa = np.interp(self.x, np.asarray(curvature.x), np.asarray(curvature.value))
        self.curved = bool(np.any(self.kappa != 0.0))
        self.heading, self.lateral = _integrated(self.x, self.kappa)
        self.k = np.asarray(stiffness)
        bodies = build.bodies()
        #: node names of the bodies in coordinate order ("car_body", "bogie1", "ws1", ...)
        self.names = [b.name.replace("wheelset", "ws") for b in bodies]
        self.offsets = np.array([b.x for b in bodies])
        self.x_ref = build.car_body.x if build.car_body is not None else 0.0
        self._points = np.append(self.offsets, self.x_ref)  #: m, from the front wheelset
        starts = np.cumsum([0] + [len(b.dof) for b in bodies])
        self.n = int(starts[-1])
        self.i_y = np.array([s + b.dof["y"] for s, b in zip(starts, bodies)])
        self.i_yaw = np.array(
            [s + b.dof["yaw"] if "yaw" in b.dof else -1 for s, b in zip(starts, bodies)]
        )
        self._yaw_bodies = np.flatnonzero(self.i_yaw >= 0)
        self._yaw_columns = self.i_yaw[self._yaw_bodies]
        model = build.model
        masses = []
        for b in bodies:
            if b.name == "car_body":
                masses.append(model.car_body.mass)
            elif b.name.startswith("bogie"):
                masses.append(model.bogie.mass)
            else:  # wheelsets: their contact element; sprung points: not in a full vehicle
                masses.append(0.0)
        self.masses = np.array(masses)
        self._t = math.nan
        self._f = np.zeros(self.n)
        self._t_geo = math.nan
        self._geo = np.zeros(self.n)
        self._x_geo = math.nan  #: m, front position of the last forces' q_geo
        self._q_geo = np.zeros(self.n)
        self._table: tuple[np.ndarray, np.ndarray] | None = None

    def tabulate(self, cache: dict) -> None:
        """Tabulate the running loads (:meth:`forces`) and q_geo at the front positions of the
        1 cm grid ``x``, shared by a run's segments through ``cache``: a step then
        interpolates them linearly (two vector operations) instead of evaluating the route's
        geometry (the loads vary over metres: at most ~0.1 N off the exact ones). Only
        running and in a curve (the static solves evaluate them exactly).

        Parameters
        ----------
        cache : dict
            Shared by the segments of a run (filled on the first call).
        """
        if not self.curved or self.frozen:
            return
        key = (float(self.x[0]), self.x.size, self.v)
        if key not in cache:
            h = _GEOMETRY_STEP
            q_geo = self.geometries(self.x)
            rate = (self.geometries(self.x + h) - self.geometries(self.x - h)) * (self.v / (2 * h))
            f = q_geo @ self.k.T + rate @ self.d.T
            kappa = np.interp(np.add.outer(self.x, self.offsets), self.x, self.kappa)
            f[:, self.i_y] -= self.masses * self.v**2 * kappa
            cache[key] = (f, q_geo)
        self._table = cache[key]

    def _interpolated(self, x_front: float) -> tuple[np.ndarray, np.ndarray]:
        """Running loads and q_geo at x_front from the table (:meth:`tabulate`)."""
        assert self._table is not None
        f, q_geo = self._table
        s = (x_front - self.x[0]) / _GEOMETRY_STEP
        i = min(max(int(s), 0), self.x.size - 2)
        w = s - i
        return f[i] + w * (f[i + 1] - f[i]), q_geo[i] + w * (q_geo[i + 1] - q_geo[i])

    def geometry(self, x_front: float) -> np.ndarray:
        """q_geo: the unstrained vehicle's coordinates in the track-following frame.

        Parameters
        ----------
        x_front : float
            m, the front wheelset's position.

        Returns
        -------
        numpy.ndarray
            m and rad, per vehicle coordinate.
        """
        return self.geometries(np.array([x_front]))[0]

    def geometries(self, x_front: np.ndarray) -> np.ndarray:
        """:meth:`geometry` at several front positions at once (one row each), with one
        interpolation of the integrated curvature for all of them (the same numbers).

        Parameters
        ----------
        x_front : numpy.ndarray
            m, front wheelset positions.

        Returns
        -------
        numpy.ndarray
            (positions, coordinates).
        """
        x_front = np.asarray(x_front, float)
        q_geo = np.zeros((len(x_front), self.n))
        if not self.curved:
            return q_geo
        xs = np.add.outer(x_front, self._points)  # the bodies' x, then the reference's
        heading = np.interp(xs, self.x, self.heading)
        lateral = np.interp(xs, self.x, self.lateral)
        h_ref, l_ref = heading[:, -1:], lateral[:, -1:]
        q_geo[:, self.i_y] = -(lateral[:, :-1] - l_ref - h_ref * (xs[:, :-1] - xs[:, -1:]))
        q_geo[:, self._yaw_columns] = -(heading[:, self._yaw_bodies] - h_ref)
        return q_geo

    def geometry_at(self, t: float) -> np.ndarray:
        """q_geo at time t (cached per t; the forces' own when they were computed at t).

        Parameters
        ----------
        t : float
            s.

        Returns
        -------
        numpy.ndarray
        """
        if t != self._t_geo:
            self._t_geo = t
            x = self.x_f0 if self.frozen else self.x_f0 + self.v * t
            self._geo = self._q_geo if x == self._x_geo else self.geometry(x)
        return self._geo

    def forces(self, x_front: float, factor: float = 1.0) -> np.ndarray:
        """Generalised forces (N, N m) on the vehicle's coordinates with the front at x_front:
        K q_geo + D q_geo_t and ``factor`` times the curving loads.

        Parameters
        ----------
        x_front : float
            m, the front wheelset's position.
        factor : float
            Share of the curving loads (a static solve ramps them up).

        Returns
        -------
        numpy.ndarray
        """
        if self.curved and not self.frozen:  # damping: D q_geo_t, q_geo_t = v dq_geo/dx
            h = _GEOMETRY_STEP
            q_geo, ahead, behind = self.geometries(np.array([x_front, x_front + h, x_front - h]))
            f = self.k @ q_geo
            rate = (ahead - behind) * (self.v / (2 * h))
            f += self.d @ rate
        else:
            q_geo = self.geometry(x_front)
            f = self.k @ q_geo
        self._x_geo, self._q_geo = x_front, q_geo
        kappa = np.interp(x_front + self.offsets, self.x, self.kappa)
        f[self.i_y] -= factor * self.masses * self.v**2 * kappa
        return f

    def __call__(self, mbs, t, item_number, q, q_t):
        if t != self._t:
            self._t = t
            if self.frozen:  # static solve: curving loads ramped over its load steps (t: 0..1)
                self._f = self.forces(self.x_f0, min(max(t, 0.0), 1.0))
            elif self._table is not None:
                x = self.x_f0 + self.v * t
                self._f, self._q_geo = self._interpolated(x)
                self._x_geo = x
            else:
                self._f = self.forces(self.x_f0 + self.v * t)
        return self._f


@dataclass(frozen=True)
class _Place:
    """Where one wheelset's track and contact are in a run segment."""

    zone: Zone
    clamped: bool  #: behind the turnout's start: zone 1 at x_min
    beyond: bool = False  #: past the turnout's end: the last zone at x_max


@dataclass
class _System:
    """One segment's Exudyn system."""

    container: Any
    mbs: Any
    places: tuple[_Place, ...]
    elements: list  #: per wheelset, its WheelsetContactElement
    params: list  #: per wheelset, its track's CoRunningParameters
    slots: list  #: per wheelset, rail slots of its element in coordinate order
    names: dict  #: node name -> node ("car_body", "bogie1", "ws1", "t1:sleeper", "t1:m0_r1")
    sensors: list  #: per wheelset, (coordinate sensors, velocity sensors) of its element nodes
    body_loads: BodyLoads
    x_front: float  #: m, front wheelset's position at t = 0


def _place(turnout: Turnout, x: float) -> _Place:
    if x < turnout.x_min - 1e-9:
        return _Place(turnout.zones[0], True)
    if x > turnout.x_max + 1e-9:
        return _Place(turnout.zones[-1], False, True)
    for zone in turnout.zones:
        if zone.x_start - 1e-9 <= x < zone.x_end - 1e-9:
            return _Place(zone, False)
    return _Place(turnout.zones[-1], False)


def _build(
    turnout: Turnout,
    route: Route,
    model: VehicleModel,
    vehicle: Vehicle,
    contact: RouteContact,
    settings: PassageSettings,
    places: tuple[_Place, ...],
    x_front: float,
    v: float,
    frozen: bool,
    x_range: tuple[float, float],
    tables: dict | None = None,
) -> _System:
    import exudyn as exu
    from exudyn.itemInterface import NodeGenericODE2, ObjectGenericODE2, SensorNode

    from exudyn_turnout.corunning.track import add_co_running_track
    from exudyn_turnout.passage import vehicle_builder
    from exudyn_turnout.passage.vehicle_builder import add_vehicle_model

    container = exu.SystemContainer()
    mbs = container.AddSystem()
    build = add_vehicle_model(
        mbs, model, representation="linear", wheelset_spin=True, bumpstop="none"
    )
    names: dict[str, int] = {b.name: b.node for b in build.bodies() if b.name[:5] != "wheel"}
    elements, params_all, slots_all, sensors = [], [], [], []
    contact_nodes: list[int] = []
    for i, (ws, place) in enumerate(zip(build.wheelsets, places)):
        x_i = x_front + ws.x
        x_track = turnout.x_min if place.clamped else turnout.x_max if place.beyond else x_i
        params = co_running_parameters(
            turnout, zone=place.zone.index, layers=settings.layers, source=settings.source
        )
        params = replace(params, zone=route.zone(params.zone))
        v_track = 0.0 if (place.clamped or place.beyond or frozen) else v
        track = add_co_running_track(
            mbs, params, x_track, v_track, mechanism=settings.track_mechanism
        )
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
    if tables is not None:
        loads.tabulate(tables)
    stops = None
    car = build.car_body
    if not loads.curved and model.bumpstop is not None and car is not None:  # q_geo = 0
        size, (stop_force, stop_jacobian) = vehicle_builder._linear_bumpstop_functions(
            model, car, build.bogies
        )
        stops = (size, stop_force, stop_jacobian)
        contact_nodes += [car.node] + [b.node for b in build.bogies]
    contacts = _Contacts(elements, stops)
    m, k = np.zeros((contacts.n, contacts.n)), np.zeros((contacts.n, contacts.n))
    for a, _ in contacts.spans:
        for j in (5, 6):  # the dummy sprung-mass coordinates
            m[a + j, a + j], k[a + j, a + j] = DUMMY_MASS, DUMMY_STIFFNESS
    mbs.AddObject(
        ObjectGenericODE2(
            nodeNumbers=contact_nodes,
            massMatrix=m,
            stiffnessMatrix=k,
            forceUserFunction=contacts,
            jacobianUserFunction=contacts.jacobian_function,
        )
    )
    keep = add_vehicle_loads(mbs, build, loads) if loads.curved else ()
    mbs.variables["exudyn_turnout.full_vehicle_passage"] = (contacts, loads, keep)
    mbs.Assemble()
    system = _System(
        container, mbs, places, elements, params_all, slots_all, names, sensors, loads, x_front
    )
    set_initial_vehicle(system, build)
    return system


def add_vehicle_loads(mbs, build, loads: BodyLoads) -> tuple:
    """The curving loads (``loads``) and the lateral bumpstops of ``vehicle_builder`` on the
    vehicle's bodies, the bumpstops acting on q - q_geo (track-following frame: a bumpstop
    sees the car body's displacement relative to the unstrained vehicle).

    For a curve (on straight track the loads are zero and the bumpstops ride on the contacts'
    object, :class:`_Contacts`): one ObjectGenericODE2 on all bodies carries both (one
    Python call per residual evaluation); its Jacobian is the bumpstops' (the loads depend
    on t only).

    Parameters
    ----------
    mbs : exudyn.MainSystem
    build : VehicleBuild
        From :func:`~exudyn_turnout.passage.vehicle_builder.add_vehicle_model`.
    loads : BodyLoads

    Returns
    -------
    tuple
        The user functions (keep them alive as long as the system).
    """
    from exudyn.itemInterface import ObjectGenericODE2

    from exudyn_turnout.passage import vehicle_builder

    model, car, bogies = build.model, build.car_body, build.bogies
    n, size = loads.n, 0  # the bumpstops' coordinates: car body and bogies, first in order
    if model.bumpstop is not None:
        size, (stop_force, stop_jacobian) = vehicle_builder._linear_bumpstop_functions(
            model, car, bogies
        )

    def forceUserFunction(mbs, t, item_number, q, q_t):
        f = loads(mbs, t, item_number, q, q_t)
        if size:
            g = loads.geometry_at(t)
            u = [a - b for a, b in zip(q[:size], g[:size])]
            stop = stop_force(mbs, t, item_number, u, q_t[:size])
            if any(stop):
                f = f.copy()
                f[:size] += stop
        return f

    def jacobianUserFunction(mbs, t, item_number, q, q_t, f_q, f_q_t):
        jac = np.zeros((n, n))
        if size:
            u = np.asarray(q[:size], float) - loads.geometry_at(t)[:size]
            jac[:size, :size] = stop_jacobian(mbs, t, item_number, u, q_t[:size], f_q, f_q_t)
        return jac

    zero = np.zeros((n, n))
    mbs.AddObject(
        ObjectGenericODE2(
            nodeNumbers=[b.node for b in build.bodies()],
            massMatrix=zero,
            stiffnessMatrix=zero,
            forceUserFunction=forceUserFunction,
            jacobianUserFunction=jacobianUserFunction,
        )
    )
    return forceUserFunction, jacobianUserFunction


def set_initial_vehicle(system, build, positions=None) -> None:
    """Vehicle at the rigid-track equilibrium, each wheelset lowered to touch its rails.

    Parameters
    ----------
    system : object
        With ``mbs`` and ``elements`` (per wheelset, its contact element).
    build : VehicleBuild
        From :func:`~exudyn_turnout.passage.vehicle_builder.add_vehicle_model`.
    positions : sequence of float, optional
        m, per wheelset the position of its contact tables (default each element's
        ``x_at(0.0)``).
    """
    import exudyn as exu

    mbs = system.mbs
    q = np.array(mbs.systemData.GetODE2Coordinates(exu.ConfigurationType.Initial))
    k = 0
    for b in build.bodies():
        i = mbs.GetNodeODE2Index(b.node)
        n = len(b.dof)
        q[i : i + n] = build.static_state[k : k + n]
        k += n
    if positions is None:
        positions = [el.x_at(0.0) for el in system.elements]
    for ws, el, x in zip(build.wheelsets, system.elements, positions):
        W = build.model.static_wheel_load
        z, roll = el.touching_position(x, (W / el.vehicle.contact.C_H) ** (2.0 / 3.0))
        i = mbs.GetNodeODE2Index(ws.node)
        q[i + ws.dof["z"]], q[i + ws.dof["roll"]] = z, roll
    mbs.systemData.SetODE2Coordinates(q, exu.ConfigurationType.Initial)


def _state(system: _System) -> dict[str, tuple[np.ndarray, np.ndarray]]:
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


def _element_vector(system: _System, state: Mapping, i: int, index: int) -> np.ndarray:
    """Element coordinates (index 0) or velocities (1) of wheelset i (0-based) in ``state``."""
    body = "m0" if system.params[i].layers == 3 else "rail"
    parts = [state[f"ws{i + 1}"][index], state[f"dummy{i + 1}"][index]]
    parts += [state[f"t{i + 1}:{body}_{r}"][index] for r in system.slots[i]]
    return np.concatenate(parts)


def _track_vector(state: Mapping, system: _System, i: int, index: int) -> dict[str, float]:
    out: dict[str, float] = {}
    prefix = f"t{i + 1}:"
    for name in system.names:
        if name.startswith(prefix):
            out.update(zip(_dof_of(name[len(prefix) :]), state[name][index]))
    return out


def _carry_over(
    state: Mapping,
    old: _System,
    new: _System,
    route: Route,
    layers: int,
    x_front: float,
    t_old: float,
) -> None:
    """Set ``new``'s initial state from ``old``'s final ``state`` (module docstring)."""
    import exudyn as exu

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
        q_el, v_el = _element_vector(old, state, i, 0), _element_vector(old, state, i, 1)
        loads_old = el.rail_loads(x, q_el, v_el)
        continues = route.continues.get(p_new.zone.index, {})
        source = {slot: continues.get(slot, slot) for slot in new.params[i].active_rails}
        loads_new = {slot: loads_old[src] for slot, src in source.items() if src in loads_old}
        # the boundary itself, in each zone's own range (x0 + v t carries round-off)
        u_old = _static_deflection(
            old.params[i], _inside(old.params[i].zone, x), loads_old, layers, True
        )
        u_new = _static_deflection(
            new.params[i], _inside(new.params[i].zone, x), loads_new, layers, True
        )
        q_old, v_old = _track_vector(state, old, i, 0), _track_vector(state, old, i, 1)
        dyn = {n: q_old[n] - u_old[n] for n in q_old}
        shift = new.params[i].zone.sleeper_y - old.params[i].zone.sleeper_y
        dyn["z_t"] += shift * dyn["phi_t"]
        v_old["z_t"] += shift * v_old["phi_t"]
        q_new, v_new = {}, {}
        for name in u_new:
            axis, _, rest = name.partition("_")
            slot = rest.rsplit("_", 1)[-1]
            src = name.replace(slot, source[slot]) if slot in source else name
            if src in dyn:
                q_new[name], v_new[name] = u_new[name] + dyn[src], v_old[src]
            else:  # a rail that appears: the sleeper's motion under it
                arm = new.params[i].zone.rail_y[slot] - new.params[i].zone.sleeper_y
                if axis == "y":
                    q_new[name], v_new[name] = u_new[name] + dyn["y_t"], v_old["y_t"]
                else:
                    q_new[name] = u_new[name] + dyn["z_t"] + arm * dyn["phi_t"]
                    v_new[name] = v_old["z_t"] + arm * v_old["phi_t"]
        for name in new.names:
            if name.startswith(prefix):
                dofs = _dof_of(name[len(prefix) :])
                values[name] = (
                    np.array([q_new[d] for d in dofs]),
                    np.array([v_new[d] for d in dofs]),
                )
        fake = SimpleNamespace(element=el)
        moved = _vehicle_shift(fake, u_old, u_new, loads_old, source, layers)  # type: ignore[arg-type]
        q_ws = values[f"ws{i + 1}"][0]
        q_ws[:3] = q_ws[:3] + moved["wheelset"]
    mbs, data = new.mbs, new.mbs.systemData
    q = np.asarray(data.GetODE2Coordinates(exu.ConfigurationType.Initial)).copy()
    q_t = np.zeros_like(q)
    for name, node in new.names.items():
        i = mbs.GetNodeODE2Index(node)
        a, b = values[name]
        q[i : i + len(a)], q_t[i : i + len(a)] = a, b
    data.SetODE2Coordinates(q, exu.ConfigurationType.Initial)
    data.SetODE2Coordinates_t(q_t, exu.ConfigurationType.Initial)


def _inside(zone: Zone, x: float) -> float:
    """x moved into the zone's range [x_start, x_end] (by round-off at its boundary)."""
    return min(max(x, zone.x_start), zone.x_end)


def _solve_static(system: _System, what: str, load_steps: int = 1) -> None:
    import exudyn as exu

    from exudyn_turnout.corunning.track import simulation_settings

    sim = simulation_settings(1.0, 1.0)
    sim.staticSolver.numberOfLoadSteps = load_steps
    sim.staticSolver.newton.absoluteTolerance = 1e-4
    sim.staticSolver.newton.maxIterations = 50
    try:
        system.mbs.SolveStatic(sim, updateInitialValues=True)
    except (exu.SolverError, RuntimeError) as err:
        raise PassageFailure(
            f"{what} not found with the front wheelset at x = {system.x_front:g} m: {err}"
        ) from None


def _relax(system: _System, duration: float, h: float) -> None:
    """Integrate with x frozen (the curving loads ramped up over the first second) until the
    vehicle is at rest in the track-following frame: the steady state at speed."""
    import exudyn as exu

    from exudyn_turnout.corunning.track import simulation_settings

    sim = simulation_settings(duration, h, duration)
    sim.timeIntegration.generalizedAlpha.spectralRadius = 0.0
    sim.timeIntegration.newton.absoluteTolerance = NEWTON_ABSOLUTE_TOLERANCE
    try:
        system.mbs.SolveDynamic(sim)
    except (exu.SolverError, RuntimeError) as err:
        raise PassageFailure(
            f"steady state at speed not found with the front wheelset at x = "
            f"{system.x_front:g} m: {str(err).strip()}"
        ) from None


def _copy_state(state: Mapping, system: _System) -> None:
    import exudyn as exu

    mbs, data = system.mbs, system.mbs.systemData
    q = np.asarray(data.GetODE2Coordinates(exu.ConfigurationType.Initial)).copy()
    q_t = np.zeros_like(q)
    for name, node in system.names.items():
        i = mbs.GetNodeODE2Index(node)
        a, b = state[name]
        q[i : i + len(a)], q_t[i : i + len(a)] = a, b
    data.SetODE2Coordinates(q, exu.ConfigurationType.Initial)
    data.SetODE2Coordinates_t(q_t, exu.ConfigurationType.Initial)


def wheelset_columns(
    element: ProfileContactElement, t: np.ndarray, q: np.ndarray, q_t: np.ndarray, label: str
) -> dict[str, np.ndarray]:
    """Per wheel forces and wheelset coordinates of one wheelset, named ``..._<label>_...``.

    Parameters
    ----------
    element : ProfileContactElement
        The wheelset's contact element.
    t : numpy.ndarray
        s, times from the segment's start.
    q, q_t : numpy.ndarray
        Its element coordinates and velocities (samples x element size).
    label : str
        E.g. "ws2".

    Returns
    -------
    dict
        ``Fz_<label>_<wheel>_N``, ``Fy_<label>_<wheel>_N``, per rail slot
        ``Fz_<label>_<wheel>_<rail>_N``, ``Fy_...``, and ``y_<label>_m``, ``z_<label>_m``,
        ``roll_<label>_rad``, ``yaw_<label>_rad``.
    """
    cols = element.columns(t, q, q_t)
    out = {}
    for name, values in cols.items():
        if name.startswith(("Fz_", "Fy_")):
            out[f"{name[:3]}{label}_{name[3:]}"] = values
    for k, name in enumerate(("y", "z", "roll", "yaw")):
        out[f"{name}_{label}_{'m' if k < 2 else 'rad'}"] = q[:, k]
    return out


def _run(
    system: _System,
    duration: float,
    settings: PassageSettings,
    t_offset: float,
    total: float,
    progress: Callable | None,
    static_load: float,
) -> dict[str, np.ndarray]:
    import exudyn as exu

    from exudyn_turnout.corunning.track import simulation_settings

    h = settings.time_step
    sim = simulation_settings(duration, h, 0.999 * (settings.output_step or h))
    sim.timeIntegration.numberOfSteps = max(1, int(math.ceil(duration / h - 1e-9)))
    sim.timeIntegration.generalizedAlpha.spectralRadius = settings.spectral_radius
    sim.timeIntegration.newton.absoluteTolerance = newton_tolerance(len(system.elements))
    sim.timeIntegration.newton.modifiedNewtonContractivity = _NEWTON_CONTRACTIVITY
    v = settings.v
    if progress is not None:
        system.mbs.SetPreStepUserFunction(
            _progress_function(progress, t_offset, total, system.x_front, v)
        )
    try:
        system.mbs.SolveDynamic(sim)
    except (exu.SolverError, RuntimeError) as err:
        t = system.mbs.systemData.GetTime()
        raise PassageFailure(
            f"solver failed at t = {t_offset + t:.5f} s, front wheelset at x = "
            f"{system.x_front + v * t:.3f} m: {str(err).strip()}"
        ) from None
    cols: dict[str, np.ndarray] = {}
    for i, (element, (pos, vel)) in enumerate(zip(system.elements, system.sensors)):
        stored = [system.mbs.GetSensorStoredData(s) for s in pos]
        stored_t = [system.mbs.GetSensorStoredData(s) for s in vel]
        t = stored[0][:, 0]
        zeros = np.zeros((len(t), 2))
        q = np.hstack([stored[0][:, 1:], zeros] + [a[:, 1:] for a in stored[1:]])
        q_t = np.hstack([stored_t[0][:, 1:], zeros] + [a[:, 1:] for a in stored_t[1:]])
        if not (np.all(np.isfinite(q)) and np.all(np.isfinite(q_t))):
            bad = t[~np.all(np.isfinite(q), axis=1)][0]
            raise PassageFailure(
                f"solution diverged at t = {t_offset + bad:.5f} s, front wheelset at x = "
                f"{system.x_front + v * bad:.3f} m: reduce the time step"
            )
        label = f"ws{i + 1}"
        x_i = system.x_front + _offset_of(system, i) + v * t
        if i == 0:
            cols["t_s"], cols["x_m"] = t + t_offset, system.x_front + v * t
            cols.update(element.columns(t, q, q_t))
            for k, name in enumerate(
                ("y_wheelset_m", "z_wheelset_m", "roll_wheelset_rad", "yaw_wheelset_rad")
            ):
                cols[name] = q[:, k]
            for j, slot in enumerate(system.slots[0]):
                base = element.n_vehicle + 2 * j
                cols[f"y_rail_{slot}_m"], cols[f"z_rail_{slot}_m"] = q[:, base], q[:, base + 1]
        own = wheelset_columns(element, t, q, q_t, label)
        own[f"x_{label}_m"] = x_i
        plausible = {
            "t_s": t + t_offset,
            "x_m": x_i,
            "y_wheelset_m": q[:, 0],
            "z_wheelset_m": q[:, 1],
            "Fz_right_N": own[f"Fz_{label}_right_N"],
            "Fz_left_N": own[f"Fz_{label}_left_N"],
        }
        for j, slot in enumerate(system.slots[i]):
            plausible[f"z_rail_{slot}_m"] = q[:, element.n_vehicle + 2 * j + 1]
        check_plausible(plausible, static_load, f"wheelset {i + 1}")
        cols.update(own)
    return cols


def _offset_of(system: _System, i: int) -> float:
    """Longitudinal offset (m) of wheelset i (0-based) behind the front one (<= 0)."""
    return system.elements[i].x0 - system.x_front


def newton_tolerance(wheelsets: int) -> float:
    """Newton's absolute residual tolerance (N) of a passage with this many wheelsets.

    Exudyn compares the L2 norm of the whole residual with it. The single wheelset's
    passage uses :data:`~exudyn_turnout.passage.simulate.NEWTON_ABSOLUTE_TOLERANCE`; n
    wheelsets, each with its own track and contact, get sqrt(n) times that, so that the
    residual's share of each wheelset (root mean square over the wheelsets) meets the single
    wheelset's tolerance. Measured (4 wheelsets, 3 layers, through route, 100 km/h, against
    1 N): Newton iterations per step 1.84 -> 1.65, the per-wheel switch and crossing peaks
    within 0.001 % (vertical) and 0.015 % (lateral), forces within 6 N.

    Parameters
    ----------
    wheelsets : int
        Number of wheelsets (at least 1).

    Returns
    -------
    float
        N.
    """
    return NEWTON_ABSOLUTE_TOLERANCE * math.sqrt(max(int(wheelsets), 1))


def _events(turnout: Turnout, offsets: tuple[float, ...], x_a: float, x_b: float) -> list[float]:
    """Front positions where any wheelset crosses x_min, a zone boundary or x_max, with x_a
    and x_b."""
    bounds = [turnout.x_min] + [z.x_start for z in turnout.zones[1:]] + [turnout.x_max]
    xs = {x_a, x_b}
    for o in offsets:
        for b in bounds:
            if x_a + 1e-9 < b - o < x_b - 1e-9:
                xs.add(b - o)
    return sorted(xs)


def simulate_vehicle_passage(
    turnout: Turnout,
    settings: PassageSettings,
    vehicle_model: VehicleModel,
    progress: Callable[[float, float], None] | None = None,
    *,
    track: str | None = None,
    fe_options=None,
) -> PassageResult:
    """Run the full vehicle through the turnout, a co-running track under every wheelset.

    See the module docstring for the model. ``settings.x_start`` / ``x_end`` are the front
    wheelset's positions (default: the turnout's start and end); wheelsets behind the
    turnout's start are on plain track. Profile contact only. With ``track="fe"`` the same
    vehicle and contacts run on the FE turnout track instead
    (:func:`~exudyn_turnout.passage.fe_vehicle_passage.simulate_fe_vehicle_passage`).

    Parameters
    ----------
    turnout : Turnout
    settings : PassageSettings
        Route, speed, x range, layers, source, time step, output step, spring mechanism.
    vehicle_model : VehicleModel
        A full vehicle (car body, bogies) from
        :func:`~exudyn_turnout.inputs.vehicle_model.load_vehicle_model`.
    progress : callable(fraction, x), optional
        Called about every 2 % of each segment's run.
    track : {"2-layer", "3-layer", "fe"}, optional
        Default: ``settings.layers`` layers of co-running track under every wheelset.
    fe_options : FEPassageOptions, optional
        Mesh options of the FE track (``track="fe"`` only).

    Returns
    -------
    PassageResult
        Columns: ``t_s``, ``x_m`` (front wheelset), per wheelset k = 1..n ``Fz_wsk_<wheel>_N``,
        ``Fy_wsk_<wheel>_N`` (per rail slot too), ``x_wsk_m``, ``y_wsk_m``, ``z_wsk_m``,
        ``roll_wsk_rad``, ``yaw_wsk_rad``; the front wheelset also under the single-wheelset
        names (``Fz_right_N``, contact points, ``y_wheelset_m``, ``z_rail_<slot>_m``...).
        Summary: :func:`~exudyn_turnout.passage.results.passage_summary` of the front
        wheelset, plus per wheelset ``peak_<Fz|Fy>_<region>_wsk_<wheel>_N`` (region by that
        wheelset's own x) and ``static_wheel_load_wsk_<wheel>_N``.

    Raises
    ------
    PassageError
        Bad settings (one line), a vehicle without car body, or a solver failure.
    """
    if track is not None and track not in TRACKS:
        raise PassageError(f"track must be one of {', '.join(TRACKS)}, got {track!r}")
    if track in ("2-layer", "3-layer"):
        settings = replace(settings, layers=int(track[0]))
    if vehicle_model.car_body is None:
        raise PassageError(f"{vehicle_model.name}: not a full vehicle (no car body)")
    if settings.contact != "profile":
        raise PassageError("the full vehicle runs with the profile contact only")
    base = load_vehicle()
    length = -min(vehicle_model.wheelset.x)  # m, front to rear wheelset
    x_a = turnout.x_min if settings.x_start is None else float(settings.x_start)
    x_b = turnout.x_max if settings.x_end is None else float(settings.x_end)
    if not (turnout.x_min <= x_a < x_b <= turnout.x_max + length + 1e-9):
        raise PassageError(
            f"x range {x_a:g}..{x_b:g} m (front wheelset) must lie within the turnout's "
            f"start and its end plus the vehicle's length ({turnout.x_min:g}.."
            f"{turnout.x_max + length:g} m) with x_start < x_end"
        )
    # speed, time step (the lightest rail under any wheelset), output step: as one wheelset's
    covered = replace(
        settings, x_start=max(turnout.x_min, x_a - length), x_end=min(turnout.x_max, x_b)
    )
    _check(covered, turnout, base)
    route = load_route(turnout, settings.route)
    for text in speed_warnings(route, settings.speed_kmh, x_a, x_b):
        warnings.warn(text, SpeedWarning, stacklevel=2)
    wall = time.perf_counter()
    if track == "fe":
        from exudyn_turnout.passage.fe_vehicle_passage import simulate_fe_vehicle_passage

        with _QuietExudyn():
            return simulate_fe_vehicle_passage(
                turnout, settings, vehicle_model, fe_options, progress=progress
            )
    with _QuietExudyn():
        return _simulate(turnout, settings, vehicle_model, base, route, x_a, x_b, progress, wall)


def _simulate(turnout, settings, model, base, route, x_a, x_b, progress, wall) -> PassageResult:
    from exudyn_turnout.passage.profile_contact import route_contact

    try:
        contact = route_contact(turnout, route.name, base)
    except ValueError as err:
        raise PassageError(str(err)) from None
    vehicle = contact_vehicle(base, model)
    offsets = tuple(model.wheelset.x)
    events = _events(turnout, offsets, x_a, x_b)
    x_range = (x_a + min(offsets), x_b)
    v = settings.v

    def places(x_lo: float, x_hi: float) -> tuple[_Place, ...]:
        return tuple(_place(turnout, 0.5 * (x_lo + x_hi) + o) for o in offsets)

    first = places(events[0], events[1])
    args = (turnout, route, model, vehicle, contact, settings)
    rest = _build(*args, first, x_a, 0.0, True, x_range)
    _solve_static(rest, "static equilibrium at rest")
    state = _state(rest)
    static_loads = [
        el.wheel_loads(el.x_at(0.0), _element_vector(rest, state, i, 0))
        for i, el in enumerate(rest.elements)
    ]
    moving = _build(*args, first, x_a, v, True, x_range)
    _copy_state(state, moving)  # the rest state has K q_geo balanced already
    try:
        for el in moving.elements:
            el.hold_spin = True
        _solve_static(moving, "steady state at speed", 10)
    except PassageFailure:  # e.g. in a curve: relax dynamically with x frozen
        moving = _build(*args, first, x_a, v, True, x_range)
        _copy_state(state, moving)
        _relax(moving, RELAX_TIME, RELAX_STEP)
    state, previous = _state(moving), moving
    t_prev = 0.0
    segments, t_offset, total = [], 0.0, (x_b - x_a) / v
    starts = []
    tables: dict = {}  # the running loads' table, shared by the segments
    for k in range(len(events) - 1):
        x0, x1 = events[k], events[k + 1]
        system = _build(*args, places(x0, x1), x0, v, False, x_range, tables)
        _carry_over(state, previous, system, route, settings.layers, x0, t_prev)
        duration = (x1 - x0) / v
        cols = _run(system, duration, settings, t_offset, total, progress, model.static_wheel_load)
        segments.append(cols if k == 0 else {n: c[1:] for n, c in cols.items()})
        starts.append(x0)
        state, previous, t_prev = _state(system), system, duration
        t_offset += duration
    columns = _join(segments)
    summary = vehicle_summary(turnout, settings, model, columns, static_loads, wall)
    return PassageResult(settings, columns, summary, tuple(starts))


def vehicle_summary(
    turnout: Turnout,
    settings: PassageSettings,
    model: VehicleModel,
    columns: Mapping[str, np.ndarray],
    static_loads: list,
    wall: float,
) -> dict:
    """Summary of a full vehicle's passage: the front wheelset's, then per wheelset peaks.

    Parameters
    ----------
    turnout : Turnout
    settings : PassageSettings
    model : VehicleModel
    columns : mapping
        The run's columns (``Fz_wsk_<wheel>_N``, ``x_wsk_m``...).
    static_loads : list of dict
        Per wheelset, "left" and "right" static wheel loads (N).
    wall : float
        s, ``time.perf_counter()`` at the start of the run.

    Returns
    -------
    dict
        :func:`~exudyn_turnout.passage.results.passage_summary` of the front wheelset plus
        ``peak_<Fz|Fy>_<region>_wsk_<wheel>_N``, ``static_wheel_load_wsk_<wheel>_N``,
        ``vehicle`` and ``wheelsets``.
    """
    front = static_loads[0]
    summary = passage_summary(columns, turnout, settings, front, time.perf_counter() - wall)
    regions = {name: turnout.regions[name] for name in ("switch", "crossing")}
    for i, loads in enumerate(static_loads):
        label = f"ws{i + 1}"
        own = {"x_m": columns[f"x_{label}_m"]}
        for wheel in ("right", "left"):
            summary[f"static_wheel_load_{label}_{wheel}_N"] = float(loads[wheel])
            for q, signed in (("Fz", False), ("Fy", True)):
                own[f"{q}_{wheel}"] = columns[f"{q}_{label}_{wheel}_N"]
                for where, rng in regions.items():
                    summary[f"peak_{q}_{where}_{label}_{wheel}_N"] = _peak(
                        own, f"{q}_{wheel}", rng, signed
                    )
    summary["vehicle"] = model.name
    summary["wheelsets"] = len(static_loads)
    return summary
