"""A contact point on the rail head: its load vector on the FE DOFs and its displacement.

For the FE passage (the FE track under the one vehicle): a wheel/rail contact at position x
on FE rail r, at height z above the rail's shear centre and lateral offset y from it
(left positive, as the layout's y), carries a lateral force F_y and a vertical force F_z
(on the rail). In the rail element containing x (nodes x_1 < x_2, order p) every field is
interpolated by the Lagrange shape functions N(xi) of
:func:`~exudyn_turnout.fe.timoshenko.lagrange_shape_functions`, so with (T1) of
:mod:`~exudyn_turnout.fe.torsion`::

    u_z = N . w_e + y N . phi_e     (vertical model's w; lateral model's phi)
    u_y = N . v_e - z N . phi_e     (lateral model's v and phi)

and the consistent loads are the transposes: F_z N on the vertical w DOFs, F_y N on the
lateral v DOFs, the torque T = y F_z - z F_y (T2) times N on the roll DOFs. Reciprocity
u_y F_y + u_z F_z = f_vertical . q_vertical + f_lateral . q_lateral holds by construction
(the tests check it). A lateral model without torsion has no roll: the torque is dropped
and the rail head moves with the shear centre (the planar model).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from exudyn_turnout.fe.model import PlaneModel
from exudyn_turnout.fe.timoshenko import lagrange_shape_functions

__all__ = ["RailHeadPoint", "rail_head_point", "element_at"]

_X_TOL = 1e-9  # m


def element_at(model: PlaneModel, rail_id: str, x: float) -> tuple[int, float]:
    """Rail element of a rail containing x and the local coordinate xi in [0, 1].

    On an element boundary the later element is taken (the value of a C0 field is the
    same in both).

    Parameters
    ----------
    model : PlaneModel
        An assembled model.
    rail_id : str
        Layout rail id.
    x : float
        Position from the switch toe (m).

    Returns
    -------
    element : int
        Index into ``model.rail_elem_nodes``.
    xi : float
        Local coordinate.

    Raises
    ------
    ValueError
        x is not on the rail.
    """
    mesh = model.mesh
    elements = mesh.rail_elems[rail_id]
    x0 = mesh.node_x[mesh.elem_nodes[elements, 0]]
    x1 = mesh.node_x[mesh.elem_nodes[elements, 1]]
    if not x0[0] - _X_TOL <= x <= x1[-1] + _X_TOL:
        raise ValueError(f"x = {x:g} m is not on rail {rail_id} ({x0[0]:g} to {x1[-1]:g} m)")
    k = int(np.clip(np.searchsorted(x0, x + _X_TOL, side="right") - 1, 0, len(elements) - 1))
    xi = float(np.clip((x - x0[k]) / (x1[k] - x0[k]), 0.0, 1.0))
    return int(elements[k]), xi


@dataclass(frozen=True)
class RailHeadPoint:
    """Where a contact acts: DOFs and shape-function weights of the fields at x."""

    rail_id: str  #: layout rail id
    x: float  #: m, position along the rail
    y: float  #: m, lateral offset of the contact from the shear centre (left positive)
    z: float  #: m, height of the contact above the shear centre
    weights: np.ndarray  #: (p + 1,) shape functions N(xi) of the element's nodes
    w_dofs: np.ndarray  #: (p + 1,) vertical model: w DOFs of the element's nodes
    v_dofs: np.ndarray  #: (p + 1,) lateral model: v DOFs
    roll_dofs: np.ndarray | None  #: (p + 1,) lateral model: phi DOFs, None without torsion
    n_dof_vertical: int  #: size of the vertical model
    n_dof_lateral: int  #: size of the lateral model

    def loads(self, F_y: float, F_z: float) -> tuple[np.ndarray, np.ndarray]:
        """Consistent load vectors of contact forces on the rail.

        Parameters
        ----------
        F_y : float
            Lateral force on the rail (N, +y left).
        F_z : float
            Vertical force on the rail (N, +z up; a wheel pressing down gives F_z < 0).

        Returns
        -------
        f_vertical, f_lateral : numpy.ndarray
            Load vectors (N, N m) on the vertical and lateral models' DOFs.
        """
        f_v = np.zeros(self.n_dof_vertical)
        f_l = np.zeros(self.n_dof_lateral)
        np.add.at(f_v, self.w_dofs, F_z * self.weights)
        np.add.at(f_l, self.v_dofs, F_y * self.weights)
        if self.roll_dofs is not None:
            torque = self.y * F_z - self.z * F_y  # (T2)
            np.add.at(f_l, self.roll_dofs, torque * self.weights)
        return f_v, f_l

    def displacement(self, q_vertical: np.ndarray, q_lateral: np.ndarray) -> tuple[float, float]:
        """Displacement of the contact point of the rail head (T1).

        Parameters
        ----------
        q_vertical, q_lateral : numpy.ndarray
            DOF vectors of the vertical and lateral models (m, rad), real or complex.

        Returns
        -------
        u_y, u_z : float or complex
            Lateral and vertical displacement of the point (m).
        """
        N = self.weights
        u_z = N @ q_vertical[self.w_dofs]
        u_y = N @ q_lateral[self.v_dofs]
        if self.roll_dofs is not None:
            phi = N @ q_lateral[self.roll_dofs]
            u_z = u_z + self.y * phi
            u_y = u_y - self.z * phi
        return u_y, u_z


def rail_head_point(
    vertical: PlaneModel,
    lateral: PlaneModel,
    rail_id: str,
    x: float,
    y: float = 0.0,
    z: float | None = None,
) -> RailHeadPoint:
    """The contact point at x on a rail: DOFs and weights of both planes' fields.

    Parameters
    ----------
    vertical, lateral : PlaneModel
        The vertical and lateral models, assembled on the same mesh (the lateral one with
        or without ``torsion``).
    rail_id : str
        Layout rail id.
    x : float
        Position along the rail (m), anywhere on it (not only at nodes).
    y : float
        Lateral offset of the contact from the rail's shear centre (m, left positive).
    z : float, optional
        Height of the contact above the shear centre (m); default the rail top
        (``torsion.height - torsion.shear_centre_height``), 0 without torsion.

    Returns
    -------
    RailHeadPoint
        With :meth:`RailHeadPoint.loads` and :meth:`RailHeadPoint.displacement`.

    Raises
    ------
    ValueError
        The models are not the vertical and lateral planes of one mesh, or x is not on
        the rail.
    """
    if (vertical.direction, lateral.direction) != ("vertical", "lateral"):
        raise ValueError("rail_head_point needs the vertical and the lateral model, in that order")
    if vertical.mesh is not lateral.mesh or vertical.order != lateral.order:
        raise ValueError("the vertical and lateral models must share one mesh")
    element, xi = element_at(vertical, rail_id, float(x))
    nodes = vertical.rail_elem_nodes[element]
    section = lateral.torsion
    if z is None:
        z = section.height - section.shear_centre_height if section is not None else 0.0
    return RailHeadPoint(
        rail_id,
        float(x),
        float(y),
        float(z),
        lagrange_shape_functions(vertical.order, [xi])[0][0],
        2 * nodes,
        2 * nodes,
        lateral.roll_dof(nodes) if section is not None else None,
        vertical.n_dof,
        lateral.n_dof,
    )
