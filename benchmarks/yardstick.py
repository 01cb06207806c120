"""A shared yardstick for the benchmarks: costs that carry over between machines.

A wall time measured on a shared or unknown machine says little by itself: the same code
measured 2.1x apart on one machine, quiet and loaded (issue 24). Every benchmark here runs
a fixed workload, the *yardstick*, interleaved with its cases (yardstick, case, yardstick,
case, ..., yardstick) and reports each case in seconds and in yardstick units: the case's
time divided by the mean of the two yardstick runs around it, median over the repeats.
Both see the same load at nearly the same moment, so the ratio moves far less than either
time.

The yardstick does not depend on this package (it stays the same when the package
changes) and mixes what a passage spends its time on (issue 24's profile of a step):
scalar Python (an explicit integration of a Duffing oscillator), many small NumPy calls,
and small dense linear algebra (LU solves of a 100 x 100 system, the size of the full
vehicle's matrices). About 0.3 s on a 2020s x86 core; one BLAS thread is used (the
matrices are too small for more).

Use from a benchmark script in this folder::

    from yardstick import Yardstick, machine_line

    stick = Yardstick()
    timing = stick.measure(lambda: simulate_passage(turnout, settings), repeats=3)
    print(timing.seconds, timing.units, machine_line())
"""

from __future__ import annotations

import math
import os
import platform
import statistics
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from datetime import UTC, datetime
from importlib import metadata

import numpy as np
import scipy.linalg

__all__ = [
    "workload",
    "Timing",
    "Yardstick",
    "machine",
    "machine_line",
    "parallel_speedup",
    "parallel_cost",
]

#: Sizes of the three parts, fixed: changing them changes the unit (never do it silently).
_DUFFING_STEPS = 60_000
_SMALL_NUMPY_CALLS = 6_000
_LU_SOLVES = 150
_LU_SIZE = 100


def workload() -> float:
    """The yardstick's fixed work (about 0.3 s on one core); returns a checksum.

    Returns
    -------
    float
        A number computed from all three parts (so that none is optimised away); the same
        on every run.
    """
    # 1. scalar Python: explicit Euler of x'' + 0.1 x' + x + x^3 = cos(t), h = 1e-3 s
    x, v, t, h = 0.1, 0.0, 0.0, 1e-3
    for _ in range(_DUFFING_STEPS):
        a = math.cos(t) - 0.1 * v - x - x * x * x
        x += h * v
        v += h * a
        t += h
    # 2. many small NumPy calls (a contact step's kind of array work)
    rng = np.random.default_rng(20240601)
    p = rng.standard_normal(8)
    q = rng.standard_normal(8)
    acc = 0.0
    for _ in range(_SMALL_NUMPY_CALLS):
        d = np.clip(p - q, -1.0, 1.0)
        acc += float(np.dot(d, d)) + float(np.max(np.abs(d)))
        p = 0.5 * (p + np.roll(q, 1))
    # 3. small dense linear algebra
    A = rng.standard_normal((_LU_SIZE, _LU_SIZE)) + _LU_SIZE * np.eye(_LU_SIZE)
    b = rng.standard_normal(_LU_SIZE)
    for _ in range(_LU_SOLVES):
        lu = scipy.linalg.lu_factor(A)
        b = scipy.linalg.lu_solve(lu, b)
        b /= np.linalg.norm(b)
    return x + v + acc + float(b.sum())


@dataclass(frozen=True)
class Timing:
    """One case measured against the yardstick.

    Parameters
    ----------
    seconds : float
        s, median wall time of the case over its repeats.
    cpu_seconds : float
        s, median CPU time over the case's repeats, of this process and of the child
        processes it waited for (a command run, a process pool shut down); on a loaded
        machine the closest to what the case costs on an idle one.
    units : float
        Median over the repeats of (case wall time / mean wall time of the yardstick runs
        just before and after it).
    yardstick_seconds : float
        s, median wall time of the yardstick runs of this measurement.
    repeats : int
        Runs of the case (after an untimed warm-up, if asked).
    samples : tuple of float
        s, every wall time of the case.
    result : object
        What the case returned on its last run (not compared).
    """

    seconds: float  #: s
    cpu_seconds: float  #: s
    units: float  #: -
    yardstick_seconds: float  #: s
    repeats: int  #: -
    samples: tuple[float, ...] = ()  #: s
    result: object = field(default=None, compare=False, repr=False)


def _cpu() -> float:
    """s, CPU time of this process and of its child processes that have ended."""
    t = os.times()
    return time.process_time() + t.children_user + t.children_system


def _timed(function: Callable[[], object]) -> tuple[float, float, object]:
    wall, cpu = time.perf_counter(), _cpu()
    out = function()
    return time.perf_counter() - wall, _cpu() - cpu, out


class Yardstick:
    """Runs cases interleaved with the yardstick workload and keeps every yardstick time.

    Parameters
    ----------
    workload_function : callable, optional
        The yardstick (default :func:`workload`; tests pass a cheap one).
    """

    def __init__(self, workload_function: Callable[[], object] = workload):
        self._workload = workload_function
        self.times: list[float] = []  #: s, wall time of every yardstick run of this object
        self.cpu_times: list[float] = []  #: s, CPU time of every yardstick run

    def units(self, seconds: float) -> float:
        """``seconds`` in yardstick units, against the last two yardstick runs.

        For a time measured between two calls of :meth:`run`.

        Parameters
        ----------
        seconds : float
            s.

        Returns
        -------
        float
            -.
        """
        last = self.times[-2:] or [math.nan]
        return seconds / (sum(last) / len(last))

    def run(self) -> float:
        """Run the yardstick once.

        Returns
        -------
        float
            s, its wall time (also appended to :attr:`times`).
        """
        wall, cpu, _ = _timed(self._workload)
        self.times.append(wall)
        self.cpu_times.append(cpu)
        return wall

    def measure(
        self,
        function: Callable[[], object],
        repeats: int = 3,
        warm_up: bool = True,
        inner: Callable[[object], float] | None = None,
    ) -> Timing:
        """Time ``function`` ``repeats`` times, the yardstick before, between and after.

        Parameters
        ----------
        function : callable()
            The case.
        repeats : int
            Timed runs (>= 1).
        warm_up : bool
            Run the case once untimed first (caches, compiled kernels).
        inner : callable(result) -> float, optional
            s, the time to report taken from what the case returns (e.g. the solver's
            time without the model's build); default: the wall time of the whole call.

        Returns
        -------
        Timing
        """
        if repeats < 1:
            raise ValueError(f"repeats must be >= 1, got {repeats}")
        if warm_up:
            function()
        sticks = [self.run()]
        walls, cpus, ratios = [], [], []
        out = None
        for _ in range(repeats):
            wall, cpu, out = _timed(function)
            if inner is not None:
                wall = float(inner(out))
            sticks.append(self.run())
            walls.append(wall)
            cpus.append(cpu)
            ratios.append(wall / (0.5 * (sticks[-2] + sticks[-1])))
        return Timing(
            seconds=statistics.median(walls),
            cpu_seconds=statistics.median(cpus),
            units=statistics.median(ratios),
            yardstick_seconds=statistics.median(sticks),
            repeats=repeats,
            samples=tuple(walls),
            result=out,
        )

    @property
    def median(self) -> float:
        """s, median wall time of every yardstick run so far (NaN before the first)."""
        return statistics.median(self.times) if self.times else math.nan

    @property
    def cpu_median(self) -> float:
        """s, median CPU time of every yardstick run so far (NaN before the first)."""
        return statistics.median(self.cpu_times) if self.cpu_times else math.nan


def _yardstick_in_child(_: int) -> float:
    wall, _, _ = _timed(workload)
    return wall


def _yardstick_cpu_in_child(_: int) -> tuple[float, float]:
    wall, cpu, _ = _timed(workload)
    return wall, cpu


def _wall_and_cpu(pool, processes: int) -> tuple[float, float]:
    """s, wall time of ``processes`` yardsticks run at once in ``pool``; their mean CPU time."""
    start = time.perf_counter()
    runs = list(pool.map(_yardstick_cpu_in_child, range(processes)))
    return time.perf_counter() - start, statistics.mean(cpu for _, cpu in runs)


def parallel_cost(processes: int = 2, rounds: int = 2) -> tuple[float, float]:
    """What the machine gives ``processes`` processes now, in wall time and in CPU time.

    As :func:`parallel_speedup` (the throughput gain), and also what one yardstick costs in
    CPU time when ``processes`` of them run at once, over its CPU time alone: 1.0 on idle
    cores; more where the processes share a core's caches or hyperthreads, or a virtual
    machine's host is busy. A parallel run's extra CPU time is the machine's up to this
    ratio.

    Parameters
    ----------
    processes : int
    rounds : int

    Returns
    -------
    tuple of float
        (throughput of ``processes`` concurrent yardsticks over one, -; CPU time of a
        yardstick among ``processes`` over alone, -), medians over the rounds.
    """
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    gains, ratios = [], []
    with ProcessPoolExecutor(processes, mp_context=multiprocessing.get_context("spawn")) as pool:
        list(pool.map(_yardstick_in_child, range(processes)))  # start and warm the workers
        for _ in range(rounds):
            alone_wall, alone_cpu = _wall_and_cpu(pool, 1)
            together_wall, together_cpu = _wall_and_cpu(pool, processes)
            gains.append(processes * alone_wall / together_wall)
            ratios.append(together_cpu / alone_cpu)
    return statistics.median(gains), statistics.median(ratios)


def parallel_speedup(processes: int = 2, rounds: int = 2) -> float:
    """What the machine gives ``processes`` processes now: the yardstick's own speed-up.

    Runs ``processes`` yardsticks at once in a process pool (spawned) and one alone,
    ``rounds`` times; returns (time of one alone) / (mean time of one among ``processes``
    running together), median over the rounds, times ``processes``... i.e. the throughput
    gain: 2.0 on two idle cores, about 1.0 when another job holds the second core.

    Parameters
    ----------
    processes : int
    rounds : int

    Returns
    -------
    float
        -, throughput of ``processes`` concurrent yardsticks over one.
    """
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    gains = []
    with ProcessPoolExecutor(processes, mp_context=multiprocessing.get_context("spawn")) as pool:
        list(pool.map(_yardstick_in_child, range(processes)))  # start and warm the workers
        for _ in range(rounds):
            alone = list(pool.map(_yardstick_in_child, [0]))[0]
            start = time.perf_counter()
            list(pool.map(_yardstick_in_child, range(processes)))
            together = time.perf_counter() - start
            gains.append(processes * alone / together)
    return statistics.median(gains)


def _cpu_model() -> str:
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as fh:
            for line in fh:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine() or "unknown CPU"


def _version(name: str) -> str:
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "not installed"


def machine() -> dict[str, object]:
    """The machine and software a measurement ran on.

    Returns
    -------
    dict
        ``cpu``, ``cores``, ``load_average`` (1, 5, 15 min), ``system``, ``python``,
        ``numpy``, ``scipy``, ``exudyn``, ``numba``, ``date`` (UTC, ISO 8601).
    """
    try:
        load = tuple(round(v, 2) for v in os.getloadavg())
    except OSError:
        load = (math.nan, math.nan, math.nan)
    return {
        "cpu": _cpu_model(),
        "cores": os.cpu_count() or 1,
        "load_average": load,
        "system": f"{platform.system()} {platform.release()}",
        "python": platform.python_version(),
        "numpy": np.__version__,
        "scipy": _version("scipy"),
        "exudyn": _version("exudyn"),
        "numba": _version("numba"),
        "date": datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC"),
    }


def machine_line(info: dict[str, object] | None = None) -> str:
    """One line describing the machine (:func:`machine`).

    Parameters
    ----------
    info : dict, optional
        From :func:`machine` (default: now).

    Returns
    -------
    str
    """
    m = machine() if info is None else info
    load = ", ".join(f"{v:.2f}" for v in m["load_average"])  # type: ignore[attr-defined]
    return (
        f"{m['cpu']}, {m['cores']} cores, load average {load} (1/5/15 min), {m['system']}; "
        f"Python {m['python']}, numpy {m['numpy']}, scipy {m['scipy']}, exudyn {m['exudyn']}, "
        f"numba {m['numba']}; {m['date']}"
    )


if __name__ == "__main__":
    stick = Yardstick()
    for _ in range(5):
        stick.run()
    runs = ", ".join(f"{t:.3f}" for t in stick.times)
    print(f"yardstick: median {stick.median:.3f} s of 5 runs ({runs})")
    print(machine_line())
