"""A wheelset passing over the FE turnout track in the time domain (vertical plane).

The FE reference for the passage forces (the paper's FE/MBS co-simulation, Figs 7, 8):
the same wheelset as :mod:`~exudyn_turnout.passage.corunning_track.wheelset` (vertical part:
wheelset heave z_w
and roll phi, sprung mass z_s on the primary suspension k_z, c_z at +-d) runs at constant
speed over the vertical FE model of :mod:`exudyn_turnout.fe` (Timoshenko rails of order
p on discrete pads, sleepers as beams on the ballast layer), with the same Hertz law
C_H delta^1.5 and the same route contact pairs and rail height profiles, so that a wheel
passes from one rail to another exactly where the co-running passage says.

Contact between nodes
---------------------
A contact point at x on FE rail r lies in one rail element (nodes x_1 < x_2, order p).
The rail's deflection there is w(x) = N(xi) . q_e with N the element's Lagrange shape
functions of order p on its p + 1 equally spaced nodes (the interpolation the element
uses for w, :func:`~exudyn_turnout.fe.timoshenko.lagrange_shape_functions`), and the
contact force F enters the rail as -N(xi) F on the same DOFs (consistent load vector).
With the wheelset DOFs the penetration of contact c is linear in the displacements::

    delta_c = g_c . u + h_c(x),   g_c = [N(xi) on the rail's w DOFs, -1 on z_w, -s b on phi]

(s = -1 right wheel, +1 left; h_c the route's rail height table); the contact's
generalised force is -g_c F_c, F_c = C_H max(delta_c, 0)^1.5.

Which rails: each route pair names a co-running slot (r1..r4); the FE rail under it at x
is ``layout.slot_rail(slot, x, route)``. Where one pair's table ends exactly where the next
pair of the same wheel starts (through route, crossing nose -> plain track at 51 m), the
point belongs to the earlier pair, so no contact is counted twice.

Time integration: HHT-alpha, one constant matrix, contacts by influence vectors
--------------------------------------------------------------------------------
Track and wheelset form one linear system M, D, K (~30 000 DOFs for the turnout with the
default 0.2 m quartic rail elements); the only nonlinearity is the few (<= 4) Hertz
contacts. The HHT-alpha scheme (Hilber, Hughes & Taylor 1977; gamma = 1/2 - alpha,
beta = (1 - alpha)^2 / 4)::

    M a_{n+1} + (1 + alpha) (D v_{n+1} + K u_{n+1}) - alpha (D v_n + K u_n)
        = (1 + alpha) f_{n+1} - alpha f_n

with the Newmark updates has the constant effective matrix
A = M + (1 + alpha) (gamma h D + beta h^2 K), factorised once (SuperLU). Each step solves
A a* = r once (everything but the new contact forces), then
a_{n+1} = a* - (1 + alpha) X F with the influence vectors X = A^-1 G of the active
contacts, and the contact forces F from Newton on the few unknowns::

    F_c = C_H max(d_c - (C F)_c, 0)^1.5,  d = G^T (u~ + beta h^2 a*) + h,
    C = (1 + alpha) beta h^2 G^T X

Influence vectors are A^-1 of the element's p + 1 unit w-vectors combined with N(xi);
they are computed when a contact enters a new element (every 0.2 m, ~70 steps at
100 km/h) and reused, so a step costs one sparse triangular solve and two sparse products.

Why this scheme: it is implicit and unconditionally stable, so the step is set by the
wheel/rail contact (~1 kHz) and not by the stiffest element (the rail's interior shear
modes, > 100 kHz, which an explicit scheme would have to resolve); the system matrix is
constant because the moving load only changes the load vector, so one factorisation
serves the whole run (modal superposition to 5 kHz would need thousands of modes of a
30 000-DOF model with non-proportional damping). HHT-alpha rather than the trapezoidal
rule: with alpha < 0 it damps the unresolved high-frequency content the moving load
excites at every node crossing (C0 shape functions) while staying second-order accurate;
alpha follows the co-running passage's ``spectral_radius`` (rho_inf = (1 + alpha) /
(1 - alpha); 0.8 gives alpha = -0.11), so both integrators dissipate alike.

Damping in the time domain
--------------------------
The FE model's structural loss G (rail loss factor 0.01, and the absorbing ends' loss
factor ramp to 1) is a frequency-domain quantity. It is replaced by the viscous D_G =
G / omega_ref (``loss_reference_hz``, default 1000 Hz): the same loss at f_ref, growing
in proportion to f above (more damping of the rail's high-frequency modes) and less below.
The ends stay absorbing for the waves that reach them (above the track's cut-on at
~100-300 Hz) and the low-frequency field of a wheel (deflection basin, decay length ~1 m)
never reaches them: the turnout model's ends are 12 m + the absorbing 12 m beyond the
passage's x range. The tests check that a plain-track passage is the same with twice the
extension.

Start in steady state
---------------------
The run starts from static equilibrium at x_start (K u = f with the Hertz contacts, the
sprung mass on its springs) with the convected velocity v du_static/dx (the static
solution carried along at speed v, by a second static solve 1 mm further) and the
acceleration from the equations of motion: a wheel on uniform track then starts in its
steady state and the force stays at the static load (tests: within 1%).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import asdict, dataclass, field, replace
from functools import cache
from typing import cast

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as sla

from exudyn_turnout.fe.layout import Layout, load_layout
from exudyn_turnout.fe.mesh import build_mesh
from exudyn_turnout.fe.model import PlaneModel, assemble
from exudyn_turnout.fe.timoshenko import lagrange_shape_functions
from exudyn_turnout.inputs.routes import WHEELS, ContactPair, Route, load_route
from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.inputs.vehicle import GRAVITY, Vehicle, load_vehicle
from exudyn_turnout.passage.common import lightest_rail_mass, max_time_step
from exudyn_turnout.passage.fe_track.options import FEPassageOptions
from exudyn_turnout.passage.results import (
    DEFAULT_SETTINGS,
    PLAUSIBLE,
    PassageError,
    PassageFailure,
    PassageResult,
    PassageSettings,
    check_plausible,
    passage_summary,
)

__all__ = [
    "FEPassageOptions",
    "FETrack",
    "ContactPoint",
    "build_fe_track",
    "contact_points",
    "solve_contacts",
    "static_state",
    "hht_parameters",
    "simulate_fe_passage",
]

#: m, positions closer than this are the same point (pair table ends, element ends).
_X_TOL = 1e-9
#: m, step of the finite difference giving the convected start velocity v du/dx.
_START_DX = 1e-3
#: m/N, compliance added to every contact in the contact solve (see :func:`solve_contacts`).
_CONTACT_EPSILON = 1e-16
#: SuperLU options: COLAMD ordering (fill ~1.5e6 for the ~30 000-DOF turnout, ~3.5 ms per solve).
_LU = dict(permc_spec="COLAMD")


@dataclass(frozen=True)
class _RailIndex:
    """Elements of one FE rail along x, for finding the element under a contact point."""

    x_left: np.ndarray  #: m, first x of each element, increasing
    x_right: np.ndarray  #: m, last x of each element
    elements: np.ndarray  #: element index (row of PlaneModel.rail_elem_nodes)


@dataclass(frozen=True)
class FETrack:
    """FE track (vertical plane) and wheelset as one linear system, SI units.

    DOFs: the FE model's (``model.n_dof``, track) then the wheelset heave z_w (m, up),
    roll phi (rad, positive lifting the left wheel) and the sprung mass heave z_s (m).
    """

    model: PlaneModel
    layout: Layout
    vehicle: Vehicle
    M: sp.csc_matrix  #: kg
    D: sp.csc_matrix  #: N s/m, track viscous damping + G / omega_ref + suspension
    K: sp.csc_matrix  #: N/m
    f_gravity: np.ndarray  #: N, weight of wheelset and sprung mass
    rails: Mapping[str, _RailIndex]
    timings: Mapping[str, float] = field(default_factory=dict)  #: s, build steps

    @property
    def n_track(self) -> int:
        """Number of track DOFs (the FE model's)."""
        return self.model.n_dof

    @property
    def n_dof(self) -> int:
        """Number of DOFs: track, then z_w, phi, z_s."""
        return self.model.n_dof + 3

    @property
    def i_zw(self) -> int:
        """Index of the wheelset heave z_w."""
        return self.model.n_dof

    @property
    def i_phi(self) -> int:
        """Index of the wheelset roll phi."""
        return self.model.n_dof + 1

    @property
    def i_zs(self) -> int:
        """Index of the sprung-mass heave z_s."""
        return self.model.n_dof + 2


@dataclass(frozen=True)
class ContactPoint:
    """One active wheel/rail pair at one position: where it acts in the FE model."""

    pair: ContactPair
    rail_id: str  #: FE rail under the pair's slot at x
    height: float  #: m, rail height of the route table at x
    element: int  #: rail element containing x
    dofs: np.ndarray  #: (p + 1,) w DOFs of the element's nodes
    shape: np.ndarray  #: (p + 1,) N(xi) at x

    @property
    def side(self) -> int:
        """+1 for the left wheel, -1 for the right."""
        return WHEELS[self.pair.wheel]


def hht_parameters(spectral_radius: float) -> tuple[float, float, float]:
    """HHT-alpha (alpha, beta, gamma) for a high-frequency spectral radius rho_inf in [0.5, 1].

    rho_inf = (1 + alpha) / (1 - alpha) (Hilber, Hughes & Taylor 1977), alpha in [-1/3, 0].

    Parameters
    ----------
    spectral_radius : float
        rho_inf in [0.5, 1].

    Returns
    -------
    tuple of float
        (alpha, beta, gamma).
    """
    if not 0.5 <= spectral_radius <= 1.0:
        raise PassageError(
            f"spectral radius must be in [0.5, 1] for HHT-alpha, got {spectral_radius:g}"
        )
    alpha = (spectral_radius - 1.0) / (spectral_radius + 1.0)
    return alpha, 0.25 * (1.0 - alpha) ** 2, 0.5 - alpha


def _vehicle_blocks(vehicle: Vehicle) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """M, D, K (3 x 3) and weight (3,) of (z_w, phi, z_s).

    The primary springs join the wheelset at +-d to the sprung point mass: elongation
    e_s = z_s - z_w - s d phi, energy k_z (z_s - z_w)^2 + k_z d^2 phi^2 (as the Exudyn
    model of :mod:`~exudyn_turnout.inputs.vehicle`: the point mass carries no roll, so the roll
    spring 2 k_z d^2 acts against a fixed direction).
    """
    d2 = vehicle.d**2
    shape = np.array([[2.0, 0.0, -2.0], [0.0, 2.0 * d2, 0.0], [-2.0, 0.0, 2.0]])
    M = np.diag([vehicle.m_w, vehicle.J_roll, vehicle.m_s])
    return (
        M,
        vehicle.c_z * shape,
        vehicle.k_z * shape,
        np.array([-vehicle.m_w * GRAVITY, 0.0, -vehicle.m_s * GRAVITY]),
    )


def _with_vehicle(A: sp.spmatrix, block: np.ndarray) -> sp.csc_matrix:
    return sp.block_diag([A, sp.csc_matrix(block)], format="csc")


def _rail_indices(model: PlaneModel) -> dict[str, _RailIndex]:
    mesh = model.mesh
    out = {}
    for rail_id, elems in mesh.rail_elems.items():
        x = mesh.node_x[mesh.elem_nodes[elems]]
        order = np.argsort(x[:, 0])
        out[rail_id] = _RailIndex(x[order, 0], x[order, 1], np.asarray(elems)[order])
    return out


def build_fe_track(
    turnout: Turnout,
    vehicle: Vehicle | None = None,
    layout: Layout | None = None,
    options: FEPassageOptions = FEPassageOptions(),
) -> FETrack:
    """Assemble the vertical FE model of the layout and couple the wheelset's DOFs to it.

    Parameters
    ----------
    turnout : Turnout
        Table 1 properties (and the ``[layout]`` section unless ``layout`` is given).
    vehicle : Vehicle, optional
        Default: the packaged Manchester benchmark wheelset.
    layout : Layout, optional
        Default :func:`~exudyn_turnout.fe.layout.load_layout` of the turnout; e.g.
        :func:`~exudyn_turnout.fe.layout.plain_track_layout` for checks.
    options : FEPassageOptions
        Mesh and solver options.

    Returns
    -------
    FETrack
        Track and wheelset matrices (M, D with the loss G / omega_ref, K), weight vector
        and the rails' element index; ``timings`` holds the assembly wall time.
    """
    vehicle = vehicle or load_vehicle()
    layout = layout or load_layout(turnout)
    t0 = time.perf_counter()
    model = assemble(turnout, build_mesh(turnout, layout, options.mesh), "vertical")
    Mv, Dv, Kv, fv = _vehicle_blocks(vehicle)
    D_track = model.D + model.G / (2.0 * math.pi * options.loss_reference_hz)
    f = np.concatenate([np.zeros(model.n_dof), fv])
    track = FETrack(
        model,
        layout,
        vehicle,
        _with_vehicle(model.M, Mv),
        _with_vehicle(D_track, Dv),
        _with_vehicle(model.K, Kv),
        f,
        _rail_indices(model),
        {"assemble_s": time.perf_counter() - t0},
    )
    return track


def _active(pair: ContactPair, pairs: Sequence[ContactPair], x: float) -> bool:
    """Tread contact of the pair at x.

    A table end shared with the next pair of the same wheel belongs to this pair.
    """
    if not pair.tread_active(x):
        return False
    if abs(x - pair.x[0]) > _X_TOL:
        return True
    return not any(
        other is not pair
        and other.wheel == pair.wheel
        and other.has_tread
        and abs(other.x[-1] - x) <= _X_TOL
        for other in pairs
    )


@cache
def _shape_coefficients(p: int) -> np.ndarray:
    """Monomial coefficients (p + 1, p + 1) of the order-p Lagrange shape functions:
    N(xi) = [1, xi, ..., xi^p] @ C, fitted to :func:`lagrange_shape_functions` (exact: both
    are polynomials of order p; ~100 times faster to evaluate per step)."""
    xi = np.linspace(0.0, 1.0, p + 1)
    return np.linalg.solve(
        np.vander(xi, p + 1, increasing=True), lagrange_shape_functions(p, xi)[0]
    )


def _shape(p: int, xi: float) -> np.ndarray:
    """N(xi) (p + 1,) of the order-p element."""
    return xi ** np.arange(p + 1) @ _shape_coefficients(p)


def _element_at(index: _RailIndex, x: float, rail_id: str) -> tuple[int, float]:
    """(element, xi in [0, 1]) of the rail element containing x."""
    k = int(np.searchsorted(index.x_left, x + _X_TOL, side="right")) - 1
    if k < 0 or x > index.x_right[k] + _X_TOL:
        raise PassageError(
            f"x = {x:g} m is not on FE rail {rail_id} "
            f"({index.x_left[0]:g} to {index.x_right[-1]:g} m)"
        )
    xi = (x - index.x_left[k]) / (index.x_right[k] - index.x_left[k])
    return int(index.elements[k]), min(max(xi, 0.0), 1.0)


def contact_points(track: FETrack, route: Route, x: float) -> tuple[ContactPoint, ...]:
    """The route's pairs in tread contact range at x, placed on the FE rails.

    Parameters
    ----------
    track : FETrack
        From :func:`build_fe_track`: the layout and the FE rails' elements.
    route : Route
        The contact pairs (slots, height tables) of the route.
    x : float
        m, wheelset position.

    Returns
    -------
    tuple of ContactPoint
        The active pairs, in ``route.pairs`` order, each with its rail element and N(xi).

    Raises
    ------
    PassageError
        A pair's slot has no FE rail at x (layout and route disagree).
    """
    out = []
    for pair in route.pairs:
        if not _active(pair, route.pairs, x):
            continue
        try:
            rail_id = track.layout.slot_rail(pair.rail, x, route.name)
        except ValueError as err:
            raise PassageError(f"{pair.name}: {err}") from None
        elem, xi = _element_at(track.rails[rail_id], x, rail_id)
        nodes = track.model.rail_elem_nodes[elem]
        shape = _shape(track.model.order, xi)
        out.append(ContactPoint(pair, rail_id, pair.height(x), elem, 2 * nodes, shape))
    return tuple(out)


def _gaps(track: FETrack, points: Sequence[ContactPoint], Y: np.ndarray) -> np.ndarray:
    """G^T Y: the penetration part g_c . y of each contact for vector(s) Y (n_dof[, m])."""
    b = track.vehicle.b
    rows = [
        point.shape @ Y[point.dofs] - Y[track.i_zw] - point.side * b * Y[track.i_phi]
        for point in points
    ]
    return np.array(rows) if rows else np.zeros((0,) + Y.shape[1:])


def _load(track: FETrack, points: Sequence[ContactPoint], F: np.ndarray) -> np.ndarray:
    """Generalised contact force -G F (n_dof,)."""
    f = np.zeros(track.n_dof)
    b = track.vehicle.b
    for point, Fc in zip(points, F):
        np.add.at(f, point.dofs, -point.shape * Fc)
        f[track.i_zw] += Fc
        f[track.i_phi] += point.side * b * Fc
    return f


def solve_contacts(
    d0: np.ndarray,
    C: np.ndarray,
    C_H: float,
    F0: np.ndarray | None = None,
    tolerance: float = 1e-3,
    max_iterations: int = 50,
    groups: Sequence[int] | None = None,
) -> np.ndarray:
    """Contact forces F (N) with F_c = C_H max(d0_c - (C F)_c, 0)^1.5 (Hertz, one-sided).

    Parameters
    ----------
    d0 : ndarray (n,)
        m, penetrations without the new contact forces.
    C : ndarray (n, n)
        m/N, compliance of the contacts (symmetric positive semi-definite).
    C_H : float
        N/m^1.5, Hertz constant.
    F0 : ndarray (n,), optional
        Start (e.g. the previous step's forces); default zero.
    tolerance : float
        N, largest force residual accepted (raised to the round-off level
        8 eps max|d0| max|C~^-1| if that is larger).
    max_iterations : int
        Newton iterations before giving up.
    groups : sequence of int (n,), optional
        Contacts with the same number act at one point (same wheel, same rail, same x:
        e.g. wing rail and crossing nose on one beam, or two route pairs at a table end):
        their rows of C are equal and they share one unknown, the point's penetration,
        with Hertz springs at their own offsets d0_c - d0_first in parallel. Default:
        every contact its own point.

    Returns
    -------
    ndarray (n,)
        C_H max(delta_c, 0)^1.5 at the solution.

    Raises
    ------
    ArithmeticError
        No convergence within ``max_iterations``.

    Notes
    -----
    The points' penetrations delta minimise the strictly convex, twice continuously
    differentiable energy::

        Pi(delta) = sum_c 2/5 C_H max(delta_g(c) + o_c, 0)^2.5
                    + 1/2 (delta - d0)^T C~^-1 (delta - d0)

    (Hertz springs at offsets o_c within their point g(c), plus the points' compliance
    C~ = C + epsilon I, epsilon = 1e-16 m/N = 1e-7 of the Hertz compliance at the static
    load, against round-off). Its gradient is the force residual and its Hessian
    diag(sum 1.5 C_H (delta + o)+^0.5) + C~^-1 is positive definite, so Newton with an
    Armijo backtracking line search converges from any start, also across the kink of
    loss of contact and when the load passes from one rail to another.
    """
    n = len(d0)
    if n == 0:
        return np.zeros(0)
    g = np.arange(n) if groups is None else np.unique(np.asarray(groups), return_inverse=True)[1]
    first = np.array([int(np.flatnonzero(g == k)[0]) for k in range(g.max() + 1)])
    offset, d0_p = d0 - d0[first][g], d0[first]
    C_inv = np.linalg.inv(
        0.5 * (C + C.T)[np.ix_(first, first)] + _CONTACT_EPSILON * np.eye(len(first))
    )
    tolerance = max(
        tolerance, 8.0 * np.finfo(float).eps * np.max(np.abs(d0_p)) * np.max(np.abs(C_inv))
    )
    F_start = (
        np.bincount(g, F0, len(first)) if F0 is not None and len(F0) == n else np.zeros(len(first))
    )
    delta = d0_p - C[np.ix_(first, first)] @ F_start
    for _ in range(max_iterations):
        pos = np.maximum(delta[g] + offset, 0.0)
        grad = np.bincount(g, C_H * pos * np.sqrt(pos), len(first)) - C_inv @ (d0_p - delta)
        if np.max(np.abs(grad)) <= tolerance:
            return C_H * pos * np.sqrt(pos)
        hess = C_inv + np.diag(np.bincount(g, 1.5 * C_H * np.sqrt(pos), len(first)))
        step = -np.linalg.solve(hess, grad)
        energy = lambda d: _contact_energy(d, d0_p, C_inv, C_H, g, offset)  # noqa: E731
        delta = delta + _armijo(energy, delta, step, grad @ step) * step
    raise ArithmeticError(
        f"contact forces did not converge in {max_iterations} Newton iterations "
        f"(residual {np.max(np.abs(grad)):.3g} N)"
    )


def _contact_energy(
    delta: np.ndarray,
    d0: np.ndarray,
    C_inv: np.ndarray,
    C_H: float,
    g: np.ndarray,
    offset: np.ndarray,
) -> float:
    pos = np.maximum(delta[g] + offset, 0.0)
    r = delta - d0
    return float(0.4 * C_H * np.sum(pos**2 * np.sqrt(pos)) + 0.5 * r @ C_inv @ r)


def _point_groups(points: Sequence[ContactPoint]) -> list[int]:
    """Group number of each contact: contacts of one wheel on one rail element share a point."""
    keys = [(p.pair.wheel, p.rail_id, p.element) for p in points]
    order = list(dict.fromkeys(keys))
    return [order.index(k) for k in keys]


def _armijo(
    energy: Callable[[np.ndarray], float], x: np.ndarray, step: np.ndarray, slope: float
) -> float:
    """Step length t (1, 1/2, ...) with energy(x + t step) <= energy(x) + 1e-4 t slope.

    A relative slack of 1e-12 lets the last Newton steps through, whose energy decrease
    is below the round-off of the energy itself.
    """
    e0, t = energy(x), 1.0
    while t > 1e-10 and energy(x + t * step) > e0 + 1e-4 * t * slope + 1e-12 * abs(e0):
        t *= 0.5
    return t


@dataclass(frozen=True)
class _Static:
    """Static equilibrium at one position."""

    u: np.ndarray  #: (n_dof,) displacements, track and vehicle
    F: np.ndarray  #: N, contact forces of ``points``
    points: tuple[ContactPoint, ...]


def _track_compliance(
    track: FETrack, K_lu, points: Sequence[ContactPoint]
) -> tuple[np.ndarray, np.ndarray]:
    """X = K_t^-1 B (rail parts of the contact vectors) and C = B^T X."""
    B = np.zeros((track.n_track, len(points)))
    for j, p in enumerate(points):
        np.add.at(B[:, j], p.dofs, p.shape)
    X = K_lu.solve(B) if points else B
    return X, np.array([[p.shape @ X[p.dofs, j] for j in range(len(points))] for p in points])


def static_state(
    track: FETrack,
    K_lu,
    points: Sequence[ContactPoint],
    tolerance: float = 1e-3,
    max_iterations: int = 100,
) -> _Static:
    """Static equilibrium with Hertz contacts: vehicle weight on the track.

    Unknowns: wheelset heave z_w and roll phi (Newton, 2 x 2), the contact forces for
    given (z_w, phi) by :func:`solve_contacts` on the track's static compliance
    C = B^T K^-1 B; then z_s = z_w - m_s g / (2 k_z) and the track u = -K^-1 B F.
    Equations: sum F = (m_w + m_s) g, b sum s F = 2 k_z d^2 phi.

    Parameters
    ----------
    track : FETrack
        From :func:`build_fe_track`: matrices, weight vector and wheelset.
    K_lu : SuperLU
        Factorisation of the track stiffness (``track.K`` without the vehicle DOFs).
    points : sequence of ContactPoint
        The contacts at the start position.
    tolerance : float
        N, force residual of the contact solution.
    max_iterations : int
        Newton iterations on (z_w, phi) before giving up.

    Returns
    -------
    _Static
        Displacements, contact points and forces of the static state.
    """
    vehicle = track.vehicle
    X, C = _track_compliance(track, K_lu, points)
    s = np.array([point.side for point in points], float)
    h = np.array([point.height for point in points])
    for wheel in ("left", "right"):
        if not any(point.pair.wheel == wheel for point in points):
            raise PassageError(f"no rail under the {wheel} wheel for the static equilibrium")
    W, k_roll = (vehicle.m_w + vehicle.m_s) * GRAVITY, 2.0 * vehicle.k_z * vehicle.d**2
    delta_0 = (0.5 * W / vehicle.contact.C_H) ** (2.0 / 3.0)
    q = np.array(
        [
            min(max(h[s == w]) for w in (-1.0, 1.0)) - 2.0 * delta_0 - 0.5 * W * np.max(np.diag(C)),
            0.0,
        ]
    )
    F = None
    for _ in range(max_iterations):
        d0 = h - q[0] - s * vehicle.b * q[1]
        F = solve_contacts(
            d0, C, vehicle.contact.C_H, F, 1e-6 * tolerance, groups=_point_groups(points)
        )
        R = np.array([F.sum() - W, vehicle.b * (s @ F) - k_roll * q[1]])
        if abs(R[0]) <= tolerance and abs(R[1]) <= tolerance * vehicle.b:
            u = np.concatenate(
                [-X @ F, [q[0], q[1], q[0] - vehicle.m_s * GRAVITY / (2.0 * vehicle.k_z)]]
            )
            return _Static(u, F, tuple(points))
        delta = np.maximum(d0 - C @ F, 0.0)
        k = 1.5 * vehicle.contact.C_H * np.sqrt(delta)
        dF_dd0 = np.linalg.solve(np.eye(len(F)) + k[:, None] * C, np.diag(k))
        dd0 = np.column_stack([-np.ones_like(s), -s * vehicle.b])
        J = np.array([np.ones_like(s), vehicle.b * s]) @ dF_dd0 @ dd0 - np.array(
            [[0.0, 0.0], [0.0, k_roll]]
        )
        q = q - np.linalg.solve(J, R)
    raise PassageFailure(
        f"static equilibrium not found in {max_iterations} iterations "
        f"(residual {R[0]:.3g} N, {R[1]:.3g} N m)"
    )


class _Integrator:
    """HHT-alpha steps of the track + wheelset system with moving Hertz contacts.

    Holds the factorised effective matrix A and the influence vectors A^-1 e of the rail
    elements currently under a wheel (see the module docstring).
    """

    def __init__(self, track: FETrack, h: float, spectral_radius: float):
        self.track, self.h = track, h
        self.alpha, self.beta, self.gamma = hht_parameters(spectral_radius)
        a = self.alpha
        t0 = time.perf_counter()
        A = track.M + (1.0 + a) * (self.gamma * h * track.D + self.beta * h * h * track.K)
        self.lu = sla.splu(A.tocsc(), **_LU)
        E = np.zeros((track.n_dof, 2))
        E[track.i_zw, 0] = E[track.i_phi, 1] = 1.0
        self.X_vehicle = self.lu.solve(E)
        self.timings = {
            "factorise_s": time.perf_counter() - t0,
            "solve_s": 0.0,
            "influence_s": 0.0,
            "products_s": 0.0,
            "contact_s": 0.0,
        }
        self._columns: dict[int, np.ndarray] = {}
        self._K, self._D = track.K.tocsr(), track.D.tocsr()  # CSR: faster products than CSC

    def _element_columns(self, point: ContactPoint) -> np.ndarray:
        cols = self._columns.get(point.element)
        if cols is None:
            t0 = time.perf_counter()
            E = np.zeros((self.track.n_dof, len(point.dofs)))
            E[point.dofs, np.arange(len(point.dofs))] = 1.0
            cols = self._columns[point.element] = self.lu.solve(E)
            self.timings["influence_s"] += time.perf_counter() - t0
        return cols

    def influence(self, points: Sequence[ContactPoint]) -> np.ndarray:
        """X = A^-1 G (n_dof, n_contacts); forgets elements no longer under a wheel."""
        b = self.track.vehicle.b
        X = (
            np.column_stack(
                [
                    self._element_columns(point) @ point.shape
                    - self.X_vehicle @ np.array([1.0, point.side * b])
                    for point in points
                ]
            )
            if points
            else np.zeros((self.track.n_dof, 0))
        )
        used = {point.element for point in points}
        for element in [element for element in self._columns if element not in used]:
            del self._columns[element]
        return X

    def step(
        self, state: _State, points: tuple[ContactPoint, ...], options: FEPassageOptions
    ) -> _State:
        """One step to the positions of ``points``.

        Raises ArithmeticError if the contact forces do not converge.
        """
        track, h, a, beta, gamma = self.track, self.h, self.alpha, self.beta, self.gamma
        u_p = state.u + h * state.v + h * h * (0.5 - beta) * state.a
        v_p = state.v + h * (1.0 - gamma) * state.a
        t0 = time.perf_counter()
        r = (
            track.f_gravity
            - a * state.f_contact
            - self._D @ ((1.0 + a) * v_p - a * state.v)
            - self._K @ ((1.0 + a) * u_p - a * state.u)
        )
        t1 = time.perf_counter()
        a_star = self.lu.solve(r)
        t2 = time.perf_counter()
        X = self.influence(points)
        t3 = time.perf_counter()
        c = (1.0 + a) * beta * h * h
        d0 = _gaps(track, points, u_p + beta * h * h * a_star) + np.array(
            [point.height for point in points]
        )
        F = solve_contacts(
            d0,
            c * _gaps(track, points, X),
            track.vehicle.contact.C_H,
            _previous_forces(state, points),
            options.contact_tolerance,
            options.max_contact_iterations,
            _point_groups(points),
        )
        acc = a_star - (1.0 + a) * (X @ F)
        new = _State(
            u_p + beta * h * h * acc, v_p + gamma * h * acc, acc, _load(track, points, F), points, F
        )
        timings = self.timings
        timings["products_s"] += t1 - t0
        timings["solve_s"] += t2 - t1
        timings["contact_s"] += time.perf_counter() - t3
        return new


@dataclass(frozen=True)
class _State:
    """State at the end of a step."""

    u: np.ndarray  #: displacements (m, rad)
    v: np.ndarray  #: velocities
    a: np.ndarray  #: accelerations
    f_contact: np.ndarray  #: generalised contact forces -G F (N)
    points: tuple[ContactPoint, ...]
    F: np.ndarray  #: N, contact forces of ``points``


def _previous_forces(state: _State, points: Sequence[ContactPoint]) -> np.ndarray:
    """Start for the contact Newton: last step's force of the same pair, else 0."""
    last = {id(p.pair): F for p, F in zip(state.points, state.F)}
    return np.array([last.get(id(p.pair), 0.0) for p in points])


def _check(
    settings: PassageSettings, turnout: Turnout, track: FETrack, own_layout: bool
) -> tuple[float, float]:
    """x range (m) of the run; PassageError naming the problem otherwise."""
    s, lay = settings, track.layout
    if not (math.isfinite(s.speed_kmh) and 0 < s.speed_kmh <= 400):
        raise PassageError(f"speed must be > 0 and <= 400 km/h, got {s.speed_kmh:g} km/h")
    lo, hi = (
        (max(turnout.x_min, lay.x_start), min(turnout.x_max, lay.x_end))
        if own_layout
        else (lay.x_start, lay.x_end)
    )
    x_a = lo if s.x_start is None else s.x_start
    x_b = hi if s.x_end is None else s.x_end
    if not (lo <= x_a < x_b <= hi):
        raise PassageError(
            f"x range {x_a:g}..{x_b:g} m must lie within {lo:g}..{hi:g} m "
            f"({'turnout and FE layout' if own_layout else 'FE layout'}) with x_start < x_end"
        )
    # the lightest rail of the turnout's (derived, two-layer) co-running set: the FE rail's
    # contact mass is of that order, and the limit must not depend on the run's x range
    m_rail = lightest_rail_mass(turnout, turnout.x_min, turnout.x_max, 2, "derived")
    h_max = max_time_step(track.vehicle, m_rail)
    if not (math.isfinite(s.time_step) and 0 < s.time_step <= h_max):
        raise PassageError(
            f"time step {s.time_step:g} s is out of range: use 0 < step <= {h_max:.2g} s "
            f"(10 steps per period of the wheel/rail contact resonance, lightest rail "
            f"{m_rail:.4g} kg)"
        )
    duration = (x_b - x_a) / s.v
    if s.output_step is not None and not (
        math.isfinite(s.output_step) and s.time_step <= s.output_step <= duration
    ):
        raise PassageError(
            f"output step {s.output_step:g} s must be >= the time step "
            f"({s.time_step:g} s) and <= the run's duration ({duration:.4g} s)"
        )
    return x_a, x_b


def _start(
    track: FETrack, route: Route, x: float, v: float, options: FEPassageOptions
) -> tuple[_State, float]:
    """Steady start at x: static state, convected velocity, acceleration from the equations.

    Returns the start state and the wall time (s) of the static solves.
    """
    t0 = time.perf_counter()
    K_lu = sla.splu(track.model.K.tocsc(), **_LU)
    st = static_state(track, K_lu, contact_points(track, route, x), options.contact_tolerance)
    ahead = static_state(
        track, K_lu, contact_points(track, route, x + _START_DX), options.contact_tolerance
    )
    vel = v * (ahead.u - st.u) / _START_DX
    vel[track.i_zs] = (
        0.0  # the sprung mass (~2.6 Hz) does not follow the sleeper-passing variation (46 Hz)
    )
    f_c = _load(track, st.points, st.F)
    acc = sla.splu(track.M.tocsc(), **_LU).solve(
        track.f_gravity + f_c - track.K @ st.u - track.D @ vel
    )
    return _State(st.u, vel, acc, f_c, st.points, st.F), time.perf_counter() - t0


def _slot_w(track: FETrack, route: Route, slot: str, x: float, u: np.ndarray) -> float:
    """Deflection (m) of the FE rail in ``slot`` at x, NaN where the slot has no rail."""
    try:
        rail_id = track.layout.slot_rail(slot, x, route.name)
    except ValueError:
        return math.nan
    elem, xi = _element_at(track.rails[rail_id], x, rail_id)
    return float(_shape(track.model.order, xi) @ u[2 * track.model.rail_elem_nodes[elem]])


class _Recorder:
    """Samples of the run: forces per route pair, wheelset motion, rail deflection per slot."""

    def __init__(self, track: FETrack, route: Route):
        self.track, self.route = track, route
        self.slots = sorted({p.rail for p in route.pairs})
        self.rows: list[list[float]] = []

    def add(self, t: float, x: float, state: _State) -> None:
        by_pair = {id(p.pair): F for p, F in zip(state.points, state.F)}
        u, tr = state.u, self.track
        self.rows.append(
            [t, x]
            + [by_pair.get(id(p), 0.0) for p in self.route.pairs]
            + [u[tr.i_zw], u[tr.i_phi], u[tr.i_zs]]
            + [_slot_w(tr, self.route, s, x, u) for s in self.slots]
        )

    def columns(self) -> dict[str, np.ndarray]:
        """Columns of :func:`~exudyn_turnout.passage.run.simulate_passage`.

        The lateral ones are NaN: the FE passage is vertical only.
        """
        data = np.array(self.rows)
        t, x, n = data[:, 0], data[:, 1], len(self.route.pairs)
        forces, vehicle, w = data[:, 2 : 2 + n], data[:, 2 + n : 5 + n], data[:, 5 + n :]
        nan = np.full_like(t, np.nan)
        cols: dict[str, np.ndarray] = {"t_s": t, "x_m": x}
        for wheel in ("right", "left"):
            cols[f"Fz_{wheel}_N"] = sum(
                (forces[:, i] for i, p in enumerate(self.route.pairs) if p.wheel == wheel),
                np.zeros_like(t),
            )
            cols[f"Fy_{wheel}_N"] = nan
        present = {s: np.isfinite(w[:, k]) for k, s in enumerate(self.slots)}
        for wheel, slot in dict.fromkeys((p.wheel, p.rail) for p in self.route.pairs):
            total = sum(
                (
                    forces[:, i]
                    for i, p in enumerate(self.route.pairs)
                    if (p.wheel, p.rail) == (wheel, slot)
                ),
                np.zeros_like(t),
            )
            cols[f"Fz_{wheel}_{slot}_N"] = np.where(present[slot], total, np.nan)
            cols[f"Fy_{wheel}_{slot}_N"] = nan
        cols.update(
            {
                "y_wheelset_m": nan,
                "z_wheelset_m": vehicle[:, 0],
                "roll_wheelset_rad": vehicle[:, 1],
                "yaw_wheelset_rad": nan,
            }
        )
        for k, slot in enumerate(self.slots):
            cols[f"y_rail_{slot}_m"], cols[f"z_rail_{slot}_m"] = nan, w[:, k]
        return cols


#: Default settings of :func:`simulate_fe_passage` (frozen: safe to share).


def _static_loads(state: _State) -> dict[str, float]:
    loads = {"left": 0.0, "right": 0.0}
    for point, force in zip(state.points, state.F):
        loads[point.pair.wheel] += float(force)
    return loads


def simulate_fe_passage(
    turnout: Turnout,
    settings: PassageSettings = DEFAULT_SETTINGS,
    vehicle: Vehicle | None = None,
    options: FEPassageOptions | None = None,
    *,
    layout: Layout | None = None,
    route: Route | None = None,
    track: FETrack | None = None,
    progress: Callable[[float, float], None] | None = None,
) -> PassageResult:
    """Run the wheelset over the vertical FE track of the turnout (see the module docstring).

    Parameters
    ----------
    turnout : Turnout
        Table 1 properties, ``[layout]``, routes and regions.
    settings : PassageSettings
        Route, speed, x range (default: the turnout's, within the FE layout), time step,
        output step and ``spectral_radius`` (rho_inf of HHT-alpha); ``layers`` and
        ``source`` do not apply (the FE model uses Table 1 directly).  The FE passage has
        the height-table contact only (vertical); its result records
        ``contact="height-table"`` whatever was asked, and an irregularity is refused.
    vehicle : Vehicle, optional
        Default: the packaged Manchester benchmark wheelset.
    options : FEPassageOptions, optional
        Mesh and solver options.
    layout : Layout, optional
        Another layout (e.g. :func:`~exudyn_turnout.fe.layout.plain_track_layout`); x may
        then be anywhere on it.
    route : Route, optional
        Contact pairs to use instead of the turnout's ``settings.route`` (e.g. a test dip);
        its slots must exist in the layout's ``slots[route.name]``.
    track : FETrack, optional
        A track from :func:`build_fe_track` to reuse (it carries layout and vehicle).
    progress : callable(fraction, x), optional
        Called about every 2 % of the run.

    Returns
    -------
    PassageResult
        The columns of :func:`~exudyn_turnout.passage.run.simulate_passage`; lateral columns
        (``Fy_*``, ``y_*``, ``yaw``) are NaN (empty in the CSV file): the FE passage is
        vertical only. ``z_rail_<slot>_m`` is the FE rail's deflection under the wheel.
        ``summary``: :func:`~exudyn_turnout.passage.results.passage_summary` plus ``model`` "FE",
        DOF count, options and the wall time of each part.

    Raises
    ------
    PassageError
        Bad settings (one line naming the problem) or a solver failure (time and position).
    """
    wall = time.perf_counter()
    if settings.irregularity is not None:
        raise PassageError("the FE passage has no track irregularities yet (height-table contact)")
    settings = replace(settings, contact="height-table")  # the only contact it has
    options = options or FEPassageOptions()
    own_layout = layout is None and track is None
    if track is None:
        track = build_fe_track(turnout, vehicle, layout, options)
    route = route or _load_route(turnout, settings.route)
    x_a, x_b = _check(settings, turnout, track, own_layout)
    columns, state0, timings = _run(track, route, settings, options, x_a, x_b, progress)
    loads = _static_loads(state0)
    check_plausible(columns, 0.5 * (loads["left"] + loads["right"]), "FE track")
    summary = passage_summary(
        columns, turnout, settings, _static_loads(state0), time.perf_counter() - wall
    )
    summary.update(_fe_summary(track, options, settings, timings))
    # passage_summary's "settings" is dataclasses.asdict(settings)
    all_settings = cast(dict[str, object], summary["settings"])
    summary["settings"] = {k: v for k, v in all_settings.items() if k not in _NOT_FE}
    return PassageResult(replace(settings, x_start=x_a, x_end=x_b), columns, summary, (x_a,))


#: PassageSettings fields that do not apply to the FE passage (left out of its summary).
_NOT_FE = ("layers", "source", "track_mechanism")


def _load_route(turnout: Turnout, name: str) -> Route:
    from exudyn_turnout.inputs.turnout import TurnoutFileError

    try:
        return load_route(turnout, name)
    except TurnoutFileError as err:
        raise PassageError(str(err)) from None


def _run(
    track: FETrack,
    route: Route,
    settings: PassageSettings,
    options: FEPassageOptions,
    x_a: float,
    x_b: float,
    progress: Callable | None,
) -> tuple[dict, _State, dict]:
    """Integrate from x_a to x_b; columns, the start state and timings."""
    v = settings.v
    n_steps = max(1, math.ceil((x_b - x_a) / v / settings.time_step - 1e-9))
    h = (x_b - x_a) / v / n_steps
    every = max(1, round((settings.output_step or h) / h))
    integrator = _Integrator(track, h, settings.spectral_radius)
    state, static_s = _start(track, route, x_a, v, options)
    state0, recorder, due = state, _Recorder(track, route), 0
    # per contact, against the whole weight (generous; the wheel check follows the run)
    f_limit = PLAUSIBLE["force_over_static"] * max(float(np.sum(state.F)), 1.0)
    recorder.add(0.0, x_a, state)
    t0 = time.perf_counter()
    for n in range(1, n_steps + 1):
        t, x = n * h, x_a + v * n * h if n < n_steps else x_b
        try:
            state = integrator.step(state, contact_points(track, route, x), options)
        except ArithmeticError as err:
            message = f"FE passage failed at t = {t:.5f} s, x = {x:.3f} m: {err}"
            raise PassageFailure(message) from None
        if not np.isfinite(state.F).all() or not np.isfinite(state.u[track.i_zw]):
            raise PassageFailure(
                f"FE passage diverged at t = {t:.5f} s, x = {x:.3f} m: reduce the time step"
            )
        if abs(state.u[track.i_zw]) > PLAUSIBLE["wheelset_m"] or (
            state.F.size and np.max(state.F) > f_limit
        ):
            what = (
                f"wheelset z {state.u[track.i_zw]:.4g} m"
                if abs(state.u[track.i_zw]) > PLAUSIBLE["wheelset_m"]
                else f"contact force {np.max(state.F):.4g} N"
            )
            raise PassageFailure(
                f"implausible run stopped at t = {t:.5f} s, x = {x:.3f} m (FE track): "
                f"{what} is beyond the physical limit"
            )
        if n % every == 0 or n == n_steps:
            recorder.add(t, x, state)
        if progress is not None and n >= due:
            due = n + max(1, n_steps // 50)
            progress(n / n_steps, x)
    timings = dict(
        track.timings,
        **integrator.timings,
        static_s=static_s,
        steps_s=time.perf_counter() - t0,
        n_steps=n_steps,
        h=h,
    )
    return recorder.columns(), state0, timings


def _fe_summary(
    track: FETrack,
    options: FEPassageOptions,
    settings: PassageSettings,
    timings: Mapping[str, float],
) -> dict[str, object]:
    alpha, beta, gamma = hht_parameters(settings.spectral_radius)
    return {
        "model": "FE",
        "layers": None,
        "source": "Table 1 (FE model)",
        "lateral": "not modelled: vertical FE plane only (Fy and y columns empty)",
        "n_dof": track.n_dof,
        "n_dof_track": track.n_track,
        "time_integration": (
            f"HHT-alpha, alpha = {alpha:.4f} (rho_inf {settings.spectral_radius:g}), "
            f"beta = {beta:.4f}, gamma = {gamma:.4f}, constant matrix factorised once"
        ),
        "time_step_s": float(timings["h"]),
        "fe_options": asdict(options.mesh),
        "loss_reference_hz": options.loss_reference_hz,
        "wall_time_parts_s": {k[:-2]: float(v) for k, v in timings.items() if k.endswith("_s")},
        "n_steps": int(timings["n_steps"]),
    }
