"""Rail cross-sections along the track: gridded surfaces, placement, slices, design sections.

Every rail surface used for contact is a :class:`SectionGrid`: the height ``z`` of the rail's
running surface (its upper envelope) on a uniform lateral grid ``y`` at positions ``x``
along the track, NaN where there is no rail.  Axes as in :mod:`.profiles`: ``y`` positive
towards the field side of the wheel/rail pair, ``z`` up, metres.  A *placed* rail is in
**side coordinates**: ``y`` is the distance from the track centre line (so the gauge point
of a standard rail is at ``gauge / 2``), the same for the left and the right rail.

Sections come from

- one profile (plain rail): :func:`plain_rail_sections`;
- a CONTACT slice set: :func:`slice_sections` (linear interpolation of the gridded heights
  between slices, which is exact for the slices and, for the 10 mm spacing of CONTACT's
  artificial crossing, moves a 1:10 flank by at most 0.5 mm in between);
- design parameters: :func:`switch_sections` (stock rail and planed switch blade) and
  :func:`crossing_sections` (wing rail and crossing nose), see :class:`SwitchDesign` and
  :class:`CrossingDesign`.

:func:`wheel_envelope` turns sections into what a rigid wheel of radius r rolling along x
feels: ``max over dx of z(x + dx, y) - dx^2 / (2 r)``, so a nose rising ahead of the wheel
is met before the wheel centre is over it (CONTACT's 3-D contact search does the same).
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
    "slice_sections",
    "section_at",
    "sections_at",
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


def slice_sections(
    slices: SliceSet,
    y_grid: np.ndarray,
    y_offset: float = 0.0,
    z_offset: float = 0.0,
    name: str = "",
) -> SectionGrid:
    """Sections at the slice positions of a CONTACT slice set, gridded.

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

    Returns
    -------
    SectionGrid
        x = the slice positions u.
    """
    heights = np.array([surface_on_grid(p, y_grid, y_offset, z_offset) for p in slices.profiles])
    return SectionGrid(x=slices.u.copy(), y=y_grid, z=heights, name=name or slices.source)


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


def wheel_envelope(
    sections: SectionGrid,
    x: np.ndarray,
    wheel_radius: float,
    reach: float = 0.12,
    step: float = 0.002,
) -> SectionGrid:
    """What a rigid wheel of radius r feels at x: ``max_dx z(x + dx, y) - dx^2 / (2 r)``.

    Parameters
    ----------
    sections : SectionGrid
        Sections to envelope.
    x : numpy.ndarray
        m, wheel-centre positions to evaluate.
    wheel_radius : float
        m, rolling radius (the envelope's drop is ``dx^2 / (2 r)``; its variation across the
        profile, +-6 % between tread and flange, is neglected).
    reach : float
        m, largest |dx| searched (at 0.12 m the wheel is 15.7 mm above its lowest point).
    step : float
        m, dx step.

    Returns
    -------
    SectionGrid
        Enveloped heights at ``x`` with ``x_offset`` = the dx where each height is met.
    """
    offsets = np.arange(-reach, reach + 0.5 * step, step)
    x = np.asarray(x, float)
    best = np.full((len(x), len(sections.y)), -np.inf)
    where = np.zeros_like(best)
    for dx in offsets:
        candidate = sections_at(sections, x + dx) - dx * dx / (2.0 * wheel_radius)
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
