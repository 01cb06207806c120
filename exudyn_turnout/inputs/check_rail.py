"""The check rail's flared ends: how the clearance opens towards each end (pure functions).

A check rail's face stands ``[check_rail] clearance`` from the back of the flange of a
centred wheelset, and opens by ``flare_opening`` over ``flare_length`` at each end so that
a wheelset running off the check line is led in rather than struck. Two run-in shapes:

``straight``
    A straight machined flare (the usual form on flat-bottom check rails, whose flare angle
    is chosen by line speed): the opening falls linearly, the flare angle
    ``opening / length`` everywhere, with a kink where the flare meets the check line.
``tangential``
    A parabolic run-in tangent to the check line: the opening falls as
    ``opening (1 - d / length)^2``, so its slope falls linearly to 0 where it meets the check
    line. A wheelset that runs ``delta`` outside the check line meets the flare where its
    slope is ``2 sqrt(opening delta) / length`` instead of ``opening / length``: lower for
    every ``delta < opening / 4`` (a wheel that nearly runs on the check line is led in
    almost without a lateral blow), higher near the mouth.

The lateral velocity the flare imposes on the wheelset at speed v is v times the slope
where it meets it (:func:`entry_lateral_velocity`): the quantity the check rail's entry
impact scales with (linear in speed, issue 23).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

from exudyn_turnout.inputs.toml_fields import did_you_mean

__all__ = [
    "CHECK_RAIL_KEYS",
    "FLARE_SHAPES",
    "CheckRailSupport",
    "support_from_section",
    "CheckRailLateral",
    "lateral_from_section",
    "CO_RUNNING_MODELS",
    "co_running_model_from_section",
    "flare_opening",
    "flare_slope",
    "entry_lateral_velocity",
]

#: Keys of a turnout file's ``[check_rail]`` section.
CHECK_RAIL_KEYS = (
    "clearance",
    "flare_length",
    "flare_opening",
    "flare_shape",
    "friction",
    "support",
    "co_running",
)

#: Run-in shapes of a check rail's flared ends (see the module docstring).
FLARE_SHAPES = ("straight", "tangential")

#: How the co-running check rail (slot r3) is made, the ``model`` key of
#: ``[check_rail.co_running]``: ``"bracket"`` from the FE check rail on its L-bracket (the
#: section's values, :mod:`exudyn_turnout.corunning.check_rail`), ``"table1"`` from Eqs 1-19
#: on Table 1 like a running rail (the paper's).
CO_RUNNING_MODELS = ("bracket", "table1")


def _check_shape(shape: str) -> None:
    if shape not in FLARE_SHAPES:
        raise ValueError(f"flare shape must be one of {', '.join(FLARE_SHAPES)}, got {shape!r}")


def flare_opening(distance: float, length: float, opening: float, shape: str = "straight") -> float:
    """Extra clearance (m) at ``distance`` from the check rail's nearer end.

    Parameters
    ----------
    distance : float
        m, from the nearer end of the check rail into it (0 at the end).
    length : float
        m, flare length (0: no flare).
    opening : float
        m, extra clearance at the very end.
    shape : {"straight", "tangential"}
        Run-in shape.

    Returns
    -------
    float
        m, ``opening (1 - d / L)`` (straight) or ``opening (1 - d / L)^2`` (tangential) for
        0 <= d < L, 0 beyond the flare.

    Raises
    ------
    ValueError
        An unknown shape.
    """
    _check_shape(shape)
    if length <= 0.0 or distance >= length:
        return 0.0
    u = 1.0 - max(distance, 0.0) / length
    return opening * (u if shape == "straight" else u * u)


def flare_slope(offset: float, length: float, opening: float, shape: str = "straight") -> float:
    """Flare angle (tangent) where the remaining opening equals ``offset``.

    Parameters
    ----------
    offset : float
        m, how far outside the check line the wheel's flange back runs (0 < offset <=
        opening): it meets the flare where the extra clearance has fallen to it.
    length, opening : float
        m, the flare.
    shape : {"straight", "tangential"}

    Returns
    -------
    float
        ``opening / length`` (straight) or ``2 sqrt(opening offset) / length`` (tangential);
        0 for no flare or an offset <= 0 (the wheel never meets the flare).

    Raises
    ------
    ValueError
        An unknown shape.
    """
    _check_shape(shape)
    if length <= 0.0 or offset <= 0.0:
        return 0.0
    offset = min(offset, opening)
    if shape == "straight":
        return opening / length
    return 2.0 * math.sqrt(opening * offset) / length


def entry_lateral_velocity(
    speed: float, offset: float, length: float, opening: float, shape: str = "straight"
) -> float:
    """Lateral velocity (m/s) the flare imposes on a wheelset that meets it.

    Parameters
    ----------
    speed : float
        m/s, running speed.
    offset : float
        m, how far outside the check line the flange back runs (e.g. the curving offset of a
        flanging leading wheelset beyond the check clearance).
    length, opening : float
        m, the flare.
    shape : {"straight", "tangential"}

    Returns
    -------
    float
        ``speed * flare_slope(offset, length, opening, shape)``.
    """
    return speed * flare_slope(offset, length, opening, shape)


@dataclass(frozen=True)
class CheckRailSupport:
    """The L-bracket under a check rail, per support (see the module docstring)."""

    #: m, height above the rail foot where the bracket holds the web (the lateral support
    #: acts there).  0.080 m: the bolt holes of a 60E1 web are at the section's neutral axis
    #: (80.9 mm above the foot, EN 13674-1), where fishplate and bracket bolts go.
    height: float = 0.080
    #: N m/rad, roll stiffness the bracket's bolted upright leg adds.  0.5 MN m/rad: a steel
    #: leg 25 mm thick and 150 mm wide along the rail, 80 mm from the baseplate to the bolts,
    #: bent by a moment at its top: E I / L = 207e9 * 0.15 * 0.025^3 / 12 / 0.08 = 0.51e6
    #: (the pad's own k_z b^2 / 12 = 0.23e6 at 120 MN/m and b = 0.15 m).  An estimate: no
    #: drawing of the UIC60-760-1:15's check chair is in the paper.
    k_roll: float = 0.5e6
    #: N m s/rad, roll damping of the leg; None: stiffness-proportional, k_roll c_y / k_y of
    #: the check rail's pad (as the pad's own roll damping is c_z b^2 / 12)
    c_roll: float | None = None

    def __post_init__(self):
        if not (math.isfinite(self.height) and 0.0 <= self.height <= 0.2):
            raise ValueError(f"height must be within 0-0.2 m, got {self.height!r}")
        if not (math.isfinite(self.k_roll) and self.k_roll >= 0.0):
            raise ValueError(f"k_roll must be >= 0, got {self.k_roll!r}")
        if self.c_roll is not None and not (math.isfinite(self.c_roll) and self.c_roll >= 0):
            raise ValueError(f"c_roll must be >= 0, got {self.c_roll!r}")


def support_from_section(check_rail: Mapping) -> CheckRailSupport:
    """The ``support`` table of a ``[check_rail]`` section over the defaults.

    Parameters
    ----------
    check_rail : mapping
        The ``[check_rail]`` section (may lack ``support``).

    Returns
    -------
    CheckRailSupport

    Raises
    ------
    ValueError
        ``support`` is not a table, has an unknown key, a value that is not a number or one
        out of range: the message names the key.
    """
    section = check_rail.get("support", {})
    if not isinstance(section, Mapping):
        raise ValueError("must be a table")
    known = ("height", "k_roll", "c_roll")
    values: dict[str, float] = {}
    for key, value in section.items():
        if key not in known:
            raise ValueError(f"{key} is not a field{did_you_mean(key, known)}")
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ValueError(f"{key} must be a number, got {value!r}")
        values[key] = float(value)
    return CheckRailSupport(**values)


@dataclass(frozen=True)
class CheckRailLateral:
    """The FE check rail's lateral receptance at its gauge corner, summarised along x.

    Computed by :func:`exudyn_turnout.fe.check_rail_receptance.check_rail_lateral_points`
    (torsion-aware FE, the rail on its L-bracket) and stored in a turnout file's
    ``[check_rail.co_running]``; the co-running check rail is derived from it
    (:mod:`exudyn_turnout.corunning.check_rail`).
    """

    rail: str  #: layout rail id of the FE check rail the values belong to
    x: tuple[float, ...]  #: m, positions along the check rail, increasing
    static_stiffness: tuple[float, ...]  #: N/m, 1 / |H(1 Hz)|
    resonance_frequency: tuple[float, ...]  #: Hz, largest |H| in the search band
    resonance_stiffness: tuple[float, ...]  #: N/m, 1 / max |H| there

    def __post_init__(self):
        n = len(self.x)
        if n == 0:
            raise ValueError("x must hold at least one position")
        for name in ("static_stiffness", "resonance_frequency", "resonance_stiffness"):
            values = getattr(self, name)
            if len(values) != n:
                raise ValueError(f"{name} must have one value per x ({n}), got {len(values)}")
            if not all(math.isfinite(v) and v > 0.0 for v in values):
                raise ValueError(f"{name} must be finite and > 0, got {list(values)}")
        if not all(math.isfinite(v) for v in self.x):
            raise ValueError(f"x must be finite, got {list(self.x)}")
        if any(b <= a for a, b in zip(self.x, self.x[1:])):
            raise ValueError(f"x must increase, got {list(self.x)}")


def lateral_from_section(check_rail: Mapping) -> CheckRailLateral | None:
    """The ``co_running`` table of a ``[check_rail]`` section, if there is one.

    Parameters
    ----------
    check_rail : mapping
        The ``[check_rail]`` section.

    Returns
    -------
    CheckRailLateral or None
        None when the section has no ``co_running`` table.

    Raises
    ------
    ValueError
        ``co_running`` is not a table, lacks or has an unknown key, or holds a value that is
        not a list of numbers or is out of range: the message names the key.
    """
    section = check_rail.get("co_running")
    if section is None:
        return None
    if not isinstance(section, Mapping):
        raise ValueError("must be a table")
    lists = ("x", "static_stiffness", "resonance_frequency", "resonance_stiffness")
    known = ("rail",) + lists
    for key in section:
        if key not in known + ("model",):
            raise ValueError(f"{key} is not a field{did_you_mean(key, known + ('model',))}")
    for key in known:
        if key not in section:
            raise ValueError(f"{key} is missing")
    rail = section["rail"]
    if not isinstance(rail, str) or not rail:
        raise ValueError(f"rail must be a layout rail id, got {rail!r}")
    values: dict[str, tuple[float, ...]] = {}
    for key in lists:
        raw = section[key]
        if not isinstance(raw, (list, tuple)) or not all(
            isinstance(v, (int, float)) and not isinstance(v, bool) for v in raw
        ):
            raise ValueError(f"{key} must be a list of numbers, got {raw!r}")
        values[key] = tuple(float(v) for v in raw)
    return CheckRailLateral(rail=rail, **values)


def co_running_model_from_section(check_rail: Mapping) -> str | None:
    """The ``model`` key of a ``[check_rail]`` section's ``co_running`` table, if given.

    ``model = "table1"`` keeps the FE values in the file but builds the co-running check rail
    from Eqs 1-19 on Table 1 (the paper's); ``"bracket"`` (the default when the table is
    there) from the FE values.

    Parameters
    ----------
    check_rail : mapping
        The ``[check_rail]`` section.

    Returns
    -------
    str or None
        One of :data:`CO_RUNNING_MODELS`; None when there is no ``co_running`` table or it
        has no ``model`` key.

    Raises
    ------
    ValueError
        ``model`` is not one of :data:`CO_RUNNING_MODELS`: the message names the key.
    """
    section = check_rail.get("co_running")
    if not isinstance(section, Mapping) or "model" not in section:
        return None
    model = section["model"]
    if not isinstance(model, str) or model not in CO_RUNNING_MODELS:
        hint = did_you_mean(model, CO_RUNNING_MODELS) if isinstance(model, str) else ""
        raise ValueError(
            f"model must be one of {', '.join(CO_RUNNING_MODELS)}, got {model!r}{hint}"
        )
    return model
