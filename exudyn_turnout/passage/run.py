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
    "manchester" Model   --+-- "2-layer" / "3-layer" --+-- "profile"      (RouteContact)
    "wheelset"  Vehicle  --+-- "fe"                  --+-- "height-table" (wheelset,
                                                             co-running only)

The default vehicle (:data:`DEFAULT_VEHICLE`) is the full Manchester benchmark vehicle: the
paper's Figs 7, 8 show its front axle, and a full vehicle's plain columns (``Fz_right_N``...)
are its front wheelset's. The single wheelset under its sprung share, four times cheaper,
is named ``"wheelset"``.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from dataclasses import replace
from typing import Any, cast

from exudyn_turnout.inputs.routes import Route, SpeedWarning, load_route, speed_warnings
from exudyn_turnout.inputs.turnout import Turnout, TurnoutFileError
from exudyn_turnout.inputs.vehicle import Vehicle, load_vehicle
from exudyn_turnout.inputs.vehicle_model import VehicleModel
from exudyn_turnout.inputs.vehicles import packaged_vehicle
from exudyn_turnout.passage.common import check_settings, check_vehicle_settings
from exudyn_turnout.passage.comparison import PassageComparison
from exudyn_turnout.passage.results import PassageResult
from exudyn_turnout.passage.settings import DEFAULT_SETTINGS, TRACKS, PassageError, PassageSettings
from exudyn_turnout.passage.track import TrackImplementation

__all__ = [
    "DEFAULT_VEHICLE",
    "simulate_passage",
    "compare_layers",
    "compare_tracks",
    "track_of",
    "vehicle_of",
]


#: The packaged vehicle a passage runs without a ``vehicle`` (``simulate`` without
#: ``--vehicle``): the full Manchester benchmark vehicle, car body on two bogies.
DEFAULT_VEHICLE = "manchester"


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
        One of :data:`~exudyn_turnout.passage.settings.TRACKS`.
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
        ``None`` (:data:`DEFAULT_VEHICLE`) or ``"manchester"``: the full Manchester
        benchmark vehicle; ``"wheelset"``: the packaged single wheelset
        (:func:`~exudyn_turnout.inputs.vehicles.packaged_vehicle`); a
        :class:`~exudyn_turnout.inputs.vehicle.Vehicle` (single wheelset) or a
        :class:`~exudyn_turnout.inputs.vehicle_model.VehicleModel` (full vehicle).

    Returns
    -------
    Vehicle or VehicleModel

    Raises
    ------
    PassageError
        An unknown name (one line listing the names).
    """
    if vehicle is None:
        vehicle = DEFAULT_VEHICLE
    if isinstance(vehicle, str):
        try:
            return packaged_vehicle(vehicle)
        except TurnoutFileError as err:
            raise PassageError(str(err)) from None
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
        spring mechanism; ``solver`` (default "compiled": the package's compiled stepper)
        steps the full vehicle on a co-running track only; the single wheelset and the FE
        track step in Exudyn whatever it says.
    vehicle : {"manchester", "wheelset"}, Vehicle or VehicleModel, optional
        Default (:data:`DEFAULT_VEHICLE`): the full Manchester benchmark vehicle, four
        wheelsets each on its own co-running track, the plain columns its front
        wheelset's (the paper's Figs 7, 8 show the front axle); ``"wheelset"`` the packaged
        single wheelset under its sprung share (about half the CPU time: README's performance
        table).
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
        (:func:`~exudyn_turnout.passage.summary.passage_summary`).

    Raises
    ------
    PassageError
        Bad settings (one line naming the problem) or a solver failure (time and position).
    """
    track, settings = track_of(settings, track)
    model = vehicle_of(vehicle)
    if settings.solver not in ("exudyn", "compiled"):
        raise PassageError(f"solver must be 'exudyn' or 'compiled', got {settings.solver!r}")
    implementation = _implementation(track)
    if isinstance(model, VehicleModel):
        base = load_vehicle()
        x_range = check_vehicle_settings(settings, turnout, model, base)
        route = _route(turnout, settings, x_range)
        contact = _contact(turnout, settings, route.name, base)
        return implementation.simulate_vehicle(
            turnout, settings, model, contact, route, x_range, progress, fe_options
        )
    if track == "fe" and settings.contact != "profile":
        raise PassageError(
            "the FE track runs with the profile contact only (the height-table contact "
            "is the single wheelset's co-running baseline)"
        )
    x_range = check_settings(settings, turnout, model)
    route = _route(turnout, settings, x_range)
    contact = _contact(turnout, settings, route.name, model)
    return implementation.simulate_wheelset(
        turnout, settings, model, contact, route, x_range, progress, fe_options
    )


def _implementation(track: str) -> TrackImplementation:
    """The track implementation of ``track`` (imported on first use: Exudyn, numba)."""
    if track == "fe":
        from exudyn_turnout.passage import fe_track

        return cast(TrackImplementation, fe_track)
    from exudyn_turnout.passage import corunning_track

    return cast(TrackImplementation, corunning_track)


def _route(turnout: Turnout, settings: PassageSettings, x_range: tuple[float, float]) -> Route:
    """The settings' route, with a warning where the speed exceeds the route's permitted."""
    route = load_route(turnout, settings.route)
    for text in speed_warnings(route, settings.speed_kmh, *x_range):
        warnings.warn(text, SpeedWarning, stacklevel=3)
    return route


def _contact(turnout: Turnout, settings: PassageSettings, route_name: str, vehicle: Vehicle):
    """The route's contact named by ``settings.contact`` (checked by the settings' check)."""
    if settings.contact == "height-table":
        from exudyn_turnout.passage.contact.height_table import HeightTableContact

        return HeightTableContact()
    from exudyn_turnout.passage.contact.profile import route_contact
    from exudyn_turnout.wheel_rail.packed_tables import scale_contact_law

    try:
        contact = route_contact(turnout, route_name, vehicle)
    except ValueError as err:
        raise PassageError(str(err)) from None
    tables = scale_contact_law(
        contact.tables, normal=settings.normal_stiffness_factor, creep=settings.creep_reduction
    )
    return contact if tables is contact.tables else replace(contact, tables=tables)


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
    vehicle : {"manchester", "wheelset"}, Vehicle or VehicleModel, optional
        Default: the full Manchester vehicle (:data:`DEFAULT_VEHICLE`).

    Returns
    -------
    dict
        {2: PassageResult, 3: PassageResult}.
    """
    return {
        layers: simulate_passage(turnout, settings, vehicle, track=f"{layers}-layer")
        for layers in (2, 3)
    }


def compare_tracks(
    turnout: Turnout,
    settings: PassageSettings = DEFAULT_SETTINGS,
    tracks: tuple[str, ...] | list[str] = ("2-layer", "3-layer"),
    vehicle: Vehicle | VehicleModel | str | None = None,
    progress: Callable[[str, float, float], None] | None = None,
) -> PassageComparison:
    """The same passage on several tracks, in the given order (the paper's Figs 7, 8).

    Parameters
    ----------
    turnout : Turnout
    settings : PassageSettings
    tracks : sequence of {"2-layer", "3-layer", "fe"}
        Each at most once.
    vehicle : {"manchester", "wheelset"}, Vehicle or VehicleModel, optional
        Default: the full Manchester vehicle (:data:`DEFAULT_VEHICLE`).
    progress : callable(track, fraction, x), optional
        Called about every 2 % of each run, with the track's name.

    Returns
    -------
    PassageComparison
        Track -> PassageResult; ``.plot()`` overlays them, ``.table()`` and ``.record()``
        give the peaks and each track against the 2-layer track in %.

    Raises
    ------
    PassageError
        An unknown or repeated track, or bad settings.
    """
    names = list(tracks)
    if not names or len(set(names)) != len(names):
        raise PassageError(f"tracks must be distinct and at least one, got {names}")
    for name in names:
        track_of(settings, name)  # an unknown track fails before any run
    results = {}
    for name in names:
        report = None if progress is None else _tagged(progress, name)
        results[name] = simulate_passage(turnout, settings, vehicle, report, track=name)
    return PassageComparison(results)


def _tagged(progress: Callable[[str, float, float], None], track: str):
    """A run's progress callback that names its track."""

    def report(fraction: float, x: float) -> None:
        progress(track, fraction, x)

    return report
