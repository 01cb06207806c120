"""exudyn_turnout: co-running track models of railway turnouts on Exudyn.

Implements Shih, Ambur & Dixon, "Developing a detailed multi-body dynamic model of a
turnout based on its finite element model", Vehicle System Dynamics 61(3) 725-738 (2023),
doi 10.1080/00423114.2021.1981952.

Modules: :mod:`~exudyn_turnout.inputs.turnout` (turnout file), :mod:`~exudyn_turnout.corunning.equations`
(Eqs 1-19), :mod:`~exudyn_turnout.corunning.parameters` (co-running parameter sets),
:mod:`~exudyn_turnout.corunning.comparison` (derived vs published Table 2), :mod:`~exudyn_turnout.cli.main`.
"""

from exudyn_turnout.corunning.parameters import (
    CoRunningParameters,
    Readings,
    co_running_parameters,
    delta_y,
    delta_z,
)
from exudyn_turnout.inputs.turnout import PARAMETER_NAMES, Turnout, TurnoutFileError, load_turnout

__version__ = "0.1.0"

__all__ = [
    "CoRunningParameters",
    "Readings",
    "co_running_parameters",
    "delta_y",
    "delta_z",
    "PARAMETER_NAMES",
    "Turnout",
    "TurnoutFileError",
    "load_turnout",
]
