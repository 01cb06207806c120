"""Element matrices: Timoshenko beam and axial bar of polynomial order p, Winkler layers.

Beam: deflection w and cross-section rotation psi are interpolated independently with
Lagrange polynomials of order p on p + 1 equally spaced element nodes (DOFs per node
(w, psi), node-major order), shear strain gamma = w' - psi::

    U = 1/2 int EI psi'^2 + kGA (w' - psi)^2 dx      -> K   (kGA = kappa G A)
    T = 1/2 int rhoA wdot^2 + rhoI psidot^2 dx       -> M   (with rotary inertia)
    W = 1/2 int s w^2 dx                             -> foundation (s in N/m^2, or N s/m^2)

integrated exactly by (p + 2)-point Gauss-Legendre quadrature. Why order p = 4 by
default: the two-node "interdependent interpolation" element (Friedman & Kosmatka 1993)
converges only as h^2 in frequency for a rail with kappa = 0.4, because its element
shear parameter 12 EI / (kGA h^2) is ~30 at h = 0.1 m: 6 elements per 0.6 m bay put the
pinned-pinned frequency 0.44% high, as much as the half-power width of that resonance
with a rail loss factor of 0.01, so the peak height would depend on the mesh. Quartic
elements, two per bay (the same number of DOFs as 8 two-node elements), put it 2e-6
high and the second pinned-pinned mode (~2 kHz lateral) 2e-4 high; shear locking is
negligible at this order and these element aspect ratios.

Bar (the sleeper's axial motion along y, for the lateral model): axial displacement u
of order p, U = 1/2 int EA u'^2, T = 1/2 int rhoA udot^2, foundation 1/2 int s u^2.

Every function is vectorised over n elements: arrays of shape (n,) in, (n, m, m) out.
"""

from __future__ import annotations

from functools import cache

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "lagrange_shape_functions",
    "gauss_points",
    "beam_stiffness",
    "beam_mass",
    "beam_foundation",
    "bar_stiffness",
    "bar_mass",
]


def lagrange_shape_functions(p: int, xi: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Lagrange polynomials of order p on nodes 0, 1/p, ..., 1 and their d/dxi.

    Parameters
    ----------
    p : int
        Polynomial order (>= 1).
    xi : array_like, shape (m,)
        Positions in [0, 1].

    Returns
    -------
    N, dN : ndarray, shape (m, p + 1)
        Shape function values and their derivatives with respect to xi, per position.
    """
    xi = np.atleast_1d(np.asarray(xi, float))
    nodes = np.linspace(0.0, 1.0, p + 1)
    N = np.ones((len(xi), p + 1))
    dN = np.zeros((len(xi), p + 1))
    for i in range(p + 1):
        others = [j for j in range(p + 1) if j != i]
        for j in others:
            N[:, i] *= (xi - nodes[j]) / (nodes[i] - nodes[j])
        for k in others:
            term = np.full(len(xi), 1.0 / (nodes[i] - nodes[k]))
            for j in others:
                if j != k:
                    term *= (xi - nodes[j]) / (nodes[i] - nodes[j])
            dN[:, i] += term
    return N, dN


@cache
def _rule(p: int):
    """Gauss points and weights on [0, 1] and the shape functions there."""
    g, w = np.polynomial.legendre.leggauss(p + 2)
    g, w = 0.5 * (g + 1.0), 0.5 * w
    N, dN = lagrange_shape_functions(p, g)
    return w, N, dN


def _beam_operators(p: int):
    """Per Gauss point, the rows mapping element DOFs to w, psi, dw/dxi, dpsi/dxi."""
    w, N, dN = _rule(p)
    zero = np.zeros_like(N)

    def interleave(w_part: np.ndarray, psi_part: np.ndarray) -> np.ndarray:
        """Rows over the element DOFs in node-major order (w, psi per node)."""
        return np.stack([w_part, psi_part], axis=-1).reshape(len(w), -1)

    return (
        w,
        interleave(N, zero),
        interleave(zero, N),
        interleave(dN, zero),
        interleave(zero, dN),
    )


def gauss_points(p: int) -> np.ndarray:
    """Quadrature points of order-p elements, where per-point coefficients are evaluated.

    Coefficients given per point (shape (n, p + 2)) are evaluated there: a section varying
    along x is then integrated as exactly as the quadrature allows, not held constant per
    element.

    Parameters
    ----------
    p : int
        Element order; the rule has p + 2 Gauss-Legendre points.

    Returns
    -------
    numpy.ndarray
        The p + 2 points, xi in [0, 1] along the element.
    """
    return 0.5 * (np.polynomial.legendre.leggauss(p + 2)[0] + 1.0)


def _per_point(p: int, L: np.ndarray, coef) -> np.ndarray:
    """A coefficient (scalar, (n,) or (n, p + 2)) as an array (n, p + 2)."""
    values = np.asarray(coef, float)
    return np.broadcast_to(values[:, None] if values.ndim == 1 else values, (len(L), p + 2))


def _integrate(p: int, L, coef, A, B) -> np.ndarray:
    """int coef A^T B dx over each element of length L (A, B per point and DOF)."""
    L = np.atleast_1d(np.asarray(L, float))
    return np.einsum("g,ng,gi,gj->nij", _rule(p)[0], _per_point(p, L, coef) * L[:, None], A, B)


def beam_stiffness(p: int, L: ArrayLike, EI: ArrayLike, kGA: ArrayLike) -> np.ndarray:
    """Timoshenko beam stiffness matrices, shape (n, 2(p+1), 2(p+1)).

    Parameters
    ----------
    p : int
        Element order.
    L : array_like, shape (n,)
        Element lengths (m).
    EI, kGA : array_like, shape (n,) or (n, p + 2)
        Bending stiffness (N m^2) and shear stiffness kappa G A (N), per element or at the
        points of :func:`gauss_points`.

    Returns
    -------
    numpy.ndarray
        Element stiffness matrices (N/m, N, N m), DOFs (w, psi) node-major.
    """
    L = np.atleast_1d(np.asarray(L, float))
    _, _, Psi, dW, dPsi = _beam_operators(p)  # d/dx = (d/dxi) / L
    EI, kGA, invL = _per_point(p, L, EI), _per_point(p, L, kGA), (1.0 / L)[:, None]
    bend = _integrate(p, L, EI * invL**2, dPsi, dPsi)
    w_w = _integrate(p, L, kGA * invL**2, dW, dW)
    w_psi = _integrate(p, L, kGA * invL, dW, Psi)
    return bend + w_w - w_psi - np.swapaxes(w_psi, 1, 2) + _integrate(p, L, kGA, Psi, Psi)


def beam_mass(p: int, L: ArrayLike, rhoA: ArrayLike, rhoI: ArrayLike) -> np.ndarray:
    """Consistent mass matrices of the Timoshenko beam, with rotary inertia.

    Parameters
    ----------
    p : int
        Element order.
    L : array_like, shape (n,)
        Element lengths (m).
    rhoA, rhoI : array_like, shape (n,) or (n, p + 2)
        Mass (kg/m) and rotary inertia (kg m) per unit length, per element or at the
        points of :func:`gauss_points`.

    Returns
    -------
    numpy.ndarray
        Element mass matrices, shape (n, 2(p+1), 2(p+1)).
    """
    _, W, Psi, _, _ = _beam_operators(p)
    return _integrate(p, L, rhoA, W, W) + _integrate(p, L, rhoI, Psi, Psi)


def beam_foundation(p: int, L: ArrayLike, s: ArrayLike) -> np.ndarray:
    """Matrix of a Winkler layer under the beam, acting on the deflection w only.

    Parameters
    ----------
    p : int
        Element order.
    L : array_like, shape (n,)
        Element lengths (m).
    s : array_like, shape (n,) or (n, p + 2)
        Layer stiffness (N/m^2) or damping (N s/m^2) per unit length.

    Returns
    -------
    numpy.ndarray
        Element matrices, shape (n, 2(p+1), 2(p+1)), DOFs (w, psi) node-major.
    """
    _, W, _, _, _ = _beam_operators(p)
    return _integrate(p, L, s, W, W)


def bar_stiffness(p: int, L: ArrayLike, EA: ArrayLike) -> np.ndarray:
    """Axial bar stiffness matrices int EA u'^2.

    Parameters
    ----------
    p : int
        Element order.
    L : array_like, shape (n,)
        Element lengths (m).
    EA : array_like, shape (n,)
        Axial stiffness (N).

    Returns
    -------
    numpy.ndarray
        Element stiffness matrices (N/m), shape (n, p+1, p+1).
    """
    L = np.atleast_1d(np.asarray(L, float))
    _, _, dN = _rule(p)
    return _integrate(p, L, np.asarray(EA, float) / L**2, dN, dN)


def bar_mass(p: int, L: ArrayLike, q: ArrayLike) -> np.ndarray:
    """Bar matrix int q u^2 for a line density q: rhoA (kg/m) or a foundation s (N/m^2).

    Parameters
    ----------
    p : int
        Element order.
    L : array_like, shape (n,)
        Element lengths (m).
    q : array_like, shape (n,) or (n, p + 2)
        Line density: mass (kg/m), stiffness (N/m^2) or damping (N s/m^2) per unit length.

    Returns
    -------
    numpy.ndarray
        Element matrices, shape (n, p+1, p+1), in the unit of q times m.
    """
    _, N, _ = _rule(p)
    return _integrate(p, L, q, N, N)
