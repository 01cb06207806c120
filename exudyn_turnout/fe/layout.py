"""Turnout layout for the FE reference model: rails, their paths, tracks, rail slots.

Read from the ``[layout]`` section of a turnout file (see the comments there for the
UIC60-760-1:15 geometry and its sources). A rail follows a route centreline at a lateral
offset (y positive to the left, through-route centreline y = 0); it is a chain of
segments, each of a Table 1 rail type, welded end to end; a rail may start or end on
another rail (a rigid joint, the crossing). Sleepers belong to tracks: the turnout's
bearers (length from ``[sleeper].length``, centred between the outermost rails they
carry) or a track of its own sleepers (e.g. the diverging track after the crossing).
``slots`` maps the co-running rail slots r1..r4 of each route to rails along x.

Errors in the section raise :class:`~exudyn_turnout.inputs.turnout.TurnoutFileError` naming
the file and the field, e.g. ``uic60.toml: layout.rails[3].route must be one of
through, diverging, got 'divergent'``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from numpy.typing import ArrayLike

from exudyn_turnout.inputs.geometry import Centreline, load_centrelines
from exudyn_turnout.inputs.turnout import RAIL_SLOTS, Turnout, TurnoutFileError

__all__ = [
    "TURNOUT_TRACK",
    "Route",
    "Segment",
    "LayoutRail",
    "Track",
    "SlotRange",
    "FitRange",
    "Layout",
    "load_layout",
    "plain_track_layout",
    "single_rail_layout",
]

#: Name of the track whose sleepers are the turnout's bearers.
TURNOUT_TRACK = "turnout"


#: A route centreline (the plan geometry lives in :mod:`exudyn_turnout.inputs.geometry`).
Route = Centreline


@dataclass(frozen=True)
class Segment:
    """A piece of rail of one rail type (Table 1) on one track's sleepers."""

    rail_type: str  #: name in Turnout.rail_types
    x_from: float  #: m
    x_to: float  #: m
    track: str = TURNOUT_TRACK  #: the track whose sleepers carry it


@dataclass(frozen=True)
class LayoutRail:
    """One continuous rail: segments welded end to end along a route at an offset."""

    id: str  #: short name used in CSV files and the API
    name: str  #: description
    route: str  #: route name
    offset: float  #: m, lateral offset from the route centreline (left positive)
    segments: tuple[Segment, ...]  #: in increasing x, each starting where the last ends
    start_joins: str | None = None  #: rail whose node the first node is
    end_joins: str | None = None  #: rail whose node the last node is

    @property
    def x_from(self) -> float:
        """Where the rail starts (m): the first segment's start."""
        return self.segments[0].x_from

    @property
    def x_to(self) -> float:
        """Where the rail ends (m): the last segment's end."""
        return self.segments[-1].x_to

    def segment_at(self, x: float) -> Segment:
        """The segment containing a position (the later one on a boundary).

        Parameters
        ----------
        x : float
            Position from the switch toe (m).

        Returns
        -------
        Segment
            The segment with x_from <= x <= x_to.

        Raises
        ------
        ValueError
            x is not on the rail.
        """
        for segment in reversed(self.segments):
            if segment.x_from <= x <= segment.x_to:
                return segment
        raise ValueError(
            f"x = {x:g} m is not on rail {self.id} ({self.x_from:g} m to {self.x_to:g} m)"
        )


@dataclass(frozen=True)
class Track:
    """Sleepers of a track: turnout bearers (length None: from the sleeper table) or own."""

    name: str  #: key in Layout.tracks
    route: str  #: centreline of own sleepers
    sleeper_length: float | None  #: m; None: ``[sleeper].length(x)``, centred between the rails


@dataclass(frozen=True)
class SlotRange:
    """The rail that fills a co-running slot (r1..r4) over an x range."""

    rail: str  #: rail id
    x_from: float  #: m
    x_to: float  #: m


@dataclass(frozen=True)
class FitRange:
    """Which rail and x range a stiffness polynomial is fitted on."""

    rail: str  #: rail id
    x_min: float  #: m
    x_max: float  #: m


@dataclass(frozen=True)
class Layout:
    """Geometry of the FE reference model (SI units)."""

    source: str  #: file name, for messages
    x_start: float  #: m, first x of the turnout proper
    x_end: float  #: m, last x
    sleeper_x0: float  #: m, a sleeper at sleeper_x0 + i L_s
    routes: Mapping[str, Route]  #: centrelines by name
    tracks: Mapping[str, Track]  #: tracks by name, the turnout's bearers included
    rails: tuple[LayoutRail, ...]  #: every rail of the model
    slots: Mapping[str, Mapping[str, tuple[SlotRange, ...]]]  #: route -> slot -> ranges
    fits: Mapping[str, FitRange]  #: "K_sw" (Eq 10 analogue), "K_sh" (Eq 14 analogue)
    bearer_shear_coefficient: float = 5.0 / 6.0  #: kappa of the sleeper (-)
    bearer_poisson: float = 0.2  #: nu of the sleeper concrete (-)
    min_overhang: float = 0.2  #: m, bearer length beyond the outermost rail it carries

    def rail(self, rail_id: str) -> LayoutRail:
        """A rail by its id.

        Parameters
        ----------
        rail_id : str
            Layout rail id, e.g. ``"straight"``.

        Returns
        -------
        LayoutRail
            The rail.

        Raises
        ------
        KeyError
            No rail has that id; the message lists the ids.
        """
        for layout_rail in self.rails:
            if layout_rail.id == rail_id:
                return layout_rail
        rail_ids = ", ".join(layout_rail.id for layout_rail in self.rails)
        raise KeyError(f"rail {rail_id!r} is not in the layout (rails: {rail_ids})")

    def rail_y(self, rail_id: str, x: ArrayLike) -> Any:
        """Lateral position of a rail.

        Parameters
        ----------
        rail_id : str
            Layout rail id.
        x : float or array_like
            Position(s) from the switch toe (m).

        Returns
        -------
        float or numpy.ndarray
            Lateral position y (m, left positive), of the shape of x.
        """
        layout_rail = self.rail(rail_id)
        return self.routes[layout_rail.route].y(x, layout_rail.offset)

    def slot_rail(self, slot: str, x: float, route: str = "through") -> str:
        """Id of the rail in a co-running slot at a position.

        Parameters
        ----------
        slot : str
            Co-running rail slot, ``"r1"`` to ``"r4"``.
        x : float
            Position from the switch toe (m), inside the layout.
        route : str
            Route whose slot table is used (``"through"``, ``"diverging"``...).

        Returns
        -------
        str
            Layout rail id.

        Raises
        ------
        ValueError
            Unknown route, x outside the layout, or no rail in the slot at x (the message
            says where the slot has a rail).
        """
        if route not in self.slots:
            raise ValueError(f"route must be one of {', '.join(self.slots)}, got {route!r}")
        if not self.x_start <= x <= self.x_end:
            raise ValueError(
                f"x = {x:g} m is outside the FE model of the turnout "
                f"({self.x_start:g} m to {self.x_end:g} m)"
            )
        ranges = self.slots[route].get(slot, ())
        for slot_range in ranges:
            if slot_range.x_from <= x <= slot_range.x_to:
                return slot_range.rail
        where = ", ".join(f"{r.x_from:g} to {r.x_to:g} m" for r in ranges) or "nowhere"
        raise ValueError(
            f"rail {slot} is not present at x = {x:g} m on the {route} route (it is at {where})"
        )


def _fail(src: str, field: str, problem: str) -> TurnoutFileError:
    return TurnoutFileError(f"{src}: {field} {problem}")


def _get(src: str, data: Mapping[str, Any], field: str, path: str, default: Any = ...) -> Any:
    if not isinstance(data, Mapping) or path not in data:
        if default is not ...:
            return default
        raise _fail(src, field, "is missing")
    return data[path]


def _number(src: str, field: str, value: Any, positive: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise _fail(src, field, f"must be a finite number, got {value!r}")
    if positive and value <= 0:
        raise _fail(src, field, f"must be > 0, got {value:g}")
    return float(value)


def _interval(src: str, field: str, value: Any) -> tuple[float, float]:
    if not isinstance(value, list) or len(value) != 2:
        raise _fail(src, field, f"must be [x_from, x_to] in metres, got {value!r}")
    a, b = (_number(src, field, v) for v in value)
    if not b > a:
        raise _fail(src, field, f"must have x_from < x_to, got [{a:g}, {b:g}]")
    return a, b


def _routes(turnout: Turnout) -> dict[str, Route]:
    return load_centrelines(turnout)


def _segments(
    src: str, p: str, raw: Any, turnout: Turnout, tracks: Mapping[str, Track]
) -> tuple[Segment, ...]:
    if not isinstance(raw, list) or not raw:
        raise _fail(src, p, "must be a non-empty list of {type = ..., x = [x_from, x_to]}")
    out: list[Segment] = []
    for i, spec in enumerate(raw):
        field = f"{p}[{i + 1}]"
        rail_type = _get(src, spec, field + ".type", "type")
        if rail_type not in turnout.rail_types:
            raise _fail(
                src,
                field + ".type",
                f"names rail type {rail_type!r}, which is not defined "
                f"(types: {', '.join(turnout.rail_types)})",
            )
        x_from, x_to = _interval(src, field + ".x", _get(src, spec, field + ".x", "x"))
        track = _get(src, spec, field + ".track", "track", TURNOUT_TRACK)
        if track not in tracks:
            raise _fail(
                src,
                field + ".track",
                f"names track {track!r}, which is not defined (tracks: {', '.join(tracks)})",
            )
        if out and abs(out[-1].x_to - x_from) > 1e-9:
            raise _fail(
                src,
                field + ".x",
                f"must start where the previous segment ends ({out[-1].x_to:g} m), got {x_from:g}",
            )
        out.append(Segment(rail_type, x_from, x_to, track))
    return tuple(out)


def _rails(
    src: str, sec: Mapping[str, Any], turnout: Turnout, routes, tracks
) -> tuple[LayoutRail, ...]:
    raw = _get(src, sec, "layout.rails", "rails")
    if not isinstance(raw, list) or not raw:
        raise _fail(src, "layout.rails", "must be a non-empty list of [[layout.rails]] tables")
    rails: list[LayoutRail] = []
    for i, r in enumerate(raw):
        p = f"layout.rails[{i + 1}]"
        rid = _get(src, r, p + ".id", "id")
        if not isinstance(rid, str) or not rid or any(c in rid for c in " ,"):
            raise _fail(
                src, p + ".id", f"must be a short name without spaces or commas, got {rid!r}"
            )
        if rid in [q.id for q in rails]:
            raise _fail(src, p + ".id", f"{rid!r} is used twice")
        route = _get(src, r, p + ".route", "route")
        if route not in routes:
            raise _fail(src, p + ".route", f"must be one of {', '.join(routes)}, got {route!r}")
        segments = _segments(
            src, p + ".segments", _get(src, r, p + ".segments", "segments"), turnout, tracks
        )
        rails.append(
            LayoutRail(
                rid,
                str(_get(src, r, p + ".name", "name", rid)),
                route,
                _number(src, p + ".offset", _get(src, r, p + ".offset", "offset")),
                segments,
                _get(src, r, p + ".start_joins", "start_joins", None),
                _get(src, r, p + ".end_joins", "end_joins", None),
            )
        )
    _check_joins(src, rails)
    return tuple(rails)


def _check_joins(src: str, rails: list[LayoutRail]) -> None:
    by_id = {rail.id: rail for rail in rails}
    for i, rail in enumerate(rails):
        for key, x in (("start_joins", rail.x_from), ("end_joins", rail.x_to)):
            target = getattr(rail, key)
            if target is None:
                continue
            field = f"layout.rails[{i + 1}].{key}"
            if target not in by_id or target == rail.id:
                raise _fail(src, field, f"must name another rail, got {target!r}")
            joined = by_id[target]
            if not joined.x_from <= x <= joined.x_to:
                raise _fail(
                    src,
                    field,
                    f"joins rail {target!r} at x = {x:g} m, outside it "
                    f"({joined.x_from:g} to {joined.x_to:g} m)",
                )


def _tracks(src: str, sec: Mapping[str, Any], routes) -> dict[str, Track]:
    tracks = {TURNOUT_TRACK: Track(TURNOUT_TRACK, "through", None)}
    raw = _get(src, sec, "layout.tracks", "tracks", {})
    if not isinstance(raw, Mapping):
        raise _fail(src, "layout.tracks", "must be a table of [layout.tracks.<name>] tables")
    for name, t in raw.items():
        p = f"layout.tracks.{name}"
        route = _get(src, t, p + ".route", "route")
        if route not in routes:
            raise _fail(src, p + ".route", f"must be one of {', '.join(routes)}, got {route!r}")
        L = _number(
            src,
            p + ".sleeper_length",
            _get(src, t, p + ".sleeper_length", "sleeper_length"),
            positive=True,
        )
        tracks[name] = Track(name, route, L)
    return tracks


def _slots(
    src: str,
    sec: Mapping[str, Any],
    rails: tuple[LayoutRail, ...],
    routes,
    route_names: tuple[str, ...] = (),
) -> dict:
    """Slot tables per route, keyed by the file's routes ([routes.<name>]) or a centreline."""
    routes = tuple(route_names) + tuple(r for r in routes if r not in route_names)
    raw = _get(src, sec, "layout.slots", "slots")
    if not isinstance(raw, Mapping) or not all(isinstance(t, Mapping) for t in raw.values()):
        raise _fail(
            src, "layout.slots", "must be tables [layout.slots.<route>] of slot = [{rail, x}, ...]"
        )
    by_id = {r.id: r for r in rails}
    out: dict[str, dict[str, tuple[SlotRange, ...]]] = {}
    for route, table in raw.items():
        if route not in routes:
            raise _fail(
                src,
                f"layout.slots.{route}",
                f"names route {route!r}; routes are {', '.join(routes)}",
            )
        out[route] = {}
        for slot, ranges in table.items():
            p = f"layout.slots.{route}.{slot}"
            if slot not in RAIL_SLOTS:
                raise _fail(src, p, f"names rail slot {slot!r}; slots are {', '.join(RAIL_SLOTS)}")
            if not isinstance(ranges, list):
                raise _fail(src, p, "must be a list of {rail = ..., x = [x_from, x_to]}")
            items = []
            for i, rng in enumerate(ranges):
                f = f"{p}[{i + 1}]"
                rid = _get(src, rng, f + ".rail", "rail")
                if rid not in by_id:
                    raise _fail(
                        src, f + ".rail", f"names rail {rid!r}, which is not in layout.rails"
                    )
                a, b = _interval(src, f + ".x", _get(src, rng, f + ".x", "x"))
                if a < by_id[rid].x_from - 1e-9 or b > by_id[rid].x_to + 1e-9:
                    raise _fail(
                        src,
                        f + ".x",
                        f"[{a:g}, {b:g}] is not within rail {rid!r} "
                        f"({by_id[rid].x_from:g} to {by_id[rid].x_to:g} m)",
                    )
                items.append(SlotRange(rid, a, b))
            out[route][slot] = tuple(items)
    return out


def _route_names(turnout: Turnout) -> tuple[str, ...]:
    routes = turnout.raw.get("routes")
    return tuple(routes) if isinstance(routes, Mapping) else ()


def _fits(src: str, sec: Mapping[str, Any], rails: tuple[LayoutRail, ...]) -> dict[str, FitRange]:
    raw = _get(src, sec, "layout.fits", "fits")
    by_id = {r.id: r for r in rails}
    out = {}
    for key in ("K_sw", "K_sh"):
        p = f"layout.fits.{key}"
        spec = _get(src, raw, p, key)
        rid = _get(src, spec, p + ".rail", "rail")
        if rid not in by_id:
            raise _fail(src, p + ".rail", f"names rail {rid!r}, which is not in layout.rails")
        a, b = _interval(src, p + ".x", _get(src, spec, p + ".x", "x"))
        out[key] = FitRange(rid, a, b)
    return out


def load_layout(turnout: Turnout) -> Layout:
    """The ``[layout]`` section of a turnout file as a :class:`Layout`.

    Parameters
    ----------
    turnout : Turnout
        A turnout loaded from a file with a ``[layout]`` section.

    Returns
    -------
    Layout
        Routes, tracks, rails, slot tables and fit ranges of the FE model.

    Raises
    ------
    TurnoutFileError
        The section is missing or a field is wrong; the message names file and field.
    """
    src = Path(turnout.source).name
    sec = turnout.raw.get("layout")
    if not isinstance(sec, Mapping):
        raise _fail(src, "layout", "is missing (the FE model needs the turnout's geometry)")
    x0 = _number(src, "layout.x_start", _get(src, sec, "layout.x_start", "x_start"))
    x1 = _number(src, "layout.x_end", _get(src, sec, "layout.x_end", "x_end"))
    if not x1 > x0:
        raise _fail(src, "layout.x_end", f"must be > x_start = {x0:g}, got {x1:g}")
    routes = _routes(turnout)
    tracks = _tracks(src, sec, routes)
    rails = _rails(src, sec, turnout, routes, tracks)
    fits = _fits(src, sec, rails)
    b = _get(src, sec, "layout.bearers", "bearers")
    kappa = _number(
        src,
        "layout.bearers.shear_coefficient",
        _get(src, b, "layout.bearers.shear_coefficient", "shear_coefficient"),
        positive=True,
    )
    nu = _number(src, "layout.bearers.poisson", _get(src, b, "layout.bearers.poisson", "poisson"))
    if not 0 <= nu < 0.5:
        raise _fail(src, "layout.bearers.poisson", f"must be in [0, 0.5), got {nu:g}")
    overhang = _number(
        src,
        "layout.bearers.min_overhang",
        _get(src, b, "layout.bearers.min_overhang", "min_overhang", 0.2),
    )
    return Layout(
        src,
        x0,
        x1,
        _number(src, "layout.sleeper_x0", _get(src, sec, "layout.sleeper_x0", "sleeper_x0")),
        routes,
        tracks,
        rails,
        _slots(src, sec, rails, routes, _route_names(turnout)),
        fits,
        kappa,
        nu,
        overhang,
    )


def plain_track_layout(
    rail_type: str = "stock",
    length: float = 6.0,
    rail_spacing: float = 1.5,
    sleeper_length: float = 2.5,
    sleeper_x0: float = 0.0,
) -> Layout:
    """Plain track: two straight rails of one type on sleepers of one length.

    Parameters
    ----------
    rail_type : str
        Rail type of the turnout's Table 1 for both rails.
    length : float
        m, x range [-length/2, length/2] of the layout (the FE options add plain-track
        extensions beyond it).
    rail_spacing : float
        m, distance of the rail-head centres; rails at y = +-rail_spacing / 2.
    sleeper_length : float
        m, length of every sleeper.
    sleeper_x0 : float
        m, a sleeper at x = sleeper_x0 + i L_s (x = 0 above a sleeper by default).

    Returns
    -------
    Layout
        Rails ``"left"`` (slot r4) and ``"right"`` (slot r1) on the through route.
    """
    half = length / 2.0
    tracks = {TURNOUT_TRACK: Track(TURNOUT_TRACK, "through", sleeper_length)}
    rails = tuple(
        LayoutRail(rail_id, rail_id, "through", y, (Segment(rail_type, -half, half),))
        for rail_id, y in (("left", rail_spacing / 2), ("right", -rail_spacing / 2))
    )
    slots = {
        "through": {
            "r1": (SlotRange("right", -half, half),),
            "r4": (SlotRange("left", -half, half),),
        }
    }
    fits = {"K_sw": FitRange("right", -half, half), "K_sh": FitRange("right", -half, half)}
    return Layout(
        "plain track",
        -half,
        half,
        sleeper_x0,
        {"through": Route("through", 0.0)},
        tracks,
        rails,
        slots,
        fits,
    )


def single_rail_layout(
    rail_type: str = "stock",
    length: float = 6.0,
    sleeper_length: float = 2.5,
    sleeper_x0: float = 0.0,
) -> Layout:
    """One straight rail centred on sleepers of one length: the FE analogue of one rail on
    its smeared support (each sleeper carries this rail only, as in Eq 13).

    Parameters
    ----------
    rail_type : str
        Rail type of the turnout's Table 1.
    length : float
        m, x range [-length/2, length/2] of the layout.
    sleeper_length : float
        m, length of every sleeper.
    sleeper_x0 : float
        m, a sleeper at x = sleeper_x0 + i L_s.

    Returns
    -------
    Layout
        Rail ``"rail"`` (slot r1) on the through route at y = 0.
    """
    half = length / 2.0
    tracks = {TURNOUT_TRACK: Track(TURNOUT_TRACK, "through", sleeper_length)}
    rails = (LayoutRail("rail", "rail", "through", 0.0, (Segment(rail_type, -half, half),)),)
    slots = {"through": {"r1": (SlotRange("rail", -half, half),)}}
    fits = {"K_sw": FitRange("rail", -half, half), "K_sh": FitRange("rail", -half, half)}
    return Layout(
        "single rail",
        -half,
        half,
        sleeper_x0,
        {"through": Route("through", 0.0)},
        tracks,
        rails,
        slots,
        fits,
    )
