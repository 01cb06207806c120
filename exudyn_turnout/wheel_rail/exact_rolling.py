"""Kalker's exact theory of steady-state rolling contact (half-space, Coulomb friction).

The package's own reference solver for the tangential contact problem of two elastically
similar bodies (equal G and nu, so the normal and tangential problems decouple), on a
rectangular grid of elements carrying a given normal pressure p(x, y).  It stands where
Kalker's program CONTACT stands in the literature, with the same boundary element
discretisation (J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
Kluwer 1990; E.A.H. Vollebregt, *User guide for CONTACT*, Vtech CMCC,
github.com/eve70a/CONTACT doc/user-guide.tex at commit d431cdb, sections on the
discretisation and the kinematic variables), written here from those descriptions:

* **Influence coefficients** (:func:`influence_coefficients`): the tangential
  displacement difference at an element's centre due to a uniform unit traction on
  another element, integrated in closed form from Cerruti's point-force solution at the
  surface of a half-space (K.L. Johnson, *Contact mechanics*, CUP 1985, eq. 2.19 at z = 0;
  A.E.H. Love, Phil. Trans. A 228 (1929) integrates the normal case the same way):

      u_x = Q_x / (2 pi G) [(1 - nu) / rho + nu x^2 / rho^3],  u_y = Q_x / (2 pi G) nu x y / rho^3,

  doubled for the two bodies (tractions q on body 1, -q on body 2, u = u1 - u2).  The
  antiderivatives over a rectangle are ``x asinh(y/|x|) + y asinh(x/|y|)`` for 1/rho,
  ``y asinh(x/|y|)`` for x^2/rho^3, ``x asinh(y/|x|)`` for y^2/rho^3 and ``-rho`` for
  x y / rho^3 (terms of one variable only cancel in the four-corner sum).
* **Steady rolling slip** (Kalker 1990; CONTACT user guide): the contact moves in +x
  over both bodies (leading edge at the largest x), material flows through it in -x,
  and the slip of body 1 relative to body 2 per unit rolling distance is

      s = w + du/dx,   w = (xi - phi y, eta + phi x)   (:func:`rigid_slip`),

  with du/dx taken upwind, ``(u_i - u_lead) / dx`` from the element ahead (the particle
  now at element i was at its leading neighbour one element of rolling earlier).
* **Coulomb's law** per element: ``|q| <= mu p``; ``s = 0`` where ``|q| < mu p``
  (adhesion), ``q = -mu p s / |s|`` where the element slips.
* **Solver**: a semi-smooth Newton method of the package's own on the fixed-point form
  of Coulomb's law, ``R(q) = q - P_g(q - r s(q)) = 0`` (P_g: projection of each element's
  traction onto its disc of radius g = mu p; r = dx / A_xx(0), the inverse of the
  element's own slip coefficient), started from the full-adhesion solution projected
  onto the discs, with a backtracking line search on ``|R|^2``; one dense LU per
  iteration (O(m^3) for m elements in contact) after eliminating the radial component of
  every slipping element's step, which the Newton equations fix directly.  It converges
  in 3-7 iterations on the cases of tests/test_exact_rolling.py.  A Gauss-Seidel sweep
  over the elements (the idea of Kalker's and Vollebregt's solvers) was tried first and
  diverged on the steady-rolling operator ``(A - A_lead) / dx`` (its element diagonal
  is a small difference of coefficients); Vollebregt's SteadyGS handles this by solving
  whole grid lines.

Sign convention (that of Kalker and CONTACT, and of ``creep.polach_creep_forces``):
creepages are those of body 1 relative to body 2 and forces act on body 1, so that the
linear theory reads ``F_x = -G c^2 C11 xi``, ``F_y = -G c^2 (C22 eta + c C23 phi)``.

Not modelled: CONTACT's leading-edge correction and its ``dq/6`` shift of the spin's
rigid slip (discretisation refinements of order dx), dissimilar materials, conformal
(curved) contact, velocity-dependent friction.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg

__all__ = [
    "influence_coefficients",
    "rigid_slip",
    "RollingSolution",
    "solve_steady_rolling",
    "hertz_pressure_grid",
    "strip_pressure",
    "exact_creep_forces_ellipse",
]


def _rect_antiderivatives(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, ...]:
    """Antiderivatives F (d2F/dxdy = f) of x^2/rho^3, y^2/rho^3, xy/rho^3 (see module)."""
    ax, ay = np.abs(x), np.abs(y)
    with np.errstate(divide="ignore", invalid="ignore"):
        fxx = np.where(ay > 0.0, y * np.arcsinh(x / np.where(ay > 0.0, ay, 1.0)), 0.0)
        fyy = np.where(ax > 0.0, x * np.arcsinh(y / np.where(ax > 0.0, ax, 1.0)), 0.0)
    fxy = -np.hypot(x, y)
    return fxx, fyy, fxy


def influence_coefficients(
    dx: float, dy: float, nx: int, ny: int, shear_modulus: float, poisson: float
) -> np.ndarray:
    """Tangential influence coefficients of uniform tractions on rectangular elements.

    Displacement difference u = u1 - u2 at an element's centre due to a unit traction
    (1 Pa) on an element offset by (i dx, j dy) from it, both bodies of shear modulus G
    and Poisson's ratio nu (Cerruti's surface solution, Johnson 1985 eq. 2.19, integrated
    over the element in closed form; see the module docstring).

    Parameters
    ----------
    dx, dy : float
        m, element size along x (rolling direction) and y.
    nx, ny : int
        Grid size; offsets -(n-1) ... n-1 are tabulated.
    shear_modulus : float
        Pa, G of each body.
    poisson : float
        Poisson's ratio nu of each body.

    Returns
    -------
    numpy.ndarray
        m/Pa, shape (3, 2 nx - 1, 2 ny - 1): A_xx, A_xy (= A_yx), A_yy, indexed
        ``[k, i + nx - 1, j + ny - 1]`` for the field element minus the source element
        = (i, j).
    """
    ox = np.arange(-(nx - 1), nx) * dx
    oy = np.arange(-(ny - 1), ny) * dy
    X, Y = np.meshgrid(ox, oy, indexing="ij")
    ixx = np.zeros_like(X)
    iyy = np.zeros_like(X)
    ixy = np.zeros_like(X)
    for sx, hx in ((1.0, 0.5 * dx), (-1.0, -0.5 * dx)):
        for sy, hy in ((1.0, 0.5 * dy), (-1.0, -0.5 * dy)):
            fxx, fyy, fxy = _rect_antiderivatives(X + hx, Y + hy)
            ixx += sx * sy * fxx
            iyy += sx * sy * fyy
            ixy += sx * sy * fxy
    scale = 1.0 / (np.pi * shear_modulus)  # 2 bodies x 1 / (2 pi G)
    one = ixx + iyy  # the integral of 1/rho
    return scale * np.stack(
        [
            (1.0 - poisson) * one + poisson * ixx,
            poisson * ixy,
            (1.0 - poisson) * one + poisson * iyy,
        ]
    )


def rigid_slip(x, y, xi: float, eta: float, phi: float) -> tuple[np.ndarray, np.ndarray]:
    """Rigid slip per unit rolling distance (Kalker 1990; CONTACT user guide, eq. of W_It).

    ``w_x = xi - phi y``, ``w_y = eta + phi x``: creepages of body 1 relative to body 2
    and the spin phi about the normal pointing into body 1, at element centres (x, y)
    measured from the point about which the spin is taken.

    Parameters
    ----------
    x, y : array_like
        m, positions in the contact plane.
    xi, eta : float
        Longitudinal and lateral creepage (-).
    phi : float
        1/m, spin creepage.

    Returns
    -------
    tuple of numpy.ndarray
        (w_x, w_y), dimensionless.
    """
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    return xi - phi * y, eta + phi * x


@dataclass(frozen=True, eq=False)
class RollingSolution:
    """Solution of a steady-state rolling contact problem (tractions on body 1)."""

    fx: float  #: N, total tangential force along x (rolling direction)
    fy: float  #: N, total tangential force along y
    mz: float  #: N m, moment of the tractions about the z axis through (0, 0)
    traction_x: np.ndarray  #: Pa, q_x per element, shape (nx, ny)
    traction_y: np.ndarray  #: Pa, q_y per element, shape (nx, ny)
    contact: np.ndarray  #: bool, elements with p > 0
    slip: np.ndarray  #: bool, elements in contact that slip (|q| = mu p, s != 0)
    iterations: int  #: -, Newton iterations used (0: full adhesion held)
    converged: bool  #: the residual |R| fell below tol mu p_max


def _slip_operator(coeff: np.ndarray, ix, iy, nx: int, ny: int, dx: float) -> np.ndarray:
    """Dense S with s = w + S q on the contact elements, S = (A - A_lead) / dx, unknowns
    ordered (q_x of every element, then q_y)."""
    di = ix[:, None] - ix[None, :] + nx
    dj = iy[:, None] - iy[None, :] + ny - 1
    blocks = [(c[di, dj] - c[di + 1, dj]) / dx for c in coeff]
    return np.block([[blocks[0], blocks[1]], [blocks[1], blocks[2]]])


def _project(z: np.ndarray, bound: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Projection of per-element vectors z (2, m) onto discs of radius bound (m)."""
    norm = np.hypot(z[0], z[1])
    outside = norm > bound
    factor = np.where(outside, bound / np.where(outside, norm, 1.0), 1.0)
    return z * factor, outside, norm


def solve_steady_rolling(
    pressure,
    dx: float,
    dy: float,
    x0: float,
    y0: float,
    xi: float,
    eta: float,
    phi: float,
    friction: float,
    shear_modulus: float,
    poisson: float,
    tol: float = 1e-10,
    max_iterations: int = 100,
) -> RollingSolution:
    """Steady-state rolling tangential contact by Kalker's exact theory (module docstring).

    The grid has ``nx x ny`` elements of ``dx x dy``, element (i, j) centred at
    ``(x0 + (i + 1/2) dx, y0 + (j + 1/2) dy)``; rolling is in +x (leading edge at the
    largest x).  Leave at least one element without pressure ahead of the contact area
    in every row (the upwind derivative reads the element ahead; a missing one counts as
    zero displacement).

    Parameters
    ----------
    pressure : array_like
        Pa, normal pressure per element, shape (nx, ny); contact where > 0.
    dx, dy : float
        m, element size.
    x0, y0 : float
        m, corner of the grid (spin and moment are taken about (0, 0)).
    xi, eta : float
        Creepages of body 1 relative to body 2 (-).
    phi : float
        1/m, spin creepage.
    friction : float
        Coefficient of friction mu.
    shear_modulus : float
        Pa, G of both bodies.
    poisson : float
        Poisson's ratio of both bodies.
    tol : float
        Convergence: largest residual of Coulomb's law (Pa), relative to mu p_max.
    max_iterations : int
        Limit on Newton iterations.

    Returns
    -------
    RollingSolution
        Forces on body 1 (``F = -G c^2 C11 xi`` in the linear range).
    """
    p = np.asarray(pressure, float)
    if p.ndim != 2:
        raise ValueError("pressure must be a 2-D array (nx, ny)")
    nx, ny = p.shape
    x = x0 + (np.arange(nx) + 0.5) * dx
    y = y0 + (np.arange(ny) + 0.5) * dy
    X, Y = np.meshgrid(x, y, indexing="ij")
    contact = (p > 0.0) & (friction > 0.0)
    qx = np.zeros((nx, ny))
    qy = np.zeros((nx, ny))
    slip = np.zeros((nx, ny), dtype=bool)
    ix, iy = np.nonzero(contact)
    m = ix.size
    iterations, converged = 0, True
    if m:
        # offsets up to nx along x: the element ahead of the last column is computed too
        coeff = influence_coefficients(dx, dy, nx + 1, ny, shear_modulus, poisson)
        S = _slip_operator(coeff, ix, iy, nx, ny, dx)
        wx, wy = rigid_slip(X[contact], Y[contact], xi, eta, phi)
        w = np.concatenate([wx, wy])
        g = friction * p[contact]
        q, iterations, converged, outside = _newton(
            S, w, g, dx / coeff[0, nx, ny - 1], tol, max_iterations
        )
        qx[contact], qy[contact] = q[:m], q[m:]
        slip[contact] = outside
    area = dx * dy
    return RollingSolution(
        fx=float(qx.sum() * area),
        fy=float(qy.sum() * area),
        mz=float((X * qy - Y * qx).sum() * area),
        traction_x=qx,
        traction_y=qy,
        contact=contact,
        slip=slip,
        iterations=int(iterations),
        converged=bool(converged),
    )


def _reduced_step(J: np.ndarray, R: np.ndarray, outside, ux, uy) -> np.ndarray:
    """Solve J step = -R with the radial part of every slipping element's step known.

    In a slipping element the projection's derivative is (g/|z|) t t^T (t: the tangent
    to the disc), so the Newton row along z/|z| reads ``z^T step_i = -z^T R_i``: that
    component is eliminated, leaving one unknown (along t) per slipping element and two
    per adhering one, which makes the LU up to 8x cheaper in full slip.
    """
    m = outside.size
    tx, ty = -uy, ux  # tangent of the slipping elements' discs
    known = np.zeros(2 * m)
    radial = -(ux * R[:m] + uy * R[m:])
    known[:m] = np.where(outside, radial * ux, 0.0)
    known[m:] = np.where(outside, radial * uy, 0.0)
    rhs_full = -R - J @ known
    stick = np.nonzero(~outside)[0]
    slip = np.nonzero(outside)[0]
    # rows: both rows of adhering elements, the tangential row of slipping ones
    rows = np.vstack(
        [J[stick], J[m + stick], tx[slip, None] * J[slip] + ty[slip, None] * J[m + slip]]
    )
    rhs = np.concatenate([rhs_full[stick], rhs_full[m + stick],
                          tx[slip] * rhs_full[slip] + ty[slip] * rhs_full[m + slip]])  # fmt: skip
    # columns: both components of adhering elements, the tangential one of slipping ones
    matrix = np.hstack([rows[:, stick], rows[:, m + stick],
                        rows[:, slip] * tx[slip] + rows[:, m + slip] * ty[slip]])  # fmt: skip
    v = scipy.linalg.solve(matrix, rhs, check_finite=False, overwrite_a=True, overwrite_b=True)
    k = stick.size
    step = known
    step[stick] += v[:k]
    step[m + stick] += v[k : 2 * k]
    step[slip] += v[2 * k :] * tx[slip]
    step[m + slip] += v[2 * k :] * ty[slip]
    return step


def _newton(S: np.ndarray, w: np.ndarray, g: np.ndarray, r: float, tol: float, limit: int):
    """Semi-smooth Newton on R(q) = q - P_g(q - r s(q)), s = w + S q (module docstring);
    returns (q, iterations, converged, slip flags)."""
    m = g.size
    scale = float(g.max())
    lu = scipy.linalg.lu_factor(S)
    q = scipy.linalg.lu_solve(lu, -w)  # full adhesion, then onto the friction discs
    q = _project(q.reshape(2, m), g)[0].ravel()

    def residual(q_now):
        z = (q_now - r * (w + S @ q_now)).reshape(2, m)
        projected, outside, norm = _project(z, g)
        return q_now - projected.ravel(), z, outside, norm

    R, z, outside, norm = residual(q)
    for iteration in range(1, limit + 1):
        if np.max(np.abs(R)) <= tol * scale:
            return q, iteration - 1, True, outside
        # derivative of the projection: I inside the disc, g/|z| (I - z z^T/|z|^2) outside
        safe = np.where(outside, norm, 1.0)
        ratio = np.where(outside, g / safe, 1.0)
        ux, uy = z[0] / safe, z[1] / safe
        pxx = np.where(outside, ratio * (1.0 - ux * ux), 1.0)
        pyy = np.where(outside, ratio * (1.0 - uy * uy), 1.0)
        pxy = np.where(outside, -ratio * ux * uy, 0.0)
        J = r * np.vstack([pxx[:, None] * S[:m] + pxy[:, None] * S[m:],
                           pxy[:, None] * S[:m] + pyy[:, None] * S[m:]])  # fmt: skip
        J[np.arange(m), np.arange(m)] += 1.0 - pxx
        J[np.arange(m, 2 * m), np.arange(m, 2 * m)] += 1.0 - pyy
        J[np.arange(m), np.arange(m, 2 * m)] -= pxy
        J[np.arange(m, 2 * m), np.arange(m)] -= pxy
        step = _reduced_step(J, R, outside, ux, uy)
        merit = float(R @ R)
        t = 1.0
        while True:
            trial = residual(q + t * step)
            if float(trial[0] @ trial[0]) <= (1.0 - 1e-4 * t) * merit or t < 1e-6:
                break
            t *= 0.5
        q = q + t * step
        R, z, outside, norm = trial
    return q, limit, bool(np.max(np.abs(R)) <= tol * scale), outside


def hertz_pressure_grid(
    a: float, b: float, normal_force: float, n: int = 40
) -> tuple[np.ndarray, float, float, float, float]:
    """Hertz pressure on a grid of ``n x n`` elements covering an ellipse (Johnson 1985,
    eq. 4.44), plus a margin: two element columns ahead, one behind, one row each side.

    ``p = p0 sqrt(1 - x^2/a^2 - y^2/b^2)`` at element centres, scaled so that the sum of
    ``p dx dy`` is the normal force exactly (the grid's share of p0 = 3 N / (2 pi a b)).

    Parameters
    ----------
    a, b : float
        m, semi-axes along x (rolling direction) and y.
    normal_force : float
        N, the normal force N.
    n : int
        Elements across each axis of the ellipse (2a = n dx, 2b = n dy).

    Returns
    -------
    tuple
        (pressure (Pa, shape (n + 3, n + 2)), dx, dy, x0, y0) for
        :func:`solve_steady_rolling`.
    """
    dx = 2.0 * a / n
    dy = 2.0 * b / n
    x0 = -a - dx
    y0 = -b - dy
    x = x0 + (np.arange(n + 3) + 0.5) * dx
    y = y0 + (np.arange(n + 2) + 0.5) * dy
    X, Y = np.meshgrid(x, y, indexing="ij")
    shape = np.sqrt(np.maximum(1.0 - (X / a) ** 2 - (Y / b) ** 2, 0.0))
    total = shape.sum() * dx * dy
    pressure = shape * (normal_force / total) if total > 0.0 else shape
    return pressure, dx, dy, x0, y0


def strip_pressure(area, dx: float, dy: float, normal_force: float) -> np.ndarray:
    """A pressure on a given contact area: semi-elliptic along x in every row (strip)
    of the grid, ``p = k sqrt(l^2 - (x - x_c)^2)`` over the row's extent ``x_c +- l``,
    with one constant k for all rows, scaled to the normal force.

    Exact for a Hertz ellipse (``p0/a sqrt(a^2 (1 - y^2/b^2) - x^2)``) and the form of
    Kik and Piotrowski's pressure (W. Kik, J. Piotrowski, Proc. 2nd Mini Conf. on
    Contact Mechanics, Budapest 1996); used to rebuild a pressure where only the contact
    area is known (CONTACT's printed maps).

    Parameters
    ----------
    area : array_like of bool
        Contact elements, shape (nx, ny), x along axis 0.
    dx, dy : float
        m, element size along x and y.
    normal_force : float
        N, total normal force.

    Returns
    -------
    numpy.ndarray
        Pa, pressure per element, shape (nx, ny).
    """
    area = np.asarray(area, bool)
    nx, ny = area.shape
    x = (np.arange(nx) + 0.5) * dx
    pressure = np.zeros(area.shape)
    for j in range(ny):
        columns = np.nonzero(area[:, j])[0]
        if columns.size == 0:
            continue
        low, high = columns.min() * dx, (columns.max() + 1) * dx
        centre, half = 0.5 * (low + high), 0.5 * (high - low)
        pressure[:, j] = np.sqrt(np.maximum(half**2 - (x - centre) ** 2, 0.0))
    pressure[~area] = 0.0
    total = pressure.sum() * dx * dy
    return pressure * (normal_force / total) if total > 0.0 else pressure


def exact_creep_forces_ellipse(
    a: float,
    b: float,
    xi: float,
    eta: float,
    phi: float,
    normal_force: float,
    friction: float,
    shear_modulus: float = 8.1e10,
    poisson: float = 0.28,
    n: int = 40,
) -> tuple[float, float]:
    """Creep forces of a Hertzian ellipse by Kalker's exact theory.

    The signature of a creep-table solver: ``solver(a, b, xi, eta, phi, N, mu, G, nu)``
    -> (F_x, F_y), N, with the sign convention of ``creep.polach_creep_forces`` (forces
    on the body whose creepages are given; ``F_x = -G a b C11 xi`` for small xi).

    Parameters
    ----------
    a, b : float
        m, semi-axes in the rolling and lateral direction.
    xi, eta : float
        Longitudinal and lateral creepage (-).
    phi : float
        1/m, spin creepage.
    normal_force : float
        N, normal force (<= 0 gives zero forces).
    friction : float
        Coefficient of friction mu.
    shear_modulus : float
        Pa, G.
    poisson : float
        Poisson's ratio.
    n : int
        Elements across each axis.  Kalker's C11, C22, C23 of a circle (nu = 0.25) are
        met within 1.4 % at 40 and 2.6 % from 20 on, except -4.3 % (C23) at 24: the error
        oscillates with n, as the staircase edge of the ellipse moves through the
        elements; forces in saturation change by under 0.2 % from 16 on
        (benchmarks/bench_exact_rolling.py).  The cost grows as n^6 (dense LU).

    Returns
    -------
    tuple of float
        (F_x, F_y), N.
    """
    if normal_force <= 0.0:
        return 0.0, 0.0
    pressure, dx, dy, x0, y0 = hertz_pressure_grid(a, b, normal_force, n)
    solution = solve_steady_rolling(
        pressure, dx, dy, x0, y0, xi, eta, phi, friction, shear_modulus, poisson
    )
    return solution.fx, solution.fy
