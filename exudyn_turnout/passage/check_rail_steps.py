"""The finer time step where a check rail carries load, in every passage.

The check rail (issue 22): the back of the flange against the check rail's face is a stiff
lateral contact whose force rings at ~1.04 kHz after the end of the check rail's entry flare
(2 layers, diverging route, 80 km/h, full vehicle: validation/vehicle_step_convergence.md).
At the default step (1e-4 s, 9.6 steps per period) its peak is 14.9 % low, at 5e-5 s 7.6 %;
2.5e-5 s is within 1.3 % of 6.25e-6 s. The vertical contact's limit
(:func:`max_time_step`) does not see it. A co-running passage therefore runs every segment
at its step first, finds where a check-rail contact carried load
(:func:`check_rail_window`: above :data:`CHECK_RAIL_LOADED` of the static wheel load) and,
where the step is coarser than ``PassageSettings.check_rail_time_step``, runs the segment
again from its start to the end of that load at the finer step (:func:`refine_pieces`),
sampled at the run's own output times (:func:`~exudyn_turnout.passage.common.pick_rows`,
:func:`piece_times`). A run that cannot (the FE track) or is told not to (the setting
None) warns with :class:`CheckRailStepWarning` instead.

Predicted check-rail segments (issue 22 follow-up): before a segment runs,
:meth:`CheckRailSteps.predict` says whether it may load the check rail: a wheelset that is on
a check-rail contact's x range during the segment (the route's ``check`` ranges) and whose
lateral displacement towards that check rail at the segment's start is at least
:data:`CHECK_RAIL_HEADING` of the least clearance it meets there (``[check_rail]`` clearance,
opened by the flares). Such a segment runs at the fine step directly, from the grid point where
the first such wheelset reaches its check rail's start (the segment's start where it is on it
already), and its fine stepping ends where :func:`refine_pieces` would end it, decided during
the run from its own samples at the segment's grid times (:class:`CheckRailStop`); the rest
runs at the run's step. The coarse run of the after-the-fact method, which was thrown away,
is saved. The after-the-fact check stays as a safety net: a segment predicted unloaded whose
check rail carries load runs again as before (``summary["check_rail_rerun"]`` names it).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from exudyn_turnout.passage.common import join_segments, pick_rows
from exudyn_turnout.passage.settings import PassageSettings

__all__ = [
    "CHECK_RAIL_LOADED",
    "CHECK_RAIL_MARGIN",
    "CHECK_RAIL_HEADING",
    "CHECK_RAIL_QUIET",
    "CheckRailStepWarning",
    "check_rail_pairs",
    "check_rail_step",
    "check_rail_force",
    "check_rail_window",
    "refine_pieces",
    "piece_times",
    "check_rail_warning",
    "CheckRailStop",
    "CheckRailSteps",
    "refined_line",
]

#: Fraction of the static wheel load above which a check-rail contact's force (the magnitude
#: of its lateral and vertical force) counts as carrying load. Below it the contact's error
#: at a coarse step (measured <= 25 % of its own force before issue 22's contact lead along
#: x, 14.9 % on the full vehicle at 1e-4 s; 1.8 % since) is below 0.25 % of a wheel load,
#: under the Newton tolerance's effect on the peaks; and a contact that only grazes (a few
#: newtons while the flange passes the flare) costs nothing.
CHECK_RAIL_LOADED = 0.01
#: s, the refined window ends this long after the check rail's last load: 5 periods of its
#: ~1.04 kHz ringing (it has died down by then).
CHECK_RAIL_MARGIN = 0.005
#: Fraction of the check rail's least clearance over a segment (``[check_rail]`` clearance,
#: opened by the flares) that a wheelset's lateral displacement towards it at the segment's
#: start must reach for the segment to be predicted to load it (:meth:`CheckRailSteps.predict`).
#: The 2-layer full vehicle on the diverging route at 80 km/h (clearance 4 mm): the leading
#: wheelset, which loads it, runs 6.2 mm towards it at 44.29 m and 5.0 mm at 46.85 m; the
#: trailing one of the bogie, which does not, 1.3 mm at 51 m; on the through route (100 km/h)
#: they run within 0.3 mm of the centre towards its check rail. A wrong guess costs time,
#: not accuracy: a segment predicted unloaded that loads it runs again (the safety net).
CHECK_RAIL_HEADING = 0.5
#: s, how long a predicted segment's fine run goes on past where :func:`refine_pieces` would
#: end it (the last load plus :data:`CHECK_RAIL_MARGIN`) before it stops
#: (:class:`CheckRailStop`): a load within it moves that end on, as the after-the-fact
#: method's window would; without one the rest runs from the state kept at that end. The
#: diverging route's leading wheelset (2 layers, 80 km/h) leaves the check rail after the
#: ringing for 21.5 ms (45.36-45.84 m) and comes back.
CHECK_RAIL_QUIET = 0.03


class CheckRailStepWarning(UserWarning):
    """A check-rail contact carried load in a run whose step is coarser than
    ``PassageSettings.check_rail_time_step`` (or than its default where refining is off)."""


def check_rail_pairs(route: Any) -> tuple[tuple[str, str], ...]:
    """The route's check-rail contacts as (wheel, rail slot), e.g. (("right", "r3"),).

    Parameters
    ----------
    route : Route
        :func:`~exudyn_turnout.inputs.routes.load_route`'s.

    Returns
    -------
    tuple of (str, str)
        Empty where the route has no check rail.
    """
    out: list[tuple[str, str]] = []
    for pair in route.pairs:
        if pair.check and (pair.wheel, pair.rail) not in out:
            out.append((pair.wheel, pair.rail))
    return tuple(out)


def check_rail_step(settings: PassageSettings) -> float | None:
    """The step (s) a loaded check rail's window is run at, or None where nothing is refined.

    Parameters
    ----------
    settings : PassageSettings

    Returns
    -------
    float or None
        ``settings.check_rail_time_step`` where it is finer than ``settings.time_step``.
    """
    h = settings.check_rail_time_step
    if h is None or not h < settings.time_step * (1.0 - 1e-9):
        return None
    return float(h)


def check_rail_force(
    columns: Mapping[str, np.ndarray],
    pairs: Sequence[tuple[str, str]],
    labels: Sequence[str] = ("",),
) -> tuple[np.ndarray, np.ndarray]:
    """The largest check-rail contact force at every sample of a run's columns.

    Parameters
    ----------
    columns : mapping
        ``t_s`` and per contact ``Fy_<label><wheel>_<slot>_N``, ``Fz_...`` (missing or NaN:
        no contact).
    pairs : sequence of (str, str)
        :func:`check_rail_pairs`.
    labels : sequence of str
        Column prefixes of the wheelsets: ``("",)`` for the single wheelset,
        ``("ws1_", "ws2_", ...)`` for the full vehicle.

    Returns
    -------
    t, force : numpy.ndarray
        s, N: the columns' times and, per sample, the largest magnitude of a check-rail
        contact's lateral and vertical force (0 without contact).
    """
    t = np.asarray(columns["t_s"], float)
    force = np.zeros(len(t))
    for label in labels:
        for wheel, slot in pairs:
            name = f"{label}{wheel}_{slot}_N"
            if f"Fy_{name}" not in columns:
                continue
            fy = np.nan_to_num(np.asarray(columns[f"Fy_{name}"], float))
            fz = np.nan_to_num(np.asarray(columns.get(f"Fz_{name}", np.zeros(len(t))), float))
            force = np.maximum(force, np.hypot(fy, fz))
    return t, force


def check_rail_window(
    columns: Mapping[str, np.ndarray],
    pairs: Sequence[tuple[str, str]],
    threshold: float,
    labels: Sequence[str] = ("",),
) -> tuple[float, float, float] | None:
    """Where a check-rail contact carried load in a run segment's columns.

    Parameters
    ----------
    columns : mapping
        The segment's columns: ``t_s`` and per contact ``Fy_<label><wheel>_<slot>_N``,
        ``Fz_...`` (missing or NaN: no contact).
    pairs : sequence of (str, str)
        :func:`check_rail_pairs`.
    threshold : float
        N, the force above which the contact carries load (:data:`CHECK_RAIL_LOADED` x the
        static wheel load).
    labels : sequence of str
        Column prefixes of the wheelsets: ``("",)`` for the single wheelset,
        ``("ws1_", "ws2_", ...)`` for the full vehicle.

    Returns
    -------
    (t_first, t_last, peak) or None
        s (the columns' own times), N: the first and last times above ``threshold`` and the
        largest force; None where it was never above.
    """
    t, force = check_rail_force(columns, pairs, labels)
    loaded = force > threshold
    if not loaded.any():
        return None
    peak = float(np.max(force))
    where = np.flatnonzero(loaded)
    return float(t[where[0]]), float(t[where[-1]]), peak


def refine_pieces(
    duration: float, time_step: float, fine_step: float, t_last: float
) -> tuple[tuple[int, int, float], ...]:
    """Split a run segment into pieces: its start to the check rail's last load at the fine
    step, the rest at the run's.

    The segment's own grid is that of its first run: n = ceil(duration / time_step) steps
    of h = duration / n. The fine piece runs from the segment's start (the integrator is not
    restarted during the check rail's approach: a restart 5-20 ms before the flare's end
    moved the 2-layer diverging route's check-rail peak by 4 %, 122.5 against 128.1 kN at
    2.5e-5 s throughout; from the segment's start, 1e-4 s refined to 2.5e-5 s gave
    126.6 kN; numbers before issue 22's contact lead along x, 86.3 kN since) to
    ``t_last`` + :data:`CHECK_RAIL_MARGIN`, widened to the grid (to the segment's end
    where less than a margin is left), at h / m, m = ceil(h / fine_step):
    every m-th of its steps lies on the grid, so that the run's samples keep their times.

    Parameters
    ----------
    duration : float
        s, the segment's duration.
    time_step : float
        s, the run's step.
    fine_step : float
        s, the check rail's (:func:`check_rail_step`).
    t_last : float
        s from the segment's start: the check rail's last load (:func:`check_rail_window`).

    Returns
    -------
    tuple of (int, int, float)
        Per piece, in order: first and last index on the grid (0..n) and its step (s).
    """
    n = max(1, int(math.ceil(duration / time_step - 1e-9)))
    h = duration / n
    m = max(1, int(math.ceil(h / fine_step - 1e-9)))
    b = max(1, int(math.ceil((t_last + CHECK_RAIL_MARGIN) / h - 1e-9)))
    if b > n - int(math.ceil(CHECK_RAIL_MARGIN / h - 1e-9)):
        b = n
    pieces = [(0, b, h / m), (b, n, h)]
    return tuple(p for p in pieces if p[1] > p[0])


def piece_times(
    t: np.ndarray, t_offset: float, a: int, b: int, h: float, step: float
) -> np.ndarray:
    """The first run's output times that a refined piece gives (:func:`refine_pieces`).

    Parameters
    ----------
    t : numpy.ndarray
        s, the segment's first run's output times (``t_s``).
    t_offset : float
        s, the segment's start.
    a, b : int
        The piece's first and last index on the segment's grid.
    h : float
        s, the grid's step.
    step : float
        s, the piece's step.

    Returns
    -------
    numpy.ndarray
        s: from the piece's start (where a > 0 after it: the piece before gives that one)
        to its end.
    """
    t = np.asarray(t, float)
    t_a, t_b = t_offset + a * h, t_offset + b * h
    after = -0.5 * step if a == 0 else 0.5 * step
    return t[(t > t_a + after) & (t <= t_b + 0.5 * step)]


def check_rail_warning(
    where: str, peak: float, x_range: tuple[float, float], time_step: float, limit: float
) -> str:
    """The one-line warning of a check-rail contact that carried load at too coarse a step.

    Parameters
    ----------
    where : str
        E.g. "the FE track" or "--time-step given".
    peak : float
        N, the contact's largest force.
    x_range : (float, float)
        m, where it carried load.
    time_step : float
        s, the run's step.
    limit : float
        s, the check rail's step (``PassageSettings.check_rail_time_step`` or its default).

    Returns
    -------
    str
    """
    return (
        f"a check rail's contact force (|(Fy, Fz)|) reached {peak / 1e3:.1f} kN at x = "
        f"{x_range[0]:.2f}-{x_range[1]:.2f} m "
        f"at a time step of {time_step:g} s, coarser than the check rail's {limit:g} s "
        f"({where}): its force may not be converged in the step (diverging route at "
        "80 km/h, 2-layer track, 1e-4 s throughout: 1.8 % above the converged force, "
        "validation/vehicle_step_convergence.md)"
    )


class CheckRailStop:
    """Where a predicted segment's fine piece ends: :func:`refine_pieces`'s rule on the fine
    run's own samples at the segment's grid times, decided while it runs.

    Called before each fine step (an Exudyn pre-step function's) with a function giving the
    check rails' largest force at the step's start, read only at the grid times, and one
    giving the system's state. The fine piece ends on grid index :attr:`end`: the last loaded
    grid time plus :data:`CHECK_RAIL_MARGIN`, on the grid (the segment's end where less than
    a margin is left after it). The state there is kept (:attr:`state`) and the run goes on
    for :data:`CHECK_RAIL_QUIET`: a load within it moves :attr:`end` on (the state is
    dropped), as the after-the-fact window of the whole segment would; without one the run
    stops and the rest runs from the kept state. Never loaded: the piece runs to the
    segment's end.

    Parameters
    ----------
    duration : float
        s, the segment's.
    time_step : float
        s, the run's step (the segment's grid: n = ceil(duration / time_step) steps of h).
    fine_step : float
        s, the check rail's.
    first : int
        The fine piece's first grid index.
    threshold : float
        N, the force above which a check rail counts as loaded.
    pairs : tuple of (str, str)
        The check-rail contacts watched (:func:`check_rail_pairs`).
    """

    def __init__(
        self,
        duration: float,
        time_step: float,
        fine_step: float,
        first: int,
        threshold: float,
        pairs: tuple[tuple[str, str], ...] = (),
    ):
        self.pairs = tuple(pairs)
        self.duration, self.time_step, self.fine_step = duration, time_step, fine_step
        pieces = refine_pieces(duration, time_step, fine_step, 0.0)
        self.n = pieces[-1][1]  #: the segment's grid steps
        self.h = duration / self.n  #: s, its grid step
        self.m = max(1, int(math.ceil(self.h / fine_step - 1e-9)))  #: fine steps per grid step
        self.first = int(first)
        self.threshold = float(threshold)
        self.steps = 0  #: fine steps begun
        self.last: int | None = None  #: the last loaded grid index
        self.end = self.n  #: grid index where the fine piece ends
        self.peak = 0.0  #: N, the largest force seen at the grid times
        #: grid steps of :data:`CHECK_RAIL_QUIET`
        self.quiet = max(1, int(math.ceil(CHECK_RAIL_QUIET / self.h - 1e-9)))
        #: the state at grid index :attr:`end` (None: not reached, or loaded after it)
        self.state: Any = None

    def __call__(
        self, force: Callable[[], float | None], state: Callable[[], Any], step: int | None = None
    ) -> bool:
        """Before a fine step: sample at a grid time, and whether to go on after the step.

        Parameters
        ----------
        force : callable() -> float or None
            N, the check rails' largest force at the step's start (None: not known).
        state : callable()
            The system's state at the step's start (kept at grid index :attr:`end`).
        step : int, optional
            The fine step's index in the run (default: one more than the last call's, every
            step called; a caller that calls at the grid times only gives it).

        Returns
        -------
        bool
            False: the run stops after this step (:data:`CHECK_RAIL_QUIET` after
            :attr:`end` without a load).
        """
        k = self.steps if step is None else int(step)
        self.steps = k + 1
        if k % self.m:
            return True
        j = self.first + k // self.m
        value = force()
        if value is not None:
            self.peak = max(self.peak, value)
            if value > self.threshold:
                self.last = j
                b = refine_pieces(self.duration, self.time_step, self.fine_step, j * self.h)
                self.end, self.state = b[0][1], None
        if self.last is None or self.end >= self.n:
            return True
        if j == self.end:
            self.state = state()
        return not (self.state is not None and j >= self.end + self.quiet)


class CheckRailSteps:
    """A passage's bookkeeping of its check rail's step: where its contact carried load, which
    windows ran at the finer step, the warning where none did.

    Parameters
    ----------
    settings : PassageSettings
        ``time_step`` and ``check_rail_time_step``.
    route : Route
        Its check-rail contacts (:func:`check_rail_pairs`).
    static_wheel_load : float
        N, the threshold's reference (:data:`CHECK_RAIL_LOADED`).
    wheelsets : int
        0: the single wheelset's columns (``Fy_right_r3_N``); n: the full vehicle's
        (``Fy_ws1_right_r3_N`` ... ``Fy_wsn_...``).
    where : str
        Why nothing is refined, for the warning (default: the setting is None).
    """

    def __init__(
        self,
        settings: PassageSettings,
        route: Any,
        static_wheel_load: float,
        wheelsets: int = 0,
        where: str = "",
    ):
        self.settings = settings
        self.pairs = check_rail_pairs(route)
        self.labels = tuple(f"ws{i + 1}_" for i in range(wheelsets)) if wheelsets else ("",)
        self.threshold = CHECK_RAIL_LOADED * float(static_wheel_load)
        #: s, the refined windows' step, or None (nothing refined)
        self.step = None if where else check_rail_step(settings)
        self.where = where or (
            "check_rail_time_step None, as with the CLI's --time-step given: the step is used "
            "everywhere; leave it at its default or give one <= the check rail's"
        )
        #: (x_from, x_to, step): m, m, s; the windows run at the finer step
        self.refined: list[tuple[float, float, float]] = []
        #: (x_from, x_to, peak): m, m, N; loaded at the run's step, not refined
        self.loaded: list[tuple[float, float, float]] = []
        #: the route's contact pairs with a check range (:meth:`predict`)
        self.check_pairs = tuple(p for p in getattr(route, "pairs", ()) if p.check)
        self.route = route
        #: (x_from, x_to, loaded): m, m; segments predicted to load the check rail
        self.predicted: list[tuple[float, float, bool]] = []
        #: (x_from, x_to, peak): m, m, N; loaded where not predicted: run again (safety net)
        self.reruns: list[tuple[float, float, float]] = []

    def window(self, columns: Mapping[str, np.ndarray]) -> tuple[float, float, float] | None:
        """:func:`check_rail_window` of a segment's columns (None: no check rail loaded).

        Parameters
        ----------
        columns : mapping
            The segment's columns.

        Returns
        -------
        (t_first, t_last, peak) or None
        """
        if not self.pairs:
            return None
        return check_rail_window(columns, self.pairs, self.threshold, self.labels)

    def predict(
        self, x0: float, x1: float, offsets: Sequence[float], lateral: Sequence[float]
    ) -> float | None:
        """Whether a segment may load a check rail, before it runs (module docstring).

        A wheelset counts if it is on a check-rail contact's x range over a positive length
        of the segment and its lateral displacement towards that check rail (the right
        wheel's check rail stands inside the right rail: +y; the left wheel's: -y) is at least
        :data:`CHECK_RAIL_HEADING` of the least clearance it meets there (the route's
        clearance opened by the flares, ``Route.check_clearance_at``).

        Parameters
        ----------
        x0, x1 : float
            m, the (front) wheelset's x at the segment's start and end.
        offsets : sequence of float
            m, every wheelset's offset from the front one (<= 0; ``(0.0,)`` for one).
        lateral : sequence of float
            m, every wheelset's lateral displacement y (positive to the left of the track's
            centreline) at the segment's start.

        Returns
        -------
        float or None
            s from the segment's start: where its fine stepping starts (the first counted
            wheelset reaching its check rail's start, 0 where one is on it already); None:
            not predicted, or nothing is refined (:attr:`step` None).
        """
        if self.step is None or not self.check_pairs:
            return None
        start = None
        for o, y in zip(offsets, lateral):
            for pair in self.check_pairs:
                c0, c1 = pair.check
                lo, hi = max(x0 + o, c0), min(x1 + o, c1)
                if not hi - lo > 1e-9:
                    continue
                points = [lo, hi] + [x for x in self._flare_ends(pair) if lo < x < hi]
                least = min(self.route.check_clearance_at(pair, x) for x in points)
                towards = float(y) if pair.wheel == "right" else -float(y)
                if towards >= CHECK_RAIL_HEADING * least:
                    t = (lo - (x0 + o)) / self.settings.v
                    start = t if start is None else min(start, t)
        return start

    def _flare_ends(self, pair: Any) -> tuple[float, float]:
        """m, where a check range's flares end (its clearance is least between them)."""
        length = float(getattr(self.route, "check_flare", (0.0, 0.0))[0])
        return pair.check[0] + length, pair.check[1] - length

    def run_predicted(
        self,
        duration: float,
        t_offset: float,
        x0: float,
        start: float,
        run_piece: Callable[..., Mapping[str, np.ndarray]],
    ) -> tuple[dict[str, np.ndarray], float]:
        """Run a predicted segment (:meth:`predict`): at the run's step to the grid point at
        or before ``start``, then at the fine step until :class:`CheckRailStop` ends it,
        the rest at the run's step; sampled at the segment's grid times, as :meth:`rerun`
        would give them. Where the rest loads a check rail after all, it runs again
        (:meth:`rerun`, noted in :attr:`reruns`).

        Parameters
        ----------
        duration : float
            s, the segment's.
        t_offset : float
            s, the run's time at the segment's start.
        x0 : float
            m, the (front) wheelset's x at the segment's start.
        start : float
            s from the segment's start: :meth:`predict`'s.
        run_piece : callable
            ``run_piece(t_from, t_length, x_from, settings, stop)``: as :meth:`rerun`'s, and
            ``stop`` (a :class:`CheckRailStop` or None) called before every step of the run
            with a function giving the check rails' largest force (N) at the step's start
            and one giving the system's state; the run ends after the step where it returns
            False, and where ``stop.state`` is not None the next piece starts from it (the
            state at ``stop.end``, this piece's duration to there).

        Returns
        -------
        columns : dict
            The segment's columns at its grid times.
        last : float
            s, the last piece's duration (the carry-over's time of the next segment).
        """
        settings, fine_step = self.settings, self.step
        if fine_step is None:
            raise ValueError("run_predicted: nothing is refined (check_rail_time_step None)")
        stop = CheckRailStop(duration, settings.time_step, fine_step, 0, self.threshold, self.pairs)
        n, h, v = stop.n, stop.h, settings.v
        a = min(n - 1, max(0, int(math.floor(start / h + 1e-9))))
        stop.first = a
        grid = t_offset + h * np.arange(n + 1)
        coarse = replace(settings, time_step=h, output_step=None)
        fine = replace(settings, time_step=h / stop.m, output_step=None)
        parts: list[dict[str, np.ndarray]] = []
        if a > 0:
            head = run_piece(0.0, a * h, x0, coarse, None)
            window = self.window(head)
            if window is None:
                parts.append(pick_rows(head, piece_times(grid, t_offset, 0, a, h, h)))
            else:  # loaded before the predicted start (the safety net): fine from the start
                self._note_rerun(window, head)
                a = stop.first = 0
        x_a = x0 + v * a * h
        piece = run_piece(a * h, (n - a) * h, x_a, fine, stop)
        b = stop.end if stop.state is not None else n
        self.predicted.append((x0, x0 + v * duration, stop.last is not None))
        tail: dict[str, np.ndarray] | None = None
        last = (n - a) * h
        while b < n:
            rest = run_piece(b * h, (n - b) * h, x0 + v * b * h, coarse, None)
            window = self.window(rest)
            if window is None:
                tail, last = pick_rows(rest, piece_times(grid, t_offset, b, n, h, h)), (n - b) * h
                break
            # loaded again after the fine piece's end (the safety net): the fine piece again
            # from its start to the end of that load, as rerun would run it (no restart)
            self._note_rerun(window, rest)
            b_last = refine_pieces(duration, settings.time_step, fine_step, window[1] - t_offset)
            b = max(b + 1, b_last[0][1])
            piece = run_piece(a * h, (b - a) * h, x_a, fine, None)
            last = (b - a) * h
        parts.append(pick_rows(piece, piece_times(grid, t_offset, a, b, h, fine.time_step)))
        if tail is not None:
            parts.append(tail)
        self.refined.append((x_a, x0 + v * b * h, fine.time_step))
        return join_segments(parts), last

    def rerun_unpredicted(
        self,
        columns: Mapping[str, np.ndarray],
        window: tuple[float, float, float],
        duration: float,
        t_offset: float,
        x0: float,
        run_piece: Callable[[float, float, float, PassageSettings], Mapping[str, np.ndarray]],
    ) -> tuple[dict[str, np.ndarray], float]:
        """:meth:`rerun` of a segment predicted not to load a check rail that did (the
        safety net; noted in :attr:`reruns`, ``summary["check_rail_rerun"]``).

        Parameters
        ----------
        columns, window, duration, t_offset, x0, run_piece
            As :meth:`rerun`'s.

        Returns
        -------
        columns : dict
        last : float
            As :meth:`rerun`'s.
        """
        self._note_rerun(window, columns)
        return self.rerun(columns, window, duration, t_offset, x0, run_piece)

    def _note_rerun(
        self, window: tuple[float, float, float], columns: Mapping[str, np.ndarray]
    ) -> None:
        t, x = np.asarray(columns["t_s"], float), np.asarray(columns["x_m"], float)
        x_from, x_to = np.interp(window[:2], t, x)
        self.reruns.append((float(x_from), float(x_to), float(window[2])))

    def rerun(
        self,
        columns: Mapping[str, np.ndarray],
        window: tuple[float, float, float],
        duration: float,
        t_offset: float,
        x0: float,
        run_piece: Callable[[float, float, float, PassageSettings], Mapping[str, np.ndarray]],
    ) -> tuple[dict[str, np.ndarray], float]:
        """Run a segment again in pieces, its loaded window at the finer step.

        The pieces are :func:`refine_pieces`'s; each runs from where the one before ended
        (the first from the segment's start), every step sampled, and keeps the rows at the
        first run's output times (:func:`piece_times`, :func:`pick_rows`). Windows run
        finer than the segment's step are noted for :meth:`record`.

        Parameters
        ----------
        columns : mapping
            The segment's columns of its first run (``t_s``: the output times to keep).
        window : (t_first, t_last, peak)
            :meth:`window`'s.
        duration : float
            s, the segment's.
        t_offset : float
            s, the run's time at the segment's start.
        x0 : float
            m, the (front) wheelset's x at the segment's start.
        run_piece : callable
            ``run_piece(t_from, t_length, x_from, settings)``: builds the track's system at
            ``x_from``, carries the state of the piece before over and runs ``t_length``
            seconds with ``settings`` (the piece's ``time_step``, every step sampled) from
            the segment's time ``t_from``; returns the piece's columns.

        Returns
        -------
        columns : dict
            The segment's columns, at the first run's output times.
        last : float
            s, the last piece's duration (the carry-over's time of the next segment).
        """
        settings, fine_step = self.settings, self.step
        if fine_step is None:
            raise ValueError("rerun: nothing is refined (check_rail_time_step None)")
        pieces = refine_pieces(duration, settings.time_step, fine_step, window[1] - t_offset)
        h = duration / pieces[-1][1]
        v = settings.v
        parts = []
        for a, b, step in pieces:
            x_p = x0 + v * a * h
            fine = replace(settings, time_step=step, output_step=None)  # every step sampled
            piece = run_piece(a * h, (b - a) * h, x_p, fine)
            parts.append(pick_rows(piece, piece_times(columns["t_s"], t_offset, a, b, h, step)))
            if step < h:
                self.refined.append((x_p, x0 + v * b * h, step))
        a, b, _ = pieces[-1]
        return join_segments(parts), (b - a) * h

    def unrefined(
        self, window: tuple[float, float, float], columns: Mapping[str, np.ndarray]
    ) -> None:
        """Note a window loaded at the run's step and not refined.

        Parameters
        ----------
        window : (t_first, t_last, peak)
            :meth:`window`'s.
        columns : mapping
            The segment's columns (``t_s``, ``x_m``).
        """
        t, x = np.asarray(columns["t_s"]), np.asarray(columns["x_m"])
        x_from, x_to = np.interp(window[:2], t, x)
        self.loaded.append((float(x_from), float(x_to), float(window[2])))

    def record(self, summary: dict, stacklevel: int = 2) -> None:
        """Put the refined windows into ``summary``; warn where a loaded check rail ran at too
        coarse a step.

        Keys: ``check_rail_time_step_s`` (the setting, None: off), ``check_rail_refined``
        (per window, merged where they touch: ``x_m`` [from, to] of the front wheelset and
        ``time_step_s``), ``check_rail_predicted`` (per segment run at the fine step
        directly, :meth:`run_predicted`: ``x_m`` [from, to] and ``loaded``, whether its check
        rail carried load), ``check_rail_rerun`` (per window loaded where not predicted and
        run again, the safety net: ``x_m`` [from, to] and ``peak_N``; empty: the prediction
        covered every load) and, where the check rail carried load at a step coarser than
        the setting (or its default where it is None), ``check_rail_step_warning``, also issued
        as a :class:`CheckRailStepWarning`.

        Parameters
        ----------
        summary : dict
            The passage's summary (changed in place).
        stacklevel : int
            Of the warning, counted from the caller of this method.
        """
        from exudyn_turnout.passage.settings import DEFAULT_SETTINGS

        summary["check_rail_time_step_s"] = self.settings.check_rail_time_step
        merged: list[list[float]] = []
        for x_from, x_to, step in self.refined:
            # touching windows of about the same step (each segment's own grid: h / m)
            if (
                merged
                and abs(merged[-1][1] - x_from) < 1e-9
                and abs(merged[-1][2] / step - 1) < 0.01
            ):
                merged[-1][1:] = [x_to, max(merged[-1][2], step)]
            else:
                merged.append([x_from, x_to, step])
        summary["check_rail_refined"] = [
            {"x_m": [round(a, 4), round(b, 4)], "time_step_s": float(h)} for a, b, h in merged
        ]
        summary["check_rail_predicted"] = [
            {"x_m": [round(a, 4), round(b, 4)], "loaded": loaded} for a, b, loaded in self.predicted
        ]
        summary["check_rail_rerun"] = [
            {"x_m": [round(a, 4), round(b, 4)], "peak_N": round(p, 1)} for a, b, p in self.reruns
        ]
        limit = self.settings.check_rail_time_step or DEFAULT_SETTINGS.check_rail_time_step
        if not self.loaded or limit is None or not self.settings.time_step > limit:
            return
        peak = max(p for *_, p in self.loaded)
        span = (min(a for a, *_ in self.loaded), max(b for _, b, _ in self.loaded))
        message = check_rail_warning(self.where, peak, span, self.settings.time_step, limit)
        summary["check_rail_step_warning"] = message
        warnings.warn(message, CheckRailStepWarning, stacklevel=stacklevel + 1)


def refined_line(summary: Mapping[str, Any]) -> str | None:
    """One console line on the windows run at the check rail's finer step; None if none.

    Parameters
    ----------
    summary : mapping
        A passage summary with ``check_rail_refined`` (:meth:`CheckRailSteps.record`).

    Returns
    -------
    str or None
        E.g. ``check rail loaded: x = 45.06-47.48 m stepped at 2.5e-05 s (run: 0.0001 s)``.
    """
    windows = summary.get("check_rail_refined") or []
    if not windows:
        return None
    parts = [
        f"x = {w['x_m'][0]:.2f}-{w['x_m'][1]:.2f} m at {w['time_step_s']:.3g} s" for w in windows
    ]
    step = summary.get("settings", {}).get("time_step")
    run = f" (the run's step {step:g} s)" if isinstance(step, float) else ""
    return f"check rail loaded: stepped finer over {', '.join(parts)}{run}"
