"""The full vehicle in the track-following frame: the curve's geometry under the bodies,
the curving and suspension loads on them, the Vehicle its wheelsets' contacts get, and the
vehicle's initial state on its rails.

Relative motion in the track-following frame
--------------------------------------------
Every body i has its own frame: origin O_i on a centreline at arc length s_i = s_f + x_i
(s_f = v t the front wheelset's, x_i <= 0 the body's offset), axes t (forward), n (left),
e_z (up), turning with the centreline at Omega_i = v kappa_i(s_i) about e_z. A body's
coordinates (y, z, roll, pitch, yaw) are its small motions in its frame; it has no
longitudinal coordinate (it stays at s_i). Plane centreline, no cant::

    r   = O_i + y n + z e_z          dt/dt = Omega n,  dn/dt = -Omega t,  dO_i/dt = v t
    r_t = (v - Omega y) t + y_t n + z_t e_z
    r_tt = (-Omega_t y - 2 Omega y_t) t                 Euler and Coriolis: longitudinal,
         + (y_tt + v Omega - Omega^2 y) n               carried by the held x (no coordinate)
         + z_tt e_z

    omega (inertial, small angles) = Omega e_z + (roll_t, pitch_t, yaw_t)
    I_z (yaw_tt + Omega_t) + (I_y - I_x) omega_x omega_y = M_z

with v Omega = v^2 kappa and Omega_t = v^2 dkappa/ds. So each body's equations in its frame
are those of the fixed frame plus two loads of the frame's motion (this class):

- lateral, the centripetal load  -m v^2 kappa_i  (on y);
- yaw, the Euler load  -I_z v^2 dkappa_i/ds  (the frame's angular acceleration): where the
  curvature steps (a curve without transition, as both packaged turnouts' routes), it is an
  impulse -I_z v Delta kappa that keeps the body's inertial yaw rate Omega + yaw_t
  continuous while its frame's rate steps.

Left out, with their size for the Manchester vehicle at 80 km/h in the UIC60-760 diverging
route (R = 760 m, v^2 kappa = 0.650 m/s^2, Omega = 0.0292 rad/s; the EW54 branch, R = 190 m
at 40 km/h, has the same v^2 kappa and Omega = 0.0585 rad/s): Omega^2 y (8.6e-4 1/s^2 times
y: 2e-5 m/s^2 at the 25 mm bumpstop clearance, against 0.65 m/s^2); the Euler and Coriolis
terms along t (no longitudinal coordinate: the held x carries them, e.g. 2 Omega y_t =
6e-3 m/s^2 at 0.1 m/s); the car body's roll-pitch coupling (I_x + I_z - I_y) Omega pitch_t
(56,800 kg m^2 x 0.029 rad/s x ~1e-3 rad/s: ~2 N m); the wheelsets' spin gyroscopic roll
moment J_spin (v / r0) Omega = 112 x 48.3 x 0.0292 = 158 N m (~105 N of wheel load between
the wheels; the vehicle model has no spin gyroscopic terms at all, also not with the
wheelsets' own yaw rate). Cant is not modelled (both packaged routes have none; a route's
``cant`` only enters the cant-deficiency check).

Sizes of the kept ones (same case): centripetal 20.8 kN on the car body (32 t), 1.70 kN per
bogie frame, 1.18 kN per wheelset (the contact element applies the wheelsets'). Euler
impulse at the curve's end (Delta kappa = 1/760 1/m): 57.6 kN m s on the car body
(I_z = 1.97e6 kg m^2), 90 N m s per bogie frame, 33 N m s per wheelset. Without it (as up to
this version) the car body's inertial yaw rate stepped by v Delta kappa = 0.0292 rad/s when
its centre passed 44.29 m; the secondary lateral dampers, d = 9.5 m from it, saw a step of
relative velocity d v Delta kappa = 0.278 m/s, c_y d v Delta kappa = 8.9 kN per damper (32
kN s/m; measured 8.6 kN, opposite in the two bogies), decaying with the car body's yaw
time constant I_z / (4 c_y d^2) = 0.17 s: the largest EN 12299 Wd peak of the run.

The suspension's geometry along the curve was not the cause: q_geo
(:meth:`BodyLoads.geometries`, from the integrated curvature as :func:`curve_geometry`) is
the unstrained vehicle, a rigid body on the tangent of the car body's frame, written in
each body's own frame, so K (q - q_geo) and D (q_t - q_geo_t) are the suspension's
physical strain and strain rate. E.g. a secondary damper at bogie j, d = x_j - x_car ahead
of the car body's CoG, sees (lateral, bogie frame) y_car_t + d yaw_car_t - y_j_t - v
(heading_j - heading_car) + d v kappa_car from the bodies' inertial velocities, and the
same from c^T (q_t - q_geo_t) (c^T q = y_car + d yaw_car - y_j, c^T q_geo = e_j, v de_j/dx
= v (heading_j - heading_car - kappa_car d)). Its term d v kappa_car steps with the car
body's frame; only the Euler load makes d yaw_car_t step against it.

Which frame each body has
-------------------------
The wheelsets' frames follow the route's centreline (their contact element reads y and yaw
relative to the rails at x, and applies their centripetal load with the route's kappa).
The car body's and the bogie frames' coordinates are read only by the suspension (through
q - q_geo) and the outputs, so their frames are free: they follow the route's centreline
smoothed over :data:`FRAME_SMOOTHING` (curvature, heading and lateral offset each
convolved with one triangular kernel, :func:`smoothing_kernel`), whose turning rate is
continuous. Their Euler load then spreads over 0.5 m (22 ms at 80 km/h, ~230 steps of 1e-4
s), and the integrator, which samples a load once per step, takes its impulse to 1e-14 at
1e-4 s and 2e-5 at 2e-4 s (80 km/h; tested); a rate step's impulse spread over one grid
cell would be off by up to the ratio of a step's travel to the ramp. The smoothed
centreline lies kappa sigma^2 / 2 = 7 um off the route's in the 760 m curve (sigma^2 = L^2
/ 24, the kernel's variance) and turns off it by at most Delta kappa L / 12 at a step
(5.5e-5 rad at the 760 m curve's end): nothing physical moves (q_geo expresses the
unstrained vehicle in each body's own frame); only the car body's and bogies'
displacements are read from these frames. The wheelsets' Euler load stays on the route's
curvature: on the 1 cm grid a step spreads over 2 cm, whose impulse the integrator takes
to 1e-13 at 1e-4 s and 1.2 % at 2e-4 s (80 km/h; tested at 1e-4 s).

In steady curving on a constant curvature every frame turns at the same Omega, q_geo is
constant and q_geo_t = 0: the dampers are force-free, the springs carry the centripetal
loads (tested).
"""

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
    "FRAME_SMOOTHING",
    "contact_vehicle",
    "curve_geometry",
    "smoothing_kernel",
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

#: m, base of the triangular kernel smoothing the car body's and bogie frames' centreline
#: (module docstring): long against a time step's travel (2.2 mm at 80 km/h and 1e-4 s),
#: short against the car body's motion (its slowest mode, ~1 Hz: 22 m at 80 km/h).
FRAME_SMOOTHING = 0.5


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


def smoothing_kernel(length: float, step: float) -> np.ndarray:
    """Weights of a triangular kernel of base ``length`` on a grid of ``step`` (sum 1).

    w_j = (n - |j|) / n^2 for j = -n+1 .. n-1, n = round(length / (2 step)): a moving
    average of half the base applied twice (no paper equation: the frames' smoothing of
    :class:`BodyLoads`, module docstring).

    Parameters
    ----------
    length : float
        m, the kernel's base (> 2 step).
    step : float
        m, the grid step.

    Returns
    -------
    numpy.ndarray
        (2 n - 1,) weights.
    """
    n = max(int(round(length / (2.0 * step))), 1)
    j = np.arange(-n + 1, n)
    return (n - np.abs(j)) / float(n * n)


def _smoothed(values: np.ndarray, kernel: np.ndarray) -> np.ndarray:
    """``values`` on a grid padded by half the kernel at both ends, convolved ('valid')."""
    return np.convolve(values, kernel, mode="valid")


class BodyLoads:
    """Force function on the vehicle's nodes: K q_geo + D q_geo_t, the centripetal loads
    -m v^2 kappa on car body and bogies and the Euler loads -I_z v^2 dkappa/ds on every
    body's yaw (module docstring: each body in its own frame; the car body and bogies in
    the frame smoothed over :data:`FRAME_SMOOTHING`).

    The force depends on t only; it is computed once per time (Newton iterations share t).
    """

    def __init__(self, build, stiffness, damping, route: Route, x_f0: float, v: float, x_lo, x_hi):
        self.x_f0, self.v, self.frozen = float(x_f0), float(v), False
        self.d = np.asarray(damping)
        curvature = route.curvature
        self.x = np.arange(x_lo - 1.0, x_hi + 1.0 + _GEOMETRY_STEP, _GEOMETRY_STEP)
        kernel = smoothing_kernel(FRAME_SMOOTHING, _GEOMETRY_STEP)
        pad = (kernel.size - 1) // 2
        # the route on the grid padded by half the kernel: raw, and smoothed on the grid
        x_pad = self.x[0] + _GEOMETRY_STEP * np.arange(-pad, self.x.size + pad)
        kappa_pad = np.interp(x_pad, np.asarray(curvature.x), np.asarray(curvature.value))
        heading_pad, lateral_pad = _integrated_curvature(x_pad, kappa_pad)
        inner = slice(pad, pad + self.x.size)
        #: 1/m, the route's curvature on the grid (the wheelsets' frames)
        self.kappa = kappa_pad[inner]
        self.heading, self.lateral = heading_pad[inner], lateral_pad[inner]
        #: 1/m, rad, m: the smoothed centreline (the car body's and bogie frames')
        self.kappa_smooth = _smoothed(kappa_pad, kernel)
        self.heading_smooth = _smoothed(heading_pad, kernel)
        self.lateral_smooth = _smoothed(lateral_pad, kernel)
        #: 1/m^2, dkappa/ds of each frame's curvature (the Euler loads)
        self.dkappa = np.gradient(self.kappa, _GEOMETRY_STEP)
        self.dkappa_smooth = np.gradient(self.kappa_smooth, _GEOMETRY_STEP)
        self.curved = bool(np.any(kappa_pad != 0.0))
        self.k = np.asarray(stiffness)
        bodies = build.bodies()
        #: node names of the bodies in coordinate order ("car_body", "bogie1", "ws1", ...)
        self.names = [b.name.replace("wheelset", "ws") for b in bodies]
        self.offsets = np.array([b.x for b in bodies])
        self.x_ref = build.car_body.x if build.car_body is not None else 0.0
        self._points = np.append(self.offsets, self.x_ref)  #: m, from the front wheelset
        #: per body, then the reference: True where the frame is the smoothed centreline
        self.smooth = np.array(
            [b.name == "car_body" or b.name.startswith("bogie") for b in bodies]
            + [build.car_body is not None]
        )
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
        masses, inertias = [], []
        for b in bodies:
            if b.name == "car_body":
                masses.append(model.car_body.mass)
                inertias.append(model.car_body.yaw_inertia)
            elif b.name.startswith("bogie"):
                masses.append(model.bogie.mass)
                inertias.append(model.bogie.yaw_inertia)
            else:  # wheelsets: their contact element; sprung points: not in a full vehicle
                masses.append(0.0)
                inertias.append(model.wheelset.yaw_inertia if "yaw" in b.dof else 0.0)
        self.masses = np.array(masses)  #: kg, per body: the centripetal loads' masses
        self.yaw_inertias = np.array(inertias)  #: kg m^2, per body: the Euler loads'
        self._t = math.nan
        self._f = np.zeros(self.n)
        self._t_geo = math.nan
        self._geo = np.zeros(self.n)
        self._x_geo = math.nan  #: m, front position of the last forces' q_geo
        self._q_geo = np.zeros(self.n)
        self._table: tuple[np.ndarray, np.ndarray] | None = None

    def _frame_values(self, x_front: np.ndarray, raw: np.ndarray, smooth: np.ndarray):
        """A grid quantity at every body's x (and the reference's): (positions, points)."""
        xs = np.add.outer(np.asarray(x_front, float), self._points)
        return np.where(self.smooth, np.interp(xs, self.x, smooth), np.interp(xs, self.x, raw))

    def frame_accelerations(self, x_front) -> tuple[np.ndarray, np.ndarray]:
        """Each body's frame: lateral acceleration of its origin v^2 kappa and angular
        acceleration v^2 dkappa/ds (module docstring; zero while ``frozen``: x stands).

        Parameters
        ----------
        x_front : array_like
            m, front wheelset positions.

        Returns
        -------
        lateral : numpy.ndarray
            m/s^2, (positions, bodies + 1): per body, then the reference (the car body's
            frame); positive to the left.
        yaw : numpy.ndarray
            rad/s^2, the same shape.
        """
        x_front = np.atleast_1d(np.asarray(x_front, float))
        kappa = self._frame_values(x_front, self.kappa, self.kappa_smooth)
        dkappa = self._frame_values(x_front, self.dkappa, self.dkappa_smooth)
        if self.frozen:
            dkappa = np.zeros_like(dkappa)
        return self.v**2 * kappa, self.v**2 * dkappa

    def _frame_loads(self, x_front: np.ndarray, factor: float = 1.0) -> np.ndarray:
        """Centripetal and Euler loads (N, N m) at front positions: (positions, n)."""
        lateral, yaw = self.frame_accelerations(x_front)
        f = np.zeros((lateral.shape[0], self.n))
        f[:, self.i_y] = -factor * self.masses * lateral[:, :-1]
        f[:, self._yaw_columns] = -(self.yaw_inertias[self._yaw_bodies] * yaw[:, self._yaw_bodies])
        return f

    def tabulate(self, cache: dict) -> None:
        """Tabulate the running loads (:meth:`forces`) and q_geo at the front positions of the
        1 cm grid ``x``, shared by a run's segments through ``cache``: a step then
        interpolates them linearly (two vector operations) instead of evaluating the route's
        geometry (the loads vary over metres: at most ~0.1 N off the exact ones; the Euler
        loads of the car body and bogies over :data:`FRAME_SMOOTHING`, the wheelsets' over
        2 cm). Only running and in a curve (the static solves evaluate them exactly).

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
            f = q_geo @ self.k.T + rate @ self.d.T + self._frame_loads(self.x)
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
        """:meth:`geometry` at several front positions at once (one row each): the
        unstrained vehicle on the tangent of the reference's frame (the car body's) at its
        x, in each body's own frame (module docstring).

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
        heading = self._frame_values(x_front, self.heading, self.heading_smooth)
        lateral = self._frame_values(x_front, self.lateral, self.lateral_smooth)
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
        K q_geo + D q_geo_t, ``factor`` times the centripetal loads and the Euler loads
        (none while ``frozen``).

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
        if self.curved:  # straight track: no frame loads
            f += self._frame_loads(np.array([x_front]), factor)[0]
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
