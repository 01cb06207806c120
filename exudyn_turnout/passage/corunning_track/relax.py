"""Relaxation of a co-running system with x frozen to its steady state at speed.

One loop for the single wheelset and the full vehicle (:mod:`.wheelset`, :mod:`.vehicle`):
integrate with generalized-alpha at spectral radius 0 (numerically damped: only the end
state matters) in chunks, each continuing from where the last ended, until every moving
coordinate's velocity is below
:data:`~exudyn_turnout.passage.vehicle.start.RELAX_SETTLED_SPEED` or
:data:`~exudyn_turnout.passage.vehicle.start.RELAX_MAX_TIME` has passed; the residual is the
largest mass x lateral acceleration left (N), as ``summary["start_residual"]`` records it.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from exudyn_turnout.passage.common import NEWTON_ABSOLUTE_TOLERANCE
from exudyn_turnout.passage.settings import PassageFailure
from exudyn_turnout.passage.vehicle.start import (
    RELAX_CHUNK,
    RELAX_MAX_TIME,
    RELAX_SETTLED_SPEED,
    RELAX_STEP,
)

__all__ = ["relax_frozen"]


def relax_frozen(
    mbs,
    moving: Sequence[int],
    lateral: Sequence[tuple[int, float]],
    where: str,
    first: float = RELAX_CHUNK,
    settle_after: float = 0.0,
    carry_time: bool = False,
) -> tuple[float, float]:
    """Integrate a frozen system in chunks until it is at rest in the track-following frame.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The assembled system, x frozen (its initial state where the relaxation starts).
    moving : sequence of int
        ODE2 indices whose velocities must fall below ``RELAX_SETTLED_SPEED`` (not the
        wheelsets' spin: its rate is steady, not zero).
    lateral : sequence of (int, float)
        (ODE2 index of a body's lateral coordinate, its mass in kg): the residual's terms.
    where : str
        Put into the failure message, e.g. ``"at x = 40 m (zone 1)"``.
    first : float
        s, the first chunk (later ones ``RELAX_CHUNK``).
    settle_after : float
        s, the relaxation is not taken as settled before this time has passed.
    carry_time : bool
        Whether each chunk goes on in time (loads ramped on t need it) or starts at t = 0.

    Returns
    -------
    residual : float
        N, the largest mass x lateral acceleration at the end.
    elapsed : float
        s, the time relaxed.

    Raises
    ------
    PassageFailure
        The solver failed; the message says where.
    """
    import exudyn as exu

    from exudyn_turnout.corunning.track import simulation_settings

    data = mbs.systemData
    initial, current = exu.ConfigurationType.Initial, exu.ConfigurationType.Current
    elapsed, chunk = 0.0, first
    while True:
        sim = simulation_settings(chunk, RELAX_STEP, chunk)
        if carry_time:  # the curving loads' ramp runs on t
            sim.timeIntegration.startTime = elapsed
            sim.timeIntegration.endTime = elapsed + chunk
        sim.timeIntegration.generalizedAlpha.spectralRadius = 0.0
        sim.timeIntegration.newton.absoluteTolerance = NEWTON_ABSOLUTE_TOLERANCE
        try:
            mbs.SolveDynamic(sim)
        except (exu.SolverError, RuntimeError) as err:
            raise PassageFailure(
                f"steady state at speed not found {where}: {str(err).strip()}"
            ) from None
        elapsed += chunk
        q_t = np.asarray(data.GetODE2Coordinates_t(current))
        settled = elapsed > settle_after and np.max(np.abs(q_t[list(moving)])) < RELAX_SETTLED_SPEED
        if settled or elapsed >= RELAX_MAX_TIME - 1e-9:
            break
        data.SetODE2Coordinates(data.GetODE2Coordinates(current), initial)  # go on from here
        data.SetODE2Coordinates_t(q_t, initial)
        chunk = RELAX_CHUNK
    a = np.asarray(data.GetODE2Coordinates_tt(current))
    return max(mass * abs(float(a[i])) for i, mass in lateral), elapsed
