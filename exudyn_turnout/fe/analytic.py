"""Closed-form references for the FE model: Timoshenko beam on a continuous support.

Infinite Timoshenko beam on a continuous two-layer support
----------------------------------------------------------
(cf. D. Thompson, *Railway Noise and Vibration*, Elsevier 2009, sections 3.3-3.4; the
Timoshenko beam on a Winkler foundation of K. F. Graff, *Wave Motion in Elastic Solids*.)

Rail: bending stiffness EI, shear stiffness kGA = kappa G A, mass rhoA, rotary inertia
rhoI per unit length. Support per unit length, harmonic e^{i omega t}: pad layer
k_p' = (k_p + i omega c_p) / L_s, sleeper mass m_s' = m_s / L_s, ballast layer
k_b' = (k_b + i omega c_b) / L_s. The sleeper layer u(x) is not coupled along x, so its
equation k_p' (u - w) + (k_b' - omega^2 m_s') u = 0 eliminates it pointwise and the rail
sees a Winkler foundation of complex stiffness per unit length::

    s(omega) = k_p' (k_b' - omega^2 m_s') / (k_p' + k_b' - omega^2 m_s')      (1)

Timoshenko equations with a unit point force F at x = 0 (w and F positive upwards)::

    kGA (w'' - psi') + (rhoA omega^2 - s) w = -F delta(x)                      (2)
    EI psi'' + kGA (w' - psi) + rhoI omega^2 psi = 0                           (3)

With w, psi ~ e^{lambda x} the determinant of (2, 3) gives a quadratic in mu = lambda^2::

    kGA EI mu^2 + [kGA rhoI omega^2 + EI (rhoA omega^2 - s)] mu
        + (rhoA omega^2 - s)(rhoI omega^2 - kGA) = 0                           (4)

For x > 0 the two roots lambda_j = -sqrt(mu_j) with Re(lambda_j) < 0 (decaying or
outgoing; damping makes the choice unique) give w = A1 e^{l1 x} + A2 e^{l2 x},
psi = r1 A1 e^{l1 x} + r2 A2 e^{l2 x} with r_j = (kGA l_j^2 + rhoA omega^2 - s)/(kGA l_j).
Symmetry (w even, psi odd) and the force balance at x = 0+ give::

    psi(0) = r1 A1 + r2 A2 = 0,   kGA (w'(0) - psi(0)) = kGA [(l1 - r1) A1 + (l2 - r2) A2] = -F/2

and the point receptance H = w(0) / F = (A1 + A2) / F. At omega = 0 with kGA -> infinity
it reduces to Eq 2 of the paper, H = 1 / (2 sqrt 2 EI^{1/4} s^{3/4}).

Simply supported Timoshenko beam (pinned-pinned mode)
-----------------------------------------------------
w = W sin(k x), psi = Psi cos(k x), k = n pi / L satisfy the pinned end conditions
(w = 0, M = EI psi' = 0); (2, 3) without support give::

    (rhoA omega^2 - kGA k^2)(rhoI omega^2 - EI k^2 - kGA) + (kGA k)^2 = 0      (5)

a quadratic in omega^2 whose lower root is the flexural frequency (Timoshenko 1921).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "two_layer_support",
    "infinite_timoshenko_receptance",
    "simply_supported_timoshenko_frequency",
    "simply_supported_euler_frequency",
]


def two_layer_support(
    omega: ArrayLike, k_p: float, c_p: float, m_s: float, k_b: float, c_b: float, L_s: float
) -> np.ndarray:
    """Complex support stiffness per unit length s(omega) of Eq (1) (N/m^2).

    Parameters
    ----------
    omega : array_like
        Circular frequency (rad/s).
    k_p, c_p : float
        Pad stiffness (N/m) and damping (N s/m) per support.
    m_s : float
        Sleeper mass per rail and support (kg).
    k_b, c_b : float
        Ballast stiffness (N/m) and damping (N s/m) per rail and support.
    L_s : float
        Support spacing (m).

    Returns
    -------
    numpy.ndarray
        Complex s(omega) (N/m^2), one value per frequency.
    """
    omega = np.asarray(omega, float)
    kp = (k_p + 1j * omega * c_p) / L_s
    kb = (k_b + 1j * omega * c_b) / L_s - omega**2 * m_s / L_s
    return kp * kb / (kp + kb)


def infinite_timoshenko_receptance(
    omega: ArrayLike, EI: float, kGA: float, rhoA: float, rhoI: float, s: ArrayLike
) -> np.ndarray:
    """Point receptance (m/N) of an infinite Timoshenko beam on a Winkler support s.

    Parameters
    ----------
    omega : array_like
        Circular frequency (rad/s); 0 gives the static compliance.
    EI, kGA, rhoA, rhoI : float
        Bending stiffness (N m^2), shear stiffness kappa G A (N), mass (kg/m) and rotary
        inertia (kg m) per unit length.
    s : array_like
        Complex support stiffness per unit length (N/m^2), e.g. :func:`two_layer_support`.

    Returns
    -------
    ndarray
        Complex H(omega) (see the module docstring for the derivation).
    """
    omega, s = np.broadcast_arrays(np.asarray(omega, float), np.asarray(s, complex))
    p = rhoA * omega**2 - s
    a = kGA * EI
    b = kGA * rhoI * omega**2 + EI * p
    c = p * (rhoI * omega**2 - kGA)
    disc = np.sqrt(b * b - 4 * a * c + 0j)
    mu = np.stack([(-b + disc) / (2 * a), (-b - disc) / (2 * a)])
    lam = np.sqrt(mu + 0j)
    lam = np.where(lam.real > 0, -lam, lam)  # the root decaying (outgoing) for x > 0
    r = (kGA * lam**2 + p) / (kGA * lam)
    (l1, l2), (r1, r2) = lam, r
    A1 = -1.0 / (2.0 * kGA * ((l1 - r1) - (l2 - r2) * r1 / r2))
    return A1 * (1.0 - r1 / r2)


def simply_supported_timoshenko_frequency(
    L: float, EI: float, kGA: float, rhoA: float, rhoI: float, n: int = 1
) -> float:
    """Flexural eigenfrequency of mode n of a simply supported Timoshenko beam, Eq (5).

    Parameters
    ----------
    L : float
        Span between the pinned supports (m).
    EI : float
        Bending stiffness (N m^2).
    kGA : float
        Shear stiffness kappa G A (N).
    rhoA : float
        Mass per unit length (kg/m).
    rhoI : float
        Rotary inertia per unit length (kg m).
    n : int
        Mode number (half-waves over the span).

    Returns
    -------
    float
        The lower (flexural) root of Eq (5), in Hz.
    """
    k = n * math.pi / L
    a = rhoA * rhoI
    b = -(rhoA * (EI * k**2 + kGA) + rhoI * kGA * k**2)
    c = kGA * k**2 * (EI * k**2 + kGA) - (kGA * k) ** 2
    q = -0.5 * (b - math.sqrt(b * b - 4 * a * c))  # b < 0: no cancellation (rhoI -> 0 too)
    w2 = c / q  # the lower root, flexural; q / a is the thickness-shear one
    return math.sqrt(w2) / (2 * math.pi)


def simply_supported_euler_frequency(L: float, EI: float, rhoA: float, n: int = 1) -> float:
    """Euler-Bernoulli counterpart of Eq (5): (n pi / L)^2 sqrt(EI / rhoA) / (2 pi).

    Parameters
    ----------
    L : float
        Span between the pinned supports (m).
    EI : float
        Bending stiffness (N m^2).
    rhoA : float
        Mass per unit length (kg/m).
    n : int
        Mode number (half-waves over the span).

    Returns
    -------
    float
        Eigenfrequency of mode n (Hz).
    """
    return (n * math.pi / L) ** 2 * math.sqrt(EI / rhoA) / (2 * math.pi)
