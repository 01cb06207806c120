"""Wheel/rail contact laws: Hertz normal force, creepages, Kalker creep with saturation.

The constants come from the vehicle file's ``[contact]`` table
(:class:`~exudyn_turnout.inputs.vehicle.ContactLaw`). Pure functions on floats (they run inside the solver's user function, once per Newton
iteration, so they avoid numpy for scalars). Sign conventions: track frame x forward,
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
    """Hertz normal force C_H delta^1.5 (N) for penetration delta > 0 (m), 0 in separation."""
    return C_H * delta * math.sqrt(delta) if delta > 0.0 else 0.0


def hertz_stiffness(delta: float, C_H: float) -> float:
    """dF/d delta = 1.5 C_H delta^0.5 (N/m), 0 in separation."""
    return 1.5 * C_H * math.sqrt(delta) if delta > 0.0 else 0.0


def creep_coefficient(f_ref: float, N: float, N_ref: float) -> float:
    """Kalker coefficient at load N: f_ref (N / N_ref)^(2/3) (contact area ~ N^(2/3))."""
    return f_ref * (N / N_ref) ** (2.0 / 3.0) if N > 0.0 else 0.0


def saturation_factor(F: float, mu_N: float) -> float:
    """Johnson-Vermeulen saturation: the factor F_sat / F for a linear creep force F (N).

    F_sat = mu N (u - u^2/3 + u^3/27) for u = F / (mu N) < 3, else mu N
    (Johnson & Vermeulen 1964; e.g. Iwnicki, Handbook of Railway Vehicle Dynamics, ch. 4).
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
    """xi_x of wheel ``side``: -s (gamma y / r0 + b psi_t / v + b kappa).

    The contact point's forward slip over the rail divided by v for a conical wheelset
    of lateral displacement y (m) and yaw rate psi_t (rad/s) relative to a track of
    curvature kappa (1/m, positive to the left): rolling radius r0 + s gamma y, yaw about
    the centre, and the outer rail of a curve being longer.
    """
    return -side * (gamma * y / r0 + b * psi_t / v + b * curvature)


def lateral_creepage(y_t: float, psi: float, v: float) -> float:
    """xi_y = y_t / v - psi: lateral slip of both wheels (yaw angle psi relative to the track)."""
    return y_t / v - psi


def flange_force(gap: float, gap_t: float, k: float, c: float) -> float:
    """One-sided flange force (N) for penetration ``gap`` (m) beyond the clearance, rate gap_t."""
    if gap <= 0.0:
        return 0.0
    return max(k * gap + c * gap_t, 0.0)
