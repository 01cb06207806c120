"""Separate local minima of gap functions, and envelopes of profile polylines on a grid.

Helpers of the candidate search in :mod:`.geometry`: two minima of a gap function belong to
separate contact regions when the gap rises by more than a prominence between them; a
minimum is refined below the grid step by a parabola through three points; a (rotated)
profile polyline, possibly multi-valued, is put on a grid as its upper (rail) or lower
(wheel) envelope.
"""

from __future__ import annotations

import math

import numpy as np

from exudyn_turnout.wheel_rail.profiles import Profile
from exudyn_turnout.wheel_rail.sections import monotone_runs, surface_on_grid

__all__ = [
    "batch_local_minima",
    "refine_minimum",
    "finite_runs",
    "rotate_profile",
    "profile_envelope",
    "lower_envelope",
]


def _local_minima(gap: np.ndarray, prominence: float) -> list[int]:
    """Indices of local minima of ``gap`` that lie in separate regions (lowest first)."""
    return batch_local_minima(gap[None, :], prominence)[0]


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


def batch_local_minima(gap: np.ndarray, prominence: float) -> list[list[int]]:
    """Separate local minima of every row of a 2-D gap array (see :func:`_local_minima`).

    Parameters
    ----------
    gap : numpy.ndarray
        (rows, n) m, gaps on a grid; non-finite where there is no surface.
    prominence : float
        m, a minimum counts separately when the gap between it and every kept lower one
        rises by at least this much.

    Returns
    -------
    list of list of int
        Per row, the indices of its separate minima, lowest first.
    """
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


def refine_minimum(gap: np.ndarray, i: int) -> tuple[float, float]:
    """Sub-grid offset (in steps) and value of a minimum by a parabola through 3 points.

    Parameters
    ----------
    gap : numpy.ndarray
        m, the gap on a grid.
    i : int
        Index of the grid minimum (not at either end).

    Returns
    -------
    offset : float
        Grid steps from ``i`` to the parabola's minimum, within [-0.5, 0.5] (0 at a rail's
        edge).
    value : float
        m, the gap there.
    """
    left, mid, right = gap[i - 1], gap[i], gap[i + 1]
    if not (np.isfinite(left) and np.isfinite(right)):
        return 0.0, float(mid)  # at the edge of a rail: no parabola
    curvature = left - 2.0 * mid + right
    offset = 0.5 * (left - right) / curvature if curvature > 0 else 0.0
    offset = min(max(offset, -0.5), 0.5)
    return offset, mid - 0.25 * (left - right) * offset


def finite_runs(values: np.ndarray) -> list[slice]:
    """Runs of at least three consecutive finite values.

    Parameters
    ----------
    values : numpy.ndarray

    Returns
    -------
    list of slice
    """
    finite = np.concatenate(([False], np.isfinite(values), [False]))
    edges = np.flatnonzero(finite[1:] != finite[:-1])
    return [slice(int(a), int(b)) for a, b in zip(edges[::2], edges[1::2]) if b - a >= 3]


def rotate_profile(y: np.ndarray, z: np.ndarray, theta: float) -> tuple[np.ndarray, np.ndarray]:
    """A profile's points in axes turned by theta (v along the new lateral axis).

    Parameters
    ----------
    y, z : numpy.ndarray
        m, the points.
    theta : float
        rad.

    Returns
    -------
    v, w : numpy.ndarray
        m.
    """
    c, s = math.cos(theta), math.sin(theta)
    return c * y + s * z, -s * y + c * z


def profile_envelope(v: np.ndarray, w: np.ndarray, grid: np.ndarray, upper: bool) -> np.ndarray:
    """The surface of the polyline (v, w) on ``grid`` (:func:`.sections.surface_on_grid`).

    Parameters
    ----------
    v, w : numpy.ndarray
        m, the polyline.
    grid : numpy.ndarray
        m, where the surface is wanted.
    upper : bool
        True: a rail (the upper envelope); False: a wheel (the lower one).

    Returns
    -------
    numpy.ndarray
        m, NaN where the polyline does not reach.
    """
    profile = Profile(y=v, z=w, kind="rail" if upper else "wheel", source="")
    return surface_on_grid(profile, grid)


def lower_envelope(
    v: np.ndarray, w: np.ndarray, attribute: np.ndarray, grid: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Lower envelope of the polyline (v, w) on ``grid`` and ``attribute`` of the point forming it.

    The polyline may be multi-valued in v (a rotated flange); each monotone run is
    interpolated on its own and the lowest run wins at every grid point, so the envelope
    equals :func:`.sections.surface_on_grid`'s and the attribute (e.g. the wheel coordinate
    s) belongs to the same point of the profile.  NaN where no run covers the grid point.

    Parameters
    ----------
    v, w : numpy.ndarray
        m, the polyline.
    attribute : numpy.ndarray
        A value per polyline point (e.g. the wheel coordinate s).
    grid : numpy.ndarray
        m.

    Returns
    -------
    height, value : numpy.ndarray
        m, the envelope, and the attribute of the point forming it.
    """
    height = np.full(grid.shape, np.inf)
    value = np.full(grid.shape, np.nan)
    for run in monotone_runs(v):
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
