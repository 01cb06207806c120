"""The railway vehicle file: read and validate it into a :class:`VehicleModel`.

:func:`load_vehicle_model` reads a vehicle file (TOML, SI units) into the frozen
:class:`VehicleModel` (:mod:`.vehicle_data`); the packaged default is
``data/manchester_vehicle.toml``, the Manchester benchmark vehicle 1 (Iwnicki (ed.),
Vehicle System Dynamics 30(3-4) (1998) 295-313). One file layout describes

- a full vehicle: a car body on two bogies, two wheelsets per bogie (``bogies = 2``), or
- single wheelsets, each under its own sprung share (``bogies = 0``, a ``[sprung_mass]``
  table, no car body, no secondary suspension): the package's fast study model.

Axes: x forward, y left, z up; heights above the rail top; x of every body relative to the
vehicle reference, the front wheelset at x = 0 (the others behind it, x < 0).

The vehicle's dataclasses (:mod:`.vehicle_data`) and the hand calculations of its natural
frequencies (:mod:`.vehicle_frequencies`) are re-exported here.

Errors in a file raise :class:`VehicleModelError` (a ``ValueError``) with one line naming
the file and the field, e.g. ``v.toml: car_body.mass must be > 0, got -1``.
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Mapping
from importlib import resources
from pathlib import Path
from typing import Any

from exudyn_turnout.inputs.vehicle import PRIMARY_STIFFNESS_MIN
from exudyn_turnout.inputs.vehicle_data import (
    GRAVITY,
    BodyData,
    BumpStop,
    SprungMass,
    SuspensionData,
    VehicleModel,
    WheelsetData,
    single_wheelset_share,
)
from exudyn_turnout.inputs.vehicle_frequencies import (
    bogie_bounce_frequency,
    bogie_pitch_frequency,
    bogie_sway_frequencies,
    carbody_bounce_frequency,
    carbody_pitch_frequency,
    carbody_sway_frequencies,
    carbody_yaw_frequency,
    hand_frequencies,
    series,
    sway_frequencies,
    wheelset_bounce_frequency,
)
from exudyn_turnout.inputs.vehicle_names import PACKAGED_VEHICLES, packaged_vehicle_path

__all__ = [
    "GRAVITY",
    "VehicleModelError",
    "BodyData",
    "WheelsetData",
    "SuspensionData",
    "BumpStop",
    "SprungMass",
    "VehicleModel",
    "default_vehicle_model_path",
    "load_vehicle_model",
    "single_wheelset_share",
    "series",
    "sway_frequencies",
    "carbody_bounce_frequency",
    "carbody_pitch_frequency",
    "carbody_yaw_frequency",
    "carbody_sway_frequencies",
    "bogie_bounce_frequency",
    "bogie_pitch_frequency",
    "bogie_sway_frequencies",
    "wheelset_bounce_frequency",
    "hand_frequencies",
]


class VehicleModelError(ValueError):
    """A vehicle file cannot be read, misses a field or holds a value that cannot be right."""


def default_vehicle_model_path() -> Path:
    """Path of the packaged Manchester benchmark vehicle 1 file.

    Returns
    -------
    Path
        ``data/manchester_vehicle.toml`` inside the installed package.
    """
    return Path(str(resources.files("exudyn_turnout") / "data" / "manchester_vehicle.toml"))


# ----------------------------------------------------------------------------------- reading
#: Plausibility bounds (upper limits, SI) of vehicle-file quantities.
_BOUNDS = {
    "mass": 1e6,
    "inertia": 1e7,
    "height": 10.0,
    "spacing": 5.0,
    "stiffness": 1e12,
    "damping": 1e10,
    "x": 1e3,
    "rot_stiffness": 1e12,
    "force": 1e8,
    "clearance": 0.5,
}


class _Fields:
    """Reads fields of a parsed vehicle file; one error naming file and field per problem."""

    def __init__(self, filename: str, data: Mapping[str, Any]):
        self.filename = filename
        self.data = data

    def fail(self, field: str, problem: str) -> VehicleModelError:
        return VehicleModelError(f"{self.filename}: {field} {problem}")

    def has(self, table: str) -> bool:
        return table in self.data

    def get(self, field: str) -> Any:
        node: Any = self.data
        for part in field.split("."):
            if not isinstance(node, Mapping) or part not in node:
                raise self.fail(field, "is missing")
            node = node[part]
        return node

    def text(self, field: str) -> str:
        value = self.get(field)
        if not isinstance(value, str):
            raise self.fail(field, f"must be a string, got {value!r}")
        return value

    def check(self, field: str, value: Any, kind: str, positive: bool = True) -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.fail(field, f"must be a number, got {value!r}")
        if not math.isfinite(value):
            raise self.fail(field, f"must be finite, got {value!r}")
        if kind == "x":
            if abs(value) > _BOUNDS["x"]:
                raise self.fail(field, f"must be within +-{_BOUNDS['x']:g} m, got {value:g}")
            return float(value)
        if positive and value <= 0:
            raise self.fail(field, f"must be > 0, got {value:g}")
        if value < 0:
            raise self.fail(field, f"must be >= 0, got {value:g}")
        if value > _BOUNDS[kind]:
            raise self.fail(
                field, f"must be <= {_BOUNDS[kind]:g} (physically plausible bound), got {value:g}"
            )
        return float(value)

    def number(self, field: str, kind: str, positive: bool = True) -> float:
        return self.check(field, self.get(field), kind, positive)

    def numbers(self, field: str, kind: str, positive: bool = True) -> tuple[float, ...]:
        value = self.get(field)
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            value = [value]
        if not isinstance(value, list) or not value:
            raise self.fail(
                field, f"must be a number or a non-empty list of numbers, got {value!r}"
            )
        return tuple(self.check(f"{field}[{i}]", v, kind, positive) for i, v in enumerate(value))

    def integer(self, field: str, lo: int, hi: int) -> int:
        return _integer(self, field, self.get(field), lo, hi)


def _read(path: Path) -> dict:
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise VehicleModelError(f"{path.name}: cannot be read ({exc.strerror or exc})") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        raise VehicleModelError(f"{path.name}: is not UTF-8 text") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise VehicleModelError(f"{path.name}: is not valid TOML ({exc})") from None


def _body(reader: _Fields, table: str, count: int | None) -> BodyData:
    x: tuple[float, ...]
    if count is None:  # the car body: one position
        x = (reader.number(f"{table}.x", "x"),)
    else:
        x = reader.numbers(f"{table}.x", "x")
        if len(x) != count:
            raise reader.fail(
                f"{table}.x", f"must list {count} positions (vehicle.bogies), got {len(x)}"
            )
    return BodyData(
        reader.number(f"{table}.mass", "mass"),
        reader.number(f"{table}.roll_inertia", "inertia"),
        reader.number(f"{table}.pitch_inertia", "inertia"),
        reader.number(f"{table}.yaw_inertia", "inertia"),
        reader.number(f"{table}.cog_height", "height"),
        x,
    )


def _suspension(reader: _Fields, table: str) -> SuspensionData:
    k = {name: reader.number(f"{table}.{name}", "stiffness") for name in ("k_x", "k_y", "k_z")}
    if table == "primary_suspension":  # the bound and its source: vehicle.PRIMARY_STIFFNESS_MIN
        for name, value in k.items():
            if value < PRIMARY_STIFFNESS_MIN:
                raise reader.fail(
                    f"{table}.{name}",
                    f"must be >= {PRIMARY_STIFFNESS_MIN:g} N/m (primary springs are 0.5-30 "
                    f"MN/m per axlebox; a unit slip?), got {value:g}",
                )
    return SuspensionData(
        k_x=k["k_x"],
        k_y=k["k_y"],
        k_z=k["k_z"],
        c_x=reader.number(f"{table}.c_x", "damping", positive=False),
        c_y=reader.number(f"{table}.c_y", "damping", positive=False),
        c_z=reader.number(f"{table}.c_z", "damping", positive=False),
        semi_spacing=reader.number(f"{table}.semi_spacing", "spacing"),
        height=reader.number(f"{table}.height", "height"),
    )


def _bumpstop(reader: _Fields) -> BumpStop:
    table = "lateral_bumpstop"
    clearance = reader.number(f"{table}.clearance", "clearance")
    u = reader.numbers(f"{table}.displacement", "clearance")
    f = reader.numbers(f"{table}.force", "force", positive=False)
    if len(f) != len(u):
        raise reader.fail(
            f"{table}.force", f"must have one value per displacement ({len(u)}), got {len(f)}"
        )
    if u[0] <= clearance or any(b <= a for a, b in zip(u, u[1:])):
        raise reader.fail(
            f"{table}.displacement", "must increase strictly and start beyond the clearance"
        )
    if any(b < a for a, b in zip(f, f[1:])):
        raise reader.fail(f"{table}.force", "must not decrease")
    return BumpStop(clearance, reader.number(f"{table}.height", "height"), u, f)


def _wheelset(reader: _Fields, n_wheelsets: int, n_bogies: int) -> WheelsetData:
    table = "wheelset"
    radius = reader.number(f"{table}.wheel_radius", "height")
    if not 0.1 <= radius <= 2.0:
        raise reader.fail(
            f"{table}.wheel_radius", f"must be in 0.1..2 m (a railway wheel), got {radius:g}"
        )
    x = reader.numbers(f"{table}.x", "x")
    if len(x) != n_wheelsets:
        raise reader.fail(
            f"{table}.x", f"must list {n_wheelsets} positions (vehicle.wheelsets), got {len(x)}"
        )
    if x[0] != 0.0 or any(b >= a for a, b in zip(x, x[1:])):
        raise reader.fail(
            f"{table}.x", "must start at 0 (the front wheelset) and decrease strictly"
        )
    if n_bogies:
        raw = reader.get(f"{table}.bogie")
        if not isinstance(raw, list) or len(raw) != n_wheelsets:
            raise reader.fail(
                f"{table}.bogie", f"must list one bogie number per wheelset, got {raw!r}"
            )
        bogie = tuple(
            _integer(reader, f"{table}.bogie[{i}]", v, 1, n_bogies) - 1 for i, v in enumerate(raw)
        )
        for j in range(n_bogies):
            if bogie.count(j) != 2:
                raise reader.fail(
                    f"{table}.bogie", f"must give bogie {j + 1} exactly two wheelsets"
                )
    else:
        bogie = (-1,) * n_wheelsets
    b = reader.number(f"{table}.contact_semi_spacing", "spacing")
    back = reader.number(f"{table}.back_to_back", "spacing")
    if back >= 2.0 * b:
        raise reader.fail(
            f"{table}.back_to_back", f"must be < 2 contact_semi_spacing ({2 * b:g} m), got {back:g}"
        )
    return WheelsetData(
        reader.number(f"{table}.mass", "mass"),
        reader.number(f"{table}.roll_inertia", "inertia"),
        reader.number(f"{table}.spin_inertia", "inertia"),
        reader.number(f"{table}.yaw_inertia", "inertia"),
        radius,
        back,
        b,
        x,
        bogie,
    )


def _integer(reader: _Fields, field: str, value: Any, lo: int, hi: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise reader.fail(field, f"must be an integer, got {value!r}")
    if not lo <= value <= hi:
        raise reader.fail(field, f"must be in {lo}..{hi}, got {value}")
    return int(value)


def load_vehicle_model(path: str | Path | None = None) -> VehicleModel:
    """Load and validate a vehicle file (default: the packaged Manchester vehicle 1).

    Every number must be finite, > 0 (dampings, yaw and anti-roll stiffness, bumpstop
    forces >= 0) and within a plausibility bound: masses <= 1e6 kg, inertias <= 1e7 kg m^2,
    heights <= 10 m, semi-spacings <= 5 m, stiffnesses <= 1e12 N/m (N m/rad), dampings
    <= 1e10 N s/m, positions |x| <= 1e3 m, wheel radius 0.1..2 m; the counts
    ``vehicle.wheelsets`` (1..16) and ``vehicle.bogies`` (0 or 2) must match the positions;
    a bogie has exactly two wheelsets; with bogies the file has ``[car_body]``, ``[bogie]``,
    ``[secondary_suspension]``, ``[secondary_yaw]``, ``[anti_roll]``,
    ``[lateral_bumpstop]`` and no ``[sprung_mass]``; without bogies it is the other way.
    Tables the vehicle model does not use (e.g. ``[contact]``) are ignored.

    Parameters
    ----------
    path : str or Path, optional
        TOML vehicle file, or the name of a packaged one (``"manchester"``, see
        :mod:`.vehicle_names`; a file of that name in the working directory comes first).

    Returns
    -------
    VehicleModel
        The validated content; ``source`` is the file's name.

    Raises
    ------
    VehicleModelError
        The file cannot be read, is not UTF-8 TOML, or a field is missing or out of range;
        one line naming the file and the field. A single-wheelset vehicle file (no
        ``[vehicle]``, a ``[contact]`` table), which
        :func:`~exudyn_turnout.inputs.vehicle.load_vehicle` reads: one line saying so.
    """
    if path is None:
        path = default_vehicle_model_path()
    elif isinstance(path, str) and path in PACKAGED_VEHICLES and not Path(path).exists():
        path = packaged_vehicle_path(path)
    path = Path(path)
    data = _read(path)
    if "vehicle" not in data and "contact" in data and "wheelset" in data:
        raise VehicleModelError(
            f"{path.name}: is a single-wheelset vehicle file (no [vehicle] table): load it "
            "with exudyn_turnout.inputs.vehicle.load_vehicle "
            "(or exudyn_turnout.inputs.vehicles.packaged_vehicle('wheelset'))"
        )
    reader = _Fields(path.name, data)
    n_wheelsets = reader.integer("vehicle.wheelsets", 1, 16)
    n_bogies = reader.integer("vehicle.bogies", 0, 2)
    if n_bogies == 1:
        raise reader.fail(
            "vehicle.bogies", "must be 0 (single wheelsets) or 2 (car body on two bogies)"
        )
    full_tables: tuple[str, ...] = (
        "car_body",
        "bogie",
        "secondary_suspension",
        "secondary_yaw",
        "anti_roll",
        "lateral_bumpstop",
    )
    single_tables: tuple[str, ...] = ("sprung_mass",)
    required, forbidden = full_tables, single_tables
    if not n_bogies:
        required, forbidden = forbidden, required
    for table in required:
        if not reader.has(table):
            raise reader.fail(f"[{table}]", f"is missing (vehicle.bogies = {n_bogies})")
    for table in forbidden:
        if reader.has(table):
            raise reader.fail(f"[{table}]", f"must be absent (vehicle.bogies = {n_bogies})")
    wheelset = _wheelset(reader, n_wheelsets, n_bogies)
    primary = _suspension(reader, "primary_suspension")
    car_body: BodyData | None
    bogie: BodyData | None
    secondary: SuspensionData | None
    bumpstop: BumpStop | None
    sprung: SprungMass | None
    if n_bogies:
        if n_wheelsets != 2 * n_bogies:
            raise reader.fail(
                "vehicle.wheelsets", f"must be 2 per bogie ({2 * n_bogies}), got {n_wheelsets}"
            )
        car_body, bogie = _body(reader, "car_body", None), _body(reader, "bogie", n_bogies)
        if not bogie.x[0] > car_body.x[0] > bogie.x[1]:
            raise reader.fail("car_body.x", "must lie between the bogie centres")
        secondary = _suspension(reader, "secondary_suspension")
        k_yaw = reader.number("secondary_yaw.stiffness", "rot_stiffness", positive=False)
        k_roll = reader.number("anti_roll.stiffness", "rot_stiffness", positive=False)
        bumpstop, sprung = _bumpstop(reader), None
    else:
        car_body = bogie = secondary = bumpstop = None
        k_yaw = k_roll = 0.0
        sprung = SprungMass(
            reader.number("sprung_mass.mass", "mass"), reader.number("sprung_mass.height", "height")
        )
    return VehicleModel(
        reader.text("vehicle.name"),
        reader.text("vehicle.description"),
        reader.text("vehicle.reference"),
        wheelset,
        primary,
        car_body,
        bogie,
        secondary,
        k_yaw,
        k_roll,
        bumpstop,
        sprung,
        path.name,
    )
