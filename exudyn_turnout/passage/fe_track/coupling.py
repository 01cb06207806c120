"""The FE turnout under the one vehicle and the one contact: exact one-step co-simulation.

The FE reference track (:mod:`exudyn_turnout.fe`: Timoshenko rails of order p on discrete
pads, sleepers on the ballast; the vertical plane and the lateral plane with rail torsion,
:mod:`~exudyn_turnout.fe.torsion`) carries the same Exudyn vehicle
(:func:`~exudyn_turnout.passage.vehicle.wheelset.add_vehicle`) through the same profile contact
element (:class:`~exudyn_turnout.passage.contact.profile.ProfileContactElement`, the numba
kernel of :mod:`~exudyn_turnout.wheel_rail.kernel`) as the co-running tracks: only the
track differs.

::

     Exudyn: vehicle (wheelset y, z, roll, yaw, spin; sprung mass y, z)
        |  ObjectGenericODE2 on the vehicle's coordinates, forceUserFunction:
        |  FEContactElement = ProfileContactElement with every rail body's (y, z)
        |  solved from the FE track's one-step response  r = r_free + C F(r)
        |
     ===+====================  FE track (scipy): vertical plane  M, D, K  (w, psi, sleepers)
        |                                     lateral plane   M, D, K  (v, psi, roll, warping)
      pre-step: predict r_free, r_t_free, C      post-step: complete the step with F

Why a co-simulation (measured, ``EXUDYN_NOTES.md``: a 35 000-DOF turnout): the whole FE
track as one sparse Exudyn object costs 26-39 ms a step, moving load markers 19-42 ms,
a scipy loop with one factorised matrix 2.1 ms; modal reduction needs 1 600-2 100 modes
below 2-3 kHz. So the FE track is stepped outside Exudyn with its constant effective
matrix factorised once, and the coupling is made exact instead of lagged.

Exact one-step coupling
-----------------------
Exudyn's implicit solver is the generalized-alpha method in the form of Arnold & Bruls
(2007) with the constants of :func:`generalized_alpha` (a test runs Exudyn and this module's
update side by side: equal to 1e-17). Stepping the linear FE track
M qdd + D v + K u = G F with the same constants, the equations hold at t_{n+1} and::

    u_{n+1} = u^ + beta' h^2 qdd_{n+1},  v_{n+1} = v^ + gamma' h qdd_{n+1},
    beta' = beta (1 - alpha_f) / (1 - alpha_m),  gamma' = gamma (1 - alpha_f) / (1 - alpha_m)

(u^, v^ from the step's start), so with A = M + gamma' h D + beta' h^2 K (constant,
factorised once per plane) qdd_{n+1} = qdd* + A^-1 G F, qdd* = A^-1 (-D v^ - K u^). The
rail coordinates r = G^T u of the contact bodies (the rail head's displacement at the
contact, (T1) of :mod:`~exudyn_turnout.fe.torsion`) are then linear in the unknown contact
forces F on the rails::

    r = r_free + C F,   r_t = r_t_free + (gamma' / (beta' h)) (r - r_free),
    r_free = G^T (u^ + beta' h^2 qdd*),   C = beta' h^2 G^T A^-1 G

Before each step (``PreStepUserFunction``, t_{n+1}) the track predicts r_free, r_t_free and
C; in every call of the force function (Newton iterations, Jacobian) the element solves
r = r_free + C F(q_vehicle, r, r_t(r)) for r by Newton (a 2m x 2m system, m rail bodies in
reach, the Jacobian of F by finite differences once a step) and returns the forces on the
vehicle; after the step (``PostStepUserFunction``) the converged forces complete the FE
step. This is the monolithic solution of the coupled equations, not an approximation:
``EXUDYN_NOTES.md`` measured 0.003-0.007 N against a monolithic run; the tests compare the
co-simulation's static state with the FE's static receptance.

Where the rail is touched: every rail body of the route (stock rail, blade, wing rail,
nose, check rail...) has its own (y, z) coordinates in the element, so one element serves
the whole run (no zones: the FE track is the whole turnout). A body in reach of the wheelset
(its table's x range contains x) is coupled to the FE rail of its co-running slot at x
(:meth:`~exudyn_turnout.fe.layout.Layout.slot_rail`), at the wheelset's x, at the rail
top (height above the shear centre from the torsion section) and on the rail's centre line
(the lateral offset of the contact point, a few cm, and its roll moment from the vertical
force are left out; the lateral force's roll moment about the shear centre is in).

Damping in the time domain: the structural loss
G becomes the viscous G / omega_ref (``loss_reference_hz``).

Start: the static equilibrium of vehicle and FE track (Exudyn's static solver with the
element coupled to the FE's static compliance G^T K^-1 G), the FE field carried at speed
(u_t = v du/dx from the static field 1 mm ahead under the same forces) and the FE
accelerations from its equations of motion (Exudyn computes the vehicle's).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from exudyn_turnout.fe.rail_head import RailHeadPoint, rail_head_point
from exudyn_turnout.passage.fe_track.options import FEPassageOptions
from exudyn_turnout.passage.fe_track.planes import (
    CholeskyFactor,
    FETrackPlanes,
    PlaneStepper,
    dof_positions,
    generalized_alpha,
    lagrange_weights,
    window_dofs,
)

__all__ = [
    "COUPLING_TARGET",
    "COUPLING_TOLERANCE",
    "COUPLING_STALL_TOLERANCE",
    "FECoSimulation",
    "FEContactElement",
    "run_progress",
]

#: m, the coupling solve iterates until its residual (of the rail coordinates) is below this
#: or stops falling (the round-off of C F, ~1e-11 m at a 125 kN load): the vehicle's Newton
#: differentiates the result with steps of ~1e-9 m, so it must be smooth far below that.
COUPLING_TARGET = 1e-13
#: m, the largest residual accepted where it stops falling: 0.15 N of Hertz force
#: (k_H ~ 1.5e9 N/m), below the vehicle's Newton tolerance (1 N).
COUPLING_TOLERANCE = 1e-10
#: m, the largest residual accepted where the Newton stalls from both starts on a kink of the
#: contact forces (the creep table is piecewise multilinear: C0): 0.5 um, 1 % of a 50 um
#: Hertz approach, ~0.75 kN of Hertz force at k_H ~ 1.5e9 N/m in the worst case; each such
#: step is counted in the summary's ``coupling_stalls`` and warned about at the end
COUPLING_STALL_TOLERANCE = 5e-7
#: m, finite-difference step of the coupling Jacobian (Hertz deflections are ~50 um).
_FD_STEP = 1e-9
#: Newton iterations of the coupling solve before giving up.
_MAX_ITERATIONS = 50
#: Step fractions of the coupling Newton's backtracking.
_DAMPING = (1.0, 0.5, 0.25, 0.125, 0.0625, 1.0 / 32, 1.0 / 128, 1.0 / 512)
#: m, a body's FE rail is looked up this far inside the body's x range at its ends.
_SLOT_INSET = 1e-6
#: m, the FE field 1 mm ahead gives the convected start velocity v du/dx.
_START_DX = 1e-3


@dataclass(frozen=True)
class _Coupled:
    """The rail bodies in reach at one position and the FE points they act on."""

    bodies: tuple  #: indices of the element's bodies in reach
    points: tuple  #: RailHeadPoint per body
    index: np.ndarray  #: element coordinates (y, z per body) of the coupled rail coordinates
    cells: tuple = ()  #: per point, its FE rail element (rail id, index): the caches' key


class FECoSimulation:
    """The FE track's side of the co-simulation: state, prediction, completion.

    Parameters
    ----------
    planes : FETrackPlanes
        From :func:`build_fe_planes`.
    route : str
        Route name (slot table of the layout).
    h : float
        s, time step (the Exudyn solver's).
    spectral_radius : float
        rho_inf of Exudyn's generalized-alpha solver.
    window : FEPassageOptions, optional
        Its ``window_*`` fields: step only a window of the FE track around the wheelsets,
        moved with them (module docstring); default: the whole model.
    """

    def __init__(
        self,
        planes: FETrackPlanes,
        route: str,
        h: float,
        spectral_radius: float,
        window: FEPassageOptions | None = None,
    ):
        t0 = time.perf_counter()
        self.planes, self.route, self.h = planes, route, float(h)
        self.ga = generalized_alpha(spectral_radius)
        self.window = window if window is not None and window.window_length else None
        self._omega_ref = 2.0 * math.pi * (window or FEPassageOptions()).loss_reference_hz
        self._dof_x: tuple | None = None  #: (lateral, vertical) DOF positions, m
        self._anchors: np.ndarray | None = None  #: m, wheelset x at the window's last cut
        self.window_cuts = 0  #: times the window was cut
        self.window_dofs: list[int] = []  #: DOFs of both planes at each cut
        mesh = planes.vertical.mesh
        self._model_range = (mesh.x_min, mesh.x_max)
        first = None if self.window is None else np.zeros(0, dtype=np.int64)  # see place()
        self.vertical = PlaneStepper(planes.vertical, planes.D_vertical, self.h, self.ga, first)
        self.lateral = PlaneStepper(planes.lateral, planes.D_lateral, self.h, self.ga, first)
        self.t = 0.0  #: s, time of the current state
        self.t_next = math.nan  #: s, time of the predicted step (nan: none predicted)
        self.static = False  #: True: couple to the static compliance (static solve)
        #: counts the changes of what the elements' rail coordinates obey (a prediction, a
        #: completed step, a new state): an element's solve is reused while it stands
        self.revision = 0
        self._predicted: dict[int, tuple] = {}
        self._static_lu: tuple | None = None
        self._static: dict[int, tuple] = {}
        self._static_forces: dict[int, np.ndarray] = {}
        self._grids: dict[str, tuple] = {}
        #: per window, (rail id, element index) -> the element's local DOFs (w, v, roll)
        self._cells: dict[tuple, tuple] = {}
        #: per window, (cell j, cell k) -> (lateral, vertical) one-step compliance blocks
        #: between the nodes of two cells (the rows of j of A^-1 G_k)
        self._blocks: dict[tuple, tuple] = {}
        self.timings = {"factorise_s": time.perf_counter() - t0, "predict_s": 0.0}
        self.timings.update({"complete_s": 0.0, "coupling_s": 0.0, "window_s": 0.0})
        #: coupling solves accepted at a stall (COUPLING_STALL_TOLERANCE): count, largest m
        self.stalls: list = [0, 0.0]

    # --- the window ---------------------------------------------------------------------

    def place(self, x_wheelsets: Sequence[float]) -> bool:
        """Cut the window anew if a wheelset has moved ``window_shift`` since the last cut.

        The window holds, about each wheelset at x_i, the track from x_i - L/2 to
        x_i + L/2 + s (L ``window_length``, s ``window_shift``): until it is cut again every
        wheelset has at least L/2 of track behind and ahead of it. Overlapping ranges merge.

        Parameters
        ----------
        x_wheelsets : sequence of float
            m, the wheelsets' positions on the FE track.

        Returns
        -------
        bool
            True if the window was cut (the influence columns and predictions are void).
        """
        if self.window is None:
            return False
        xs = np.sort(np.asarray(x_wheelsets, float))
        shift = self.window.window_shift
        if (
            self._anchors is not None
            and len(self._anchors) == len(xs)
            and np.all(xs - self._anchors <= shift + 1e-9)
            and np.all(xs >= self._anchors - 1e-9)
        ):
            return False
        t0 = time.perf_counter()
        if self._dof_x is None:
            self._dof_x = (dof_positions(self.planes.lateral), dof_positions(self.planes.vertical))
        half = 0.5 * float(self.window.window_length or 0.0)
        intervals: list[list[float]] = []
        for x in xs:
            lo = max(x - half, self._model_range[0])
            hi = min(x + half + shift, self._model_range[1])
            if intervals and lo <= intervals[-1][1]:
                intervals[-1][1] = max(intervals[-1][1], hi)
            else:
                intervals.append([lo, hi])
        ranges = [(lo, hi) for lo, hi in intervals]
        sizes = []
        for plane, x_dof in zip((self.lateral, self.vertical), self._dof_x):
            dofs, eta = window_dofs(
                x_dof,
                ranges,
                self._model_range,
                self.window.window_absorbing_length,
                self.window.window_eta_max,
            )
            plane.set_window(dofs, eta, self._omega_ref)
            sizes.append(len(dofs))
        self._anchors = xs
        self.revision += 1
        self._static_lu = None
        self._cells, self._blocks = {}, {}
        self._predicted = {}
        self.window_cuts += 1
        self.window_dofs.append(sum(sizes))
        self.timings["window_s"] += time.perf_counter() - t0
        return True

    # --- the step size ------------------------------------------------------------------

    def set_step(self, h: float) -> None:
        """Step on at ``h`` (a loaded check rail's finer step, or back to the run's).

        Both planes refactorise their step matrix for the new h (:meth:`PlaneStepper.set_step
        <exudyn_turnout.passage.fe_track.planes.PlaneStepper.set_step>`); the one-step
        compliance blocks and any prediction are void. The state is carried over: the
        Exudyn solver steps its next piece at the same h without a restart
        (:func:`~exudyn_turnout.passage.fe_track.common.solve_in_pieces`).

        Parameters
        ----------
        h : float
            s.
        """
        if h == self.h:
            return
        t0 = time.perf_counter()
        self.vertical.set_step(h)
        self.lateral.set_step(h)
        self.h = float(h)
        self._blocks = {}
        self._predicted = {}
        self.t_next = math.nan
        self.revision += 1
        self.timings["factorise_s"] += time.perf_counter() - t0

    # --- where the wheels touch ---------------------------------------------------------

    def points(self, element, x: float, x_fe: float | None = None) -> _Coupled:
        """The element's rail bodies in reach at x and their FE contact points.

        Parameters
        ----------
        element : ProfileContactElement
            With one (y, z) coordinate pair per rail body.
        x : float
            m, the position of the contact tables (which bodies are in reach).
        x_fe : float, optional
            m, the position on the FE track (default x). It differs for a wheelset of a
            long vehicle beyond the turnout's ends, whose contact is the plain rail's at
            the end and whose FE point lies on the model's plain-track extension (its slot's
            FE rail at the layout's end, continued).

        Returns
        -------
        _Coupled

        Raises
        ------
        ValueError
            A body in reach has no FE rail in its slot at x.
        """
        bounds, layout = element.tables.bounds, self.planes.layout
        x_fe = x if x_fe is None else x_fe
        x_slot = min(max(x_fe, layout.x_start), layout.x_end)
        bodies, points, index, cells = [], [], [], []
        for k, body in enumerate(element.bodies):
            lo, hi = bounds[k, 2], bounds[k, 3]
            if not lo - 1e-9 <= x <= hi + 1e-9:
                continue
            # the slot's FE rail inside the body's own range: at its ends (x0 + v t carries
            # round-off, slot ranges are half-open) the rail it has just inside
            inside = min(max(x_slot, lo + _SLOT_INSET), hi - _SLOT_INSET)
            try:
                rail_id = layout.slot_rail(body.rail, inside, self.route)
            except ValueError as err:
                raise ValueError(f"rail body '{body.name}' at x = {x:.3f} m: {err}") from None
            point, cell = self._point(rail_id, x_fe)
            bodies.append(k)
            points.append(point)
            cells.append(cell)
            index += [body.i_y, body.i_z]
        return _Coupled(tuple(bodies), tuple(points), np.array(index, dtype=np.int64), tuple(cells))

    def _point(self, rail_id: str, x: float) -> tuple[RailHeadPoint, tuple]:
        """:func:`~exudyn_turnout.fe.rail_head.rail_head_point` at the rail top, fast, and
        its cell (rail id, element index).

        The rails' element bounds are gathered once, an element's window DOFs once per
        window, and the shape functions evaluated by scalar products (the step's hot path;
        the same values, tested).
        """
        grid = self._grids.get(rail_id)
        if grid is not None and not grid[1][0] - 1e-9 <= x <= grid[2][-1] + 1e-9:
            raise ValueError(
                f"x = {x:.3f} m is beyond the FE model's rail {rail_id} "
                f"({grid[1][0]:g} to {grid[2][-1]:g} m): lengthen FEOptions.extension"
            )
        if grid is None:
            ref = rail_head_point(self.planes.vertical, self.planes.lateral, rail_id, x)
            mesh = self.planes.vertical.mesh
            elements = np.asarray(mesh.rail_elems[rail_id])
            x0 = mesh.node_x[mesh.elem_nodes[elements, 0]]
            x1 = mesh.node_x[mesh.elem_nodes[elements, 1]]
            grid = self._grids[rail_id] = (elements, x0, x1, ref.z)
        elements, x0, x1, z = grid
        k = int(np.searchsorted(x0, x + 1e-9, side="right")) - 1
        k = min(max(k, 0), len(elements) - 1)
        xi = min(max((x - x0[k]) / (x1[k] - x0[k]), 0.0), 1.0)
        cell = (rail_id, k)
        dofs = self._cells.get(cell)
        if dofs is None:
            nodes = self.planes.vertical.rail_elem_nodes[elements[k]]
            lateral = self.planes.lateral
            w_dofs = self.vertical.local[2 * nodes]
            v_dofs = self.lateral.local[2 * nodes]
            roll = (
                self.lateral.local[lateral.roll_dof(nodes)] if lateral.torsion is not None else None
            )
            if np.any(w_dofs < 0) or np.any(v_dofs < 0) or (roll is not None and np.any(roll < 0)):
                raise ValueError(f"x = {x:.3f} m on rail {rail_id} is outside the FE window")
            dofs = self._cells[cell] = (w_dofs, v_dofs, roll)
        w_dofs, v_dofs, roll = dofs
        point = RailHeadPoint(
            rail_id,
            float(x),
            0.0,
            float(z),
            lagrange_weights(self.planes.vertical.order, xi),
            w_dofs,
            v_dofs,
            roll,
            self.vertical.n,
            self.lateral.n,
        )
        return point, cell

    def _cell_columns(self, point: RailHeadPoint, cell: tuple) -> tuple[np.ndarray, np.ndarray]:
        """A^-1 of the unit loads on a cell's nodes: lateral (the head's lateral load: v and,
        with torsion, -z times the roll, (T1, T2)) and vertical, (n, p + 1) each."""
        lateral = self.lateral.columns(point.v_dofs, point.roll_dofs, -point.z, key=cell)
        return lateral, self.vertical.columns(point.w_dofs, key=cell)

    def _block(self, p_j: RailHeadPoint, cell_j: tuple, cell_k: tuple, columns: tuple) -> tuple:
        """The rows of point j's head displacements of A^-1 G_k (lateral, vertical), cached."""
        block = self._blocks.get((cell_j, cell_k))
        if block is None:
            lat, ver = columns
            rows = lat[p_j.v_dofs]
            if p_j.roll_dofs is not None:
                rows = rows - p_j.z * lat[p_j.roll_dofs]
            block = self._blocks[(cell_j, cell_k)] = (rows, ver[p_j.w_dofs])
        return block

    def _influence(self, point: RailHeadPoint) -> tuple[np.ndarray, np.ndarray]:
        """A^-1 g of a point's lateral and vertical unit loads (lateral, vertical plane)."""
        N = point.weights
        x_z = self.vertical.columns(point.w_dofs) @ N
        # the head's lateral unit load: v and, with torsion, -z times the roll (T1, T2)
        x_y = self.lateral.columns(point.v_dofs, point.roll_dofs, -point.z) @ N
        return x_y, x_z

    @staticmethod
    def _lateral_at(point: RailHeadPoint, q: np.ndarray) -> float:
        value = point.weights @ q[point.v_dofs]
        if point.roll_dofs is not None:
            value -= point.z * (point.weights @ q[point.roll_dofs])
        return float(value)

    def _gather(self, coupled: _Coupled, q_lat: np.ndarray, q_ver: np.ndarray) -> np.ndarray:
        """G^T q: (y, z) per body of the lateral and vertical plane vectors."""
        out = np.empty(2 * len(coupled.points))
        for j, p in enumerate(coupled.points):
            out[2 * j] = self._lateral_at(p, q_lat)
            out[2 * j + 1] = p.weights @ q_ver[p.w_dofs]
        return out

    def _compliance(self, coupled: _Coupled) -> tuple[np.ndarray, list]:
        """G^T A^-1 G (2m x 2m) and the column blocks A^-1 G of every point's cell.

        Built from the cached blocks of :meth:`_block`: per pair of points two small
        products, no vector of the window's length.
        """
        m = len(coupled.points)
        C = np.zeros((2 * m, 2 * m))
        columns = [self._cell_columns(p, c) for p, c in zip(coupled.points, coupled.cells)]
        for k, (p_k, cell_k) in enumerate(zip(coupled.points, coupled.cells)):
            for j, (p_j, cell_j) in enumerate(zip(coupled.points, coupled.cells)):
                lat, ver = self._block(p_j, cell_j, cell_k, columns[k])
                C[2 * j, 2 * k] = p_j.weights @ (lat @ p_k.weights)
                C[2 * j + 1, 2 * k + 1] = p_j.weights @ (ver @ p_k.weights)
        return C, columns

    # --- the step -----------------------------------------------------------------------

    def predict(self, t_next: float, elements: Sequence) -> None:
        """Prepare the step to t_next: r_free, r_t_free and C of every element's bodies.

        Parameters
        ----------
        t_next : float
            s, time at the end of the step.
        elements : sequence of FEContactElement
            The elements coupled to this track.
        """
        self.place([el.positions(t_next)[1] for el in elements])
        t0 = time.perf_counter()
        self.lateral.predict()
        self.vertical.predict()
        h, ga = self.h, self.ga
        bh2 = ga.beta_eff * h * h
        keep: set = set()
        self._predicted = {}
        u_lat = self.lateral.u_hat + bh2 * self.lateral.qdd_star
        u_ver = self.vertical.u_hat + bh2 * self.vertical.qdd_star
        v_lat = self.lateral.v_hat + ga.gamma_eff * h * self.lateral.qdd_star
        v_ver = self.vertical.v_hat + ga.gamma_eff * h * self.vertical.qdd_star
        for el in elements:
            coupled = self.points(el.element, *el.positions(t_next))
            C, columns = self._compliance(coupled)
            r_free = self._gather(coupled, u_lat, u_ver)
            r_t_free = self._gather(coupled, v_lat, v_ver)
            self._predicted[id(el)] = (coupled, r_free, r_t_free, bh2 * C, columns)
            keep.update(coupled.cells)
        if len(self._blocks) > 4 * len(keep) ** 2:  # blocks of cells left behind
            self._blocks = {k: b for k, b in self._blocks.items() if k[0] in keep and k[1] in keep}
        self.vertical.forget(keep)
        self.lateral.forget(keep)
        self.t_next = float(t_next)
        self.revision += 1
        self.timings["predict_s"] += time.perf_counter() - t0

    def coupling(self, element, t: float) -> tuple:
        """What the element's rail coordinates obey at time t.

        Parameters
        ----------
        element : FEContactElement
        t : float
            s.

        Returns
        -------
        tuple
            (coupled, r_free, r_t_free, C, c_v): r = r_free + C F,
            r_t = r_t_free + c_v (r - r_free); C = 0 at the current state's time (the rails
            are where the FE state says).
        """
        x, x_fe = element.positions(t)
        if self.static:
            coupled, blocks = self._static[id(element)]
            r_free = np.zeros(len(coupled.index))
            for other, C_ij in blocks.items():
                if other != id(element):
                    r_free += C_ij @ self._static_forces[other]
            return coupled, r_free, np.zeros_like(r_free), blocks[id(element)], 0.0
        if t == self.t_next and id(element) in self._predicted:
            coupled, r_free, r_t_free, C, _ = self._predicted[id(element)]
            return coupled, r_free, r_t_free, C, self.ga.gamma_eff / (self.ga.beta_eff * self.h)
        coupled = self.points(element.element, x, x_fe)
        r = self._gather(coupled, self.lateral.u, self.vertical.u)
        r_t = self._gather(coupled, self.lateral.v, self.vertical.v)
        return coupled, r, r_t, np.zeros((len(r), len(r))), 0.0

    def complete(self, forces: Sequence[tuple[object, np.ndarray]]) -> None:
        """Finish the predicted step with the converged forces on the rail coordinates.

        Parameters
        ----------
        forces : sequence of (FEContactElement, numpy.ndarray)
            Per element, the forces on its coupled rail coordinates (y, z per body, N).
        """
        t0 = time.perf_counter()
        # A^-1 G F by one solve per plane: cheaper than the sum of the points' influence
        # columns (a window's length times p + 1 per point, memory bound), equal to round-off
        g_ver = np.zeros(self.vertical.n)
        g_lat = np.zeros(self.lateral.n)
        for el, F in forces:
            coupled = self._predicted[id(el)][0]
            for k, p in enumerate(coupled.points):
                g_lat[p.v_dofs] += F[2 * k] * p.weights
                if p.roll_dofs is not None:  # the head's lateral load (T1, T2)
                    g_lat[p.roll_dofs] -= p.z * F[2 * k] * p.weights
                g_ver[p.w_dofs] += F[2 * k + 1] * p.weights
        self.vertical.complete(self.vertical.solve(g_ver))
        self.lateral.complete(self.lateral.solve(g_lat))
        self.t, self.t_next = self.t_next, math.nan
        self.revision += 1
        self.timings["complete_s"] += time.perf_counter() - t0

    # --- static state and start ---------------------------------------------------------

    def _static_factors(self) -> tuple:
        if self._static_lu is None:
            self._static_lu = (CholeskyFactor(self.lateral.K), CholeskyFactor(self.vertical.K))
        return self._static_lu

    def _static_loads(self, coupled: _Coupled, F: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        f_lat = np.zeros(self.lateral.n)
        f_ver = np.zeros(self.vertical.n)
        for k, p in enumerate(coupled.points):
            fv, fl = p.loads(F[2 * k], F[2 * k + 1])
            f_lat += fl
            f_ver += fv
        return f_lat, f_ver

    def _static_field(self, coupled: _Coupled, F: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        lu_lat, lu_ver = self._static_factors()
        f_lat, f_ver = self._static_loads(coupled, F)
        return lu_lat.solve(f_lat), lu_ver.solve(f_ver)

    def _loads_sum(self, coupled: Sequence[_Coupled], forces: Sequence[np.ndarray]) -> tuple:
        """Load vectors (lateral, vertical) of several elements' forces together."""
        f_lat = np.zeros(self.lateral.n)
        f_ver = np.zeros(self.vertical.n)
        for c, F in zip(coupled, forces):
            fl, fv = self._static_loads(c, F)
            f_lat += fl
            f_ver += fv
        return f_lat, f_ver

    def _static_sum(self, coupled: Sequence[_Coupled], forces: Sequence[np.ndarray]) -> tuple:
        """Static fields (lateral, vertical) of several elements' forces together."""
        lu_lat, lu_ver = self._static_factors()
        f_lat, f_ver = self._loads_sum(coupled, forces)
        return lu_lat.solve(f_lat), lu_ver.solve(f_ver)

    def begin_static(self, elements: Sequence) -> None:
        """Couple the elements to the FE's static compliance (for Exudyn's static solve).

        Every element's rail coordinates obey r_i = sum_j C_ij F_j, C_ij = G_i^T K^-1 G_j
        (the wheelsets of a bogie deflect each other's rails); an element solves for its own
        F_i with the others' latest forces (:meth:`report_static`) held.

        Parameters
        ----------
        elements : sequence of FEContactElement
            At their positions at t = 0 (the static solve does not move them).
        """
        self.place([el.positions(0.0)[1] for el in elements])
        coupled = [self.points(el.element, *el.positions(0.0)) for el in elements]
        fields = []
        for c in coupled:
            columns = []
            for k in range(len(c.points)):
                for j in (0, 1):
                    F = np.zeros(2 * len(c.points))
                    F[2 * k + j] = 1.0
                    columns.append(self._static_field(c, F))
            fields.append(columns)
        self._static = {}
        self._static_forces = {}
        for el, c in zip(elements, coupled):
            blocks = {}
            for other, c_other, columns in zip(elements, coupled, fields):
                C = np.zeros((len(c.index), len(c_other.index)))
                for col, (u_lat, u_ver) in enumerate(columns):
                    C[:, col] = self._gather(c, u_lat, u_ver)
                blocks[id(other)] = C
            self._static[id(el)] = (c, blocks)
            self._static_forces[id(el)] = np.zeros(len(c.index))
        self.static = True
        self.revision += 1

    def report_static(self, element, forces: np.ndarray) -> None:
        """Record an element's latest forces on its rail coordinates in the static solve.

        Parameters
        ----------
        element : FEContactElement
        forces : numpy.ndarray
            N, y and z per coupled body.
        """
        if self.static and id(element) in self._static_forces:
            self._static_forces[id(element)] = np.array(forces, float)

    def end_static(self) -> None:
        """Leave the static coupling (the next calls couple dynamically)."""
        self.static = False
        self.revision += 1

    def start(self, elements: Sequence, forces: Sequence[np.ndarray], v: float) -> None:
        """Set the FE state to the static field under the elements' forces, carried at speed v.

        Parameters
        ----------
        elements : sequence of FEContactElement
            At their positions at t = 0.
        forces : sequence of numpy.ndarray
            N, per element the static forces on its coupled rail coordinates (y, z per body).
        v : float
            m/s, speed: the field moves with the vehicle, u_t = v du/dx.
        """
        self.place([el.positions(0.0)[1] for el in elements])
        here, ahead = [], []
        for el in elements:
            x, x_fe = el.positions(0.0)
            coupled = self.points(el.element, x, x_fe)
            there = self.points(el.element, x + _START_DX, x_fe + _START_DX)
            here.append(coupled)
            ahead.append(there if there.bodies == coupled.bodies else coupled)
        u_lat, u_ver = self._static_sum(here, forces)
        a_lat, a_ver = self._static_sum(ahead, forces)
        self.lateral.u, self.vertical.u = u_lat, u_ver
        self.lateral.v = v * (a_lat - u_lat) / _START_DX
        self.vertical.v = v * (a_ver - u_ver) / _START_DX
        f_lat, f_ver = self._loads_sum(here, forces)
        for plane, f in ((self.lateral, f_lat), (self.vertical, f_ver)):
            rhs = f - plane.D @ plane.v - plane.K @ plane.u
            plane.qdd = CholeskyFactor(plane.M).solve(rhs)
            plane.a = plane.qdd.copy()
        self.t, self.t_next, self.static = 0.0, math.nan, False
        self.revision += 1

    def rail_displacements(self, coupled: _Coupled) -> np.ndarray:
        """The current state's rail-head displacements at coupled points.

        Parameters
        ----------
        coupled : _Coupled
            From :meth:`points`.

        Returns
        -------
        numpy.ndarray
            m, (y, z) per coupled body.
        """
        return self._gather(coupled, self.lateral.u, self.vertical.u)


class FEContactElement:
    """Exudyn ``forceUserFunction``: the profile contact element on the FE track.

    The wrapped :class:`~exudyn_turnout.passage.contact.profile.ProfileContactElement` has
    the vehicle's 7 coordinates and one (y, z) pair per rail body; Exudyn sees the vehicle's
    coordinates only, the rail coordinates are solved in every call from the FE track's
    one-step response (module docstring).

    Parameters
    ----------
    element : ProfileContactElement
        The contact element, one coordinate pair per rail body.
    track : FECoSimulation
        The FE track it is coupled to.
    """

    def __init__(self, element, track: FECoSimulation, fe_position: Callable | None = None):
        self.element, self.track = element, track
        self._fe_position = fe_position
        self.n = element.n_vehicle
        self.q = np.zeros(element.n)
        self.q_t = np.zeros(element.n)
        #: ((t, coupled bodies), Newton matrix, its inverse): one step's calls share it while
        #: the Newton converges fast with it (a modified Newton; the residual decides). Kept
        #: from step to step it is too far off: measured 2.9x the iterations
        self._jacobian: tuple | None = None
        self.last: tuple = ((), np.zeros(0), np.zeros(0))  #: (coupled, r, forces on r)
        #: (track revision, t, q, q_t, forces) of the last solve: the same call again (the
        #: post-step call at Exudyn's converged state) returns its result
        self._solved: tuple | None = None
        self._last_t = math.nan  #: s, time of the last solve

    def positions(self, t: float) -> tuple[float, float]:
        """Positions (m) at time t of the contact tables and on the FE track.

        Parameters
        ----------
        t : float
            s.

        Returns
        -------
        x, x_fe : float
            The element's ``x_at(t)`` and the wheelset's position on the FE track (the
            same unless a ``fe_position`` was given).
        """
        x = self.element.x_at(t)
        return x, (x if self._fe_position is None else float(self._fe_position(t)))

    def solve(self, t: float, q, q_t) -> np.ndarray:
        """Rail coordinates and forces for vehicle coordinates q, q_t at time t.

        Parameters
        ----------
        t : float
            s.
        q, q_t : array_like
            The vehicle's coordinates and velocities (the element's first 7).

        Returns
        -------
        numpy.ndarray
            The forces on the coupled rail coordinates (N, y and z per body); the full
            coordinate vectors are in ``self.q``, ``self.q_t`` after the call.

        Raises
        ------
        ArithmeticError
            The coupling Newton did not converge (with time and position).
        """
        t0 = time.perf_counter()
        solved, self._solved = self._solved, None
        if (
            solved is not None
            and solved[0] == self.track.revision
            and solved[1] == t
            and not self.track.static
            and np.array_equal(solved[2], q)
            and np.array_equal(solved[3], q_t)
        ):  # self.q, self.q_t, self.last are still this call's
            self._solved = solved
            return solved[4].copy()
        el, n = self.element, self.n
        x = el.x_at(t)
        coupled, r_free, r_t_free, C, c_v = self.track.coupling(self, t)
        self.q[:n], self.q_t[:n] = q, q_t
        self.q[n:], self.q_t[n:] = 0.0, 0.0
        idx = coupled.index
        el.prepare(x)
        if idx.size == 0:
            forces = el.forces_at(x, self.q, self.q_t)
            self.last = (coupled, np.zeros(0), np.zeros(0))
            return np.zeros(0)

        def rail_forces(r: np.ndarray) -> np.ndarray:
            self.q[idx] = r
            self.q_t[idx] = r_t_free + c_v * (r - r_free)
            return el.forces_at(x, self.q, self.q_t)[idx]  # a copy (fancy index)

        r = r_free.copy()
        if not C.any():  # the rails are where the FE state says
            forces = rail_forces(r)
            self.last = (coupled, r, forces)
            return forces
        starts = [r]
        if len(self.last[1]) == len(r) and self.last[0].bodies == coupled.bodies:
            # the previous solution (usually within a few nm); on a new step first the rails'
            # free motion plus the last forces' response (fewer iterations), the previous
            # solution kept as a second start where that one stalls on a kink of the forces
            starts = [self.last[1].copy()]
            if not (t == self._last_t or self.track.static):
                starts.insert(0, r_free + C @ self.last[2])
        J_inv = None
        if self._jacobian is not None and self._jacobian[0] == (t, coupled.bodies):
            J_inv = self._jacobian[2]

        def residual(r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            forces = rail_forces(r)
            return r - r_free - C @ forces, forces

        for r in starts:
            r, forces, size, J_inv = self._newton(residual, rail_forces, r, C, J_inv, t, coupled)
            if size <= COUPLING_TOLERANCE:
                break
        if size > COUPLING_STALL_TOLERANCE:
            raise ArithmeticError(
                f"FE coupling did not converge at t = {t:.6f} s, x = {x:.3f} m "
                f"(residual {size:.3g} m)"
            )
        if size > COUPLING_TOLERANCE:  # a stall on a kink of the forces: counted, reported
            self.track.stalls[0] += 1
            self.track.stalls[1] = max(self.track.stalls[1], size)
        self.q[idx] = r
        self.q_t[idx] = r_t_free + c_v * (r - r_free)
        self.last = (coupled, r, forces)
        self._last_t = t
        self.track.report_static(self, forces)
        self._solved = (self.track.revision, t, np.array(q, float), np.array(q_t, float), forces)
        self.track.timings["coupling_s"] += time.perf_counter() - t0
        return forces.copy()

    def _newton(self, residual, rail_forces, r, C, J_inv, t, coupled):
        """The coupling Newton from one start: (r, forces, largest residual, J^-1)."""
        g, forces = residual(r)
        size = float(np.abs(g).max())
        fresh = False
        for _ in range(_MAX_ITERATIONS):
            if size <= COUPLING_TARGET:
                break
            if J_inv is None or self.track.static:
                J = self._newton_matrix(rail_forces, r, forces, C)
                J_inv, fresh = np.linalg.inv(J), True
                self._jacobian = ((t, coupled.bodies), J, J_inv)
            step = J_inv @ g
            # backtracking on the largest residual: the creep forces' dependence on the rail
            # velocity makes a full step with an old Jacobian overshoot where points switch
            for damping in _DAMPING:
                trial = r - damping * step
                g_trial, f_trial = residual(trial)
                size_trial = float(np.abs(g_trial).max())
                if size_trial < (1.0 - 1e-4 * damping) * size:
                    break
            else:
                if fresh:  # no descent even with a new Jacobian
                    break
                J_inv = None  # an old Jacobian: recompute and retry
                continue
            if size_trial > 0.25 * size:  # slow: a new Jacobian for the next iteration
                J_inv = None
            r, g, forces, size, fresh = trial, g_trial, f_trial, size_trial, False
        return r, forces, size, J_inv

    @staticmethod
    def _newton_matrix(rail_forces, r, forces, C, scale: float = 1.0) -> np.ndarray:
        """I - C dF/dr (dF/dr with the rail velocity's dependence on r) by differences."""
        dF = np.empty((len(r), len(r)))
        step = scale * _FD_STEP
        for j in range(len(r)):
            dr = r.copy()
            dr[j] += step
            dF[:, j] = (rail_forces(dr) - forces) / step
        return np.eye(len(r)) - C @ dF

    def __call__(self, mbs, t, item_number, q, q_t):
        """Exudyn ``forceUserFunction``: generalised forces on the vehicle's coordinates."""
        try:
            self.solve(t, q, q_t)
        except (ArithmeticError, ValueError) as err:
            raise RuntimeError(str(err)) from None
        return self.element(mbs, t, item_number, self.q, self.q_t)[: self.n].copy()


def run_progress(
    progress: Callable[[float, float], None] | None, total: float, x0: float, v: float
) -> Callable[[float], None]:
    """A callable t -> None reporting progress about every 2 % of the run (or doing nothing).

    Parameters
    ----------
    progress : callable(fraction, x) or None
    total : float
        s, duration of the run.
    x0, v : float
        m, m/s: start position and speed.

    Returns
    -------
    callable
    """
    due = [0.0]

    def report(t: float) -> None:
        if progress is not None and t >= due[0]:
            due[0] = t + 0.02 * total
            progress(min(t / total, 1.0), x0 + v * t)

    return report
