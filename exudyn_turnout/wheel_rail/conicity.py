"""Characteristics of a wheelset's contact geometry: equivalent conicity, flange angle, Nadal.

EN 15302's equivalent conicity from a rolling-radius difference function Delta r(y)
(from :func:`.geometry.solve_wheelset`), by linear regression over a sinusoid
(:func:`equivalent_conicity`) or by integrating the kinematic motion
(:func:`equivalent_conicity_klingel`); a wheel's flange angle and Nadal's flange-climb limit.
"""

from __future__ import annotations

import math

import numpy as np

from exudyn_turnout.wheel_rail.profile_grid import WheelGrid

__all__ = ["equivalent_conicity", "equivalent_conicity_klingel", "flange_angle", "nadal_limit"]


def equivalent_conicity(
    y: np.ndarray, delta_r: np.ndarray, amplitude: float, samples: int = 2000
) -> float:
    """Equivalent conicity by EN 15302's linear regression of the Delta r function.

    The wheelset moves sinusoidally, ``y = amplitude sin(theta)``, sampled uniformly in time
    over one period; the regression line of Delta r on y through the origin has slope
    ``2 gamma_e`` (EN 15302:2008+A1:2010, Annex C; for a sinusoid this is the first-harmonic
    (describing-function) linearisation).

    Parameters
    ----------
    y : numpy.ndarray
        m, lateral displacements where Delta r is known (increasing, covering +-amplitude).
    delta_r : numpy.ndarray
        m, rolling-radius difference r_left - r_right at ``y``.
    amplitude : float
        m, amplitude of the wheelset's lateral motion (3 mm for EN 15302's reference value).
    samples : int
        Samples over one period.

    Returns
    -------
    float
        Equivalent conicity gamma_e (-).

    Notes
    -----
    The regression line passes through the origin, so ``delta_r`` must be odd in ``y``
    (symmetric wheelset and track).  Where the amplitude just reaches a jump of Delta r
    (contact moving to the flange root) the regression overestimates the conicity of the
    kinematic motion: on EN 15302's reference function E2 (Annex E) it gives 0.090 at 3 mm
    against the reference 0.058, and on E4 0.372 at 2 mm against 0.293, outside the
    standard's tolerance band.  :func:`equivalent_conicity_klingel` reproduces all nine
    reference functions; for S1002 on UIC60 1:40 (1435 / 1360 mm) the two agree to 0.002
    at 3 mm.
    """
    theta = 2.0 * np.pi * (np.arange(samples) + 0.5) / samples
    motion = amplitude * np.sin(theta)
    dr = np.interp(motion, y, delta_r)
    return float(np.sum(dr * motion) / (2.0 * np.sum(motion * motion)))


def equivalent_conicity_klingel(
    y: np.ndarray, delta_r: np.ndarray, amplitude: float, samples: int = 2000, refine: int = 20
) -> float:
    """Equivalent conicity from the wavelength of the kinematic motion (EN 15302, Annex B).

    The wheelset's kinematic (Klingel) motion obeys ``y'' = -Delta r(y) / (2 e r0)``; its
    energy integral gives the yaw angle ``psi(y)^2 = F(y) / (e r0)`` with
    ``F(y) = integral from y to y_max of Delta r``, and the wavelength is
    ``lambda = 2 integral from y_min to y_max of dy / psi``.  The equivalent conicity is the
    cone with Klingel's wavelength ``2 pi sqrt(e r0 / gamma_e)``, so
    ``gamma_e = (pi / integral dy / sqrt(F))^2``, independent of ``e`` and ``r0``.  The
    turning points are ``y_min, y_max = c -+ amplitude``, the centre ``c`` chosen so that
    the integral of Delta r between them vanishes (``c = 0`` for an odd Delta r; not zero
    for unequal wheel radii).  The substitution ``y = c - amplitude cos(theta)`` removes the
    square-root singularities at the turning points.

    Parameters
    ----------
    y : numpy.ndarray
        Lateral displacements where Delta r is known (increasing; any length unit).
    delta_r : numpy.ndarray
        Rolling-radius difference r_left - r_right at ``y`` (same unit), increasing through
        zero over the motion.
    amplitude : float
        Half the peak-to-peak lateral motion (same unit; 3 mm for EN 15302's value).
    samples : int
        Midpoint samples in ``theta`` over the half period.
    refine : int
        Sub-intervals per interval of ``y`` for the running integral of Delta r (linear
        interpolation between the given points, as for :func:`equivalent_conicity`).

    Returns
    -------
    float
        Equivalent conicity gamma_e (-).

    Raises
    ------
    ValueError
        If the motion does not fit into ``y`` or Delta r does not change sign over it.

    Notes
    -----
    Checked against the nine reference Delta r functions of EN 15302:2008+A1:2010, Annex E
    and their reference conicities (amplitudes 1-6 mm every 0.1 mm, where the motion fits
    the tabulated range): within 0.001 for eight cases, 0.007 for E5 (unequal wheel radii,
    at 1-2 mm).
    """
    y = np.asarray(y, float)
    delta_r = np.asarray(delta_r, float)
    fine = np.linspace(y[0], y[-1], refine * (len(y) - 1) + 1)
    values = np.interp(fine, y, delta_r)
    running = np.concatenate(([0.0], np.cumsum(0.5 * (values[1:] + values[:-1]) * np.diff(fine))))

    def window(centre: float) -> float:
        return float(
            np.interp(centre + amplitude, fine, running)
            - np.interp(centre - amplitude, fine, running)
        )

    low, high = y[0] + amplitude, y[-1] - amplitude
    if not low < high or not window(low) < 0.0 < window(high):
        raise ValueError(
            f"a motion of amplitude {amplitude} does not fit into y = "
            f"[{y[0]}, {y[-1]}] with Delta r changing sign over it"
        )
    for _ in range(100):  # bisection: the window integral increases with the centre
        middle = 0.5 * (low + high)
        if window(middle) < 0.0:
            low = middle
        else:
            high = middle
    centre = 0.5 * (low + high)
    theta = np.pi * (np.arange(samples) + 0.5) / samples
    position = centre - amplitude * np.cos(theta)
    remaining = np.interp(centre + amplitude, fine, running) - np.interp(position, fine, running)
    integral = np.sum(amplitude * np.sin(theta) / np.sqrt(np.maximum(remaining, 1e-300)))
    integral *= np.pi / samples
    return float((np.pi / integral) ** 2)


def flange_angle(wheel: WheelGrid, s_range: tuple = (-0.065, -0.020)) -> float:
    """Largest contact angle on the flange flank of a wheel (the flange angle).

    Parameters
    ----------
    wheel : WheelGrid
        Gridded wheel.
    s_range : tuple
        m, lateral range of the flange flank (S1002: the flank lies between the flange tip,
        about 55 mm, and the flange root, about 25 mm, on the gauge side of the taping line).

    Returns
    -------
    float
        rad, ``max atan(-dz/ds)``... expressed as a positive angle of the flank to the
        horizontal.
    """
    inside = (wheel.s >= s_range[0]) & (wheel.s <= s_range[1]) & np.isfinite(wheel.slope)
    return float(np.max(np.arctan(wheel.slope[inside])))


def nadal_limit(flange_angle_rad: float, friction: float) -> float:
    """Nadal's flange-climb limit Y/Q = (tan g - mu) / (1 + mu tan g).

    Parameters
    ----------
    flange_angle_rad : float
        rad, flange angle g.
    friction : float
        Friction coefficient mu at the flange.

    Returns
    -------
    float
        Limit ratio of lateral to vertical wheel force.
    """
    t = math.tan(flange_angle_rad)
    return (t - friction) / (1.0 + friction * t)
