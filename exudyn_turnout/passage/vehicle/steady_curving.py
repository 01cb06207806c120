"""Quasi-static (steady-state) curving of the full vehicle, without time integration.

In the track-following frame a vehicle running at constant speed v through a curve of
constant curvature kappa on rigid rails has a steady state: every coordinate constant, each
wheelset turning at v / r0 + Omega (Omega: its spin-perturbation rate, unknown). Setting
d/dt = 0 in the equations of motion of the package's own model leaves the nonlinear
algebraic system

    f(q, q_t = [0, ..., Omega_i at the spin coordinates, ...]) = 0

in the unknowns q (every coordinate but the spin angles, which no force depends on) and
Omega_i (one per wheelset; its equation is the wheelset's spin moment). f is the ODE2
right-hand side of the same Exudyn system a passage integrates (linear vehicle, primary
and secondary suspension, bumpstops acting on q - q_geo, curving loads -m v^2 kappa on every
body) evaluated by Exudyn (``MainSolverStatic.ComputeODE2RHS``), with the profile contact
(:class:`~exudyn_turnout.passage.contact.profile.ProfileContactElement`: the node's normal
law per contact point, creep forces of the FASTSIM table with spin) on rigid rails held at
their design position.
:func:`solve_steady_state` solves it by a damped Newton method with a forward-difference
Jacobian (:func:`newton_steady`), no time step involved.

:func:`conical_wheelset_residual` is the textbook case with a closed form (a single
wheelset, conical treads, linear creep): :func:`newton_steady` finds its pure-rolling
offset y0 = r0 b / (lambda R) (Wickens 2003, Fundamentals of Rail Vehicle Dynamics,
sec. 2.3; Iwnicki (ed.) 2006, Handbook of Railway Vehicle Dynamics, ch. 9).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from types import SimpleNamespace
from typing import Any

import numpy as np

from exudyn_turnout.inputs.routes import load_route
from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.inputs.turnout_data import Table1D
from exudyn_turnout.inputs.vehicle import load_vehicle
from exudyn_turnout.inputs.vehicle_model import VehicleModel, load_vehicle_model
from exudyn_turnout.passage.contact.profile import (
    RigidRailContact,
    route_contact,
)

__all__ = [
    "NewtonResult",
    "newton_steady",
    "conical_wheelset_residual",
    "pure_rolling_offset",
    "RigidCurveSystem",
    "build_rigid_curve",
    "SteadyCurving",
    "solve_steady_state",
    "steady_curving",
]


@dataclass(frozen=True, eq=False)
class NewtonResult:
    """Solution of f(u) = 0 by :func:`newton_steady`."""

    u: np.ndarray  #: the solution (units of the unknowns)
    residual: np.ndarray  #: f(u) at the solution (units of the equations)
    iterations: int  #: -, Newton iterations done
    converged: bool  #: True if max |f| <= the tolerance


def newton_steady(
    f: Callable[[np.ndarray], np.ndarray],
    u0: np.ndarray,
    steps: np.ndarray,
    tolerance: float = 1e-3,
    max_iterations: int = 60,
    max_update: np.ndarray | None = None,
) -> NewtonResult:
    """Damped Newton method with a forward-difference Jacobian for a square system f(u) = 0.

    Each iteration: J_ij = (f_i(u + h_j e_j) - f_i(u)) / h_j, the update du = -J^-1 f(u),
    scaled down so that |du_j| <= max_update_j, then halved until |f| decreases (at most 8
    halvings; the last trial is taken anyway so that a flat region is left).

    Parameters
    ----------
    f : callable
        The residual, u -> f(u) (same length as u).
    u0 : numpy.ndarray
        Start.
    steps : numpy.ndarray
        Finite-difference step per unknown (units of u).
    tolerance : float
        Largest |f_i| accepted (units of f).
    max_iterations : int
        Newton iterations at most.
    max_update : numpy.ndarray, optional
        Largest |du_j| per iteration (default: no limit).

    Returns
    -------
    NewtonResult
    """
    u = np.array(u0, float)
    r = np.asarray(f(u), float)
    steps = np.asarray(steps, float)
    for it in range(max_iterations):
        if np.max(np.abs(r)) <= tolerance:
            return NewtonResult(u, r, it, True)
        jac = np.empty((r.size, u.size))
        for j in range(u.size):
            du = np.zeros_like(u)
            du[j] = steps[j]
            jac[:, j] = (np.asarray(f(u + du), float) - r) / steps[j]
        try:
            du = -np.linalg.solve(jac, r)
        except np.linalg.LinAlgError:
            du = -np.linalg.lstsq(jac, r, rcond=None)[0]
        if max_update is not None:
            scale = np.max(np.abs(du) / np.asarray(max_update, float))
            if scale > 1.0:
                du = du / scale
        norm = float(np.linalg.norm(r))
        for _ in range(8):
            trial = np.asarray(f(u + du), float)
            if np.linalg.norm(trial) < norm:
                break
            du = 0.5 * du
        u, r = u + du, trial
    return NewtonResult(u, r, max_iterations, bool(np.max(np.abs(r)) <= tolerance))


def pure_rolling_offset(r0: float, b: float, conicity: float, radius: float) -> float:
    """Lateral offset at which a conical wheelset rolls round a curve without slip.

    y0 = r0 b / (lambda R) (Wickens 2003, Fundamentals of Rail Vehicle Dynamics, sec. 2.3;
    Iwnicki (ed.) 2006, Handbook of Railway Vehicle Dynamics, ch. 9): the rolling-radius
    difference 2 lambda y0 matches the difference of the rails' lengths, 2 b / R per unit
    length times r0.

    Parameters
    ----------
    r0 : float
        m, nominal rolling radius.
    b : float
        m, semi-distance of the contact points.
    conicity : float
        -, lambda.
    radius : float
        m, curve radius R (> 0).

    Returns
    -------
    float
        m, towards the outer rail.
    """
    return r0 * b / (conicity * radius)


def conical_wheelset_residual(
    u: np.ndarray,
    v: float,
    kappa: float,
    mass: float,
    r0: float,
    b: float,
    conicity: float,
    f11: float,
    f22: float,
) -> np.ndarray:
    """Steady-state equations of a single conical wheelset with linear creep in a curve.

    Unknowns u = (y, psi, Omega): lateral offset (m, positive left), yaw relative to the
    track (rad) and spin-perturbation rate (rad/s; the wheels turn at v / r0 + Omega).
    Curvature kappa > 0 curves to the left. Per wheel (s = +1 left, -1 right): rolling
    radius r = r0 + s lambda y, longitudinal creepage xi = 1 - kappa s b - (v / r0 + Omega)
    r / v, lateral creepage eta = -psi (steady: no lateral velocity), creep forces
    F_x = -f11 xi, F_y = -f22 eta (Kalker's linear theory, spin left out). Equations: the
    lateral force sum F_y - m v^2 kappa (track-following frame), the yaw moment
    sum -s b F_x, the spin moment sum -r F_x. The solution is y = -kappa r0 b / lambda
    (:func:`pure_rolling_offset`), psi = m v^2 kappa / (2 f22), Omega = 0 to first order.

    Parameters
    ----------
    u : numpy.ndarray
        (y, psi, Omega) in m, rad, rad/s.
    v : float
        m/s.
    kappa : float
        1/m.
    mass : float
        kg, wheelset mass (its centrifugal load).
    r0, b : float
        m, rolling radius and contact semi-spacing.
    conicity : float
        -, lambda.
    f11, f22 : float
        N, Kalker's longitudinal and lateral creep coefficients per wheel.

    Returns
    -------
    numpy.ndarray
        (lateral force N, yaw moment N m, spin moment N m).
    """
    y, psi, omega = u
    lateral = -mass * v**2 * kappa
    yaw = spin = 0.0
    for s in (1.0, -1.0):
        r = r0 + s * conicity * y
        xi = 1.0 - kappa * s * b - (v / r0 + omega) * r / v
        fx = -f11 * xi
        lateral += f22 * psi
        yaw += -s * b * fx
        spin += -r * fx
    return np.array([lateral, yaw, spin])


@dataclass(eq=False)
class RigidCurveSystem:
    """The full vehicle on rigid rails with every wheelset at a fixed route position."""

    container: Any  #: exudyn.SystemContainer (keeps the system alive)
    mbs: Any  #: exudyn.MainSystem, assembled, initial state: static + q_geo
    build: Any  #: VehicleBuild
    contacts: list  #: RigidRailContact per wheelset
    x_front: float  #: m, front wheelset position
    kappa: tuple  #: 1/m, curvature at each wheelset
    v: float  #: m/s
    keep: tuple = field(default=(), repr=False)  #: user functions kept alive


def build_rigid_curve(
    turnout: Turnout,
    route_name: str,
    model: VehicleModel,
    v: float,
    x_front: float,
    curvature: float | None = None,
) -> RigidCurveSystem:
    """Build the vehicle on rigid rails of the route, its position frozen at x_front.

    ::

        track-following frame at x_front, rails rigid (the route's sections at each x_i)
                      car body
             +---------------------------+     curving loads -m v^2 kappa on every body,
          bogie 2                    bogie 1   suspension on q - q_geo (q_geo: the
          ws4  ws3                  ws2  ws1   unstrained vehicle's chord in the curve)
        ===o====o==================o====o====  profile contact per wheel (KP/Hertz, FASTSIM)

    The same vehicle model (linear representation, spin free, bumpstops on q - q_geo) and
    curving loads (:class:`~exudyn_turnout.passage.vehicle.track_frame.BodyLoads`, frozen) as
    the co-running passage, the same contact element, with the rails fixed.

    Parameters
    ----------
    turnout : Turnout
    route_name : str
    model : VehicleModel
        A full vehicle.
    v : float
        m/s, speed (> 0).
    x_front : float
        m, position of the front wheelset (every wheelset within the turnout).
    curvature : float, optional
        1/m: replaces the route's curvature by this constant (a study of the radius with the
        same rail sections: the curvature enters the creepages and the curving loads only).

    Returns
    -------
    RigidCurveSystem

    Raises
    ------
    ValueError
        Not a full vehicle, v <= 0, or a wheelset outside the turnout.
    """
    import exudyn as exu
    from exudyn.itemInterface import ObjectGenericODE2

    from exudyn_turnout.passage.vehicle.builder import add_vehicle_model
    from exudyn_turnout.passage.vehicle.track_frame import (
        BodyLoads,
        add_vehicle_loads,
        contact_vehicle,
        set_initial_vehicle,
    )

    if model.car_body is None:
        raise ValueError(f"{model.name}: not a full vehicle (no car body)")
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"steady curving: v = {v!r} must be > 0 m/s")
    base = load_vehicle()
    route = load_route(turnout, route_name)
    contact = route_contact(turnout, route.name, base)
    if curvature is not None:
        route = replace(route, curvature=Table1D((0.0,), (float(curvature),)))
    vehicle = contact_vehicle(base, model)
    container = exu.SystemContainer()
    mbs = container.AddSystem()
    build = add_vehicle_model(
        mbs, model, representation="linear", wheelset_spin=True, bumpstop="none"
    )
    contacts, kappas = [], []
    for ws in build.wheelsets:
        if tuple(ws.dof) != ("y", "z", "roll", "yaw", "spin"):
            raise ValueError(f"unexpected wheelset coordinates {tuple(ws.dof)}")
        x_i = x_front + ws.x
        zones = [z for z in turnout.zones if z.x_start - 1e-9 <= x_i < z.x_end - 1e-9]
        if not zones:
            raise ValueError(
                f"steady curving: wheelset at x = {x_i:g} m is outside the turnout "
                f"({turnout.x_min:g}..{turnout.x_max:g} m)"
            )
        element, _ = contact.element(vehicle, route, zones[0], x_i, v)
        kappa = float(np.interp(x_i, route.curvature.x, route.curvature.value))
        force = RigidRailContact(element, x_i, len(ws.dof), model.wheelset.mass * v**2 * kappa)
        zero = np.zeros((force.n, force.n))
        mbs.AddObject(
            ObjectGenericODE2(
                nodeNumbers=[ws.node],
                massMatrix=zero,
                stiffnessMatrix=zero,
                forceUserFunction=force,
            )
        )
        contacts.append(force)
        kappas.append(kappa)
    stiffness = mbs.GetObjectParameter(build.items["suspension"], "stiffnessMatrix")
    damping = mbs.GetObjectParameter(build.items["suspension"], "dampingMatrix")
    length = -min(ws.x for ws in build.wheelsets)
    loads = BodyLoads(
        build,
        np.asarray(stiffness.GetPythonObject(), float),
        np.asarray(damping.GetPythonObject(), float),
        route,
        x_front,
        v,
        x_front - length - 2.0,
        x_front + 2.0,
    )
    loads.frozen = True
    keep = add_vehicle_loads(mbs, build, loads)
    mbs.variables["exudyn_turnout.steady_curving"] = (contacts, loads, keep)
    mbs.Assemble()
    set_initial_vehicle(
        SimpleNamespace(mbs=mbs, elements=[c.element for c in contacts]),
        build,
        [c.x for c in contacts],
    )
    # start: every body centred on its own track, the car body on the chord of the bogie
    # centres (q_geo: the unstrained vehicle, tangent to the curve at the car body's centre)
    q = np.array(mbs.systemData.GetODE2Coordinates(exu.ConfigurationType.Initial))
    q_geo = loads.geometry(x_front)
    if build.car_body is not None and build.bogies:
        i_y = loads.i_y[[k for k, name in enumerate(loads.names) if name.startswith("bogie")]]
        car = build.car_body
        q[mbs.GetNodeODE2Index(car.node) + car.dof["y"]] -= float(np.mean(q_geo[i_y]))
    mbs.systemData.SetODE2Coordinates(q.tolist(), exu.ConfigurationType.Initial)
    return RigidCurveSystem(
        container, mbs, build, contacts, float(x_front), tuple(kappas), float(v), (loads, keep)
    )


@dataclass(frozen=True, eq=False)
class SteadyCurving:
    """Steady state of the vehicle in a curve (:func:`solve_steady_state`), per wheelset
    front first; lateral quantities positive left (towards +y of the track frame)."""

    speed_kmh: float  #: km/h
    x_front: float  #: m, front wheelset position
    kappa: tuple  #: 1/m, curvature at each wheelset (< 0: curving right)
    y: np.ndarray  #: m, wheelset lateral displacement relative to the track centreline
    yaw: np.ndarray  #: rad, wheelset yaw relative to the local track tangent
    spin_rate: np.ndarray  #: rad/s, spin perturbation Omega (wheels at v / r0 + Omega)
    H: np.ndarray  #: N, sum of the wheelset's lateral forces on the rails
    Y: np.ndarray  #: N, (wheelsets, 2) lateral force on the (right, left) rail
    Q: np.ndarray  #: N, (wheelsets, 2) vertical force on the (right, left) rail
    Fx: np.ndarray  #: N, (wheelsets, 2) longitudinal creep force on the (right, left) wheel
    yaw_moment: np.ndarray  #: N m, per wheelset: yaw moment of the longitudinal creep forces
    contact_angle: np.ndarray  #: rad, (wheelsets, 2) load-weighted contact angle (right, left)
    bodies: dict  #: name -> (y m, yaw rad) of car body and bogies, relative to the track
    residual: float  #: N (or N m), largest |equation| left at the solution
    iterations: int  #: -, Newton iterations
    q: np.ndarray = field(repr=False)  #: m, rad: ODE2 coordinates of the solution

    @property
    def total_lateral(self) -> float:
        """Sum of H over the wheelsets (N): in a steady state it equals sum m v^2 kappa.

        Returns
        -------
        float
            N, positive left.
        """
        return float(np.sum(self.H))


def _rhs_function(system: RigidCurveSystem):
    """(q, q_t) -> Exudyn's ODE2 right-hand side of the system at t = 1 (full curving loads)."""
    import exudyn as exu

    from exudyn_turnout.passage.vehicle.builder import static_settings

    mbs, data = system.mbs, system.mbs.systemData
    solver: Any = exu.MainSolverStatic()  # Exudyn's stubs type its methods as unbound
    previous = exu.config.printToConsole
    exu.config.printToConsole = False
    try:
        solver.InitializeSolver(mbs, static_settings())
    finally:
        exu.config.printToConsole = previous
    data.SetTime(1.0, exu.ConfigurationType.Current)

    def rhs(q: np.ndarray, q_t: np.ndarray) -> np.ndarray:
        data.SetODE2Coordinates(q.tolist(), exu.ConfigurationType.Current)
        data.SetODE2Coordinates_t(q_t.tolist(), exu.ConfigurationType.Current)
        solver.ComputeODE2RHS(mbs)
        return np.array(solver.GetSystemResidual()[: len(q)])

    return rhs, solver


def solve_steady_state(
    system: RigidCurveSystem, tolerance: float = 1e-2, max_iterations: int = 200
) -> SteadyCurving:
    """Solve the steady state of a :class:`RigidCurveSystem` (module docstring).

    Unknowns: every ODE2 coordinate but the wheelsets' spin angles, and each wheelset's spin
    rate Omega; equations: the ODE2 right-hand side with all velocities zero but the spin
    rates (accelerations zero). Start: the system's initial state. Newton
    (:func:`newton_steady`) with the updates limited to 1 mm / 1 mrad (0.1 rad/s for the spin
    rates) per iteration.

    Parameters
    ----------
    system : RigidCurveSystem
    tolerance : float
        N (N m), largest residual accepted.
    max_iterations : int

    Returns
    -------
    SteadyCurving

    Raises
    ------
    ValueError
        Newton did not converge (one line with the residual left).
    """
    import exudyn as exu

    mbs, build = system.mbs, system.build
    q0 = np.array(mbs.systemData.GetODE2Coordinates(exu.ConfigurationType.Initial))
    n = q0.size
    spin = np.array([mbs.GetNodeODE2Index(ws.node) + ws.dof["spin"] for ws in build.wheelsets])
    rhs, _solver = _rhs_function(system)

    def state(u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        q, q_t = u.copy(), np.zeros(n)
        q[spin] = q0[spin]
        q_t[spin] = u[spin]
        return q, q_t

    def f(u: np.ndarray) -> np.ndarray:
        return rhs(*state(u))

    u0 = q0.copy()
    u0[spin] = 0.0
    steps = np.full(n, 1e-8)
    steps[spin] = 1e-5
    limit = np.full(n, 1e-3)
    limit[spin] = 0.1
    result = newton_steady(f, u0, steps, tolerance, max_iterations, limit)
    if not result.converged:
        raise ValueError(
            f"steady curving at {system.v * 3.6:g} km/h, x = {system.x_front:g} m: Newton did "
            f"not converge (largest residual {np.max(np.abs(result.residual)):.3g} after "
            f"{result.iterations} iterations)"
        )
    q, q_t = state(result.u)
    return _steady_result(system, q, q_t, float(np.max(np.abs(result.residual))), result)


def _steady_result(system: RigidCurveSystem, q, q_t, residual: float, result) -> SteadyCurving:
    """The SteadyCurving of the state (q, q_t)."""
    from exudyn_turnout.wheel_rail.kernel import DETAIL_FIELDS

    mbs, build = system.mbs, system.build
    col = {name: k for k, name in enumerate(DETAIL_FIELDS)}
    ys, yaws, spins, H, Y, Q, FX, moment, angle = [], [], [], [], [], [], [], [], []
    for ws, c in zip(build.wheelsets, system.contacts):
        i = mbs.GetNodeODE2Index(ws.node)
        qw, qw_t = c.full(q[i : i + c.n], q_t[i : i + c.n])
        forces, details = c.element.evaluate(c.x, qw, qw_t)
        ys.append(qw[0])
        yaws.append(qw[3])
        spins.append(qw_t[4])
        H.append(-forces[0])
        n_c = c.element.tables.n_candidates
        y_wheel: dict[str, float] = {}
        q_wheel: dict[str, float] = {}
        fx_wheel: dict[str, float] = {}
        ang: dict[str, float] = {}
        m = 0.0
        for k, body in enumerate(c.element.bodies):
            rows = details[k * n_c : (k + 1) * n_c]
            w = body.wheel
            fz = float(rows[:, col["Fz"]].sum())
            y_wheel[w] = y_wheel.get(w, 0.0) - float(rows[:, col["Fy"]].sum())
            q_wheel[w] = q_wheel.get(w, 0.0) + fz
            fx_wheel[w] = fx_wheel.get(w, 0.0) + float(rows[:, col["Fx"]].sum())
            s = 1.0 if w == "left" else -1.0
            found = np.maximum(rows[:, col["found"]], 1e-12)  # the fields are weight sums
            y_c = s * rows[:, col["y_rail"]] / found - qw[0]
            m += float(np.sum(-y_c * rows[:, col["Fx"]]))
            ang[w] = ang.get(w, 0.0) + float(
                np.sum(rows[:, col["Fz"]] * rows[:, col["angle"]] / found)
            )
        Y.append([y_wheel.get("right", 0.0), y_wheel.get("left", 0.0)])
        Q.append([q_wheel.get("right", 0.0), q_wheel.get("left", 0.0)])
        FX.append([fx_wheel.get("right", 0.0), fx_wheel.get("left", 0.0)])
        angle.append([ang.get(w, 0.0) / max(q_wheel.get(w, 0.0), 1e-9) for w in ("right", "left")])
        moment.append(m)
    bodies = {}
    for b in build.bodies():
        if b.name.startswith("wheelset"):
            continue
        i = mbs.GetNodeODE2Index(b.node)
        bodies[b.name] = (float(q[i + b.dof["y"]]), float(q[i + b.dof["yaw"]]))
    return SteadyCurving(
        system.v * 3.6,
        system.x_front,
        system.kappa,
        np.array(ys),
        np.array(yaws),
        np.array(spins),
        np.array(H),
        np.array(Y),
        np.array(Q),
        np.array(FX),
        np.array(moment),
        np.array(angle),
        bodies,
        residual,
        result.iterations,
        np.asarray(q, float),
    )


def steady_curving(
    turnout: Turnout,
    speed_kmh: float,
    x_front: float,
    route: str = "diverging",
    vehicle_model: VehicleModel | None = None,
    speeds: Sequence[float] = (),
    curvature: float | None = None,
) -> SteadyCurving:
    """Steady curving of the full vehicle with its front wheelset at x_front (rigid rails).

    :func:`build_rigid_curve` then :func:`solve_steady_state`; ``speeds`` (km/h, increasing,
    below ``speed_kmh``) are solved first, each from the previous solution (continuation).

    Parameters
    ----------
    turnout : Turnout
    speed_kmh : float
        km/h.
    x_front : float
        m, front wheelset position (the whole vehicle in the curve for a curving result).
    route : str
    vehicle_model : VehicleModel, optional
        Default: the packaged Manchester vehicle 1.
    speeds : sequence of float
        km/h, continuation speeds.
    curvature : float, optional
        1/m, replaces the route's curvature (:func:`build_rigid_curve`).

    Returns
    -------
    SteadyCurving

    Raises
    ------
    ValueError
        As :func:`build_rigid_curve` and :func:`solve_steady_state`.
    """
    import exudyn as exu

    model = load_vehicle_model() if vehicle_model is None else vehicle_model
    state = None
    result = None
    for kmh in [*speeds, speed_kmh]:
        system = build_rigid_curve(turnout, route, model, kmh / 3.6, x_front, curvature)
        if state is not None:
            system.mbs.systemData.SetODE2Coordinates(state, exu.ConfigurationType.Initial)
        result = solve_steady_state(system)
        state = result.q.tolist()
    assert result is not None
    return result
