"""A wheel's contact along a rail whose gap varies along the track: where it lies and how
long its patch is (the compiled contact kernel's, :mod:`.kernel`).

Two parts, each called by :func:`.kernel.contact_forces` for a contact point whose rail
body's table varies along x (its nodes' gaps differ, within the table's slope bound):

* :func:`lead_along_x`: the contact's lead, the minimum along x of the yawed wheel's
  parabola (R_x = r / cos(gamma)), a profile term and the rail's gap between the table's x
  nodes (piecewise linear, constant beyond the nodes that hold the same contact point).
* :func:`patch_along_x`: the patch along x on that gap, a slender line model against the
  same model on the node law's parabola (the ratio corrects the node law's force, its
  stiffness, the semi-axis a and the force centre; applied from :data:`PATCH_SLENDER`'s
  a / b on, beyond :data:`PATCH_DEADBAND`).

Node values are read from the kernel's packed layout: a node's gap at its flat index, its
contact position on the rail :data:`Y_RAIL_FIELD` - :data:`GAP_FIELD` entries later.
"""

from __future__ import annotations

import math

import numba
import numpy as np

__all__ = [
    "GAP_FIELD",
    "Y_RAIL_FIELD",
    "EMPTY_GAP",
    "X_BLEND_DISTANCE",
    "BETA_PER_B",
    "PATCH_CELLS",
    "PATCH_DEADBAND",
    "PATCH_SLENDER",
    "PATCH_SCRATCH",
    "lead_along_x",
    "patch_along_x",
]

#: Index of a node's gap in the packed node fields (:mod:`.kernel`'s layout).
GAP_FIELD = 0
#: Index of a node's contact position on the rail in the packed node fields.
Y_RAIL_FIELD = 1
#: m, a gap this large marks an empty candidate slot (tables store 1 m)
EMPTY_GAP = 0.5
#: m, a candidate slot held by both x nodes of a cell whose contact positions on the rail
#: differ by less than this is one contact point drifting along x (interpolated along x)
X_BLEND_DISTANCE = 0.01


@numba.njit(cache=True)
def _node_gap(values, i, w_b, b_offset):  # pragma: no cover (compiled)
    """Gap of a node at flat index ``i``, blended with the next shift node by ``w_b``."""
    if w_b > 0.0:
        return (1.0 - w_b) * values[i] + w_b * values[i + b_offset]
    return values[i]


@numba.njit(cache=True)
def _same_point(values, i, j, w_b, b_offset):  # pragma: no cover (compiled)
    """1 if the node at flat index ``i`` (and its next shift node if ``w_b`` > 0) holds the
    point of its neighbour along x at ``j``: a gap, positions on the rail within
    :data:`X_BLEND_DISTANCE`."""
    dy = Y_RAIL_FIELD - GAP_FIELD
    if not (values[i] < EMPTY_GAP and abs(values[i + dy] - values[j + dy]) < X_BLEND_DISTANCE):
        return False
    if w_b > 0.0:
        i += b_offset
        j += b_offset
        return values[i] < EMPTY_GAP and abs(values[i + dy] - values[j + dy]) < X_BLEND_DISTANCE
    return True


@numba.njit(cache=True)
def _point_nodes(
    values, xs, i_node, k0, pair, n_x, plane, w_b, b_offset, x, lo, hi
):  # pragma: no cover (compiled)
    """(k_lo, k_hi): the x nodes from ``k0`` on in both directions that hold the same
    contact point (:func:`_same_point`), within ``xs - x`` of ``lo`` and ``hi``."""
    k_hi = k0 + 1 if pair else k0
    while (
        k_hi + 1 < n_x
        and xs[k_hi] - x < hi
        and _same_point(
            values, i_node + (k_hi + 1 - k0) * plane, i_node + (k_hi - k0) * plane, w_b, b_offset
        )
    ):
        k_hi += 1
    k_lo = k0
    while (
        k_lo > 0
        and xs[k_lo] - x > lo
        and _same_point(
            values, i_node + (k_lo - 1 - k0) * plane, i_node + (k_lo - k0) * plane, w_b, b_offset
        )
    ):
        k_lo -= 1
    return k_lo, k_hi


@numba.njit(cache=True)
def _segment_minimum(g0, x0, slope, left, right, x, x_yaw, radius_x, quartic):  # pragma: no cover
    """(value, xi) of ``g0 + slope (x + xi - x0) + (xi - x_yaw)^2 / (2 R_x) + quartic xi^4``
    smallest over xi in ``[left, right]`` (compiled; convex: its derivative increases, its
    root by Newton's method kept within the bracket, bisection where a step leaves it)."""
    if quartic == 0.0:  # the parabola alone: its stationary point, clamped
        xi = min(max(x_yaw - slope * radius_x, left), right)
        value = g0 + slope * (x + xi - x0) + (xi - x_yaw) * (xi - x_yaw) / (2.0 * radius_x)
        return value, xi
    a = left
    b = right
    d_a = slope + (a - x_yaw) / radius_x + 4.0 * quartic * a * a * a
    d_b = slope + (b - x_yaw) / radius_x + 4.0 * quartic * b * b * b
    if d_a >= 0.0:
        xi = a
    elif d_b <= 0.0:
        xi = b
    else:
        xi = min(max(x_yaw - slope * radius_x, a), b)
        for _ in range(60):
            d = slope + (xi - x_yaw) / radius_x + 4.0 * quartic * xi * xi * xi
            if d > 0.0:
                b = xi
            else:
                a = xi
            step = d / (1.0 / radius_x + 12.0 * quartic * xi * xi)
            new = xi - step
            if not (a < new < b):
                new = 0.5 * (a + b)
            if abs(new - xi) < 1e-12:
                xi = new
                break
            xi = new
    value = g0 + slope * (x + xi - x0) + (xi - x_yaw) * (xi - x_yaw) / (2.0 * radius_x)
    return value + quartic * xi * xi * xi * xi, xi


@numba.njit(cache=True)
def lead_along_x(
    values,
    xs,
    i_node,
    k0,
    pair,
    n_x,
    plane,
    b_offset,
    w_b,
    x,
    x_yaw,
    radius_x,
    quartic,
    lo,
    hi,
):  # pragma: no cover (compiled; tested in tests/test_wheel_rail_lead.py)
    """Lead of a contact along a rail whose gap varies along x, and the gap it closes.

    Near its contact a yawed wheel's normal distance to a prismatic rail, taken over the
    points of the wheel ahead of its axle by xi, is the parabola
    ``(xi - x_yaw)^2 / (2 R_x)`` minus the yaw's closing (:mod:`.lead`: ``x_yaw = r
    sin(theta)``, closing ``r (1 - cos(theta)) cos(gamma) = x_yaw^2 / (2 R_x)`` to second
    order, so ``R_x = r / cos(gamma)``).  The rail adds its own gap at ``x + xi``, ``g(x +
    xi)``: piecewise linear between the table's x nodes that hold the same contact point
    (from node ``k0`` on in both directions, each node's position on the rail within
    :data:`X_BLEND_DISTANCE` of its neighbour's), constant beyond the last of them in
    either direction (as the kernel takes a point that one node alone holds, so that the
    gap stays continuous where the tables' points change).  The contact lies at the
    minimum of the sum over xi in ``[lo, hi]``: per segment of slope m at ``x_yaw - m R_x``
    (clamped to the segment), at a slope change (a flare's end, the top of a ramp: a
    convex edge of the rail along x) where the stationary points of the two segments lie
    beyond it.  On a prismatic rail (equal node gaps) and without the profile term the
    result is exactly ``(x_yaw, 0)``; on one slope m it is ``x_yaw - m R_x`` and ``m x_yaw
    - m^2 R_x / 2``.

    Profile term (``quartic xi^4``): the wheel's point xi ahead lies ``h = xi^2 / (2 r)``
    higher; at a steep contact (a flange back at 81 deg) that moves the wheel's profile
    along the contact's tangent by ``h sin(gamma)``, millimetres at leads of 40 mm, and two
    convex profiles slid along their tangent by u open the gap by ``u^2 / (2 (rho_w +
    rho_r))``: ``quartic = sin(gamma)^2 / (8 r^2 (rho_w + rho_r))``.  Without it the gap
    along x at the packaged check rail's flare end closes far too much at 40 mm leads
    (validation/check_rail_kink.md: against the 3-D gap on the rail's exact sections).
    The minimiser lies between ``x_yaw -+ |m|_max R_x`` and 0 (the derivative's root, m
    the slopes).

    Parameters
    ----------
    values : numpy.ndarray
        Flat node values; the gap of node k of the contact's slot at ``i_node + (k - k0)
        plane``, its contact position on the rail ``Y_RAIL_FIELD - GAP_FIELD`` entries later.
    xs : numpy.ndarray
        m, (n_x,) the table's x nodes.
    i_node : int
        Flat index of the slot's gap at node ``k0`` (first shift node).
    k0 : int
        A node that holds the point.
    pair : bool
        Node ``k0 + 1`` holds it too (a cell interpolated along x), unchecked.
    n_x : int
        Number of x nodes.
    plane : int
        Flat stride of one x node.
    b_offset : int
        Flat offset of the next shift node.
    w_b : float
        Weight of the next shift node (0: the first alone).
    x : float
        m, wheelset position.
    x_yaw : float
        m, the yaw's lead on a prismatic rail.
    radius_x : float
        m, ``R_x = r / cos(gamma)``, the radius of the wheel's distance along x.
    quartic : float
        1/m^3, the profile term's coefficient (0: the parabola alone).
    lo, hi : float
        m, range of the lead searched (within the lead's cap, around ``x_yaw``).

    Returns
    -------
    x_lead : float
        m, the contact's lead ahead of the axle.
    change : float
        m, gap at the contact plus the parabola, minus the rail's gap at x (add it to the
        gap at x, then subtract the yaw's closing).
    """
    k_lo, k_hi = _point_nodes(values, xs, i_node, k0, pair, n_x, plane, w_b, b_offset, x, lo, hi)
    # the rail's gap at x (on the nodes' polyline, constant beyond its ends)
    first = _node_gap(values, i_node + (k_lo - k0) * plane, w_b, b_offset)
    last = _node_gap(values, i_node + (k_hi - k0) * plane, w_b, b_offset)
    if x <= xs[k_lo]:
        here = first
    elif x >= xs[k_hi]:
        here = last
    else:
        k = k_lo
        while xs[k + 1] < x:
            k += 1
        ga = _node_gap(values, i_node + (k - k0) * plane, w_b, b_offset)
        gb = _node_gap(values, i_node + (k + 1 - k0) * plane, w_b, b_offset)
        here = ga + (x - xs[k]) * ((gb - ga) / (xs[k + 1] - xs[k]))
    # constant before the first node and after the last, linear between
    best, best_xi = _segment_minimum(
        first, xs[k_lo], 0.0, lo, min(xs[k_lo] - x, hi), x, x_yaw, radius_x, quartic
    )
    if not xs[k_lo] - x > lo:  # the first node lies at or behind the range: no such part
        best = math.inf
    value, xi = _segment_minimum(
        last, xs[k_hi], 0.0, max(xs[k_hi] - x, lo), hi, x, x_yaw, radius_x, quartic
    )
    if xs[k_hi] - x < hi and value < best:
        best, best_xi = value, xi
    gb = first
    for k in range(k_lo, k_hi):
        ga = gb
        gb = _node_gap(values, i_node + (k + 1 - k0) * plane, w_b, b_offset)
        left = max(xs[k] - x, lo)
        right = min(xs[k + 1] - x, hi)
        if left > right:
            continue
        value, xi = _segment_minimum(
            ga, xs[k], (gb - ga) / (xs[k + 1] - xs[k]), left, right, x, x_yaw, radius_x, quartic
        )
        if value < best:
            best, best_xi = value, xi
    if not best < math.inf:
        return x_yaw, 0.0
    return best_xi, best - here


#: Cells of :func:`patch_along_x`'s line model along x (the patch and its reference each)
PATCH_CELLS = 16
#: Below this relative change of the normal force :func:`patch_along_x`'s correction is not
#: applied (its own accuracy, tests/test_check_rail_kink_law.py), blended in smoothly up to
#: twice it (the force, semi-axis and centre stay continuous)
PATCH_DEADBAND = 0.01
#: a / b of the node's ellipse from which :func:`patch_along_x`'s correction applies in full;
#: none below half of it, blended smoothly between.  The line model takes the patch as a
#: line load along x (Boussinesq over a width much smaller than its length): the flange
#: back on a check rail (a / b ~ 40) is one, a tread patch (a / b ~ 1) is not.  Measured on
#: a tread: a dipped joint (tests/test_irregularity_contact.py) moved 6 % of its peak with
#: the line model applied, against the same dip as an irregularity of the wheel's path.
PATCH_SLENDER = 6.0
_CHAIN = 64  # largest number of x nodes of a contact's gap along x that patch_along_x holds
#: the lateral spread of the line load as a distance along x: a semi-elliptic load of
#: half-width b seen from its centre line acts as ``1 / sqrt(s^2 + beta^2)``, ``beta = b
#: exp(-1/2) / 2`` (its integral over a cell matches the strip's, ``2 d (ln(4 d / b) - 1/2)``)
BETA_PER_B = 0.5 * math.exp(-0.5)
# _line_model's cells k >= 2 apart: the kernel 1 / |s| over two cells, (k + 1) ln(k + 1) -
# 2 k ln(k) + (k - 1) ln(k - 1), and the coefficient of -rho^2, 1 / (2 k (k^2 - 1))
_CELL_FAR = np.array(
    [0.0, 0.0]
    + [
        (k + 1) * math.log(k + 1) - 2 * k * math.log(k) + (k - 1) * math.log(k - 1)
        for k in range(2, 64)
    ]
)
_CELL_NEAR = np.array([0.0, 0.0] + [1.0 / (2.0 * k * (k * k - 1.0)) for k in range(2, 64)])
# the parabola's cells (patch_along_x's reference) in units of the level: loads 1 - v^2 and
# gaps v^2 at the cells' midpoints v, their sums, and the sums over pairs k cells apart of
# the loads' products and of the loads (both orders), for _reference_model
_V = -1.0 + (np.arange(PATCH_CELLS) + 0.5) * 2.0 / PATCH_CELLS
_W_REF = 1.0 - _V * _V
_REF_SUMS = np.array([_W_REF.sum(), (_W_REF * _V * _V).sum(), (_V * _V).sum()])
_REF_PAIRS = np.array(
    [
        np.sum(
            [
                _W_REF[i] * _W_REF[j]
                for i in range(PATCH_CELLS)
                for j in range(PATCH_CELLS)
                if abs(i - j) == k
            ]
        )
        for k in range(PATCH_CELLS)
    ]
)
_REF_LOADS = np.array(
    [
        np.sum(
            [_W_REF[j] for i in range(PATCH_CELLS) for j in range(PATCH_CELLS) if abs(i - j) == k]
        )
        for k in range(PATCH_CELLS)
    ]
)


@numba.njit(cache=True)
def _chain_gap(cx, cg, n, xi):  # pragma: no cover (compiled)
    """The rail's gap at xi on the chain's polyline (constant beyond its ends)."""
    if xi <= cx[0]:
        return cg[0]
    if xi >= cx[n - 1]:
        return cg[n - 1]
    k = 0
    while cx[k + 1] < xi:
        k += 1
    return cg[k] + (xi - cx[k]) * ((cg[k + 1] - cg[k]) / (cx[k + 1] - cx[k]))


@numba.njit(cache=True)
def _cell_coefficients(n, rho, c, dc):  # pragma: no cover (compiled)
    """c[k], dc[k]: two cells k apart of :func:`_line_model`, the kernel integrated over
    both, over the cell size, and its derivative by rho."""
    # two cells k apart: int int 1 / sqrt(s^2 + rho^2) over d, Phi(k + 1) - 2 Phi(k) +
    # Phi(k - 1) with Phi(s) = s asinh(s / rho) - sqrt(s^2 + rho^2) (Phi'' the kernel), and
    # its derivative by rho, from dPhi / drho = -sqrt(s^2 + rho^2) / rho; from k = 2 on
    # (rho < 1/2) its expansion in rho, _CELL_FAR - rho^2 / (2 k (k^2 - 1)), the next term
    # below 5e-3 rho^4 relative
    exact = n if rho >= 0.5 else min(n, 2)
    root_b = math.sqrt(1.0 + rho * rho)
    phi_b = math.asinh(1.0 / rho) - root_b
    root_c = rho
    phi_c = -rho
    for k in range(exact):
        root_a = math.sqrt((k + 1.0) * (k + 1.0) + rho * rho)
        phi_a = (k + 1.0) * math.asinh((k + 1.0) / rho) - root_a
        c[k] = phi_a - 2.0 * phi_c + phi_b
        dc[k] = -(root_a - 2.0 * root_c + root_b) / rho
        root_b, phi_b = root_c, phi_c
        root_c, phi_c = root_a, phi_a
    for k in range(exact, n):
        c[k] = _CELL_FAR[k] - rho * rho * _CELL_NEAR[k]
        dc[k] = -2.0 * rho * _CELL_NEAR[k]


@numba.njit(cache=True)
def _reference_model(n, d, delta, level, rise, rho, drho, c, dc):  # pragma: no cover
    """:func:`_line_model` on the parabola's n cells (d each, the loads ``level (1 - v^2)``),
    from the sums of its normalised cells (_REF_SUMS, _REF_PAIRS, _REF_LOADS)."""
    _cell_coefficients(n, rho, c, dc)
    energy = 0.0
    spread = 0.0
    acting = 0.0
    for k in range(n):
        energy += c[k] * _REF_PAIRS[k]
        spread += dc[k] * _REF_PAIRS[k]
        acting += c[k] * _REF_LOADS[k]
    energy *= level * level
    spread *= level * level
    acting *= level
    total = level * _REF_SUMS[0]
    fit = level * (delta * _REF_SUMS[0] - level * _REF_SUMS[1])
    dfit = rise * (delta * n - level * _REF_SUMS[2]) + total
    if total <= 0.0 or fit <= 0.0 or energy <= 0.0:
        return 0.0, 0.0
    denergy = 2.0 * rise * acting + spread * drho / delta
    force = d * total * fit / energy
    return force, delta * (rise * n / total + dfit / fit - denergy / energy)


@numba.njit(cache=True)
def _line_model(w, h, n, d, delta, rise, rho, drho, c, dc):  # pragma: no cover (compiled)
    """(force / (pi E*), its d ln / d ln delta) of :func:`patch_along_x`'s line model on n
    cells of size d: loads per length w (the virtual interpenetration, > 0 in the patch),
    geometric gaps h; ``rise`` = d w / d delta in the patch, ``rho = beta / d``, ``drho`` =
    d rho / d ln delta; c, dc work space (n)."""
    _cell_coefficients(n, rho, c, dc)
    total = 0.0
    fit = 0.0
    dfit = 0.0
    moved = 0.0
    energy = 0.0  # sum over i, j of c_|i-j| w_i w_j
    spread = 0.0  # ... of dc_|i-j| w_i w_j
    acting = 0.0  # ... of c_|i-j| w_j
    for i in range(n):
        if w[i] <= 0.0:
            continue
        total += w[i]
        moved += rise
        fit += w[i] * (delta - h[i])
        dfit += rise * (delta - h[i]) + w[i]
        energy += c[0] * w[i] * w[i]
        spread += dc[0] * w[i] * w[i]
        acting += c[0] * w[i]
        for j in range(i + 1, n):
            if w[j] > 0.0:
                energy += 2.0 * c[j - i] * w[i] * w[j]
                spread += 2.0 * dc[j - i] * w[i] * w[j]
                acting += c[j - i] * (w[i] + w[j])
    if total <= 0.0 or fit <= 0.0 or energy <= 0.0:
        return 0.0, 0.0
    # every load grows by rise, the kernel with the lateral half-width
    denergy = 2.0 * rise * acting + spread * drho / delta
    force = d * total * fit / energy
    return force, delta * (moved / total + dfit / fit - denergy / energy)


@numba.njit(cache=True)
def _piece(cx, cg, n, p):  # pragma: no cover (compiled)
    """Piece p of the chain's polyline: (gap at xi0, xi0, slope, left, right); p = -1 and
    n - 1 are the constant parts before its first node and after its last (1 m long)."""
    if p < 0:
        return cg[0], cx[0], 0.0, cx[0] - 1.0, cx[0]
    if p >= n - 1:
        return cg[n - 1], cx[n - 1], 0.0, cx[n - 1], cx[n - 1] + 1.0
    slope = (cg[p + 1] - cg[p]) / (cx[p + 1] - cx[p])
    return cg[p], cx[p], slope, cx[p], cx[p + 1]


@numba.njit(cache=True)
def _piece_gap(g0, x0, slope, xi, x_yaw, radius_x, quartic):  # pragma: no cover (compiled)
    """The gap along x on one piece and its slope at xi (lead_along_x's sum)."""
    value = g0 + slope * (xi - x0) + (xi - x_yaw) * (xi - x_yaw) / (2.0 * radius_x)
    rate = slope + (xi - x_yaw) / radius_x + 4.0 * quartic * xi * xi * xi
    return value + quartic * xi * xi * xi * xi, rate


@numba.njit(cache=True)
def _piece_root(g0, x0, slope, start, top, x_yaw, radius_x, quartic):  # pragma: no cover
    """Where one convex piece's gap comes down to ``top``, by Newton's method from
    ``start`` (gap >= top there, on the side away from the piece's minimum: the steps
    approach the root monotonically)."""
    xi = start
    for _ in range(40):
        value, rate = _piece_gap(g0, x0, slope, xi, x_yaw, radius_x, quartic)
        if rate == 0.0:
            break
        step = (value - top) / rate
        xi -= step
        if abs(step) < 1e-10:
            break
    return xi


@numba.njit(cache=True)
def _patch_end(cx, cg, n, j, xi_min, top, x_yaw, radius_x, quartic, slope_bound, limit, ahead):
    # pragma: no cover (compiled)
    """The patch's end ahead of (or behind) the deepest point xi_min in piece j: the last
    point where the gap along x stays below ``top``, piece after piece until the slopes
    (``slope_bound``) cannot bring the gap back below it."""
    end = xi_min
    p = j
    while p >= -1 and p <= n - 1:
        g0, x0, slope, left, right = _piece(cx, cg, n, p)
        if ahead:
            left = max(left, xi_min)
        else:
            right = min(right, xi_min)
        if left <= right:
            # the piece's minimum: at its inner edge where the gap rises from there (the
            # deepest point's own piece, most others), else inside (convex)
            inner = left if ahead else right
            low, rate = _piece_gap(g0, x0, slope, inner, x_yaw, radius_x, quartic)
            at = inner
            if (rate < 0.0 if ahead else rate > 0.0) and p != j:
                low, at = _segment_minimum(
                    g0, x0, slope, left, right, 0.0, x_yaw, radius_x, quartic
                )
            if low < top:
                # a point where the gap is at least top (curvature >= 1 / R_x beyond `at`)
                reach = math.sqrt(2.0 * radius_x * (top - low))
                outer = min(right, at + reach) if ahead else max(left, at - reach)
                value, _ = _piece_gap(g0, x0, slope, outer, x_yaw, radius_x, quartic)
                if value < top:
                    end = outer
                else:
                    end = _piece_root(g0, x0, slope, outer, top, x_yaw, radius_x, quartic)
            edge = right if ahead else left
            value, _ = _piece_gap(g0, x0, slope, edge, x_yaw, radius_x, quartic)
            # the wheel's part of the slope grows along x: beyond the edge the gap's slope
            # is at least (at most) this; then it stays above top
            bound = (edge - x_yaw) / radius_x + 4.0 * quartic * edge * edge * edge
            if value >= top and (bound > slope_bound if ahead else bound < -slope_bound):
                break
            if abs(edge - xi_min) > limit:
                break
        p += 1 if ahead else -1
    return end


@numba.njit(cache=True)
def patch_along_x(
    values, xs, i_node, k0, pair, n_x, plane, b_offset, w_b, x, x_yaw, radius_x, quartic,
    xi_min, delta, level, rise, beta, beta_exp, slope_bound, limit, scratch,
):  # pragma: no cover (compiled; tested in tests/test_check_rail_kink_law.py)  # fmt: skip
    """The normal force of a contact whose gap along x is not the wheel's parabola alone.

    The node's law (:mod:`.node_laws`) holds for the gap ``u^2 / (2 R_x)`` along x about the
    deepest point; where the rail's gap varies along x (:func:`lead_along_x`'s sum of the
    rail's polyline, the parabola and the profile term) the patch is another: at the check
    rail's flare end (a convex kink of its face in plan) the flare opens the gap behind the
    kink and the patch is truncated.  A slender patch (the flange back's: a / b ~ 40) is a
    line load along x; Hertz's ellipse carries per length exactly ``w ∝ eps delta - h(x)``
    (its pressure integrated across), with ``eps delta = a^2 / (2 R_x)`` the node's semi-axis
    a (``level``).  The same distribution on the actual gap h(x) gives the patch's extent
    and force centre; its magnitude follows from the displacement condition in the mean
    over the patch (Galerkin: ``int w (u - (delta - h)) dx = 0``, u the surface
    displacement of the line load by Boussinesq's ``1 / (pi E* s)``, across the width
    spread as ``1 / sqrt(s^2 + beta^2)``, ``beta = b exp(-1/2) / 2``), on
    :data:`PATCH_CELLS` cells of constant load (cell integrals exact).  The ratio of the
    actual patch's force to the parabola's (the same model on both, so their errors cancel)
    corrects the node's law.  Against the exact half-space solution on a flat face behind
    a 1:67 flare (tests/test_check_rail_kink_law.py) within ~1 %.

    Parameters
    ----------
    values, xs, i_node, k0, pair, n_x, plane, b_offset, w_b, x, x_yaw, radius_x, quartic
        As for :func:`lead_along_x` (the rail's gap along x of the contact's slot).
    xi_min : float
        m, the deepest point along x (:func:`lead_along_x`'s lead).
    delta : float
        m, the penetration there (> 0).
    level : float
        m, the virtual interpenetration ``a^2 / (2 R_x)`` (the node's semi-axis a at delta).
    rise : float
        d level / d delta.
    beta : float
        m, the lateral spread as a distance along x, ``b exp(-1/2) / 2``.
    beta_exp : float
        d ln beta / d ln delta.
    slope_bound : float
        The table's largest gap slope along x (:func:`.packed_tables.gap_slope_bound`).
    limit : float
        m, the patch is searched this far from xi_min at most (the lead's cap).
    scratch : numpy.ndarray
        Work space, at least ``128 + 4 PATCH_CELLS`` values.

    Returns
    -------
    ratio : float
        The patch's normal force over the parabola's (1: the same).
    rate : float
        ``d ln(ratio) / d ln(delta)``.
    length : float
        The patch's length along x over the parabola's ``2 a``.
    centre : float
        m, where the force acts, ahead of the axle.
    """
    cx = scratch[:_CHAIN]
    cg = scratch[_CHAIN : 2 * _CHAIN]
    w = scratch[2 * _CHAIN : 2 * _CHAIN + PATCH_CELLS]
    h = scratch[2 * _CHAIN + PATCH_CELLS : 2 * _CHAIN + 2 * PATCH_CELLS]
    c = scratch[2 * _CHAIN + 2 * PATCH_CELLS : 2 * _CHAIN + 3 * PATCH_CELLS]
    dc = scratch[2 * _CHAIN + 3 * PATCH_CELLS : 2 * _CHAIN + 4 * PATCH_CELLS]
    # the nodes that hold the point (as lead_along_x walks them), within the lead's cap
    k_lo, k_hi = _point_nodes(
        values,
        xs,
        i_node,
        k0,
        pair,
        n_x,
        plane,
        w_b,
        b_offset,
        x,
        xi_min - limit,
        xi_min + limit,
    )
    while k_hi - k_lo + 1 > _CHAIN:  # keep the nodes nearest the contact
        if xs[k_hi] - x - xi_min > xi_min - (xs[k_lo] - x):
            k_hi -= 1
        else:
            k_lo += 1
    n = k_hi - k_lo + 1
    for i in range(n):
        cx[i] = xs[k_lo + i] - x
        cg[i] = _node_gap(values, i_node + (k_lo + i - k0) * plane, w_b, b_offset)
    j = -1
    while j + 1 < n and cx[j + 1] <= xi_min:
        j += 1
    g0, x0, slope, _, _ = _piece(cx, cg, n, j)
    deepest, _ = _piece_gap(g0, x0, slope, xi_min, x_yaw, radius_x, quartic)
    top = deepest + level
    front = _patch_end(
        cx, cg, n, j, xi_min, top, x_yaw, radius_x, quartic, slope_bound, limit, True
    )
    back = _patch_end(
        cx, cg, n, j, xi_min, top, x_yaw, radius_x, quartic, slope_bound, limit, False
    )
    d = (front - back) / PATCH_CELLS
    if not d > 0.0:
        return 1.0, 0.0, 1.0, xi_min
    loaded = 0.0
    moment = 0.0
    for i in range(PATCH_CELLS):
        xi = back + (i + 0.5) * d
        h[i] = _chain_gap(cx, cg, n, xi) + (xi - x_yaw) * (xi - x_yaw) / (2.0 * radius_x)
        h[i] += quartic * xi * xi * xi * xi - deepest
        w[i] = level - h[i]
        if w[i] > 0.0:
            loaded += w[i]
            moment += w[i] * xi
    force, rate = _line_model(
        w, h, PATCH_CELLS, d, delta, rise, beta / d, beta_exp * beta / d, c, dc
    )
    # the same model on the parabola (the node law's gap along x)
    half = math.sqrt(2.0 * radius_x * level)
    d_s = 2.0 * half / PATCH_CELLS
    reference, reference_rate = _reference_model(
        PATCH_CELLS, d_s, delta, level, rise, beta / d_s, beta_exp * beta / d_s, c, dc
    )
    if not (force > 0.0 and reference > 0.0 and loaded > 0.0):
        return 1.0, 0.0, 1.0, xi_min
    return force / reference, rate - reference_rate, (front - back) / (2.0 * half), moment / loaded


#: Length of the work array :func:`patch_along_x` takes (``scratch``).
PATCH_SCRATCH = 2 * _CHAIN + 4 * PATCH_CELLS
