"""Plots of computed results (the only module that imports matplotlib).

Each function takes data objects (e.g. :class:`~exudyn_turnout.receptance.Receptance`),
draws into given axes or a new figure, and returns ``(figure, axes)``; saving is left to
the caller (``fig.savefig(path)``).
"""
from __future__ import annotations

import math
from typing import Sequence

import matplotlib.pyplot as plt
import numpy as np

from .receptance import Receptance

__all__ = ["receptance_label", "plot_receptance", "passage_label", "plot_passage_forces"]


def receptance_label(r: Receptance) -> str:
    """Legend text of a receptance: model, rail, direction and position."""
    x = "" if math.isnan(r.x) else f" at x = {r.x:g} m"
    return f"{r.model} {r.rail} {r.direction}{x}".strip()


def plot_receptance(receptances: Receptance | Sequence[Receptance], ax=None, *, phase: bool = False,
                    labels: Sequence[str] | None = None, title: str | None = None):
    """Log-log magnitude |H| (m/N) over frequency (Hz), optionally the phase below it.

    Parameters
    ----------
    receptances : Receptance or sequence of Receptance
        Curves to draw, in order.
    ax : matplotlib Axes or (Axes, Axes), optional
        Magnitude axes, or (magnitude, phase) axes when ``phase``; new figure if None.
    phase : bool
        Also draw the phase (degrees, -180 to 180).
    labels : sequence of str, optional
        Legend entries; default :func:`receptance_label`.
    title : str, optional

    Returns
    -------
    (Figure, tuple of Axes)
    """
    curves = [receptances] if isinstance(receptances, Receptance) else list(receptances)
    axes = _axes(ax, phase)
    names = list(labels) if labels is not None else [receptance_label(r) for r in curves]
    for r, name in zip(curves, names):
        axes[0].loglog(r.frequency_hz, r.magnitude, label=name)
        if phase:
            axes[1].semilogx(r.frequency_hz, np.degrees(np.angle(r.H)), label=name)
    axes[0].set_ylabel("receptance |H| (m/N)")
    axes[0].grid(True, which="both", alpha=0.3)
    if curves:
        axes[0].legend(fontsize="small")
    if title:
        axes[0].set_title(title)
    if phase:
        axes[1].set_ylabel("phase (deg)")
        axes[1].set_ylim(-180, 180)
        axes[1].grid(True, which="both", alpha=0.3)
    axes[-1].set_xlabel("frequency (Hz)")
    return axes[0].figure, axes


def _axes(ax, phase: bool) -> tuple:
    if ax is None:
        if phase:
            _, pair = plt.subplots(2, 1, sharex=True, figsize=(6.4, 6.0), height_ratios=(2, 1))
            return tuple(pair)
        _, single = plt.subplots(figsize=(6.4, 4.2))
        return (single,)
    axes = tuple(ax) if isinstance(ax, (tuple, list, np.ndarray)) else (ax,)
    if len(axes) != (2 if phase else 1):
        raise ValueError(f"phase={phase} needs {2 if phase else 1} axes, got {len(axes)}")
    return axes


def passage_label(result) -> str:
    """Legend text of a passage: layers (or model), parameter source and speed."""
    s = result.settings
    model = result.summary.get("model", f"{s.layers}-layer")
    return f"{model}, {s.source}, {s.speed_kmh:g} km/h"


def plot_passage_forces(results, wheel: str = "right", labels=None, title: str | None = None):
    """Contact forces of passages against x, at the switch and at the crossing (Figs 7, 8 layout).

    Parameters
    ----------
    results : sequence of PassageResult
        Runs to overlay (e.g. 2-layer, 3-layer, FE reference).
    wheel : {"right", "left"}
    labels : sequence of str, optional

    Returns
    -------
    (figure, axes)
        A 2 x 2 grid: rows vertical (Fz) and lateral (Fy) force on the rail, columns the
        switch and crossing regions named in the results' summaries.
    """
    results = list(results)
    fig, axes = plt.subplots(2, 2, figsize=(10.0, 6.4), sharex="col")
    names = list(labels) if labels is not None else [passage_label(r) for r in results]
    regions = (("switch", results[0].summary["switch_region_m"]), ("crossing", results[0].summary["crossing_region_m"]))
    for row, (quantity, unit) in enumerate((("Fz", "vertical"), ("Fy", "lateral"))):
        for col, (where, (x0, x1)) in enumerate(regions):
            ax = axes[row, col]
            for r, name in zip(results, names):
                x, f = r.columns["x_m"], r.columns[f"{quantity}_{wheel}_N"]
                sel = (x >= x0) & (x <= x1)
                ax.plot(x[sel], f[sel] / 1e3, label=name, lw=1.0)
            ax.grid(True, alpha=0.3)
            ax.set_title(f"{unit} force, {wheel} wheel, {where}", fontsize="medium")
            if col == 0:
                ax.set_ylabel(f"{quantity} on rail (kN)")
            if row == 1:
                ax.set_xlabel("x from switch toe (m)")
    axes[0, 0].legend(fontsize="small")
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    return fig, axes
