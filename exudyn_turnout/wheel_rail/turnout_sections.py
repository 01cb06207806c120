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
rail body that entry's wheel runs on, as a list of segments along x::

    sections = [{ kind = "plain", x = [-5.0, -1.0] }, { kind = "stock", x = [-1.0, 7.0] }]

Kinds (x of each segment a number or a plan feature expression, ``"nose_tip + 0.5"``;
the segments follow each other without gaps):

===========  ==============================================================================
``plain``    the full rail on the route's running line (gauge point at gauge / 2)
``closure``  the same (a closure rail is a full rail on the running line)
``stock``    switch stock rail moved to the field side by the setback ``set(x) + e x +
             x^2 / (2 R)`` (:func:`stock_setback`): the curve leaving the route, the entry
             angle, the stock-rail set ahead of the toe
``blade``    switch blade: full rail planed on its field side to the setback (head width
             ``min(setback, head_width)``, a rounded 76 deg planed face,
             :func:`blade_heights`), top lowered near the toe (:func:`blade_lowering`)
``wing``     wing rail: leaves the running line at 1:N from the throat (:func:`wing_flare`)
``nose``     crossing nose: two upright rail legs ``tip_width + (x - nose_tip) / N`` apart
             (:func:`.sections.nose_heights`), lowered near the tip, nothing before it;
             over the segment's last ``crossing.inclination_transition`` (2 m) the legs
             twist to the track's inclination (:func:`.sections.inclination_ramp`), so the
             section at its end is the plain rail's: no step where the plain rail after
             the crossing takes the wheel over
``check``    check rail (back-of-flange contact): an upright rail head whose face stands
             ``clearance(x)`` from the back of the flange of a centred wheelset, opened by
             the flares at the segment's ends (:func:`check_face`)
``slices``   a CONTACT slice set: ``file`` (relative to the turnout file, or a packaged
             name), ``x0`` the x of its u = 0; placed with the gauge point of its first slice
             at gauge / 2 and its highest point at z = 0, no inclination
===========  ==============================================================================

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
yaw in the curve (a table has no yaw, as for the through route).

x grid
------
A body's sections are computed on a non-uniform x grid with nodes only where the section
changes (:func:`section_nodes`): the design's break points, then bisection until linear
interpolation between nodes is within ``section_tolerance`` (normal distance, over the
part of the section a wheel can touch: per kind, down to 5 or 16 mm below its top) or the
step is ``min_step``, then nodes that their neighbours interpolate within the tolerance
are dropped; ``plain`` and ``closure`` keep their two ends.  Where a body begins
abruptly (a nose tip), nodes every ``min_step`` over ``envelope_reach`` before it let the
wheel's envelope (:func:`.sections.wheel_envelope`, applied by
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

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from exudyn_turnout.inputs.geometry import TurnoutPlan, resolve_position, turnout_plan
from exudyn_turnout.inputs.routes import load_route
from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.wheel_rail.geometry import (
    CHECK_RAIL_DIRECTION,
    WheelGrid,
    WheelsetSetup,
)
from exudyn_turnout.wheel_rail.profiles import (
    Profile,
    ProfileFormatError,
    read_slices,
)
from exudyn_turnout.wheel_rail.sections import (
    SectionGrid,
    SwitchDesign,
    gauge_point,
    inclination_ramp,
    lateral_grid,
    nose_heights,
    sections_at,
    slice_sections,
    surface_on_grid,
    wheel_envelope,
)
from exudyn_turnout.wheel_rail.tables import (
    ContactTable,
    TableSettings,
    build_contact_table,
)
from exudyn_turnout.wheel_rail.turnout_design import (
    RailGeometry,
    _fail,
    _number,
    _placed,
    _rail_profile,
    _resolve_file,
    _src,
    _throat,
    blade_heights,
    blade_lowering,
    check_face,
    rail_geometry,
    stock_setback,
    wing_flare,
)

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
]


#: Segment kinds of a ``sections`` list (see the module docstring).
SEGMENT_KINDS = ("plain", "closure", "stock", "blade", "wing", "nose", "check", "slices")


_ENVELOPED = ("blade", "wing", "nose", "slices")  # kinds whose height or edge changes fast


_CONSTANT = ("plain", "closure")


#: m, depth below its top above which a point of a section counts for the x grid (a wheel
#: touches a rail above ~15 mm below its top; the flange root sits 10-14 mm below the tread)
_TOUCHABLE = -0.016


#: m, per kind, the depth below the top above which a section's change counts for the x
#: grid: the stock rail's gauge face is behind the blade and the wing rail's and the nose's
#: field-side faces are under the tread (only their tops and corners are touched); the
#: blade's planed edge, the gauge faces (flange contact) and a check rail's face (back of
#: the flange) count down to the flange root
_DEPTH = {"stock": -0.005, "wing": -0.005, "nose": -0.005}


#: a rail edge that moves (the blade's planed field side, which lies against the stock
#: rail's gauge face) may move 5x the tolerance between nodes: with 0.2 mm, 2 mm, so the
#: blend of two nodes lacks a strip at most 1 mm wide next to the stock rail's face
_EDGE_FACTOR = 5.0


#: per kind, factor on ``section_tolerance``: a check rail's face moves at its flares
#: (1:67) and the back of the flange meets a flare only 4-19 mm off centre, so 0.5 mm there
#: (1 mm lateral steps) instead of ~80 nodes on a 6.7 m check rail; the nose's top near its
#: tip is where the wheel lands on it: half the tolerance from the tip to full height (the
#: dip's rising slope moved by 10 % between 0.2 and 0.1 mm, for 8 more nodes), the common
#: one behind it (:func:`_tolerance_pieces`)
_TOLERANCE_FACTOR = {"check": 2.5, "nose": 0.5}


#: m, initial node spacing before bisection (no break point of a design is closer)
_MAX_STEP = 0.5


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


@dataclass(frozen=True)
class Segment:
    """One stretch of a rail body along x with one kind of cross-section."""

    kind: str  #: a kind of :data:`SEGMENT_KINDS`
    x_from: float  #: m, start along the through route
    x_to: float  #: m, end
    path: str = ""  #: slice file (``slices`` only)
    x0: float = 0.0  #: m, x of the slice set's u = 0 (``slices`` only)


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
    slices: dict  #: path -> SectionGrid of the slice set (side coordinates)
    raw: Profile  #: the profile as read (placed at other inclinations by the nose's twist)
    upright_heights: np.ndarray  #: the upright rail on ``y``


def _context(geometry: RailGeometry, check: bool) -> _Context:
    half = geometry.half_gauge
    low = half - (0.19 if check else 0.0775)
    y = lateral_grid(low, half + 0.1225, geometry.grid_step)
    raw = _rail_profile(geometry)
    base = _placed(geometry, geometry.inclination, raw)
    upright = _placed(geometry, 0.0, raw)
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


def _slice_grid(context: _Context, segment: Segment) -> SectionGrid:
    if segment.path not in context.slices:
        slices = read_slices(segment.path)
        first = slices.profiles[0]
        top = float(np.max(first.z))
        g = context.geometry
        dy = g.half_gauge - gauge_point(replace(first, z=first.z - top), g.gauge_depth)
        grid = slice_sections(slices, context.y, y_offset=dy, z_offset=-top)
        context.slices[segment.path] = replace(grid, x=grid.x + segment.x0)
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
    return sections_at(_slice_grid(context, segment), np.array([x]))[0]


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
        leg = surface_on_grid(_placed(g, tilt, context.raw), y)
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
        points += [float(v) for v in np.linspace(_throat(c), end, n + 1)]
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
        points += list(_slice_grid(context, segment).x)
    return sorted({p for p in points if segment.x_from <= p <= segment.x_to})


def _solve_width(design: SwitchDesign, width: float) -> float:
    """x >= 0 where the setback reaches ``width`` (positive root of the quadratic)."""
    a, b, c = 1.0 / (2.0 * design.radius), design.entry_tangent, design.toe_width - width
    return max(0.0, (-b + math.sqrt(b * b - 4.0 * a * c)) / (2.0 * a))


def _linear_error(
    za: np.ndarray,
    zm: np.ndarray,
    zb: np.ndarray,
    t,
    region: slice,
    step: float,
    depth: float = _TOUCHABLE,
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
    depth: float = _TOUCHABLE,
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


def _position(src: str, name: str, value: Any, plan: TurnoutPlan | None) -> float:
    if isinstance(value, str):
        try:
            return resolve_position(value, plan)
        except ValueError as err:
            raise _fail(src, name, str(err)) from None
    return _number(src, name, value, -1e4, 1e4)


def route_segments(turnout: Turnout, route: str) -> tuple[tuple[Segment, ...], ...]:
    """The ``sections`` lists of a route's contact entries, validated.

    Parameters
    ----------
    turnout : Turnout
        A loaded turnout file.
    route : str
        Route name (a ``[routes.<name>]`` key).

    Returns
    -------
    tuple
        Per contact entry (file order), its segments in increasing x.

    Raises
    ------
    TurnoutFileError
        A missing or malformed ``sections`` list, an unknown kind, segments with gaps or
        overlaps, segments that do not cover the entry's x range, a check segment mixed with
        running-rail kinds, a slice file that cannot be read.
    """
    src = _src(turnout)
    pairs = load_route(turnout, route).pairs
    raw_pairs = turnout.raw["routes"][route]["contacts"]
    plan = turnout_plan(turnout) if isinstance(turnout.raw.get("layout"), Mapping) else None
    out = []
    for i, (pair, raw) in enumerate(zip(pairs, raw_pairs)):
        p = f"routes.{route}.contacts[{i}].sections"
        items = raw.get("sections")
        if not isinstance(items, list) or not items:
            raise _fail(src, p, "must be a non-empty list of {kind, x} (the rail body along x)")
        segments: list[Segment] = []
        for k, item in enumerate(items):
            f = f"{p}[{k}]"
            if not isinstance(item, Mapping):
                raise _fail(src, f, "must be a table {kind = ..., x = [x_from, x_to]}")
            unknown = set(item) - {"kind", "x", "file", "x0"}
            if unknown:
                raise _fail(src, f, f"has unknown keys {sorted(unknown)} (kind, x, file, x0)")
            kind = item.get("kind")
            if kind not in SEGMENT_KINDS:
                raise _fail(
                    src, f + ".kind", f"must be one of {', '.join(SEGMENT_KINDS)}, got {kind!r}"
                )
            xs = item.get("x")
            if not isinstance(xs, list) or len(xs) != 2:
                raise _fail(src, f + ".x", f"must be [x_from, x_to], got {xs!r}")
            a, b = (_position(src, f + ".x", v, plan) for v in xs)
            if not b > a:
                raise _fail(src, f + ".x", f"range is inverted: {a:g} >= {b:g}")
            if segments and abs(a - segments[-1].x_to) > 1e-9:
                raise _fail(
                    src,
                    f + ".x",
                    f"must start where the previous segment ends "
                    f"({segments[-1].x_to:g} m), got {a:g}",
                )
            path, x0 = "", 0.0
            if kind == "slices":
                name = item.get("file")
                if not isinstance(name, str) or not name:
                    raise _fail(src, f + ".file", "must name a CONTACT .slcs file")
                path = str(_resolve_file(name, turnout.source))
                try:
                    read_slices(path)
                except ProfileFormatError as err:
                    raise _fail(src, f + ".file", str(err)) from None
                x0 = _position(src, f + ".x0", item.get("x0", 0.0), plan)
            segments.append(Segment(kind, a, b, path, x0))
        kinds = {seg.kind for seg in segments}
        if "check" in kinds and kinds != {"check"}:
            raise _fail(src, p, "mixes a check rail with running-rail kinds (one body each)")
        lo, hi = pair.x_range()
        if segments[0].x_from > lo + 1e-9 or segments[-1].x_to < hi - 1e-9:
            raise _fail(
                src,
                p,
                f"cover {segments[0].x_from:g}..{segments[-1].x_to:g} m, "
                f"not the contact's x range {lo:g}..{hi:g} m",
            )
        out.append(tuple(segments))
    return tuple(out)


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
    present = np.any(z[:, region] > _TOUCHABLE, axis=1)
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
            _DEPTH.get(segment.kind, _TOUCHABLE),
        )
        if xs:  # the shared node once
            x, z = x[1:], z[1:]
        xs.append(x)
        zs.append(z)
    return np.concatenate(xs), np.concatenate(zs)


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
                raise _fail(
                    _src(turnout),
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
    bodies = []
    for pair, body_segments in zip(pairs, segments):
        check = body_segments[0].kind == "check"
        if check not in contexts:
            contexts[check] = _context(geometry, check)
        sections = _body(contexts[check], body_segments, f"{route}: {pair.name}")
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
    body: RailBody, geometry: RailGeometry, wheel_radius: float, x: np.ndarray | None = None
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
    return wheel_envelope(
        body.sections,
        body.sections.x if x is None else np.asarray(x, float),
        wheel_radius,
        geometry.envelope_reach,
        geometry.envelope_step,
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
        sections = envelope_sections(body, geometry, setup.nominal_radius)
        table = build_contact_table(
            wheel,
            sections,
            setup.taping_line,
            body_table_settings(body, geometry, settings),
            cache_dir,
        )
        out.append((body, table))
    return tuple(out)
