"""Creep forces of FASTSIM on the Kik-Piotrowski patch itself, strip by strip.

The passage kernel's creep law (:mod:`.creep_table`) is FASTSIM on the *equivalent
ellipse* of a Kik-Piotrowski (KP) patch (:mod:`.nonhertz`: the ellipse of the patch's area
and length-to-width ratio).  This module gives FASTSIM the KP patch as it is, as Piotrowski
& Kik intended it for non-elliptic contact (J. Piotrowski, W. Kik, "A simplified model of
wheel/rail contact mechanics for non-Hertzian problems and its application in rail
vehicle dynamic simulations", VSD 46 (2008) 27-48, the tangential part: FASTSIM on the
strips of the virtual interpenetration region):

- the strips are those of KP's virtual penetration ``epsilon delta``: at lateral position
  t (along the contact's lateral tangent, the contact point at t = 0) the strip reaches
  ``|x| <= x_l(t) = sqrt((epsilon delta - g(t)) / A)`` on the connected run of
  ``g < epsilon delta`` around the contact point (the same region as
  :func:`.nonhertz.kik_piotrowski`, rebuilt here strip by strip);
- the strips carry KP's pressure ``c sqrt(x_l^2 - x^2)``, i.e. a load per unit width
  ``(pi / 2) c x_l(t)^2``, scaled to the normal force of :func:`.nonhertz.kik_piotrowski`;
- FASTSIM's three flexibilities (:func:`.fastsim.kalker_flexibilities`) are those of the
  patch's equivalent ellipse (Piotrowski & Kik 2008 take the flexibility of a
  non-elliptic patch from an ellipse of the same area in this way; the review of
  Piotrowski & Chollet, VSD 43 (2005) 455-483, describes the same practice);
- the spin acts about the patch's force centre (:func:`.nonhertz.force_centre`), where
  the kernel puts the contact and where CONTACT's reference point lies.

Pressure along x in FASTSIM.  ``"parabolic"`` (the default) is Kalker's choice for FASTSIM
carried over to a strip patch: ``p = k (x_l(t)^2 - x^2)`` with one k for the whole patch,
so a strip carries ``(4 / 3) k x_l^3``.  On an elliptic patch this is exactly the
pressure of :func:`.fastsim.fastsim_ellipse`, so the method reduces to the elliptic FASTSIM
(tests/test_wheel_rail_kp_creep.py).  ``"kp"`` keeps KP's own semi-elliptic pressure
(strip loads ``~ x_l^2``).  Both bound every strip's traction by mu times its load, so
``|F| <= mu N``.

What it measured (validation/contact_vs_contact.md, ``python
validation/contact_vs_contact.py``).  On CONTACT's five reference cases this law has FX
within 10 % in 3 of 5 and FS in 2 of 5, as the kernel's table on the equivalent ellipse:
it is no closer.  Two diagnostics say why:

- Kalker's exact theory on KP's own patch and pressure (:func:`patch_pressure_grid`) is
  within 10 % in 4 of 10, as on KP's equivalent ellipse, against 8 of 10 on CONTACT's own
  area: KP's patch itself misses (cross+wing: strips up to 7.7 mm long against CONTACT's
  rows of 9.0 mm), not the equivalent ellipse;
- FASTSIM strip by strip on CONTACT's own rows (:func:`area_strips`) is within 10 % in 4
  of 10: on the skewed bands of the wing-rail cases (rows 6.4 mm long whose centres drift
  7 mm along x) the strips are short, and FX falls 26 % below CONTACT's, where the exact
  theory on the same area is 2 % off.  FASTSIM's independent springs have no elastic
  coupling between the rows of a skewed patch; the exact theory on the same rows moved
  to x = 0 (de-skewed) gives -22.5 % there, so it is the skew that FASTSIM cannot see.

Our 2-D geometry knows the skew: where the rigid wheel meets the rail under each KP strip
(``references.ContactResult.kp_skew``) drifts along x as CONTACT's rows do, by about half
as much.  The exact theory on KP's patch with that skew gets wing_brute's FS within 1 %
(unskewed +66 %) and cw_interrupt#1's within 0.1 % (+21 %), but wing_brute's FX moves to
+15 % (KP's strips, 8.2 mm, are longer than CONTACT's rows, 6.4 mm): 5 of 10.  A creep
law that reaches the 10 % more often needs a patch that carries the skew and a law that
feels it; FASTSIM does not.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from exudyn_turnout.wheel_rail.fastsim import DEFAULT_ELEMENTS, fastsim_strips, kalker_flexibilities
from exudyn_turnout.wheel_rail.nonhertz import EPSILON, kik_piotrowski

__all__ = [
    "KP_PRESSURES",
    "StripPatch",
    "kp_strips",
    "area_strips",
    "fastsim_patch",
    "patch_pressure_grid",
]

#: Pressures along x that :func:`fastsim_patch` offers (module docstring).
KP_PRESSURES = ("parabolic", "kp")


@dataclass(frozen=True, eq=False)
class StripPatch:
    """A contact patch as lateral strips across the rolling direction (KP's, or a map's)."""

    t: np.ndarray  #: m, strip centres along the lateral tangent, from the contact point
    width: np.ndarray  #: m, strip widths
    half_length: np.ndarray  #: m, half-length of each strip along x
    x_centre: np.ndarray  #: m, each strip's centre along x (KP's: 0; a skewed map's: not)
    load: np.ndarray  #: N/m, normal load per unit width (semi-elliptic strips), sum = N
    normal_force: float  #: N, the normal force the loads sum to
    centre: float  #: m, force centre along t (the spin's pole)
    a: float  #: m, equivalent ellipse, rolling direction (area and length / width kept)
    b: float  #: m, equivalent ellipse, lateral

    @property
    def length(self) -> float:
        """m, the patch's extent along x (twice the longest strip's half-length)."""
        return 2.0 * float(self.half_length.max()) if self.half_length.size else 0.0

    @property
    def area(self) -> float:
        """m^2, the patch's area (sum of strip lengths times widths)."""
        return float(np.sum(2.0 * self.half_length * self.width))


def kp_strips(
    gap, step: float, a_sum: float, delta: float, modulus: float, epsilon: float = EPSILON
) -> StripPatch:
    """The strips of Kik-Piotrowski's patch on one sampled gap function (Piotrowski & Kik
    2008; the module docstring).

    Parameters
    ----------
    gap : array_like
        m, (n_t,) normal gap of the undeformed surfaces along the lateral tangent on
        ``t = (k - n_t // 2) step``, the contact point in the centre (as
        :func:`.nonhertz.kik_piotrowski` takes it); NaN where there is no surface.
    step : float
        m, lateral sample step (the strip width).
    a_sum : float
        1/m, relative curvature in the rolling direction (> 0).
    delta : float
        m, penetration.
    modulus : float
        Pa, contact modulus E*.
    epsilon : float
        Virtual-penetration factor.

    Returns
    -------
    StripPatch
        Only the strips of the patch (none where ``delta <= 0`` or nothing penetrates).

    Raises
    ------
    ValueError
        If the gap is not one-dimensional, or step or a_sum is not positive.
    """
    gap = np.asarray(gap, float)
    if gap.ndim != 1 or gap.size == 0:
        raise ValueError("gap must be a non-empty one-dimensional array")
    if not step > 0.0 or not a_sum > 0.0:
        raise ValueError(f"step and a_sum must be positive, not {step!r} and {a_sum!r}")
    empty = np.zeros(0)
    if not delta > 0.0:
        return StripPatch(empty, empty, empty, empty, empty, 0.0, 0.0, 0.0, 0.0)
    gap = np.nan_to_num(gap, nan=np.inf)
    centre = gap.size // 2
    virtual = epsilon * delta
    inside = gap < virtual
    run = np.zeros(gap.size, dtype=bool)
    for direction in (1, -1):  # the connected run around the contact point
        k = centre
        while 0 <= k < gap.size and inside[k]:
            run[k] = True
            k += direction
    patch = kik_piotrowski(gap[None, :], step, a_sum, delta, modulus, epsilon)
    force = float(patch.normal_force[0])
    depth = virtual - gap[run]
    if depth.size == 0 or force <= 0.0:
        return StripPatch(empty, empty, empty, empty, empty, 0.0, 0.0, 0.0, 0.0)
    t = (np.nonzero(run)[0] - centre) * step
    half = np.sqrt(depth / a_sum)
    width = np.full(t.size, float(step))
    share = half * half  # KP's strip load (pi / 2) c x_l^2
    load = share * force / float(np.sum(share * width))
    return StripPatch(
        t=t,
        width=width,
        half_length=half,
        x_centre=np.zeros(t.size),
        load=load,
        normal_force=force,
        centre=float(np.sum(share * t) / np.sum(share)),
        a=float(patch.a[0]),
        b=float(patch.b[0]),
    )


def area_strips(area, dx: float, dy: float, normal_force: float) -> StripPatch:
    """A contact area given element by element (e.g. CONTACT's printed map) as strips.

    Every row of elements (constant t) is a strip from its first to its last element along
    x, centred where that run is (a skewed band keeps its skew), and carries a
    semi-elliptic pressure with one constant for all rows, as
    :func:`.exact_rolling.strip_pressure` rebuilds it (loads ``~ x_l^2``, KP's form).  The
    equivalent ellipse is defined as KP's (:func:`.nonhertz.kik_piotrowski`): the same area,
    and the ratio of the longest strip's half-length to the half-width.

    Parameters
    ----------
    area : array_like of bool
        (nx, ny) elements in contact, x along axis 0, t along axis 1.
    dx, dy : float
        m, element size along x and t.
    normal_force : float
        N, the load.

    Returns
    -------
    StripPatch
        t and x measured from the grid's corner.

    Raises
    ------
    ValueError
        If the area is not two-dimensional or has no element in contact.
    """
    area = np.asarray(area, bool)
    if area.ndim != 2 or not area.any():
        raise ValueError("area must be a two-dimensional map with elements in contact")
    rows = [j for j in range(area.shape[1]) if area[:, j].any()]
    first = np.array([np.nonzero(area[:, j])[0].min() for j in rows], float)
    last = np.array([np.nonzero(area[:, j])[0].max() + 1 for j in rows], float)
    half = 0.5 * (last - first) * dx
    share = half * half
    load = share * normal_force / float(np.sum(share) * dy)
    total = float(area.sum()) * dx * dy
    half_width = 0.5 * (max(rows) - min(rows) + 1) * dy
    a = float(np.sqrt(total / np.pi * half.max() / half_width))
    t = (np.array(rows, float) + 0.5) * dy
    return StripPatch(
        t=t,
        width=np.full(t.size, float(dy)),
        half_length=half,
        x_centre=0.5 * (first + last) * dx,
        load=load,
        normal_force=float(normal_force),
        centre=float(np.sum(share * t) / np.sum(share)),
        a=a,
        b=total / (np.pi * a),
    )


def fastsim_patch(
    creep_longitudinal: float,
    creep_lateral: float,
    spin: float,
    strips: StripPatch,
    friction: float,
    shear_modulus: float = 8.1e10,
    poisson: float = 0.28,
    pressure: str = "parabolic",
    normal_force: float | None = None,
    n_x: int = DEFAULT_ELEMENTS,
) -> tuple[float, float]:
    """FASTSIM on a Kik-Piotrowski patch, strip by strip (the module docstring).

    Parameters
    ----------
    creep_longitudinal, creep_lateral : float
        Creepages xi, eta (-).
    spin : float
        1/m, spin creepage phi (about the patch's force centre).
    strips : StripPatch
        The patch (:func:`kp_strips`).
    friction : float
        Coefficient of friction mu.
    shear_modulus : float
        Pa, G.
    poisson : float
        Poisson's ratio for Kalker's coefficients of the equivalent ellipse.
    pressure : str
        Along x in every strip: "parabolic" (Kalker's FASTSIM, strip loads ``~ x_l^3``)
        or "kp" (KP's semi-elliptic pressure, strip loads ``~ x_l^2``).
    normal_force : float, optional
        N, the patch's load (default: KP's, ``strips.normal_force``); the strips' loads
        are scaled to it.
    n_x : int
        Elements along x per strip (:func:`.fastsim.fastsim_strips`).

    Returns
    -------
    tuple of float
        N, (F_x, F_y) on the wheel (the sign convention of :func:`.fastsim.fastsim_ellipse`);
        ``|F| <= mu N``.

    Raises
    ------
    ValueError
        For an unknown pressure.
    """
    if pressure not in KP_PRESSURES:
        raise ValueError(f"pressure must be one of {KP_PRESSURES}, not {pressure!r}")
    load_total = strips.normal_force if normal_force is None else float(normal_force)
    if strips.t.size == 0 or load_total <= 0.0 or strips.a <= 0.0 or strips.b <= 0.0:
        return 0.0, 0.0
    half = strips.half_length
    share = half**3 if pressure == "parabolic" else half * half
    load = share * load_total / float(np.sum(share * strips.width))
    flex = tuple(float(f) for f in kalker_flexibilities(strips.a, strips.b, shear_modulus, poisson))
    pole_x = float(np.sum(share * strips.width * strips.x_centre) / np.sum(share * strips.width))
    return fastsim_strips(
        creep_longitudinal, creep_lateral, spin, strips.t - strips.centre, strips.width, half,
        load, (flex[0], flex[1], flex[2]), friction, n_x=n_x,
        pressure="elliptic" if pressure == "kp" else "parabolic",
        x_centre=strips.x_centre - pole_x,
    )  # fmt: skip


def patch_pressure_grid(
    strips: StripPatch, dx: float, dy: float, normal_force: float | None = None
) -> tuple[np.ndarray, float, float]:
    """KP's pressure on a grid of ``dx x dy`` elements, for Kalker's exact theory.

    The strips are resampled at the element rows (linear interpolation of the half-length
    and of the centre along x, in t); each row carries KP's semi-elliptic pressure
    ``c sqrt(x_l^2 - (x - x_c)^2)`` with one c, scaled to the normal force.  The grid
    leaves one empty element column ahead of and behind the patch
    (:func:`.exact_rolling.solve_steady_rolling` needs it), and its origin is the spin's
    pole: the force centre along t, the strips' load-weighted mean centre along x.

    Parameters
    ----------
    strips : StripPatch
        The patch (:func:`kp_strips`).
    dx, dy : float
        m, element size along x and along t.
    normal_force : float, optional
        N, total load (default: KP's).

    Returns
    -------
    tuple
        (pressure (nx, ny) in Pa, x0 in m, y0 in m): the grid's corner relative to the pole.

    Raises
    ------
    ValueError
        If the patch is empty or dx, dy are not positive.
    """
    if strips.t.size == 0:
        raise ValueError("the patch has no strips")
    if not dx > 0.0 or not dy > 0.0:
        raise ValueError(f"dx and dy must be positive, not {dx!r} and {dy!r}")
    load = strips.normal_force if normal_force is None else float(normal_force)
    t_low = float(strips.t[0] - 0.5 * strips.width[0])
    t_high = float(strips.t[-1] + 0.5 * strips.width[-1])
    n_y = max(int(np.ceil((t_high - t_low) / dy)), 1)
    y = t_low + (np.arange(n_y) + 0.5) * dy
    half = np.interp(y, strips.t, strips.half_length, left=0.0, right=0.0)
    weight = strips.load * strips.width
    pole_x = float(np.sum(weight * strips.x_centre) / np.sum(weight))
    centre = np.interp(y, strips.t, strips.x_centre) - pole_x
    reach = float(np.max(np.abs(centre) + half))
    n_x = int(np.ceil(2.0 * reach / dx)) + 2
    x0 = -0.5 * n_x * dx
    x = x0 + (np.arange(n_x) + 0.5) * dx
    offset = x[:, None] - centre[None, :]
    pressure = np.sqrt(np.maximum(half[None, :] ** 2 - offset**2, 0.0))
    total = float(pressure.sum()) * dx * dy
    if total > 0.0:
        pressure *= load / total
    return pressure, x0, t_low - strips.centre
