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

from collections.abc import Mapping
from pathlib import Path

from exudyn_turnout.inputs.check_rail import CheckRailSupport, support_from_section
from exudyn_turnout.inputs.turnout import Turnout, TurnoutFileError

__all__ = ["CheckRailSupport", "check_rail_support", "check_rail_types"]


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
    src = Path(str(turnout.source)).name
    check = turnout.raw.get("check_rail", {})
    try:
        return support_from_section(check if isinstance(check, Mapping) else {})
    except ValueError as err:
        raise TurnoutFileError(f"{src}: check_rail.support: {err}") from None


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
