"""The report's one door to the passage stage (:mod:`exudyn_turnout.passage`).

Every name of :mod:`exudyn_turnout.passage` that the report uses is imported here and
nowhere else in :mod:`exudyn_turnout.report`, so a change of the passage API is one edit:
the result and settings containers, and :func:`run_track_passage`, which runs the single
wheelset or the full vehicle on a co-running or the FE track.
"""

from __future__ import annotations

from exudyn_turnout.fe.mesh import FEOptions
from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.passage.events import nose_region
from exudyn_turnout.passage.results import PassageResult
from exudyn_turnout.passage.settings import PassageSettings

__all__ = [
    "PassageResult",
    "PassageSettings",
    "fe_passage_options",
    "nose_region",
    "run_track_passage",
]


def fe_passage_options(mesh: FEOptions):
    """The FE passage's options with the FE mesh ``mesh``.

    Parameters
    ----------
    mesh : FEOptions
        FE discretisation and model ends.

    Returns
    -------
    FEPassageOptions
        :class:`~exudyn_turnout.passage.fe_track.options.FEPassageOptions` with ``mesh``.
    """
    from exudyn_turnout.passage.fe_track.options import FEPassageOptions

    return FEPassageOptions(mesh=mesh)


def run_track_passage(
    turnout: Turnout, settings: PassageSettings, vehicle: str, track: str, mesh: FEOptions
) -> PassageResult:
    """One passage of ``vehicle`` on ``track``.

    Parameters
    ----------
    turnout : Turnout
    settings : PassageSettings
        Route, speed, x range, time step, contact.
    vehicle : {"full", "wheelset"}
        The full Manchester vehicle (packaged vehicle model) or the single benchmark
        wheelset under its sprung share.
    track : {"2-layer", "3-layer", "fe"}
        The track under the vehicle.
    mesh : FEOptions
        The FE track's mesh (``track="fe"`` only).

    Returns
    -------
    PassageResult
        The single wheelset's, or the full vehicle's (the front wheelset's forces under the
        single-wheelset column names).
    """
    from exudyn_turnout.passage.run import simulate_passage

    options = fe_passage_options(mesh) if track == "fe" else None
    name = "wheelset" if vehicle == "wheelset" else "manchester"
    return simulate_passage(turnout, settings, name, track=track, fe_options=options)
