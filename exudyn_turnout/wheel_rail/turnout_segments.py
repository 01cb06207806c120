"""The ``sections`` lists of a turnout file: which kind of rail section a wheel meets along x.

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

:func:`route_segments` reads and validates these lists into :class:`Segment` tuples; the
rail bodies' sections built from them are :mod:`.turnout_sections`, the design data the
kinds use :mod:`.turnout_design`.

Stage: may import :mod:`exudyn_turnout.inputs` and :mod:`exudyn_turnout.wheel_rail`; pure
Python.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from exudyn_turnout.inputs.geometry import TurnoutPlan, resolve_position, turnout_plan
from exudyn_turnout.inputs.routes import load_route
from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.wheel_rail.profiles import ProfileFormatError, read_slices
from exudyn_turnout.wheel_rail.turnout_design import (
    design_error,
    design_number,
    design_source,
    resolve_design_file,
)

__all__ = ["SEGMENT_KINDS", "Segment", "route_segments"]


#: Segment kinds of a ``sections`` list (see the module docstring).
SEGMENT_KINDS = ("plain", "closure", "stock", "blade", "wing", "nose", "check", "slices")


@dataclass(frozen=True)
class Segment:
    """One stretch of a rail body along x with one kind of cross-section."""

    kind: str  #: a kind of :data:`SEGMENT_KINDS`
    x_from: float  #: m, start along the through route
    x_to: float  #: m, end
    path: str = ""  #: slice file (``slices`` only)
    x0: float = 0.0  #: m, x of the slice set's u = 0 (``slices`` only)


def _position(src: str, name: str, value: Any, plan: TurnoutPlan | None) -> float:
    if isinstance(value, str):
        try:
            return resolve_position(value, plan)
        except ValueError as err:
            raise design_error(src, name, str(err)) from None
    return design_number(src, name, value, -1e4, 1e4)


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
    src = design_source(turnout)
    pairs = load_route(turnout, route).pairs
    raw_pairs = turnout.raw["routes"][route]["contacts"]
    plan = turnout_plan(turnout) if isinstance(turnout.raw.get("layout"), Mapping) else None
    out = []
    for i, (pair, raw) in enumerate(zip(pairs, raw_pairs)):
        p = f"routes.{route}.contacts[{i}].sections"
        items = raw.get("sections")
        if not isinstance(items, list) or not items:
            raise design_error(
                src, p, "must be a non-empty list of {kind, x} (the rail body along x)"
            )
        segments: list[Segment] = []
        for k, item in enumerate(items):
            f = f"{p}[{k}]"
            if not isinstance(item, Mapping):
                raise design_error(src, f, "must be a table {kind = ..., x = [x_from, x_to]}")
            unknown = set(item) - {"kind", "x", "file", "x0"}
            if unknown:
                raise design_error(
                    src, f, f"has unknown keys {sorted(unknown)} (kind, x, file, x0)"
                )
            kind = item.get("kind")
            if kind not in SEGMENT_KINDS:
                raise design_error(
                    src, f + ".kind", f"must be one of {', '.join(SEGMENT_KINDS)}, got {kind!r}"
                )
            xs = item.get("x")
            if not isinstance(xs, list) or len(xs) != 2:
                raise design_error(src, f + ".x", f"must be [x_from, x_to], got {xs!r}")
            a, b = (_position(src, f + ".x", v, plan) for v in xs)
            if not b > a:
                raise design_error(src, f + ".x", f"range is inverted: {a:g} >= {b:g}")
            if segments and abs(a - segments[-1].x_to) > 1e-9:
                raise design_error(
                    src,
                    f + ".x",
                    f"must start where the previous segment ends "
                    f"({segments[-1].x_to:g} m), got {a:g}",
                )
            path, x0 = "", 0.0
            if kind == "slices":
                name = item.get("file")
                if not isinstance(name, str) or not name:
                    raise design_error(src, f + ".file", "must name a CONTACT .slcs file")
                path = str(resolve_design_file(name, turnout.source))
                try:
                    read_slices(path)
                except ProfileFormatError as err:
                    raise design_error(src, f + ".file", str(err)) from None
                x0 = _position(src, f + ".x0", item.get("x0", 0.0), plan)
            segments.append(Segment(kind, a, b, path, x0))
        kinds = {seg.kind for seg in segments}
        if "check" in kinds and kinds != {"check"}:
            raise design_error(src, p, "mixes a check rail with running-rail kinds (one body each)")
        lo, hi = pair.x_range()
        if segments[0].x_from > lo + 1e-9 or segments[-1].x_to < hi - 1e-9:
            raise design_error(
                src,
                p,
                f"cover {segments[0].x_from:g}..{segments[-1].x_to:g} m, "
                f"not the contact's x range {lo:g}..{hi:g} m",
            )
        out.append(tuple(segments))
    return tuple(out)
