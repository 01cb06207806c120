"""Time-step convergence of the full vehicle's passage: the peaks against the step h.

Run: ``python validation/vehicle_step_convergence.py [--steps H ...] [--cases NAME ...]
[--out PATH]``; writes ``validation/vehicle_step_convergence.md`` and prints it.

The full Manchester vehicle (the default of :func:`~exudyn_turnout.passage.run.simulate_passage`,
four wheelsets each on its own co-running track,
:mod:`exudyn_turnout.passage.corunning_track.vehicle`), profile contact, in the cases of
:data:`CASES` (through route at 100 km/h, front wheelset -5..60 m; diverging route at its
permitted 80 km/h over the crossing and its check rail, 20..55 m; 2 and 3 layers), run at
every time step of :data:`STEPS` in one process, one after the other. Peaks, in the
summary's own definitions (:func:`~exudyn_turnout.passage.summary.vehicle_summary`: Fz the
maximum, Fy the largest magnitude with its sign, in the turnout file's switch and crossing
regions): every wheel of the front wheelset; the whole vehicle's (the largest of its
wheelsets' per-wheel peaks); the check rail's lateral force; the wheel unloading Delta Q/Q0
over the run. Each is given against the default step (1e-4 s) and the reference
(:data:`REFERENCE`), with the order of convergence from the three finest steps, the CPU time
and Newton iterations per step of each run. Steps above the package's limit (10 steps per
period of the wheel's contact resonance on the lightest rail) are run with the limit lifted
(``--keep-limit``: not run) and marked. About 8 min of CPU in all (one process).
"""

from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import time
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

#: s, the time steps run; 1.25e-5 and 6.25e-6 s check the reference (and give the observed
#: order from the three finest, 6.25e-6, 1.25e-5, 2.5e-5 s). The package refuses steps above
#: 10 per period of the wheel on the lightest rail under any wheelset (1.10e-4 s with 2
#: layers, 1.17e-4 s with 3 on every case here): those run with the limit lifted, marked.
STEPS = (6.25e-6, 1.25e-5, 2.5e-5, 5e-5, 1e-4, 1.1e-4, 1.25e-4, 1.5e-4, 1.8e-4, 2e-4)
#: s, the reference step and the package's default step
REFERENCE = 2.5e-5
DEFAULT = 1e-4
#: %, the thresholds the page's conclusion checks
THRESHOLDS = (0.1, 0.5)


@dataclass(frozen=True)
class Case:
    """One passage of the study.

    Parameters
    ----------
    route : str
        Route name of the turnout file.
    speed_kmh : float
        km/h.
    layers : int
        Co-running track layers (2 or 3).
    x_start, x_end : float
        m, the front wheelset's x range.
    """

    route: str
    speed_kmh: float  #: km/h
    layers: int  #: -
    x_start: float  #: m
    x_end: float  #: m


#: The study's cases by name.
CASES = {
    "through-2L": Case("through", 100.0, 2, -5.0, 60.0),
    "through-3L": Case("through", 100.0, 3, -5.0, 60.0),
    "diverging-2L": Case("diverging", 80.0, 2, 20.0, 55.0),
    "diverging-3L": Case("diverging", 80.0, 3, 20.0, 55.0),
}


@dataclass(frozen=True)
class Run:
    """What one passage at one step gave.

    Parameters
    ----------
    peaks : dict
        Peak name -> value (N for forces, - for Delta Q/Q0); empty if the run failed.
    cpu : float
        s, CPU time of the whole ``simulate_passage`` call.
    steps : int
        Time steps of the run (all segments).
    newton : float
        Newton iterations per step.
    error : str
        Why the run failed ("" if it did not).
    limit : float
        s, the package's time-step limit for the case (10 steps per period of the wheel on
        the lightest rail under any wheelset).
    beyond_limit : bool
        h is above ``limit``: run with the limit lifted.
    where : dict
        m, x of some peaks (:func:`summary_positions`).
    ringing : float
        Hz, :func:`ringing_frequency` of the check rail's lateral force (NaN: none).
    """

    peaks: dict[str, float]  #: N or -
    cpu: float  #: s
    steps: int  #: -
    newton: float  #: -
    error: str = ""
    limit: float = math.nan  #: s
    beyond_limit: bool = False
    where: dict[str, float] = field(default_factory=dict)  #: m
    ringing: float = math.nan  #: Hz


def summary_peaks(summary: Mapping[str, object]) -> dict[str, float]:
    """The study's peaks from a full vehicle's passage summary.

    Parameters
    ----------
    summary : mapping
        :func:`~exudyn_turnout.passage.summary.vehicle_summary` of the run.

    Returns
    -------
    dict
        ``ws1 <Fz|Fy> <wheel> <region>`` (front wheelset, N), ``vehicle <Fz|Fy> <region>``
        (largest magnitude over every wheelset's per-wheel peaks, N), ``check rail Fy``
        (N, where the route has one), ``ws1 dQ/Q0`` and ``vehicle dQ/Q0`` (largest wheel
        unloading over the run, -). NaN where the run does not reach the region.
    """

    def number(key: str) -> float:
        value = summary.get(key)
        return float(value) if isinstance(value, (int, float)) else math.nan

    wheelsets = int(number("wheelsets")) if math.isfinite(number("wheelsets")) else 1
    out: dict[str, float] = {}
    for region in ("switch", "crossing"):
        for q in ("Fz", "Fy"):
            for wheel in ("right", "left"):
                out[f"ws1 {q} {wheel} {region}"] = number(f"peak_{q}_{region}_ws1_{wheel}_N")
            values = [
                number(f"peak_{q}_{region}_ws{k}_{wheel}_N")
                for k in range(1, wheelsets + 1)
                for wheel in ("right", "left")
            ]
            finite = [v for v in values if math.isfinite(v)]
            out[f"vehicle {q} {region}"] = max(finite, key=abs) if finite else math.nan
    out["check rail Fy"] = number("peak_Fy_check_rail_N")
    for who, labels in (("ws1", [1]), ("vehicle", range(1, wheelsets + 1))):
        values = [
            number(f"dQ_Q0_max_run_ws{k}_{wheel}") for k in labels for wheel in ("right", "left")
        ]
        finite = [v for v in values if math.isfinite(v)]
        out[f"{who} dQ/Q0"] = max(finite) if finite else math.nan
    return out


def summary_positions(summary: Mapping[str, object]) -> dict[str, float]:
    """Where (x, m) the front wheelset's largest crossing forces and check-rail force are.

    Parameters
    ----------
    summary : mapping
        :func:`~exudyn_turnout.passage.summary.vehicle_summary` of the run.

    Returns
    -------
    dict
        ``x of ws1 max Fz crossing``, ``x of ws1 max abs Fy crossing``, ``x of check rail Fy``
        (m; NaN where absent).
    """
    keys = {
        "x of ws1 max Fz crossing": "max_Fz_crossing_x_m",
        "x of ws1 max abs Fy crossing": "max_Fy_crossing_x_m",
        "x of check rail Fy": "peak_Fy_check_rail_x_m",
    }
    out = {}
    for name, key in keys.items():
        value = summary.get(key)
        out[name] = float(value) if isinstance(value, (int, float)) else math.nan
    return out


def ringing_frequency(
    x: Sequence[float], force: Sequence[float], speed: float, x_peak: float
) -> float:
    """Frequency (Hz) of the oscillation of a force about its peak: v / spacing of its maxima.

    The local maxima of the force (its peak's sign made positive) from 0.05 m before to
    0.1 m after ``x_peak`` that exceed 10 % of the peak; their mean spacing in x over the
    speed.

    Parameters
    ----------
    x : sequence of float
        m, positions of the samples (increasing).
    force : sequence of float
        N.
    speed : float
        m/s.
    x_peak : float
        m, where the peak is.

    Returns
    -------
    float
        Hz; NaN with fewer than two maxima.
    """
    import numpy as np

    xs, f = np.asarray(x, dtype=float), np.asarray(force, dtype=float)
    sel = np.flatnonzero((xs >= x_peak - 0.05) & (xs <= x_peak + 0.1))
    if len(sel) < 3:
        return math.nan
    g = f[sel] * np.sign(f[sel][np.argmax(np.abs(f[sel]))])  # the peak's sign made positive
    top = g.max()
    inner = np.arange(1, len(g) - 1)
    maxima = inner[(g[inner] > g[inner - 1]) & (g[inner] >= g[inner + 1]) & (g[inner] > 0.1 * top)]
    if len(maxima) < 2:
        return math.nan
    return float(speed / np.mean(np.diff(xs[sel][maxima])))


def percent(value: float, reference: float) -> float:
    """Change of ``value`` against ``reference`` in percent (NaN if reference is 0 or NaN).

    Parameters
    ----------
    value, reference : float

    Returns
    -------
    float
        %, 100 (value / reference - 1).
    """
    if not (math.isfinite(value) and math.isfinite(reference)) or reference == 0.0:
        return math.nan
    return 100.0 * (value / reference - 1.0)


def order(steps: Sequence[float], values: Sequence[float]) -> float:
    """Observed order of convergence from three steps with a constant ratio.

    With P(h) = P0 + C h^p and h3 / h2 = h2 / h1 = r:
    p = log(|P3 - P2| / |P2 - P1|) / log(r).

    Parameters
    ----------
    steps : sequence of 3 floats
        s, h1 < h2 < h3 with h3 / h2 = h2 / h1.
    values : sequence of 3 floats
        P(h1), P(h2), P(h3).

    Returns
    -------
    float
        p; NaN where the differences are zero or change sign (not in the asymptotic range)
        or a value is NaN.

    Raises
    ------
    ValueError
        The steps are not increasing with a constant ratio.
    """
    h1, h2, h3 = steps
    if not (0.0 < h1 < h2 < h3) or not math.isclose(h3 / h2, h2 / h1, rel_tol=1e-9):
        raise ValueError(f"steps {steps} are not increasing with a constant ratio")
    p1, p2, p3 = values
    d21, d32 = p2 - p1, p3 - p2
    if not (math.isfinite(d21) and math.isfinite(d32)) or d21 * d32 <= 0.0:
        return math.nan
    return math.log(abs(d32) / abs(d21)) / math.log(h2 / h1)


def step_label(h: float) -> str:
    """Column label of a step, e.g. ``1e-04``."""
    return f"{h:.3g}"


def _cell(value: float, digits: int = 3, sign: bool = False) -> str:
    if not math.isfinite(value):
        return "-"
    return f"{value:+.{digits}f}" if sign else f"{value:.{digits}f}"


def _shown(peak: str, value: float) -> float:
    """Value as tabulated: forces in kN, ratios as they are."""
    return value if "dQ/Q0" in peak else value / 1e3


def kept_peaks(runs: Mapping[float, Run]) -> tuple[list[str], list[str]]:
    """Peaks with a non-zero value at some step, and those zero or NaN at every step.

    Parameters
    ----------
    runs : mapping
        Step (s) -> :class:`Run`.

    Returns
    -------
    kept, dropped : list of str
    """
    names: list[str] = []
    for run in runs.values():
        names += [n for n in run.peaks if n not in names]
    kept = [
        n
        for n in names
        if any(math.isfinite(r.peaks.get(n, math.nan)) and r.peaks[n] != 0.0 for r in runs.values())
    ]
    return kept, [n for n in names if n not in kept]


def three_finest(steps: Sequence[float], finest: float) -> tuple[float, float, float] | None:
    """The steps finest, 2 finest, 4 finest if all are in ``steps``, else None.

    Parameters
    ----------
    steps : sequence of float
        s, the steps that ran.
    finest : float
        s.

    Returns
    -------
    tuple of 3 floats or None
    """
    want = (finest, 2.0 * finest, 4.0 * finest)
    found = [next((h for h in steps if math.isclose(h, w, rel_tol=1e-9)), None) for w in want]
    return None if any(h is None for h in found) else tuple(found)  # type: ignore[return-value]


def case_tables(
    runs: Mapping[float, Run], reference: float = REFERENCE, default: float = DEFAULT
) -> tuple[str, dict[float, dict[str, float]], dict[float, dict[str, float]]]:
    """Markdown tables of one case, and the changes of every peak against default and reference.

    Parameters
    ----------
    runs : mapping
        Step (s) -> :class:`Run`; must hold ``reference`` and ``default`` (successful).
    reference, default : float
        s.

    Returns
    -------
    text : str
        The values table (kN, CPU s, Newton iterations per step) and the changes table
        (% against the default and against the reference, observed orders).
    vs_default, vs_reference : dict
        Step -> peak -> % (successful runs only).
    """
    ok = sorted(h for h, r in runs.items() if not r.error)
    kept, dropped = kept_peaks({h: runs[h] for h in ok})
    ref, dflt = runs[reference].peaks, runs[default].peaks
    vs_default = {h: {n: percent(runs[h].peaks[n], dflt[n]) for n in kept} for h in ok}
    vs_reference = {h: {n: percent(runs[h].peaks[n], ref[n]) for n in kept} for h in ok}
    mark = {h: "*" if runs[h].beyond_limit else "" for h in ok}
    head = "| peak | " + " | ".join(f"h = {step_label(h)} s{mark[h]}" for h in ok) + " |"
    lines = [
        "Peaks (kN; Delta Q/Q0 in units of 1):",
        "",
        head,
        "|---|" + "---|" * len(ok),
    ]
    for n in kept:
        cells = [_cell(_shown(n, runs[h].peaks[n])) for h in ok]
        lines.append(f"| {n} | " + " | ".join(cells) + " |")
    for n in runs[reference].where:
        if n == "x of check rail Fy" and "check rail Fy" not in kept:
            continue
        if any(math.isfinite(runs[h].where.get(n, math.nan)) for h in ok):
            cells = [_cell(runs[h].where.get(n, math.nan), 4) for h in ok]
            lines.append(f"| {n} (m) | " + " | ".join(cells) + " |")
    if any(math.isfinite(runs[h].ringing) for h in ok):
        cells = [_cell(runs[h].ringing, 0) for h in ok]
        lines.append("| check rail Fy ringing (Hz) | " + " | ".join(cells) + " |")
    lines.append("| CPU s | " + " | ".join(f"{runs[h].cpu:.1f}" for h in ok) + " |")
    lines.append("| steps | " + " | ".join(f"{runs[h].steps}" for h in ok) + " |")
    lines.append("| Newton it./step | " + " | ".join(f"{runs[h].newton:.3f}" for h in ok) + " |")
    orders = [t for t in (three_finest(ok, ok[0]), three_finest(ok, reference)) if t]
    orders = list(dict.fromkeys(orders))
    lines += [
        "",
        "Change of each peak (%) against the default step (1e-4 s) | against the reference "
        f"({step_label(reference)} s); p: observed order from the steps named:",
        "",
        "| peak | "
        + " | ".join(f"{step_label(h)}{mark[h]}" for h in ok)
        + "".join(f" | p ({', '.join(step_label(h) for h in t)})" for t in orders)
        + " |",
        "|---|" + "---|" * (len(ok) + len(orders)),
    ]
    for n in kept:
        cells = [
            f"{_cell(vs_default[h][n], 3, True)} \\| {_cell(vs_reference[h][n], 3, True)}"
            for h in ok
        ]
        ps = [_cell(order(t, [runs[h].peaks[n] for h in t]), 2) for t in orders]
        lines.append(f"| {n} | " + " | ".join(cells + ps) + " |")
    failed = [h for h in sorted(runs) if runs[h].error]
    ringing = runs[reference].ringing
    if math.isfinite(ringing):
        lines += [
            "",
            f"The check rail's lateral force rings at {ringing:.0f} Hz about its peak in the "
            f"reference run (spacing of its maxima): {1.0 / (ringing * default):.1f} steps per "
            "period at the default step.",
        ]
    limit = next((r.limit for r in runs.values() if math.isfinite(r.limit)), math.nan)
    if any(mark.values()):
        lines += [
            "",
            f"\\* above the package's step limit for this case ({limit:.4g} s: 10 steps per "
            f"period of the wheel's contact resonance, {0.1 / limit:.0f} Hz, on the lightest "
            "rail under any wheelset), which refuses it; run here with the limit lifted.",
        ]
    if dropped:
        lines += ["", "Zero or not reached at every step (left out): " + ", ".join(dropped) + "."]
    for h in failed:
        lines += ["", f"h = {step_label(h)} s not run: {runs[h].error}"]
    return "\n".join(lines), vs_default, vs_reference


def largest(changes: Mapping[str, Mapping[float, Mapping[str, float]]], h: float):
    """Largest |change| (%) at step h over every case's peaks, with its case and peak.

    Parameters
    ----------
    changes : mapping
        Case -> step -> peak -> %.
    h : float
        s.

    Returns
    -------
    tuple
        (|change| %, case, peak); (NaN, "", "") if no case ran h.
    """
    best = (math.nan, "", "")
    for case, by_step in changes.items():
        for peak, value in by_step.get(h, {}).items():
            if math.isfinite(value) and not (abs(value) <= best[0]):
                best = (abs(value), case, peak)
    return best


def overview(
    vs_default: Mapping[str, Mapping[float, Mapping[str, float]]],
    vs_reference: Mapping[str, Mapping[float, Mapping[str, float]]],
    steps: Sequence[float],
    marked: Sequence[float] = (),
    cpu: Mapping[float, float] | None = None,
) -> tuple[str, dict[float, float]]:
    """The largest changes over all cases per step, as a Markdown table.

    Parameters
    ----------
    vs_default, vs_reference : mapping
        Case -> step -> peak -> %, of :func:`case_tables`.
    steps : sequence of float
        s, the steps to list.
    marked : sequence of float
        s, steps shown with a ``*`` (above the package's limit in some case).
    cpu : mapping, optional
        Step -> CPU time of all cases in units of the default step's (a column if given).

    Returns
    -------
    text : str
    worst : dict
        Step -> largest |change| against the default (%).
    """
    lines = [
        "| h (s) | max \\|change\\| vs 1e-4 s (%) | where | max \\|change\\| vs reference (%) "
        "| where |" + (" CPU / CPU at 1e-4 s |" if cpu else ""),
        "|---|---|---|---|---|" + ("---|" if cpu else ""),
    ]
    worst: dict[float, float] = {}
    for h in steps:
        d, case_d, peak_d = largest(vs_default, h)
        r, case_r, peak_r = largest(vs_reference, h)
        worst[h] = d
        star = "*" if h in marked else ""
        lines.append(
            f"| {step_label(h)}{star} | {_cell(d)} | {case_d}: {peak_d} | {_cell(r)} | "
            f"{case_r}: {peak_r} |" + (f" {_cell(cpu.get(h, math.nan), 2)} |" if cpu else "")
        )
    return "\n".join(lines), worst


def within(worst: Mapping[float, float], limit: float, default: float = DEFAULT) -> float:
    """Largest step above the default whose peaks all stay within ``limit`` % of the default's.

    Every step between the default and it must stay within too (a step is not accepted
    past one that failed the limit or did not run).

    Parameters
    ----------
    worst : mapping
        Step -> largest |change| against the default (%), NaN where the step did not run.
    limit : float
        %.
    default : float
        s.

    Returns
    -------
    float
        s; ``default`` if no larger step stays within.
    """
    best = default
    for h in sorted(k for k in worst if k > default):
        if not worst[h] <= limit:
            break
        best = h
    return best


def conclusion_table(
    groups: Mapping[str, Sequence[str]],
    vs_default: Mapping[str, Mapping[float, Mapping[str, float]]],
    vs_reference: Mapping[str, Mapping[float, Mapping[str, float]]],
    marked: Sequence[float],
    finest: float,
) -> str:
    """Markdown table: per group of cases, the largest steps within the thresholds and errors.

    Parameters
    ----------
    groups : mapping
        Group name -> case names.
    vs_default, vs_reference : mapping
        Case -> step -> peak -> %, of :func:`case_tables`.
    marked : sequence of float
        s, steps above the package's limit in some case.
    finest : float
        s, the finest step run (its change against the reference is the reference's error).

    Returns
    -------
    str
    """
    head = "| cases | " + " | ".join(
        f"largest h within {x:g} % (within the limit / lifted)" for x in THRESHOLDS
    )
    head += " | default vs reference: max \\|change\\| (%) |"
    if finest < REFERENCE:
        head += f" {step_label(finest)} s vs reference: max \\|change\\| (%) |"
    columns = 2 + len(THRESHOLDS) + (finest < REFERENCE)
    lines = [head, "|" + "---|" * columns]
    for group, names in groups.items():
        d = {n: vs_default[n] for n in names}
        r = {n: vs_reference[n] for n in names}
        steps = sorted({h for n in names for h in d[n]})
        worst = {h: largest(d, h)[0] for h in steps}
        allowed = {h: w for h, w in worst.items() if h not in marked}
        cells = [
            f"{step_label(within(allowed, x))} / {step_label(within(worst, x))}" for x in THRESHOLDS
        ]
        err, case, peak = largest(r, DEFAULT)
        cells.append(f"{err:.3f} ({case}: {peak})")
        if finest < REFERENCE:
            err, case, peak = largest(r, finest)
            cells.append(f"{err:.3f} ({case}: {peak})")
        lines.append(f"| {group} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def _commit() -> str:
    try:
        out = subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"],
            cwd=Path(__file__).resolve().parent,
            capture_output=True,
            text=True,
            check=True,
        )
        dirty = subprocess.run(
            ["git", "status", "--porcelain", "--untracked-files=no"],
            cwd=Path(__file__).resolve().parent,
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
        return out.stdout.strip() + (" (with uncommitted changes)" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


class _NewtonCount:
    """Sums Exudyn's step and Newton iteration counts over a full vehicle's run segments."""

    def __init__(self, module) -> None:
        self.module = module
        self.steps = self.iterations = 0
        self._run = module._run

    def __enter__(self) -> _NewtonCount:
        def counted(system, *args, **kwargs):
            cols = self._run(system, *args, **kwargs)
            it = system.mbs.sys["dynamicSolver"].it
            self.steps += it.currentStepIndex
            self.iterations += it.newtonStepsCount
            return cols

        self.module._run = counted
        return self

    def __exit__(self, *exc) -> None:
        self.module._run = self._run


class _StepLimit:
    """Records the package's time-step limit of a run; lifts it (returns inf) if asked."""

    def __init__(self, module, lift: bool) -> None:
        self.module, self.lift = module, lift
        self.limit = math.nan
        self._function = module.max_time_step

    def __enter__(self) -> _StepLimit:
        def recorded(*args, **kwargs):
            self.limit = self._function(*args, **kwargs)
            return math.inf if self.lift else self.limit

        self.module.max_time_step = recorded
        return self

    def __exit__(self, *exc) -> None:
        self.module.max_time_step = self._function


def default_text(refined: Run, runs: Mapping[float, Run], finest: float) -> str:
    """The paragraph on a case's package-default run (1e-4 s, the check rail refined).

    Parameters
    ----------
    refined : Run
        :func:`run_case` with ``refine=True`` at :data:`DEFAULT`.
    runs : mapping
        Step (s) -> :class:`Run` of the case (h throughout).
    finest : float
        s, the finest step run.

    Returns
    -------
    str
    """
    windows = [
        f"{refined.where[f'refined {k} from']:.2f}-{refined.where[f'refined {k} to']:.2f} m"
        for k in range(1, 10)
        if f"refined {k} from" in refined.where
    ]
    head = (
        "Package default (1e-4 s; "
        + (
            f"the check rail's loaded window x = {', '.join(windows)} of the front wheelset "
            "run again at 2.5e-5 s"
            if windows
            else "no check rail loaded: nothing refined"
        )
        + f"): CPU {refined.cpu:.1f} s ({refined.cpu / runs[DEFAULT].cpu:.2f} x the run at "
        f"1e-4 s throughout)."
    )
    rows = []
    for name, value in refined.peaks.items():
        base, ref, fine = (runs[h].peaks.get(name, math.nan) for h in (DEFAULT, REFERENCE, finest))
        if not any(math.isfinite(v) and v != 0.0 for v in (value, base, ref)):
            continue
        rows.append((name, value, percent(value, base), percent(value, ref), percent(value, fine)))
    worst = max(rows, key=lambda r: abs(r[3]) if math.isfinite(r[3]) else -1.0, default=None)
    lines = [head, ""]
    check = [r for r in rows if r[0] == "check rail Fy"]
    for name, value, d_base, d_ref, d_fine in check:
        lines.append(
            f"- {name}: {_shown(name, value):.3f} kN; against 1e-4 s throughout "
            f"{_cell(d_base, sign=True)} %, against {REFERENCE:g} s {_cell(d_ref, sign=True)} %, "
            f"against {finest:g} s {_cell(d_fine, sign=True)} %"
        )
    if worst is not None:
        lines.append(
            f"- the largest change of any peak against {REFERENCE:g} s: "
            f"{_cell(worst[3], sign=True)} % ({worst[0]})"
        )
    return "\n".join(lines)


def defaults_table(
    defaults: Mapping[str, Run], all_runs: Mapping[str, Mapping[float, Run]], finest: float
) -> str:
    """The conclusion's table of the package-default runs against the reference.

    Parameters
    ----------
    defaults : mapping
        Case -> :func:`run_case` with ``refine=True`` at :data:`DEFAULT`.
    all_runs : mapping
        Case -> step (s) -> :class:`Run` (h throughout).
    finest : float
        s, the finest step run.

    Returns
    -------
    str
        Markdown.
    """
    lines = [
        "The package's default run (1e-4 s, a loaded check rail's window at 2.5e-5 s) "
        "against the reference:",
        "",
        f"| case | check rail Fy (kN) | vs 1e-4 s throughout (%) | vs {REFERENCE:g} s (%) | "
        f"vs {finest:g} s (%) | max \\|change\\| of any peak vs {REFERENCE:g} s (%) | CPU / "
        "CPU at 1e-4 s |",
        "|---|---|---|---|---|---|---|",
    ]
    for name, run in defaults.items():
        runs = all_runs[name]
        value = run.peaks.get("check rail Fy", math.nan)
        changes = [
            (abs(percent(v, runs[REFERENCE].peaks.get(k, math.nan))), k)
            for k, v in run.peaks.items()
            if math.isfinite(percent(v, runs[REFERENCE].peaks.get(k, math.nan)))
        ]
        worst = max(changes, default=(math.nan, "-"))
        shown = _cell(value / 1e3) if math.isfinite(value) and value != 0.0 else "-"
        lines.append(
            f"| {name} | {shown} | "
            + " | ".join(
                _cell(percent(value, runs[h].peaks.get("check rail Fy", math.nan)), sign=True)
                for h in (DEFAULT, REFERENCE, finest)
            )
            + f" | {_cell(worst[0])} ({worst[1]}) | {run.cpu / runs[DEFAULT].cpu:.2f} |"
        )
    return "\n".join(lines)


def run_case(turnout, case: Case, h: float, lift_limit: bool = True, refine: bool = False) -> Run:
    """One passage of the full vehicle at step h: its peaks, CPU time and Newton counts.

    Parameters
    ----------
    turnout : Turnout
    case : Case
    h : float
        s.
    lift_limit : bool
        Where the package refuses h (above its limit of 10 steps per period of the wheel on
        the lightest rail), run it with the limit lifted (``Run.beyond_limit``).
    refine : bool
        False: h throughout (``check_rail_time_step=None``: the step's own convergence);
        True: the package's default, a loaded check rail's window at its
        ``check_rail_time_step``.

    Returns
    -------
    Run
        With ``error`` set (and no peaks) where the passage refused the step or failed.
    """
    from exudyn_turnout.inputs.vehicle import load_vehicle
    from exudyn_turnout.passage import common
    from exudyn_turnout.passage.corunning_track import vehicle as full_vehicle
    from exudyn_turnout.passage.run import simulate_passage, vehicle_of
    from exudyn_turnout.passage.settings import PassageError, PassageSettings

    settings = PassageSettings(
        route=case.route,
        speed_kmh=case.speed_kmh,
        layers=case.layers,
        x_start=case.x_start,
        x_end=case.x_end,
        time_step=h,
        check_rail_time_step=PassageSettings().check_rail_time_step if refine else None,
        solver="exudyn",  # the study's runs and Newton counts (Exudyn's solver's) as measured
    )
    with _StepLimit(common, lift=False) as limit:
        try:  # the passage's own check of the settings (as simulate_passage makes it)
            common.check_vehicle_settings(settings, turnout, vehicle_of(None), load_vehicle())
            refused = ""
        except PassageError as err:
            refused = str(err).splitlines()[0]
    if refused and not (lift_limit and refused.startswith("time step")):
        return Run({}, 0.0, 0, math.nan, refused, limit=limit.limit)
    with _StepLimit(common, lift=bool(refused)), _NewtonCount(full_vehicle) as count:
        c0 = time.process_time()
        try:
            result = simulate_passage(turnout, settings)
        except PassageError as err:
            why = str(err).splitlines()[0]
            if refused:
                why = f"above the package's limit {limit.limit:.3g} s; with it lifted: {why}"
            return Run({}, time.process_time() - c0, 0, math.nan, why, limit=limit.limit)
        cpu = time.process_time() - c0
    peaks = summary_peaks(result.summary)
    windows = result.summary.get("check_rail_refined") or []
    where = summary_positions(result.summary)
    for k, w in enumerate(windows):  # the refined windows (x of the front wheelset, m)
        where[f"refined {k + 1} from"], where[f"refined {k + 1} to"] = w["x_m"]
    return Run(
        peaks,
        cpu,
        count.steps,
        count.iterations / count.steps,
        limit=limit.limit,
        beyond_limit=bool(refused),
        where=where,
        ringing=_check_rail_ringing(result, settings.v),
    )


def _check_rail_ringing(result, speed: float) -> float:
    """Hz, :func:`ringing_frequency` of the front wheelset's check-rail force (NaN: none)."""
    summary, columns = result.summary, result.columns
    name = f"Fy_{summary.get('check_rail_wheel')}_{summary.get('check_rail_rail')}_N"
    x_peak = summary.get("peak_Fy_check_rail_x_m")
    peak = summary.get("peak_Fy_check_rail_N")
    if name not in columns or not isinstance(x_peak, float) or not peak:
        return math.nan
    return ringing_frequency(columns["x_m"], columns[name], speed, x_peak)


#: m, the front wheelset's x range of the FE table (the check rail's flare ends at 45.29 m)
FE_WINDOW = (42.0, 52.0)
#: s, the FE table's steps throughout (output every step)
FE_STEPS = (2.5e-5, 1.25e-5)
#: the FE table's heading: ``--fe-only`` replaces the page from it to its end
FE_HEADING = "## FE track: the check rail's step (diverging route, 80 km/h)"


def _check_rail_force(turnout, result, route: str, wheelsets: int):
    """N per sample: the largest |(Fy, Fz)| of every wheelset's check-rail contacts."""
    import numpy as np

    from exudyn_turnout.inputs.routes import load_route
    from exudyn_turnout.passage.check_rail_steps import check_rail_pairs

    columns = result.columns
    labels = [f"ws{i + 1}_" for i in range(wheelsets)] if wheelsets else [""]
    force = np.zeros(len(columns["t_s"]))
    for label in labels:
        for wheel, slot in check_rail_pairs(load_route(turnout, route)):
            name = f"{label}{wheel}_{slot}_N"
            if f"Fy_{name}" in columns:
                fy = np.nan_to_num(np.asarray(columns[f"Fy_{name}"], float))
                fz = np.nan_to_num(np.asarray(columns[f"Fz_{name}"], float))
                force = np.maximum(force, np.hypot(fy, fz))
    return force


def fe_section(turnout) -> str:
    """The FE table: the check-rail force's peak of the FE single wheelset and full vehicle
    at the default step unrefined, the package's default (refined), the default sampling
    every step of its refined windows, and the steps of :data:`FE_STEPS` throughout; each
    peak over all of its samples and over the samples of the 1e-4 s grid; CPU time.

    Parameters
    ----------
    turnout : Turnout

    Returns
    -------
    str
        Markdown, from :data:`FE_HEADING` on.
    """
    from exudyn_turnout.passage.common import pick_rows
    from exudyn_turnout.passage.fe_track.options import FEPassageOptions
    from exudyn_turnout.passage.run import simulate_passage
    from exudyn_turnout.passage.settings import PassageSettings

    base = PassageSettings(
        route="diverging", speed_kmh=80.0, x_start=FE_WINDOW[0], x_end=FE_WINDOW[1]
    )
    runs = [
        ("1e-4 s, unrefined", {"check_rail_time_step": None}, None),
        ("package default (1e-4 s, refined)", {}, None),
        ("default, every refined step sampled", {}, FEPassageOptions(check_rail_every_step=True)),
    ] + [(f"{h:g} s throughout", {"time_step": h}, None) for h in FE_STEPS]
    with warnings.catch_warnings():  # untimed warm-up: contact tables, compiled kernels
        warnings.simplefilter("ignore")
        warm = PassageSettings(**{**base.__dict__, "x_start": 44.29, "x_end": 45.6})
        for vehicle in ("wheelset", "manchester"):
            simulate_passage(turnout, warm, vehicle, track="fe")
    lines = [
        FE_HEADING,
        "",
        f"Generated by `python validation/{Path(__file__).name} --fe-only` (do not edit) at "
        f"commit {_commit()}. The FE track (`passage/fe_track/`), front wheelset x = "
        f"{FE_WINDOW[0]:g}..{FE_WINDOW[1]:g} m (the check rail's entry flare ends at 45.29 m; "
        "the full vehicle's second wheelset passes it too). Peak: the largest |(Fy, Fz)| of "
        "any wheelset's check-rail contact over all samples, and over the samples at the "
        "1e-4 s grid's times (the default's output times; a finer run's rows nearest to "
        "them). After an untimed warm-up run of each vehicle. 'package default': the "
        "loaded check rail's windows run again at "
        "`check_rail_time_step` (2.5e-5 s), output on the 1e-4 s grid "
        "(`passage/fe_track/common.py`); 'every refined step sampled': "
        "`FEPassageOptions(check_rail_every_step=True)`. CPU: the whole `simulate_passage` "
        "call, one process, the runs one after the other.",
        "",
    ]
    for vehicle, wheelsets in (("wheelset", 0), ("manchester", 4)):
        results = {}
        for label, change, options in runs:
            settings = PassageSettings(**{**base.__dict__, **change})
            c0 = time.process_time()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                result = simulate_passage(
                    turnout, settings, vehicle, track="fe", fe_options=options
                )
            results[label] = (result, time.process_time() - c0)
            print(f"FE {vehicle} {label}: CPU {results[label][1]:.1f} s", file=sys.stderr)
        grid = results[runs[0][0]][0].columns["t_s"]
        ref_label = runs[-1][0]
        peaks = {}
        for label, (result, cpu) in results.items():
            force = _check_rail_force(turnout, result, "diverging", wheelsets)
            on_grid = pick_rows({"t_s": result.columns["t_s"], "F": force}, grid)["F"]
            peaks[label] = (float(force.max()), float(on_grid.max()), cpu, len(force))
        ref_all, ref_grid = peaks[ref_label][:2]
        cpu_0 = peaks[runs[0][0]][2]
        name = "single wheelset" if not wheelsets else "full vehicle (Manchester)"
        lines += [
            f"### {name}",
            "",
            "| run | samples | peak, all samples (kN) | vs finest | peak at the 1e-4 s grid "
            "(kN) | vs finest | CPU s | CPU / unrefined |",
            "|---|---|---|---|---|---|---|---|",
        ]
        for label, (p_all, p_grid, cpu, n) in peaks.items():
            lines.append(
                f"| {label} | {n} | {p_all / 1e3:.2f} | {percent(p_all, ref_all):+.1f} % | "
                f"{p_grid / 1e3:.2f} | {percent(p_grid, ref_grid):+.1f} % | {cpu:.1f} | "
                f"{cpu / cpu_0:.2f} |"
            )
        windows = results[runs[1][0]][0].summary.get("check_rail_refined") or []
        lines += [
            "",
            "Refined windows of the default (front wheelset's x): "
            + (
                ", ".join(
                    f"{w['x_m'][0]:.2f}-{w['x_m'][1]:.2f} m at {w['time_step_s']:.3g} s"
                    for w in windows
                )
                or "none"
            )
            + ".",
            "",
        ]
    return "\n".join(lines)


def _replace_fe_section(path: Path, section: str) -> str:
    """The page at ``path`` with its FE section (from :data:`FE_HEADING` to the end)
    replaced by ``section`` (appended where it has none)."""
    old = path.read_text(encoding="utf-8") if path.exists() else ""
    head = old.split(FE_HEADING, 1)[0].rstrip("\n")
    return (head + "\n\n" if head else "") + section


def main(argv: Sequence[str] | None = None) -> None:
    """Run the study, write and print the page.

    Parameters
    ----------
    argv : sequence of str, optional
        Command-line arguments (default: ``sys.argv[1:]``).
    """
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=float, nargs="+", default=list(STEPS), help="s")
    parser.add_argument("--cases", nargs="+", choices=list(CASES), default=list(CASES))
    parser.add_argument("--out", default=str(Path(__file__).with_suffix(".md")))
    parser.add_argument(
        "--keep-limit",
        action="store_true",
        help="do not run the steps the package refuses (default: run them with its limit lifted)",
    )
    parser.add_argument(
        "--fe-only",
        action="store_true",
        help="run only the FE track's check-rail table (~6 min) and replace it in the page",
    )
    args = parser.parse_args(argv)
    if args.fe_only:
        from exudyn_turnout.inputs.turnout import load_turnout

        page = _replace_fe_section(Path(args.out), fe_section(load_turnout()))
        Path(args.out).write_text(page, encoding="utf-8")
        print(page.split(FE_HEADING, 1)[1])
        return
    steps = sorted(set(args.steps))
    for h in (REFERENCE, DEFAULT):
        if not any(math.isclose(h, s) for s in steps):
            parser.error(f"--steps must include the reference {REFERENCE:g} s and {DEFAULT:g} s")
    from exudyn_turnout.inputs.routes import load_route
    from exudyn_turnout.inputs.turnout import load_turnout
    from exudyn_turnout.passage.common import newton_tolerance
    from exudyn_turnout.passage.corunning_track import vehicle as full_vehicle
    from exudyn_turnout.passage.run import simulate_passage
    from exudyn_turnout.passage.settings import PassageSettings

    turnout = load_turnout()
    load_before = os.getloadavg()
    # untimed warm-up: contact tables, compiled kernels
    simulate_passage(turnout, PassageSettings(x_start=40.0, x_end=40.2))
    sections: list[str] = []
    vs_default: dict[str, dict[float, dict[str, float]]] = {}
    vs_reference: dict[str, dict[float, dict[str, float]]] = {}
    wall = time.perf_counter()
    all_runs: dict[str, dict[float, Run]] = {}
    defaults: dict[str, Run] = {}  # the package's default run of each case (refined)
    for name in args.cases:
        case = CASES[name]
        runs = all_runs[name] = {}
        for h in steps:
            runs[h] = run_case(turnout, case, h, lift_limit=not args.keep_limit)
            print(
                f"{name} h = {h:g} s: CPU {runs[h].cpu:.1f} s {runs[h].error}",
                file=sys.stderr,
                flush=True,
            )
        for h in (REFERENCE, DEFAULT):
            if runs[h].error:
                sys.exit(f"error: {name} at h = {h:g} s failed: {runs[h].error}")
        refined = defaults[name] = run_case(turnout, case, DEFAULT, refine=True)
        print(f"{name} package default: CPU {refined.cpu:.1f} s", file=sys.stderr, flush=True)
        text, vs_default[name], vs_reference[name] = case_tables(runs)
        text += "\n\n" + default_text(refined, runs, steps[0])
        pairs = [p for p in load_route(turnout, case.route).pairs if p.check]
        flare = load_route(turnout, case.route).check_flare[0]
        check = (
            f"Check rail: x = {pairs[0].check[0]:g}..{pairs[0].check[1]:g} m, flared ends "
            f"{flare:g} m long (the flare's end, where the clearance's slope jumps: x = "
            f"{pairs[0].check[0] + flare:g} m)."
            if pairs and pairs[0].check
            else ""
        )
        sections += [
            f"## {name}: {case.route} route, {case.speed_kmh:g} km/h, {case.layers} layers, "
            f"front wheelset x = {case.x_start:g}..{case.x_end:g} m",
            "",
            *([check, ""] if check else []),
            text,
            "",
        ]
    wall = time.perf_counter() - wall
    load_after = os.getloadavg()
    marked = [h for h in steps if any(r[h].beyond_limit for r in all_runs.values())]
    failed = [h for h in steps if any(r[h].error for r in all_runs.values())]
    total = {h: sum(r[h].cpu for r in all_runs.values()) for h in steps if h not in failed}
    cpu = {h: c / total[DEFAULT] for h, c in total.items()}
    table, _ = overview(vs_default, vs_reference, steps, marked, cpu)
    limits = sorted({r[h].limit for r in all_runs.values() for h in steps})
    groups = {"all cases": list(all_runs)}
    for route in dict.fromkeys(CASES[n].route for n in all_runs):
        groups[f"{route} route"] = [n for n in all_runs if CASES[n].route == route]
    conclusions = [
        "The package's step limit (10 steps per period of the wheel's contact resonance on "
        "the lightest rail under any wheelset): "
        + ", ".join(f"{v:.4g} s" for v in limits if math.isfinite(v))
        + " in these cases; a step marked * is above it (run with the limit lifted). "
        "'largest h within x %': the largest step above the default whose peaks all stay "
        "within x % of the default's, every step between included (1e-4: none does).",
        "",
        conclusion_table(groups, vs_default, vs_reference, marked, steps[0]),
        "",
        defaults_table(defaults, all_runs, steps[0]),
    ]
    load = ", ".join(f"{v:.2f}" for v in load_before + load_after)
    newton_abs = full_vehicle.NEWTON_TOLERANCE_FACTOR * newton_tolerance(4)
    text = "\n".join(
        [
            "# Full vehicle: time-step convergence of the passage",
            "",
            f"Generated by `python validation/{Path(__file__).name}` (do not edit) at commit "
            f"{_commit()}; {os.cpu_count()} cores shared with other jobs, load average "
            f"(1/5/15 min) before and after: {load}; {wall / 60:.1f} min wall in all.",
            "",
            "The full Manchester vehicle (the package's default: four wheelsets each on its "
            "own co-running track, `passage/corunning_track/vehicle.py`), profile contact, "
            "generalized-alpha (spectral radius 0.8) at a fixed step h, output every step "
            "(`check_rail_time_step=None`: h throughout, also where a check rail carries "
            "load; 'package default': 1e-4 s with the check rail's loaded windows run again "
            "at `check_rail_time_step`, `passage/common.py`); "
            "every run starts from its steady state at speed, which does not depend on h. "
            "Peaks as the summary defines them (`vehicle_summary`): Fz the maximum, Fy the "
            "largest magnitude with its sign (+ left), in the turnout file's regions switch "
            f"{tuple(turnout.regions['switch'])} m and crossing "
            f"{tuple(turnout.regions['crossing'])} m of each wheelset's own x; `ws1`: the "
            "front wheelset's wheels; `vehicle`: the largest magnitude over every wheelset's "
            "per-wheel peaks (only wheelsets that reach the region: over -5..60 m of the "
            "front wheelset the rear bogie's wheelsets do not reach the crossing; over "
            "20..55 m only the rear bogie's pass the switch region, from x = 1.0 and -1.56 m); "
            "`check rail Fy`: the front wheelset's lateral force on the check rail "
            "(`peak_Fy_check_rail_N`); `dQ/Q0`: the largest wheel unloading "
            "(Q0 - Q)/Q0 over the run. Changes in % of the peak itself (a small lateral "
            "peak's 0.1 % is a few newtons). CPU s: the whole `simulate_passage` call (set-up, "
            "start at speed, steps, summary), one process, the runs one after the other. "
            "Newton it./step: Exudyn's Newton iterations over its steps, all run segments. "
            "The observed order p = log2(|P(4h) - P(2h)| / |P(2h) - P(h)|) from three steps "
            "halving; '-' where the two differences have opposite signs (not in the "
            "asymptotic range: a peak sampled at the steps, or the Newton tolerance, "
            f"{newton_abs:g} N absolute, dominates).",
            "",
            "## Overview: the largest change of any peak of any case",
            "",
            table,
            "",
            "## Conclusion",
            "",
            *conclusions,
            "",
            *sections,
        ]
    )
    out = Path(args.out)
    if out.exists() and FE_HEADING in out.read_text(encoding="utf-8"):  # kept: --fe-only's
        text = (
            text.rstrip("\n")
            + "\n\n"
            + FE_HEADING
            + out.read_text(encoding="utf-8").split(FE_HEADING, 1)[1]
        )
    out.write_text(text, encoding="utf-8")
    print(text)


if __name__ == "__main__":
    main()
