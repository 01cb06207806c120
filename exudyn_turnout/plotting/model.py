"""Pictures of the model: the co-running cross-section as built, and a passage animated.

:func:`cross_section_geometry` lists the bodies and spring-dampers of the co-running
cross-section of a zone at a position x, taken from the same spring list the Exudyn
builder (:mod:`exudyn_turnout.corunning.track`) turns into ``CartesianSpringDamper`` objects, with
their values at x (``params.at(x)``). :func:`draw_cross_section` draws it like the
paper's Figs 2 and 3; :func:`animate_passage` writes a GIF of a passage's cross-section
(:func:`passage_frames` picks its samples). Compute returns data; only the ``draw_`` and
``animate_`` functions use matplotlib (from :mod:`.backend`, when they draw).

Drawing coordinates: lateral positions are the model's (m, y positive left, seen in the
running direction), except that rails closer than ``min_gap`` are drawn apart (their
model y stays in :attr:`Body.y` and in the labels); heights are schematic levels, since
the model places every body at z = 0 and carries displacements only.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from exudyn_turnout.corunning.parameters import CoRunningParameters
from exudyn_turnout.inputs.routes import Route, load_route
from exudyn_turnout.inputs.turnout import RAIL_SLOTS, Turnout
from exudyn_turnout.inputs.vehicle import Vehicle
from exudyn_turnout.plotting.backend import patches, pillow_writer, pyplot

__all__ = [
    "Body",
    "Contact",
    "CrossSection",
    "SpringDamper",
    "animate_passage",
    "cross_section_geometry",
    "draw_cross_section",
    "entry_symbol",
    "format_damping",
    "format_stiffness",
    "passage_frames",
    "spring_label",
]


@dataclass(frozen=True)
class Body:
    """A body of the cross-section drawing (a mass of the model, or the ground).

    Parameters
    ----------
    name : str
        ``ground``, ``sleeper``, a rail slot ``r1``..``r4``, ``m0_r1``..``m0_r4`` (m_0 above
        that rail, three layers), ``wheelset``, ``sprung_mass``.
    label : str
        Text drawn on or beside the body.
    y : float
        Lateral position in the model (m).
    y_drawn : float
        Lateral position of its centre in the drawing (m).
    z : float
        Schematic drawing level of its centre.
    width, height : float
        Drawn size (m, schematic units).
    mass : float or None
        kg; None for the ground.
    inertia : float or None
        Roll inertia (kg m^2) of the sleeper (J_t) and the wheelset; None otherwise.
    """

    name: str
    label: str
    y: float  #: m, lateral position in the model (track frame, positive left)
    y_drawn: float  #: m, lateral position of its centre in the drawing
    z: float  #: -, schematic drawing level of its centre (the model has every body at z = 0)
    width: float  #: m, drawn width
    height: float  #: -, drawn height (schematic units)
    mass: float | None = None  #: kg (None: the ground)
    inertia: float | None = None  #: kg m^2, roll inertia (sleeper J_t, wheelset)


@dataclass(frozen=True)
class SpringDamper:
    """One direction of one spring-damper connector (a spring || dashpot pair).

    Parameters
    ----------
    name : str
        The connector's name: for the track the name the Exudyn builder gives its
        ``CartesianSpringDamper`` (``ballast_z1``, ``ballast_y``, ``pad_r2``,
        ``layer_r2``); ``primary_right``, ``primary_left`` for the vehicle.
    direction : {"z", "y"}
        Vertical or lateral.
    bodies : (str, str)
        Names of the bodies it connects (lower or outer end first).
    attach_y : (float, float)
        Model lateral positions (m) of its two attachment points (marker positions).
    from_point, to_point : (float, float)
        Drawn ends (lateral m, schematic level).
    k_name, c_name : str
        Entry names of its stiffness and damping (``k_rt2_z``, ``c_rt2_z``).
    k, c : float
        Stiffness (N/m) and damping (N s/m) at x.
    """

    name: str
    direction: str
    bodies: tuple[str, str]  #: (lower or outer end, upper or inner end) body names
    attach_y: tuple[float, float]  #: m, model lateral positions of the two attachment points
    from_point: tuple[float, float]  #: (m, -), drawn start (lateral, schematic level)
    to_point: tuple[float, float]  #: (m, -), drawn end
    k_name: str  #: entry name of the stiffness (``k_rt2_z``; ``k_z`` for the vehicle)
    c_name: str  #: entry name of the damping
    k: float  #: N/m, at x
    c: float  #: N s/m, at x


@dataclass(frozen=True)
class Contact:
    """A wheel/rail tread contact active at x (a Hertz spring in the passage, not a connector).

    Parameters
    ----------
    name : str
        The route's contact pair name.
    wheel : {"left", "right"}
        The wheel of the pair.
    rail : str
        Rail slot.
    body : str
        The body the wheel loads: the rail (two layers) or the m_0 above it (three).
    from_point, to_point : (float, float)
        Drawn points on the wheel and on the loaded body.
    """

    name: str  #: the route's contact pair name
    wheel: str  #: "left" or "right"
    rail: str  #: rail slot
    body: str  #: body the wheel loads: the rail (two layers) or the m_0 above it (three)
    from_point: tuple[float, float]  #: (m, -), drawn point on the wheel
    to_point: tuple[float, float]  #: (m, -), drawn point on the loaded body


@dataclass(frozen=True)
class CrossSection:
    """The co-running cross-section of one zone at x, as the Exudyn builder builds it.

    ``springs`` holds exactly the track's connectors (one item per connector and
    direction with a stiffness entry); ``suspension`` the vehicle's primary springs and
    ``contacts`` the active tread contacts (both empty without a vehicle).

    Parameters
    ----------
    turnout : str
        Turnout name.
    zone : int
        1-based zone index.
    zone_name : str
        The zone's name in the turnout file.
    x : float
        Position (m).
    layers : {2, 3}
        Track model: rail on sleeper (2) or with the m_0 layer (3).
    source : {"derived", "published"}
        Parameter set: derived from Table 1 (Eqs 1-19) or the paper's Table 2.
    route : str or None
        Route whose rail positions are used; None: the zone's.
    bodies : tuple of Body
        Ground, sleeper, rails (and m_0 layers), with a vehicle also wheelset and sprung mass.
    springs : tuple of SpringDamper
        The track's connectors, one item per connector and direction.
    suspension : tuple of SpringDamper
        The vehicle's primary springs (empty without a vehicle).
    contacts : tuple of Contact
        Tread contacts active at x (empty without a vehicle).
    spread_rails : tuple of str
        Rails drawn away from their model y (closer than ``min_gap``).
    min_gap : float
        Smallest drawn distance between rails (m).
    """

    turnout: str  #: turnout name
    zone: int  #: 1-based zone index
    zone_name: str  #: the zone's name in the turnout file
    x: float  #: m, position of the cross-section
    layers: int  #: 2 or 3
    source: str  #: "derived" or "published"
    route: str | None  #: route name whose rail positions are used; None: the zone's
    bodies: tuple[Body, ...]  #: ground, sleeper, rails, m_0 layers (, wheelset, sprung mass)
    springs: tuple[SpringDamper, ...]  #: the track's connectors, per direction
    suspension: tuple[SpringDamper, ...]  #: the vehicle's primary springs
    contacts: tuple[Contact, ...]  #: tread contacts active at x
    spread_rails: tuple[str, ...]  #: rails drawn away from their model y (closer than min_gap)
    min_gap: float  #: m, smallest drawn distance between rails

    def body(self, name: str) -> Body:
        """The body called ``name``.

        Parameters
        ----------
        name : str
            ``sleeper``, ``r2``, ``m0_r2``, ...

        Returns
        -------
        Body
            The first body of that name; KeyError if there is none.
        """
        for body in self.bodies:
            if body.name == name:
                return body
        names = ", ".join(body.name for body in self.bodies)
        raise KeyError(f"no body {name!r} in the cross-section ({names})")

    @property
    def connectors(self) -> tuple[str, ...]:
        """Names of the track's spring-damper connectors, in the builder's order."""
        return tuple(dict.fromkeys(spring.name for spring in self.springs))


@dataclass(frozen=True)
class _Levels:
    """Schematic drawing levels (bottom, top) of the layers, and drawn sizes."""

    ground: float = 0.0
    sleeper: tuple[float, float] = (1.0, 1.3)
    rail: tuple[float, float] = (2.3, 2.6)
    layer: tuple[float, float] = (3.6, 3.85)
    contact_gap: float = 0.45
    wheel_height: float = 0.7
    suspension: float = 1.1
    sprung_height: float = 0.45
    rail_width: float = 0.24  #: m
    layer_width: float = 0.2  #: m
    wheel_width: float = 0.16  #: m
    post: float = 0.26  #: m, post of a lateral spring, left of the body it holds
    wall: float = 0.5  #: m, lateral ballast spring length


def _spread(model_y: Mapping[str, float], gap: float) -> dict[str, float]:
    """Drawn lateral positions: clusters of rails closer than ``gap`` spread around their mean."""
    order = sorted(model_y, key=lambda r: (model_y[r], r))
    clusters = [[r] for r in order]

    def centre(cl: list[str]) -> float:
        return float(np.mean([model_y[r] for r in cl]))

    def half(cl: list[str]) -> float:
        return 0.5 * (len(cl) - 1) * gap

    merged = True
    while merged:
        merged = False
        for i in range(len(clusters) - 1):
            a, b = clusters[i], clusters[i + 1]
            if (centre(b) - half(b)) - (centre(a) + half(a)) < gap - 1e-9:
                clusters[i : i + 2] = [a + b]
                merged = True
                break
    drawn = {}
    for cl in clusters:
        start = centre(cl) - half(cl)
        if len(cl) == 1:
            drawn[cl[0]] = model_y[cl[0]]
            continue
        for k, r in enumerate(cl):
            drawn[r] = start + k * gap
    return drawn


def _lateral_map(
    model_y: Mapping[str, float], drawn: Mapping[str, float]
) -> Callable[[float], float]:
    """Piecewise-linear map model y -> drawn y through the rails (slope 1 outside them)."""
    knots: dict[float, list[float]] = {}
    for r, y in model_y.items():
        knots.setdefault(round(y, 9), []).append(drawn[r])
    ys = np.array(sorted(knots))
    ds = np.array([float(np.mean(knots[y])) for y in ys])

    def to_drawn(y: float) -> float:
        if y <= ys[0]:
            return float(ds[0] + (y - ys[0]))
        if y >= ys[-1]:
            return float(ds[-1] + (y - ys[-1]))
        return float(np.interp(y, ys, ds))

    return to_drawn


def entry_symbol(name: str) -> str:
    """Mathtext symbol of an entry name: ``k_rt2_z`` -> ``$k_{rt2,z}$``, ``m_0`` -> ``$m_{0}$``.

    Parameters
    ----------
    name : str
        Entry name of :data:`~exudyn_turnout.inputs.turnout.PARAMETER_NAMES` (or a
        vehicle's ``k_z``).

    Returns
    -------
    str
        Matplotlib mathtext, the part after the first ``_`` as subscript.
    """
    head, _, tail = name.partition("_")
    return f"${head}_{{{tail.replace('_', ',')}}}$" if tail else f"${head}$"


def format_stiffness(k: float) -> str:
    """A stiffness in MN/m with 3 significant digits (``369 MN/m``).

    Parameters
    ----------
    k : float
        N/m.

    Returns
    -------
    str
        The value and its unit.
    """
    return f"{_three_digits(k / 1e6)} MN/m"


def format_damping(c: float) -> str:
    """A damping in kN s/m with 3 significant digits (``76.9 kN s/m``).

    Parameters
    ----------
    c : float
        N s/m.

    Returns
    -------
    str
        The value and its unit.
    """
    return f"{_three_digits(c / 1e3)} kN s/m"


def _three_digits(value: float) -> str:
    """3 significant digits, but whole numbers from 1000 on (no exponent): 369, 76.9, 1346."""
    return f"{value:.0f}" if abs(value) >= 999.5 else f"{value:.3g}"


def spring_label(spring: SpringDamper) -> str:
    """Label of one spring-damper: ``$k_{rt2,z}$ = 369 MN/m, $c$ = 76.9 kN s/m``.

    Parameters
    ----------
    spring : SpringDamper
        One item of :attr:`CrossSection.springs` or :attr:`CrossSection.suspension`.

    Returns
    -------
    str
        Matplotlib mathtext: stiffness symbol and value, damping value.
    """
    stiffness, damping = format_stiffness(spring.k), format_damping(spring.c)
    return f"{entry_symbol(spring.k_name)} = {stiffness}, $c$ = {damping}"


def _track_springs(params: CoRunningParameters) -> list:
    """The Exudyn builder's own spring list (:mod:`~exudyn_turnout.corunning.cross_section`)."""
    from exudyn_turnout.corunning.cross_section import cross_section_springs as _springs

    return _springs(params)


def cross_section_geometry(
    params: CoRunningParameters,
    x: float,
    route: Route | str | None = None,
    vehicle: Vehicle | None = None,
    min_gap: float = 1.25,
) -> CrossSection:
    """Bodies, spring-dampers and contacts of the co-running cross-section at x, as built.

    The springs are those :func:`exudyn_turnout.corunning.track.add_co_running_track` builds
    (same list, same names), with stiffness and damping at x (``params.at(x)``); bodies
    are the ground, the sleeper (m_t, J_t), the active rails (m_r) and, for three
    layers, the m_0 above each rail; with a vehicle also the wheelset (wheels at +-b),
    its sprung mass on the primary suspension (at +-d) and the tread contacts active at x.

    Parameters
    ----------
    params : CoRunningParameters
        Parameter set of the zone
        (:func:`~exudyn_turnout.corunning.parameters.co_running_parameters`).
    x : float
        Position (m) in the zone.
    route : Route or str, optional
        Route (or its name) whose rail positions and contacts are used, as in a passage;
        None: the zone's rail positions, no contacts.
    vehicle : Vehicle, optional
        Draw the wheelset above the track.
    min_gap : float
        Smallest drawn distance (m) between rails; closer rails are drawn apart.

    Returns
    -------
    CrossSection
        Bodies, spring-dampers and contacts with their drawn positions and values at x.
    """
    from dataclasses import replace

    if isinstance(route, str):
        route = load_route(params.turnout, route)
    if route is not None:
        params = replace(params, zone=route.zone(params.zone))
    values = params.at(x)
    zone, lv = params.zone, _Levels()
    rails = [r for r in RAIL_SLOTS if r in params.active_rails]
    model_y = {r: float(zone.rail_y[r]) for r in rails}
    drawn = _spread(model_y, min_gap)
    to_drawn = _lateral_map(model_y, drawn)
    three = params.layers == 3
    bodies = _track_bodies(params, values, model_y, drawn, to_drawn, lv)
    where = {b.name: b for b in bodies}
    springs = tuple(
        s
        for spring in _track_springs(params)
        for s in _connector(spring, zone, where, to_drawn, values, lv)
    )
    suspension: tuple[SpringDamper, ...] = ()
    contacts: tuple[Contact, ...] = ()
    if vehicle is not None:
        top = lv.layer[1] if three else lv.rail[1]
        vehicle_bodies, suspension = _vehicle(vehicle, to_drawn, top, lv)
        bodies += vehicle_bodies
        where = {b.name: b for b in bodies}
        contacts = _contacts(route, params, x, vehicle, where, to_drawn)
    spread = tuple(r for r in rails if abs(drawn[r] - model_y[r]) > 1e-9)
    return CrossSection(
        params.turnout.name,
        zone.index,
        zone.name,
        float(x),
        params.layers,
        params.source,
        None if route is None else route.name,
        bodies,
        springs,
        suspension,
        contacts,
        spread,
        float(min_gap),
    )


def _track_bodies(
    params: CoRunningParameters,
    values: Mapping[str, float],
    model_y: Mapping[str, float],
    drawn: Mapping[str, float],
    to_drawn: Callable[[float], float],
    lv: _Levels,
) -> tuple[Body, ...]:
    zone, turnout = params.zone, params.turnout
    length = turnout.rail_types[zone.ballast_rail_type].sleeper_length
    left = min(to_drawn(zone.sleeper_y - 0.5 * length), min(drawn.values()) - lv.post - 0.25)
    right = max(to_drawn(zone.sleeper_y + 0.5 * length), max(drawn.values()) + 0.75)
    extent = (left - lv.wall - 0.3, right + 0.2)
    sleeper_label = (
        f"sleeper  {entry_symbol('m_t')} = {values['m_t']:.4g} kg, "
        f"{entry_symbol('J_t')} = {values['J_t']:.4g} kg m$^2$"
    )
    mid = 0.5 * sum(lv.sleeper)
    out = [
        Body(
            "ground",
            "ground",
            0.5 * (extent[0] + extent[1]),
            0.5 * (extent[0] + extent[1]),
            lv.ground,
            extent[1] - extent[0],
            0.0,
        ),
        Body(
            "sleeper",
            sleeper_label,
            zone.sleeper_y,
            0.5 * (left + right),
            mid,
            right - left,
            lv.sleeper[1] - lv.sleeper[0],
            values["m_t"],
            values["J_t"],
        ),
    ]
    rail_mid, layer_mid = 0.5 * sum(lv.rail), 0.5 * sum(lv.layer)
    for r in (r for r in RAIL_SLOTS if r in model_y):
        m = values[f"m_r{r[1:]}"]
        kind = zone.rail_types[r]
        label = f"{r} {kind}\n{entry_symbol('m_' + r)} = {m:.4g} kg\ny = {model_y[r]:.3g} m"
        out.append(
            Body(
                r, label, model_y[r], drawn[r], rail_mid, lv.rail_width, lv.rail[1] - lv.rail[0], m
            )
        )
        if params.layers == 3:
            out.append(
                Body(
                    f"m0_{r}",
                    f"{entry_symbol('m_0')} = {values['m_0']:.3g} kg",
                    model_y[r],
                    drawn[r],
                    layer_mid,
                    lv.layer_width,
                    lv.layer[1] - lv.layer[0],
                    values["m_0"],
                )
            )
    return tuple(out)


def _connector(
    spring: Any,
    zone: Any,
    where: Mapping[str, Body],
    to_drawn: Callable[[float], float],
    values: Mapping[str, float],
    lv: _Levels,
) -> list[SpringDamper]:
    """The drawn spring-dampers (z, then y) of one connector of the builder's list."""
    ends: list[tuple[str, float]] = []
    if spring.ground_y is not None:
        ends.append(("ground", float(spring.ground_y)))
    if spring.sleeper_y is not None:
        ends.append(("sleeper", float(zone.sleeper_y + spring.sleeper_y)))
    for node in spring.nodes:
        ends.append((node, float(zone.rail_y[node.removeprefix("m0_")])))
    (low, y_low), (high, y_high) = ends
    lower, upper = where[low], where[high]
    lower_top, upper_bottom = lower.z + 0.5 * lower.height, upper.z - 0.5 * upper.height
    out = []
    for direction, k_name, c_name in (
        ("z", spring.k[1], spring.c[1]),
        ("y", spring.k[0], spring.c[0]),
    ):
        if k_name is None:
            continue
        if direction == "z":
            y = to_drawn(y_high) if high == "sleeper" else upper.y_drawn
            start, end = (y, lower_top), (y, upper_bottom)
        elif (
            high == "sleeper"
        ):  # lateral ballast spring: from a ground wall to the sleeper's left end
            left = upper.y_drawn - 0.5 * upper.width
            start, end = (left - lv.wall, upper.z), (left, upper.z)
        else:  # from a post standing on the lower body to the upper body's left side
            left = upper.y_drawn - 0.5 * upper.width
            start, end = (upper.y_drawn - lv.post - 0.5 * upper.width, upper.z), (left, upper.z)
        out.append(
            SpringDamper(
                spring.name,
                direction,
                (low, high),
                (y_low, y_high),
                start,
                end,
                k_name,
                c_name or "",
                float(values[k_name]),
                float(values[c_name]) if c_name else 0.0,
            )
        )
    return out


def _vehicle(
    vehicle: Vehicle, to_drawn: Callable[[float], float], top: float, lv: _Levels
) -> tuple[tuple[Body, ...], tuple[SpringDamper, ...]]:
    """Wheelset, sprung mass and primary springs, drawn affinely between the wheels."""
    right, left = to_drawn(-vehicle.b), to_drawn(vehicle.b)
    mid, per_m = 0.5 * (left + right), (left - right) / (2.0 * vehicle.b)
    axle = top + lv.contact_gap + 0.5 * lv.wheel_height
    sprung = axle + lv.suspension + 0.5 * lv.sprung_height
    width = 2.0 * vehicle.d * per_m + 0.6
    wheelset = Body(
        "wheelset",
        f"wheelset {entry_symbol('m_w')} = {vehicle.m_w:.4g} kg, "
        f"$J$ = {vehicle.J_roll:.4g} kg m$^2$\nwheels at $\\pm b$ = "
        f"$\\pm${vehicle.b:.3g} m",
        0.0,
        mid,
        axle,
        (left - right) + lv.wheel_width,
        lv.wheel_height,
        vehicle.m_w,
        vehicle.J_roll,
    )
    mass = Body(
        "sprung_mass",
        f"sprung mass {entry_symbol('m_s')} = {vehicle.m_s:.4g} kg",
        0.0,
        mid,
        sprung,
        width,
        lv.sprung_height,
        vehicle.m_s,
    )
    springs = []
    for side, name in ((-1.0, "primary_right"), (1.0, "primary_left")):
        y = mid + side * vehicle.d * per_m
        start, end = (y, axle + 0.08), (y, sprung - 0.5 * lv.sprung_height)
        springs.append(
            SpringDamper(
                name,
                "z",
                ("wheelset", "sprung_mass"),
                (side * vehicle.d, 0.0),
                start,
                end,
                "k_z",
                "c_z",
                vehicle.k_z,
                vehicle.c_z,
            )
        )
        springs.append(
            SpringDamper(
                name,
                "y",
                ("wheelset", "sprung_mass"),
                (side * vehicle.d, 0.0),
                start,
                end,
                "k_y",
                "c_y",
                vehicle.k_y,
                vehicle.c_y,
            )
        )
    return (wheelset, mass), tuple(springs)


def _contacts(
    route: Route | None,
    params: CoRunningParameters,
    x: float,
    vehicle: Vehicle,
    where: Mapping[str, Body],
    to_drawn: Callable[[float], float],
) -> tuple[Contact, ...]:
    if route is None:
        return ()
    wheelset = where["wheelset"]
    bottom = wheelset.z - 0.5 * wheelset.height
    per_m = (to_drawn(vehicle.b) - to_drawn(-vehicle.b)) / (2.0 * vehicle.b)
    out = []
    for pair in route.pairs_in(params.zone):
        if pair.rail not in params.active_rails or not pair.tread_active(x):
            continue
        body = where[f"m0_{pair.rail}" if params.layers == 3 else pair.rail]
        wheel_y = wheelset.y_drawn + pair.side * vehicle.b * per_m
        out.append(
            Contact(
                pair.name,
                pair.wheel,
                pair.rail,
                body.name,
                (wheel_y, bottom),
                (body.y_drawn, body.z + 0.5 * body.height),
            )
        )
    return tuple(out)


# ------------------------------------------------------------------------------------- drawing


def _spring_symbol(
    ax: Any,
    start: tuple[float, float],
    end: tuple[float, float],
    offset: float,
    color: str = "0.15",
    coils: int = 4,
    lw: float = 1.0,
) -> None:
    """A spring || dashpot pair between two points (vertical or horizontal)."""
    (y0, z0), (y1, z1) = start, end
    vertical = abs(y1 - y0) < 1e-12
    along0, along1 = (z0, z1) if vertical else (y0, y1)
    across = y0 if vertical else z0

    def line(a: Sequence[float], c: Sequence[float]) -> None:
        pts = (np.array(c), np.array(a)) if vertical else (np.array(a), np.array(c))
        ax.plot(*pts, color=color, lw=lw, solid_capstyle="butt")

    length = along1 - along0
    # common end plates
    line([along0, along0], [across - offset, across + offset])
    line([along1, along1], [across - offset, across + offset])
    # spring branch at -offset
    a = np.linspace(along0 + 0.2 * length, along0 + 0.8 * length, 2 * coils + 1)
    zig = np.array([0.0] + [(-1) ** k * 0.45 * offset for k in range(1, 2 * coils)] + [0.0])
    line([along0, *a, along1], [across - offset, *(across - offset + zig), across - offset])
    # dashpot branch at +offset: rod, cylinder (open towards the piston side), piston
    c = across + offset
    w = 0.45 * offset
    line([along0, along0 + 0.35 * length], [c, c])
    line([along0 + 0.35 * length, along0 + 0.35 * length], [c - w, c + w])
    line([along0 + 0.35 * length, along0 + 0.65 * length], [c - w, c - w])
    line([along0 + 0.35 * length, along0 + 0.65 * length], [c + w, c + w])
    line([along0 + 0.52 * length, along0 + 0.52 * length], [c - 0.7 * w, c + 0.7 * w])
    line([along0 + 0.52 * length, along1], [c, c])


def _hatch(ax: Any, y0: float, y1: float, z: float, dz: float, vertical: bool = False) -> None:
    """Ground symbol: a line with short hatches below (or, vertical, to the left)."""
    if vertical:
        ax.plot([y0, y0], [z - dz, z + dz], color="0.2", lw=1.2)
        for zz in np.linspace(z - dz, z + dz, 7):
            ax.plot([y0 - 0.06, y0], [zz - 0.06, zz], color="0.4", lw=0.7)
        return
    ax.plot([y0, y1], [z, z], color="0.2", lw=1.2)
    for yy in np.arange(y0, y1, 0.08):
        ax.plot([yy, yy + 0.05], [z - dz, z], color="0.4", lw=0.7)


def _block(springs: Sequence[SpringDamper]) -> str:
    return "\n".join(
        f"{entry_symbol(s.k_name)} = {format_stiffness(s.k)}\n"
        f"{entry_symbol(s.c_name)} = {format_damping(s.c)}"
        for s in springs
    )


def draw_cross_section(
    params: CoRunningParameters,
    x: float,
    route: Route | str | None = None,
    vehicle: Vehicle | None = None,
    ax: Any = None,
    *,
    min_gap: float = 1.25,
    fontsize: float = 8.0,
) -> Any:
    """Draw the co-running cross-section of a zone at x as it is built (paper Figs 2, 3).

    Every body and spring-damper comes from :func:`cross_section_geometry` (the Exudyn
    builder's spring list, values at x): sleeper, active rails, m_0 layer (three
    layers), ballast springs to ground, lateral ballast spring, rail pads, and with a
    vehicle the wheelset, its primary suspension and sprung mass. Each spring || dashpot
    is labelled with its entry names and values (MN/m, kN s/m).

    Parameters
    ----------
    params : CoRunningParameters
        Parameter set of the zone (2 or 3 layers, derived or published).
    x : float
        Position (m) in the zone.
    route : Route or str, optional
        Route whose rail positions (and contacts, with a vehicle) are drawn.
    vehicle : Vehicle, optional
        Draw the wheelset above the track.
    ax : matplotlib Axes, optional
        Axes to draw into; a new figure if None.
    min_gap : float
        Smallest drawn distance (m) between rails.
    fontsize : float
        Label font size (points).

    Returns
    -------
    matplotlib Axes
        The axes drawn into.
    """
    plt = pyplot()
    Rectangle = patches().Rectangle

    geo = cross_section_geometry(params, x, route, vehicle, min_gap)
    lv = _Levels()
    ground = geo.body("ground")
    y_lo, y_hi = ground.y_drawn - 0.5 * ground.width, ground.y_drawn + 0.5 * ground.width
    if ax is None:
        top = max(b.z + 0.5 * b.height for b in geo.bodies)
        _, ax = plt.subplots(figsize=(2.0 * (y_hi - y_lo) + 0.6, 1.25 * top + 1.4))
    label = {"fontsize": fontsize, "va": "center", "linespacing": 1.25}
    box = {"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.85}
    colours = {
        "sleeper": "#c9b48f",
        "rail": "#8fa9c9",
        "layer": "#c98f8f",
        "wheelset": "#b0b0b0",
        "sprung_mass": "#d9d9d9",
    }
    _hatch(ax, y_lo, y_hi, lv.ground, 0.08)
    for b in geo.bodies:
        if b.name == "ground":
            continue
        kind = "rail" if b.name in RAIL_SLOTS else "layer" if b.name.startswith("m0_") else b.name
        if b.name == "wheelset":
            _draw_wheelset(ax, b, geo, lv, colours["wheelset"], fontsize)
            continue
        ax.add_patch(
            Rectangle(
                (b.y_drawn - 0.5 * b.width, b.z - 0.5 * b.height),
                b.width,
                b.height,
                fc=colours[kind],
                ec="0.2",
                lw=1.0,
                zorder=3,
            )
        )
        if kind == "rail":
            slot, rest = b.label.split("\n", 1)
            ax.text(
                b.y_drawn,
                b.z,
                slot.split()[0],
                ha="center",
                va="center",
                fontsize=fontsize,
                weight="bold",
                zorder=4,
            )
            ax.text(
                b.y_drawn + 0.5 * b.width + 0.04,
                b.z,
                f"{slot.split()[1]} rail\n{rest}",
                ha="left",
                **{**label, "fontsize": fontsize - 0.5},
                zorder=5,
            )
        elif kind == "layer":
            ax.text(b.y_drawn + 0.5 * b.width + 0.04, b.z, b.label, ha="left", **label, zorder=5)
        else:
            ax.text(b.y_drawn, b.z, b.label, ha="center", **label, zorder=4)
    sleeper = geo.body("sleeper")  # its centre, where the lateral ballast spring acts
    ax.plot(
        [_centre_mark(geo, sleeper.y)],
        [sleeper.z - 0.5 * sleeper.height],
        marker="^",
        color="k",
        ms=5,
        zorder=5,
    )
    _draw_springs(ax, geo.springs, {b.name: b for b in geo.bodies}, label, box)
    _draw_suspension(ax, geo.suspension, label, box)
    for c in geo.contacts:
        ax.plot(
            *zip(c.from_point, c.to_point, strict=True), color="tab:red", ls=":", lw=1.4, zorder=2
        )
    where = f", {geo.route} route" if geo.route else ""
    ax.set_title(
        f"{geo.turnout}: co-running cross-section, zone {geo.zone} ({geo.zone_name}), "
        f"x = {geo.x:g} m\n{geo.layers}-layer model, {geo.source} parameters{where}",
        fontsize=fontsize + 2,
    )
    note = (
        "Lateral positions from the model (y in m, positive left, looking along x); "
        "heights schematic (the model has every body at z = 0).\n"
        "Each connector acts in z and y between the same two points; the lateral ballast "
        "spring acts at the sleeper centre (triangle)."
    )
    if geo.contacts:
        note += " Red dotted: wheel/rail (Hertz) contacts active at x."
    if geo.spread_rails:
        note += f" Rails {', '.join(geo.spread_rails)} are drawn apart (model y in their labels)."
    ax.text(
        0.0,
        -0.01,
        note,
        transform=ax.transAxes,
        ha="left",
        va="top",
        fontsize=fontsize - 1,
        color="0.3",
        wrap=True,
    )
    ax.set_xlim(y_lo - 0.05, y_hi + 0.05)
    ax.set_ylim(lv.ground - 0.15, max(b.z + 0.5 * b.height for b in geo.bodies) + 0.15)
    ax.set_axis_off()
    return ax


def _centre_mark(geo: CrossSection, centre_model_y: float) -> float:
    """Drawn position of the sleeper centre (model y), through the same lateral map."""
    model = {b.name: b.y for b in geo.bodies if b.name in RAIL_SLOTS}
    drawn = {b.name: b.y_drawn for b in geo.bodies if b.name in RAIL_SLOTS}
    return _lateral_map(model, drawn)(centre_model_y)


def _draw_springs(
    ax: Any, springs: Sequence[SpringDamper], bodies: Mapping[str, Body], label: dict, box: dict
) -> None:
    by_connector: dict[str, list[SpringDamper]] = {}
    for s in springs:
        by_connector.setdefault(s.name, []).append(s)
    for parts in by_connector.values():
        for s in parts:
            if s.direction == "z":
                _spring_symbol(ax, s.from_point, s.to_point, offset=0.045)
            else:
                _spring_symbol(ax, s.from_point, s.to_point, offset=0.06, coils=3)
                if s.bodies[0] == "ground":
                    _hatch(
                        ax, s.from_point[0], s.from_point[0], s.from_point[1], 0.18, vertical=True
                    )
                else:  # post on the lower body (a bracket from its top left corner for a rail)
                    y, z = s.from_point
                    lower = bodies[s.bodies[0]]
                    top = lower.z + 0.5 * lower.height
                    ys, zs = [y, y], [top, z + 0.09]
                    if s.bodies[0] != "sleeper":
                        ys, zs = [lower.y_drawn - 0.5 * lower.width, *ys], [top, *zs]
                    ax.plot(ys, zs, color="0.2", lw=1.6, zorder=2)
        vertical = [s for s in parts if s.direction == "z"]
        if vertical:  # one block right of the vertical symbol: z lines, then y lines
            s = vertical[0]
            mid = 0.5 * (s.from_point[1] + s.to_point[1])
            ax.text(
                s.from_point[0] + 0.1, mid, _block(parts), ha="left", bbox=box, zorder=6, **label
            )
        else:  # lateral ballast spring: label above it
            s = parts[0]
            ax.text(
                0.5 * (s.from_point[0] + s.to_point[0]) - 0.1,
                s.from_point[1] - 0.2,
                _block(parts),
                ha="center",
                va="top",
                bbox=box,
                zorder=6,
                **{k: v for k, v in label.items() if k != "va"},
            )


def _draw_suspension(ax: Any, springs: Sequence[SpringDamper], label: dict, box: dict) -> None:
    vertical = [s for s in springs if s.direction == "z"]
    for s in vertical:
        _spring_symbol(ax, s.from_point, s.to_point, offset=0.05)
        parts = [p for p in springs if p.name == s.name]
        text = (
            _block(parts)
            .replace("k_{z}", "k_{p,z}")
            .replace("c_{z}", "c_{p,z}")
            .replace("k_{y}", "k_{p,y}")
            .replace("c_{y}", "c_{p,y}")
        )
        side = "left" if s.name.endswith("left") else "right"
        mid = 0.5 * (s.from_point[1] + s.to_point[1])
        dy = 0.12 if side == "left" else -0.12
        ax.text(
            s.from_point[0] + dy,
            mid,
            f"primary, {side}\n{text}",
            ha="left" if side == "left" else "right",
            bbox=box,
            zorder=6,
            **label,
        )


def _draw_wheelset(
    ax: Any, b: Body, geo: CrossSection, lv: _Levels, colour: str, fontsize: float
) -> None:
    Polygon, Rectangle = patches().Polygon, patches().Rectangle

    half = 0.5 * (b.width - lv.wheel_width)
    bottom = b.z - 0.5 * b.height
    for side in (-1.0, 1.0):
        y = b.y_drawn + side * half
        w = lv.wheel_width
        inner = -side  # flange on the inner side of each wheel
        flange_y = y + inner * 0.5 * w
        pts = [
            (y - 0.5 * w, bottom),
            (y + 0.5 * w, bottom),
            (y + 0.5 * w, bottom + b.height),
            (y - 0.5 * w, bottom + b.height),
        ]
        ax.add_patch(Polygon(pts, closed=True, fc=colour, ec="0.2", lw=1.0, zorder=3))
        ax.add_patch(
            Polygon(
                [
                    (flange_y, bottom + 0.1),
                    (flange_y, bottom - 0.12),
                    (flange_y - inner * 0.05, bottom + 0.05),
                ],
                closed=True,
                fc=colour,
                ec="0.2",
                lw=1.0,
                zorder=3,
            )
        )
    ax.add_patch(
        Rectangle(
            (b.y_drawn - half, b.z - 0.06), 2 * half, 0.12, fc=colour, ec="0.2", lw=1.0, zorder=2
        )
    )
    ax.text(
        b.y_drawn,
        b.z + 0.5 * b.height + 0.05,
        b.label,
        ha="center",
        va="bottom",
        fontsize=fontsize,
        bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.85},
        zorder=6,
    )


# ----------------------------------------------------------------------------------- animation


def passage_frames(n_samples: int, every: int | None = None, max_frames: int = 150) -> np.ndarray:
    """Sample indices of an animation's frames: every ``every``-th sample from the first.

    Parameters
    ----------
    n_samples : int
        Number of output samples of the passage.
    every : int, optional
        Take every ``every``-th sample; default: the smallest step giving at most
        ``max_frames`` frames.
    max_frames : int
        Frame budget used when ``every`` is None.

    Returns
    -------
    numpy.ndarray of int
        Increasing indices into the passage's output samples, starting at 0.
    """
    if n_samples < 1:
        raise ValueError("a passage without samples cannot be animated")
    step = max(1, math.ceil(n_samples / max_frames)) if every is None else int(every)
    if step < 1:
        raise ValueError(f"every must be >= 1, got {every}")
    return np.arange(0, n_samples, step)


def _rail_outline(y: float, z: float) -> np.ndarray:
    """A UIC60-like rail section (m): head 72 mm, web 16.5 mm, foot 150 mm, height 172 mm."""
    h = [
        (-0.036, 0.0),
        (0.036, 0.0),
        (0.036, -0.05),
        (0.008, -0.06),
        (0.008, -0.15),
        (0.075, -0.16),
        (0.075, -0.172),
        (-0.075, -0.172),
        (-0.075, -0.16),
        (-0.008, -0.15),
        (-0.008, -0.06),
        (-0.036, -0.05),
    ]
    return np.array([(y + a, z + b) for a, b in h])


def _wheelset_outline(b: float, r0: float) -> list[np.ndarray]:
    """Wheel sections (tread contact at (+-b, 0), flange inside) and axle (m, wheelset frame)."""
    out = []
    for side in (-1.0, 1.0):
        c, i = side * b, -side  # i points towards the track centre
        out.append(
            np.array(
                [
                    (c - i * 0.075, 0.03),
                    (c - i * 0.075, 0.004),
                    (c + i * 0.035, 0.0),
                    (c + i * 0.045, -0.028),
                    (c + i * 0.06, -0.03),
                    (c + i * 0.068, 0.0),
                    (c + i * 0.068, 0.06),
                    (c + i * 0.025, 0.1),
                    (c + i * 0.025, r0 - 0.12),
                    (c + i * 0.06, r0 - 0.1),
                    (c + i * 0.06, r0 + 0.1),
                    (c - i * 0.035, r0 + 0.1),
                    (c - i * 0.035, 0.1),
                    (c - i * 0.075, 0.06),
                ]
            )
        )
    out.append(
        np.array(
            [
                (-b + 0.06, r0 - 0.07),
                (b - 0.06, r0 - 0.07),
                (b - 0.06, r0 + 0.07),
                (-b + 0.06, r0 + 0.07),
            ]
        )
    )
    return out


def _nice(value: float) -> float:
    """The largest of 1, 2, 5 x 10^n not above value."""
    e = 10.0 ** math.floor(math.log10(value))
    return max(m * e for m in (1.0, 2.0, 5.0) if m * e <= value)


def animate_passage(
    result: Any,
    path: str | Path,
    every: int | None = None,
    scale: float = 200.0,
    fps: float = 15.0,
    *,
    turnout: Turnout | None = None,
    vehicle: Vehicle | None = None,
    max_frames: int = 150,
    dpi: float = 90.0,
    force_scale: float | None = None,
) -> Path:
    """Write a GIF of a passage's cross-section: wheelset and rails moving, forces as arrows.

    Each frame shows the wheelset (a rigid axle with two wheels, at its y, z and roll about
    its reference point at contact height, as in
    :mod:`~exudyn_turnout.passage.contact.height_table`),
    the rails the wheels touch (y, z, and the route's rail height under the wheel) with
    their unloaded outlines dashed, all displacements multiplied by ``scale``, and the
    contact forces on the rails as arrows (kN, with a scale key); the title gives x, t and
    the zone.

    Parameters
    ----------
    result : PassageResult
        From :func:`~exudyn_turnout.passage.run.simulate_passage` (co-running track).
    path : str or Path
        GIF file to write (replaced if it exists).
    every : int, optional
        Take every ``every``-th output sample (:func:`passage_frames`); default: at most
        ``max_frames`` frames.
    scale : float
        Displacement magnification (200: 1 mm is drawn as 0.2 m).
    fps : float
        Frames per second of the GIF.
    turnout : Turnout, optional
        The turnout of the run (rail positions and height profiles); default the packaged one.
    vehicle : Vehicle, optional
        The vehicle of the run (wheel radius, b); default the packaged one.
    max_frames : int
        Frame budget when ``every`` is None.
    dpi : float
        Resolution of the frames (dots per inch of a 7 x 5.4 inch frame).
    force_scale : float, optional
        Arrow length per force (m/kN); default: the largest normal force drawn 0.6 m long.

    Returns
    -------
    Path
        The GIF written.
    """
    plt = pyplot()
    FancyArrowPatch, Polygon = patches().FancyArrowPatch, patches().Polygon

    from exudyn_turnout.inputs.turnout import load_turnout
    from exudyn_turnout.inputs.vehicle import load_vehicle

    turnout = load_turnout() if turnout is None else turnout
    vehicle = load_vehicle() if vehicle is None else vehicle
    route = load_route(turnout, result.settings.route)
    cols = result.columns
    frames = [int(i) for i in passage_frames(len(cols["t_s"]), every, max_frames)]
    slots = [r for r in RAIL_SLOTS if f"z_rail_{r}_m" in cols]
    forces = [
        tuple(n.split("_")[1:3])
        for n in cols
        if n.startswith("Fz_") and n.count("_") == 3 and n.split("_")[2] in slots
    ]
    peak = max([float(np.nanmax(np.abs(cols[f"Fz_{w}_{r}_N"]))) for w, r in forces] + [1.0])
    per_kn = force_scale if force_scale is not None else 0.6 / (peak / 1e3)
    key = _nice(0.5 * peak / 1e3)
    ys = [-vehicle.b, vehicle.b]
    for i in frames:  # lateral extent: the rails drawn in some frame
        zone = route.zone(turnout.zone_at(float(cols["x_m"][i])))
        ys += [
            zone.rail_y[r]
            for r in slots
            if r in zone.active_rails and math.isfinite(float(cols[f"z_rail_{r}_m"][i]))
        ]
    y_lo, y_hi = min(ys) - 0.75, max(ys) + 0.75
    z_lo, z_hi = -1.05, vehicle.r0 + 0.3
    width = 7.0
    fig, ax = plt.subplots(figsize=(width, width * (z_hi - z_lo + 0.5) / (y_hi - y_lo) + 0.3))
    ax.set_xlim(y_lo, y_hi)
    ax.set_ylim(z_lo, z_hi)
    ax.set_aspect("equal")
    ax.set_xlabel("y (m, positive left); vertical and lateral displacements magnified", fontsize=8)
    ax.tick_params(labelsize=7)
    ax.set_yticks([])
    outline = _wheelset_outline(vehicle.b, vehicle.r0)
    for poly in outline:
        ax.add_patch(Polygon(poly, closed=True, fill=False, ec="0.6", ls="--", lw=0.8))
    wheel_parts = [
        Polygon(poly, closed=True, fc="#b0b0b0", ec="0.2", lw=0.9, zorder=3) for poly in outline
    ]
    for part in wheel_parts:
        ax.add_patch(part)
    rails = {}  # slot -> (unloaded outline, moved outline, label)
    for r in slots:
        nominal = Polygon(
            _rail_outline(0.0, 0.0), closed=True, fill=False, ec="0.6", ls="--", lw=0.8
        )
        moved = Polygon(
            _rail_outline(0.0, 0.0), closed=True, fc="#8fa9c9", ec="0.2", lw=0.9, zorder=2
        )
        ax.add_patch(nominal)
        ax.add_patch(moved)
        rails[r] = (
            nominal,
            moved,
            ax.text(0.0, -0.5, r, ha="center", va="top", fontsize=8, color="0.3"),
        )
    arrows = {}
    for wheel, r in forces:
        arrow = FancyArrowPatch(
            (0, 0),
            (0, 0),
            arrowstyle="-|>",
            mutation_scale=11,
            color="tab:red",
            lw=1.6,
            zorder=5,
        )
        ax.add_patch(arrow)
        text = ax.text(
            0,
            0,
            "",
            fontsize=7.5,
            color="tab:red",
            va="center",
            ha="right" if wheel == "right" else "left",
            zorder=6,
        )
        arrows[(wheel, r)] = (arrow, text)
    ky = y_lo + 0.1
    ax.add_patch(
        FancyArrowPatch(
            (ky, z_lo + 0.12),
            (ky + key * per_kn, z_lo + 0.12),
            arrowstyle="-|>",
            mutation_scale=11,
            color="tab:red",
            lw=1.6,
        )
    )
    ax.text(
        ky,
        z_lo + 0.18,
        f"{key:g} kN (force on the rail)",
        fontsize=7.5,
        color="tab:red",
        va="bottom",
    )
    ax.text(
        y_hi - 0.05,
        z_lo + 0.08,
        f"displacements x{scale:g} (1 mm drawn as {scale / 1e3:g} m)\ndashed: unloaded position",
        ha="right",
        va="bottom",
        fontsize=7.5,
        color="0.3",
    )
    title = ax.set_title("", fontsize=9, family="monospace")
    settings = result.settings
    head = (
        f"{turnout.name}, {route.name} route, {settings.layers}-layer, {settings.speed_kmh:g} km/h"
    )

    def top_of(r: str, x: float) -> float:
        heights = [p.height(x) for p in route.pairs if p.rail == r and p.tread_active(x)]
        return max(heights) if heights else 0.0

    def draw(i: int) -> list:
        x, t = float(cols["x_m"][i]), float(cols["t_s"][i])
        zone = route.zone(turnout.zone_at(x))
        place = {}
        for r, (nominal, moved, label) in rails.items():
            y_r, z_r = float(cols[f"y_rail_{r}_m"][i]), float(cols[f"z_rail_{r}_m"][i])
            shown = r in zone.active_rails and math.isfinite(y_r) and math.isfinite(z_r)
            for artist in (nominal, moved, label):
                artist.set_visible(shown)
            if shown:
                y0 = zone.rail_y[r]
                place[r] = (y0 + scale * y_r, scale * (z_r + top_of(r, x)))
                nominal.set_xy(_rail_outline(y0, 0.0))
                moved.set_xy(_rail_outline(*place[r]))
                label.set_position((y0, -0.5))
                label.set_horizontalalignment("center")
        shown_y = sorted((zone.rail_y[r], r) for r in place)
        for (ya, ra), (yb, rb) in itertools.pairwise(shown_y):
            # close rails (a check rail, a blade beside its stock rail): labels apart
            if yb - ya < 0.2:
                rails[ra][2].set_horizontalalignment("right")
                rails[ra][2].set_position((ya - 0.02, -0.5))
                rails[rb][2].set_horizontalalignment("left")
                rails[rb][2].set_position((yb + 0.02, -0.5))
        yw, zw, roll = (
            float(cols[n][i]) for n in ("y_wheelset_m", "z_wheelset_m", "roll_wheelset_rad")
        )
        cos_roll, sin_roll = math.cos(scale * roll), math.sin(scale * roll)
        rot = np.array([[cos_roll, -sin_roll], [sin_roll, cos_roll]])
        for poly, part in zip(outline, wheel_parts, strict=True):
            # roll about the contact-level centre
            part.set_xy(poly @ rot.T + [scale * yw, scale * zw])
        for (wheel, r), (arrow, text) in arrows.items():
            fz, fy = float(cols[f"Fz_{wheel}_{r}_N"][i]), float(cols[f"Fy_{wheel}_{r}_N"][i])
            shown = r in place and math.hypot(fz, fy) >= 100.0
            arrow.set_visible(shown)
            text.set_visible(shown)
            if shown:
                y0, z0 = place[r]
                tip = (y0 + fy / 1e3 * per_kn, z0 - fz / 1e3 * per_kn)
                arrow.set_positions((y0, z0), tip)
                side = -1.0 if wheel == "right" else 1.0
                text.set_position(
                    (
                        min(y0, tip[0]) - 0.1 if side < 0 else max(y0, tip[0]) + 0.1,
                        0.5 * (z0 + tip[1]),
                    )
                )
                text.set_text(
                    f"{wheel} wheel on {r}\nFz = {fz / 1e3:.1f} kN\nFy = {fy / 1e3:.1f} kN"
                )
        title.set_text(f"{head}\nx = {x:7.3f} m   t = {t * 1e3:6.1f} ms   zone {zone.index}")
        return []

    fig.tight_layout()
    out = Path(path)
    # PillowWriter only computes int(1000 / fps): a float fps works
    writer = pillow_writer(fps)
    try:
        with writer.saving(fig, str(out), dpi):
            for i in frames:
                draw(i)
                writer.grab_frame()
    finally:
        plt.close(fig)
    return out
