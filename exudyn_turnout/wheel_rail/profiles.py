"""Readers for wheel and rail cross-section profiles.

Formats
-------
- Simpack profile files (``.prw`` wheel, ``.prr`` rail): ``header`` and ``spline`` blocks
  with ``keyword = value`` lines and a ``point`` block of ``y z [weight]`` rows.  The
  processing options of the ``spline`` block are applied in Simpack's order (as CONTACT's
  reader documents it): shift y/z, rotate about the origin, keep points inside the y bounds,
  clip z to the z bounds, mirror y, mirror z, invert the point order, convert lengths with
  ``units.len.f`` (user length per metre).
- Plain two-column text profiles (``y z`` per line, ``%``/``!``/``#`` comments), as used by
  CONTACT's slice sets; the length unit is an argument (``"auto"``: metres if every
  coordinate is below 1 in magnitude, else millimetres).
- CONTACT slice files (``.slcs``): ``U_OFFSET U_SCALE``, ``NSLC``, ``NFEAT NKINK NACCEL``,
  ``U_INTPOL``; NSLC lines ``u 'file'``; optional kink/acceleration lines; NSLC lines of
  feature positions when NFEAT > 1.  Slice positions are ``U_SCALE * (u + U_OFFSET)`` mm.

Sign convention (every dataclass of this package)
-------------------------------------------------
A profile is described in its own cross-section plane, SI metres:

- ``y`` lateral, **positive towards the field side** (away from the track centre), for
  wheels and rails alike; this is the convention of Simpack and CONTACT for a right-hand
  wheel/rail, so their data are used without mirroring;
- ``z`` vertical, **positive up**.  (Simpack and CONTACT store z positive *down*; the
  readers negate it.)  For a rail, z is the height of its surface; for a wheel, z is the
  height of its running surface above the lowest point of the taping (nominal rolling)
  circle, so the wheel's radius at lateral position y is ``r0 - z(y)`` (the flange, below
  the tread, has z < 0).

The origin is the file's: for the S1002 wheel the taping line (70 mm from the back of the
flange); for a rail its reference point, which is not always the standard one (the
Manchester benchmark's UIC60 is already inclined 1:40 and referenced at its highest point).
Placing a rail in the track therefore never relies on the reference point:
:func:`exudyn_turnout.wheel_rail.sections.place_rail` puts its top at z = 0 and its gauge
point (14 mm below the top, EN 15302) at the given distance from the track centre.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

__all__ = [
    "ProfileFormatError",
    "Profile",
    "SliceSet",
    "read_simpack_profile",
    "read_plain_profile",
    "read_profile",
    "read_slices",
    "PROFILE_SIZE",
]

_MIN_POINTS = 5
_METRES_PER_MM = 1e-3


class ProfileFormatError(ValueError):
    """A profile or slice file that cannot be read; the message names file and problem."""


@dataclass(frozen=True, eq=False)
class Profile:
    """A wheel or rail cross-section, as read (see the module docstring for the axes)."""

    y: np.ndarray  #: m, lateral coordinates, positive towards the field side
    z: np.ndarray  #: m, vertical coordinates, positive up
    kind: str  #: "wheel" or "rail"
    source: str  #: file the profile was read from ("" when generated)
    comment: str = ""  #: the file's comment, if any

    def __post_init__(self) -> None:
        if self.kind not in ("wheel", "rail"):
            raise ValueError(f"Profile kind must be 'wheel' or 'rail', got {self.kind!r}")
        if self.y.shape != self.z.shape or self.y.ndim != 1:
            raise ValueError("Profile y and z must be 1-D arrays of equal length")


@dataclass(frozen=True, eq=False)
class SliceSet:
    """A rail whose cross-section varies along the track: one profile per position u."""

    u: np.ndarray  #: m, slice positions along the track, strictly increasing
    profiles: tuple  #: Profile per slice, same order as u
    features: np.ndarray  #: m, feature positions per slice (n_slices, n_features), may be empty
    source: str  #: the .slcs file


def _fail(path: Path | str, problem: str) -> ProfileFormatError:
    return ProfileFormatError(f"{Path(path).name}: {problem}")


def _read_text(path: Path) -> list[str]:
    try:
        return path.read_text(encoding="utf-8", errors="replace").splitlines()
    except FileNotFoundError:
        raise _fail(path, "file not found") from None
    except OSError as err:
        raise _fail(path, f"cannot be read ({err.strerror})") from None


def _strip_comment(line: str, markers: str) -> str:
    cut = len(line)
    in_quote = False
    for i, ch in enumerate(line):
        if ch in "'\"":
            in_quote = not in_quote
        elif ch in markers and not in_quote:
            cut = i
            break
    return line[:cut].strip()


def _parse_simpack(path: Path) -> tuple[dict, dict, np.ndarray]:
    header: dict = {}
    spline: dict = {}
    rows: list[list[float]] = []
    section = ""
    closed: set[str] = set()
    for number, raw in enumerate(_read_text(path), start=1):
        line = _strip_comment(raw, "!")
        if not line:
            continue
        match = re.fullmatch(r"(\w+)\.(begin|end)", line)
        if match:
            name, edge = match.groups()
            if name not in ("header", "spline", "point"):
                raise _fail(path, f"line {number}: unknown block '{name}'")
            if edge == "end" and section != name:
                raise _fail(path, f"line {number}: {name}.end outside its block")
            if edge == "end":
                closed.add(name)
            section = name if edge == "begin" else {"point": "spline"}.get(name, "")
            continue
        if "=" in line:
            key, value = (part.strip() for part in line.split("=", 1))
            if section == "header":
                header[key] = value.strip("'\"")
            elif section == "spline":
                spline[key] = value.strip("'\"")
            else:
                raise _fail(path, f"line {number}: keyword '{key}' outside a block")
            continue
        if section != "point":
            raise _fail(path, f"line {number}: unexpected text {line[:40]!r}")
        try:
            values = [float(v) for v in line.split()]
        except ValueError:
            raise _fail(path, f"line {number}: not a number in {line[:40]!r}") from None
        if len(values) < 2:
            raise _fail(path, f"line {number}: a point needs y and z")
        rows.append(values[:2])
    if not rows:
        raise _fail(path, "no profile points (point.begin ... point.end)")
    # a file cut short ends inside its point block (the points come last)
    if "point" not in closed and len(rows) >= _MIN_POINTS:  # else: "only N points"
        raise _fail(
            path,
            f"is cut short: no point.end after its {len(rows)} points (the file ends inside "
            "the point block)",
        )
    return header, spline, np.asarray(rows, dtype=float)


def _option(spline: dict, key: str, default: float, path: Path) -> float:
    if key not in spline:
        return default
    try:
        return float(spline[key])
    except ValueError:
        raise _fail(path, f"{key} = {spline[key]!r} is not a number") from None


def _apply_simpack_options(points: np.ndarray, spline: dict, path: Path) -> np.ndarray:
    y, z = points[:, 0].copy(), points[:, 1].copy()
    y += _option(spline, "shift.y", 0.0, path)
    z += _option(spline, "shift.z", 0.0, path)
    angle_factor = _option(spline, "units.ang.f", 1.0, path)
    angle = _option(spline, "rotate", 0.0, path) / angle_factor
    if angle != 0.0:
        c, s = math.cos(angle), math.sin(angle)
        y, z = c * y - s * z, s * y + c * z
    y_min, y_max = (
        _option(spline, k, 1.0 if k.endswith("min") else 0.0, path)
        for k in ("bound.y.min", "bound.y.max")
    )
    if y_min < y_max:
        keep = (y >= y_min) & (y <= y_max)
        y, z = y[keep], z[keep]
    z_min, z_max = (
        _option(spline, k, 1.0 if k.endswith("min") else 0.0, path)
        for k in ("bound.z.min", "bound.z.max")
    )
    if z_min < z_max:
        z = np.clip(z, z_min, z_max)
    if int(_option(spline, "mirror.y", 0, path)) == 1:
        y = -y
    if int(_option(spline, "mirror.z", 0, path)) == 1:
        z = -z
    if int(_option(spline, "inversion", 0, path)) == 1:
        y, z = y[::-1], z[::-1]
    length_factor = _option(spline, "units.len.f", 1.0, path)
    if length_factor <= 0.0:
        raise _fail(path, f"units.len.f = {length_factor} must be positive")
    return np.column_stack((y / length_factor, z / length_factor))


#: m, plausible extent of a profile, (y span min, y span max, z span min, z span max):
#: a wheel profile runs from the back of the flange over the tread (S1002: 130 mm wide, its
#: flange 28 mm high, EN 13715 flange heights 28-32 mm); a rail profile may be a narrow
#: piece of a crossing's slice (a few mm) and is at most a whole crossing or rail section
#: (well within 0.5 m wide, 0.3 m high). Outside: a cut-short file or a wrong unit.
PROFILE_SIZE = {"wheel": (0.08, 0.25, 0.015, 0.08), "rail": (0.005, 0.5, 0.0, 0.3)}


def _checked(points: np.ndarray, path: Path, kind: str | None = None) -> np.ndarray:
    if len(points) < _MIN_POINTS:
        raise _fail(path, f"only {len(points)} profile points (at least {_MIN_POINTS} needed)")
    if not np.all(np.isfinite(points)):
        raise _fail(path, "profile points contain NaN or infinity")
    step = np.diff(points, axis=0)
    if np.any(np.hypot(*step.T) > 0.05):
        raise _fail(path, "consecutive profile points more than 50 mm apart (wrong unit?)")
    if not (np.all(step[:, 0] >= 0.0) or np.all(step[:, 0] <= 0.0)):
        i = int(np.argmax(step[:, 0] * np.sign(points[-1, 0] - points[0, 0]) < 0.0))
        raise _fail(
            path,
            f"profile points are not monotonic in y (point {i + 2} goes back, y = "
            f"{points[i + 1, 0]:.6g} after {points[i, 0]:.6g} m)",
        )
    if kind is not None:
        y_lo, y_hi, z_lo, z_hi = PROFILE_SIZE[kind]
        width, height = float(np.ptp(points[:, 0])), float(np.ptp(points[:, 1]))
        if not (y_lo <= width <= y_hi and z_lo <= height <= z_hi):
            raise _fail(
                path,
                f"a {kind} profile {1e3 * width:.1f} mm wide and {1e3 * height:.1f} mm high "
                f"is implausible (expected {1e3 * y_lo:g}-{1e3 * y_hi:g} mm wide, "
                f"{1e3 * z_lo:g}-{1e3 * z_hi:g} mm high): cut short, or a wrong unit?",
            )
    return points


def read_simpack_profile(path: str | Path, kind: str | None = None) -> Profile:
    """Read a Simpack ``.prw``/``.prr`` profile, checking what it is.

    The file must be complete (its ``point.end``), its points monotonic
    in y, its extent plausible for its kind (:data:`PROFILE_SIZE`), its header type agree
    with its suffix (``.prw`` wheel, ``.prr`` rail) and with ``kind`` if given.

    Parameters
    ----------
    path : str or Path
        The profile file.
    kind : {"wheel", "rail"}, optional
        What the caller needs; a file of the other kind is an error.

    Returns
    -------
    Profile
        Points in metres, y towards the field side, z up (the file's z is negated); the
        kind from ``header.type`` (0 rail, 1 wheel).

    Raises
    ------
    ProfileFormatError
        Missing file, unknown block, text that is not a number, no or too few points,
        an unknown profile type; a file cut short, points that go back in y, an
        implausible size; a wheel profile where a rail profile is needed or vice versa.
    """
    path = Path(path)
    header, spline, points = _parse_simpack(path)
    kind_code = header.get("type", "0" if path.suffix.lower() == ".prr" else "1")
    kinds = {"0": "rail", "1": "wheel"}
    if kind_code.strip() not in kinds:
        raise _fail(path, f"header type = {kind_code!r} (0 rail or 1 wheel expected)")
    found = kinds[kind_code.strip()]
    by_suffix = {".prr": "rail", ".prw": "wheel"}.get(path.suffix.lower(), found)
    if by_suffix != found:
        raise _fail(
            path, f"header type = {kind_code.strip()} says {found}, the suffix says {by_suffix}"
        )
    if kind is not None and kind != found:
        raise _fail(
            path,
            f"is a {found} profile (header type = {kind_code.strip()}), "
            f"a {kind} profile is needed here",
        )
    points = _checked(_apply_simpack_options(points, spline, path), path, found)
    return Profile(
        y=points[:, 0],
        z=-points[:, 1],
        kind=found,
        source=str(path),
        comment=spline.get("comment", ""),
    )


def read_plain_profile(path: str | Path, kind: str = "rail", length_unit: str = "auto") -> Profile:
    """Read a two-column ``y z`` text profile (z positive down in the file).

    Parameters
    ----------
    path : str or Path
        The profile file.
    kind : {"rail", "wheel"}
        What the profile describes.
    length_unit : {"auto", "m", "mm"}
        Unit of the file's numbers; ``"auto"`` takes metres when every number is below 1 in
        magnitude (a rail section is wider than 1 mm and narrower than 1 m).

    Returns
    -------
    Profile
        Points in metres, y towards the field side, z up.

    Raises
    ------
    ProfileFormatError
        Missing file, a line that is not two numbers, too few points, unknown unit.
    """
    path = Path(path)
    rows = []
    for number, raw in enumerate(_read_text(path), start=1):
        line = _strip_comment(raw, "%!#")
        if not line:
            continue
        try:
            values = [float(v) for v in line.replace(",", " ").split()]
        except ValueError:
            raise _fail(path, f"line {number}: not a number in {line[:40]!r}") from None
        if len(values) < 2:
            raise _fail(path, f"line {number}: a point needs y and z")
        rows.append(values[:2])
    if not rows:
        raise _fail(path, "no profile points")
    points = np.asarray(rows, dtype=float)
    if length_unit == "auto":
        length_unit = "m" if np.max(np.abs(points)) < 1.0 else "mm"
    if length_unit not in ("m", "mm"):
        raise _fail(path, f"length unit {length_unit!r} (m or mm expected)")
    if length_unit == "mm":
        points = points * _METRES_PER_MM
    points = _checked(points, path, kind if kind in PROFILE_SIZE else None)
    return Profile(y=points[:, 0], z=-points[:, 1], kind=kind, source=str(path))


def read_profile(path: str | Path, kind: str | None = None, length_unit: str = "auto") -> Profile:
    """Read a profile in Simpack format (``.prr``/``.prw``) or plain text (anything else).

    Parameters
    ----------
    path : str or Path
        The profile file.
    kind : {"rail", "wheel"}, optional
        What the caller needs: a Simpack file of the other kind is an error (its header
        says what it is); a plain text file is read as this kind (default rail) and its
        size checked for it.
    length_unit : {"auto", "m", "mm"}
        Used for plain text files only, see :func:`read_plain_profile`.

    Returns
    -------
    Profile
    """
    if Path(path).suffix.lower() in (".prr", ".prw"):
        return read_simpack_profile(path, kind)
    return read_plain_profile(path, kind=kind or "rail", length_unit=length_unit)


def _slices_header(lines: list[tuple[int, str]], path: Path) -> tuple[float, float, int, int, int]:
    if len(lines) < 4:
        raise _fail(
            path, "header needs 4 lines: U_OFFSET U_SCALE, NSLC, NFEAT NKINK NACCEL, U_INTPOL"
        )
    try:
        first = lines[0][1].split()
        offset, scale = float(first[0]), float(first[1])
        n_slices = int(float(lines[1][1].split()[0]))
        counts = [int(float(v)) for v in lines[2][1].split()[:3]] + [0, 0]
    except (ValueError, IndexError):
        raise _fail(path, f"line {lines[0][0]}-{lines[2][0]}: header is not numeric") from None
    if n_slices < 2:
        raise _fail(path, f"NSLC = {n_slices}: at least 2 slices are needed")
    if scale <= 0.0:
        raise _fail(path, f"U_SCALE = {scale} must be positive")
    return offset, scale, n_slices, counts[0], counts[1] + counts[2]


def read_slices(path: str | Path, length_unit: str = "auto") -> SliceSet:
    """Read a CONTACT slice file (``.slcs``) and the profile of every slice.

    Parameters
    ----------
    path : str or Path
        The ``.slcs`` file; slice file names are relative to its folder.
    length_unit : {"auto", "m", "mm"}
        Unit of plain-text slice profiles (Simpack slices carry their own unit).

    Returns
    -------
    SliceSet
        Positions u in metres (``U_SCALE * (u + U_OFFSET)`` millimetres), the profiles,
        the feature positions in metres.

    Raises
    ------
    ProfileFormatError
        Bad header, a slice line without ``u 'file'``, positions not increasing, a missing
        or bad slice profile (named with the .slcs file).
    """
    path = Path(path)
    lines = [(n, _strip_comment(raw, "%")) for n, raw in enumerate(_read_text(path), start=1)]
    lines = [(n, s) for n, s in lines if s]
    offset, scale, n_slices, n_features, n_extra = _slices_header(lines, path)
    u_values, names = [], []
    body = lines[4:]
    for number, text in body[:n_slices]:
        match = re.match(r"([-+0-9.eEdD]+)\s+['\"](.+?)['\"]", text)
        if not match:
            raise _fail(path, f"line {number}: expected u 'file', got {text[:40]!r}")
        u_values.append(float(match.group(1).replace("d", "e").replace("D", "e")))
        names.append(match.group(2))
    if len(names) < n_slices:
        raise _fail(path, f"{len(names)} slice lines, NSLC = {n_slices}")
    u = scale * (np.asarray(u_values) + offset) * _METRES_PER_MM
    if np.any(np.diff(u) <= 0.0):
        raise _fail(path, "slice positions are not strictly increasing")
    rest = body[n_slices:]
    features = np.zeros((n_slices, 0))
    numeric = [r for r in rest if re.match(r"^[-+0-9.]", r[1])]
    if n_features > 1:
        rows = numeric[-n_slices:] if len(numeric) >= n_slices else []
        try:
            table = np.array([[float(v) for v in t.split()] for _, t in rows])
        except ValueError:
            table = np.zeros((0, 0))
        if table.shape != (n_slices, n_features + 1):
            raise _fail(path, f"expected {n_slices} feature lines of u + {n_features} values")
        features = table[:, 1:] * _METRES_PER_MM
    profiles = []
    for name in names:
        try:
            profiles.append(read_profile(path.parent / name, kind="rail", length_unit=length_unit))
        except ProfileFormatError as err:
            raise _fail(path, f"slice '{name}': {err}") from None
    del n_extra
    return SliceSet(u=u, profiles=tuple(profiles), features=features, source=str(path))
