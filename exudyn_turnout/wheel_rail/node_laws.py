"""The per-node laws of the contact tables and the contact point they give.

The Kik-Piotrowski solution and the fit of a node's law to it live in :mod:`.nonhertz`;
this module holds what the tables store per node and how the kernel (:mod:`.kernel`) and
the tables' lookup (:mod:`.tables`) evaluate it, one compiled function per law so that
both use the same code.

The normal force
----------------
At each table node the normal force is stored as a power law through its values at the
two reference penetrations :data:`DELTA_LOW` and :data:`DELTA_HIGH`,
``N = N_ref (delta / DELTA_REF)^n`` with ``DELTA_REF = sqrt(DELTA_LOW DELTA_HIGH)``
(:func:`node_normal_force`); a Hertz node has n = 1.5, i.e. exactly ``C_H delta^1.5``.

The force centre
----------------
Every node also stores KP's force centre (:func:`.nonhertz.force_centre`) at DELTA_REF
and a power law in the penetration (:func:`node_centre`, its exponent from
:func:`centre_exponent`), Hertz node or not: the kernel and the lookup put the contact
there (its positions on rail and wheel, the moment arms).

The contact point on the rail surface
-------------------------------------
The centre is a position along the lateral tangent of the deepest point; the contact
position is the point of the rail surface on the normal force's line of action through it
(the normal), found in the node's section (:func:`surface_offset`) and stored as the
surface's offset from the tangent line, ``w = a c^2 + b c^3`` in the centre
(:func:`centre_offset_law`, :func:`node_offset`, :func:`centre_point`).  The tangent point
itself lay off the rail at a flange: 3.5 mm above it at 7 mm of shift and 30 kN on plain
UIC60 (issue 22, tests/test_flange_contact_point.py).  It is the line of action, not the
arc length along the surface, that fixes the point: every strip's force acts along the one
normal at its tangent position, so their resultant's moments are those of a force through
``P0 + c t`` along the normal; the point on the surface on that line carries the same
moments.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from exudyn_turnout.wheel_rail.geometry import PreparedRail

__all__ = [
    "DELTA_LOW",
    "DELTA_HIGH",
    "DELTA_REF",
    "CENTRE_EXPONENT_MAX",
    "SURFACE_WINDOW",
    "node_normal_force",
    "node_normal_forces",
    "node_centre",
    "node_centres",
    "centre_exponent",
    "surface_offset",
    "centre_offset_law",
    "node_offset",
    "node_offsets",
    "centre_point",
]

#: m, smaller reference penetration of the per-node law (about 15 kN on a tread)
DELTA_LOW = 2e-5
#: m, larger reference penetration of the per-node law (about 150 kN on a tread)
DELTA_HIGH = 2e-4
#: m, penetration at which the per-node law stores its values
DELTA_REF = math.sqrt(DELTA_LOW * DELTA_HIGH)
#: Largest exponent of a node's force-centre law (:func:`node_centre`)
CENTRE_EXPONENT_MAX = 2.0
#: m, the rail surface is searched this far either side of a contact point for the force
#: centre's point on it (:func:`surface_offset`)
SURFACE_WINDOW = 0.03
_OFFSET_SPAN = 1e-3  # m, smallest centre and spread of the two points of the offset's fit


@numba.njit(cache=True)
def node_normal_force(reference, exponent, delta):  # pragma: no cover (compiled)
    """The per-node normal-contact law: ``N = N_ref (delta / DELTA_REF)^n``, 0 if delta <= 0.

    The one law of the kernel (:mod:`.kernel`) and of the tables' lookup
    (:func:`.tables.normal_force`); for a Hertz node (n = 1.5) exactly ``C_H delta^1.5``.

    Parameters
    ----------
    reference : float
        N, the node's force at :data:`DELTA_REF` (field ``patch_force``).
    exponent : float
        Its exponent n (field ``patch_force_exponent``).
    delta : float
        m, normal penetration.

    Returns
    -------
    float
        N, normal force (>= 0).
    """
    if delta <= 0.0:
        return 0.0
    return reference * math.exp(exponent * math.log(delta / DELTA_REF))


@numba.njit(cache=True)
def node_normal_forces(reference, exponent, delta):  # pragma: no cover (compiled)
    """:func:`node_normal_force` over arrays of one shape (flattened in C order).

    Parameters
    ----------
    reference, exponent, delta : numpy.ndarray
        N, -, m: per contact, C-contiguous float arrays of one size.

    Returns
    -------
    numpy.ndarray
        N, flat, one force per contact.
    """
    r, e, d = reference.ravel(), exponent.ravel(), delta.ravel()
    out = np.empty(d.size)
    for i in range(d.size):
        out[i] = node_normal_force(r[i], e[i], d[i])
    return out


@numba.njit(cache=True)
def node_centre(reference, exponent, delta):  # pragma: no cover (compiled)
    """The per-node force centre at a penetration: ``c_ref (delta / DELTA_REF)^m``.

    KP's force centre (:func:`.nonhertz.force_centre`) is the deepest point at vanishing
    penetration and moves out as the virtual interpenetration region grows (for a gap rising as t^2
    on one side and slower on the other it grows as delta^0.5, on the packaged crossings
    as delta^0.9-1.4); the power law goes through its values at :data:`DELTA_LOW` and
    :data:`DELTA_HIGH` (m = 1 where they change sign), held at DELTA_HIGH's value beyond
    it.  The one position law of the kernel and of the tables' lookup.

    Parameters
    ----------
    reference : float
        m, the centre at :data:`DELTA_REF` (field ``patch_centre``).
    exponent : float
        Its exponent m (field ``patchcentre_exponent``).
    delta : float
        m, normal penetration (<= 0: the deepest point, centre 0).

    Returns
    -------
    float
        m, the force centre from the deepest point along the lateral tangent.
    """
    if delta <= 0.0:
        return 0.0
    return reference * math.exp(exponent * math.log(min(delta, DELTA_HIGH) / DELTA_REF))


@numba.njit(cache=True)
def node_centres(reference, exponent, delta):  # pragma: no cover (compiled)
    """:func:`node_centre` over arrays of one size (flattened in C order).

    Parameters
    ----------
    reference, exponent, delta : numpy.ndarray
        m, -, m: per contact, C-contiguous float arrays of one size.

    Returns
    -------
    numpy.ndarray
        m, flat, one centre per contact.
    """
    r, k, d = reference.ravel(), exponent.ravel(), delta.ravel()
    out = np.empty(d.size)
    for i in range(d.size):
        out[i] = node_centre(r[i], k[i], d[i])
    return out


def centre_exponent(low, ref, high) -> np.ndarray:
    """Exponent of the centre's power law through its values at the three penetrations.

    Through DELTA_LOW and DELTA_HIGH where all three have one sign.  Where a second region
    joins the run between DELTA_LOW and DELTA_REF (the centre 0 at DELTA_LOW, 10 mm at
    DELTA_REF on a flange at 7 mm of shift), through DELTA_REF and DELTA_HIGH, so that the
    law does not run off to several times the centre at DELTA_HIGH; a sign change above
    DELTA_REF: through DELTA_LOW and DELTA_REF; else 1.  Clipped to [0,
    :data:`CENTRE_EXPONENT_MAX`].

    Parameters
    ----------
    low, ref, high : numpy.ndarray
        m, (n,) the force centre (:func:`.nonhertz.force_centre`) at :data:`DELTA_LOW`,
        :data:`DELTA_REF` and :data:`DELTA_HIGH`.

    Returns
    -------
    numpy.ndarray
        (n,) exponent m of the centre's law (field ``patch_centre_exponent``,
        :func:`node_centre`).
    """
    same = (low * ref > 0.0) & (high * ref > 0.0)
    upper = ~same & (high * ref > 0.0)
    lower = ~same & ~upper & (low * ref > 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        whole = np.log(np.abs(high / np.where(same, low, 1.0))) / math.log(DELTA_HIGH / DELTA_LOW)
        top = np.log(np.abs(high / np.where(upper, ref, 1.0))) / math.log(DELTA_HIGH / DELTA_REF)
        bottom = np.log(np.abs(ref / np.where(lower, low, 1.0))) / math.log(DELTA_REF / DELTA_LOW)
    exponent = np.where(same, whole, np.where(upper, top, np.where(lower, bottom, 1.0)))
    return np.clip(exponent, 0.0, CENTRE_EXPONENT_MAX)


def surface_offset(rail_y, rail_z, y_rail, z_rail, angle, centre) -> np.ndarray:
    """Where the rail surface meets the normal force's line of action, from the tangent line.

    KP's force centre ``c`` (:func:`.nonhertz.force_centre`) is a position along the lateral
    tangent ``t = (cos(gamma), sin(gamma))`` of the deepest point ``P0``; every strip's force, and
    so the resultant, acts along the contact normal ``n = (-sin(gamma), cos(gamma))`` (side
    coordinates, outward from the rail).  The point of the rail surface on that line of
    action, ``P0 + c t + w n``, is the contact position: it carries the same moment of the
    normal force as the tangent point ``P0 + c t``, and lies on the rail, which the tangent
    point does not (3.5 mm off it on the gauge face at a flange contact of 30 kN on plain
    UIC60).  The rail is the polyline of its heights on the lateral grid; the crossing
    nearest to the tangent point within :data:`SURFACE_WINDOW` of ``P0`` is taken.

    Parameters
    ----------
    rail_y, rail_z : array_like
        m, the rail's uniform lateral grid and heights (NaN: no rail).
    y_rail, z_rail, angle : array_like
        m, m, rad, (n,) the contact points (deepest points) and contact angles.
    centre : array_like
        m, (n,) the force centre along the tangent.

    Returns
    -------
    numpy.ndarray
        m, (n,) offset w along the normal (negative: the surface lies below the tangent
        line, a convex rail); 0 where ``centre`` is 0 or no crossing is found.
    """
    rail_y, rail_z = np.asarray(rail_y, float), np.asarray(rail_z, float)
    y0 = np.atleast_1d(np.asarray(y_rail, float))
    z0 = np.atleast_1d(np.asarray(z_rail, float))
    gamma = np.broadcast_to(np.asarray(angle, float), y0.shape)
    c = np.broadcast_to(np.asarray(centre, float), y0.shape)
    out = np.zeros(y0.shape)
    step = float(rail_y[1] - rail_y[0])
    # (points x window) in slices of bounded size, by growing |c|: the crossing lies within
    # about 2 |c| of the deepest point: a slice's window is 3 times its largest |c| and 3 mm
    order = np.argsort(np.abs(c))
    for lo in range(0, y0.size, 512):
        sl = order[lo : lo + 512]
        reach = min(SURFACE_WINDOW, 3.0 * float(np.max(np.abs(c[sl]))) + 3e-3)
        half = int(np.ceil(reach / step))
        k = np.arange(-half, half + 1)
        index = np.round((y0[sl] - rail_y[0]) / step).astype(int)[:, None] + k[None, :]
        inside = (index >= 0) & (index < rail_y.size)
        index = np.clip(index, 0, rail_y.size - 1)
        y = np.where(inside, rail_y[index], np.nan)
        z = np.where(inside, rail_z[index], np.nan)
        cos_g, sin_g = np.cos(gamma[sl])[:, None], np.sin(gamma[sl])[:, None]
        dy, dz = y - y0[sl, None], z - z0[sl, None]
        along = dy * cos_g + dz * sin_g - c[sl, None]  # from the line of action, along t
        normal = -dy * sin_g + dz * cos_g  # from the tangent line, along n
        a0, a1 = along[:, :-1], along[:, 1:]
        crossing = np.isfinite(a0) & np.isfinite(a1) & (a0 * a1 <= 0.0) & (a0 != a1)
        with np.errstate(divide="ignore", invalid="ignore"):
            f = np.where(crossing, a0 / (a0 - a1), 0.0)
        w = np.where(crossing, normal[:, :-1] + f * (normal[:, 1:] - normal[:, :-1]), np.inf)
        best = np.take_along_axis(w, np.argmin(np.abs(w), axis=1)[:, None], axis=1)[:, 0]
        out[sl] = np.where(np.isfinite(best) & (c[sl] != 0.0), best, 0.0)
    return out


def centre_offset_law(rail: PreparedRail, y_rail, z_rail, angle, reference, exponent):
    """The law of the rail surface's offset at the force centre (fields 9 and 10).

    ``w(c) = a c^2 + b c^3`` (:func:`node_offset`: 0 with zero slope at the deepest point,
    where the tangent touches), put through the surface's offsets (:func:`surface_offset`)
    at the centre's law (:func:`node_centre`) at :data:`DELTA_REF` (at least
    ``_OFFSET_SPAN`` = 1 mm out, on its side) and at its largest value at :data:`DELTA_LOW`
    and :data:`DELTA_HIGH` (at least 1.25 times and 1 mm beyond the first point).  Linear
    in its coefficients, so that the kernel's bilinear blend of neighbouring nodes that
    share the deepest point (a flange) is a blend of two fits of one surface, evaluated at
    the blended centre: the point stays on the surface, where a blend of two surface points
    would cut the chord between them.

    Parameters
    ----------
    rail : PreparedRail
        The section the contact points lie on.
    y_rail, z_rail, angle : array_like
        m, m, rad, (n,) deepest points and contact angles.
    reference, exponent : array_like
        m, -, (n,) the centre's law (fields ``patch_centre``, ``patchcentre_exponent``).

    Returns
    -------
    numpy.ndarray
        (n, 2): ``patch_offset_c2`` (1/m, a) and ``patch_offset_c3`` (1/m^2, b).
    """
    reference = np.ascontiguousarray(reference, dtype=float)
    exponent = np.ascontiguousarray(exponent, dtype=float)
    out = np.zeros((reference.size, 2))
    if reference.size == 0:
        return out
    centres = np.stack(
        [
            np.abs(node_centres(reference, exponent, np.full(reference.size, delta)))
            for delta in (DELTA_LOW, DELTA_HIGH)
        ]
    )
    sign = np.where(reference < 0.0, -1.0, 1.0)
    near = np.maximum(np.abs(reference), _OFFSET_SPAN)
    far = np.maximum(np.maximum(centres.max(axis=0), 1.25 * near), near + _OFFSET_SPAN)
    near, far = sign * near, sign * far
    w_near = surface_offset(rail.y, rail.z, y_rail, z_rail, angle, near)
    w_far = surface_offset(rail.y, rail.z, y_rail, z_rail, angle, far)
    # a near^2 + b near^3 = w_near, a far^2 + b far^3 = w_far
    det = near * near * far * far * (far - near)
    usable = np.abs(det) > 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        a = (w_near * far**3 - w_far * near**3) / det
        b = (w_far * near**2 - w_near * far**2) / det
    out[:, 0] = np.where(usable, a, 0.0)
    out[:, 1] = np.where(usable, b, 0.0)
    return out


@numba.njit(cache=True)
def node_offset(c2, c3, centre):  # pragma: no cover (compiled)
    """The rail surface's offset at a force centre: ``w = a c^2 + b c^3``.

    The one offset law of the kernel and the tables' lookup (:func:`centre_offset_law`).

    Parameters
    ----------
    c2 : float
        1/m, a (field ``patch_offset_c2``).
    c3 : float
        1/m^2, b (field ``patch_offset_c3``).
    centre : float
        m, the force centre along the tangent (:func:`node_centre`).

    Returns
    -------
    float
        m, the offset along the normal (negative: the surface below the tangent line).
    """
    return centre * centre * (c2 + c3 * centre)


@numba.njit(cache=True)
def node_offsets(c2, c3, centre):  # pragma: no cover (compiled)
    """:func:`node_offset` over arrays of one size (flattened in C order).

    Parameters
    ----------
    c2, c3, centre : numpy.ndarray
        1/m, 1/m^2, m: per contact, C-contiguous float arrays of one size.

    Returns
    -------
    numpy.ndarray
        m, flat, one offset per contact.
    """
    a, b, c = c2.ravel(), c3.ravel(), centre.ravel()
    out = np.empty(c.size)
    for i in range(c.size):
        out[i] = node_offset(a[i], b[i], c[i])
    return out


@numba.njit(cache=True)
def centre_point(centre, offset, sin_g, cos_g):  # pragma: no cover (compiled)
    """The contact position's displacement from the deepest point (side coordinates).

    ``c t + w n`` with ``t = (cos(gamma), sin(gamma))``, ``n = (-sin(gamma), cos(gamma))``:
    the force centre moved onto the rail surface along the force's line of action
    (:func:`surface_offset`).  The one formula of the kernel and of the tables' lookup.

    Parameters
    ----------
    centre : float
        m, force centre along the tangent (:func:`node_centre`).
    offset : float
        m, the surface's offset along the normal there (:func:`node_offset`).
    sin_g, cos_g : float
        Sine and cosine of the contact angle.

    Returns
    -------
    (float, float)
        m, lateral (towards the field side) and vertical displacement.
    """
    return centre * cos_g - offset * sin_g, centre * sin_g + offset * cos_g
