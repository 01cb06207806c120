"""Exact (half-space) normal contact on a grid: the reference for the semi-Hertzian method.

What it solves
--------------
Two elastically similar bodies (equal E and nu), each treated as a half-space, touch over
a flat potential contact plane discretised into rectangular elements of constant
pressure (the boundary element discretisation of Kalker's program CONTACT: J.J. Kalker,
*Three-dimensional elastic bodies in rolling contact*, Kluwer 1990, ch. 5; E.A.H.
Vollebregt, *User guide for CONTACT*, the normal problem).  With the undeformed
separation h >= 0 of the surfaces at the element centres, the approach delta of the
bodies and the surface displacement u = A p of the pressure (both bodies together), the
deformed gap ``g = h + A p - delta`` must satisfy Signorini's conditions

    p >= 0,   g >= 0,   p g = 0   in every element,

with either the approach delta or the total force ``N = sum p dx dy`` prescribed.

* **Influence coefficients** (:func:`boussinesq_coefficients`): the normal displacement
  of both surfaces at an element's centre due to a uniform unit pressure on another
  element, ``1 / (pi E*) int int 1 / rho dA`` (Boussinesq, Johnson *Contact mechanics*,
  CUP 1985, eq. 3.2 and its integration over a rectangle, eq. 3.25; Love, Phil. Trans. A
  228 (1929)), ``1 / E* = 2 (1 - nu^2) / E``.  The integral of 1/rho over a rectangle is
  the one in Cerruti's A_xx at nu = 0, so :func:`.exact_rolling.influence_coefficients`
  with G = E* and nu = 0 gives exactly these coefficients.
* **Solver** (:func:`solve_normal`): the conjugate-gradient method of I.A. Polonsky & L.M.
  Keer, "A numerical method for solving rough contact problems based on the multi-level
  multi-summation and conjugate gradient techniques", Wear 231 (1999) 206-219, with the
  displacement ``A p`` evaluated as a discrete convolution by FFT (the coefficients
  depend only on the offset of two elements).  With the force prescribed, the mean gap
  over the current contact set is the Lagrange multiplier of the force constraint, and
  at convergence it is the approach.  This is the same quadratic programme as Kalker's
  NORM (Kalker 1990, sec. 5.3), solved by another iteration.

What it is for
--------------
:func:`solve_on_lateral_gap` puts the gap the semi-Hertzian method
(:mod:`.nonhertz`) works on, ``h(x, t) = g(t) + A x^2`` (the lateral gap function of the
undeformed profiles plus the relative curvature in the rolling direction), on a grid
and solves it exactly.  Kik-Piotrowski against this solution is the error of KP's method
alone; this solution against CONTACT is the error of the gap (our geometry), see
``validation/normal_vs_contact.md``.  On the gap of our 3-D surfaces
(:func:`.reference_normal.exact_on_surface`) it carries the exact tangential solution of
:mod:`.detailed_contact` (``validation/detailed_vs_contact.md``).

Not modelled: dissimilar materials (no coupling of normal and tangential problems),
conformal (curved) contact planes, the interaction of the tangential tractions with the
normal problem.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
import scipy.fft

from exudyn_turnout.wheel_rail.exact_rolling import influence_coefficients

__all__ = [
    "boussinesq_coefficients",
    "NormalSolution",
    "solve_normal",
    "lateral_gap_grid",
    "solve_on_lateral_gap",
]

#: Default convergence tolerance of :func:`solve_normal`: relative change of the pressure
#: field in one iteration (Polonsky & Keer's criterion)
TOLERANCE = 1e-9


def boussinesq_coefficients(dx: float, dy: float, nx: int, ny: int, modulus: float) -> np.ndarray:
    """Normal influence coefficients of uniform pressures on rectangular elements.

    The normal displacement of both surfaces together at an element's centre due to a
    pressure of 1 Pa on the element offset by (i dx, j dy) from it:
    ``1 / (pi E*) int int 1 / rho dA`` (Boussinesq; Johnson 1985, eqs 3.2, 3.25).

    Parameters
    ----------
    dx, dy : float
        m, element size along x (rolling direction) and y (lateral).
    nx, ny : int
        Grid size; offsets -(n-1) ... n-1 are tabulated.
    modulus : float
        Pa, contact modulus E* (:func:`.hertz.effective_modulus`).

    Returns
    -------
    numpy.ndarray
        m/Pa, shape (2 nx - 1, 2 ny - 1), indexed ``[i + nx - 1, j + ny - 1]`` for the
        field element minus the source element = (i, j).
    """
    # Cerruti's A_xx at nu = 0 is 1 / (pi G) int int 1 / rho dA (module docstring)
    return influence_coefficients(dx, dy, nx, ny, modulus, 0.0)[0]


@dataclass(frozen=True, eq=False)
class NormalSolution:
    """Exact normal contact on a grid (element centres ``x[i]``, ``y[j]``)."""

    pressure: np.ndarray  #: Pa, (nx, ny) pressure per element
    x: np.ndarray  #: m, (nx,) element centres along x (rolling direction)
    y: np.ndarray  #: m, (ny,) element centres along y (lateral)
    dx: float  #: m, element size along x
    dy: float  #: m, element size along y
    approach: float  #: m, approach of the bodies (delta)
    normal_force: float  #: N, sum of p dx dy
    p_max: float  #: Pa, largest element pressure
    length: float  #: m, extent along x of the elements in contact (columns x dx)
    width: float  #: m, extent along y of the elements in contact (rows x dy)
    area: float  #: m^2, elements in contact x dx dy
    x_centre: float  #: m, where the normal force acts, along x
    y_centre: float  #: m, where the normal force acts, along y
    iterations: int  #: -, conjugate-gradient iterations
    converged: bool  #: reached the tolerance within the iteration limit


class _Convolution:
    """``u = A p`` for a field of shape (nx, ny) by FFT (no wrap-around: see below)."""

    def __init__(self, coefficients: np.ndarray, nx: int, ny: int) -> None:
        # u[f] = sum_s C[f - s + n - 1] p[s]: a circular convolution of length
        # L >= 2 n - 1 never wraps for the wanted outputs f in [0, n) (f - s + n - 1 lies in
        # [0, 2 n - 2]); they are entries n - 1 ... 2 n - 2 of it
        self.nx, self.ny = nx, ny
        self.shape = (scipy.fft.next_fast_len(2 * nx - 1), scipy.fft.next_fast_len(2 * ny - 1))
        self.kernel = scipy.fft.rfft2(coefficients, self.shape)

    def __call__(self, field: np.ndarray) -> np.ndarray:
        full = scipy.fft.irfft2(scipy.fft.rfft2(field, self.shape) * self.kernel, self.shape)
        return full[self.nx - 1 : 2 * self.nx - 1, self.ny - 1 : 2 * self.ny - 1]


def solve_normal(
    gap,
    dx: float,
    dy: float,
    modulus: float,
    force: float | None = None,
    approach: float | None = None,
    tolerance: float = TOLERANCE,
    max_iterations: int = 5000,
) -> NormalSolution:
    """Exact normal contact of two elastic half-spaces on a grid (Polonsky & Keer 1999).

    Exactly one of ``force`` and ``approach`` is given.

    Parameters
    ----------
    gap : array_like
        m, (nx, ny) undeformed separation h at the element centres (its minimum is the
        datum of the approach: 0 where the surfaces first touch).
    dx, dy : float
        m, element size along axis 0 (x) and axis 1 (y).
    modulus : float
        Pa, contact modulus E*.
    force : float, optional
        N, prescribed normal force (> 0).
    approach : float, optional
        m, prescribed approach delta.
    tolerance : float
        Convergence: ``sum |p - p_previous| / sum p`` below it.
    max_iterations : int
        Iteration limit.

    Returns
    -------
    NormalSolution
        Element centres from ``x = (i - (nx - 1) / 2) dx`` (likewise y).

    Raises
    ------
    ValueError
        If not exactly one of force and approach is given, the force is not positive,
        or the gap is not finite.
    """
    h = np.asarray(gap, float)
    if (force is None) == (approach is None):
        raise ValueError("solve_normal: give exactly one of force and approach")
    if force is not None and not force > 0.0:
        raise ValueError(f"solve_normal: force must be > 0, got {force}")
    if h.ndim != 2 or not np.all(np.isfinite(h)):
        raise ValueError("solve_normal: gap must be a finite 2-D array")
    nx, ny = h.shape
    element = dx * dy
    conv = _Convolution(boussinesq_coefficients(dx, dy, nx, ny, modulus), nx, ny)
    by_force = force is not None
    level = 0.0 if approach is None else float(approach)
    if by_force:
        p = np.full(h.shape, float(force) / (element * h.size))  # type: ignore[arg-type]
    else:
        # each element pressed alone to the approach: a start on the safe side
        p = np.maximum(level - h, 0.0) / float(boussinesq_coefficients(dx, dy, 1, 1, modulus)[0, 0])
    direction = np.zeros_like(p)
    previous_norm, conjugate = 1.0, False
    mean_gap = level
    converged = False
    iteration = 0
    while iteration < max_iterations:
        iteration += 1
        contact = p > 0.0
        if not np.any(contact):
            # prescribed approach below first touch: nothing carries load
            if not by_force and np.all(h >= level):
                converged = True
                break
            contact = h <= np.min(h)
        g = h + conv(p)
        mean_gap = float(np.mean(g[contact])) if by_force else level
        g = g - mean_gap
        norm = float(np.sum(g[contact] ** 2))
        factor = norm / previous_norm if conjugate else 0.0
        direction = np.where(contact, g + factor * direction, 0.0)
        previous_norm = norm
        response = conv(direction)
        if by_force:
            response = response - float(np.mean(response[contact]))
        curvature = float(np.sum(response[contact] * direction[contact]))
        if curvature <= 0.0:
            converged = norm == 0.0
            break
        tau = float(np.sum(g[contact] * direction[contact])) / curvature
        old = p
        p = np.where(contact, p - tau * direction, 0.0)
        p = np.maximum(p, 0.0)
        reenter = (p == 0.0) & (g < 0.0)
        conjugate = not np.any(reenter)
        p = np.where(reenter, p - tau * g, p)
        if by_force:
            total = float(np.sum(p)) * element
            p = p * (float(force) / total)  # type: ignore[arg-type]
        change = float(np.sum(np.abs(p - old)))
        scale = float(np.sum(p))
        if scale > 0.0 and change <= tolerance * scale:
            converged = True
            break
    if by_force:
        contact = p > 0.0
        mean_gap = float(np.mean((h + conv(p))[contact]))
    return _solution(p, dx, dy, mean_gap, iteration, converged)


def _solution(p, dx, dy, approach, iterations, converged) -> NormalSolution:
    nx, ny = p.shape
    x = (np.arange(nx) - 0.5 * (nx - 1)) * dx
    y = (np.arange(ny) - 0.5 * (ny - 1)) * dy
    contact = p > 0.0
    total = float(np.sum(p))
    if total > 0.0:
        rows, cols = np.nonzero(contact)
        length = (rows.max() - rows.min() + 1) * dx
        width = (cols.max() - cols.min() + 1) * dy
        x_c = float(np.sum(p.sum(axis=1) * x) / total)
        y_c = float(np.sum(p.sum(axis=0) * y) / total)
    else:
        length = width = x_c = y_c = 0.0
    return NormalSolution(
        pressure=p,
        x=x,
        y=y,
        dx=dx,
        dy=dy,
        approach=approach,
        normal_force=total * dx * dy,
        p_max=float(np.max(p)) if p.size else 0.0,
        length=float(length),
        width=float(width),
        area=float(np.count_nonzero(contact)) * dx * dy,
        x_centre=x_c,
        y_centre=y_c,
        iterations=iterations,
        converged=converged,
    )


def lateral_gap_grid(
    lateral_gap, step: float, a_sum: float, dx: float, dy: float, level: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The gap ``h(x, t) = g(t) + A x^2`` on a grid covering ``h < level``.

    Parameters
    ----------
    lateral_gap : array_like
        m, (n_t,) normal gap of the undeformed surfaces along the lateral tangent on
        ``t = (k - n_t // 2) step`` (:func:`.nonhertz.normal_gap_function`); NaN or large
        where there is no surface.
    step : float
        m, its sample step.
    a_sum : float
        1/m, relative curvature in the rolling direction (half the curvature sum, > 0).
    dx, dy : float
        m, element size along x and t.
    level : float
        m, the grid covers every element centre with ``h < level`` (the whole
        interpenetration region of any approach up to ``level``), plus one element.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray, numpy.ndarray)
        m: the gap (nx, ny), element centres x (nx,) and t (ny,), x symmetric about 0.
    """
    g = np.nan_to_num(np.asarray(lateral_gap, float), nan=np.inf)
    n_t = g.size
    t_samples = (np.arange(n_t) - n_t // 2) * step
    below = np.nonzero(g < level)[0]
    if below.size == 0:
        below = np.array([int(np.argmin(g))])
    t_low, t_high = t_samples[below[0]] - step, t_samples[below[-1]] + step
    ny = int(math.ceil((t_high - t_low) / dy)) + 2
    t = 0.5 * (t_low + t_high) + (np.arange(ny) - 0.5 * (ny - 1)) * dy
    x_half = math.sqrt(max(level, 0.0) / a_sum) + dx
    nx = 2 * int(math.ceil(x_half / dx)) + 1
    x = (np.arange(nx) - 0.5 * (nx - 1)) * dx
    finite = np.where(np.isfinite(g), g, 1.0)
    g_t = np.interp(t, t_samples, finite, left=1.0, right=1.0)
    return g_t[None, :] + a_sum * x[:, None] ** 2, x, t


def solve_on_lateral_gap(
    lateral_gap,
    step: float,
    a_sum: float,
    force: float,
    modulus: float,
    dx: float,
    dy: float,
    level: float = 1e-4,
) -> NormalSolution:
    """Exact normal contact on the semi-Hertzian method's gap ``g(t) + A x^2``.

    The grid (:func:`lateral_gap_grid`) covers ``h < level``; the contact area lies inside
    the interpenetration region ``h < delta`` (``A p >= 0``), so while the solved approach
    exceeds ``level`` the grid is enlarged (``level`` = 1.3 delta) and the problem solved
    again.

    Parameters
    ----------
    lateral_gap : array_like
        m, (n_t,) lateral gap function (see :func:`lateral_gap_grid`).
    step : float
        m, its sample step.
    a_sum : float
        1/m, relative curvature in the rolling direction.
    force : float
        N, normal force.
    modulus : float
        Pa, contact modulus E*.
    dx, dy : float
        m, element size along x and the lateral tangent t.
    level : float
        m, first guess of the grid's reach in h.

    Returns
    -------
    NormalSolution
        ``y`` holds the lateral tangent t of the gap function (0 at its centre sample).
    """
    for _ in range(8):
        h, x, t = lateral_gap_grid(lateral_gap, step, a_sum, dx, dy, level)
        solved = solve_normal(h, dx, dy, modulus, force=force)
        if solved.approach < level:
            break
        level = 1.3 * solved.approach
    shift = float(t[0] - solved.y[0])
    return dataclasses.replace(solved, y=solved.y + shift, y_centre=solved.y_centre + shift)
