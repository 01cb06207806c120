"""The safety figure of a passage: Y/Q with Nadal, sum Y with Prud'homme, Delta Q/Q0 along x.

Draws the columns and summary of a passage
(:class:`~exudyn_turnout.passage.results.PassageResult`; quantities and limits of
:mod:`exudyn_turnout.passage.safety`).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from exudyn_turnout.passage.safety import sliding_mean, wheel_labels, wheel_unloading
from exudyn_turnout.plotting.backend import place_axes, pyplot

__all__ = ["plot_passage_safety"]


def _float(summary: Mapping, key: str) -> float | None:
    value = summary.get(key)
    return float(value) if isinstance(value, (int, float)) else None


def plot_passage_safety(result, title: str | None = None):
    """Y/Q per wheel, sum Y per wheelset and the wheel unloading against x, with limits.

    Thin lines: the samples; thick lines: the 2 m sliding means (EN 14363). Dashed: Nadal's
    limit (+-, the flange and the back of the flange), Prud'homme's limit (+-), the
    unloading limit. The summary's regions are shaded.

    Parameters
    ----------
    result : PassageResult
        With the safety columns (``YQ_[<ws>_]<wheel>``, ``sumY_[<ws>_]N``) and the summary
        keys ``nadal_limit``, ``prudhomme_limit_[<ws>_]N``, ``safety_limits`` and the
        static wheel loads.
    title : str, optional

    Returns
    -------
    (figure, axes)
        Three axes sharing x.
    """
    plt = pyplot()
    cols, summary = result.columns, result.summary
    fig, axes = plt.subplots(3, 1, figsize=(9, 8), sharex=True)
    labels = [lab for lab in wheel_labels(cols) if lab] or [""]
    limits = summary.get("safety_limits") or {}
    window = float(limits.get("window_m", 2.0))
    x_range = [np.inf, -np.inf]
    for label in labels:
        x = np.asarray(cols.get(f"x_{label}_m", cols["x_m"]) if label else cols["x_m"])
        x_range = [min(x_range[0], float(x.min())), max(x_range[1], float(x.max()))]
        tag = f"{label} " if label else ""
        for wheel in ("right", "left"):
            name = f"YQ_{label}_{wheel}" if label else f"YQ_{wheel}"
            if name not in cols:
                continue
            (line,) = axes[0].plot(x, cols[name], lw=0.6, alpha=0.6)
            axes[0].plot(
                x, sliding_mean(x, cols[name], window), lw=1.6, color=line.get_color(),
                label=f"{tag}{wheel}",
            )  # fmt: skip
            fz = f"Fz_{label}_{wheel}_N" if label else f"Fz_{wheel}_N"
            load_key = (
                f"static_wheel_load_{label}_{wheel}_N"
                if label
                else ("static_wheel_load_N" if wheel == "right" else "static_wheel_load_left_N")
            )
            q0 = _float(summary, load_key)
            if fz in cols and q0:
                axes[2].plot(x, wheel_unloading(cols[fz], q0), lw=0.8, label=f"{tag}{wheel}")
        name = f"sumY_{label}_N" if label else "sumY_N"
        if name in cols:
            (line,) = axes[1].plot(x, np.asarray(cols[name]) / 1e3, lw=0.6, alpha=0.6)
            axes[1].plot(
                x, sliding_mean(x, cols[name], window) / 1e3, lw=1.6, color=line.get_color(),
                label=f"{label or 'wheelset'}",
            )  # fmt: skip
    nadal = _float(summary, "nadal_limit")
    prud = _float(summary, f"prudhomme_limit_{labels[0]}_N" if labels[0] else "prudhomme_limit_N")
    unloading = limits.get("unloading")
    for ax, limit, text in (
        (axes[0], nadal, "Nadal"),
        (axes[1], None if prud is None else prud / 1e3, "Prud'homme"),
    ):
        if limit is not None:
            for sign in (1, -1):
                ax.axhline(sign * limit, color="k", ls="--", lw=1, label=text if sign > 0 else None)
    if isinstance(unloading, (int, float)):
        axes[2].axhline(float(unloading), color="k", ls="--", lw=1, label="limit")
    for key in ("switch_region_m", "crossing_region_m"):
        region = summary.get(key)
        if isinstance(region, (list, tuple)) and len(region) == 2:
            for ax in axes:
                ax.axvspan(float(region[0]), float(region[1]), color="0.9", zorder=0)
    axes[0].set_ylabel("Y/Q (-)")
    axes[1].set_ylabel("sum Y (kN)")
    axes[2].set_ylabel(r"$\Delta$Q/Q0 (-)")
    axes[2].set_xlabel("x (m)")
    if x_range[1] > x_range[0]:
        axes[2].set_xlim(*x_range)
    for ax in axes:
        ax.grid(True, lw=0.3)
        ax.legend(fontsize=7, ncol=4, loc="upper right")
    short = x_range[1] - x_range[0] < window
    heading = (
        (title + "\n" if title else "")
        + f"thin: samples, thick: {window:g} m sliding mean"
        + (f" (none: the run is shorter than {window:g} m)" if short else "")
        + "; grey: switch and crossing regions"
    )
    fig.suptitle(heading, fontsize=9)
    # fixed margins, not tight_layout (half the figure's time, issue 24)
    place_axes(fig, 0.8, 0.25, 0.58, 0.2 + 0.16 * (heading.count("\n") + 1), hspace=0.1)
    return fig, axes
