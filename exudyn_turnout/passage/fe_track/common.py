"""What the wheelset's and the full vehicle's passages on the FE track share: a wheelset's
FE contact element, the coupled run's settings, failure reasons, output columns, the
summary of the FE track and its finer step where a check rail carries load.

The check rail's finer step (issue 22): as on the co-running tracks
(:class:`~exudyn_turnout.passage.check_rail_steps.CheckRailSteps`), a run whose check rail carried
load (above :data:`~exudyn_turnout.passage.check_rail_steps.CHECK_RAIL_LOADED` of the static wheel
load) at a step coarser than ``PassageSettings.check_rail_time_step`` is run again from
its start, by default. Unlike there, the second run is not restarted anywhere: one Exudyn
solver steps it in pieces (:func:`solve_in_pieces`), the run's step up to
:data:`CHECK_RAIL_LEAD` before each loaded window (:func:`loaded_windows`), h / m
(m = ceil(h / check_rail_time_step)) through it to
:data:`~exudyn_turnout.passage.check_rail_steps.CHECK_RAIL_MARGIN` after its last load, the run's
step again after it (:func:`refined_pieces`); the FE planes refactorise their step matrix
at each change (:meth:`FECoSimulation.set_step
<exudyn_turnout.passage.fe_track.coupling.FECoSimulation.set_step>`). Every m-th fine
step lies on the first run's grid, where the samples are taken (:class:`StepGrid`): the
output times are the first run's.

Why a first run and not a window predicted from the route: the check rail is within reach
(the route's check range, 44.29-51 m on both routes of the packaged turnout) whether it
carries load or not; which it does is the wheelset's lateral dynamics (the diverging
route's 51 kN at the default step, the through route's 0 N). And why pieces of one solver:
Exudyn's generalized-alpha keeps its step within one ``SolveSteps`` (writing
``it.currentStepSize`` from a step function broke its time grid; a pre-step function that
returns False leaves the solver stopped), while its pieces carry the state and the
algorithmic accelerations on (pieces at one step reproduce one solve to the Newton
tolerance: 0.06 N of 51 kN measured, the solver re-evaluating the forces at a piece's start)."""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import asdict

import numpy as np

from exudyn_turnout.inputs.routes import Route
from exudyn_turnout.inputs.vehicle import Vehicle
from exudyn_turnout.passage.check_rail_steps import (
    CHECK_RAIL_MARGIN,
    CheckRailSteps,
    check_rail_force,
    check_rail_pairs,
    check_rail_step,
)
from exudyn_turnout.passage.fe_track.coupling import COUPLING_STALL_TOLERANCE
from exudyn_turnout.passage.fe_track.planes import generalized_alpha
from exudyn_turnout.passage.settings import DEFAULT_SETTINGS, PassageError, PassageSettings

__all__ = [
    "fe_contact_element",
    "coupled_run_settings",
    "failure_reason",
    "fe_columns",
    "fe_summary",
    "check_rail_steps",
    "CHECK_RAIL_LEAD",
    "loaded_windows",
    "refined_pieces",
    "StepGrid",
    "solve_in_pieces",
    "check_rail_plan",
    "FIRST_RUN_SHARE",
    "two_run_progress",
]

#: s, the finer step begins this long before a check rail's first load (its force above
#: CHECK_RAIL_LOADED of the static wheel load in the first run): the contact builds up from
#: 0 N over this time at the finer step too (the 1.04 kHz ringing is ~1 ms a period).
CHECK_RAIL_LEAD = CHECK_RAIL_MARGIN


def fe_contact_element(route_contact, vehicle: Vehicle, route: Route, x0: float, v: float, irr):
    """The profile contact element with one (y, z) coordinate pair per rail body of the route.

    Parameters
    ----------
    route_contact : RouteContact
        The route's rail bodies and tables
        (:func:`~exudyn_turnout.passage.contact.profile.route_contact`).
    vehicle : Vehicle
    route : Route
    x0, v : float
        m, m/s: position at t = 0 and speed (0: static).
    irr : Irregularity or None

    Returns
    -------
    ProfileContactElement

    Raises
    ------
    PassageError
        Both wheels touch one rail slot.
    """
    from exudyn_turnout.passage.contact.profile import N_VEHICLE_COORDINATES, ProfileContactElement

    n_bodies = route_contact.tables.n_bodies
    for slot in set(route_contact.rails):
        wheels = {w for w, r in zip(route_contact.wheels, route_contact.rails) if r == slot}
        if len(wheels) > 1:
            raise PassageError(f"route {route.name}: rail {slot} is touched by both wheels")
    coordinates = [
        (N_VEHICLE_COORDINATES + 2 * k, N_VEHICLE_COORDINATES + 2 * k + 1) for k in range(n_bodies)
    ]
    return ProfileContactElement(
        vehicle,
        route,
        route_contact.tables.select(range(n_bodies), coordinates),
        list(zip(route_contact.wheels, route_contact.rails)),
        x0,
        v,
        irr,
    )


def coupled_run_settings(duration: float, n_steps: int, settings: PassageSettings, tolerance):
    """Exudyn's settings of a run coupled to the FE track: fixed steps, the run's rho_inf.

    Parameters
    ----------
    duration : float
        s.
    n_steps : int
        Steps (the FE side's h = duration / n_steps: no adaptive step).
    settings : PassageSettings
        ``spectral_radius``.
    tolerance : float
        N, Newton's absolute tolerance.

    Returns
    -------
    exudyn.SimulationSettings
    """
    from exudyn_turnout.corunning.track import simulation_settings

    sim = simulation_settings(duration, duration / n_steps)
    sim.timeIntegration.numberOfSteps = n_steps
    sim.timeIntegration.generalizedAlpha.spectralRadius = settings.spectral_radius
    sim.timeIntegration.newton.absoluteTolerance = tolerance
    sim.timeIntegration.adaptiveStep = False
    return sim


def failure_reason(err: Exception) -> str:
    """The one line of an Exudyn error that says what went wrong (a user function's own).

    Parameters
    ----------
    err : Exception

    Returns
    -------
    str
    """
    lines = [line.strip() for line in str(err).splitlines() if line.strip()]
    for line in lines:
        if line.startswith(("RuntimeError:", "ArithmeticError:", "ValueError:")):
            return line.split(":", 1)[1].strip()
    return lines[0] if lines else type(err).__name__


def fe_columns(element, t, q, q_t, x0: float, v: float) -> dict[str, np.ndarray]:
    """Output columns: the co-running passage's names, rail columns per slot from the FE.

    ``t``: sample times (s); ``q``, ``q_t``: the element's full coordinates per sample.

    Parameters
    ----------
    element : ProfileContactElement
        The wheelset's FE contact element.
    t : numpy.ndarray
        s.
    q, q_t : numpy.ndarray
        Stored element coordinates and velocities (samples x n).
    x0, v : float
        m, m/s.

    Returns
    -------
    dict
    """
    t, q, q_t = np.asarray(t, float), np.asarray(q, float), np.asarray(q_t, float)
    cols: dict[str, np.ndarray] = {"t_s": t, "x_m": x0 + v * t}
    cols.update(element.columns(t, q, q_t))
    names = ("y_wheelset_m", "z_wheelset_m", "roll_wheelset_rad", "yaw_wheelset_rad")
    for i, name in enumerate(names + ("spin_wheelset_rad",)):
        cols[name] = q[:, i]
    x = cols["x_m"]
    bounds = element.tables.bounds
    for slot in dict.fromkeys(b.rail for b in element.bodies):
        y, z = np.full(len(t), np.nan), np.full(len(t), np.nan)
        for k, b in enumerate(element.bodies):
            if b.rail != slot:
                continue
            inside = (x >= bounds[k, 2] - 1e-9) & (x <= bounds[k, 3] + 1e-9) & np.isnan(y)
            y[inside], z[inside] = q[inside, b.i_y], q[inside, b.i_z]
        cols[f"y_rail_{slot}_m"], cols[f"z_rail_{slot}_m"] = y, z
    return cols


def fe_summary(
    planes, settings, track, h, n_steps, static_s, steps_s, first_run_s: float = 0.0
) -> dict[str, object]:
    """What the summary of an FE passage adds: the FE model, its integrator, the costs.

    Parameters
    ----------
    planes : FETrackPlanes
    settings : PassageSettings
    track : FECoSimulation
    h : float
        s, time step.
    n_steps : int
    static_s, steps_s : float
        s, wall time of the static solve and of the steps.
    first_run_s : float
        s, wall time of the first run's steps where the run was run again finer through a
        loaded check rail (``wall_time_parts_s["steps_first_run"]``); 0: not run again.

    Returns
    -------
    dict
    """
    ga = generalized_alpha(settings.spectral_radius)
    all_settings = asdict(settings)
    not_fe = ("layers", "source", "track_mechanism")
    parts = dict(track.timings, build=planes.build_s, static=static_s, steps=steps_s)
    if first_run_s:
        parts["steps_first_run"] = first_run_s
    if track.stalls[0]:
        warnings.warn(
            f"FE coupling stalled on a kink of the contact forces in {track.stalls[0]} step(s); "
            f"accepted with residuals up to {track.stalls[1]:.2g} m (limit "
            f"{COUPLING_STALL_TOLERANCE:g} m, summary['coupling_stalls'])",
            RuntimeWarning,
            stacklevel=2,
        )
    return {
        "settings": {k: val for k, val in all_settings.items() if k not in not_fe},
        "model": "FE",
        "layers": None,
        "source": "Table 1 (FE model)",
        "lateral": "FE lateral plane with rail torsion (roll and warping)"
        if planes.lateral.torsion is not None
        else "FE lateral plane, bending only",
        "n_dof": planes.vertical.n_dof + planes.lateral.n_dof,
        "n_dof_vertical": planes.vertical.n_dof,
        "n_dof_lateral": planes.lateral.n_dof,
        "time_integration": (
            f"generalized-alpha (Exudyn's), rho_inf {settings.spectral_radius:g}: alpha_m = "
            f"{ga.alpha_m:.4f}, alpha_f = {ga.alpha_f:.4f}, beta = {ga.beta:.4f}, gamma = "
            f"{ga.gamma:.4f}; FE track co-simulated with exact one-step coupling"
        ),
        "time_step_s": float(h),
        "n_steps": int(n_steps),
        "fe_options": asdict(planes.vertical.mesh.options),
        "fe_window": (
            "whole model"
            if track.window is None
            else (
                f"{track.window.window_length:g} m about each wheelset, cut every "
                f"{track.window.window_shift:g} m ({track.window_cuts} cuts, "
                f"{min(track.window_dofs)}-{max(track.window_dofs)} DOFs), absorbing ends "
                f"{track.window.window_absorbing_length:g} m to loss factor "
                f"{track.window.window_eta_max:g}"
            )
        ),
        "wall_time_parts_s": {k.removesuffix("_s"): float(t) for k, t in parts.items()},
        "coupling_stalls": {
            "count": int(track.stalls[0]),
            "largest_residual_m": float(track.stalls[1]),
        },
    }


def check_rail_steps(
    settings: PassageSettings,
    route: Route,
    static_wheel_load: float,
    columns: dict,
    summary: dict,
    wheelsets: int = 0,
    stacklevel: int = 2,
    refined: Sequence[tuple[float, float, float]] = (),
) -> None:
    """Record the check rail's step in an FE passage's summary, and warn where a check-rail
    contact carried load at a step coarser than ``settings.check_rail_time_step``.

    Keys as on the co-running tracks (:meth:`CheckRailSteps.record
    <exudyn_turnout.passage.check_rail_steps.CheckRailSteps.record>`): ``check_rail_time_step_s``,
    ``check_rail_refined`` (the windows run at the finer step, front wheelset's x) and,
    where a loaded window ran at the coarse step (refining off: ``check_rail_time_step``
    None; or a load outside the windows the first run found),
    ``check_rail_step_warning``, issued as a
    :class:`~exudyn_turnout.passage.check_rail_steps.CheckRailStepWarning`. Measured (diverging
    route, 80 km/h, single wheelset, x 42..52 m, the check-rail force's peak at the
    samples every 1e-4 s): 51.18 kN at 1e-4 s unrefined, 52.09 kN refined, 52.09 / 51.95 kN
    at 2.5e-5 / 1.25e-5 s throughout. The 66.9 / 67.7 kN of those fine runs sampled every
    step is a spike of ~50 us at the end of the check rail's entry flare (45.29 m), between
    the samples of a 1e-4 s output grid whatever the step.

    Parameters
    ----------
    settings : PassageSettings
    route : Route
    static_wheel_load : float
        N.
    columns : dict
        The run's columns (``t_s``, ``x_m``: the front wheelset's).
    summary : dict
        Its summary (changed in place).
    wheelsets : int
        0: the single wheelset; n: the full vehicle's n wheelsets.
    stacklevel : int
        Of the warning, counted from the caller of this function.
    refined : sequence of (float, float, float)
        s, s, s: per piece run at the finer step, its start and end time and its step.
    """
    limit = settings.check_rail_time_step or DEFAULT_SETTINGS.check_rail_time_step
    if check_rail_step(settings) is None:
        where = (
            "the FE track refines a loaded check rail only with check_rail_time_step set: "
            f"leave it at its default or give --time-step <= {limit:g} s"
        )
    else:
        where = "the FE track's windows at the finer step (from its first run) missed it"
    check = CheckRailSteps(settings, route, static_wheel_load, wheelsets, where)
    t, x = np.asarray(columns["t_s"], float), np.asarray(columns["x_m"], float)
    for t_a, t_b, step in refined:
        x_a, x_b = np.interp((t_a, t_b), t, x)
        check.refined.append((float(x_a), float(x_b), float(step)))
    for window in loaded_windows(columns, check.pairs, check.threshold, check.labels):
        inside = any(a - 1e-9 <= window[0] and window[1] <= b + 1e-9 for a, b, _ in refined)
        if not inside:
            check.unrefined(window, columns)
    check.record(summary, stacklevel + 1)


def loaded_windows(
    columns: Mapping[str, np.ndarray],
    pairs: Sequence[tuple[str, str]],
    threshold: float,
    labels: Sequence[str] = ("",),
    gap: float = 2.0 * CHECK_RAIL_MARGIN + CHECK_RAIL_LEAD,
) -> list[tuple[float, float, float]]:
    """The time windows in which a check-rail contact carried load, each one's peak.

    As :func:`~exudyn_turnout.passage.check_rail_steps.check_rail_window`, but split where the load
    stops for longer than ``gap`` (the full vehicle's bogies pass a check rail ~0.8 s
    apart at 80 km/h: two windows, not one over the whole run).

    Parameters
    ----------
    columns : mapping
        The run's columns: ``t_s`` and per contact ``Fy_<label><wheel>_<slot>_N``,
        ``Fz_...``.
    pairs : sequence of (str, str)
        :func:`~exudyn_turnout.passage.check_rail_steps.check_rail_pairs`.
    threshold : float
        N.
    labels : sequence of str
        Column prefixes of the wheelsets (``("",)``: the single wheelset).
    gap : float
        s, the shortest pause that splits two windows.

    Returns
    -------
    list of (float, float, float)
        s, s, N: first and last time above ``threshold`` and the largest force, in order.
    """
    t, force = check_rail_force(columns, pairs, labels)
    where = np.flatnonzero(force > threshold)
    windows: list[tuple[float, float, float]] = []
    if not len(where):
        return windows
    breaks = np.flatnonzero(np.diff(t[where]) > gap)
    for first, last in zip(np.r_[0, breaks + 1], np.r_[breaks, len(where) - 1]):
        i, j = where[first], where[last]
        windows.append((float(t[i]), float(t[j]), float(np.max(force[i : j + 1]))))
    return windows


def refined_pieces(
    n_steps: int, h: float, fine_step: float, windows: Sequence[tuple[float, float, float]]
) -> tuple[tuple[int, int, int], ...]:
    """The pieces of a run at the finer step through its loaded windows.

    A window (t_first, t_last) is run at h / m, m = ceil(h / ``fine_step``), from the grid
    point at or before t_first - :data:`CHECK_RAIL_LEAD` to the one at or after t_last +
    :data:`~exudyn_turnout.passage.check_rail_steps.CHECK_RAIL_MARGIN` (to the run's end where less
    than a margin is left); overlapping windows merge; the rest at h.

    Parameters
    ----------
    n_steps : int
        The run's steps of h.
    h : float
        s, the run's step.
    fine_step : float
        s, ``check_rail_time_step``.
    windows : sequence of (float, float, float)
        :func:`loaded_windows`' (s from the run's start).

    Returns
    -------
    tuple of (int, int, int)
        Per piece in order: first and last grid index (0..n_steps) and its substeps m per
        step of h (1: the run's step).
    """
    m = max(1, int(math.ceil(h / fine_step - 1e-9)))
    tail = int(math.ceil(CHECK_RAIL_MARGIN / h - 1e-9))
    spans: list[list[int]] = []
    for t_first, t_last, _ in windows:
        a = max(0, int(math.floor((t_first - CHECK_RAIL_LEAD) / h + 1e-9)))
        b = min(n_steps, int(math.ceil((t_last + CHECK_RAIL_MARGIN) / h - 1e-9)))
        if b > n_steps - tail:
            b = n_steps
        if spans and a <= spans[-1][1]:
            spans[-1][1] = max(spans[-1][1], b)
        elif b > a:
            spans.append([a, b])
    pieces: list[tuple[int, int, int]] = []
    at = 0
    for a, b in spans:
        if a > at:
            pieces.append((at, a, 1))
        pieces.append((a, b, m))
        at = b
    if at < n_steps:
        pieces.append((at, n_steps, 1))
    return tuple(pieces)


class StepGrid:
    """Which steps of a run in pieces end on the first run's grid, and which are sampled.

    Call :meth:`step` once for the start state and once after every step; set
    ``substeps`` (m: steps per grid step) before each piece.

    Parameters
    ----------
    every : int
        Grid steps per output sample.
    every_fine_step : bool
        Sample every step of a piece finer than the grid as well.
    """

    def __init__(self, every: int, every_fine_step: bool = False):
        self.every = max(1, int(every))
        self.every_fine_step = bool(every_fine_step)
        self.substeps = 1  #: steps per grid step in the current piece
        self.index = 0  #: the grid index of the last grid point reached
        self._sub = 0
        self._started = False

    def step(self, last: bool = False) -> bool:
        """Count a step (the first call: the start state); whether to sample it.

        Parameters
        ----------
        last : bool
            The run's last step (always sampled).

        Returns
        -------
        bool
            True where the step ends on the grid at an output step, or is the last.
        """
        if not self._started:
            self._started = True
            return True
        fine = self.every_fine_step and self.substeps > 1
        self._sub += 1
        if self._sub < self.substeps:
            return last or fine
        self._sub = 0
        self.index += 1
        return last or fine or self.index % self.every == 0


def solve_in_pieces(
    solver,
    mbs,
    sim,
    pieces: Sequence[tuple[int, int, int]],
    h: float,
    duration: float,
    set_step,
    grid: StepGrid,
) -> None:
    """Run an assembled Exudyn system through ``pieces`` with one implicit solver.

    Per piece the FE track and the grid are told its step (``set_step(h / m)``,
    ``grid.substeps = m``) and the solver's ``SolveSteps`` runs it from where the one
    before ended: no restart (the state and the algorithmic accelerations carry on).
    Each ``SolveSteps`` calls the post-step function once at its start with the state
    already stepped to: the step functions skip that call (``t`` equal to the FE track's
    current time).

    Parameters
    ----------
    solver : exudyn.MainSolverImplicitSecondOrder
        A new one (made by the builder: only builders import exudyn).
    mbs : exudyn.MainSystem
        Assembled, its step functions set.
    sim : exudyn.SimulationSettings
        :func:`coupled_run_settings`' for the whole run at ``h``.
    pieces : sequence of (int, int, int)
        :func:`refined_pieces`'.
    h : float
        s, the grid's step.
    duration : float
        s, the run's end.
    set_step : callable(float)
        Sets the FE track's step (:meth:`FECoSimulation.set_step
        <exudyn_turnout.passage.fe_track.coupling.FECoSimulation.set_step>`).
    grid : StepGrid

    Raises
    ------
    RuntimeError
        The solver reports a failure (a user function's error is raised as it is).
    """
    if not solver.InitializeSolver(mbs, sim):
        raise RuntimeError("the dynamic solver could not be initialised")
    t = float(solver.it.startTime)
    for _, b, m in pieces:
        step = h / m
        set_step(step)
        grid.substeps = m
        it = solver.it
        it.startTime = t
        it.endTime = duration if b == pieces[-1][1] else b * h
        it.currentStepSize = step
        it.maxStepSize = step
        if not solver.SolveSteps(mbs, sim):
            raise RuntimeError(solver.GetErrorString() or "SolveSteps failed")
        t = float(solver.it.currentTime)
    solver.FinalizeSolver(mbs, sim)


def check_rail_plan(
    settings: PassageSettings,
    route: Route,
    static_wheel_load: float,
    columns: Mapping[str, np.ndarray],
    n_steps: int,
    h: float,
    wheelsets: int = 0,
) -> tuple[tuple[int, int, int], ...] | None:
    """The pieces of a second run at the finer step, or None where none is due.

    None where the route has no check rail, refining is off or not finer
    (:func:`~exudyn_turnout.passage.check_rail_steps.check_rail_step`), or no check rail carried
    load in the first run (``columns``).

    Parameters
    ----------
    settings : PassageSettings
    route : Route
    static_wheel_load : float
        N.
    columns : mapping
        The first run's columns.
    n_steps : int
    h : float
        s, its step.
    wheelsets : int
        0: the single wheelset; n: the full vehicle's n wheelsets.

    Returns
    -------
    tuple of (int, int, int) or None
        :func:`refined_pieces`.
    """
    from exudyn_turnout.passage.check_rail_steps import CHECK_RAIL_LOADED

    fine = check_rail_step(settings)
    pairs = check_rail_pairs(route)
    if fine is None or not pairs:
        return None
    labels = tuple(f"ws{i + 1}_" for i in range(wheelsets)) if wheelsets else ("",)
    threshold = CHECK_RAIL_LOADED * float(static_wheel_load)
    windows = loaded_windows(columns, pairs, threshold, labels)
    if not windows:
        return None
    return refined_pieces(n_steps, h, fine, windows)


#: The share of the progress line the first run takes where a second, finer run through a
#: loaded check rail may follow: refining makes a diverging FE run 2.1-2.3x the CPU of one
#: run (validation/vehicle_step_convergence.md, ``--fe-only``), so the first is ~0.45 of it.
FIRST_RUN_SHARE = 0.45


def two_run_progress(
    progress: Callable[[float, float], None] | None, settings: PassageSettings, route: Route
) -> tuple[Callable[[float, float], None] | None, Callable[[float, float], None] | None]:
    """Progress callbacks of an FE passage's first run and of its second, finer one.

    Where no second run can follow (no check rail on the route, or refining off,
    :func:`~exudyn_turnout.passage.check_rail_steps.check_rail_step`), the first run reports
    0..1 and the second callback is None. Otherwise the first reports 0..:data:`FIRST_RUN_SHARE` and
    the second the rest, so that the line neither stands at 100 % nor goes back while the
    second run works; where none follows, the line goes from the share to its end.

    Parameters
    ----------
    progress : callable(fraction, x) or None
        The user's callback.
    settings : PassageSettings
    route : Route

    Returns
    -------
    first, second : callable(fraction, x) or None
    """
    if progress is None:
        return None, None
    user = progress
    if check_rail_step(settings) is None or not check_rail_pairs(route):
        return user, None

    def first(fraction: float, x: float) -> None:
        user(FIRST_RUN_SHARE * fraction, x)

    def second(fraction: float, x: float) -> None:
        user(FIRST_RUN_SHARE + (1.0 - FIRST_RUN_SHARE) * fraction, x)

    return first, second
