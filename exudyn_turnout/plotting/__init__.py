"""Figures: computed results (:mod:`.curves`) and the model itself (:mod:`.model`).

The only place, with the report's figures, that imports matplotlib. Compute functions
return data objects; these functions draw them (``Receptance.plot`` and
``PassageResult.plot`` delegate here).
"""

from exudyn_turnout.plotting.curves import plot_passage_forces, plot_receptance
from exudyn_turnout.plotting.model import (
    animate_passage,
    cross_section_geometry,
    draw_cross_section,
)

__all__ = [
    "animate_passage",
    "cross_section_geometry",
    "draw_cross_section",
    "plot_passage_forces",
    "plot_receptance",
]
