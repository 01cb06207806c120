"""Caches and keys of the profile contact: the wheel grid, a route's tables in memory and on disk.

:func:`~exudyn_turnout.passage.contact.profile.route_contact` builds a route's packed contact
tables once; this module says when it need not: :func:`route_contact_key` names everything
the tables depend on (the turnout's :data:`CONTACT_SECTIONS` and design files, the route,
the wheel), :func:`recent_contact` and :func:`keep_recent` hold the last few routes in
memory, :func:`route_entry`, :func:`read_route_entry` and :func:`write_route_entry` keep a
route on disk beside the contact tables, and :func:`wheel_grid` keeps the gridded wheel
profile there.
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping
from typing import Any

import numpy as np

from exudyn_turnout.inputs.vehicle import Vehicle
from exudyn_turnout.wheel_rail.packed_tables import PackedTables

__all__ = [
    "CONTACT_SECTIONS",
    "route_contact_key",
    "wheel_grid",
    "recent_contact",
    "keep_recent",
    "route_entry",
    "read_route_entry",
    "write_route_entry",
]


#: Sections of a turnout file that a route's contact tables depend on: the rail design
#: (``wheel_rail``: profiles, gauge, inclination, switch and crossing design, grid and table
#: settings), the ``layout`` and ``check_rail`` that fill its defaults (radius, nose tip,
#: check clearance), the ``routes`` (contact pairs, heights, sections, slice files) and the
#: ``zones`` (the active rails a route is checked against, the turnout's x range). Not the
#: track's rail types, sleeper, ballast, stiffness profiles or extra layer (masses,
#: springs, dampers), nor names, descriptions and regions: a study of the pad stiffness
#: reuses the route's tables.
CONTACT_SECTIONS = ("wheel_rail", "layout", "check_rail", "routes", "zones")


def _design_files(section: object) -> list[str]:
    """Every file name a contact section gives (``profile``, ``file`` keys), in file order."""
    names: list[str] = []
    if isinstance(section, Mapping):
        for key, value in section.items():
            if key in ("profile", "file") and isinstance(value, str):
                names.append(value)
            else:
                names += _design_files(value)
    elif isinstance(section, (list, tuple)):
        for item in section:
            names += _design_files(item)
    return names


def _file_identity(path) -> str:
    """A file's resolved path and the SHA-256 of its content ("missing" if unreadable)."""
    import hashlib
    from pathlib import Path

    resolved = Path(path).resolve()
    try:
        digest = hashlib.sha256(resolved.read_bytes()).hexdigest()
    except OSError:
        digest = "missing"
    return f"{resolved}:{digest}"


def route_contact_key(turnout, route: str, vehicle: Vehicle, cache_dir=None) -> str:
    """The key of a route's contact tables in memory: everything the tables depend on.

    The turnout's :data:`CONTACT_SECTIONS` (as parsed), the design files they name
    (profiles, slice files: resolved beside the turnout file or packaged, by path and
    content), the route, the wheel profile (resolved beside the vehicle file or packaged,
    by path and content), back-to-back and radius, the cache location and the package
    version. The track's stiffness, damping and masses are not in it, nor where the
    turnout or vehicle file is (only the design files it resolves to).

    Parameters
    ----------
    turnout : Turnout
    route : str
        Route name.
    vehicle : Vehicle
        Its ``wheel_profile``, ``back_to_back``, ``r0`` and ``source``.
    cache_dir : str or Path, optional
        Table cache location (part of the key).

    Returns
    -------
    str
        SHA-256, hex.
    """
    import hashlib
    import json
    from pathlib import Path

    from exudyn_turnout import __version__
    from exudyn_turnout.wheel_rail.data import profile_path
    from exudyn_turnout.wheel_rail.turnout_design import RailGeometry, resolve_design_file

    sections = {name: turnout.raw.get(name) for name in CONTACT_SECTIONS}
    names = _design_files(sections)
    wheel_rail = sections["wheel_rail"]
    if not (isinstance(wheel_rail, Mapping) and "profile" in wheel_rail):
        names.append(RailGeometry.profile)  # the default rail profile
    files = []
    for name in names:
        try:
            files.append(_file_identity(resolve_design_file(name, str(turnout.source))))
        except ValueError:  # a name no path can have (a NUL): the name itself
            files.append(f"unresolved:{name}")
    wheel = Path(str(vehicle.wheel_profile))
    if not wheel.is_absolute():  # as wheel_and_setup finds it
        beside = Path(str(vehicle.source)).parent / wheel
        wheel = beside if beside.exists() else profile_path(str(vehicle.wheel_profile))
    parts = [
        __version__,
        json.dumps(sections, sort_keys=True, default=str),
        json.dumps(files),
        route,
        repr((vehicle.wheel_profile, vehicle.back_to_back, vehicle.r0)),
        _file_identity(wheel),
        str(cache_dir),
    ]
    return hashlib.sha256("\n".join(parts).encode()).hexdigest()


#: Arrays of a cached wheel grid (besides ``key`` and ``checksum``).
_WHEEL_ARRAYS = ("s", "z", "slope", "curvature", "nominal_radius")


def _wheel_grid_key(profile_bytes: bytes, step: float, nominal_radius: float) -> str:
    """SHA-256 of a wheel grid's inputs: the profile file, the grid, and the code that grids it."""
    import hashlib

    import scipy

    from exudyn_turnout.wheel_rail import profile_grid, profiles, sections

    digest = hashlib.sha256(b"wheel-grid/1")
    digest.update(profile_bytes)
    digest.update(repr((float(step), float(nominal_radius), np.__version__)).encode())
    digest.update(scipy.__version__.encode())
    for module in (profiles, profile_grid, sections):  # a change of the code: a new entry
        with open(str(module.__file__), "rb") as handle:
            digest.update(handle.read())
    return digest.hexdigest()


def _array_checksum(arrays: Mapping[str, np.ndarray]) -> str:
    import hashlib

    digest = hashlib.sha256()
    for name, array in arrays.items():
        a = np.ascontiguousarray(array)
        digest.update(f"{name}:{a.dtype.str}:{a.shape}".encode())
        digest.update(a.tobytes())
    return digest.hexdigest()


def wheel_grid(profile_file, step: float, nominal_radius: float, cache_dir=None):
    """A wheel profile file gridded with its slopes and curvatures, kept in the table cache.

    :func:`~exudyn_turnout.wheel_rail.geometry.grid_wheel` of the file's profile, stored
    beside the contact tables under the SHA-256 of the file's bytes, the grid step, the
    radius, the numpy and scipy versions and the source of the code that reads and grids a
    profile; the arrays are returned bit for bit as computed. A run then needs neither the
    Savitzky-Golay filter nor ``scipy.signal`` (0.5 s to import). A damaged or unreadable
    entry is computed again and overwritten (one ``RuntimeWarning`` naming the file); an
    unusable cache location means computing it (one warning,
    :func:`~exudyn_turnout.wheel_rail.tables.write_cache_file`).

    Parameters
    ----------
    profile_file : str or Path
        The wheel profile (a file :func:`~exudyn_turnout.wheel_rail.profiles.read_profile`
        reads).
    step : float
        m, lateral grid step.
    nominal_radius : float
        m, wheel radius at the taping line.
    cache_dir : str or Path, optional
        Cache location (default :func:`~exudyn_turnout.wheel_rail.tables.default_cache_dir`).

    Returns
    -------
    WheelGrid
        Equal, array for array, to ``grid_wheel(read_profile(profile_file, kind="wheel"),
        step=step, nominal_radius=nominal_radius)``.
    """
    from pathlib import Path

    from exudyn_turnout.wheel_rail.geometry import WheelGrid, grid_wheel
    from exudyn_turnout.wheel_rail.profiles import read_profile
    from exudyn_turnout.wheel_rail.tables import default_cache_dir, write_cache_file

    def computed():
        return grid_wheel(
            read_profile(profile_file, kind="wheel"), step=step, nominal_radius=nominal_radius
        )

    try:
        profile_bytes = Path(profile_file).read_bytes()
    except OSError:
        return computed()  # read_profile says what is wrong with the file
    key = _wheel_grid_key(profile_bytes, step, nominal_radius)
    path = Path(cache_dir or default_cache_dir()) / f"wheel_grid_{key[:24]}.npz"
    if path.is_file():
        problem = None
        try:
            with open(path, "rb") as handle, np.load(handle, allow_pickle=False) as data:
                arrays = {name: data[name] for name in _WHEEL_ARRAYS}
                if str(data["key"]) == key:
                    if str(data["checksum"]) == _array_checksum(arrays):
                        return WheelGrid(
                            s=arrays["s"],
                            z=arrays["z"],
                            slope=arrays["slope"],
                            curvature=arrays["curvature"],
                            nominal_radius=float(arrays["nominal_radius"]),
                        )
                    problem = "fails its checksum"
        except Exception as err:  # noqa: BLE001 - any unreadable entry is computed again below
            problem = f"cannot be read ({type(err).__name__}: {err})".replace("\n", " ")
        if problem is not None:
            warnings.warn(
                f"wheel-grid cache {path}: {problem}; the grid is computed again",
                RuntimeWarning,
                2,
            )
    wheel = computed()
    arrays = {name: np.asarray(getattr(wheel, name), float) for name in _WHEEL_ARRAYS}
    write_cache_file(
        path,
        dict(arrays, key=np.array(key), checksum=np.array(_array_checksum(arrays))),
        "contact-table cache",
    )
    return wheel


class _RecentContacts:
    """The last few routes' contact tables in memory, keyed by everything they depend on.

    Building a route's sections and loading its tables from the disk cache takes seconds;
    a study or a test suite runs many passages on the same route. Tables are read-only
    once built, so sharing them is safe. At most ``size`` routes (~30-60 MB each) are kept.
    """

    def __init__(self, size: int = 4):
        self.size = size
        self.entries: dict[str, Any] = {}

    def get(self, key: str) -> Any:
        entry = self.entries.pop(key, None)
        if entry is not None:
            self.entries[key] = entry  # most recent last
        return entry

    def put(self, key: str, entry: Any) -> None:
        self.entries[key] = entry
        while len(self.entries) > self.size:
            self.entries.pop(next(iter(self.entries)))


_RECENT = _RecentContacts()


def recent_contact(key: str) -> Any:
    """A route's contact kept in memory under ``key``, or None.

    Parameters
    ----------
    key : str
        :func:`route_contact_key` of the route.

    Returns
    -------
    RouteContact or None
        The very object kept (read-only once built), now the most recent.
    """
    return _RECENT.get(key)


def keep_recent(key: str, contact: Any) -> None:
    """Keep a route's contact in memory under ``key`` (the oldest of the last few dropped).

    Parameters
    ----------
    key : str
        :func:`route_contact_key` of the route.
    contact : RouteContact
    """
    _RECENT.put(key, contact)


#: Arrays of a cached route contact (besides ``key`` and ``checksum``): the packed tables'
#: arrays, then the bodies' names, wheels and rail slots as unicode arrays.
_PACKED_ARRAYS = ("values", "blendable", "x", "layout", "bounds")
_PACKED_TEXTS = ("names", "wheels", "rails")


def _packed_sources() -> list:
    """The source files a route's packed contact is built by, in a fixed order.

    By the package's import rules (CONTRIBUTING.md) building the rail sections, the tables
    and the packed arrays can use only ``inputs/`` (turnout and route loaders),
    ``wheel_rail/`` (sections, transfer nodes, tables and their format version, the
    non-Hertz node law, the creep table, ``packed_tables``), the shared modules
    at the package's top level, the profile contact module that builds and packs a route
    (:mod:`~exudyn_turnout.passage.contact.profile`) and this module that stores it: all of
    them, every ``.py`` file.
    """
    from pathlib import Path

    import exudyn_turnout

    package = Path(str(exudyn_turnout.__file__)).parent
    files = sorted(package.glob("*.py"))
    for folder in ("inputs", "wheel_rail"):
        files += sorted((package / folder).rglob("*.py"))
    here = Path(__file__).resolve()
    return files + [here.parent / "profile.py", here]


def _packed_key(key: str) -> str:
    """SHA-256 of a route contact's disk entry: :func:`route_contact_key`, the source of
    :func:`_packed_sources` (a change of the code: a new entry) and the numpy, scipy and
    numba versions."""
    import hashlib

    import numba
    import scipy

    digest = hashlib.sha256(b"route-contact/1")
    digest.update(key.encode())
    digest.update(repr((np.__version__, scipy.__version__, numba.__version__)).encode())
    for file in _packed_sources():
        digest.update(f"{file.parent.name}/{file.name}".encode())
        digest.update(file.read_bytes())
    return digest.hexdigest()


def _crc_checksum(arrays: Mapping[str, np.ndarray]) -> str:
    """CRC-32 of arrays with their names, dtypes and shapes (a third of SHA-256's time on the
    ~40 MB of a route: it finds damage, the key in the file finds another entry)."""
    import zlib

    crc = 0
    for name, array in arrays.items():
        a = np.ascontiguousarray(array)
        crc = zlib.crc32(f"{name}:{a.dtype.str}:{a.shape}".encode(), crc)
        crc = zlib.crc32(a.reshape(-1).view(np.uint8).data, crc)
    return f"crc32:{crc:08x}"


def _packed_cache_path(key: str, cache_dir=None):
    """The disk entry of a route's packed contact, beside the contact tables.

    Named by :func:`route_contact_key` alone: one entry per route, wheel and turnout
    geometry, overwritten when the code that builds it changes (its full key is inside).
    """
    from pathlib import Path

    from exudyn_turnout.wheel_rail.tables import default_cache_dir

    return Path(cache_dir or default_cache_dir()) / f"route_contact_{key[:24]}.npz"


def route_entry(key: str, cache_dir=None) -> tuple:
    """Where a route's packed contact is kept on disk, and the full key stored in it.

    Parameters
    ----------
    key : str
        :func:`route_contact_key` of the route (it names the entry).
    cache_dir : str or Path, optional
        Cache location (default :func:`~exudyn_turnout.wheel_rail.tables.default_cache_dir`).

    Returns
    -------
    path : Path
        ``route_contact_<key>.npz`` beside the contact tables.
    full_key : str
        SHA-256 of ``key``, the source of the code that builds and stores the entry and the
        numpy, scipy and numba versions (a change of any: the entry is built again).
    """
    return _packed_cache_path(key, cache_dir), _packed_key(key)


def read_route_entry(path, full_key: str) -> tuple | None:
    """The route contact stored at ``path`` under ``full_key``, or None.

    None for a missing entry or one stored under another key (code or inputs changed), and
    for a damaged one (unreadable, failing its checksum, arrays that do not fit together),
    which also gives one ``RuntimeWarning`` naming the file and what is wrong with it: the
    caller builds the route again and overwrites the entry.

    Parameters
    ----------
    path : Path
        From :func:`route_entry`.
    full_key : str
        From :func:`route_entry`.

    Returns
    -------
    tuple or None
        ``(tables, wheels, rails)``: the packed tables (:class:`PackedTables`) as built, bit
        for bit, and per body its wheel and rail slot (tuples of str).
    """
    if not path.is_file():
        return None
    try:
        with open(path, "rb") as handle, np.load(handle, allow_pickle=False) as data:
            if str(data["key"]) != full_key:
                return None
            arrays = {name: data[name] for name in _PACKED_ARRAYS}
            texts = {name: tuple(str(a) for a in data[name]) for name in _PACKED_TEXTS}
            problem = None
            if str(data["checksum"]) != _crc_checksum(arrays):
                problem = "fails its checksum"
        if problem is None:
            n = arrays["layout"].shape[0]
            shapes_fit = arrays["layout"].shape == (n, 9)
            if not shapes_fit or any(len(texts[t]) != n for t in _PACKED_TEXTS):
                problem = "holds arrays that do not fit together"
        if problem is None:
            tables = PackedTables(names=texts["names"], **arrays)
            return tables, texts["wheels"], texts["rails"]
    except Exception as err:  # noqa: BLE001 - any unreadable entry is built again by the caller
        problem = f"cannot be read ({type(err).__name__}: {err})".replace("\n", " ")
    warnings.warn(
        f"route contact cache {path}: {problem}; the route's contact is built again",
        RuntimeWarning,
        2,
    )
    return None


def write_route_entry(path, full_key: str, tables: PackedTables, wheels, rails) -> None:
    """Store a route contact at ``path`` (an unusable location: one warning, no entry).

    Parameters
    ----------
    path : Path
        From :func:`route_entry`.
    full_key : str
        From :func:`route_entry`.
    tables : PackedTables
        The route's packed tables.
    wheels, rails : sequence of str
        Per body, its wheel ("left" or "right") and rail slot.
    """
    from exudyn_turnout.wheel_rail.tables import write_cache_file

    arrays = {name: getattr(tables, name) for name in _PACKED_ARRAYS}
    texts = {
        "names": np.array(tables.names, dtype=str),
        "wheels": np.array(wheels, dtype=str),
        "rails": np.array(rails, dtype=str),
    }
    content = dict(arrays, **texts)
    content.update(key=np.array(full_key), checksum=np.array(_crc_checksum(arrays)))
    write_cache_file(path, content, "contact-table cache")
