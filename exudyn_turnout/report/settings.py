"""What the validation report needs to know about a turnout: the ``[report]`` section.

Every turnout-specific choice of the report (:mod:`exudyn_turnout.report.metrics`) comes from
the turnout file or from the model, never from code: which routes are run, at which
speed, which wheel and which forces are plotted, where the receptances are taken, the
short passage window of ``validate --quick``, which FE rails are the "stock" and the
"check" rails of the paper's statements on Fig. 1. :func:`report_settings` reads the
optional ``[report]`` section of a turnout file into the frozen :class:`ReportSettings`
and fills every missing field with a default derived from the rest of the file:

================================  ===========================================================
field                             default (when absent)
================================  ===========================================================
``routes`` (``[report.routes]``)  every route of ``[routes]``, in file order
``routes.<r>.speed_kmh``          straight route: 100 km/h; curved route (radius R from the
                                  route's largest ``|curvature|``): the speed of a steady
                                  lateral acceleration ``lateral_acceleration`` without cant,
                                  sqrt(a R), rounded down to 5 km/h, at most 100 km/h
``routes.<r>.wheel``              ``"right"`` (the paper's Figs 7, 8)
``routes.<r>.forces``             ``["Fz"]`` on a straight route, ``["Fy"]`` on a curved one
                                  (the paper's Fig. 7 and Fig. 8)
``routes.<r>.fe_slots``           the route's name: the key of ``[layout.slots]`` that maps
                                  this route's rail slots to FE rails
``lateral_acceleration``          0.65 m/s^2 (~100 mm cant deficiency on standard gauge)
``receptance_route``              the first route of ``routes``
``receptance_wheel``              the wheel of that route with a tread contact on
                                  ``receptance_slot``
``receptance_slot``               ``"r2"`` (switch rail in the switch panel, crossing nose in
                                  the crossing panel, Table 3)
``quick_passage_x``               3.5 m centred on the crossing dip (the lowest point of the
                                  receptance wheel's path in the crossing region), rounded
                                  outwards to 0.1 m, clipped to the turnout
``crossing_plot_window``          [0.8, 2.2] m before / after the crossing dip
``stock_rails``                   FE layout rails of the reference rail type over their whole
                                  length that start at ``layout.x_start`` (the rails that run
                                  into the turnout from plain track)
``check_rails``                   FE layout rails whose every segment is of a rail type that
                                  slot r3 (Table 3: check rail) has in a zone where r3 is
                                  active
``speeds_note``                   a sentence naming how the speeds were chosen
================================  ===========================================================

Derived from the model, not settable: the regions "switch" and "crossing" (``[regions]``,
defaults as the passage's: 0-10 m and the last zone), the x of the switch-rail claim (the
end ``x_max`` of the Eq 10 polynomial ``K_sw``, beyond which the paper holds it constant),
the reference rail type (``[turnout].reference_rail_type``, default ``"stock"``) and each
route's radius (1 / its largest ``|curvature|``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from exudyn_turnout.fe.check_rail import check_rail_types
from exudyn_turnout.inputs.routes import WHEELS, dip_angle, load_route, route_names
from exudyn_turnout.inputs.toml_fields import FieldReader
from exudyn_turnout.inputs.turnout import RAIL_SLOTS, Turnout, TurnoutFileError

__all__ = [
    "quick_passage_x",
    "REGIONS",
    "FORCES",
    "ReportRoute",
    "ReportSettings",
    "report_settings",
    "regions",
    "stock_rails",
    "check_rails",
]

#: Regions where peaks are taken (``[regions]`` of the turnout file).
REGIONS = ("switch", "crossing")
#: Force quantities a report route can plot: vertical and lateral force on the rail.
FORCES = ("Fz", "Fy")

_KEYS = {
    "routes",
    "lateral_acceleration",
    "receptance_route",
    "receptance_wheel",
    "receptance_slot",
    "quick_passage_x",
    "crossing_plot_window",
    "stock_rails",
    "check_rails",
    "speeds_note",
}
_ROUTE_KEYS = {"speed_kmh", "wheel", "forces", "fe_slots"}
_STRAIGHT_SPEED_KMH = 100.0  # default speed of a straight route (a usual line speed)
_QUICK_HALF_WIDTH = 1.75  # m, half of the default quick passage window around the crossing dip


@dataclass(frozen=True)
class ReportRoute:
    """One route the report runs (section 3 of the report: contact forces)."""

    name: str  #: route of ``[routes]``
    speed_kmh: float  #: km/h
    wheel: str  #: "right" or "left": the wheel whose forces are plotted and compared
    forces: tuple[str, ...]  #: "Fz" and/or "Fy", plotted at the switch and at the crossing
    fe_slots: str  #: key of ``[layout.slots]`` for this route's FE rails
    radius: float  #: m, 1 / largest |curvature| of the route (inf: straight)

    @property
    def signals(self) -> tuple[tuple[str, str], ...]:
        """(force, region) pairs plotted for this route, e.g. ``("Fz", "crossing")``."""
        return tuple((q, r) for q in self.forces for r in REGIONS)


@dataclass(frozen=True)
class ReportSettings:
    """The turnout-specific settings of the validation report (see the module docstring)."""

    source: str  #: turnout file name, for messages
    routes: tuple[ReportRoute, ...]  #: routes run in section 3 (contact forces), in report order
    regions: Mapping[str, tuple[float, float]]  #: m, "switch" and "crossing" (``[regions]``)
    lateral_acceleration: float  #: m/s^2, for the default speed of curved routes
    receptance_route: str  #: route whose wheel path gives the receptance positions
    receptance_wheel: str  #: its wheel running over ``receptance_slot``
    receptance_slot: str  #: co-running rail slot of the receptances
    #: m, passage x range of ``validate --quick``; None: not given, derived by
    #: :func:`quick_passage_x` (3.5 m centred on the crossing dip)
    quick_passage_x: tuple[float, float] | None
    crossing_plot_window: tuple[float, float]  #: m before / after the crossing dip in figures
    switch_claim_x: float  #: m, x of the switch-rail stiffness claim (``K_sw.x_max``)
    reference_rail_type: str  #: the plain-track rail type (Eqs 11, 15 denominators)
    stock_rails_given: tuple[str, ...] | None  #: FE rail ids, None: derived from the layout
    check_rails_given: tuple[str, ...] | None  #: FE rail ids, None: derived from the layout
    speeds_note: str  #: how the speeds were chosen (printed in the report)

    def route(self, name: str) -> ReportRoute:
        """The report route ``name``.

        Parameters
        ----------
        name : str
            A route of ``[routes]`` that the report runs.

        Returns
        -------
        ReportRoute

        Raises
        ------
        KeyError
            The report does not run that route (the message names those it runs).
        """
        for r in self.routes:
            if r.name == name:
                return r
        raise KeyError(
            f"route {name!r} is not run by the report (routes: "
            f"{', '.join(r.name for r in self.routes)})"
        )

    @property
    def speeds_kmh(self) -> tuple[tuple[str, float], ...]:
        """(route, km/h) per report route."""
        return tuple((r.name, r.speed_kmh) for r in self.routes)

    @property
    def impact_route(self) -> str | None:
        """The first route whose vertical force at the crossing is plotted (claim F4), or None."""
        return next((r.name for r in self.routes if ("Fz", "crossing") in r.signals), None)

    @property
    def lateral_route(self) -> str | None:
        """The first route whose lateral force at the crossing is plotted (claim F6), or None."""
        return next((r.name for r in self.routes if ("Fy", "crossing") in r.signals), None)


def _filename(turnout: Turnout) -> str:
    return Path(str(turnout.source)).name


def regions(turnout: Turnout) -> dict[str, tuple[float, float]]:
    """``[regions]`` of the turnout file: "switch", "crossing" -> (x_from, x_to) in m.

    Defaults as :mod:`exudyn_turnout.passage.results` (whose peaks the report reads): switch 0-10 m
    from the toe, crossing the last zone.

    Parameters
    ----------
    turnout : Turnout

    Returns
    -------
    dict
        "switch" and "crossing" -> (x_from, x_to) in m.

    Raises
    ------
    TurnoutFileError
        A region that is not two increasing finite numbers.
    """
    r = FieldReader(_filename(turnout), turnout.raw)
    defaults = {"switch": (0.0, 10.0), "crossing": (turnout.zones[-1].x_start, turnout.x_max)}
    out = {}
    for name in REGIONS:
        value = r.get(f"regions.{name}", None)
        if value is None:
            out[name] = defaults[name]
            continue
        if not isinstance(value, list) or len(value) != 2:
            raise r.fail(f"regions.{name}", f"must be [x_from, x_to] in metres, got {value!r}")
        a, b = (r.check(f"regions.{name}", v, positive=False) for v in value)
        if not b > a:
            raise r.fail(f"regions.{name}", f"must have x_from < x_to, got [{a:g}, {b:g}]")
        out[name] = (a, b)
    return out


def _radius(turnout: Turnout, route: str) -> float:
    kappa = max(abs(k) for k in load_route(turnout, route).curvature.value)
    return math.inf if kappa == 0 else 1.0 / kappa


def _default_speed(radius: float, a_lat: float) -> float:
    if not math.isfinite(radius):
        return _STRAIGHT_SPEED_KMH
    v = 3.6 * math.sqrt(a_lat * radius)
    return min(_STRAIGHT_SPEED_KMH, max(5.0, 5.0 * math.floor(v / 5.0 + 1e-9)))


def _names(r: FieldReader, field: str) -> tuple[str, ...] | None:
    value = r.get(field, None)
    if value is None:
        return None
    if not isinstance(value, list) or not all(isinstance(v, str) and v for v in value):
        raise r.fail(field, f"must be a list of names, got {value!r}")
    return tuple(value)


def _pair(
    r: FieldReader, field: str, default: tuple[float, float], positive: bool
) -> tuple[float, float]:
    pair = _optional_pair(r, field, positive)
    return default if pair is None else pair


def _optional_pair(r: FieldReader, field: str, positive: bool) -> tuple[float, float] | None:
    """Two numbers [a, b] from ``field`` (lengths >= 0 if ``positive``), None when absent."""
    value = r.get(field, None)
    if value is None:
        return None
    if not isinstance(value, list) or len(value) != 2:
        raise r.fail(field, f"must be two numbers [a, b], got {value!r}")
    a, b = (r.check(field, v, positive=False) for v in value)
    if positive and not (a >= 0 and b >= 0 and a + b > 0):
        raise r.fail(field, f"must be two lengths >= 0, not both 0, got [{a:g}, {b:g}]")
    return a, b


def _route(r: FieldReader, turnout: Turnout, name: str, a_lat: float) -> ReportRoute:
    p = f"report.routes.{name}"
    if name not in route_names(turnout):
        raise r.fail(
            p,
            f"names route {name!r}, which is not in [routes] "
            f"({', '.join(route_names(turnout)) or 'none'})",
        )
    section = r.get(p, {})
    if not isinstance(section, Mapping):
        raise r.fail(p, "must be a table (speed_kmh, wheel, forces, fe_slots)")
    for key in section:
        if key not in _ROUTE_KEYS:
            raise r.fail(
                f"{p}.{key}", f"is not a report route field ({', '.join(sorted(_ROUTE_KEYS))})"
            )
    radius = _radius(turnout, name)
    speed = r.number(p + ".speed_kmh", default=_default_speed(radius, a_lat))
    if speed > 400:
        raise r.fail(p + ".speed_kmh", f"must be <= 400 km/h, got {speed:g}")
    forces = r.get(p + ".forces", ["Fz"] if not math.isfinite(radius) else ["Fy"])
    if not isinstance(forces, list) or not forces or any(f not in FORCES for f in forces):
        raise r.fail(
            p + ".forces", f"must be a non-empty list of {', '.join(FORCES)}, got {forces!r}"
        )
    fe_slots = r.get(p + ".fe_slots", name)
    if not isinstance(fe_slots, str) or not fe_slots:
        raise r.fail(p + ".fe_slots", f"must be a key of [layout.slots], got {fe_slots!r}")
    return ReportRoute(
        name,
        speed,
        r.choice(p + ".wheel", tuple(WHEELS), "right"),
        tuple(dict.fromkeys(forces)),
        fe_slots,
        radius,
    )


def _receptance_wheel(turnout: Turnout, route: str, slot: str) -> str:
    wheels = [p.wheel for p in load_route(turnout, route).pairs if p.rail == slot and p.has_tread]
    if not wheels:
        raise TurnoutFileError(
            f"{_filename(turnout)}: report.receptance_slot {slot} is not under any wheel "
            f"of route {route!r}"
        )
    return wheels[0]


def _speeds_note(routes: tuple[ReportRoute, ...], given: Mapping[str, Any], a_lat: float) -> str:
    derived = [r for r in routes if "speed_kmh" not in given.get(r.name, {})]
    if not derived:
        return "Speeds from the turnout file's [report] section."
    return (
        f"Speeds of {', '.join(r.name for r in derived)} by the report's default: "
        f"{_STRAIGHT_SPEED_KMH:g} km/h on a straight route, on a curved one the speed of a steady "
        f"lateral acceleration of {a_lat:g} m/s^2 without cant, sqrt(a R), rounded down to 5 km/h "
        f"(at most {_STRAIGHT_SPEED_KMH:g} km/h)."
    )


def report_settings(turnout: Turnout) -> ReportSettings:
    """The report settings of a turnout: its ``[report]`` section, defaults from the model.

    Parameters
    ----------
    turnout : Turnout
        From :func:`~exudyn_turnout.inputs.turnout.load_turnout`; ``turnout.raw`` holds the
        optional ``[report]`` section.

    Returns
    -------
    ReportSettings
        Every field filled (see the module docstring for the defaults).

    Raises
    ------
    TurnoutFileError
        A field of ``[report]`` (or ``[regions]``) that cannot be right; the message names
        the file and the field.
    """
    r = FieldReader(_filename(turnout), turnout.raw)
    section = r.get("report", {})
    if not isinstance(section, Mapping):
        raise r.fail("report", "must be a table")
    for key in section:
        if key not in _KEYS:
            raise r.fail(f"report.{key}", f"is not a report field ({', '.join(sorted(_KEYS))})")
    a_lat = r.number("report.lateral_acceleration", default=0.65)
    given = r.get("report.routes", {})
    if not isinstance(given, Mapping):
        raise r.fail("report.routes", "must be tables [report.routes.<route>]")
    names = list(given) or list(route_names(turnout))
    if not names:
        raise r.fail("routes", "is missing (the report runs the routes of the file)")
    routes = tuple(_route(r, turnout, n, a_lat) for n in names)
    rec_route = r.choice("report.receptance_route", tuple(route_names(turnout)), routes[0].name)
    slot = r.choice("report.receptance_slot", RAIL_SLOTS, "r2")
    wheel = r.get("report.receptance_wheel", None)
    wheel = (
        _receptance_wheel(turnout, rec_route, slot)
        if wheel is None
        else r.choice("report.receptance_wheel", tuple(WHEELS))
    )
    reg = regions(turnout)
    quick = _optional_pair(r, "report.quick_passage_x", positive=False)
    if quick is not None and not turnout.x_min <= quick[0] < quick[1] <= turnout.x_max:
        raise r.fail(
            "report.quick_passage_x",
            f"must be an x range within the turnout ({turnout.x_min:g} to "
            f"{turnout.x_max:g} m), got [{quick[0]:g}, {quick[1]:g}]",
        )
    note = r.get("report.speeds_note", None)
    if note is not None and not isinstance(note, str):
        raise r.fail("report.speeds_note", f"must be a text, got {note!r}")
    return ReportSettings(
        source=r.filename,
        routes=routes,
        regions=reg,
        lateral_acceleration=a_lat,
        receptance_route=rec_route,
        receptance_wheel=wheel,
        receptance_slot=slot,
        quick_passage_x=quick,
        crossing_plot_window=_pair(r, "report.crossing_plot_window", (0.8, 2.2), positive=True),
        switch_claim_x=turnout.K_sw.x_max,
        reference_rail_type=str(r.get("turnout.reference_rail_type", "stock")),
        stock_rails_given=_names(r, "report.stock_rails"),
        check_rails_given=_names(r, "report.check_rails"),
        speeds_note=note if note is not None else _speeds_note(routes, given, a_lat),
    )


def quick_passage_x(turnout: Turnout, settings: ReportSettings) -> tuple[float, float]:
    """The passage x range (m) of ``validate --quick``.

    ``report.quick_passage_x`` if the file gives it; otherwise 3.5 m centred on the crossing
    dip (the lowest point of the receptance wheel's path in the crossing region, the same x
    as the crossing receptance), rounded outwards to 0.1 m and clipped to the turnout.
    Derived here, not in :func:`report_settings`, because the dip takes a fine scan of the
    route's height tables.

    Parameters
    ----------
    turnout : Turnout
    settings : ReportSettings
        Of the same turnout (:func:`report_settings`).

    Returns
    -------
    (float, float)
        x_start, x_end in m.
    """
    if settings.quick_passage_x is not None:
        return settings.quick_passage_x
    route = load_route(turnout, settings.receptance_route)
    x_dip = dip_angle(route, settings.receptance_wheel, *settings.regions["crossing"])[0]
    return (
        max(turnout.x_min, math.floor(10.0 * (x_dip - _QUICK_HALF_WIDTH)) / 10.0),
        min(turnout.x_max, math.ceil(10.0 * (x_dip + _QUICK_HALF_WIDTH)) / 10.0),
    )


def _check_ids(
    settings: ReportSettings, layout, field: str, ids: tuple[str, ...]
) -> tuple[str, ...]:
    known = {rail.id for rail in layout.rails}
    for rid in ids:
        if rid not in known:
            raise TurnoutFileError(
                f"{settings.source}: {field} names rail {rid!r}, which is not in "
                f"layout.rails ({', '.join(sorted(known))})"
            )
    return ids


def stock_rails(settings: ReportSettings, layout) -> tuple[str, ...]:
    """FE rail ids of the stock rails (``report.stock_rails`` or derived, see the module doc).

    Parameters
    ----------
    settings : ReportSettings
    layout : Layout
        The turnout's FE layout (:func:`~exudyn_turnout.fe.layout.load_layout`).

    Returns
    -------
    tuple of str
        Layout rail ids, in layout order.

    Raises
    ------
    TurnoutFileError
        ``report.stock_rails`` names a rail that is not in ``layout.rails``.
    """
    if settings.stock_rails_given is not None:
        return _check_ids(settings, layout, "report.stock_rails", settings.stock_rails_given)
    return tuple(
        r.id
        for r in layout.rails
        if abs(r.x_from - layout.x_start) < 1e-9
        and all(s.rail_type == settings.reference_rail_type for s in r.segments)
    )


def check_rails(settings: ReportSettings, layout, turnout: Turnout) -> tuple[str, ...]:
    """FE rail ids of the check rails (``report.check_rails`` or derived, see the module doc).

    Parameters
    ----------
    settings : ReportSettings
    layout : Layout
        The turnout's FE layout (:func:`~exudyn_turnout.fe.layout.load_layout`).
    turnout : Turnout
        Its zones say which rail types slot r3 (the check rail) has.

    Returns
    -------
    tuple of str
        Layout rail ids, in layout order.

    Raises
    ------
    TurnoutFileError
        ``report.check_rails`` names a rail that is not in ``layout.rails``.
    """
    if settings.check_rails_given is not None:
        return _check_ids(settings, layout, "report.check_rails", settings.check_rails_given)
    types = check_rail_types(turnout)
    return tuple(r.id for r in layout.rails if all(s.rail_type in types for s in r.segments))
