"""Plots of computed results: receptances, passage forces, stiffness along the turnout.

Each function takes data objects (e.g. :class:`~exudyn_turnout.receptance.Receptance`),
draws into given axes or a new figure, and returns ``(figure, axes)``; saving is left to
the caller (``fig.savefig(path)``).
"""

from __future__ import annotations

import math
import textwrap
from collections.abc import Sequence

import numpy as np

from exudyn_turnout.plotting.backend import TITLE_LINE, place_axes, pyplot, save_options
from exudyn_turnout.receptance import Receptance

__all__ = [
    "receptance_label",
    "plot_receptance",
    "passage_label",
    "plot_passage_forces",
    "FIGURE_POINTS",
    "decimate_min_max",
    "missing_region_note",
    "plot_receptance_agreement",
    "plot_force_signals",
    "plot_force_grid",
    "plot_stiffness_series",
    "save_figure",
    "plot_stiffness_profile",
]


def receptance_label(r: Receptance) -> str:
    """Legend text of a receptance: model, rail, direction and position.

    Parameters
    ----------
    r : Receptance
        The curve to name.

    Returns
    -------
    str
        E.g. ``"3-layer r2 vertical at x = 45.8 m"`` (no position if ``r.x`` is NaN).
    """
    position = "" if math.isnan(r.x) else f" at x = {r.x:g} m"
    return f"{r.model} {r.rail} {r.direction}{position}".strip()


def plot_receptance(
    receptances: Receptance | Sequence[Receptance],
    ax=None,
    *,
    phase: bool = False,
    labels: Sequence[str] | None = None,
    title: str | None = None,
):
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
        Title of the magnitude axes.

    Returns
    -------
    (Figure, tuple of Axes)
        The figure and its (magnitude[, phase]) axes.
    """
    curves = [receptances] if isinstance(receptances, Receptance) else list(receptances)
    axes = _axes(ax, phase)
    names = list(labels) if labels is not None else [receptance_label(r) for r in curves]
    for curve, name in zip(curves, names):
        axes[0].loglog(curve.frequency_hz, curve.magnitude, label=name)
        if phase:
            axes[1].semilogx(curve.frequency_hz, np.degrees(np.angle(curve.H)), label=name)
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
    plt = pyplot()
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
    """Legend text of a passage: layers (or model), parameter source and speed.

    Parameters
    ----------
    result : PassageResult
        The run to name (its settings and ``summary["model"]``).

    Returns
    -------
    str
        E.g. ``"3-layer, derived, 100 km/h"`` or ``"FE, 100 km/h"``.
    """
    settings = result.settings
    model = result.summary.get("model", f"{settings.layers}-layer")
    if model == "FE":  # the FE track takes Table 1 directly: no parameter source
        return f"FE, {settings.speed_kmh:g} km/h"
    return f"{model}, {settings.source}, {settings.speed_kmh:g} km/h"


#: Points per curve and panel a passage figure draws at most (:func:`decimate_min_max`).
FIGURE_POINTS = 2000


def decimate_min_max(x, y, points: int = FIGURE_POINTS) -> tuple[np.ndarray, np.ndarray]:
    """At most ``points`` samples of a curve for a figure, keeping every local extreme.

    The samples are split into ``points // 2`` consecutive buckets of equal count; of each
    bucket the smallest and the largest value are kept, in their order. The drawn line
    then reaches every peak of the full curve (a plain stride would miss a peak between
    two kept samples). Curves of at most ``points`` samples are returned as they are.
    Measured on the default passage (23,402 samples): no measurable change in the time
    of a PNG (Agg simplifies dense paths itself); what it saves is the size of vector
    figures (PDF, SVG) and of long runs' figures.

    Parameters
    ----------
    x, y : array_like
        The curve (same length); NaN in ``y`` is kept where a whole bucket is NaN.
    points : int
        Most samples returned (at least 2).

    Returns
    -------
    x, y : ndarray
        The kept samples, in the original order.
    """
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    n, buckets = len(y), max(int(points) // 2, 1)
    if n <= max(int(points), 2):
        return x, y
    size = -(-n // buckets)  # ceil
    padded = np.full(buckets * size, np.nan)
    padded[:n] = y
    table = padded.reshape(buckets, size)
    finite = np.isfinite(table)
    lowest = np.where(finite, table, np.inf).argmin(axis=1)
    highest = np.where(finite, table, -np.inf).argmax(axis=1)
    start = np.arange(buckets) * size
    keep = np.unique(np.concatenate([start + lowest, start + highest]))
    keep = keep[keep < n]
    return x[keep], y[keep]


def _run_range(result) -> tuple[float, float]:
    """m, the first and last x of a run (the front wheelset's for a full vehicle)."""
    x = np.asarray(result.columns["x_m"], dtype=float)
    return float(np.nanmin(x)), float(np.nanmax(x))


def missing_region_note(results, where: str) -> str | None:
    """Why a passage figure has no panel of a region, or None where a run covers it.

    Parameters
    ----------
    results : sequence of PassageResult
        The runs of one figure.
    where : {"switch", "crossing"}
        The region (``summary["<where>_region_m"]``).

    Returns
    -------
    str or None
        E.g. ``"switch 0-10 m outside the run's x range 40-50 m"`` when no run has a
        sample inside the region, None otherwise.
    """
    region = results[0].summary.get(f"{where}_region_m")
    if not isinstance(region, (list, tuple)) or len(region) != 2:
        return f"{where}: no region in the summary"
    x0, x1 = float(region[0]), float(region[1])
    for result in results:
        x = np.asarray(result.columns["x_m"], dtype=float)
        if np.count_nonzero((x >= x0) & (x <= x1)) >= 2:
            return None
    lo = min(_run_range(r)[0] for r in results)
    hi = max(_run_range(r)[1] for r in results)
    whose = "the front wheelset's" if "x_ws2_m" in results[0].columns else "the run's"
    return f"{where} {x0:g}-{x1:g} m outside {whose} x range {lo:.4g}-{hi:.4g} m"


def _passage_style(result) -> dict:
    """Line style of a passage in an overlay: by track model (:func:`_style`), thin."""
    model = result.summary.get("model", f"{result.settings.layers}-layer")
    style = dict(_style(str(model)))
    style.setdefault("lw", 1.0)
    return style


def plot_passage_forces(
    results,
    wheel: str = "right",
    labels=None,
    title: str | None = None,
    points: int = FIGURE_POINTS,
):
    """Contact forces of passages against x, at the switch and at the crossing (Figs 7, 8 layout).

    A region no run reaches has no panel; the figure says why below its title (e.g.
    "switch 0-10 m outside the run's x range 40-50 m"). A run reaching neither region is
    drawn over its whole x range, with that note. Each curve is drawn with at most
    ``points`` samples per panel (:func:`decimate_min_max`: every peak kept).

    Parameters
    ----------
    results : sequence of PassageResult
        Runs to overlay (e.g. 2-layer, 3-layer, FE reference); styled by track model
        (FE black, 2-layer blue dashed, 3-layer red).
    wheel : {"right", "left"}
        Which wheel's forces (columns ``Fz_<wheel>_N``, ``Fy_<wheel>_N``; a full vehicle's
        front wheelset).
    labels : sequence of str, optional
        Legend entries; default :func:`passage_label`.
    title : str, optional
        Title of the figure.
    points : int
        Most samples per curve and panel.

    Returns
    -------
    (figure, axes)
        A 2 x n grid (n = regions reached, or 1): rows vertical (Fz) and lateral (Fy)
        force on the rail, columns the switch and crossing regions named in the results'
        summaries.
    """
    plt = pyplot()
    results = list(results)
    if not results:
        raise ValueError("plot_passage_forces: no results to draw")
    names = list(labels) if labels is not None else [passage_label(r) for r in results]
    notes = {where: missing_region_note(results, where) for where in ("switch", "crossing")}
    columns: list[tuple[str, tuple[float, float]]] = [
        (where, tuple(results[0].summary[f"{where}_region_m"]))
        for where, note in notes.items()
        if note is None
    ]
    if not columns:
        lo = min(_run_range(r)[0] for r in results)
        hi = max(_run_range(r)[1] for r in results)
        columns = [(f"x {lo:.4g}-{hi:.4g} m", (lo, hi))]
    fig, axes = plt.subplots(
        2, len(columns), figsize=(5.0 * len(columns), 6.4), sharex="col", squeeze=False
    )
    for row, (quantity, unit) in enumerate((("Fz", "vertical"), ("Fy", "lateral"))):
        for col, (where, (x0, x1)) in enumerate(columns):
            ax = axes[row, col]
            for result, name in zip(results, names):
                x, force = result.columns["x_m"], result.columns[f"{quantity}_{wheel}_N"]
                sel = (x >= x0) & (x <= x1)
                xs, fs = decimate_min_max(x[sel], force[sel] / 1e3, points)
                ax.plot(xs, fs, label=name, **_passage_style(result))
            ax.grid(True, alpha=0.3)
            ax.set_title(f"{unit} force, {wheel} wheel, {where}", fontsize="medium")
            if col == 0:
                ax.set_ylabel(f"{quantity} on rail (kN)")
            if row == 1:
                ax.set_xlabel("x from switch toe (m)")
    axes[0, 0].legend(fontsize="small")
    missing = [note for note in notes.values() if note is not None]
    width = 5.0 * len(columns)  # in
    heading = "\n".join(
        textwrap.fill(line, int(13 * width))  # ~13 characters per inch: inside the figure
        for line in ([title] if title else []) + [f"no panel: {n}" for n in missing]
    )
    if heading:
        fig.suptitle(heading, fontsize="medium")
    lines = heading.count("\n") + 1 if heading else 0
    place_axes(fig, 0.9, 0.15, 0.58, 0.42 + TITLE_LINE * lines, wspace=0.15, hspace=0.2)
    return fig, axes


# --- validation report figures (exudyn_turnout.report.metrics) ---------------------------------


def _style(model: str) -> dict:
    """Line style of a model in the validation report's figures.

    FE black, 2-layer blue dashed, 3-layer red.
    """
    styles = {
        "FE": dict(color="black", lw=1.6),
        "2-layer": dict(color="tab:blue", lw=1.1, ls="--"),
        "3-layer": dict(color="tab:red", lw=1.1),
    }
    return styles.get(model, {})


def plot_receptance_agreement(
    panels,
    reference: str = "FE",
    agree_db: float = 3.0,
    range_edges: Sequence[float] = (125.0, 500.0),
):
    """Receptances of several models and their level difference from a reference, side by side.

    Parameters
    ----------
    panels : sequence of (str, mapping, float or None)
        Per column: title, model name -> Receptance (same frequencies), and a frequency
        (Hz) to mark with a dotted line (e.g. the pinned-pinned resonance) or None.
    reference : str
        Model the level difference 20 log10(|H| / |H_ref|) (dB) is taken against.
    agree_db : float
        dB, shaded band +- agree_db in the difference plot.
    range_edges : sequence of float
        Hz, frequencies drawn as thin vertical lines (the report's range limits).

    Returns
    -------
    (Figure, ndarray of Axes)
        2 x n: magnitude |H| (m/N) on top, difference (dB) below.
    """
    plt = pyplot()
    panels = list(panels)
    fig, axes = plt.subplots(
        2,
        len(panels),
        figsize=(5.0 * len(panels), 6.2),
        sharex=True,
        height_ratios=(2, 1),
        squeeze=False,
    )
    for col, (title, curves, mark) in enumerate(panels):
        top, bottom = axes[0, col], axes[1, col]
        ref = curves[reference]
        for name, curve in curves.items():
            top.loglog(curve.frequency_hz, curve.magnitude, label=name, **_style(name))
            if name != reference:
                bottom.semilogx(
                    curve.frequency_hz,
                    20 * np.log10(curve.magnitude / ref.magnitude),
                    label=name,
                    **_style(name),
                )
        bottom.axhspan(-agree_db, agree_db, color="0.85", zorder=0)
        for ax in (top, bottom):
            for edge in range_edges:
                ax.axvline(edge, color="0.6", lw=0.6)
            if mark is not None:
                ax.axvline(mark, color="tab:green", ls=":", lw=1.2)
            ax.grid(True, which="both", alpha=0.3)
        top.set_title(title, fontsize="medium")
        bottom.set_xlabel("frequency (Hz)")
        bottom.set_ylim(-20, 20)
    axes[0, 0].set_ylabel("receptance |H| (m/N)")
    axes[1, 0].set_ylabel(f"20 log10(|H|/|H_{reference}|) (dB)")
    axes[0, 0].legend(fontsize="small")
    fig.tight_layout()
    return fig, axes


def plot_force_signals(panels, ylabel: str = "force on rail (kN)"):
    """Contact-force histories of several models along x, one panel per signal.

    Parameters
    ----------
    panels : sequence of (str, mapping, str, (float, float))
        Per panel: title, model name -> PassageResult, column name (e.g. "Fz_right_N")
        and the x range (m) to show.
    ylabel : str
        Label of the y axis (the forces are drawn in kN).

    Returns
    -------
    (Figure, ndarray of Axes)
        One row of panels.
    """
    plt = pyplot()
    panels = list(panels)
    fig, axes = plt.subplots(1, len(panels), figsize=(5.0 * len(panels), 3.6), squeeze=False)
    for ax, (title, results, column, (x0, x1)) in zip(axes[0], panels):
        for name, result in results.items():
            x, force = result.columns["x_m"], result.columns[column]
            sel = (x >= x0) & (x <= x1)
            ax.plot(x[sel], force[sel] / 1e3, label=name, **_style(name))
        ax.set_xlim(x0, x1)
        ax.set_title(title, fontsize="medium")
        ax.set_xlabel("x from switch toe (m)")
        ax.grid(True, alpha=0.3)
    axes[0, 0].set_ylabel(ylabel)
    axes[0, 0].legend(fontsize="small")
    fig.tight_layout()
    return fig, axes


def plot_force_grid(rows, ylabels=None, missing: str = "outside the passage's x range"):
    """Contact-force histories of several models along x in a grid of panels.

    Parameters
    ----------
    rows : sequence of sequence of (str, mapping, str, (float, float)) or None
        Per row (e.g. vertical, lateral) and column (e.g. switch, crossing): title, model
        name -> PassageResult, column name (e.g. "Fy_right_N") and the x range (m) to show;
        None leaves that panel empty with the text ``missing``.
    ylabels : sequence of str, optional
        y-axis label per row (the forces are drawn in kN); default "force on rail (kN)".
    missing : str
        Text of an empty panel.

    Returns
    -------
    (Figure, ndarray of Axes)
        len(rows) x (longest row) axes.
    """
    plt = pyplot()
    rows = [list(r) for r in rows]
    n_rows, n_cols = len(rows), max(len(r) for r in rows)
    fig, axes = plt.subplots(n_rows, n_cols, figsize=(5.0 * n_cols, 3.4 * n_rows), squeeze=False)
    labels = list(ylabels) if ylabels is not None else ["force on rail (kN)"] * n_rows
    legend = None
    for i, row in enumerate(rows):
        for j in range(n_cols):
            ax = axes[i, j]
            panel = row[j] if j < len(row) else None
            if panel is None:
                ax.text(0.5, 0.5, missing, ha="center", va="center", transform=ax.transAxes)
                ax.set_xticks([])
                ax.set_yticks([])
                continue
            title, results, column, (x0, x1) = panel
            for name, result in results.items():
                x, force = result.columns["x_m"], result.columns[column]
                sel = (x >= x0) & (x <= x1)
                ax.plot(x[sel], force[sel] / 1e3, label=name, **_style(name))
            ax.set_xlim(x0, x1)
            ax.set_title(title, fontsize="medium")
            ax.grid(True, alpha=0.3)
            if i == n_rows - 1:
                ax.set_xlabel("x from switch toe (m)")
            if j == 0 or axes[i, 0].get_ylabel() == "":
                ax.set_ylabel(labels[i])
            if legend is None and results:
                legend = ax
    if legend is not None:
        legend.legend(fontsize="small")
    fig.tight_layout()
    return fig, axes


def plot_stiffness_series(panels, ylabel: str = "static stiffness (MN/m)"):
    """Stiffness along x: one panel per direction, several labelled series each.

    Parameters
    ----------
    panels : sequence of (str, sequence of (str, array, array, str))
        Per panel (stacked, shared x): title and series (label, x in m, K in N/m, kind);
        kind "points" (markers, e.g. FE values at the sleepers), "fit", "paper" or "model"
        (lines: solid, dashed, dotted).
    ylabel : str
        Label of every panel's y axis (the stiffness is drawn in MN/m).

    Returns
    -------
    (Figure, ndarray of Axes)
        One column of panels.
    """
    plt = pyplot()
    panels = list(panels)
    styles = {
        "points": dict(ls="none", marker=".", ms=3),
        "fit": dict(color="black", lw=1.6),
        "paper": dict(color="black", lw=1.4, ls="--"),
        "model": dict(color="tab:red", lw=1.2, ls=":"),
    }
    fig, axes = plt.subplots(
        len(panels), 1, figsize=(9.0, 3.4 * len(panels)), sharex=True, squeeze=False
    )
    for ax, (title, series) in zip(axes[:, 0], panels):
        for label, x, K, kind in series:
            ax.plot(x, np.asarray(K) / 1e6, label=label, **styles.get(kind, {}))
        ax.set_title(title, fontsize="medium")
        ax.set_ylabel(ylabel)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize="x-small", ncol=2)
    axes[-1, 0].set_xlabel("x from switch toe (m)")
    fig.tight_layout()
    return fig, axes


def save_figure(fig, path, dpi: int = 100) -> None:
    """Save a figure to ``path`` (format from the suffix) and close it.

    Parameters
    ----------
    fig : matplotlib Figure
        The figure; closed afterwards.
    path : str or Path
        File to write; the suffix (e.g. ``.png``) sets the format.
    dpi : int
        Resolution (dots per inch) of raster formats.
    """
    plt = pyplot()
    fig.savefig(path, dpi=dpi, **save_options(path))
    plt.close(fig)


# --- FE static stiffness along the turnout (exudyn_turnout.fe) ----------------------------


def plot_stiffness_profile(profile, fits=None, turnout=None, axes=None):
    """The analogue of the paper's Fig. 1(b,c): static stiffness of every rail along x.

    Parameters
    ----------
    profile : exudyn_turnout.fe.stiffness.StiffnessProfile
        FE values at every sleeper (one marker shape and colour per rail, so rails with
        equal values stay visible).
    fits : exudyn_turnout.fe.fits.TurnoutFits, optional
        Fitted K_sw (vertical) and K_sh (lateral), drawn over their x range (solid black).
    turnout : exudyn_turnout.inputs.turnout.Turnout, optional
        Its K_sw (Eq 10) and K_sh (Eq 14), drawn dashed: K_sw from its x_min to the end of
        the first zone (held constant beyond its x_max, as the paper says), K_sh over its
        range.
    axes : (Axes, Axes), optional
        Vertical and lateral axes; a new figure if None.

    Returns
    -------
    (Figure, tuple of Axes)
        The figure and its (vertical, lateral) axes.
    """
    plt = pyplot()
    if axes is None:
        _, pair = plt.subplots(2, 1, figsize=(12.0, 8.0), sharex=True)
        axes = tuple(pair)
    markers = "o^sDvx+P*<>"
    for i, rail in enumerate(profile.rails):
        x, kz, ky = profile.of(rail)
        style = dict(
            ls="none",
            marker=markers[i % len(markers)],
            ms=3.5,
            mfc="none",
            mew=0.9,
            label=f"{rail}: {profile.rail_names.get(rail, rail)}",
        )
        for ax, K in zip(axes, (kz, ky)):
            ax.plot(x, K / 1e6, **style)
    if fits is not None:
        for ax, fit, eq in zip(axes, (fits.K_sw, fits.K_sh), ("Eq 10", "Eq 14")):
            xs = np.linspace(fit.x_min, fit.x_max, 200)
            ax.plot(
                xs,
                [fit(v) / 1e6 for v in xs],
                color="black",
                lw=1.6,
                label=f"FE fit, {eq} analogue ({fit.rail}, R$^2$ = {fit.r_squared:.2f})",
            )
    if turnout is not None:
        spans = (
            (turnout.K_sw.x_min, turnout.zones[0].x_end),
            (turnout.K_sh.x_min, turnout.K_sh.x_max),
        )
        for ax, poly, (x_from, x_to), eq in zip(
            axes, (turnout.K_sw, turnout.K_sh), spans, ("Eq 10 (paper)", "Eq 14 (paper)")
        ):
            xs = np.linspace(x_from, x_to, 200)
            ax.plot(xs, [poly(v) / 1e6 for v in xs], color="black", lw=1.4, ls="--", label=eq)
    for ax, title in zip(
        axes,
        ("(b) vertical static stiffness 1/|H(1 Hz)|", "(c) lateral static stiffness 1/|H(1 Hz)|"),
    ):
        ax.set_title(title, fontsize="medium")
        ax.set_ylabel("stiffness (MN/m)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize="x-small", loc="upper left", bbox_to_anchor=(1.01, 1.0))
    axes[-1].set_xlabel("x from switch toe (m)")
    axes[0].figure.tight_layout()
    return axes[0].figure, axes
