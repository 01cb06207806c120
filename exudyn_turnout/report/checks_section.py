"""Section 5 of the validation report: convergence and static checks.

Peak forces of the co-running passages at the report's time step and at half of it
(:func:`convergence_metrics`); static wheel loads at the start of every passage against
the vehicle's, and the co-running static stiffness against FE's (:func:`static_checks`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

from exudyn_turnout.inputs.routes import load_route
from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.inputs.vehicle import load_vehicle
from exudyn_turnout.report import agreement as ag
from exudyn_turnout.report.config import ReportConfig
from exudyn_turnout.report.criteria import Criteria
from exudyn_turnout.report.metrics_types import ReceptanceMetrics
from exudyn_turnout.report.passage_api import PassageResult
from exudyn_turnout.report.passages import (
    peak_key,
    run_passage,
    signal_key,
    summary_float,
    vehicle_mass,
    vehicle_static_load,
)
from exudyn_turnout.report.settings import (
    ReportSettings,
    report_settings,
)

__all__ = ["convergence_metrics", "static_checks"]


def convergence_metrics(
    turnout: Turnout,
    passages: Mapping[str, Mapping[str, PassageResult]],
    config: ReportConfig,
    settings: ReportSettings | None = None,
) -> dict[str, Any]:
    """Peak forces of the co-running passages at the report's time step and at half of it.

    Parameters
    ----------
    turnout : Turnout
    passages : mapping
        route -> model -> PassageResult of :func:`passage_section`.
    config : ReportConfig
        Resolved; ``time_step`` is halved.
    settings : ReportSettings, optional
        The report routes' signals and wheels (default: the turnout's).

    Returns
    -------
    dict
        Per run and signal the peaks at h and h/2 and their relative change.
    """
    settings = settings or report_settings(turnout)
    out: dict[str, Any] = {
        "time_step_s": config.time_step,
        "half_step_s": 0.5 * config.time_step,
        "runs": {},
    }
    for rr in settings.routes:
        route = rr.name
        for layers in (2, 3):
            base = passages[route][
                f"{layers}-layer"
            ]  # the report's run, same settings but the step
            half = run_passage(
                turnout,
                config,
                route,
                f"{layers}-layer",
                replace(base.settings, time_step=0.5 * config.time_step),
            )
            peaks = {}
            for q, r in rr.signals:
                k = peak_key(q, r, rr.wheel)
                a, b = summary_float(base.summary, k), summary_float(half.summary, k)
                peaks[signal_key(q, r)] = {
                    "h_N": a,
                    "h_half_N": b,
                    "relative_change": ag.relative_difference(b, a),
                }
            out["runs"][f"{route}, {layers}-layer"] = peaks
    worst = [
        abs(p["relative_change"])
        for run in out["runs"].values()
        for p in run.values()
        if math.isfinite(p["relative_change"])
    ]
    out["max_relative_change"] = max(worst) if worst else math.nan
    out["converged"] = out["max_relative_change"] <= config.criteria.converged if worst else None
    return out


def static_checks(
    turnout: Turnout,
    passages: Mapping[str, Mapping[str, PassageResult]],
    receptance: ReceptanceMetrics,
    criteria: Criteria,
    vehicle: str = "wheelset",
) -> dict[str, Any]:
    """Static wheel loads at the start of every passage vs the vehicle's static wheel load.

    The single wheelset's is (m_w + m_s) g / 2, the full vehicle's M g / 8 (front wheelset).
    And the co-running models' static stiffness relative to FE's.

    The criterion is on the mean of the two wheels (vertical equilibrium of the vehicle);
    each wheel's own difference (the split between them) is reported beside it.

    Parameters
    ----------
    turnout : Turnout
    passages : mapping
        route -> model -> PassageResult of
        :func:`~exudyn_turnout.report.passages.passage_section`.
    receptance : ReceptanceMetrics
        The receptance section (its static stiffness ratios to FE).
    criteria : Criteria
        ``static_tolerance``.
    vehicle : {"full", "wheelset"}
        The report's vehicle.

    Returns
    -------
    dict
        JSON-ready: the expected and measured static wheel loads, whether they balance, the
        rails' y at the passages' starts, the static stiffness ratios.
    """
    v = load_vehicle()
    expected = vehicle_static_load(vehicle)
    loads = {}
    for route, res in passages.items():
        for m, r in res.items():
            right, left = (
                summary_float(r.summary, "static_wheel_load_N"),
                summary_float(r.summary, "static_wheel_load_left_N"),
            )
            loads[f"{route}, {m}"] = {
                "right_N": right,
                "left_N": left,
                "mean_N": 0.5 * (right + left),
                "right_relative": ag.relative_difference(right, expected),
                "left_relative": ag.relative_difference(left, expected),
                "mean_relative": ag.relative_difference(0.5 * (right + left), expected),
            }
    ok = all(abs(x["mean_relative"]) <= criteria.static_tolerance for x in loads.values())
    stiff = {
        case: {m: c.models[m].static_stiffness_ratio_to_FE for m in ("2-layer", "3-layer")}
        for case, c in receptance.cases.items()
    }
    starts: dict[str, float] = {}
    for route, res in passages.items():
        if res:
            x_start = next(iter(res.values())).settings.x_start
            assert x_start is not None  # the report's passages start at config.passage_x[0]
            starts[route] = x_start
    rail_y = {
        route: {
            k: float(y)
            for k, y in load_route(turnout, route).zone(turnout.zone_at(x)).rail_y.items()
        }
        for route, x in starts.items()
    }
    return {
        "vehicle": vehicle,
        "m_w_kg": v.m_w,
        "m_s_kg": v.m_s,
        "vehicle_mass_kg": vehicle_mass(vehicle),
        "expected_static_wheel_load_N": expected,
        "static_wheel_load": loads,
        "static_wheel_load_ok": ok,
        "start_x_m": starts,
        "start_rail_y_m": rail_y,
        "max_split_relative": max(
            (max(abs(x["right_relative"]), abs(x["left_relative"])) for x in loads.values()),
            default=math.nan,
        ),
        "static_stiffness_ratio_to_FE": stiff,
    }
