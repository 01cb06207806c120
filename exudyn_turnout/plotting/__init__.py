"""Figures: computed results (:mod:`.curves`), the model itself (:mod:`.model`: the
cross-section drawn, its data :mod:`.cross_section`, a passage animated :mod:`.animation`)
and the wheel/rail geometry (:mod:`.wheel_rail`).

The only package that imports matplotlib, through :mod:`.backend` when a figure is
drawn. Compute functions return data objects; these functions draw them (``Receptance.plot`` and
``PassageResult.plot`` delegate here).
"""

from exudyn_turnout.plotting.animation import animate_passage
from exudyn_turnout.plotting.cross_section import cross_section_geometry
from exudyn_turnout.plotting.curves import plot_passage_forces, plot_receptance
from exudyn_turnout.plotting.model import draw_cross_section

__all__ = [
    "animate_passage",
    "cross_section_geometry",
    "draw_cross_section",
    "plot_passage_forces",
    "plot_receptance",
]
