"""Semi-Hertzian normal contact (Kik-Piotrowski) where the Hertz ellipse does not fit.

Why a second normal-contact method
----------------------------------
Hertz theory (:mod:`.hertz`) assumes a gap ``A x^2 + B y^2`` over the whole patch.  On the
flat back of the flange against a check-rail face (B floored at
:data:`.hertz.MIN_CURVATURE_SUM`, A = cos(84 deg) / (2 r)) it gave a lateral semi-axis of
172 mm on a face about 25 mm high (issue 22); on the flange of the switch blade and at the
nose the tables held ellipses over 300 mm wide (validation/contact_vs_contact.md); at the
gauge corner of worn or conformal profiles the curvature sum is floored or changes sign
within the patch.  There the patch, its pressure and the normal stiffness must follow
from the real gap of the undeformed surfaces.

Choice.  Three published families were weighed:

- *Multi-Hertzian* (a Hertz ellipse per minimum of the gap) still takes each ellipse from
  local curvatures, so a flat face keeps its 172 mm axis unless it is cut off by hand;
- *STRIPES* (Ayasse & Chollet, "Determination of the wheel rail contact patch in
  semi-Hertzian conditions", VSD 43 (2005) 161-172) is semi-Hertzian as well (Hertz-like
  along x in every strip, the lateral extent from a corrected interpenetration) but
  works with curvatures per strip, which the tables hold only at the contact point;
- *Kik-Piotrowski* (J. Piotrowski & W. Kik, "A simplified model of wheel/rail contact
  mechanics for non-Hertzian problems and its application in rail vehicle dynamic
  simulations", VSD 46 (2008) 27-48) needs only the lateral gap function g(y) of the
  undeformed profiles and the rolling-direction curvature: no lateral curvature at all,
  so a flat face or a conformal region is no special case, and it is non-iterative.

Kik-Piotrowski (KP) is used: the tables hold the undeformed profiles at every node, the
gap function follows from them directly, the method needs no curvature where curvatures
are meaningless (flat faces, corners), and its two integrals per penetration are cheap
enough to be tabulated per node.  Its known weakness (the contact area is that of a
*virtual* penetration, so the patch shape is approximate; the pressure is semi-elliptic
along x in every strip) is stated with the comparisons against CONTACT
(``validation/contact_vs_contact.md``) and measured against the exact half-space solution
on the same gap (:mod:`.exact_normal`; ``validation/normal_vs_contact.md``: on CONTACT's
five cases KP's approach is 0.2-5.8 % below the exact one and its patch 13-16 % short
along x; on a wedge, two radii and a flat face -6.3, -5.1 and +4.7 %,
tests/test_nonhertz_exact.py).  In three of those five cases the larger error of the
approach is the 2-D slice the method works on, not the method (the same page).

The method (Piotrowski & Kik 2008)
----------------------------------
With the normal gap ``g(t) >= 0`` of the undeformed surfaces along the lateral tangent t
(0 at the contact point) and the relative curvature A in the rolling direction:

- the contact area is the interpenetration region of a *virtual* penetration
  ``delta_0 = epsilon delta`` (``epsilon`` = :data:`EPSILON` = 0.55, their value):
  ``|x| <= x_l(t) = sqrt((delta_0 - g(t)) / A)`` on the connected run of
  ``g < delta_0`` around the contact point;
- the pressure is semi-elliptic along x in every strip,
  ``p(x, t) = c sqrt(x_l(t)^2 - x^2)`` (for a Hertz gap this is Hertz's pressure);
- c follows from the contact condition at the contact point only: the surfaces' normal
  displacement there (Boussinesq, two identical half-spaces) equals the penetration,
  ``delta = 1 / (pi E*) int int p / sqrt(x^2 + t^2) dx dt``, so
  ``c = pi E* delta / I_1`` with ``I_1 = int J(x_l(t), t) dt`` and the strip integral
  ``J(L, t) = int_{-L}^{L} sqrt(L^2 - x^2) / sqrt(x^2 + t^2) dx
  = 2 sqrt(L^2 + t^2) (K(m) - E(m))``, ``m = L^2 / (L^2 + t^2)`` (complete elliptic
  integrals; derived here by x = L sin(theta));
- the normal force ``N = c I_2`` with ``I_2 = int (pi / 2) x_l(t)^2 dt``, and the peak
  pressure ``c max_t x_l(t)``.

For the creep law the patch is replaced by the ellipse of the same area and the same
ratio of length to width, the "equivalent ellipse" through which Piotrowski & Kik (2008)
give FASTSIM its flexibility for a non-elliptic patch (see also the review of Piotrowski &
Chollet, VSD 43 (2005) 455-483); here it feeds Kalker's coefficients and the creep law
(the FASTSIM table of :mod:`.creep_table` by default, or Polach's).

Where Hertz is kept.  Hertz's ellipse is exact where the gap is Hertzian, so it stays
wherever it *fits the surfaces*: at both reference penetrations
(:data:`.node_laws.DELTA_LOW`, :data:`.node_laws.DELTA_HIGH`) its lateral semi-axis must lie
inside the region where the undeformed surfaces come closer than that penetration, and
neither curvature sum may be floored (:func:`hertz_misfit`: the semi-axis over the distance
to that region's nearer edge).
Where the ellipse overshoots by :data:`MISFIT_FULL` (2) or more (flat faces, corners of
finite width, conformal points) KP alone is used, and in between the two laws are blended
linearly in the misfit.  The blend keeps the law continuous in the geometry: with a hard
switch, neighbouring table nodes on a plain rail's tread (0.2 mm of shift apart, where the
ellipse only just fails to fit) jumped between laws whose forces differ by up to 23 %.

A law per table node
--------------------
The kernel evaluates every contact of every step; KP's integrals are too slow there.  At
each table node the normal force, and the equivalent semi-axes, are evaluated at
:data:`.node_laws.DELTA_LOW` and :data:`.node_laws.DELTA_HIGH` and stored as a power law
through both (:func:`patch_law`; the laws themselves, their compiled evaluation for the
kernel and the tables' lookup, KP's force centre and the contact point on the rail surface
are in :mod:`.node_laws`).  A Hertz node has n = 1.5 and exponents 0.5 for a and b, i.e.
exactly ``C_H delta^1.5``.  How far the power law is from KP in between and outside is
measured in tests/test_wheel_rail_nonhertz.py.

Gap function.  The table search finds each contact point in one of a few frames (vertical,
and the tilted search directions of :mod:`.geometry`); the gap in the frame closest to the
contact angle is sampled around the point and turned into the normal gap to first order:
``g(t) = cos(D) g_theta(v_c + t cos(D))`` with D the angle between contact normal and
search direction (|D| <= 30 deg; exact for parallel surfaces, otherwise correct to first
order in the gap's slope).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.special import ellipe, ellipk

from exudyn_turnout.wheel_rail.geometry import Candidates, PreparedRail, PreparedWheel
from exudyn_turnout.wheel_rail.hertz import (
    MIN_CURVATURE_SUM,
    effective_modulus,
    hertz_constant,
    hertz_contact,
)
from exudyn_turnout.wheel_rail.node_laws import (
    DELTA_HIGH,
    DELTA_LOW,
    DELTA_REF,
    centre_exponent,
    centre_offset_law,
)

__all__ = [
    "EPSILON",
    "GAP_STEP",
    "GAP_WINDOW",
    "PATCH_FIELDS",
    "SemiHertzPatch",
    "strip_integral",
    "kik_piotrowski",
    "force_centre",
    "normal_gap_function",
    "MISFIT_FULL",
    "hertz_misfit",
    "hertz_fits",
    "semi_hertz_weight",
    "patch_law",
    "patch_law_fields",
]

#: Kik-Piotrowski's virtual-penetration factor, delta_0 = EPSILON delta (their value)
EPSILON = 0.55
#: Misfit (Hertz's lateral semi-axis over the surfaces' reach) from which KP alone is used
MISFIT_FULL = 2.0
#: m, lateral step of the sampled gap function in the tables
GAP_STEP = 1e-4
#: m, the gap function is sampled this far either side of the contact point
GAP_WINDOW = 0.03
#: Names of the per-node law fields (:func:`patch_law`), in their order.
PATCH_FIELDS = (
    "patch_force",  # N, normal force at DELTA_REF
    "patch_force_exponent",  # n of N = N_ref (delta / DELTA_REF)^n
    "patch_a",  # m, semi-axis (rolling direction) at DELTA_REF
    "patch_a_exponent",  # its exponent
    "patch_b",  # m, lateral semi-axis at DELTA_REF
    "patch_b_exponent",  # its exponent
    "semi_hertzian",  # weight of the Kik-Piotrowski law: 0 Hertz fits ... 1 KP alone
    "patch_centre",  # m, KP's force centre at DELTA_REF along the lateral tangent (every node)
    "patch_centre_exponent",  # m of the centre's law c_ref (delta / DELTA_REF)^m
    # the rail surface's offset w along the contact normal from the tangent line at the
    # force centre c, w = a c^2 + b c^3 (:func:`.node_laws.node_offset`), so that the contact
    # position lies on the rail surface (:func:`.node_laws.surface_offset`,
    # :func:`.node_laws.centre_point`)
    "patch_offset_c2",  # 1/m, a
    "patch_offset_c3",  # 1/m^2, b
)
_UNREACHABLE = 1.0  # m, gap written where no surface is (never inside a patch)


@dataclass(frozen=True, eq=False)
class SemiHertzPatch:
    """Kik-Piotrowski patch of one or several contacts (arrays over contacts)."""

    normal_force: np.ndarray  #: N
    p_max: np.ndarray  #: Pa, peak pressure
    half_length: np.ndarray  #: m, largest half-length along x (rolling direction)
    t_low: np.ndarray  #: m, lateral edge of the patch towards negative t
    t_high: np.ndarray  #: m, lateral edge towards positive t
    area: np.ndarray  #: m^2, contact area
    a: np.ndarray  #: m, equivalent ellipse, rolling direction (same area, same L/W)
    b: np.ndarray  #: m, equivalent ellipse, lateral
    t_centre: np.ndarray  #: m, lateral position of the normal force's line of action


def strip_integral(half_length, t) -> np.ndarray:
    """Boussinesq integral of one strip's semi-elliptic pressure at the contact point.

    ``J(L, t) = int_{-L}^{L} sqrt(L^2 - x^2) / sqrt(x^2 + t^2) dx
    = 2 sqrt(L^2 + t^2) (K(m) - E(m))``, ``m = L^2 / (L^2 + t^2)`` (substitute
    x = L sin(theta); one strip of Piotrowski & Kik's contact condition).

    Parameters
    ----------
    half_length : array_like
        m, half-length L of the strip (>= 0).
    t : array_like
        m, lateral distance of the strip from the contact point (non-zero where L > 0).

    Returns
    -------
    numpy.ndarray
        m, J (0 where L = 0).
    """
    length = np.asarray(half_length, float)
    t = np.abs(np.asarray(t, float))
    radius2 = length * length + t * t
    with np.errstate(divide="ignore", invalid="ignore"):
        m = np.where(radius2 > 0.0, length * length / radius2, 0.0)
    m = np.minimum(m, 1.0 - 1e-16)
    return np.where(length > 0.0, 2.0 * np.sqrt(radius2) * (ellipk(m) - ellipe(m)), 0.0)


def _connected_run(inside: np.ndarray) -> np.ndarray:
    """Mask of the run of True around the centre column of each row."""
    centre = inside.shape[-1] // 2
    right = np.cumprod(inside[..., centre:], axis=-1).astype(bool)
    left = np.cumprod(inside[..., centre::-1], axis=-1).astype(bool)[..., ::-1]
    return np.concatenate((left[..., :-1], right), axis=-1)


def kik_piotrowski(gap, step: float, a_sum, delta, modulus: float, epsilon: float = EPSILON):
    """Kik-Piotrowski normal contact on sampled gap functions (Piotrowski & Kik 2008).

    Parameters
    ----------
    gap : array_like
        m, (n, n_t) normal gap of the undeformed surfaces along the lateral tangent, on
        ``t = (k - n_t // 2) step``: the contact point is the centre column (gap 0 there);
        NaN or large where there is no surface.
    step : float
        m, lateral sample step.
    a_sum : array_like
        1/m, (n,) relative curvature in the rolling direction (half the curvature sum).
    delta : array_like
        m, (n,) or scalar penetration (> 0).
    modulus : float
        Pa, contact modulus E*.
    epsilon : float
        Virtual-penetration factor.

    Returns
    -------
    SemiHertzPatch
    """
    gap = np.nan_to_num(np.atleast_2d(np.asarray(gap, float)), nan=_UNREACHABLE)
    n, n_t = gap.shape
    a_sum = np.broadcast_to(np.asarray(a_sum, float), (n,))
    delta = np.broadcast_to(np.asarray(delta, float), (n,))
    centre = n_t // 2
    t = (np.arange(n_t) - centre) * step
    virtual = (epsilon * delta)[:, None]
    run = _connected_run(gap < virtual)
    depth = np.where(run, virtual - gap, 0.0)
    half = np.sqrt(depth / a_sum[:, None])
    i2 = 0.5 * np.pi * np.sum(half * half, axis=1) * step
    strips = strip_integral(half, np.where(t == 0.0, step, t)) * step
    strips[:, centre] = 0.0
    # the centre strip holds J's logarithmic singularity at t = 0: its asymptote
    # 2 L (ln(4 L / t) - 1) integrated exactly, plus the smooth remainder (midpoint)
    h0 = half[:, centre]
    with np.errstate(divide="ignore", invalid="ignore"):
        asym = 2.0 * h0 * step * np.log(8.0 * h0 / step)
        quarter = 0.25 * step
        rest = strip_integral(h0, quarter) - 2.0 * h0 * (np.log(4.0 * h0 / quarter) - 1.0)
    centre_strip = np.where(h0 > 0.0, asym + step * rest, 0.0)
    i1 = np.sum(strips, axis=1) + centre_strip
    with np.errstate(divide="ignore", invalid="ignore"):
        c = np.where(i1 > 0.0, np.pi * modulus * delta / i1, 0.0)
    force = c * i2
    t_centre = _centre(depth, t)
    length = np.max(half, axis=1)
    area = 2.0 * np.sum(half, axis=1) * step
    # lateral edges, interpolated where the gap crosses the virtual penetration
    first = np.argmax(run, axis=1)
    last = n_t - 1 - np.argmax(run[:, ::-1], axis=1)
    t_low = t[first] - _edge_fraction(gap, virtual[:, 0], first, first - 1) * step
    t_high = t[last] + _edge_fraction(gap, virtual[:, 0], last, last + 1) * step
    width = np.maximum(0.5 * (t_high - t_low), 1e-12)
    with np.errstate(divide="ignore", invalid="ignore"):
        a_eq = np.sqrt(area / np.pi * length / width)
        b_eq = np.where(a_eq > 0.0, area / (np.pi * a_eq), 0.0)
    return SemiHertzPatch(
        normal_force=force,
        p_max=c * length,
        half_length=length,
        t_low=t_low,
        t_high=t_high,
        area=area,
        a=np.nan_to_num(a_eq),
        b=np.nan_to_num(b_eq),
        t_centre=t_centre,
    )


def _edge_fraction(gap: np.ndarray, level: np.ndarray, inner: np.ndarray, outer: np.ndarray):
    """Fraction of a step beyond ``inner`` where the gap reaches ``level`` (linear)."""
    rows = np.arange(gap.shape[0])
    outside = (outer < 0) | (outer >= gap.shape[1])
    outer = np.clip(outer, 0, gap.shape[1] - 1)
    g_in, g_out = gap[rows, inner], gap[rows, outer]
    with np.errstate(divide="ignore", invalid="ignore"):
        fraction = (level - g_in) / (g_out - g_in)
    return np.where(outside, 0.5, np.clip(np.nan_to_num(fraction, nan=0.5), 0.0, 1.0))


def _centre(depth: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Force centre of strips loaded as their depth below the virtual penetration."""
    # every strip carries (pi / 2) c x_l(t)^2 = (pi / 2) c depth / A: the force acts at the
    # depth-weighted mean t
    total = np.sum(depth, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(total > 0.0, np.sum(depth * t, axis=1) / total, 0.0)


def force_centre(gap, step: float, delta, epsilon: float = EPSILON) -> np.ndarray:
    """Where Kik-Piotrowski's normal force acts, along the lateral tangent (Piotrowski & Kik
    2008).

    Every strip of the virtual interpenetration region carries ``(pi / 2) c x_l(t)^2``
    with ``x_l(t)^2 = (epsilon delta - g(t)) / A``, so the force acts at the mean of t
    weighted by ``epsilon delta - g(t)`` over the connected run around the contact point;
    neither the modulus nor the rolling-direction curvature enters.  Equal to
    :attr:`SemiHertzPatch.t_centre` of :func:`kik_piotrowski`.  For a gap symmetric about
    the contact point (Hertz) it is the contact point; where the gap is not (a flat nose
    top beside its flank) it moves towards the flatter side, as CONTACT's contact
    reference does (validation/contact_vs_contact.md).

    Parameters
    ----------
    gap : array_like
        m, (n, n_t) normal gap functions (:func:`normal_gap_function`), the contact point
        in the centre column.
    step : float
        m, their sample step.
    delta : array_like
        m, (n,) or scalar penetration (> 0).
    epsilon : float
        Virtual-penetration factor.

    Returns
    -------
    numpy.ndarray
        m, (n,) position of the force's line of action from the contact point along the
        lateral tangent ``(cos(gamma), sin(gamma))`` in side coordinates (y, z).
    """
    gap = np.nan_to_num(np.atleast_2d(np.asarray(gap, float)), nan=_UNREACHABLE)
    n, n_t = gap.shape
    delta = np.broadcast_to(np.asarray(delta, float), (n,))
    t = (np.arange(n_t) - n_t // 2) * step
    virtual = (epsilon * delta)[:, None]
    run = _connected_run(gap < virtual)
    return _centre(np.where(run, virtual - gap, 0.0), t)


def _frames(rail: PreparedRail, wheel: PreparedWheel) -> list:
    """Search frames: (theta, v grid, rail surface, wheel v, wheel surface); vertical first."""
    frames = [(0.0, rail.y, rail.z, wheel.y, wheel.z)]
    for (theta, v_grid, rail_w, _dw, _k), wheel_frame in zip(
        rail.directions, wheel.directions, strict=False
    ):
        wheel_v, wheel_w = wheel_frame[1], wheel_frame[2]
        frames.append((float(theta), v_grid, rail_w, wheel_v, wheel_w))
    return frames


def normal_gap_function(
    rail: PreparedRail,
    wheel: PreparedWheel,
    shift,
    y_rail,
    z_rail,
    angle,
    step: float = GAP_STEP,
    window: float = GAP_WINDOW,
    lift: float = 0.0,
) -> np.ndarray:
    """Normal gap of the undeformed surfaces along the lateral tangent of contact points.

    Parameters
    ----------
    rail, wheel : PreparedRail, PreparedWheel
        The section and the wheel as the candidate search used them (zero lift).
    shift : array_like
        m, (n,) the wheel's lateral shift of each contact point.
    y_rail, z_rail, angle : array_like
        m, m, rad, (n,) contact point on the rail and contact angle.
    step, window : float
        m, sample step and half-width of the window around each point.
    lift : float
        m, the wheel's lift (the tables' nodes: 0).

    Returns
    -------
    numpy.ndarray
        m, (n, 2 round(window / step) + 1) normal gap on ``t = (k - centre) step``, zero at
        its minimum near the centre, :data:`_UNREACHABLE` where there is no surface.
    """
    shift = np.atleast_1d(np.asarray(shift, float))
    y_rail = np.atleast_1d(np.asarray(y_rail, float))
    z_rail = np.atleast_1d(np.asarray(z_rail, float))
    angle = np.atleast_1d(np.asarray(angle, float))
    half = int(round(window / step))
    t = np.arange(-half, half + 1) * step
    out = np.full((len(angle), len(t)), _UNREACHABLE)
    frames = _frames(rail, wheel)
    thetas = np.array([f[0] for f in frames])
    choice = np.argmin(np.abs(angle[:, None] - thetas[None, :]), axis=1)
    for index, (theta, v_grid, rail_w, wheel_v, wheel_w) in enumerate(frames):
        rows = np.nonzero(choice == index)[0]
        if rows.size == 0:
            continue
        c, s = math.cos(theta), math.sin(theta)
        tilt = np.cos(angle[rows] - theta)
        v_c = c * y_rail[rows] + s * z_rail[rows]
        v = v_c[:, None] + t[None, :] * tilt[:, None]
        dv, dw = shift[rows] * c + lift * s, -shift[rows] * s + lift * c
        local = v - dv[:, None]
        inside = (local >= wheel_v[0]) & (local <= wheel_v[-1])
        inside &= (v >= v_grid[0]) & (v <= v_grid[-1])
        wheel_surface = np.interp(local, wheel_v, wheel_w) + dw[:, None]
        rail_surface = np.interp(v, v_grid, rail_w)
        gap = np.where(inside, wheel_surface - rail_surface, np.nan)
        gap = np.where(np.isfinite(gap), gap, np.inf)
        centre = len(t) // 2
        near = max(int(round(5e-4 / step)), 1)
        g0 = np.min(gap[:, centre - near : centre + near + 1], axis=1)
        g0 = np.where(np.isfinite(g0), g0, 0.0)
        normal = tilt[:, None] * np.maximum(gap - g0[:, None], 0.0)
        out[rows] = np.where(np.isfinite(normal), np.minimum(normal, _UNREACHABLE), _UNREACHABLE)
    return out


def hertz_misfit(gap, step: float, a_sum, b_sum, modulus: float) -> np.ndarray:
    """How far the Hertz ellipse overshoots the surfaces (see the module docstring).

    Parameters
    ----------
    gap : array_like
        m, (n, n_t) normal gap functions (:func:`normal_gap_function`).
    step : float
        m, their sample step.
    a_sum, b_sum : array_like
        1/m, (n,) unfloored relative curvatures (rolling, lateral).
    modulus : float
        Pa, contact modulus E*.

    Returns
    -------
    numpy.ndarray
        (n,): the larger, over :data:`.node_laws.DELTA_LOW` and
        :data:`.node_laws.DELTA_HIGH`, of Hertz's lateral semi-axis divided by the distance
        from the contact point to the nearer edge of the region where the undeformed gap is
        below that penetration (<= 1: the ellipse fits); infinite where a curvature sum is at
        or below :data:`.hertz.MIN_CURVATURE_SUM`.
    """
    gap = np.nan_to_num(np.atleast_2d(np.asarray(gap, float)), nan=_UNREACHABLE)
    a_sum = np.broadcast_to(np.asarray(a_sum, float), gap.shape[:1])
    b_sum = np.broadcast_to(np.asarray(b_sum, float), gap.shape[:1])
    floored = (a_sum <= MIN_CURVATURE_SUM) | (b_sum <= MIN_CURVATURE_SUM)
    a_f, b_f = np.maximum(a_sum, MIN_CURVATURE_SUM), np.maximum(b_sum, MIN_CURVATURE_SUM)
    constant = hertz_constant(a_f, b_f, modulus)
    n, n_t = gap.shape
    centre = n_t // 2
    ratio = np.zeros(n)
    for delta in (DELTA_LOW, DELTA_HIGH):
        ellipse = hertz_contact(a_f, b_f, constant * delta**1.5, modulus)
        run = _connected_run(gap < delta)
        stop = np.ones((n, 1), dtype=bool)  # a run reaching the window's end stops there
        left = np.argmax(np.concatenate((~run[:, centre::-1], stop), axis=1), axis=1)
        right = np.argmax(np.concatenate((~run[:, centre:], stop), axis=1), axis=1)
        reach = (np.minimum(left, right) - 0.5) * step
        ratio = np.maximum(ratio, ellipse.b / reach)
    return np.where(floored, np.inf, ratio)


def hertz_fits(gap, step: float, a_sum, b_sum, modulus: float) -> np.ndarray:
    """Whether the Hertz ellipse fits the surfaces: :func:`hertz_misfit` <= 1.

    Parameters
    ----------
    gap : array_like
        m, (n, n_t) normal gap functions (:func:`normal_gap_function`).
    step : float
        m, their sample step.
    a_sum, b_sum : array_like
        1/m, (n,) unfloored relative curvatures (rolling, lateral).
    modulus : float
        Pa, contact modulus E*.

    Returns
    -------
    numpy.ndarray
        bool (n,).
    """
    return hertz_misfit(gap, step, a_sum, b_sum, modulus) <= 1.0


def semi_hertz_weight(misfit) -> np.ndarray:
    """Weight of the Kik-Piotrowski law in a node's law, from :func:`hertz_misfit`.

    0 where the ellipse fits (misfit <= 1), 1 from :data:`MISFIT_FULL` on, linear in
    between, so that the law is continuous in the geometry and neighbouring table nodes do
    not jump between the methods.

    Parameters
    ----------
    misfit : array_like
        Misfit ratio (-).

    Returns
    -------
    numpy.ndarray
        Weight in [0, 1].
    """
    misfit = np.asarray(misfit, float)
    return np.clip((misfit - 1.0) / (MISFIT_FULL - 1.0), 0.0, 1.0)


def patch_law(gap, step: float, a_sum, b_sum, modulus: float) -> np.ndarray:
    """Per-node normal-contact law (:data:`PATCH_FIELDS`): Hertz where it fits, else KP.

    Between (:func:`semi_hertz_weight`) the two laws' fields are blended linearly.

    Parameters
    ----------
    gap : array_like
        m, (n, n_t) normal gap functions (:func:`normal_gap_function`).
    step : float
        m, their sample step.
    a_sum, b_sum : array_like
        1/m, (n,) unfloored relative curvatures (rolling, lateral).
    modulus : float
        Pa, contact modulus E*.

    Returns
    -------
    numpy.ndarray
        (n, len(PATCH_FIELDS)); field 6 is the weight of the KP law, field 7 KP's force
        centre (:func:`force_centre`) at :data:`.node_laws.DELTA_REF`, whatever the weight,
        field 8 the exponent of its power law in the penetration (:func:`.node_laws.node_centre`).
    """
    gap = np.atleast_2d(np.asarray(gap, float))
    a_sum = np.broadcast_to(np.asarray(a_sum, float), gap.shape[:1])
    b_sum = np.broadcast_to(np.asarray(b_sum, float), gap.shape[:1])
    n = gap.shape[0]
    out = np.zeros((n, len(PATCH_FIELDS)))
    if n == 0:
        return out
    a_f, b_f = np.maximum(a_sum, MIN_CURVATURE_SUM), np.maximum(b_sum, MIN_CURVATURE_SUM)
    constant = hertz_constant(a_f, b_f, modulus)
    ref = hertz_contact(a_f, b_f, constant * DELTA_REF**1.5, modulus)
    out[:, 0] = constant * DELTA_REF**1.5
    out[:, 1] = 1.5
    out[:, 2], out[:, 3] = ref.a, 0.5
    out[:, 4], out[:, 5] = ref.b, 0.5
    # the contact position: KP's force centre, at every node (the Hertz ellipse's centre is
    # the deepest point, which is not where the load acts when the gap is lopsided), and
    # how it moves with the penetration (a power law through its values at DELTA_LOW and
    # DELTA_HIGH: it starts at the deepest point and moves out as the region grows)
    out[:, 7] = force_centre(gap, step, DELTA_REF)
    low, high = force_centre(gap, step, DELTA_LOW), force_centre(gap, step, DELTA_HIGH)
    out[:, 8] = centre_exponent(low, out[:, 7], high)
    # the surface's offset there (fields 9, 10): set by patch_law_fields (needs the rail)
    weight = semi_hertz_weight(hertz_misfit(gap, step, a_sum, b_sum, modulus))
    semi = weight > 0.0
    if np.any(semi):
        low = kik_piotrowski(gap[semi], step, a_f[semi], DELTA_LOW, modulus)
        high = kik_piotrowski(gap[semi], step, a_f[semi], DELTA_HIGH, modulus)
        span = math.log(DELTA_HIGH / DELTA_LOW)
        kp = np.zeros((int(np.sum(semi)), 6))
        usable = np.ones(kp.shape[0], dtype=bool)
        for k, (lo, hi) in enumerate(
            ((low.normal_force, high.normal_force), (low.a, high.a), (low.b, high.b))
        ):
            good = (lo > 0.0) & (hi > 0.0)
            usable &= good
            with np.errstate(divide="ignore", invalid="ignore"):
                kp[:, 2 * k] = np.where(good, np.sqrt(lo * hi), 0.0)
                kp[:, 2 * k + 1] = np.where(good, np.log(hi / lo) / span, 0.0)
        rows = np.nonzero(semi)[0][usable]
        w = weight[rows][:, None]
        out[rows, :6] = (1.0 - w) * out[rows, :6] + w * kp[usable]
        out[rows, 6] = weight[rows]
    return out


def patch_law_fields(
    rail: PreparedRail,
    wheel: PreparedWheel,
    shifts,
    batch: list[Candidates],
    young: float = 2.1e11,
    poisson: float = 0.3,
) -> list[np.ndarray]:
    """The per-node law of every candidate of a section's search (what the tables store).

    Parameters
    ----------
    rail, wheel : PreparedRail, PreparedWheel
        The section and wheel the search used.
    shifts : array_like
        m, the search's lateral shifts.
    batch : list of Candidates
        The search's result, one per shift.
    young, poisson : float
        Pa, -: wheel and rail steel.

    Returns
    -------
    list of numpy.ndarray
        Per shift, (n_candidates, len(PATCH_FIELDS)) in the candidates' order.
    """
    shifts = np.atleast_1d(np.asarray(shifts, float))
    counts = [len(found.gap) for found in batch]
    if sum(counts) == 0:
        return [np.zeros((0, len(PATCH_FIELDS))) for _ in batch]
    cat = {
        name: np.concatenate([getattr(found, name) for found in batch])
        for name in ("y_rail", "z_rail", "angle", "radius", "curvature_rail", "curvature_wheel")
    }
    shift = np.repeat(shifts, counts)
    gap = normal_gap_function(rail, wheel, shift, cat["y_rail"], cat["z_rail"], cat["angle"])
    a_sum = 0.5 * np.cos(cat["angle"]) / cat["radius"]
    b_sum = 0.5 * (np.nan_to_num(cat["curvature_wheel"]) + np.nan_to_num(cat["curvature_rail"]))
    law = patch_law(gap, GAP_STEP, a_sum, b_sum, effective_modulus(young, poisson))
    law[:, 9:11] = centre_offset_law(
        rail, cat["y_rail"], cat["z_rail"], cat["angle"], law[:, 7], law[:, 8]
    )
    return np.split(law, np.cumsum(counts)[:-1])
