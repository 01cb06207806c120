"""The full vehicle in the track-following frame: the curve's geometry under the bodies,
the curving and suspension loads on them, the Vehicle its wheelsets' contacts get, and the
vehicle's initial state on its rails."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from exudyn_turnout.inputs.routes import Route
from exudyn_turnout.inputs.vehicle import Vehicle
from exudyn_turnout.inputs.vehicle_model import VehicleModel

__all__ = [
    "DUMMY_MASS",
    "DUMMY_STIFFNESS",
    "contact_vehicle",
    "curve_geometry",
    "BodyLoads",
    "add_vehicle_loads",
    "set_initial_vehicle",
]

#: kg, mass of each of the contact element's two unused sprung-mass coordinates.
DUMMY_MASS = 1.0

#: N/m, stiffness holding them at rest (nothing loads them: m_s = 0).
DUMMY_STIFFNESS = 1e6

#: m, grid step of the route's integrated curvature (heading and lateral offset).
_GEOMETRY_STEP = 0.01


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
    return _curve_offsets(x, *_integrated_curvature(x, kappa), x_points, x_ref)


def _integrated_curvature(x: np.ndarray, kappa: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Heading int kappa and lateral offset int heading from x[0] (trapezoidal rule).

    Parameters
    ----------
    x, kappa : numpy.ndarray
        m, 1/m: curvature on an increasing grid.

    Returns
    -------
    heading : numpy.ndarray
        rad.
    lateral : numpy.ndarray
        m.
    """
    heading = np.concatenate(([0.0], np.cumsum(0.5 * (kappa[1:] + kappa[:-1]) * np.diff(x))))
    lateral = np.concatenate(([0.0], np.cumsum(0.5 * (heading[1:] + heading[:-1]) * np.diff(x))))
    return heading, lateral


def _curve_offsets(
    x: np.ndarray, heading: np.ndarray, lateral: np.ndarray, x_points: np.ndarray, x_ref: float
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`curve_geometry` from the integrated curvature (:func:`_integrated_curvature`).

    Parameters
    ----------
    x, heading, lateral : numpy.ndarray
        m, rad, m: the grid and its integrated curvature.
    x_points : numpy.ndarray
        m, where e and theta are wanted.
    x_ref : float
        m, the reference point (tangent).

    Returns
    -------
    e, theta : numpy.ndarray
        m, rad.
    """
    h_ref, l_ref = np.interp(x_ref, x, heading), np.interp(x_ref, x, lateral)
    h, lat = np.interp(x_points, x, heading), np.interp(x_points, x, lateral)
    return lat - l_ref - h_ref * (x_points - x_ref), h - h_ref


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
        self.heading, self.lateral = _integrated_curvature(self.x, self.kappa)
        self.k = np.asarray(stiffness)
        bodies = build.bodies()
        #: node names of the bodies in coordinate order ("car_body", "bogie1", "ws1", ...)
        self.names = [b.name.replace("wheelset", "ws") for b in bodies]
        self.offsets = np.array([b.x for b in bodies])
        self.x_ref = build.car_body.x if build.car_body is not None else 0.0
        self._points = np.append(self.offsets, self.x_ref)  #: m, from the front wheelset
        starts = np.cumsum([0] + [len(b.dof) for b in bodies])
        self.n = int(starts[-1])
        #: index of each body's first coordinate in the bodies' coordinate order
        self.starts = starts[:-1].astype(int)
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


def add_vehicle_loads(mbs, build, loads: BodyLoads) -> tuple:
    """The curving loads (``loads``) and the lateral bumpstops of ``vehicle_builder`` on the
    vehicle's bodies, the bumpstops acting on q - q_geo (track-following frame: a bumpstop
    sees the car body's displacement relative to the unstrained vehicle).

    For a curve: one ObjectGenericODE2 on all bodies carries both (one Python call per
    residual evaluation); its Jacobian is the bumpstops' (the loads depend on t only). The
    co-running full vehicle puts both on its contacts' object instead
    (:class:`~exudyn_turnout.passage.contact.vehicle_contacts.VehicleContacts`).

    Parameters
    ----------
    mbs : exudyn.MainSystem
    build : VehicleBuild
        From :func:`~exudyn_turnout.passage.vehicle.builder.add_vehicle_model`.
    loads : BodyLoads

    Returns
    -------
    tuple
        The user functions (keep them alive as long as the system).
    """
    from exudyn.itemInterface import ObjectGenericODE2

    from exudyn_turnout.passage.vehicle import builder as vehicle_builder

    model, car, bogies = build.model, build.car_body, build.bogies
    n, size = loads.n, 0  # the bumpstops' coordinates: car body and bogies, first in order
    if model.bumpstop is not None:
        size, (stop_force, stop_jacobian) = vehicle_builder.linear_bumpstop_functions(
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
        From :func:`~exudyn_turnout.passage.vehicle.builder.add_vehicle_model`.
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
