"""Routes through the turnout: which rails each wheel can touch along x, and how high.

A route (``through``, ``diverging``) is read from the turnout file's ``[routes.<name>]``
section (see the file's comments for the format and the reasoning behind the default
profiles). Positions in a route (profile x, flange and check ranges) are numbers (m) or
features of the turnout's plan (:mod:`exudyn_turnout.inputs.geometry`), e.g.
``"nose_tip + 0.5"``, so that the crossing lies where the layout puts it. Load transfer
between rails (stock rail to switch blade, wing rail to crossing nose) is not coded
anywhere: it follows from the height tables alone, through the Hertz springs of whichever
rail stands higher under the wheel.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from exudyn_turnout.inputs.check_rail import FLARE_SHAPES, flare_opening
from exudyn_turnout.inputs.geometry import TurnoutPlan, resolve_position, turnout_plan
from exudyn_turnout.inputs.toml_fields import FieldReader, TurnoutFileError
from exudyn_turnout.inputs.turnout_data import RAIL_SLOTS, Table1D, Turnout, Zone

__all__ = [
    "ContactPair",
    "Route",
    "load_route",
    "route_names",
    "WHEELS",
    "dip_angle",
    "SpeedWarning",
    "cant_deficiency",
    "speed_warnings",
    "RAIL_CENTRE_DISTANCE",
    "GRAVITY",
]

#: m, distance between the rail centres used to express cant (EN 13803: 1500 mm for
#: 1435 mm gauge).
RAIL_CENTRE_DISTANCE = 1.5
#: m/s^2
GRAVITY = 9.81


class SpeedWarning(UserWarning):
    """A passage runs a route faster than the turnout file permits (a warning, not an error)."""


#: Wheels of the wheelset and their side: +1 left (positive y), -1 right.
WHEELS = {"left": 1, "right": -1}


@dataclass(frozen=True)
class ContactPair:
    """A wheel and a rail it can touch, with the rail height profile seen by the wheel."""

    name: str  #: description, e.g. "left wheel on r1"
    wheel: str  #: "left" or "right"
    rail: str  #: rail slot r1..r4
    x: tuple[float, ...]  #: m, profile abscissae (empty: no vertical contact)
    z: tuple[float, ...]  #: m, rail height relative to nominal at x
    flange: tuple[float, float] | None  #: m, x range where the flange can touch this rail
    check: tuple[float, float] | None  #: m, x range where the flange back can touch it

    @property
    def side(self) -> int:
        """Side of the wheel: +1 left (positive y), -1 right."""
        return WHEELS[self.wheel]

    @property
    def has_tread(self) -> bool:
        """Whether the pair has a height profile (vertical tread contact somewhere)."""
        return bool(self.x)

    def tread_active(self, x: float) -> bool:
        """Whether the wheel's tread can touch the rail at a position.

        Parameters
        ----------
        x : float
            Wheel position from the switch toe (m).

        Returns
        -------
        bool
            True inside the height profile's x range.
        """
        return self.has_tread and self.x[0] <= x <= self.x[-1]

    def height(self, x: float) -> float:
        """Rail height at a position, linear between the table's points.

        Parameters
        ----------
        x : float
            Position from the switch toe (m).

        Returns
        -------
        float
            Rail height relative to nominal (m), held at the end values outside the table.
        """
        return float(np.interp(x, self.x, self.z))

    def x_range(self) -> tuple[float, float]:
        """The x range over which the wheel can touch the rail at all.

        Returns
        -------
        tuple of float
            (x_from, x_to) in m: the union of the height profile, flange and check ranges.
        """
        ranges = [r for r in (self.flange, self.check) if r] + (
            [(self.x[0], self.x[-1])] if self.x else []
        )
        return min(r[0] for r in ranges), max(r[1] for r in ranges)


@dataclass(frozen=True)
class Route:
    """A route through the turnout: its curve, the wheel/rail pairs and the speed limits."""

    name: str  #: key of ``[routes.<name>]``, e.g. "through"
    description: str  #: free text from the file
    curvature: Table1D  #: 1/m, positive for a curve to the left
    pairs: tuple[ContactPair, ...]  #: every wheel/rail pair the route can bring into contact
    rail_y: Mapping[str, float]  #: m, overrides of the zones' rail positions for this route
    continues: Mapping[int, Mapping[str, str]]  #: zone -> {new slot: slot it continues}
    check_clearance: float  #: m, nominal check-rail clearance
    check_flare: tuple[float, float] = (0.0, 0.0)  #: m, (length, opening) of the flared ends
    cant: float = 0.0  #: m, cant of the route's curve (height difference of the rails)
    permitted_speed_kmh: float | None = None  #: km/h, the file's permitted speed; None: none
    permitted_cant_deficiency: float | None = None  #: m, the file's limit; None: none
    check_flare_shape: str = "straight"  #: run-in shape of the flares (inputs/check_rail.py)

    def max_curvature(self, x_from: float, x_to: float) -> float:
        """Largest curvature of the route over an x range (table points and ends).

        Parameters
        ----------
        x_from, x_to : float
            The range (m).

        Returns
        -------
        float
            Largest |1/R| (1/m).
        """
        x_points = [x_from, x_to] + [x for x in self.curvature.x if x_from <= x <= x_to]
        return max(abs(self.curvature(x)) for x in x_points)

    def check_clearance_at(self, pair: ContactPair, x: float) -> float | None:
        """Check-rail clearance at a position, opened at the flared ends.

        Parameters
        ----------
        pair : ContactPair
            A pair with a check range.
        x : float
            Position from the switch toe (m).

        Returns
        -------
        float or None
            Clearance (m); None outside the pair's check range.
        """
        if not pair.check or not pair.check[0] <= x <= pair.check[1]:
            return None
        length, opening = self.check_flare
        into = min(x - pair.check[0], pair.check[1] - x)
        return self.check_clearance + flare_opening(into, length, opening, self.check_flare_shape)

    def zone(self, zone: Zone) -> Zone:
        """The zone with this route's rail positions.

        Parameters
        ----------
        zone : Zone
            A zone of the turnout (Table 3).

        Returns
        -------
        Zone
            A copy whose ``rail_y`` carries the route's overrides.
        """
        from dataclasses import replace

        rail_y = {slot: self.rail_y.get(slot, y) for slot, y in zone.rail_y.items()}
        return replace(zone, rail_y=rail_y)

    def pairs_in(self, zone: Zone) -> tuple[ContactPair, ...]:
        """Pairs whose x range overlaps a zone over a positive length (not just a boundary).

        Parameters
        ----------
        zone : Zone
            A zone of the turnout.

        Returns
        -------
        tuple of ContactPair
            The pairs, in the route's order.
        """
        return tuple(
            pair
            for pair in self.pairs
            if min(pair.x_range()[1], zone.x_end) - max(pair.x_range()[0], zone.x_start) > 1e-9
        )


def route_names(turnout: Turnout) -> tuple[str, ...]:
    """Names of the routes the turnout file defines.

    Parameters
    ----------
    turnout : Turnout
        The turnout.

    Returns
    -------
    tuple of str
        The ``[routes.<name>]`` keys, in file order (empty when there are none).
    """
    return tuple(turnout.raw.get("routes", {}))


def _x(r: FieldReader, field: str, value: object, plan: TurnoutPlan | None) -> float:
    """A position: a number (m) or a feature of the plan, e.g. ``"nose_tip - 0.2"``."""
    if isinstance(value, str):
        try:
            return resolve_position(value, plan)
        except ValueError as err:
            raise r.fail(field, str(err)) from None
    return r.check(field, value, positive=False)


def _range(r: FieldReader, field: str, plan: TurnoutPlan | None) -> tuple[float, float] | None:
    value = r.get(field, None)
    if value is None:
        return None
    if not isinstance(value, list) or len(value) != 2:
        raise r.fail(field, f"must be [x_from, x_to], got {value!r}")
    x_from, x_to = (_x(r, field, v, plan) for v in value)
    if not x_to > x_from:
        raise r.fail(field, f"range is inverted: {x_from:g} >= {x_to:g}")
    return x_from, x_to


def _pair(r: FieldReader, p: str, plan: TurnoutPlan | None) -> ContactPair:
    wheel = r.choice(p + ".wheel", tuple(WHEELS))
    rail = r.choice(p + ".rail", RAIL_SLOTS)
    xs, zs = r.get(p + ".x", []), r.get(p + ".z", [])
    if not isinstance(xs, list) or not isinstance(zs, list) or len(xs) != len(zs) or len(xs) == 1:
        raise r.fail(p, "needs lists x and z of the same length (>= 2), or neither")
    xs = [_x(r, p + ".x", v, plan) for v in xs]
    zs = [r.check(p + ".z", v, positive=False) for v in zs]
    if any(b <= a for a, b in zip(xs, xs[1:])):
        raise r.fail(p + ".x", f"must be increasing, got {xs}")
    if any(abs(z) > 0.05 for z in zs):
        raise r.fail(p + ".z", f"heights must be within +-0.05 m of nominal, got {zs}")
    pair = ContactPair(
        str(r.get(p + ".name", f"{wheel} wheel on {rail}")),
        wheel,
        rail,
        tuple(xs),
        tuple(zs),
        _range(r, p + ".flange", plan),
        _range(r, p + ".check", plan),
    )
    if not pair.x and not pair.check:
        raise r.fail(p, "needs a height profile (x, z) or a check range")
    return pair


def _check_active(r: FieldReader, turnout: Turnout, field: str, pair: ContactPair) -> None:
    x_from, x_to = pair.x_range()
    if x_from < turnout.x_min - 1e-9 or x_to > turnout.x_max + 1e-9:
        raise r.fail(
            field,
            f"x range {x_from:g}..{x_to:g} m is outside the turnout "
            f"({turnout.x_min:g}..{turnout.x_max:g} m)",
        )
    for zone in turnout.zones:
        start, end = max(x_from, zone.x_start), min(x_to, zone.x_end)
        if end - start > 1e-9 and pair.rail not in zone.active_rails:
            raise r.fail(
                field,
                f"uses rail {pair.rail} over {start:g}..{end:g} m, "
                f"where zone {zone.index} has no such active rail",
            )


def _continues(r: FieldReader, field: str, turnout: Turnout) -> dict[int, dict[str, str]]:
    out: dict[int, dict[str, str]] = {}
    for i, item in enumerate(r.get(field, []) or []):
        item_field = f"{field}[{i}]"
        zone = int(
            r.check(item_field + ".zone", item.get("zone") if isinstance(item, Mapping) else None)
        )
        item = item if isinstance(item, Mapping) else {}
        if not 2 <= zone <= len(turnout.zones):
            raise r.fail(
                item_field + ".zone",
                f"must be a zone after the first (2..{len(turnout.zones)}), got {zone}",
            )
        slot, previous_slot = item.get("slot"), item.get("from")
        if (
            slot not in turnout.zone(zone).active_rails
            or previous_slot not in turnout.zone(zone - 1).active_rails
        ):
            raise r.fail(
                item_field,
                f"maps {previous_slot!r} of zone {zone - 1} to {slot!r} of zone {zone}: "
                "both must be active there",
            )
        out.setdefault(zone, {})[slot] = previous_slot
    return out


def load_route(turnout: Turnout, name: str) -> Route:
    """The route ``name`` of the turnout file, validated.

    Parameters
    ----------
    turnout : Turnout
        The turnout whose file defines ``[routes.<name>]``.
    name : str
        Route name, e.g. ``"through"`` or ``"diverging"``.

    Returns
    -------
    Route
        Contact pairs, curvature, check-rail clearance, cant and speed limits.

    Raises
    ------
    TurnoutFileError
        Unknown route, or a field that cannot be right (the message names the field).
    """
    filename = turnout.source.replace("\\", "/").rsplit("/", 1)[-1]
    r = FieldReader(filename, turnout.raw)
    if name not in route_names(turnout):
        raise TurnoutFileError(
            f"{filename}: no route {name!r} (routes: {', '.join(route_names(turnout)) or 'none'})"
        )
    p = f"routes.{name}"
    raw_pairs = r.get(p + ".contacts")
    if not isinstance(raw_pairs, list) or not raw_pairs:
        raise r.fail(p + ".contacts", "must be a non-empty list of [[contacts]] tables")
    plan = turnout_plan(turnout) if isinstance(turnout.raw.get("layout"), Mapping) else None
    pairs = []
    for i, raw in enumerate(raw_pairs):
        field = f"{p}.contacts[{i}]"
        pair = _pair(r.sub(field, raw), field, plan)
        _check_active(r, turnout, field, pair)
        pairs.append(pair)
    curvature = r.get(p + ".curvature", 0.0)
    curvature = (
        Table1D((0.0,), (float(curvature),))
        if isinstance(curvature, (int, float))
        else _curvature(r, p)
    )
    rail_y = {s: r.number(f"{p}.rail_y.{s}", positive=False) for s in r.get(p + ".rail_y", {})}
    has_check = any(q.check for q in pairs)
    clearance = r.number("check_rail.clearance") if has_check else math.nan
    flare = (
        (
            r.number("check_rail.flare_length", False, 0.0),
            r.number("check_rail.flare_opening", False, 0.0),
        )
        if has_check
        else (0.0, 0.0)
    )
    shape = (
        r.choice("check_rail.flare_shape", FLARE_SHAPES, default="straight")
        if has_check
        else "straight"
    )
    limit_speed = r.get(p + ".permitted_speed_kmh", None)
    limit_deficiency = r.get(p + ".permitted_cant_deficiency", None)
    return Route(
        name,
        str(r.get(p + ".description", "")),
        curvature,
        tuple(pairs),
        rail_y,
        _continues(r, p + ".continues", turnout),
        clearance,
        flare,
        r.number(p + ".cant", positive=False, default=0.0),
        None if limit_speed is None else r.number(p + ".permitted_speed_kmh"),
        None if limit_deficiency is None else r.number(p + ".permitted_cant_deficiency"),
        shape,
    )


def cant_deficiency(speed_kmh: float, curvature: float, cant: float = 0.0) -> float:
    """Cant deficiency (m): the cant that would balance the curve, less the cant there is.

    D = G v^2 |1/R| / g - cant, G = :data:`RAIL_CENTRE_DISTANCE` (EN 13803's definition of
    cant deficiency for standard gauge).

    Parameters
    ----------
    speed_kmh : float
        Speed (km/h).
    curvature : float
        1/R (1/m); its sign is ignored.
    cant : float
        Cant (m) of the curve.

    Returns
    -------
    float
        Cant deficiency (m).
    """
    v = speed_kmh / 3.6
    return RAIL_CENTRE_DISTANCE * v**2 * abs(curvature) / GRAVITY - cant


def speed_warnings(route: Route, speed_kmh: float, x_from: float, x_to: float) -> list[str]:
    """Warnings for a passage above the route's permitted speed or cant deficiency.

    Parameters
    ----------
    route : Route
        The route run.
    speed_kmh : float
        The passage's speed (km/h).
    x_from, x_to : float
        The passage's x range (m).

    Returns
    -------
    list of str
        One sentence per limit exceeded (empty when none is or the file sets none).
    """
    out = []
    if route.permitted_speed_kmh is not None and speed_kmh > route.permitted_speed_kmh + 1e-9:
        out.append(
            f"route {route.name}: {speed_kmh:g} km/h is above the permitted "
            f"{route.permitted_speed_kmh:g} km/h of the turnout file"
        )
    deficiency = cant_deficiency(speed_kmh, route.max_curvature(x_from, x_to), route.cant)
    if (
        route.permitted_cant_deficiency is not None
        and deficiency > route.permitted_cant_deficiency + 1e-9
    ):
        out.append(
            f"route {route.name}: cant deficiency {1e3 * deficiency:.0f} mm at "
            f"{speed_kmh:g} km/h is above the permitted "
            f"{1e3 * route.permitted_cant_deficiency:.0f} mm of the turnout file"
        )
    return out


def _curvature(r: FieldReader, p: str) -> Table1D:
    f = p + ".curvature"
    xs, vs = r.get(f + ".x"), r.get(f + ".value")
    if not isinstance(xs, list) or not isinstance(vs, list) or len(xs) != len(vs) or len(xs) < 2:
        raise r.fail(f, "must be a number or {x = [...], value = [...]} of equal length")
    xs = [r.check(f + ".x", v, positive=False) for v in xs]
    if any(b <= a for a, b in zip(xs, xs[1:])):
        raise r.fail(f + ".x", f"must be increasing, got {xs}")
    return Table1D(tuple(xs), tuple(r.check(f + ".value", v, positive=False) for v in vs))


def dip_angle(
    route: Route, wheel: str, x_from: float, x_to: float, n: int = 20001
) -> tuple[float, float, float]:
    """Dip of the wheel's path over the highest rail between x_from and x_to.

    Parameters
    ----------
    route : Route
        The route.
    wheel : {"left", "right"}
        The wheel whose path is taken.
    x_from, x_to : float
        The x range searched (m).
    n : int
        Number of sample points over the range.

    Returns
    -------
    (x_dip, depth, two_alpha)
        Position (m) and depth (m) of the lowest point of the upper envelope of the rail
        heights, and the total dip angle 2 alpha (rad): the slope after minus the slope
        before that point (the angle Jenkins' P2 formula takes).
    """
    xs = np.linspace(x_from, x_to, n)
    pairs = [pair for pair in route.pairs if pair.wheel == wheel and pair.has_tread]
    envelope = np.array(
        [
            max((pair.height(x) for pair in pairs if pair.tread_active(x)), default=-np.inf)
            for x in xs
        ]
    )
    i = int(np.argmin(envelope))
    spacing = xs[1] - xs[0]
    k = max(1, int(0.02 / spacing))  # slopes over 20 mm either side
    before = (envelope[i] - envelope[max(i - k, 0)]) / (xs[i] - xs[max(i - k, 0)])
    after = (envelope[min(i + k, n - 1)] - envelope[i]) / (xs[min(i + k, n - 1)] - xs[i])
    return float(xs[i]), float(-envelope[i]), float(after - before)
