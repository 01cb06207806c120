"""Stage 5, the passage: a vehicle runs through the turnout on any track.

- :mod:`.results`: settings and result types, peaks, summary, output files (no Exudyn);
- :mod:`.simulate`: :func:`simulate_passage` (co-running track under the wheelset, zones
  switched during the run, or the FE track);
- :mod:`.fe_track`: the FE turnout as the passage's track (time integration of the FE
  model of :mod:`exudyn_turnout.fe` under the moving contact);
- :mod:`.contact_element`: the wheel/rail penalty contact as an Exudyn element;
- :mod:`.vehicle`: the single wheelset with its sprung share in Exudyn;
- :mod:`.vehicle_builder`: the full Manchester vehicle in Exudyn.
"""

from exudyn_turnout.passage.results import (
    TRACKS,
    PassageError,
    PassageFailure,
    PassageResult,
    PassageSettings,
    write_passage,
)
from exudyn_turnout.passage.simulate import simulate_passage

__all__ = [
    "TRACKS",
    "PassageError",
    "PassageFailure",
    "PassageResult",
    "PassageSettings",
    "simulate_passage",
    "write_passage",
]
