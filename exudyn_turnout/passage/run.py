"""The passage's one door: any vehicle on any track with any contact.

:func:`simulate_passage` takes a *vehicle* (the single wheelset with its sprung mass, or a
full vehicle of 1..n wheelsets with bogies and car body), a *track* (co-running 2-layer,
co-running 3-layer, or the FE reference) and the *contact* named by the settings (the
profile contact, or the height-table baseline on the single wheelset's co-running run),
checks the settings once, and hands the run to the driver of that combination. This is the
only module that knows every track and every contact: the track implementations
(:mod:`~exudyn_turnout.passage.corunning_track`, :mod:`~exudyn_turnout.passage.fe_track`)
never import each other, and nothing but this module imports the height-table contact.

::

    vehicle                  track                       contact
    -------                  -----                       -------
    "wheelset"  Vehicle  --+-- "2-layer" / "3-layer" --+-- "profile"      (RouteContact)
    "manchester" Model   --+-- "fe"                  --+-- "height-table" (wheelset,
                                                             co-running only)
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from dataclasses import replace
from importlib.resources import files
from typing import Any

from exudyn_turnout.inputs.routes import SpeedWarning, load_route, speed_warnings
from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.inputs.vehicle import Vehicle, load_vehicle
from exudyn_turnout.inputs.vehicle_model import VehicleModel, load_vehicle_model
from exudyn_turnout.passage.common import QuietExudyn, check_settings, check_vehicle_settings
from exudyn_turnout.passage.results import (
    DEFAULT_SETTINGS,
    TRACKS,
    PassageError,
    PassageResult,
    PassageSettings,
)

__all__ = [
    "PACKAGED_VEHICLES",
    "simulate_passage",
    "compare_layers",
    "track_of",
    "vehicle_of",
]

#: Names of the packaged vehicles -> their files in ``exudyn_turnout/data``.
PACKAGED_VEHICLES = {
    "wheelset": "manchester_wheelset.toml",  # the single wheelset with its sprung share
    "manchester": "manchester_vehicle.toml",  # the full Manchester benchmark vehicle
}


def track_of(settings: PassageSettings, track: str | None) -> tuple[str, PassageSettings]:
    """The run's track, and the settings made to agree with it.

    ``track`` is the one source of truth; without it the settings' ``layers`` name the
    co-running track (``"3-layer"`` by default).

    Parameters
    ----------
    settings : PassageSettings
    track : {"2-layer", "3-layer", "fe"} or None

    Returns
    -------
    track : str
        One of :data:`~exudyn_turnout.passage.results.TRACKS`.
    settings : PassageSettings
        With ``layers`` of the co-running track (unchanged for the FE track).

    Raises
    ------
    PassageError
        An unknown track.
    """
    if track is None:
        track = f"{settings.layers}-layer"
    if track not in TRACKS:
        raise PassageError(f"track must be one of {', '.join(TRACKS)}, got {track!r}")
    if track != "fe":
        settings = replace(settings, layers={"2-layer": 2, "3-layer": 3}[track])
    return track, settings


def vehicle_of(vehicle: Vehicle | VehicleModel | str | None) -> Vehicle | VehicleModel:
    """The vehicle of a passage: a packaged one by name, or the one given.

    Parameters
    ----------
    vehicle : Vehicle, VehicleModel, str or None
        ``None`` or ``"wheelset"``: the packaged single wheelset; ``"manchester"``: the
        full Manchester benchmark vehicle (:data:`PACKAGED_VEHICLES`); a
        :class:`~exudyn_turnout.inputs.vehicle.Vehicle` (single wheelset) or a
        :class:`~exudyn_turnout.inputs.vehicle_model.VehicleModel` (full vehicle).

    Returns
    -------
    Vehicle or VehicleModel

    Raises
    ------
    PassageError
        An unknown name.
    """
    if vehicle is None:
        vehicle = "wheelset"
    if isinstance(vehicle, str):
        if vehicle not in PACKAGED_VEHICLES:
            raise PassageError(
                f"vehicle must be one of {', '.join(PACKAGED_VEHICLES)} or a vehicle file, "
                f"got {vehicle!r}"
            )
        path = str(files("exudyn_turnout") / "data" / PACKAGED_VEHICLES[vehicle])
        return load_vehicle(path) if vehicle == "wheelset" else load_vehicle_model(path)
    return vehicle


def simulate_passage(
    turnout: Turnout,
    settings: PassageSettings = DEFAULT_SETTINGS,
    vehicle: Vehicle | VehicleModel | str | None = None,
    progress: Callable[[float, float], None] | None = None,
    *,
    track: str | None = None,
    fe_options: Any = None,
) -> PassageResult:
    """Run a vehicle through the turnout on a co-running track or on the FE track.

    One door for every combination of vehicle and track (module docstring): the single
    wheelset or a full vehicle, on the 2-layer or 3-layer co-running track (the paper's
    Figs 2, 3, zones switched during the run) or on the FE reference track (vertical and
    lateral, the same vehicle and profile contact, exact one-step co-simulation).

    Parameters
    ----------
    turnout : Turnout
        From :func:`~exudyn_turnout.inputs.turnout.load_turnout`.
    settings : PassageSettings
        The scenario: route, speed, x range (the front wheelset's), time step, output step,
        contact, irregularity; for the co-running tracks also the parameter source and the
        spring mechanism.
    vehicle : {"wheelset", "manchester"}, Vehicle or VehicleModel, optional
        Default: the packaged single wheelset (the paper's vehicle is one wheelset with its
        sprung share); ``"manchester"`` the full Manchester benchmark vehicle.
    progress : callable(fraction, x), optional
        Called about every 2 % of the run.
    track : {"2-layer", "3-layer", "fe"}, optional
        Default: ``settings.layers`` layers of co-running track.
    fe_options : FEPassageOptions, optional
        Mesh and solver options of the FE track (``track="fe"`` only).

    Returns
    -------
    PassageResult
        ``columns``: ``t_s``, ``x_m``; per wheel and rail ``Fz_<wheel>_<rail>_N`` (normal force
        pressing the rail down) and ``Fy_<wheel>_<rail>_N`` (lateral force on the rail,
        positive left); per wheel ``Fz_<wheel>_N``, ``Fy_<wheel>_N``; wheelset ``y``, ``z``,
        ``roll``, ``yaw``; per rail touched ``y_rail_<rail>_m``, ``z_rail_<rail>_m`` (NaN
        where that rail is not part of the zone); a full vehicle adds every wheelset's
        columns (``Fz_wsk_<wheel>_N``, ``x_wsk_m``...). ``summary``: peaks
        (:func:`~exudyn_turnout.passage.results.passage_summary`).

    Raises
    ------
    PassageError
        Bad settings (one line naming the problem) or a solver failure (time and position).
    """
    track, settings = track_of(settings, track)
    model = vehicle_of(vehicle)
    if isinstance(model, VehicleModel):
        return _full_vehicle(turnout, settings, model, track, fe_options, progress)
    if track == "fe":
        return _wheelset_on_fe(turnout, settings, model, fe_options, progress)
    return _wheelset_on_corunning(turnout, settings, model, progress)


def _wheelset_on_corunning(turnout, settings, vehicle, progress) -> PassageResult:
    from exudyn_turnout.passage.corunning_track.wheelset import simulate_wheelset

    x_a, x_b = check_settings(settings, turnout, vehicle)
    route = load_route(turnout, settings.route)
    for text in speed_warnings(route, settings.speed_kmh, x_a, x_b):
        warnings.warn(text, SpeedWarning, stacklevel=3)
    contact = _contact(turnout, settings, route.name, vehicle)
    return simulate_wheelset(turnout, settings, vehicle, contact, route, (x_a, x_b), progress)


def _contact(turnout, settings, route_name: str, vehicle: Vehicle):
    """The route's contact named by ``settings.contact`` (checked by ``check_settings``)."""
    if settings.contact == "height-table":
        from exudyn_turnout.passage.contact.height_table import HeightTableContact

        return HeightTableContact()
    from exudyn_turnout.passage.contact.profile import route_contact

    try:
        return route_contact(turnout, route_name, vehicle)
    except ValueError as err:
        raise PassageError(str(err)) from None


def _wheelset_on_fe(turnout, settings, vehicle, fe_options, progress) -> PassageResult:
    if settings.contact == "height-table":  # the vertical-only FE passage (legacy)
        from exudyn_turnout.passage.fe_track.vertical_legacy import simulate_fe_passage

        return simulate_fe_passage(turnout, settings, vehicle, fe_options, progress=progress)
    from exudyn_turnout.passage.fe_track.wheelset import simulate_wheelset

    return simulate_wheelset(turnout, settings, vehicle, fe_options, progress=progress)


def _full_vehicle(turnout, settings, model, track, fe_options, progress) -> PassageResult:
    base = load_vehicle()
    x_a, x_b = check_vehicle_settings(settings, turnout, model, base)
    route = load_route(turnout, settings.route)
    for text in speed_warnings(route, settings.speed_kmh, x_a, x_b):
        warnings.warn(text, SpeedWarning, stacklevel=3)
    if track == "fe":
        from exudyn_turnout.passage.fe_track.vehicle import simulate_vehicle as on_fe

        with QuietExudyn():
            return on_fe(turnout, settings, model, fe_options, progress=progress)
    from exudyn_turnout.passage.corunning_track.vehicle import simulate_vehicle

    return simulate_vehicle(turnout, settings, model, route, (x_a, x_b), progress)


def compare_layers(
    turnout: Turnout,
    settings: PassageSettings = DEFAULT_SETTINGS,
    vehicle: Vehicle | VehicleModel | str | None = None,
) -> dict[int, PassageResult]:
    """The same passage on the two-layer and the three-layer track.

    Parameters
    ----------
    turnout : Turnout
    settings : PassageSettings
    vehicle : {"wheelset", "manchester"}, Vehicle or VehicleModel, optional

    Returns
    -------
    dict
        {2: PassageResult, 3: PassageResult}.
    """
    return {
        layers: simulate_passage(turnout, settings, vehicle, track=f"{layers}-layer")
        for layers in (2, 3)
    }
