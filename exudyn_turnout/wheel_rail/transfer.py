"""Load transfer between two rails and the dip a wheel's path sees, from geometry alone.

For a wheel at a fixed lateral shift rolling along x over sections that are wheel-enveloped
(:func:`.sections.wheel_envelope`, so a nose rising ahead of the wheel is met early, as a
rigid wheel meets it), the rigid-contact height of the wheel is ``-min(vertical gap)``: the
*wheel path*.  The rail carrying the wheel is the one under the touching point; the load
passes from one rail to the other where that changes (both touch there).  The *dip* is the
depression of the path between the two rails: its depth below the straight line joining the
path's levels before and after, and its angle, the sum of the largest falling and rising
slopes (the "2 alpha" of dip-angle crossing assessments).

:func:`wheel_path` takes one set of sections that holds both rails (a CONTACT crossing
slice set); :func:`two_rail_path` takes two rail bodies on the same x (stock rail and
blade, wing rail and nose, as :mod:`.turnout_sections` builds them).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from exudyn_turnout.wheel_rail.geometry import (
    WheelGrid,
    prepare_rail,
    prepare_wheel,
    search_candidates,
    search_candidates_batch,
    surface_derivatives,
)
from exudyn_turnout.wheel_rail.sections import SectionGrid

__all__ = [
    "WheelPath",
    "DipSummary",
    "rail_runs",
    "wheel_path",
    "two_rail_path",
    "two_rail_paths",
    "dip_summary",
]


@dataclass(frozen=True, eq=False)
class WheelPath:
    """Rigid-contact path of one wheel along x (arrays over x)."""

    x: np.ndarray  #: m, wheel-centre position along the track
    shift: float  #: m, lateral shift of the wheel towards the field side
    height: np.ndarray  #: m, height of the wheel (its taping circle) when touching
    y_rail: np.ndarray  #: m, lateral position of the touching point on the rail
    x_offset: np.ndarray  #: m, longitudinal position of the touching point from the centre
    #: per x: 0 = the rail the load passes to (nose, blade; the gauge-side head for
    #: :func:`wheel_path`), 1 = the rail it comes from (wing rail, stock rail); -1: none
    carrier: np.ndarray
    second_gap: np.ndarray  #: m, normal gap of the other rail's nearest candidate (NaN: none)


@dataclass(frozen=True)
class DipSummary:
    """Where the load passes between two rails and the dip of the wheel's path."""

    shift: float  #: m, lateral shift of the wheel
    transfer_x: float  #: m, first x where the second rail (nose, blade) carries the wheel
    depth: float  #: m, largest depth of the path below the chord of its end levels
    depth_x: float  #: m, where the path is deepest below that chord
    falling_slope: float  #: rad, steepest fall of the path before the deepest point
    rising_slope: float  #: rad, steepest rise after it
    dip_angle: float  #: rad, falling + rising slope ("2 alpha")


def rail_runs(heights: np.ndarray, threshold: float) -> list[slice]:
    """Contiguous lateral runs of a section that stand above a height threshold.

    Parameters
    ----------
    heights : numpy.ndarray
        m, section heights (NaN: no rail).
    threshold : float
        m, height separating rail heads from flangeways.

    Returns
    -------
    list of slice
        Index ranges of the rail heads, from the gauge side to the field side.
    """
    high = np.concatenate(([False], np.nan_to_num(heights, nan=-np.inf) > threshold, [False]))
    edges = np.flatnonzero(high[1:] != high[:-1])
    return [slice(int(a), int(b)) for a, b in zip(edges[::2], edges[1::2])]


def wheel_path(
    sections: SectionGrid,
    wheel: WheelGrid,
    taping_line: float,
    shift: float,
    head_threshold: float = -0.010,
) -> WheelPath:
    """Rigid-contact path of a wheel over (wheel-enveloped) sections with one or two rails.

    Parameters
    ----------
    sections : SectionGrid
        Sections along x; enveloped ones carry ``x_offset``.
    wheel : WheelGrid
        Gridded wheel (same grid step).
    taping_line : float
        m, nominal lateral position of the wheel's taping line in the sections' frame.
    shift : float
        m, lateral shift of the wheel towards the field side.
    head_threshold : float
        m, a rail head stands above this height (flangeways are deeper).

    Returns
    -------
    WheelPath
        ``carrier`` is 0 when the touching point is on the gauge-side head of a section with
        two or more heads (the nose of a crossing), else 1 (the wing rail, or a single head).
    """
    derivatives = surface_derivatives(sections)
    step = float(sections.y[1] - sections.y[0])
    out: dict[str, list[float]] = {
        k: [] for k in ("height", "y_rail", "x_offset", "carrier", "second_gap")
    }
    prepared = prepare_wheel(wheel, taping_line, 0.0, directions=())
    for i in range(len(sections.x)):
        rail = prepare_rail(
            sections.z[i], derivatives.slope[i], derivatives.curvature[i], sections.y, directions=()
        )
        found = search_candidates(rail, prepared, shift=shift, max_candidates=3, max_gap=0.02)
        if len(found.gap) == 0:
            for key, value in (
                ("height", np.nan),
                ("y_rail", np.nan),
                ("x_offset", np.nan),
                ("carrier", -1),
                ("second_gap", np.nan),
            ):
                out[key].append(value)
            continue
        touching = int(np.argmin(found.gap / np.cos(found.angle)))
        y = float(found.y_rail[touching])
        index = min(max(int(round((y - sections.y[0]) / step)), 0), len(sections.y) - 1)
        runs = rail_runs(sections.z[i], head_threshold)
        run_of = [k for k, run in enumerate(runs) if run.start <= index < run.stop]
        carrier = 0 if (len(runs) >= 2 and run_of and run_of[0] == 0) else 1
        others = [
            found.gap[k]
            for k in range(len(found.gap))
            if k != touching
            and _run_index(runs, sections.y, found.y_rail[k], step) != (run_of or [-1])[0]
        ]
        out["height"].append(-float(found.gap[touching] / math.cos(found.angle[touching])))
        out["y_rail"].append(y)
        out["x_offset"].append(
            float(sections.x_offset[i, index]) if sections.x_offset is not None else 0.0
        )
        out["carrier"].append(carrier)
        out["second_gap"].append(min(others) if others else np.nan)
    return WheelPath(
        x=sections.x.copy(),
        shift=shift,
        **{k: np.asarray(v, dtype=int if k == "carrier" else float) for k, v in out.items()},
    )


def _touch_heights(sections: SectionGrid, index: int, derivatives, prepared, shifts) -> list:
    """Per shift: (height, y on the rail, x offset) of the touching candidate (-inf: none)."""
    rail = prepare_rail(
        sections.z[index],
        derivatives.slope[index],
        derivatives.curvature[index],
        sections.y,
        directions=(),
    )
    out = []
    batch = search_candidates_batch(rail, prepared, shifts, max_candidates=3, max_gap=0.02)
    for found in batch:
        if len(found.gap) == 0:
            out.append((-math.inf, math.nan, 0.0))
            continue
        heights = -found.gap / np.cos(found.angle)
        best = int(np.argmax(heights))
        y = float(found.y_rail[best])
        offset = 0.0
        if sections.x_offset is not None:
            step = float(sections.y[1] - sections.y[0])
            k = min(max(int(round((y - sections.y[0]) / step)), 0), len(sections.y) - 1)
            offset = float(sections.x_offset[index, k])
        out.append((float(heights[best]), y, offset))
    return out


def two_rail_path(
    first: SectionGrid,
    second: SectionGrid,
    wheel: WheelGrid,
    taping_line: float,
    shift: float,
) -> WheelPath:
    """Rigid-contact path of a wheel over two rail bodies on the same x grid.

    At every x the wheel stands on whichever body lifts it higher (``-min(vertical gap)``
    over each body's candidates); the load passes from ``first`` to ``second`` where that
    changes.

    Parameters
    ----------
    first, second : SectionGrid
        The rail the load comes from (stock rail, wing rail) and the one it passes to
        (blade, nose), same ``x`` (enveloped sections carry ``x_offset``).
    wheel : WheelGrid
        Gridded wheel (same grid step).
    taping_line : float
        m, nominal lateral position of the taping line in the sections' frame.
    shift : float
        m, lateral shift of the wheel towards the field side.

    Returns
    -------
    WheelPath
        ``carrier`` 0 where ``second`` carries the wheel, 1 where ``first`` does, -1 where
        neither is under it; ``second_gap`` the vertical gap of the other body there.

    Raises
    ------
    ValueError
        The two bodies' x grids differ.
    """
    return two_rail_paths(first, second, wheel, taping_line, (shift,))[0]


def two_rail_paths(
    first: SectionGrid,
    second: SectionGrid,
    wheel: WheelGrid,
    taping_line: float,
    shifts: tuple,
) -> tuple:
    """:func:`two_rail_path` for several lateral shifts (one rail preparation per x).

    Parameters
    ----------
    first, second : SectionGrid
        See :func:`two_rail_path`.
    wheel : WheelGrid
        Gridded wheel.
    taping_line : float
        m, nominal lateral position of the taping line.
    shifts : tuple of float
        m, lateral shifts of the wheel towards the field side.

    Returns
    -------
    tuple of WheelPath
        One per shift.

    Raises
    ------
    ValueError
        The two bodies' x grids differ.
    """
    if first.x.shape != second.x.shape or not np.allclose(first.x, second.x):
        raise ValueError("two_rail_path: the two bodies must share their x grid")
    prepared = prepare_wheel(wheel, taping_line, 0.0, directions=())
    derivatives = (surface_derivatives(first), surface_derivatives(second))
    n, m = len(first.x), len(shifts)
    height = np.full((m, n), np.nan)
    y_rail, x_offset, second_gap = (np.full((m, n), np.nan) for _ in range(3))
    carrier = np.full((m, n), -1, dtype=int)
    for i in range(n):
        found = [
            _touch_heights(body, i, d, prepared, np.asarray(shifts, float))
            for body, d in zip((first, second), derivatives)
        ]
        for j in range(m):
            (h1, y1, o1), (h2, y2, o2) = found[0][j], found[1][j]
            if not (math.isfinite(h1) or math.isfinite(h2)):
                continue
            on_second = h2 >= h1
            height[j, i] = h2 if on_second else h1
            y_rail[j, i], x_offset[j, i] = (y2, o2) if on_second else (y1, o1)
            carrier[j, i] = 0 if on_second else 1
            other = h1 if on_second else h2
            second_gap[j, i] = height[j, i] - other if math.isfinite(other) else math.nan
    return tuple(
        WheelPath(
            x=first.x.copy(),
            shift=float(shifts[j]),
            height=height[j],
            y_rail=y_rail[j],
            x_offset=x_offset[j],
            carrier=carrier[j],
            second_gap=second_gap[j],
        )
        for j in range(m)
    )


def _run_index(runs: list[slice], y_grid: np.ndarray, y: float, step: float) -> int:
    index = int(round((y - y_grid[0]) / step))
    for k, run in enumerate(runs):
        if run.start <= index < run.stop:
            return k
    return -1


def dip_summary(path: WheelPath, baseline: float = 0.0) -> DipSummary:
    """Transfer position and dip of a wheel path.

    Parameters
    ----------
    path : WheelPath
        From :func:`wheel_path` or :func:`two_rail_path`, over an x range that starts on
        the first rail and ends on the second.
    baseline : float
        m, slopes are chords over this length (0: between neighbouring samples).  A path
        over sections interpolated between x nodes is piecewise linear with kinks at the
        nodes; a 20 mm baseline (that of :func:`exudyn_turnout.inputs.routes.dip_angle`)
        measures the dip's slope rather than the kinks.

    Returns
    -------
    DipSummary
        Depth below the chord between the path's first and last heights, the steepest
        falling slope before and rising slope after the deepest point.
    """
    x, h = path.x, path.height
    good = np.isfinite(h)
    x, h, carrier = x[good], h[good], path.carrier[good]
    on_nose = np.flatnonzero(carrier == 0)
    transfer = float(x[on_nose[0]]) if on_nose.size else math.nan
    chord = h[0] + (h[-1] - h[0]) * (x - x[0]) / (x[-1] - x[0])
    below = chord - h
    deepest = int(np.argmax(below))
    if baseline > 0.0:
        half = 0.5 * baseline
        ahead = np.interp(np.minimum(x + half, x[-1]), x, h)
        behind = np.interp(np.maximum(x - half, x[0]), x, h)
        span = np.minimum(x + half, x[-1]) - np.maximum(x - half, x[0])
        slope = (ahead - behind) / np.where(span > 0.0, span, 1.0)
    else:
        slope = np.gradient(h, x)
    falling = float(np.max(-slope[: deepest + 1])) if deepest > 0 else 0.0
    rising = float(np.max(slope[deepest:])) if deepest < len(x) - 1 else 0.0
    falling, rising = max(falling, 0.0), max(rising, 0.0)
    return DipSummary(
        shift=path.shift,
        transfer_x=transfer,
        depth=float(below[deepest]),
        depth_x=float(x[deepest]),
        falling_slope=math.atan(falling),
        rising_slope=math.atan(rising),
        dip_angle=math.atan(falling) + math.atan(rising),
    )
