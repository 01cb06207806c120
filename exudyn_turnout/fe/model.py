"""Sparse K, G, D, M of the FE turnout model, one bending plane at a time.

Dynamic stiffness at circular frequency omega (harmonic e^{i omega t})::

    Z(omega) = K + i G + i omega D - omega^2 M

K stiffness, G structural loss (the rails' loss factor and the absorbing ends), D viscous
damping (pads, ballast), M mass. All four share one sparsity pattern so Z is formed by
adding data arrays.

Planes
------
``vertical``: rails bend in the x-z plane (Timoshenko, I_z of Table 1, DOFs w, psi per
node); sleepers are Timoshenko beams along y bending in the y-z plane (E_s I_s, DOFs w,
rotation) on the vertical ballast layer s_b,z, d_b,z per unit length; pads k_p,z, c_p,z.
Heave and roll of a bearer are its rigid-body modes, so the cross-section coupling the
co-running model carries with m_t, J_t (Table 2) is in this plane.

``lateral``: rails bend in the x-y plane (I_y of Table 1, DOFs v, psi); a lateral pad
force acts along the sleeper's axis, so each sleeper is an axial bar along y (E_s A_s,
first free axial mode 790 Hz at 2.5 m, 486 Hz at 4.06 m) on the lateral ballast layer
s_b,y, d_b,y per unit length (total s_b,y L_t: Eq 13); pads k_p,y, c_p,y.

Why two planar models instead of the paper's 3-D one
----------------------------------------------------
With the load at the shear centre and sections symmetric about the vertical, vertical and
lateral bending of a rail are uncoupled. They couple only through eccentricities: the
lateral pad force acts at the rail foot, below the shear centre, and the lateral load at
the rail head ~0.11 m above it rolls the rail. Table 1 gives neither rail torsion, rail
heights nor pad roll stiffness; the paper's own equivalent parameters (Eqs 1-15) treat the
two directions separately, and so do the co-running models we compare with. The vertical
receptance is unaffected to first order (a vertical load on a symmetric section excites
no lateral motion, and the pad's vertical springs, symmetric about the shear centre,
resist roll without heave); the planar lateral one misses rail roll, which lowers the
lateral stiffness at the rail head above a few hundred Hz.

Rail torsion (lateral plane, optional)
--------------------------------------
``assemble(..., torsion=RailTorsionSection())`` adds to every rail node of the lateral
model the roll phi (and, with warping, the warping variable theta) of
:mod:`~exudyn_turnout.fe.torsion` (60E1 data there, not from Table 1): St Venant and
warping stiffness, roll inertia about the shear centre, the mass coupling rho A e_c of the
centroid's offset, the rail's loss factor on all of it. The lateral pad then acts at the
rail foot, ``foot_depth`` below the shear centre (it stretches by v + d phi - u_sleeper),
and a roll spring k_z b^2 / 12 (damping c_z b^2 / 12) of the vertical pad joins phi to
ground; a check rail's lateral support acts at its L-bracket's bolts instead,
with the bracket's roll spring added (:mod:`~exudyn_turnout.fe.check_rail`).
Without ``torsion`` the lateral model is the planar one, unchanged.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike

from exudyn_turnout.fe import timoshenko as tim
from exudyn_turnout.fe.check_rail import check_rail_support, check_rail_types
from exudyn_turnout.fe.mesh import Mesh
from exudyn_turnout.fe.torsion import (
    RailTorsionSection,
    pad_roll_stiffness,
    polar_moment_about_shear_centre,
    torsion_mass,
    torsion_stiffness,
)
from exudyn_turnout.inputs.turnout import Turnout

__all__ = ["DIRECTIONS", "PlaneModel", "Triplets", "rail_section", "element_nodes", "assemble"]

#: Bending planes of the model.
DIRECTIONS = ("vertical", "lateral")


@dataclass(frozen=True)
class PlaneModel:
    """Sparse matrices of one bending plane and how the DOFs map to the mesh.

    Nodes: the mesh's rail vertex nodes first, then the interior nodes of every rail
    element (order p: p - 1 each), then the sleeper vertex and interior nodes likewise.
    A rail node has DOFs (2k, 2k + 1) = (w or v, psi); a sleeper node 2 DOFs (vertical: w,
    rotation) or 1 (lateral: axial u) after all rail DOFs. With torsion (lateral plane),
    rail node k also has the roll phi at ``torsion_dof_offset + n_t k`` (and the warping
    variable theta at the next DOF, n_t = 2) after all sleeper DOFs.
    """

    direction: str  #: "vertical" or "lateral"
    mesh: Mesh  #: the geometry the matrices were assembled on
    order: int  #: element order p
    K: sp.csc_matrix  #: N/m, stiffness
    G: sp.csc_matrix  #: N/m, structural loss (rail loss factor, absorbing ends)
    D: sp.csc_matrix  #: N s/m, viscous damping
    M: sp.csc_matrix  #: kg, mass
    rail_elem_nodes: np.ndarray  #: (n, p + 1) nodes of each rail element, along x
    sleeper_dof_offset: int  #: first sleeper DOF (all rail DOFs come before)
    torsion: RailTorsionSection | None = None  #: rail torsion data, None: no roll DOFs
    torsion_dof_offset: int = -1  #: first torsion DOF (after the sleeper DOFs), -1: none

    @property
    def torsion_dofs_per_node(self) -> int:
        """Torsion DOFs per rail node: 0 (none), 1 (phi) or 2 (phi, theta)."""
        return 0 if self.torsion is None else self.torsion.dofs_per_node

    def roll_dof(self, node: ArrayLike) -> np.ndarray:
        """Global DOF of the roll phi of rail node(s).

        Parameters
        ----------
        node : array_like of int
            Rail node indices (vertex or interior).

        Returns
        -------
        numpy.ndarray
            DOF indices, of the shape of ``node``.

        Raises
        ------
        ValueError
            The model has no torsion DOFs.
        """
        if self.torsion is None:
            raise ValueError("the model has no rail torsion DOFs (assemble with torsion=...)")
        return self.torsion_dof_offset + self.torsion_dofs_per_node * np.asarray(node)

    @property
    def n_dof(self) -> int:
        """Number of degrees of freedom of the model."""
        return self.K.shape[0]

    def vertex_dofs(self) -> np.ndarray:
        """DOFs of the element end nodes (rail and sleeper), without element interiors.

        Returns
        -------
        numpy.ndarray
            DOF indices: every rail vertex DOF, then every sleeper vertex DOF.
        """
        per_sleeper_node = 2 if self.direction == "vertical" else 1
        rail = np.arange(2 * self.mesh.n_rail_nodes)
        sleeper = self.sleeper_dof_offset + np.arange(per_sleeper_node * self.mesh.n_sleeper_nodes)
        n_t = self.torsion_dofs_per_node
        torsion = self.torsion_dof_offset + np.arange(n_t * self.mesh.n_rail_nodes)
        return np.concatenate([rail, sleeper, torsion if n_t else []]).astype(int)

    def dynamic_stiffness(self, omega: float) -> sp.csc_matrix:
        """Dynamic stiffness Z(omega) = K + iG + i omega D - omega^2 M.

        Parameters
        ----------
        omega : float
            Circular frequency (rad/s).

        Returns
        -------
        scipy.sparse.csc_matrix
            Complex Z (N/m), on the shared sparsity pattern.
        """
        data = self.K.data + 1j * (self.G.data + omega * self.D.data) - omega**2 * self.M.data
        return sp.csc_matrix((data, self.K.indices, self.K.indptr), shape=self.K.shape)

    def point_vector(self, rail_id: str, x: float) -> np.ndarray:
        """b (n_dof,) with w(x) = b . q: the unit vector of the rail node at x.

        Also the load vector of a unit point force there.

        Parameters
        ----------
        rail_id : str
            Layout rail id.
        x : float
            Position from the switch toe (m); must be a node (see
            :meth:`~exudyn_turnout.fe.mesh.Mesh.node_at`).

        Returns
        -------
        numpy.ndarray
            b, 1 at the rail node's deflection DOF, 0 elsewhere.
        """
        b = np.zeros(self.n_dof)
        b[2 * self.mesh.node_at(rail_id, x)] = 1.0
        return b

    def head_vector(self, rail_id: str, x: float, height: float) -> np.ndarray:
        """b with u_y = b . q: lateral displacement at a height above the shear centre (T1).

        u_y = v - z phi (also the load vector of a unit lateral force there: torque -z).
        Without torsion DOFs it is :meth:`point_vector` (the planar model has no roll).

        Parameters
        ----------
        rail_id : str
            Layout rail id.
        x : float
            Position from the switch toe (m); must be a node.
        height : float
            z, height above the shear centre (m).

        Returns
        -------
        numpy.ndarray
            b (n_dof,).
        """
        b = self.point_vector(rail_id, x)
        if self.torsion is not None:
            b[self.roll_dof(self.mesh.node_at(rail_id, x))] = -height
        return b


def rail_section(
    turnout: Turnout, type_name: str, x: np.ndarray, direction: str
) -> dict[str, np.ndarray]:
    """Section properties of a rail type at positions x, for one bending plane.

    Parameters
    ----------
    turnout : Turnout
        Table 1 rail types.
    type_name : str
        Rail type name.
    x : numpy.ndarray
        Positions from the switch toe (m); the type's tables are interpolated there.
    direction : {"vertical", "lateral"}
        Bending plane: I_z for vertical, I_y for lateral.

    Returns
    -------
    dict of str to numpy.ndarray
        ``EI`` (N m^2), ``kGA`` (N), ``rhoA`` (kg/m), ``rhoI`` (kg m), each of the shape of x.
    """
    rail = turnout.rail_types[type_name]
    x = np.asarray(x, float)
    A = np.interp(x, rail.area.x, rail.area.value)
    I_table = rail.I_z if direction == "vertical" else rail.I_y
    I = np.interp(x, I_table.x, I_table.value)
    G = rail.youngs_modulus / (2.0 * (1.0 + rail.poisson))
    return dict(
        EI=rail.youngs_modulus * I,
        kGA=rail.shear_coefficient * G * A,
        rhoA=rail.density * A,
        rhoI=rail.density * I,
    )


def _rail_props(turnout: Turnout, mesh: Mesh, direction: str) -> dict[str, np.ndarray]:
    """Element lengths (n,) and sections at the quadrature points (n, p + 2)."""
    x_start = mesh.node_x[mesh.elem_nodes[:, 0]]
    L = mesh.node_x[mesh.elem_nodes[:, 1]] - x_start
    x_gauss = x_start[:, None] + L[:, None] * tim.gauss_points(mesh.options.element_order)[None, :]
    types = np.array(mesh.elem_type)
    out = {quantity: np.empty(x_gauss.shape) for quantity in ("EI", "kGA", "rhoA", "rhoI")}
    for name in set(mesh.elem_type):
        selected = types == name
        section = rail_section(turnout, name, x_gauss[selected], direction)
        for quantity, values in section.items():
            out[quantity][selected] = values
    out["L"] = L
    return out


def element_nodes(vertex_pairs: np.ndarray, n_vertices: int, p: int) -> tuple[np.ndarray, int]:
    """Nodes of order-p elements on vertex pairs, interior nodes numbered after the vertices.

    Parameters
    ----------
    vertex_pairs : numpy.ndarray
        (n, 2) end (vertex) nodes of each element.
    n_vertices : int
        Number of vertex nodes; interior nodes are numbered from it on.
    p : int
        Element order (p - 1 interior nodes per element).

    Returns
    -------
    nodes : numpy.ndarray
        (n, p + 1) nodes of each element, in order along it.
    n_nodes : int
        Total number of nodes, vertices and interiors.
    """
    n_elements = len(vertex_pairs)
    interior = n_vertices + np.arange(n_elements * (p - 1)).reshape(n_elements, p - 1)
    nodes = np.column_stack([vertex_pairs[:, 0], interior, vertex_pairs[:, 1]])
    return nodes, n_vertices + n_elements * (p - 1)


class Triplets:
    """COO triplets of K, G, D, M collected on one shared pattern."""

    def __init__(self, n: int):
        self.n = n  #: matrix size (number of DOFs)
        self.rows: list[np.ndarray] = []
        self.cols: list[np.ndarray] = []
        self.vals: dict[str, list[np.ndarray]] = {name: [] for name in "KGDM"}

    def add(self, dofs: np.ndarray, **blocks: np.ndarray) -> None:
        """Add element blocks for any of K, G, D, M.

        Parameters
        ----------
        dofs : numpy.ndarray
            (n_el, m) global DOFs of each element.
        **blocks : numpy.ndarray
            ``K``, ``G``, ``D`` and/or ``M``: (n_el, m, m) element matrices; the missing
            ones add zeros, so that all four keep one pattern.
        """
        m = dofs.shape[1]
        self.rows.append(np.repeat(dofs, m, axis=1).ravel())
        self.cols.append(np.tile(dofs, (1, m)).ravel())
        size = dofs.shape[0] * m * m
        for name in "KGDM":
            self.vals[name].append(blocks[name].ravel() if name in blocks else np.zeros(size))

    def matrices(self) -> dict[str, sp.csc_matrix]:
        """The summed matrices on their shared sparsity pattern.

        Returns
        -------
        dict of str to scipy.sparse.csc_matrix
            ``K``, ``G``, ``D``, ``M``, n x n, duplicate entries summed.
        """
        rows, cols, n = np.concatenate(self.rows), np.concatenate(self.cols), self.n
        linear, inverse = np.unique(cols.astype(np.int64) * n + rows, return_inverse=True)
        indices, col = (linear % n).astype(np.int32), linear // n
        indptr = np.searchsorted(col, np.arange(n + 1)).astype(np.int32)
        out = {}
        for name, values in self.vals.items():
            data = np.bincount(inverse, weights=np.concatenate(values), minlength=len(linear))
            out[name] = sp.csc_matrix((data, indices, indptr), shape=(n, n))
        return out


def _spring(k: np.ndarray) -> np.ndarray:
    return np.asarray(k, float)[:, None, None] * np.array([[1.0, -1.0], [-1.0, 1.0]])


def _beam_dofs(nodes: np.ndarray, offset: int = 0) -> np.ndarray:
    """DOFs (w, psi) node-major of elements with nodes (n, p + 1)."""
    return offset + np.stack([2 * nodes, 2 * nodes + 1], axis=-1).reshape(len(nodes), -1)


def assemble(
    turnout: Turnout,
    mesh: Mesh,
    direction: str,
    torsion: RailTorsionSection | None = None,
) -> PlaneModel:
    """Sparse model of one plane (see the module docstring).

    Parameters
    ----------
    turnout : Turnout
        Table 1 properties (rails, pads, sleepers, ballast).
    mesh : Mesh
        From :func:`~exudyn_turnout.fe.mesh.build_mesh`.
    direction : {"vertical", "lateral"}
        Bending plane.
    torsion : RailTorsionSection, optional
        Rail torsion data: adds the roll (and warping) DOFs to the lateral plane (see the
        module docstring). Ignored for the vertical plane (no roll by symmetry).

    Returns
    -------
    PlaneModel
        K, G, D, M and the DOF map.

    Raises
    ------
    ValueError
        For an unknown direction.
    """
    if direction not in DIRECTIONS:
        raise ValueError(f"direction must be one of {', '.join(DIRECTIONS)}, got {direction!r}")
    torsion = torsion if direction == "lateral" else None
    p = mesh.options.element_order
    rail_nodes, n_rail = element_nodes(mesh.elem_nodes, mesh.n_rail_nodes, p)
    sleeper_nodes, n_sleeper = element_nodes(mesh.selem_nodes, mesh.n_sleeper_nodes, p)
    per_snode = 2 if direction == "vertical" else 1
    torsion_offset = 2 * n_rail + per_snode * n_sleeper
    n_t = 0 if torsion is None else torsion.dofs_per_node
    triplets = Triplets(torsion_offset + n_t * n_rail)
    rail = _rail_props(turnout, mesh, direction)
    K_elements = tim.beam_stiffness(p, rail["L"], rail["EI"], rail["kGA"])
    triplets.add(
        _beam_dofs(rail_nodes),
        K=K_elements,
        G=mesh.elem_eta[:, None, None] * K_elements,
        M=tim.beam_mass(p, rail["L"], rail["rhoA"], rail["rhoI"]),
    )
    _add_sleepers(triplets, turnout, mesh, direction, sleeper_nodes, 2 * n_rail)
    if torsion is None:
        _add_pads(triplets, turnout, mesh, direction, 2 * n_rail)
    else:
        _add_torsion(triplets, turnout, mesh, rail, rail_nodes, torsion, torsion_offset)
        _add_torsion_pads(triplets, turnout, mesh, torsion, 2 * n_rail, torsion_offset)
    matrices = triplets.matrices()
    return PlaneModel(
        direction,
        mesh,
        p,
        matrices["K"],
        matrices["G"],
        matrices["D"],
        matrices["M"],
        rail_nodes,
        2 * n_rail,
        torsion,
        torsion_offset if torsion is not None else -1,
    )


def _rail_material(turnout: Turnout, mesh: Mesh) -> dict[str, np.ndarray]:
    """E (Pa), G (Pa), rho (kg/m^3) of each rail element's type."""
    types = [turnout.rail_types[name] for name in mesh.elem_type]
    E = np.array([t.youngs_modulus for t in types])
    return dict(
        E=E,
        G=E / (2.0 * (1.0 + np.array([t.poisson for t in types]))),
        rho=np.array([t.density for t in types]),
    )


def _add_torsion(
    triplets: Triplets,
    turnout: Turnout,
    mesh: Mesh,
    rail: dict[str, np.ndarray],
    rail_nodes: np.ndarray,
    section: RailTorsionSection,
    offset: int,
) -> None:
    """Torsion-warping elements (T3, T4) and the mass coupling rho A e_c of each rail."""
    p, n_t = mesh.options.element_order, section.dofs_per_node
    material = _rail_material(turnout, mesh)
    E, G, rho = (material[k][:, None] for k in ("E", "G", "rho"))
    GJ = (G * section.J_t)[:, 0]
    area = rail["rhoA"] / rho  # (n, p + 2), Table 1 area at the quadrature points
    e_c = section.centroid_offset
    rhoIp = rho * polar_moment_about_shear_centre(section.I_p, area, e_c)
    K = torsion_stiffness(
        p, rail["L"], GJ, E * section.C_w, section.warping_penalty * GJ, section.warping
    )
    M = torsion_mass(p, rail["L"], rhoIp, rho * section.C_w, section.warping)
    dofs = offset + np.stack([n_t * rail_nodes + j for j in range(n_t)], axis=-1).reshape(
        len(rail_nodes), -1
    )
    triplets.add(dofs, K=K, G=mesh.elem_eta[:, None, None] * K, M=M)
    # kinetic energy - rho A e_c vdot phidot (T4): Gram matrix of the shape functions
    coupling = tim.bar_mass(p, rail["L"], -rail["rhoA"] * e_c)
    zeros = np.zeros_like(coupling)
    both = np.concatenate([2 * rail_nodes, offset + n_t * rail_nodes], axis=1)
    triplets.add(
        both,
        M=np.block([[zeros, coupling], [np.swapaxes(coupling, 1, 2), zeros]]),
    )


def _add_torsion_pads(
    triplets: Triplets,
    turnout: Turnout,
    mesh: Mesh,
    section: RailTorsionSection,
    sleeper_offset: int,
    offset: int,
) -> None:
    """Lateral pads at the rail foot (v + d phi - u) and the pads' roll springs (T5).

    Check rails (:func:`~exudyn_turnout.fe.check_rail.check_rail_types`): the lateral
    support at the bracket's height instead of the foot, and the bracket's roll spring
    (:class:`~exudyn_turnout.fe.check_rail.CheckRailSupport`).
    """
    pads = [turnout.rail_types[rail_type].pad for rail_type in mesh.pad_type]
    k_y, c_y = np.array([pad.k_y for pad in pads]), np.array([pad.c_y for pad in pads])
    k_z, c_z = np.array([pad.k_z for pad in pads]), np.array([pad.c_z for pad in pads])
    roll = offset + section.dofs_per_node * mesh.pad_rail_node
    # check rails: the lateral support acts at the bracket's bolts, and the bracket's leg
    # adds a roll spring (fe/check_rail.py); other rails: at the foot, u_y = v + d phi
    support = check_rail_support(turnout)
    on_bracket = np.isin(np.array(mesh.pad_type), list(check_rail_types(turnout)))
    z = np.where(on_bracket, support.height - section.shear_centre_height, -section.foot_depth)
    a = np.stack([np.ones_like(z), -z, -np.ones_like(z)], axis=1)
    lever = a[:, :, None] * a[:, None, :]
    dofs = np.column_stack([2 * mesh.pad_rail_node, roll, sleeper_offset + mesh.pad_sleeper_node])
    triplets.add(dofs, K=k_y[:, None, None] * lever, D=c_y[:, None, None] * lever)
    b = section.foot_width
    c_leg = np.where(
        c_y > 0,
        support.k_roll * c_y / np.where(k_y > 0, k_y, 1.0),
        0.0,
    )
    if support.c_roll is not None:
        c_leg = np.full_like(c_leg, support.c_roll)
    triplets.add(
        roll[:, None],
        K=(pad_roll_stiffness(k_z, b) + np.where(on_bracket, support.k_roll, 0.0))[:, None, None],
        D=(pad_roll_stiffness(c_z, b) + np.where(on_bracket, c_leg, 0.0))[:, None, None],
    )


def _add_sleepers(
    triplets: Triplets, turnout: Turnout, mesh: Mesh, direction: str, nodes: np.ndarray, offset: int
) -> None:
    sleeper, ballast = turnout.sleeper, turnout.ballast
    layout, p = mesh.layout, mesh.options.element_order
    L = np.diff(mesh.snode_y[mesh.selem_nodes], axis=1)[:, 0]
    if direction == "vertical":
        kGA = (
            layout.bearer_shear_coefficient
            * sleeper.youngs_modulus
            / (2 * (1 + layout.bearer_poisson))
            * sleeper.area
        )
        triplets.add(
            _beam_dofs(nodes, offset),
            K=tim.beam_stiffness(p, L, sleeper.youngs_modulus * sleeper.I, kGA)
            + tim.beam_foundation(p, L, ballast.s_b_z),
            D=tim.beam_foundation(p, L, ballast.d_b_z),
            M=tim.beam_mass(p, L, sleeper.density * sleeper.area, sleeper.density * sleeper.I),
        )
    else:
        triplets.add(
            offset + nodes,
            K=tim.bar_stiffness(p, L, sleeper.youngs_modulus * sleeper.area)
            + tim.bar_mass(p, L, ballast.s_b_y),
            D=tim.bar_mass(p, L, ballast.d_b_y),
            M=tim.bar_mass(p, L, sleeper.density * sleeper.area),
        )


def _add_pads(
    triplets: Triplets, turnout: Turnout, mesh: Mesh, direction: str, offset: int
) -> None:
    pads = [turnout.rail_types[rail_type].pad for rail_type in mesh.pad_type]
    vertical = direction == "vertical"
    k = np.array([pad.k_z if vertical else pad.k_y for pad in pads])
    c = np.array([pad.c_z if vertical else pad.c_y for pad in pads])
    snode_dof = offset + (2 if vertical else 1) * mesh.pad_sleeper_node
    dofs = np.column_stack([2 * mesh.pad_rail_node, snode_dof])
    triplets.add(dofs, K=_spring(k), D=_spring(c))
