"""What a passage's track offers its door: the written interface of a track implementation.

A track implementation is a sub-package of :mod:`exudyn_turnout.passage` (today
:mod:`~exudyn_turnout.passage.corunning_track` for the 2- and 3-layer co-running tracks and
:mod:`~exudyn_turnout.passage.fe_track` for the FE reference) whose ``__init__`` offers the
two functions of :class:`TrackImplementation`, with the same signature in every
implementation. Each builds the track under the vehicle's wheelsets, couples it (zone
carry-over on the co-running track, one-step co-simulation on the FE track), and returns
the same :class:`~exudyn_turnout.passage.results.PassageResult` columns, with Exudyn's
console output silenced during the run. The door,
:func:`exudyn_turnout.passage.run.simulate_passage`, has checked the settings and made the
route's contact before it calls one. Implementations never import each other; a new track
(rigid, a measured receptance) is one more sub-package and one line in ``run.py``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Protocol

from exudyn_turnout.inputs.routes import Route
from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.inputs.vehicle import Vehicle
from exudyn_turnout.inputs.vehicle_model import VehicleModel
from exudyn_turnout.passage.contact.protocol import Contact
from exudyn_turnout.passage.results import PassageResult
from exudyn_turnout.passage.settings import PassageSettings

__all__ = ["TrackImplementation"]


class TrackImplementation(Protocol):
    """The two runs a track implementation offers (module docstring)."""

    def simulate_wheelset(
        self,
        turnout: Turnout,
        settings: PassageSettings,
        vehicle: Vehicle,
        contact: Contact,
        route: Route,
        x_range: tuple[float, float],
        progress: Callable[[float, float], None] | None = None,
        options: Any = None,
    ) -> PassageResult:
        """The single wheelset with its sprung mass over this track.

        Parameters
        ----------
        turnout : Turnout
        settings : PassageSettings
            Checked by the door.
        vehicle : Vehicle
        contact : Contact
            The route's contact for this vehicle.
        route : Route
        x_range : tuple of float
            m, start and end of the run.
        progress : callable(fraction, x), optional
        options : object, optional
            The track's own options (the FE track's ``FEPassageOptions``).

        Returns
        -------
        PassageResult
        """

    def simulate_vehicle(
        self,
        turnout: Turnout,
        settings: PassageSettings,
        model: VehicleModel,
        contact: Contact,
        route: Route,
        x_range: tuple[float, float],
        progress: Callable[[float, float], None] | None = None,
        options: Any = None,
    ) -> PassageResult:
        """A full vehicle (car body, bogies, n wheelsets) over this track.

        Parameters
        ----------
        turnout : Turnout
        settings : PassageSettings
            Checked by the door.
        model : VehicleModel
        contact : Contact
            The route's profile contact (its ``vehicle``: contact law and wheel profile).
        route : Route
        x_range : tuple of float
            m, the front wheelset's start and end.
        progress : callable(fraction, x), optional
        options : object, optional
            The track's own options.

        Returns
        -------
        PassageResult
        """
