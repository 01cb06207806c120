"""Wheel/rail contact geometry from profiles: candidate contact points, wheelset equilibrium.

Method (undeformed-distance, "rigid" contact geometry)
------------------------------------------------------
Wheel and rail surfaces are gridded on the same uniform lateral grid (side coordinates of
:mod:`.sections`: y from the track centre towards the field side, z up, metres).  For a
wheel at lateral shift ``s`` (its taping line ``s`` further towards the field side than
nominal), height ``lift`` (of its taping circle's lowest point above the top of rail
level) and roll, the vertical gap is

    g(y) = z_wheel(y) - z_rail(y).

Every local minimum of g over a separate region of the profile is a *candidate* contact
point (tread, flange root, flange; wing rail and nose on a crossing): two minima belong to
separate regions when g rises by more than ``prominence`` between them.  The global minimum
is where a rigid wheel touches; with elastic (penalty) contact every candidate with a small
gap can carry load.  At a minimum the two surfaces are parallel, so

- the contact angle ``gamma = atan(dz/dy)`` of the surfaces there is **positive when the
  normal force on the wheel points towards the track centre** (tread of a coned wheel,
  flange against the gauge face);
- the normal gap is ``g cos(gamma)`` for small gaps;
- ``dg/ds = -tan(gamma)``: moving the wheel towards the field side closes the gap of a
  point with positive contact angle.

The principal curvatures for Hertz are the profiles' lateral curvatures (positive when the
body is convex towards the other: a rail crown, a wheel tread bulging down) and the wheel's
rolling-direction curvature ``cos(gamma) / r``.  Profile curvatures come from a
Savitzky-Golay fit (cubic, 1.5 mm window) of the gridded surfaces.

Wheelset: the two wheels share lateral shift (towards the left field side for the left
wheel, the right field side for the right one), height and roll (left side up positive);
:func:`solve_wheelset` finds roll and height at which both wheels touch for every lateral
position, EN 15302's rolling-radius difference and :func:`equivalent_conicity` (regression)
or :func:`equivalent_conicity_klingel` (integration of the kinematic motion) follow.

Modules: the gridded profiles and their derivatives live in :mod:`.profile_grid`, the
minima and envelope helpers in :mod:`.gap_minima`, the conicity and flange-climb
characteristics in :mod:`.conicity`; their public names are re-exported here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from scipy.optimize import brentq

from exudyn_turnout.wheel_rail.conicity import (
    equivalent_conicity,
    equivalent_conicity_klingel,
    flange_angle,
    nadal_limit,
)
from exudyn_turnout.wheel_rail.gap_minima import (
    batch_local_minima,
    finite_runs,
    lower_envelope,
    profile_envelope,
    refine_minimum,
    rotate_profile,
)
from exudyn_turnout.wheel_rail.lead import contact_lead
from exudyn_turnout.wheel_rail.profile_grid import (
    CURVATURE_WINDOW,
    SurfaceDerivatives,
    WheelGrid,
    WheelsetSetup,
    grid_wheel,
    savgol_derivatives,
    surface_derivatives,
    wheel_heights_on_grid,
)
from exudyn_turnout.wheel_rail.sections import SectionGrid

__all__ = [
    "WheelsetSetup",
    "WheelGrid",
    "SurfaceDerivatives",
    "Candidates",
    "yawed",
    "grid_wheel",
    "surface_derivatives",
    "find_candidates",
    "FLANGE_DIRECTION",
    "CHECK_RAIL_DIRECTION",
    "PreparedRail",
    "PreparedWheel",
    "prepare_rail",
    "prepare_wheel",
    "flange_back_arc",
    "FLANGE_BACK",
    "FLANGE_BACK_RADIUS",
    "search_candidates",
    "search_candidates_batch",
    "wheel_heights_on_grid",
    "WheelsetContact",
    "solve_wheelset",
    "rail_row",
    "equivalent_conicity",
    "equivalent_conicity_klingel",
    "flange_angle",
    "nadal_limit",
]

_NO_GAP = 1.0  # m, gap written where a candidate slot is empty
_CANDIDATE_FIELDS = (
    "gap", "y_rail", "z_rail", "s_wheel", "angle", "radius", "curvature_rail",
    "curvature_wheel", "x_lead",
)  # fmt: skip

#: One rail section for the contact solvers: heights z (m), slope dz/dy (-), curvature
#: (1/m), all on the lateral grid y (m), in side coordinates (see :func:`rail_row`).
RailRow = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]


@dataclass(frozen=True, eq=False)
class Candidates:
    """Candidate contact points of one wheel on one rail (arrays over candidates)."""

    gap: np.ndarray  #: m, normal gap at the candidate (negative: interpenetration)
    y_rail: np.ndarray  #: m, lateral position on the rail grid (side coordinates)
    z_rail: np.ndarray  #: m, rail surface height there
    s_wheel: np.ndarray  #: m, lateral position on the wheel from its taping line
    angle: np.ndarray  #: rad, contact angle (positive: normal on wheel towards track centre)
    radius: np.ndarray  #: m, wheel rolling radius at the candidate
    curvature_rail: np.ndarray  #: 1/m, rail lateral curvature (convex positive)
    curvature_wheel: np.ndarray  #: 1/m, wheel lateral curvature (convex positive)
    #: m, contact point ahead of the axle (the lead of a yawed wheel, :func:`yawed`); None:
    #: no yaw, 0
    x_lead: np.ndarray | None = None


def yawed(found: Candidates, side: int, yaw: float) -> Candidates:
    """Candidates of a wheel yawed by ``yaw``: leading or trailing, nearer the rail.

    The wheel is a surface of revolution: yawed, it meets the (prismatic) rail at
    ``x_lead = r sin(theta)`` ahead of its axle, ``sin(theta) = s tan(gamma) tan(psi)``,
    and reaches ``r (1 - cos(theta)) cos(gamma)`` further towards it along the normal
    (:func:`.lead.contact_lead`).  Position, angle and radius of each candidate are those
    of the profile (changes of second order in the yaw).

    Parameters
    ----------
    found : Candidates
        Candidates of the wheel without yaw (side coordinates).
    side : int
        +1 for the left wheel, -1 for the right.
    yaw : float
        rad, wheelset yaw relative to the rail (about the vertical, positive to the left).

    Returns
    -------
    Candidates
        ``gap`` closed by the yaw, ``x_lead`` set.
    """
    lead, closing = contact_lead(found.radius, found.angle, side, yaw)
    return replace(found, gap=found.gap - closing, x_lead=np.asarray(lead, float))


#: rad, default extra search direction: finds a flange millimetres away from the gauge corner
FLANGE_DIRECTION = math.radians(60.0)
#: rad, search direction for the back of the flange against a check rail
CHECK_RAIL_DIRECTION = math.radians(-70.0)
#: m, height of the wheel's inner face added above the flange back's tangent point
INNER_FACE_HEIGHT = 0.06
#: m, lateral distance of the wheel's inner face (back of the flange) from the taping line:
#: EN 13715's S1002, 70 mm (:attr:`.profile_grid.WheelsetSetup.flange_back`)
FLANGE_BACK = 0.070
#: m, radius of the flange back where it meets the inner face: EN 13715's S1002 (as UIC
#: 510-2) defines it as section H, a circle of 20.5 mm centred 49.5 mm from the taping
#: line, tangent to the inner face 70 mm from it (9.519 mm below the taping circle)
FLANGE_BACK_RADIUS = 0.0205


@dataclass(frozen=True, eq=False)
class PreparedRail:
    """One rail section made ready for repeated candidate searches (see :func:`prepare_rail`)."""

    y: np.ndarray  #: m, uniform lateral grid
    z: np.ndarray  #: m, heights on the grid (NaN: no rail)
    slope: np.ndarray  #: dz/dy
    curvature: np.ndarray  #: 1/m, convex positive
    #: per extra direction: (theta, v grid, rail surface w on it, dw/dv, curvature)
    directions: tuple


@dataclass(frozen=True, eq=False)
class PreparedWheel:
    """A wheel (possibly rolled) made ready for repeated searches (:func:`prepare_wheel`)."""

    wheel: WheelGrid  #: the gridded wheel
    y: np.ndarray  #: m, lateral positions of its surface points at zero shift
    z: np.ndarray  #: m, heights of its surface points at zero lift
    s: np.ndarray  #: m, the points' lateral coordinate on the wheel
    surface_z: np.ndarray  #: m, the unrolled wheel's height at ``s`` (for the radius)
    #: per extra direction: (theta, v, lower surface w, s at v, curvature, unrolled height
    #: at v: the rolling radius is ``nominal_radius`` minus it; the point at the rail
    #: point's v, which is the one on the contact normal when the two touch)
    directions: tuple


def prepare_rail(
    rail_z: np.ndarray,
    rail_slope: np.ndarray,
    rail_curvature: np.ndarray,
    y_grid: np.ndarray,
    directions: tuple = (FLANGE_DIRECTION,),
) -> PreparedRail:
    """Precompute a rail section's surface in each extra search direction.

    Parameters
    ----------
    rail_z, rail_slope, rail_curvature : numpy.ndarray
        Heights (m), slopes, curvatures (1/m) on ``y_grid``.
    y_grid : numpy.ndarray
        m, uniform lateral grid.
    directions : tuple
        rad, extra search directions (tilted towards the track centre; negative: towards
        the field side, e.g. -70 deg for the back of the flange against a check rail).

    Returns
    -------
    PreparedRail
    """
    step = float(y_grid[1] - y_grid[0])
    prepared = []
    for theta in directions:
        runs = finite_runs(rail_z)
        if not runs:
            continue
        rotated = [
            rotate_profile(*_with_side_faces(y_grid[run], rail_z[run]), theta) for run in runs
        ]
        low = min(float(np.min(v)) for v, _w in rotated)
        high = max(float(np.max(v)) for v, _w in rotated)
        v_grid = np.arange(low, high + step, step)
        surface = np.full(v_grid.shape, np.nan)
        for v, w in rotated:
            surface = np.fmax(surface, profile_envelope(v, w, v_grid, upper=True))
        slope, second = savgol_derivatives(surface, step, CURVATURE_WINDOW)
        curvature = -second / (1.0 + slope**2) ** 1.5
        prepared.append((theta, v_grid, surface, np.nan_to_num(slope), curvature))
    return PreparedRail(
        y=y_grid, z=rail_z, slope=rail_slope, curvature=rail_curvature, directions=tuple(prepared)
    )


def _with_side_faces(
    y: np.ndarray, z: np.ndarray, depth: float = 0.03
) -> tuple[np.ndarray, np.ndarray]:
    """A rail run with vertical faces ``depth`` deep at both ends (the grid drops them)."""
    return (
        np.concatenate(([y[0]], y, [y[-1]])),
        np.concatenate(([z[0] - depth], z, [z[-1] - depth])),
    )


def flange_back_arc(
    s0: float,
    z0: float,
    step: float,
    flange_back: float = FLANGE_BACK,
    radius: float = FLANGE_BACK_RADIUS,
) -> tuple[np.ndarray, np.ndarray]:
    """The flange back from a profile's first point down to the wheel's inner face.

    A wheel profile file stops short of the inner face (``MBench_S1002_v3.prw`` comments
    out its first point, the vertical tangent at s = -70 mm, and starts at -69.61 mm on a
    78.8 deg slope).  Joined to a vertical face there, the flange back had a corner whose
    curvature (288 1/m on the 1.5 mm filter) made the check-rail patch 0.3 mm wide at
    6 GPa.  EN 13715's S1002 rounds it instead: its section H is a circle of
    :data:`FLANGE_BACK_RADIUS` tangent to the inner face at :data:`FLANGE_BACK` from the
    taping line.  This returns that circle from the first point to the tangent point:
    the circle of ``radius`` tangent to the face ``s = -flange_back`` through ``(s0, z0)``
    (for S1002 exactly section H, since the file's points lie on it).

    Parameters
    ----------
    s0, z0 : float
        m, the profile's first point (flange-back end): lateral coordinate from the taping
        line (negative) and height above the taping circle's lowest point (negative).
    step : float
        m, arc-length step of the points.
    flange_back : float
        m, distance of the inner face from the taping line.
    radius : float
        m, radius of the flange back.

    Returns
    -------
    s, z : numpy.ndarray
        m, points from the tangent point on the face (first) towards ``(s0, z0)``, which
        is not included; empty when the profile already reaches the face, or when no
        circle of ``radius`` tangent to the face passes below the point (then the face
        starts at the profile's first point).
    """
    centre_s = -flange_back + radius
    reach = s0 - centre_s  # negative: the point lies on the face's side of the centre
    if s0 <= -flange_back + 1e-9 or reach >= 0.0:
        return np.zeros(0), np.zeros(0)
    centre_z = z0 + math.sqrt(radius * radius - reach * reach)
    start = math.atan2(z0 - centre_z, reach)  # in (-pi, -pi/2)
    sweep = start + math.pi
    count = max(int(math.ceil(sweep * radius / step)), 1)
    phi = -math.pi + sweep * np.arange(count) / count
    return centre_s + radius * np.cos(phi), centre_z + radius * np.sin(phi)


def prepare_wheel(
    wheel: WheelGrid,
    taping_line: float,
    roll: float = 0.0,
    directions: tuple = (FLANGE_DIRECTION,),
    flange_back: float = FLANGE_BACK,
    back_radius: float = FLANGE_BACK_RADIUS,
) -> PreparedWheel:
    """Precompute a wheel's surface (at a roll angle) in each extra search direction.

    The profile is completed at the back of the flange as EN 13715 draws it: the flange
    back's circle (:func:`flange_back_arc`) down to its vertical tangent on the inner face,
    and the inner face :data:`INNER_FACE_HEIGHT` above it (a check rail touches them).

    Parameters
    ----------
    wheel : WheelGrid
        Gridded wheel.
    taping_line : float
        m, nominal lateral position of the taping line in the rail grid's frame.
    roll : float
        rad, see :func:`wheel_heights_on_grid`.
    directions : tuple
        rad, the same extra directions as the rail's.
    flange_back : float
        m, distance of the wheel's inner face from the taping line (S1002: 70 mm).
    back_radius : float
        m, radius of the flange back at the inner face (S1002: 20.5 mm).

    Returns
    -------
    PreparedWheel
    """
    finite = np.isfinite(wheel.z)
    step = float(wheel.s[1] - wheel.s[0])
    arc_s, arc_h = flange_back_arc(
        float(wheel.s[finite][0]), float(wheel.z[finite][0]), step, flange_back, back_radius
    )
    # unrolled points: the arc, then the profile (s increasing); h is the height above the
    # taping circle's lowest point (gives the rolling radius of a point)
    s_points = np.concatenate((arc_s, wheel.s[finite]))
    h_points = np.concatenate((arc_h, wheel.z[finite]))
    y_points, z_points = _placed(s_points, h_points, wheel.nominal_radius, taping_line, roll)
    # the inner face above the flange back's tangent point, from its top down
    rise = np.arange(INNER_FACE_HEIGHT, 0.0, -step)
    face_s = np.full(rise.shape, s_points[0])
    face_h = h_points[0] + rise
    all_s = np.concatenate((face_s, s_points))
    all_h = np.concatenate((face_h, h_points))
    face_y, face_z = _placed(all_s, all_h, wheel.nominal_radius, taping_line, roll)
    prepared = []
    for theta in directions:
        v, w = rotate_profile(face_y, face_z, theta)
        v_grid = np.arange(float(np.min(v)), float(np.max(v)), step)
        # the rotated profile folds over itself (flange, inner face): s is that of the
        # point forming the lower envelope, not an interpolation across the folds
        lower, s_at = lower_envelope(v, w, all_s, v_grid)
        _lower, h_at = lower_envelope(v, w, all_h, v_grid)
        slope, second = savgol_derivatives(lower, step, CURVATURE_WINDOW)
        prepared.append((theta, v_grid, lower, s_at, second / (1.0 + slope**2) ** 1.5, h_at))
    return PreparedWheel(
        wheel=wheel,
        y=y_points,
        z=z_points,
        s=s_points,
        surface_z=h_points,
        directions=tuple(prepared),
    )


def _placed(
    s: np.ndarray, h: np.ndarray, nominal_radius: float, taping_line: float, roll: float
) -> tuple[np.ndarray, np.ndarray]:
    """Wheel points (s, height) in the track frame at zero shift and lift (as
    :func:`.profile_grid.wheel_points`)."""
    y, z = taping_line + s, h - nominal_radius
    if roll:
        c, sn = math.cos(roll), math.sin(roll)
        y, z = c * y - sn * z, sn * y + c * z
    return y, z + nominal_radius


def _vertical_minima(
    rail: PreparedRail, wheel: PreparedWheel, shifts: np.ndarray, lift: float, prominence: float
) -> list[list]:
    y_grid = rail.y
    step = float(y_grid[1] - y_grid[0])
    local = y_grid[None, :] - shifts[:, None]
    inside = (local >= wheel.y[0]) & (local <= wheel.y[-1])
    heights = np.where(inside, np.interp(local, wheel.y, wheel.z) + lift, np.nan)
    gap = heights - rail.z[None, :]
    wheel_s = wheel.wheel.s
    wheel_step = float(wheel_s[1] - wheel_s[0])
    results = []
    for row, minima in enumerate(batch_local_minima(gap, prominence)):
        found = []
        shift = float(shifts[row])
        for i in minima:
            offset, value = refine_minimum(gap[row], i)
            y = float(y_grid[i] + offset * step)
            s = float(np.interp(y - shift, wheel.y, wheel.s))
            k = min(max(int(round((s - wheel_s[0]) / wheel_step)), 0), len(wheel_s) - 1)
            # slopes at the refined point (the grid point's would step the angle by up to
            # 2.5 deg per grid step on the flange root)
            wheel_slope = float(np.interp(s, wheel_s, wheel.wheel.slope))
            rail_slope = float(np.interp(y, y_grid, rail.slope))
            rail_slope = rail_slope if math.isfinite(rail_slope) else 0.0
            slope = 0.5 * (rail_slope + wheel_slope) if math.isfinite(wheel_slope) else rail_slope
            angle = math.atan(slope)
            found.append(
                (
                    y,
                    float(np.interp(y, y_grid, rail.z)),
                    s,
                    value * math.cos(angle),
                    angle,
                    0.0,
                    float(rail.curvature[i]),
                    float(wheel.wheel.curvature[k]),
                    float(np.interp(s, wheel.s, wheel.surface_z)),
                )
            )
        results.append(found)
    return results


def _directional_minima(
    rail: PreparedRail, wheel: PreparedWheel, shifts: np.ndarray, lift: float, prominence: float
) -> list[list]:
    results: list[list] = [[] for _ in range(len(shifts))]
    for (theta, v_grid, rail_w, rail_dw, rail_k), wheel_frame in zip(
        rail.directions, wheel.directions
    ):
        _t, wheel_v, wheel_w, wheel_s, wheel_k, wheel_h = wheel_frame
        c, s = math.cos(theta), math.sin(theta)
        dv = shifts * c + lift * s
        dw = -shifts * s + lift * c
        local = v_grid[None, :] - dv[:, None]
        inside = (local >= wheel_v[0]) & (local <= wheel_v[-1])
        surface = np.where(inside, np.interp(local, wheel_v, wheel_w) + dw[:, None], np.nan)
        gap = surface - rail_w[None, :]
        step = float(v_grid[1] - v_grid[0])
        limit = math.radians(30.0)
        rail_w_filled = np.nan_to_num(rail_w)
        for row, minima in enumerate(batch_local_minima(gap, prominence)):
            for i in minima:
                if abs(math.atan(float(rail_dw[i]))) >= limit:
                    continue
                offset, value = refine_minimum(gap[row], i)
                v = float(v_grid[i] + offset * step)
                angle = theta + math.atan(float(np.interp(v, v_grid, rail_dw)))
                w_rail = float(np.interp(v, v_grid, rail_w_filled))
                results[row].append(
                    (
                        c * v - s * w_rail,
                        s * v + c * w_rail,
                        float(np.interp(v - dv[row], wheel_v, wheel_s)),
                        value * math.cos(angle - theta),
                        angle,
                        theta,
                        float(rail_k[i]),
                        float(np.interp(v - dv[row], wheel_v, wheel_k)),
                        float(np.interp(v - dv[row], wheel_v, wheel_h)),
                    )
                )
    return results


def _candidates_from(
    raw: list, rail: PreparedRail, wheel: PreparedWheel, max_candidates: int, max_gap: float
) -> Candidates:
    unique: list = []
    for item in sorted(raw, key=lambda c: abs(c[4] - c[5])):
        if all(abs(item[0] - other[0]) > 1.5e-3 for other in unique):
            unique.append(item)
    if unique:
        lowest = min(item[3] for item in unique)
        unique = [item for item in unique if item[3] - lowest <= max_gap]
    unique = sorted(unique, key=lambda c: c[3])[:max_candidates]
    grid = wheel.wheel
    columns = []
    for y, z, s, value, angle, _theta, rail_curvature, wheel_curvature, height in unique:
        # the height of the wheel point that forms the contact (on the inner face, s alone
        # does not tell it)
        radius = grid.nominal_radius - height
        columns.append((value, y, z, s, angle, radius, rail_curvature, wheel_curvature))
    table = np.array(columns, dtype=float).reshape(-1, 8)
    return Candidates(*(table[:, k].copy() for k in range(8)))


def search_candidates_batch(
    rail: PreparedRail,
    wheel: PreparedWheel,
    shifts,
    lift: float = 0.0,
    max_candidates: int = 3,
    prominence: float = 5e-5,
    max_gap: float = 0.01,
) -> list:
    """:func:`search_candidates` for many lateral shifts at once (vectorised gaps).

    Parameters
    ----------
    rail, wheel : PreparedRail, PreparedWheel
        Prepared section and wheel.
    shifts : array_like
        m, lateral shifts.
    lift, max_candidates, prominence, max_gap
        See :func:`find_candidates`.

    Returns
    -------
    list of Candidates
        One per shift.
    """
    shifts = np.atleast_1d(np.asarray(shifts, float))
    vertical = _vertical_minima(rail, wheel, shifts, lift, prominence)
    directional = _directional_minima(rail, wheel, shifts, lift, prominence)
    return [
        _candidates_from(a + b, rail, wheel, max_candidates, max_gap)
        for a, b in zip(vertical, directional)
    ]


def search_candidates(
    rail: PreparedRail,
    wheel: PreparedWheel,
    shift: float = 0.0,
    lift: float = 0.0,
    max_candidates: int = 3,
    prominence: float = 5e-5,
    max_gap: float = 0.01,
) -> Candidates:
    """Candidate contact points of a prepared wheel on a prepared rail section.

    Parameters
    ----------
    rail : PreparedRail
        From :func:`prepare_rail`.
    wheel : PreparedWheel
        From :func:`prepare_wheel` (its roll is fixed there).
    shift, lift : float
        m, lateral shift towards the field side and lift of the wheel.
    max_candidates, prominence, max_gap
        See :func:`find_candidates`.

    Returns
    -------
    Candidates
    """
    return search_candidates_batch(rail, wheel, [shift], lift, max_candidates, prominence, max_gap)[
        0
    ]


def find_candidates(
    rail_z: np.ndarray,
    rail_slope: np.ndarray,
    rail_curvature: np.ndarray,
    y_grid: np.ndarray,
    wheel: WheelGrid,
    taping_line: float,
    shift: float = 0.0,
    lift: float = 0.0,
    roll: float = 0.0,
    max_candidates: int = 3,
    prominence: float = 5e-5,
    max_gap: float = 0.01,
    directions: tuple = (FLANGE_DIRECTION,),
    yaw: float = 0.0,
    side: int = 1,
) -> Candidates:
    """Candidate contact points of a wheel on one rail section, smallest normal gap first.

    The gap is searched vertically (tread, flange root, any point near touching) and along
    each of ``directions`` (angles tilted towards the track centre: 60 deg finds a flange
    that is still millimetres away from the gauge corner, where the vertical gap has no
    minimum; a negative angle such as -70 deg finds the back of the flange against a check
    rail).  A point found by several searches is kept once, from the search whose direction
    is closest to its contact angle.  For many positions on one section use
    :func:`prepare_rail`, :func:`prepare_wheel` and :func:`search_candidates`.

    Parameters
    ----------
    rail_z, rail_slope, rail_curvature : numpy.ndarray
        Rail surface height (m), slope (-), curvature (1/m) on ``y_grid``.
    y_grid : numpy.ndarray
        m, uniform lateral grid.
    wheel : WheelGrid
        Gridded wheel.
    taping_line, shift, lift, roll : float
        Wheel position, see :func:`wheel_heights_on_grid`.
    max_candidates : int
        Most candidates returned.
    prominence : float
        m, rise of the gap between two minima for them to count as separate regions
        (default 0.05 mm).
    max_gap : float
        m, candidates whose normal gap exceeds the smallest one's by more are dropped.
    directions : tuple
        rad, extra search directions.
    yaw : float
        rad, wheelset yaw relative to the rail (:func:`yawed`; 0: none).
    side : int
        +1 for the left wheel, -1 for the right (the sign of the lead).

    Returns
    -------
    Candidates
        Arrays of length <= ``max_candidates``; ``gap`` is the normal gap.
    """
    rail = prepare_rail(rail_z, rail_slope, rail_curvature, y_grid, directions)
    prepared = prepare_wheel(wheel, taping_line, roll, directions)
    found = search_candidates(rail, prepared, shift, lift, max_candidates, prominence, max_gap)
    return _with_yaw(found, side, yaw)


def _with_yaw(found: Candidates, side: float, yaw: float) -> Candidates:
    """:func:`yawed` candidates, re-sorted by gap (unchanged without yaw)."""
    if yaw == 0.0:
        return found
    found = yawed(found, int(side), yaw)
    order = np.argsort(found.gap, kind="stable")
    return Candidates(**{k: getattr(found, k)[order] for k in _CANDIDATE_FIELDS})


def _vertical_gap(found: Candidates) -> float:
    return float(found.gap[0] / math.cos(found.angle[0]))


def _solve_roll(
    gaps: Any, lever: float, evaluations: int, tolerance: float, start: float = 0.0
) -> float:
    """Roll at which the two wheels' vertical gaps are equal (``gaps(roll)`` -> both gaps).

    The difference increases with the roll (it lifts the left wheel and lowers the right
    one).  From ``start`` a first step with the tread's slope ``2 lever``, then steps
    doubling until the difference changes sign, then Brent's method on the bracket.
    """

    def difference(roll: float) -> float:
        left, right = gaps(roll)
        return left - right

    low, f_low = start, difference(start)
    if abs(f_low) <= tolerance:
        return start
    step = -f_low / (2.0 * lever)
    high, f_high = low + step, difference(low + step)
    used = 2
    while f_high * f_low > 0.0 and abs(f_high) > tolerance:
        if used >= evaluations:
            raise RuntimeError("solve_wheelset: no roll found at which the wheel gaps agree")
        step *= 2.0
        low, f_low = high, f_high
        high, f_high = low + step, difference(low + step)
        used += 1
    if abs(f_high) <= tolerance:
        return high
    return float(
        brentq(difference, min(low, high), max(low, high), xtol=1e-12, maxiter=evaluations)
    )


@dataclass(frozen=True, eq=False)
class WheelsetContact:
    """Rigid-contact wheelset geometry over lateral displacements (arrays over y)."""

    y: np.ndarray  #: m, wheelset lateral displacement, positive to the left
    roll: np.ndarray  #: rad, wheelset roll, left side up positive
    lift: np.ndarray  #: m, height of the wheelset centre above its nominal position
    radius_left: np.ndarray  #: m, rolling radius of the left wheel's contact point
    radius_right: np.ndarray  #: m, rolling radius of the right wheel's contact point
    angle_left: np.ndarray  #: rad, contact angle of the left wheel (towards centre +)
    angle_right: np.ndarray  #: rad, contact angle of the right wheel
    s_left: np.ndarray  #: m, contact point on the left wheel from its taping line
    s_right: np.ndarray  #: m, contact point on the right wheel
    y_rail_left: np.ndarray  #: m, contact point on the left rail (side coordinates)
    y_rail_right: np.ndarray  #: m, contact point on the right rail (side coordinates)
    x_lead_left: np.ndarray  #: m, left wheel's contact point ahead of the axle (yaw)
    x_lead_right: np.ndarray  #: m, right wheel's contact point ahead of the axle (yaw)
    candidates_left: tuple  #: Candidates of the left wheel at each y
    candidates_right: tuple  #: Candidates of the right wheel at each y

    @property
    def delta_r(self) -> np.ndarray:
        """m, rolling-radius difference r_left - r_right (EN 15302's Delta r)."""
        return self.radius_left - self.radius_right


def solve_wheelset(
    y_values: np.ndarray,
    wheel: WheelGrid,
    left_rail: RailRow,
    right_rail: RailRow,
    setup: WheelsetSetup,
    iterations: int = 60,
    max_candidates: int = 3,
    max_gap: float = 0.005,
    tolerance: float = 1e-10,
    yaw: float = 0.0,
) -> WheelsetContact:
    """Roll and height of a rigid wheelset touching both rails, for each lateral displacement.

    Parameters
    ----------
    y_values : numpy.ndarray
        m, lateral displacements (positive to the left).
    wheel : WheelGrid
        Gridded wheel (both wheels of the wheelset are this profile, mirrored).
    left_rail, right_rail : tuple
        ``(heights, SurfaceDerivatives row slope, curvature, y_grid)`` of one section each,
        in side coordinates (see :func:`rail_row`).
    setup : WheelsetSetup
        Dimensions.
    iterations : int
        Most evaluations of the two vertical gaps per lateral position in the roll search.
    max_candidates : int
        Candidates kept per wheel.
    max_gap : float
        m, candidates with a larger gap (at equilibrium) are dropped.
    tolerance : float
        m, the roll is solved until the two wheels' vertical gaps differ by less.
    yaw : float
        rad, wheelset yaw relative to the rails: each wheel's contacts lead or trail and
        reach nearer the rail (:func:`yawed`).

    Returns
    -------
    WheelsetContact

    Notes
    -----
    The roll makes the two wheels' vertical gaps equal (then the lift closes both).  The
    difference grows with the roll by about twice the half track width while both wheels run
    on their treads, but far less once one flange is in contact (the roll also moves that
    wheel sideways, against the flange); a fixed-point step with the tread's slope then
    converges by a factor of only ~0.85 per step and left the wheelset interpenetrating the
    rail by up to 0.13 mm after 8 steps.  :func:`_solve_roll` brackets the root and
    refines it with Brent's method instead.
    """
    taping = setup.taping_line
    lever = taping
    results: dict[str, list[Any]] = {
        key: []
        for key in (
            "roll",
            "lift",
            "radius_left",
            "radius_right",
            "angle_left",
            "angle_right",
            "s_left",
            "s_right",
            "y_rail_left",
            "y_rail_right",
            "x_lead_left",
            "x_lead_right",
            "candidates_left",
            "candidates_right",
        )
    }
    rails = [
        (prepare_rail(*rail, directions=()), prepare_rail(*rail), side)
        for rail, side in ((left_rail, 1.0), (right_rail, -1.0))
    ]
    roll = 0.0
    for y in np.asarray(y_values, float):

        def gaps(roll: float, y: float = y) -> tuple[float, float]:
            left, right = (
                _vertical_gap(
                    _with_yaw(
                        search_candidates(
                            vertical,
                            prepare_wheel(wheel, taping, side * roll, ()),
                            shift=side * y,
                            max_candidates=1,
                            max_gap=1.0,
                        ),
                        side,
                        yaw,
                    )  # fmt: skip
                )
                for vertical, _full, side in rails
            )
            return left, right

        # the previous position's roll starts the search (the roll changes little per step)
        roll = _solve_roll(gaps, lever, iterations, tolerance, start=roll)
        gap_left, gap_right = gaps(roll)
        lift = -0.5 * (gap_left + gap_right)
        left, right = (
            _with_yaw(
                search_candidates(
                    full,
                    prepare_wheel(wheel, taping, side * roll),
                    shift=side * y,
                    lift=lift,
                    max_candidates=max_candidates,
                    max_gap=max_gap,
                ),
                side,
                yaw,
            )  # fmt: skip
            for _vertical, full, side in rails
        )
        results["roll"].append(roll)
        results["lift"].append(lift)
        for side, found in (("left", left), ("right", right)):
            results[f"radius_{side}"].append(found.radius[0])
            results[f"angle_{side}"].append(found.angle[0])
            results[f"s_{side}"].append(found.s_wheel[0])
            results[f"y_rail_{side}"].append(found.y_rail[0])
            results[f"x_lead_{side}"].append(0.0 if found.x_lead is None else found.x_lead[0])
            results[f"candidates_{side}"].append(found)

    def column(key: str) -> np.ndarray:
        return np.asarray(results[key])

    return WheelsetContact(
        y=np.asarray(y_values, float),
        roll=column("roll"),
        lift=column("lift"),
        radius_left=column("radius_left"),
        radius_right=column("radius_right"),
        angle_left=column("angle_left"),
        angle_right=column("angle_right"),
        s_left=column("s_left"),
        s_right=column("s_right"),
        y_rail_left=column("y_rail_left"),
        y_rail_right=column("y_rail_right"),
        x_lead_left=column("x_lead_left"),
        x_lead_right=column("x_lead_right"),
        candidates_left=tuple(results["candidates_left"]),
        candidates_right=tuple(results["candidates_right"]),
    )


def rail_row(sections: SectionGrid, derivatives: SurfaceDerivatives, index: int = 0) -> RailRow:
    """The ``(heights, slope, curvature, y_grid)`` tuple of one section for the solvers.

    Parameters
    ----------
    sections : SectionGrid
        Gridded rail sections.
    derivatives : SurfaceDerivatives
        From :func:`surface_derivatives`.
    index : int
        Which section.

    Returns
    -------
    tuple of numpy.ndarray
        ``(heights, slope, curvature, y_grid)``: rail heights (m), slope dz/dy (-) and
        curvature (1/m) of section ``index`` on the lateral grid ``y_grid`` (m).
    """
    return (sections.z[index], derivatives.slope[index], derivatives.curvature[index], sections.y)
