"""Stage 3, co-running track models (paper Section 3): parameters, linear model, Exudyn.

- :mod:`.equations`: Eqs 1-19, one pure function each;
- :mod:`.parameters`: co-running parameter sets of a zone or position (derived from
  Table 1 with Eqs 1-19, or Table 2 as published);
- :mod:`.comparison`: derived vs published Table 2, entry by entry;
- :mod:`.modal`: the model's M, K, D by hand, modes and receptance (Figs 5, 6);
- :mod:`.cross_section`: the springs of the cross-section (Figs 2, 3), as data;
- :mod:`.track`: the two- or three-layer track in Exudyn (the builder; imports exudyn).
"""

from exudyn_turnout.corunning.modal import co_running_modes, co_running_receptance
from exudyn_turnout.corunning.parameters import (
    CoRunningParameters,
    Readings,
    co_running_parameters,
    delta_y,
    delta_z,
)

__all__ = [
    "CoRunningParameters",
    "Readings",
    "co_running_modes",
    "co_running_parameters",
    "co_running_receptance",
    "delta_y",
    "delta_z",
]
