"""Appendix A of the validation report: the co-running parameters, derived vs published.

:func:`parameters_metrics`: the derived Table 2 against the turnout file's published one
(ratio, reproduced or not, why not), or the derived set per zone when the file has none.
"""

from __future__ import annotations

from typing import Any

from exudyn_turnout.corunning.comparison import TOLERANCE, compare_with_table2
from exudyn_turnout.inputs.turnout import Turnout

__all__ = ["parameters_metrics"]


def parameters_metrics(turnout: Turnout) -> dict[str, Any]:
    """Derived vs published Table 2 (at each zone's middle, SI), with ratio and explanation.

    Parameters
    ----------
    turnout : Turnout

    Returns
    -------
    dict
        JSON-ready: the tolerance, one row per entry, how many are reproduced; the derived
        set per zone when the file has no published one.
    """
    rows = compare_with_table2(turnout)
    table = [
        {
            "zone": r.zone,
            "name": r.name,
            "derived": r.derived,
            "published": r.published,
            "published_text": r.published_text,
            "as_printed": r.as_printed,
            "ratio_min": r.ratio_min,
            "ratio_max": r.ratio_max,
            "reproduced": r.reproduced,
            "explanation": r.explanation,
            "reading_value": r.reading_value,
        }
        for r in rows
    ]
    out = {
        "tolerance": TOLERANCE,
        "rows": table,
        "reproduced": sum(r.reproduced for r in rows),
        "entries": len(rows),
        "published_zones": sorted(turnout.published),
    }
    if not rows:  # no published set to compare with: the derived set, zone by zone
        out["derived"] = {str(z.index): _derived_at_middle(turnout, z.index) for z in turnout.zones}
    return out


def _derived_at_middle(turnout: Turnout, zone: int) -> dict[str, float]:
    """The derived 3-layer co-running entries of a zone at its middle (SI units)."""
    from exudyn_turnout.corunning.parameters import co_running_parameters
    from exudyn_turnout.inputs.turnout import PARAMETER_NAMES

    z = turnout.zone(zone)
    values = co_running_parameters(turnout, zone=zone, layers=3).at(0.5 * (z.x_start + z.x_end))
    return {n: float(values[n]) for n in PARAMETER_NAMES if n in values}
