"""The paper's equations (Shih, Ambur & Dixon 2023, Eqs 1-19), one pure function each.

Every function takes and returns SI values. Where an equation as printed cannot be right
or is ambiguous, the function takes a ``reading`` argument; the docstring says what is
printed, what each reading computes and which one reproduces the paper's Table 2. The
readings the package uses by default are chosen in :mod:`exudyn_turnout.corunning.parameters`.
"""

from __future__ import annotations

import math

__all__ = [
    "effective_length_rail",
    "continuous_support_stiffness",
    "static_track_stiffness",
    "ballast_stiffness_middle",
    "ballast_stiffness_edge",
    "sleeper_effective_length",
    "pad_stiffness",
    "pad_damping",
    "ballast_spring_stiffness",
    "ballast_spring_damping",
    "stiffness_ratio",
    "shear_modulus",
    "extra_layer_damping",
    "lateral_ballast_stiffness",
    "rail_mass",
    "switch_rail_mass",
    "sleeper_mass",
    "crossing_sleeper_mass",
    "sleeper_roll_inertia",
]


def effective_length_rail(K_st: float, k_s: float) -> float:
    """Eq 1: effective rail length L_eff,r = K_st / k_s (m).

    Parameters
    ----------
    K_st : float
        Static track stiffness at the rail (N/m), Eq 2.
    k_s : float
        Equivalent continuous support stiffness per unit length (N/m^2), Eq 2.

    Returns
    -------
    float
        Effective rail length L_eff,r (m): the length of rail whose supports carry a
        point load.
    """
    return K_st / k_s


def continuous_support_stiffness(k_p: float, k_b: float, L_s: float) -> float:
    """Eq 2 (first part): k_s = k_p k_b / (L_s (k_p + k_b)) (N/m^2).

    Pad k_p and equivalent ballast k_b (both N/m per support) in series, smeared over the
    sleeper spacing L_s (m).

    Parameters
    ----------
    k_p : float
        Rail pad stiffness per support (N/m).
    k_b : float
        Equivalent ballast stiffness per support (N/m), Eq 3 or Eq 4.
    L_s : float
        Sleeper spacing (m).

    Returns
    -------
    float
        Continuous support stiffness k_s per unit rail length (N/m^2).
    """
    return k_p * k_b / (L_s * (k_p + k_b))


def static_track_stiffness(EI: float, k_s: float) -> float:
    """Eq 2 (second part): K_st = 2 sqrt(2) (EI)^(1/4) k_s^(3/4) (N/m).

    Point stiffness of an infinite Euler-Bernoulli beam of bending stiffness EI (N m^2) on
    a Winkler foundation k_s (N/m^2); equal to 8 EI beta^3 with beta = (k_s/4EI)^(1/4).

    Parameters
    ----------
    EI : float
        Rail bending stiffness in the direction considered (N m^2).
    k_s : float
        Continuous support stiffness (N/m^2), first part of Eq 2.

    Returns
    -------
    float
        Static point stiffness K_st of the track at the rail (N/m).
    """
    return 2.0 * math.sqrt(2.0) * EI**0.25 * k_s**0.75


def ballast_stiffness_middle(s_b: float, L_eff_s: float) -> float:
    """Eq 3: equivalent ballast stiffness under a rail in the middle of the sleeper.

    k_b = s_b L_eff,s, with s_b (N/m^2) and L_eff,s from Eq 5, which is dimensionless as
    printed; the product is used as a stiffness in N/m, as the paper does.

    Parameters
    ----------
    s_b : float
        Ballast vertical stiffness per unit sleeper length (N/m^2).
    L_eff_s : float
        Effective sleeper length from Eq 5 (dimensionless as printed).

    Returns
    -------
    float
        Equivalent ballast stiffness k_b under the rail (N/m).
    """
    return s_b * L_eff_s


def ballast_stiffness_edge(s_b: float, L_t: float, n: int) -> float:
    """Eq 4: equivalent ballast stiffness under a rail at the edge of the sleeper.

    k_b = s_b L_t / n (N/m): the ballast under the whole sleeper of length L_t (m) shared
    by the n rails it carries (n = 2 in plain track, 3 in the crossing region).
    The same form gives the equivalent ballast damping with d_b (N s/m^2) for s_b.

    Parameters
    ----------
    s_b : float
        Ballast vertical stiffness per unit sleeper length (N/m^2), or the damping d_b
        (N s/m^2).
    L_t : float
        Sleeper length (m).
    n : int
        Number of rails the sleeper carries.

    Returns
    -------
    float
        Equivalent ballast stiffness k_b under one rail (N/m), or damping (N s/m).
    """
    return s_b * L_t / n


def sleeper_effective_length(
    L_t: float, s_b: float, EI_s: float, reading: str = "reciprocal"
) -> float:
    """Eq 5: effective length L_eff,s of a sleeper (finite beam on elastic foundation).

    Printed: L_eff,s = 2 / (L_t beta) with beta = (s_b / (4 E_s I_s))^(1/4) (1/m). For the
    UIC60 crossing sleeper (L_t = 4.06 m) that is 0.561. The paper's crossing-rail entries
    of Table 2 (k_rt2,z = 453e6 N/m, k_tg1,z = 134e6 N/m, m_r2 = 409 kg, m_t = 881 kg)
    reproduce only with the reciprocal, L_eff,s = L_t beta / 2 = 1.783. Both are
    dimensionless (beta L_t is), so neither is a length in metres; the reciprocal is what
    the authors evaluated.

    Parameters
    ----------
    L_t : float
        Sleeper length (m).
    s_b : float
        Ballast vertical stiffness per unit length (N/m^2).
    EI_s : float
        Sleeper bending stiffness (N m^2).
    reading : {"reciprocal", "printed"}
        ``"reciprocal"``: L_t beta / 2 (reproduces Table 2); ``"printed"``: 2 / (L_t beta).

    Returns
    -------
    float
        Effective sleeper length L_eff,s (dimensionless, see above).

    Raises
    ------
    ValueError
        For an unknown ``reading``.
    """
    beta_L = L_t * (s_b / (4.0 * EI_s)) ** 0.25
    if reading == "printed":
        return 2.0 / beta_L
    if reading == "reciprocal":
        return beta_L / 2.0
    raise ValueError(f"unknown reading of Eq 5: {reading!r}")


def pad_stiffness(k_p: float, L_eff_r: float, L_s: float) -> float:
    """Eq 6: co-running rail pad stiffness k_rt = k_p L_eff,r / L_s (N/m).

    Parameters
    ----------
    k_p : float
        Rail pad stiffness per support (N/m).
    L_eff_r : float
        Effective rail length (m), Eq 1.
    L_s : float
        Sleeper spacing (m).

    Returns
    -------
    float
        Pad stiffness k_rt of the co-running model (N/m).
    """
    return k_p * L_eff_r / L_s


def pad_damping(c_p: float, L_eff_r: float, L_s: float) -> float:
    """Eq 7: co-running rail pad damping c_rt = c_p L_eff,r / L_s (N s/m).

    Parameters
    ----------
    c_p : float
        Rail pad damping per support (N s/m).
    L_eff_r : float
        Effective rail length (m), Eq 1.
    L_s : float
        Sleeper spacing (m).

    Returns
    -------
    float
        Pad damping c_rt of the co-running model (N s/m).
    """
    return c_p * L_eff_r / L_s


def ballast_spring_stiffness(k_b: float, L_eff_r: float, L_s: float) -> float:
    """Eq 8: co-running ballast stiffness k_tg = k_b L_eff,r / L_s (N/m).

    Parameters
    ----------
    k_b : float
        Equivalent ballast stiffness per support (N/m), Eq 3 or 4.
    L_eff_r : float
        Effective rail length (m), Eq 1.
    L_s : float
        Sleeper spacing (m).

    Returns
    -------
    float
        Ballast stiffness k_tg of the co-running model (N/m).
    """
    return k_b * L_eff_r / L_s


def ballast_spring_damping(c_b: float, L_eff_r: float, L_s: float) -> float:
    """Eq 9: co-running ballast damping c_tg = c_b L_eff,r / L_s (N s/m).

    Parameters
    ----------
    c_b : float
        Equivalent ballast damping per support (N s/m), Eq 4 form.
    L_eff_r : float
        Effective rail length (m), Eq 1.
    L_s : float
        Sleeper spacing (m).

    Returns
    -------
    float
        Ballast damping c_tg of the co-running model (N s/m).
    """
    return c_b * L_eff_r / L_s


def stiffness_ratio(K: float, K_st: float) -> float:
    """Eqs 11 and 15: Delta = K / K_st (-).

    Delta_z = K_sw(x) / K_st,z with K_sw from Eq 10; Delta_y = K_sh(x) / K_st,y with K_sh
    from Eq 14, K_st the stock rail's static stiffness of Eq 2 in that direction.

    Parameters
    ----------
    K : float
        Static stiffness of the switch rail (Eq 10) or switch-rail head (Eq 14) at x (N/m).
    K_st : float
        Static stiffness of the stock rail in the same direction (N/m), Eq 2.

    Returns
    -------
    float
        Stiffness ratio Delta_z or Delta_y (-).
    """
    return K / K_st


def shear_modulus(E: float, nu: float, reading: str = "E/(2(1+nu))") -> float:
    """Shear modulus G (Pa) for Eq 12 ("Poisson's ratio of 0.3 is considered").

    ``"E/(2(1+nu))"`` is the isotropic relation (79.6 GPa for steel). Table 2's
    c_0j = 315e3 N s/m (stock) and 946e3 N s/m (crossing rail) reproduce only with
    ``"E(1+nu)/2"`` (134.6 GPa), a misplaced bracket: see :func:`extra_layer_damping`.

    Parameters
    ----------
    E : float
        Young's modulus (Pa).
    nu : float
        Poisson's ratio (-).
    reading : {"E/(2(1+nu))", "E(1+nu)/2"}
        The isotropic relation, or the misplaced bracket that reproduces Table 2.

    Returns
    -------
    float
        Shear modulus G (Pa).

    Raises
    ------
    ValueError
        For an unknown ``reading``.
    """
    if reading == "E/(2(1+nu))":
        return E / (2.0 * (1.0 + nu))
    if reading == "E(1+nu)/2":
        return E * (1.0 + nu) / 2.0
    raise ValueError(f"unknown reading of the shear modulus: {reading!r}")


def extra_layer_damping(A_r: float, G_r: float, rho_r: float, kappa: float = 0.4) -> float:
    """Eq 12: c_0j = 2 A_r sqrt(kappa G_r rho_r) (N s/m).

    The high-frequency point impedance of an infinite Timoshenko beam, where the shear
    wave (speed sqrt(kappa G / rho)) carries the load away in both directions. The paper
    prints kappa = 0.4 (Table 1's shear constant). With G = E/(2(1+nu)) = 79.6 GPa the
    UIC60 stock rail gives 242e3 N s/m; Table 2 prints 315e3 (= 1.30 times, G = 134.6 GPa).

    Parameters
    ----------
    A_r : float
        Rail cross-section area (m^2).
    G_r : float
        Rail shear modulus (Pa), see :func:`shear_modulus`.
    rho_r : float
        Rail density (kg/m^3).
    kappa : float
        Timoshenko shear coefficient (-).

    Returns
    -------
    float
        Damping c_0j of the extra rail layer (N s/m).
    """
    return 2.0 * A_r * math.sqrt(kappa * G_r * rho_r)


def lateral_ballast_stiffness(s_b_y: float, L_t: float) -> float:
    """Eq 13: lateral equivalent ballast stiffness k_b,y = s_b,y L_t (N/m).

    The whole sleeper length, not L_t / n: the co-running model has one lateral ballast
    spring per sleeper. The same form gives the damping with d_b,y.

    Parameters
    ----------
    s_b_y : float
        Lateral ballast stiffness per unit sleeper length (N/m^2), or the damping d_b,y
        (N s/m^2).
    L_t : float
        Sleeper length (m).

    Returns
    -------
    float
        Lateral equivalent ballast stiffness k_b,y (N/m), or damping (N s/m).
    """
    return s_b_y * L_t


def rail_mass(
    A_r: float, rho_r: float, L_eff_r: float, L_s: float, reading: str = "per_effective_length"
) -> float:
    """Eq 16: co-running rail mass m_r (kg).

    Printed: m_r = A_r rho_r L_eff,r / L_s, which has the unit kg/m (185 for the stock
    rail). ``"per_effective_length"`` (default) reads it as the rail mass over the
    effective length, A_r rho_r L_eff,r (kg): 111 kg, Table 2's value.

    Parameters
    ----------
    A_r : float
        Rail cross-section area (m^2).
    rho_r : float
        Rail density (kg/m^3).
    L_eff_r : float
        Effective rail length (m), Eq 1.
    L_s : float
        Sleeper spacing (m); used by the ``"printed"`` reading only.
    reading : {"per_effective_length", "printed"}
        ``"per_effective_length"``: A_r rho_r L_eff,r (reproduces Table 2);
        ``"printed"``: A_r rho_r L_eff,r / L_s.

    Returns
    -------
    float
        Co-running rail mass m_r (kg; kg/m for the ``"printed"`` reading).

    Raises
    ------
    ValueError
        For an unknown ``reading``.
    """
    if reading == "printed":
        return A_r * rho_r * L_eff_r / L_s
    if reading == "per_effective_length":
        return A_r * rho_r * L_eff_r
    raise ValueError(f"unknown reading of Eq 16: {reading!r}")


def switch_rail_mass(
    A_r: float,
    rho_r: float,
    L_eff_r: float,
    delta_z: float,
    L_s: float,
    reading: str = "per_effective_length",
) -> float:
    """Eq 17: switch rail mass, Eq 16 times Delta_z (kg); same readings as Eq 16.

    Parameters
    ----------
    A_r : float
        Switch rail cross-section area (m^2).
    rho_r : float
        Rail density (kg/m^3).
    L_eff_r : float
        Effective rail length (m), Eq 1.
    delta_z : float
        Vertical stiffness ratio Delta_z at the position (-), Eq 11.
    L_s : float
        Sleeper spacing (m); used by the ``"printed"`` reading only.
    reading : {"per_effective_length", "printed"}
        As in :func:`rail_mass`.

    Returns
    -------
    float
        Co-running switch rail mass (kg).
    """
    return rail_mass(A_r, rho_r, L_eff_r, L_s, reading) * delta_z


def sleeper_mass(
    A_s: float, rho_s: float, L_t: float, L_eff_r: float, delta_y: float, L_s: float, n: int = 1
) -> float:
    """Eq 18: co-running sleeper mass m_t = A_s rho_s (L_t / n) L_eff,r Delta_y / L_s (kg).

    Printed with the whole sleeper (n = 1): 1013 kg for plain track. Table 2 prints 500 kg
    (and J_t = 265 kg m^2, which needs m_t = 505 kg), reproduced by the rail's share of
    the sleeper, L_t / n with n = 2, the same share Eq 4 uses for the ballast, and
    Delta_y = 1.

    Parameters
    ----------
    A_s : float
        Sleeper cross-section area (m^2).
    rho_s : float
        Sleeper density (kg/m^3).
    L_t : float
        Sleeper length (m).
    L_eff_r : float
        Effective rail length (m), Eq 1.
    delta_y : float
        Lateral stiffness ratio Delta_y (-), Eq 15.
    L_s : float
        Sleeper spacing (m).
    n : int
        Number of rails sharing the sleeper (1 as printed, 2 reproduces Table 2).

    Returns
    -------
    float
        Co-running sleeper mass m_t (kg).
    """
    return A_s * rho_s * (L_t / n) * L_eff_r * delta_y / L_s


def crossing_sleeper_mass(
    A_s: float, rho_s: float, L_eff_s: float, L_eff_r: float, L_s: float
) -> float:
    """Eq 19: sleeper mass at the crossing m_t = A_s rho_s L_eff,s L_eff,r / L_s (kg).

    Parameters
    ----------
    A_s : float
        Sleeper cross-section area (m^2).
    rho_s : float
        Sleeper density (kg/m^3).
    L_eff_s : float
        Effective sleeper length (-), Eq 5.
    L_eff_r : float
        Effective rail length (m), Eq 1.
    L_s : float
        Sleeper spacing (m).

    Returns
    -------
    float
        Co-running crossing sleeper mass m_t (kg).
    """
    return A_s * rho_s * L_eff_s * L_eff_r / L_s


def sleeper_roll_inertia(m_t: float, L_t: float, h_t: float) -> float:
    """Table 2, J_t = m_t (L_t^2 + h_t^2) / 12 (kg m^2): a rectangle L_t wide, h_t high.

    Parameters
    ----------
    m_t : float
        Co-running sleeper mass (kg), Eq 18 or 19.
    L_t : float
        Sleeper length (m).
    h_t : float
        Sleeper height (m).

    Returns
    -------
    float
        Roll moment of inertia J_t of the sleeper about its centre (kg m^2).
    """
    return m_t * (L_t**2 + h_t**2) / 12.0
