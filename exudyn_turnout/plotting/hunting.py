"""Figure of a straight-track hunting study (:mod:`exudyn_turnout.passage.hunting`).

:func:`plot_hunting`: left, the decay rate of the least damped wheelset against speed
(time-domain runs, decaying ones filled) with the linearised system's least damped
eigenvalue (-Re lambda) and the onset bracket; right, the leading wheelset's lateral
displacement over the distance run for a few speeds.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from exudyn_turnout.plotting.backend import pyplot

__all__ = ["plot_hunting"]


def plot_hunting(
    runs: Sequence[Any],
    linear: Sequence[Any] = (),
    bracket_kmh: tuple[float, float] | None = None,
    traces: Sequence[Any] = (),
    min_decay_rate: float = 0.0,
) -> tuple[Any, Any]:
    """Decay rate against speed and lateral displacement traces.

    Parameters
    ----------
    runs : sequence of HuntingRun
        Time-domain runs (:func:`~exudyn_turnout.passage.hunting.simulate_hunting`).
    linear : sequence of LinearHunting
        Linearised system at some speeds (:func:`~exudyn_turnout.passage.hunting.linear_hunting`).
    bracket_kmh : (float, float), optional
        km/h, the onset bracket to shade.
    traces : sequence of HuntingRun
        Runs whose leading wheelset's y(x) is drawn on the right (default: none, one panel).
    min_decay_rate : float
        1/s, the decay threshold drawn as a line.

    Returns
    -------
    fig : matplotlib.figure.Figure
    axes : numpy.ndarray of matplotlib.axes.Axes
        One or two axes.
    """
    plt = pyplot()
    n = 2 if traces else 1
    fig, axes = plt.subplots(1, n, figsize=(6.0 * n, 4.2), squeeze=False)
    axes = axes[0]
    ax = axes[0]
    runs = sorted(runs, key=lambda r: r.settings.speed_kmh)
    speed = np.array([r.settings.speed_kmh for r in runs])
    rate = np.array([r.decay_rate for r in runs])
    good = rate > min_decay_rate
    if len(runs):
        ax.plot(speed, rate, color="0.6", lw=0.8)
        ax.plot(speed[good], rate[good], "o", color="tab:blue", label="time domain: decays")
        ax.plot(speed[~good], rate[~good], "o", mfc="none", color="tab:red", label="does not decay")
    if len(linear):
        lin = sorted(linear, key=lambda r: r.speed_kmh)
        ax.plot(
            [r.speed_kmh for r in lin],
            [-r.growth_rate for r in lin],
            "s--",
            ms=4,
            color="tab:green",
            label="linearised: -Re(lambda) least damped",
        )
    if bracket_kmh is not None:
        ax.axvspan(*bracket_kmh, color="tab:orange", alpha=0.3, label="onset bracket")
    ax.axhline(min_decay_rate, color="k", lw=0.6)
    ax.set_xlabel("speed (km/h)")
    ax.set_ylabel("decay rate of the least damped wheelset (1/s)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    if traces:
        ax = axes[1]
        for run in sorted(traces, key=lambda r: r.settings.speed_kmh):
            x = run.settings.v * run.t
            ax.plot(x, 1e3 * run.y[0], lw=0.8, label=f"{run.settings.speed_kmh:g} km/h")
        ax.set_xlabel("distance run (m)")
        ax.set_ylabel("leading wheelset lateral y (mm)")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig, axes
