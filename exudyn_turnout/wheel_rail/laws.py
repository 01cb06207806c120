"""Wheel/rail contact laws: Hertz normal force, creepages, Kalker creep with saturation.

The constants come from the vehicle file's ``[contact]`` table
(:class:`~exudyn_turnout.inputs.vehicle.ContactLaw`). Pure functions on floats (they run
inside the solver's user function, once per Newton iteration, so they avoid numpy for
scalars). Sign conventions: track frame x forward,
y to the left, z up; a wheel's side s = +1 (left) or -1 (right).
"""

from __future__ import annotations

import math

__all__ = [
    "hertz_force",
    "hertz_stiffness",
    "creep_coefficient",
    "saturation_factor",
    "longitudinal_creepage",
    "lateral_creepage",
    "flange_force",
]


def hertz_force(delta: float, C_H: float) -> float:
    """Hertz normal force C_H delta^1.5 (N) for penetration delta > 0, 0 in separation.

    Parameters
    ----------
    delta : float
        Normal penetration of wheel into rail (m); zero or negative in separation.
    C_H : float
        Hertz constant (N/m^1.5) of the contact (Hertz 1882; e.g. Johnson, Contact
        Mechanics, ch. 4), from the vehicle file's ``[contact]`` table.

    Returns
    -------
    float
        Normal contact force (N), compressive positive.
    """
    return C_H * delta * math.sqrt(delta) if delta > 0.0 else 0.0


def hertz_stiffness(delta: float, C_H: float) -> float:
    """Tangent stiffness of the Hertz contact dF/d delta = 1.5 C_H delta^0.5, 0 in separation.

    Parameters
    ----------
    delta : float
        Normal penetration of wheel into rail (m); zero or negative in separation.
    C_H : float
        Hertz constant (N/m^1.5), as in :func:`hertz_force`.

    Returns
    -------
    float
        Contact stiffness (N/m) at this penetration.
    """
    return 1.5 * C_H * math.sqrt(delta) if delta > 0.0 else 0.0


def creep_coefficient(f_ref: float, N: float, N_ref: float) -> float:
    """Kalker creep coefficient at normal load N: f_ref (N / N_ref)^(2/3).

    Kalker's linear coefficients scale with the contact area, which grows as N^(2/3) for a
    Hertz contact (Kalker 1967; e.g. Iwnicki, Handbook of Railway Vehicle Dynamics, ch. 4).

    Parameters
    ----------
    f_ref : float
        Creep coefficient (N) at the reference load.
    N : float
        Normal load of the contact (N); zero or negative in separation.
    N_ref : float
        Reference normal load (N) at which ``f_ref`` holds (> 0).

    Returns
    -------
    float
        Creep coefficient (N) at load N, 0 in separation.
    """
    return f_ref * (N / N_ref) ** (2.0 / 3.0) if N > 0.0 else 0.0


def saturation_factor(F: float, mu_N: float) -> float:
    """Johnson-Vermeulen saturation: the factor F_sat / F for a linear creep force F.

    F_sat = mu N (u - u^2/3 + u^3/27) for u = F / (mu N) < 3, else mu N
    (Johnson & Vermeulen 1964; e.g. Iwnicki, Handbook of Railway Vehicle Dynamics, ch. 4).

    Parameters
    ----------
    F : float
        Magnitude of the linear (Kalker) creep force (N).
    mu_N : float
        Friction limit mu N (N): friction coefficient times normal load.

    Returns
    -------
    float
        Factor (-) in [0, 1] that scales the linear creep force to the saturated one; 1 for
        F <= 0, 0 when there is no friction limit (mu_N <= 0).
    """
    if F <= 0.0 or mu_N <= 0.0:
        return 1.0 if F <= 0.0 else 0.0
    u = F / mu_N
    if u >= 3.0:
        return mu_N / F
    return (u - u * u / 3.0 + u**3 / 27.0) / u


def longitudinal_creepage(
    side: int, y: float, psi_t: float, v: float, b: float, r0: float, gamma: float, curvature: float
) -> float:
    """Longitudinal creepage xi_x of wheel ``side``: -s (gamma y / r0 + b psi_t / v + b kappa).

    The contact point's forward slip over the rail divided by v for a conical wheelset
    relative to a track of curvature kappa: rolling radius r0 + s gamma y, yaw about
    the centre, and the outer rail of a curve being longer (e.g. Iwnicki, Handbook of
    Railway Vehicle Dynamics, ch. 4).

    Parameters
    ----------
    side : int
        +1 for the left wheel, -1 for the right wheel.
    y : float
        Lateral displacement of the wheelset relative to the track (m, to the left).
    psi_t : float
        Yaw rate of the wheelset relative to the track (rad/s).
    v : float
        Forward speed (m/s, > 0).
    b : float
        Lateral semi-distance of the contact points (m).
    r0 : float
        Nominal rolling radius (m).
    gamma : float
        Equivalent conicity (-).
    curvature : float
        Track curvature kappa (1/m, positive for a curve to the left).

    Returns
    -------
    float
        Longitudinal creepage (-), positive when the wheel slides forward over the rail.
    """
    return -side * (gamma * y / r0 + b * psi_t / v + b * curvature)


def lateral_creepage(y_t: float, psi: float, v: float) -> float:
    """Lateral creepage xi_y = y_t / v - psi, the same for both wheels.

    Parameters
    ----------
    y_t : float
        Lateral velocity of the wheelset relative to the track (m/s).
    psi : float
        Yaw angle of the wheelset relative to the track (rad).
    v : float
        Forward speed (m/s, > 0).

    Returns
    -------
    float
        Lateral creepage (-).
    """
    return y_t / v - psi


def flange_force(gap: float, gap_t: float, k: float, c: float) -> float:
    """One-sided spring-damper flange force k gap + c gap_t, never pulling.

    Parameters
    ----------
    gap : float
        Penetration of the flange beyond the flangeway clearance (m); zero or negative
        while the flange is clear.
    gap_t : float
        Rate of that penetration (m/s).
    k : float
        Flange contact stiffness (N/m).
    c : float
        Flange contact damping (N s/m).

    Returns
    -------
    float
        Flange force (N), pushing the wheel back, zero when clear or when the damper would
        pull.
    """
    if gap <= 0.0:
        return 0.0
    return max(k * gap + c * gap_t, 0.0)
