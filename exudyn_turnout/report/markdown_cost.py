"""Section 4 of ``report.md``: computing cost.

Wall times of the passages (every timed run, best and median, the paired 3-layer /
2-layer ratio, FE / 3-layer), the FE passage's size, and the co-running model's
coordinates per zone (:func:`cost_lines`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from exudyn_turnout.report.criteria import Claim
from exudyn_turnout.report.markdown_format import claims_table, fe_source, fmt, table
from exudyn_turnout.report.metrics_types import CostMetrics, FERun, PassageMetrics

__all__ = ["cost_lines"]


def _fe_run_text(runs: Mapping[str, FERun]) -> str:
    """FE passage size and where its wall time went, per route."""
    parts = []
    for route, r in runs.items():
        shares = r.wall_time_parts_s or {}
        where = ", ".join(f"{k} {fmt(v, '.1f')} s" for k, v in shares.items())
        parts.append(
            f"{route}: {fmt(r.n_dof, 'g')} FE coordinates, {fmt(r.n_steps, 'g')} "
            f"steps of {fmt(r.time_step_s, '.3g')} s" + (f" ({where})" if where else "")
        )
    return (" " + "; ".join(parts) + ".") if parts else ""


def _fe_text(cost: CostMetrics, passage: PassageMetrics) -> str:
    """Where the FE passages came from and their size, or that there is none."""
    fe_src = [
        f"{route}: {fe_source(rt.fe)}" for route, rt in passage.routes.items() if rt.fe is not None
    ]
    cached = any(rt.fe is not None and rt.fe.cached for rt in passage.routes.values())
    return (
        "FE passage (one run): "
        + "; ".join(fe_src)
        + (" (a cached wall time was measured when it was computed)." if cached else ".")
        + _fe_run_text(cost.fe_run)
        if fe_src
        else "FE passage: not available."
    )


def cost_lines(cost: CostMetrics, passage: PassageMetrics, claims: Sequence[Claim]) -> list[str]:
    """Section 4: wall times and ratios per route, coordinates per zone, the claims.

    Parameters
    ----------
    cost : CostMetrics
        The report's cost section.
    passage : PassageMetrics
        The report's passage section (every timed run, where the FE passages came from).
    claims : sequence of Claim
        The report's claims (those on computing cost are tabled).

    Returns
    -------
    list of str
        Lines.
    """
    median = cost.median_wall_time_s
    rows = [
        [
            route,
            fmt(w.get("2-layer"), ".2f"),
            fmt(w.get("3-layer"), ".2f"),
            fmt(median[route]["2-layer"], ".2f"),
            fmt(median[route]["3-layer"], ".2f"),
            fmt(w.get("FE"), ".1f"),
            fmt(cost.simulated_time_s[route], ".3f"),
            fmt(cost.ratio_3_over_2[route], ".3f"),
            fmt(cost.best_ratio_3_over_2[route], ".3f"),
            fmt(cost.ratio_FE_over_3.get(route), ".1f"),
        ]
        for route, w in cost.wall_time_s.items()
    ]
    runs = "; ".join(
        f"{route} {m}: " + ", ".join(fmt(t, ".2f") for t in ts)
        for route, rt in passage.routes.items()
        for m, ts in rt.co_running_wall_times_s.items()
    )
    dof = [
        [z, str(d["2-layer"]), str(d["3-layer"]), str(cost.extra_dof_per_zone[z])]
        for z, d in cost.dof_per_zone.items()
    ]
    return (
        [
            "## 4 Computing cost",
            "",
            "Wall times of the passages of section 3, measured in this run on 2 cores shared with "
            f"other work; co-running: {cost.repeats} runs each, 2-layer and 3-layer "
            "alternating. The ratio 3-layer / 2-layer is the median over the pairs (3-layer run / "
            "the 2-layer run just before it), robust to a load on the machine that changes during "
            f"the report; the ratio of the best times is shown beside it. All runs (s): {runs}. "
            f"{_fe_text(cost, passage)}",
            "",
        ]
        + table(
            [
                "route",
                "2-layer best (s)",
                "3-layer best (s)",
                "2-layer median (s)",
                "3-layer median (s)",
                "FE (s)",
                "simulated (s)",
                "3-layer / 2-layer (paired median)",
                "3-layer / 2-layer (best)",
                "FE / 3-layer (median)",
            ],
            rows,
        )
        + ["Coordinates of the co-running model per zone:", ""]
        + table(["zone", "2-layer", "3-layer", "extra"], dof)
        + claims_table(claims, "computing cost")
    )
