"""Stage 1, inputs: the turnout file, its plan geometry and routes, the vehicle files.

- :mod:`.turnout`: the turnout file (Table 1 per rail type, sleepers, ballast, Eqs 10 and
  14, zones of Table 3, Table 2 verbatim), validated as a whole at load time; its
  dataclasses :mod:`.turnout_data`; the TOML field reader :mod:`.toml_fields`;
- :mod:`.geometry`: the plan (route centrelines, crossing point, nose tip);
- :mod:`.routes`: which rails each wheel can touch along a route, speed limits;
- :mod:`.vehicle`: the single-wheelset vehicle file and its contact constants;
- :mod:`.vehicle_model`: the full Manchester benchmark vehicle file; its dataclasses
  :mod:`.vehicle_data`; hand-calculated natural frequencies :mod:`.vehicle_frequencies`;
- :mod:`.vehicle_names`, :mod:`.vehicles`: the packaged vehicles by name
  (``packaged_vehicle("wheelset")``, ``packaged_vehicle("manchester")``);
- :mod:`.irregularity`: track irregularities; standard spectra :mod:`.track_spectra`.
"""

from exudyn_turnout.inputs.geometry import TurnoutPlan, turnout_plan
from exudyn_turnout.inputs.routes import Route, load_route, route_names
from exudyn_turnout.inputs.turnout import Turnout, TurnoutFileError, load_turnout
from exudyn_turnout.inputs.vehicle import Vehicle, load_vehicle
from exudyn_turnout.inputs.vehicle_model import VehicleModel, load_vehicle_model
from exudyn_turnout.inputs.vehicle_names import PACKAGED_VEHICLES
from exudyn_turnout.inputs.vehicles import packaged_vehicle

__all__ = [
    "PACKAGED_VEHICLES",
    "Route",
    "Turnout",
    "TurnoutFileError",
    "TurnoutPlan",
    "Vehicle",
    "VehicleModel",
    "load_route",
    "load_turnout",
    "load_vehicle",
    "load_vehicle_model",
    "packaged_vehicle",
    "route_names",
    "turnout_plan",
]
