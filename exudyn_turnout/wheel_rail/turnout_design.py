"""The turnout's rail design as data: the ``[wheel_rail]`` section and its design formulas.

:func:`rail_geometry` reads and validates ``[wheel_rail]`` of a turnout file (rail profile,
inclination, gauge, switch, crossing and check-rail design; every field with a default and a
source or reason, gauge, switch radius and nose tip from the plan unless given) into a
:class:`RailGeometry`. The small pure formulas of the design along x (stock-rail setback,
blade lowering and head, wing-rail flare, check-rail face) live here too; the rail bodies'
sections built from them are :mod:`.turnout_sections`.

Stage: may import :mod:`exudyn_turnout.inputs` and :mod:`exudyn_turnout.wheel_rail`; pure
numpy.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from exudyn_turnout.inputs.check_rail import flare_opening
from exudyn_turnout.inputs.geometry import TurnoutPlan, turnout_plan
from exudyn_turnout.inputs.turnout import Turnout, TurnoutFileError
from exudyn_turnout.wheel_rail.data import profile_path
from exudyn_turnout.wheel_rail.profiles import (
    Profile,
    ProfileFormatError,
    read_profile,
)
from exudyn_turnout.wheel_rail.sections import (
    CrossingDesign,
    SwitchDesign,
    place_rail,
)

__all__ = [
    "CheckRailDesign",
    "RailGeometry",
    "rail_geometry",
    "stock_setback",
    "blade_lowering",
    "wing_flare",
    "blade_heights",
    "check_face",
    "crossing_throat",
    "design_error",
    "design_number",
    "design_source",
    "placed_rail",
    "read_rail_profile",
    "resolve_design_file",
]


@dataclass(frozen=True)
class CheckRailDesign:
    """Check rail opposite a crossing: where its face stands, how high, its flares (SI)."""

    #: m, from the back of the flange of a centred wheelset to the check rail's face
    #: (``[check_rail] clearance``)
    clearance: float = 0.004
    flare_length: float = 1.0  #: m, length of each flared end (``[check_rail] flare_length``)
    #: m, extra opening at each end (``[check_rail] flare_opening``)
    flare_opening: float = 0.015
    #: m, top of the check rail above the running rail's top.  0: a running-rail section on
    #: the same chairs (the turnout files' check rail type is the stock rail's section)
    height: float = 0.0
    #: run-in shape of the flares, "straight" or "tangential" (``[check_rail] flare_shape``,
    #: :mod:`exudyn_turnout.inputs.check_rail`)
    flare_shape: str = "straight"
    #: -, friction coefficient of the wheel's contacts on the check rail (``[check_rail]
    #: friction``, e.g. 0.1-0.2 lubricated); 0: the vehicle's ``[contact] mu``
    friction: float = 0.0


@dataclass(frozen=True)
class RailGeometry:
    """The ``[wheel_rail]`` design data of a turnout file, defaults filled (SI)."""

    #: rail profile: a name in ``exudyn_turnout/data/wheel_rail/profiles`` or a path
    #: relative to the turnout file (Simpack .prr or two-column text)
    profile: str = "MBench_UIC60_v3.prr"
    #: tangent of the inclination the profile file already has (the Manchester benchmark's
    #: UIC60 is stored inclined 1:40)
    profile_inclination: float = 1.0 / 40.0
    inclination: float = 1.0 / 40.0  #: tangent of the rails' inclination in the track
    gauge: float = 1.435  #: m, track gauge (``[layout] gauge``)
    gauge_depth: float = 0.014  #: m, gauge point below the top of rail (EN 15302)
    #: m, wheelset back-to-back distance the check rail clearance refers to (EN 13260)
    back_to_back: float = 1.360
    #: m, length ahead of the toe over which the stock rail is set out by the blade's toe
    #: width (assumed; a set bend of 3 mm over 1 m, 1:333)
    stock_set_length: float = 1.0
    switch: SwitchDesign = field(default_factory=SwitchDesign)  #: switch design
    crossing: CrossingDesign = field(default_factory=CrossingDesign)  #: crossing design
    check_rail: CheckRailDesign = field(default_factory=CheckRailDesign)  #: check rail
    grid_step: float = 1e-4  #: m, lateral grid step of the sections
    #: m, largest normal distance between a section and the linear interpolation of its
    #: neighbouring x nodes.  0.2 mm, the tables' lateral shift step: the designs' heights
    #: change linearly along x (exact between nodes), so it binds where a face or corner
    #: moves sideways (stock rail, wing rail, nose); 0.1 mm took 1.4x the nodes
    #: (``validation/turnout_contact_geometry.md``)
    section_tolerance: float = 2e-4
    min_step: float = 0.01  #: m, smallest x step of a body's grid
    #: m, how far ahead and behind the wheel centre its envelope looks (at 0.1 m a 0.46 m
    #: wheel is 10.9 mm above its lowest point: deeper than any step of these designs)
    envelope_reach: float = 0.1
    envelope_step: float = 0.002  #: m, dx step of the envelope search
    source: str = ""  #: turnout file the geometry was read from

    @property
    def half_gauge(self) -> float:
        """m, distance of the gauge point from the route's centre line."""
        return 0.5 * self.gauge


def design_error(geometry_src: str, field_name: str, problem: str) -> TurnoutFileError:
    """The error of one field of a turnout file's rail design: ``<file>: <field> <problem>``.

    Parameters
    ----------
    geometry_src : str
        File name (:func:`design_source`).
    field_name : str
        Dotted field name.
    problem : str
        What is wrong.

    Returns
    -------
    TurnoutFileError
        The error (to raise).
    """
    return TurnoutFileError(f"{geometry_src}: {field_name} {problem}")


def design_source(turnout: Turnout) -> str:
    """The turnout file's name, as errors of its rail design name it.

    Parameters
    ----------
    turnout : Turnout
        A loaded turnout file.

    Returns
    -------
    str
        The file name without its directory.
    """
    return Path(turnout.source).name


def design_number(
    src: str, name: str, value: Any, lo: float, hi: float, lo_open: bool = False
) -> float:
    """``value`` as a finite float in [lo, hi] (``(lo, hi]`` if ``lo_open``), else an error.

    Parameters
    ----------
    src : str
        File name, for the message.
    name : str
        Dotted field name, for the message.
    value : Any
        The value read.
    lo, hi : float
        Bounds.
    lo_open : bool
        The lower bound is excluded.

    Returns
    -------
    float
        The value.

    Raises
    ------
    TurnoutFileError
        Not a finite number, or out of bounds.
    """
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise design_error(src, name, f"must be a finite number, got {value!r}")
    if value < lo or (lo_open and value <= lo) or value > hi:
        low = f"> {lo:g}" if lo_open else f">= {lo:g}"
        raise design_error(src, name, f"must be {low} and <= {hi:g}, got {value:g}")
    return float(value)


#: field -> (lower bound, upper bound, lower bound open): plausibility bounds, SI
_BOUNDS = {
    "profile_inclination": (-0.1, 0.1, False),
    "inclination": (-0.1, 0.1, False),
    "gauge": (0.6, 2.0, True),
    "gauge_depth": (0.005, 0.03, True),
    "back_to_back": (0.5, 2.0, True),
    "stock_set_length": (0.0, 10.0, True),  # 0 would step the stock rail at the toe
    "grid_step": (1e-5, 1e-3, False),
    "section_tolerance": (1e-6, 1e-3, False),
    "min_step": (1e-3, 1.0, False),
    "envelope_reach": (0.0, 0.3, False),
    "envelope_step": (1e-4, 0.02, False),
    "switch.radius": (10.0, 1e5, True),
    "switch.entry_tangent": (0.0, 0.1, False),
    "switch.toe_width": (0.0, 0.05, False),
    "switch.toe_lowering": (0.0, 0.02, False),
    "switch.lowering_length": (0.0, 50.0, True),
    "switch.head_width": (0.03, 0.12, True),
    "crossing.nose_tip": (-1e4, 1e4, False),
    "crossing.crossing_number": (2.0, 100.0, False),
    "crossing.tip_width": (0.0, 0.05, False),
    "crossing.tip_lowering": (0.0, 0.02, False),
    "crossing.lowering_length": (0.0, 10.0, True),
    "crossing.flangeway": (0.02, 0.1, False),
    "crossing.head_width": (0.03, 0.12, True),
    "crossing.inclination_transition": (0.0, 20.0, False),
    "check_rail.height": (-0.03, 0.06, False),
}


def _section(raw: Mapping[str, Any], src: str, name: str) -> Mapping[str, Any]:
    value = raw.get(name, {})
    if not isinstance(value, Mapping):
        raise design_error(src, name, "must be a table")
    return value


def _fields(
    src: str, prefix: str, table: Mapping[str, Any], known: tuple[str, ...]
) -> dict[str, float]:
    out = {}
    for key, value in table.items():
        name = f"{prefix}.{key}"
        if key not in known:
            raise design_error(src, name, f"is not a field (fields: {', '.join(known)})")
        lo, hi, lo_open = _BOUNDS[name.split(".", 1)[1]]
        out[key] = design_number(src, name, value, lo, hi, lo_open)
    return out


def rail_geometry(turnout: Turnout) -> RailGeometry:
    """The turnout's ``[wheel_rail]`` design data, validated, defaults filled.

    Defaults that come from elsewhere in the file: ``gauge`` from ``[layout] gauge``;
    ``switch.radius`` from ``[layout.diverging] radius``; ``crossing.nose_tip``,
    ``crossing_number`` and ``tip_width`` from the plan (:func:`.inputs.geometry.turnout_plan`);
    the check rail's clearance, flares and friction from ``[check_rail]``.  Without ``[layout]`` the
    class defaults stand.

    Parameters
    ----------
    turnout : Turnout
        A loaded turnout file.

    Returns
    -------
    RailGeometry

    Raises
    ------
    TurnoutFileError
        An unknown field, a value that is not a number or out of its plausible range, a
        profile that cannot be read (one line naming the file and the field).
    """
    src = design_source(turnout)
    raw = turnout.raw.get("wheel_rail", {})
    if not isinstance(raw, Mapping):
        raise design_error(src, "wheel_rail", "must be a table")
    sub = ("switch", "crossing", "check_rail")
    top = tuple(k for k in _BOUNDS if "." not in k)
    scalars = _fields(
        src,
        "wheel_rail",
        {k: v for k, v in raw.items() if k not in sub + ("profile",)},
        top,
    )
    profile = raw.get("profile", RailGeometry.profile)
    if not isinstance(profile, str) or not profile.strip():
        raise design_error(src, "wheel_rail.profile", f"must be a file name, got {profile!r}")
    parts = {}
    for name in sub:
        known = tuple(k.split(".", 1)[1] for k in _BOUNDS if k.startswith(name + "."))
        parts[name] = _fields(src, f"wheel_rail.{name}", _section(raw, src, name), known)
    layout = turnout.raw.get("layout")
    plan: TurnoutPlan | None = turnout_plan(turnout) if isinstance(layout, Mapping) else None
    switch_defaults: dict[str, float] = {}
    crossing_defaults: dict[str, float] = {}
    if plan is not None:
        scalars.setdefault("gauge", plan.gauge)
        diverging = layout.get("diverging", {}) if isinstance(layout, Mapping) else {}
        if isinstance(diverging, Mapping) and "radius" in diverging:
            switch_defaults["radius"] = float(diverging["radius"])
        crossing_defaults = {
            "nose_tip": plan.nose_tip_x,
            "crossing_number": plan.crossing_angle_n,
            "tip_width": plan.nose_tip_width,
        }
    check = turnout.raw.get("check_rail", {})
    check_defaults: dict[str, Any] = {
        k: float(check[k])
        for k in ("clearance", "flare_length", "flare_opening", "friction")
        if isinstance(check, Mapping) and k in check
    }
    if isinstance(check, Mapping) and "flare_shape" in check:
        check_defaults["flare_shape"] = str(check["flare_shape"])
    geometry = RailGeometry(
        profile=profile,
        switch=SwitchDesign(**{**switch_defaults, **parts["switch"]}),
        crossing=CrossingDesign(**{**crossing_defaults, **parts["crossing"]}),
        check_rail=CheckRailDesign(**{**check_defaults, **parts["check_rail"]}),
        source=str(turnout.source),
        **scalars,
    )
    read_rail_profile(geometry, src)  # a profile that cannot be read fails here, at load
    return geometry


def resolve_design_file(name: str, turnout_source: str) -> Path:
    """A design file named in a turnout file: next to the file if there, else packaged.

    Parameters
    ----------
    name : str
        File name (a profile or slice file) as the turnout file gives it.
    turnout_source : str
        Path of the turnout file ("" for the working directory).

    Returns
    -------
    Path
        The file relative to the turnout file if it exists, else the packaged profile of
        that name (:func:`.data.profile_path`).
    """
    local = Path(turnout_source).parent / name if turnout_source else Path(name)
    return local if local.exists() else profile_path(name)


def read_rail_profile(geometry: RailGeometry, src: str = "") -> Profile:
    """The rail profile of ``[wheel_rail] profile``, as read (not placed).

    Parameters
    ----------
    geometry : RailGeometry
        The design data (profile name, source file).
    src : str
        File name for errors (default: the geometry's source).

    Returns
    -------
    Profile
        The rail profile.

    Raises
    ------
    TurnoutFileError
        The profile cannot be read.
    """
    try:
        return read_profile(resolve_design_file(geometry.profile, geometry.source), kind="rail")
    except ProfileFormatError as err:
        raise design_error(
            src or Path(geometry.source).name, "wheel_rail.profile", str(err)
        ) from None


def placed_rail(
    geometry: RailGeometry, inclination: float, profile: Profile | None = None
) -> Profile:
    """The profile rotated to ``inclination`` and placed: top z = 0, gauge point gauge / 2.

    Parameters
    ----------
    geometry : RailGeometry
        Gauge, gauge depth, the inclination the profile file has.
    inclination : float
        Tangent of the inclination wanted.
    profile : Profile, optional
        The profile as read (default: :func:`read_rail_profile`).

    Returns
    -------
    Profile
        The placed rail (side coordinates).
    """
    profile = read_rail_profile(geometry) if profile is None else profile
    extra = math.tan(math.atan(inclination) - math.atan(geometry.profile_inclination))
    return place_rail(profile, geometry.gauge, extra, geometry.gauge_depth)


def stock_setback(x: float, design: SwitchDesign, set_length: float) -> float:
    """Lateral distance of the stock rail's gauge face from the route's running line.

    ``toe_width + e x + x^2 / (2 R)`` from the toe (x = 0): the blade head fills it
    (:func:`.sections.switch_sections`); the curve of radius R leaves the route tangentially
    (the plan's ``[layout.diverging]``) and the entry tangent e adds the switch's entry
    angle.  Ahead of the toe the stock rail is *set* out linearly from 0 at ``-set_length``
    to the toe width (the set bend that houses the blade tip; without it the stock rail
    would step by ``toe_width`` at the toe).

    Parameters
    ----------
    x : float
        m, position from the toe.
    design : SwitchDesign
        Radius, entry tangent and toe width.
    set_length : float
        m, length of the set ahead of the toe (0: a step at the toe).

    Returns
    -------
    float
        m, towards the field side.
    """
    if x >= 0.0:
        return design.toe_width + design.entry_tangent * x + x * x / (2.0 * design.radius)
    if set_length <= 0.0:
        return 0.0
    return design.toe_width * max(0.0, 1.0 + x / set_length)


def blade_lowering(x: float, design: SwitchDesign) -> float:
    """How far the blade's top is below the full rail's: linear from the toe to full height.

    ``toe_lowering * max(0, 1 - x / lowering_length)`` (the design of
    :class:`.sections.SwitchDesign`, after Kassa & Nielsen, VSD 46 S1, 2008).

    Parameters
    ----------
    x : float
        m, position from the toe.
    design : SwitchDesign
        Toe lowering and lowering length.

    Returns
    -------
    float
        m, >= 0.
    """
    return design.toe_lowering * max(0.0, 1.0 - x / design.lowering_length)


def blade_heights(
    base: np.ndarray,
    y: np.ndarray,
    edge: float,
    lowering: float,
    face_slope: float = 4.0,
    fillet: float = 0.003,
) -> np.ndarray:
    """A blade section: the full rail lowered, planed on its field side from ``edge``.

    The planed side falls at ``face_slope`` (4: a 76 deg face, the blade fitted under the
    stock rail's gauge corner; a vertical cut would leave a knife edge that the gap search
    resolves badly) until it is 30 mm down (then no rail); the edge is rounded by a
    parabola over ``edge +- fillet`` (assumed: a planed edge is not sharp; a moving sharp
    edge would also need x nodes every ~0.3 mm of its lateral travel).

    Parameters
    ----------
    base : numpy.ndarray
        m, heights of the full rail on ``y``.
    y : numpy.ndarray
        m, lateral grid.
    edge : float
        m, lateral position of the planed edge (running line + head width there).
    lowering : float
        m, how far the blade's top is below the full rail's.
    face_slope : float
        Fall of the planed side per unit lateral distance.
    fillet : float
        m, half-width of the rounded edge.

    Returns
    -------
    numpy.ndarray
        m, heights (NaN: no blade).
    """
    z = base - lowering
    top = float(np.interp(edge, y, z))
    beyond = y > edge
    z[beyond] = np.minimum(z[beyond], top - face_slope * (y[beyond] - edge))
    # round the edge: a parabola tangent to the rail (slope s1) at edge - w and to the
    # planed face (slope -face_slope) at edge + w
    w = fillet
    s1 = (top - float(np.interp(edge - w, y, base - lowering))) / w  # the rail's mean slope
    s2 = -face_slope
    near = np.abs(y - edge) <= w
    u = y[near] - edge
    z[near] = top + s1 * u + (s2 - s1) * (u + w) ** 2 / (4.0 * w)
    z[beyond & (z < top - 0.03)] = np.nan
    return z


def crossing_throat(design: CrossingDesign) -> float:
    """x of the crossing's throat: ``nose_tip - N (tip_width + flangeway)``.

    Parameters
    ----------
    design : CrossingDesign
        The crossing.

    Returns
    -------
    float
        m, where the wing rail begins to leave the running line (:func:`wing_flare`).
    """
    return design.nose_tip - design.crossing_number * (design.tip_width + design.flangeway)


def wing_flare(x: float, design: CrossingDesign) -> float:
    """Lateral distance of the wing rail's gauge face from the running line.

    ``max(0, (x - x_throat) / N)``, ``x_throat = nose_tip - N (tip_width + flangeway)``: the
    wing rail runs parallel to the nose's other leg, ``flangeway`` from it (as in
    :func:`.sections.crossing_sections`).

    Parameters
    ----------
    x : float
        m, position along the route.
    design : CrossingDesign
        Nose tip, crossing number, tip width, flangeway.

    Returns
    -------
    float
        m, towards the field side.
    """
    return max(0.0, (x - crossing_throat(design)) / design.crossing_number)


def check_face(x: float, x_from: float, x_to: float, check: CheckRailDesign) -> float:
    """Distance of the check rail's face from the back of the flange of a centred wheelset.

    ``clearance`` plus the flare's opening at d, the distance from the nearer end of the
    check rail (:func:`exudyn_turnout.inputs.check_rail.flare_opening`, as
    :meth:`exudyn_turnout.inputs.routes.Route.check_clearance_at`).

    Parameters
    ----------
    x : float
        m, position along the route.
    x_from, x_to : float
        m, ends of the check rail.
    check : CheckRailDesign
        Clearance and flares.

    Returns
    -------
    float
        m, clearance at x.
    """
    into = min(x - x_from, x_to - x)
    opening = flare_opening(into, check.flare_length, check.flare_opening, check.flare_shape)
    return check.clearance + opening
