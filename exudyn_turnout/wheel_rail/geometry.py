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
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.optimize import brentq
from scipy.signal import savgol_filter

from exudyn_turnout.wheel_rail.profiles import Profile
from exudyn_turnout.wheel_rail.sections import SectionGrid, _monotone_runs, surface_on_grid

__all__ = [
    "WheelsetSetup",
    "WheelGrid",
    "SurfaceDerivatives",
    "Candidates",
    "grid_wheel",
    "surface_derivatives",
    "find_candidates",
    "FLANGE_DIRECTION",
    "CHECK_RAIL_DIRECTION",
    "PreparedRail",
    "PreparedWheel",
    "prepare_rail",
    "prepare_wheel",
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

#: One rail section for the contact solvers: heights z (m), slope dz/dy (-), curvature
#: (1/m), all on the lateral grid y (m), in side coordinates (see :func:`rail_row`).
RailRow = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]


@dataclass(frozen=True)
class WheelsetSetup:
    """Track and wheelset dimensions that place the profiles (SI)."""

    gauge: float = 1.435  #: m, track gauge at the gauge points (standard gauge)
    back_to_back: float = 1.360  #: m, wheelset back-to-back distance (EN 13260 nominal)
    #: m, lateral distance from the back of the flange to the taping line (S1002, EN 13715)
    flange_back: float = 0.070
    #: tangent of the rail inclination still to apply to the rail profile (1/40 standard)
    inclination: float = 1.0 / 40.0
    gauge_depth: float = 0.014  #: m, gauge point below the top of rail (EN 15302)
    nominal_radius: float = 0.46  #: m, wheel radius at the taping line (Manchester)
    grid_step: float = 1e-4  #: m, lateral grid step

    @property
    def taping_line(self) -> float:
        """m, nominal distance of the taping line from the track centre."""
        return 0.5 * self.back_to_back + self.flange_back


@dataclass(frozen=True, eq=False)
class WheelGrid:
    """A wheel profile's lower surface on a uniform grid of its own lateral coordinate."""

    s: np.ndarray  #: m, lateral coordinate from the taping line, towards the field side
    z: np.ndarray  #: m, surface height above the taping circle's lowest point (NaN: none)
    slope: np.ndarray  #: dz/ds (-)
    curvature: np.ndarray  #: 1/m, lateral curvature, positive convex towards the rail
    nominal_radius: float  #: m, radius at s = 0


@dataclass(frozen=True, eq=False)
class SurfaceDerivatives:
    """Slope and curvature of gridded rail surfaces (same shape as the heights)."""

    slope: np.ndarray  #: dz/dy (-)
    curvature: np.ndarray  #: 1/m, positive convex (crown)


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


def _derivatives(z: np.ndarray, step: float, window: float) -> tuple[np.ndarray, np.ndarray]:
    points = max(5, int(round(window / step)) | 1)
    filled = np.where(np.isfinite(z), z, np.nan)
    finite = np.isfinite(filled)
    slope = np.full(z.shape, np.nan)
    second = np.full(z.shape, np.nan)
    if finite.sum() <= points:
        return slope, second
    idx = np.arange(z.shape[-1])
    padded = np.interp(idx, idx[finite], filled[finite])
    slope = savgol_filter(padded, points, 3, deriv=1, delta=step)
    second = savgol_filter(padded, points, 3, deriv=2, delta=step)
    slope[~finite] = np.nan
    second[~finite] = np.nan
    return slope, second


def grid_wheel(
    profile: Profile, step: float = 1e-4, nominal_radius: float = 0.46, window: float = 1.5e-3
) -> WheelGrid:
    """Grid a wheel profile and compute its slope and lateral curvature.

    Parameters
    ----------
    profile : Profile
        Wheel profile (kind "wheel").
    step : float
        m, grid step (the rail grid must use the same).
    nominal_radius : float
        m, radius at the taping line.
    window : float
        m, Savitzky-Golay window for the derivatives.

    Returns
    -------
    WheelGrid
    """
    s = np.round(np.min(profile.y) / step) * step + step * np.arange(
        int((np.max(profile.y) - np.min(profile.y)) / step) + 1
    )
    z = surface_on_grid(profile, s)
    slope, second = _derivatives(z, step, window)
    curvature = second / (1.0 + slope**2) ** 1.5
    return WheelGrid(s=s, z=z, slope=slope, curvature=curvature, nominal_radius=nominal_radius)


def surface_derivatives(sections: SectionGrid, window: float = 1.5e-3) -> SurfaceDerivatives:
    """Slopes and curvatures of every gridded rail section.

    Parameters
    ----------
    sections : SectionGrid
        Gridded rail sections.
    window : float
        m, Savitzky-Golay window.

    Returns
    -------
    SurfaceDerivatives
        Arrays shaped like ``sections.z``.
    """
    step = float(sections.y[1] - sections.y[0])
    slopes, curvatures = [], []
    for row in np.atleast_2d(sections.z):
        slope, second = _derivatives(row, step, window)
        slopes.append(slope)
        curvatures.append(-second / (1.0 + slope**2) ** 1.5)
    return SurfaceDerivatives(slope=np.array(slopes), curvature=np.array(curvatures))


def wheel_heights_on_grid(
    wheel: WheelGrid,
    y_grid: np.ndarray,
    taping_line: float,
    shift: float = 0.0,
    lift: float = 0.0,
    roll: float = 0.0,
) -> tuple[np.ndarray, np.ndarray]:
    """Wheel surface height and its lateral coordinate at every rail grid point.

    Parameters
    ----------
    wheel : WheelGrid
        Gridded wheel.
    y_grid : numpy.ndarray
        m, rail grid (side coordinates, or any frame in which the wheel's taping line is at
        ``taping_line + shift``).
    taping_line : float
        m, nominal lateral position of the taping line in the grid's frame.
    shift : float
        m, lateral displacement of the wheel towards the field side.
    lift : float
        m, height of the taping circle's lowest point above z = 0.
    roll : float
        rad, rotation about the wheelset centre, which lies ``taping_line`` towards the track
        centre and ``nominal_radius`` above the taping circle's lowest point; positive lifts
        the field side of this wheel.

    Returns
    -------
    heights : numpy.ndarray
        m, wheel surface height on the grid (NaN outside the wheel).
    s_wheel : numpy.ndarray
        m, wheel lateral coordinate at each grid point.
    """
    y_points, z_points = _wheel_points(wheel, taping_line, shift, lift, roll)
    finite = np.isfinite(z_points)
    inside = (y_grid >= y_points[finite][0]) & (y_grid <= y_points[finite][-1])
    heights = np.full(y_grid.shape, np.nan)
    heights[inside] = np.interp(y_grid[inside], y_points[finite], z_points[finite])
    s_wheel = np.interp(y_grid, y_points[finite], wheel.s[finite])
    return heights, s_wheel


def _local_minima(gap: np.ndarray, prominence: float) -> list[int]:
    """Indices of local minima of ``gap`` that lie in separate regions (lowest first)."""
    return _batch_local_minima(gap[None, :], prominence)[0]


def _merge_minima(g: np.ndarray, minima: list, prominence: float) -> list[int]:
    minima = sorted(minima, key=lambda i: g[i])
    kept: list[int] = []
    for i in minima:
        separate = True
        for j in kept:
            lo, hi = (i, j) if i < j else (j, i)
            if np.max(g[lo : hi + 1]) - g[i] < prominence:
                separate = False
                break
        if separate:
            kept.append(i)
    return kept


def _batch_local_minima(gap: np.ndarray, prominence: float) -> list[list[int]]:
    """Separate local minima of every row of a 2-D gap array (see :func:`_local_minima`)."""
    g = np.where(np.isfinite(gap), gap, np.inf)
    interior = (g[:, 1:-1] <= g[:, :-2]) & (g[:, 1:-1] < g[:, 2:]) & np.isfinite(g[:, 1:-1])
    rows, cols = np.nonzero(interior)
    result: list[list[int]] = [[] for _ in range(gap.shape[0])]
    for row, col in zip(rows.tolist(), (cols + 1).tolist()):
        result[row].append(col)
    return [
        (_merge_minima(g[r], found, prominence) if len(found) > 1 else found)
        for r, found in enumerate(result)
    ]


def _refine(gap: np.ndarray, i: int) -> tuple[float, float]:
    """Sub-grid offset (in steps) and value of a minimum by a parabola through 3 points."""
    left, mid, right = gap[i - 1], gap[i], gap[i + 1]
    if not (np.isfinite(left) and np.isfinite(right)):
        return 0.0, float(mid)  # at the edge of a rail: no parabola
    curvature = left - 2.0 * mid + right
    offset = 0.5 * (left - right) / curvature if curvature > 0 else 0.0
    offset = min(max(offset, -0.5), 0.5)
    return offset, mid - 0.25 * (left - right) * offset


def _finite_runs(values: np.ndarray) -> list[slice]:
    finite = np.concatenate(([False], np.isfinite(values), [False]))
    edges = np.flatnonzero(finite[1:] != finite[:-1])
    return [slice(int(a), int(b)) for a, b in zip(edges[::2], edges[1::2]) if b - a >= 3]


def _rotate(y: np.ndarray, z: np.ndarray, theta: float) -> tuple[np.ndarray, np.ndarray]:
    c, s = math.cos(theta), math.sin(theta)
    return c * y + s * z, -s * y + c * z


def _envelope(v: np.ndarray, w: np.ndarray, grid: np.ndarray, upper: bool) -> np.ndarray:
    profile = Profile(y=v, z=w, kind="rail" if upper else "wheel", source="")
    return surface_on_grid(profile, grid)


#: rad, default extra search direction: finds a flange millimetres away from the gauge corner
FLANGE_DIRECTION = math.radians(60.0)
#: rad, search direction for the back of the flange against a check rail
CHECK_RAIL_DIRECTION = math.radians(-70.0)
#: m, height of the wheel's inner face added above the profile's first (flange back) point
INNER_FACE_HEIGHT = 0.06
#: m, Savitzky-Golay window for profile slopes and curvatures
CURVATURE_WINDOW = 1.5e-3


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
    #: per extra direction: (theta, v, lower surface w, s at v, curvature)
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
        runs = _finite_runs(rail_z)
        if not runs:
            continue
        rotated = [_rotate(*_with_side_faces(y_grid[run], rail_z[run]), theta) for run in runs]
        low = min(float(np.min(v)) for v, _w in rotated)
        high = max(float(np.max(v)) for v, _w in rotated)
        v_grid = np.arange(low, high + step, step)
        surface = np.full(v_grid.shape, np.nan)
        for v, w in rotated:
            surface = np.fmax(surface, _envelope(v, w, v_grid, upper=True))
        slope, second = _derivatives(surface, step, CURVATURE_WINDOW)
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


def prepare_wheel(
    wheel: WheelGrid, taping_line: float, roll: float = 0.0, directions: tuple = (FLANGE_DIRECTION,)
) -> PreparedWheel:
    """Precompute a wheel's surface (at a roll angle) in each extra search direction.

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

    Returns
    -------
    PreparedWheel
    """
    y_points, z_points = _wheel_points(wheel, taping_line, 0.0, 0.0, roll)
    finite = np.isfinite(z_points)
    y_points, z_points, s_points = y_points[finite], z_points[finite], wheel.s[finite]
    step = float(wheel.s[1] - wheel.s[0])
    # the back of the flange continues as the wheel's vertical inner face (EN 13715), which
    # a profile file stops short of; a check rail touches it there
    rise = np.arange(step, INNER_FACE_HEIGHT + step, step)
    c, s = math.cos(roll), math.sin(roll)
    face_y = np.concatenate((y_points[:1] - s * rise, y_points))
    face_z = np.concatenate((z_points[:1] + c * rise, z_points))
    face_s = np.concatenate((np.full(rise.shape, s_points[0]), s_points))
    prepared = []
    for theta in directions:
        v, w = _rotate(face_y, face_z, theta)
        v_grid = np.arange(float(np.min(v)), float(np.max(v)), step)
        # the rotated profile folds over itself (flange, inner face): s is that of the
        # point forming the lower envelope, not an interpolation across the folds
        lower, s_at = _lower_envelope(v, w, face_s, v_grid)
        slope, second = _derivatives(lower, step, CURVATURE_WINDOW)
        prepared.append((theta, v_grid, lower, s_at, second / (1.0 + slope**2) ** 1.5))
    return PreparedWheel(
        wheel=wheel,
        y=y_points,
        z=z_points,
        s=s_points,
        surface_z=wheel.z[finite],
        directions=tuple(prepared),
    )


def _lower_envelope(
    v: np.ndarray, w: np.ndarray, attribute: np.ndarray, grid: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Lower envelope of the polyline (v, w) on ``grid`` and ``attribute`` of the point forming it.

    The polyline may be multi-valued in v (a rotated flange); each monotone run is
    interpolated on its own and the lowest run wins at every grid point, so the envelope
    equals :func:`.sections.surface_on_grid`'s and the attribute (e.g. the wheel coordinate
    s) belongs to the same point of the profile.  NaN where no run covers the grid point.
    """
    height = np.full(grid.shape, np.inf)
    value = np.full(grid.shape, np.nan)
    for run in _monotone_runs(v):
        vr, wr, ar = v[run], w[run], attribute[run]
        if vr[-1] < vr[0]:
            vr, wr, ar = vr[::-1], wr[::-1], ar[::-1]
        if vr[-1] <= vr[0]:
            continue
        inside = np.flatnonzero((grid >= vr[0]) & (grid <= vr[-1]))
        w_run = np.interp(grid[inside], vr, wr)
        lower = w_run < height[inside]
        height[inside[lower]] = w_run[lower]
        value[inside[lower]] = np.interp(grid[inside[lower]], vr, ar)
    height[np.isinf(height)] = np.nan
    return height, value


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
    for row, minima in enumerate(_batch_local_minima(gap, prominence)):
        found = []
        shift = float(shifts[row])
        for i in minima:
            offset, value = _refine(gap[row], i)
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
                )
            )
        results.append(found)
    return results


def _directional_minima(
    rail: PreparedRail, wheel: PreparedWheel, shifts: np.ndarray, lift: float, prominence: float
) -> list[list]:
    results: list[list] = [[] for _ in range(len(shifts))]
    for (theta, v_grid, rail_w, rail_dw, rail_k), (_t, wheel_v, wheel_w, wheel_s, wheel_k) in zip(
        rail.directions, wheel.directions
    ):
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
        for row, minima in enumerate(_batch_local_minima(gap, prominence)):
            for i in minima:
                if abs(math.atan(float(rail_dw[i]))) >= limit:
                    continue
                offset, value = _refine(gap[row], i)
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
    for y, z, s, value, angle, _theta, rail_curvature, wheel_curvature in unique:
        radius = grid.nominal_radius - float(np.interp(s, wheel.s, wheel.surface_z))
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

    Returns
    -------
    Candidates
        Arrays of length <= ``max_candidates``; ``gap`` is the normal gap.
    """
    rail = prepare_rail(rail_z, rail_slope, rail_curvature, y_grid, directions)
    prepared = prepare_wheel(wheel, taping_line, roll, directions)
    return search_candidates(rail, prepared, shift, lift, max_candidates, prominence, max_gap)


def _wheel_points(
    wheel: WheelGrid, taping_line: float, shift: float, lift: float, roll: float
) -> tuple[np.ndarray, np.ndarray]:
    r0 = wheel.nominal_radius
    y_points = taping_line + wheel.s
    z_points = wheel.z - r0
    if roll:
        c, s = math.cos(roll), math.sin(roll)
        y_points, z_points = c * y_points - s * z_points, s * y_points + c * z_points
    return y_points + shift, z_points + r0 + lift


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
                    search_candidates(
                        vertical,
                        prepare_wheel(wheel, taping, side * roll, ()),
                        shift=side * y,
                        max_candidates=1,
                        max_gap=1.0,
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
            search_candidates(
                full,
                prepare_wheel(wheel, taping, side * roll),
                shift=side * y,
                lift=lift,
                max_candidates=max_candidates,
                max_gap=max_gap,
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


def equivalent_conicity(
    y: np.ndarray, delta_r: np.ndarray, amplitude: float, samples: int = 2000
) -> float:
    """Equivalent conicity by EN 15302's linear regression of the Delta r function.

    The wheelset moves sinusoidally, ``y = amplitude sin(theta)``, sampled uniformly in time
    over one period; the regression line of Delta r on y through the origin has slope
    ``2 gamma_e`` (EN 15302:2008+A1:2010, Annex C; for a sinusoid this is the first-harmonic
    (describing-function) linearisation).

    Parameters
    ----------
    y : numpy.ndarray
        m, lateral displacements where Delta r is known (increasing, covering +-amplitude).
    delta_r : numpy.ndarray
        m, rolling-radius difference r_left - r_right at ``y``.
    amplitude : float
        m, amplitude of the wheelset's lateral motion (3 mm for EN 15302's reference value).
    samples : int
        Samples over one period.

    Returns
    -------
    float
        Equivalent conicity gamma_e (-).

    Notes
    -----
    The regression line passes through the origin, so ``delta_r`` must be odd in ``y``
    (symmetric wheelset and track).  Where the amplitude just reaches a jump of Delta r
    (contact moving to the flange root) the regression overestimates the conicity of the
    kinematic motion: on EN 15302's reference function E2 (Annex E) it gives 0.090 at 3 mm
    against the reference 0.058, and on E4 0.372 at 2 mm against 0.293, outside the
    standard's tolerance band.  :func:`equivalent_conicity_klingel` reproduces all nine
    reference functions; for S1002 on UIC60 1:40 (1435 / 1360 mm) the two agree to 0.002
    at 3 mm.
    """
    theta = 2.0 * np.pi * (np.arange(samples) + 0.5) / samples
    motion = amplitude * np.sin(theta)
    dr = np.interp(motion, y, delta_r)
    return float(np.sum(dr * motion) / (2.0 * np.sum(motion * motion)))


def equivalent_conicity_klingel(
    y: np.ndarray, delta_r: np.ndarray, amplitude: float, samples: int = 2000, refine: int = 20
) -> float:
    """Equivalent conicity from the wavelength of the kinematic motion (EN 15302, Annex B).

    The wheelset's kinematic (Klingel) motion obeys ``y'' = -Delta r(y) / (2 e r0)``; its
    energy integral gives the yaw angle ``psi(y)^2 = F(y) / (e r0)`` with
    ``F(y) = integral from y to y_max of Delta r``, and the wavelength is
    ``lambda = 2 integral from y_min to y_max of dy / psi``.  The equivalent conicity is the
    cone with Klingel's wavelength ``2 pi sqrt(e r0 / gamma_e)``, so
    ``gamma_e = (pi / integral dy / sqrt(F))^2``, independent of ``e`` and ``r0``.  The
    turning points are ``y_min, y_max = c -+ amplitude``, the centre ``c`` chosen so that
    the integral of Delta r between them vanishes (``c = 0`` for an odd Delta r; not zero
    for unequal wheel radii).  The substitution ``y = c - amplitude cos(theta)`` removes the
    square-root singularities at the turning points.

    Parameters
    ----------
    y : numpy.ndarray
        Lateral displacements where Delta r is known (increasing; any length unit).
    delta_r : numpy.ndarray
        Rolling-radius difference r_left - r_right at ``y`` (same unit), increasing through
        zero over the motion.
    amplitude : float
        Half the peak-to-peak lateral motion (same unit; 3 mm for EN 15302's value).
    samples : int
        Midpoint samples in ``theta`` over the half period.
    refine : int
        Sub-intervals per interval of ``y`` for the running integral of Delta r (linear
        interpolation between the given points, as for :func:`equivalent_conicity`).

    Returns
    -------
    float
        Equivalent conicity gamma_e (-).

    Raises
    ------
    ValueError
        If the motion does not fit into ``y`` or Delta r does not change sign over it.

    Notes
    -----
    Checked against the nine reference Delta r functions of EN 15302:2008+A1:2010, Annex E
    and their reference conicities (amplitudes 1-6 mm every 0.1 mm, where the motion fits
    the tabulated range): within 0.001 for eight cases, 0.007 for E5 (unequal wheel radii,
    at 1-2 mm).
    """
    y = np.asarray(y, float)
    delta_r = np.asarray(delta_r, float)
    fine = np.linspace(y[0], y[-1], refine * (len(y) - 1) + 1)
    values = np.interp(fine, y, delta_r)
    running = np.concatenate(([0.0], np.cumsum(0.5 * (values[1:] + values[:-1]) * np.diff(fine))))

    def window(centre: float) -> float:
        return float(
            np.interp(centre + amplitude, fine, running)
            - np.interp(centre - amplitude, fine, running)
        )

    low, high = y[0] + amplitude, y[-1] - amplitude
    if not low < high or not window(low) < 0.0 < window(high):
        raise ValueError(
            f"a motion of amplitude {amplitude} does not fit into y = "
            f"[{y[0]}, {y[-1]}] with Delta r changing sign over it"
        )
    for _ in range(100):  # bisection: the window integral increases with the centre
        middle = 0.5 * (low + high)
        if window(middle) < 0.0:
            low = middle
        else:
            high = middle
    centre = 0.5 * (low + high)
    theta = np.pi * (np.arange(samples) + 0.5) / samples
    position = centre - amplitude * np.cos(theta)
    remaining = np.interp(centre + amplitude, fine, running) - np.interp(position, fine, running)
    integral = np.sum(amplitude * np.sin(theta) / np.sqrt(np.maximum(remaining, 1e-300)))
    integral *= np.pi / samples
    return float((np.pi / integral) ** 2)


def flange_angle(wheel: WheelGrid, s_range: tuple = (-0.065, -0.020)) -> float:
    """Largest contact angle on the flange flank of a wheel (the flange angle).

    Parameters
    ----------
    wheel : WheelGrid
        Gridded wheel.
    s_range : tuple
        m, lateral range of the flange flank (S1002: the flank lies between the flange tip,
        about 55 mm, and the flange root, about 25 mm, on the gauge side of the taping line).

    Returns
    -------
    float
        rad, ``max atan(-dz/ds)``... expressed as a positive angle of the flank to the
        horizontal.
    """
    inside = (wheel.s >= s_range[0]) & (wheel.s <= s_range[1]) & np.isfinite(wheel.slope)
    return float(np.max(np.arctan(wheel.slope[inside])))


def nadal_limit(flange_angle_rad: float, friction: float) -> float:
    """Nadal's flange-climb limit Y/Q = (tan g - mu) / (1 + mu tan g).

    Parameters
    ----------
    flange_angle_rad : float
        rad, flange angle g.
    friction : float
        Friction coefficient mu at the flange.

    Returns
    -------
    float
        Limit ratio of lateral to vertical wheel force.
    """
    t = math.tan(flange_angle_rad)
    return (t - friction) / (1.0 + friction * t)
