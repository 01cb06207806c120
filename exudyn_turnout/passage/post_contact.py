"""CONTACT-style post-processing of a passage: the exact contact at one recorded instant.

What a Simpack user does with CONTACT after a run, done with our own detailed contact
(:mod:`exudyn_turnout.wheel_rail.detailed_contact`): take one contact point of one sample of
a :class:`~exudyn_turnout.passage.results.PassageResult`, rebuild the wheel's position
against the rail body there, solve the contact exactly and put the passage's own numbers
beside the exact ones (:func:`post_contact`, :class:`PostContact`).

Rebuilding the instant
----------------------
* **The passage's own contact** is evaluated again by the passage's compiled kernel
  (:func:`~exudyn_turnout.wheel_rail.kernel.contact_forces`) on the recorded coordinates:
  the wheelset's lateral displacement, height, roll and yaw and the rail body's lateral and
  vertical displacement (columns ``y_wheelset_m``, ``z_wheelset_m``, ``roll_wheelset_rad``,
  ``yaw_wheelset_rad``, ``y_rail_<slot>_m``, ``z_rail_<slot>_m``; a full vehicle's plain
  columns are its front wheelset's).  This gives what the result does not record: the
  penetration delta, the semi-axes of the creep law's ellipse and the contact stiffness.
  Its normal force must equal the recorded one (checked: :attr:`PostContact.rebuilt_normal`;
  the normal damping of the packaged vehicles is 0).  :func:`rebuild_contact` alone gives
  this state (milliseconds once the route's tables are loaded).
* **The 3-D gap**: the rail body's sections (not enveloped), with the rail's exact section
  added every 1 mm around the contact (``section_step``;
  :func:`~exudyn_turnout.wheel_rail.turnout_sections.exact_sections_between`: between the
  body's own nodes a linear blend of a check rail's flared face is not a face),
  interpolated along the track at ``x + X`` for every row X of the grid, the wheel a body
  of revolution at the passage's lateral shift ``s (y_w + r0 phi - y_r)``, lift ``z_w +
  Y_c phi - z_r`` (the kernel's, see
  :mod:`~exudyn_turnout.wheel_rail.kernel`) and yaw (to first order in psi: a point at
  ``y_p - y_0`` from the taping line lies ``s (y_p - y_0) psi`` behind its row and moves
  ``s X psi`` sideways; this gives the lead of flange contacts of
  :mod:`~exudyn_turnout.wheel_rail.lead` without its formula).  As in the passage, X is
  measured from the wheel's own axle point (the wheel's shift along the track by
  ``-s 0.75 m psi`` of a yawed wheelset is not applied to the rail: the passage does not).
  Both profiles are turned into the frame of the passage's contact angle and the gap is
  taken along that normal (the upper envelope of the rail's polyline, the lower of the
  wheel's), so that flange and check-rail contacts are as well posed as the tread;
  times ``cos(pitch)`` of the contact plane pitched by ``asin(x_c / r0)``
  (:func:`~exudyn_turnout.wheel_rail.reference_normal.contact_pitch`).  The grid is
  centred on the gap's deepest point along the tangent (within 15 mm of the passage's
  contact point, which is its law's force centre; at a flange contact that centre lies
  several millimetres along the tangent from the deepest point, ~9 mm at 30 kN on the
  plain stock rail, tests/test_peak_contact.py's flange case; the passage records it
  moved along its normal onto the rail's surface,
  :func:`~exudyn_turnout.wheel_rail.node_laws.surface_offset`).  Roll is applied as the
  passage applies it (shift and lift), not as a tilt of the profile across the patch.
* **Exact normal problem** (:func:`~exudyn_turnout.wheel_rail.exact_normal.solve_normal`)
  on that gap, **at the passage's normal force** (the comparison's primary quantity: the
  approach there, against the passage's penetration).  Why the force and not the
  position: the force is recorded exactly and is what the paper's peaks are, whereas an
  approach of 0.05-0.15 mm rebuilt from body positions of metres inherits every
  difference of the two geometries (the 2-D enveloped slices of the tables against the
  3-D surfaces) on top of the law's.  Both other views are given too: the exact force at
  the passage's penetration taken as approach beyond first touch of the 3-D surfaces (the
  law's error alone, :attr:`PostContact.exact_normal_at_approach`), and the exact force
  at the passage's state, from the 3-D surfaces' own interpenetration (law and geometry,
  :attr:`PostContact.exact_normal_at_state`).
* **The 2-D slice and the choice of law**: on the 2-D lateral gap at the contact's x (the
  3-D gap's row there along the tangent, plus ``A x^2``, ``A = cos(gamma) / (2 r0)``: the
  gap a semi-Hertzian method sees), Kik-Piotrowski's force at the passage's penetration
  (:attr:`PostContact.kp_normal_at_approach`: the tables' law had it taken KP instead of
  Hertz) and the exact approach at the passage's force
  (:attr:`PostContact.exact_2d_approach`: against the 3-D approach, what no method on the
  2-D slice can recover).
* **The creep law alone**: Kalker's exact theory on the passage's own ellipse with
  Hertz's pressure (:func:`~exudyn_turnout.wheel_rail.exact_rolling.exact_creep_forces_ellipse`)
  at the same creepages separates the FASTSIM table's error from the patch's.
* **Exact tangential problem** (Kalker's steady rolling,
  :func:`~exudyn_turnout.wheel_rail.detailed_contact.rolling_on_normal`) on the exact
  pressure at the passage's creepages xi, eta and spin (about the force centre), its
  friction coefficient and the creep law's G = 81 GPa and nu = 0.28 (those of the
  passage's creep table); forces on the wheel along X and the passage's lateral tangent
  ``t = (0, cos(gamma), s sin(gamma))``, the signs of the recorded ``Fx``, ``Ft``.

Elements are sized to the exact patch (about :data:`ELEMENTS_ACROSS` along each axis, a
first solve on the passage's ellipse finds it): a few hundred elements in contact, one to
a few seconds per call.  Not modelled: the conformal (curved) contact plane of a flange
or two-point contact (one plane per call; call it per contact point), the interaction
of two patches of one wheel, dissimilar materials.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import PchipInterpolator

from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.inputs.vehicle import Vehicle, load_vehicle
from exudyn_turnout.passage.contact.profile import route_contact, wheel_and_setup
from exudyn_turnout.passage.results import PassageResult
from exudyn_turnout.wheel_rail.detailed_contact import rolling_on_normal
from exudyn_turnout.wheel_rail.exact_normal import (
    NormalSolution,
    solve_normal,
    solve_on_lateral_gap,
)
from exudyn_turnout.wheel_rail.exact_rolling import exact_creep_forces_ellipse
from exudyn_turnout.wheel_rail.geometry import prepare_wheel
from exudyn_turnout.wheel_rail.hertz import effective_modulus
from exudyn_turnout.wheel_rail.kernel import DETAIL_FIELDS, contact_forces
from exudyn_turnout.wheel_rail.nonhertz import kik_piotrowski
from exudyn_turnout.wheel_rail.reference_normal import contact_pitch
from exudyn_turnout.wheel_rail.sections import sections_at
from exudyn_turnout.wheel_rail.turnout_design import rail_geometry
from exudyn_turnout.wheel_rail.turnout_sections import (
    EXACT_SECTION_STEP,
    exact_sections_between,
    route_rail_bodies,
)

__all__ = [
    "ELEMENTS_ACROSS",
    "SMOOTHING",
    "ELLIPSE_ELEMENTS",
    "smooth_wheel",
    "SHEAR_MODULUS",
    "CREEP_POISSON",
    "PostContact",
    "RebuiltContact",
    "rebuild_contact",
    "contact_stems",
    "post_contact",
]

#: elements along each axis of the exact patch (the element size follows the patch)
ELEMENTS_ACROSS = 26
#: elements across each axis of the passage's ellipse for :attr:`PostContact.ellipse_fx`
#: (Kalker's C11, C22, C23 within 2.6 % from 20 on: ``exact_creep_forces_ellipse``)
ELLIPSE_ELEMENTS = 30
#: the rail's section rows and the wheel's points are joined by a shape-preserving cubic,
#: sampled this many times denser than their 0.1 mm grid (:func:`smooth_wheel`)
SMOOTHING = 4
#: Pa, G of the passage's creep law (``ProfileContactElement``'s default)
SHEAR_MODULUS = 8.1e10
#: Poisson's ratio of the passage's creep coefficients (``packed_tables.pack_tables``' default)
CREEP_POISSON = 0.28
_YOUNG, _POISSON = 2.1e11, 0.3  # Pa, -: the tables' E* (TableSettings defaults)
_D = {name: k for k, name in enumerate(DETAIL_FIELDS)}
_SEARCH, _SEARCH_STEP = 0.015, 5e-5  # m, the deepest point is searched this far along t
_LATERAL_REACH = 0.03  # m, the 2-D lateral gap's reach either side of the deepest point
_N_VEHICLE = 7  # y_w, z_w, phi, psi, beta, y_s, z_s (profile contact element)


@dataclass(frozen=True)
class PostContact:
    """The passage's contact and the exact one at one recorded instant (SI units)."""

    stem: str  #: the contact's column stem, ``cp_<wheel>_<rail>_<body>_<k>``
    x: float  #: m, wheelset position of the sample
    t: float  #: s, its time
    angle: float  #: rad, contact angle (the passage's)
    semi_hertzian: float  #: -, weight of the Kik-Piotrowski law at the node (0: Hertz)
    y_rail: float  #: m, recorded contact position on the rail (side coordinates)
    y_rail_rebuilt: float  #: m, the kernel's, re-evaluated on the recorded coordinates
    y_rail_exact: float  #: m, where the exact normal force acts, on the rail
    x_contact: float  #: m, recorded contact position ahead of the wheel's axle
    x_contact_exact: float  #: m, the exact force centre's
    normal: float  #: N, recorded normal force
    rebuilt_normal: float  #: N, the kernel's elastic law at the rebuilt penetration
    approach: float  #: m, the passage's penetration delta (rebuilt)
    exact_approach: float  #: m, exact approach at the passage's normal force
    exact_normal_at_approach: float  #: N, exact force at approach ``approach``
    interpenetration: float  #: m, undeformed interpenetration of the 3-D surfaces there
    exact_normal_at_state: float  #: N, exact force at that interpenetration
    stiffness: float  #: N/m, the passage law's dN/d(delta) at ``approach``
    exact_stiffness: float  #: N/m, exact secant stiffness between the two approaches
    length: float  #: m, the passage's patch length 2 a (creep law's ellipse)
    exact_length: float  #: m, exact patch extent along x
    width: float  #: m, the passage's patch width 2 b
    exact_width: float  #: m, exact patch extent along the lateral tangent
    p_max: float  #: Pa, the passage ellipse's Hertzian peak 3 N / (2 pi a b)
    exact_p_max: float  #: Pa, the exact solution's largest element pressure
    xi: float  #: -, the passage's longitudinal creepage
    eta: float  #: -, lateral creepage
    spin: float  #: 1/m, spin creepage
    friction: float  #: -, coefficient of friction
    fx: float  #: N, recorded longitudinal creep force on the wheel
    exact_fx: float  #: N, exact, at the same creepages
    fs: float  #: N, recorded lateral creep force along the tangent t
    exact_fs: float  #: N, exact
    #: N, Kalker's exact theory on the passage's own ellipse (Hertzian pressure, 2a x 2b) at
    #: the same creepages: against ``fx`` the creep law's error alone, against ``exact_fx``
    #: the patch's
    ellipse_fx: float
    ellipse_fs: float  #: N, the same for FS
    #: N, Kik-Piotrowski on the 2-D lateral gap at the contact's x (the 3-D surfaces' gap
    #: along the tangent there, plus ``A x^2``) at the passage's penetration: what the
    #: tables' law would give there if it took KP instead of Hertz
    kp_normal_at_approach: float
    kp_width: float  #: m, KP's patch width there
    #: m, the exact approach on that 2-D gap ``g(t) + A x^2`` at the passage's normal force:
    #: against :attr:`exact_approach` (3-D) the error of any method on the 2-D slice
    exact_2d_approach: float
    exact_2d_width: float  #: m, its patch width
    dx: float  #: m, element length
    ds: float  #: m, element width
    elements: int  #: -, elements in contact
    seconds: float  #: s, wall time of the exact solution

    @property
    def force_difference(self) -> float:
        """N, exact force at the passage's approach minus the passage's force."""
        return self.exact_normal_at_approach - self.normal


def contact_stems(result: PassageResult, wheel: str | None = None) -> tuple[str, ...]:
    """The contact points a passage recorded, as column stems.

    Parameters
    ----------
    result : PassageResult
        A profile-contact passage.
    wheel : {"left", "right"}, optional
        Only this wheel's.

    Returns
    -------
    tuple of str
        ``cp_<wheel>_<rail>_<body>_<k>`` of every ``..._N_N`` column.
    """
    head = "cp_" if wheel is None else f"cp_{wheel}_"
    return tuple(
        name[: -len("_N_N")]
        for name in result.columns
        if name.startswith(head) and name.endswith("_N_N")
    )


def _slug(text: str) -> str:
    return "_".join(part for part in "".join(
        c if c.isalnum() else " " for c in text.lower()).split())  # fmt: skip


def _column(result: PassageResult, name: str, index: int) -> float:
    if name not in result.columns:
        raise ValueError(f"post_contact: the result has no column {name!r}")
    return float(result.columns[name][index])


def _envelope(tau, nu, grid, upper: bool) -> np.ndarray:
    """Upper (lower) envelope of a polyline (tau, nu) at ``grid``; NaN where none."""
    good = np.isfinite(tau) & np.isfinite(nu)
    a = good[:-1] & good[1:]
    t0, t1, n0, n1 = tau[:-1][a], tau[1:][a], nu[:-1][a], nu[1:][a]
    lo, hi = np.minimum(t0, t1), np.maximum(t0, t1)
    near = (hi >= grid.min()) & (lo <= grid.max())
    t0, t1, n0, n1, lo, hi = t0[near], t1[near], n0[near], n1[near], lo[near], hi[near]
    g = grid[None, :]
    inside = (g >= lo[:, None]) & (g <= hi[:, None])
    span = np.where(t1 != t0, t1 - t0, 1.0)[:, None]
    w = np.clip((g - t0[:, None]) / span, 0.0, 1.0)
    value = n0[:, None] + w * (n1 - n0)[:, None]
    if upper:
        out = np.max(np.where(inside, value, -np.inf), axis=0, initial=-np.inf)
    else:
        out = np.min(np.where(inside, value, np.inf), axis=0, initial=np.inf)
    return np.where(np.isfinite(out), out, np.nan)


@dataclass(frozen=True)
class _Instant:
    """What the gap needs of the rebuilt instant."""

    side: int
    shift: float
    lift: float
    yaw: float
    angle: float
    y_c: float
    z_c: float
    x_c: float
    r0: float
    taping_line: float


def _smooth_row(y: np.ndarray, z: np.ndarray, refine: int) -> tuple[np.ndarray, np.ndarray]:
    """A section row's finite runs through a shape-preserving cubic, ``refine`` x denser.

    The sections are polylines on the lateral grid: between their points the lateral
    curvature is zero and at them a delta, which the exact solution's pressure peaks on
    (``reference_normal``'s module docstring); PCHIP (Fritsch-Carlson) removes the kinks
    without overshooting steps and edges.
    """
    finite = np.isfinite(z)
    edges = np.flatnonzero(np.diff(np.concatenate(([0], finite.astype(np.int8), [0]))))
    ys, zs = [], []
    for a, b in zip(edges[::2], edges[1::2]):
        if b - a < 3:
            ys.append(y[a:b])
            zs.append(z[a:b])
        else:
            fine = np.linspace(y[a], y[b - 1], (b - a - 1) * refine + 1)
            ys.append(fine)
            zs.append(PchipInterpolator(y[a:b], z[a:b])(fine))
        ys.append(np.array([np.nan]))  # keeps runs apart
        zs.append(np.array([np.nan]))
    return np.concatenate(ys), np.concatenate(zs)


def smooth_wheel(y, z, refine: int = SMOOTHING) -> tuple[np.ndarray, np.ndarray]:
    """A wheel's surface points through a parametric shape-preserving cubic.

    Parameters
    ----------
    y, z : numpy.ndarray
        m, the points in order along the profile (may turn back in y: flange back).
    refine : int
        Points per original interval.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        m, the denser points (:func:`PchipInterpolator` of y and z over the chord length).
    """
    y, z = np.asarray(y, float), np.asarray(z, float)
    keep = np.concatenate(([True], np.hypot(np.diff(y), np.diff(z)) > 0.0))
    y, z = y[keep], z[keep]
    s = np.concatenate(([0.0], np.cumsum(np.hypot(np.diff(y), np.diff(z)))))
    fine = np.linspace(0.0, s[-1], (len(s) - 1) * refine + 1)
    return PchipInterpolator(s, y)(fine), PchipInterpolator(s, z)(fine)


def _gap(inst: _Instant, sections, wheel_pts, x_ws: float, rows, t) -> np.ndarray:
    """Normal gap (m) at rows X (from the wheel's axle point) and tangent positions t."""
    s = inst.side
    cos_g, sin_g = math.cos(inst.angle), math.sin(inst.angle)
    tau = s * np.asarray(t, float)  # side-coordinate tangent (cos g, sin g)
    rail_z = sections_at(sections, x_ws + np.asarray(rows, float))
    y_p, z_p, r_p = wheel_pts
    out = np.empty((len(rows), len(t)))
    for i, X in enumerate(rows):
        y_r, z_r = _smooth_row(sections.y, rail_z[i], SMOOTHING)
        dy, dz = y_r - inst.y_c, z_r - inst.z_c
        rail = _envelope(dy * cos_g + dz * sin_g, -dy * sin_g + dz * cos_g, tau, True)
        xi_w = X + s * (y_p - inst.taping_line) * inst.yaw
        y_w = y_p + inst.shift + s * xi_w * inst.yaw - inst.y_c
        drop = r_p - np.sqrt(np.maximum(r_p**2 - xi_w**2, 0.0))
        z_w = z_p + inst.lift + drop - inst.z_c
        wheel = _envelope(y_w * cos_g + z_w * sin_g, -y_w * sin_g + z_w * cos_g, tau, False)
        out[i] = wheel - rail
    return np.where(np.isfinite(out), out, 1.0)


def _deepest(inst: _Instant, sections, wheel_pts, x_ws: float) -> float:
    """Where along the tangent (m, from the passage's contact point) the gap is lowest.

    The passage's contact point is its law's force centre, moved along the tangent from
    the deepest point (and along the normal onto the rail, which leaves its tangent
    coordinate); the exact grid is centred on the deepest point itself.
    """
    t = np.arange(-_SEARCH, _SEARCH + 0.5 * _SEARCH_STEP, _SEARCH_STEP)
    gap = _gap(inst, sections, wheel_pts, x_ws, np.array([inst.x_c]), t)[0]
    return float(t[int(np.argmin(gap))])


def _solve(inst, sections, wheel_pts, x_ws, pitch, dx, ds, half_x, half_t, modulus, force, t0):
    """Exact normal solution at ``force`` on a grid grown until the patch fits."""
    along = math.cos(pitch)
    for _ in range(8):
        nx, ny = 2 * int(half_x / dx) + 1, 2 * int(half_t / ds) + 1
        rows = inst.x_c + (np.arange(nx) - 0.5 * (nx - 1)) * dx * along
        t = t0 + (np.arange(ny) - 0.5 * (ny - 1)) * ds
        h = math.cos(pitch) * _gap(inst, sections, wheel_pts, x_ws, rows, t)
        lowest = float(np.min(h))
        solved = solve_normal(h - lowest, dx, ds, modulus, force=force)
        r, c = np.nonzero(solved.pressure)
        if r.min() > 0 and c.min() > 0 and r.max() < nx - 1 and c.max() < ny - 1:
            return solved, h, lowest, rows, t
        half_x, half_t = 1.5 * half_x, 1.5 * half_t
    raise ValueError("post_contact: the exact patch does not fit an 8-times grown grid")


def _lateral(inst, sections, wheel_pts, x_ws, pitch, t0, delta, force, modulus, dx, ds):
    """KP at ``delta`` and the exact solution at ``force`` on the 2-D lateral gap at the
    contact's x (a semi-Hertzian method's gap, ``g(t) + A x^2`` with ``A = cos(gamma) /
    (2 r0)``, the wheel's circle seen along the contact normal)."""
    t = t0 + np.arange(-_LATERAL_REACH, _LATERAL_REACH + 0.5 * _SEARCH_STEP, _SEARCH_STEP)
    gap = math.cos(pitch) * _gap(inst, sections, wheel_pts, x_ws, np.array([inst.x_c]), t)[0]
    gap = gap - float(np.min(gap))
    a_sum = math.cos(inst.angle) / (2.0 * inst.r0)
    kp = kik_piotrowski(gap[None, :], _SEARCH_STEP, a_sum, delta, modulus)
    flat = solve_on_lateral_gap(gap, _SEARCH_STEP, a_sum, force, modulus, dx, ds)
    return kp, flat


@dataclass(frozen=True)
class RebuiltContact:
    """The passage's own contact at a recorded sample, evaluated again by its kernel (SI)."""

    body: str  #: the rail body's name
    side: int  #: +1 left wheel, -1 right
    x: float  #: m, wheelset position
    shift: float  #: m, the wheel's lateral shift towards its field side, relative to the body
    lift: float  #: m, the wheel's lift above the body at the contact (the kernel's)
    yaw: float  #: rad, wheelset yaw
    approach: float  #: m, penetration delta (<= 0: not in contact)
    normal: float  #: N, the elastic normal law at ``approach``
    stiffness: float  #: N/m, its dN/d(delta)
    a: float  #: m, semi-axis of the creep law's ellipse along x
    b: float  #: m, lateral semi-axis
    semi_hertzian: float  #: -, weight of the Kik-Piotrowski law (0: Hertz)
    angle: float  #: rad, contact angle
    y_rail: float  #: m, contact position on the rail (side coordinates)
    z_rail: float  #: m, its height
    x_contact: float  #: m, contact position ahead of the wheel's axle (lead included)


def rebuild_contact(
    turnout: Turnout,
    result: PassageResult,
    stem: str,
    index: int,
    vehicle: Vehicle | None = None,
) -> RebuiltContact:
    """The passage's contact point at one sample, from its kernel on the recorded coordinates.

    The compiled kernel (:func:`~exudyn_turnout.wheel_rail.kernel.contact_forces`) on the
    route's contact tables, with the wheelset's and the rail body's recorded coordinates,
    velocities zero (no creep, no normal damping: the elastic law alone).

    Parameters
    ----------
    turnout : Turnout
        The turnout the passage ran on.
    result : PassageResult
        A profile-contact passage on a co-running track.
    stem : str
        The contact point (:func:`contact_stems`).
    index : int
        Sample index.
    vehicle : Vehicle, optional
        Default :func:`.load_vehicle`.

    Returns
    -------
    RebuiltContact

    Raises
    ------
    ValueError
        Unknown contact or sample, or a result without the columns.
    """
    vehicle = vehicle if vehicle is not None else load_vehicle()
    n = len(result.columns["x_m"])
    if not -n <= index < n:
        raise ValueError(f"post_contact: sample {index} outside the result's {n} samples")
    x_ws = _column(result, "x_m", index)
    route = result.settings.route
    contact = route_contact(turnout, route, vehicle)
    tables = contact.tables
    body = next(
        (
            k
            for k, name in enumerate(tables.names)
            if stem.startswith(f"cp_{contact.wheels[k]}_{contact.rails[k]}_{_slug(name)}_")
        ),
        None,
    )
    if body is None:
        raise ValueError(f"post_contact: no rail body of route {route!r} matches {stem!r}")
    candidate = int(stem.rsplit("_", 1)[1])
    side = 1 if contact.wheels[body] == "left" else -1
    slot = contact.rails[body]
    q = np.zeros(_N_VEHICLE + 2)
    names = ("y_wheelset_m", "z_wheelset_m", "roll_wheelset_rad", "yaw_wheelset_rad")
    for k, name in enumerate(names):
        q[k] = _column(result, name, index)
    q[_N_VEHICLE] = _column(result, f"y_rail_{slot}_m", index)
    q[_N_VEHICLE + 1] = _column(result, f"z_rail_{slot}_m", index)
    packed = tables.select([body], [(_N_VEHICLE, _N_VEHICLE + 1)])
    n_c = int(packed.layout[0, 5])
    if not 0 <= candidate < n_c:
        raise ValueError(f"post_contact: {stem!r} names candidate {candidate} of {n_c}")
    details = np.zeros((n_c, len(DETAIL_FIELDS)))
    constants = np.array([0.0, vehicle.r0, vehicle.contact.mu, SHEAR_MODULUS, 0.0, 0.0])
    contact_forces(
        x_ws, q, np.zeros_like(q), np.zeros(4), packed.values, packed.blendable, packed.x,
        packed.layout, packed.bounds, constants, np.zeros_like(q), details,
    )  # fmt: skip
    row = details[candidate]
    y_w, z_w, phi, psi = q[0], q[1], q[2], q[3]
    y_c = float(row[_D["y_rail"]])
    return RebuiltContact(
        body=str(tables.names[body]),
        side=side,
        x=x_ws,
        shift=float(side * (y_w + vehicle.r0 * phi - q[_N_VEHICLE])),
        lift=float(z_w + (side * y_c - y_w) * phi - q[_N_VEHICLE + 1]),
        yaw=float(psi),
        approach=float(row[_D["delta"]]),
        normal=float(row[_D["normal"]]),
        stiffness=float(row[_D["stiffness"]]),
        a=float(row[_D["a"]]),
        b=float(row[_D["b"]]),
        semi_hertzian=float(row[_D["semi_hertzian"]]),
        angle=float(row[_D["angle"]]),
        y_rail=y_c,
        z_rail=float(row[_D["z_rail"]]),
        x_contact=float(row[_D["x_offset"]]),
    )


def post_contact(
    turnout: Turnout,
    result: PassageResult,
    stem: str,
    index: int,
    vehicle: Vehicle | None = None,
    elements: int = ELEMENTS_ACROSS,
    section_step: float | None = EXACT_SECTION_STEP,
) -> PostContact:
    """The exact contact at one sample of a passage, beside the passage's (module docstring).

    Parameters
    ----------
    turnout : Turnout
        The turnout the passage ran on.
    result : PassageResult
        A profile-contact passage on a co-running track (single wheelset or full vehicle;
        the full vehicle's plain columns are its front wheelset's).
    stem : str
        The contact point, a column stem of :func:`contact_stems`.
    index : int
        Sample index into the result's columns; the contact must carry load there.
    vehicle : Vehicle, optional
        The wheelset vehicle of the contact (default :func:`.load_vehicle`, which the full
        vehicle's contact uses too).
    elements : int
        Elements along each axis of the exact patch.
    section_step : float or None
        m: the rail's exact section every ``section_step`` around the contact
        (:func:`~exudyn_turnout.wheel_rail.turnout_sections.exact_sections_between`, within
        5 cm + 4 a of it); None: the body's sections blended linearly between its nodes, as
        the passage's tables see the rail (at a check rail's flare end that blend cuts the
        face's kink: the exact force 79-81 % below the passage's instead of 36-57 %).

    Returns
    -------
    PostContact

    Raises
    ------
    ValueError
        Unknown contact, a sample without load there, or a result without the columns.
    """
    started = time.perf_counter()
    vehicle = vehicle if vehicle is not None else load_vehicle()
    normal = _column(result, f"{stem}_N_N", index)
    if not normal > 0.0:
        raise ValueError(f"post_contact: {stem} carries no load at sample {index}")
    rebuilt = rebuild_contact(turnout, result, stem, index, vehicle)
    if not rebuilt.approach > 0.0:
        raise ValueError(f"post_contact: the rebuilt {stem} is not in contact at sample {index}")
    x_ws = rebuilt.x
    route = result.settings.route
    side = rebuilt.side
    angle = rebuilt.angle
    delta = rebuilt.approach
    y_c = rebuilt.y_rail
    inst = _Instant(
        side=side,
        shift=rebuilt.shift,
        lift=rebuilt.lift,
        yaw=rebuilt.yaw,
        angle=angle,
        y_c=y_c,
        z_c=rebuilt.z_rail,
        x_c=rebuilt.x_contact,
        r0=vehicle.r0,
        taping_line=0.0,
    )
    wheel, setup = wheel_and_setup(turnout, vehicle)
    prepared = prepare_wheel(wheel, setup.taping_line, 0.0, ())
    inst = _Instant(**{**inst.__dict__, "taping_line": setup.taping_line})
    y_p, z_p = smooth_wheel(prepared.y, prepared.z)
    wheel_pts = (y_p, z_p, vehicle.r0 - z_p)
    rail_body = next(b for b in route_rail_bodies(turnout, route) if b.name == rebuilt.body)
    sections = rail_body.sections
    if section_step is not None:
        span = 0.05 + 4.0 * rebuilt.a
        x_c = x_ws + rebuilt.x_contact
        sections = exact_sections_between(turnout, rail_body, x_c - span, x_c + span, section_step)
    # the friction the passage's kernel used there: a check rail's own, else the vehicle's
    mu = float(vehicle.contact.mu)
    if rail_body.back_of_flange and rail_geometry(turnout).check_rail.friction > 0.0:
        mu = rail_geometry(turnout).check_rail.friction
    modulus = effective_modulus(_YOUNG, _POISSON)
    pitch = contact_pitch(inst.x_c, vehicle.r0)
    a, b = rebuilt.a, rebuilt.b
    dx, ds = 2.0 * a / elements, 2.0 * b / elements
    t0 = _deepest(inst, sections, wheel_pts, x_ws)
    solved, h, lowest, rows, t = _solve(
        inst, sections, wheel_pts, x_ws, pitch, dx, ds, 1.5 * a, 1.5 * b, modulus, normal, t0
    )
    # elements sized to the exact patch, then the final solution
    dx, ds = solved.length / elements, solved.width / elements
    solved, h, lowest, rows, t = _solve(
        inst, sections, wheel_pts, x_ws, pitch, dx, ds,
        0.75 * solved.length, 0.75 * solved.width, modulus, normal, _centre(solved, t),
    )  # fmt: skip
    shifted = h - lowest
    at_approach = solve_normal(shifted, dx, ds, modulus, approach=delta).normal_force
    at_state = (
        solve_normal(shifted, dx, ds, modulus, approach=-lowest).normal_force
        if lowest < 0.0
        else 0.0
    )
    xi, eta, spin = (_column(result, f"{stem}_{k}", index) for k in ("xi_1", "eta_1", "spin_1pm"))
    rolling = rolling_on_normal(solved, xi, eta, spin, mu, SHEAR_MODULUS, CREEP_POISSON)
    on_ellipse = exact_creep_forces_ellipse(
        a, b, xi, eta, spin, normal, mu, SHEAR_MODULUS, CREEP_POISSON,
        n=ELLIPSE_ELEMENTS,
    )  # fmt: skip
    kp, flat = _lateral(inst, sections, wheel_pts, x_ws, pitch, t0, delta, normal, modulus, dx, ds)
    t_centre = _centre(solved, t)
    x_centre = _centre_x(solved, rows)
    gap_step = solved.approach - delta
    stiffness_exact = (
        (at_approach - normal) / (delta - solved.approach) if abs(gap_step) > 1e-12 else math.nan
    )
    return PostContact(
        stem=stem,
        x=x_ws,
        t=_column(result, "t_s", index),
        angle=angle,
        semi_hertzian=rebuilt.semi_hertzian,
        y_rail=_column(result, f"{stem}_y_rail_m", index),
        y_rail_rebuilt=y_c,
        y_rail_exact=y_c + side * t_centre * math.cos(angle),
        x_contact=_column(result, f"{stem}_x_m", index),
        x_contact_exact=x_centre,
        normal=normal,
        rebuilt_normal=rebuilt.normal,
        approach=delta,
        exact_approach=float(solved.approach),
        exact_normal_at_approach=float(at_approach),
        interpenetration=max(-lowest, 0.0),
        exact_normal_at_state=float(at_state),
        stiffness=rebuilt.stiffness,
        exact_stiffness=float(stiffness_exact),
        length=2.0 * a,
        exact_length=float(solved.length),
        width=2.0 * b,
        exact_width=float(solved.width),
        p_max=3.0 * normal / (2.0 * math.pi * a * b),
        exact_p_max=float(solved.p_max),
        xi=xi,
        eta=eta,
        spin=spin,
        friction=mu,
        fx=_column(result, f"{stem}_Fx_N", index),
        exact_fx=float(rolling.fx),
        fs=_column(result, f"{stem}_Ft_N", index),
        exact_fs=float(rolling.fy),
        ellipse_fx=float(on_ellipse[0]),
        ellipse_fs=float(on_ellipse[1]),
        kp_normal_at_approach=float(kp.normal_force[0]),
        kp_width=float(kp.t_high[0] - kp.t_low[0]),
        exact_2d_approach=float(flat.approach),
        exact_2d_width=float(flat.width),
        dx=dx,
        ds=ds,
        elements=int(np.count_nonzero(solved.pressure)),
        seconds=time.perf_counter() - started,
    )


def _centre(solution: NormalSolution, t: np.ndarray) -> float:
    """Where the normal force acts along the tangent, in the grid's t (m)."""
    p = solution.pressure
    return float(np.sum(p.sum(axis=0) * t) / p.sum())


def _centre_x(solution: NormalSolution, rows: np.ndarray) -> float:
    """Where the normal force acts along the track, from the wheel's axle point (m)."""
    p = solution.pressure
    return float(np.sum(p.sum(axis=1) * rows) / p.sum())
