"""A non-uniform x grid for a rail section that changes along x.

:func:`section_nodes` places x nodes only where a section changes: the design's break
points, then bisection until linear interpolation between nodes is within a tolerance
(normal distance, over the part of the section a wheel can touch, down to
:data:`TOUCHABLE_DEPTH` below its top unless told otherwise) or the step is ``min_step``,
then nodes that their neighbours interpolate within the tolerance are dropped. The rail
bodies of a turnout (:mod:`.turnout_sections`) are gridded with it.

Stage: pure numpy.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["TOUCHABLE_DEPTH", "section_nodes"]


#: m, depth below its top above which a point of a section counts for the x grid (a wheel
#: touches a rail above ~15 mm below its top; the flange root sits 10-14 mm below the tread)
TOUCHABLE_DEPTH = -0.016


#: a rail edge that moves (the blade's planed field side, which lies against the stock
#: rail's gauge face) may move 5x the tolerance between nodes: with 0.2 mm, 2 mm, so the
#: blend of two nodes lacks a strip at most 1 mm wide next to the stock rail's face
_EDGE_FACTOR = 5.0


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
