"""Exact normal contact at CONTACT's reference cases, on our 2-D slice and on the 3-D surfaces.

The packaged CONTACT reference outputs (:mod:`.references`) give, per case, the approach,
the patch and its peak pressure of CONTACT's exact (half-space) solution.  This module
builds our undeformed geometry at a case's wheel position the way
:func:`.references.contact_at_reference` does (the slices enveloped by the rigid wheel
along the track, the candidate nearest CONTACT's patch, its lateral gap function) and adds
the gap of the *3-D* surfaces around it (:func:`surface_gap`): the slices interpolated
along the track at every x of a grid, the wheel profile with the drop of its circle.  The
exact solver of :mod:`.exact_normal` on that gap (:func:`exact_on_surface`) is the
reference the 2-D methods are measured against (``validation/normal_vs_contact.py``).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

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
from exudyn_turnout.wheel_rail.profiles import read_slices
from exudyn_turnout.wheel_rail.references import ReferenceCase
from exudyn_turnout.wheel_rail.sections import lateral_grid, slice_sections, wheel_envelope

__all__ = [
    "GAP_SAMPLE_STEP",
    "GAP_SAMPLE_WINDOW",
    "NOMINAL_RADIUS",
    "CaseGeometry",
    "case_geometry",
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
    slices = read_slices(Path(profiles_dir) / Path(case.rail_file).name)
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
        z_rail=float(found.z_rail[k]) + dx * dx / (2 * NOMINAL_RADIUS),
        interpenetration=-float(found.gap[k]),
        x_offset=dx,
        wheel_y=prepared.y,
        wheel_z=prepared.z,
    )


def surface_gap(
    case: ReferenceCase, geometry: CaseGeometry, profiles_dir: str | Path, x, t
) -> np.ndarray:
    """Undeformed normal gap of the 3-D surfaces on a grid at CONTACT's wheel position.

    The rail is the slice set interpolated along the track at every ``S + x`` (no
    envelope, no 2-D slice); the wheel is its profile at the case's shift and height
    plus the drop ``x^2 / (2 r)`` of its circle (r = :data:`NOMINAL_RADIUS`); the vertical
    gap at ``y = y_c + t cos(gamma)`` times ``cos(gamma)`` is the normal gap, as
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

    Returns
    -------
    numpy.ndarray
        m, (nx, ny), negative where the surfaces interpenetrate, 1 m where there is no rail.
    """
    x = np.asarray(x, float)
    t = np.asarray(t, float)
    slices = read_slices(Path(profiles_dir) / Path(case.rail_file).name)
    cosine = math.cos(geometry.angle)
    y = geometry.y_rail + t * cosine
    rail = slice_sections(slices, y, x=case.s + x, interpolation="auto").z
    order = np.argsort(geometry.wheel_y)
    wheel = np.interp(y - case.y, geometry.wheel_y[order], geometry.wheel_z[order])
    vertical = wheel[None, :] + case.wheel_height + x[:, None] ** 2 / (2 * NOMINAL_RADIUS) - rail
    return np.where(np.isfinite(vertical), cosine * vertical, _NO_RAIL)


@dataclass(frozen=True, eq=False)
class SurfaceContact:
    """The exact normal solution on the 3-D gap of a CONTACT case."""

    #: the solution at the prescribed force; its ``x`` and ``x_centre`` from the wheel
    #: centre along the track, its ``y`` and ``y_centre`` along the lateral tangent from the
    #: deepest point of the 2-D slice
    solution: NormalSolution
    interpenetration: float  #: m, largest undeformed interpenetration of the 3-D surfaces
    force_at_geometry: float  #: N, exact normal force at that interpenetration


def exact_on_surface(
    case: ReferenceCase,
    geometry: CaseGeometry,
    profiles_dir: str | Path,
    force: float,
    modulus: float,
    dx: float,
    ds: float,
    reach: tuple[float, float] = (6e-3, 3e-3),
) -> SurfaceContact:
    """Exact normal contact on the 3-D gap (:func:`surface_gap`) of a CONTACT case.

    The grid spans ``reach`` around the envelope's contact point and grows (x 1.5) while
    the contact touches its edge.

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

    Returns
    -------
    SurfaceContact
    """
    half_x, half_t = reach
    for _ in range(6):
        nx, ny = 2 * int(half_x / dx) + 1, 2 * int(half_t / ds) + 1
        x = geometry.x_offset + (np.arange(nx) - 0.5 * (nx - 1)) * dx
        t = (np.arange(ny) - 0.5 * (ny - 1)) * ds
        h = surface_gap(case, geometry, profiles_dir, x, t)
        lowest = float(np.min(h))
        solved = solve_normal(h - lowest, dx, ds, modulus, force=force)
        rows, cols = np.nonzero(solved.pressure)
        if rows.min() > 0 and cols.min() > 0 and rows.max() < nx - 1 and cols.max() < ny - 1:
            break
        half_x, half_t = 1.5 * half_x, 1.5 * half_t
    at_geometry = solve_normal(h - lowest, dx, ds, modulus, approach=-lowest).normal_force
    shift_x, shift_t = float(x[0] - solved.x[0]), float(t[0] - solved.y[0])
    placed = dataclasses.replace(
        solved,
        x=solved.x + shift_x,
        x_centre=solved.x_centre + shift_x,
        y=solved.y + shift_t,
        y_centre=solved.y_centre + shift_t,
    )
    return SurfaceContact(placed, -lowest, float(at_geometry))
