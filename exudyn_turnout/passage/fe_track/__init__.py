"""The FE reference track under the passage's vehicle, coupled to Exudyn by exact one-step
co-simulation: a :class:`~exudyn_turnout.passage.track.TrackImplementation`.

- :mod:`.options`: mesh and damping options;
- :mod:`.coupling`: the FE planes, their time integration and the coupled contact element;
- :mod:`.wheelset`, :mod:`.vehicle`: the single wheelset's and the full vehicle's runs;
- :mod:`.common`: what the two runs share (contact element, run settings, outputs).
"""

from exudyn_turnout.passage.fe_track.vehicle import simulate_vehicle
from exudyn_turnout.passage.fe_track.wheelset import simulate_wheelset

__all__ = ["simulate_wheelset", "simulate_vehicle"]
