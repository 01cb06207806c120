"""Wheel and rail profiles on a uniform lateral grid: heights, slopes, curvatures.

The wheelset and track dimensions that place the profiles (:class:`WheelsetSetup`), a wheel
profile gridded in its own lateral coordinate with Savitzky-Golay slopes and curvatures
(:func:`grid_wheel`), the same derivatives for gridded rail sections
(:func:`surface_derivatives`) and a (shifted, lifted, rolled) wheel's heights on a rail grid
(:func:`wheel_heights_on_grid`).  Axes and signs as in :mod:`.geometry`, which uses these
and re-exports the public names.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from exudyn_turnout.wheel_rail.profiles import Profile
from exudyn_turnout.wheel_rail.sections import SectionGrid, surface_on_grid

__all__ = [
    "WheelsetSetup",
    "WheelGrid",
    "SurfaceDerivatives",
    "CURVATURE_WINDOW",
    "grid_wheel",
    "wheel_surface",
    "surface_derivatives",
    "wheel_heights_on_grid",
    "savgol_derivatives",
    "wheel_points",
]

#: m, Savitzky-Golay window for profile slopes and curvatures
CURVATURE_WINDOW = 1.5e-3


@dataclass(frozen=True)
class WheelsetSetup:
    """Track and wheelset dimensions that place the profiles (SI)."""

    gauge: float = 1.435  #: m, track gauge at the gauge points (standard gauge)
    back_to_back: float = 1.360  #: m, wheelset back-to-back distance (EN 13260 nominal)
    #: m, lateral distance from the back of the flange to the taping line (S1002, EN 13715)
    flange_back: float = 0.070
    #: tangent of the rail inclination still to apply to the rail profile (1/40 standard)
    inclination: float = 1.0 / 40.0
    gauge_depth: float = 0.014  #: m, gauge point below the top of rail (EN 15302)
    nominal_radius: float = 0.46  #: m, wheel radius at the taping line (Manchester)
    grid_step: float = 1e-4  #: m, lateral grid step

    @property
    def taping_line(self) -> float:
        """m, nominal distance of the taping line from the track centre."""
        return 0.5 * self.back_to_back + self.flange_back


@dataclass(frozen=True, eq=False)
class WheelGrid:
    """A wheel profile's lower surface on a uniform grid of its own lateral coordinate."""

    s: np.ndarray  #: m, lateral coordinate from the taping line, towards the field side
    z: np.ndarray  #: m, surface height above the taping circle's lowest point (NaN: none)
    slope: np.ndarray  #: dz/ds (-)
    curvature: np.ndarray  #: 1/m, lateral curvature, positive convex towards the rail
    nominal_radius: float  #: m, radius at s = 0


@dataclass(frozen=True, eq=False)
class SurfaceDerivatives:
    """Slope and curvature of gridded rail surfaces (same shape as the heights)."""

    slope: np.ndarray  #: dz/dy (-)
    curvature: np.ndarray  #: 1/m, positive convex (crown)


def savgol_derivatives(z: np.ndarray, step: float, window: float) -> tuple[np.ndarray, np.ndarray]:
    """First and second derivatives of a gridded surface by Savitzky-Golay filters (cubic).

    Parameters
    ----------
    z : numpy.ndarray
        m, heights on a uniform grid; non-finite where there is no surface.
    step : float
        m, grid step.
    window : float
        m, the filter's window (at least 5 points).

    Returns
    -------
    slope, second : numpy.ndarray
        -, 1/m; NaN where ``z`` is not finite.
    """
    points = max(5, int(round(window / step)) | 1)
    filled = np.where(np.isfinite(z), z, np.nan)
    finite = np.isfinite(filled)
    slope = np.full(z.shape, np.nan)
    second = np.full(z.shape, np.nan)
    if finite.sum() <= points:
        return slope, second
    idx = np.arange(z.shape[-1])
    padded = np.interp(idx, idx[finite], filled[finite])
    from scipy.signal import savgol_filter  # here: scipy.signal costs 0.6 s to import

    slope = savgol_filter(padded, points, 3, deriv=1, delta=step)
    second = savgol_filter(padded, points, 3, deriv=2, delta=step)
    slope[~finite] = np.nan
    second[~finite] = np.nan
    return slope, second


def wheel_surface(profile: Profile, step: float = 1e-4) -> tuple[np.ndarray, np.ndarray]:
    """A wheel profile on a uniform lateral grid, heights only (:func:`grid_wheel`'s grid).

    What :func:`grid_wheel` computes before its Savitzky-Golay derivatives, for a caller
    that needs no slopes or curvatures (and so not ``scipy.signal``, 0.3-0.6 s to import).

    Parameters
    ----------
    profile : Profile
        Wheel profile (kind "wheel").
    step : float
        m, grid step.

    Returns
    -------
    s : numpy.ndarray
        m, lateral coordinate (:attr:`WheelGrid.s`).
    z : numpy.ndarray
        m, surface height (:attr:`WheelGrid.z`; NaN: none).
    """
    s = np.round(np.min(profile.y) / step) * step + step * np.arange(
        int((np.max(profile.y) - np.min(profile.y)) / step) + 1
    )
    return s, surface_on_grid(profile, s)


def grid_wheel(
    profile: Profile, step: float = 1e-4, nominal_radius: float = 0.46, window: float = 1.5e-3
) -> WheelGrid:
    """Grid a wheel profile and compute its slope and lateral curvature.

    Parameters
    ----------
    profile : Profile
        Wheel profile (kind "wheel").
    step : float
        m, grid step (the rail grid must use the same).
    nominal_radius : float
        m, radius at the taping line.
    window : float
        m, Savitzky-Golay window for the derivatives.

    Returns
    -------
    WheelGrid
    """
    s, z = wheel_surface(profile, step)
    slope, second = savgol_derivatives(z, step, window)
    curvature = second / (1.0 + slope**2) ** 1.5
    return WheelGrid(s=s, z=z, slope=slope, curvature=curvature, nominal_radius=nominal_radius)


def surface_derivatives(sections: SectionGrid, window: float = 1.5e-3) -> SurfaceDerivatives:
    """Slopes and curvatures of every gridded rail section.

    Parameters
    ----------
    sections : SectionGrid
        Gridded rail sections.
    window : float
        m, Savitzky-Golay window.

    Returns
    -------
    SurfaceDerivatives
        Arrays shaped like ``sections.z``.
    """
    step = float(sections.y[1] - sections.y[0])
    slopes, curvatures = [], []
    for row in np.atleast_2d(sections.z):
        slope, second = savgol_derivatives(row, step, window)
        slopes.append(slope)
        curvatures.append(-second / (1.0 + slope**2) ** 1.5)
    return SurfaceDerivatives(slope=np.array(slopes), curvature=np.array(curvatures))


def wheel_heights_on_grid(
    wheel: WheelGrid,
    y_grid: np.ndarray,
    taping_line: float,
    shift: float = 0.0,
    lift: float = 0.0,
    roll: float = 0.0,
) -> tuple[np.ndarray, np.ndarray]:
    """Wheel surface height and its lateral coordinate at every rail grid point.

    Parameters
    ----------
    wheel : WheelGrid
        Gridded wheel.
    y_grid : numpy.ndarray
        m, rail grid (side coordinates, or any frame in which the wheel's taping line is at
        ``taping_line + shift``).
    taping_line : float
        m, nominal lateral position of the taping line in the grid's frame.
    shift : float
        m, lateral displacement of the wheel towards the field side.
    lift : float
        m, height of the taping circle's lowest point above z = 0.
    roll : float
        rad, rotation about the wheelset centre, which lies ``taping_line`` towards the track
        centre and ``nominal_radius`` above the taping circle's lowest point; positive lifts
        the field side of this wheel.

    Returns
    -------
    heights : numpy.ndarray
        m, wheel surface height on the grid (NaN outside the wheel).
    s_wheel : numpy.ndarray
        m, wheel lateral coordinate at each grid point.
    """
    y_points, z_points = wheel_points(wheel, taping_line, shift, lift, roll)
    finite = np.isfinite(z_points)
    inside = (y_grid >= y_points[finite][0]) & (y_grid <= y_points[finite][-1])
    heights = np.full(y_grid.shape, np.nan)
    heights[inside] = np.interp(y_grid[inside], y_points[finite], z_points[finite])
    s_wheel = np.interp(y_grid, y_points[finite], wheel.s[finite])
    return heights, s_wheel


def wheel_points(
    wheel: WheelGrid, taping_line: float, shift: float, lift: float, roll: float
) -> tuple[np.ndarray, np.ndarray]:
    """A wheel's profile points in the track frame for a wheelset position.

    Parameters
    ----------
    wheel : WheelGrid
    taping_line : float
        m, lateral position of the wheel's taping line on the centred wheelset.
    shift, lift, roll : float
        m, m, rad: the wheelset's lateral shift, lift and roll (about its centre).

    Returns
    -------
    y, z : numpy.ndarray
        m.
    """
    r0 = wheel.nominal_radius
    y_points = taping_line + wheel.s
    z_points = wheel.z - r0
    if roll:
        c, s = math.cos(roll), math.sin(roll)
        y_points, z_points = c * y_points - s * z_points, s * y_points + c * z_points
    return y_points + shift, z_points + r0 + lift
