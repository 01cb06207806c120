"""Stage 5, the passage: a vehicle runs through the turnout on any track.

A passage is a vehicle, a track and a contact; :func:`~.run.simulate_passage` is the one
door and the only module that knows every track.

- :mod:`.run`: the door and the dispatch;
- :mod:`.common`: settings checks, time-step limit, Newton tolerance, progress;
- :mod:`.settings`: what a passage is asked (settings, tracks, errors; no Exudyn);
- :mod:`.summary`: the plausibility stop, peaks and summaries (no Exudyn);
- :mod:`.results`: the result object and writing it (no Exudyn);
- :mod:`.output_files`: the output files, their CSV and NPZ formats and writers;
- :mod:`.vehicle`: the single wheelset and the full vehicle in Exudyn;
- :mod:`.contact`: the wheel/rail contact (protocol, profile contact, height-table baseline);
- :mod:`.corunning_track`: the 2- and 3-layer co-running track under every wheelset, zones
  switched during the run;
- :mod:`.fe_track`: the FE reference track, coupled to Exudyn by exact one-step
  co-simulation;
- :mod:`.hunting`: the full vehicle's hunting stability on rigid straight track.
"""

from exudyn_turnout.passage.results import PassageResult, write_passage
from exudyn_turnout.passage.run import compare_layers, simulate_passage
from exudyn_turnout.passage.settings import TRACKS, PassageError, PassageFailure, PassageSettings

__all__ = [
    "TRACKS",
    "PassageError",
    "PassageFailure",
    "PassageResult",
    "PassageSettings",
    "compare_layers",
    "simulate_passage",
    "write_passage",
]
