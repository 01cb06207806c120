"""The check rail's support in the FE reference: an L-bracket that holds its roll.

A check rail is not clipped down like a running rail: it stands on a bracket (an L-shaped
check chair) bolted to the running rail's baseplate, and its web is bolted to the bracket's
upright leg. The paper says so (Sec. 2: "check rails sit on stiff L-brackets") and gives the
bracket's lateral stiffness and damping as the check rail type's pad values of Table 1
(k_y = 120 MN/m, c_y = 25 kN s/m against 25 MN/m for a running rail's pad). In the planar
lateral FE that is all there is. In the torsion-aware one, where the rails roll
(:mod:`~exudyn_turnout.fe.torsion`), where that lateral support acts matters: at the foot,
as a running rail's pad, the check rail rolls about it under a load at its head, and its
head moves ~2.2 mm under 31 kN near its free end (13.7 MN/m, issue 23). The bracket holds
the web, so:

- the lateral support (the Table 1 ``pad.k_y``, ``c_y`` of the check rail's type) acts at
  ``height`` above the rail foot, at the bolts in the web, and
- the bolted upright leg adds a roll stiffness ``k_roll`` (with damping ``c_roll``) to the
  pad's own k_z b^2 / 12.

Both are per support (per sleeper). They come from ``[check_rail.support]`` of the turnout
file, with the defaults of :class:`CheckRailSupport` (reasons there). The check rail's rail
types are those of slot r3 in the zones where r3 is active (Table 3), as the report takes
them.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

from exudyn_turnout.inputs.turnout import Turnout, TurnoutFileError

__all__ = ["CheckRailSupport", "check_rail_support", "check_rail_types"]


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


def check_rail_support(turnout: Turnout) -> CheckRailSupport:
    """The file's ``[check_rail.support]`` over the defaults of :class:`CheckRailSupport`.

    Parameters
    ----------
    turnout : Turnout
        A loaded turnout file.

    Returns
    -------
    CheckRailSupport

    Raises
    ------
    TurnoutFileError
        An unknown key or a value out of range, naming the file and the field.
    """
    src = getattr(turnout.source, "name", str(turnout.source))
    check = turnout.raw.get("check_rail", {})
    section = check.get("support", {}) if isinstance(check, Mapping) else {}
    if not isinstance(section, Mapping):
        raise TurnoutFileError(f"{src}: check_rail.support must be a table")
    known = ("height", "k_roll", "c_roll")
    values: dict[str, float] = {}
    for key, value in section.items():
        if key not in known:
            raise TurnoutFileError(
                f"{src}: check_rail.support.{key} is not a field (fields: {', '.join(known)})"
            )
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise TurnoutFileError(f"{src}: check_rail.support.{key} must be a number")
        values[key] = float(value)
    try:
        return CheckRailSupport(**values)  # type: ignore[arg-type]
    except ValueError as err:
        raise TurnoutFileError(f"{src}: check_rail.support.{err}") from None


def check_rail_types(turnout: Turnout) -> frozenset[str]:
    """Rail types of the check rails: slot r3's in the zones where r3 is active (Table 3).

    Parameters
    ----------
    turnout : Turnout

    Returns
    -------
    frozenset of str
        Names in ``turnout.rail_types``.
    """
    return frozenset(z.rail_types["r3"] for z in turnout.zones if "r3" in z.active_rails)
