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

from exudyn_turnout.fe import timoshenko as tim
from exudyn_turnout.fe.mesh import FEOptions
from exudyn_turnout.fe.model import Triplets, rail_section
from exudyn_turnout.inputs.turnout import Turnout

__all__ = ["ContinuousSupport", "smeared_support", "continuous_beam_receptance"]


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
    """
    t, s, b = turnout.rail_types[rail_type], turnout.sleeper, turnout.ballast
    L_s = s.spacing
    if direction == "vertical":
        share = t.sleeper_length / t.rails_per_sleeper
        return ContinuousSupport(
            t.pad.k_z / L_s,
            t.pad.c_z / L_s,
            s.density * s.area * share / L_s,
            b.s_b_z * share / L_s,
            b.d_b_z * share / L_s,
        )
    L_t = t.sleeper_length
    return ContinuousSupport(
        t.pad.k_y / L_s,
        t.pad.c_y / L_s,
        s.density * s.area * L_t / L_s,
        b.s_b_y * L_t / L_s,
        b.d_b_y * L_t / L_s,
    )


def _model(section: dict, support: ContinuousSupport, length: float, options: FEOptions):
    """K + iG, D, M (CSC) and the DOF of w at x = 0 of the beam on the layers."""
    p, reach = options.element_order, length / 2 + options.absorbing_length
    n_el = 2 * int(np.ceil(reach / options.element_length))
    x = np.linspace(-reach, reach, n_el + 1)
    L = np.diff(x)
    depth = np.clip(
        (np.abs(0.5 * (x[:-1] + x[1:])) - length / 2) / options.absorbing_length, 0.0, 1.0
    )
    eta = options.rail_loss_factor + options.eta_max * depth**2
    nodes = np.arange(n_el * p + 1)
    elem = np.stack([nodes[i * p : i * p + p + 1] for i in range(n_el)])
    beam = np.stack([2 * elem, 2 * elem + 1], axis=-1).reshape(n_el, -1)  # (w, psi) per node
    layer = 2 * len(nodes) + elem  # sleeper-layer u per node
    trip = Triplets(3 * len(nodes))
    K = tim.beam_stiffness(p, L, section["EI"], section["kGA"])
    trip.add(
        beam, K=K, G=eta[:, None, None] * K, M=tim.beam_mass(p, L, section["rhoA"], section["rhoI"])
    )
    N = lambda q: tim.bar_mass(p, L, q)  # noqa: E731  int q N N^T, the layers' Gram matrix
    both = np.concatenate([beam[:, 0::2], layer], axis=1)  # w and u DOFs of each element
    pad = lambda q: np.block([[N(q), -N(q)], [-N(q), N(q)]])  # noqa: E731  int q (w - u)^2
    trip.add(both, K=pad(support.k_p), D=pad(support.c_p))
    trip.add(layer, K=N(support.k_b), D=N(support.c_b), M=N(support.m_s))
    m = trip.matrices()
    return m["K"] + 1j * m["G"], m["D"], m["M"], 2 * (n_el // 2) * p


def continuous_beam_receptance(
    turnout: Turnout,
    support: ContinuousSupport,
    frequencies,
    rail_type: str = "stock",
    direction: str = "vertical",
    length: float = 40.0,
    options: FEOptions = FEOptions(rail_loss_factor=0.0),
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
    length : float
        m, undamped length of beam before the absorbing ends.
    options : FEOptions
        Element order and length, absorbing ends; the rail loss factor is 0 by default,
        as in the closed form.
    section : dict, optional
        EI, kGA, rhoA, rhoI (SI) overriding the rail type's.
    """
    section = section or {
        k: float(np.ravel(v)[0])
        for k, v in rail_section(turnout, rail_type, np.array([0.0]), direction).items()
    }
    A, D, M, dof = _model(section, support, length, options)
    out = []
    for f in np.asarray(frequencies, float):
        w = 2 * np.pi * f
        b = np.zeros(A.shape[0], complex)
        b[dof] = 1.0
        out.append(sla.splu((A + 1j * w * D - w**2 * M).tocsc()).solve(b)[dof])
    return np.array(out)
