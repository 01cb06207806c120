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
---------------------------------------------------
With the load at the shear centre and sections symmetric about the vertical, vertical and
lateral bending of a rail are uncoupled. They couple only through eccentricities: the
lateral pad force acts at the rail foot, h_t / 2 = 0.11 m above the sleeper's axis, and
the lateral load at the rail head ~0.17 m above the shear centre rolls the rail. Table 1
gives neither rail torsion, rail heights nor pad roll stiffness, so a coupled model would
rest on invented data; the paper's own equivalent parameters (Eqs 1-15) treat the two
directions separately, and so do the co-running models we compare with. The vertical
receptance is unaffected to first order (a vertical load on a symmetric section excites
no lateral motion); the lateral one misses rail roll, which lowers the lateral stiffness
of a real rail above ~500 Hz and is not in the paper's model either.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from exudyn_turnout.fe import timoshenko as tim
from exudyn_turnout.fe.mesh import Mesh
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
    rotation) or 1 (lateral: axial u) after all rail DOFs.
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
        return np.concatenate([rail, sleeper])

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


def assemble(turnout: Turnout, mesh: Mesh, direction: str) -> PlaneModel:
    """Sparse model of one plane (see the module docstring).

    Parameters
    ----------
    turnout : Turnout
        Table 1 properties (rails, pads, sleepers, ballast).
    mesh : Mesh
        From :func:`~exudyn_turnout.fe.mesh.build_mesh`.
    direction : {"vertical", "lateral"}
        Bending plane.

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
    p = mesh.options.element_order
    rail_nodes, n_rail = element_nodes(mesh.elem_nodes, mesh.n_rail_nodes, p)
    sleeper_nodes, n_sleeper = element_nodes(mesh.selem_nodes, mesh.n_sleeper_nodes, p)
    per_snode = 2 if direction == "vertical" else 1
    triplets = Triplets(2 * n_rail + per_snode * n_sleeper)
    rail = _rail_props(turnout, mesh, direction)
    K_elements = tim.beam_stiffness(p, rail["L"], rail["EI"], rail["kGA"])
    triplets.add(
        _beam_dofs(rail_nodes),
        K=K_elements,
        G=mesh.elem_eta[:, None, None] * K_elements,
        M=tim.beam_mass(p, rail["L"], rail["rhoA"], rail["rhoI"]),
    )
    _add_sleepers(triplets, turnout, mesh, direction, sleeper_nodes, 2 * n_rail)
    _add_pads(triplets, turnout, mesh, direction, 2 * n_rail)
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
