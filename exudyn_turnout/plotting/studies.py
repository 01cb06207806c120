"""Figures of a study's results table (:func:`exudyn_turnout.studies.run_study`).

- :func:`plot_peak_vs_factor`: a peak against a factor, one curve per value of another
  factor (the routes or the track models); where other factors vary too (seeds, a Latin
  hypercube) the curve is their mean with the range shaded;
- :func:`plot_peak_distribution`: the distribution of a peak over the cases (e.g. over
  irregularity seeds): histogram and empirical cumulative distribution;
- :func:`study_figures`: the figures a study's command writes.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from exudyn_turnout.plotting.backend import pyplot

__all__ = [
    "plot_peak_vs_factor",
    "plot_peak_distribution",
    "study_figures",
    "save_study_figure",
    "DEFAULT_PEAK",
]

#: The peak drawn by default: the largest vertical force at the crossing (either wheel).
DEFAULT_PEAK = "max_Fz_crossing_N"


def _label(name: str) -> str:
    if name.endswith("_N"):
        return f"{name[:-2]} (kN)"
    return name


def _value_label(name: str, value) -> str:
    """``k_z = 1.2e+08`` for a group of a factor (its last dotted part)."""
    short = name.rsplit(".", 1)[-1]
    return f"{short} = {value:g}" if isinstance(value, (int, float, np.number)) else f"{value}"


def _scale(name: str) -> float:
    return 1e-3 if name.endswith("_N") else 1.0


def _ok(table: Mapping[str, np.ndarray]) -> np.ndarray:
    status = table.get("status")
    n = len(table["case"])
    return np.ones(n, bool) if status is None else np.asarray(status) == "ok"


def plot_peak_vs_factor(
    table: Mapping[str, np.ndarray],
    factor: str,
    peak: str = DEFAULT_PEAK,
    curves: str | None = None,
    ax=None,
):
    """A peak against a numeric factor, one curve per value of ``curves``.

    Parameters
    ----------
    table : mapping
        The results table (column -> array).
    factor : str
        Numeric input column on the x axis (e.g. ``speed_kmh``).
    peak : str
        Result column (N columns drawn in kN).
    curves : str, optional
        Input column whose values make separate curves (e.g. ``route``, ``track``).
    ax : matplotlib Axes, optional

    Returns
    -------
    (figure, axes)
    """
    plt = pyplot()
    if ax is None:
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
    else:
        fig = ax.figure
    ok = _ok(table) & np.isfinite(np.asarray(table[peak], dtype=float))
    x_all = np.asarray(table[factor], dtype=float)
    y_all = np.asarray(table[peak], dtype=float) * _scale(peak)
    labels = np.asarray(table[curves]) if curves is not None else np.zeros(len(ok))
    groups = [None] if curves is None else list(dict.fromkeys(labels[ok]))
    spread = False
    for group in groups:
        sel = ok if group is None else ok & (labels == group)
        xs = np.unique(x_all[sel])
        stats = [y_all[sel & (x_all == x)] for x in xs]
        mean = np.array([s.mean() for s in stats])
        label = None if group is None else _value_label(str(curves), group)
        (line,) = ax.plot(xs * _scale(factor), mean, marker="o", label=label)
        if any(s.size > 1 for s in stats):
            spread = True
            low = np.array([s.min() for s in stats])
            high = np.array([s.max() for s in stats])
            ax.fill_between(xs * _scale(factor), low, high, color=line.get_color(), alpha=0.2)
    ax.set_xlabel(_label(factor))
    ax.set_ylabel(_label(peak) + (" (mean, range shaded)" if spread else ""))
    ax.grid(True, alpha=0.3)
    if curves is not None:
        ax.legend(fontsize="small")
    return fig, ax


def plot_peak_distribution(
    table: Mapping[str, np.ndarray],
    peak: str = DEFAULT_PEAK,
    by: str | None = None,
    bins: int | None = None,
    axes=None,
):
    """Distribution of a peak over the cases: histogram and empirical CDF.

    Parameters
    ----------
    table : mapping
        The results table.
    peak : str
        Result column.
    by : str, optional
        Input column whose values get separate distributions (e.g. a pad stiffness).
    bins : int, optional
        Histogram bins (default: about sqrt(n)).
    axes : (Axes, Axes), optional

    Returns
    -------
    (figure, axes)
    """
    plt = pyplot()
    if axes is None:
        fig, axes = plt.subplots(1, 2, figsize=(9.0, 3.8))
    else:
        fig = axes[0].figure
    values = np.asarray(table[peak], dtype=float) * _scale(peak)
    ok = _ok(table) & np.isfinite(values)
    labels = np.asarray(table[by]) if by is not None else np.zeros(len(ok))
    groups = [None] if by is None else list(dict.fromkeys(labels[ok]))
    for group in groups:
        sel = ok if group is None else ok & (labels == group)
        v = np.sort(values[sel])
        if v.size == 0:
            continue
        label = (
            f"n = {v.size}" if group is None else f"{_value_label(str(by), group)} (n = {v.size})"
        )
        n_bins = bins or max(3, int(math.sqrt(v.size)))
        axes[0].hist(v, bins=n_bins, alpha=0.5, label=label)
        axes[1].step(v, np.arange(1, v.size + 1) / v.size, where="post", label=label)
    axes[0].set_xlabel(_label(peak))
    axes[0].set_ylabel("cases")
    axes[1].set_xlabel(_label(peak))
    axes[1].set_ylabel("fraction of cases <= value")
    for a in axes:
        a.grid(True, alpha=0.3)
    axes[1].legend(loc="lower right", fontsize="small")
    return fig, axes


def save_study_figure(fig, path) -> None:
    """Save a figure (format from the suffix; directory created) and close it.

    Parameters
    ----------
    fig : matplotlib Figure
    path : str or Path
    """
    plt = pyplot()
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(target, dpi=110, bbox_inches="tight")
    plt.close(fig)


def study_figures(
    table: Mapping[str, np.ndarray],
    varied: Sequence[str],
    out_dir,
    peak: str = DEFAULT_PEAK,
) -> list[str]:
    """The figures of a study: the peak against each numeric factor, its distribution.

    For each numeric factor with more than one value: ``peak_vs_<factor>.png`` with one
    curve per route / track / turnout if those vary; with irregularity seeds
    ``peak_distribution.png``.

    Parameters
    ----------
    table : mapping
        The results table.
    varied : sequence of str
        The study's varied factors (``Study.varied``).
    out_dir : str or Path
        Directory the PNG files are written to.
    peak : str
        Result column drawn.

    Returns
    -------
    list of str
        Paths written.
    """
    out = Path(out_dir)
    if peak not in table or not _ok(table).any():
        return []
    text = [f for f in varied if np.asarray(table[f]).dtype.kind in "US"]
    curves = next((f for f in ("route", "track", "turnout", "layers") if f in varied), None)
    if curves is None and text:
        curves = text[0]
    paths = []
    for factor in varied:
        if factor in ("seed", curves) or np.asarray(table[factor]).dtype.kind not in "fiu":
            continue
        if len(np.unique(np.asarray(table[factor], dtype=float))) < 2:
            continue
        fig, _ = plot_peak_vs_factor(table, factor, peak, curves=curves)
        safe = factor.replace(".", "_").replace("/", "_")
        path = out / f"peak_vs_{safe}.png"
        save_study_figure(fig, path)
        paths.append(str(path))
    if "seed" in varied:
        fig, _ = plot_peak_distribution(table, peak)
        path = out / "peak_distribution.png"
        save_study_figure(fig, path)
        paths.append(str(path))
    return paths
