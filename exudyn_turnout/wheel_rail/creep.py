"""Kalker's creep coefficients and Polach's creep-force law with spin.

Kalker coefficients
-------------------
``C11, C22, C23, C33`` of the linear theory, ``F_x = -G a b C11 xi``,
``F_y = -G a b (C22 eta + sqrt(a b) C23 phi)``, ``M_z = -G (a b)^1.5 (-C23 eta + sqrt(a b)
C33 phi)`` (a: semi-axis in the rolling direction, b lateral), interpolated linearly in the
ellipse ratio and in Poisson's ratio from Kalker's table (J.J. Kalker, *Three-dimensional
elastic bodies in rolling contact*, Kluwer 1990, Table E3; first published in his 1967
thesis; reproduced in Iwnicki (ed.), *Handbook of Railway Vehicle Dynamics*, CRC 2006,
ch. 4).  Rows a/b = 0.1 ... 1 and b/a = 0.9 ... 0.1, columns nu = 0, 0.25, 0.5; outside
a/b in [0.1, 10] Kalker's slender-ellipse asymptotes, joined to the end rows without a jump
(below).

Slender ellipses (issue 22).  Kalker's asymptotes for g = min(a/b, b/a) -> 0 (Kalker
1990 Table E3, its first and last rows; quoted from CONTACT, ``src/m_hertz.f90``,
subroutine ``linrol``, commit 0ecc556, which uses them for g < 0.101):

* a/b = g -> 0 (patch wide across the rolling direction; Carter's 2-D theory per strip):
  ``C11 = pi^2 / (4 (1 - nu))``, ``C22 = pi^2 / 4``,
  ``C23 = pi sqrt(g) / (3 (1 - nu)) (1 + nu (ln(16 / g) - 5))``, and
  ``C33 = pi^2 / (16 (1 - nu) g)`` (the strip-theory limit; not in CONTACT);
* b/a = g -> 0 (patch long in the rolling direction: the crossing nose, check rail and
  flange patches), with ``L = ln(16 / g^2)``:
  ``C11 = 2 pi / ((L - 2 nu) g) (1 + (3 - ln 4) / (L - 2 nu))``,
  ``C22 = 2 pi / (g D) (1 + (1 - nu) (3 - ln 4) / D)``, ``D = (1 - nu) L + 2 nu``,
  ``C23 = 2 pi / (3 g^1.5 ((1 - nu) L - 2 + 4 nu))``; C33 has no asymptote here (none in
  CONTACT) and keeps the end row b/a = 0.1 (it is used nowhere in the package).

At g = 0.1 the asymptotes differ from the table's end rows by up to 4 % (C11, C22) and
7 % (C23 of a wide patch, nu = 0.28); CONTACT switches with that jump.  Here the
asymptote is multiplied by ``1 + (r - 1) w(g)``, r the ratio of table row to asymptote at
g = 0.1 (at the given nu), with ``w = g / 0.1`` for a/b < 0.1 and ``w = (L(0.1) / L)^2``
for b/a < 0.1 (the relative error of a two-term expansion in 1/L): continuous at 0.1 and
tending to the asymptote.  Checked against the package's exact steady-rolling solver
(:mod:`.exact_rolling`, full stick, Hertz ellipse on 48 x 48 elements, nu = 0.28; it
reads the table's rows at a/b = 5 and 10 1.1-1.9 % high in C11 and C22, 1.1-1.4 % low
in C23, and a/b = 0.1, 0.2 within 1.3 % except C23, 2.7-3.5 % low): at a/b = 20, 30, 50
it gives C11 19.21, 25.72, 37.74 (joined asymptote 18.84, 25.23, 37.02: +2.0, +2.0,
+1.9 %), C22 22.26, 30.33, 45.31 (+2.0, +2.0, +2.0 %), C23 34.27, 56.88, 109.13 (-1.0,
-0.9, -0.7 %), at a/b = 0.05, 0.02 C11 and C22 within 0.8 %, C23 3.2 and 2.0 % low: the
same offsets as on the table's own rows (tests/test_wheel_rail_slender_creep.py).  The
former end rows held C11, C22, C23 at a/b = 20 at 0.62, 0.59, 0.44 of the exact values.

Provenance of the numbers (checked 2026-11):

* C11, C22, C23: all 171 entries equal, digit for digit, the copy of Table E.3 in CONTACT
  (E.A.H. Vollebregt, github.com/eve70a/CONTACT, ``src/m_hertz.f90``, subroutine
  ``linrol``, commit e60b3ac, which cites Kalker 1990 Table E.3).  CONTACT interpolates in
  Poisson's ratio with a parabola in 1/C; the linear interpolation here differs from it by
  at most 2.4 % at nu = 0.28 (C33 at b/a = 0.1), mostly by well under 1 %.
* C33: no published copy could be consulted (CONTACT tabulates only C11, C22, C23, and
  the book was not at hand), so this column was not checked entry by entry against a
  publication.  Its a/b = 0.1 row agrees with the leading-order strip-theory asymptote
  ``C33 -> pi^2 / (16 (1 - nu) a/b)`` (derived from Carter's 2-D linear solution per
  strip) within 4 %, 1 % and 5 % for nu = 0, 0.25, 0.5, the same size as the deviation of
  the verified C23 row from its asymptote.  An independent numerical solution of the
  linear theory for nu = 0 (panel method: two identical half-spaces, uniform tractions on
  up to 170 x 170 cells, full stick in steady rolling; a one-off check, not part of the
  package) reproduces the verified C11 and C23 within 1 % and gives C33 = 1.22 at
  a/b = 1 (table 1.19), 0.97 at b/a = 0.5 (0.958), and, on 80 x 80 cells and still
  falling with refinement, 1.76 at a/b = 0.5 (1.74) and 3.48 at 0.2 (3.46).  So the
  nu = 0 column of C33 is confirmed within about 3 %; the nu = 0.25 and 0.5 columns only
  by the asymptote.  Treat C33 as uncertain to a few per cent until compared with
  Table E3 itself.

Saturation: Polach's method
---------------------------
O. Polach, "A fast wheel-rail forces calculation computer code", VSD 33 Suppl. (1999)
728-739 (its Fortran listing is the reference for the formulas below), with the reduction
factors of O. Polach, "Creep forces in simulations of traction vehicles running on adhesion
limit", Wear 258 (2005) 992-1000.  Spin enters through the lateral creepage corrected for
spin and the resultant creepage that includes it,

    s_yC = eta + phi a   if |eta + phi a| > |eta|,  else eta,
    s_C = sqrt(xi^2 + s_yC^2),

and the tangential force of the translational creepages is saturated with s_C (spin uses up
adhesion, so the translational force saturates earlier):

    F = 2 Q mu / pi (k_A eps / (1 + (k_A eps)^2) + arctan(k_S eps)),
    eps = pi G a b c_jj s_C / (4 Q mu),  c_jj = sqrt((C11 xi / s)^2 + (C22 eta / s)^2),
    F_x = -F xi / s_C,  F_y = -F eta / s_C + F_yS,

with s = sqrt(xi^2 + eta^2) and the lateral force of spin

    F_yS = (9/16) a Q mu K_M (1 + 6.3 (1 - exp(-a/b))) phi / s_C,
    K_M = |eps_M| (delta^3/3 - delta^2/2 + 1/6) - sqrt((1 - delta^2)^3) / 3  (<= 0),
    delta = (eps_M^2 - 1) / (eps_M^2 + 1),
    eps_M = (8/3) G b sqrt(a b) C23 s_yC / (Q mu (1 + 6.3 (1 - exp(-a/b)))).

Friction bound.  Coulomb's law holds at every point of the patch, |tau| <= mu p, so the
resultant obeys |F| <= integral |tau| dA <= mu Q (Kalker's exact theory and FASTSIM never
exceed it).  Dividing the translational part by s_C (not s) is what keeps Polach's sum
within it: in full slip F -> mu Q and (F_x, F_y) -> -mu Q (xi, eta + k phi a) / s_C with
k = -(9/16) K_M (1 + 6.3 (1 - exp(-a/b))) in [0, 0.72], and eta + k phi a lies between
eta and eta + phi a, so |eta + k phi a| <= |s_yC| and |F| <= mu Q.  (Dividing by s and
saturating with s, then adding F_yS, gives up to 1.47 mu Q at phi = -0.3 1/m.)  For the
mixed, partly saturated range no proof is at hand; a search over 2 million random
creepages, spins, semi-axes and loads plus a numerical maximisation found no |F| above
mu Q (1 + 1e-12).  The resultant is therefore projected onto the friction disc,
``F <- F min(1, mu Q / |F|)``, as a guard that holds the bound by construction; with
k_A = k_S = 1 it is inactive to round-off (tests/test_wheel_rail_creep_bound.py).  With
k_S > k_A Polach's saturation function itself exceeds 1 (by up to 1/pi) and the guard
bites.

Small creepage: for xi = 0, or without spin, the forces tend to Kalker's linear theory
exactly (``-G a b C11 xi``, ``-G a b C22 eta - G (a b)^1.5 C23 phi``); with xi and eta
both non-zero the magnitude is Kalker's and the direction that of (xi, eta).  With xi and
spin both non-zero the linear spin force is Kalker's times |s_yC| / s_C (Polach's
approximation; smaller than Kalker's where |xi| >> |phi a|).

Polach and FASTSIM.  Polach's law is closed form (a few dozen flops per contact), smooth
in the creepages and reproduces Kalker's linear theory and Coulomb's saturation, but its
spin force is an approximation: against CONTACT's reference outputs (Kalker's exact
theory on the real patch) its lateral force was 4.4 times too large in the
spin-dominated wing_brute case and of the wrong sign in cw_interrupt#1.  The contact
kernel therefore uses Kalker's FASTSIM (:mod:`.fastsim`), tabulated once
(:mod:`.creep_table`), whose lateral force there is 16 % and 6 % off, with the right
signs (tests/test_wheel_rail_fastsim_contact.py); Polach's law stays selectable in the kernel
(``packed_tables.pack_tables(..., creep_law="polach")``) and is what
:func:`.references.contact_at_reference` reports.

Sign convention: forces on the wheel, opposing the creepages (Kalker's convention).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = [
    "SLENDER_LIMIT",
    "KalkerCoefficients",
    "kalker_coefficients",
    "slender_asymptotes",
    "CreepForces",
    "polach_creep_forces",
]

#: -, a / b below which (and b / a below which) Kalker's slender asymptotes are joined on
SLENDER_LIMIT = 0.1

# Kalker (1990) Table E3.  Columns: C11 (nu = 0, .25, .5), C22 (...), C23 (...), C33 (...).
# Rows: a/b = 0.1 ... 1.0, then b/a = 0.9 ... 0.1.  C11-C23 checked against CONTACT's
# copy (src/m_hertz.f90, linrol); C33 unchecked against a publication (module docstring).
_KALKER_ROWS = (
    (2.51, 3.31, 4.85, 2.51, 2.52, 2.53, 0.334, 0.473, 0.731, 6.42, 8.28, 11.7),
    (2.59, 3.37, 4.81, 2.59, 2.63, 2.66, 0.483, 0.603, 0.809, 3.46, 4.27, 5.66),
    (2.68, 3.44, 4.80, 2.68, 2.75, 2.81, 0.607, 0.715, 0.889, 2.49, 2.96, 3.72),
    (2.78, 3.53, 4.82, 2.78, 2.88, 2.98, 0.720, 0.823, 0.977, 2.02, 2.32, 2.77),
    (2.88, 3.62, 4.83, 2.88, 3.01, 3.14, 0.827, 0.929, 1.07, 1.74, 1.93, 2.22),
    (2.98, 3.72, 4.91, 2.98, 3.14, 3.31, 0.930, 1.03, 1.18, 1.56, 1.68, 1.86),
    (3.09, 3.81, 4.97, 3.09, 3.28, 3.48, 1.03, 1.14, 1.29, 1.43, 1.50, 1.60),
    (3.19, 3.91, 5.05, 3.19, 3.41, 3.65, 1.13, 1.25, 1.40, 1.33, 1.37, 1.42),
    (3.29, 4.01, 5.12, 3.29, 3.54, 3.82, 1.23, 1.36, 1.51, 1.26, 1.26, 1.27),
    (3.40, 4.12, 5.20, 3.40, 3.67, 3.98, 1.33, 1.47, 1.63, 1.19, 1.17, 1.16),
    (3.51, 4.22, 5.30, 3.51, 3.81, 4.16, 1.44, 1.59, 1.77, 1.14, 1.09, 1.06),
    (3.65, 4.36, 5.42, 3.65, 3.99, 4.39, 1.58, 1.75, 1.94, 1.09, 1.01, 0.954),
    (3.82, 4.54, 5.58, 3.82, 4.21, 4.67, 1.76, 1.95, 2.18, 1.05, 0.946, 0.852),
    (4.06, 4.78, 5.80, 4.06, 4.50, 5.04, 2.01, 2.23, 2.50, 1.01, 0.892, 0.751),
    (4.37, 5.10, 6.11, 4.37, 4.90, 5.56, 2.35, 2.62, 2.96, 0.958, 0.830, 0.649),
    (4.84, 5.57, 6.57, 4.84, 5.48, 6.31, 2.88, 3.24, 3.70, 0.912, 0.773, 0.555),
    (5.57, 6.34, 7.34, 5.57, 6.40, 7.51, 3.79, 4.32, 5.01, 0.868, 0.708, 0.455),
    (6.96, 7.78, 8.82, 6.96, 8.14, 9.79, 5.72, 6.63, 7.89, 0.828, 0.642, 0.356),
    (10.7, 11.7, 12.9, 10.7, 12.8, 16.0, 12.2, 14.6, 18.0, 0.795, 0.578, 0.261),
)
# Table axis: t = a/b for a <= b, t = 2 - b/a for a > b (continuous, increasing in a/b).
_KALKER_AXIS = tuple([0.1 * i for i in range(1, 11)] + [2.0 - 0.1 * i for i in range(9, 0, -1)])


@dataclass(frozen=True, eq=False)
class KalkerCoefficients:
    """Kalker's creep and spin coefficients (dimensionless, arrays like the inputs)."""

    c11: np.ndarray  #: longitudinal creep
    c22: np.ndarray  #: lateral creep
    c23: np.ndarray  #: lateral force from spin / moment from lateral creep
    c33: np.ndarray  #: spin moment


def kalker_coefficients(a, b, poisson: float = 0.28) -> KalkerCoefficients:
    """Kalker's coefficients for a contact ellipse (table and slender asymptotes).

    Parameters
    ----------
    a, b : array_like
        m (or any common unit), semi-axes in rolling and lateral direction.
    poisson : float
        Poisson's ratio, 0 ... 0.5 (steel 0.28-0.3).

    Returns
    -------
    KalkerCoefficients

    Notes
    -----
    C11, C22 and C23 are Kalker's published values (checked against CONTACT's copy of
    Table E3); C33 is not checked against a publication and is uncertain to a few per cent
    (see the module docstring).  Beyond a / b in [0.1, 10]: Kalker's asymptotes
    (:func:`slender_asymptotes`), joined continuously to the end rows (module docstring).
    """
    ratio = np.asarray(a, float) / np.asarray(b, float)
    nu = float(np.clip(poisson, 0.0, 0.5))
    values = list(_table_values(ratio, nu))
    wide = ratio < SLENDER_LIMIT
    long = ratio > 1.0 / SLENDER_LIMIT
    if np.any(wide) or np.any(long):
        end_wide = _table_values(np.asarray(SLENDER_LIMIT), nu)
        end_long = _table_values(np.asarray(1.0 / SLENDER_LIMIT), nu)
        limit_wide = _as_list(slender_asymptotes(SLENDER_LIMIT, nu))
        limit_long = _as_list(slender_asymptotes(1.0 / SLENDER_LIMIT, nu))
        g_wide = np.where(wide, ratio, SLENDER_LIMIT)
        g_long = np.where(long, 1.0 / np.where(long, ratio, 1.0), SLENDER_LIMIT)
        asym_wide = _as_list(slender_asymptotes(g_wide, nu))
        asym_long = _as_list(slender_asymptotes(1.0 / g_long, nu))
        w_wide = g_wide / SLENDER_LIMIT
        w_long = (_log_parameter(SLENDER_LIMIT) / _log_parameter(g_long)) ** 2
        for k in range(4):
            joined_wide = asym_wide[k] * (1.0 + (end_wide[k] / limit_wide[k] - 1.0) * w_wide)
            if k < 3:  # C33 of a long patch: no asymptote, the end row (module docstring)
                joined_long = asym_long[k] * (1.0 + (end_long[k] / limit_long[k] - 1.0) * w_long)
            else:
                joined_long = np.broadcast_to(end_long[k], ratio.shape)
            values[k] = np.where(wide, joined_wide, np.where(long, joined_long, values[k]))
    return KalkerCoefficients(*values)


def _as_list(c: KalkerCoefficients) -> list:
    return [c.c11, c.c22, c.c23, c.c33]


def _table_values(ratio: np.ndarray, nu: float) -> list:
    """C11, C22, C23, C33 interpolated in Kalker's table (end rows held outside it)."""
    axis = np.where(ratio <= 1.0, ratio, 2.0 - 1.0 / ratio)
    table = np.asarray(_KALKER_ROWS)
    values = []
    for block in range(4):
        columns = table[:, 3 * block : 3 * block + 3]
        per_nu = [np.interp(axis, _KALKER_AXIS, columns[:, j]) for j in range(3)]
        values.append(_interp_poisson(nu, per_nu))
    return values


def _log_parameter(g):
    """Kalker's ``L = ln(16 / g^2)`` of a long patch, g = b / a."""
    return np.log(16.0 / np.asarray(g, float) ** 2)


def slender_asymptotes(ratio, poisson: float = 0.28) -> KalkerCoefficients:
    """Kalker's asymptotes of his coefficients for slender ellipses (module docstring).

    Parameters
    ----------
    ratio : array_like
        a / b; below 1 the forms for a / b -> 0 (patch wide across the rolling direction),
        above 1 those for b / a -> 0 (patch long in the rolling direction).  Meant for
        ratios beyond :data:`SLENDER_LIMIT` (0.1) and its inverse.
    poisson : float
        Poisson's ratio nu.

    Returns
    -------
    KalkerCoefficients
        The leading terms (Kalker 1990 Table E3, as in CONTACT's ``linrol``); C33 of a long
        patch is NaN (no asymptote available).
    """
    ratio = np.asarray(ratio, float)
    nu = float(poisson)
    long = ratio > 1.0
    g = np.where(long, 1.0 / np.where(long, ratio, 1.0), ratio)
    # a / b -> 0
    w11 = np.full_like(g, np.pi**2 / (4.0 * (1.0 - nu)))
    w22 = np.full_like(g, np.pi**2 / 4.0)
    w23 = np.pi * np.sqrt(g) / (3.0 * (1.0 - nu)) * (1.0 + nu * (np.log(16.0 / g) - 5.0))
    w33 = np.pi**2 / (16.0 * (1.0 - nu) * g)
    # b / a -> 0
    lam = _log_parameter(g)
    l11 = 2.0 * np.pi / ((lam - 2.0 * nu) * g) * (1.0 + (3.0 - np.log(4.0)) / (lam - 2.0 * nu))
    d = (1.0 - nu) * lam + 2.0 * nu
    l22 = 2.0 * np.pi / (g * d) * (1.0 + (1.0 - nu) * (3.0 - np.log(4.0)) / d)
    l23 = 2.0 * np.pi / (3.0 * g**1.5 * ((1.0 - nu) * lam - 2.0 + 4.0 * nu))
    return KalkerCoefficients(
        c11=np.where(long, l11, w11),
        c22=np.where(long, l22, w22),
        c23=np.where(long, l23, w23),
        c33=np.where(long, np.nan, w33),
    )


def _interp_poisson(nu: float, per_nu: list) -> np.ndarray:
    if nu <= 0.25:
        t = nu / 0.25
        return (1.0 - t) * per_nu[0] + t * per_nu[1]
    t = (nu - 0.25) / 0.25
    return (1.0 - t) * per_nu[1] + t * per_nu[2]


@dataclass(frozen=True, eq=False)
class CreepForces:
    """Creep forces on the wheel (N), arrays like the inputs."""

    longitudinal: np.ndarray  #: N, along the rolling direction
    lateral: np.ndarray  #: N, in the contact plane, across the rolling direction


def polach_creep_forces(
    creep_longitudinal,
    creep_lateral,
    spin,
    a,
    b,
    normal_force,
    friction,
    shear_modulus: float = 8.1e10,
    poisson: float = 0.28,
    reduction_adhesion: float = 1.0,
    reduction_slip: float = 1.0,
    bound_resultant: bool = True,
) -> CreepForces:
    """Creep forces by Polach's method (1999, with 2005's reduction factors).

    Parameters
    ----------
    creep_longitudinal, creep_lateral : array_like
        Creepages xi, eta (-).
    spin : array_like
        1/m, spin creepage phi.
    a, b : array_like
        m, Hertz semi-axes in rolling and lateral direction.
    normal_force : array_like
        N, normal force Q (>= 0; zero gives zero force).
    friction : array_like
        Coefficient of friction mu.
    shear_modulus : float
        Pa, G (steel 81 GPa).
    poisson : float
        Poisson's ratio for Kalker's coefficients.
    reduction_adhesion, reduction_slip : float
        Polach's k_A and k_S (1 and 1: the 1999 model, Kalker's linear slope).
    bound_resultant : bool
        Project the resultant onto the friction disc, ``|F| <= mu Q`` (default).  False
        gives Polach's closed form alone (for testing that it keeps the bound itself).

    Returns
    -------
    CreepForces
        On the wheel, ``|F| <= mu Q``; for small creepages Kalker's linear theory (see the
        module docstring for the combined cases).
    """
    xi = np.asarray(creep_longitudinal, float)
    eta = np.asarray(creep_lateral, float)
    phi = np.asarray(spin, float)
    a = np.asarray(a, float)
    b = np.asarray(b, float)
    q = np.asarray(normal_force, float)
    mu = np.asarray(friction, float)
    coeff = kalker_coefficients(a, b, poisson)
    loaded = q > 0.0
    q_mu = np.where(loaded, q * mu, 1.0)
    # lateral creepage corrected for spin and the resultant creepage (Polach 1999)
    eta_spin = eta + phi * a
    eta_c = np.where(np.abs(eta_spin) > np.abs(eta), eta_spin, eta)
    s = np.hypot(xi, eta)
    s_c = np.hypot(xi, eta_c)
    safe_s = np.where(s > 0.0, s, 1.0)
    safe_sc = np.where(s_c > 0.0, s_c, 1.0)
    c_jj = np.where(s > 0.0, np.hypot(coeff.c11 * xi / safe_s, coeff.c22 * eta / safe_s), coeff.c11)
    # translational force, saturated with the resultant creepage s_C
    eps = np.pi * shear_modulus * a * b * c_jj * s_c / (4.0 * q_mu)
    ka_eps = reduction_adhesion * eps
    force = 2.0 * q_mu / np.pi * (ka_eps / (1.0 + ka_eps**2) + np.arctan(reduction_slip * eps))
    fx = -force * xi / safe_sc
    fy = -force * eta / safe_sc
    # lateral force of spin (Polach 1999)
    growth = 1.0 + 6.3 * (1.0 - np.exp(-a / b))
    eps_m = (8.0 / 3.0) * shear_modulus * b * np.sqrt(a * b) / q_mu * coeff.c23 * eta_c / growth
    delta = (eps_m**2 - 1.0) / (eps_m**2 + 1.0)
    k_m = (
        np.abs(eps_m) * (delta**3 / 3.0 - delta**2 / 2.0 + 1.0 / 6.0)
        - np.sqrt(np.maximum(1.0 - delta**2, 0.0) ** 3) / 3.0
    )
    fy = fy + (9.0 / 16.0) * a * q_mu * k_m * growth * phi / safe_sc
    if bound_resultant:  # Coulomb: |F| <= mu Q (module docstring: inactive for k_A = k_S)
        resultant = np.hypot(fx, fy)
        scale = np.where(resultant > q_mu, q_mu / np.where(resultant > 0.0, resultant, 1.0), 1.0)
        fx, fy = fx * scale, fy * scale
    return CreepForces(longitudinal=np.where(loaded, fx, 0.0), lateral=np.where(loaded, fy, 0.0))
