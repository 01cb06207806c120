"""How a passage starts, and whether the vehicle has settled before the turnout's regions.

A run starts either

- ``"static at rest"``: the static equilibrium under gravity, the wheelset's lateral
  position and spin held (on straight track the steady state at speed up to what the holds
  carry), or
- ``"steady ..."``: the steady state at speed (curving in a curve): the vehicle at rest in
  the track-following frame with the creep forces of speed v, reached by a dynamic
  relaxation with x frozen.

Every run records ``summary["start"]`` (a string beginning with ``"steady"`` or
``"static"``) and ``summary["start_residual"]`` (N: the largest lateral force the run's
equations leave unbalanced at its start, :data:`START_TOLERANCE` decides whether it counts
as settled): after a static start the lateral hold's force, after a relaxation the largest
mass x lateral acceleration left on a body, after a static solve at speed its tolerance.
The spin holds' torque is not counted: released, it settles in about 1 ms (the spin
inertia over the creep's damping 2 r0^2 f11 / v, 112 kg m^2 / 1.5e5 N m s at 100 km/h).

A run that is not settled at its start needs :data:`SETTLING_TIME` to forget its start;
:func:`unsettled_warning` says so when one of the turnout's regions (``[regions]``: switch,
crossing) begins before that.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import MutableMapping

from exudyn_turnout.inputs.turnout import Turnout

__all__ = [
    "StartWarning",
    "START_TOLERANCE",
    "SETTLING_TIME",
    "RELAX_CHUNK",
    "RELAX_MAX_TIME",
    "RELAX_STEP",
    "RELAX_SETTLED_SPEED",
    "steady_description",
    "unsettled_warning",
    "record_start",
    "FrozenPosition",
]

#: N: a start whose residual is below this is settled. Measured with the single
#: wheelset at 80 km/h, 2-layer track, by relaxing the static start at speed with x frozen:
#: on the through route at x = 43 m the holds carry 54 N and the wheelset settles 0.05 mm
#: away (1 % of its ~6 mm flange clearance); at x = 2 m (switch) they carry 423 N and it
#: drifts more than 4 mm. The relaxation to steady curving ends near 3 N.
START_TOLERANCE = 100.0

#: s, time a start transient needs to decay: the single wheelset started at rest at
#: x = 5 m in the 760 m curve at 80 km/h (the old start, commit 13f0f7d, 2-layer track) came
#: within 1 % of its steady lateral position (5.23 mm) after 0.65 s (14.5 m) and its left
#: wheel's lateral force within 1 % of the steady 5.74 kN after 1.7 s (37 m); 2 s leaves a
#: margin. At speed v the distance is 2 s x v (44 m at 80 km/h).
SETTLING_TIME = 2.0

#: s, the relaxation to the steady state runs in chunks of this time until settled
RELAX_CHUNK = 1.0
#: s, longest relaxation (then the run starts from where it got, its residual recorded)
RELAX_MAX_TIME = 20.0
#: s, time step of the relaxation (implicit, numerically damped: only the end state matters)
RELAX_STEP = 5e-3
#: m/s (rad/s): the relaxation stops when every vehicle coordinate's velocity (the spin's
#: steady rate excepted) is below this after a chunk: a drift of 1e-5 m/s is 0.45 um per m
#: of run at 80 km/h
RELAX_SETTLED_SPEED = 1e-5


class StartWarning(UserWarning):
    """A run's first region begins before the vehicle has settled from its start."""


def steady_description(speed_kmh: float, curvature: float) -> str:
    """The ``summary["start"]`` of a steady start.

    Parameters
    ----------
    speed_kmh : float
        km/h.
    curvature : float
        1/m, the route's curvature at the start (0: straight).

    Returns
    -------
    str
        e.g. ``"steady curving at 80 km/h, R = 760 m"`` or ``"steady at 100 km/h, straight"``.
    """
    if curvature == 0.0:
        return f"steady at {speed_kmh:g} km/h, straight"
    return f"steady curving at {speed_kmh:g} km/h, R = {1.0 / abs(curvature):.0f} m"


def unsettled_warning(
    turnout: Turnout, x_start: float, v: float, start: str, residual: float
) -> str | None:
    """The one-line warning for a run whose first region begins before the vehicle settled.

    Criterion: a start is settled when ``residual`` <= :data:`START_TOLERANCE`; otherwise the
    vehicle settles :data:`SETTLING_TIME` x v after ``x_start``. The run's first region is
    the first of the turnout's ``[regions]`` that ends after ``x_start``.

    Parameters
    ----------
    turnout : Turnout
        Its ``regions``.
    x_start : float
        m, the (front wheelset's) start.
    v : float
        m/s, speed.
    start : str
        ``summary["start"]``.
    residual : float
        N, ``summary["start_residual"]``.

    Returns
    -------
    str or None
        The warning, or None when the vehicle settles before its first region.
    """
    if math.isfinite(residual) and residual <= START_TOLERANCE:
        return None
    ahead = [(a, name) for name, (a, b) in turnout.regions.items() if b > x_start]
    if not ahead:
        return None
    x_region, name = min(ahead)
    x_settled = x_start + SETTLING_TIME * v
    if x_region >= x_settled:
        return None
    where = (
        f"inside the {name} region ({x_region:g}-{turnout.regions[name][1]:g} m)"
        if x_region <= x_start
        else f"{x_region - x_start:.3g} m before the {name} region (x = {x_region:g} m)"
    )
    return (
        f"the run starts at x = {x_start:g} m {where}, {start} with residual "
        f"{residual:.3g} N (settled: <= {START_TOLERANCE:g} N): its start transient needs "
        f"about {SETTLING_TIME:g} s x v = {x_settled - x_start:.3g} m; start earlier"
    )


def record_start(
    summary: MutableMapping[str, object],
    turnout: Turnout,
    x_start: float,
    v: float,
    start: str,
    residual: float,
    stacklevel: int = 2,
) -> None:
    """Put how a run started into its summary; warn (:class:`StartWarning`) if unsettled.

    Parameters
    ----------
    summary : mapping
        Gets ``start`` and ``start_residual`` (N).
    turnout : Turnout
        Its ``regions``.
    x_start : float
        m, the (front wheelset's) start.
    v : float
        m/s, speed.
    start : str
        How the run started (:func:`steady_description` or "static at rest").
    residual : float
        N, what the start left unbalanced.
    stacklevel : int
        Of the warning, counted from the caller of this function.
    """
    summary["start"], summary["start_residual"] = start, float(residual)
    warning = unsettled_warning(turnout, x_start, v, start, float(residual))
    if warning is not None:
        warnings.warn(warning, StartWarning, stacklevel=stacklevel + 1)


class FrozenPosition:
    """The ``x_at`` of a contact element held at one position while the vehicle relaxes.

    Parameters
    ----------
    x0 : float
        m, the position returned for every t.
    """

    def __init__(self, x0: float):
        self.x0 = float(x0)

    def __call__(self, t: float) -> float:
        """The position (m) at t (s): ``x0``."""
        del t
        return self.x0
