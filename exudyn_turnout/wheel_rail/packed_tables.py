"""The contact tables of one wheelset packed into flat arrays: the compiled kernel's input.

:func:`pack_tables` turns the :class:`.tables.ContactTable` of every rail body a wheelset
can touch into one :class:`PackedTables`: per table node the fields of :data:`NODE_FIELDS`
(geometry, the node's normal law ``N = F_REF (delta / DELTA_REF)^F_EXP`` of
:mod:`.nonhertz`, the semi-axes and Kalker's coefficients of its ellipse, the force
centre's law, the profile term of the lead along x), per body its layout and bounds, and
behind the nodes the creep law (the FASTSIM creep table of :mod:`.creep_table`, or
Polach's).  :func:`scale_contact_law` scales the normal laws and the creep coefficients
(the contact law's sensitivity knobs), :func:`gap_slope_bound` bounds the search of the
lead along x, :func:`hertz_axes_per_root` gives Hertz's semi-axes of a table without a
per-node law.  :mod:`.kernel` evaluates the packed arrays in one compiled call.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from exudyn_turnout.wheel_rail.along_x import (
    EMPTY_GAP,
    GAP_FIELD,
    X_BLEND_DISTANCE,
    Y_RAIL_FIELD,
)
from exudyn_turnout.wheel_rail.creep import kalker_coefficients
from exudyn_turnout.wheel_rail.creep_table import CreepTableSettings, creep_table
from exudyn_turnout.wheel_rail.hertz import curvature_sums, ellipse_parameter
from exudyn_turnout.wheel_rail.node_laws import DELTA_REF
from exudyn_turnout.wheel_rail.nonhertz import PATCH_FIELDS
from exudyn_turnout.wheel_rail.tables import ContactTable

__all__ = [
    "NODE_FIELDS",
    "N_BOUNDS",
    "PackedTables",
    "pack_tables",
    "scale_contact_law",
    "hertz_axes_per_root",
    "gap_slope_bound",
]

#: Fields of a packed table node, in order: geometry (gap, positions, angle, radius), the
#: normal law N = f_ref (delta / DELTA_REF)^f_exp, the Hertz constant (kept for outputs), x
#: offset, sin and cos of the angle, the semi-axes at DELTA_REF, Kalker's coefficients of
#: the node's ellipse shape, the semi-axes' exponents, the weight of the semi-Hertzian law,
#: the force centre's law c_ref (delta / DELTA_REF)^m, the rail surface's offset there
#: (a c^2 + b c^3), and 1 / (rho_w + rho_r), the profiles' lateral radii of curvature at
#: the contact summed (1/m, 0 where either is flat or concave: the lead's profile term).
#: The first two are :data:`.along_x.GAP_FIELD` and :data:`.along_x.Y_RAIL_FIELD`.
NODE_FIELDS = (
    "gap", "y_rail", "z_rail", "s_wheel", "angle", "radius",
    "f_ref", "f_exp", "hertz_constant", "x_offset", "sin", "cos",
    "a_ref", "b_ref", "c11", "c22", "c23", "a_exp", "b_exp", "semi_hertzian",
    "centre", "centre_exp", "offset_c2", "offset_c3", "slide",
)  # fmt: skip
#: Columns of :attr:`PackedTables.bounds`.
N_BOUNDS = 6

_GAP, _Y_RAIL = NODE_FIELDS.index("gap"), NODE_FIELDS.index("y_rail")
_F_REF, _C_H = NODE_FIELDS.index("f_ref"), NODE_FIELDS.index("hertz_constant")
_F_EXP, _X_OFFSET = NODE_FIELDS.index("f_exp"), NODE_FIELDS.index("x_offset")
_SIN, _COS = NODE_FIELDS.index("sin"), NODE_FIELDS.index("cos")
_A_REF, _A_EXP = NODE_FIELDS.index("a_ref"), NODE_FIELDS.index("a_exp")
_B_REF, _B_EXP = NODE_FIELDS.index("b_ref"), NODE_FIELDS.index("b_exp")
_C11, _C22, _C23 = NODE_FIELDS.index("c11"), NODE_FIELDS.index("c22"), NODE_FIELDS.index("c23")
_SEMI = NODE_FIELDS.index("semi_hertzian")
_CENTRE, _CENTRE_EXP = NODE_FIELDS.index("centre"), NODE_FIELDS.index("centre_exp")
_OFFSET_C2, _OFFSET_C3 = NODE_FIELDS.index("offset_c2"), NODE_FIELDS.index("offset_c3")
_SLIDE = NODE_FIELDS.index("slide")
_N_FIELDS = len(NODE_FIELDS)
_N_BOUNDS = N_BOUNDS
_GEOMETRY = NODE_FIELDS[:6]  # the table's own fields of these names
_EMPTY = EMPTY_GAP
if (_GAP, _Y_RAIL) != (GAP_FIELD, Y_RAIL_FIELD):  # pragma: no cover (a layout change)
    raise ImportError("NODE_FIELDS and .along_x disagree on the gap and y_rail fields")


@dataclass(frozen=True, eq=False)
class PackedTables:
    """The contact tables of one wheelset's rail bodies as flat arrays (kernel input)."""

    values: np.ndarray  #: flat node values, body after body, (n_x, n_s, n_c, 25) each
    blendable: np.ndarray  #: flat uint8 cell flags, (n_x, n_s) each
    x: np.ndarray  #: m, section positions, body after body
    #: per body: value offset, blend offset, x offset, n_x, n_s, n_c, side (+1 / -1),
    #: index of the rail body's lateral coordinate, of its vertical coordinate
    layout: np.ndarray
    #: per body: first shift (m), shift step (m), x_from (m), x_to (m) of its existence, and
    #: the largest slope of a contact point's gap along x in its table (:func:`gap_slope_bound`;
    #: stored negative for a table of the wheel's envelope: no search along x there), and its
    #: friction coefficient (-, 0: the vehicle's mu, ``constants[2]``; a check rail's own)
    bounds: np.ndarray
    names: tuple  #: body names, for outputs

    @property
    def n_bodies(self) -> int:
        """Number of rail bodies."""
        return int(self.layout.shape[0])

    def select(
        self, indices: Sequence[int], rail_coordinates: Sequence[tuple[int, int]]
    ) -> PackedTables:
        """Some of the bodies, bound to other coordinate indices (the arrays are shared).

        Parameters
        ----------
        indices : sequence of int
            Bodies to keep, in the new order.
        rail_coordinates : sequence of (int, int)
            Per kept body, the indices of its lateral and vertical coordinate.

        Returns
        -------
        PackedTables
        """
        layout = self.layout[list(indices)].copy().reshape(-1, 9)
        for row, (i_y, i_z) in zip(layout, rail_coordinates, strict=True):
            row[7], row[8] = i_y, i_z
        return PackedTables(
            values=self.values,
            blendable=self.blendable,
            x=self.x,
            layout=layout,
            bounds=self.bounds[list(indices)].copy().reshape(-1, _N_BOUNDS),
            names=tuple(self.names[i] for i in indices),
        )

    @property
    def n_candidates(self) -> int:
        """Largest number of candidate slots of a body (rows per body in the details)."""
        return int(self.layout[:, 5].max()) if self.layout.size else 0


def hertz_axes_per_root(
    a_sum: np.ndarray, b_sum: np.ndarray, modulus: float
) -> tuple[np.ndarray, np.ndarray]:
    """Hertz semi-axes per square root of the penetration, ``a / sqrt(delta)``, ``b / ...``.

    Johnson (1985) Eqs 4.39-4.41 (see :mod:`.hertz`): ``major^2 = delta (K - E) / (A_min e^2
    K)`` and ``minor = major sqrt(1 - e^2)``, so both grow with ``sqrt(delta)`` and the ratio
    per node is fixed by the curvatures alone.

    Parameters
    ----------
    a_sum, b_sum : numpy.ndarray
        1/m, relative curvatures in rolling and lateral direction.
    modulus : float
        Pa, contact modulus (unused by the shape; kept for a uniform signature).

    Returns
    -------
    a_root, b_root : numpy.ndarray
        m^0.5: semi-axes in rolling and lateral direction divided by ``sqrt(delta)``.
    """
    from scipy.special import ellipe, ellipk

    del modulus
    a_sum = np.asarray(a_sum, float)
    b_sum = np.asarray(b_sum, float)
    small = np.minimum(a_sum, b_sum)
    m = ellipse_parameter(np.maximum(a_sum, b_sum) / small)
    k, e = ellipk(m), ellipe(m)
    ke = np.where(m > 1e-10, (k - e) / np.where(m > 1e-10, m, 1.0), np.pi / 4.0)
    major = np.sqrt(ke / (small * k))
    minor = major * np.sqrt(1.0 - m)
    rolling_is_major = a_sum <= b_sum
    return np.where(rolling_is_major, major, minor), np.where(rolling_is_major, minor, major)


def gap_slope_bound(gap: np.ndarray, y_rail: np.ndarray, x: np.ndarray) -> float:
    """Largest slope along x of a contact point's gap in a table (bounds the lead's search).

    A candidate slot held at two neighbouring x nodes by one contact point (both gaps
    below the empty mark, positions on the rail within :data:`X_BLEND_DISTANCE`) has the
    secant slope ``|g1 - g0| / (x1 - x0)``; the largest over the table bounds how far the
    contact can move from the yaw's lead along x (:func:`.along_x.lead_along_x`).

    Parameters
    ----------
    gap, y_rail : numpy.ndarray
        m, (n_x, n_s, n_c) node gaps and contact positions on the rail.
    x : numpy.ndarray
        m, (n_x,) section positions.

    Returns
    -------
    float
        Largest slope (-), 0 for a prismatic table.
    """
    gap = np.asarray(gap, float)
    y_rail = np.asarray(y_rail, float)
    dx = np.diff(np.asarray(x, float)).reshape(-1, 1, 1)
    same = (
        (gap[:-1] < _EMPTY)
        & (gap[1:] < _EMPTY)
        & (np.abs(y_rail[1:] - y_rail[:-1]) < X_BLEND_DISTANCE)
    )
    slopes = np.where(same, np.abs(np.diff(gap, axis=0)) / dx, 0.0)
    return float(slopes.max()) if slopes.size else 0.0


def _node_fields(table: ContactTable, modulus: float, poisson: float) -> np.ndarray:
    """(n_x, n_s, n_c, 25) node values: geometry, the normal law, semi-axes and Kalker's.

    A table that carries the per-node law of :mod:`.nonhertz` (``PATCH_FIELDS``) is used
    as it is; an older table (without it) gets Hertz's law from its curvatures.
    """
    base = table.values
    index = {name: k for k, name in enumerate(table.fields)}
    n_public = len(table.fields)
    out = np.zeros(base.shape[:3] + (_N_FIELDS,))
    for k, name in enumerate(_GEOMETRY):
        out[..., k] = base[..., index[name]]
    out[..., _C_H] = base[..., index["hertz_constant"]]
    out[..., _X_OFFSET] = base[..., index["x_offset"]]
    out[..., _SIN] = base[..., n_public]
    out[..., _COS] = base[..., n_public + 1]
    if "patch_centre" in index:  # the contact position is the force centre (.nonhertz)
        out[..., _CENTRE] = base[..., index["patch_centre"]]
        out[..., _CENTRE_EXP] = base[..., index["patch_centre_exponent"]]
    if "patch_offset_c2" in index:  # ... moved onto the rail surface (.nonhertz)
        out[..., _OFFSET_C2] = base[..., index["patch_offset_c2"]]
        out[..., _OFFSET_C3] = base[..., index["patch_offset_c3"]]
    valid = base[..., index["gap"]] < _EMPTY
    if "curvature_wheel" in index and "curvature_rail" in index:
        # two convex profiles slid along their common tangent by u open the gap by
        # u^2 / (2 (rho_w + rho_r)) (two circles): lead_along_x's profile term
        k_w = np.nan_to_num(base[..., index["curvature_wheel"]])
        k_r = np.nan_to_num(base[..., index["curvature_rail"]])
        convex = valid & (k_w > 0.0) & (k_r > 0.0)
        out[..., _SLIDE] = np.where(convex, k_w * k_r / np.where(convex, k_w + k_r, 1.0), 0.0)
    if not np.any(valid):
        return out
    if all(name in index for name in PATCH_FIELDS):
        law = np.stack([base[..., index[name]][valid] for name in PATCH_FIELDS], axis=-1)
    else:
        a_sum, b_sum = curvature_sums(
            base[..., index["radius"]][valid], base[..., index["angle"]][valid],
            base[..., index["curvature_wheel"]][valid], base[..., index["curvature_rail"]][valid],
        )  # fmt: skip
        a_root, b_root = hertz_axes_per_root(a_sum, b_sum, modulus)
        root = np.sqrt(DELTA_REF)
        law = np.zeros((a_root.size, len(PATCH_FIELDS)))
        law[:, 0] = base[..., index["hertz_constant"]][valid] * DELTA_REF * root
        law[:, 1] = 1.5
        law[:, 2], law[:, 3] = a_root * root, 0.5
        law[:, 4], law[:, 5] = b_root * root, 0.5
    for k, target in enumerate((_F_REF, _F_EXP, _A_REF, _A_EXP, _B_REF, _B_EXP, _SEMI)):
        out[..., target][valid] = law[:, k]
    a_ref, b_ref = law[:, 2], law[:, 4]
    usable = (a_ref > 0.0) & (b_ref > 0.0)
    coefficients = kalker_coefficients(
        np.where(usable, a_ref, 1.0), np.where(usable, b_ref, 1.0), poisson
    )
    out[..., _C11][valid] = coefficients.c11
    out[..., _C22][valid] = coefficients.c22
    out[..., _C23][valid] = coefficients.c23
    return out


def pack_tables(
    tables: Sequence[ContactTable],
    sides: Sequence[int],
    rail_coordinates: Sequence[tuple[int, int]],
    x_ranges: Sequence[tuple[float, float]],
    names: Sequence[str] | None = None,
    modulus: float = 2.1e11 / (2.0 * (1.0 - 0.3**2)),
    poisson: float = 0.28,
    creep_law: str = "fastsim",
    friction: Sequence[float] | None = None,
) -> PackedTables:
    """Pack the tables of one wheelset's rail bodies for :func:`.kernel.contact_forces`.

    Parameters
    ----------
    tables : sequence of ContactTable
        One table per rail body.
    sides : sequence of int
        +1 (left wheel) or -1 (right wheel) per body.
    rail_coordinates : sequence of (int, int)
        Indices of each body's lateral and vertical coordinate in the coordinate vector
        the kernel receives.
    x_ranges : sequence of (float, float)
        m, where each body exists; outside it the body carries nothing.
    names : sequence of str, optional
        Body names for outputs.
    modulus : float
        Pa, contact modulus E* (default steel, E = 210 GPa, nu = 0.3).
    poisson : float
        Poisson's ratio for Kalker's coefficients (0.28: Kalker's tables as used by CONTACT).
    creep_law : str
        "fastsim": FASTSIM's forces from the creep table (:mod:`.creep_table`, the
        default); "polach": Polach's method (:func:`.kernel.polach_scalar`).
    friction : sequence of float, optional
        -, per body, its own friction coefficient (a lubricated check rail); 0 or omitted:
        the vehicle's mu that :func:`.kernel.contact_forces` receives in ``constants``.

    Returns
    -------
    PackedTables
        Its ``values`` end with the creep law: the packed creep table (FASTSIM), then
        its index and the law (1 FASTSIM, 0 Polach).
    """
    if creep_law not in ("fastsim", "polach"):
        raise ValueError(f"creep_law must be 'fastsim' or 'polach', not {creep_law!r}")
    values, blends, xs, layout, bounds = [], [], [], [], []
    v_off = b_off = x_off = 0
    mus = [0.0] * len(tables) if friction is None else [float(f) for f in friction]
    if len(mus) != len(tables) or not all(0.0 <= f < math.inf for f in mus):
        raise ValueError("friction must give one coefficient >= 0 per body")
    for table, side, (i_y, i_z), (x_from, x_to), mu in zip(
        tables, sides, rail_coordinates, x_ranges, mus, strict=True
    ):
        fields = _node_fields(table, modulus, poisson)
        n_x, n_s, n_c = fields.shape[:3]
        if n_x < 2 or n_s < 2:
            raise ValueError("a contact table needs at least two x and two shift nodes")
        values.append(fields.ravel())
        blends.append(np.asarray(table.blendable, np.uint8).ravel())
        xs.append(np.asarray(table.x, float))
        layout.append((v_off, b_off, x_off, n_x, n_s, n_c, int(side), int(i_y), int(i_z)))
        step = float(table.shift[1] - table.shift[0])
        slope = gap_slope_bound(fields[..., _GAP], fields[..., _Y_RAIL], np.asarray(table.x, float))
        if np.any(fields[..., _X_OFFSET] != 0.0):
            # the table's gap is already the rigid wheel's envelope along x (the minimum over
            # the wheel's circle, .sections.wheel_envelope: blade, wing, nose, slices): a
            # search with the wheel's parabola again would count it twice; the contact stays
            # at the yaw's lead on it (a negative bound tells the kernel so)
            slope = -slope
        bounds.append((float(table.shift[0]), step, float(x_from), float(x_to), slope, mu))
        v_off += fields.size
        b_off += n_x * n_s
        x_off += n_x
    # the creep law behind the node values: [table..., index of the table, law]
    law = np.zeros(0)
    if creep_law == "fastsim":
        law = creep_table(CreepTableSettings(poisson=poisson)).packed
    values.append(law)
    values.append(np.array([float(v_off), 1.0 if creep_law == "fastsim" else 0.0]))
    return PackedTables(
        values=np.concatenate(values),
        blendable=np.concatenate(blends) if blends else np.zeros(0, np.uint8),
        x=np.concatenate(xs) if xs else np.zeros(0),
        layout=np.array(layout, dtype=np.int64).reshape(-1, 9),
        bounds=np.array(bounds, dtype=float).reshape(-1, _N_BOUNDS),
        names=tuple(names) if names is not None else tuple(f"body{i}" for i in range(len(xs))),
    )


def scale_contact_law(
    tables: PackedTables, normal: float = 1.0, creep: float = 1.0
) -> PackedTables:
    """The tables with every node's normal law and creep coefficients scaled (a copy).

    Two sensitivity knobs of the contact law, both 1 by default (the tables unchanged):

    * ``normal`` multiplies the normal force of every node's law at a given penetration,
      ``N = normal F_REF (delta / DELTA_REF)^F_EXP``, and with it the contact stiffness
      dN/d(delta) and the Hertz constant kept for outputs; the semi-axes at a given
      penetration are geometry and stay.  It is the same as scaling the effective modulus
      E* of the normal problem alone: at the same load the approach changes by the factor
      ``normal^(-1 / F_EXP)`` (Hertz: ``normal^(-2/3)``), so an approach error e of the law
      against an exact solution is the factor ``(1 + e)^(-F_EXP)``;
    * ``creep`` multiplies Kalker's coefficients C11, C22, C23 of every node: the creep
      forces' initial slopes scale by it and their saturation at mu N does not (the creep
      force reduction factor of Simpack's and GENSYS's contact elements; Polach's and the
      FASTSIM table's normalised creepages ``G a b C_ij creepage / (3 mu N)`` are linear in
      the coefficients).

    Parameters
    ----------
    tables : PackedTables
        From :func:`pack_tables`.
    normal, creep : float
        Factors (> 0).

    Returns
    -------
    PackedTables
        ``tables`` itself where both factors are 1, else a copy with new ``values``.

    Raises
    ------
    ValueError
        A factor that is not a finite number > 0.
    """
    for name, factor in (("normal", normal), ("creep", creep)):
        if not (math.isfinite(factor) and factor > 0.0):
            raise ValueError(f"scale_contact_law: {name} = {factor!r} must be a number > 0")
    if normal == 1.0 and creep == 1.0:
        return tables
    values = tables.values.copy()
    nodes = values[: int(values[-2])].reshape(-1, _N_FIELDS)  # a view: the creep law follows
    nodes[:, _F_REF] *= normal
    nodes[:, _C_H] *= normal
    nodes[:, _C11] *= creep
    nodes[:, _C22] *= creep
    nodes[:, _C23] *= creep
    return replace(tables, values=values)
