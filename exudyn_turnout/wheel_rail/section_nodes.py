"""A non-uniform x grid for a rail section that changes along x.

:func:`section_nodes` places x nodes only where a section changes: the design's break
points, then bisection until linear interpolation between nodes is within a tolerance
(normal distance, over the part of the section a wheel can touch, down to
:data:`TOUCHABLE_DEPTH` below its top unless told otherwise) or the step is ``min_step``,
then nodes that their neighbours interpolate within the tolerance are dropped. The rail
bodies of a turnout (:mod:`.turnout_sections`) are gridded with it.

Where two rails (or two heads of one section) both carry a wheel, the load split between
them follows the difference of their first-touch heights, to ~0.6 percentage points of
load per um at a static wheel load (validation/two_patch_split.md), and the contact tables
interpolate each rail's contact linearly between x nodes.  :func:`transfer_nodes` refines
a grid there: it bisects a cell while, for a rigid wheel at some lateral shift, two rails
are within :data:`TRANSFER_NEAR` of first touch (or trade places) and the difference of
their first-touch heights departs from linear by more than :data:`TRANSFER_TOLERANCE` at
the cell's middle, down to :data:`TRANSFER_MIN_STEP`.  :func:`first_touch_heights` gives
those heights of a gridded section (the wheel over its grid: :func:`wheel_heights`).

Stage: pure numpy.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "TOUCHABLE_DEPTH",
    "TRANSFER_NEAR",
    "TRANSFER_TOLERANCE",
    "TRANSFER_MIN_STEP",
    "section_nodes",
    "wheel_heights",
    "first_touch_heights",
    "transfer_nodes",
]


#: m, depth below its top above which a point of a section counts for the x grid (a wheel
#: touches a rail above ~15 mm below its top; the flange root sits 10-14 mm below the tread)
TOUCHABLE_DEPTH = -0.016


#: a rail edge that moves (the blade's planed field side, which lies against the stock
#: rail's gauge face) may move 5x the tolerance between nodes: with 0.2 mm, 2 mm, so the
#: blend of two nodes lacks a strip at most 1 mm wide next to the stock rail's face
_EDGE_FACTOR = 5.0


#: m, two rails share a wheel's load when both are this close to its first touch (a static
#: wheel load of 54.5 kN presses a wheel ~0.1 mm into a rail: validation/two_patch_split.md)
TRANSFER_NEAR = 2e-4

#: m, largest departure from linear of the first-touch height difference of two rails over
#: an x cell in a transfer (0.6 percentage points of load per um: ~1 point at 54.5 kN)
TRANSFER_TOLERANCE = 2e-6

#: m, smallest x cell :func:`transfer_nodes` makes (the contact patch is ~10 mm long)
TRANSFER_MIN_STEP = 1e-3

#: m, initial node spacing before bisection (no break point of a design is closer)
_MAX_STEP = 0.5


def _linear_error(
    za: np.ndarray,
    zm: np.ndarray,
    zb: np.ndarray,
    t,
    region: slice,
    step: float,
    depth: float = TOUCHABLE_DEPTH,
) -> float:
    """Normal distance (m) between sections and the linear blend of their neighbours.

    Over ``region`` where a rail stands less than ``-depth`` below its top; a strip of rail
    present in a section and not in the blend (or the reverse) counts by its width /
    :data:`_EDGE_FACTOR`.  ``zm`` may hold several sections (rows) at fractions ``t``.
    """
    zm = np.atleast_2d(zm)[:, region]
    t = np.asarray(t, float).reshape(-1, 1)
    blend = (1.0 - t) * za[region] + t * zb[region]
    both_rows = np.concatenate((blend, zm), axis=1)
    if not np.any(np.isfinite(both_rows)):
        return 0.0
    with np.errstate(invalid="ignore"):
        level = np.nanmax(np.where(np.isfinite(both_rows), both_rows, -1.0), axis=1) + depth
        high_blend, high_middle = blend > level[:, None], zm > level[:, None]
    lost = (np.isnan(blend) & high_middle) | (np.isnan(zm) & high_blend)
    strip = float(np.max(np.count_nonzero(lost, axis=1))) * step / _EDGE_FACTOR
    both = np.isfinite(blend) & np.isfinite(zm) & (high_blend | high_middle)
    if not np.any(both):
        return strip
    slope = np.zeros_like(zm)
    slope[:, 1:-1] = (zm[:, 2:] - zm[:, :-2]) / (2.0 * step)
    slope = np.where(np.isfinite(slope), slope, 0.0)
    normal = np.abs(zm - blend)[both] / np.sqrt(1.0 + slope[both] ** 2)
    return max(strip, float(np.max(normal)))


def section_nodes(
    evaluate,
    break_points: list[float],
    tolerance: float,
    min_step: float,
    region: slice,
    grid_step: float,
    depth: float = TOUCHABLE_DEPTH,
) -> tuple[np.ndarray, np.ndarray]:
    """Non-uniform x nodes of a section that changes along x.

    Break points, then every interval at most 0.5 m long, bisected while the section at its
    middle differs from the mean of its ends by more than ``tolerance`` (normal distance
    over ``region``, where a rail stands above -16 mm; a strip of rail that appears or
    disappears counts by its width) and the halves are at least ``min_step`` long; last,
    inner nodes other than break points that their neighbours interpolate within the
    tolerance are dropped.

    Parameters
    ----------
    evaluate : callable
        ``evaluate(x) -> numpy.ndarray`` heights on the lateral grid (m, NaN: no rail).
    break_points : list of float
        m, sorted; the first and last are the ends.
    tolerance : float
        m, interpolation tolerance.
    min_step : float
        m, smallest node spacing.
    region : slice
        Lateral grid points a wheel can reach.
    grid_step : float
        m, lateral grid step.
    depth : float
        m, the part of a section above its top + depth counts (a laterally moving face that
        no wheel reaches, e.g. a stock rail's gauge face behind the blade, is left out by
        a shallower depth).

    Returns
    -------
    tuple
        (x nodes (m, increasing), heights (n_x, n_y)).
    """
    cache: dict[float, np.ndarray] = {}

    def at(x: float) -> np.ndarray:
        if x not in cache:
            cache[x] = evaluate(x)
        return cache[x]

    nodes: set[float] = set()
    for a, b in zip(break_points[:-1], break_points[1:]):
        pieces = max(1, int(math.ceil((b - a) / _MAX_STEP - 1e-9)))
        edges = [float(v) for v in np.linspace(a, b, pieces + 1)]
        intervals = list(zip(edges[:-1], edges[1:]))
        while intervals:
            lo, hi = intervals.pop()
            nodes.update((lo, hi))
            if hi - lo < 2.0 * min_step:
                continue
            mid = 0.5 * (lo + hi)
            if _linear_error(at(lo), at(mid), at(hi), 0.5, region, grid_step, depth) > tolerance:
                intervals += [(lo, mid), (mid, hi)]
    keep = sorted(nodes)
    fixed = set(break_points)
    dropped: list[float] = []
    i = 1
    while i < len(keep) - 1:
        a, b = keep[i - 1], keep[i + 1]
        inside = [keep[i]] + [v for v in dropped if a < v < b]
        if keep[i] not in fixed and (
            _linear_error(
                at(a),
                np.array([at(v) for v in inside]),
                at(b),
                [(v - a) / (b - a) for v in inside],
                region,
                grid_step,
                depth,
            )
            <= tolerance
        ):
            dropped.append(keep.pop(i))
        else:
            i += 1
    x = np.array(keep)
    return x, np.array([at(float(v)) for v in x])


def wheel_heights(
    y: np.ndarray,
    wheel_s: np.ndarray,
    wheel_z: np.ndarray,
    taping_line: float,
    shifts: np.ndarray,
) -> np.ndarray:
    """A wheel's lower surface over a section's lateral grid, at several lateral shifts.

    Parameters
    ----------
    y : numpy.ndarray
        m, lateral grid of the sections.
    wheel_s, wheel_z : numpy.ndarray
        m, the wheel's lower surface: lateral coordinate from its taping line and height
        above the taping circle's lowest point (NaN: no wheel).
    taping_line : float
        m, lateral position of the taping line at zero shift.
    shifts : numpy.ndarray
        m, lateral shifts of the wheel.

    Returns
    -------
    numpy.ndarray
        m, (n_shifts, n_y): ``z_wheel(y - taping_line - shift)`` (NaN: no wheel there).
    """
    s = np.asarray(y, float)[None, :] - taping_line - np.asarray(shifts, float)[:, None]
    return np.interp(s, wheel_s, wheel_z, left=np.nan, right=np.nan)


def first_touch_heights(
    heights: np.ndarray, wheel: np.ndarray, head_threshold: float | None = None
) -> np.ndarray:
    """Heights at which a rigid wheel first touches each rail of a section (vertical).

    Parameters
    ----------
    heights : numpy.ndarray
        m, section heights on its lateral grid (NaN: no rail).
    wheel : numpy.ndarray
        m, (n_shifts, n_y) the wheel over the same grid (:func:`wheel_heights`).
    head_threshold : float, optional
        m, a rail head stands above this height (flangeways are deeper): the section holds
        two rails, its gauge-side head (the nose of a crossing, where there are two or more
        heads) and the others (the wing rail).  Default: one rail, the whole section.

    Returns
    -------
    numpy.ndarray
        m, (1 or 2, n_shifts): the height of the wheel's taping circle bottom when the rail
        first touches it, ``max(z_rail(y) - z_wheel(y))`` over the rail (NaN: wheel and
        rail do not overlap laterally).
    """
    n_y = len(heights)
    runs = [slice(0, n_y)]
    if head_threshold is not None:
        high = np.concatenate(([False], np.nan_to_num(heights, nan=-np.inf) > head_threshold))
        edges = np.flatnonzero(np.concatenate((high[1:] != high[:-1], [high[-1]])))
        heads = [slice(int(a), int(b)) for a, b in zip(edges[::2], edges[1::2])]
        if len(heads) >= 2:
            runs = [heads[0], slice(heads[1].start, heads[-1].stop)]
        else:
            runs = [slice(0, 0), slice(0, n_y)]
    lift = heights[None, :] - wheel
    out = np.full((len(runs), wheel.shape[0]), np.nan)
    for k, run in enumerate(runs):
        part = lift[:, run]
        some = np.any(np.isfinite(part), axis=1)
        if np.any(some):
            out[k, some] = np.nanmax(part[some], axis=1)
    return out


def _transfer_error(h: np.ndarray, near: float) -> float:
    """Largest departure from linear of two rails' height difference where they share a wheel.

    ``h`` is (3, n_rails, n_shifts): first-touch heights at a cell's start, middle and end.
    """
    n = h.shape[1]
    if n < 2:
        return 0.0
    with np.errstate(invalid="ignore"):
        top = np.nanmax(np.where(np.isfinite(h), h, -np.inf), axis=1)  # (3, n_shifts)
        worst = 0.0
        for r in range(n):
            for q in range(r + 1, n):
                d = h[:, q] - h[:, r]  # (3, n_shifts)
                finite = np.all(np.isfinite(d), axis=0)
                near_top = (h[:, r] >= top - near) & (h[:, q] >= top - near)
                shared = np.any(near_top & (np.abs(d) <= near), axis=0)
                crossing = (np.sign(d[0]) != np.sign(d[1])) | (np.sign(d[1]) != np.sign(d[2]))
                check = finite & (shared | crossing)
                if np.any(check):
                    error = np.abs(d[1] - 0.5 * (d[0] + d[2]))[check]
                    worst = max(worst, float(np.max(error)))
    return worst


def transfer_nodes(
    first_touch,
    nodes,
    near: float = TRANSFER_NEAR,
    tolerance: float = TRANSFER_TOLERANCE,
    min_step: float = TRANSFER_MIN_STEP,
) -> np.ndarray:
    """x nodes added where two rails share a wheel, so their height difference is linear.

    Each cell between neighbouring ``nodes`` is bisected while, at some lateral shift, two
    rails are both within ``near`` of the wheel's first touch (the highest rail) at the
    cell's start, middle or end, or their order changes over it, and the difference of
    their first-touch heights at its middle departs from the mean of its ends by more than
    ``tolerance``; halves shorter than ``min_step`` are not made.  A cell without such a
    transfer gets no node.

    Parameters
    ----------
    first_touch : callable
        ``first_touch(x) -> numpy.ndarray`` (n_rails, n_shifts), m: the heights at which a
        rigid wheel first touches each rail at x (:func:`first_touch_heights`; NaN: none).
    nodes : array_like
        m, the existing x nodes (increasing).
    near : float
        m, two rails share the wheel when both are this close to its first touch.
    tolerance : float
        m, allowed departure from linear of their height difference at a cell's middle.
    min_step : float
        m, smallest cell.

    Returns
    -------
    numpy.ndarray
        m, the added nodes (increasing; empty when none).
    """
    cache: dict[float, np.ndarray] = {}

    def at(x: float) -> np.ndarray:
        if x not in cache:
            cache[x] = np.atleast_2d(np.asarray(first_touch(x), float))
        return cache[x]

    x = [float(v) for v in np.asarray(nodes, float)]
    added: list[float] = []
    cells = list(zip(x[:-1], x[1:]))
    while cells:
        lo, hi = cells.pop()
        if hi - lo < 2.0 * min_step:
            continue
        mid = 0.5 * (lo + hi)
        h = np.stack((at(lo), at(mid), at(hi)))
        if _transfer_error(h, near) > tolerance:
            added.append(mid)
            cells += [(lo, mid), (mid, hi)]
    return np.array(sorted(added))
