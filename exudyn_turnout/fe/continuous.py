"""A single rail on a smeared (continuous) two-layer support, by the same elements.

The check of the FE machinery against the closed form of
:func:`~exudyn_turnout.fe.analytic.infinite_timoshenko_receptance`: one Timoshenko beam
(the elements of :mod:`~exudyn_turnout.fe.timoshenko`) on a continuous pad layer k_p',
c_p' (N/m^2, N s/m^2), a sleeper-mass layer m_s' (kg/m) and a ballast layer k_b', c_b',
the discrete supports of Table 1 smeared over the sleeper spacing L_s. The sleeper layer
u(x) is interpolated like w; its matrices are the Gram matrix of the shape functions
times the layer values. The ends absorb: beyond ``length`` the rail's loss factor grows
quadratically to ``eta_max`` over ``absorbing_length`` (as in the turnout model).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse.linalg as sla
from numpy.typing import ArrayLike

from exudyn_turnout.fe import timoshenko as tim
from exudyn_turnout.fe.mesh import FEOptions
from exudyn_turnout.fe.model import Triplets, rail_section
from exudyn_turnout.inputs.turnout import Turnout

__all__ = ["ContinuousSupport", "smeared_support", "continuous_beam_receptance"]

#: Default options of :func:`continuous_beam_receptance`: no rail damping, as the closed form.
_CLOSED_FORM_OPTIONS = FEOptions(rail_loss_factor=0.0)


@dataclass(frozen=True)
class ContinuousSupport:
    """Two-layer support per unit rail length (SI)."""

    k_p: float  #: N/m^2, pad layer stiffness
    c_p: float  #: N s/m^2, pad layer damping
    m_s: float  #: kg/m, sleeper mass layer
    k_b: float  #: N/m^2, ballast layer stiffness
    c_b: float  #: N s/m^2, ballast layer damping

    @property
    def k_s(self) -> float:
        """Static stiffness of the two layers in series (N/m^2): Eq 2's k_s."""
        return self.k_p * self.k_b / (self.k_p + self.k_b)


def smeared_support(
    turnout: Turnout, rail_type: str = "stock", direction: str = "vertical"
) -> ContinuousSupport:
    """Table 1's pads, sleeper and ballast under one rail, smeared over the spacing L_s.

    Vertical: the rail's share of the sleeper, L_t / n (Eq 4), for its mass and ballast;
    lateral: the whole sleeper (Eq 13). L_t and n are the rail type's Table 1 values.

    Parameters
    ----------
    turnout : Turnout
        Table 1 properties of pads, sleeper and ballast.
    rail_type : str
        Rail type whose pads, sleeper length and rails per sleeper are used.
    direction : {"vertical", "lateral"}
        Which pad and ballast properties.

    Returns
    -------
    ContinuousSupport
        The layers per unit rail length.
    """
    rail, sleeper, ballast = turnout.rail_types[rail_type], turnout.sleeper, turnout.ballast
    L_s = sleeper.spacing
    if direction == "vertical":
        share = rail.sleeper_length / rail.rails_per_sleeper
        return ContinuousSupport(
            rail.pad.k_z / L_s,
            rail.pad.c_z / L_s,
            sleeper.density * sleeper.area * share / L_s,
            ballast.s_b_z * share / L_s,
            ballast.d_b_z * share / L_s,
        )
    L_t = rail.sleeper_length
    return ContinuousSupport(
        rail.pad.k_y / L_s,
        rail.pad.c_y / L_s,
        sleeper.density * sleeper.area * L_t / L_s,
        ballast.s_b_y * L_t / L_s,
        ballast.d_b_y * L_t / L_s,
    )


def _model(section: dict, support: ContinuousSupport, length: float, options: FEOptions):
    """K + iG, D, M (CSC) and the DOF of w at x = 0 of the beam on the layers."""
    p, reach = options.element_order, length / 2 + options.absorbing_length
    n_elements = 2 * int(np.ceil(reach / options.element_length))
    x = np.linspace(-reach, reach, n_elements + 1)
    L = np.diff(x)
    depth = np.clip(
        (np.abs(0.5 * (x[:-1] + x[1:])) - length / 2) / options.absorbing_length, 0.0, 1.0
    )
    eta = options.rail_loss_factor + options.eta_max * depth**2
    nodes = np.arange(n_elements * p + 1)
    elements = np.stack([nodes[i * p : i * p + p + 1] for i in range(n_elements)])
    # (w, psi) per node
    beam = np.stack([2 * elements, 2 * elements + 1], axis=-1).reshape(n_elements, -1)
    layer = 2 * len(nodes) + elements  # sleeper-layer u per node
    triplets = Triplets(3 * len(nodes))
    K = tim.beam_stiffness(p, L, section["EI"], section["kGA"])
    M = tim.beam_mass(p, L, section["rhoA"], section["rhoI"])
    triplets.add(beam, K=K, G=eta[:, None, None] * K, M=M)

    def gram(q: float) -> np.ndarray:
        """int q N N^T over each element, the layers' Gram matrix."""
        return tim.bar_mass(p, L, q)

    def pad(q: float) -> np.ndarray:
        """int q (w - u)^2 over each element: a layer between the rail's w and u."""
        return np.block([[gram(q), -gram(q)], [-gram(q), gram(q)]])

    both = np.concatenate([beam[:, 0::2], layer], axis=1)  # w and u DOFs of each element
    triplets.add(both, K=pad(support.k_p), D=pad(support.c_p))
    triplets.add(layer, K=gram(support.k_b), D=gram(support.c_b), M=gram(support.m_s))
    matrices = triplets.matrices()
    centre_dof = 2 * (n_elements // 2) * p
    return matrices["K"] + 1j * matrices["G"], matrices["D"], matrices["M"], centre_dof


def continuous_beam_receptance(
    turnout: Turnout,
    support: ContinuousSupport,
    frequencies: ArrayLike,
    rail_type: str = "stock",
    direction: str = "vertical",
    length: float = 40.0,
    options: FEOptions = _CLOSED_FORM_OPTIONS,
    section: dict | None = None,
) -> np.ndarray:
    """Point receptance (m/N, complex) at the middle of the smeared-support beam.

    Parameters
    ----------
    turnout : Turnout
        Rail section of ``rail_type`` (Table 1) unless ``section`` is given.
    support : ContinuousSupport
        From :func:`smeared_support` or built by hand.
    frequencies : array_like
        Hz; 0 gives the static compliance.
    rail_type : str
        Rail type whose section is used (Table 1), unless ``section`` is given.
    direction : {"vertical", "lateral"}
        Bending plane of the rail section.
    length : float
        m, undamped length of beam before the absorbing ends.
    options : FEOptions
        Element order and length, absorbing ends; the rail loss factor is 0 by default,
        as in the closed form.
    section : dict, optional
        EI, kGA, rhoA, rhoI (SI) overriding the rail type's.

    Returns
    -------
    numpy.ndarray
        Complex receptance (m/N), one value per frequency.
    """
    section = section or {
        name: float(np.ravel(value)[0])
        for name, value in rail_section(turnout, rail_type, np.array([0.0]), direction).items()
    }
    A, D, M, dof = _model(section, support, length, options)
    out = []
    for frequency in np.asarray(frequencies, float):
        omega = 2 * np.pi * frequency
        force = np.zeros(A.shape[0], complex)
        force[dof] = 1.0
        out.append(sla.splu((A + 1j * omega * D - omega**2 * M).tocsc()).solve(force)[dof])
    return np.array(out)
