"""Hertz normal contact of two bodies from their principal curvatures.

Ellipse: exact Hertz theory with complete elliptic integrals (``scipy.special.ellipk``,
``ellipe``; no Greenwood or Hamrock-Brewe approximation).  With the relative curvatures
``A`` (rolling direction) and ``B`` (lateral) of the gap ``h = A x^2 + B y^2`` and
``e^2 = 1 - (b/a)^2`` for the semi-axes a >= b (a along the direction of the smaller
curvature sum ``A_min``), Johnson, *Contact Mechanics* (1985), Eqs 4.39-4.41 give

    B_max / A_min = (E(e) / (1 - e^2) - K(e)) / (K(e) - E(e)),
    a^2 = delta (K - E) / (A_min e^2 K),     b = a sqrt(1 - e^2),
    F = (2 pi / 3) a E* delta / K,

so that ``F = C_H delta^1.5`` with

    C_H = (2 pi E* / (3 K)) sqrt((K - E) / (A_min e^2 K)),

``1 / E* = (1 - nu_1^2) / E_1 + (1 - nu_2^2) / E_2``.  For a sphere of radius R on a plane
(A = B = 1 / (2R)) this is Hertz's ``(4/3) E* sqrt(R)``.  Conformal points (B <= 0, e.g.
flange root on the gauge corner) are outside Hertz theory; :func:`curvature_sums` floors
both sums at a small positive value and says so.  Where a floor bites, or the ellipse is
wider than the surfaces (a flat flange back on a check-rail face), the contact tables use
the semi-Hertzian method of :mod:`.nonhertz` instead.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import ellipe, ellipk

__all__ = [
    "HertzContact",
    "effective_modulus",
    "curvature_sums",
    "ellipse_parameter",
    "hertz_constant",
    "hertz_contact",
]

#: 1/m, smallest relative lateral curvature used (a 1 km radius: conformal contact floor)
MIN_CURVATURE_SUM = 5e-4


@dataclass(frozen=True, eq=False)
class HertzContact:
    """Hertz ellipse of one or several contacts (arrays broadcast like the inputs)."""

    a: np.ndarray  #: m, semi-axis in the rolling direction
    b: np.ndarray  #: m, semi-axis in the lateral direction
    p0: np.ndarray  #: Pa, peak pressure
    constant: np.ndarray  #: N/m^1.5, C_H of F = C_H delta^1.5


def effective_modulus(
    young: float = 2.1e11,
    poisson: float = 0.3,
    young_2: float | None = None,
    poisson_2: float | None = None,
) -> float:
    """Contact modulus E* of two elastic bodies.

    Parameters
    ----------
    young, poisson : float
        Pa, -, body 1 (default steel: 210 GPa, 0.3).
    young_2, poisson_2 : float, optional
        Body 2 (default: same as body 1).

    Returns
    -------
    float
        Pa, ``1 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2)``.
    """
    young_2 = young if young_2 is None else young_2
    poisson_2 = poisson if poisson_2 is None else poisson_2
    return 1.0 / ((1.0 - poisson**2) / young + (1.0 - poisson_2**2) / young_2)


def curvature_sums(radius, angle, curvature_wheel, curvature_rail, rail_longitudinal_curvature=0.0):
    """Relative curvatures A (rolling) and B (lateral) of a wheel/rail contact point.

    Parameters
    ----------
    radius : array_like
        m, wheel rolling radius at the contact point.
    angle : array_like
        rad, contact angle (the wheel's curvature along the rolling direction, normal to the
        contact plane, is ``cos(angle) / radius``; Meusnier).
    curvature_wheel, curvature_rail : array_like
        1/m, lateral profile curvatures, positive convex towards the other body.
    rail_longitudinal_curvature : array_like
        1/m, rail curvature along x (0 for straight rail).

    Returns
    -------
    A, B : numpy.ndarray
        1/m, half the curvature sums, floored at ``MIN_CURVATURE_SUM`` (a flat wheel face
        against a check rail has A = 0; conformal points B <= 0).
    """
    a_sum = np.maximum(
        0.5 * (np.cos(angle) / np.asarray(radius, float) + rail_longitudinal_curvature),
        MIN_CURVATURE_SUM,
    )
    b_sum = 0.5 * (np.asarray(curvature_wheel, float) + np.asarray(curvature_rail, float))
    return a_sum, np.maximum(np.nan_to_num(b_sum, nan=MIN_CURVATURE_SUM), MIN_CURVATURE_SUM)


def ellipse_parameter(ratio) -> np.ndarray:
    """Elliptic parameter m = e^2 of the Hertz ellipse for a curvature ratio B_max / A_min.

    Parameters
    ----------
    ratio : array_like
        Ratio of the larger to the smaller relative curvature (>= 1).

    Returns
    -------
    numpy.ndarray
        m = 1 - (b/a)^2, solved by bisection to 1e-13.
    """
    ratio = np.maximum(np.asarray(ratio, float), 1.0)
    low = np.zeros_like(ratio)
    high = np.full_like(ratio, 1.0 - 1e-14)
    for _ in range(60):
        mid = 0.5 * (low + high)
        k, e = ellipk(mid), ellipe(mid)
        with np.errstate(divide="ignore", invalid="ignore"):
            value = (e / (1.0 - mid) - k) / (k - e)
        value = np.where(mid < 1e-12, 1.0, value)
        above = value > ratio
        high = np.where(above, mid, high)
        low = np.where(above, low, mid)
    return 0.5 * (low + high)


def _shape_factors(a_sum, b_sum):
    a_sum = np.asarray(a_sum, float)
    b_sum = np.asarray(b_sum, float)
    small = np.minimum(a_sum, b_sum)
    m = ellipse_parameter(np.maximum(a_sum, b_sum) / small)
    k, e = ellipk(m), ellipe(m)
    with np.errstate(divide="ignore", invalid="ignore"):
        ke = np.where(m > 1e-10, (k - e) / m, np.pi / 4.0)
    return small, m, k, ke


def hertz_constant(a_sum, b_sum, modulus: float) -> np.ndarray:
    """Hertz constant C_H of ``F = C_H delta^1.5``.

    Parameters
    ----------
    a_sum, b_sum : array_like
        1/m, relative curvatures (see :func:`curvature_sums`).
    modulus : float
        Pa, contact modulus E* (:func:`effective_modulus`).

    Returns
    -------
    numpy.ndarray
        N/m^1.5.
    """
    small, _m, k, ke = _shape_factors(a_sum, b_sum)
    return 2.0 * np.pi * modulus / (3.0 * k) * np.sqrt(ke / (small * k))


def hertz_contact(a_sum, b_sum, force, modulus: float) -> HertzContact:
    """Hertz ellipse for a normal force.

    Parameters
    ----------
    a_sum, b_sum : array_like
        1/m, relative curvatures in rolling and lateral direction.
    force : array_like
        N, normal force (> 0).
    modulus : float
        Pa, contact modulus E*.

    Returns
    -------
    HertzContact
        Semi-axes in rolling (a) and lateral (b) direction, peak pressure, C_H.
    """
    a_sum = np.asarray(a_sum, float)
    b_sum = np.asarray(b_sum, float)
    small, m, k, ke = _shape_factors(a_sum, b_sum)
    constant = 2.0 * np.pi * modulus / (3.0 * k) * np.sqrt(ke / (small * k))
    delta = (np.asarray(force, float) / constant) ** (2.0 / 3.0)
    major = np.sqrt(delta * ke / (small * k))
    minor = major * np.sqrt(1.0 - m)
    rolling_is_major = a_sum <= b_sum
    a = np.where(rolling_is_major, major, minor)
    b = np.where(rolling_is_major, minor, major)
    p0 = 1.5 * np.asarray(force, float) / (np.pi * major * minor)
    return HertzContact(a=a, b=b, p0=p0, constant=constant)
