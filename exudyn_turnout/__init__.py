"""exudyn_turnout: co-running track models of railway turnouts on Exudyn.

Implements Shih, Ambur & Dixon, "Developing a detailed multi-body dynamic model of a
turnout based on its finite element model", Vehicle System Dynamics 61(3) 725-738 (2023),
doi 10.1080/00423114.2021.1981952.

The pipeline, one sub-package per stage::

    inputs/      turnout file, plan geometry, routes, vehicle files
    wheel_rail/  wheel and rail profiles, contact geometry, Hertz, creep
    corunning/   Eqs 1-19 -> co-running parameters -> linear model, Exudyn track
    fe/          the FE reference of the turnout (receptance, static stiffness)
    passage/     a vehicle through the turnout on a 2-layer, 3-layer or FE track
    report/      2-layer vs 3-layer vs FE against the paper's claims
    cli/         the exudyn-turnout command
    plotting/    figures of results and of the model

The front door::

    import exudyn_turnout as et

    turnout = et.load_turnout()                       # the packaged UIC60-760-1:15
    params = et.co_running_parameters(turnout, zone=2, layers=3)
    h = et.co_running_receptance(turnout, 3, "r2", "vertical", x=47.2)
    result = et.simulate_passage(turnout, et.PassageSettings(route="through"),
                                 track="3-layer")     # the full Manchester vehicle;
                                                      # vehicle="wheelset": one wheelset
    result.plot(); h.plot()

Names that need Exudyn, scipy's FE solvers or matplotlib are imported on first use, so
``import exudyn_turnout`` stays light.
"""

from __future__ import annotations

import importlib
from typing import Any

from exudyn_turnout.compiled_cache import refresh_compiled_cache
from exudyn_turnout.corunning.parameters import (
    CoRunningParameters,
    Readings,
    co_running_parameters,
    delta_y,
    delta_z,
)
from exudyn_turnout.inputs.geometry import TurnoutPlan, turnout_plan
from exudyn_turnout.inputs.routes import Route, load_route
from exudyn_turnout.inputs.turnout import (
    PARAMETER_NAMES,
    Turnout,
    TurnoutFileError,
    load_turnout,
)
from exudyn_turnout.inputs.vehicle import Vehicle, load_vehicle
from exudyn_turnout.receptance import Receptance, log_frequencies

# numba checks a cached function against its own file only: drop the package's compiled
# cache when any compiled source changed (a kernel kept an old callee's code otherwise)
refresh_compiled_cache()

__version__ = "0.3.0"

#: Names imported on first use: name -> module.
_LAZY = {
    "co_running_receptance": "exudyn_turnout.corunning.modal",
    "co_running_modes": "exudyn_turnout.corunning.modal",
    "fe_receptance": "exudyn_turnout.fe.frf",
    "FEOptions": "exudyn_turnout.fe.mesh",
    "simulate_passage": "exudyn_turnout.passage.run",
    "compare_layers": "exudyn_turnout.passage.run",
    "compare_tracks": "exudyn_turnout.passage.run",
    "packaged_vehicle": "exudyn_turnout.inputs.vehicles",
    "load_vehicle_model": "exudyn_turnout.inputs.vehicle_model",
    "VehicleModel": "exudyn_turnout.inputs.vehicle_model",
    "simulate_hunting": "exudyn_turnout.passage.hunting",
    "find_hunting_onset": "exudyn_turnout.passage.hunting",
    "HuntingSettings": "exudyn_turnout.passage.hunting",
    "run_study": "exudyn_turnout.studies.run",
    "write_report": "exudyn_turnout.report",
    "PassageSettings": "exudyn_turnout.passage.settings",
    "PassageResult": "exudyn_turnout.passage.results",
    "PassageError": "exudyn_turnout.passage.settings",
    "TRACKS": "exudyn_turnout.passage.settings",
    "FEPassageOptions": "exudyn_turnout.passage.fe_track.options",
    "plot_receptance": "exudyn_turnout.plotting.curves",
    "plot_passage_forces": "exudyn_turnout.plotting.curves",
    "draw_cross_section": "exudyn_turnout.plotting.model",
    "animate_passage": "exudyn_turnout.plotting.model",
}

__all__ = [
    "__version__",
    "CoRunningParameters",
    "PARAMETER_NAMES",
    "Readings",
    "Receptance",
    "Route",
    "Turnout",
    "TurnoutFileError",
    "TurnoutPlan",
    "Vehicle",
    "co_running_parameters",
    "delta_y",
    "delta_z",
    "load_route",
    "load_turnout",
    "load_vehicle",
    "log_frequencies",
    "turnout_plan",
    *_LAZY,
]


def __getattr__(name: str) -> Any:
    """Import the names of :data:`_LAZY` on first use (PEP 562)."""
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'exudyn_turnout' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
