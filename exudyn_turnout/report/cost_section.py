"""Section 4 of the validation report: computing cost.

Wall times of the passages, the paired 3-layer / 2-layer ratio, FE / 3-layer, the FE
passage's size, coordinates per zone, receptance wall times (:func:`cost_metrics`).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from exudyn_turnout.corunning.modal import dof_names
from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.report import agreement as ag
from exudyn_turnout.report.config import ReportConfig
from exudyn_turnout.report.metrics_types import PassageMetrics, ReceptanceMetrics
from exudyn_turnout.report.passage_api import PassageResult
from exudyn_turnout.report.passages import (
    summary_float,
)

__all__ = ["cost_metrics"]


def cost_metrics(
    turnout: Turnout,
    passages: Mapping[str, Mapping[str, PassageResult]],
    receptance: ReceptanceMetrics,
    passage_metrics: PassageMetrics,
    config: ReportConfig,
) -> dict[str, Any]:
    """Wall times measured in this run, ratios, coordinates per zone, receptance times.

    The 3-layer / 2-layer ratio is the median over the interleaved repeats of (3-layer run /
    the 2-layer run just before it): neighbouring runs see the same load of a shared
    machine, so the ratio is robust to load that changes during the report. Best and median
    wall times per model are reported beside it. FE / 3-layer uses the 3-layer median.

    Parameters
    ----------
    turnout : Turnout
    passages : mapping
        route -> model -> PassageResult of
        :func:`~exudyn_turnout.report.passages.passage_section`.
    receptance : ReceptanceMetrics
        The receptance section (its wall times).
    passage_metrics : PassageMetrics
        The passage section (every timed run).
    config : ReportConfig
        ``timing_repeats``.

    Returns
    -------
    dict
        JSON-ready: wall times (s) and their ratios per route, the FE passage's size,
        coordinates per zone, receptance wall times.
    """
    wall = {
        route: {m: summary_float(r.summary, "wall_time_s") for m, r in res.items()}
        for route, res in passages.items()
    }
    runs = {route: rt.co_running_wall_times_s for route, rt in passage_metrics.routes.items()}
    median = {route: {m: float(np.median(v)) for m, v in w.items()} for route, w in runs.items()}
    dof = {
        str(z.index): {f"{n}-layer": len(dof_names(z.active_rails, n)) for n in (2, 3)}
        for z in turnout.zones
    }
    out = {
        "repeats": config.timing_repeats,
        "wall_time_s": wall,
        "median_wall_time_s": median,
        "simulated_time_s": {
            route: summary_float(res["3-layer"].summary, "simulated_time_s")
            for route, res in passages.items()
        },
        "ratio_3_over_2": {
            route: ag.paired_median_ratio(w["3-layer"], w["2-layer"]) for route, w in runs.items()
        },
        "best_ratio_3_over_2": {route: w["3-layer"] / w["2-layer"] for route, w in wall.items()},
        "ratio_FE_over_3": {
            route: w["FE"] / median[route]["3-layer"] for route, w in wall.items() if "FE" in w
        },
        "fe_run": {
            route: {
                "n_dof": res["FE"].summary.get("n_dof"),
                "time_step_s": res["FE"].summary.get("time_step_s"),
                "n_steps": res["FE"].summary.get("n_steps"),
                "wall_time_parts_s": res["FE"].summary.get("wall_time_parts_s"),
            }
            for route, res in passages.items()
            if "FE" in res
        },
        "dof_per_zone": dof,
        "extra_dof_per_zone": {z: d["3-layer"] - d["2-layer"] for z, d in dof.items()},
        "receptance_wall_time_s": {
            case: {
                "co-running": c.co_running_wall_time_s,
                "FE": c.fe.wall_time_s,
                "FE_cached": c.fe.cached,
            }
            for case, c in receptance.cases.items()
        },
    }
    return out
