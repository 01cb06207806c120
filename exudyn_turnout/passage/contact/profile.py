"""Profile wheel/rail contact of the single wheelset: an Exudyn ``ObjectGenericODE2`` force.

The element couples the wheelset (y, z, roll), its yaw and spin-perturbation coordinates,
the sprung mass (y, z; for the curving load) and the contact body of every rail slot the
route's rail bodies follow in the current zone (the rail mass for two layers, m_0 for
three).  Its force function evaluates, in one compiled call
(:func:`exudyn_turnout.wheel_rail.kernel.contact_forces`), every candidate contact point of
every rail body at the wheelset's position x = x0 + v t: normal force along the contact
normal (the node's law: Hertz where its ellipse fits the surfaces, else a power law through
two Kik-Piotrowski solutions; :mod:`exudyn_turnout.wheel_rail.nonhertz`), creepages with
spin, creep forces from Kalker's FASTSIM table (|F| <= mu N), and the resulting generalised
forces on the wheelset and the rails.  The curving load -m v^2 kappa acts on wheelset and
sprung mass (track-following frame).

Coordinates of the element: ``[y_w, z_w, phi, psi, beta, y_s, z_s, y_r1, z_r1, ...]``
(beta: spin perturbation about the axle, the wheel turning at v / r0 + beta_t).

Nothing is evaluated twice: the solver calls the force function, and the outputs (forces,
contact positions, creepages per contact point) are computed afterwards from the stored
coordinates and velocities by the same kernel (:meth:`ProfileContactElement.columns`).
"""

from __future__ import annotations

import math
import re
import time
from bisect import bisect_right
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from exudyn_turnout.inputs.routes import Route
from exudyn_turnout.inputs.vehicle import Vehicle
from exudyn_turnout.passage.contact import route_cache
from exudyn_turnout.passage.contact.protocol import ContactElement
from exudyn_turnout.passage.contact.route_cache import route_contact_key, wheel_grid
from exudyn_turnout.wheel_rail.kernel import DETAIL_FIELDS, contact_forces, contact_history
from exudyn_turnout.wheel_rail.packed_tables import PackedTables

__all__ = [
    "RouteContact",
    "route_contact",
    "wheel_and_setup",
    "ProfileContactElement",
    "STATIC_LATERAL_STIFFNESS",
    "STATIC_SPIN_STIFFNESS",
    "N_VEHICLE_COORDINATES",
    "contact_columns",
    "RigidRailContact",
]

#: N/m: holds the wheelset's lateral position in the static solve (v = 0), where creep gives
#: no lateral stiffness; the design geometry's symmetric equilibrium has y = 0.
STATIC_LATERAL_STIFFNESS = 1e7
#: N m/rad: holds the spin perturbation in the static solve, where it has no stiffness.
STATIC_SPIN_STIFFNESS = 1e6
#: Vehicle coordinates at the head of the element: y_w, z_w, phi, psi, beta, y_s, z_s.
N_VEHICLE_COORDINATES = 7

_DETAIL = {name: k for k, name in enumerate(DETAIL_FIELDS)}


def _interp(xs: tuple, values: tuple, x: float) -> float:
    """Piecewise-linear table (xs, values) at x, constant beyond its ends (scalar, fast)."""
    i = bisect_right(xs, x)
    if i <= 0:
        return values[0]
    if i >= len(xs):
        return values[-1]
    x0, x1 = xs[i - 1], xs[i]
    return values[i - 1] + (values[i] - values[i - 1]) * (x - x0) / (x1 - x0)


def _slug(text: str) -> str:
    return re.sub(r"[^a-z0-9]+", "_", text.lower()).strip("_")


@dataclass(frozen=True)
class _Body:
    """A rail body bound to the element: its name, wheel, rail slot and coordinates."""

    name: str
    wheel: str  #: "left" or "right"
    rail: str  #: co-running rail slot
    i_y: int  #: index of the slot's lateral coordinate in the element
    i_z: int  #: index of its vertical coordinate


class ProfileContactElement(ContactElement):
    """Force function of the profile contact element (see the module docstring).

    Parameters
    ----------
    vehicle : Vehicle
        Wheelset radius, masses for the curving load, friction and normal damping.
    route : Route
        The route: its curvature.
    tables : PackedTables
        The rail bodies of this zone, bound to the element's coordinates
        (:meth:`PackedTables.select <exudyn_turnout.wheel_rail.packed_tables.PackedTables>`).
    bodies : sequence of (wheel, rail slot)
        Per packed body, the wheel ("left"/"right") and the rail slot it follows.
    x0 : float
        m, position of the wheelset at t = 0.
    v : float
        m/s, speed; 0 for the static solve (no creep, lateral position and spin held).
    irregularity : Irregularity, optional
        Rail irregularities (its ``at(x)`` gives vertical left/right, lateral left/right).
    shear_modulus : float
        Pa, G of wheel and rail steel for the creep forces.
    """

    n_vehicle = N_VEHICLE_COORDINATES
    #: its lateral loads at rest are N tan(gamma) of real contact points (re-based at zone
    #: boundaries, passage.corunning_track.carry_over.static_deflection)
    lateral_static_loads = True

    def __init__(
        self,
        vehicle: Vehicle,
        route: Route,
        tables: PackedTables,
        bodies: Sequence[tuple[str, str]],
        x0: float,
        v: float,
        irregularity=None,
        shear_modulus: float = 8.1e10,
    ):
        self.vehicle, self.route, self.tables = vehicle, route, tables
        self.x0, self.v = float(x0), float(v)
        self.irregularity = irregularity
        #: m, depth of the running surfaces below the axle: a roll phi moves them by this
        #: times phi sideways (the kernel's shift)
        self.running_surface_depth = vehicle.r0
        layout = tables.layout
        self.bodies = tuple(
            _Body(tables.names[k], wheel, rail, int(layout[k, 7]), int(layout[k, 8]))
            for k, (wheel, rail) in enumerate(bodies)
        )
        slots = {(b.i_y, b.i_z) for b in self.bodies}
        self.n = self.n_vehicle + 2 * len(slots)
        self.wheel_of = {b.rail: b.wheel for b in self.bodies}
        self._constants = np.array(
            [self.v, vehicle.r0, vehicle.contact.mu, shear_modulus, vehicle.contact.damping, 0.0]
        )
        self._forces = np.zeros(self.n)
        self._details = np.zeros((max(tables.n_bodies, 1) * tables.n_candidates, len(_DETAIL)))
        self._irr = np.zeros(4)
        self._cached_t = math.nan
        self._kappa = 0.0
        curvature = route.curvature
        self._curvature_x = np.asarray(curvature.x, float)
        self._curvature_v = np.asarray(curvature.value, float)
        self._curvature_xs = tuple(float(a) for a in curvature.x)
        self._curvature_vs = tuple(float(a) for a in curvature.value)

    def _prepare(self, x: float) -> None:
        self._kappa = _interp(self._curvature_xs, self._curvature_vs, x)
        self._constants[5] = self._kappa
        if self.irregularity is not None:
            self._irr[:] = self.irregularity.at(x)

    def prepare(self, x: float) -> None:
        """Set the curvature and irregularity at x for the next :meth:`forces_at` calls.

        Parameters
        ----------
        x : float
            m, wheelset position.
        """
        self._prepare(x)

    def forces_at(self, x: float, q: np.ndarray, q_t: np.ndarray) -> np.ndarray:
        """Generalised contact forces for coordinates q, q_t at x (after :meth:`prepare`).

        The hot path of a caller that evaluates the contact many times at one x (the FE
        track's coupling solve): no copies, no curving load, no static holds.

        Parameters
        ----------
        x : float
            m, wheelset position (the one given to :meth:`prepare`).
        q, q_t : numpy.ndarray
            Element coordinates and velocities (float arrays of length ``n``).

        Returns
        -------
        numpy.ndarray
            The element's force buffer (overwritten by the next call).
        """
        self._call(x, q, q_t)
        return self._forces

    def evaluate(self, x: float, q, q_t) -> tuple[np.ndarray, np.ndarray]:
        """Contact forces at position x for element coordinates q, q_t.

        Parameters
        ----------
        x : float
            m, position of the wheelset along the route.
        q, q_t : array_like
            Element coordinates and velocities (module docstring order).

        Returns
        -------
        forces : numpy.ndarray
            Generalised contact forces on the element's coordinates (without the curving
            load and the static holds); a copy.
        details : numpy.ndarray
            Per body and candidate slot, the columns of
            :data:`~exudyn_turnout.wheel_rail.kernel.DETAIL_FIELDS`; a copy.
        """
        self._prepare(x)
        self._call(x, np.asarray(q, float), np.asarray(q_t, float))
        return self._forces.copy(), self._details.copy()

    def _call(self, x: float, q: np.ndarray, q_t: np.ndarray) -> None:
        p = self.tables
        contact_forces(
            x,
            q,
            q_t,
            self._irr,
            p.values,
            p.blendable,
            p.x,
            p.layout,
            p.bounds,
            self._constants,
            self._forces,
            self._details,
        )

    def touching_position(self, x: float, penetration: float) -> tuple[float, float]:
        """Wheelset height and roll at which both wheels touch their rails, pressed in.

        A start for the static solver (the Hertz contacts need closed contact to have any
        stiffness): the rigid lift at which each wheel's nearest point touches, at zero
        lateral shift, less ``penetration``.

        Parameters
        ----------
        x : float
            m, wheelset position.
        penetration : float
            m, normal penetration to add (e.g. the static Hertz penetration).

        Returns
        -------
        z_w, phi : float
            m and rad: wheelset height and roll.
        """
        _, details = self.evaluate(x, np.zeros(self.n), np.zeros(self.n))
        touch = {"left": -math.inf, "right": -math.inf}
        n_c = self.tables.n_candidates
        for k, body in enumerate(self.bodies):
            for row in details[k * n_c : (k + 1) * n_c]:
                if row[_DETAIL["found"]] > 0.0:
                    lift = row[_DETAIL["delta"]] / max(math.cos(row[_DETAIL["angle"]]), 0.1)
                    touch[body.wheel] = max(touch[body.wheel], lift)
        left = touch["left"] if math.isfinite(touch["left"]) else 0.0
        right = touch["right"] if math.isfinite(touch["right"]) else 0.0
        b = self.vehicle.b
        return 0.5 * (left + right) - penetration, (left - right) / (2.0 * b)

    def rail_loads(self, x: float, q, q_t) -> dict[str, tuple[float, float]]:
        """Total (vertical, lateral) force on each rail slot touched.

        Parameters
        ----------
        x : float
            m, wheelset position.
        q, q_t : array_like
            Element coordinates and velocities.

        Returns
        -------
        dict
            Slot -> (vertical force pressing it down, lateral force on it, positive left), N.
        """
        forces, _ = self.evaluate(x, q, q_t)
        out: dict[str, tuple[float, float]] = {}
        for b in self.bodies:
            out[b.rail] = (-forces[b.i_z], forces[b.i_y])
        return out

    def wheel_loads(self, x: float, q) -> dict[str, float]:
        """Total vertical force (N) on each wheel at rest (velocities zero).

        Parameters
        ----------
        x : float
            m, wheelset position.
        q : array_like
            Element coordinates.

        Returns
        -------
        dict
            "left", "right" -> N.
        """
        _, details = self.evaluate(x, q, np.zeros(self.n))
        loads = {"left": 0.0, "right": 0.0}
        n_c = self.tables.n_candidates
        for k, b in enumerate(self.bodies):
            loads[b.wheel] += float(details[k * n_c : (k + 1) * n_c, _DETAIL["Fz"]].sum())
        return loads

    def last_forces(self) -> np.ndarray:
        """The generalised forces of the last :meth:`__call__` (during a run, before a step:
        those of the step's start; the check rail's watch,
        :class:`~exudyn_turnout.passage.check_rail_steps.CheckRailStop`). A view, overwritten by the
        next call.

        Returns
        -------
        numpy.ndarray
            N, (element size,).
        """
        return self._forces

    def __call__(self, mbs, t, item_number, q, q_t):
        """Exudyn ``forceUserFunction``: generalised forces on the element's coordinates."""
        if t != self._cached_t:  # Newton iterations of one step share t
            self._cached_t = t
            self._prepare(self.x_at(t))
        q = np.array(q, dtype=float)
        self._call(self.x_at(t), q, np.array(q_t, dtype=float))
        forces = self._forces
        vehicle = self.vehicle
        if self.v > 0.0:
            a_y = self.v**2 * self._kappa
            forces[0] -= vehicle.m_w * a_y
            forces[5] -= vehicle.m_s * a_y
        else:
            forces[0] -= STATIC_LATERAL_STIFFNESS * q[0]
            forces[4] -= STATIC_SPIN_STIFFNESS * q[4]
        return forces

    def columns(self, t: np.ndarray, q: np.ndarray, q_t: np.ndarray) -> dict[str, np.ndarray]:
        """Output columns of a stored run, computed from coordinates and velocities.

        Parameters
        ----------
        t : numpy.ndarray
            s, (n,) times of the samples (from the zone's start).
        q, q_t : numpy.ndarray
            (n, element size) stored element coordinates and velocities.

        Returns
        -------
        dict
            Per wheel and rail slot ``Fz_<wheel>_<rail>_N``, ``Fy_<wheel>_<rail>_N`` (on the
            rail), per wheel ``Fz_<wheel>_N``, ``Fy_<wheel>_N``, and per contact point
            (:func:`contact_columns`).
        """
        n = len(t)
        x = self.x0 + self.v * np.asarray(t, float)
        irregularity = np.zeros((n, 4))
        if self.irregularity is not None:
            irregularity[:] = np.asarray(self.irregularity.at_array(x), float).T
        p = self.tables
        forces, details = contact_history(
            x,
            np.ascontiguousarray(q, float),
            np.ascontiguousarray(q_t, float),
            irregularity,
            np.interp(x, self._curvature_x, self._curvature_v),
            p.values,
            p.blendable,
            p.x,
            p.layout,
            p.bounds,
            self._constants,
        )
        return self.columns_of(forces, details)

    def columns_of(self, forces: np.ndarray, details: np.ndarray) -> dict[str, np.ndarray]:
        """:meth:`columns` from the contact kernel's outputs of the samples (e.g. recorded
        during the run instead of evaluated again after it).

        Parameters
        ----------
        forces : numpy.ndarray
            (n, element size) generalised contact forces.
        details : numpy.ndarray
            (n, rows, fields) per-contact rows.

        Returns
        -------
        dict
            As :meth:`columns`.
        """
        n = len(forces)
        # per slot, the forces on its distinct coordinate pairs (bodies of one slot share a
        # pair on the co-running track; on the FE track every body has its own)
        rails: dict[str, np.ndarray] = {}
        seen: set = set()
        for b in self.bodies:
            if (b.i_y, b.i_z) in seen:
                continue
            seen.add((b.i_y, b.i_z))
            values = np.column_stack((-forces[:, b.i_z], forces[:, b.i_y]))
            rails[b.rail] = rails[b.rail] + values if b.rail in rails else values
        cols: dict[str, np.ndarray] = {}
        for wheel in ("right", "left"):
            cols[f"Fz_{wheel}_N"], cols[f"Fy_{wheel}_N"] = np.zeros(n), np.zeros(n)
        for rail, values in rails.items():
            wheel = self.wheel_of[rail]
            cols[f"Fz_{wheel}_{rail}_N"], cols[f"Fy_{wheel}_{rail}_N"] = values[:, 0], values[:, 1]
            cols[f"Fz_{wheel}_N"] = cols[f"Fz_{wheel}_N"] + values[:, 0]
            cols[f"Fy_{wheel}_N"] = cols[f"Fy_{wheel}_N"] + values[:, 1]
        cols.update(contact_columns(details, self.bodies, self.tables.n_candidates))
        return cols


@dataclass(frozen=True, eq=False)
class RouteContact:
    """The rail bodies of a route with their packed contact tables (built once per passage)."""

    #: profile contact: spin coordinate, outputs from the stored coordinates and velocities
    profile = True

    tables: PackedTables  #: every body of the route (coordinates bound per zone)
    wheels: tuple  #: per body, "left" or "right"
    rails: tuple  #: per body, the co-running rail slot it follows
    build_seconds: float  #: s, time to build or load the tables

    def element(
        self,
        vehicle: Vehicle,
        route: Route,
        zone,
        x0: float,
        v: float,
        irregularity=None,
    ) -> tuple[ProfileContactElement, list[str]]:
        """The contact element of one zone: the bodies that exist in it on an active rail.

        A body takes part if its rail slot is active in the zone (Table 3) and its x range
        overlaps the zone's over a positive length: a body that ends where the zone begins
        (the crossing nose, whose rail slot continues as another in the next zone) is left
        out, so that its rail slot's meaning in one zone never mixes with the next's.

        Parameters
        ----------
        vehicle : Vehicle
        route : Route
        zone : Zone
            The zone (``active_rails``, ``x_start``, ``x_end``).
        x0, v : float
            m, m/s: start position and speed (0: static solve).
        irregularity : Irregularity, optional

        Returns
        -------
        element : ProfileContactElement
        slots : list of str
            The rail slots the element couples to, in coordinate order.

        Raises
        ------
        ValueError
            Both wheels would touch the same rail slot.
        """
        active_rails = zone.active_rails
        bounds = self.tables.bounds
        keep = [
            k
            for k, rail in enumerate(self.rails)
            if rail in active_rails
            and min(bounds[k, 3], zone.x_end) - max(bounds[k, 2], zone.x_start) > 1e-9
        ]
        slots = [r for r in active_rails if any(self.rails[k] == r for k in keep)]
        for r in slots:
            if len({self.wheels[k] for k in keep if self.rails[k] == r}) > 1:
                raise ValueError(f"route {route.name}: rail {r} is touched by both wheels")
        index = {r: N_VEHICLE_COORDINATES + 2 * i for i, r in enumerate(slots)}
        coordinates = [(index[self.rails[k]], index[self.rails[k]] + 1) for k in keep]
        element = ProfileContactElement(
            vehicle,
            route,
            self.tables.select(keep, coordinates),
            [(self.wheels[k], self.rails[k]) for k in keep],
            x0,
            v,
            irregularity,
        )
        return element, slots


def wheel_and_setup(turnout, vehicle: Vehicle, cache_dir=None) -> tuple:
    """The vehicle's wheel profile, gridded, and the wheelset/track dimensions that place it.

    Parameters
    ----------
    turnout : Turnout
        Its ``[wheel_rail]`` gauge and rail inclination.
    vehicle : Vehicle
        Its ``wheel_profile`` (beside the vehicle file or packaged), ``back_to_back`` and
        wheel radius r0.
    cache_dir : str or Path, optional
        Where the gridded wheel is cached
        (:func:`~exudyn_turnout.passage.contact.route_cache.wheel_grid`; default: the user's
        cache directory).

    Returns
    -------
    wheel : WheelGrid
    setup : WheelsetSetup
    """
    from pathlib import Path

    from exudyn_turnout.wheel_rail.data import profile_path
    from exudyn_turnout.wheel_rail.geometry import WheelsetSetup
    from exudyn_turnout.wheel_rail.turnout_design import rail_geometry

    geometry = rail_geometry(turnout)
    setup = WheelsetSetup(
        gauge=geometry.gauge,
        back_to_back=float(vehicle.back_to_back),  # type: ignore[arg-type]
        inclination=geometry.inclination,
        nominal_radius=vehicle.r0,
    )
    profile_file = Path(str(vehicle.wheel_profile))
    if not profile_file.is_absolute():
        beside = Path(vehicle.source).parent / profile_file
        profile_file = beside if beside.exists() else profile_path(str(vehicle.wheel_profile))
    return wheel_grid(profile_file, setup.grid_step, setup.nominal_radius, cache_dir), setup


def route_contact(turnout, route: str, vehicle: Vehicle, cache_dir=None) -> RouteContact:
    """Contact tables of every rail body of a route for the vehicle's wheel profile.

    Kept in memory for the last few routes (keyed by
    :func:`~exudyn_turnout.passage.contact.route_cache.route_contact_key`: the turnout
    file's contact sections and design files, the route, the wheel's profile, back-to-back
    and radius; not the track's stiffness, damping or masses). Otherwise loaded from the
    route's disk entry beside the contact tables (``route_contact_<key>.npz``, uncompressed,
    read without pickle, ~40 MB for a route of the packaged turnout): the packed arrays, body
    names, wheels and rail slots as built, bit for bit, under that key plus the source of
    the code that builds, packs and stores them (every module of ``wheel_rail/``, the route
    and turnout loaders, this module and
    :mod:`~exudyn_turnout.passage.contact.route_cache`) and the numpy, scipy and numba
    versions, with a CRC-32 of the arrays. A process then skips building the rail sections
    and loading and packing each body's table (~0.4 s). A missing, damaged or foreign entry
    is built again and overwritten; an unusable cache location means building (one warning,
    :func:`~exudyn_turnout.wheel_rail.tables.write_cache_file`).

    Parameters
    ----------
    turnout : Turnout
        With its ``[wheel_rail]`` geometry and the route's rail bodies.
    route : str
        Route name.
    vehicle : Vehicle
        Needs ``wheel_profile``, ``back_to_back`` and ``J_spin`` (profile contact).
    cache_dir : str or Path, optional
        Where tables are cached (default: the user's cache directory).

    Returns
    -------
    RouteContact

    Raises
    ------
    ValueError
        The vehicle file lacks what profile contact needs (one line naming the field).
    """
    from pathlib import Path

    from exudyn_turnout.wheel_rail.packed_tables import pack_tables
    from exudyn_turnout.wheel_rail.turnout_design import rail_geometry
    from exudyn_turnout.wheel_rail.turnout_sections import route_contact_tables

    name = Path(vehicle.source).name
    for field, value in (
        ("spin_inertia", vehicle.J_spin),
        ("back_to_back", vehicle.back_to_back),
        ("wheel_profile", vehicle.wheel_profile),
    ):
        if value is None:
            raise ValueError(
                f"{name}: [wheelset].{field} is needed for profile contact "
                "(or run with contact='height-table')"
            )
    key = route_contact_key(turnout, route, vehicle, cache_dir)
    recent = route_cache.recent_contact(key)
    if recent is not None:
        return recent
    start = time.perf_counter()
    path, full_key = route_cache.route_entry(key, cache_dir)
    stored = route_cache.read_route_entry(path, full_key)
    if stored is not None:
        tables, wheels, rails = stored
        contact = RouteContact(tables, wheels, rails, time.perf_counter() - start)
    else:
        wheel, setup = wheel_and_setup(turnout, vehicle, cache_dir)
        pairs = route_contact_tables(turnout, route, wheel, setup, cache_dir=cache_dir)
        bodies = [body for body, _ in pairs]
        # the check rail's own friction ([check_rail] friction; 0: the vehicle's mu)
        check_mu = rail_geometry(turnout).check_rail.friction
        packed = pack_tables(
            [table for _, table in pairs],
            [1 if b.wheel == "left" else -1 for b in bodies],
            [(0, 0)] * len(bodies),
            [(b.x_from, b.x_to) for b in bodies],
            names=[b.name for b in bodies],
            friction=[check_mu if b.back_of_flange else 0.0 for b in bodies],
        )
        contact = RouteContact(
            packed,
            tuple(b.wheel for b in bodies),
            tuple(b.rail for b in bodies),
            time.perf_counter() - start,
        )
        route_cache.write_route_entry(path, full_key, contact.tables, contact.wheels, contact.rails)
    route_cache.keep_recent(key, contact)
    return contact


#: Per contact point outputs: column stem -> detail field (SI units in the stem's suffix).
_POINT_COLUMNS = {
    "N": "normal",
    "Fx": "Fx",
    "Ft": "Ft",
    "y_rail": "y_rail",
    "s_wheel": "s_wheel",
    "x": "x_offset",
    "angle": "angle",
    "xi": "xi",
    "eta": "eta",
    "spin": "spin",
}
_UNITS = {
    "N": "N",
    "Fx": "N",
    "Ft": "N",
    "y_rail": "m",
    "s_wheel": "m",
    "x": "m",
    "angle": "rad",
    "xi": "1",
    "eta": "1",
    "spin": "1pm",
}


def contact_columns(
    details: np.ndarray, bodies: Sequence, n_candidates: int
) -> Mapping[str, np.ndarray]:
    """Per contact point columns from the kernel's detail rows over time.

    Parameters
    ----------
    details : numpy.ndarray
        (n, n_bodies * n_candidates, len(DETAIL_FIELDS)).
    bodies : sequence
        The element's bodies (``name``, ``wheel``, ``rail``).
    n_candidates : int
        Candidate slots per body.

    Returns
    -------
    dict
        ``cp_<wheel>_<rail>_<body>_<k>_<quantity>_<unit>``: normal force, creep forces,
        position on rail and wheel, position ahead of the wheel centre (``x``: the lead
        of a yawed wheel's contact, :mod:`exudyn_turnout.wheel_rail.lead`, plus where the
        wheel meets a rail rising along x), contact angle, creepages, and the wear number
        ``Tgamma_..._N`` = |F_x xi| + |F_t eta| (N m/m).  Forces are 0 out of contact,
        creepages NaN; positions and angle are kept while the point is found (a candidate
        within the table's gap range), even unloaded, else NaN.  Only points that carry load
        at some time get columns.
    """
    out: dict[str, np.ndarray] = {}
    for k, body in enumerate(bodies):
        stem = f"cp_{body.wheel}_{body.rail}_{_slug(body.name)}"
        for c in range(n_candidates):
            rows = details[:, k * n_candidates + c, :]
            loaded = rows[:, _DETAIL["normal"]] > 0.0
            if not loaded.any():
                continue
            found = rows[:, _DETAIL["delta"]] > -0.5
            for name, field in _POINT_COLUMNS.items():
                values = rows[:, _DETAIL[field]].copy()
                if name in ("xi", "eta", "spin"):
                    values[~loaded] = np.nan
                elif name not in ("N", "Fx", "Ft"):  # forces are 0 out of contact
                    values[~found] = np.nan
                out[f"{stem}_{c}_{name}_{_UNITS[name]}"] = values
            wear = np.abs(rows[:, _DETAIL["Fx"]] * rows[:, _DETAIL["xi"]]) + np.abs(
                rows[:, _DETAIL["Ft"]] * rows[:, _DETAIL["eta"]]
            )
            out[f"{stem}_{c}_Tgamma_N"] = np.where(loaded, wear, 0.0)
    return out


class RigidRailContact:
    """Force function of one wheelset's profile contact on rigid rails at a fixed position.

    The contact element's ``evaluate`` at x = ``x`` whatever t, its rail coordinates (and the
    element's sprung-mass coordinates) held at zero; only the wheelset's first ``n``
    coordinates (y, z, roll, yaw, spin) are in the Exudyn object (an ``ObjectGenericODE2``
    on the wheelset node, this object its ``forceUserFunction``). Subtracts a lateral
    ``load`` (the wheelset's curving load m_w v^2 kappa); with ``static`` set, the lateral
    position and the spin are held by :data:`STATIC_LATERAL_STIFFNESS` and
    :data:`STATIC_SPIN_STIFFNESS` (a static solve, where creep gives no stiffness).

    Parameters
    ----------
    element : ProfileContactElement
        The wheelset's contact element.
    x : float
        m, the position along the route.
    n : int
        Number of the wheelset node's coordinates.
    load : float
        N, lateral load subtracted from the lateral force.
    """

    def __init__(self, element: ProfileContactElement, x: float, n: int, load: float = 0.0):
        self.element, self.x, self.n, self.load = element, float(x), n, float(load)
        self.q = np.zeros(element.n)
        self.q_t = np.zeros(element.n)
        self.static = False

    def full(self, q, q_t) -> tuple[np.ndarray, np.ndarray]:
        """The element's coordinates and velocities for the wheelset's ``q``, ``q_t``.

        Parameters
        ----------
        q, q_t : array_like
            The wheelset node's coordinates and velocities.

        Returns
        -------
        (numpy.ndarray, numpy.ndarray)
            Copies, the other coordinates zero.
        """
        self.q[: self.n], self.q_t[: self.n] = q, q_t
        return self.q.copy(), self.q_t.copy()

    def __call__(self, mbs, t, item_number, q, q_t):
        """Exudyn's force user function: the contact forces on the wheelset's coordinates."""
        n = self.n
        self.q[:n], self.q_t[:n] = q, q_t
        forces = self.element.evaluate(self.x, self.q, self.q_t)[0][:n]
        forces[0] -= self.load
        if self.static:
            forces[0] -= STATIC_LATERAL_STIFFNESS * q[0]
            forces[4] -= STATIC_SPIN_STIFFNESS * q[4]
        return forces
