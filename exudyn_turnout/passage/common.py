"""What every passage shares, whatever its vehicle and track: settings checks, the time-step
limit of the wheel/rail contact, Newton's tolerance, progress reports, joining run segments
(and picking a finer run's rows at a coarser one's times) and keeping Exudyn quiet. The
finer step where a check rail carries load is :mod:`.check_rail_steps`'s.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import replace

import numpy as np

from exudyn_turnout.corunning.parameters import co_running_parameters
from exudyn_turnout.inputs.turnout import Turnout, Zone
from exudyn_turnout.inputs.vehicle import Vehicle
from exudyn_turnout.inputs.vehicle_model import VehicleModel
from exudyn_turnout.passage.settings import PassageError, PassageSettings

__all__ = [
    "monotone_progress",
    "pick_rows",
    "CONTACT_MODELS",
    "NEWTON_ABSOLUTE_TOLERANCE",
    "contact_resonance",
    "max_time_step",
    "lightest_rail_mass",
    "check_settings",
    "join_segments",
    "progress_function",
    "QuietExudyn",
    "zones_of_run",
    "newton_tolerance",
    "check_vehicle_settings",
]

#: Wheel/rail contact models of a passage (``PassageSettings.contact``).
CONTACT_MODELS = ("profile", "height-table")

#: N: Newton's absolute residual tolerance in a passage (see benchmarks/bench_passage.py).
NEWTON_ABSOLUTE_TOLERANCE = 1.0


def contact_resonance(vehicle: Vehicle, m_contact: float) -> float:
    """Wheel-on-rail resonance (Hz): half the wheelset on the linear Hertz spring over m_contact.

    Parameters
    ----------
    vehicle : Vehicle
    m_contact : float
        kg, the mass of rail under the wheel.

    Returns
    -------
    float
        Hz.
    """
    W = vehicle.static_wheel_load
    k_H = 1.5 * vehicle.contact.C_H ** (2.0 / 3.0) * W ** (1.0 / 3.0)  # dF/d delta at F = W
    m_w = 0.5 * vehicle.m_w
    return math.sqrt(k_H * (1.0 / m_w + 1.0 / m_contact)) / (2.0 * math.pi)


def max_time_step(vehicle: Vehicle, m_rail: float) -> float:
    """Largest time step (s) that resolves the wheel/rail contact: 10 steps per period.

    The vertical contact only. A check rail's contact (the back of the flange against its
    face) rings faster, ~1.04 kHz on the 2-layer track, and its force needs ~40 steps per
    period (the module docstring): the co-running passages step its loaded windows at
    ``PassageSettings.check_rail_time_step`` (:class:`CheckRailSteps`), whatever this limit.

    Parameters
    ----------
    vehicle : Vehicle
    m_rail : float
        kg, the lightest rail mass of the run (:func:`lightest_rail_mass`).

    Returns
    -------
    float
        s.
    """
    return 1.0 / (10.0 * contact_resonance(vehicle, m_rail))


def lightest_rail_mass(
    turnout: Turnout, x_a: float, x_b: float, layers: int = 3, source: str = "derived"
) -> float:
    """Lightest co-running rail mass m_r (kg) of the active rails between x_a and x_b.

    Evaluated from the actual parameter set (``layers``, ``source``) at both ends of each
    zone's part of the range; it sets the time-step limit (:func:`max_time_step`).

    Parameters
    ----------
    turnout : Turnout
    x_a, x_b : float
        Range of the run (m).
    layers : {2, 3}
    source : {"derived", "published"}

    Returns
    -------
    float
        kg.

    Raises
    ------
    PassageError
        The parameter set does not exist (e.g. ``source="published"`` without Table 2 for a zone).
    """
    masses = []
    for zone in zones_of_run(turnout, x_a, x_b):
        try:
            p = co_running_parameters(turnout, zone=zone.index, layers=layers, source=source)
        except (KeyError, ValueError) as err:
            name = turnout.source.replace("\\", "/").rsplit("/", 1)[-1]
            raise PassageError(
                f"--source {source}: {name} has no parameter set for zone {zone.index} "
                f"({str(err).rsplit(': ', 1)[-1]})"
            ) from None
        for x in (max(zone.x_start, x_a), min(zone.x_end, x_b)):
            values = p.at(x)
            masses += [values[f"m_r{slot[1:]}"] for slot in zone.active_rails]
    return float(min(masses))


def check_settings(
    settings: PassageSettings, turnout: Turnout, vehicle: Vehicle
) -> tuple[float, float]:
    """Check a single wheelset's passage settings; the run's x range.

    Contact model, irregularity (profile contact only), speed (0..400 km/h), x range inside
    the turnout, time step against the wheel/rail contact resonance with the lightest rail
    (:func:`max_time_step`) and output step (:func:`_check_output_step`).

    Parameters
    ----------
    settings : PassageSettings
    turnout : Turnout
    vehicle : Vehicle

    Returns
    -------
    x_a, x_b : float
        m, start and end of the run.

    Raises
    ------
    PassageError
        One line naming the problem.
    """
    s = settings
    if s.contact not in CONTACT_MODELS:
        raise PassageError(f"contact must be one of {', '.join(CONTACT_MODELS)}, got {s.contact!r}")
    if s.irregularity is not None and s.contact != "profile":
        raise PassageError("track irregularities need the profile contact (contact='profile')")
    if not (math.isfinite(s.speed_kmh) and 0 < s.speed_kmh <= 400):
        raise PassageError(f"speed must be > 0 and <= 400 km/h, got {s.speed_kmh:g} km/h")
    x_a = turnout.x_min if s.x_start is None else s.x_start
    x_b = turnout.x_max if s.x_end is None else s.x_end
    if not (turnout.x_min <= x_a < x_b <= turnout.x_max):
        raise PassageError(
            f"x range {x_a:g}..{x_b:g} m must lie within the turnout "
            f"({turnout.x_min:g}..{turnout.x_max:g} m) with x_start < x_end"
        )
    for name, factor in (
        ("creep_reduction", s.creep_reduction),
        ("normal_stiffness_factor", s.normal_stiffness_factor),
    ):
        if not (isinstance(factor, (int, float)) and math.isfinite(factor) and 0 < factor <= 10):
            raise PassageError(f"{name} must be > 0 and <= 10, got {factor!r}")
    if s.contact != "profile" and (s.creep_reduction, s.normal_stiffness_factor) != (1.0, 1.0):
        raise PassageError(
            "creep_reduction and normal_stiffness_factor scale the profile contact's law "
            "(contact='profile')"
        )
    m_rail = lightest_rail_mass(turnout, x_a, x_b, s.layers, s.source)
    # a stiffer normal law rings faster: the linear Hertz spring grows as factor^(2/3)
    h_max = max_time_step(vehicle, m_rail) / s.normal_stiffness_factor ** (1.0 / 3.0)
    if not (math.isfinite(s.time_step) and 0 < s.time_step <= h_max):
        raise PassageError(
            f"time step {s.time_step:g} s is too large to resolve the wheel/rail contact "
            f"(~{contact_resonance(vehicle, m_rail):.0f} Hz with the lightest rail, "
            f"{m_rail:.4g} kg): use a step <= {h_max:.2g} s (a loaded check rail needs "
            "check_rail_time_step, finer still)"
        )
    c = s.check_rail_time_step
    if c is not None and not (isinstance(c, (int, float)) and math.isfinite(c) and c > 0):
        raise PassageError(f"check_rail_time_step must be > 0 s or None, got {c!r}")
    _check_output_step(s, (x_b - x_a) / s.v)
    return x_a, x_b


def _check_output_step(s: PassageSettings, duration: float) -> None:
    """Check the output step: at least the time step, at most the run's duration.

    Parameters
    ----------
    s : PassageSettings
    duration : float
        s, the run's simulated time.

    Raises
    ------
    PassageError
        One line naming the problem.
    """
    if s.output_step is None:
        return
    if not (math.isfinite(s.output_step) and s.time_step <= s.output_step <= duration):
        raise PassageError(
            f"output step {s.output_step:g} s must be >= the time step "
            f"({s.time_step:g} s) and <= the run's duration ({duration:.4g} s)"
        )


def join_segments(segments: list[dict[str, np.ndarray]]) -> dict[str, np.ndarray]:
    """Concatenate run segments; a column missing in a segment is NaN there (rail not present).

    Parameters
    ----------
    segments : list of dict
        Each segment's columns (name -> samples).

    Returns
    -------
    dict
        The run's columns.
    """
    names: list[str] = []
    for seg in segments:
        names += [n for n in seg if n not in names]
    out = {}
    for n in names:
        out[n] = np.concatenate([seg.get(n, np.full(len(seg["t_s"]), np.nan)) for seg in segments])
    return out


def progress_function(
    progress: Callable[[float, float], None], t_offset: float, total: float, x0: float, v: float
) -> Callable:
    """Exudyn pre-step function reporting progress about every 2 % of the run.

    Parameters
    ----------
    progress : callable(fraction, x)
        The user's callback.
    t_offset : float
        s, the segment's start in the run.
    total : float
        s, the run's simulated time.
    x0, v : float
        m, m/s: position at the segment's start and speed.

    Returns
    -------
    callable
        ``pre_step(mbs, t) -> True``.
    """
    due = [0.0]

    def pre_step(mbs, t):
        if t >= due[0]:
            due[0] = t + 0.02 * total
            progress(min((t_offset + t) / total, 1.0), x0 + v * t)
        return True

    return pre_step


class QuietExudyn:
    """Silence Exudyn's console warnings (e.g. on user-function memory use) during a solve."""

    def __enter__(self):
        import exudyn as exu

        self._saved = exu.config.suppressWarnings, exu.config.printToConsole
        exu.config.suppressWarnings, exu.config.printToConsole = True, False

    def __exit__(self, *exc):
        import exudyn as exu

        exu.config.suppressWarnings, exu.config.printToConsole = self._saved
        return False


def zones_of_run(turnout: Turnout, x_a: float, x_b: float) -> list[Zone]:
    """The zones (Table 3) a run from x_a to x_b passes through.

    Parameters
    ----------
    turnout : Turnout
    x_a, x_b : float
        m.

    Returns
    -------
    list of Zone
    """
    return [z for z in turnout.zones if min(z.x_end, x_b) - max(z.x_start, x_a) > 1e-9]


def newton_tolerance(wheelsets: int) -> float:
    """Newton's absolute residual tolerance (N) of a passage with this many wheelsets.

    Exudyn compares the L2 norm of the whole residual with it. The single wheelset's
    passage uses :data:`NEWTON_ABSOLUTE_TOLERANCE`; n
    wheelsets, each with its own track and contact, get sqrt(n) times that, so that the
    residual's share of each wheelset (root mean square over the wheelsets) meets the single
    wheelset's tolerance. Measured (4 wheelsets, 3 layers, through route, 100 km/h, against
    1 N): Newton iterations per step 1.84 -> 1.65, the per-wheel switch and crossing peaks
    within 0.001 % (vertical) and 0.015 % (lateral), forces within 6 N.

    Parameters
    ----------
    wheelsets : int
        Number of wheelsets (at least 1).

    Returns
    -------
    float
        N.
    """
    return NEWTON_ABSOLUTE_TOLERANCE * math.sqrt(max(int(wheelsets), 1))


def check_vehicle_settings(
    settings: PassageSettings, turnout: Turnout, model: VehicleModel, base: Vehicle
) -> tuple[float, float]:
    """Check a full vehicle's passage settings; the front wheelset's x range.

    The front wheelset may run from the turnout's start to its end plus the vehicle's length
    (the rear wheelsets then pass the whole turnout); speed, time step (the lightest rail
    under any wheelset) and output step are checked as for one wheelset
    (:func:`check_settings`) over the range the wheelsets cover.

    Parameters
    ----------
    settings : PassageSettings
    turnout : Turnout
    model : VehicleModel
        A full vehicle (car body, bogies).
    base : Vehicle
        The contact law and wheel profile (the single-wheelset file).

    Returns
    -------
    x_a, x_b : float
        m, the front wheelset's start and end.

    Raises
    ------
    PassageError
        One line naming the problem.
    """
    if model.car_body is None:
        raise PassageError(f"{model.name}: not a full vehicle (no car body)")
    if settings.contact != "profile":
        raise PassageError("the full vehicle runs with the profile contact only")
    length = -min(model.wheelset.x)  # m, front to rear wheelset
    x_a = turnout.x_min if settings.x_start is None else float(settings.x_start)
    x_b = turnout.x_max if settings.x_end is None else float(settings.x_end)
    if not (turnout.x_min <= x_a < x_b <= turnout.x_max + length + 1e-9):
        raise PassageError(
            f"x range {x_a:g}..{x_b:g} m (front wheelset) must lie within the turnout's "
            f"start and its end plus the vehicle's length ({turnout.x_min:g}.."
            f"{turnout.x_max + length:g} m) with x_start < x_end"
        )
    covered = replace(
        settings, x_start=max(turnout.x_min, x_a - length), x_end=min(turnout.x_max, x_b)
    )
    check_settings(covered, turnout, base)
    return x_a, x_b


def pick_rows(columns: Mapping[str, np.ndarray], times: np.ndarray) -> dict[str, np.ndarray]:
    """The rows of ``columns`` nearest to ``times`` (a finer run sampled at a coarser one's
    times).

    Parameters
    ----------
    columns : mapping
        A run's columns, ``t_s`` among them.
    times : numpy.ndarray
        s, the times wanted (on the columns' clock), each within half a sample of one.

    Returns
    -------
    dict
        The same columns at those rows.

    Raises
    ------
    ValueError
        A time lies further than half a sample from every row.
    """
    t = np.asarray(columns["t_s"], float)
    times = np.asarray(times, float)
    last = len(t) - 1
    after = np.clip(np.searchsorted(t, times), 0, last)
    before = np.clip(after - 1, 0, last)
    at = np.where(np.abs(t[before] - times) < np.abs(t[after] - times), before, after)
    spacing = float(np.min(np.diff(t))) if last > 0 else math.inf
    if len(times) and not float(np.max(np.abs(t[at] - times))) <= 0.5 * spacing:
        raise ValueError("pick_rows: a time wanted lies between the run's samples")
    return {name: np.asarray(c)[at] for name, c in columns.items()}


def monotone_progress(
    progress: Callable[[float, float], None] | None,
) -> Callable[[float, float], None] | None:
    """The progress callback, called only where the fraction has not gone backwards (a
    segment run again, :meth:`CheckRailSteps.rerun`, reports its times again).

    Parameters
    ----------
    progress : callable(fraction, x) or None
        The user's callback.

    Returns
    -------
    callable(fraction, x) or None
        None where ``progress`` is None.
    """
    if progress is None:
        return None
    reached = [-math.inf]

    def report(fraction: float, x: float) -> None:
        if fraction >= reached[0]:
            reached[0] = fraction
            progress(fraction, x)

    return report
