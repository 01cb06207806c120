"""Rail torsion: section data of the 60E1 (UIC60) rail, torsion-warping elements, pad roll.

Why torsion
-----------
A lateral wheel force acts at the rail head, ~0.11 m above the rail's shear centre, and
the lateral pad force at the rail foot, ~0.05 m below it: lateral bending and roll of the
rail couple. The planar lateral model (bending only) misses the roll (cf. Thompson,
*Railway Noise and Vibration*, 2009, ch. 3: the lateral rail receptance is governed by
coupled bending and torsion). For the UIC60 turnout the roll doubles the static lateral
receptance at the gauge corner (+6 dB) and moves the lateral track resonance from ~125 Hz
to ~95 Hz (validation/fe_lateral_torsion.md).

Kinematics (x along the rail, y left, z up, roll phi about +x, right-handed): a point of
the section at height z above the shear centre and lateral offset y from it moves by::

    u_y = v - z phi,    u_z = w + y phi                                          (T1)

with v, w the shear centre's lateral and vertical displacements. A force (F_y, F_z) there
does the virtual work F_y dv + F_z dw + (y F_z - z F_y) dphi: its torque about the shear
centre is T = y F_z - z F_y (T2).

Energy per unit length (Vlasov torsion with warping, Timoshenko-like so that the
element's Lagrange interpolation of :mod:`~exudyn_turnout.fe.timoshenko` applies)::

    U = 1/2 [G J_t phi'^2 + E C_w theta'^2 + kappa_w (phi' - theta)^2]           (T3)
    T = 1/2 [rho A (vdot - e_c phidot)^2 + rho I_p,c phidot^2 + rho C_w thetadot^2]   (T4)

theta is the warping variable, equal to phi' in Vlasov's theory; kappa_w is a penalty
(``warping_penalty`` x G J_t, default 1000) that enforces it: the closed form of
:func:`~exudyn_turnout.fe.analytic.infinite_rail_lateral_torsion_receptance` changes by
< 0.001 dB below 2 kHz when it grows ten times (validation/fe_lateral_torsion.md).
e_c is the height of the centroid above the shear centre (mass coupling, T4); I_p,c the
polar second moment about the centroid, so rho (I_p,c + A e_c^2) is the roll inertia
about the shear centre (parallel axes).

Does warping matter below 2 kHz? The ratio of the warping to the St Venant stiffness of
a torsional wave of wavenumber k is (E C_w / G J_t) k^2; with the 60E1 values below
E C_w / G J_t = 0.027 m^2 and the free torsional wave k = omega sqrt(rho I_p / G J_t)
(8.9 rad/m at 1 kHz) it is 0.55 at 500 Hz, 2.2 at 1 kHz and 8.7 at 2 kHz
(:func:`warping_ratio`): warping dominates the rail's torsional stiffness above ~500 Hz,
so it is included (``warping=True``).

Pad roll stiffness: the vertical pad stiffness k_z spread uniformly over the foot width b
resists roll with k_phi = k_z b^2 / 12 (T5, the second moment of a uniform spring bed
about its centre line); damping alike. The roll spring acts between the rail and ground:
the sleeper's own rotation about x (its bending in the y-z plane, in the vertical model)
is 65 times stiffer (1.5e7 N m/rad, the static rotational stiffness of the vertical
plain-track model at the rail seat of a 2.5 m sleeper, against k_phi = 2.25e5 N m/rad):
grounding stiffens the rotational support by ~1.5 %, which keeps the two planes separate.

Section data (60E1 = UIC60, EN 13674-1:2011, Annex A): A = 76.70 cm^2, I about the
horizontal axis 3038.3 cm^4, about the vertical axis 512.3 cm^4 (I_p,c = 3550.6 cm^4),
elastic section modulus at the foot 375.5 cm^3 (centroid 3038.3 / 375.5 = 8.09 cm above
the foot), height 172 mm, head width 72 mm, foot width 150 mm, web 16.5 mm. EN 13674-1
gives neither the torsion constant nor the shear centre nor the warping constant:

- J_t = 2.09e-6 m^4 (209.2 cm^4), the value tabulated for UIC60 in rail-property data
  sets; a thin-walled estimate (head, web and foot as rectangles of the EN widths whose
  depths reproduce A and I_z, Roark's torsion constants of rectangles, no fillets) gives
  2.7e-6 m^4: uncertain by ~+-25 %;
- shear centre 50 mm above the foot and C_w = 2.2e-8 m^6 by Vlasov's two-flange formulas
  (:func:`two_flange_shear_centre`, :func:`two_flange_warping_constant`: head and foot
  as flanges with their lateral second moments, web ignored): the rectangles above give
  55 mm and 2.2e-8 m^6, head and foot of 39 % and 37 % of A (typical of flat-bottom
  rails) 47 mm: shear centre 45-55 mm, C_w within a factor 2.

The sensitivity of the lateral receptance to these three numbers is in
``validation/fe_lateral_torsion.md``. The same section is used for every rail type (the
turnout file has no torsion data; the lead moves these values to the file later).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from exudyn_turnout.fe import timoshenko as tim

__all__ = [
    "RailTorsionSection",
    "UIC60_SECTION",
    "pad_roll_stiffness",
    "polar_moment_about_shear_centre",
    "two_flange_shear_centre",
    "two_flange_warping_constant",
    "warping_ratio",
    "torsion_stiffness",
    "torsion_mass",
]


@dataclass(frozen=True)
class RailTorsionSection:
    """Torsion data and geometry of a rail section (defaults: 60E1 = UIC60, SI).

    Heights are measured from the underside of the rail foot (the pad's top surface).
    """

    name: str = "60E1 (UIC60)"  #: description
    J_t: float = 2.09e-6  #: m^4, St Venant torsion constant
    I_p: float = 3.5506e-5  #: m^4, polar second moment about the centroid (I_y + I_z)
    C_w: float = 2.2e-8  #: m^6, warping constant about the shear centre
    height: float = 0.172  #: m, rail height
    centroid_height: float = 0.0809  #: m, centroid above the foot
    shear_centre_height: float = 0.050  #: m, shear centre above the foot
    head_width: float = 0.072  #: m
    foot_width: float = 0.150  #: m, also the width of the pad (roll stiffness, T5)
    contact_depth: float = 0.014  #: m, lateral contact (gauge corner) below the rail top
    warping: bool = True  #: include the warping DOF theta (Vlasov)
    warping_penalty: float = 1000.0  #: kappa_w / (G J_t) enforcing theta = phi' (-)

    def __post_init__(self):
        for field in ("J_t", "I_p", "height", "foot_width", "warping_penalty"):
            if not getattr(self, field) > 0:
                raise ValueError(f"RailTorsionSection.{field} must be > 0")
        if not self.C_w >= 0:
            raise ValueError("RailTorsionSection.C_w must be >= 0")
        for field in ("centroid_height", "shear_centre_height", "contact_depth"):
            if not 0 <= getattr(self, field) <= self.height:
                raise ValueError(f"RailTorsionSection.{field} must be within the rail height")
        if self.warping and self.C_w == 0:
            raise ValueError("RailTorsionSection.C_w must be > 0 with warping = True")

    @property
    def centroid_offset(self) -> float:
        """e_c (m): height of the centroid above the shear centre (T4)."""
        return self.centroid_height - self.shear_centre_height

    @property
    def foot_depth(self) -> float:
        """m: depth of the pad (rail foot underside) below the shear centre."""
        return self.shear_centre_height

    @property
    def gauge_corner_height(self) -> float:
        """m: height of the lateral contact point above the shear centre."""
        return self.height - self.contact_depth - self.shear_centre_height

    @property
    def dofs_per_node(self) -> int:
        """Torsion DOFs per rail node: (phi, theta) with warping, phi without."""
        return 2 if self.warping else 1


#: The default section, 60E1 (UIC60); see the module docstring for the sources.
UIC60_SECTION = RailTorsionSection()


def pad_roll_stiffness(k_z: ArrayLike, width: float) -> np.ndarray:
    """Roll stiffness of a pad of vertical stiffness k_z spread over a width (T5).

    k_phi = k_z b^2 / 12: uniform springs of k_z / b per metre across -b/2..b/2 resist a
    roll phi with the moment int (k_z / b) y^2 phi dy.

    Parameters
    ----------
    k_z : array_like
        Vertical pad stiffness (N/m), or damping (N s/m) for the roll damping.
    width : float
        Pad (rail foot) width b (m).

    Returns
    -------
    numpy.ndarray
        Roll stiffness (N m/rad), or roll damping (N m s/rad).
    """
    return np.asarray(k_z) * width**2 / 12.0


def polar_moment_about_shear_centre(I_p: float, area: float, e_c: float) -> float:
    """Polar second moment about the shear centre, by parallel axes: I_p,c + A e_c^2.

    Parameters
    ----------
    I_p : float
        Polar second moment about the centroid (m^4).
    area : float
        Section area (m^2).
    e_c : float
        Distance of the centroid from the shear centre (m).

    Returns
    -------
    float
        I_p about the shear centre (m^4).
    """
    return I_p + area * e_c**2


def two_flange_shear_centre(h: float, I_head: float, I_foot: float) -> float:
    """Shear centre of a two-flange section above the foot flange's centroid (Vlasov).

    e = h I_head / (I_head + I_foot): the lateral shear splits between the flanges in
    proportion to their lateral second moments (e.g. Timoshenko & Gere, *Theory of
    Elastic Stability*, 1961, sec. 5.3, monosymmetric I-beam).

    Parameters
    ----------
    h : float
        Distance between the flange centroids (m).
    I_head, I_foot : float
        Second moments of the head and foot about the vertical axis (m^4).

    Returns
    -------
    float
        Height of the shear centre above the foot flange's centroid (m).
    """
    return h * I_head / (I_head + I_foot)


def two_flange_warping_constant(h: float, I_head: float, I_foot: float) -> float:
    """Warping constant of a two-flange section: C_w = h^2 I_head I_foot / (I_head + I_foot).

    Same source as :func:`two_flange_shear_centre`.

    Parameters
    ----------
    h : float
        Distance between the flange centroids (m).
    I_head, I_foot : float
        Second moments of the head and foot about the vertical axis (m^4).

    Returns
    -------
    float
        C_w (m^6).
    """
    return h**2 * I_head * I_foot / (I_head + I_foot)


def warping_ratio(
    section: RailTorsionSection,
    frequency_hz: ArrayLike,
    E: float,
    G: float,
    density: float,
    area: float,
) -> np.ndarray:
    """Warping over St Venant stiffness, (E C_w / G J_t) k^2, of the free torsional wave.

    k = omega sqrt(rho I_p / G J_t) with I_p about the shear centre (St Venant wave).

    Parameters
    ----------
    section : RailTorsionSection
        Torsion data.
    frequency_hz : array_like
        Frequencies (Hz).
    E, G : float
        Young's and shear moduli (Pa).
    density : float
        Rail density (kg/m^3).
    area : float
        Section area (m^2), for I_p about the shear centre.

    Returns
    -------
    numpy.ndarray
        The ratio (-), one value per frequency.
    """
    I_p = polar_moment_about_shear_centre(section.I_p, area, section.centroid_offset)
    k = 2 * math.pi * np.asarray(frequency_hz, float) * math.sqrt(density * I_p / (G * section.J_t))
    return E * section.C_w / (G * section.J_t) * k**2


def torsion_stiffness(
    p: int, L: ArrayLike, GJ: ArrayLike, ECw: ArrayLike, kappa_w: ArrayLike, warping: bool
) -> np.ndarray:
    """Element stiffness of rail torsion (T3), DOFs (phi, theta) node-major or phi alone.

    Parameters
    ----------
    p : int
        Element order.
    L : array_like, shape (n,)
        Element lengths (m).
    GJ : array_like
        St Venant stiffness G J_t (N m^2).
    ECw : array_like
        Warping stiffness E C_w (N m^4); unused without warping.
    kappa_w : array_like
        Penalty kappa_w (N m^2) on phi' - theta; unused without warping.
    warping : bool
        With the warping DOF theta.

    Returns
    -------
    numpy.ndarray
        (n, 2(p+1), 2(p+1)) with warping, else (n, p+1, p+1) (N m/rad).
    """
    L = np.atleast_1d(np.asarray(L, float))
    st_venant = tim.bar_stiffness(p, L, GJ)
    if not warping:
        return st_venant
    K = tim.beam_stiffness(p, L, ECw, kappa_w)  # EI psi'^2 + kGA (w' - psi)^2 analogue
    K[:, 0::2, 0::2] += st_venant
    return K


def torsion_mass(
    p: int, L: ArrayLike, rhoIp: ArrayLike, rhoCw: ArrayLike, warping: bool
) -> np.ndarray:
    """Element mass of rail torsion (T4, roll part), DOFs as :func:`torsion_stiffness`.

    Parameters
    ----------
    p : int
        Element order.
    L : array_like, shape (n,)
        Element lengths (m).
    rhoIp : array_like
        Roll inertia about the shear centre per unit length (kg m).
    rhoCw : array_like
        Warping inertia rho C_w (kg m^3); unused without warping.
    warping : bool
        With the warping DOF theta.

    Returns
    -------
    numpy.ndarray
        (n, 2(p+1), 2(p+1)) with warping, else (n, p+1, p+1) (kg m^2).
    """
    if not warping:
        return tim.bar_mass(p, L, rhoIp)
    return tim.beam_mass(p, L, rhoIp, rhoCw)
