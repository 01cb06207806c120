"""The FE track's two planes as the passage steps them: Exudyn's generalized-alpha constants,
the planes' assembled matrices (vertical; lateral with rail torsion), the sparse Cholesky
factor of their SPD matrices, the moving window of DOFs a passage steps, and the time
stepper of one plane (factorised effective matrix, free prediction, completion with the
contact forces, influence columns). The coupling to the vehicle is :mod:`.coupling`.

Why CHOLMOD (the ``cholespy`` wheel): the step matrices A = M + gamma' h D + beta' h^2 K,
the stiffness K and the mass M are symmetric positive definite, and nearly all of a step is
the two triangular solves with A. Measured on the packaged turnout (h = 1e-4 s, one process,
``benchmarks/bench_fe.py --solver``): a solve with CHOLMOD's supernodal factor takes 0.3-0.5 of
SuperLU's with its best ordering (minimum degree on A + A^T, no pivoting), equal to 1e-13
relative; PARDISO (``pypardiso``) was 2-2.4x slower than SuperLU (issue 24) and
scikit-sparse has no wheel. ``cholespy`` ships wheels for Linux, macOS and Windows
(CPython 3.8-3.13) and bundles CHOLMOD. No SuperLU fallback is kept: the dependency is a
wheel, and two paths would be two sets of numbers to defend. Its solves hold the GIL, so
the two planes are solved one after the other."""

from __future__ import annotations

import atexit
import math
import time
import weakref
from collections.abc import Sequence
from dataclasses import dataclass

import numba
import numpy as np
import scipy.sparse as sp

from exudyn_turnout.fe.layout import Layout, load_layout
from exudyn_turnout.fe.mesh import build_mesh
from exudyn_turnout.fe.model import PlaneModel, assemble
from exudyn_turnout.fe.torsion import UIC60_SECTION, RailTorsionSection
from exudyn_turnout.inputs.turnout import Turnout

__all__ = [
    "CholeskyFactor",
    "dof_positions",
    "window_dofs",
    "GeneralizedAlpha",
    "generalized_alpha",
    "FETrackPlanes",
    "build_fe_planes",
    "PlaneStepper",
    "lagrange_weights",
]


#: The live factors: freed before the interpreter's shutdown (nanobind, cholespy's binding,
#: otherwise reports every factor still referenced then, e.g. from an Exudyn user function, as
#: a leak on stderr).
_FACTORS: weakref.WeakSet = weakref.WeakSet()


@atexit.register
def _free_factors() -> None:
    for factor in list(_FACTORS):
        factor._solver = None


class CholeskyFactor:
    """Sparse Cholesky factor (CHOLMOD through ``cholespy``) of a symmetric positive
    definite matrix (module docstring: why).

    Parameters
    ----------
    A : scipy.sparse matrix
        (n, n) symmetric positive definite.
    """

    def __init__(self, A: sp.spmatrix):
        from cholespy import CholeskySolverD, MatrixType

        C = sp.coo_matrix(A)
        self.n = C.shape[0]
        self._solver = CholeskySolverD(
            self.n,
            C.row.astype(np.int32),
            C.col.astype(np.int32),
            C.data.astype(np.float64),
            MatrixType.COO,
        )
        _FACTORS.add(self)

    def solve(self, b: np.ndarray) -> np.ndarray:
        """x = A^-1 b.

        Parameters
        ----------
        b : numpy.ndarray
            (n,) or (n, k) right-hand sides.

        Returns
        -------
        numpy.ndarray
            x, of the shape of b.
        """
        rhs = np.ascontiguousarray(b, dtype=np.float64)
        x = np.empty_like(rhs)
        self._solver.solve(rhs, x)
        return x


def dof_positions(model) -> np.ndarray:
    """x (m) of every DOF of a plane: its node's x; a sleeper's DOFs the x of its rail nodes.

    Rail DOFs (deflection, rotation, roll and warping of a vertex or interior node) take the
    node's x (interior nodes evenly spaced in their element, as the elements are built);
    every other DOF (sleepers) takes the mean x of the DOFs it is coupled to in K, repeated
    until all have one (a sleeper lies at one x under all its rails).

    Parameters
    ----------
    model : PlaneModel

    Returns
    -------
    numpy.ndarray
        (n_dof,) m.
    """
    mesh, p = model.mesh, model.order
    x = np.full(model.n_dof, np.nan)
    nodes = np.asarray(model.rail_elem_nodes)
    x0 = mesh.node_x[mesh.elem_nodes[:, 0]]
    x1 = mesh.node_x[mesh.elem_nodes[:, 1]]
    n_t = model.torsion_dofs_per_node
    for j in range(p + 1):
        node, xn = nodes[:, j], x0 + (j / p) * (x1 - x0)
        x[2 * node] = x[2 * node + 1] = xn
        for k in range(n_t):
            x[model.roll_dof(node) + k] = xn
    pattern = sp.csr_matrix(model.K, copy=True)
    pattern.data[:] = 1.0
    for _ in range(model.n_dof):
        known = np.isfinite(x)
        if known.all():
            break
        total = pattern @ np.where(known, x, 0.0)
        count = pattern @ known.astype(float)
        new = ~known & (count > 0)
        if not new.any():
            raise ValueError("FE plane: DOFs not connected to any rail (no position)")
        x[new] = total[new] / count[new]
    return x


def window_dofs(
    x_dof: np.ndarray,
    intervals: Sequence[tuple[float, float]],
    model_range: tuple[float, float],
    absorbing_length: float,
    eta_max: float,
) -> tuple[np.ndarray, np.ndarray]:
    """The DOFs of a window and the loss factor of its absorbing ends.

    Inside a cut end (not at the model's own end), over ``absorbing_length`` the loss factor
    grows quadratically from 0 to ``eta_max`` towards the cut, as the model's own absorbing
    ends (:mod:`~exudyn_turnout.fe.mesh`): eta = eta_max (d / a)^2, d the depth into the zone.

    Parameters
    ----------
    x_dof : numpy.ndarray
        m, the DOFs' positions (:func:`dof_positions`).
    intervals : sequence of (float, float)
        m, disjoint x ranges of the window, increasing.
    model_range : tuple of float
        m, the model's first and last x (an interval end there is not a cut).
    absorbing_length : float
        m, a.
    eta_max : float
        Loss factor at a cut (-).

    Returns
    -------
    dofs : numpy.ndarray
        Global DOF indices in the window, increasing.
    eta : numpy.ndarray
        Added loss factor of each (-).
    """
    inside = np.zeros(len(x_dof), dtype=bool)
    eta = np.zeros(len(x_dof))
    for lo, hi in intervals:
        here = (x_dof >= lo) & (x_dof <= hi)
        inside |= here
        depth = np.zeros(len(x_dof))
        if lo > model_range[0] + 1e-9:
            depth = np.maximum(depth, (lo + absorbing_length - x_dof) / absorbing_length)
        if hi < model_range[1] - 1e-9:
            depth = np.maximum(depth, (x_dof - hi + absorbing_length) / absorbing_length)
        eta[here] = eta_max * np.clip(depth[here], 0.0, 1.0) ** 2
    dofs = np.nonzero(inside)[0]
    return dofs, eta[dofs]


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
    """State, factorised effective matrix and influence columns of one FE plane.

    The plane is stepped on a window of its DOFs (all by default): the DOFs outside are held
    at rest (u = 0), the window's state vectors, matrices and influence columns are indexed
    by local DOF numbers (``local`` maps a global DOF to its local one, -1 outside).
    """

    def __init__(
        self,
        model: PlaneModel,
        D: sp.spmatrix,
        h: float,
        ga: GeneralizedAlpha,
        dofs: np.ndarray | None = None,
    ):
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
        dofs : numpy.ndarray, optional
            The first window (:meth:`set_window`, no absorbing ends); default all DOFs;
            empty: none until :meth:`set_window`.
        """
        self.model, self.h, self.ga = model, h, ga
        self._M, self._D = sp.csr_matrix(model.M), sp.csr_matrix(D)
        self._K = sp.csr_matrix(model.K)
        n = model.n_dof
        self.dofs = np.arange(n)
        self.local = np.arange(n)
        self.n = n
        self.u, self.v, self.qdd, self.a = (np.zeros(n) for _ in range(4))
        self.factor: CholeskyFactor | None = None
        self.set_window(self.dofs if dofs is None else dofs, None, 1.0)

    def set_window(self, dofs: np.ndarray, eta: np.ndarray | None, omega_ref: float) -> None:
        """Step the DOFs ``dofs`` from now on, carrying the state of those already stepped.

        DOFs entering the window start at rest (they were held at rest), DOFs leaving it are
        held at rest. The window's damping adds S K S / omega_ref, S = diag(sqrt(eta)),
        eta > 0 in the absorbing ends (:func:`window_dofs`): the structural loss eta K in
        its viscous equivalent, as the model's own, graded per DOF.

        Parameters
        ----------
        dofs : numpy.ndarray
            Global DOF indices, increasing.
        eta : numpy.ndarray or None
            Added loss factor per window DOF (-); None: none.
        omega_ref : float
            rad/s, reference circular frequency of the viscous equivalent.
        """
        ga, h = self.ga, self.h
        dofs = np.asarray(dofs, dtype=np.int64)
        local = np.full(self.model.n_dof, -1, dtype=np.int64)
        local[dofs] = np.arange(len(dofs))
        state = []
        for vec in (self.u, self.v, self.qdd, self.a):
            new = np.zeros(len(dofs))
            both = local[self.dofs] >= 0
            new[local[self.dofs[both]]] = vec[both]
            state.append(new)
        self.u, self.v, self.qdd, self.a = state
        self.dofs, self.local, self.n = dofs, local, len(dofs)
        whole = len(dofs) == self.model.n_dof
        pick = (lambda m: m) if whole else (lambda m: m[dofs][:, dofs])
        self.M, self.D, self.K = pick(self._M), pick(self._D), pick(self._K)
        if eta is not None and np.any(eta > 0):
            s = sp.diags(np.sqrt(np.asarray(eta, float) / omega_ref))
            self.D = (self.D + s @ self.K @ s).tocsr()
        A = self.M + ga.gamma_eff * h * self.D + ga.beta_eff * h * h * self.K
        self.factor = CholeskyFactor(A) if self.n else None
        self.u_hat, self.v_hat, self.qdd_star = (np.zeros(self.n) for _ in range(3))
        self._columns: dict = {}  #: key (see columns) -> A^-1 E

    def set_step(self, h: float) -> None:
        """Step on at ``h`` from now on: refactorise A = M + gamma' h D + beta' h^2 K of the
        window (its absorbing ends included) and drop the influence columns.

        The state (u, v, qdd and the algorithmic acceleration a) is carried over as it is:
        the generalized-alpha update of the next step takes the new h, as Exudyn's own does
        when its pieces step at another size (no restart).

        Parameters
        ----------
        h : float
            s, the new time step (> 0).
        """
        if not (math.isfinite(h) and h > 0):
            raise ValueError(f"FE plane: time step must be > 0, got {h!r}")
        if h == self.h:
            return
        ga = self.ga
        self.h = float(h)
        A = self.M + ga.gamma_eff * h * self.D + ga.beta_eff * h * h * self.K
        self.factor = CholeskyFactor(A) if self.n else None
        self._columns = {}

    def _factor(self) -> CholeskyFactor:
        if self.factor is None:
            raise RuntimeError("the FE plane has no window yet (FECoSimulation.place)")
        return self.factor

    def columns(
        self,
        dofs: np.ndarray,
        other: np.ndarray | None = None,
        factor: float = 0.0,
        key: object = None,
    ) -> np.ndarray:
        """A^-1 of the unit vectors of ``dofs`` (plus ``factor`` times those of ``other``).

        Parameters
        ----------
        dofs : numpy.ndarray
            (k,) local DOF indices.
        other : numpy.ndarray, optional
            (k,) DOFs whose unit vectors are added, times ``factor``, column by column
            (a rail node's lateral displacement and roll: the head's lateral motion).
        factor : float
            Weight of ``other``.
        key : hashable, optional
            The cache key of these columns (the caller's name for ``dofs``, ``other`` and
            ``factor``); default the three themselves.

        Returns
        -------
        numpy.ndarray
            (n, k), cached per key until :meth:`forget` or :meth:`set_window`.
        """
        if key is None:
            first = tuple(int(d) for d in dofs)
            second = tuple(int(d) for d in other) if other is not None else ()
            key = (first, second, float(factor))
        cols = self._columns.get(key)
        if cols is None:
            k = len(dofs)
            E = np.zeros((self.n, k))
            E[np.asarray(dofs), np.arange(k)] = 1.0
            if other is not None:
                E[np.asarray(other), np.arange(k)] += factor
            cols = self._columns[key] = self._factor().solve(E)
        return cols

    def forget(self, keep: set) -> None:
        """Drop the cached columns whose keys are not in ``keep``.

        Parameters
        ----------
        keep : set
            Keys (:meth:`columns`) still in use.
        """
        for key in [k for k in self._columns if k not in keep]:
            del self._columns[key]

    def solve(self, b: np.ndarray) -> np.ndarray:
        """A^-1 b on the window.

        Parameters
        ----------
        b : numpy.ndarray
            (n,) or (n, k).

        Returns
        -------
        numpy.ndarray
            Of the shape of b.
        """
        return self._factor().solve(b)

    def _constants(self) -> np.ndarray:
        ga = self.ga
        return np.array([self.h, ga.alpha_m, ga.alpha_f, ga.beta, ga.gamma])

    def predict(self) -> None:
        """u^, v^ and qdd* of the next step (no contact forces).

        u^ = u + h v + h^2 ((1/2 - beta) a + beta c), v^ = v + h ((1 - gamma) a + gamma c),
        c = (alpha_f qdd - alpha_m a) / (1 - alpha_m); qdd* = A^-1 (-D v^ - K u^). The
        vector updates are one compiled pass (the numbers of the NumPy expressions,
        operation by operation, 8x faster).
        """
        self.u_hat, self.v_hat = np.empty(self.n), np.empty(self.n)
        _free_motion(self._constants(), self.u, self.v, self.a, self.qdd, self.u_hat, self.v_hat)
        # SciPy's sparse products: a compiled fused -(D v^) - K u^ took twice as long
        self.qdd_star = self._factor().solve(-(self.D @ self.v_hat) - self.K @ self.u_hat)

    def complete(self, qdd_contact: np.ndarray) -> None:
        """Finish the step with the contact forces' part A^-1 G F of the acceleration.

        Parameters
        ----------
        qdd_contact : numpy.ndarray
            (n,) the acceleration the contact forces add.
        """
        qdd = self.qdd_star + qdd_contact
        _complete(self._constants(), self.u, self.v, self.a, self.qdd, qdd)
        self.qdd = qdd


@numba.njit(cache=True)
def _free_motion(c, u, v, a, qdd, u_hat, v_hat):  # pragma: no cover (compiled)
    """u^, v^ of :meth:`PlaneStepper.predict`, c = (h, alpha_m, alpha_f, beta, gamma)."""
    h, alpha_m, alpha_f, beta, gamma = c[0], c[1], c[2], c[3], c[4]
    for i in range(len(u)):
        carry = (alpha_f * qdd[i] - alpha_m * a[i]) / (1.0 - alpha_m)
        u_hat[i] = u[i] + h * v[i] + h * h * ((0.5 - beta) * a[i] + beta * carry)
        v_hat[i] = v[i] + h * ((1.0 - gamma) * a[i] + gamma * carry)


@numba.njit(cache=True)
def _complete(c, u, v, a, qdd_old, qdd):  # pragma: no cover (compiled)
    """u, v, a at the step's end, in place (:meth:`PlaneStepper.complete`)."""
    h, alpha_m, alpha_f, beta, gamma = c[0], c[1], c[2], c[3], c[4]
    for i in range(len(u)):
        a_new = ((1.0 - alpha_f) * qdd[i] + alpha_f * qdd_old[i] - alpha_m * a[i]) / (1.0 - alpha_m)
        u[i] = u[i] + h * v[i] + h * h * ((0.5 - beta) * a[i] + beta * a_new)
        v[i] = v[i] + h * ((1.0 - gamma) * a[i] + gamma * a_new)
        a[i] = a_new


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
