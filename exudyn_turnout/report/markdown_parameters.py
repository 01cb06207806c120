"""Appendix A of ``report.md``: the co-running parameters, derived against published.

The derived Table 2 against the published one, or, for a turnout file without a published
set, the derived entries per zone (:func:`parameters_lines`).
"""

from __future__ import annotations

from exudyn_turnout.report.markdown_format import fmt, table
from exudyn_turnout.report.metrics_types import ParameterMetrics, ParameterRow

__all__ = ["parameters_lines"]


def _ratio_text(row: ParameterRow) -> str:
    lo, hi = fmt(row.ratio_min, ".3f"), fmt(row.ratio_max, ".3f")
    return lo if lo == hi else f"{lo}-{hi}"


def _derived_parameters(derived: dict[str, dict[str, float]]) -> list[str]:
    """Appendix A of a turnout without a published set: the derived entries per zone."""
    zones = list(derived)
    names = list(dict.fromkeys(n for z in zones for n in derived[z]))
    rows = [[f"`{n}`"] + [fmt(derived[z].get(n), ".4g") for z in zones] for n in names]
    return [
        "## Appendix A Parameters: derived (no published set in this file)",
        "",
        "The turnout file has no `[published]` co-running parameters to compare with; the derived "
        "3-layer set (Eqs 1-19 on the file's rail, sleeper and ballast data) at each zone's "
        "middle, SI units (N/m, N s/m, kg, kg m^2); entries of rails that are not active in a "
        "zone are derived all the same.",
        "",
    ] + table(["entry"] + [f"zone {z}" for z in zones], rows)


def parameters_lines(parameters: ParameterMetrics) -> list[str]:
    """Appendix A: derived vs published Table 2 (or the derived set alone).

    Parameters
    ----------
    parameters : ParameterMetrics
        The report's parameters section.

    Returns
    -------
    list of str
        Lines.
    """
    if not parameters.rows and parameters.derived:
        return _derived_parameters(parameters.derived)
    rows = [
        [
            str(r.zone),
            f"`{r.name}`",
            fmt(r.derived, ".4g"),
            fmt(r.published, ".4g"),
            r.published_text,
            _ratio_text(r),
            "yes" if r.reproduced else "no",
            r.explanation or "-",
        ]
        for r in parameters.rows
    ]
    return [
        "## Appendix A Parameters: derived vs published Table 2",
        "",
        "Values in SI units at each zone's middle (N/m, N s/m, kg, kg m^2). *ratio*: "
        "derived/published, min-max over the zone's start, middle and end; reproduced if within "
        f"{parameters.tolerance:.0%} of 1. Reproduced: **{parameters.reproduced} of "
        f"{parameters.entries}** entries. Full table with the as-printed values: "
        "`validation/derived_vs_published.md`.",
        "",
    ] + table(
        ["zone", "entry", "derived", "published", "Table 2", "ratio", "reproduced", "explanation"],
        rows,
    )
