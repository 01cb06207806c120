"""The validation report's PNG figures, drawn by :mod:`exudyn_turnout.plotting.curves`.

:func:`write_figures` takes a built :class:`~exudyn_turnout.report.metrics.Report` and writes
each figure it has data for into the output directory; it returns name -> file name
(relative to that directory) for the Markdown to embed. Matplotlib stays inside
:mod:`~exudyn_turnout.plotting.curves`.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

__all__ = [
    "write_model_figure",
    "write_figures",
    "receptance_panels",
    "force_panels",
    "force_grid",
    "crossing_window",
    "stiffness_panels",
]

#: One force panel: title, model -> PassageResult, column, x range (m).
_Panel = tuple[str, Mapping, str, tuple[float, float]]
#: m, before / after the wheel's dip shown in a crossing panel when the report has no settings.
_DEFAULT_CROSSING_WINDOW = (0.8, 2.2)


def receptance_panels(report, direction: str) -> list[tuple[str, Mapping, float]]:
    """(title, model -> Receptance, pinned-pinned Hz) per rail for one direction.

    Parameters
    ----------
    report : Report
    direction : {"vertical", "lateral"}

    Returns
    -------
    list of (str, dict, float)
    """
    cases = report.typed_metrics.receptance.cases
    return [
        (f"{case} at x = {c.x_m:.2f} m", report.receptances[case], c.pinned_pinned_hz)
        for case, c in cases.items()
        if c.direction == direction
    ]


def crossing_window(report) -> tuple[float, float]:
    """x range (m) of the crossing panels: around the crossing receptance position (the dip).

    How far before and after: the turnout file's ``report.crossing_plot_window``.

    Parameters
    ----------
    report : Report

    Returns
    -------
    (float, float)
        m, x_from and x_to.
    """
    x = report.typed_metrics.receptance.positions["crossing rail"].x_m
    settings = getattr(report, "settings", None)
    window = settings.crossing_plot_window if settings is not None else _DEFAULT_CROSSING_WINDOW
    before, after = window
    return x - before, x + after


def force_panels(report, route: str) -> list[tuple[str, Mapping, str, tuple[float, float]]]:
    """(title, model -> PassageResult, column, x range) per signal of a route with data.

    Vertical and lateral force at the switch and at the crossing (the route's
    ``all_signals``; older metrics: its plotted ``signals``), skipping the regions outside
    the passage's x range.

    Parameters
    ----------
    report : Report
    route : str
        A route of the report.

    Returns
    -------
    list of (str, dict, str, (float, float))
    """
    return [panel for row in force_grid(report, route) for panel in row if panel is not None]


def force_grid(
    report, route: str
) -> list[list[tuple[str, Mapping, str, tuple[float, float]] | None]]:
    """The panels of a route's force figure: rows Fz, Fy; columns switch, crossing.

    Parameters
    ----------
    report : Report
    route : str
        A route of the report.

    Returns
    -------
    list of list
        Per force ("Fz", "Fy") the panels at the switch and the crossing, each
        (title, model -> PassageResult, column, x range) or None (outside the x range, or a
        signal the metrics do not have).
    """
    p = report.typed_metrics.passage
    lo, hi = p.x_range_m
    rt = p.routes[route]
    wheel = rt.wheel or "right"
    signals = set(rt.all_signals if rt.all_signals is not None else rt.signals)
    grid: list[list[_Panel | None]] = []
    for quantity, what in (("Fz", "vertical"), ("Fy", "lateral (+ left)")):
        row: list[_Panel | None] = []
        for region in ("switch", "crossing"):
            x0, x1 = crossing_window(report) if region == "crossing" else p.regions_m[region]
            x0, x1 = max(x0, lo), min(x1, hi)
            if f"{quantity}_{region}" not in signals or not x1 > x0:
                row.append(None)
                continue
            title = f"{route}, {p.speeds_kmh[route]:g} km/h: {what} force, {wheel} wheel, {region}"
            column = f"{quantity}_{wheel}_N"
            results = {
                m: r
                for m, r in report.passages[route].items()
                if column in r.columns and np.isfinite(r.columns[column]).any()
            }
            row.append((title, results, column, (x0, x1)))
        if any(panel is not None for panel in row):
            grid.append(row)
    return grid


def write_figures(report, out_dir: str | Path, dpi: int = 100) -> dict[str, str]:
    """Write the report's figures into out_dir; name -> file name.

    Parameters
    ----------
    report : Report
    out_dir : str or Path
    dpi : int

    Returns
    -------
    dict
        Figure name -> file name.
    """
    from exudyn_turnout.plotting.curves import (
        plot_force_grid,
        plot_receptance_agreement,
        save_figure,
    )

    out, files = Path(out_dir), {}
    agree = report.config.criteria.agree_db
    for direction in ("vertical", "lateral"):
        curves = receptance_panels(report, direction)
        if curves:
            fig, _ = plot_receptance_agreement(curves, agree_db=agree)
            files[f"receptance_{direction}"] = _save(
                fig, out, f"receptance_{direction}.png", dpi, save_figure
            )
    for route in report.passages:
        grid = force_grid(report, route)
        if grid:
            labels = [_ylabel(row) for row in grid]
            fig, _ = plot_force_grid(grid, labels)
            files[f"forces_{route}"] = _save(fig, out, f"forces_{route}.png", dpi, save_figure)
    files.update(_stiffness_figure(report, out, dpi))
    return files


def write_model_figure(report, turnout, out_dir: str | Path, dpi: int = 100) -> dict[str, str]:
    """The three-layer cross-section at the crossing receptance point, as it is built.

    Parameters
    ----------
    report : Report
        Gives the crossing rail's receptance position and route.
    turnout : Turnout
        The turnout the report was computed for.
    out_dir : str or Path
        Directory of the report.
    dpi : int
        Resolution of the PNG.

    Returns
    -------
    dict
        ``{"model": "model_cross_section.png"}``, or empty if the report has no receptance.
    """
    from exudyn_turnout.corunning.parameters import co_running_parameters
    from exudyn_turnout.inputs.routes import load_route
    from exudyn_turnout.inputs.vehicle import load_vehicle
    from exudyn_turnout.plotting.curves import save_figure
    from exudyn_turnout.plotting.model import draw_cross_section

    receptance = report.typed_metrics.receptance
    position = receptance.positions.get("crossing rail")
    if position is None:
        return {}
    x = float(position.x_m)
    route = receptance.route
    params = co_running_parameters(turnout, x=x, layers=3)
    ax = draw_cross_section(
        params, x, route=load_route(turnout, route) if route else None, vehicle=load_vehicle()
    )
    return {"model": _save(ax.figure, Path(out_dir), "model_cross_section.png", dpi, save_figure)}


def _ylabel(row) -> str:
    """y label of a row of force panels: vertical, or lateral with its sign."""
    column = next(p[2] for p in row if p is not None)
    return "Fz on rail (kN)" if column.startswith("Fz") else "Fy on rail, + left (kN)"


def _save(fig: Any, out: Path, name: str, dpi: int, save_figure) -> str:
    save_figure(fig, out / name, dpi=dpi)
    return name


def stiffness_panels(report) -> list[tuple[str, list]]:
    """Vertical and lateral panels: FE per rail (points), fits, the paper's Eqs 10/14, the 2-layer
    model's receptance slot (r2).

    Parameters
    ----------
    report : Report
        With a stiffness profile (``report.stiffness``).

    Returns
    -------
    list of (str, list)
        Title and series (label, x, y, kind) per panel.
    """
    stiffness = report.typed_metrics.stiffness
    data, paper = report.stiffness, stiffness.paper
    profile, fits = data["profile"], data["fits"]
    panels = []
    for direction, fit, eq, idx in (
        ("vertical", fits.K_sw, ("Eq 10 K_sw", "K_sw_N_per_m"), 1),
        ("lateral", fits.K_sh, ("Eq 14 K_sh", "K_sh_N_per_m"), 2),
    ):
        series = [
            (f"FE {rail}", profile.of(rail)[0], profile.of(rail)[idx], "points")
            for rail in profile.rails
        ]
        xf = [fit.x_min + (fit.x_max - fit.x_min) * k / 50 for k in range(51)]
        series.append(
            (
                f"fit of FE {fit.rail} ({fit.x_min:g}-{fit.x_max:g} m)",
                xf,
                [fit(x) for x in xf],
                "fit",
            )
        )
        series.append((f"paper {eq[0]}", paper.x_m, getattr(paper, eq[1]), "paper"))
        slot = stiffness.co_running_slot or "r2"
        series.append(
            (
                f"2-layer co-running {slot}, 1/|H(1 Hz)|",
                data["co_running_x"],
                data["co_running"][direction],
                "model",
            )
        )
        panels.append((f"{direction} static stiffness 1/|H(1 Hz)|", series))
    return panels


def _stiffness_figure(report, out: Path, dpi: int) -> dict[str, str]:
    """The FE stiffness profile figure, when the report has a profile (``report.stiffness``)."""
    if not report.stiffness:
        return {}
    from exudyn_turnout.plotting.curves import plot_stiffness_series, save_figure

    fig, _ = plot_stiffness_series(stiffness_panels(report))
    return {"stiffness": _save(fig, out, "stiffness.png", dpi, save_figure)}
