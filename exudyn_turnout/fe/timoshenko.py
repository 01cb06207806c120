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

__all__ = [
    "lagrange_shape_functions",
    "gauss_points",
    "beam_stiffness",
    "beam_mass",
    "beam_foundation",
    "bar_stiffness",
    "bar_mass",
]


def lagrange_shape_functions(p: int, xi) -> tuple[np.ndarray, np.ndarray]:
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
    inter = lambda a, b: np.stack([a, b], axis=-1).reshape(len(w), -1)  # noqa: E731 node-major
    return w, inter(N, zero), inter(zero, N), inter(dN, zero), inter(zero, dN)


def gauss_points(p: int) -> np.ndarray:
    """Quadrature points (xi in [0, 1]) of order-p elements, where coefficients given per
    point (shape (n, p + 2)) are evaluated: a section varying along x is then integrated
    as exactly as the quadrature allows, not held constant per element."""
    return 0.5 * (np.polynomial.legendre.leggauss(p + 2)[0] + 1.0)


def _per_point(p: int, L: np.ndarray, coef) -> np.ndarray:
    """A coefficient (scalar, (n,) or (n, p + 2)) as an array (n, p + 2)."""
    c = np.asarray(coef, float)
    return np.broadcast_to(c[:, None] if c.ndim == 1 else c, (len(L), p + 2))


def _integrate(p: int, L, coef, A, B) -> np.ndarray:
    """int coef A^T B dx over each element of length L (A, B per point and DOF)."""
    L = np.atleast_1d(np.asarray(L, float))
    return np.einsum("g,ng,gi,gj->nij", _rule(p)[0], _per_point(p, L, coef) * L[:, None], A, B)


def beam_stiffness(p: int, L, EI, kGA) -> np.ndarray:
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
    """
    L = np.atleast_1d(np.asarray(L, float))
    _, _, Psi, dW, dPsi = _beam_operators(p)  # d/dx = (d/dxi) / L
    EI, kGA, invL = _per_point(p, L, EI), _per_point(p, L, kGA), (1.0 / L)[:, None]
    bend = _integrate(p, L, EI * invL**2, dPsi, dPsi)
    w_w = _integrate(p, L, kGA * invL**2, dW, dW)
    w_psi = _integrate(p, L, kGA * invL, dW, Psi)
    return bend + w_w - w_psi - np.swapaxes(w_psi, 1, 2) + _integrate(p, L, kGA, Psi, Psi)


def beam_mass(p: int, L, rhoA, rhoI) -> np.ndarray:
    """Consistent mass matrices with rotary inertia (rhoA kg/m, rhoI kg m), (n, m, m);
    coefficients per element or per point as in :func:`beam_stiffness`."""
    _, W, Psi, _, _ = _beam_operators(p)
    return _integrate(p, L, rhoA, W, W) + _integrate(p, L, rhoI, Psi, Psi)


def beam_foundation(p: int, L, s) -> np.ndarray:
    """Matrix of a Winkler layer under the beam, s in N/m^2 (or N s/m^2), (n, m, m)."""
    _, W, _, _, _ = _beam_operators(p)
    return _integrate(p, L, s, W, W)


def bar_stiffness(p: int, L, EA) -> np.ndarray:
    """Axial bar stiffness matrices int EA u'^2 (N/m), shape (n, p+1, p+1)."""
    L = np.atleast_1d(np.asarray(L, float))
    _, _, dN = _rule(p)
    return _integrate(p, L, np.asarray(EA, float) / L**2, dN, dN)


def bar_mass(p: int, L, q) -> np.ndarray:
    """Bar matrix int q u^2 for a line density q: rhoA (kg/m) or a foundation s (N/m^2)."""
    _, N, _ = _rule(p)
    return _integrate(p, L, q, N, N)
