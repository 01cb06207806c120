"""The co-running cross-section as its figure shows it: bodies, spring-dampers, contacts.

:func:`cross_section_geometry` lists the bodies and spring-dampers of the co-running
cross-section of a zone at a position x, taken from the same spring list the Exudyn
builder (:mod:`exudyn_turnout.corunning.track`) turns into ``CartesianSpringDamper`` objects,
with their values at x (``params.at(x)``), and their drawn positions; the labels of entries
and values (:func:`entry_symbol`, :func:`format_stiffness`, :func:`format_damping`,
:func:`spring_label`). Data only: :func:`exudyn_turnout.plotting.model.draw_cross_section`
draws it.

Drawing coordinates: lateral positions are the model's (m, y positive left, seen in the
running direction), except that rails closer than ``min_gap`` are drawn apart (their
model y stays in :attr:`Body.y` and in the labels, :func:`lateral_map` maps one to the
other); heights are schematic levels (:class:`DrawingLevels`), since the model places
every body at z = 0 and carries displacements only.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from exudyn_turnout.corunning.parameters import CoRunningParameters
from exudyn_turnout.inputs.routes import Route, load_route
from exudyn_turnout.inputs.turnout import RAIL_SLOTS
from exudyn_turnout.inputs.vehicle import Vehicle

__all__ = [
    "Body",
    "Contact",
    "CrossSection",
    "DrawingLevels",
    "SpringDamper",
    "cross_section_geometry",
    "entry_symbol",
    "format_damping",
    "format_stiffness",
    "lateral_map",
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
class DrawingLevels:
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


def lateral_map(
    model_y: Mapping[str, float], drawn: Mapping[str, float]
) -> Callable[[float], float]:
    """Piecewise-linear map model y -> drawn y through the rails (slope 1 outside them).

    Parameters
    ----------
    model_y : Mapping of str to float
        m, model lateral position of each rail.
    drawn : Mapping of str to float
        m, drawn lateral position of the same rails.

    Returns
    -------
    callable
        ``to_drawn(y) -> float``: the drawn position of model position y (m).
    """
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
    zone, lv = params.zone, DrawingLevels()
    rails = [r for r in RAIL_SLOTS if r in params.active_rails]
    model_y = {r: float(zone.rail_y[r]) for r in rails}
    drawn = _spread(model_y, min_gap)
    to_drawn = lateral_map(model_y, drawn)
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
    lv: DrawingLevels,
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
    lv: DrawingLevels,
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
    vehicle: Vehicle, to_drawn: Callable[[float], float], top: float, lv: DrawingLevels
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
