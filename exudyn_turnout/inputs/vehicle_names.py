"""The packaged vehicle files by name.

========== ================================== =============================================
name       file (``exudyn_turnout/data/``)     read by
========== ================================== =============================================
wheelset   ``manchester_wheelset.toml``        :func:`.vehicle.load_vehicle`: one wheelset
                                               of the Manchester benchmark vehicle 1 under
                                               its sprung share (a ``Vehicle``)
manchester ``manchester_vehicle.toml``         :func:`.vehicle_model.load_vehicle_model`:
                                               the full Manchester benchmark vehicle 1, car
                                               body on two bogies (a ``VehicleModel``)
========== ================================== =============================================

:func:`.vehicles.packaged_vehicle` loads one by name; :func:`.vehicle.load_vehicle` and
:func:`.vehicle_model.load_vehicle_model` accept the names of their kind in place of a path.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from exudyn_turnout.inputs.toml_fields import TurnoutFileError

__all__ = [
    "PACKAGED_VEHICLES",
    "SINGLE_WHEELSET",
    "FULL_VEHICLE",
    "packaged_vehicle_kind",
    "packaged_vehicle_path",
]

#: Kind of a packaged vehicle read by :func:`.vehicle.load_vehicle` (a ``Vehicle``).
SINGLE_WHEELSET = "single wheelset"
#: Kind of a packaged vehicle read by :func:`.vehicle_model.load_vehicle_model`.
FULL_VEHICLE = "full vehicle"

#: name -> (file in ``exudyn_turnout/data``, kind).
PACKAGED_VEHICLES: dict[str, tuple[str, str]] = {
    "wheelset": ("manchester_wheelset.toml", SINGLE_WHEELSET),
    "manchester": ("manchester_vehicle.toml", FULL_VEHICLE),
}


def _known(name: str) -> tuple[str, str]:
    if name not in PACKAGED_VEHICLES:
        raise TurnoutFileError(
            f"unknown packaged vehicle {name!r} (packaged: {', '.join(PACKAGED_VEHICLES)})"
        )
    return PACKAGED_VEHICLES[name]


def packaged_vehicle_path(name: str) -> Path:
    """Path of a packaged vehicle file by name.

    Parameters
    ----------
    name : str
        A key of :data:`PACKAGED_VEHICLES` (``"wheelset"``, ``"manchester"``).

    Returns
    -------
    Path
        The file inside the installed package.

    Raises
    ------
    TurnoutFileError
        Unknown name; one line listing the names.
    """
    filename, _ = _known(name)
    return Path(str(resources.files("exudyn_turnout") / "data" / filename))


def packaged_vehicle_kind(name: str) -> str:
    """Kind of a packaged vehicle: :data:`SINGLE_WHEELSET` or :data:`FULL_VEHICLE`.

    Parameters
    ----------
    name : str
        A key of :data:`PACKAGED_VEHICLES`.

    Returns
    -------
    str
        Its kind.

    Raises
    ------
    TurnoutFileError
        Unknown name; one line listing the names.
    """
    return _known(name)[1]
