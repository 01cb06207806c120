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
    mesh: Mesh
    order: int  #: element order p
    K: sp.csc_matrix  #: N/m, stiffness
    G: sp.csc_matrix  #: N/m, structural loss (rail loss factor, absorbing ends)
    D: sp.csc_matrix  #: N s/m, viscous damping
    M: sp.csc_matrix  #: kg, mass
    rail_elem_nodes: np.ndarray  #: (n, p + 1) nodes of each rail element, along x
    sleeper_dof_offset: int  #: first sleeper DOF (all rail DOFs come before)

    @property
    def n_dof(self) -> int:
        return self.K.shape[0]

    def vertex_dofs(self) -> np.ndarray:
        """DOFs of the element end nodes (rail and sleeper), without element interiors."""
        per = 2 if self.direction == "vertical" else 1
        rail = np.arange(2 * self.mesh.n_rail_nodes)
        return np.concatenate(
            [rail, self.sleeper_dof_offset + np.arange(per * self.mesh.n_sleeper_nodes)]
        )

    def dynamic_stiffness(self, omega: float) -> sp.csc_matrix:
        """Z(omega) = K + iG + i omega D - omega^2 M (complex, CSC)."""
        data = self.K.data + 1j * (self.G.data + omega * self.D.data) - omega**2 * self.M.data
        return sp.csc_matrix((data, self.K.indices, self.K.indptr), shape=self.K.shape)

    def point_vector(self, rail_id: str, x: float) -> np.ndarray:
        """b (n_dof,) with w(x) = b . q: the unit vector of the rail node at x.

        Also the load vector of a unit point force there. x must be a node (see
        :meth:`~exudyn_turnout.fe.mesh.Mesh.node_at`).
        """
        b = np.zeros(self.n_dof)
        b[2 * self.mesh.node_at(rail_id, x)] = 1.0
        return b


def rail_section(
    turnout: Turnout, type_name: str, x: np.ndarray, direction: str
) -> dict[str, np.ndarray]:
    """EI, kGA, rhoA, rhoI (SI) of a rail type at positions x, for one bending plane."""
    t = turnout.rail_types[type_name]
    x = np.asarray(x, float)
    A = np.interp(x, t.area.x, t.area.value)
    I_tab = t.I_z if direction == "vertical" else t.I_y
    I = np.interp(x, I_tab.x, I_tab.value)
    G = t.youngs_modulus / (2.0 * (1.0 + t.poisson))
    return dict(
        EI=t.youngs_modulus * I,
        kGA=t.shear_coefficient * G * A,
        rhoA=t.density * A,
        rhoI=t.density * I,
    )


def _rail_props(turnout: Turnout, mesh: Mesh, direction: str) -> dict[str, np.ndarray]:
    """Element lengths (n,) and sections at the quadrature points (n, p + 2)."""
    x1 = mesh.node_x[mesh.elem_nodes[:, 0]]
    L = mesh.node_x[mesh.elem_nodes[:, 1]] - x1
    xg = x1[:, None] + L[:, None] * tim.gauss_points(mesh.options.element_order)[None, :]
    types = np.array(mesh.elem_type)
    out = {k: np.empty(xg.shape) for k in ("EI", "kGA", "rhoA", "rhoI")}
    for name in set(mesh.elem_type):
        sel = types == name
        for k, v in rail_section(turnout, name, xg[sel], direction).items():
            out[k][sel] = v
    out["L"] = L
    return out


def element_nodes(vertex_pairs: np.ndarray, n_vertices: int, p: int) -> tuple[np.ndarray, int]:
    """Nodes (n, p + 1) of order-p elements on vertex pairs, interior nodes numbered after
    the vertices; and the total number of nodes."""
    n = len(vertex_pairs)
    interior = n_vertices + np.arange(n * (p - 1)).reshape(n, p - 1)
    return np.column_stack([vertex_pairs[:, 0], interior, vertex_pairs[:, 1]]), n_vertices + n * (
        p - 1
    )


class Triplets:
    """COO triplets of K, G, D, M collected on one shared pattern."""

    def __init__(self, n: int):
        self.n, self.rows, self.cols, self.vals = n, [], [], {k: [] for k in "KGDM"}

    def add(self, dofs: np.ndarray, **blocks: np.ndarray) -> None:
        """Element blocks (n_el, m, m) on DOFs (n_el, m) for any of K, G, D, M."""
        m = dofs.shape[1]
        self.rows.append(np.repeat(dofs, m, axis=1).ravel())
        self.cols.append(np.tile(dofs, (1, m)).ravel())
        size = dofs.shape[0] * m * m
        for k in "KGDM":
            self.vals[k].append(blocks[k].ravel() if k in blocks else np.zeros(size))

    def matrices(self) -> dict[str, sp.csc_matrix]:
        rows, cols, n = np.concatenate(self.rows), np.concatenate(self.cols), self.n
        lin, inv = np.unique(cols.astype(np.int64) * n + rows, return_inverse=True)
        indices, col = (lin % n).astype(np.int32), lin // n
        indptr = np.searchsorted(col, np.arange(n + 1)).astype(np.int32)
        out = {}
        for k, v in self.vals.items():
            data = np.bincount(inv, weights=np.concatenate(v), minlength=len(lin))
            out[k] = sp.csc_matrix((data, indices, indptr), shape=(n, n))
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
    """
    if direction not in DIRECTIONS:
        raise ValueError(f"direction must be one of {', '.join(DIRECTIONS)}, got {direction!r}")
    p = mesh.options.element_order
    rail_nodes, n_rail = element_nodes(mesh.elem_nodes, mesh.n_rail_nodes, p)
    sleeper_nodes, n_sleeper = element_nodes(mesh.selem_nodes, mesh.n_sleeper_nodes, p)
    per_snode = 2 if direction == "vertical" else 1
    trip = Triplets(2 * n_rail + per_snode * n_sleeper)
    rp = _rail_props(turnout, mesh, direction)
    Ke = tim.beam_stiffness(p, rp["L"], rp["EI"], rp["kGA"])
    trip.add(
        _beam_dofs(rail_nodes),
        K=Ke,
        G=mesh.elem_eta[:, None, None] * Ke,
        M=tim.beam_mass(p, rp["L"], rp["rhoA"], rp["rhoI"]),
    )
    _add_sleepers(trip, turnout, mesh, direction, sleeper_nodes, 2 * n_rail)
    _add_pads(trip, turnout, mesh, direction, 2 * n_rail)
    m = trip.matrices()
    return PlaneModel(direction, mesh, p, m["K"], m["G"], m["D"], m["M"], rail_nodes, 2 * n_rail)


def _add_sleepers(
    trip: Triplets, turnout: Turnout, mesh: Mesh, direction: str, nodes: np.ndarray, offset: int
) -> None:
    s, b, lay, p = turnout.sleeper, turnout.ballast, mesh.layout, mesh.options.element_order
    L = np.diff(mesh.snode_y[mesh.selem_nodes], axis=1)[:, 0]
    if direction == "vertical":
        kGA = (
            lay.bearer_shear_coefficient
            * s.youngs_modulus
            / (2 * (1 + lay.bearer_poisson))
            * s.area
        )
        trip.add(
            _beam_dofs(nodes, offset),
            K=tim.beam_stiffness(p, L, s.youngs_modulus * s.I, kGA)
            + tim.beam_foundation(p, L, b.s_b_z),
            D=tim.beam_foundation(p, L, b.d_b_z),
            M=tim.beam_mass(p, L, s.density * s.area, s.density * s.I),
        )
    else:
        trip.add(
            offset + nodes,
            K=tim.bar_stiffness(p, L, s.youngs_modulus * s.area) + tim.bar_mass(p, L, b.s_b_y),
            D=tim.bar_mass(p, L, b.d_b_y),
            M=tim.bar_mass(p, L, s.density * s.area),
        )


def _add_pads(trip: Triplets, turnout: Turnout, mesh: Mesh, direction: str, offset: int) -> None:
    pads = [turnout.rail_types[t].pad for t in mesh.pad_type]
    vertical = direction == "vertical"
    k = np.array([p.k_z if vertical else p.k_y for p in pads])
    c = np.array([p.c_z if vertical else p.c_y for p in pads])
    snode_dof = offset + (2 if vertical else 1) * mesh.pad_sleeper_node
    dofs = np.column_stack([2 * mesh.pad_rail_node, snode_dof])
    trip.add(dofs, K=_spring(k), D=_spring(c))
