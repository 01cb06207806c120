"""A single rail on a smeared (continuous) two-layer support, by the same elements.

The check of the FE machinery against the closed form of
:func:`~exudyn_turnout.fe.analytic.infinite_timoshenko_receptance`: one Timoshenko beam
(the elements of :mod:`~exudyn_turnout.fe.timoshenko`) on a continuous pad layer k_p',
c_p' (N/m^2, N s/m^2), a sleeper-mass layer m_s' (kg/m) and a ballast layer k_b', c_b',
the discrete supports of Table 1 smeared over the sleeper spacing L_s. The sleeper layer
u(x) is interpolated like w; its matrices are the Gram matrix of the shape functions
times the layer values. The ends absorb: beyond ``length`` the rail's loss factor grows
quadratically to ``eta_max`` over ``absorbing_length`` (as in the turnout model).

For the torsion-aware lateral model, :func:`lateral_torsion_closed_form` evaluates the
closed form :func:`~exudyn_turnout.fe.analytic.infinite_rail_lateral_torsion_receptance`
with a rail type's data and its smeared lateral support, and :func:`refined_supports`
gives a turnout whose discrete supports approach that continuous support (closer sleepers
at the same support per unit length, rigid sleepers), on which the turnout FE itself
(:func:`~exudyn_turnout.fe.model.assemble`) can be compared with the closed form.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
import scipy.sparse.linalg as sla
from numpy.typing import ArrayLike

from exudyn_turnout.fe import timoshenko as tim
from exudyn_turnout.fe.analytic import (
    infinite_rail_lateral_torsion_receptance,
    two_layer_support,
)
from exudyn_turnout.fe.mesh import FEOptions
from exudyn_turnout.fe.model import Triplets, rail_section
from exudyn_turnout.fe.torsion import RailTorsionSection, pad_roll_stiffness
from exudyn_turnout.inputs.turnout import Turnout

__all__ = [
    "ContinuousSupport",
    "smeared_support",
    "continuous_beam_receptance",
    "lateral_torsion_closed_form",
    "refined_supports",
]

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


def lateral_torsion_closed_form(
    turnout: Turnout,
    section: RailTorsionSection,
    frequencies: ArrayLike,
    height: float,
    rail_type: str = "stock",
    eta: float = 0.0,
    warping: bool | None = None,
) -> np.ndarray:
    """Closed-form lateral receptance of one rail type on its smeared support, with torsion.

    Rail: Table 1 section of ``rail_type`` (lateral bending), torsion data of ``section``;
    support: :func:`smeared_support` (lateral pad, whole sleeper, lateral ballast) at the
    rail foot, the pads' roll stiffness k_z b^2 / 12 per sleeper spacing.

    Parameters
    ----------
    turnout : Turnout
        Table 1 properties.
    section : RailTorsionSection
        Torsion data and geometry.
    frequencies : array_like
        Hz.
    height : float
        Height of the lateral load and response above the shear centre (m).
    rail_type : str
        Rail type (section, pads).
    eta : float
        Rail loss factor.
    warping : bool, optional
        Override ``section.warping``.

    Returns
    -------
    numpy.ndarray
        Complex receptance (m/N), one value per frequency.
    """
    rail = turnout.rail_types[rail_type]
    lateral = {
        name: float(np.ravel(value)[0])
        for name, value in rail_section(turnout, rail_type, np.array([0.0]), "lateral").items()
    }
    E, rho = rail.youngs_modulus, rail.density
    G = E / (2.0 * (1.0 + rail.poisson))
    omega = 2 * np.pi * np.asarray(frequencies, float)
    support = smeared_support(turnout, rail_type, "lateral")
    s_y = two_layer_support(
        omega, support.k_p, support.c_p, support.m_s, support.k_b, support.c_b, 1.0
    )
    k_phi = pad_roll_stiffness(rail.pad.k_z + 1j * omega * rail.pad.c_z, section.foot_width) / (
        turnout.sleeper.spacing
    )
    with_warping = section.warping if warping is None else warping
    GJ = G * section.J_t
    return infinite_rail_lateral_torsion_receptance(
        omega,
        lateral["EI"],
        lateral["kGA"],
        lateral["rhoA"],
        lateral["rhoI"],
        GJ,
        E * section.C_w if with_warping else 0.0,
        section.warping_penalty * GJ,
        rho * section.I_p,
        section.centroid_offset,
        s_y,
        section.foot_depth,
        k_phi,
        height,
        eta=eta,
        rhoCw=rho * section.C_w,
    )


def refined_supports(turnout: Turnout, spacing: float, rigid_factor: float = 1e3) -> Turnout:
    """The turnout with sleepers ``spacing`` apart and the same support per unit length.

    Pads (all four values), sleeper mass and ballast per sleeper scale with
    spacing / L_s; the sleepers' Young's modulus is multiplied by ``rigid_factor`` (the
    smeared support of :func:`smeared_support` treats the sleeper as a rigid mass). With
    a spacing well below the bending and torsional wavelengths the discrete FE approaches
    the continuous support of the closed form (the pinned-pinned frequency moves up by
    (L_s / spacing)^2).

    Parameters
    ----------
    turnout : Turnout
        The turnout.
    spacing : float
        New sleeper spacing (m).
    rigid_factor : float
        Factor on the sleeper's Young's modulus.

    Returns
    -------
    Turnout
        A modified copy.
    """
    scale = spacing / turnout.sleeper.spacing
    sleeper = dataclasses.replace(
        turnout.sleeper,
        spacing=spacing,
        density=turnout.sleeper.density * scale,
        youngs_modulus=turnout.sleeper.youngs_modulus * rigid_factor,
    )
    ballast = dataclasses.replace(
        turnout.ballast,
        s_b_z=turnout.ballast.s_b_z * scale,
        d_b_z=turnout.ballast.d_b_z * scale,
        s_b_y=turnout.ballast.s_b_y * scale,
        d_b_y=turnout.ballast.d_b_y * scale,
    )
    rail_types = {
        name: dataclasses.replace(
            rail,
            pad=dataclasses.replace(
                rail.pad,
                k_z=rail.pad.k_z * scale,
                c_z=rail.pad.c_z * scale,
                k_y=rail.pad.k_y * scale,
                c_y=rail.pad.c_y * scale,
            ),
        )
        for name, rail in turnout.rail_types.items()
    }
    return dataclasses.replace(turnout, sleeper=sleeper, ballast=ballast, rail_types=rail_types)
