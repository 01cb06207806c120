"""The railway vehicle as data: bodies, suspensions, bumpstop; derived loads; hand frequencies.

Pure data and arithmetic (no Exudyn, no plotting). :func:`load_vehicle_model` reads a
vehicle file (TOML, SI units) into the frozen :class:`VehicleModel`; the packaged default
is ``data/manchester_vehicle.toml``, the Manchester benchmark vehicle 1 (Iwnicki (ed.),
Vehicle System Dynamics 30(3-4) (1998) 295-313). One file layout describes

- a full vehicle: a car body on two bogies, two wheelsets per bogie (``bogies = 2``), or
- single wheelsets, each under its own sprung share (``bogies = 0``, a ``[sprung_mass]``
  table, no car body, no secondary suspension): the package's fast study model.

Axes: x forward, y left, z up; heights above the rail top; x of every body relative to the
vehicle reference, the front wheelset at x = 0 (the others behind it, x < 0).

The ``*_frequency`` functions are hand calculations of natural frequencies on rigid track,
used as references for the Exudyn model (``tests/test_full_vehicle.py``). Each states its
source and its assumptions (which neighbours are held, which springs act in series).

Errors in a file raise :class:`VehicleModelError` (a ``ValueError``) with one line naming
the file and the field, e.g. ``v.toml: car_body.mass must be > 0, got -1``.
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, replace
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

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

GRAVITY = 9.81  #: m/s^2, as the package's single-wheelset model (vehicle.GRAVITY)


class VehicleModelError(ValueError):
    """A vehicle file cannot be read, misses a field or holds a value that cannot be right."""


@dataclass(frozen=True)
class BodyData:
    """A rigid body kind (car body or bogie frame) and where its copies sit."""

    mass: float  #: kg, each
    roll_inertia: float  #: kg m^2, Jx about the longitudinal axis through the CoG
    pitch_inertia: float  #: kg m^2, Jy about the lateral axis
    yaw_inertia: float  #: kg m^2, Jz about the vertical axis
    cog_height: float  #: m above the rail top
    x: tuple[float, ...]  #: m, longitudinal position of each copy (front wheelset at 0)


@dataclass(frozen=True)
class WheelsetData:
    """The wheelsets: one kind, several positions."""

    mass: float  #: kg, each
    roll_inertia: float  #: kg m^2, Jx
    spin_inertia: float  #: kg m^2, Jy about the axle
    yaw_inertia: float  #: kg m^2, Jz
    wheel_radius: float  #: m, nominal rolling radius r0 (= axle height above the rail)
    back_to_back: float  #: m, flange back distance
    contact_semi_spacing: float  #: m, lateral semi-distance of the nominal contact points
    x: tuple[float, ...]  #: m, position of each wheelset, x[0] = 0 (front), then decreasing
    bogie: tuple[int, ...]  #: 0-based bogie index of each wheelset, -1: none

    @property
    def cog_height(self) -> float:
        """Height (m) of the axle above the rail: the wheel radius."""
        return self.wheel_radius


@dataclass(frozen=True)
class SuspensionData:
    """One suspension element (per axlebox or per bogie side), acting along x, y, z."""

    k_x: float  #: N/m, longitudinal stiffness
    k_y: float  #: N/m, lateral stiffness
    k_z: float  #: N/m, vertical stiffness
    c_x: float  #: N s/m, longitudinal damping
    c_y: float  #: N s/m, lateral damping
    c_z: float  #: N s/m, vertical damping
    semi_spacing: float  #: m, lateral semi-spacing of the two elements of a body
    height: float  #: m above the rail top, where the element acts


@dataclass(frozen=True)
class BumpStop:
    """Lateral bumpstop between car body and bogie: free within +-clearance, then a table."""

    clearance: float  #: m, free play each side
    height: float  #: m above the rail, where it acts (at the bogie centre's x)
    displacement: tuple[float, ...]  #: m, increasing, all > clearance
    force: tuple[float, ...]  #: N at those displacements, non-decreasing, >= 0

    def ramps(self) -> tuple[tuple[float, ...], tuple[float, ...]]:
        """Breakpoints u_i (m) and slope increments s_i (N/m) of the characteristic.

        F(u) = sign(u) sum_i s_i max(|u| - u_i, 0): the table (with (clearance, 0) in front),
        linear in between and extrapolated with the last slope, as a sum of ramps; written
        with abs, max and sign only, so it serves Python and Exudyn symbolic functions.

        Returns
        -------
        tuple of tuple of float
            (breakpoints, slope increments), the same length.
        """
        u = (self.clearance,) + self.displacement
        f = (0.0,) + self.force
        slopes = [(f[i + 1] - f[i]) / (u[i + 1] - u[i]) for i in range(len(u) - 1)]
        slopes.append(slopes[-1])  # extrapolation beyond the table: the last slope
        increments = [slopes[0]] + [slopes[i] - slopes[i - 1] for i in range(1, len(u) - 1)]
        return u[:-1], tuple(increments)

    def lateral_force(self, u: float) -> float:
        """Force (N) at relative lateral displacement u (m); odd in u, 0 within the clearance.

        Parameters
        ----------
        u : float
            Relative lateral displacement car body minus bogie at the bumpstop (m).

        Returns
        -------
        float
            Restoring force magnitude with the sign of u (N).
        """
        points, increments = self.ramps()
        a = abs(u)
        return math.copysign(sum(s * max(a - p, 0.0) for p, s in zip(points, increments)), u)


@dataclass(frozen=True)
class SprungMass:
    """Share of bogie and car body carried by one wheelset (single-wheelset model)."""

    mass: float  #: kg, per wheelset
    height: float  #: m above the rail, where the point mass sits (primary springs reach it)


@dataclass(frozen=True)
class VehicleModel:
    """A vehicle file's content, SI units (see the module docstring for the two layouts)."""

    name: str
    description: str
    reference: str  #: literature source of the data
    wheelset: WheelsetData
    primary: SuspensionData  #: per axlebox
    car_body: BodyData | None  #: None for the single-wheelset layout
    bogie: BodyData | None  #: None for the single-wheelset layout
    secondary: SuspensionData | None  #: per bogie side
    secondary_yaw_stiffness: float  #: N m/rad per bogie, bogie vs car body about z
    anti_roll_stiffness: float  #: N m/rad per bogie, anti-roll bar (relative roll)
    bumpstop: BumpStop | None  #: lateral, one per bogie
    sprung_mass: SprungMass | None  #: per wheelset, single-wheelset layout only
    source: str  #: file name the model was read from ("" if built in code)

    @property
    def n_wheelsets(self) -> int:
        """Number of wheelsets."""
        return len(self.wheelset.x)

    @property
    def n_bogies(self) -> int:
        """Number of bogies (0 in the single-wheelset layout)."""
        return 0 if self.bogie is None else len(self.bogie.x)

    @property
    def total_mass(self) -> float:
        """Mass (kg) of the whole vehicle (for a single wheelset: wheelset + sprung share)."""
        m = self.n_wheelsets * self.wheelset.mass
        if self.car_body is not None:
            m += self.car_body.mass * len(self.car_body.x)
        if self.bogie is not None:
            m += self.bogie.mass * self.n_bogies
        if self.sprung_mass is not None:
            m += self.sprung_mass.mass * self.n_wheelsets
        return m

    @property
    def unsprung_mass_per_wheel(self) -> float:
        """Unsprung mass (kg) per wheel: half a wheelset."""
        return 0.5 * self.wheelset.mass

    def wheelset_loads(self) -> tuple[float, ...]:
        """Static vertical load (N) of each wheelset on level track, by the lever rule.

        The car body's weight goes to the two bogies in inverse proportion to their
        distance from its CoG, each bogie's load (its share plus its weight) to its two
        wheelsets the same way, plus each wheelset's own weight (statics, first principles).

        Returns
        -------
        tuple of float
            One load per wheelset (N), in the order of ``wheelset.x``.
        """
        wheelset = self.wheelset
        loads = [wheelset.mass * GRAVITY] * self.n_wheelsets
        if self.sprung_mass is not None:
            return tuple(load + self.sprung_mass.mass * GRAVITY for load in loads)
        body, bogie, _ = _full_vehicle_parts(self)
        x_bogies = bogie.x
        x_body = body.x[0]
        shares = _car_body_shares(x_body, x_bogies)
        for j, share in enumerate(shares):
            bogie_load = share * body.mass * GRAVITY + bogie.mass * GRAVITY
            mine = [i for i, b in enumerate(wheelset.bogie) if b == j]
            x0, x1 = wheelset.x[mine[0]], wheelset.x[mine[1]]
            loads[mine[0]] += bogie_load * (x_bogies[j] - x1) / (x0 - x1)
            loads[mine[1]] += bogie_load * (x0 - x_bogies[j]) / (x0 - x1)
        return tuple(loads)

    def static_wheel_loads(self) -> tuple[float, ...]:
        """Static wheel load (N) of each wheelset on straight level track: half its load.

        Returns
        -------
        tuple of float
            One value per wheelset (both wheels carry the same on level track).
        """
        return tuple(0.5 * q for q in self.wheelset_loads())

    @property
    def static_wheel_load(self) -> float:
        """Mean static wheel load (N): total weight / (2 n_wheelsets)."""
        return self.total_mass * GRAVITY / (2 * self.n_wheelsets)


def _full_vehicle_parts(model: VehicleModel) -> tuple[BodyData, BodyData, SuspensionData]:
    """The car body, the bogie kind and the secondary suspension of a full vehicle.

    Raises
    ------
    ValueError
        The model is a single-wheelset layout (no car body, bogies or secondary suspension).
    """
    if model.car_body is None or model.bogie is None or model.secondary is None:
        raise ValueError(f"{model.name}: has no car body and bogies (single-wheelset layout)")
    return model.car_body, model.bogie, model.secondary


def _car_body_shares(x_body: float, x_bogies: tuple[float, ...]) -> tuple[float, float]:
    """Shares of the car body's weight on bogie 1 and bogie 2 (lever rule, sum 1)."""
    span = x_bogies[0] - x_bogies[1]
    return (x_body - x_bogies[1]) / span, (x_bogies[0] - x_body) / span


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
    return SuspensionData(
        k_x=reader.number(f"{table}.k_x", "stiffness"),
        k_y=reader.number(f"{table}.k_y", "stiffness"),
        k_z=reader.number(f"{table}.k_z", "stiffness"),
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
        TOML vehicle file.

    Returns
    -------
    VehicleModel
        The validated content; ``source`` is the file's name.

    Raises
    ------
    VehicleModelError
        The file cannot be read, is not UTF-8 TOML, or a field is missing or out of range;
        one line naming the file and the field.
    """
    path = Path(path) if path is not None else default_vehicle_model_path()
    reader = _Fields(path.name, _read(path))
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


def single_wheelset_share(model: VehicleModel, index: int = 0) -> VehicleModel:
    """The single-wheelset study model of a full vehicle: one wheelset under its sprung share.

    The sprung mass is the wheelset's static load / g minus its own mass (lever rule; for
    the Manchester vehicle 32000 / 4 + 2615 / 2 = 9307.5 kg), at the primary springs'
    height, on the same primary suspension.

    Parameters
    ----------
    model : VehicleModel
        A full vehicle (with bogies), or a single-wheelset model (returned unchanged).
    index : int
        Which wheelset's share (0: the front one).

    Returns
    -------
    VehicleModel
        One wheelset at x = 0 with a ``sprung_mass`` and no car body, bogies, secondary
        suspension or bumpstop.
    """
    if model.sprung_mass is not None:
        return model
    share = model.wheelset_loads()[index] / GRAVITY - model.wheelset.mass
    wheelset = replace(model.wheelset, x=(0.0,), bogie=(-1,))
    return replace(
        model,
        name=f"{model.name}, wheelset {index + 1} with its sprung share",
        wheelset=wheelset,
        car_body=None,
        bogie=None,
        secondary=None,
        secondary_yaw_stiffness=0.0,
        anti_roll_stiffness=0.0,
        bumpstop=None,
        sprung_mass=SprungMass(share, model.primary.height),
    )


# -------------------------------------------------------------------------- hand calculations
def series(*stiffnesses: float) -> float:
    """Stiffness of springs in series, 1 / sum(1 / k_i) (first principles; inf allowed).

    Parameters
    ----------
    *stiffnesses : float
        Stiffnesses (any consistent unit); ``math.inf`` is a rigid link.

    Returns
    -------
    float
        The series stiffness (same unit as the inputs).
    """
    return 1.0 / sum(1.0 / k for k in stiffnesses)


def _hz(k: float, m: float) -> float:
    return math.sqrt(k / m) / (2.0 * math.pi)


def sway_frequencies(
    mass: float, roll_inertia: float, k_lateral: float, lever: float, k_roll: float
) -> tuple[float, float]:
    """Coupled lateral-roll (sway) frequencies of a rigid body on springs, 2x2 (Hz).

    First principles (as Garg & Dukkipati, Dynamics of Railway Vehicle Systems, 1984,
    ch. 7, lateral/roll model of a car body): coordinates y (lateral, at the CoG) and phi
    (roll, positive lifting the left side); the lateral springs act at ``lever`` above the
    CoG (negative: below), where the lateral displacement is y - lever phi, so
    ``K = [[k, -k e], [-k e, k e^2 + k_roll]]``, ``M = diag(m, J)``.

    Parameters
    ----------
    mass : float
        kg.
    roll_inertia : float
        kg m^2 about the longitudinal axis through the CoG.
    k_lateral : float
        N/m, total lateral stiffness.
    lever : float
        m, height of the lateral springs relative to the CoG.
    k_roll : float
        N m/rad, roll stiffness from the vertical springs (and anti-roll bars), including
        the gravitational term (negative for a body standing on springs below its CoG).

    Returns
    -------
    tuple of float
        (lower sway, upper sway) frequencies in Hz.
    """
    k = np.array(
        [[k_lateral, -k_lateral * lever], [-k_lateral * lever, k_lateral * lever**2 + k_roll]]
    )
    w2 = np.linalg.eigvalsh(k / np.sqrt(np.outer([mass, roll_inertia], [mass, roll_inertia])))
    lo, hi = np.sqrt(np.clip(w2, 0.0, None)) / (2.0 * math.pi)
    return float(lo), float(hi)


def _wheelsets_of(model: VehicleModel, j: int) -> list[int]:
    return [i for i, b in enumerate(model.wheelset.bogie) if b == j]


def _primary_vertical(model: VehicleModel, k_track_z: float) -> float:
    """Vertical stiffness (N/m) of one axlebox spring in series with its wheel's track spring."""
    return series(model.primary.k_z, k_track_z)


def _per_bogie_vertical(model: VehicleModel, k_track_z: float) -> float:
    """Vertical stiffness (N/m) under the car body at one bogie: secondary in series with the
    bogie's four axlebox springs (each in series with its track spring); bogie mass neglected."""
    _, _, secondary = _full_vehicle_parts(model)
    return series(2.0 * secondary.k_z, 4.0 * _primary_vertical(model, k_track_z))


def carbody_bounce_frequency(model: VehicleModel, k_track_z: float = math.inf) -> float:
    """Car body bounce (Hz): f = sqrt(K / m) / 2 pi.

    K: per bogie the two secondary springs in series with the four axlebox springs (each in
    series with the wheel's track spring ``k_track_z``), summed over the bogies; the bogie
    mass is neglected (quasi-static series: Iwnicki (ed.), Handbook of Railway Vehicle
    Dynamics, 2006, ch. 5 "Suspension components", the suspension stages of a bogie vehicle
    in series; first principles). Bounce and pitch uncouple for a car body midway between
    the bogies.

    Parameters
    ----------
    model : VehicleModel
        A full vehicle.
    k_track_z : float
        N/m, vertical support stiffness under each wheel (default: rigid).

    Returns
    -------
    float
        Hz.
    """
    car_body, _, _ = _full_vehicle_parts(model)
    return _hz(model.n_bogies * _per_bogie_vertical(model, k_track_z), car_body.mass)


def carbody_pitch_frequency(model: VehicleModel, k_track_z: float = math.inf) -> float:
    """Car body pitch (Hz): K = sum_bogies (K_b a_b^2 + 2 k_x2 e^2) + m g e, J = Jy.

    K_b as in :func:`carbody_bounce_frequency`, a_b the bogie centre's distance from the
    car body's CoG; e = height of the secondary springs minus the CoG height (< 0): pitch
    moves the springs' ends longitudinally by e theta against the bogies (the car body's
    longitudinal position is held by the moving frame), and m g e is the gravitational term
    of a body standing on vertical springs below its CoG (first principles; Garg &
    Dukkipati 1984, ch. 7).

    Parameters
    ----------
    model : VehicleModel
        A full vehicle.
    k_track_z : float
        N/m, vertical support stiffness under each wheel (default: rigid).

    Returns
    -------
    float
        Hz.
    """
    car_body, bogie, secondary = _full_vehicle_parts(model)
    e = secondary.height - car_body.cog_height
    k = sum(
        _per_bogie_vertical(model, k_track_z) * (x_bogie - car_body.x[0]) ** 2
        + 2.0 * secondary.k_x * e**2
        for x_bogie in bogie.x
    )
    return _hz(k + car_body.mass * GRAVITY * e, car_body.pitch_inertia)


def carbody_yaw_frequency(model: VehicleModel) -> float:
    """Car body yaw on the secondary suspension, bogies held (Hz).

    K = sum over bogies of 2 k_y a_b^2 (lateral springs at the bogie centre's distance a_b
    from the CoG) + 2 k_x b^2 (longitudinal springs at the lateral semi-spacing b) +
    the secondary yaw stiffness; J = Jz (first principles; Garg & Dukkipati 1984, ch. 7).

    Parameters
    ----------
    model : VehicleModel
        A full vehicle.

    Returns
    -------
    float
        Hz.
    """
    car_body, bogie, secondary = _full_vehicle_parts(model)
    k = sum(
        2.0 * secondary.k_y * (x_bogie - car_body.x[0]) ** 2
        + 2.0 * secondary.k_x * secondary.semi_spacing**2
        + model.secondary_yaw_stiffness
        for x_bogie in bogie.x
    )
    return _hz(k, car_body.yaw_inertia)


def carbody_sway_frequencies(
    model: VehicleModel, k_track_z: float = math.inf, bogies_held: bool = False
) -> tuple[float, float]:
    """Car body lower and upper sway (coupled lateral-roll), 2x2 (Hz).

    :func:`sway_frequencies` with: lateral springs 2 k_y2 per bogie at the secondary
    height (in series with the bogie's four primary k_y1 unless ``bogies_held``); roll
    stiffness per bogie (2 k_z2 b2^2 + anti-roll bar) in series with the primary roll
    stiffness 4 k_z1 b1^2 (unless ``bogies_held``); gravitational term m g e with
    e = secondary height - CoG height (< 0). Bogie masses neglected (quasi-static series).

    Parameters
    ----------
    model : VehicleModel
        A full vehicle.
    k_track_z : float
        N/m, vertical support stiffness under each wheel (default: rigid).
    bogies_held : bool
        True: the textbook model on the secondary suspension alone.

    Returns
    -------
    tuple of float
        (lower, upper) in Hz.
    """
    car_body, _, secondary = _full_vehicle_parts(model)
    primary = model.primary
    k_lat = 2.0 * secondary.k_y
    k_roll = 2.0 * secondary.k_z * secondary.semi_spacing**2 + model.anti_roll_stiffness
    if not bogies_held:
        k_lat = series(k_lat, 4.0 * primary.k_y)
        k_roll = series(k_roll, 4.0 * _primary_vertical(model, k_track_z) * primary.semi_spacing**2)
    e = secondary.height - car_body.cog_height
    return sway_frequencies(
        car_body.mass,
        car_body.roll_inertia,
        model.n_bogies * k_lat,
        e,
        model.n_bogies * k_roll + car_body.mass * GRAVITY * e,
    )


def bogie_bounce_frequency(model: VehicleModel, k_track_z: float = math.inf) -> float:
    """Bogie frame bounce with car body held (Hz): K = 4 k_z1 (series track) + 2 k_z2.

    First principles: the car body is ~12x heavier and bounces at ~1 Hz, far below, so it
    acts as held; the axlebox springs stand on the wheelsets on the track springs.

    Parameters
    ----------
    model : VehicleModel
        A full vehicle.
    k_track_z : float
        N/m, vertical support stiffness under each wheel (default: rigid).

    Returns
    -------
    float
        Hz.
    """
    _, bogie, secondary = _full_vehicle_parts(model)
    k = 4.0 * _primary_vertical(model, k_track_z) + 2.0 * secondary.k_z
    return _hz(k, bogie.mass)


def bogie_pitch_frequency(model: VehicleModel, k_track_z: float = math.inf, j: int = 0) -> float:
    """Bogie frame pitch, car body and wheelsets held longitudinally (Hz).

    K = sum over its axleboxes of k_z1 a^2 (a: axle distance from the bogie centre)
    + 4 k_x1 h1^2 + 2 k_x2 h2^2 (longitudinal springs at heights h1, h2 relative to the
    bogie CoG) + the gravitational terms sum F_i h_i of the preloaded vertical springs;
    J = Jy (first principles).

    Parameters
    ----------
    model : VehicleModel
        A full vehicle.
    k_track_z : float
        N/m, vertical support stiffness under each wheel (default: rigid).
    j : int
        Bogie index.

    Returns
    -------
    float
        Hz.
    """
    _, bogie, secondary = _full_vehicle_parts(model)
    primary = model.primary
    h1, h2 = primary.height - bogie.cog_height, secondary.height - bogie.cog_height
    kz = _primary_vertical(model, k_track_z)
    k = sum(2.0 * kz * (model.wheelset.x[i] - bogie.x[j]) ** 2 for i in _wheelsets_of(model, j))
    k += 4.0 * primary.k_x * h1**2 + 2.0 * secondary.k_x * h2**2 + _bogie_gravity_term(model, j)
    return _hz(k, bogie.pitch_inertia)


def _bogie_gravity_term(model: VehicleModel, j: int) -> float:
    """sum_i F_i h_i (N m/rad) of the preloaded vertical springs on bogie j: primary forces up
    at h1, secondary forces down at h2 (relative to the bogie CoG): the geometric stiffness
    of rotating a body under vertical point loads (first principles)."""
    car_body, bogie, secondary = _full_vehicle_parts(model)
    share = _car_body_shares(car_body.x[0], bogie.x)[j] * car_body.mass * GRAVITY
    h1 = model.primary.height - bogie.cog_height
    h2 = secondary.height - bogie.cog_height
    return (share + bogie.mass * GRAVITY) * h1 - share * h2


def bogie_sway_frequencies(
    model: VehicleModel, k_track_z: float = math.inf, k_track_y: float = math.inf, j: int = 0
) -> tuple[float, float]:
    """Bogie frame lower and upper sway (coupled lateral-roll), car body held (Hz).

    For the Manchester bogie the lower mode is ~80 % roll (kinetic energy), the upper ~80 %
    lateral (the lateral springs act 0.14 m below and 0.23 m above the CoG).

    :func:`sway_frequencies` with lateral springs 4 k_y1 at the primary height (each
    wheelset's pair in series with its two track springs ``k_track_y``) and 2 k_y2 at the
    secondary height (their combined lever about the CoG), roll stiffness
    4 k_z1 b1^2 (series track) + 2 k_z2 b2^2 + anti-roll bar + the gravitational term
    (first principles; car body ~33x the bogie's roll inertia: held).

    Parameters
    ----------
    model : VehicleModel
        A full vehicle.
    k_track_z, k_track_y : float
        N/m, vertical and lateral support stiffness under each wheel (default: rigid).
    j : int
        Bogie index.

    Returns
    -------
    tuple of float
        (lower, upper) in Hz.
    """
    _, bogie, secondary = _full_vehicle_parts(model)
    primary = model.primary
    h1, h2 = primary.height - bogie.cog_height, secondary.height - bogie.cog_height
    k1 = 2.0 * series(2.0 * primary.k_y, 2.0 * k_track_y)  # two wheelsets
    k2 = 2.0 * secondary.k_y
    k_lat = k1 + k2
    lever = (k1 * h1 + k2 * h2) / k_lat
    # the lateral springs' own roll stiffness beyond k_lat lever^2 (two levers)
    extra = k1 * h1**2 + k2 * h2**2 - k_lat * lever**2
    k_roll = (
        4.0 * _primary_vertical(model, k_track_z) * primary.semi_spacing**2
        + 2.0 * secondary.k_z * secondary.semi_spacing**2
        + model.anti_roll_stiffness
        + _bogie_gravity_term(model, j)
        + extra
    )
    return sway_frequencies(bogie.mass, bogie.roll_inertia, k_lat, lever, k_roll)


def wheelset_bounce_frequency(model: VehicleModel, k_track_z: float) -> float:
    """Wheelset bounce on the track springs and the primary suspension, bogie held (Hz).

    K = 2 k_track_z + 2 k_z1, m = wheelset mass (first principles).

    Parameters
    ----------
    model : VehicleModel
        Any vehicle (full or single-wheelset); its wheelset and primary suspension are used.
    k_track_z : float
        N/m, vertical support stiffness under each wheel.

    Returns
    -------
    float
        Hz.
    """
    return _hz(2.0 * k_track_z + 2.0 * model.primary.k_z, model.wheelset.mass)


def hand_frequencies(
    model: VehicleModel, k_track_z: float = math.inf, k_track_y: float = math.inf
) -> dict[str, float]:
    """All hand-calculated natural frequencies of a full vehicle (Hz), keyed by mode name.

    Keys: ``carbody_bounce``, ``carbody_pitch``, ``carbody_yaw``, ``carbody_lower_sway``,
    ``carbody_upper_sway``, ``bogie_bounce``, ``bogie_pitch``, ``bogie_lower_sway``,
    ``bogie_upper_sway`` and, for finite ``k_track_z``, ``wheelset_bounce``.

    Parameters
    ----------
    model : VehicleModel
        A full vehicle.
    k_track_z, k_track_y : float
        N/m, vertical and lateral support stiffness under each wheel (default: rigid).

    Returns
    -------
    dict of str to float
        Mode name -> frequency (Hz).
    """
    lower, upper = carbody_sway_frequencies(model, k_track_z)
    b_lower, b_upper = bogie_sway_frequencies(model, k_track_z, k_track_y)
    out = {
        "carbody_bounce": carbody_bounce_frequency(model, k_track_z),
        "carbody_pitch": carbody_pitch_frequency(model, k_track_z),
        "carbody_yaw": carbody_yaw_frequency(model),
        "carbody_lower_sway": lower,
        "carbody_upper_sway": upper,
        "bogie_bounce": bogie_bounce_frequency(model, k_track_z),
        "bogie_pitch": bogie_pitch_frequency(model, k_track_z),
        "bogie_lower_sway": b_lower,
        "bogie_upper_sway": b_upper,
    }
    if math.isfinite(k_track_z):
        out["wheelset_bounce"] = wheelset_bounce_frequency(model, k_track_z)
    return out
