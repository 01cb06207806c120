"""Compiled wheel/rail contact of one wheelset: every contact point of a step in one call.

The tables of :mod:`.tables` hold, for each rail body a wheel can touch, the candidate
contact points over the section position x and the wheel's lateral shift.
:mod:`.packed_tables` packs the tables of one wheelset into flat arrays; this module
evaluates, in one numba-compiled call, for every body and every candidate at the current state:

1. **Geometry** as :func:`.tables.lookup_values` does it (bilinear in cells whose four nodes
   hold the same contact points, else the cell's first node with the gap carried to the
   query's shift to first order), the normal gap carried to the wheel's lift,
   ``gap + cos(gamma) lift``.  The contact's position (on rail and wheel, and the moment
   arms) is the node's force centre at the penetration (:func:`.node_laws.node_centre`):
   the point of the rail surface on the normal force's line of action through it
   (:func:`.node_laws.centre_point`).
2. **Normal force** along the contact normal, the node's law
   ``N_ref (delta / DELTA_REF)^n`` (:mod:`.nonhertz`: exact Hertz ``C_H delta^1.5`` where the
   Hertz ellipse fits the surfaces, a power law through two Kik-Piotrowski solutions
   where it does not: flat faces, corners, conformal points; one compiled law with the
   tables' lookup, :func:`.node_laws.node_normal_force`), plus an optional normal
   damping ``c d(delta)/dt`` (never pulling).  The semi-axes for the creep law follow the
   same per-node law (Hertz's ellipse, or the equivalent ellipse of the KP patch).
   Where the rail's gap varies along x (the lead's search below) the law is corrected for
   the patch along x (:func:`.along_x.patch_along_x`: a slender line model on the actual gap along
   x against the same model on the node law's parabola; at the check rail's flare end the
   flare truncates the patch, 0.4-0.6 of the node law's force, within ~1 % of the exact
   half-space solution on a synthetic kink): the force, its stiffness, the semi-axis a and
   the contact's x (the force centre).  Not applied below a change of
   :data:`.along_x.PATCH_DEADBAND` (so prismatic rails, the rigid-envelope tables and the through
   route's runs are unchanged to the bit).
3. **Creepages** at the contact point from the wheelset's motion relative to the rail body
   (derivation below) and **creep forces** of Kalker's FASTSIM, interpolated in the creep
   table of :mod:`.creep_table` (``|F| <= mu N`` by construction), with Kalker's
   coefficients for the node's ellipse shape; Polach's method
   (:func:`.creep.polach_creep_forces`, compiled) is selectable in
   :func:`.packed_tables.pack_tables`.
4. **Generalised forces** on the wheelset (lateral, vertical, roll, yaw, spin perturbation)
   and, opposite, on each rail body's lateral and vertical coordinate.

Frames and signs.  Track frame: X forward, Y to the left, Z up.  Side s = +1 for the left
wheel, -1 for the right.  Table quantities are in side coordinates (y from the track centre
towards the wheel's field side, so track Y = s y).  A contact angle gamma > 0 tilts the
normal towards the track centre: the unit normal on the wheel is
``n = (0, -s sin(gamma), cos(gamma))`` and the lateral unit tangent
``t = (0, cos(gamma), s sin(gamma))``, so (X, t, n) is right-handed.  The contact point
sits at ``(x_c, Y_c, -r)`` from the wheelset centre, ``Y_c = s y_rail - y_w`` (y_rail from the
table, y_w the wheelset's lateral displacement) and ``x_c`` the table's longitudinal offset.
The wheel's lateral shift relative to a rail body is ``s (y_w + r0 phi - y_rail_body)``: a
roll phi moves the running surface, r0 below the axle, sideways by r0 phi; its lift at the
contact point is ``z_w + Y_c phi - z_rail_body``.

Creepages.  In the track-following frame, which moves at v and turns at v kappa, a rail
point at lateral Y moves backwards at v (1 - kappa Y); the wheelset turns about its axle at
``Omega = v / r0 + beta_t`` (beta: spin perturbation), about X at the roll rate and about Z
at the yaw rate psi_t relative to the track.  The wheel's material velocity at the contact
minus the rail's, divided by v:

- longitudinal ``xi = 1 - kappa Y_c - Omega r / v - Y_c psi_t / v``;
- lateral, along t: ``eta = (u_Y cos(gamma) + u_Z s sin(gamma)) / v`` with
  ``u_Y = y_w_t - y_r_t - v psi + r phi_t`` and ``u_Z = z_w_t + Y_c phi_t - z_r_t``;
- spin, the wheelset's angular velocity along n, over v:
  ``phi_s = (-s Omega sin(gamma) + psi_t cos(gamma)) / v``.

Known approximation: the lateral component of a normal force uses the contact angle of
the table (interpolated), whereas the tabulated gap changes with the shift by the secant
of its nodes; where the angle changes fast with the shift (flange root: ~0.1 rad per
0.2 mm step) the two differ by up to ~17 %, on the tread by < 2 %
(tests/test_wheel_rail_kernel.py).

Lead (:mod:`.lead`): on the yawed wheelset a contact lies ``x_lead = r sin(theta)``,
``sin(theta) = s tan(gamma) tan(psi)``, ahead of the axle, closer to the rail by
``r (1 - cos(theta)) cos(gamma)`` along the normal; its moment arm is ``x_c + x_lead`` and
the wheel's vertical material velocity there, ``-Omega x_lead``, enters ``eta``.  Where the
rail varies along x (a flare, a ramp, a blade) the contact is not at the yaw's lead: along
x the wheel's distance to the rail is the parabola ``(xi - x_yaw)^2 / (2 R_x)``, ``R_x = r /
cos(gamma)`` (4.4 m for a flange back at 84 deg, 0.46 m on the tread), plus the rail's gap
at ``x + xi``, piecewise linear between the table's x nodes that hold the point, plus a
profile term ``sin(gamma)^2 xi^4 / (8 r^2 (rho_w + rho_r))`` (the point xi ahead lies
``xi^2 / (2 r)`` higher, which slides the two curved profiles along their tangent; it
matters at a flange back's millimetre rises); :func:`.along_x.lead_along_x` takes its minimum
within the lead's cap (on a slope a, without the profile term, at ``x_yaw - a R_x``,
closing ``a^2 R_x / 2`` more than the first order ``a x_yaw``; at a slope change, the
flare's end, where the slopes on both sides point to it: on the packaged check rail
31 ... 36 mm ahead, within 1 mm and 3 ... 15 um of the 3-D gap on its exact sections,
validation/check_rail_kink.md).  The walk along x stops where the table's slopes
(:func:`.packed_tables.gap_slope_bound`, ``bounds[:, 4]``) cannot move the contact
further.  Not on a body whose table is already the rigid wheel's envelope along x (blade,
wing rail, nose, slices: :func:`.sections.wheel_envelope`, the table's ``x_offset`` not all
0; its bound is stored negative): the envelope holds the wheel's circle already, a second
minimum with the parabola would count it twice (on the UK crossing it moved the nose's
first touch against the wing rail's by 11-16 um, validation/two_patch_split.md), so there
the contact stays at the yaw's lead and takes the envelope's gap there (the first order of
before).  Left out there: the tilt of the contact's tangent plane along x (the rail's plan
angle alpha adds ``alpha cos(gamma)`` to ``eta``; the lead's term gives the ``alpha
sin(gamma) tan(gamma)`` part, 98 % of the lateral creepage's change at 81 deg).

Left out (small here, named so a reader can judge): the rail's own roll, the wheel's
roll relative to the rail in the contact geometry (it tilts the contact angle by phi), and
the rail's longitudinal curvature in the Hertz constant.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from exudyn_turnout.wheel_rail.along_x import (
    BETA_PER_B,
    EMPTY_GAP,
    GAP_FIELD,
    PATCH_DEADBAND,
    PATCH_SCRATCH,
    PATCH_SLENDER,
    X_BLEND_DISTANCE,
    Y_RAIL_FIELD,
    lead_along_x,
    patch_along_x,
)
from exudyn_turnout.wheel_rail.creep_table import table_creep_scalar
from exudyn_turnout.wheel_rail.lead import MAX_LEAD_SINE
from exudyn_turnout.wheel_rail.node_laws import (
    DELTA_REF,
    centre_point,
    node_centre,
    node_normal_force,
    node_offset,
)
from exudyn_turnout.wheel_rail.packed_tables import NODE_FIELDS

__all__ = [
    "DETAIL_FIELDS",
    "contact_forces",
    "contact_history",
    "polach_scalar",
    "X_BLEND_DISTANCE",
]

# Indices of the packed node fields (.packed_tables.NODE_FIELDS)
_GAP, _Y_RAIL = GAP_FIELD, Y_RAIL_FIELD  # (.along_x reads these two)
_Z_RAIL, _S_WHEEL = NODE_FIELDS.index("z_rail"), NODE_FIELDS.index("s_wheel")
_ANGLE, _RADIUS = NODE_FIELDS.index("angle"), NODE_FIELDS.index("radius")
_F_REF, _F_EXP = NODE_FIELDS.index("f_ref"), NODE_FIELDS.index("f_exp")
_X_OFFSET = NODE_FIELDS.index("x_offset")
_SIN, _COS = NODE_FIELDS.index("sin"), NODE_FIELDS.index("cos")
_A_REF, _A_EXP = NODE_FIELDS.index("a_ref"), NODE_FIELDS.index("a_exp")
_B_REF, _B_EXP = NODE_FIELDS.index("b_ref"), NODE_FIELDS.index("b_exp")
_C11, _C22, _C23 = NODE_FIELDS.index("c11"), NODE_FIELDS.index("c22"), NODE_FIELDS.index("c23")
_SEMI = NODE_FIELDS.index("semi_hertzian")
_CENTRE, _CENTRE_EXP = NODE_FIELDS.index("centre"), NODE_FIELDS.index("centre_exp")
_OFFSET_C2, _OFFSET_C3 = NODE_FIELDS.index("offset_c2"), NODE_FIELDS.index("offset_c3")
_SLIDE = NODE_FIELDS.index("slide")
_N_FIELDS = len(NODE_FIELDS)
_EMPTY = EMPTY_GAP
_X_BLEND = X_BLEND_DISTANCE

#: Columns of the per-contact detail rows written by :func:`contact_forces`.
DETAIL_FIELDS = (
    "body",  # index of the rail body
    "candidate",  # candidate slot within the body
    "normal",  # N, normal force magnitude (>= 0)
    "Fz",  # N, vertical force on the wheel
    "Fy",  # N, lateral force on the wheel (track Y, to the left)
    "Fx",  # N, longitudinal creep force on the wheel
    "Ft",  # N, lateral creep force on the wheel along the tangent t
    "y_rail",  # m, contact position on the rail (side coordinates)
    "z_rail",  # m, contact height on the rail
    "s_wheel",  # m, contact position on the wheel from its taping line
    "angle",  # rad, contact angle
    "xi",  # longitudinal creepage
    "eta",  # lateral creepage
    "spin",  # 1/m, spin creepage
    "delta",  # m, normal penetration (negative: separated)
    "radius",  # m, rolling radius
    "x_offset",  # m, contact point ahead of the wheel centre
    "a",  # m, semi-axis, rolling direction (Hertz, or KP's equivalent ellipse)
    "b",  # m, semi-axis, lateral (Hertz, or KP's equivalent ellipse)
    "found",  # weight of the table nodes that hold this point (1: all; 0: not found)
    "carried",  # weight of the table nodes at which it carries load
    "stiffness",  # N/m, normal contact stiffness dN/d(delta) (elastic part)
    "semi_hertzian",  # weight of the nodes whose law is Kik-Piotrowski (0: Hertz)
)
_N_DETAIL = len(DETAIL_FIELDS)


@numba.njit(cache=True)
def polach_scalar(xi, eta, phi, a, b, Q, mu, G, c11, c22, c23):  # pragma: no cover (compiled)
    """Polach's creep forces (1999) for one contact, compiled: (F_x, F_y) on the wheel.

    The formulas of :func:`.creep.polach_creep_forces` with ``k_A = k_S = 1`` and the
    resultant bounded by ``mu Q`` (tested equal to it), for scalar inputs and Kalker's
    coefficients given.

    Parameters
    ----------
    xi, eta : float
        Longitudinal and lateral creepage (-).
    phi : float
        1/m, spin creepage.
    a, b : float
        m, Hertz semi-axes in rolling and lateral direction.
    Q : float
        N, normal force (> 0).
    mu : float
        Friction coefficient.
    G : float
        Pa, shear modulus.
    c11, c22, c23 : float
        Kalker's coefficients of the ellipse.

    Returns
    -------
    tuple of float
        N, longitudinal and lateral creep force on the wheel.
    """
    if Q <= 0.0 or a <= 0.0 or b <= 0.0:
        return 0.0, 0.0
    q_mu = Q * mu
    eta_spin = eta + phi * a
    eta_c = eta_spin if abs(eta_spin) > abs(eta) else eta
    s = math.hypot(xi, eta)
    s_c = math.hypot(xi, eta_c)
    if s_c <= 0.0:
        return 0.0, 0.0
    fx = 0.0
    fy = 0.0
    if s > 0.0:  # translational force, saturated with the resultant creepage s_C
        c_jj = math.hypot(c11 * xi / s, c22 * eta / s)
        eps = math.pi * G * a * b * c_jj * s_c / (4.0 * q_mu)
        force = 2.0 * q_mu / math.pi * (eps / (1.0 + eps * eps) + math.atan(eps))
        fx = -force * xi / s_c
        fy = -force * eta / s_c
    growth = 1.0 + 6.3 * (1.0 - math.exp(-a / b))
    eps_m = (8.0 / 3.0) * G * b * math.sqrt(a * b) / q_mu * c23 * eta_c / growth
    delta = (eps_m * eps_m - 1.0) / (eps_m * eps_m + 1.0)
    k_m = (
        abs(eps_m) * (delta**3 / 3.0 - delta * delta / 2.0 + 1.0 / 6.0)
        - math.sqrt(max(1.0 - delta * delta, 0.0) ** 3) / 3.0
    )
    fy += (9.0 / 16.0) * a * q_mu * k_m * growth * phi / s_c
    resultant = math.hypot(fx, fy)
    if resultant > q_mu:  # Coulomb: |F| <= mu Q (guard, see creep's docstring)
        fx *= q_mu / resultant
        fy *= q_mu / resultant
    return fx, fy


@numba.njit(cache=True)
def _interpolate(values, v_base, n_s, n_c, c, tx, ts, blend, out):  # pragma: no cover (compiled)
    """Interpolated fields of candidate c into ``out`` (20,); the gap is not yet carried."""
    row = n_c * _N_FIELDS
    plane = n_s * row
    i00 = v_base + c * _N_FIELDS
    if blend:
        i10 = i00 + plane
        i01 = i00 + row
        i11 = i10 + row
        for f in range(_N_FIELDS):
            v00 = values[i00 + f]
            v10 = values[i10 + f]
            v01 = values[i01 + f]
            v11 = values[i11 + f]
            out[f] = v00 + tx * (v10 - v00) + ts * ((v01 - v00) + tx * (v11 - v10 - v01 + v00))
    else:
        for f in range(_N_FIELDS):
            out[f] = values[i00 + f]


@numba.njit(cache=True)
def _bilinear(values, i00, n_s, n_c, tx, ts):  # pragma: no cover (compiled)
    """One field of :func:`_interpolate`'s bilinear form (the same floats), its node value
    at flat index ``i00``."""
    row = n_c * _N_FIELDS
    i10 = i00 + n_s * row
    v00 = values[i00]
    v10 = values[i10]
    v01 = values[i00 + row]
    v11 = values[i10 + row]
    return v00 + tx * (v10 - v00) + ts * ((v01 - v00) + tx * (v11 - v10 - v01 + v00))


@numba.njit(cache=True)
def _point(
    fields, gap, weight, s, row, i_y, i_z, q, q_t, shift_t, z_irr, omega, constants, forces,
    details, creep, creep_at, walk, xs, x, mu,
):  # pragma: no cover (compiled)  # fmt: skip
    """Forces of one contact point (node or interpolated ``fields``, normal ``gap`` at zero
    lift), times ``weight``, added to ``forces`` and ``details[row]``; 1 if it carries load.
    ``creep[creep_at:]`` holds the creep table (``creep_at`` < 0: Polach's law) behind the
    node values; ``walk`` (i_node, k0, n_x, plane, b_offset, w_b, slope bound, pair) where
    the slot lies in them for :func:`.along_x.lead_along_x` (i_node < 0: the rail prismatic),
    ``xs`` the body's x nodes, ``x`` the wheelset's position, ``mu`` the body's friction."""
    v, G, damping, kappa = constants[0], constants[3], constants[4], constants[5]
    sin_g, cos_g = fields[_SIN], fields[_COS]
    norm = math.hypot(sin_g, cos_g)
    sin_g, cos_g = sin_g / norm, cos_g / norm
    y_w, z_w, phi, psi = q[0], q[1], q[2], q[3]
    Y_c = s * fields[_Y_RAIL] - y_w
    r = fields[_RADIUS]
    lift = z_w + Y_c * phi - q[i_z] - z_irr
    lift_t = q_t[1] + Y_c * q_t[2] - q_t[i_z]
    # lead of the contact on the yawed wheel and the gap it closes (.lead.contact_lead)
    lead = s * sin_g * math.tan(psi)
    cap = MAX_LEAD_SINE * cos_g
    lead = (min(max(lead, -cap), cap) / cos_g) if cos_g > 0.0 else 0.0
    x_lead = r * lead
    x_yaw = x_lead
    radius_x = 0.0
    quartic = 0.0
    limit = 0.0
    if walk[0] >= 0.0 and cos_g > 0.0 and walk[6] != 0.0:
        # the rail's gap along x (piecewise linear between the table's nodes) moves the
        # contact off the yaw's lead: the minimum of the wheel's parabola and profile term
        # plus the rail, searched within the lead's cap and as far as the table's slopes
        # can take it (between x_yaw -+ reach and 0, lead_along_x's docstring); on a table
        # of the wheel's envelope (negative bound) the rail's gap at the yaw's lead alone
        radius_x = r / cos_g
        limit = MAX_LEAD_SINE * r
        quartic = sin_g * sin_g * fields[_SLIDE] / (8.0 * r * r)
        if walk[6] > 0.0:
            reach = walk[6] * radius_x
            lo = max(min(x_lead - reach, 0.0), -limit)
            hi = min(max(x_lead + reach, 0.0), limit)
        else:
            lo = x_lead
            hi = x_lead
        x_lead, change = lead_along_x(
            creep, xs, int(walk[0]), int(walk[1]), walk[7] > 0.0, int(walk[2]), int(walk[3]),
            int(walk[4]), walk[5], x, x_lead, radius_x, quartic, lo, hi,
        )  # fmt: skip
        gap += change
    gap -= r * lead * lead / (1.0 + math.sqrt(1.0 - lead * lead)) * cos_g
    delta = -(gap + cos_g * lift)
    # where the rail's gap along x was searched, the patch along x it gives (patch_along_x):
    # the ratio of its force to the node law's, of its length, and its force centre
    kink = 1.0
    kink_rate = 0.0
    kink_length = 1.0
    if walk[0] >= 0.0 and cos_g > 0.0 and walk[6] > 0.0 and delta > 0.0:
        log_delta = math.log(delta / DELTA_REF)
        a_node = fields[_A_REF] * math.exp(fields[_A_EXP] * log_delta)
        b_node = fields[_B_REF] * math.exp(fields[_B_EXP] * log_delta)
        level = a_node * a_node / (2.0 * radius_x)
        # only on slender patches (PATCH_SLENDER), blended in smoothly from half of it
        slender = 0.0
        if b_node > 0.0:
            u = (2.0 * a_node / b_node - PATCH_SLENDER) / PATCH_SLENDER
            slender = 1.0 if u >= 1.0 else (u * u * (3.0 - 2.0 * u) if u > 0.0 else 0.0)
        if level > 0.0 and slender > 0.0:
            ratio_x, rate_x, length_x, centre_x = patch_along_x(
                creep, xs, int(walk[0]), int(walk[1]), walk[7] > 0.0, int(walk[2]),
                int(walk[3]), int(walk[4]), walk[5], x, x_yaw, radius_x, quartic, x_lead,
                delta, level, 2.0 * fields[_A_EXP] * level / delta, BETA_PER_B * b_node,
                fields[_B_EXP], walk[6], limit, np.empty(PATCH_SCRATCH),
            )  # fmt: skip
            # applied beyond PATCH_DEADBAND, blended in smoothly up to twice it
            z = abs(ratio_x - 1.0) / PATCH_DEADBAND
            if z > 1.0:
                blend = 1.0
                blend_z = 0.0
                if z < 2.0:
                    blend = (z - 1.0) * (z - 1.0) * (5.0 - 2.0 * z)
                    blend_z = 6.0 * (z - 1.0) * (2.0 - z)
                blend *= slender
                blend_z *= slender
                kink = 1.0 + (ratio_x - 1.0) * blend
                kink_rate = (blend + z * blend_z) * ratio_x * rate_x / kink
                kink_length = 1.0 + (length_x - 1.0) * blend
                x_lead += (centre_x - x_lead) * blend
    # the contact position: the force centre at this penetration (.node_laws.node_centre)
    # on the rail surface, on the force's line of action (.node_laws.centre_point)
    moved = node_centre(fields[_CENTRE], fields[_CENTRE_EXP], delta)
    offset = node_offset(fields[_OFFSET_C2], fields[_OFFSET_C3], moved)
    moved_y, moved_z = centre_point(moved, offset, sin_g, cos_g)
    Y_c += s * moved_y
    if details[row, 14] == -1.0:  # first corner that finds this slot
        details[row, 14] = 0.0
    details[row, 19] += weight
    details[row, 7] += weight * (fields[_Y_RAIL] + moved_y)
    details[row, 8] += weight * (fields[_Z_RAIL] + moved_z)
    details[row, 9] += weight * (fields[_S_WHEEL] + moved_y)
    details[row, 10] += weight * math.atan2(sin_g, cos_g)
    details[row, 14] += weight * delta
    details[row, 15] += weight * r
    details[row, 16] += weight * (fields[_X_OFFSET] + x_lead)
    if delta <= 0.0:
        return 0
    delta_t = -(cos_g * lift_t - sin_g * shift_t)
    # the node's normal law N_ref (delta / DELTA_REF)^n and semi-axes (see .nonhertz)
    ratio = math.log(delta / DELTA_REF)
    elastic = node_normal_force(fields[_F_REF], fields[_F_EXP], delta) * kink
    normal = elastic + damping * delta_t
    if normal <= 0.0:
        return 0
    a = fields[_A_REF] * math.exp(fields[_A_EXP] * ratio) * kink_length
    b = fields[_B_REF] * math.exp(fields[_B_EXP] * ratio)
    fx = 0.0
    ft = 0.0
    xi = 0.0
    eta = 0.0
    spin = 0.0
    if v > 0.0:
        psi_t = q_t[3]
        xi = 1.0 - kappa * Y_c - omega * r / v - Y_c * psi_t / v
        u_y = q_t[0] - q_t[i_y] - v * psi + r * q_t[2]
        # the wheel's material at the lead moves vertically at -omega x_lead
        eta = (u_y * cos_g + (lift_t - omega * x_lead) * s * sin_g) / v
        spin = (-s * omega * sin_g + psi_t * cos_g) / v
        if creep_at >= 0:  # FASTSIM's forces from the creep table (.creep_table)
            fx, ft = table_creep_scalar(
                creep, creep_at, xi, eta, spin, a, b, normal, mu, G, fields[_C11],
                fields[_C22], fields[_C23],
            )  # fmt: skip
        else:
            fx, ft = polach_scalar(
                xi, eta, spin, a, b, normal, mu, G, fields[_C11], fields[_C22], fields[_C23]
            )
    F_Y = weight * (-s * sin_g * normal + cos_g * ft)
    F_Z = weight * (cos_g * normal + s * sin_g * ft)
    fx *= weight
    x_c = fields[_X_OFFSET] + x_lead
    r_arm = r - moved_z  # the contact position's depth below the axle
    forces[0] += F_Y
    forces[1] += F_Z
    forces[2] += Y_c * F_Z + r_arm * F_Y
    forces[3] += x_c * F_Y - Y_c * fx
    forces[4] += -r_arm * fx - x_c * F_Z
    forces[i_y] -= F_Y
    forces[i_z] -= F_Z
    details[row, 20] += weight
    details[row, 2] += weight * normal
    details[row, 3] += F_Z
    details[row, 4] += F_Y
    details[row, 5] += fx
    details[row, 6] += weight * ft
    details[row, 11] += weight * xi
    details[row, 12] += weight * eta
    details[row, 13] += weight * spin
    details[row, 17] += weight * a
    details[row, 18] += weight * b
    details[row, 21] += weight * (fields[_F_EXP] + kink_rate) * elastic / delta
    details[row, 22] += weight * fields[_SEMI]
    return 1


@numba.njit(cache=True)
def contact_forces(
    x,
    q,
    q_t,
    irregularity,
    values,
    blendable,
    xs,
    layout,
    bounds,
    constants,
    forces,
    details,
):  # pragma: no cover (compiled; tested through its Python callers)
    """All contacts of one wheelset at one instant (see the module docstring).

    Parameters
    ----------
    x : float
        m, wheelset position along the route.
    q, q_t : numpy.ndarray
        Coordinates and velocities: ``[y_w, z_w, phi, psi, beta, ...]`` then the rail bodies'
        coordinates at the indices of ``layout``.
    irregularity : numpy.ndarray
        (4,) m at x: vertical left, vertical right, lateral left, lateral right (track Y).
    values, blendable, xs, layout, bounds : numpy.ndarray
        From :class:`.packed_tables.PackedTables`.
    constants : numpy.ndarray
        v (m/s), r0 (m), mu, G (Pa), normal damping (N s/m), curvature (1/m).
    forces : numpy.ndarray
        Output, generalised forces on q (zeroed, then filled).
    details : numpy.ndarray
        Output, (n_bodies * n_c, len(DETAIL_FIELDS)) per-contact rows (filled).

    Returns
    -------
    int
        Number of contacts carrying load.
    """
    v, r0 = constants[0], constants[1]
    for i in range(forces.shape[0]):
        forces[i] = 0.0
    details[:, :] = 0.0
    finite = math.isfinite(x)
    for i in range(q.shape[0]):
        finite = finite and math.isfinite(q[i]) and math.isfinite(q_t[i])
    for i in range(irregularity.shape[0]):
        finite = finite and math.isfinite(irregularity[i])
    if not finite:  # a diverged state: NaN forces (the solver stops and says where)
        for i in range(forces.shape[0]):
            forces[i] = math.nan
        return 0
    y_w, phi = q[0], q[2]
    omega = (v / r0 + q_t[4]) if v > 0.0 else 0.0
    n_values = values.shape[0]  # the creep law is packed behind the nodes (pack_tables)
    creep_at = int(values[n_values - 2]) if values[n_values - 1] > 0.5 else -1
    fields = np.empty(_N_FIELDS)
    walk = np.empty(8)  # where a slot's gaps lie along x, for lead_along_x (see _point)
    n_max = details.shape[0] // max(layout.shape[0], 1)
    loaded = 0
    for k in range(layout.shape[0]):
        v_off, b_off, x_off = layout[k, 0], layout[k, 1], layout[k, 2]
        n_x, n_s, n_c, s = layout[k, 3], layout[k, 4], layout[k, 5], layout[k, 6]
        i_y, i_z = layout[k, 7], layout[k, 8]
        shift0, step, x_from, x_to = bounds[k, 0], bounds[k, 1], bounds[k, 2], bounds[k, 3]
        walk[2], walk[3], walk[6] = n_x, n_s * n_c * _N_FIELDS, bounds[k, 4]
        # the body's own friction (a check rail's), else the vehicle's
        mu = bounds[k, 5] if bounds.shape[1] > 5 and bounds[k, 5] > 0.0 else constants[2]
        xs_body = xs[x_off : x_off + n_x]
        for c in range(n_max):
            details[k * n_max + c, 0] = k
            details[k * n_max + c, 1] = c
            details[k * n_max + c, 14] = -1.0
        if x < x_from or x > x_to:
            continue
        z_irr = irregularity[0] if s > 0 else irregularity[1]
        y_irr = irregularity[2] if s > 0 else irregularity[3]
        # the wheel's lateral shift towards its field side, relative to the rail body
        # (the roll phi moves the wheel's running surface, r0 below the axle, by r0 phi)
        shift = s * (y_w + r0 * phi - q[i_y] - y_irr)
        shift_t = s * (q_t[0] + r0 * q_t[2] - q_t[i_y])
        # cell along x (clamped to the table)
        lo = 0
        hi = n_x - 1
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if xs[x_off + mid] <= x:
                lo = mid
            else:
                hi = mid
        ix = lo
        x0 = xs[x_off + ix]
        tx = min(max((x - x0) / (xs[x_off + ix + 1] - x0), 0.0), 1.0)
        position = min(max((shift - shift0) / step, 0.0), n_s - 1.000001)
        js = int(position)
        ts = position - js
        blend = blendable[b_off + ix * n_s + js] != 0
        v_base = v_off + (ix * n_s + js) * n_c * _N_FIELDS
        plane = n_s * n_c * _N_FIELDS
        if blend:
            for c in range(n_c):
                # the gap first: an empty slot (most of them) skips the other fields
                if not _bilinear(values, v_base + c * _N_FIELDS, n_s, n_c, tx, ts) < _EMPTY:
                    continue
                _interpolate(values, v_base, n_s, n_c, c, tx, ts, True, fields)
                # the slot's gaps along x at the query's shift (bilinear form's x nodes)
                walk[0], walk[1], walk[4], walk[5] = v_base + c * _N_FIELDS, ix, n_c * _N_FIELDS, ts
                walk[7] = 1.0
                if fields[_GAP] < _EMPTY:
                    loaded += _point(
                        fields, fields[_GAP], 1.0, s, k * n_max + c, i_y, i_z, q, q_t, shift_t,
                        z_irr, omega, constants, forces, details, values, creep_at, walk,
                        xs_body, x, mu,
                    )  # fmt: skip
            continue
        # cell whose nodes hold different contact points.  Per shift node of the cell and
        # candidate slot: a point that both x nodes hold (within X_BLEND_DISTANCE, e.g. a
        # contact drifting across a flaring rail) is interpolated along x, otherwise the two
        # nodes' points are taken each with its x weight; either is carried to the query's
        # shift to first order and the forces are blended with the shift weights.  The
        # force is so continuous in x and shift (a nearest-node lookup jumps).
        for db in range(2):
            wb = ts if db else 1.0 - ts
            if wb <= 0.0:
                continue
            jb = min(js + db, n_s - 1)
            base0 = v_off + (ix * n_s + jb) * n_c * _N_FIELDS
            shift_node = shift0 + jb * step
            for c in range(n_c):
                i0 = base0 + c * _N_FIELDS
                i1 = i0 + plane
                ok0 = values[i0 + _GAP] < _EMPTY
                ok1 = values[i1 + _GAP] < _EMPTY
                if ok0 and ok1 and abs(values[i0 + _Y_RAIL] - values[i1 + _Y_RAIL]) < _X_BLEND:
                    for f in range(_N_FIELDS):
                        fields[f] = values[i0 + f] + tx * (values[i1 + f] - values[i0 + f])
                    walk[0], walk[1], walk[4], walk[5] = i0 + _GAP, ix, 0.0, 0.0  # shift node's
                    walk[7] = 1.0
                    gap = fields[_GAP] - fields[_SIN] * (shift - shift_node)
                    loaded += _point(
                        fields, gap, wb, s, k * n_max + c, i_y, i_z, q, q_t, shift_t, z_irr,
                        omega, constants, forces, details, values, creep_at, walk, xs_body, x, mu,
                    )  # fmt: skip
                    continue
                for da in range(2):
                    w = wb * (tx if da else 1.0 - tx)
                    if w <= 0.0 or not (ok1 if da else ok0):
                        continue
                    i = i1 if da else i0
                    for f in range(_N_FIELDS):
                        fields[f] = values[i + f]
                    # two different points, each its own node's: along x from that node
                    walk[0], walk[1], walk[4], walk[5] = i + _GAP, ix + da, 0.0, 0.0
                    walk[7] = 0.0
                    gap = fields[_GAP] - fields[_SIN] * (shift - shift_node)
                    loaded += _point(
                        fields, gap, w, s, k * n_max + c, i_y, i_z, q, q_t, shift_t, z_irr,
                        omega, constants, forces, details, values, creep_at, walk, xs_body, x, mu,
                    )  # fmt: skip
        for c in range(n_c):  # positions: averages over the nodes that hold the point
            row = k * n_max + c
            found = details[row, 19]
            if found > 0.0:
                for f in (7, 8, 9, 10, 14, 15, 16):
                    details[row, f] /= found
            carried = details[row, 20]
            if carried > 0.0:
                for f in (11, 12, 13, 17, 18, 21, 22):
                    details[row, f] /= carried
    return loaded


@numba.njit(cache=True)
def contact_history(
    x, q, q_t, irregularity, curvature, values, blendable, xs, layout, bounds, constants
):  # pragma: no cover (compiled; tested through its Python callers)
    """:func:`contact_forces` over the samples of a stored run.

    Parameters
    ----------
    x : numpy.ndarray
        m, (n,) wheelset positions.
    q, q_t : numpy.ndarray
        (n, n_q) coordinates and velocities.
    irregularity : numpy.ndarray
        (n, 4) m, irregularities at x (see :func:`contact_forces`).
    curvature : numpy.ndarray
        1/m, (n,) track curvature at x.
    values, blendable, xs, layout, bounds : numpy.ndarray
        From :class:`.packed_tables.PackedTables`.
    constants : numpy.ndarray
        As for :func:`contact_forces` (its curvature entry is replaced per sample).

    Returns
    -------
    forces : numpy.ndarray
        (n, n_q) generalised contact forces.
    details : numpy.ndarray
        (n, n_bodies * n_c, len(DETAIL_FIELDS)) per-contact rows.
    """
    n = x.shape[0]
    n_c = 1
    for k in range(layout.shape[0]):
        n_c = max(n_c, layout[k, 5])
    forces = np.zeros((n, q.shape[1]))
    details = np.zeros((n, max(layout.shape[0], 1) * n_c, _N_DETAIL))
    c = constants.copy()
    for i in range(n):
        c[5] = curvature[i]
        contact_forces(
            x[i], q[i], q_t[i], irregularity[i], values, blendable, xs, layout, bounds, c,
            forces[i], details[i],
        )  # fmt: skip
    return forces, details
