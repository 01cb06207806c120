"""Rail cross-sections along the track: gridded surfaces, placement, slices, design sections.

Every rail surface used for contact is a :class:`SectionGrid`: the height ``z`` of the rail's
running surface (its upper envelope) on a uniform lateral grid ``y`` at positions ``x``
along the track, NaN where there is no rail.  Axes as in :mod:`.profiles`: ``y`` positive
towards the field side of the wheel/rail pair, ``z`` up, metres.  A *placed* rail is in
**side coordinates**: ``y`` is the distance from the track centre line (so the gauge point
of a standard rail is at ``gauge / 2``), the same for the left and the right rail.

Sections come from

- one profile (plain rail): :func:`plain_rail_sections`;
- a CONTACT slice set: :func:`slice_surface` and :func:`slice_sections`, interpolated along
  the track as CONTACT does (:data:`SLICE_INTERPOLATIONS`; see below);
- design parameters: :func:`switch_sections` (stock rail and planed switch blade) and
  :func:`crossing_sections` (wing rail and crossing nose), see :class:`SwitchDesign` and
  :class:`CrossingDesign`.

:func:`wheel_envelope` turns sections into what a rigid wheel of radius r rolling along x
feels: ``max over dx of z(x + dx, y) - (r - sqrt(r^2 - dx^2))``, so a nose rising ahead of the wheel
is met before the wheel centre is over it (CONTACT's 3-D contact search does the same).

Slices along the track
----------------------
CONTACT (open-source version, ``matlab/read_slices.m``, ``resample_slices.m`` and
``make_2dspline.m`` of its distribution, Vollebregt 2008-2023, Apache-2.0) turns a slice
set into a parametric surface (y, z)(u, v): each slice is cut at its feature positions
(``S_F`` of the ``.slcs`` file; without features, one part from the first point to the
last) and every part is resampled by arc length with the same number of points in every
slice, so the point index v follows a feature (a flange root, a nose tip) along the track;
a part whose feature positions are negative is absent in that slice.  Along u, each
point's y and z are interpolated through the slices where the point is present, in runs of
consecutive slices, by a cubic spline with not-a-knot end conditions (``U_INTPOL = 1``;
``2`` asks for an approximating spline instead).  :func:`slice_surface` builds the same
surface (along v, straight lines between resampled points 0.1 mm apart instead of CONTACT's
cubic spline) or joins the slices at constant y on the lateral grid, with
(:data:`SLICE_INTERPOLATIONS`)

- ``"auto"`` (default): CONTACT's surface (features, not-a-knot cubic along u) when the
  file gives features; without them, a shape-preserving cubic (PCHIP, Fritsch & Carlson,
  SIAM J. Numer. Anal. 17, 1980) along u at constant y.  Without features CONTACT joins
  points by their fraction of the slice's length, which joins unrelated points where the
  slices change shape: on ``uk_crossing.slcs`` the nose appears between u = 113.95 and
  118.94 mm and the profile's length doubles (107 -> 218 mm), and that surface rises 68
  mm above the rail between u = 80.8 and 118.9 mm (CONTACT's authors add features for this
  crossing, ``uk_interrupt_v2.slcs`` of their test bank).  At constant y a not-a-knot cubic rings
  where a vertical face crosses the column (at y = 38.6 mm: 1.59 mm at u = 238.5 mm between
  slices of 1.46 and 1.24 mm, 0.04 mm at u = 258.2 mm between 1.24 and 0.25 mm); PCHIP
  stays within its neighbouring slices and there agrees with the feature-aligned cubic
  within 0.01 mm (``tests/test_wheel_rail_sections_tables.py``);
- ``"spline"``, ``"pchip"``: that cubic along u, aligned by features when the file has
  them (``alignment`` overrides);
- ``"linear"``: the earlier behaviour, the gridded heights of neighbouring slices blended
  linearly at constant y (a laterally moving flank is then cut by the blend: on CONTACT's
  1:10 artificial crossing by up to 0.5 mm between slices 10 mm apart).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from exudyn_turnout.wheel_rail.profiles import Profile, SliceSet

__all__ = [
    "monotone_runs",
    "SectionGrid",
    "surface_on_grid",
    "incline_profile",
    "gauge_point",
    "place_rail",
    "plain_rail_sections",
    "SLICE_INTERPOLATIONS",
    "SliceSurface",
    "slice_surface",
    "slice_heights",
    "slice_sections",
    "section_at",
    "sections_at",
    "wheel_drop",
    "wheel_envelope",
    "SwitchDesign",
    "CrossingDesign",
    "switch_sections",
    "crossing_sections",
    "inclination_ramp",
    "nose_heights",
    "lateral_grid",
]

#: m, default lateral grid step: fine enough that a 0.1 mm shift resolves the contact point
DEFAULT_GRID_STEP = 1e-4

#: interpolations of a slice set along the track (:func:`slice_surface`); the first is the
#: default, CONTACT's
SLICE_INTERPOLATIONS = ("auto", "spline", "pchip", "linear")

#: m, arc-length step of the resampled slices (CONTACT: at most 0.5 mm with a cubic spline
#: along v; here straight lines along v, so the lateral grid's step)
SLICE_RESAMPLE_STEP = 1e-4


@dataclass(frozen=True, eq=False)
class SectionGrid:
    """Rail surface heights on a uniform lateral grid at positions along the track."""

    x: np.ndarray  #: m, positions along the track (n_x,), increasing
    y: np.ndarray  #: m, uniform lateral grid (n_y,), positive towards the field side
    z: np.ndarray  #: m, surface height (n_x, n_y), positive up; NaN where there is no rail
    name: str = ""  #: what the sections describe
    x_offset: np.ndarray | None = None  #: m, (n_x, n_y) where along x the surface is met


def lateral_grid(y_min: float, y_max: float, step: float = DEFAULT_GRID_STEP) -> np.ndarray:
    """Uniform lateral grid from ``y_min`` to at least ``y_max``.

    Parameters
    ----------
    y_min, y_max : float
        m, range to cover.
    step : float
        m, grid step.

    Returns
    -------
    numpy.ndarray
        ``y_min + step * arange(n)``.
    """
    count = int(math.ceil((y_max - y_min) / step)) + 1
    return y_min + step * np.arange(count)


def monotone_runs(y: np.ndarray) -> list[slice]:
    """Runs over which ``y`` does not change direction (a folded polyline's branches).

    Parameters
    ----------
    y : numpy.ndarray

    Returns
    -------
    list of slice
        Consecutive runs sharing their end points.
    """
    direction = np.sign(np.diff(y))
    nonzero = np.flatnonzero(direction)
    if nonzero.size == 0:
        return [slice(0, len(y))]
    filled = direction[
        nonzero[
            np.maximum(np.searchsorted(nonzero, np.arange(len(direction)), side="right") - 1, 0)
        ]
    ]
    changes = np.flatnonzero(filled[1:] != filled[:-1]) + 1
    starts = np.concatenate(([0], changes))
    ends = np.concatenate((changes, [len(direction)])) + 1
    return [slice(int(a), int(b)) for a, b in zip(starts, ends)]


def surface_on_grid(
    profile: Profile, y_grid: np.ndarray, y_offset: float = 0.0, z_offset: float = 0.0
) -> np.ndarray:
    """Surface of a profile on a lateral grid: the upper envelope for a rail, lower for a wheel.

    Parameters
    ----------
    profile : Profile
        Wheel or rail profile (may be multi-valued in y, e.g. a vertical rail side).
    y_grid : numpy.ndarray
        m, grid in the profile's frame shifted by ``y_offset``.
    y_offset, z_offset : float
        m, where the profile's origin lies in the grid's frame.

    Returns
    -------
    numpy.ndarray
        m, height at every grid point, NaN outside the profile.
    """
    sign = 1.0 if profile.kind == "rail" else -1.0
    y = profile.y + y_offset
    z = sign * (profile.z + z_offset)
    result = np.full(y_grid.shape, -np.inf)
    for run in monotone_runs(y):
        yr, zr = y[run], z[run]
        if yr[-1] < yr[0]:
            yr, zr = yr[::-1], zr[::-1]
        if yr[-1] <= yr[0]:
            continue
        inside = (y_grid >= yr[0]) & (y_grid <= yr[-1])
        result[inside] = np.maximum(result[inside], np.interp(y_grid[inside], yr, zr))
    result[np.isneginf(result)] = np.nan
    return sign * result


def incline_profile(profile: Profile, inclination: float) -> Profile:
    """Rotate a rail profile so that its top leans towards the track centre.

    Parameters
    ----------
    profile : Profile
        Rail profile with vertical axis of symmetry (e.g. ``uic60_true.prr``).
    inclination : float
        Tangent of the inclination angle (1/40 for standard track); positive tilts the
        running surface's normal towards the gauge side (the field side rises).

    Returns
    -------
    Profile
        The rotated profile (rotation about the profile origin).
    """
    angle = math.atan(inclination)
    c, s = math.cos(angle), math.sin(angle)
    return replace(profile, y=c * profile.y - s * profile.z, z=s * profile.y + c * profile.z)


def gauge_point(profile: Profile, depth: float = 0.014) -> float:
    """Lateral position of a rail's gauge point: the most gauge-side point ``depth`` below its top.

    Parameters
    ----------
    profile : Profile
        Rail profile.
    depth : float
        m, below the highest point (EN 15302 / EN 13848-1: 14 mm).

    Returns
    -------
    float
        m, y of the gauge point in the profile's frame.

    Raises
    ------
    ValueError
        If the profile does not reach ``depth`` below its top.
    """
    level = float(np.max(profile.z)) - depth
    z0, z1 = profile.z[:-1] - level, profile.z[1:] - level
    crossing = np.flatnonzero(z0 * z1 <= 0.0)
    crossing = crossing[np.abs(z1[crossing] - z0[crossing]) > 0.0]
    if crossing.size == 0:
        raise ValueError(
            f"{profile.source or 'profile'}: does not reach {depth * 1e3:.1f} mm below its top"
        )
    t = -z0[crossing] / (z1[crossing] - z0[crossing])
    y_cross = profile.y[crossing] + t * (profile.y[crossing + 1] - profile.y[crossing])
    return float(np.min(y_cross))


def place_rail(
    profile: Profile, gauge: float = 1.435, inclination: float = 0.0, gauge_depth: float = 0.014
) -> Profile:
    """Put a rail profile into side coordinates: top at z = 0, gauge point at ``gauge / 2``.

    Independent of the file's reference point (the Manchester benchmark's UIC60 is referenced
    at its highest point, already inclined: pass ``inclination=0`` for it).

    Parameters
    ----------
    profile : Profile
        Rail profile, y towards the field side.
    gauge : float
        m, track gauge measured at the gauge points.
    inclination : float
        Tangent of the inclination still to apply (0 if the profile is already inclined).
    gauge_depth : float
        m, depth of the gauge point below the top of rail.

    Returns
    -------
    Profile
        y = distance from the track centre (field side positive), z up, top at 0.
    """
    inclined = incline_profile(profile, inclination) if inclination else profile
    top = float(np.max(inclined.z))
    inclined = replace(inclined, z=inclined.z - top)
    shift = 0.5 * gauge - gauge_point(inclined, gauge_depth)
    return replace(inclined, y=inclined.y + shift)


def plain_rail_sections(
    profile: Profile, x: np.ndarray, y_grid: np.ndarray, name: str = "plain rail"
) -> SectionGrid:
    """The same (placed) profile at every x.

    Parameters
    ----------
    profile : Profile
        Rail profile in the grid's frame (see :func:`place_rail`).
    x : numpy.ndarray
        m, positions along the track.
    y_grid : numpy.ndarray
        m, lateral grid.
    name : str
        Label.

    Returns
    -------
    SectionGrid
    """
    heights = surface_on_grid(profile, y_grid)
    return SectionGrid(x=np.asarray(x, float), y=y_grid, z=np.tile(heights, (len(x), 1)), name=name)


@dataclass(frozen=True, eq=False)
class SliceSurface:
    """A slice set ready for interpolation along the track (see the module docstring)."""

    u: np.ndarray  #: m, slice positions (n_s,)
    y: np.ndarray  #: m, lateral grid of the heights returned (n_y,), side coordinates
    method: str  #: interpolation along u, one of :data:`SLICE_INTERPOLATIONS`
    alignment: str  #: "features" (CONTACT's v) or "lateral" (constant y)
    #: (u_first, u_last, columns, interpolant of y or None, interpolant of z) per run of
    #: slices and group of points (features) or grid columns (lateral)
    pieces: tuple
    n_points: int  #: points per resampled slice (features) or grid columns (lateral)
    y_offset: float = 0.0  #: m, where the slice profiles' origin lies in the grid's frame
    z_offset: float = 0.0  #: m, the same vertically
    source: str = ""  #: the slice file


def _breaks(features: np.ndarray, length: float) -> np.ndarray:
    """Feature positions of one slice along its arc length (NaN: feature absent)."""
    if features.size <= 1:
        return np.array([0.0, length])
    breaks = np.where(features >= 0.0, features, np.nan)
    last = int(np.flatnonzero(np.isfinite(breaks))[-1])
    breaks[last] = min(breaks[last], length)
    return breaks


def _resample(slices: SliceSet, step: float) -> tuple[np.ndarray, np.ndarray]:
    """Every slice resampled with the same number of points per part (CONTACT's v)."""
    arcs = []
    for profile in slices.profiles:
        ds = np.hypot(np.diff(profile.y), np.diff(profile.z))
        arcs.append(np.concatenate(([0.0], np.cumsum(ds))))
    features = slices.features if slices.features.shape[1] > 1 else np.zeros((len(arcs), 0))
    breaks = np.array([_breaks(np.asarray(f, float), float(a[-1])) for f, a in zip(features, arcs)])
    with np.errstate(invalid="ignore"):
        lengths = np.diff(breaks, axis=1)
    if np.any(lengths <= 0.0):
        raise ValueError(f"{slices.source}: feature positions are not increasing in a slice")
    longest = np.nanmax(np.where(np.isfinite(lengths), lengths, -1.0), axis=0)
    segments = np.maximum(np.ceil(np.maximum(longest, 0.0) / step - 1e-9).astype(int), 1)
    first = np.concatenate(([0], np.cumsum(segments)))
    n_v = int(first[-1]) + 1
    y = np.full((len(arcs), n_v), np.nan)
    z = np.full((len(arcs), n_v), np.nan)
    for i, (profile, arc) in enumerate(zip(slices.profiles, arcs)):
        for part in np.flatnonzero(np.isfinite(lengths[i])):
            a, b = first[part], first[part + 1]
            s = np.linspace(breaks[i, part], breaks[i, part + 1], b - a + 1)
            y[i, a : b + 1] = np.interp(s, arc, profile.y)
            z[i, a : b + 1] = np.interp(s, arc, profile.z)
    return y, z


def _runs(present: np.ndarray) -> list[tuple[int, int]]:
    """(first, last) indices of the runs of True in a 1-D mask."""
    edges = np.flatnonzero(np.diff(np.concatenate(([0], present.astype(int), [0]))))
    return [(int(a), int(b) - 1) for a, b in zip(edges[::2], edges[1::2])]


def _interpolant(u: np.ndarray, values: np.ndarray, method: str):
    """Interpolant along u of the rows of ``values`` (None for a single slice)."""
    # imported here: a passage whose route tables are stored never builds sections, and
    # scipy.interpolate is ~0.03 s of every process's start (a study's serial part)
    from scipy.interpolate import CubicSpline, PchipInterpolator, make_interp_spline

    if len(u) == 1:
        return None
    if method == "linear" or len(u) == 2:
        return make_interp_spline(u, values, k=1, axis=0)
    if method == "pchip":
        return PchipInterpolator(u, values, axis=0)
    return CubicSpline(u, values, axis=0, bc_type="not-a-knot")


def _pieces(u: np.ndarray, values: tuple, method: str) -> tuple:
    """Interpolants over the runs of slices where a point (column) is present."""
    present = np.all([np.isfinite(v) for v in values], axis=0)
    patterns: dict[bytes, list[int]] = {}
    for j in range(present.shape[1]):
        if present[:, j].any():
            patterns.setdefault(present[:, j].tobytes(), []).append(j)
    pieces = []
    for columns in patterns.values():
        cols = np.array(columns)
        for a, b in _runs(present[:, cols[0]]):
            run = slice(a, b + 1)
            fits = [_interpolant(u[run], v[run][:, cols], method) for v in values]
            if len(values) == 1:
                fits = [None] + fits
            if fits[-1] is None:  # a point present in one slice only: there only
                fits = [v[a, cols] for v in values]
                if len(values) == 1:
                    fits = [None] + fits
            pieces.append((float(u[a]), float(u[b]), cols, fits[0], fits[1]))
    return tuple(pieces)


def slice_surface(
    slices: SliceSet,
    y_grid: np.ndarray,
    y_offset: float = 0.0,
    z_offset: float = 0.0,
    interpolation: str = "auto",
    alignment: str = "auto",
    step: float = SLICE_RESAMPLE_STEP,
) -> SliceSurface:
    """A slice set as a surface along the track, interpolated between its slices.

    Parameters
    ----------
    slices : SliceSet
        From :func:`.profiles.read_slices`.
    y_grid : numpy.ndarray
        m, lateral grid of the heights (:func:`slice_heights`), in the frame of the slice
        profiles shifted by ``y_offset``.
    y_offset, z_offset : float
        m, where the slice profiles' origin lies in the grid's frame.
    interpolation : str
        Along u, one of :data:`SLICE_INTERPOLATIONS` (see the module docstring).
    alignment : {"auto", "features", "lateral"}
        Which points of neighbouring slices are joined: by CONTACT's feature-aligned
        resampling, or at constant y on the grid.  ``"auto"``: features if the file gives
        at least two per slice and the interpolation is not linear, else lateral.  The
        surface records the interpolation and alignment used (``"auto"`` resolved).
    step : float
        m, arc-length step of the resampled slices (features).

    Returns
    -------
    SliceSurface

    Raises
    ------
    ValueError
        Unknown interpolation or alignment, or a slice whose feature positions do not
        increase.
    """
    if interpolation not in SLICE_INTERPOLATIONS:
        raise ValueError(
            f"slice interpolation {interpolation!r}: expected one of {SLICE_INTERPOLATIONS}"
        )
    if alignment not in ("auto", "features", "lateral"):
        raise ValueError(f"slice alignment {alignment!r}: expected auto, features or lateral")
    featured = slices.features.shape[1] > 1
    if interpolation == "auto":
        interpolation = "spline" if featured else "pchip"
    if alignment == "auto":
        alignment = "features" if featured and interpolation != "linear" else "lateral"
    u = np.asarray(slices.u, float)
    y_grid = np.asarray(y_grid, float)
    if alignment == "features":
        y, z = _resample(slices, step)
        pieces = _pieces(u, (y, z), interpolation)
        n_points = y.shape[1]
    else:
        heights = np.array(
            [surface_on_grid(p, y_grid, y_offset, z_offset) for p in slices.profiles]
        )
        pieces = _pieces(u, (heights,), interpolation)
        n_points = len(y_grid)
    return SliceSurface(
        u=u,
        y=y_grid,
        method=interpolation,
        alignment=alignment,
        pieces=pieces,
        n_points=n_points,
        y_offset=y_offset,
        z_offset=z_offset,
        source=slices.source,
    )


def _evaluate(surface: SliceSurface, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Interpolated points (features) or heights (lateral) at x, NaN where absent."""
    y = np.full((len(x), surface.n_points), np.nan)
    z = np.full((len(x), surface.n_points), np.nan)
    scale = 1e-12 * max(1.0, float(np.max(np.abs(surface.u))))
    for first, last, cols, fy, fz in surface.pieces:
        inside = np.flatnonzero((x >= first - scale) & (x <= last + scale))
        if inside.size == 0:
            continue
        if callable(fz):
            xi = np.clip(x[inside], first, last)
            z[np.ix_(inside, cols)] = fz(xi)
            if fy is not None:
                y[np.ix_(inside, cols)] = fy(xi)
        else:  # one slice: the points themselves, at its position only
            z[np.ix_(inside, cols)] = fz
            if fy is not None:
                y[np.ix_(inside, cols)] = fy
    return y, z


def slice_heights(surface: SliceSurface, x: np.ndarray) -> np.ndarray:
    """Heights of a slice surface on its lateral grid at positions along the track.

    Parameters
    ----------
    surface : SliceSurface
        From :func:`slice_surface`.
    x : numpy.ndarray
        m, positions (slice coordinate u; clamped to the slices' range).

    Returns
    -------
    numpy.ndarray
        m, (len(x), n_y) heights (upper envelope), NaN where there is no rail.
    """
    x = np.clip(np.atleast_1d(np.asarray(x, float)), surface.u[0], surface.u[-1])
    y, z = _evaluate(surface, x)
    if surface.alignment == "lateral":
        return z
    out = np.full((len(x), len(surface.y)), np.nan)
    for i in range(len(x)):
        finite = np.isfinite(y[i]) & np.isfinite(z[i])
        for a, b in _runs(finite):
            if b == a:
                continue
            piece = Profile(y=y[i, a : b + 1], z=z[i, a : b + 1], kind="rail", source="")
            heights = surface_on_grid(piece, surface.y, surface.y_offset, surface.z_offset)
            out[i] = np.fmax(out[i], heights)
    return out


def slice_sections(
    slices: SliceSet,
    y_grid: np.ndarray,
    y_offset: float = 0.0,
    z_offset: float = 0.0,
    name: str = "",
    x: np.ndarray | None = None,
    interpolation: str = "auto",
) -> SectionGrid:
    """Sections of a CONTACT slice set, gridded, at the slice positions or at given x.

    Parameters
    ----------
    slices : SliceSet
        From :func:`.profiles.read_slices`.
    y_grid : numpy.ndarray
        m, lateral grid in the frame of the slice profiles shifted by ``y_offset``.
    y_offset, z_offset : float
        m, where the slice profiles' origin lies in the grid's frame.
    name : str
        Label (default: the slice file).
    x : numpy.ndarray, optional
        m, positions along the track (slice coordinate u) to evaluate.  Default: the slice
        positions, each slice's own profile gridded (between them :func:`sections_at`
        interpolates linearly); for the interpolation along u, pass the positions that
        will be used, as dense as needed.
    interpolation : str
        One of :data:`SLICE_INTERPOLATIONS` (used with ``x``; alignment ``"auto"``).

    Returns
    -------
    SectionGrid
    """
    if x is None:
        heights = np.array(
            [surface_on_grid(p, y_grid, y_offset, z_offset) for p in slices.profiles]
        )
        return SectionGrid(x=slices.u.copy(), y=y_grid, z=heights, name=name or slices.source)
    positions = np.asarray(x, float)
    surface = slice_surface(slices, y_grid, y_offset, z_offset, interpolation)
    return SectionGrid(
        x=positions, y=y_grid, z=slice_heights(surface, positions), name=name or slices.source
    )


def section_at(sections: SectionGrid, x: float) -> np.ndarray:
    """Heights at one position, linearly interpolated between the two neighbouring sections.

    Parameters
    ----------
    sections : SectionGrid
        Gridded sections.
    x : float
        m, position (clamped to the sections' range).

    Returns
    -------
    numpy.ndarray
        m, heights on ``sections.y`` (NaN where either neighbour has no rail).
    """
    xs = sections.x
    if x <= xs[0]:
        return sections.z[0].copy()
    if x >= xs[-1]:
        return sections.z[-1].copy()
    i = int(np.searchsorted(xs, x, side="right")) - 1
    t = (x - xs[i]) / (xs[i + 1] - xs[i])
    if t == 0.0:
        return sections.z[i].copy()
    return (1.0 - t) * sections.z[i] + t * sections.z[i + 1]


def sections_at(sections: SectionGrid, x: np.ndarray) -> np.ndarray:
    """Heights at several positions (vectorised :func:`section_at`).

    Parameters
    ----------
    sections : SectionGrid
        Gridded sections.
    x : numpy.ndarray
        m, positions (clamped to the sections' range).

    Returns
    -------
    numpy.ndarray
        m, (len(x), n_y) heights.
    """
    xs = sections.x
    x = np.clip(np.asarray(x, float), xs[0], xs[-1])
    i = np.clip(np.searchsorted(xs, x, side="right") - 1, 0, len(xs) - 2)
    t = ((x - xs[i]) / (xs[i + 1] - xs[i]))[:, None]
    blend = (1.0 - t) * sections.z[i] + t * sections.z[i + 1]
    return np.where(t == 0.0, sections.z[i], np.where(t == 1.0, sections.z[i + 1], blend))


def wheel_drop(dx, wheel_radius: float):
    """How far a wheel's circle lies above its lowest point at dx ahead of the axle.

    Parameters
    ----------
    dx : float or numpy.ndarray
        m, distance along the track from the axle (|dx| < ``wheel_radius``).
    wheel_radius : float
        m, rolling radius.

    Returns
    -------
    float or numpy.ndarray
        m, ``r - sqrt(r^2 - dx^2)`` (the parabola ``dx^2 / (2 r)`` lies below it by
        ``dx^4 / (8 r^3)``).
    """
    return wheel_radius - np.sqrt(wheel_radius * wheel_radius - np.square(dx))


def wheel_envelope(
    sections: SectionGrid,
    x: np.ndarray,
    wheel_radius: float,
    reach: float = 0.12,
    step: float = 0.002,
) -> SectionGrid:
    """What a rigid wheel of radius r feels at x: ``max_dx z(x + dx, y) - d(dx)``.

    ``d(dx) = r - sqrt(r^2 - dx^2)`` is the circle's drop at dx ahead of (or behind) the
    axle.  The parabola ``dx^2 / (2 r)`` used before lies below the circle by
    ``dx^4 / (8 r^3)``: 5.7 um at 46 mm ahead, where CONTACT's cross_brute case has its
    contact (+19.5 % of its 0.034 mm approach; validation/detailed_vs_contact.md).

    Parameters
    ----------
    sections : SectionGrid
        Sections to envelope.
    x : numpy.ndarray
        m, wheel-centre positions to evaluate.
    wheel_radius : float
        m, rolling radius (the envelope's drop is the circle's; its variation across the
        profile, +-6 % between tread and flange, is neglected).
    reach : float
        m, largest |dx| searched (at 0.12 m a wheel of r = 0.46 m is 15.9 mm above its
        lowest point); at most the radius.
    step : float
        m, dx step.

    Returns
    -------
    SectionGrid
        Enveloped heights at ``x`` with ``x_offset`` = the dx where each height is met.
    """
    if not 0.0 < reach < wheel_radius:
        raise ValueError(f"reach {reach} m must lie between 0 and the wheel radius {wheel_radius}")
    offsets = np.arange(-reach, reach + 0.5 * step, step)
    x = np.asarray(x, float)
    best = np.full((len(x), len(sections.y)), -np.inf)
    where = np.zeros_like(best)
    for dx in offsets:
        candidate = sections_at(sections, x + dx) - wheel_drop(dx, wheel_radius)
        better = np.nan_to_num(candidate, nan=-np.inf) > best
        best[better] = candidate[better]
        where[better] = dx
    best[np.isneginf(best)] = np.nan
    return SectionGrid(
        x=np.asarray(x, float),
        y=sections.y,
        z=best,
        name=f"{sections.name} (wheel envelope r = {wheel_radius} m)",
        x_offset=where,
    )


@dataclass(frozen=True)
class SwitchDesign:
    """Design parameters of a switch (stock rail and planed blade), through route.

    x is measured from the switch toe along the (straight) through route; the blade carries
    the through route's wheel, the stock rail curves away from it to the field side.
    """

    #: m, radius of the diverging route, which sets how fast the stock rail leaves the
    #: through route (x^2 / 2R); 760 m: the packaged UIC60-760-1:15 turnout.
    radius: float = 760.0
    #: tangent of the blade's entry angle at the toe.  0.0052 makes the blade head 45 mm
    #: wide 5 m after the toe, where Kassa & Nielsen (VSD 46 S1, 2008) put full height
    #: for a 60E1-760-1:15 switch (the value the packaged turnout file cites).
    entry_tangent: float = 0.0052
    #: m, blade head width at the toe: a planed blade tip (assumed; it must fit under the
    #: stock rail's gauge corner, so a few mm).
    toe_width: float = 0.003
    #: m, how far the blade top is below the stock rail at the toe (3 mm: the packaged
    #: turnout file, after Kassa & Nielsen 2008).
    toe_lowering: float = 0.003
    #: m, distance from the toe over which the blade top rises linearly to full height
    #: (5 m: the packaged turnout file, after Kassa & Nielsen 2008).
    lowering_length: float = 5.0
    #: m, head width of the full rail (UIC60 / 60E1: 72 mm, EN 13674-1).
    head_width: float = 0.072


@dataclass(frozen=True)
class CrossingDesign:
    """Design parameters of a fixed common crossing (wing rail and nose), through route.

    x is measured along the through route in the same frame as the turnout; the wheel's
    running line is the straight gauge line; the nose's gauge face stays on it and the nose
    widens towards the field side, the wing rail flares away to the field side.
    """

    #: m, position of the nose tip (45.5 m in the packaged turnout file).
    nose_tip: float = 45.5
    #: crossing number N of a 1:N crossing (15: UIC60-760-1:15).
    crossing_number: float = 15.0
    #: m, width of the blunt nose tip (assumed: 10 mm; a nose is blunted for strength).
    tip_width: float = 0.010
    #: m, how far the nose top is below the wing rail at its tip (3 mm: the packaged
    #: turnout file).
    tip_lowering: float = 0.003
    #: m, length after the tip over which the nose rises linearly to full height (0.5 m:
    #: the packaged turnout file).
    lowering_length: float = 0.5
    #: m, flangeway between wing rail and nose at the tip (assumed 41 mm, a common figure
    #: for standard-gauge crossings; no source at hand).
    flangeway: float = 0.041
    #: m, head width of the full rail (72 mm, EN 13674-1); :func:`crossing_sections`
    #: fills the nose between its legs' crowns at crown level (:func:`nose_heights`).
    head_width: float = 0.072
    #: m, length over which the crossing's upright rail twists to the track's inclination
    #: before the plain track that follows it (:func:`inclination_ramp`; used by
    #: :mod:`.turnout_sections`, which ends it where the nose segment ends).  Assumed: a
    #: crossing laid upright in 1:40 track is joined by rails twisted over a few sleeper
    #: bays; 2 m (3-4 bays) turns a 72 mm head by 25 mrad with its edges moving 0.9 mm
    #: vertically, 0.45 mm per metre (no source at hand for a standard length).
    inclination_transition: float = 2.0


def inclination_ramp(x: float, x_end: float, length: float, inclination: float) -> float:
    """Inclination of a rail that twists from upright to ``inclination`` ending at ``x_end``.

    Linear in the tangent: 0 up to ``x_end - length``, ``inclination`` from ``x_end`` on
    (a twisted rail turns at a constant rate; the rate is the design's choice, linear is
    the simplest that is continuous at both ends).

    Parameters
    ----------
    x : float
        m, position along the route.
    x_end : float
        m, where the rail reaches the track's inclination.
    length : float
        m, length of the twist (0: none, the rail stays upright and the rail that follows
        it steps).
    inclination : float
        Tangent of the track's inclination (1/40).

    Returns
    -------
    float
        Tangent of the inclination at x.
    """
    if length <= 0.0:  # no twist: upright to its end, where the next rail steps
        return 0.0
    return inclination * min(max((x - (x_end - length)) / length, 0.0), 1.0)


def nose_heights(
    leg: np.ndarray,
    y_grid: np.ndarray,
    half_gauge: float,
    width: float,
    lowering: float,
    head_width: float | None = None,
) -> np.ndarray:
    """A crossing nose section: two rail legs ``width`` apart, mirrored about their middle.

    The through leg is ``leg`` (a full rail placed with its gauge point at ``half_gauge``)
    up to the middle line ``half_gauge + width / 2``; beyond it, the other leg, the same
    rail mirrored so that its gauge face is at ``half_gauge + width``.  With ``head_width``
    the part between the two crowns (``head_width / 2`` from each gauge face) is filled at
    crown level (a machined nose block, :func:`crossing_sections`); without it each leg
    keeps its own head, so once the legs are apart (the mirror beyond the grid) the section
    is ``leg`` itself, the plain rail a crossing leg continues as.  The rail is cut 20 mm
    on the gauge side of the gauge face; the whole nose is lowered by ``lowering``.

    Parameters
    ----------
    leg : numpy.ndarray
        m, heights of the full rail on ``y_grid`` (NaN: no rail).
    y_grid : numpy.ndarray
        m, uniform lateral grid (side coordinates).
    half_gauge : float
        m, lateral position of the through leg's gauge point.
    width : float
        m, nose width between the two legs' gauge faces.
    lowering : float
        m, how far the nose top is below the rail's.
    head_width : float, optional
        m, head width: fill between the crowns (default: no fill).

    Returns
    -------
    numpy.ndarray
        m, heights (NaN: no rail).
    """
    from_gauge = np.minimum(y_grid - half_gauge, half_gauge + width - y_grid)
    if head_width is not None:
        distance = np.minimum(from_gauge, 0.5 * head_width)
        nose = np.interp(half_gauge + distance, y_grid, leg)
    else:
        nose = leg.copy()
        far = y_grid > half_gauge + 0.5 * width
        nose[far] = np.interp(2.0 * half_gauge + width - y_grid[far], y_grid, leg)
    nose[from_gauge < -0.02] = np.nan
    return nose - lowering


def _shifted_heights(base: Profile, y_grid: np.ndarray, shift: float) -> np.ndarray:
    return surface_on_grid(base, y_grid, y_offset=shift)


def switch_sections(
    design: SwitchDesign, base: Profile, x: np.ndarray, y_grid: np.ndarray, gauge: float = 1.435
) -> dict[str, SectionGrid]:
    """Stock rail and switch blade sections from design parameters (through route).

    Parameters
    ----------
    design : SwitchDesign
        Design parameters.
    base : Profile
        Placed full rail profile (gauge point at ``gauge / 2``, top at 0; see
        :func:`place_rail`).
    x : numpy.ndarray
        m, positions from the toe.
    y_grid : numpy.ndarray
        m, lateral grid (side coordinates).
    gauge : float
        m, track gauge.

    Returns
    -------
    dict
        ``{"stock": SectionGrid, "blade": SectionGrid}``.  The blade's head spans from the
        running gauge line to the stock rail's gauge face (planed on its field side), capped
        at the full head width; its top is lowered near the toe.
    """
    half = 0.5 * gauge
    heights: dict[str, list[np.ndarray]] = {"stock": [], "blade": []}
    for xi in np.asarray(x, float):
        setback = design.toe_width + design.entry_tangent * xi + xi * xi / (2 * design.radius)
        heights["stock"].append(_shifted_heights(base, y_grid, max(setback, 0.0)))
        blade = _shifted_heights(base, y_grid, 0.0)
        if xi < 0.0:
            blade[:] = np.nan
        else:
            lowering = design.toe_lowering * max(0.0, 1.0 - xi / design.lowering_length)
            width = min(setback, design.head_width)
            blade[y_grid > half + width] = np.nan
            blade -= lowering
        heights["blade"].append(blade)
    return {
        key: SectionGrid(x=np.asarray(x, float), y=y_grid, z=np.array(value), name=f"switch {key}")
        for key, value in heights.items()
    }


def crossing_sections(
    design: CrossingDesign, base: Profile, x: np.ndarray, y_grid: np.ndarray, gauge: float = 1.435
) -> dict[str, SectionGrid]:
    """Wing rail and crossing nose sections from design parameters (through route).

    Parameters
    ----------
    design : CrossingDesign
        Design parameters.
    base : Profile
        Placed full rail profile (gauge point at ``gauge / 2``, top at 0).
    x : numpy.ndarray
        m, positions along the route.
    y_grid : numpy.ndarray
        m, lateral grid (side coordinates).
    gauge : float
        m, track gauge.

    Returns
    -------
    dict
        ``{"wing": SectionGrid, "nose": SectionGrid}``.  The nose is two gauge-corner halves
        of the base profile ``width`` apart (so a narrow nose is also lower, as a real one),
        ``width = tip_width + (x - nose_tip) / N``, lowered near the tip; the wing rail's gauge
        face leaves the running line at 1:N from the throat so that the flangeway at the
        nose tip is ``flangeway``.
    """
    half = 0.5 * gauge
    slope = 1.0 / design.crossing_number
    throat = design.nose_tip - design.crossing_number * (design.tip_width + design.flangeway)
    base_heights = surface_on_grid(base, y_grid)
    heights: dict[str, list[np.ndarray]] = {"wing": [], "nose": []}
    for xi in np.asarray(x, float):
        flare = max(0.0, (xi - throat) * slope)
        heights["wing"].append(_shifted_heights(base, y_grid, flare))
        if xi < design.nose_tip:
            heights["nose"].append(np.full(y_grid.shape, np.nan))
            continue
        width = design.tip_width + (xi - design.nose_tip) * slope
        lowering = design.tip_lowering * max(
            0.0, 1.0 - (xi - design.nose_tip) / design.lowering_length
        )
        heights["nose"].append(
            nose_heights(base_heights, y_grid, half, width, lowering, design.head_width)
        )
    return {
        key: SectionGrid(
            x=np.asarray(x, float), y=y_grid, z=np.array(value), name=f"crossing {key}"
        )
        for key, value in heights.items()
    }
