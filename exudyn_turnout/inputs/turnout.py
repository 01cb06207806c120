"""Turnout definition: load and validate a turnout file (TOML) into frozen dataclasses.

A turnout file holds the FE properties of the paper's Table 1 per rail type, sleepers and
ballast, the support-stiffness polynomials (Eqs 10, 14), the simulation zones with their
active rails (Table 3) and the published co-running parameters (Table 2). Every quantity
is in SI units. The packaged default is ``data/uic60_760_1_15.toml``; another turnout is
another file, never a code change.

This module reads and validates the file (:func:`load_turnout`); the dataclasses it fills
are :mod:`.turnout_data`, the TOML field reader :mod:`.toml_fields` (both re-exported here).

Errors in a file raise :class:`TurnoutFileError` with one message naming the file and the
field, e.g. ``uic60.toml: sleeper.spacing must be > 0, got -0.6``.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from exudyn_turnout.inputs.check_rail import (
    CHECK_RAIL_KEYS,
    FLARE_SHAPES,
    co_running_model_from_section,
    lateral_from_section,
    support_from_section,
)
from exudyn_turnout.inputs.routes import load_route, route_names
from exudyn_turnout.inputs.toml_fields import (
    X_LIMIT,
    FieldReader,
    TurnoutFileError,
    did_you_mean,
    read_toml,
)
from exudyn_turnout.inputs.turnout_data import (
    PARAMETER_NAMES,
    RAIL_SLOTS,
    Ballast,
    Entry,
    ExtraLayer,
    Polynomial,
    RailPad,
    RailType,
    Sleeper,
    Table1D,
    Turnout,
    Zone,
)

__all__ = [
    "TurnoutFileError",
    "Table1D",
    "Polynomial",
    "RailPad",
    "RailType",
    "Sleeper",
    "Ballast",
    "ExtraLayer",
    "Zone",
    "Entry",
    "Turnout",
    "RAIL_SLOTS",
    "PARAMETER_NAMES",
    "X_LIMIT",
    "FieldReader",
    "default_turnout_path",
    "load_turnout",
    "read_toml",
    "SECTIONS",
    "REQUIRED_REGIONS",
]

#: Plausibility bounds (upper limits, SI) of turnout-file quantities; every value must also
#: be > 0. Wide on purpose (they catch unit slips and typos, not unusual designs):
#: densities <= 1e5 kg/m^3 (steel 7850, concrete 2400), Young's moduli <= 1e13 Pa
#: (diamond 1.2e12), Poisson's ratio in (0, 0.5) (checked apart), shear coefficient <= 2,
#: areas <= 1 m^2, second moments <= 1 m^4, lengths <= 20 m (sleeper, bearer), spacing
#: <= 5 m, stiffnesses <= 1e12 N/m (per metre for the ballast), damping <= 1e10 N s/m,
#: masses <= 1e5 kg, stiffness ratios <= 1e6, rails per sleeper 1..10.
BOUNDS = {
    "density": 1e5,
    "youngs_modulus": 1e13,
    "shear_coefficient": 2.0,
    "area": 1.0,
    "I": 1.0,
    "length": 20.0,
    "spacing": 5.0,
    "stiffness": 1e12,
    "damping": 1e10,
    "mass": 1e5,
    "ratio": 1e6,
}


#: Sections of a turnout file (the top-level tables), each with the module that reads it:
#: this one (turnout .. published, routes' generic checks, regions, check_rail), routes
#: (:mod:`.routes`), the plan and FE layout (``layout``), the rail sections
#: (``wheel_rail``, ``check_rail``: :mod:`exudyn_turnout.wheel_rail.turnout_design`) and the
#: validation report (``report``). Any other section is an error naming the closest.
SECTIONS = (
    "turnout",
    "rail_types",
    "sleeper",
    "ballast",
    "stiffness_profiles",
    "extra_layer",
    "zones",
    "published",
    "routes",
    "regions",
    "check_rail",
    "wheel_rail",
    "layout",
    "report",
)

#: Keys of the tables this module reads in full (an unknown key is an error with a "did
#: you mean"); ``wheel_rail``, ``check_rail``, ``layout`` and ``report`` are checked by
#: their readers.
_KEYS = {
    "turnout": ("name", "description", "reference_rail_type"),
    "rail_type": (
        "density",
        "youngs_modulus",
        "shear_coefficient",
        "poisson",
        "area",
        "I_z",
        "I_y",
        "sleeper_length",
        "support",
        "rails_per_sleeper",
        "pad",
        "vertical_factor",
        "lateral_factor",
        "equivalent_to",
    ),
    "pad": ("k_z", "c_z", "k_y", "c_y"),
    "sleeper": ("density", "youngs_modulus", "area", "I", "spacing", "length"),
    "ballast": ("s_b_z", "d_b_z", "s_b_y", "d_b_y"),
    "extra_layer": ("m_0", "k_0_z_over_k_rt_z", "k_0_y_over_k_rt_y"),
    "stiffness_profiles": ("K_sw", "K_sh"),
    "polynomial": ("coefficients", "x_min", "x_max", "plain_track_end"),
    "zone": (
        "name",
        "x_start",
        "x_end",
        "rail_types",
        "active_rails",
        "ballast_rail_type",
        "mass_at_x",
        "rail_y",
        "ballast_y",
        "sleeper_y",
    ),
    "route": (
        "description",
        "curvature",
        "cant",
        "permitted_speed_kmh",
        "permitted_cant_deficiency",
        "rail_y",
        "continues",
        "contacts",
    ),
    "contact": ("name", "wheel", "rail", "x", "z", "flange", "check", "sections"),
}

#: Regions a ``[regions]`` table must name (where the report takes the peaks "at the
#: switch" and "at the crossing"); further names are the file's own.
REQUIRED_REGIONS = ("switch", "crossing")


def default_turnout_path() -> Path:
    """Path of the packaged UIC60-760-1:15 turnout file.

    Returns
    -------
    Path
        ``data/uic60_760_1_15.toml`` inside the installed package.
    """
    return Path(str(resources.files("exudyn_turnout") / "data" / "uic60_760_1_15.toml"))


def _rail_type(r: FieldReader, name: str) -> RailType:
    p = f"rail_types.{name}"
    r.keys(p, _KEYS["rail_type"])
    r.keys(p + ".pad", _KEYS["pad"])
    factor_options = (None, "Delta_z", "Delta_y")
    b = BOUNDS
    pad_bounds = {
        "k_z": b["stiffness"],
        "c_z": b["damping"],
        "k_y": b["stiffness"],
        "c_y": b["damping"],
    }
    poisson = r.number(p + ".poisson", positive=False)
    if not 0.0 < poisson < 0.5:
        raise r.fail(p + ".poisson", f"must be in (0, 0.5), got {poisson:g}")
    equivalent_to = r.get(p + ".equivalent_to", None)
    if equivalent_to is not None and not isinstance(equivalent_to, str):
        raise r.fail(p + ".equivalent_to", f"must be a rail type name, got {equivalent_to!r}")
    return RailType(
        name=name,
        density=r.number(p + ".density", upper=b["density"]),
        youngs_modulus=r.number(p + ".youngs_modulus", upper=b["youngs_modulus"]),
        shear_coefficient=r.number(p + ".shear_coefficient", upper=b["shear_coefficient"]),
        poisson=poisson,
        area=r.table(p + ".area", upper=b["area"]),
        I_z=r.table(p + ".I_z", upper=b["I"]),
        I_y=r.table(p + ".I_y", upper=b["I"]),
        sleeper_length=r.number(p + ".sleeper_length", upper=b["length"]),
        support=r.choice(p + ".support", ("edge", "middle")),
        rails_per_sleeper=r.integer(p + ".rails_per_sleeper", 1, 10),
        # an undamped pad (c = 0) is a legitimate limiting case: the track keeps the
        # ballast's damping (Eqs 5-9: c_rt and the k_0 layer's damping then come from the
        # ballast only) and every spring-damper stays well defined; a negative damping
        # would feed energy in, and is refused
        pad=RailPad(
            *(
                r.number(
                    f"{p}.pad.{k}",
                    positive=k.startswith("k"),
                    upper=pad_bounds[k],
                    lower=None if k.startswith("k") else 0.0,
                )
                for k in ("k_z", "c_z", "k_y", "c_y")
            )
        ),
        vertical_factor=r.choice(p + ".vertical_factor", factor_options, None),
        lateral_factor=r.choice(p + ".lateral_factor", factor_options, None),
        equivalent_to=equivalent_to,
    )


def _polynomial(r: FieldReader, name: str) -> Polynomial:
    p = f"stiffness_profiles.{name}"
    r.keys(p, _KEYS["polynomial"])
    coefficients = r.get(p + ".coefficients")
    if not isinstance(coefficients, list) or not coefficients:
        raise r.fail(p + ".coefficients", "must be a non-empty list of numbers")
    for i, c in enumerate(coefficients):
        r.check(f"{p}.coefficients[{i}]", c, positive=False)
    x_min = r.number(p + ".x_min", positive=False)
    x_max = r.number(p + ".x_max", positive=False)
    if not x_max > x_min:
        raise r.fail(p, f"range is inverted: x_min = {x_min:g} must be < x_max = {x_max:g}")
    plain_end = r.get(p + ".plain_track_end", None)
    if plain_end is not None:
        plain_end = r.check(p + ".plain_track_end", plain_end, positive=False)
        if not plain_end < x_min:
            raise r.fail(p + ".plain_track_end", f"must be < x_min = {x_min:g}, got {plain_end:g}")
    poly = Polynomial(tuple(map(float, coefficients)), x_min, x_max, plain_end)
    for x in np.linspace(x_min, x_max, 101):
        if not poly(x) > 0:
            raise r.fail(p, f"must be > 0 over its range, got {poly(x):g} at x = {x:g}")
    return poly


def _zones(r: FieldReader, rail_types: Mapping[str, RailType]) -> tuple[Zone, ...]:
    raw = r.get("zones")
    if not isinstance(raw, list) or not raw:
        raise r.fail("zones", "must be a non-empty list of [[zones]] tables")
    zones = []
    for i, _ in enumerate(raw, start=1):
        p = f"zones[{i}]"
        zr = r.sub(p, raw[i - 1])
        zr.keys(p, _KEYS["zone"])
        x0 = zr.number(p + ".x_start", False, upper=X_LIMIT)
        x1 = zr.number(p + ".x_end", False, upper=X_LIMIT)
        if not x1 > x0:
            raise r.fail(p, f"has x_end = {x1:g} <= x_start = {x0:g}")
        types = zr.get(p + ".rail_types")
        if not isinstance(types, Mapping):
            raise r.fail(p + ".rail_types", 'must be a table {r1 = "stock", ...}')
        for slot, tname in types.items():
            if slot not in RAIL_SLOTS:
                raise r.fail(
                    f"{p}.rail_types",
                    f"names rail slot {slot!r}; slots are {', '.join(RAIL_SLOTS)}",
                )
            if tname not in rail_types:
                raise r.fail(
                    f"{p}.rail_types.{slot}", f"names rail type {tname!r}, which is not defined"
                )
        active = zr.get(p + ".active_rails")
        if not isinstance(active, list) or not active:
            raise r.fail(p + ".active_rails", "must be a non-empty list of rail slots")
        for slot in active:
            if slot not in types:
                raise r.fail(
                    f"{p}.active_rails",
                    f"names rail {slot!r}, which is not defined in its rail_types",
                )
        ballast_type = zr.choice(p + ".ballast_rail_type", tuple(rail_types))
        mass_at_x = zr.get(p + ".mass_at_x", None)
        if mass_at_x is not None:
            mass_at_x = zr.number(p + ".mass_at_x", positive=False)
        rail_y = zr.get(p + ".rail_y")
        if not isinstance(rail_y, Mapping):
            raise r.fail(
                p + ".rail_y", "must be a table {r1 = y1, ...} of lateral rail positions (m)"
            )
        for slot in types:
            if slot not in rail_y:
                raise r.fail(
                    f"{p}.rail_y.{slot}", "is missing (every rail in rail_types needs a position)"
                )
        rail_y = {s: zr.number(f"{p}.rail_y.{s}", positive=False) for s in types}
        ballast_y = zr.get(p + ".ballast_y")
        if not isinstance(ballast_y, list) or len(ballast_y) != 2:
            raise r.fail(
                p + ".ballast_y",
                f"must be two lateral positions [y_tg1, y_tg2] (m), got {ballast_y!r}",
            )
        ballast_y = tuple(zr.check(f"{p}.ballast_y", y, positive=False) for y in ballast_y)
        if not abs(ballast_y[1] - ballast_y[0]) > 0:
            raise r.fail(p + ".ballast_y", "must be two different positions")
        zones.append(
            Zone(
                i,
                str(zr.get(p + ".name", f"zone {i}")),
                x0,
                x1,
                tuple(active),
                dict(types),
                ballast_type,
                mass_at_x,
                rail_y,
                ballast_y,
                zr.number(p + ".sleeper_y", positive=False),
            )
        )
    for a, b in zip(zones, zones[1:]):
        if abs(a.x_end - b.x_start) > 1e-9:
            kind = "overlap" if b.x_start < a.x_end else "leave a gap"
            raise r.fail(
                "zones",
                f"{a.index} and {b.index} {kind}: zone {a.index} ends at "
                f"{a.x_end:g} m, zone {b.index} starts at {b.x_start:g} m",
            )
    return tuple(zones)


_FORMULA = re.compile(r"^\s*([-+0-9.eE]+)\s*\*\s*(Delta_z|Delta_y)\s*$")


def _entry(r: FieldReader, field: str) -> Entry:
    value = r.get(field)
    if isinstance(value, str):
        m = _FORMULA.match(value)
        if not m:
            raise r.fail(
                field,
                "must be a number, 'NUMBER * Delta_z', 'NUMBER * Delta_y' or [a, b], "
                f"got {value!r}",
            )
        return Entry(m.group(2), r.check(field, float(m.group(1))))
    if isinstance(value, list):
        if len(value) != 2:
            raise r.fail(field, f"range must have two values [a, b], got {value!r}")
        return Entry("ramp", *(r.check(field, v) for v in value))
    return Entry("const", r.number(field))


def _published(r: FieldReader, zones: tuple[Zone, ...]) -> dict[int, dict[str, Entry]]:
    """Table 2 sections ``[published.zoneN]``; optional per zone (a file may have more zones)."""
    out: dict[int, dict[str, Entry]] = {}
    sections = r.get("published", None) or {}
    for key in sections:
        index = int(key[4:]) if key.startswith("zone") and key[4:].isdigit() else 0
        if not 1 <= index <= len(zones):
            raise r.fail(f"published.{key}", f"names no zone of this file (zones 1..{len(zones)})")
        p = f"published.{key}"
        section = r.get(p)
        for name in section:
            if name not in PARAMETER_NAMES:
                raise r.fail(f"{p}.{name}", "is not a co-running parameter name")
        missing = [n for n in PARAMETER_NAMES if n not in section]
        if missing:
            raise r.fail(f"{p}.{missing[0]}", "is missing")
        out[index] = {n: _entry(r, f"{p}.{n}") for n in PARAMETER_NAMES}
    return out


def _check_references(r: FieldReader, rail_types: Mapping[str, RailType]) -> None:
    for t in rail_types.values():
        if t.equivalent_to is not None and t.equivalent_to not in rail_types:
            raise r.fail(
                f"rail_types.{t.name}.equivalent_to",
                f"names rail type {t.equivalent_to!r}, which is not defined",
            )


def _regions(r: FieldReader, zones: tuple[Zone, ...]) -> dict[str, tuple[float, float]]:
    """``[regions]``: each value two increasing numbers [x_from, x_to] inside the turnout.

    Defaults where the file gives none: ``switch`` 0-10 m from the toe, ``crossing`` the
    last zone (the packaged files give both).
    """
    x_min, x_max = zones[0].x_start, zones[-1].x_end
    out = {"switch": (0.0, min(10.0, x_max)), "crossing": (zones[-1].x_start, x_max)}
    regions = r.get("regions", None)
    if regions is None:
        return out
    if not isinstance(regions, Mapping):
        raise r.fail("regions", "must be a table of name = [x_from, x_to]")
    for name in REQUIRED_REGIONS:
        if name not in regions:
            raise r.fail(
                f"regions.{name}",
                "is missing: a [regions] table names the switch and the crossing "
                f"[x_from, x_to] (m){did_you_mean(name, regions) if regions else ''}",
            )
    for name, value in regions.items():
        f = f"regions.{name}"
        if not isinstance(value, list) or len(value) != 2:
            raise r.fail(f, f"must be two numbers [x_from, x_to] (m), got {value!r}")
        a, b = (r.check(f, v, positive=False) for v in value)
        if not b > a:
            raise r.fail(f, f"must be increasing [x_from, x_to], got [{a:g}, {b:g}]")
        if a < x_min - 1e-9 or b > x_max + 1e-9:
            raise r.fail(
                f, f"[{a:g}, {b:g}] m must lie inside the turnout ({x_min:g}..{x_max:g} m)"
            )
        out[str(name)] = (a, b)
    return out


def _reference_rail_type(r: FieldReader, rail_types: Mapping[str, RailType]) -> str:
    """``[turnout] reference_rail_type`` (default "stock"), a rail type of the file."""
    name = r.get("turnout.reference_rail_type", "stock")
    if name not in rail_types:
        raise r.fail(
            "turnout.reference_rail_type",
            f"must be a rail type of the file ({', '.join(rail_types)}), got {name!r}",
        )
    return str(name)


def _increasing(
    r: FieldReader, field: str, value: Any, min_length: int = 1, features: bool = False
) -> list[Any]:
    """A list of positions; consecutive numbers must increase.

    Positions are numbers (finite, |x| <= X_LIMIT) and, with ``features``, plan expressions
    (strings such as ``"nose_tip + 0.5"``, resolved by :mod:`exudyn_turnout.inputs.routes`).
    """
    if not isinstance(value, list) or len(value) < min_length:
        raise r.fail(field, f"must be a list of at least {min_length} positions, got {value!r}")
    xs = [
        v
        if features and isinstance(v, str)
        else r.check(f"{field}[{i}]", v, positive=False, upper=X_LIMIT)
        for i, v in enumerate(value)
    ]
    pairs = zip(xs, xs[1:])
    if any(not isinstance(a, str) and not isinstance(b, str) and b <= a for a, b in pairs):
        raise r.fail(field, f"must be increasing, got {xs}")
    return xs


def _routes(r: FieldReader, n_zones: int) -> None:
    """Generic checks of ``[routes.*]`` at load time (``routes.load_route`` checks the rest).

    Numbers finite (also table x), x lists increasing, ranges [a, b] increasing, wheel and
    rail names valid, ``continues`` zones integers of this file.
    """
    routes = r.get("routes", None)
    if routes is None:
        return
    if not isinstance(routes, Mapping):
        raise r.fail("routes", "must be a table of [routes.<name>] sections")
    for name, route in routes.items():
        p = f"routes.{name}"
        if not isinstance(route, Mapping):
            raise r.fail(p, "must be a table")
        r.keys(p, _KEYS["route"])
        curvature = route.get("curvature", 0.0)
        if isinstance(curvature, Mapping):
            xs = _increasing(r, p + ".curvature.x", curvature.get("x"), 2)
            vs = curvature.get("value")
            if not isinstance(vs, list) or len(vs) != len(xs):
                raise r.fail(p + ".curvature.value", "must be a list as long as curvature.x")
            for i, v in enumerate(vs):
                r.check(f"{p}.curvature.value[{i}]", v, positive=False, upper=1.0)
        else:
            r.check(p + ".curvature", curvature, positive=False, upper=1.0)
        for key, upper in (
            ("cant", 0.3),
            ("permitted_speed_kmh", 500.0),
            ("permitted_cant_deficiency", 0.5),
        ):
            if route.get(key) is not None:
                r.check(f"{p}.{key}", route[key], positive=key != "cant", upper=upper)
        for key, y in (route.get("rail_y") or {}).items():
            r.check(f"{p}.rail_y.{key}", y, positive=False, upper=10.0)
        continues = route.get("continues", [])
        if not isinstance(continues, list):
            raise r.fail(p + ".continues", "must be a list of {zone, slot, from}")
        for i, item in enumerate(continues):
            item = item if isinstance(item, Mapping) else {}
            r.check_integer(f"{p}.continues[{i}].zone", item.get("zone"), 2, max(n_zones, 2))
        contacts = route.get("contacts", [])
        if not isinstance(contacts, list):
            raise r.fail(p + ".contacts", "must be a list of [[contacts]] tables")
        for i, c in enumerate(contacts):
            f = f"{p}.contacts[{i}]"
            if not isinstance(c, Mapping):
                raise r.fail(f, "must be a table")
            r.sub(f, c).keys(f, _KEYS["contact"])
            sections = c.get("sections")
            if not isinstance(sections, list) or not sections:
                raise r.fail(
                    f + ".sections",
                    "is missing: every contact lists the rail bodies it runs on, "
                    "sections = [{ kind = ..., x = [x_from, x_to] }, ...] (a turnout file of "
                    "the previous format: see the packaged uic60_760_1_15.toml)",
                )
            if c.get("wheel") not in ("left", "right"):
                raise r.fail(f + ".wheel", f"must be one of left, right, got {c.get('wheel')!r}")
            if c.get("rail") not in RAIL_SLOTS:
                raise r.fail(
                    f + ".rail", f"must be one of {', '.join(RAIL_SLOTS)}, got {c.get('rail')!r}"
                )
            if "x" in c:
                _increasing(r, f + ".x", c["x"], 2, features=True)
                zs = c.get("z")
                if not isinstance(zs, list) or len(zs) != len(c["x"]):
                    raise r.fail(f + ".z", "must be a list as long as x")
                zs = [r.check(f"{f}.z[{k}]", z, positive=False) for k, z in enumerate(zs)]
                if any(abs(z) > 0.05 for z in zs):
                    raise r.fail(f + ".z", f"heights must be within +-0.05 m of nominal, got {zs}")
            for key in ("flange", "check"):
                if key in c:
                    _increasing(r, f"{f}.{key}", c[key], 2, features=True)
                    if len(c[key]) != 2:
                        raise r.fail(f"{f}.{key}", f"must be [x_from, x_to], got {c[key]!r}")


def _layout_numbers(r: FieldReader) -> None:
    """The ``[layout]`` section's plain numbers (the FE layout and the plan check the rest)."""
    if not isinstance(r.get("layout", None), Mapping):
        return
    for key in ("x_start", "x_end", "sleeper_x0"):
        if r.get(f"layout.{key}", None) is not None:
            r.number(f"layout.{key}", positive=False, upper=X_LIMIT)
    for key in ("gauge", "nose_tip_width"):
        if r.get(f"layout.{key}", None) is not None:
            r.number(f"layout.{key}", upper=10.0)


def _check_rail(r: FieldReader) -> None:
    if r.get("check_rail", None) is None:
        return
    r.number("check_rail.clearance", upper=0.1)
    r.number("check_rail.flare_length", False, 0.0, upper=100.0)
    r.number("check_rail.flare_opening", False, 0.0, upper=0.1)
    r.choice("check_rail.flare_shape", FLARE_SHAPES, default="straight")
    if r.get("check_rail.friction", None) is not None:  # absent: the vehicle's mu
        r.number("check_rail.friction", upper=2.0)
    r.keys("check_rail", CHECK_RAIL_KEYS)
    section = r.get("check_rail")
    try:
        support_from_section(section if isinstance(section, Mapping) else {})
    except ValueError as err:
        raise r.fail("check_rail.support", str(err)) from None
    try:
        lateral_from_section(section if isinstance(section, Mapping) else {})
        co_running_model_from_section(section if isinstance(section, Mapping) else {})
    except ValueError as err:
        raise r.fail("check_rail.co_running", str(err)) from None


def load_turnout(path: str | Path | None = None) -> Turnout:
    """Load and validate a turnout file.

    Parameters
    ----------
    path : str or Path, optional
        TOML turnout file; the packaged UIC60-760-1:15 turnout when omitted.

    Returns
    -------
    Turnout
        Frozen definition in SI units.

    Raises
    ------
    TurnoutFileError
        The file cannot be read, or a field is missing or out of range; the message names
        the file and the field.
    """
    path = Path(path) if path is not None else default_turnout_path()
    data = read_toml(path)
    r = FieldReader(path.name, data)
    r.keys("", SECTIONS)
    for section in ("turnout", "sleeper", "ballast", "extra_layer", "stiffness_profiles"):
        r.keys(section, _KEYS[section])
    names = r.get("rail_types")
    if not isinstance(names, Mapping) or not names:
        raise r.fail("rail_types", "must define at least one rail type")
    rail_types = {n: _rail_type(r, n) for n in names}
    _check_references(r, rail_types)
    s, b = "sleeper", BOUNDS
    sleeper = Sleeper(
        density=r.number(f"{s}.density", upper=b["density"]),
        youngs_modulus=r.number(f"{s}.youngs_modulus", upper=b["youngs_modulus"]),
        area=r.number(f"{s}.area", upper=b["area"]),
        I=r.number(f"{s}.I", upper=b["I"]),
        spacing=r.number(f"{s}.spacing", upper=b["spacing"]),
        length=r.table(f"{s}.length", upper=b["length"]),
    )
    ballast = Ballast(
        *(
            r.number(f"ballast.{k}", upper=b[u])
            for k, u in (
                ("s_b_z", "stiffness"),
                ("d_b_z", "damping"),
                ("s_b_y", "stiffness"),
                ("d_b_y", "damping"),
            )
        )
    )
    extra = ExtraLayer(
        *(
            r.number(f"extra_layer.{k}", upper=b[u])
            for k, u in (
                ("m_0", "mass"),
                ("k_0_z_over_k_rt_z", "ratio"),
                ("k_0_y_over_k_rt_y", "ratio"),
            )
        )
    )
    zones = _zones(r, rail_types)
    name = r.get("turnout.name")
    if not isinstance(name, str) or not name.strip():
        raise r.fail("turnout.name", f"must be a non-empty string, got {name!r}")
    regions = _regions(r, zones)
    reference = _reference_rail_type(r, rail_types)
    _routes(r, len(zones))
    _check_rail(r)
    _layout_numbers(r)
    turnout = Turnout(
        name=str(r.get("turnout.name")),
        description=str(r.get("turnout.description", "")),
        source=str(path),
        rail_types=rail_types,
        sleeper=sleeper,
        ballast=ballast,
        K_sw=_polynomial(r, "K_sw"),
        K_sh=_polynomial(r, "K_sh"),
        extra_layer=extra,
        zones=zones,
        published=_published(r, zones),
        raw=data,
        reference_rail_type=reference,
        regions=regions,
    )
    for route in route_names(turnout):  # each contact within the turnout, on active rails
        load_route(turnout, route)
    return turnout
