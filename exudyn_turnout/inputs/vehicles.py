"""A packaged vehicle by name, loaded: the single wheelset or the full Manchester vehicle.

:func:`packaged_vehicle` reads the file of a name of :data:`.vehicle_names.PACKAGED_VEHICLES`
with the loader of its kind: ``"wheelset"`` gives the single-wheelset
:class:`~exudyn_turnout.inputs.vehicle.Vehicle` (:func:`.vehicle.load_vehicle`),
``"manchester"`` the full :class:`~exudyn_turnout.inputs.vehicle_data.VehicleModel`
(:func:`.vehicle_model.load_vehicle_model`).
"""

from __future__ import annotations

from exudyn_turnout.inputs.vehicle import Vehicle, load_vehicle
from exudyn_turnout.inputs.vehicle_data import VehicleModel
from exudyn_turnout.inputs.vehicle_model import load_vehicle_model
from exudyn_turnout.inputs.vehicle_names import (
    FULL_VEHICLE,
    PACKAGED_VEHICLES,
    packaged_vehicle_kind,
    packaged_vehicle_path,
)

__all__ = ["PACKAGED_VEHICLES", "packaged_vehicle", "packaged_vehicle_names"]


def packaged_vehicle_names() -> tuple[str, ...]:
    """Names accepted by :func:`packaged_vehicle`.

    Returns
    -------
    tuple of str
        ``("wheelset", "manchester")``.
    """
    return tuple(PACKAGED_VEHICLES)


def packaged_vehicle(name: str) -> Vehicle | VehicleModel:
    """Load a packaged vehicle by name.

    Parameters
    ----------
    name : str
        ``"wheelset"``: one wheelset of the Manchester benchmark vehicle 1 under its sprung
        share (``data/manchester_wheelset.toml``); ``"manchester"``: the full Manchester
        benchmark vehicle 1, car body on two bogies (``data/manchester_vehicle.toml``).

    Returns
    -------
    Vehicle or VehicleModel
        A :class:`~exudyn_turnout.inputs.vehicle.Vehicle` for ``"wheelset"``, a
        :class:`~exudyn_turnout.inputs.vehicle_data.VehicleModel` for ``"manchester"``.

    Raises
    ------
    TurnoutFileError
        Unknown name; one line listing the names.
    """
    path = packaged_vehicle_path(name)
    if packaged_vehicle_kind(name) == FULL_VEHICLE:
        return load_vehicle_model(path)
    return load_vehicle(path)
