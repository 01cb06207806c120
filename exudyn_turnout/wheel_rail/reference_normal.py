"""Exact normal contact at CONTACT's reference cases, on our 2-D slice and on the 3-D surfaces.

The packaged CONTACT reference outputs (:mod:`.references`) give, per case, the approach,
the patch and its peak pressure of CONTACT's exact (half-space) solution.  This module
builds our undeformed geometry at a case's wheel position the way
:func:`.references.contact_at_reference` does (the slices enveloped by the rigid wheel
along the track, the candidate nearest CONTACT's patch, its lateral gap function) and adds
the gap of the *3-D* surfaces around it (:func:`surface_gap`): the slices interpolated
along the track at every x of a grid, the wheel a body of revolution.  The exact solver of
:mod:`.exact_normal` on that gap (:func:`exact_on_surface`) is the reference the 2-D
methods are measured against (``validation/normal_vs_contact.py``) and carries the
tangential reference (:mod:`.detailed_contact`).

Two surfaces (:data:`SURFACES`, which also mixes them to split their effects):

- ``"spline"`` (default): the profile points (wheel and every rail slice) joined by a
  parametric cubic spline as CONTACT does (:func:`spline_profile`; its ``make_spline``
  with ``SMOOTH = 0``: interpolating, broken at kinks); the wheel is the body of
  revolution, ``z(x, y) = z_w(y) + r(y) - sqrt(r(y)^2 - x^2)`` with the rolling radius
  ``r(y) = r_0 - z_w(y)`` of every profile point (CONTACT's wheel is a surface of
  revolution too); the contact plane is pitched by the wheel's slope at the contact,
  ``theta = asin(x_c / r_c)``: elements of ``dx`` along that plane and the gap along its
  normal, ``cos(theta) cos(gamma)`` times the vertical gap.  Between two spline points
  (every :data:`SPLINE_STEP`) straight lines;
- ``"linear"``: what this module did first: profile points joined by straight lines
  (:func:`.sections.surface_on_grid`; the wheel from its 0.1 mm grid), the wheel's drop
  the parabola ``x^2 / (2 r_0)`` and a horizontal contact plane.  At CONTACT's
  cross_brute case, 46 mm ahead of the axle, the parabola lowers the wheel by
  ``x^4 / (8 r^3)`` = 5.7 um against the circle and the rolling radius of the contact
  point (0.1 mm under r_0) by 0.6 um more: the undeformed interpenetration is 0.0402 mm
  there against CONTACT's approach 0.0337 mm; with the body of revolution 0.0339 mm, and
  along the pitched normal 0.0337 mm; the spline then raises the nose's crown by 0.8 um
  over its polygon, to 0.0345 mm (+2.4 %; in the other three prescribed-position cases
  the spline brings the interpenetration from -1.2 ... -1.7 % to -0.5 ... +0.0 % of
  CONTACT's approach; ``validation/detailed_vs_contact.md``).  Between the points of a
  linear profile the lateral curvature is zero and at the points a delta: the exact
  pressure peaks there and PMAX grows as the elements shrink.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType

import numpy as np
from scipy.interpolate import CubicSpline

from exudyn_turnout.wheel_rail.data import profile_path
from exudyn_turnout.wheel_rail.exact_normal import NormalSolution, solve_normal
from exudyn_turnout.wheel_rail.geometry import (
    FLANGE_DIRECTION,
    WheelGrid,
    prepare_rail,
    prepare_wheel,
    search_candidates,
    surface_derivatives,
)
from exudyn_turnout.wheel_rail.hertz import curvature_sums
from exudyn_turnout.wheel_rail.nonhertz import normal_gap_function
from exudyn_turnout.wheel_rail.profiles import (
    Profile,
    SliceSet,
    read_simpack_profile,
    read_slices,
)
from exudyn_turnout.wheel_rail.references import ReferenceCase
from exudyn_turnout.wheel_rail.sections import (
    lateral_grid,
    slice_heights,
    slice_sections,
    slice_surface,
    surface_on_grid,
    wheel_drop,
    wheel_envelope,
)

__all__ = [
    "GAP_SAMPLE_STEP",
    "GAP_SAMPLE_WINDOW",
    "NOMINAL_RADIUS",
    "SPLINE_STEP",
    "KINK_ANGLE",
    "SURFACES",
    "WHEEL_FILE",
    "CaseGeometry",
    "case_geometry",
    "spline_profile",
    "spline_slices",
    "contact_pitch",
    "surface_gap",
    "SurfaceContact",
    "exact_on_surface",
]

#: m, sample step of the lateral gap function (as :func:`.references.contact_at_reference`)
GAP_SAMPLE_STEP = 2e-5
#: m, its half-width
GAP_SAMPLE_WINDOW = 0.02
#: m, CONTACT's wheel radius NOMRAD in the packaged cases
NOMINAL_RADIUS = 0.46
#: m, parameter step at which :func:`spline_profile` evaluates the spline (0.2 mm between
#: the points of CONTACT's slices; the chord of a 10 mm radius over it is 0.1 nm off)
SPLINE_STEP = 1e-5
#: rad, a turn of the profile polygon above it is a kink where the spline breaks (CONTACT's
#: KINKHIG default, 30 deg, printed in every packaged reference output)
KINK_ANGLE = math.radians(30.0)
#: the 3-D surfaces :func:`surface_gap` can build (module docstring), as (profile points
#: joined by, wheel shape); the first is the default; the last two mix them
SURFACES = MappingProxyType(
    {
        "spline": ("spline", "revolution"),
        "linear": ("linear", "parabola"),
        "linear+revolution": ("linear", "revolution"),
        "spline+parabola": ("spline", "parabola"),
    }
)
#: the wheel profile of every packaged CONTACT case (their ``.inp`` files' WFNAME)
WHEEL_FILE = "MBench_S1002_v3.prw"
_ENVELOPE_STEP, _REACH = 2.5e-4, 0.1  # m, as references.contact_at_reference
_NO_RAIL = 1.0  # m, gap written where the rail is absent (never in contact)


@dataclass(frozen=True, eq=False)
class CaseGeometry:
    """Our geometry at a CONTACT case: the candidate nearest CONTACT's first patch."""

    gap: np.ndarray  #: m, normal gap along the lateral tangent, every GAP_SAMPLE_STEP
    table_gap: np.ndarray  #: m, the same every ``nonhertz.GAP_STEP`` (the tables' sampling)
    a_sum: float  #: 1/m, relative curvature along x (floored as in the tables)
    a_raw: float  #: 1/m, the same unfloored
    b_raw: float  #: 1/m, unfloored relative lateral curvature
    angle: float  #: rad, contact angle
    y_rail: float  #: m, deepest point on the rail profile
    z_rail: float  #: m, its height (at the envelope's x)
    interpenetration: float  #: m, undeformed interpenetration at CONTACT's position
    x_offset: float  #: m, where along x (from the wheel centre) the rigid wheel meets the rail
    wheel_y: np.ndarray  #: m, the wheel's surface points at zero shift (lateral)
    wheel_z: np.ndarray  #: m, their heights at zero lift


def case_geometry(case: ReferenceCase, wheel: WheelGrid, profiles_dir: str | Path) -> CaseGeometry:
    """Our undeformed geometry at a case, built as :func:`.references.contact_at_reference`.

    Parameters
    ----------
    case : ReferenceCase
        The CONTACT case.
    wheel : WheelGrid
        The S1002 wheel, gridded.
    profiles_dir : str or Path
        Folder holding the slice files.

    Returns
    -------
    CaseGeometry
    """
    slices = _slices(str(Path(profiles_dir) / Path(case.rail_file).name))
    grid = lateral_grid(-0.08, 0.30, wheel.s[1] - wheel.s[0])
    offsets = np.arange(-_REACH, _REACH + 0.5 * _ENVELOPE_STEP, _ENVELOPE_STEP)
    sections = slice_sections(slices, grid, x=case.s + offsets, interpolation="auto")
    enveloped = wheel_envelope(
        sections, np.array([case.s]), NOMINAL_RADIUS, reach=_REACH, step=_ENVELOPE_STEP
    )
    derivatives = surface_derivatives(enveloped)
    rail = prepare_rail(enveloped.z[0], derivatives.slope[0], derivatives.curvature[0], grid)
    prepared = prepare_wheel(wheel, 0.0, 0.0, (FLANGE_DIRECTION,))
    found = search_candidates(rail, prepared, shift=case.y, lift=case.wheel_height)
    k = int(np.argmin(np.abs(found.y_rail - case.y_contact_rail)))
    row = slice(k, k + 1)
    args = (rail, prepared, np.array([case.y]), found.y_rail[row], found.z_rail[row],
            found.angle[row])  # fmt: skip
    gap = normal_gap_function(
        *args, step=GAP_SAMPLE_STEP, window=GAP_SAMPLE_WINDOW, lift=case.wheel_height
    )[0]
    table_gap = normal_gap_function(*args, lift=case.wheel_height)[0]
    a_sum, _b = curvature_sums(
        found.radius[row], found.angle[row], found.curvature_wheel[row],
        found.curvature_rail[row],
    )  # fmt: skip
    index = int(round((found.y_rail[k] - grid[0]) / (grid[1] - grid[0])))
    x_offset = enveloped.x_offset
    assert x_offset is not None  # wheel_envelope records where along x each height is met
    dx = float(x_offset[0, index])
    lateral = np.nan_to_num(found.curvature_wheel[k]) + np.nan_to_num(found.curvature_rail[k])
    return CaseGeometry(
        gap=gap,
        table_gap=table_gap,
        a_sum=float(a_sum[0]),
        a_raw=float(0.5 * np.cos(found.angle[k]) / found.radius[k]),
        b_raw=float(0.5 * lateral),
        angle=float(found.angle[k]),
        y_rail=float(found.y_rail[k]),
        z_rail=float(found.z_rail[k] + wheel_drop(dx, NOMINAL_RADIUS)),
        interpenetration=-float(found.gap[k]),
        x_offset=dx,
        wheel_y=prepared.y,
        wheel_z=prepared.z,
    )


def spline_profile(
    profile: Profile, step: float = SPLINE_STEP, kink: float = KINK_ANGLE
) -> Profile:
    """A profile's points joined by a parametric cubic spline, sampled densely.

    ``(y, z)(s)`` through every point, ``s`` the accumulated chord length, not-a-knot ends
    (CONTACT's interpolating spline: ``make_spline`` with lambda = 0 on the polygon's arc
    length, as ``matlab/resample_slices.m`` of its distribution calls it, github
    eve70a/CONTACT, Apache-2.0; the packaged outputs print SMOOTH 0, LAMBDA 0 for both
    profiles); where the polygon turns by more than ``kink`` at a point the spline is
    broken there (CONTACT's kink detection, KINKHIG).  Repeated points are dropped.

    Parameters
    ----------
    profile : Profile
        Wheel or rail profile (may be multi-valued in y).
    step : float
        m, largest parameter step between the returned points.
    kink : float
        rad, turn of the polygon above which a point is a kink.

    Returns
    -------
    Profile
        The same kind and source, every point of ``profile`` kept.
    """
    points = np.column_stack((profile.y, profile.z))
    keep = np.concatenate(([True], np.hypot(*np.diff(points, axis=0).T) > 0.0))
    points = points[keep]
    chords = np.diff(points, axis=0)
    heading = np.arctan2(chords[:, 1], chords[:, 0])
    turn = np.abs(np.angle(np.exp(1j * np.diff(heading))))
    breaks = np.concatenate(([0], np.flatnonzero(turn > kink) + 1, [len(points) - 1]))
    ys, zs = [points[:1, 0]], [points[:1, 1]]
    for a, b in zip(breaks[:-1], breaks[1:]):
        piece = points[a : b + 1]
        s = np.concatenate(([0.0], np.cumsum(np.hypot(*np.diff(piece, axis=0).T))))
        n = max(int(math.ceil(s[-1] / step)), 1)
        u = np.union1d(np.linspace(0.0, s[-1], n + 1), s)[1:]
        if len(piece) == 2:
            ys.append(np.interp(u, s, piece[:, 0]))
            zs.append(np.interp(u, s, piece[:, 1]))
            continue
        spline = CubicSpline(s, piece, axis=0, bc_type="not-a-knot")
        values = spline(u)
        ys.append(values[:, 0])
        zs.append(values[:, 1])
    return dataclasses.replace(profile, y=np.concatenate(ys), z=np.concatenate(zs))


def spline_slices(slices: SliceSet, step: float = SPLINE_STEP) -> SliceSet:
    """A slice set with every slice's points joined by :func:`spline_profile`.

    Parameters
    ----------
    slices : SliceSet
        From :func:`.profiles.read_slices`.
    step : float
        m, parameter step of the dense points.

    Returns
    -------
    SliceSet
        Same positions and features (arc lengths: the spline's differ from the polygon's
        by the chord error, below 1e-4 of the length on CONTACT's slices).
    """
    profiles = tuple(spline_profile(p, step) for p in slices.profiles)
    return dataclasses.replace(slices, profiles=profiles)


def contact_pitch(x_contact: float, radius: float = NOMINAL_RADIUS) -> float:
    """Pitch of the contact plane of a wheel touching ``x_contact`` ahead of its axle.

    The wheel's surface there is inclined by ``asin(x / r)`` (its circle's tangent);
    the rail surface in contact has the same slope.

    Parameters
    ----------
    x_contact : float
        m, contact point along the track from the wheel centre.
    radius : float
        m, rolling radius.

    Returns
    -------
    float
        rad, positive when the contact lies ahead (the plane rises along x).
    """
    return math.asin(x_contact / radius)


def surface_gap(
    case: ReferenceCase,
    geometry: CaseGeometry,
    profiles_dir: str | Path,
    x,
    t,
    surface: str = "spline",
    pitch: float = 0.0,
) -> np.ndarray:
    """Undeformed normal gap of the 3-D surfaces on a grid at CONTACT's wheel position.

    The rail is the slice set interpolated along the track at every ``S + x``
    (:func:`.sections.slice_sections`, no envelope, no 2-D slice); the wheel is its
    profile at the case's shift and height, a body of revolution (``"spline"``) or with
    the parabola ``x^2 / (2 r_0)`` (``"linear"``, module docstring); the vertical gap at
    ``y = y_c + t cos(gamma)`` times ``cos(gamma) cos(pitch)`` is the normal gap, as
    :func:`.nonhertz.normal_gap_function` takes it in the vertical frame.

    Parameters
    ----------
    case : ReferenceCase
        The CONTACT case.
    geometry : CaseGeometry
        Our geometry there (:func:`case_geometry`).
    profiles_dir : str or Path
        Folder holding the slice files.
    x : array_like
        m, (nx,) positions along the track from the wheel centre.
    t : array_like
        m, (ny,) positions along the lateral tangent from the deepest point.
    surface : str
        A key of :data:`SURFACES`.
    pitch : float
        rad, pitch of the contact plane (:func:`contact_pitch`).

    Returns
    -------
    numpy.ndarray
        m, (nx, ny), negative where the surfaces interpenetrate, 1 m where there is no rail.

    Raises
    ------
    ValueError
        For an unknown surface.
    """
    if surface not in SURFACES:
        raise ValueError(f"surface {surface!r}: expected one of {tuple(SURFACES)}")
    joined, shape = SURFACES[surface]
    x = np.asarray(x, float)
    t = np.asarray(t, float)
    rail_path = str(Path(profiles_dir) / Path(case.rail_file).name)
    cosine = math.cos(geometry.angle) * math.cos(pitch)
    y = geometry.y_rail + t * math.cos(geometry.angle)
    if joined == "linear":
        rail = slice_sections(_slices(rail_path), y, x=case.s + x, interpolation="auto").z
        order = np.argsort(geometry.wheel_y)
        wheel = np.interp(y - case.y, geometry.wheel_y[order], geometry.wheel_z[order])
    else:
        smooth = slice_surface(_splined(rail_path), y, interpolation="auto", step=SPLINE_STEP)
        rail = slice_heights(smooth, case.s + x)
        wheel = surface_on_grid(_wheel_spline(), y - case.y)
    if shape == "parabola":
        drop = np.broadcast_to(x[:, None] ** 2 / (2 * NOMINAL_RADIUS), (len(x), len(y)))
    else:
        radius = NOMINAL_RADIUS - wheel[None, :]
        drop = radius - np.sqrt(radius**2 - x[:, None] ** 2)
    vertical = wheel[None, :] + case.wheel_height + drop - rail
    return np.where(np.isfinite(vertical), cosine * vertical, _NO_RAIL)


# The slice file, its splines and the wheel's spline are read and built once per process:
# surface_gap is called again for every grid a solution grows to (and per node by callers).
@functools.lru_cache(maxsize=8)
def _slices(path: str):
    return read_slices(Path(path))


@functools.lru_cache(maxsize=8)
def _splined(path: str):
    return spline_slices(_slices(path))


@functools.lru_cache(maxsize=1)
def _wheel_spline():
    return spline_profile(read_simpack_profile(profile_path(WHEEL_FILE), kind="wheel"))


@dataclass(frozen=True, eq=False)
class SurfaceContact:
    """The exact normal solution on the 3-D gap of a CONTACT case."""

    #: the solution at the prescribed force; its ``x`` and ``x_centre`` along the track from
    #: the wheel centre (horizontal; its ``dx`` lies in the pitched contact plane), its
    #: ``y`` and ``y_centre`` along the lateral tangent from the deepest point of the 2-D slice
    solution: NormalSolution
    interpenetration: float  #: m, largest undeformed interpenetration along the normal
    force_at_geometry: float  #: N, exact normal force at that interpenetration
    pitch: float  #: rad, pitch of the contact plane (:func:`contact_pitch`)
    surface: str  #: which surfaces (a key of :data:`SURFACES`)


def exact_on_surface(
    case: ReferenceCase,
    geometry: CaseGeometry,
    profiles_dir: str | Path,
    force: float,
    modulus: float,
    dx: float,
    ds: float,
    reach: tuple[float, float] = (6e-3, 3e-3),
    surface: str = "spline",
) -> SurfaceContact:
    """Exact normal contact on the 3-D gap (:func:`surface_gap`) of a CONTACT case.

    The grid spans ``reach`` around the envelope's contact point and grows (x 1.5) while
    the contact touches its edge.  On the ``"spline"`` surfaces the contact plane is
    pitched by :func:`contact_pitch` at the envelope's contact point (elements of ``dx``
    along it); on ``"linear"`` it is horizontal (module docstring).

    Parameters
    ----------
    case : ReferenceCase
        The CONTACT case.
    geometry : CaseGeometry
        Our geometry there (:func:`case_geometry`).
    profiles_dir : str or Path
        Folder holding the slice files.
    force : float
        N, normal force.
    modulus : float
        Pa, contact modulus E*.
    dx, ds : float
        m, element size along x and the lateral tangent.
    reach : (float, float)
        m, first half-widths of the grid along x and t.
    surface : str
        A key of :data:`SURFACES`.

    Returns
    -------
    SurfaceContact
    """
    pitch = contact_pitch(geometry.x_offset) if surface == "spline" else 0.0
    if surface not in SURFACES:
        raise ValueError(f"surface {surface!r}: expected one of {tuple(SURFACES)}")
    along = math.cos(pitch)  # horizontal length of a unit length in the contact plane
    half_x, half_t = reach
    for _ in range(6):
        nx, ny = 2 * int(half_x / dx) + 1, 2 * int(half_t / ds) + 1
        x = geometry.x_offset + (np.arange(nx) - 0.5 * (nx - 1)) * dx * along
        t = (np.arange(ny) - 0.5 * (ny - 1)) * ds
        h = surface_gap(case, geometry, profiles_dir, x, t, surface, pitch)
        lowest = float(np.min(h))
        solved = solve_normal(h - lowest, dx, ds, modulus, force=force)
        rows, cols = np.nonzero(solved.pressure)
        if rows.min() > 0 and cols.min() > 0 and rows.max() < nx - 1 and cols.max() < ny - 1:
            break
        half_x, half_t = 1.5 * half_x, 1.5 * half_t
    at_geometry = solve_normal(h - lowest, dx, ds, modulus, approach=-lowest).normal_force
    shift_t = float(t[0] - solved.y[0])
    placed = dataclasses.replace(
        solved,
        x=x,
        x_centre=geometry.x_offset + solved.x_centre * along,
        y=solved.y + shift_t,
        y_centre=solved.y_centre + shift_t,
    )
    return SurfaceContact(placed, -lowest, float(at_geometry), pitch, surface)
