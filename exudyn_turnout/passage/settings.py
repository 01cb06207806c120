"""What a passage is asked: its settings, the tracks it runs on, and its errors.

Pure data (no Exudyn): :class:`PassageSettings` (the scenario, SI units but the speed in
km/h), :data:`DEFAULT_SETTINGS`, :data:`TRACKS`, :data:`PLAUSIBLE` (the limits beyond which
a run stops), and :class:`PassageError` / :class:`PassageFailure`.
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any

__all__ = [
    "PassageError",
    "PassageFailure",
    "PLAUSIBLE",
    "PassageSettings",
    "settings_record",
    "DEFAULT_SETTINGS",
    "TRACKS",
]


class PassageError(RuntimeError):
    """Bad passage settings, or a solver failure (the message says when and where)."""


class PassageFailure(PassageError):
    """A run that failed, diverged or left every physical state (the CLI's exit code 3).

    The message gives the time, the position and what went wrong.
    """


#: Plausibility limits of a passage: beyond any of them the run stops with a
#: :class:`PassageFailure`. m: wheelset vertical and lateral displacement (a wheel 50 mm
#: up or down has derailed or fallen through the track); m: rail deflection; -: contact
#: force over the static wheel load.
PLAUSIBLE = {"wheelset_m": 0.05, "rail_m": 0.02, "force_over_static": 50.0}


@dataclass(frozen=True)
class PassageSettings:
    """Settings of a passage (SI units but the speed in km/h)."""

    route: str = "through"
    speed_kmh: float = 100.0  #: km/h
    layers: int = 3
    source: str = "derived"
    x_start: float | None = None  #: m, default: the turnout's start
    x_end: float | None = None  #: m, default: the turnout's end
    #: s; converged on the through route (<= 0.23 % against 2.5e-5 s), not for the 2-layer
    #: check-rail force on the diverging route (-14.9 %): validation/vehicle_step_convergence.md;
    #: where a check rail carries load the co-running track's runs step at
    #: ``check_rail_time_step`` instead
    time_step: float = 1e-4
    #: s, the step of a run segment where a check-rail contact carries load: such a segment
    #: runs at this step (no finer than needed: the segment's step over an integer) over the
    #: window of the check rail's load, predicted or run again
    #: (:mod:`~exudyn_turnout.passage.corunning_track.vehicle`; the FE track runs again,
    #: :mod:`~exudyn_turnout.passage.fe_track.common`); None: never (a run at a coarser step
    #: warns, :class:`~exudyn_turnout.passage.check_rail_steps.CheckRailStepWarning`). 2.5e-5 s: the
    #: 2-layer check-rail force on the diverging route, full vehicle at 80 km/h, 86.43 kN
    #: against 86.34 / 86.32 kN at 1.25e-5 / 6.25e-6 s, 87.91 kN (+1.8 %) at 1e-4 s
    #: throughout (validation/vehicle_step_convergence.md; before issue 22's contact lead
    #: along x the flange back struck the flare's end in the wrong place and the force rang
    #: at ~1 kHz: 128.1 kN at 2.5e-5 s, 109.1 kN at 1e-4 s)
    check_rail_time_step: float | None = 2.5e-5
    output_step: float | None = None  #: s, default: every time step
    spectral_radius: float = 0.8  #: generalized-alpha rho_inf
    #: how track springs follow x: "compiled" (one numba call for all springs), "symbolic",
    #: "python" or "constant" (corunning.track.MECHANISMS)
    track_mechanism: str = "compiled"
    #: wheel/rail contact: "profile" (S1002 on the turnout's rail sections, multi-point,
    #: semi-Hertzian normal contact, FASTSIM creep table with spin) or "height-table" (the
    #: route's rail height tables on a conical tread with flange springs: a simplification
    #: kept for comparison)
    contact: str = "profile"
    #: track irregularity (:class:`~exudyn_turnout.inputs.irregularity.Irregularity`) added
    #: to the rails' heights and lateral positions; None: the design geometry
    irregularity: Any = None
    #: time integration of the full vehicle on the co-running track: "compiled" (the
    #: default: Exudyn's generalized-alpha scheme in one numba loop,
    #: :mod:`~exudyn_turnout.passage.corunning_track.stepper`; a segment it does not model
    #: runs in Exudyn, ``summary["stepping"]`` says why) or "exudyn" (Exudyn's
    #: ``SolveDynamic``). The single wheelset and the FE track always step in Exudyn.
    solver: str = "compiled"
    #: the creep force reduction factor: Kalker's coefficients of every contact times this
    #: (the creep forces' initial slopes scale, their saturation at mu N does not; 1: none;
    #: Simpack's and GENSYS's factor of the same name; a sensitivity knob:
    #: validation/contact_law_sensitivity.md gives what it moves)
    creep_reduction: float = 1.0
    #: the normal contact law's force at a given penetration times this (the effective
    #: modulus of the normal problem alone; 1: none): a sensitivity knob for the law's
    #: approach error against exact solutions, (1 + e)^-1.5 for an approach error e
    #: (``wheel_rail.packed_tables.scale_contact_law``, validation/contact_law_sensitivity.md)
    normal_stiffness_factor: float = 1.0

    @property
    def v(self) -> float:
        """Speed in m/s."""
        return self.speed_kmh / 3.6


def settings_record(settings: PassageSettings) -> dict[str, Any]:
    """The settings as plain data for summaries and provenance.

    Parameters
    ----------
    settings : PassageSettings

    Returns
    -------
    dict
        Every field; the irregularity as its source (spec or file name), not its samples.
    """
    record = {f.name: getattr(settings, f.name) for f in fields(settings)}
    irregularity = record.get("irregularity")
    if irregularity is not None:
        record["irregularity"] = str(getattr(irregularity, "source", "") or "given")
    return record


#: The default scenario (frozen, so one instance serves as every function's default).
DEFAULT_SETTINGS = PassageSettings()


#: Track models of :func:`simulate_passage`.
TRACKS = ("2-layer", "3-layer", "fe")
