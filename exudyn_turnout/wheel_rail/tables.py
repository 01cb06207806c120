"""Precomputed contact-geometry tables, cached on disk, with a vectorised lookup.

A :class:`ContactTable` holds, for one wheel and one rail body, every candidate contact
point over the section position x and the wheel's lateral shift towards the field side
(see :mod:`.geometry`), at zero lift and zero roll relative to the rail: gap, positions on
rail and wheel, contact angle, rolling radius, curvatures and the Hertz constant.  Roll
relative to the rail (a few mrad) changes the contact angle by the roll angle to first
order; the table does not tabulate it.

:func:`lookup` evaluates all contacts of a time step in one call.  Per query it interpolates
bilinearly between the four surrounding table nodes when they describe the same contact
points (same candidates present, positions on the rail within 2 mm); otherwise it takes the
cell's first node (so a change of contact configuration happens within one grid step).
Gaps are normal gaps, carried to the query's lift to first order, ``gap + cos(gamma) lift``;
in a cell that is not interpolated also to its shift, ``- sin(gamma) (shift - shift_node)``.

Tables are cached as ``.npz`` under a directory (default ``$XDG_CACHE_HOME/exudyn_turnout``
or ``~/.cache/exudyn_turnout``, never the working directory) keyed by a SHA-256 of every
input. A cached file holds its key and a SHA-256 of its arrays: one that cannot be read,
misses an array, has the wrong shapes, a non-finite value or a wrong checksum is named in
one warning and rebuilt. A cache directory that cannot be made or written (an unwritable
home, a file in its place) means running without a cache, with one warning.
"""

from __future__ import annotations

import hashlib
import os
import time
import uuid
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from exudyn_turnout.wheel_rail.geometry import (
    FLANGE_DIRECTION,
    WheelGrid,
    prepare_rail,
    prepare_wheel,
    search_candidates_batch,
    surface_derivatives,
)
from exudyn_turnout.wheel_rail.hertz import curvature_sums, effective_modulus, hertz_constant
from exudyn_turnout.wheel_rail.node_laws import (
    centre_point,
    node_centres,
    node_normal_forces,
    node_offsets,
)
from exudyn_turnout.wheel_rail.nonhertz import PATCH_FIELDS, patch_law_fields
from exudyn_turnout.wheel_rail.sections import SectionGrid, wheel_envelope

__all__ = [
    "TableSettings",
    "ContactTable",
    "ContactLookup",
    "default_cache_dir",
    "table_key",
    "build_contact_table",
    "cached_wheel_envelope",
    "write_cache_file",
    "lookup",
    "lookup_values",
    "cell_coefficients",
    "normal_force",
]

# 10: key and checksum stored in the file; 11: slices interpolated along u as CONTACT and a
# per-node normal-contact law (semi-Hertzian where the Hertz ellipse does not fit); 12: the
# flange back rounded to the inner face as EN 13715 (geometry.flange_back_arc), the radius
# of an inner-face contact from its height; 13: KP's force centre per node (patch_centre,
# patch_centre_exponent), the contact position; 15: the surface's offset at the force centre
# (patch_offset_c2, patch_offset_c3): the contact position on the rail
_FORMAT_VERSION = "wheel_rail-table-15"
_FIELDS = (
    "gap",
    "y_rail",
    "z_rail",
    "s_wheel",
    "angle",
    "radius",
    "curvature_rail",
    "curvature_wheel",
    "hertz_constant",
    "x_offset",
    *PATCH_FIELDS,  # normal-contact law per node: Hertz where it fits, else Kik-Piotrowski
)
_SIN = len(_FIELDS)  # stored after the public fields: sin(angle) and cos(angle), for the
_COS = _SIN + 1  # gap's first-order change with shift and lift
_EMPTY_GAP = 1.0  # m, gap of an empty candidate slot
_CONSISTENT_DISTANCE = 2e-3  # m, nodes describe the same contact point when this close


@dataclass(frozen=True)
class TableSettings:
    """Grid and candidate settings of a contact table (SI)."""

    shift_min: float = -0.012  #: m, smallest lateral shift (towards the track centre)
    shift_max: float = 0.012  #: m, largest lateral shift (towards the field side)
    shift_step: float = 2e-4  #: m, shift step (0.2 mm: Delta r is piecewise smooth on it)
    max_candidates: int = 3  #: candidate slots per node
    #: m, candidates up to this much above the lowest gap are kept (a flange 5 mm away
    #: from the rail is still tabulated, so that it is found before it hits)
    max_gap: float = 0.005
    prominence: float = 5e-5  #: m, gap rise that separates two contact regions
    #: rad, extra search directions besides vertical (60 deg: flange; add e.g. -70 deg,
    #: radians, for the back of the flange against a check rail)
    directions: tuple = (FLANGE_DIRECTION,)
    young: float = 2.1e11  #: Pa, Young's modulus of wheel and rail steel
    poisson: float = 0.3  #: Poisson's ratio of wheel and rail steel


@dataclass(frozen=True, eq=False)
class ContactTable:
    """Candidate contact points over section position and lateral shift."""

    x: np.ndarray  #: m, section positions (n_x,)
    shift: np.ndarray  #: m, lateral shifts of the wheel towards the field side (n_s,)
    #: (n_x, n_s, n_c, n_fields + 2) values, fields in ``ContactTable.fields`` order, then
    #: sin and cos of the contact angle; empty slots: gap 1 m, everything else 0
    values: np.ndarray
    count: np.ndarray  #: (n_x, n_s) number of candidates found
    #: (n_x, n_s) the cell from this node to the next x and shift node may be interpolated
    #: (its four nodes hold the same slots, contact points within 2 mm)
    blendable: np.ndarray
    key: str  #: SHA-256 of the inputs
    build_seconds: float  #: s, time to build (0 when loaded from the cache)
    fields: tuple = _FIELDS  #: names of the last axis of ``values``

    @property
    def coefficients(self) -> np.ndarray:
        """(n_x - 1, n_s - 1, n_c, n_fields + 2, 4) per cell: value = c0 + c1 tx + c2 ts
        + c3 tx ts (bilinear in blendable cells; else the cell's first node with the gap's
        first-order change with shift), see :func:`cell_coefficients`.

        Computed on first use and kept: four times the size of ``values`` (80 MB for the
        through route), used by :func:`lookup_values` only, not by the compiled kernel of
        a passage (which interpolates the node values itself).
        """
        kept = self.__dict__.get("_coefficients")
        if kept is None:
            kept = cell_coefficients(self.values, self.blendable, self.shift)
            object.__setattr__(self, "_coefficients", kept)  # frozen: set once, same value
        return kept

    def field(self, name: str) -> np.ndarray:
        """One field of every candidate at every node.

        Parameters
        ----------
        name : str
            A name in :attr:`fields`, e.g. ``"gap"`` (m), ``"angle"`` (rad),
            ``"curvature_rail"`` (1/m) or ``"hertz_constant"`` (N/m^1.5).

        Returns
        -------
        numpy.ndarray
            (n_x, n_s, n_c) view of ``values``: section position, lateral shift, candidate.
        """
        return self.values[..., self.fields.index(name)]


@dataclass(frozen=True, eq=False)
class ContactLookup:
    """Interpolated candidates for a batch of queries, arrays (n_query, n_candidates)."""

    gap: np.ndarray  #: m, normal gap (negative: interpenetration); 1 m for empty slots
    penetration: np.ndarray  #: m, normal interpenetration max(-gap, 0)
    #: m, contact position on the rail (side coordinates): the point of the rail surface on
    #: the normal force's line of action through its centre (:func:`.nonhertz.force_centre`,
    #: :func:`.node_laws.centre_point`)
    y_rail: np.ndarray
    z_rail: np.ndarray  #: m, height of that position on the rail surface
    s_wheel: np.ndarray  #: m, that position on the wheel from its taping line
    angle: np.ndarray  #: rad, contact angle (positive: normal on wheel towards track centre)
    radius: np.ndarray  #: m, rolling radius
    hertz_constant: np.ndarray  #: N/m^1.5
    x_offset: np.ndarray  #: m, longitudinal position of the contact relative to the wheel
    valid: np.ndarray  #: bool, slot holds a candidate
    patch_force: np.ndarray  #: N, the node law's force at :data:`.node_laws.DELTA_REF`
    force_exponent: np.ndarray  #: -, the node law's exponent n
    #: m, force centre from the deepest point along the lateral tangent at the query's
    #: penetration (:func:`.node_laws.node_centre`; y_rail, z_rail and s_wheel include it,
    #: moved onto the rail surface along the normal)
    centre: np.ndarray


def default_cache_dir() -> Path:
    """User cache directory for tables: ``$XDG_CACHE_HOME/exudyn_turnout`` or ``~/.cache/...``.

    Returns
    -------
    Path
    """
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "exudyn_turnout" / "wheel_rail"


def table_key(
    wheel: WheelGrid, sections: SectionGrid, taping_line: float, settings: TableSettings
) -> str:
    """SHA-256 of every input of a table.

    Parameters
    ----------
    wheel : WheelGrid
        Gridded wheel.
    sections : SectionGrid
        Rail sections.
    taping_line : float
        m, nominal taping-line position in the sections' frame.
    settings : TableSettings
        Grid settings.

    Returns
    -------
    str
        Hex digest.
    """
    digest = hashlib.sha256(_FORMAT_VERSION.encode())
    for array in (
        wheel.s,
        wheel.z,
        sections.x,
        sections.y,
        sections.z,
        sections.x_offset if sections.x_offset is not None else np.zeros(0),
    ):
        digest.update(np.ascontiguousarray(array, dtype=float).tobytes())
    digest.update(repr((wheel.nominal_radius, taping_line, settings)).encode())
    return digest.hexdigest()


def _blendable_cells(values: np.ndarray) -> np.ndarray:
    valid = values[..., 0] < 0.5 * _EMPTY_GAP
    y_rail = values[..., 1]
    ok = np.zeros(valid.shape[:2], dtype=bool)
    base_valid, base_y = valid[:-1, :-1], y_rail[:-1, :-1]
    ok_inner = np.ones(base_valid.shape[:2], dtype=bool)
    for di, dj in ((1, 0), (0, 1), (1, 1)):
        other_valid = valid[di : valid.shape[0] - 1 + di, dj : valid.shape[1] - 1 + dj]
        other_y = y_rail[di : valid.shape[0] - 1 + di, dj : valid.shape[1] - 1 + dj]
        same = np.all(other_valid == base_valid, axis=-1)
        close = np.all(np.abs(other_y - base_y) < _CONSISTENT_DISTANCE, axis=-1)
        ok_inner &= same & close
    ok[:-1, :-1] = ok_inner
    return ok


def _build_values(
    wheel: WheelGrid,
    sections: SectionGrid,
    taping_line: float,
    settings: TableSettings,
    shifts: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    derivatives = surface_derivatives(sections)
    n_c = settings.max_candidates
    values = np.zeros((len(sections.x), len(shifts), n_c, len(_FIELDS) + 2))
    values[..., 0] = _EMPTY_GAP
    count = np.zeros((len(sections.x), len(shifts)), dtype=int)
    step = float(sections.y[1] - sections.y[0])
    prepared_wheel = prepare_wheel(wheel, taping_line, 0.0, settings.directions)
    for i in range(len(sections.x)):
        rail = prepare_rail(
            sections.z[i],
            derivatives.slope[i],
            derivatives.curvature[i],
            sections.y,
            settings.directions,
        )
        batch = search_candidates_batch(
            rail,
            prepared_wheel,
            shifts,
            max_candidates=n_c,
            prominence=settings.prominence,
            max_gap=settings.max_gap,
        )
        laws = patch_law_fields(
            rail, prepared_wheel, shifts, batch, settings.young, settings.poisson
        )
        for j, found in enumerate(batch):
            n = len(found.gap)
            count[i, j] = n
            if n == 0:
                continue
            if sections.x_offset is not None:
                index = np.clip(
                    np.round((found.y_rail - sections.y[0]) / step).astype(int),
                    0,
                    len(sections.y) - 1,
                )
                x_offset = sections.x_offset[i, index]
            else:
                x_offset = np.zeros(n)
            order = np.argsort(found.y_rail)  # slots ordered from gauge to field side
            columns = (
                found.gap,
                found.y_rail,
                found.z_rail,
                found.s_wheel,
                found.angle,
                found.radius,
                np.nan_to_num(found.curvature_rail),
                np.nan_to_num(found.curvature_wheel),
                np.zeros(n),
                x_offset,
                *laws[j].T,
                np.sin(found.angle),
                np.cos(found.angle),
            )
            for k, column in enumerate(columns):
                values[i, j, :n, k] = np.asarray(column, float)[order]
    valid = count[..., None] > np.arange(n_c)
    a_sum, b_sum = curvature_sums(
        values[valid][:, 5], values[valid][:, 4], values[valid][:, 7], values[valid][:, 6]
    )
    values[..., 8][valid] = hertz_constant(
        a_sum, b_sum, effective_modulus(settings.young, settings.poisson)
    )
    return values, count, _blendable_cells(values)


def cell_coefficients(values: np.ndarray, blendable: np.ndarray, shifts: np.ndarray) -> np.ndarray:
    """Per-cell interpolation coefficients of a table (what :func:`lookup_values` uses).

    Parameters
    ----------
    values : numpy.ndarray
        (n_x, n_s, n_c, n_f) node values (``ContactTable.values``).
    blendable : numpy.ndarray
        (n_x, n_s) whether the cell starting at a node may be interpolated bilinearly.
    shifts : numpy.ndarray
        m, the table's uniform shift grid.

    Returns
    -------
    numpy.ndarray
        (n_x - 1, n_s - 1, n_c, n_f, 4): ``value = c0 + c1 tx + c2 ts + c3 tx ts`` for the
        fractions tx, ts of the query inside the cell.  A cell whose four nodes do not hold
        the same contact points uses its first node, with the normal gap carried to the
        query's shift to first order (``-sin(angle) (shift - shift_node)``).
    """
    v00, v10 = values[:-1, :-1], values[1:, :-1]
    v01, v11 = values[:-1, 1:], values[1:, 1:]
    bilinear = np.stack((v00, v10 - v00, v01 - v00, v11 - v10 - v01 + v00), axis=-1)
    nearest = np.zeros_like(bilinear)
    nearest[..., 0] = v00
    step = float(shifts[1] - shifts[0])
    nearest[..., 0, 2] = -v00[..., _SIN] * step
    ok = blendable[:-1, :-1][..., None, None, None]
    return np.where(ok, bilinear, nearest)


def build_contact_table(
    wheel: WheelGrid,
    sections: SectionGrid,
    taping_line: float,
    settings: TableSettings = TableSettings(),
    cache_dir: str | Path | None = None,
    use_cache: bool = True,
) -> ContactTable:
    """Build (or load from the cache) the contact table of one wheel on one rail body.

    Parameters
    ----------
    wheel : WheelGrid
        Gridded wheel (same grid step as the sections).
    sections : SectionGrid
        Rail sections along x (side coordinates, or the rail's own frame with the wheel's
        nominal taping line at ``taping_line``).
    taping_line : float
        m, nominal lateral position of the wheel's taping line in the sections' frame.
    settings : TableSettings
        Grid and candidate settings.
    cache_dir : str or Path, optional
        Where tables are cached (default :func:`default_cache_dir`).
    use_cache : bool
        Read and write the cache.

    Returns
    -------
    ContactTable
    """
    shifts = settings.shift_min + settings.shift_step * np.arange(
        int(round((settings.shift_max - settings.shift_min) / settings.shift_step)) + 1
    )
    key = table_key(wheel, sections, taping_line, settings)
    path = Path(cache_dir or default_cache_dir()) / f"contact_table_{key[:24]}.npz"
    shape = (len(sections.x), len(shifts), settings.max_candidates, len(_FIELDS) + 2)
    if use_cache and path.is_file():
        cached = _read_cached(path, key, np.asarray(sections.x, float), shifts, shape)
        if cached is not None:
            return cached
    start = time.perf_counter()
    values, count, blendable = _build_values(wheel, sections, taping_line, settings, shifts)
    elapsed = time.perf_counter() - start
    if use_cache:
        arrays = {
            "x": np.asarray(sections.x, float),
            "shift": shifts,
            "values": values,
            "count": count,
            "blendable": blendable,
        }
        _write_cached(path, key, arrays)
    return ContactTable(
        x=np.asarray(sections.x, float),
        shift=shifts,
        values=values,
        count=count,
        blendable=blendable,
        key=key,
        build_seconds=elapsed,
    )


#: Arrays of a cached table file (besides ``key`` and ``checksum``).
_ARRAYS = ("x", "shift", "values", "count", "blendable")

#: Cache directories found unusable in this process (warned about once each).
_UNUSABLE: set[str] = set()


def _checksum(arrays: dict[str, np.ndarray], names: tuple[str, ...] = _ARRAYS) -> str:
    """SHA-256 of the arrays' dtypes, shapes and bytes, in ``names`` order."""
    digest = hashlib.sha256()
    for name in names:
        a = np.ascontiguousarray(arrays[name])
        digest.update(f"{name}:{a.dtype.str}:{a.shape}".encode())
        digest.update(a.tobytes())
    return digest.hexdigest()


def _cache_problem(
    data, key: str, x: np.ndarray, shifts: np.ndarray, shape: tuple[int, ...]
) -> str | None:
    """What is wrong with a loaded cache file (None: nothing)."""
    missing = [n for n in (*_ARRAYS, "key", "checksum") if n not in data.files]
    if missing:
        return f"misses {', '.join(missing)}"
    if str(data["key"]) != key:
        return "holds another table (its key differs)"
    arrays = {n: data[n] for n in _ARRAYS}
    expected = {
        "x": x.shape,
        "shift": shifts.shape,
        "values": shape,
        "count": shape[:2],
        "blendable": shape[:2],
    }
    for name, want in expected.items():
        if arrays[name].shape != want:
            return f"has {name} of shape {arrays[name].shape}, expected {want}"
    if _checksum(arrays) != str(data["checksum"]):
        return "fails its checksum"
    if not np.all(np.isfinite(arrays["values"])):
        return "holds NaN or infinite values"
    if not (np.allclose(arrays["x"], x, atol=1e-12) and np.allclose(arrays["shift"], shifts)):
        return "has other x or shift nodes"
    return None


def _read_cached(
    path: Path, key: str, x: np.ndarray, shifts: np.ndarray, shape: tuple[int, ...]
) -> ContactTable | None:
    """The cached table, or None (with one warning naming the file) if it is damaged."""
    try:
        # opened here: np.load leaves its own handle open when the zip is damaged
        with open(path, "rb") as handle, np.load(handle, allow_pickle=False) as data:
            problem = _cache_problem(data, key, x, shifts, shape)
            if problem is None:
                values, blendable = data["values"], data["blendable"]
                return ContactTable(
                    x=data["x"],
                    shift=data["shift"],
                    values=values,
                    count=data["count"],
                    blendable=blendable,
                    key=key,
                    build_seconds=0.0,
                )
    except Exception as err:  # any file numpy cannot read is a damaged cache entry
        problem = f"cannot be read ({type(err).__name__}: {err})".replace("\n", " ")
    warnings.warn(f"contact-table cache {path}: {problem}; the table is rebuilt", RuntimeWarning, 2)
    return None


def _write_cached(path: Path, key: str, arrays: dict[str, np.ndarray]) -> None:
    """Write a table to the cache; an unusable cache directory: one warning, no cache."""
    content: dict[str, Any] = dict(arrays, key=np.array(key))
    content["checksum"] = np.array(_checksum(arrays, tuple(arrays)))
    write_cache_file(path, content, "contact-table cache")


def write_cache_file(path: Path, content: dict[str, Any], what: str) -> None:
    """Write arrays to a cache file atomically; an unusable directory: one warning, no cache.

    The file is written under a name of its own per writer (parallel workers may build the
    same entry at once) and moved into place; a directory that cannot be written is
    remembered for the process and warned about once.

    Parameters
    ----------
    path : pathlib.Path
        The cache file (``.npz``).
    content : dict
        Arrays to store, by name.
    what : str
        The cache's name in the warning, e.g. ``"contact-table cache"``.
    """
    if str(path.parent) in _UNUSABLE:
        return
    temporary = path.with_name(f"{path.stem}.{os.getpid()}-{uuid.uuid4().hex[:8]}.tmp.npz")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        np.savez(temporary, **content)
        os.replace(temporary, path)
    except OSError as err:
        _UNUSABLE.add(str(path.parent))
        warnings.warn(
            f"{what} {path.parent}: cannot be written ({err.strerror or err}); "
            "running without a cache",
            RuntimeWarning,
            3,
        )
    finally:
        try:
            temporary.unlink(missing_ok=True)
        except OSError:
            pass


def lookup(table: ContactTable, x, shift, lift=0.0) -> ContactLookup:
    """All candidate contacts for a batch of wheel positions, in one vectorised call.

    Parameters
    ----------
    table : ContactTable
        Table of the wheel/rail pair.
    x : array_like
        m, section positions of the queries (clamped to the table).
    shift : array_like
        m, lateral shifts of the wheel towards the field side (clamped to the table).
    lift : array_like
        m, height of the wheel above its table reference (positive: up).

    Returns
    -------
    ContactLookup
        Arrays (n_query, n_candidates).
    """
    values = lookup_values(table, x, shift, lift)
    index = {name: k for k, name in enumerate(table.fields)}
    gap = values[..., index["gap"]]
    valid = gap < 0.5 * _EMPTY_GAP
    angle = values[..., index["angle"]]
    penetration = np.where(valid, np.maximum(-gap, 0.0), 0.0)
    centre = node_centres(
        np.ascontiguousarray(values[..., index["patch_centre"]]),
        np.ascontiguousarray(values[..., index["patch_centre_exponent"]]),
        np.ascontiguousarray(penetration),
    ).reshape(gap.shape)
    if "patch_offset_c2" in index:
        offset = node_offsets(
            np.ascontiguousarray(values[..., index["patch_offset_c2"]]),
            np.ascontiguousarray(values[..., index["patch_offset_c3"]]),
            np.ascontiguousarray(centre),
        ).reshape(gap.shape)
    else:
        offset = np.zeros_like(centre)
    along_y, along_z = centre_point(centre, offset, np.sin(angle), np.cos(angle))
    return ContactLookup(
        gap=gap,
        penetration=penetration,
        y_rail=values[..., index["y_rail"]] + along_y,
        z_rail=values[..., index["z_rail"]] + along_z,
        s_wheel=values[..., index["s_wheel"]] + along_y,
        angle=angle,
        radius=values[..., index["radius"]],
        hertz_constant=values[..., index["hertz_constant"]],
        x_offset=values[..., index["x_offset"]],
        valid=valid,
        patch_force=values[..., index["patch_force"]],
        force_exponent=values[..., index["patch_force_exponent"]],
        centre=centre,
    )


def lookup_values(table: ContactTable, x, shift, lift=0.0) -> np.ndarray:
    """The raw interpolated field array of :func:`lookup` (fastest form).

    Parameters
    ----------
    table : ContactTable
        Table of the wheel/rail pair.
    x, shift, lift : array_like
        m, as for :func:`lookup`.

    Returns
    -------
    numpy.ndarray
        (n_query, n_candidates, n_fields) in ``table.fields`` order; the gap (field 0) is the
        normal gap at the query's shift and lift, 1 m in empty slots (whose Hertz constant
        is 0, so they never carry force).
    """
    xs = table.x
    shifts = table.shift
    x = np.asarray(x, dtype=float).ravel()
    ix = np.minimum(np.maximum(xs.searchsorted(x, side="right") - 1, 0), xs.shape[0] - 2)
    x_low = xs[ix]
    tx = np.minimum(np.maximum((x - x_low) / (xs[ix + 1] - x_low), 0.0), 1.0)
    position = (np.asarray(shift, dtype=float).ravel() - shifts[0]) / (shifts[1] - shifts[0])
    position = np.minimum(np.maximum(position, 0.0), shifts.shape[0] - 1.000001)
    js = position.astype(np.intp)
    ts = (position - js)[:, None, None]
    tx = tx[:, None, None]
    c = table.coefficients[ix, js]  # (n_q, n_c, n_f, 4)
    result = c[..., 0] + tx * c[..., 1] + ts * (c[..., 2] + tx * c[..., 3])
    gap = result[..., 0]
    empty = gap >= 0.5 * _EMPTY_GAP
    gap += result[..., _COS] * np.asarray(lift, dtype=float).reshape(-1, 1)
    gap[empty] = _EMPTY_GAP
    return result[..., :_SIN]


def normal_force(contacts: ContactLookup) -> np.ndarray:
    """One-sided normal force along each contact normal, by the node's law.

    The kernel's law (:func:`.node_laws.node_normal_force`, the same compiled function):
    ``N_ref (delta / DELTA_REF)^n`` with the interpolated law fields; exactly
    ``C_H delta^1.5`` where the nodes are Hertz's.

    Parameters
    ----------
    contacts : ContactLookup
        From :func:`lookup`.

    Returns
    -------
    numpy.ndarray
        N, (n_query, n_candidates); 0 where separated or empty.
    """
    delta = np.where(contacts.valid, contacts.penetration, 0.0)
    forces = node_normal_forces(
        np.ascontiguousarray(contacts.patch_force, dtype=float),
        np.ascontiguousarray(contacts.force_exponent, dtype=float),
        np.ascontiguousarray(delta, dtype=float),
    )
    return forces.reshape(delta.shape)


#: Arrays of a cached wheel envelope (besides ``key`` and ``checksum``).
_ENVELOPE_ARRAYS = ("x", "y", "z", "x_offset", "name")


def cached_wheel_envelope(
    sections: SectionGrid,
    x: np.ndarray,
    wheel_radius: float,
    reach: float,
    step: float,
    cache_dir: str | Path | None = None,
) -> SectionGrid:
    """:func:`.sections.wheel_envelope`, kept in the table cache beside the tables.

    The envelope of a turnout's rail bodies is the same in every run of a route and costs
    about a second; it is stored under the SHA-256 of every input (the sections' arrays,
    x, radius, reach, step and the table format), with a checksum of its arrays. A damaged
    or unreadable entry is computed again and overwritten; an unusable cache location
    means computing it (the tables' one warning names the location).

    Parameters
    ----------
    sections : SectionGrid
        The rail body's sections.
    x : numpy.ndarray
        m, where the envelope is wanted.
    wheel_radius, reach, step : float
        m, as :func:`.sections.wheel_envelope`.
    cache_dir : str or Path, optional
        Cache location (default :func:`default_cache_dir`).

    Returns
    -------
    SectionGrid
        Identical to ``wheel_envelope(sections, x, wheel_radius, reach, step)``.
    """
    x = np.asarray(x, float)
    digest = hashlib.sha256(f"envelope/{_FORMAT_VERSION}".encode())
    for array in (sections.x, sections.y, sections.z, x):
        digest.update(np.ascontiguousarray(array, dtype=float).tobytes())
    digest.update(repr((float(wheel_radius), float(reach), float(step), sections.name)).encode())
    key = digest.hexdigest()
    path = Path(cache_dir or default_cache_dir()) / f"envelope_{key[:24]}.npz"
    if path.is_file():
        try:
            with open(path, "rb") as handle, np.load(handle, allow_pickle=False) as data:
                arrays = {name: data[name] for name in _ENVELOPE_ARRAYS}
                if str(data["key"]) == key and str(data["checksum"]) == _checksum(
                    arrays, _ENVELOPE_ARRAYS
                ):
                    return SectionGrid(
                        x=arrays["x"],
                        y=arrays["y"],
                        z=arrays["z"],
                        name=str(arrays["name"]),
                        x_offset=arrays["x_offset"],
                    )
        except Exception:  # noqa: S110 - any unreadable entry is computed again below
            pass
    envelope = wheel_envelope(sections, x, wheel_radius, reach, step)
    if envelope.x_offset is not None:
        _write_cached(
            path,
            key,
            {
                name: np.asarray(getattr(envelope, name), float if name != "name" else str)
                for name in _ENVELOPE_ARRAYS
            },
        )
    return envelope
