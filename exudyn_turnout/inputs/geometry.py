"""Plan geometry of the turnout: route centrelines, crossing point and nose tip.

One source for where things are along x: the ``[layout]`` section of the turnout file
gives the diverging route's centreline (a tangential circular curve, its radius and
where it starts and ends), the track gauge and the width of the crossing nose's tip.
From them follow

- the switch toe: where the diverging curve leaves the through route (``curve_start_x``);
- the theoretical crossing point: where the gauge line of the diverging route's rail on
  the outside of the curve meets the gauge line of the through route's rail on the
  inside of the curve;
- the nose tip: where those two gauge lines are ``nose_tip_width`` apart, just after the
  crossing point (a real nose is blunt: its tip is 10-15 mm wide);
- the crossing angle 1:N at the crossing point.

The FE layout (:mod:`exudyn_turnout.fe.layout`) builds its rails on these centrelines,
and the co-running routes (:mod:`exudyn_turnout.inputs.routes`) may place their profile points
relative to these features (``"nose_tip + 0.5"``), so both models see the crossing at
the same x.

Conventions: x along the through route from the switch toe, y lateral, positive to the
left looking in +x, y = 0 on the through route's centreline.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from scipy.optimize import brentq

from exudyn_turnout.inputs.toml_fields import TurnoutFileError
from exudyn_turnout.inputs.turnout_data import Turnout

__all__ = [
    "Centreline",
    "TurnoutPlan",
    "DEFAULT_GAUGE",
    "DEFAULT_NOSE_TIP_WIDTH",
    "FEATURES",
    "load_centrelines",
    "turnout_plan",
    "resolve_position",
]

#: m, standard gauge (EN 13848-1), between the gauge points 14 mm below the rail tops.
DEFAULT_GAUGE = 1.435
#: m, width of a fixed crossing's nose at its blunt tip (10-15 mm is usual; 12 mm is ours).
DEFAULT_NOSE_TIP_WIDTH = 0.012
#: Names of the plan's features that positions in the file may refer to.
FEATURES = ("toe", "crossing_point", "nose_tip")


@dataclass(frozen=True)
class Centreline:
    """A route centreline: straight, or straight - circular curve - straight tangent."""

    name: str  #: route name, "through" or "diverging"
    side: float  #: -1 curve to the right, +1 to the left, 0 straight
    radius: float = math.inf  #: m, R of the curve
    curve_start_x: float = math.inf  #: m, where the curve leaves y = 0 tangentially
    curve_end_x: float = math.inf  #: m, centreline tangent point after the curve

    def y(self, x, offset: float = 0.0):
        """Lateral position (m) of a line at ``offset`` (m, left positive) from the centreline.

        On the curve the line is the concentric circle of radius R - side * offset.

        Parameters
        ----------
        x : float or array_like
            Position along the through route (m).
        offset : float
            Lateral offset from the centreline (m, positive to the left).

        Returns
        -------
        float or numpy.ndarray
            y (m) of the line at x.
        """
        x = np.asarray(x, float)
        if self.side == 0 or not math.isfinite(self.radius):
            return np.full_like(x, offset) if x.ndim else float(offset)
        R, s = self.radius, self.side
        rho = R - s * offset
        theta1 = math.asin(min((self.curve_end_x - self.curve_start_x) / R, 1.0))
        x1 = self.curve_start_x + rho * math.sin(theta1)
        dx = np.clip(x - self.curve_start_x, 0.0, x1 - self.curve_start_x)
        y = s * (R - np.sqrt(rho**2 - dx**2))
        y = y + s * math.tan(theta1) * np.maximum(x - x1, 0.0)
        return y if y.ndim else float(y)


@dataclass(frozen=True)
class TurnoutPlan:
    """Where the switch and the crossing are, derived from the route centrelines (SI)."""

    toe_x: float  #: m, switch toe: the diverging curve leaves the through route
    crossing_point_x: float  #: m, theoretical crossing point (gauge lines meet)
    nose_tip_x: float  #: m, blunt nose tip: the gauge lines ``nose_tip_width`` apart
    crossing_angle_n: float  #: -, the crossing angle as 1:N at the crossing point
    gauge: float  #: m, track gauge
    nose_tip_width: float  #: m

    def feature(self, name: str) -> float:
        """x (m) of a feature of :data:`FEATURES`.

        Parameters
        ----------
        name : str
            ``"toe"``, ``"crossing_point"`` or ``"nose_tip"``.

        Returns
        -------
        float
            Its x (m).
        """
        return {
            "toe": self.toe_x,
            "crossing_point": self.crossing_point_x,
            "nose_tip": self.nose_tip_x,
        }[name]


def _fail(src: str, field: str, problem: str) -> TurnoutFileError:
    return TurnoutFileError(f"{src}: {field} {problem}")


def _number(src: str, field: str, value: Any, positive: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise _fail(src, field, f"must be a finite number, got {value!r}")
    if positive and value <= 0:
        raise _fail(src, field, f"must be > 0, got {value:g}")
    return float(value)


def _layout_section(turnout: Turnout) -> tuple[str, Mapping[str, Any]]:
    src = Path(turnout.source).name
    sec = turnout.raw.get("layout")
    if not isinstance(sec, Mapping):
        raise _fail(src, "layout", "is missing (the turnout's plan geometry is read from it)")
    return src, sec


def load_centrelines(turnout: Turnout) -> dict[str, Centreline]:
    """The through and diverging route centrelines of ``[layout.diverging]``.

    Parameters
    ----------
    turnout : Turnout
        A loaded turnout file with a ``[layout]`` section.

    Returns
    -------
    dict
        ``{"through": Centreline, "diverging": Centreline}``.

    Raises
    ------
    TurnoutFileError
        The section or a field is missing or wrong (one line naming file and field).
    """
    src, sec = _layout_section(turnout)
    p = "layout.diverging"
    diverging = sec.get("diverging")
    if not isinstance(diverging, Mapping):
        raise _fail(src, p, "is missing")
    for key in ("side", "radius", "curve_start_x", "curve_end_x"):
        if key not in diverging:
            raise _fail(src, f"{p}.{key}", "is missing")
    side = diverging["side"]
    if side not in ("left", "right"):
        raise _fail(src, p + ".side", f"must be one of left, right, got {side!r}")
    radius = _number(src, p + ".radius", diverging["radius"], positive=True)
    x_start = _number(src, p + ".curve_start_x", diverging["curve_start_x"])
    x_end = _number(src, p + ".curve_end_x", diverging["curve_end_x"])
    if not x_end > x_start:
        raise _fail(
            src, p + ".curve_end_x", f"must be > curve_start_x = {x_start:g}, got {x_end:g}"
        )
    if x_end - x_start >= radius:
        raise _fail(src, p + ".curve_end_x", f"makes a curve longer than its radius ({radius:g} m)")
    return {
        "through": Centreline("through", 0.0),
        "diverging": Centreline(
            "diverging", 1.0 if side == "left" else -1.0, radius, x_start, x_end
        ),
    }


def turnout_plan(turnout: Turnout) -> TurnoutPlan:
    """Switch toe, crossing point, nose tip and crossing angle of the turnout's plan.

    ``[layout] gauge`` (default :data:`DEFAULT_GAUGE`) and ``nose_tip_width`` (default
    :data:`DEFAULT_NOSE_TIP_WIDTH`) are optional.

    Parameters
    ----------
    turnout : Turnout
        A loaded turnout file with a ``[layout]`` section.

    Returns
    -------
    TurnoutPlan
        Toe, crossing point and nose tip along x (m), the crossing angle 1:N, gauge and
        nose tip width.

    Raises
    ------
    TurnoutFileError
        The layout is missing or its diverging route never crosses the through route's
        rail within the turnout.
    """
    src, sec = _layout_section(turnout)
    gauge = _number(src, "layout.gauge", sec.get("gauge", DEFAULT_GAUGE), positive=True)
    width = _number(
        src,
        "layout.nose_tip_width",
        sec.get("nose_tip_width", DEFAULT_NOSE_TIP_WIDTH),
        positive=True,
    )
    diverging = load_centrelines(turnout)["diverging"]
    s = diverging.side

    def gap(x: float) -> float:
        # the outer-of-curve gauge line of the diverging route, measured from the through
        # route's inner-of-curve gauge line towards the curve's inside: g at the toe
        return -s * (diverging.y(x, -s * gauge / 2.0) - s * gauge / 2.0)

    x_end = _number(src, "layout.x_end", sec.get("x_end", turnout.x_max))
    if not gap(x_end) < -width:
        raise _fail(
            src,
            "layout.diverging",
            f"does not cross the through route's rail before x = {x_end:g} m (gauge {gauge:g} m)",
        )
    x_cp = float(brentq(gap, diverging.curve_start_x, x_end, xtol=1e-9))
    x_tip = float(brentq(lambda x: gap(x) + width, x_cp, x_end, xtol=1e-9))
    slope = abs(gap(x_cp + 1e-3) - gap(x_cp - 1e-3)) / 2e-3
    return TurnoutPlan(diverging.curve_start_x, x_cp, x_tip, 1.0 / slope, gauge, width)


_POSITION = re.compile(r"^\s*([a-z_]+)\s*(?:([+-])\s*([0-9.]+(?:[eE][+-]?[0-9]+)?))?\s*$")


def resolve_position(value: Any, plan: TurnoutPlan | None) -> float:
    """A position in a turnout file: a number (m) or ``"<feature> [+-] <metres>"``.

    Parameters
    ----------
    value : float or str
        e.g. ``45.3``, ``"nose_tip"``, ``"nose_tip - 0.2"``.
    plan : TurnoutPlan or None
        The plan the features refer to; None if the file has none.

    Returns
    -------
    float
        x (m).

    Raises
    ------
    ValueError
        Not a number nor a feature expression, or a feature without a plan (the message
        says which; callers add the file and field).
    """
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return float(value)
    match = _POSITION.match(value) if isinstance(value, str) else None
    if match is None or match.group(1) not in FEATURES:
        raise ValueError(
            f"must be a number or '<feature> [+-] <metres>' with a feature of "
            f"{', '.join(FEATURES)}, got {value!r}"
        )
    if plan is None:
        raise ValueError(f"refers to {match.group(1)!r}, but the file has no [layout] to derive it")
    x = plan.feature(match.group(1))
    if match.group(2):
        x += float(match.group(3)) * (1.0 if match.group(2) == "+" else -1.0)
    return x
