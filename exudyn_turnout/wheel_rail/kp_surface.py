"""Kik-Piotrowski's semi-Hertzian method on the 3-D gap h(x, t) of the undeformed surfaces.

Why
---
Kik-Piotrowski (KP, :mod:`.nonhertz`) works on a 2-D slice: the gap ``g(t) + A x^2``, the
rail taken as constant along x within the patch.  Against CONTACT's five reference cases
that slice is the larger error of the approach in three of five
(``validation/normal_vs_contact.md``): the wing-rail patches are skewed bands, and in
cw_interrupt#2 the rail ends along x inside the patch.  This module keeps KP's
construction and takes the gap of the 3-D surfaces instead, sampled on a grid
(e.g. :func:`.reference_normal.surface_gap`); ``validation/kp_surface_vs_contact.py``
measures it against CONTACT and the exact half-space solution on the same gap.

The method
----------
With the undeformed normal gap ``h(x, t)`` (x along the track, t along the lateral
tangent; shifted so that its minimum, the *reference point* ``(x_0, t_0)``, is 0), the
penetration (approach) delta and ``epsilon`` = :data:`.nonhertz.EPSILON` (KP's value, not
tuned):

- **Region.**  The contact region is the connected set (4-neighbours on the grid) around
  the reference point where ``h(x, t) < epsilon delta`` (KP's virtual penetration).
  Every lateral strip (grid row t_k) covers one or several x-intervals
  ``[x_1, x_2]`` of it; their ends are where h crosses ``epsilon delta``, found on the
  parabola through three samples along x (exact for a gap quadratic in x); where the
  surface ends between two samples (no rail) the interval ends midway.  Intervals may be
  off-centre (a skewed band) and truncated.
- **Pressure.**  Semi-elliptic along x on every interval, one constant c for the patch,
  ``p = c sqrt(L^2 - (x - x_c)^2)``, ``L = (x_2 - x_1) / 2``, ``x_c = (x_1 + x_2) / 2``.
  For ``h = g(t) + A x^2`` the interval is ``|x| <= sqrt((epsilon delta - g(t)) / A)``
  and this is KP's pressure; for ``h = A x^2 + B t^2`` KP's (close to Hertz's).
- **Approach.**  KP's contact condition at the reference point: the surfaces' normal
  displacement there (Boussinesq, two elastically similar half-spaces, modulus E*)
  equals delta,

      delta = 1 / (pi E*) int int p(x, t) / sqrt((x - x_0)^2 + (t - t_0)^2) dx dt
            = c I_1 / (pi E*),

  ``I_1 = sum_k w_k J(L_k, d_k, t_k - t_0)`` over the intervals (strip width w_k), with
  the offset strip integral (:func:`offset_strip_integral`)

      J(L, d, t) = int_{-L}^{L} sqrt(L^2 - u^2) / sqrt((u + d)^2 + t^2) du,
      d = x_c - x_0,

  which is KP's ``J(L, t) = 2 sqrt(L^2 + t^2) (K(m) - E(m))`` at d = 0
  (:func:`.nonhertz.strip_integral`).  The reference strip (t = t_0) holds J's
  logarithmic singularity; its integral over the strip width uses J's asymptote for
  t -> 0, ``s_0 ln(4 |a| b / t^2) + R`` with ``s_0 = sqrt(L^2 - d^2)`` (the pressure
  shape at x_0), ``a = d - L < 0 < b = d + L`` and
  ``R = int_a^b (sqrt(L^2 - (v - d)^2) - s_0) / |v| dv``, integrated over t exactly, plus
  the smooth remainder at t = w / 4 (KP's treatment; at d = 0 the asymptote is KP's
  ``2 L (ln(4 L / t) - 1)``).  Hence ``c = pi E* delta / I_1``.
- **Force.**  ``N = c I_2``, ``I_2 = sum_k w_k (pi / 2) L_k^2``; peak pressure
  ``c max L_k``; the force centre is the load-weighted mean of the intervals' centres.

On ``h = g(t) + A x^2`` sampled on a grid symmetric about x = 0 every step of this
construction is KP's, and :func:`kp_surface` returns :func:`.nonhertz.kik_piotrowski`'s
force, peak pressure, extents and force centre to round-off (tests/test_kp_surface.py).
What it cannot do, as KP: the pressure is semi-elliptic along x in every interval (at a
rail end the exact pressure is singular, here it falls to zero); the region is that of a
virtual penetration; the contact condition holds at one point only.

Where the condition holds.  ``condition="deepest"`` (the default) is KP's: the deepest
point of the gap.  ``condition="centre"`` puts it at the patch's force centre instead
(row nearest to it), ``delta - h(x_c, t_c) = c I_1(x_c, t_c) / (pi E*)``; on a gap whose
force centre is its deepest point the two are one.  It was tried after the first
comparison with CONTACT and is not adopted (below).

What it measured (``python validation/kp_surface_vs_contact.py``, CONTACT's five cases at
its FN): the approach within 5 % of CONTACT's in 4 of 5 (KP on the 2-D slice: 2 of 5):
-0.6, -1.8, -4.8, -2.1 % where KP 2-D has -4.2, -1.3, -5.6, -6.5 %, and within 0.1-6.0 %
of the exact solution on the same gap.  It fails where the rail ends inside the patch
(cw_interrupt#2, -35.6 %; KP 2-D -24.8 %, the exact solution -0.8 %): there the deepest
point lies on the rail's end, at the region's edge, where the Boussinesq displacement of a
given load is about half that at an interior point, and the semi-elliptic pressure falls
to zero where the exact one is singular; the condition at the force centre overshoots
instead (+2.8 ... +15.2 %, 2 of 5).  On a paraboloid cut at x_end, no profiles involved,
KP 3-D is within 2.4 % of the exact approach while the cut is 2 mm or more from the deepest
point, -8.3 % at 1 mm, -33 % at the deepest point: the method's limit, not the geometry's.
The patch is skewed as the surfaces are, but its extent along x stays 13-18 % short of the
exact one's (the virtual penetration, as KP on the slice), and the creep forces gain
nothing: 4 of 10 within 10 % by the exact theory on the patch (KP 2-D 4), 2 of 10 by
FASTSIM on its strips (KP 2-D 5).  One call costs
2-6x KP's on the 2-D slice at the tables' resolution (2.3-6.2x and 2.2-4.1x in two runs on
a shared machine); the 3-D gap around a node costs far more (same page).

The offset strip integral has no closed form used here; it is integrated by
Gauss-Legendre on panels graded geometrically towards the point nearest the reference
point (``u = L sin(theta)`` removes the square roots at the interval's ends): 2e-10
relative against a 30-digit quadrature (mpmath, L = 5, d = -2, t = 0.02 mm), within 1e-9
of scipy's adaptive quadrature in tests/test_kp_surface.py.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from exudyn_turnout.wheel_rail.kp_creep import StripPatch
from exudyn_turnout.wheel_rail.nonhertz import EPSILON, strip_integral

__all__ = [
    "NO_SURFACE",
    "CONDITIONS",
    "SurfacePatch",
    "offset_strip_integral",
    "offset_strip_asymptote",
    "kp_surface",
    "kp_surface_at_force",
]

#: Where :func:`kp_surface` applies the contact condition (module docstring)
CONDITIONS = ("deepest", "centre")
#: m, gap values at or above this (and NaN) mean no surface there (a rail that ends)
NO_SURFACE = 0.5
_PANELS = 18  # geometrically graded panels per side of the offset strip integral
_RATIO = 0.25  # width ratio of neighbouring panels
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(10)
_CENTRED = 1e-12  # |d| / L below which the closed form at d = 0 is used


@dataclass(frozen=True, eq=False)
class SurfacePatch:
    """KP's patch on a 3-D gap: the intervals as strips, and the patch's totals (SI)."""

    #: the intervals as strips (several per grid row where the region is split along x),
    #: t and x_centre in the grid's coordinates, loads summing to the normal force
    strips: StripPatch
    approach: float  #: m, the penetration delta
    normal_force: float  #: N
    pressure_constant: float  #: Pa/m, c of ``p = c sqrt(L^2 - (x - x_c)^2)``
    p_max: float  #: Pa, peak pressure
    x_reference: float  #: m, where the contact condition holds, along x
    t_reference: float  #: m, along t
    x_centre: float  #: m, force centre along x
    t_centre: float  #: m, force centre along t
    x_low: float  #: m, the region's extent along x: first interval start
    x_high: float  #: m, last interval end
    t_low: float  #: m, lateral edge towards negative t (interpolated as KP's)
    t_high: float  #: m, lateral edge towards positive t
    area: float  #: m^2, sum of interval lengths times strip widths
    touches_edge: bool  #: the region reaches the grid's edge (grid too small)

    @property
    def length(self) -> float:
        """m, the region's extent along x."""
        return self.x_high - self.x_low

    @property
    def width(self) -> float:
        """m, the region's extent along t."""
        return self.t_high - self.t_low


def _graded_nodes(start, stop):
    """Gauss nodes and weights on panels from ``start`` to ``stop`` (arrays (n,)), graded
    geometrically towards ``start``: shape (n, panels * nodes)."""
    start = np.asarray(start, float)[:, None]
    span = (np.asarray(stop, float) - start[:, 0])[:, None]
    edges = np.concatenate(([0.0], _RATIO ** np.arange(_PANELS - 1, -1, -1)))
    low, high = edges[:-1], edges[1:]
    half = 0.5 * (high - low)
    mid = 0.5 * (high + low)
    unit = (mid[:, None] + half[:, None] * _NODES[None, :]).ravel()
    weight = (half[:, None] * _WEIGHTS[None, :]).ravel()
    return start + span * unit[None, :], span * weight[None, :]


def offset_strip_integral(half_length, offset, t) -> np.ndarray:
    """Boussinesq integral of one off-centre semi-elliptic strip at the reference point.

    ``J(L, d, t) = int_{-L}^{L} sqrt(L^2 - u^2) / sqrt((u + d)^2 + t^2) du``: the strip's
    centre lies d along x and t across from the reference point (module docstring).  At
    d = 0 it is :func:`.nonhertz.strip_integral` (used there, closed form).

    Parameters
    ----------
    half_length : array_like
        m, L (>= 0).
    offset : array_like
        m, d = strip centre minus reference point along x.
    t : array_like
        m, lateral distance (non-zero where the strip spans u = -d).

    Returns
    -------
    numpy.ndarray
        m, J (0 where L = 0), the arguments' broadcast shape.
    """
    length, d, t = np.broadcast_arrays(
        np.asarray(half_length, float), np.asarray(offset, float), np.abs(np.asarray(t, float))
    )
    shape = length.shape
    length, d, t = length.ravel(), d.ravel(), t.ravel()
    out = np.zeros(length.size)
    live = length > 0.0
    centred = live & (np.abs(d) <= _CENTRED * length)
    out[centred] = strip_integral(length[centred], t[centred])
    rest = live & ~centred
    if np.any(rest):
        big, dd, tt = length[rest], d[rest], t[rest]
        pivot = np.arcsin(np.clip(-dd / big, -1.0, 1.0))
        total = np.zeros(big.size)
        for stop in (0.5 * np.pi, -0.5 * np.pi):
            theta, weight = _graded_nodes(pivot, np.full(big.size, stop))
            u = big[:, None] * np.sin(theta)
            cosine = np.cos(theta)
            f = (big[:, None] * cosine) ** 2 / np.hypot(u + dd[:, None], tt[:, None])
            total += np.abs(np.sum(f * weight, axis=1))
        out[rest] = total
    return out.reshape(shape)


def offset_strip_asymptote(half_length: float, offset: float) -> tuple[float, float]:
    """J's behaviour for t -> 0 where the strip spans the reference point (|d| < L).

    ``J(L, d, t) = s_0 ln(4 |a| b / t^2) + R + o(1)``, returned as ``(s_0, C)`` with
    ``C = s_0 ln(4 |a| b) + R`` (module docstring; at d = 0, ``s_0 = L`` and
    ``C = 2 L ln(2 L) + 2 L (ln 2 - 1)``, KP's ``2 L (ln(4 L / t) - 1)``).

    Parameters
    ----------
    half_length : float
        m, L (> 0).
    offset : float
        m, d (|d| < L).

    Returns
    -------
    tuple of float
        (s_0 in m, C in m).
    """
    length, d = float(half_length), float(offset)
    if abs(d) <= _CENTRED * length:
        return length, 2.0 * length * math.log(2.0 * length) + 2.0 * length * (math.log(2.0) - 1.0)
    s0 = math.sqrt(length * length - d * d)
    pivot = math.asin(-d / length)
    remainder = 0.0
    for stop, sign in ((0.5 * math.pi, 1.0), (-0.5 * math.pi, -1.0)):
        theta, weight = _graded_nodes(np.array([pivot]), np.array([stop]))
        v = length * np.sin(theta) + d
        shape = length * np.cos(theta)
        # (s - s0) / |v| with s - s0 = (s^2 - s0^2) / (s + s0) = -v (v - 2 d) / (s + s0)
        f = -np.sign(v) * (v - 2.0 * d) / (shape + s0) * shape
        remainder += sign * float(np.sum(f * weight))
    return s0, s0 * math.log(4.0 * (length - d) * (length + d)) + remainder


def _crossing(h_in, h_out, h_back, level, outside_surface):
    """Fraction of a step from the last sample inside to the first outside where the gap
    reaches ``level``: on the parabola through (back, in, out), else linear; 0.5 where
    there is no surface outside."""
    q2 = 0.5 * (h_out - 2.0 * h_in + h_back)
    q1 = 0.5 * (h_out - h_back)
    q0 = h_in - level
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        linear = np.clip((level - h_in) / (h_out - h_in), 0.0, 1.0)
        disc = q1 * q1 - 4.0 * q2 * q0
        root = np.sqrt(np.maximum(disc, 0.0))
        big = -0.5 * (q1 + np.where(q1 >= 0.0, root, -root))
        r1 = big / q2
        r2 = q0 / big
        ok1 = (r1 >= 0.0) & (r1 <= 1.0)
        ok2 = (r2 >= 0.0) & (r2 <= 1.0)
        s = np.where(ok2, r2, np.where(ok1, r1, linear))
        usable = np.isfinite(h_back) & (disc >= 0.0) & (ok1 | ok2)
    s = np.where(usable, s, linear)
    return np.where(outside_surface, 0.5, np.nan_to_num(s, nan=0.5))


def _intervals(h, inside, level, dx):
    """(row, first, last, lower fraction, upper fraction) of every run of ``inside``."""
    nx = h.shape[0]
    padded = np.zeros((nx + 2, h.shape[1]), dtype=np.int8)
    padded[1:-1] = inside
    change = np.diff(padded, axis=0)
    start_i, start_j = np.nonzero(change == 1)
    stop_i, stop_j = np.nonzero(change == -1)
    order_a = np.lexsort((start_i, start_j))
    order_b = np.lexsort((stop_i, stop_j))
    rows = start_j[order_a]
    first = start_i[order_a]
    last = stop_i[order_b] - 1
    surface = np.isfinite(h) & (h < NO_SURFACE)
    hh = np.where(surface, h, np.inf)

    def end(index, step):
        out_index = index + step
        back_index = index - step
        valid_out = (out_index >= 0) & (out_index < nx)
        o = np.clip(out_index, 0, nx - 1)
        b = np.clip(back_index, 0, nx - 1)
        h_in = hh[index, rows]
        h_out = np.where(valid_out, hh[o, rows], np.inf)
        h_back = np.where((back_index >= 0) & (back_index < nx), hh[b, rows], np.nan)
        h_back = np.where(np.isfinite(h_back), h_back, np.nan)
        no_surface = ~np.isfinite(h_out)
        return _crossing(h_in, np.where(no_surface, h_in, h_out), h_back, level, no_surface)

    low = end(first, -1)
    high = end(last, 1)
    edge = bool(np.any(first == 0) or np.any(last == nx - 1))
    return rows, first, last, low, high, edge


def _boussinesq_integral(half, offset, t_rel, on_reference_row, dt: float) -> float:
    """I_1 of the module docstring: the strips' Boussinesq integrals at the reference point
    (midpoint across each strip; the strip through the point by its asymptote)."""
    spans = on_reference_row & (np.abs(offset) < half)
    others = ~spans
    i1 = float(np.sum(offset_strip_integral(half[others], offset[others], t_rel[others]))) * dt
    quarter = 0.25 * dt
    for k in np.nonzero(spans)[0]:
        s0, const = offset_strip_asymptote(float(half[k]), float(offset[k]))
        asym = dt * (const - 2.0 * s0 * (math.log(0.5 * dt) - 1.0))
        asym_quarter = const - 2.0 * s0 * math.log(quarter)
        exact_quarter = float(offset_strip_integral(half[k], offset[k], quarter))
        i1 += asym + dt * (exact_quarter - asym_quarter)
    return i1


def kp_surface(
    gap, x, t, delta: float, modulus: float, epsilon: float = EPSILON, condition: str = "deepest"
) -> SurfacePatch:
    """Kik-Piotrowski's method on a sampled 3-D gap (the module docstring).

    Parameters
    ----------
    gap : array_like
        m, (nx, nt) undeformed normal gap h(x_i, t_j) (any constant offset: its minimum
        is taken as zero); NaN or >= :data:`NO_SURFACE` where there is no surface.
    x : array_like
        m, (nx,) uniform positions along the rolling direction.
    t : array_like
        m, (nt,) uniform positions along the lateral tangent.
    delta : float
        m, penetration (approach of the bodies at the reference point), > 0.
    modulus : float
        Pa, contact modulus E*.
    epsilon : float
        Virtual-penetration factor.
    condition : str
        Where the contact condition holds (:data:`CONDITIONS`): "deepest", KP's reference
        point; "centre", the force centre (module docstring).

    Returns
    -------
    SurfacePatch

    Raises
    ------
    ValueError
        For an unknown condition; if the shapes disagree, a grid has fewer than three
        points or is not uniform and increasing, or delta or the modulus is not positive.
    """
    if condition not in CONDITIONS:
        raise ValueError(f"condition must be one of {CONDITIONS}, not {condition!r}")
    h = np.array(gap, float)
    x = np.asarray(x, float)
    t = np.asarray(t, float)
    if h.ndim != 2 or h.shape != (x.size, t.size) or x.size < 3 or t.size < 3:
        raise ValueError(f"gap must have shape (len(x), len(t)) >= (3, 3), not {h.shape}")
    dx, dt = float(x[1] - x[0]), float(t[1] - t[0])
    for grid, step in ((x, dx), (t, dt)):
        if not step > 0.0 or not np.allclose(np.diff(grid), step, rtol=1e-9, atol=0.0):
            raise ValueError("x and t must be uniform and increasing")
    if not delta > 0.0 or not modulus > 0.0:
        raise ValueError(f"delta and modulus must be positive, not {delta!r}, {modulus!r}")
    surface = np.isfinite(h) & (h < NO_SURFACE)
    h = np.where(surface, h, np.inf)
    i0, j0 = np.unravel_index(int(np.argmin(h)), h.shape)
    # the reference point: the vertex of the parabola along x through the deepest sample
    x0, h0 = float(x[i0]), float(h[i0, j0])
    if 0 < i0 < x.size - 1 and np.isfinite(h[i0 - 1, j0]) and np.isfinite(h[i0 + 1, j0]):
        q2 = 0.5 * (h[i0 + 1, j0] - 2.0 * h[i0, j0] + h[i0 - 1, j0])
        q1 = 0.5 * (h[i0 + 1, j0] - h[i0 - 1, j0])
        if q2 > 0.0:
            s = float(np.clip(-q1 / (2.0 * q2), -0.5, 0.5))
            x0, h0 = x0 + s * dx, float(h[i0, j0] + q1 * s + q2 * s * s)
    h = h - h0
    level = epsilon * delta
    labels, _count = ndimage.label(h < level)
    region = labels == labels[i0, j0]
    rows, first, last, low, high, edge = _intervals(h, region, level, dx)
    x1 = x[first] - low * dx
    x2 = x[last] + high * dx
    half = 0.5 * (x2 - x1)
    centre_x = 0.5 * (x1 + x2)
    i2 = 0.5 * math.pi * float(np.sum(half * half)) * dt
    share = half * half
    weight = float(np.sum(share))
    t_centre = float(np.sum(share * t[rows]) / weight)
    x_centre = float(np.sum(share * centre_x) / weight)
    j_ref, x_ref, h_ref = int(j0), x0, 0.0
    if condition == "centre":
        j_ref = int(np.argmin(np.abs(t - t_centre)))
        x_ref = x_centre
        h_ref = float(np.interp(x_centre, x, h[:, j_ref]))
        if not np.isfinite(h_ref) or h_ref >= delta:  # no surface there: KP's point
            j_ref, x_ref, h_ref = int(j0), x0, 0.0
    i1 = _boussinesq_integral(half, centre_x - x_ref, t[rows] - t[j_ref], rows == j_ref, dt)
    c = math.pi * modulus * (delta - h_ref) / i1 if i1 > 0.0 else 0.0
    force = c * i2
    load = share * force / float(np.sum(share * dt)) if force > 0.0 else share * 0.0
    # lateral edges: the rows' smallest gap crossing the level, interpolated as KP's
    row_min = np.min(h, axis=0)
    j_low, j_high = int(rows.min()), int(rows.max())

    def edge_fraction(inner: int, outer: int) -> float:
        if outer < 0 or outer >= t.size or not np.isfinite(row_min[outer]):
            return 0.5
        g_in, g_out = row_min[inner], row_min[outer]
        if g_out == g_in:
            return 0.5
        return float(np.clip((level - g_in) / (g_out - g_in), 0.0, 1.0))

    t_low = float(t[j_low] - edge_fraction(j_low, j_low - 1) * dt)
    t_high = float(t[j_high] + edge_fraction(j_high, j_high + 1) * dt)
    edge = edge or j_low == 0 or j_high == t.size - 1
    area = 2.0 * float(np.sum(half)) * dt
    width = max(0.5 * (t_high - t_low), 1e-12)
    length = float(half.max())
    a_eq = math.sqrt(area / math.pi * length / width)
    strips = StripPatch(
        t=t[rows].astype(float),
        width=np.full(rows.size, dt),
        half_length=half,
        x_centre=centre_x,
        load=load,
        normal_force=force,
        centre=t_centre,
        a=a_eq,
        b=area / (math.pi * a_eq),
    )
    return SurfacePatch(
        strips=strips,
        approach=float(delta),
        normal_force=force,
        pressure_constant=c,
        p_max=c * length,
        x_reference=x_ref,
        t_reference=float(t[j_ref]),
        x_centre=x_centre,
        t_centre=t_centre,
        x_low=float(x1.min()),
        x_high=float(x2.max()),
        t_low=t_low,
        t_high=t_high,
        area=area,
        touches_edge=edge,
    )


def kp_surface_at_force(
    gap,
    x,
    t,
    force: float,
    modulus: float,
    epsilon: float = EPSILON,
    condition: str = "deepest",
    iterations: int = 60,
) -> SurfacePatch:
    """:func:`kp_surface` at the penetration that carries a normal force (bisection in
    log delta between 1e-8 and 2e-3 m, as ``references.contact_at_reference`` solves KP).

    Parameters
    ----------
    gap, x, t : array_like
        As :func:`kp_surface`.
    force : float
        N, normal force (> 0).
    modulus : float
        Pa, contact modulus E*.
    epsilon : float
        Virtual-penetration factor.
    condition : str
        Where the contact condition holds (:func:`kp_surface`).
    iterations : int
        Bisection steps (60: delta to about 1e-16 relative).

    Returns
    -------
    SurfacePatch

    Raises
    ------
    ValueError
        If the force is not positive.
    """
    if not force > 0.0:
        raise ValueError(f"force must be positive, not {force!r}")
    low, high = 1e-8, 2e-3
    for _ in range(iterations):
        mid = math.sqrt(low * high)
        if kp_surface(gap, x, t, mid, modulus, epsilon, condition).normal_force < force:
            low = mid
        else:
            high = mid
    return kp_surface(gap, x, t, math.sqrt(low * high), modulus, epsilon, condition)
