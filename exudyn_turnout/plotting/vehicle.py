"""Figures of a full vehicle's passage: the forces of every wheelset, the bodies' motion and
suspension forces.

Draws the columns of a :class:`~exudyn_turnout.passage.results.PassageResult` of a full
vehicle (:mod:`~exudyn_turnout.passage.vehicle.body_outputs`,
:mod:`~exudyn_turnout.passage.ride_comfort`). Long runs are drawn as min/max envelopes of
at most :data:`MAX_POINTS` bins per curve (every peak kept, the drawing fast).
"""

from __future__ import annotations

import textwrap
from collections.abc import Mapping

import numpy as np

from exudyn_turnout.plotting.backend import TITLE_LINE, place_axes, pyplot

__all__ = ["MAX_POINTS", "envelope", "plot_wheelset_forces", "plot_vehicle_bodies"]

#: Bins of a curve's min/max envelope (2 points each; a 2.3 s run at 1e-4 s has 23,400 samples).
MAX_POINTS = 1000


def envelope(x: np.ndarray, y: np.ndarray, bins: int = MAX_POINTS) -> tuple:
    """A curve reduced to the minimum and maximum of each of ``bins`` consecutive groups.

    Parameters
    ----------
    x, y : numpy.ndarray
        The curve (x increasing).
    bins : int
        Groups; a curve with fewer than 2 x bins samples is returned unchanged.

    Returns
    -------
    (x, y)
        Two points per group (its minimum and maximum, in their order), so that every
        extreme of y is drawn.
    """
    x, y = np.asarray(x, float), np.asarray(y, float)
    n = x.size
    if n < 2 * bins:
        return x, y
    size = n // bins
    m = size * bins
    xs, ys = x[:m].reshape(bins, size), y[:m].reshape(bins, size)
    filled = np.where(np.isfinite(ys), ys, np.nanmean(ys) if np.isfinite(ys).any() else 0.0)
    lo, hi = np.argmin(filled, axis=1), np.argmax(filled, axis=1)
    first, second = np.minimum(lo, hi), np.maximum(lo, hi)
    rows = np.arange(bins)
    idx = np.stack([first, second], axis=1)
    out_x = xs[rows[:, None], idx].ravel()
    out_y = ys[rows[:, None], idx].ravel()
    return np.append(out_x, x[m:]), np.append(out_y, y[m:])


def _shade(ax, summary: Mapping) -> None:
    for key, colour in (("switch_region_m", "0.92"), ("crossing_region_m", "0.85")):
        region = summary.get(key)
        if isinstance(region, (list, tuple)) and len(region) == 2:
            ax.axvspan(float(region[0]), float(region[1]), color=colour, zorder=0, lw=0)


def plot_wheelset_forces(result, title: str | None = None):
    """Vertical and lateral wheel forces of every wheelset against its own x.

    One row per wheelset (front first), vertical force left, lateral force right, both
    wheels in each; the turnout's switch and crossing regions shaded (each wheelset meets
    them at its own x).

    Parameters
    ----------
    result : PassageResult
        A full vehicle's (``Fz_ws<k>_<wheel>_N``, ``Fy_ws<k>_<wheel>_N``, ``x_ws<k>_m``).
    title : str, optional

    Returns
    -------
    (figure, axes)
        Axes of shape (wheelsets, 2).

    Raises
    ------
    ValueError
        The result has no per-wheelset columns (a single wheelset).
    """
    plt = pyplot()
    cols, summary = result.columns, result.summary
    count = 0
    while f"x_ws{count + 1}_m" in cols:
        count += 1
    if count == 0:
        raise ValueError("no per-wheelset columns: a single wheelset's result")
    fig, axes = plt.subplots(count, 2, figsize=(11, 2.1 * count + 0.8), sharex=False)
    axes = np.atleast_2d(axes)
    for k in range(count):
        label = f"ws{k + 1}"
        x = cols[f"x_{label}_m"]
        for j, (q, name) in enumerate((("Fz", "vertical"), ("Fy", "lateral"))):
            ax = axes[k, j]
            _shade(ax, summary)
            for wheel, style in (("right", "-"), ("left", "--")):
                column = f"{q}_{label}_{wheel}_N"
                if column in cols:
                    ex, ey = envelope(x, np.asarray(cols[column]) / 1e3)
                    ax.plot(ex, ey, style, lw=0.7, label=f"{wheel} wheel")
            ax.set_ylabel(f"wheelset {k + 1}\n{name} (kN)")
            ax.grid(True, alpha=0.3)
            ax.set_xlim(float(np.min(x)), float(np.max(x)))
    axes[0, 0].legend(fontsize=8, loc="upper left")
    for ax in axes[-1]:
        ax.set_xlabel("x of the wheelset (m)")
    heading = title or "wheel forces of every wheelset (shaded: switch, crossing)"
    fig.suptitle(heading)
    lines = heading.count("\n") + 1
    place_axes(fig, 0.95, 0.25, 0.6, 0.25 + TITLE_LINE * lines, wspace=0.24, hspace=0.25)
    return fig, axes


def plot_vehicle_bodies(result, title: str | None = None):
    """Car body and bogie frames: motion, floor accelerations with EN 12299 weightings, and
    suspension forces, against the front wheelset's x.

    Panels: lateral and vertical displacement of the floor points and bogie centres;
    lateral (floor, car-body axes) and vertical accelerations at the floor points, thin
    the raw ones, thick the Wd / Wb weighted ones; the vertical suspension forces' change
    from the start (primary per axlebox, secondary per bogie side: the static loads are
    ~46 and ~78 kN) and the lateral ones with the bumpstops.

    Parameters
    ----------
    result : PassageResult
        A full vehicle's (body columns, :mod:`~exudyn_turnout.passage.vehicle.body_outputs`).
    title : str, optional

    Returns
    -------
    (figure, axes)
        Axes of shape (3, 2).

    Raises
    ------
    ValueError
        The result has no body columns.
    """
    plt = pyplot()
    cols = result.columns
    if "az_car_centre_mps2" not in cols:
        raise ValueError("no body columns: not a full vehicle's result")
    x = np.asarray(cols["x_m"])
    points = [n[2:-2] for n in cols if n.startswith("y_") and f"z_{n[2:-2]}_m" in cols]
    points = [p for p in points if p.startswith(("car_", "bogie"))]
    fig, axes = plt.subplots(3, 2, figsize=(12, 9), sharex=True)

    def draw(ax, name, scale=1.0, **style):
        if name in cols:
            ex, ey = envelope(x, np.asarray(cols[name]) * scale)
            ax.plot(ex, ey, **style)

    for point in points:
        draw(axes[0, 0], f"y_{point}_m", 1e3, lw=0.8, label=point)
        draw(axes[0, 1], f"z_{point}_m", 1e3, lw=0.8, label=point)
    axes[0, 0].set_ylabel("lateral displacement (mm)")
    axes[0, 1].set_ylabel("vertical displacement (mm)\nfrom the static state")
    for point in ("car_front", "car_centre", "car_rear"):
        (line,) = axes[1, 0].plot([], [])
        colour = line.get_color()
        draw(axes[1, 0], f"ay_floor_{point}_mps2", lw=0.4, alpha=0.5, color=colour)
        draw(axes[1, 0], f"awd_y_{point}_mps2", lw=1.4, color=colour, label=f"{point} Wd")
        draw(axes[1, 1], f"az_{point}_mps2", lw=0.4, alpha=0.5, color=colour)
        draw(axes[1, 1], f"awb_z_{point}_mps2", lw=1.4, color=colour, label=f"{point} Wb")
    axes[1, 0].set_ylabel("floor lateral acc. (m/s$^2$)")
    axes[1, 1].set_ylabel("floor vertical acc. (m/s$^2$)")
    for name in cols:
        start = float(np.asarray(cols[name])[0]) if name.startswith("Fz_") else 0.0
        for stage, width in (("primary", 0.6), ("secondary", 1.4)):
            if not name.startswith((f"Fz_{stage}_", f"Fy_{stage}_")):
                continue
            label = f"{name[:2]} {name[len('Fz_') : -2]}".replace("_", " ")
            ax = axes[2, 0] if name.startswith("Fz_") else axes[2, 1]
            ls = "-" if stage == "primary" else "--"
            ex, ey = envelope(x, (np.asarray(cols[name]) - start) / 1e3)
            ax.plot(ex, ey, lw=width, ls=ls, label=label)
        if name.startswith("Fy_bumpstop_"):
            draw(axes[2, 1], name, 1e-3, lw=1.6, ls=":", label=name[3:-2].replace("_", " "))
    axes[2, 0].set_ylabel("vertical suspension force,\nchange from the start (kN)")
    axes[2, 1].set_ylabel("lateral suspension force (kN)")
    for ax in axes.ravel():
        _shade(ax, result.summary)
        ax.grid(True, alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=6, ncol=3, loc="upper left")  # "best" costs seconds
    axes[0, 0].set_xlim(float(x.min()), float(x.max()))
    for ax in axes[-1]:
        ax.set_xlabel("x of the front wheelset (m)")
    note = str(result.summary.get("ride_comfort_note") or "")
    heading = title or "car body and bogies (thin: raw, thick: EN 12299 weighted)"
    text = "\n".join([heading, *textwrap.wrap(note, 150)])
    fig.suptitle(text, fontsize=9)
    lines = text.count("\n") + 1
    place_axes(fig, 0.9, 0.25, 0.6, 0.25 + 0.16 * lines, wspace=0.2, hspace=0.1)
    return fig, axes
