"""The co-running track (the paper's 2- and 3-layer models, Figs 2, 3) under every
wheelset, zones switched during the run: a
:class:`~exudyn_turnout.passage.track.TrackImplementation`.

- :mod:`.wheelset`: the single wheelset's run;
- :mod:`.vehicle`: the full vehicle's run, a co-running track under every wheelset;
- :mod:`.carry_over`: re-basing the track's state when a wheelset enters a new zone.
"""

from exudyn_turnout.passage.corunning_track.vehicle import simulate_vehicle
from exudyn_turnout.passage.corunning_track.wheelset import simulate_wheelset

__all__ = ["simulate_wheelset", "simulate_vehicle"]
