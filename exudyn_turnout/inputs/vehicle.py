"""Vehicle files: the single wheelset with its sprung share, and the contact constants.

The packaged default is ``data/manchester_wheelset.toml`` (one wheelset of the Manchester
benchmark vehicle under its share of bogie and car body), by name ``"wheelset"``
(:mod:`.vehicle_names`). The Exudyn model built from it is
:func:`exudyn_turnout.passage.vehicle.wheelset.add_vehicle`; the full vehicle's file is
read by
:mod:`exudyn_turnout.inputs.vehicle_model` (:func:`load_vehicle` given one says so in one
line and names that loader).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

from exudyn_turnout.inputs.toml_fields import FieldReader, TurnoutFileError, read_toml
from exudyn_turnout.inputs.vehicle_names import PACKAGED_VEHICLES, packaged_vehicle_path

__all__ = [
    "Vehicle",
    "ContactLaw",
    "load_vehicle",
    "load_contact_law",
    "default_vehicle_path",
    "resolve_vehicle_path",
    "GRAVITY",
    "PRIMARY_STIFFNESS_MIN",
]

GRAVITY = 9.81  #: m/s^2

#: N/m, smallest primary stiffness (k_x, k_y, k_z per axlebox) a vehicle file may give.
#: Primary springs of railway vehicles are stiff: 0.5-30 MN/m per axlebox (the Manchester
#: benchmark vehicle: 1.22 MN/m vertical, 3.9 MN/m lateral, 31.4 MN/m longitudinal, Iwnicki
#: 1998; passenger bogies ~1 MN/m vertical, Iwnicki (ed.), Handbook of Railway Vehicle
#: Dynamics, 2006, ch. 3). Below 1e5 N/m a 5 t axlebox load (50 kN) would compress the
#: spring by 0.5 m: a unit slip (kN/m for N/m), not a design.
PRIMARY_STIFFNESS_MIN = 1e5

#: Sections and keys of a single-wheelset vehicle file (others are errors, did you mean).
_KEYS = {
    "wheelset": (
        "mass",
        "roll_inertia",
        "yaw_inertia",
        "spin_inertia",
        "wheel_radius",
        "contact_semi_spacing",
        "back_to_back",
        "wheel_profile",
    ),
    "sprung_mass": ("mass",),
    "primary_suspension": ("k_x", "k_y", "k_z", "c_y", "c_z", "semi_spacing"),
    "contact": (
        "C_H",
        "damping",
        "f11_ref",
        "f22_ref",
        "N_ref",
        "mu",
        "conicity",
        "flange_stiffness",
        "flange_damping",
        "flange_clearance",
    ),
}


@dataclass(frozen=True)
class Vehicle:
    """The single wheelset with its sprung share, primary suspension and contact constants.

    Read from a vehicle file by :func:`load_vehicle`; SI units.
    """

    m_w: float  #: kg, wheelset mass
    J_roll: float  #: kg m^2, wheelset roll inertia
    J_yaw: float  #: kg m^2, wheelset yaw inertia
    r0: float  #: m, nominal rolling radius
    b: float  #: m, lateral semi-distance of the contact points
    m_s: float  #: kg, sprung mass carried by this wheelset
    k_x: float  #: N/m, primary longitudinal stiffness per axlebox
    k_y: float  #: N/m, primary lateral stiffness per axlebox
    k_z: float  #: N/m, primary vertical stiffness per axlebox
    c_y: float  #: N s/m, primary lateral damping per axlebox
    c_z: float  #: N s/m, primary vertical damping per axlebox
    d: float  #: m, lateral semi-spacing of the axleboxes
    contact: ContactLaw  #: the file's ``[contact]`` table
    source: str  #: path of the file read
    #: kg m^2, wheelset spin inertia about the axle (profile contact: spin perturbation)
    J_spin: float | None = None
    back_to_back: float | None = None  #: m, flange back distance (profile contact)
    #: wheel profile file (a name in ``data/wheel_rail/profiles`` or a path; profile contact)
    wheel_profile: str | None = None

    @property
    def static_wheel_load(self) -> float:
        """(m_w + m_s) g / 2 (N), each wheel's share on straight level track."""
        return (self.m_w + self.m_s) * GRAVITY / 2.0

    @property
    def k_roll(self) -> float:
        """Primary roll stiffness 2 k_z d^2 (N m/rad) of the wheelset against the sprung point."""
        return 2.0 * self.k_z * self.d**2

    @property
    def k_yaw(self) -> float:
        """Primary yaw stiffness 2 k_x d^2 (N m/rad) against the (non-yawing) sprung mass."""
        return 2.0 * self.k_x * self.d**2


def default_vehicle_path() -> Path:
    """Path of the packaged Manchester benchmark wheelset file.

    Returns
    -------
    Path
        ``data/manchester_wheelset.toml`` inside the installed package.
    """
    return Path(str(resources.files("exudyn_turnout") / "data" / "manchester_wheelset.toml"))


def load_vehicle(path: str | Path | None = None) -> Vehicle:
    """Load and validate a vehicle file (default: the packaged Manchester benchmark wheelset).

    Every number must be finite and > 0 (dampings >= 0) and within a plausibility bound:
    primary stiffnesses >= :data:`PRIMARY_STIFFNESS_MIN`, masses <= 1e6 kg, inertias
    <= 1e7 kg m^2, wheel radius 0.1..2 m, semi-spacings <= 5 m,
    stiffnesses <= 1e12 N/m, dampings <= 1e10 N s/m; contact: C_H <= 1e14 N/m^1.5,
    creep coefficients and N_ref <= 1e10 N, mu <= 2, conicity <= 1, flange clearance <= 0.1 m.

    Parameters
    ----------
    path : str or Path, optional
        TOML vehicle file, or the name of a packaged one (``"wheelset"``, see
        :mod:`.vehicle_names`; a file of that name in the working directory comes first).

    Returns
    -------
    Vehicle
        The validated wheelset, suspension and contact constants.

    Raises
    ------
    TurnoutFileError
        The file cannot be read, or a field is missing or out of range (the message names
        the file and the field); the file is a full-vehicle (vehicle-model) file, which
        :func:`~exudyn_turnout.inputs.vehicle_model.load_vehicle_model` reads (one line
        saying so).
    """
    path = resolve_vehicle_path(path)
    data = read_toml(path)
    _refuse_vehicle_model_file(path, data)
    r = FieldReader(path.name, data)
    r.keys("", _KEYS)
    for table, keys in _KEYS.items():
        r.keys(table, keys)
    w, p = "wheelset", "primary_suspension"  # table names
    k_max, c_max = 1e12, 1e10  # N/m, N s/m: plausibility bounds
    radius = r.number(f"{w}.wheel_radius", upper=2.0)
    if radius < 0.1:
        raise r.fail(f"{w}.wheel_radius", f"must be >= 0.1 m (a railway wheel), got {radius:g}")
    contact_bounds = {
        "C_H": (True, 1e14),
        "damping": (False, c_max),
        "f11_ref": (True, 1e10),
        "f22_ref": (True, 1e10),
        "N_ref": (True, 1e10),
        "mu": (True, 2.0),
        "conicity": (True, 1.0),
        "flange_stiffness": (True, k_max),
        "flange_damping": (False, c_max),
        "flange_clearance": (True, 0.1),
    }
    for name, (positive, upper) in contact_bounds.items():
        r.number(f"contact.{name}", positive, upper=upper, lower=None if positive else 0.0)
    for k in ("k_x", "k_y", "k_z"):
        _primary_stiffness(r, f"{p}.{k}", k_max)
    return Vehicle(
        r.number(f"{w}.mass", upper=1e6),
        r.number(f"{w}.roll_inertia", upper=1e7),
        r.number(f"{w}.yaw_inertia", upper=1e7),
        radius,
        r.number(f"{w}.contact_semi_spacing", upper=5.0),
        r.number("sprung_mass.mass", upper=1e6),
        r.number(f"{p}.k_x", upper=k_max),
        r.number(f"{p}.k_y", upper=k_max),
        r.number(f"{p}.k_z", upper=k_max),
        r.number(f"{p}.c_y", positive=False, upper=c_max, lower=0.0),
        r.number(f"{p}.c_z", positive=False, upper=c_max, lower=0.0),
        r.number(f"{p}.semi_spacing", upper=5.0),
        load_contact_law(data, str(path)),
        str(path),
        *_profile_fields(r, data, path),
    )


def _primary_stiffness(r: FieldReader, field: str, upper: float) -> float:
    """A primary stiffness (N/m) in [PRIMARY_STIFFNESS_MIN, upper]."""
    value = r.number(field, upper=upper)
    if value < PRIMARY_STIFFNESS_MIN:
        raise r.fail(
            field,
            f"must be >= {PRIMARY_STIFFNESS_MIN:g} N/m (primary springs are 0.5-30 MN/m per "
            f"axlebox; a unit slip?), got {value:g}",
        )
    return value


def resolve_vehicle_path(path: str | Path | None) -> Path:
    """The file a vehicle argument names: a path, a packaged name, or None (the default).

    Parameters
    ----------
    path : str or Path or None
        A path; a name of :data:`.vehicle_names.PACKAGED_VEHICLES` (when no file of that
        name exists); None for :func:`default_vehicle_path`.

    Returns
    -------
    Path
        The file to read.

    Raises
    ------
    TurnoutFileError
        A string without suffix or directory that is neither a file nor a packaged name
        (one line listing the names).
    """
    if path is None:
        return default_vehicle_path()
    if isinstance(path, str) and not Path(path).exists():
        if path in PACKAGED_VEHICLES or not (Path(path).suffix or "/" in path or "\\" in path):
            return packaged_vehicle_path(path)  # a name: unknown ones fail listing the names
    return Path(path)


def _refuse_vehicle_model_file(path: Path, data: Mapping[str, Any]) -> None:
    """One clear line if ``data`` is a vehicle-model file (``[vehicle]``, no ``[contact]``)."""
    layout = data.get("vehicle")
    if "contact" in data or not isinstance(layout, Mapping):
        return
    full = layout.get("bogies") or "car_body" in data or "bogie" in data
    what = "a full-vehicle file (car body on bogies)" if full else "a vehicle-model file"
    packaged = " (or exudyn_turnout.inputs.vehicles.packaged_vehicle('manchester'))" if full else ""
    raise TurnoutFileError(
        f"{path.name}: is {what}, not a single-wheelset vehicle file: load it with "
        f"exudyn_turnout.inputs.vehicle_model.load_vehicle_model{packaged}"
    )


def _profile_fields(r: FieldReader, data: dict, path: Path) -> tuple:
    """(J_spin, back_to_back, wheel_profile) of ``[wheelset]``, None where not given."""
    w = "wheelset"
    table = data.get(w, {})
    spin = r.number(f"{w}.spin_inertia", upper=1e7) if "spin_inertia" in table else None
    back = None
    if "back_to_back" in table:
        back = r.number(f"{w}.back_to_back", upper=5.0)
        b = r.number(f"{w}.contact_semi_spacing", upper=5.0)
        if not 0.5 * b < back < 2.0 * b:
            raise r.fail(
                f"{w}.back_to_back",
                f"must lie between b and 4 b of contact_semi_spacing b = {b:g} m, got {back:g}",
            )
    profile = table.get("wheel_profile")
    if profile is not None:
        if not isinstance(profile, str) or not profile.strip():
            raise r.fail(f"{w}.wheel_profile", f"must be a file name, got {profile!r}")
        candidate = Path(profile)
        if not candidate.is_absolute():
            candidate = path.parent / candidate
        packaged = resources.files("exudyn_turnout") / "data" / "wheel_rail" / "profiles"
        if not candidate.exists() and not Path(str(packaged / profile)).exists():
            raise r.fail(
                f"{w}.wheel_profile",
                f"no such profile next to the file or in the package's profiles: {profile!r}",
            )
    return spin, back, profile


@dataclass(frozen=True)
class ContactLaw:
    """Wheel/rail contact constants (from the vehicle file's ``[contact]``)."""

    C_H: float  #: N/m^1.5, Hertz constant
    damping: float  #: N s/m, normal contact damping (0: none)
    f11_ref: float  #: N, longitudinal creep coefficient at N_ref
    f22_ref: float  #: N, lateral creep coefficient at N_ref
    N_ref: float  #: N, reference normal load
    mu: float  #: friction coefficient
    conicity: float  #: equivalent conicity gamma (-)
    flange_stiffness: float  #: N/m
    flange_damping: float  #: N s/m
    flange_clearance: float  #: m


def load_contact_law(data: dict, filename: str) -> ContactLaw:
    """Contact constants from the parsed ``[contact]`` table; errors name file and field.

    Parameters
    ----------
    data : dict
        The parsed vehicle file (its ``contact`` table is read).
    filename : str
        Path of the file, for messages.

    Returns
    -------
    ContactLaw
        Hertz, creep, friction and flange constants.

    Raises
    ------
    TurnoutFileError
        A field is missing or not a valid number.
    """
    r = FieldReader(Path(filename).name, data)
    names = _KEYS["contact"]
    positive = {"damping": False, "flange_damping": False}
    return ContactLaw(*(r.number(f"contact.{name}", positive.get(name, True)) for name in names))
