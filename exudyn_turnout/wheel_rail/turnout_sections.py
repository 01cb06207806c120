"""The turnout's rail bodies as data: design sections per route, and their contact tables.

What the turnout file says
--------------------------
``[wheel_rail]`` holds the rail's design data (:class:`RailGeometry`): the rail profile, its
inclination, the gauge, the switch (:class:`.sections.SwitchDesign`), the crossing
(:class:`.sections.CrossingDesign`, nose tip, crossing angle and tip width from the plan
:class:`exudyn_turnout.inputs.geometry.TurnoutPlan` unless given) and the check rail
(:class:`CheckRailDesign`, clearance and flares from ``[check_rail]``).  Every field has a
default; :func:`rail_geometry` validates the section (one-line
:class:`~exudyn_turnout.inputs.turnout.TurnoutFileError` naming file and field).

Each ``[[routes.<name>.contacts]]`` entry carries ``sections``: the cross-section of the
rail body that entry's wheel runs on, as a list of segments along x (kinds ``plain``,
``closure``, ``stock``, ``blade``, ``wing``, ``nose``, ``check``, ``slices``:
:mod:`.turnout_segments`, re-exported here).

Coordinates
-----------
Sections are in **side coordinates of the wheel that runs on them** (:mod:`.sections`):
y from the route's centre line towards that wheel's field side, z up, so left and right
bodies look alike.  The lateral position along the route is in the sections: the stock
rail's setback, the wing rail's flare, the check rail's face.

The diverging route uses the same design functions in its own route-following frame (x
along the through route, y from the diverging centre line).  That is exact for what the
wheel of a tangential switch sees: the straight stock rail leaves the curved route by
x^2 / (2 R) as the curved stock rail leaves the straight one, the curved blade is planed
like the straight one, and a straight 1:N crossing is symmetric about its bisector.  What
it neglects: the curvature of the route over the length a section is seen (the wing rail
and nose legs are straight while the route curves: a lateral error of dx^2 / (2 R), 0.16
mm at 0.5 m after the nose tip for R = 760 m, 0.66 mm for R = 190 m), and the wheelset's
yaw in the curve in the tables (a table has no yaw, as for the through route; the contact
kernel adds the lead of a yawed wheel's contact points and the gap it closes at run time,
:mod:`.lead`).

x grid
------
A body's sections are computed on a non-uniform x grid with nodes only where the section
changes (:mod:`.section_nodes`): the design's break points, then bisection until linear
interpolation between nodes is within ``section_tolerance`` (normal distance, over the
part of the section a wheel can touch: per kind, down to 5 or 16 mm below its top) or the
step is ``min_step``, then nodes that their neighbours interpolate within the tolerance
are dropped; ``plain`` and ``closure`` keep their two ends.  At a node a section is exact:
the design functions of :mod:`.turnout_design` for the design kinds, and for ``slices`` the
slice set interpolated along u as CONTACT does (:func:`.sections.slice_surface`; the slice
positions are break points).  Between nodes every kind is linear, within the tolerance.
Where two running rails share a wheel (stock rail and blade, wing rail and nose: two bodies
of one wheel; the nose's and wing rail's heads of a ``slices`` section) the load split
follows the difference of their first-touch heights, which the tables interpolate linearly
between nodes: there :func:`.section_nodes.transfer_nodes` adds nodes (the S1002 wheel at
the nominal taping line over the tables' +-12 mm shifts, :data:`TRANSFER_SHIFTS`), down to
1 mm, until that difference is linear within 2 um over every cell where both rails are
within 0.2 mm of first touch; both bodies of a pair get the nodes.
Where a body begins abruptly (a nose tip), nodes every ``min_step`` over ``envelope_reach``
before it let the wheel's envelope (:func:`.sections.wheel_envelope`, applied by
:func:`route_contact_tables`) meet the front ahead of the wheel centre.

Between two x nodes :mod:`.tables` interpolates a contact only where its position on the
rail moves by less than 2 mm, else it holds the first node's contact over the cell (the
wheel's rest height then steps at the next node).  So where a rail moves sideways and can
carry the wheel (the stock rail's setback up to the blade's full height, the wing rail's
flare up to the nose's) nodes are at most 1.5 mm of its lateral motion apart, and the
nose's twist has a node every 1/1200 of tilt.  What remains: where the contact point jumps
(two-point contact) a held cell steps by what the rest height changes over it (0.03 mm at
the start of the stock rail's set and of the wing rail's flare; 0.07-0.08 mm on the blade's
0.125 m nodes as it rises, which the section tolerance sets).

Hand-overs
----------
Where one body or segment of a wheel ends and the next begins, the wheel's rigid rest
height over all its bodies present at x has no step in the packaged turnouts
(:mod:`.handovers`, ``tests/test_turnout_sections.py``). The ``[wheel_rail]`` design data
and its formulas are :mod:`.turnout_design`.

Stage: may import :mod:`exudyn_turnout.inputs` and :mod:`exudyn_turnout.wheel_rail`; pure
numpy (the contact tables are :mod:`.tables`').
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, replace

import numpy as np

from exudyn_turnout.inputs.routes import load_route
from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.wheel_rail.data import s1002_surface
from exudyn_turnout.wheel_rail.geometry import (
    CHECK_RAIL_DIRECTION,
    WheelGrid,
    WheelsetSetup,
)
from exudyn_turnout.wheel_rail.profiles import Profile, read_slices
from exudyn_turnout.wheel_rail.section_nodes import (
    TOUCHABLE_DEPTH,
    TRANSFER_MIN_STEP,
    first_touch_heights,
    section_nodes,
    transfer_nodes,
    wheel_heights,
)
from exudyn_turnout.wheel_rail.sections import (
    SectionGrid,
    SliceSurface,
    SwitchDesign,
    gauge_point,
    inclination_ramp,
    lateral_grid,
    nose_heights,
    sections_at,
    slice_heights,
    slice_surface,
    surface_on_grid,
    wheel_envelope,
)
from exudyn_turnout.wheel_rail.tables import (
    ContactTable,
    TableSettings,
    build_contact_table,
    cached_wheel_envelope,
)
from exudyn_turnout.wheel_rail.turnout_design import (
    RailGeometry,
    blade_heights,
    blade_lowering,
    check_face,
    crossing_throat,
    design_error,
    design_source,
    placed_rail,
    rail_geometry,
    read_rail_profile,
    stock_setback,
    wing_flare,
)
from exudyn_turnout.wheel_rail.turnout_segments import SEGMENT_KINDS, Segment, route_segments

__all__ = [
    "SEGMENT_KINDS",
    "Segment",
    "RailBody",
    "route_segments",
    "route_rail_bodies",
    "body_table_settings",
    "route_contact_tables",
    "section_nodes",
    "envelope_sections",
    "exact_sections_between",
    "EXACT_SECTION_STEP",
    "TRANSFER_SHIFTS",
    "HEAD_THRESHOLD",
]


_ENVELOPED = ("blade", "wing", "nose", "slices")  # kinds whose height or edge changes fast


_CONSTANT = ("plain", "closure")


#: m, per kind, the depth below the top above which a section's change counts for the x
#: grid: the stock rail's gauge face is behind the blade and the wing rail's and the nose's
#: field-side faces are under the tread (only their tops and corners are touched); the
#: blade's planed edge, the gauge faces (flange contact) and a check rail's face (back of
#: the flange) count down to the flange root
_DEPTH = {"stock": -0.005, "wing": -0.005, "nose": -0.005}


#: per kind, factor on ``section_tolerance``: a check rail's face moves at its flares
#: (1:67) and the back of the flange meets a flare only 4-19 mm off centre, so 0.5 mm there
#: (1 mm lateral steps) instead of ~80 nodes on a 6.7 m check rail; the nose's top near its
#: tip is where the wheel lands on it: half the tolerance from the tip to full height (the
#: dip's rising slope moved by 10 % between 0.2 and 0.1 mm, for 8 more nodes), the common
#: one behind it (:func:`_tolerance_pieces`)
_TOLERANCE_FACTOR = {"check": 2.5, "nose": 0.5}


#: m, largest lateral motion of a rail that moves sideways (the stock rail's setback up to
#: where the blade is at full height, the wing rail's flare up to where the nose is) between
#: x nodes.  The tables blend two nodes only where the contact point moves by less than 2 mm
#: (:mod:`.tables`) and the contact rides on the moving rail at about its speed (3.3 mm per
#: 3.0 mm on the stock rail); in a cell they cannot blend they hold its first node, and the
#: wheel's rest height fell in steps: 0.21 mm every 52 mm along the wing rail's 1:16 flare,
#: 0.03-0.05 mm every 0.5 m on the stock rail, with the section tolerance alone
_LATERAL_STEP = 1.5e-3


#: largest change of the nose's inclination (tangent) between x nodes of its twist: the
#: rest height of the S1002 wheel moves by 0.36 mm over the 1:40 twist and its contact point
#: by 13 mm, 10 mm of it in one jump (two-point contact), where the tables hold a cell: its
#: step was 0.025 mm with 1/800, 0.02 mm is the hand-over check's tolerance
#: (tests/test_turnout_sections.py); 1/1200 (0.067 m on a 2 m twist)
_TWIST_STEP = 1.0 / 1200.0


#: m, lateral shifts of the design wheel (S1002 at the nominal taping line) over which the
#: x grid looks for two rails sharing the wheel (:func:`.section_nodes.transfer_nodes`): the
#: running rails' table range (:class:`.tables.TableSettings`, +-12 mm) every 0.5 mm
TRANSFER_SHIFTS = (-0.012, 0.012, 5e-4)

#: m, a rail head of a slice set stands above this height (flangeways are deeper)
HEAD_THRESHOLD = -0.010


@dataclass(frozen=True, eq=False)
class RailBody:
    """A rail body one wheel can touch on one route, with its sections along x."""

    name: str  #: the route contact's name
    wheel: str  #: "left" | "right"
    rail: str  #: co-running rail slot "r1".."r4" whose motion this body follows
    x_from: float  #: m, where the body's sections begin on this route
    x_to: float  #: m, where they end
    #: side coordinates of ``wheel``, non-uniform x grid (NaN where there is no rail)
    sections: SectionGrid
    back_of_flange: bool  #: True for check rails (search direction -70 deg)
    segments: tuple = ()  #: the :class:`Segment` list it was built from
    enveloped: bool = False  #: tables use the wheel's envelope (height changes along x)


@dataclass(frozen=True, eq=False)
class _Context:
    geometry: RailGeometry
    base: Profile  #: placed, inclined rail
    upright: Profile  #: placed, not inclined (check rails, crossing noses are upright)
    y: np.ndarray  #: lateral grid
    base_heights: np.ndarray
    slices: dict  #: path -> SliceSurface of the slice set (side coordinates, u = x - x0)
    raw: Profile  #: the profile as read (placed at other inclinations by the nose's twist)
    upright_heights: np.ndarray  #: the upright rail on ``y``


def _context(geometry: RailGeometry, check: bool) -> _Context:
    half = geometry.half_gauge
    low = half - (0.19 if check else 0.0775)
    y = lateral_grid(low, half + 0.1225, geometry.grid_step)
    raw = read_rail_profile(geometry)
    base = placed_rail(geometry, geometry.inclination, raw)
    upright = placed_rail(geometry, 0.0, raw)
    return _Context(
        geometry,
        base,
        upright,
        y,
        surface_on_grid(base, y),
        slices={},
        raw=raw,
        upright_heights=surface_on_grid(upright, y),
    )


def _slice_surface(context: _Context, segment: Segment) -> SliceSurface:
    """The segment's slice set (side coordinates; u = x - x0), interpolated along u."""
    if segment.path not in context.slices:
        slices = read_slices(segment.path)
        first = slices.profiles[0]
        top = float(np.max(first.z))
        g = context.geometry
        dy = g.half_gauge - gauge_point(replace(first, z=first.z - top), g.gauge_depth)
        context.slices[segment.path] = slice_surface(slices, context.y, y_offset=dy, z_offset=-top)
    return context.slices[segment.path]


def _heights(context: _Context, segment: Segment, x: float) -> np.ndarray:
    g, y = context.geometry, context.y
    kind = segment.kind
    if kind in _CONSTANT:
        return context.base_heights.copy()
    if kind == "stock":
        shift = stock_setback(x, g.switch, g.stock_set_length)
        return surface_on_grid(context.base, y, y_offset=shift)
    if kind == "blade":
        if x < 0.0:
            return np.full(y.shape, np.nan)
        return blade_heights(
            context.base_heights,
            y,
            g.half_gauge + min(stock_setback(x, g.switch, g.stock_set_length), g.switch.head_width),
            blade_lowering(x, g.switch),
        )
    if kind == "wing":
        return surface_on_grid(context.base, y, y_offset=wing_flare(x, g.crossing))
    if kind == "nose":
        return _nose(context, segment, x)
    if kind == "check":
        face = 0.5 * g.back_to_back - check_face(x, segment.x_from, segment.x_to, g.check_rail)
        mirrored = replace(
            context.upright,
            y=face - (context.upright.y - g.half_gauge),
            z=context.upright.z + g.check_rail.height,
        )
        return surface_on_grid(mirrored, y)
    return slice_heights(_slice_surface(context, segment), np.array([x - segment.x0]))[0]


def _nose(context: _Context, segment: Segment, x: float) -> np.ndarray:
    """Nose section at x: upright legs, twisted to the track's inclination at its end."""
    g, c, y = context.geometry, context.geometry.crossing, context.y
    if x < c.nose_tip:
        return np.full(y.shape, np.nan)
    tilt = inclination_ramp(x, segment.x_to, c.inclination_transition, g.inclination)
    if tilt == g.inclination:
        leg = context.base_heights
    elif tilt == 0.0:
        leg = context.upright_heights
    else:
        leg = surface_on_grid(placed_rail(g, tilt, context.raw), y)
    width = c.tip_width + (x - c.nose_tip) / c.crossing_number
    lowering = c.tip_lowering * max(0.0, 1.0 - (x - c.nose_tip) / c.lowering_length)
    return nose_heights(leg, y, g.half_gauge, width, lowering)


def _break_points(context: _Context, segment: Segment) -> list[float]:
    g = context.geometry
    points = [segment.x_from, segment.x_to]
    if segment.kind == "stock":
        s = g.switch
        points += [-g.stock_set_length, 0.0]
        if g.stock_set_length > 0.0:  # the set, linear from 0 to the toe width
            n = int(math.ceil(s.toe_width / _LATERAL_STEP - 1e-9))
            points += [float(v) for v in np.linspace(-g.stock_set_length, 0.0, n + 1)]
        reach = stock_setback(s.lowering_length, s, g.stock_set_length)
        widths = np.arange(s.toe_width + _LATERAL_STEP, reach + 1e-12, _LATERAL_STEP)
        points += [_solve_width(s, float(w)) for w in widths] + [s.lowering_length]
    elif segment.kind == "blade":
        s = g.switch
        full = _solve_width(s, s.head_width)
        points += [0.0, s.lowering_length, full]
    elif segment.kind == "wing":
        c = g.crossing
        end = c.nose_tip + c.lowering_length  # the nose carries the wheel from here on
        n = int(math.ceil(wing_flare(end, c) / _LATERAL_STEP - 1e-9))
        points += [float(v) for v in np.linspace(crossing_throat(c), end, n + 1)]
    elif segment.kind == "nose":
        c = g.crossing
        points += [
            c.nose_tip,
            c.nose_tip + c.lowering_length,
            c.nose_tip + c.crossing_number * max(c.head_width - c.tip_width, 0.0),
            segment.x_to - c.inclination_transition,
        ]
        if c.inclination_transition > 0.0:
            n = int(math.ceil(abs(g.inclination) / _TWIST_STEP - 1e-9))
            start = segment.x_to - c.inclination_transition
            points += [float(v) for v in np.linspace(start, segment.x_to, n + 1)]
    elif segment.kind == "check":
        length = g.check_rail.flare_length
        points += [segment.x_from + length, segment.x_to - length]
    elif segment.kind == "slices":
        points += [float(u) + segment.x0 for u in _slice_surface(context, segment).u]
    return sorted({p for p in points if segment.x_from <= p <= segment.x_to})


def _solve_width(design: SwitchDesign, width: float) -> float:
    """x >= 0 where the setback reaches ``width`` (positive root of the quadratic)."""
    a, b, c = 1.0 / (2.0 * design.radius), design.entry_tangent, design.toe_width - width
    return max(0.0, (-b + math.sqrt(b * b - 4.0 * a * c)) / (2.0 * a))


def _region(context: _Context, check: bool) -> slice:
    """Lateral grid points a wheel (shifted by up to 12 mm, or the check rail's range) touches."""
    half = context.geometry.half_gauge
    low = half - (0.19 if check else 0.062)
    inside = np.flatnonzero((context.y >= low) & (context.y <= half + 0.11))
    return slice(int(inside[0]), int(inside[-1]) + 1)


def _front_nodes(
    x: np.ndarray, z: np.ndarray, region: slice, reach: float, step: float
) -> list[float]:
    """Extra x nodes ahead of where a body begins (no touchable rail -> rail)."""
    present = np.any(z[:, region] > TOUCHABLE_DEPTH, axis=1)
    extra = []
    for i in np.flatnonzero(~present[:-1] & present[1:]):
        k = np.arange(1, int(round(reach / step)) + 1)
        candidates = x[i + 1] - k * step
        extra += [float(v) for v in candidates if v > x[i] + 0.5 * step]
    return extra


def _tolerance_pieces(context: _Context, segment: Segment) -> list[tuple[float, float, float]]:
    """(x_from, x_to, factor on ``section_tolerance``) pieces of a segment.

    The nose's finer tolerance holds where the wheel lands on it, from its tip to full
    height; behind that (where its legs part and it twists to the track's inclination) the
    common tolerance.
    """
    factor = _TOLERANCE_FACTOR.get(segment.kind, 1.0)
    if segment.kind == "nose":
        c = context.geometry.crossing
        split = c.nose_tip + c.lowering_length
        if segment.x_from < split < segment.x_to:
            return [(segment.x_from, split, factor), (split, segment.x_to, 1.0)]
    return [(segment.x_from, segment.x_to, factor)]


@functools.lru_cache(maxsize=8)
def _design_wheel(y0: float, n_y: int, grid_step: float, taping: float) -> np.ndarray:
    """The S1002 wheel over a lateral grid at :data:`TRANSFER_SHIFTS` (its own grid step).

    Its surface only (:func:`.data.s1002_surface`): no slopes, so no ``scipy.signal``.
    """
    s, z = s1002_surface(grid_step)
    low, high, step = TRANSFER_SHIFTS
    shifts = low + step * np.arange(int(round((high - low) / step)) + 1)
    y = y0 + grid_step * np.arange(n_y)
    return wheel_heights(y, s, z, taping, shifts)


def _first_touch(context: _Context, heights: np.ndarray, head_threshold: float | None):
    """First-touch heights of the design wheel on a section (:func:`first_touch_heights`)."""
    g, y = context.geometry, context.y
    taping = 0.5 * g.back_to_back + WheelsetSetup().flange_back
    wheel = _design_wheel(float(y[0]), len(y), float(y[1] - y[0]), taping)
    return first_touch_heights(heights, wheel, head_threshold)


def _segment_nodes(
    context: _Context, segment: Segment, region: slice
) -> tuple[np.ndarray, np.ndarray]:
    """x nodes and sections of one segment whose section changes along x."""
    g = context.geometry
    points = _break_points(context, segment)
    xs: list[np.ndarray] = []
    zs: list[np.ndarray] = []
    for a, b, factor in _tolerance_pieces(context, segment):
        x, z = section_nodes(
            lambda v, seg=segment: _heights(context, seg, v),
            sorted({a, b} | {p for p in points if a <= p <= b}),
            g.section_tolerance * factor,
            g.min_step,
            region,
            g.grid_step,
            _DEPTH.get(segment.kind, TOUCHABLE_DEPTH),
        )
        if xs:  # the shared node once
            x, z = x[1:], z[1:]
        xs.append(x)
        zs.append(z)
    x, z = np.concatenate(xs), np.concatenate(zs)
    if segment.kind == "slices":  # a crossing's nose and wing rail in one section
        extra = transfer_nodes(
            lambda v: _first_touch(context, _heights(context, segment, v), HEAD_THRESHOLD), x
        )
        if len(extra):
            x = np.concatenate((x, extra))
            z = np.concatenate((z, [_heights(context, segment, float(v)) for v in extra]))
            order = np.argsort(x)
            x, z = x[order], z[order]
    return x, z


def _body(context: _Context, segments: tuple[Segment, ...], name: str) -> SectionGrid:
    g = context.geometry
    check = segments[0].kind == "check"
    region = _region(context, check)
    xs: list[np.ndarray] = []
    zs: list[np.ndarray] = []
    for k, segment in enumerate(segments):
        if segment.kind in _CONSTANT:  # the same section all along: its two ends
            x = np.array([segment.x_from, segment.x_to])
            z = np.tile(context.base_heights, (2, 1))
        else:
            x, z = _segment_nodes(context, segment, region)
        if k > 0:  # the shared node belongs to the later segment
            xs[-1], zs[-1] = xs[-1][:-1], zs[-1][:-1]
        xs.append(x)
        zs.append(z)
    x_all, z_all = np.concatenate(xs), np.concatenate(zs)
    if any(seg.kind in _ENVELOPED for seg in segments):
        extra = _front_nodes(x_all, z_all, region, g.envelope_reach, g.min_step)
        if extra:
            owner = [next(s for s in segments if s.x_from <= v <= s.x_to) for v in extra]
            x_all = np.concatenate((x_all, extra))
            z_all = np.concatenate((z_all, [_heights(context, s, v) for s, v in zip(owner, extra)]))
            order = np.argsort(x_all)
            x_all, z_all = x_all[order], z_all[order]
    return SectionGrid(x=x_all, y=context.y, z=z_all, name=name)


def _body_heights(context: _Context, segments: tuple[Segment, ...], x: float) -> np.ndarray:
    """Exact section of a body at x (the segment holding x)."""
    segment = next(s for s in segments if s.x_from <= x <= s.x_to)
    return _heights(context, segment, x)


def _pair_transfer_nodes(
    context: _Context,
    first: tuple[Segment, ...],
    second: tuple[Segment, ...],
    nodes: tuple[np.ndarray, np.ndarray],
) -> np.ndarray:
    """x nodes both bodies of a wheel need where they share it (:func:`transfer_nodes`).

    On the union of the two bodies' nodes where both are present; the nodes added and the
    union's nodes of the cells refined (so that both bodies' tables hold every node of
    those cells).
    """
    lo = max(first[0].x_from, second[0].x_from)
    hi = min(first[-1].x_to, second[-1].x_to)
    if hi <= lo:
        return np.zeros(0)
    union = np.unique(np.concatenate([n[(n >= lo) & (n <= hi)] for n in nodes] + [[lo, hi]]))

    def touch(x: float) -> np.ndarray:
        return np.concatenate(
            [_first_touch(context, _body_heights(context, b, x), None) for b in (first, second)]
        )

    extra = transfer_nodes(touch, union)
    if not len(extra):
        return extra
    cell = np.clip(np.searchsorted(union, extra) - 1, 0, len(union) - 2)
    ends = np.concatenate((union[cell], union[cell + 1]))
    return np.unique(np.concatenate((extra, ends)))


def _add_nodes(
    context: _Context, segments: tuple[Segment, ...], grid: SectionGrid, extra: np.ndarray
) -> SectionGrid:
    """A body's sections with exact sections at more x nodes.

    A node within half the transfer floor of one it has (or of one added before) is left
    out: the other body's nodes may lie a fraction of a mm from its own.
    """
    kept = list(grid.x)
    new = []
    for v in sorted(extra):
        if np.min(np.abs(np.asarray(kept) - v)) >= 0.5 * TRANSFER_MIN_STEP:
            kept.append(float(v))
            new.append(float(v))
    if not new:
        return grid
    x = np.concatenate((grid.x, new))
    z = np.concatenate((grid.z, [_body_heights(context, segments, float(v)) for v in new]))
    order = np.argsort(x)
    return replace(grid, x=x[order], z=z[order])


#: m, the step along x of the exact sections :func:`exact_sections_between` adds (the exact
#: force of ``post_contact`` at the passage's approach, single wheelset, 2-layer, at the
#: crossing's peak through 100 km/h / the check rail's diverging 80 km/h: 202.2 / 63.1 kN at
#: 4 mm, 203.5 / 63.6 at 1 mm, 203.6 / 63.6 at 0.5 mm; the body's nodes alone 202.3 / 19.3)
EXACT_SECTION_STEP = 1e-3


def exact_sections_between(
    turnout: Turnout,
    body: RailBody,
    x_from: float,
    x_to: float,
    step: float = EXACT_SECTION_STEP,
) -> SectionGrid:
    """A rail body's sections with its exact section added every ``step`` on [x_from, x_to].

    A body's sections are exact at its x nodes and blended linearly between them
    (:func:`.sections.sections_at`), which is what its contact tables are built from. Where
    the rail changes faster than the nodes follow, the blend is not the rail: a check rail's
    face kinks in plan where its flare meets the check line, and between nodes 10-20 mm
    apart the blend cuts that corner (at the packaged check rail's flare end the gap 40 mm
    ahead of the axle differs by up to 0.3 mm, ``validation/check_rail_kink.md``). The exact
    sections added here, every ``step``, make the blend follow the rail to within the
    rail's own curvature over ``step``. A node within half of
    :data:`.section_nodes.TRANSFER_MIN_STEP` of one the body has is left out.

    Parameters
    ----------
    turnout : Turnout
        The turnout the body belongs to (its ``[wheel_rail]`` design).
    body : RailBody
        From :func:`route_rail_bodies` of that turnout.
    x_from, x_to : float
        m, the range along the track (clipped to the body's own range).
    step : float
        m, > 0.

    Returns
    -------
    SectionGrid
        The body's sections, with more nodes; the body's own where the range misses it.

    Raises
    ------
    ValueError
        ``step`` not positive, or a body whose lateral grid is not this turnout's.
    """
    if not step > 0.0:
        raise ValueError(f"exact_sections_between: step must be > 0, got {step!r}")
    lo, hi = max(float(x_from), body.x_from), min(float(x_to), body.x_to)
    if not hi >= lo or not body.segments:
        return body.sections
    context = _context(rail_geometry(turnout), body.back_of_flange)
    if not np.array_equal(context.y, body.sections.y):
        raise ValueError(
            f"exact_sections_between: body {body.name!r} was not built from this turnout's "
            "[wheel_rail] design (its lateral grid differs)"
        )
    extra = np.arange(lo, hi + 0.5 * step, step)
    return _add_nodes(context, body.segments, body.sections, extra[extra <= hi])


def _check_twist(
    turnout: Turnout, geometry: RailGeometry, segments: tuple[tuple[Segment, ...], ...]
) -> None:
    """The nose's twist to the track's inclination must begin after it is at full height."""
    c = geometry.crossing
    length = c.inclination_transition
    full = c.nose_tip + c.lowering_length
    for body in segments:
        for seg in body:
            if seg.kind == "nose" and length > 0.0 and seg.x_to - length < full - 1e-9:
                raise design_error(
                    design_source(turnout),
                    "wheel_rail.crossing.inclination_transition",
                    f"{length:g} m would begin the nose's twist at {seg.x_to - length:g} m, "
                    f"before the nose reaches full height at {full:g} m (its section ends at "
                    f"{seg.x_to:g} m)",
                )


def route_rail_bodies(turnout: Turnout, route: str) -> tuple[RailBody, ...]:
    """Every rail body of a route with its sections along x (side coordinates of its wheel).

    Parameters
    ----------
    turnout : Turnout
        A loaded turnout file with ``[wheel_rail]`` (optional) and ``sections`` in every
        ``[[routes.<route>.contacts]]`` entry.
    route : str
        Route name.

    Returns
    -------
    tuple of RailBody
        One per contact entry, in file order.

    Raises
    ------
    TurnoutFileError
        Bad ``[wheel_rail]`` or ``sections`` (see :func:`rail_geometry`,
        :func:`route_segments`).
    """
    geometry = rail_geometry(turnout)
    segments = route_segments(turnout, route)
    _check_twist(turnout, geometry, segments)
    pairs = load_route(turnout, route).pairs
    contexts: dict[bool, _Context] = {}
    grids = []
    for pair, body_segments in zip(pairs, segments):
        check = body_segments[0].kind == "check"
        if check not in contexts:
            contexts[check] = _context(geometry, check)
        grids.append(_body(contexts[check], body_segments, f"{route}: {pair.name}"))
    # two running rails under one wheel (stock rail and blade, wing rail and nose): nodes
    # where they share it, in both bodies' grids
    running = [i for i, seg in enumerate(segments) if seg[0].kind != "check"]
    for i in running:
        for j in running:
            if j <= i or pairs[i].wheel != pairs[j].wheel:
                continue
            kinds = {seg.kind for seg in segments[i] + segments[j]}
            if not kinds & set(_ENVELOPED):
                continue
            extra = _pair_transfer_nodes(
                contexts[False], segments[i], segments[j], (grids[i].x, grids[j].x)
            )
            grids[i] = _add_nodes(contexts[False], segments[i], grids[i], extra)
            grids[j] = _add_nodes(contexts[False], segments[j], grids[j], extra)
    bodies = []
    for pair, body_segments, sections in zip(pairs, segments, grids):
        check = body_segments[0].kind == "check"
        bodies.append(
            RailBody(
                name=pair.name,
                wheel=pair.wheel,
                rail=pair.rail,
                x_from=body_segments[0].x_from,
                x_to=body_segments[-1].x_to,
                sections=sections,
                back_of_flange=check,
                segments=body_segments,
                enveloped=any(seg.kind in _ENVELOPED for seg in body_segments),
            )
        )
    return tuple(bodies)


def body_table_settings(
    body: RailBody, geometry: RailGeometry, settings: TableSettings | None = None
) -> TableSettings:
    """Table settings of one body: shift range and search directions.

    Running rails: ``settings`` or :class:`.tables.TableSettings` defaults, +-12 mm at 0.2
    mm.  The S1002 flange meets a UIC60 1:40 gauge face at a +5.4 mm shift (standard gauge,
    1360 mm back to back), and the other wheel's flange stops the wheelset at -5.4 mm; +-12
    mm leaves 6 mm for elastic approach, rail displacement and a wheelset running at an
    angle on the diverging route's curve, where the outer wheel runs in flange contact.
    Check rails: the back of the flange meets the face at a shift of ``-clearance`` towards
    the track centre and, at the flared ends, ``-(clearance + flare_opening)``: the range is
    ``-(clearance + flare_opening + 6 mm)`` to +6 mm at 0.25 mm (125 shifts), searched along
    -70 deg (:data:`.geometry.CHECK_RAIL_DIRECTION`).

    Parameters
    ----------
    body : RailBody
        The body.
    geometry : RailGeometry
        Check-rail clearance and flares.
    settings : TableSettings, optional
        Base settings (default :class:`.tables.TableSettings`).

    Returns
    -------
    TableSettings
    """
    base = settings if settings is not None else TableSettings()
    if not body.back_of_flange:
        return base
    check = geometry.check_rail
    return replace(
        base,
        shift_min=-(check.clearance + check.flare_opening + 0.006),
        shift_max=0.006,
        shift_step=2.5e-4,
        directions=(CHECK_RAIL_DIRECTION,),
    )


def envelope_sections(
    body: RailBody,
    geometry: RailGeometry,
    wheel_radius: float,
    x: np.ndarray | None = None,
    cache: bool = False,
    cache_dir=None,
) -> SectionGrid:
    """What a rigid wheel feels on a body at its x nodes (:func:`.sections.wheel_envelope`).

    Parameters
    ----------
    body : RailBody
        The body.
    geometry : RailGeometry
        Envelope reach and step.
    wheel_radius : float
        m, nominal rolling radius.
    x : numpy.ndarray, optional
        m, some of the body's x nodes (default: all): the same values there, computed only
        there.
    cache : bool
        Keep the envelope in the table cache (:func:`.tables.cached_wheel_envelope`).
    cache_dir : str or Path, optional
        That cache's location (default :func:`.tables.default_cache_dir`).

    Returns
    -------
    SectionGrid
        The body's sections if it is not enveloped (constant in height along x), else their
        envelope with ``x_offset``.
    """
    if not body.enveloped or geometry.envelope_reach <= 0.0:
        if x is None:
            return body.sections
        return replace(body.sections, x=np.asarray(x, float), z=sections_at(body.sections, x))
    nodes = body.sections.x if x is None else np.asarray(x, float)
    if cache:
        return cached_wheel_envelope(
            body.sections,
            nodes,
            wheel_radius,
            geometry.envelope_reach,
            geometry.envelope_step,
            cache_dir,
        )
    return wheel_envelope(
        body.sections, nodes, wheel_radius, geometry.envelope_reach, geometry.envelope_step
    )


def route_contact_tables(
    turnout: Turnout,
    route: str,
    wheel: WheelGrid,
    setup: WheelsetSetup,
    settings: TableSettings | None = None,
    cache_dir=None,
) -> tuple[tuple[RailBody, ContactTable], ...]:
    """Contact tables of every rail body of a route, built or loaded from the disk cache.

    The table of a body is queried with the wheel's lateral shift towards its field side
    relative to the body, ``s (y_wheelset - y_rail_body)`` (s = +1 left, -1 right wheel, y
    to the left) and the lift of the wheel above the body.  The wheel's taping line is at
    ``setup.taping_line`` in side coordinates; the rails are the turnout's
    (:func:`rail_geometry`: gauge, inclination), so a wheelset's back-to-back distance that
    differs from ``[wheel_rail] back_to_back`` changes its check-rail clearance.

    Parameters
    ----------
    turnout : Turnout
        A loaded turnout file.
    route : str
        Route name.
    wheel : WheelGrid
        Gridded wheel, grid step ``[wheel_rail] grid_step``.
    setup : WheelsetSetup
        Wheelset dimensions (taping line, nominal radius for the envelope).
    settings : TableSettings, optional
        Base settings of running-rail tables (see :func:`body_table_settings`).
    cache_dir : str or Path, optional
        Table cache (default :func:`.tables.default_cache_dir`).

    Returns
    -------
    tuple
        ``(body, table)`` per body, in the route's contact order.

    Raises
    ------
    TurnoutFileError
        Bad geometry input (see :func:`route_rail_bodies`).
    ValueError
        The wheel's grid step is not the sections'.
    """
    geometry = rail_geometry(turnout)
    step = float(wheel.s[1] - wheel.s[0])
    if abs(step - geometry.grid_step) > 1e-12:
        raise ValueError(
            f"wheel grid step {step:g} m differs from [wheel_rail] grid_step "
            f"{geometry.grid_step:g} m"
        )
    out = []
    for body in route_rail_bodies(turnout, route):
        sections = envelope_sections(
            body, geometry, setup.nominal_radius, cache=True, cache_dir=cache_dir
        )
        table = build_contact_table(
            wheel,
            sections,
            setup.taping_line,
            body_table_settings(body, geometry, settings),
            cache_dir,
        )
        out.append((body, table))
    return tuple(out)
