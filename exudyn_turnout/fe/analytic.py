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

Infinite rail in coupled lateral bending and torsion on a continuous support
----------------------------------------------------------------------------
The independent check of the torsion-aware lateral FE (:mod:`exudyn_turnout.fe.torsion`).
Fields u = (v, psi, phi, theta): lateral displacement of the shear centre, bending
rotation (Timoshenko), roll, warping variable. Energy per unit length (harmonic, complex
stiffnesses carry the losses)::

    U = 1/2 [EI psi'^2 + kGA (v' - psi)^2 + GJ phi'^2 + ECw theta'^2 + kw (phi' - theta)^2
             + s_y (v + d phi)^2 + k_phi phi^2]
    T = 1/2 [rhoA (v - e_c phi)^2 + rhoI psi^2 + rhoIp_c phi^2 + rhoCw theta^2] (rates)

s_y(omega) the lateral two-layer support per unit length at the rail foot (d below the
shear centre), k_phi the pads' roll stiffness per unit length, e_c the centroid above the
shear centre. Written as U = 1/2 (u'^T A2 u' + 2 u'^T A1 u + u^T A0 u), the Euler-Lagrange
equations with a load f delta(x) are::

    A2 u'' + (A1 - A1^T) u' - (A0 - omega^2 M) u = -f delta(x)                (6)

Modes u = phi_j e^{lambda_j x} solve the quadratic eigenproblem
(lambda^2 A2 + lambda (A1 - A1^T) - (A0 - omega^2 M)) phi = 0, linearised to 2n x 2n.
For x > 0 the n modes with Re(lambda) < 0 (decaying, or outgoing with damping), for
x < 0 the n with Re(lambda) > 0; at x = 0 the displacements are continuous and (6)
integrated across it gives the jump A2 (u'(0+) - u'(0-)) = -f: 2n equations for the 2n
amplitudes. The receptance is g^T u(0) for a response vector g (for a lateral force at
height z above the shear centre, f = g = (1, 0, -z, 0)). Without warping the fields are
(v, psi, phi). This is the residue evaluation of the wavenumber integral
(1 / 2 pi) int g^T Z(k)^-1 f dk, done by the ODE's modes.
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
    "infinite_point_response",
    "infinite_rail_lateral_torsion_receptance",
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


def infinite_point_response(
    A2: np.ndarray, A1: np.ndarray, A0: np.ndarray, f: np.ndarray
) -> np.ndarray:
    """u(0) of an infinite uniform 1-D system loaded by f delta(x), Eq (6) of the docstring.

    Parameters
    ----------
    A2, A1 : numpy.ndarray
        (n, n) coefficient matrices of u'^T A2 u' and 2 u'^T A1 u in the energy (complex
        for losses); A2 invertible.
    A0 : numpy.ndarray
        (n, n) coefficient of u^T A0 u minus omega^2 times the mass matrix (the dynamic
        stiffness without derivatives).
    f : numpy.ndarray
        (n,) load amplitudes.

    Returns
    -------
    numpy.ndarray
        (n,) complex displacements at x = 0.

    Raises
    ------
    ValueError
        The modes do not split n / n between decaying on either side (no damping and
        a mode exactly on the imaginary axis).
    """
    n = len(f)
    A2inv = np.linalg.inv(A2)
    L = np.zeros((2 * n, 2 * n), complex)
    L[:n, n:] = np.eye(n)
    L[n:, :n] = A2inv @ A0
    L[n:, n:] = -A2inv @ (A1 - A1.T)
    lam, W = np.linalg.eig(L)
    right, left = lam.real < 0, lam.real > 0
    if right.sum() != n or left.sum() != n:
        raise ValueError("modes do not split into decaying ones on both sides (add damping)")
    Phi_r, Phi_l = W[:n, right], W[:n, left]
    system = np.block([[Phi_r, -Phi_l], [A2 @ (Phi_r * lam[right]), -A2 @ (Phi_l * lam[left])]])
    amplitudes = np.linalg.solve(system, np.concatenate([np.zeros(n), -np.asarray(f, complex)]))
    return Phi_r @ amplitudes[:n]


def infinite_rail_lateral_torsion_receptance(
    omega: ArrayLike,
    EI: float,
    kGA: float,
    rhoA: float,
    rhoI: float,
    GJ: float,
    ECw: float,
    kappa_w: float,
    rhoIp: float,
    e_c: float,
    s_y: ArrayLike,
    d: float,
    k_phi: ArrayLike,
    z: float,
    eta: float = 0.0,
    rhoCw: float = 0.0,
) -> np.ndarray:
    """Lateral point receptance at height z above the shear centre, coupled bending-torsion.

    See the module docstring (infinite rail in coupled lateral bending and torsion).

    Parameters
    ----------
    omega : array_like
        Circular frequency (rad/s).
    EI, kGA, rhoA, rhoI : float
        Lateral bending stiffness (N m^2), shear stiffness (N), mass (kg/m), rotary
        inertia (kg m) per unit length.
    GJ : float
        St Venant torsional stiffness (N m^2).
    ECw : float
        Warping stiffness (N m^4); 0: no warping (fields v, psi, phi).
    kappa_w : float
        Penalty on phi' - theta (N m^2), unused without warping.
    rhoIp : float
        Roll inertia about the centroid per unit length, rho I_p,c (kg m).
    e_c : float
        Height of the centroid above the shear centre (m).
    s_y : array_like
        Complex lateral support stiffness per unit length at the foot (N/m^2), per omega.
    d : float
        Depth of the lateral support (rail foot) below the shear centre (m).
    k_phi : array_like
        Complex roll support stiffness per unit length (N m/rad/m), per omega.
    z : float
        Height of the lateral load and response above the shear centre (m).
    eta : float
        Rail loss factor: the rail's stiffnesses are multiplied by (1 + i eta).
    rhoCw : float
        Warping inertia rho C_w (kg m^3), with warping.

    Returns
    -------
    numpy.ndarray
        Complex receptance (m/N), one value per omega.
    """
    omega = np.atleast_1d(np.asarray(omega, float))
    s_y = np.broadcast_to(np.asarray(s_y, complex), omega.shape)
    k_phi = np.broadcast_to(np.asarray(k_phi, complex), omega.shape)
    warping = ECw > 0
    n = 4 if warping else 3
    c = 1.0 + 1j * eta
    A2 = np.zeros((n, n), complex)
    A1 = np.zeros((n, n), complex)
    A0r = np.zeros((n, n), complex)  # rail part of A0
    M = np.zeros((n, n))
    A2[0, 0], A2[1, 1], A1[0, 1], A0r[1, 1] = c * kGA, c * EI, -c * kGA, c * kGA
    A2[2, 2] = c * GJ
    if warping:
        A2[2, 2] += c * kappa_w
        A2[3, 3], A1[2, 3], A0r[3, 3] = c * ECw, -c * kappa_w, c * kappa_w
        M[3, 3] = rhoCw
    M[0, 0], M[1, 1], M[2, 2] = rhoA, rhoI, rhoIp + rhoA * e_c**2
    M[0, 2] = M[2, 0] = -rhoA * e_c
    g = np.zeros(n)
    g[0], g[2] = 1.0, -z
    out = np.empty(omega.shape, complex)
    for i, w in enumerate(omega):
        A0 = A0r - w**2 * M
        A0[0, 0] += s_y[i]
        A0[0, 2] += s_y[i] * d
        A0[2, 0] += s_y[i] * d
        A0[2, 2] += s_y[i] * d**2 + k_phi[i]
        out[i] = g @ infinite_point_response(A2, A1, A0, g)
    return out
