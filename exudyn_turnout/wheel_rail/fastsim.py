"""Kalker's FASTSIM: creep forces of the simplified theory, with spin, never above mu N.

The simplified theory (J.J. Kalker, "A fast algorithm for the simplified theory of rolling
contact", Vehicle System Dynamics 11 (1982) 1-13) replaces the elastic half-space by a bed
of independent springs: the surface displacement is ``u = L p`` (L, m/Pa, a flexibility).
In steady rolling along x the material crosses the patch from its leading edge
``x = x_l(y)`` to its trailing edge ``-x_l(y)``; with the rigid slip (per unit rolling
distance) ``w = (xi - phi y, eta + phi x)`` it sticks where

    dp/dx = w / L   (traction grows from 0 at the leading edge),

and where that would give ``|p| > mu p_z`` it slides with ``|p| = mu p_z``, the traction
along the trial traction.  Coulomb's bound holds at every point, so ``|F| <= mu N``.

Choices made here
-----------------
*Three flexibilities.*  Kalker's 1982 paper uses one flexibility, a creepage-weighted mean
of ``L1 = 8 a / (3 G C11)``, ``L2 = 8 a / (3 G C22)`` and ``L3 = pi a sqrt(a / b) / (4 G
C23)``, which gives Kalker's linear theory only for a pure creepage.  Here each creepage
has its own: ``dp_x/dx = xi / L1 - phi y / L3``, ``dp_y/dx = eta / L2 + phi x / L3``, so the
small-creepage limit is Kalker's linear theory for every combination of xi, eta and phi
(``F_x = -G a b C11 xi``, ``F_y = -G a b (C22 eta + sqrt(a b) C23 phi)``), and the force
is a smooth function of the creepages (the weighted mean has kinks where a creepage
changes sign, which a table would have to resolve).

*Discretisation.*  The rigid slip is integrated exactly over every element (it is linear
in x), and the traction is taken at the element centres (midpoint rule), so a strip in
stick is exact.  Where the material slides, the traction is the trial traction projected
onto the friction bound, which is first order in the element length: the lateral force
of spin moved by 7 % of itself from 60 to 480 elements.  Every strip is therefore solved
on n and 2n elements and extrapolated (Richardson, ``2 F_2n - F_n``), then projected
back onto the strip's friction bound; this converges at second order (to 3e-4 mu N at
the default 40 strips x 60 elements, tests/test_wheel_rail_fastsim.py).  Vollebregt &
Wilders treat the same first-order error with a second-order integration of the
sliding part (E.A.H. Vollebregt, P. Wilders, "FASTSIM2: a second-order accurate
frictional rolling contact algorithm", Computational Mechanics 47 (2011) 105-116); the
extrapolation here is simpler and enough for a table computed once.

*Parabolic pressure* ``p_z = p_0 (1 - (x / x_l)^2)`` along x in every strip, Kalker's
choice for FASTSIM (it brings the simplified theory's saturation close to the exact
one's).  With it, each strip under a pure creepage saturates as the cubic
``1 - (1 - k)^3`` of Vermeulen & Johnson (1964), ``k = G a b C11 |xi| / (3 mu N)``; the
ellipse's strips saturate from their trailing edges by the same length, not the same
fraction, so the patch's curve lies up to 0.011 mu N below theirs (measured).  The
semi-elliptic (Hertz) pressure can be chosen for a strip patch.

*Elliptic patch.*  Strips at ``y = b sin(theta)`` with equal steps in theta (a midpoint
rule in theta): the strip half-length is ``a cos(theta)`` and the strips are dense near
the lateral edges, where the half-length changes fastest; their normal load is exactly
N.  Every strip's traction is divided by its discrete load and multiplied by its exact
one, so the resultant is bounded by ``mu N`` exactly, not only in the limit.

Known weakness: spin.  The simplified theory's lateral force of spin in partial slip is
too large.  Against a boundary-element solution of Kalker's exact theory on Hertz
ellipses (24 elements across, itself about 4 % stiff in the linear range), at normalised
creepages up to 0.8 and spins up to 1.5 (a / b = 0.5, 1, 2; 24 states), FASTSIM was within
0.047 mu N without spin and 0.133 mu N with it (its lateral force 20-80 % too large where
eta and spin oppose), Polach's law within 0.046 and 0.37 mu N.

Sign convention: forces on the wheel, opposing the creepages (Kalker's; that of
:func:`.creep.polach_creep_forces`).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from exudyn_turnout.wheel_rail.creep import CreepForces, kalker_coefficients

__all__ = [
    "DEFAULT_STRIPS",
    "DEFAULT_ELEMENTS",
    "kalker_flexibilities",
    "strip_forces",
    "fastsim_strips",
    "fastsim_ellipse",
    "fastsim_solver",
]

#: Strips across an elliptic patch (with DEFAULT_ELEMENTS: within 3e-4 mu N of 4x finer)
DEFAULT_STRIPS = 40
#: Elements along x in every strip (and twice as many, extrapolated)
DEFAULT_ELEMENTS = 60


def kalker_flexibilities(a, b, shear_modulus: float, poisson: float = 0.28):
    """FASTSIM's flexibilities from Kalker's coefficients (Kalker 1982, three of them).

    ``L1 = 8 a / (3 G C11)``, ``L2 = 8 a / (3 G C22)``, ``L3 = pi a sqrt(a / b) / (4 G C23)``:
    with these a patch in full stick gives Kalker's linear creep forces.

    Parameters
    ----------
    a, b : array_like
        m, semi-axes in rolling and lateral direction.
    shear_modulus : float
        Pa, G.
    poisson : float
        Poisson's ratio for Kalker's coefficients.

    Returns
    -------
    tuple of numpy.ndarray
        m/Pa, (L1, L2, L3).
    """
    a = np.asarray(a, float)
    b = np.asarray(b, float)
    c = kalker_coefficients(a, b, poisson)
    g = float(shear_modulus)
    return (
        8.0 * a / (3.0 * g * c.c11),
        8.0 * a / (3.0 * g * c.c22),
        np.pi * a * np.sqrt(a / b) / (4.0 * g * c.c23),
    )


@numba.njit(cache=True)
def strip_forces(
    y, width, half_length, strip_load, elliptic, flex1, flex2, flex3, xi, eta, phi, mu, n_x,
    x_centre,
):  # pragma: no cover (compiled; tested through its Python callers)  # fmt: skip
    """FASTSIM on a patch given as strips across the rolling direction (compiled).

    Parameters
    ----------
    y : numpy.ndarray
        m, (n,) lateral position of each strip's centre line (from the spin's pole).
    width : numpy.ndarray
        m, (n,) strip widths.
    half_length : numpy.ndarray
        m, (n,) half-length of each strip along x, symmetric about x = 0.
    strip_load : numpy.ndarray
        N/m, (n,) normal load of each strip per unit width (its pressure integrated along x).
    elliptic : bool
        Semi-elliptic pressure along x in every strip (else Kalker's parabolic one).
    flex1, flex2, flex3 : float
        m/Pa, flexibilities for xi, eta and phi (:func:`kalker_flexibilities`).
    xi, eta : float
        Creepages (-).
    phi : float
        1/m, spin creepage.
    mu : float
        Friction coefficient.
    n_x : int
        Elements along x in every strip.
    x_centre : numpy.ndarray
        m, (n,) centre of each strip along x (from the spin's pole): a strip at x_c sees
        the rigid slip ``eta + phi x`` of its own x (a skewed patch); zeros for a patch
        symmetric about x = 0.

    Returns
    -------
    tuple of float
        N, (F_x, F_y) on the wheel; ``|F| <= mu sum(strip_load width)`` exactly.
    """
    fx_total = 0.0
    fy_total = 0.0
    for j in range(y.shape[0]):
        half = half_length[j]
        load = strip_load[j]
        if half <= 0.0 or load <= 0.0:
            continue
        # a strip centred at x_c: the spin's slip phi (x_c + x) about the strip's centre
        eta_j = eta + phi * x_centre[j] * (flex2 / flex3)
        # Richardson: the sliding update is first order in the element length
        coarse_x, coarse_y = _strip(half, load, y[j], elliptic, flex1, flex2, flex3,
                                    xi, eta_j, phi, mu, n_x)  # fmt: skip
        fine_x, fine_y = _strip(half, load, y[j], elliptic, flex1, flex2, flex3,
                                xi, eta_j, phi, mu, 2 * n_x)  # fmt: skip
        sx = 2.0 * fine_x - coarse_x
        sy = 2.0 * fine_y - coarse_y
        size = math.hypot(sx, sy)
        if size > mu:  # the extrapolation may overshoot the strip's friction bound
            sx *= mu / size
            sy *= mu / size
        fx_total += sx * load * width[j]
        fy_total += sy * load * width[j]
    return fx_total, fy_total


@numba.njit(cache=True)
def _strip(
    half, load, y, elliptic, flex1, flex2, flex3, xi, eta, phi, mu, n_x
):  # pragma: no cover (compiled)
    """Traction of one strip over its load, (F_x, F_y) / q, on n_x elements."""
    dx = 2.0 * half / n_x
    # peak pressure of the strip: parabolic 3 q / (4 L), semi-elliptic 2 q / (pi L)
    peak = 2.0 * load / (math.pi * half) if elliptic else 0.75 * load / half
    gx = xi / flex1 - phi * y / flex3  # dp_x/dx, constant along the strip
    gy = eta / flex2
    gs = phi / flex3
    px = 0.0
    py = 0.0
    sum_x = 0.0
    sum_y = 0.0
    sum_z = 0.0
    x_prev = half
    inv_half2 = 1.0 / (half * half)
    for i in range(n_x):  # element centres, from the leading edge backwards
        x_i = half - (i + 0.5) * dx
        # rigid slip integrated exactly from the previous centre (linear in x)
        step = x_prev - x_i
        px -= step * gx
        py -= step * (gy + gs * 0.5 * (x_prev + x_i))
        x_prev = x_i
        shape = 1.0 - x_i * x_i * inv_half2
        pz = peak * (math.sqrt(shape) if elliptic else shape)
        bound = mu * pz
        size2 = px * px + py * py
        if size2 > bound * bound:  # sliding: the traction on the friction bound
            ratio = bound / math.sqrt(size2)
            px *= ratio
            py *= ratio
        sum_x += px
        sum_y += py
        sum_z += pz
    if sum_z <= 0.0:
        return 0.0, 0.0
    return sum_x / sum_z, sum_y / sum_z  # midpoint rule, over the strip's load


def fastsim_strips(
    xi: float,
    eta: float,
    phi: float,
    y,
    width,
    half_length,
    strip_load,
    flexibilities: tuple[float, float, float],
    friction: float,
    n_x: int = DEFAULT_ELEMENTS,
    pressure: str = "parabolic",
    x_centre=None,
) -> tuple[float, float]:
    """FASTSIM on an arbitrary patch given as strips (e.g. a Kik-Piotrowski patch).

    Parameters
    ----------
    xi, eta : float
        Creepages (-).
    phi : float
        1/m, spin creepage (about the origin of ``y`` and x = 0).
    y, width, half_length : array_like
        m, strips: lateral centre, width, half-length along x.
    strip_load : array_like
        N/m, normal load per unit width of each strip.
    flexibilities : tuple of float
        m/Pa, (L1, L2, L3), e.g. of the patch's equivalent ellipse
        (:func:`kalker_flexibilities`; Piotrowski & Kik 2008 take FASTSIM's flexibility
        for a non-elliptic patch this way).
    friction : float
        Coefficient of friction mu.
    n_x : int
        Elements along x per strip.
    pressure : str
        "parabolic" (Kalker's FASTSIM) or "elliptic" along x in every strip.
    x_centre : array_like, optional
        m, centre of each strip along x from the spin's pole (default: all at x = 0).

    Returns
    -------
    tuple of float
        N, (F_x, F_y) on the wheel.
    """
    if pressure not in ("parabolic", "elliptic"):
        raise ValueError(f"pressure must be 'parabolic' or 'elliptic', not {pressure!r}")
    y_, width_, half_, load_ = (
        np.ascontiguousarray(v, dtype=float) for v in (y, width, half_length, strip_load)
    )
    centre_ = (
        np.zeros(y_.shape) if x_centre is None else np.ascontiguousarray(x_centre, dtype=float)
    )
    flex1, flex2, flex3 = (float(v) for v in flexibilities)
    fx, fy = strip_forces(
        y_, width_, half_, load_, pressure == "elliptic", flex1, flex2, flex3,
        float(xi), float(eta), float(phi), float(friction), int(n_x), centre_,
    )  # fmt: skip
    return float(fx), float(fy)


@numba.njit(cache=True)
def _ellipse_strips(a, b, normal_force, n_strips):  # pragma: no cover (compiled)
    """Strips of an elliptic patch at y = b sin(theta), parabolic pressure, load N."""
    y = np.empty(n_strips)
    width = np.empty(n_strips)
    half = np.empty(n_strips)
    load = np.empty(n_strips)
    step = math.pi / n_strips
    p0 = 2.0 * normal_force / (math.pi * a * b)
    for j in range(n_strips):
        theta = -0.5 * math.pi + (j + 0.5) * step
        cos_t = math.cos(theta)
        y[j] = b * math.sin(theta)
        width[j] = b * cos_t * step
        half[j] = a * cos_t
        load[j] = p0 * cos_t * cos_t * 4.0 * half[j] / 3.0
    return y, width, half, load


@numba.njit(cache=True)
def ellipse_many(
    xi, eta, phi, a, b, q, mu, flex1, flex2, flex3, n_strips, n_x
):  # pragma: no cover (compiled)
    """FASTSIM's creep forces on many elliptic patches, compiled (as :func:`fastsim_ellipse`).

    Parameters
    ----------
    xi, eta, phi : numpy.ndarray
        (n,) longitudinal and lateral creepage, spin (1/m).
    a, b : numpy.ndarray
        (n,) m, semi-axes along and across the rolling direction.
    q : numpy.ndarray
        (n,) N, normal force (a patch with q, a or b <= 0 gives zero force).
    mu : numpy.ndarray
        (n,) friction coefficient.
    flex1, flex2, flex3 : numpy.ndarray
        (n,) m/Pa, Kalker's flexibilities (:func:`kalker_flexibilities`).
    n_strips, n_x : int
        Strips across the patch and elements along each strip.

    Returns
    -------
    numpy.ndarray
        (n, 2) N, longitudinal and lateral force on the wheel.
    """
    n = xi.shape[0]
    out = np.zeros((n, 2))
    centred = np.zeros(n_strips)  # the ellipse's strips are centred at x = 0
    for k in range(n):
        if q[k] <= 0.0 or a[k] <= 0.0 or b[k] <= 0.0:
            continue
        y, width, half, load = _ellipse_strips(a[k], b[k], q[k], n_strips)
        fx, fy = strip_forces(
            y, width, half, load, False, flex1[k], flex2[k], flex3[k], xi[k], eta[k], phi[k],
            mu[k], n_x, centred,
        )  # fmt: skip
        out[k, 0] = fx
        out[k, 1] = fy
    return out


def fastsim_ellipse(
    creep_longitudinal,
    creep_lateral,
    spin,
    a,
    b,
    normal_force,
    friction,
    shear_modulus: float = 8.1e10,
    poisson: float = 0.28,
    n_strips: int = DEFAULT_STRIPS,
    n_x: int = DEFAULT_ELEMENTS,
) -> CreepForces:
    """FASTSIM on a Hertz ellipse, three flexibilities, parabolic pressure (arrays).

    Parameters
    ----------
    creep_longitudinal, creep_lateral : array_like
        Creepages xi, eta (-).
    spin : array_like
        1/m, spin creepage phi.
    a, b : array_like
        m, semi-axes in rolling and lateral direction.
    normal_force : array_like
        N, normal force (<= 0 gives zero force).
    friction : array_like
        Coefficient of friction mu.
    shear_modulus : float
        Pa, G.
    poisson : float
        Poisson's ratio for Kalker's coefficients.
    n_strips, n_x : int
        Strips across the patch and elements along x per strip.

    Returns
    -------
    CreepForces
        On the wheel (the sign convention of :func:`.creep.polach_creep_forces`);
        ``|F| <= mu N``.
    """
    arrays = np.broadcast_arrays(
        *(np.asarray(v, float) for v in (creep_longitudinal, creep_lateral, spin, a, b,
                                          normal_force, friction))
    )  # fmt: skip
    shape = arrays[0].shape
    xi, eta, phi, a_, b_, q, mu = (np.array(v, dtype=float).ravel() for v in arrays)
    usable = (a_ > 0.0) & (b_ > 0.0)
    flex = kalker_flexibilities(
        np.where(usable, a_, 1.0), np.where(usable, b_, 1.0), shear_modulus, poisson
    )
    flex1, flex2, flex3 = (np.ascontiguousarray(f) for f in flex)
    out = ellipse_many(xi, eta, phi, a_, b_, q, mu, flex1, flex2, flex3, int(n_strips), int(n_x))
    return CreepForces(longitudinal=out[:, 0].reshape(shape), lateral=out[:, 1].reshape(shape))


def fastsim_solver(a, b, xi, eta, phi, normal_force, friction, shear_modulus, poisson):
    """:func:`fastsim_ellipse` with the signature of a creep-table solver.

    Parameters
    ----------
    a, b : float
        m, semi-axes.
    xi, eta : float
        Creepages (-).
    phi : float
        1/m, spin creepage.
    normal_force : float
        N.
    friction : float
        Coefficient of friction.
    shear_modulus : float
        Pa.
    poisson : float
        Poisson's ratio.

    Returns
    -------
    tuple of float
        N, (F_x, F_y) on the wheel.
    """
    forces = fastsim_ellipse(xi, eta, phi, a, b, normal_force, friction, shear_modulus, poisson)
    return float(forces.longitudinal), float(forces.lateral)
