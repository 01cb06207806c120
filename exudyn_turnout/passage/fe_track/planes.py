"""The FE track's two planes as the passage steps them: Exudyn's generalized-alpha constants,
the planes' assembled matrices (vertical; lateral with rail torsion) and the time stepper
of one plane (factorised effective matrix, free prediction, completion with the contact
forces, influence columns). The coupling to the vehicle is :mod:`.coupling`."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as sla

from exudyn_turnout.fe.layout import Layout, load_layout
from exudyn_turnout.fe.mesh import build_mesh
from exudyn_turnout.fe.model import PlaneModel, assemble
from exudyn_turnout.fe.torsion import UIC60_SECTION, RailTorsionSection
from exudyn_turnout.inputs.turnout import Turnout

__all__ = [
    "SUPERLU_OPTIONS",
    "GeneralizedAlpha",
    "generalized_alpha",
    "FETrackPlanes",
    "build_fe_planes",
    "PlaneStepper",
    "lagrange_weights",
]


#: SuperLU options for the symmetric positive definite matrices A and K: minimum degree on
#: A + A^T, no pivoting. Against COLAMD a quarter of the fill and half the solve time
#: (turnout, h = 1e-4 s: vertical 0.48 vs 1.80 million nonzeros in L + U, lateral 0.93 vs 2.97).
SUPERLU_OPTIONS = dict(
    permc_spec="MMD_AT_PLUS_A", options=dict(SymmetricMode=True, DiagPivotThresh=0.0)
)


@dataclass(frozen=True)
class GeneralizedAlpha:
    """Constants of the generalized-alpha method (Arnold & Bruls 2007), as Exudyn's."""

    alpha_m: float  #: -
    alpha_f: float  #: -
    beta: float  #: -
    gamma: float  #: -

    @property
    def beta_eff(self) -> float:
        """beta' = beta (1 - alpha_f) / (1 - alpha_m): u_{n+1} = u^ + beta' h^2 qdd_{n+1}."""
        return self.beta * (1.0 - self.alpha_f) / (1.0 - self.alpha_m)

    @property
    def gamma_eff(self) -> float:
        """gamma' = gamma (1 - alpha_f) / (1 - alpha_m): v_{n+1} = v^ + gamma' h qdd_{n+1}."""
        return self.gamma * (1.0 - self.alpha_f) / (1.0 - self.alpha_m)


def generalized_alpha(spectral_radius: float) -> GeneralizedAlpha:
    """Generalized-alpha constants for a high-frequency spectral radius rho_inf in [0, 1].

    alpha_m = (2 rho - 1) / (rho + 1), alpha_f = rho / (rho + 1), gamma = 1/2 + alpha_f -
    alpha_m, beta = (gamma + 1/2)^2 / 4 (Chung & Hulbert 1993, in the form of Arnold &
    Bruls 2007, "Convergence of the generalized-alpha scheme for constrained mechanical
    systems", Multibody System Dynamics 18: the constants Exudyn's ``generalizedAlpha``
    uses, checked by a test against Exudyn's own integration).

    Parameters
    ----------
    spectral_radius : float
        rho_inf in [0, 1].

    Returns
    -------
    GeneralizedAlpha
    """
    rho = float(spectral_radius)
    if not 0.0 <= rho <= 1.0:
        raise ValueError(f"spectral radius must be in [0, 1], got {spectral_radius!r}")
    alpha_m = (2.0 * rho - 1.0) / (rho + 1.0)
    alpha_f = rho / (rho + 1.0)
    gamma = 0.5 + alpha_f - alpha_m
    return GeneralizedAlpha(alpha_m, alpha_f, 0.25 * (gamma + 0.5) ** 2, gamma)


@dataclass(frozen=True)
class FETrackPlanes:
    """The FE track's two planes with time-domain damping (SI units)."""

    vertical: PlaneModel  #: vertical plane (w, psi of the rails; sleepers)
    lateral: PlaneModel  #: lateral plane (v, psi, roll, warping of the rails; sleepers)
    layout: Layout  #: which FE rail lies under each co-running slot
    D_vertical: sp.csc_matrix  #: N s/m, viscous damping + G / omega_ref, vertical
    D_lateral: sp.csc_matrix  #: N s/m, likewise lateral
    build_s: float  #: s, wall time of meshing and assembly


def build_fe_planes(
    turnout: Turnout,
    options=None,
    layout: Layout | None = None,
    torsion: RailTorsionSection | None = UIC60_SECTION,
) -> FETrackPlanes:
    """Mesh and assemble the vertical and the lateral FE planes of the turnout.

    Parameters
    ----------
    turnout : Turnout
        Table 1 properties and the ``[layout]`` section.
    options : FEPassageOptions, optional
        Mesh and ``loss_reference_hz``
        (:class:`~exudyn_turnout.passage.fe_track.options.FEPassageOptions`).
    layout : Layout, optional
        Default :func:`~exudyn_turnout.fe.layout.load_layout` of the turnout.
    torsion : RailTorsionSection or None
        Rail torsion in the lateral plane (default the 60E1 section); None: planar lateral
        bending only.

    Returns
    -------
    FETrackPlanes
    """
    from exudyn_turnout.passage.fe_track.options import FEPassageOptions

    options = options or FEPassageOptions()
    layout = layout or load_layout(turnout)
    t0 = time.perf_counter()
    mesh = build_mesh(turnout, layout, options.mesh)
    vertical = assemble(turnout, mesh, "vertical")
    lateral = assemble(turnout, mesh, "lateral", torsion=torsion)
    omega_ref = 2.0 * math.pi * options.loss_reference_hz
    return FETrackPlanes(
        vertical,
        lateral,
        layout,
        (vertical.D + vertical.G / omega_ref).tocsc(),
        (lateral.D + lateral.G / omega_ref).tocsc(),
        time.perf_counter() - t0,
    )


class PlaneStepper:
    """State, factorised effective matrix and influence columns of one FE plane."""

    def __init__(self, model: PlaneModel, D: sp.spmatrix, h: float, ga: GeneralizedAlpha):
        """Factorise A = M + gamma' h D + beta' h^2 K and start at rest.

        Parameters
        ----------
        model : PlaneModel
            The plane's assembled M and K.
        D : scipy.sparse matrix
            Its damping matrix (viscous and structural at the reference frequency).
        h : float
            s, the time step.
        ga : GeneralizedAlpha
            The integrator's constants.
        """
        self.model, self.h, self.ga = model, h, ga
        A = model.M + ga.gamma_eff * h * D + ga.beta_eff * h * h * model.K
        self.lu = sla.splu(sp.csc_matrix(A), **SUPERLU_OPTIONS)
        self.M, self.D, self.K = model.M.tocsr(), sp.csr_matrix(D), model.K.tocsr()
        n = model.n_dof
        self.u, self.v, self.qdd, self.a = (np.zeros(n) for _ in range(4))
        self.u_hat, self.v_hat, self.qdd_star = np.zeros(n), np.zeros(n), np.zeros(n)
        self._columns: dict[tuple, np.ndarray] = {}  #: (dofs, other, factor) -> A^-1 E

    def columns(
        self, dofs: np.ndarray, other: np.ndarray | None = None, factor: float = 0.0
    ) -> np.ndarray:
        """A^-1 of the unit vectors of ``dofs`` (plus ``factor`` times those of ``other``).

        Parameters
        ----------
        dofs : numpy.ndarray
            (k,) DOF indices.
        other : numpy.ndarray, optional
            (k,) DOFs whose unit vectors are added, times ``factor``, column by column
            (a rail node's lateral displacement and roll: the head's lateral motion).
        factor : float
            Weight of ``other``.

        Returns
        -------
        numpy.ndarray
            (n, k), cached per (dofs, other, factor).
        """
        first = tuple(int(d) for d in dofs)
        second = tuple(int(d) for d in other) if other is not None else ()
        key = (first, second, float(factor))
        cols = self._columns.get(key)
        if cols is None:
            k = len(first)
            E = np.zeros((self.model.n_dof, k))
            E[list(first), np.arange(k)] = 1.0
            if second:
                E[list(second), np.arange(k)] += factor
            cols = self._columns[key] = self.lu.solve(E)
        return cols

    def forget(self, keep: set) -> None:
        """Drop the cached columns whose DOF sets are not in ``keep``.

        Parameters
        ----------
        keep : set of tuple
            DOF sets (tuples of int) still in use.
        """
        for key in [k for k in self._columns if k[0] not in keep]:
            del self._columns[key]

    def predict(self) -> None:
        """u^, v^ and qdd* of the next step (no contact forces)."""
        ga, h = self.ga, self.h
        carry = (ga.alpha_f * self.qdd - ga.alpha_m * self.a) / (1.0 - ga.alpha_m)
        self.u_hat = self.u + h * self.v + h * h * ((0.5 - ga.beta) * self.a + ga.beta * carry)
        self.v_hat = self.v + h * ((1.0 - ga.gamma) * self.a + ga.gamma * carry)
        self.qdd_star = self.lu.solve(-(self.D @ self.v_hat) - self.K @ self.u_hat)

    def complete(self, qdd_contact: np.ndarray) -> None:
        """Finish the step with the contact forces' part A^-1 G F of the acceleration.

        Parameters
        ----------
        qdd_contact : numpy.ndarray
            (n,) the acceleration the contact forces add.
        """
        ga, h = self.ga, self.h
        qdd = self.qdd_star + qdd_contact
        a = ((1.0 - ga.alpha_f) * qdd + ga.alpha_f * self.qdd - ga.alpha_m * self.a) / (
            1.0 - ga.alpha_m
        )
        self.u = self.u + h * self.v + h * h * ((0.5 - ga.beta) * self.a + ga.beta * a)
        self.v = self.v + h * ((1.0 - ga.gamma) * self.a + ga.gamma * a)
        self.qdd, self.a = qdd, a


def lagrange_weights(p: int, xi: float) -> np.ndarray:
    """Lagrange shape functions of order p on nodes 0, 1/p, ..., 1 at one xi (fast scalar).

    The values of :func:`~exudyn_turnout.fe.timoshenko.lagrange_shape_functions` (tested),
    without its derivatives and array overhead.

    Parameters
    ----------
    p : int
        Polynomial order (>= 1).
    xi : float
        Position in [0, 1].

    Returns
    -------
    numpy.ndarray
        (p + 1,) N_i(xi).
    """
    nodes = [i / p for i in range(p + 1)]
    out = np.empty(p + 1)
    for i in range(p + 1):
        value = 1.0
        for j in range(p + 1):
            if j != i:
                value *= (xi - nodes[j]) / (nodes[i] - nodes[j])
        out[i] = value
    return out
