"""Load transfer, dips and hand-overs of a route's rail bodies, from geometry alone.

:func:`route_transfers`: where the load passes from stock rail to blade and from wing rail to
nose for a rigid wheel at several lateral shifts, and the dip its path falls into
(:func:`.transfer.two_rail_paths`, :func:`.transfer.dip_summary`). :func:`handover_points`,
:func:`rest_path` and :func:`table_rest_path`: the wheel's rigid rest height over all its
bodies around the places where one body or segment ends and the next begins, from the
sections or as the passage reads the tables (no step there in the packaged turnouts,
``tests/test_turnout_sections.py``).

Stage: may import :mod:`exudyn_turnout.inputs` and :mod:`exudyn_turnout.wheel_rail`; pure
numpy.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.wheel_rail.geometry import (
    WheelGrid,
    WheelsetSetup,
    prepare_rail,
    prepare_wheel,
    search_candidates_batch,
    surface_derivatives,
)
from exudyn_turnout.wheel_rail.sections import (
    SectionGrid,
    sections_at,
    wheel_envelope,
)
from exudyn_turnout.wheel_rail.tables import (
    lookup_values,
)
from exudyn_turnout.wheel_rail.transfer import dip_summary, two_rail_paths
from exudyn_turnout.wheel_rail.turnout_design import RailGeometry, rail_geometry
from exudyn_turnout.wheel_rail.turnout_sections import RailBody, route_rail_bodies

__all__ = [
    "DIP_BASELINE",
    "Transfer",
    "route_transfers",
    "RestPath",
    "handover_points",
    "handover_windows",
    "rest_path",
    "table_rest_path",
]


#: m, baseline of the dip's slopes (:func:`.transfer.dip_summary`): 20 mm, as
#: :func:`exudyn_turnout.inputs.routes.dip_angle` takes for the height tables
DIP_BASELINE = 0.02


@dataclass(frozen=True, eq=False)
class Transfer:
    """Load transfer between two rail bodies of a route for several lateral shifts."""

    route: str  #: route name
    place: str  #: "switch" (stock rail -> blade) or "crossing" (wing rail -> nose)
    wheel: str  #: "left" | "right"
    first: str  #: name of the body the load comes from
    second: str  #: name of the body it passes to
    paths: tuple  #: :class:`.transfer.WheelPath` per shift
    summaries: tuple  #: :class:`.transfer.DipSummary` per shift


def _body_with(bodies: tuple[RailBody, ...], kind: str, wheel: str) -> RailBody | None:
    for body in bodies:
        if body.wheel == wheel and any(seg.kind == kind for seg in body.segments):
            return body
    return None


def _sections_on(
    body: RailBody, x: np.ndarray, geometry: RailGeometry, radius: float
) -> SectionGrid:
    """A body's sections at x: enveloped if the body is, else interpolated."""
    if body.enveloped and geometry.envelope_reach > 0.0:
        return wheel_envelope(
            body.sections, x, radius, geometry.envelope_reach, geometry.envelope_step
        )
    return SectionGrid(x=x, y=body.sections.y, z=sections_at(body.sections, x), name=body.name)


def route_transfers(
    turnout: Turnout,
    route: str,
    wheel: WheelGrid,
    setup: WheelsetSetup,
    shifts: tuple = (-0.003, 0.0, 0.003),
    step: float = 0.005,
    bodies: tuple[RailBody, ...] | None = None,
    x_ranges: Mapping[str, tuple[float, float]] | None = None,
) -> tuple[Transfer, ...]:
    """Where the load passes from stock rail to blade and from wing rail to nose, and the dip.

    For each wheel of the route that has a ``stock`` and a ``blade`` body (switch), or a
    ``wing`` and a ``nose`` body (crossing): the rigid-contact path of the wheel over both
    bodies' envelopes (:func:`envelope_sections`, :func:`.transfer.two_rail_path`) at each
    lateral shift, and its :func:`.transfer.dip_summary` (slopes over
    :data:`DIP_BASELINE`).  x ranges: the switch from 0.5 m before the toe to where the
    stock rail's body ends; the crossing from 1 m before to 1.5 m after the nose tip.

    Parameters
    ----------
    turnout : Turnout
        A loaded turnout file.
    route : str
        Route name.
    wheel : WheelGrid
        Gridded wheel.
    setup : WheelsetSetup
        Taping line and nominal radius.
    shifts : tuple of float
        m, lateral shifts of the wheel towards its field side (a wheelset offset y to the
        left is a shift +y of the left wheel and -y of the right one).
    step : float
        m, x step of the path.
    bodies : tuple of RailBody, optional
        The route's bodies (default :func:`route_rail_bodies`).
    x_ranges : mapping, optional
        ``{"switch": (x_from, x_to), "crossing": (...)}``: other x ranges (m).

    Returns
    -------
    tuple of Transfer
    """
    geometry = rail_geometry(turnout)
    bodies = route_rail_bodies(turnout, route) if bodies is None else bodies
    out = []
    for place, kinds in (("switch", ("stock", "blade")), ("crossing", ("wing", "nose"))):
        for side in ("left", "right"):
            first, second = (_body_with(bodies, kind, side) for kind in kinds)
            if first is None or second is None:
                continue
            if place == "switch":
                x_from = max(first.x_from, second.x_from - 0.5)
                x_to = min(first.x_to, second.x_to)
            else:
                tip = geometry.crossing.nose_tip
                x_from, x_to = max(tip - 1.0, first.x_from), min(tip + 1.5, second.x_to)
            if x_ranges and place in x_ranges:
                x_from, x_to = x_ranges[place]
            x = np.arange(x_from, x_to + 0.5 * step, step)
            pair = [
                _sections_on(body, x, geometry, setup.nominal_radius) for body in (first, second)
            ]
            paths = two_rail_paths(pair[0], pair[1], wheel, setup.taping_line, tuple(shifts))
            out.append(
                Transfer(
                    route,
                    place,
                    side,
                    first.name,
                    second.name,
                    paths,
                    tuple(dip_summary(path, baseline=DIP_BASELINE) for path in paths),
                )
            )
    return tuple(out)


@dataclass(frozen=True, eq=False)
class RestPath:
    """Rigid rest height of one wheel over every running-rail body of it present at x."""

    wheel: str  #: "left" | "right"
    shift: float  #: m, lateral shift of the wheel towards its field side
    x: np.ndarray  #: m, wheel-centre positions
    #: m, lift of the wheel (its taping circle) at which its nearest candidate touches
    #: (``max over bodies and candidates of -gap / cos(angle)``); NaN: no body under it
    height: np.ndarray
    body: np.ndarray  #: index into the bodies of the body that carries the wheel (-1: none)
    y_rail: np.ndarray  #: m, contact point on that body (side coordinates)
    angle: np.ndarray  #: rad, contact angle there


def handover_points(bodies: tuple[RailBody, ...], wheel: str) -> list[float]:
    """Where a running-rail body or segment of one wheel begins or ends inside the route.

    Parameters
    ----------
    bodies : tuple of RailBody
        The route's bodies (:func:`route_rail_bodies`).
    wheel : str
        "left" | "right".

    Returns
    -------
    list of float
        m, sorted, without the route's first and last x of that wheel's bodies; check rails
        (back-of-flange contact, they never carry the wheel) are left out.
    """
    running = [b for b in bodies if b.wheel == wheel and not b.back_of_flange]
    if not running:
        return []
    lo, hi = min(b.x_from for b in running), max(b.x_to for b in running)
    points = {seg.x_from for b in running for seg in b.segments}
    points |= {seg.x_to for b in running for seg in b.segments}
    return sorted(p for p in points if lo < p < hi)


def rest_path(
    bodies: tuple[RailBody, ...],
    geometry: RailGeometry,
    wheel_grid: WheelGrid,
    setup: WheelsetSetup,
    wheel: str,
    x: np.ndarray,
    shift: float = 0.0,
) -> RestPath:
    """Rigid rest height of a wheel along x over all its running-rail bodies present there.

    At each x, every body of ``wheel`` whose range ``[x_from, x_to]`` holds x (the kernel's
    rule, :mod:`.kernel`) is searched as the contact tables are built (its wheel envelope
    where the body is enveloped, :func:`envelope_sections`; vertical search, no roll); the
    wheel rests on the candidate that lifts it highest, ``-gap / cos(angle)`` (as
    :func:`.transfer.two_rail_path`).  A step in this height between close x is a step the
    passage's wheel runs into.

    Parameters
    ----------
    bodies : tuple of RailBody
        The route's bodies.
    geometry : RailGeometry
        Envelope reach and step.
    wheel_grid : WheelGrid
        Gridded wheel.
    setup : WheelsetSetup
        Taping line and nominal radius.
    wheel : str
        "left" | "right".
    x : numpy.ndarray
        m, wheel-centre positions.
    shift : float
        m, lateral shift of the wheel towards its field side.

    Returns
    -------
    RestPath
    """
    x = np.asarray(x, float)
    n = len(x)
    height = np.full(n, -np.inf)
    carrier = np.full(n, -1, dtype=int)
    y_rail, angle = np.full(n, np.nan), np.full(n, np.nan)
    prepared = prepare_wheel(wheel_grid, setup.taping_line, 0.0, directions=())
    for k, body in enumerate(bodies):
        if body.wheel != wheel or body.back_of_flange:
            continue
        inside = np.flatnonzero((x >= body.x_from) & (x <= body.x_to))
        if inside.size == 0:
            continue
        sections = _sections_on(body, x[inside], geometry, setup.nominal_radius)
        derivatives = surface_derivatives(sections)
        for row, i in enumerate(inside):
            rail = prepare_rail(
                sections.z[row],
                derivatives.slope[row],
                derivatives.curvature[row],
                sections.y,
                directions=(),
            )
            found = search_candidates_batch(rail, prepared, [shift], max_candidates=3)[0]
            if len(found.gap) == 0:
                continue
            lifts = -found.gap / np.cos(found.angle)
            best = int(np.argmax(lifts))
            if lifts[best] > height[i]:
                height[i], carrier[i] = float(lifts[best]), k
                y_rail[i], angle[i] = float(found.y_rail[best]), float(found.angle[best])
    height[np.isneginf(height)] = np.nan
    return RestPath(wheel, float(shift), x, height, carrier, y_rail, angle)


def handover_windows(
    bodies: tuple[RailBody, ...], wheel: str, geometry: RailGeometry, margin: float = 0.1
) -> list[tuple[float, float]]:
    """x ranges to check for steps: around every hand-over, and over the nose's twist.

    Parameters
    ----------
    bodies : tuple of RailBody
        The route's bodies.
    wheel : str
        "left" | "right".
    geometry : RailGeometry
        The crossing's ``inclination_transition``.
    margin : float
        m, half-width of the window around each hand-over point.

    Returns
    -------
    list of tuple
        m, sorted, non-overlapping ``(x_from, x_to)``.
    """
    length = geometry.crossing.inclination_transition
    windows = [(p - margin, p + margin) for p in handover_points(bodies, wheel)]
    for body in bodies:
        if body.wheel == wheel and not body.back_of_flange:
            windows += [
                (seg.x_to - length - margin, seg.x_to + margin)
                for seg in body.segments
                if seg.kind == "nose" and length > 0.0
            ]
    merged: list[tuple[float, float]] = []
    for lo, hi in sorted(windows):
        if merged and lo <= merged[-1][1]:
            merged[-1] = (merged[-1][0], max(hi, merged[-1][1]))
        else:
            merged.append((lo, hi))
    return merged


def table_rest_path(pairs, wheel: str, x: np.ndarray, shift: float = 0.0) -> RestPath:
    """:func:`rest_path` from the contact tables, as the passage's contact reads them.

    At each x, every running-rail body of ``wheel`` whose range holds x is looked up
    (:func:`.tables.lookup_values`, lift 0); the wheel rests on the candidate that lifts it
    highest, ``-gap / cos(angle)``.

    Parameters
    ----------
    pairs : sequence
        ``(body, table)`` pairs (:func:`route_contact_tables`); a table may cover only part
        of its body's x range (the query x must lie in it).
    wheel : str
        "left" | "right".
    x : numpy.ndarray
        m, wheel-centre positions.
    shift : float
        m, lateral shift of the wheel towards its field side.

    Returns
    -------
    RestPath
    """
    x = np.asarray(x, float)
    n = len(x)
    height = np.full(n, -np.inf)
    carrier = np.full(n, -1, dtype=int)
    y_rail, angle = np.full(n, np.nan), np.full(n, np.nan)
    for k, (body, table) in enumerate(pairs):
        if body.wheel != wheel or body.back_of_flange:
            continue
        inside = np.flatnonzero((x >= body.x_from) & (x <= body.x_to))
        if inside.size == 0:
            continue
        values = lookup_values(table, x[inside], np.full(inside.size, shift))
        gap = values[..., table.fields.index("gap")]
        theta = values[..., table.fields.index("angle")]
        lifts = np.where(gap < 0.5, -gap / np.cos(theta), -np.inf)
        best = np.argmax(lifts, axis=1)
        rows = np.arange(inside.size)
        better = lifts[rows, best] > height[inside]
        chosen = inside[better]
        height[chosen] = lifts[rows, best][better]
        carrier[chosen] = k
        y_rail[chosen] = values[rows, best, table.fields.index("y_rail")][better]
        angle[chosen] = theta[rows, best][better]
    height[np.isneginf(height)] = np.nan
    return RestPath(wheel, float(shift), x, height, carrier, y_rail, angle)
