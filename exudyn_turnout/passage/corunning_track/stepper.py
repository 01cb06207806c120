"""A compiled time stepper for the full vehicle's co-running passage (the default).

``PassageSettings(solver="compiled")`` (the default; ``solver="exudyn"`` asks for Exudyn's
integrator) runs each segment of :mod:`~exudyn_turnout.passage.corunning_track.vehicle` here
instead of Exudyn's ``SolveDynamic``: the same implicit generalized-alpha scheme, the same
modified Newton method and the same tolerances as Exudyn 1.13's ``GeneralizedAlpha`` solver
(``CSolverImplicitSecondOrder.cpp`` and ``CSolverBase::Newton``), with no Python call per
step. What a step costs in Exudyn is mostly the passing of its coordinate lists to the
Python force function and back (~20 us of a ~30 us residual evaluation, 2.3 evaluations per
step; :mod:`~exudyn_turnout.passage.corunning_track.vehicle`); here the compiled residual
(:class:`~exudyn_turnout.passage.contact.vehicle_kernel.CompiledResidual`) is called from
numba directly.

The system. The vehicle in linear representation is a constant mass matrix M, linear
objects (``ObjectGenericODE2`` with constant K, D and force vector: the suspension, the
dummy sprung masses) and ONE ``ObjectGenericODE2`` whose force f(q, q_t, t) is the compiled
residual (contacts, bumpstops, track springs, body loads in a curve). M is Exudyn's own
(``ComputeLinearizedSystem``); K, D and the force vectors are read from the linear objects'
parameters. :func:`unsupported` names anything else acting (loads, constraints, ODE1
coordinates, another user function, an object type without constant mass, a Python
residual path): the run then goes to Exudyn as before.

The scheme (Arnold and Bruls' form, Exudyn's variable names): with rho the spectral radius,
alpha_m = (2 rho - 1)/(rho + 1), alpha_f = rho/(rho + 1), gamma = 1/2 + alpha_f - alpha_m,
beta = (gamma + 1/2)^2/4; predictor q = q_n + h v_n + h^2 (1/2 - beta) a*_n,
v = v_n + h (1 - gamma) a*_n, a* = (alpha_f a_n - alpha_m a*_n)/(1 - alpha_m),
q += h^2 beta a*, v += h gamma a*, a = 0; Newton on the residual r = M a + K q + D v - f_0
- f(q, v, t_n+1) with the increment solved from J dx = beta h^2 r,
J = (1 - alpha_m)/(1 - alpha_f) M + beta h^2 (K_t + gamma/(h beta) D_t),
q -= dx, v -= gamma/(h beta) dx, a -= (1 - alpha_m)/(h^2 beta (1 - alpha_f)) dx; after
convergence a* += (1 - alpha_f)/(1 - alpha_m) a. Initial accelerations from M a_0 =
-r(a = 0) at t = 0. Newton stops at ||r|| <= the run's absolute tolerance or a relative
reduction of 1e-8 (Exudyn's default); it keeps the factorised J between iterations and
steps (modified Newton) and recomputes it where an iteration after the second reduces the
residual by less than the run's ``modifiedNewtonContractivity``, after 8 iterations, and
restarts the step from the predictor where the contraction is worse than 2 (Exudyn's
rules, literally). K_t, D_t: the linear objects' K, D plus the force object's forward
differences (Exudyn's step: 1e-7 x max(|q_j|, 0.01)); J is LU-factorised with partial
pivoting in a reverse Cuthill-McKee order of its pattern and solved with the compressed
factors (on the full vehicle's 103 coordinates ~1,000 entries instead of ~10,600 of a dense
LU: ~3 us a solve). The contacts' forces and details of each accepted step are recorded
once, after Newton converged (what the residual records at Newton's last call of a time in
Exudyn's run: the same rows). Times and sensor samples follow Exudyn's adaptive-step bookkeeping
(t += h, the last step shortened to the end time; a sample where t reaches the last
sample's time plus the period, and at the end). A step whose Newton fails is not retried
smaller (Exudyn would): the run stops with the time and position.

Stopping early (the check rail's predicted fine piece,
:class:`~exudyn_turnout.passage.check_rail_steps.CheckRailStop`, which acts every ``m`` fine
steps, at the segment's grid times): the steps run in compiled chunks ending on those steps,
and between two chunks ``stop`` is called with the contacts' last evaluation at the step's
start (the last accepted step's, Newton's last call: what ``VehicleContacts.last_forces``
reads, as on Exudyn's path before a step) and a function writing the state into Exudyn's
current configuration; False ends the run after that step, as an Exudyn pre-step function
returning False does. A run without ``stop`` makes no Python call between its progress
reports. On the diverging route (80 km/h, 2 and 3 layers, 20..55 m) the same refined and
predicted windows as Exudyn's path and every peak of the summary within 2e-9 of Exudyn's
(relative).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numba
import numpy as np

from exudyn_turnout.passage.contact.vehicle_kernel import (
    PACKED_NAMES,
    record_kernel,
    residual_kernel,
)

__all__ = [
    "RELATIVE_TOLERANCE",
    "StepperRun",
    "alpha_constants",
    "step_times",
    "sample_rows",
    "unsupported",
    "integrate",
    "integrate_linear",
]

#: Newton's relative tolerance (Exudyn's default ``newton.relativeTolerance``)
RELATIVE_TOLERANCE = 1e-8
#: Exudyn's ``newton.maxIterations``, ``maxModifiedNewtonIterations``,
#: ``maxModifiedNewtonRestartIterations`` (defaults)
_MAX_ITERATIONS, _MAX_MODIFIED, _MAX_RESTART = 25, 8, 7
#: relative and smallest-coordinate factors of the forward differences (Exudyn's defaults)
_EPSILON, _MINIMUM_SIZE = 1e-7, 0.01
#: object types with a constant mass and nothing else (besides ObjectGenericODE2)
_PLAIN_OBJECTS = ("Ground", "RigidBody2D", "MassPoint2D", "MassPoint")


def alpha_constants(rho: float) -> tuple[float, float, float, float]:
    """Exudyn's generalized-alpha constants of the spectral radius ``rho``.

    Parameters
    ----------
    rho : float
        Spectral radius at infinite frequency (0..1).

    Returns
    -------
    alpha_m, alpha_f, beta, gamma : float
        Chung-Hulbert's alpha_m, alpha_f and the Newmark beta, gamma of
        ``CSolverImplicitSecondOrder::PreInitializeSolverSpecific``.
    """
    alpha_m = (2.0 * rho - 1.0) / (rho + 1.0)
    alpha_f = rho / (rho + 1.0)
    gamma = 0.5 + alpha_f - alpha_m
    beta = 0.25 * (gamma + 0.5) ** 2
    return alpha_m, alpha_f, beta, gamma


def step_times(end_time: float, steps: int) -> tuple[np.ndarray, np.ndarray]:
    """Exudyn's times and step sizes of a run (adaptive-step bookkeeping, no reduction).

    Parameters
    ----------
    end_time : float
        s, the run's end (it starts at 0).
    steps : int
        ``timeIntegration.numberOfSteps``.

    Returns
    -------
    times : numpy.ndarray
        s, t_0 = 0 and the end of every step.
    sizes : numpy.ndarray
        s, every step's size (sizes[0] unused).
    """
    times, sizes, count = _step_times(float(end_time), int(steps))
    return times[:count].copy(), sizes[:count].copy()


@numba.njit(cache=True)
def _step_times(end_time, steps):  # pragma: no cover (compiled)
    """:func:`step_times` (a loop over the run's steps: compiled)."""
    h = end_time / steps
    size = steps + 2  # round-off may add a last, tiny step
    times, sizes = np.zeros(size), np.full(size, h)
    t = 0.0
    count = 1
    while True:
        if t + h > end_time:
            h = end_time - t
        t += h
        if count == size:  # never: the loop ends within steps + 1 steps
            break
        times[count] = t
        sizes[count] = h
        count += 1
        if t >= end_time - 1e-10:
            break
    return times, sizes, count


def sample_rows(times: np.ndarray, sizes: np.ndarray, period: float) -> np.ndarray:
    """Which times Exudyn's sensors store (``CSolverBase::WriteSensorsToFile``).

    Parameters
    ----------
    times, sizes : numpy.ndarray
        :func:`step_times`.
    period : float
        s, ``solution.sensors.writePeriod``.

    Returns
    -------
    numpy.ndarray
        bool per time.
    """
    return _sample_rows(np.asarray(times, float), np.asarray(sizes, float), float(period))


@numba.njit(cache=True)
def _sample_rows(times, sizes, period):  # pragma: no cover (compiled)
    """:func:`sample_rows` (a loop over the run's times: compiled)."""
    end = times[-1]
    last = 0.0
    out = np.zeros(times.shape[0], dtype=np.bool_)
    for k in range(times.shape[0]):
        t = times[k]
        if k > 0 and abs(t - end) <= 1e-10:
            last = end - sizes[k]
        if k == 0 or t - last >= -1e-10:
            out[k] = True
            last = max(last + period, t)
    return out


@numba.njit(cache=True)
def _user(t, q, v, ltg, fbuf, ibuf, header, values, blendable, xs, record, f):  # pragma: no cover
    """The force object's f(q, v, t) scattered into the global vector f."""
    n = ltg.shape[0]
    f[:] = 0.0
    if n == 0:  # no force object (integrate_linear)
        return
    for i in range(n):
        g = ltg[i]
        fbuf[i] = q[g]
        fbuf[n + i] = v[g]
    residual_kernel(t, fbuf, ibuf, header, values, blendable, xs, record)
    o = header[2, 0]
    for i in range(n):
        f[ltg[i]] += fbuf[o + i]


@numba.njit(cache=True)
def _residual_of(t, q, v, a, lin, f0, user, record, f, r):  # pragma: no cover
    """r = M a + K q + D v - f_0 - f(q, v, t); returns ||r||."""
    indptr, indices, mv, kv, dv = lin
    ltg, fbuf, ibuf, header, values, blendable, xs = user
    _user(t, q, v, ltg, fbuf, ibuf, header, values, blendable, xs, record, f)
    total = 0.0
    for i in range(r.shape[0]):
        s = 0.0
        for p in range(indptr[i], indptr[i + 1]):
            j = indices[p]
            s += mv[p] * a[j] + kv[p] * q[j] + dv[p] * v[j]
        r[i] = s - f0[i] - f[i]
        total += r[i] * r[i]
    return math.sqrt(total)


@numba.njit(cache=True)
def _lu_factor(a, piv):  # pragma: no cover
    """In-place LU with partial pivoting; False if singular."""
    n = a.shape[0]
    for k in range(n):
        p = k
        big = abs(a[k, k])
        for i in range(k + 1, n):
            if abs(a[i, k]) > big:
                big = abs(a[i, k])
                p = i
        piv[k] = p
        if big == 0.0:
            return False
        if p != k:
            for j in range(n):
                a[k, j], a[p, j] = a[p, j], a[k, j]
        inv = 1.0 / a[k, k]
        for i in range(k + 1, n):
            m = a[i, k] * inv
            a[i, k] = m
            if m != 0.0:
                for j in range(k + 1, n):
                    a[i, j] -= m * a[k, j]
    return True


@numba.njit(cache=True)
def _lu_solve(a, piv, b):  # pragma: no cover
    """Solve in place (b becomes x) with :func:`_lu_factor`'s factors."""
    n = a.shape[0]
    for k in range(n):
        p = piv[k]
        if p != k:
            b[k], b[p] = b[p], b[k]
    for i in range(n):
        s = b[i]
        for j in range(i):
            s -= a[i, j] * b[j]
        b[i] = s
    for i in range(n - 1, -1, -1):
        s = b[i]
        for j in range(i + 1, n):
            s -= a[i, j] * b[j]
        b[i] = s / a[i, i]


@numba.njit(cache=True)
def _factor(jac, fac):  # pragma: no cover
    """LU of J in the fill-reducing order (partial pivoting), kept as compressed rows of L
    and U for :func:`_solve`; False if J is singular."""
    order, lu, piv, l_ptr, l_idx, l_val, u_ptr, u_idx, u_val = fac
    n = order.shape[0]
    for i in range(n):
        for j in range(n):
            lu[i, j] = jac[order[i], order[j]]
    if not _lu_factor(lu, piv):
        return False
    nl = 0
    nu = 0
    for i in range(n):
        l_ptr[i] = nl
        for j in range(i):
            if lu[i, j] != 0.0:
                l_idx[nl] = j
                l_val[nl] = lu[i, j]
                nl += 1
        u_ptr[i] = nu
        for j in range(i, n):  # the diagonal first
            if lu[i, j] != 0.0 or j == i:
                u_idx[nu] = j
                u_val[nu] = lu[i, j]
                nu += 1
    l_ptr[n] = nl
    u_ptr[n] = nu
    return True


@numba.njit(cache=True)
def _solve(fac, b, y):  # pragma: no cover
    """Solve J x = b in place (b becomes x) with :func:`_factor`'s compressed factors."""
    order, lu, piv, l_ptr, l_idx, l_val, u_ptr, u_idx, u_val = fac
    n = order.shape[0]
    for i in range(n):
        y[i] = b[order[i]]
    for k in range(n):
        p = piv[k]
        if p != k:
            y[k], y[p] = y[p], y[k]
    for i in range(n):
        s = y[i]
        for m in range(l_ptr[i], l_ptr[i + 1]):
            s -= l_val[m] * y[l_idx[m]]
        y[i] = s
    for i in range(n - 1, -1, -1):
        s = y[i]
        a = u_ptr[i]
        for m in range(a + 1, u_ptr[i + 1]):
            s -= u_val[m] * y[u_idx[m]]
        y[i] = s / u_val[a]
    for i in range(n):
        b[order[i]] = y[i]


@numba.njit(cache=True)
def _jacobian(t, h, q, v, lin, consts, user, norecord, f0, f1, jac):  # pragma: no cover
    """Exudyn's iteration matrix J (module docstring) at (q, v, t), not factorised."""
    indptr, indices, mv, kv, dv = lin
    ltg, fbuf, ibuf, header, values, blendable, xs = user
    alpha_m, alpha_f, beta, gamma = consts[0], consts[1], consts[2], consts[3]
    s = beta * h * h
    gp = gamma / (h * beta)
    cm = (1.0 - alpha_m) / (h * h * beta * (1.0 - alpha_f)) * s
    jac[:, :] = 0.0
    for i in range(jac.shape[0]):
        for p in range(indptr[i], indptr[i + 1]):
            j = indices[p]
            jac[i, j] += cm * mv[p] + s * kv[p] + s * gp * dv[p]
    _user(t, q, v, ltg, fbuf, ibuf, header, values, blendable, xs, norecord, f0)
    for jj in range(ltg.shape[0]):
        g = ltg[jj]
        for which in range(2):
            vec = q if which == 0 else v
            factor = s if which == 0 else s * gp
            value = vec[g]
            eps = _EPSILON * max(abs(value), _MINIMUM_SIZE)
            vec[g] = value + eps
            _user(t, q, v, ltg, fbuf, ibuf, header, values, blendable, xs, norecord, f1)
            vec[g] = value
            c = factor / eps
            for i in range(jac.shape[0]):
                jac[i, g] += c * (f0[i] - f1[i])


@numba.njit(cache=True)
def _predict(h, q, v, a, aalg, consts):  # pragma: no cover
    """Exudyn's ``ComputeNewtonUpdate(initial=True)`` for generalized-alpha."""
    alpha_m, alpha_f, beta, gamma = consts[0], consts[1], consts[2], consts[3]
    c0, c1 = h * h * (0.5 - beta), h * (1.0 - gamma)
    c2, c3 = -alpha_m / (1.0 - alpha_m), alpha_f / (1.0 - alpha_m)
    c4, c5 = h * h * beta, h * gamma
    for i in range(q.shape[0]):
        q[i] += h * v[i]
        q[i] += c0 * aalg[i]
        v[i] += c1 * aalg[i]
        aalg[i] *= c2
        aalg[i] += c3 * a[i]
        q[i] += c4 * aalg[i]
        v[i] += c5 * aalg[i]
        a[i] = 0.0


@numba.njit(cache=True)
def _prepare(k, fbuf, prep, segments):  # pragma: no cover
    """Copy time k's per-time inputs (body loads, bumpstop shift, irregularity) in place."""
    if prep.shape[0] == 0:
        return
    j = 0
    for s in range(segments.shape[0]):
        o, n = segments[s, 0], segments[s, 1]
        for i in range(n):
            fbuf[o + i] = prep[k, j]
            j += 1


@numba.njit(cache=True)
def _integrate(
    k0,
    k1,
    times,
    sizes,
    stored,
    state,
    work,
    lin,
    f0,
    consts,
    user,
    record,
    norecord,
    recorded,
    prep,
    segments,
    jac,
    fac,
    flags,
    counts,
    out_q,
    out_v,
    out_a,
):  # pragma: no cover
    """Steps k0..k1-1 (to times[k0 + 1..k1]); returns -1 or the step that failed.

    ``state``: rows q, v, a, a*; ``work``: rows q, v, a, a* at the step's start, f, f1, r,
    dx; ``flags``: [Jacobian requested, next output row]; ``counts``: [residual calls,
    Newton iterations, Jacobians]."""
    q, v, a, aalg = state[0], state[1], state[2], state[3]
    q_s, v_s, a_s, aalg_s = work[0], work[1], work[2], work[3]
    f, f1, r, dx = work[4], work[5], work[6], work[7]
    alpha_m, alpha_f, beta, gamma = consts[0], consts[1], consts[2], consts[3]
    abs_tol, rel_tol, contractivity = consts[4], consts[5], consts[6]
    fbuf = user[1]
    n = q.shape[0]
    for k in range(k0, k1):
        t, h = times[k + 1], sizes[k + 1]
        _prepare(k + 1, fbuf, prep, segments)
        s = beta * h * h
        gp = gamma / (h * beta)
        bp = (1.0 - alpha_m) / (h * h * beta * (1.0 - alpha_f))
        q_s[:] = q
        v_s[:] = v
        a_s[:] = a
        aalg_s[:] = aalg
        _predict(h, q, v, a, aalg, consts)
        initial = _residual_of(t, q, v, a, lin, f0, user, norecord, f, r)
        counts[0] += 1
        if initial <= abs_tol:
            initial = 2.0 * abs_tol
        last = initial
        restarted = False
        full = False
        add_restart = False
        stop = False
        converged = False
        it = 0
        while not converged and not stop and it < _MAX_ITERATIONS:
            it += 1
            counts[1] += 1
            if flags[0] != 0 or full:
                _jacobian(t, h, q, v, lin, consts, user, norecord, f, f1, jac)
                counts[2] += 1
                flags[0] = 0
                if not _factor(jac, fac):
                    flags[0] = 1
                    return k
            for i in range(n):
                dx[i] = s * r[i]
            _solve(fac, dx, f1)
            for i in range(n):
                q[i] -= dx[i]
                v[i] += -gp * dx[i]
                a[i] += -bp * dx[i]
            residual = _residual_of(t, q, v, a, lin, f0, user, norecord, f, r)
            counts[0] += 1
            if residual > initial and it <= 1:
                initial = residual
                last = residual
            if residual / initial <= rel_tol:
                converged = True
            elif residual <= abs_tol:
                converged = True
            if add_restart and converged:
                add_restart = False
                converged = False
            elif not converged:
                add_restart = False
                norm_q = 0.0
                norm_v = 0.0
                for i in range(n):
                    norm_q += q[i] * q[i]
                    norm_v += v[i] * v[i]
                diverged = False
                if norm_q >= 1e38 or norm_v >= 1e38 or math.isnan(norm_q) or math.isnan(norm_v):
                    if full:
                        stop = True
                    else:
                        diverged = True
                if not full and it > _MAX_MODIFIED:
                    flags[0] = 1
                switch = False
                if not full and it > _MAX_MODIFIED + _MAX_RESTART:
                    full = True
                    switch = True
                ratio = residual / last
                last = residual
                if not full and (diverged or switch or (ratio > contractivity and it > 2)):
                    flags[0] = 1
                    if restarted and not full:
                        full = True
                    if not stop and (diverged or ratio > 2.0 or full):
                        restarted = True
                        last = initial
                        q[:] = q_s
                        v[:] = v_s
                        a[:] = a_s
                        aalg[:] = aalg_s
                        _predict(h, q, v, a, aalg, consts)
                        _residual_of(t, q, v, a, lin, f0, user, norecord, f, r)
                        counts[0] += 1
                        add_restart = True
        if stop or not converged:
            return k
        if record.shape[0] > 1:  # the contacts of the last call: the accepted state's
            record_kernel(t, recorded[0], recorded[1], record)
        c = (1.0 - alpha_f) / (1.0 - alpha_m)
        for i in range(n):
            aalg[i] += c * a[i]
        if stored[k + 1]:
            row = flags[1]
            out_q[row] = q
            out_v[row] = v
            out_a[row] = a
            flags[1] = row + 1
    return -1


@numba.njit(cache=True)
def _start(state, lin, f0, user, record, f, r, mass, piv):  # pragma: no cover
    """Exudyn's initial accelerations: M a_0 = -r(q_0, v_0, a = 0, t = 0); False if M is
    singular."""
    q, v, a, aalg = state[0], state[1], state[2], state[3]
    a[:] = 0.0
    _residual_of(0.0, q, v, a, lin, f0, user, record, f, r)
    if not _lu_factor(mass, piv):
        return False
    for i in range(r.shape[0]):
        a[i] = -r[i]
    _lu_solve(mass, piv, a)
    aalg[:] = a
    return True


@dataclass(frozen=True)
class StepperRun:
    """What :func:`integrate` returns: the samples of a run and its statistics."""

    times: np.ndarray  #: s, the sampled times (from the run's start)
    q: np.ndarray  #: m or rad, (samples, coordinates) global ODE2 coordinates
    q_t: np.ndarray  #: m/s or rad/s, their velocities
    q_tt: np.ndarray  #: m/s^2 or rad/s^2, their accelerations
    steps: int  #: time steps taken
    residuals: int  #: residual evaluations (force-object calls outside the Jacobians)
    iterations: int  #: Newton iterations
    jacobians: int  #: iteration matrices computed
    failed_at: float  #: s, time of the step whose Newton failed (NaN: none)

    def sensor_data(self, mbs: Any, sensor: int) -> np.ndarray:
        """A node or body sensor's samples as Exudyn's ``GetSensorStoredData`` gives them.

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The run's system.
        sensor : int
            A ``SensorNode`` or ``SensorBody`` (on an ``ObjectGenericODE2``) of coordinates,
            velocities or accelerations.

        Returns
        -------
        numpy.ndarray
            (samples, 1 + values): time, then the values.
        """
        import exudyn as exu

        item = mbs.GetSensor(sensor)
        if "nodeNumber" in item:
            index = _node_indices(mbs, [int(item["nodeNumber"])])
        else:
            index = _node_indices(mbs, list(mbs.GetObject(int(item["bodyNumber"]))["nodeNumbers"]))
        kind = item["outputVariableType"]
        source = {
            exu.OutputVariableType.Coordinates: self.q,
            exu.OutputVariableType.Coordinates_t: self.q_t,
            exu.OutputVariableType.Coordinates_tt: self.q_tt,
        }[kind]
        return np.column_stack([self.times, source[:, index]])


def _node_indices(mbs: Any, nodes: list) -> np.ndarray:
    """Global ODE2 indices of the nodes' coordinates, in order."""
    out: list[int] = []
    for node in nodes:
        start = mbs.GetNodeODE2Index(int(node))
        size = len(np.atleast_1d(mbs.GetNode(int(node))["referenceCoordinates"]))
        out += range(start, start + size)
    return np.array(out, dtype=np.int64)


def unsupported(mbs: Any, contacts: Any) -> str | None:
    """Why the compiled stepper cannot run this assembled system (None: it can).

    Parameters
    ----------
    mbs : exudyn.MainSystem
        A full vehicle's segment, assembled.
    contacts : VehicleContacts
        Its force object's function.

    Returns
    -------
    str or None
        One line naming what else acts, or None.
    """
    data = mbs.systemData
    if contacts._compiled is None or not contacts._fast_at(0.0):
        return "the force object has no compiled residual at speed"
    if data.NumberOfLoads() != 0:
        return "the system has loads"
    if len(data.GetODE1Coordinates()) or len(data.GetAECoordinates()):
        return "the system has ODE1 coordinates or constraints"
    users = 0
    for i in range(data.NumberOfObjects()):
        item = mbs.GetObject(i)
        kind = item["objectType"]
        if kind == "GenericODE2":
            has = [item[k] != 0 for k in ("forceUserFunction", "massMatrixUserFunction")]
            if has[1]:
                return "an object has a mass matrix user function"
            users += has[0]
        elif kind not in _PLAIN_OBJECTS:
            return f"object type {kind} is not supported"
    if users != 1:
        return "more than one force user function"
    return None


def _linear_parts(mbs: Any) -> tuple[tuple, np.ndarray, np.ndarray, np.ndarray]:
    """M (Exudyn's), K, D of the linear objects in one CSR pattern, their force vector, the
    force object's local-to-global indices and M dense."""
    import exudyn as exu

    from exudyn_turnout.corunning.track import simulation_settings

    n = len(mbs.systemData.GetODE2Coordinates())
    mass = np.asarray(mbs.ComputeLinearizedSystem(simulation_settings(1.0, 1.0))[0], float)
    stiffness, damping, force = np.zeros((n, n)), np.zeros((n, n)), np.zeros(n)
    ltg = None
    for i in range(mbs.systemData.NumberOfObjects()):
        item = mbs.GetObject(i)
        if item["objectType"] != "GenericODE2":
            continue
        index = _node_indices(mbs, list(item["nodeNumbers"]))
        if item["forceUserFunction"] != 0:
            ltg = index
        for name, target in (("stiffnessMatrix", stiffness), ("dampingMatrix", damping)):
            matrix = mbs.GetObjectParameter(i, name)
            if isinstance(matrix, exu.MatrixContainer):
                matrix = matrix.Convert2DenseMatrix()
            matrix = np.asarray(matrix, float)
            if matrix.size:
                target[np.ix_(index, index)] += matrix
        vector = np.asarray(mbs.GetObjectParameter(i, "forceVector"), float)
        if vector.size:
            force[index] += vector
    pattern = (mass != 0.0) | (stiffness != 0.0) | (damping != 0.0)
    rows, cols = np.nonzero(pattern)
    indptr = np.zeros(n + 1, dtype=np.int64)
    np.add.at(indptr, rows + 1, 1)
    indptr = np.cumsum(indptr)
    lin = (
        indptr,
        cols.astype(np.int64),
        mass[rows, cols].copy(),
        stiffness[rows, cols].copy(),
        damping[rows, cols].copy(),
    )
    assert ltg is not None
    return lin, force, ltg, mass


def _per_time(contacts: Any, times: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The compiled residual's per-time inputs at every time (body loads, bumpstop shift,
    irregularities: what ``CompiledResidual.prepare`` writes), as rows, and their (offset,
    length) segments in its float buffer."""
    compiled = contacts._compiled
    names = list(PACKED_NAMES)
    views = {
        "irregularity": compiled._irregularity,
        "body_loads": compiled._body_loads,
        "stop_shift": compiled._stop_shift,
    }
    varying = contacts.body_loads is not None or bool(compiled._irregular)
    segments = [
        (int(compiled._header[names.index(k), 0]), int(view.size))
        for k, view in views.items()
        if view.size
    ]
    if not varying or not segments:
        contacts._fast_at(float(times[0]))
        return np.zeros((0, 0)), np.zeros((0, 2), dtype=np.int64)
    fbuf = compiled._fbuf
    rows = np.zeros((len(times), sum(n for _, n in segments)))
    for k, t in enumerate(times):
        contacts._fast_at(float(t))
        rows[k] = np.concatenate([fbuf[o : o + n] for o, n in segments])
    contacts._fast_at(float(times[0]))
    return rows, np.array(segments, dtype=np.int64)


def _factors(
    jac: np.ndarray,
    state: np.ndarray,
    lin: tuple,
    consts: np.ndarray,
    user: tuple,
    work: np.ndarray,
    h: float,
) -> tuple:
    """The factor arrays of :func:`_factor`, with a fill-reducing order: reverse
    Cuthill-McKee of the pattern of J at the start (a quarter of the dense solve's work on
    the full vehicle: L and U 478 and 483 entries instead of 911 and 907)."""
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import reverse_cuthill_mckee

    norecord = np.zeros((1, 2))
    _jacobian(0.0, h, state[0], state[1], lin, consts, user, norecord, work[4], work[5], jac)
    pattern = csr_matrix((jac != 0.0) | (jac.T != 0.0))
    order = np.asarray(reverse_cuthill_mckee(pattern, symmetric_mode=True), dtype=np.int64)
    n = len(order)
    return (
        order,
        np.zeros((n, n)),
        np.zeros(n, dtype=np.int64),
        np.zeros(n + 1, dtype=np.int64),
        np.zeros(n * n, dtype=np.int64),
        np.zeros(n * n),
        np.zeros(n + 1, dtype=np.int64),
        np.zeros(n * n, dtype=np.int64),
        np.zeros(n * n),
    )


def integrate(
    mbs: Any,
    contacts: Any,
    end_time: float,
    steps: int,
    sensor_period: float,
    spectral_radius: float,
    absolute_tolerance: float,
    contractivity: float,
    progress: Callable[[float], None] | None = None,
    stop: Callable[[int, Callable[[], None]], bool] | None = None,
    stop_every: int = 1,
) -> StepperRun:
    """Run an assembled full-vehicle segment from its initial state (module docstring) and
    write the final state into Exudyn's current configuration.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        Assembled; :func:`unsupported` gives None for it.
    contacts : VehicleContacts
        Its force object's function (recording started if the run records).
    end_time : float
        s.
    steps : int
        Exudyn's ``numberOfSteps``.
    sensor_period : float
        s, Exudyn's sensor write period.
    spectral_radius : float
        Generalized-alpha's rho_inf.
    absolute_tolerance : float
        N, Newton's absolute tolerance on ||r||.
    contractivity : float
        Exudyn's ``modifiedNewtonContractivity``.
    progress : callable(t), optional
        Called with the time about every 2 % of the run.
    stop : callable(k, current) -> bool, optional
        Called before every ``stop_every``-th step k (k = 0, stop_every, ...; between
        compiled chunks, no Python call on the other steps), when the contacts' last
        evaluation is the step's start (the last accepted step's, at k = 0 the initial
        state's: what ``VehicleContacts.last_forces`` reads); ``current()`` writes that state
        into Exudyn's current configuration (for ``named_state``). False: the run ends after
        step k, as after an Exudyn pre-step function returning False.
    stop_every : int
        Steps between the calls of ``stop`` (>= 1).

    Returns
    -------
    StepperRun
        Ended early by ``stop``: the samples up to the end of its last step.
    """
    import exudyn as exu

    lin, force, ltg, mass = _linear_parts(mbs)
    times, sizes = step_times(end_time, steps)
    prep, segments = _per_time(contacts, times)
    compiled = contacts._compiled
    user = (ltg, compiled._fbuf, compiled._ibuf, compiled._header, *compiled._tables)
    data = mbs.systemData
    initial = exu.ConfigurationType.Initial
    q0 = np.asarray(data.GetODE2Coordinates(initial), float)
    v0 = np.asarray(data.GetODE2Coordinates_t(initial), float)
    current = exu.ConfigurationType.Current
    watch = None
    if stop is not None:

        def watch(k: int, state: np.ndarray) -> bool:
            def write() -> None:
                data.SetODE2Coordinates(state[0], current)
                data.SetODE2Coordinates_t(state[1], current)
                data.SetODE2Coordinates_tt(state[2], current)

            return stop(k, write)

    run, state = _run_steps(
        (lin, force, mass),
        user,
        compiled._record[0],
        (prep, segments),
        (q0, v0),
        (times, sizes, sample_rows(times, sizes, sensor_period)),
        np.array(
            [
                *alpha_constants(spectral_radius),
                absolute_tolerance,
                RELATIVE_TOLERANCE,
                contractivity,
            ]
        ),
        progress,
        (compiled._work, compiled._details),
        (watch, max(1, int(stop_every))),
    )
    data.SetODE2Coordinates(state[0], current)
    data.SetODE2Coordinates_t(state[1], current)
    data.SetODE2Coordinates_tt(state[2], current)
    return run


def integrate_linear(
    mass: np.ndarray,
    stiffness: np.ndarray,
    damping: np.ndarray,
    q0: np.ndarray,
    v0: np.ndarray,
    end_time: float,
    steps: int,
    spectral_radius: float,
    absolute_tolerance: float = 1e-10,
    stop: Callable[[int, np.ndarray], bool] | None = None,
    stop_every: int = 1,
) -> StepperRun:
    """The stepper on M q_tt + D q_t + K q = 0 (no force object): the scheme alone, for
    checks against Exudyn and closed forms.

    Parameters
    ----------
    mass, stiffness, damping : numpy.ndarray
        (n, n) in kg, N/m, N s/m (or consistent units).
    q0, v0 : numpy.ndarray
        Initial coordinates and velocities.
    end_time : float
        s.
    steps : int
        Number of steps (Exudyn's ``numberOfSteps``).
    spectral_radius : float
        Generalized-alpha's rho_inf.
    absolute_tolerance : float
        Newton's absolute tolerance (Exudyn's default 1e-10).
    stop : callable(k, q) -> bool, optional
        As :func:`integrate`'s, given the coordinates at step k's start (a copy).
    stop_every : int
        Steps between the calls of ``stop``.

    Returns
    -------
    StepperRun
        Every step sampled.
    """
    mass, stiffness, damping = (np.asarray(a, float) for a in (mass, stiffness, damping))
    n = len(mass)
    pattern = (mass != 0.0) | (stiffness != 0.0) | (damping != 0.0)
    rows, cols = np.nonzero(pattern)
    indptr = np.concatenate([[0], np.cumsum(np.bincount(rows, minlength=n))]).astype(np.int64)
    lin = (
        indptr,
        cols.astype(np.int64),
        mass[rows, cols].copy(),
        stiffness[rows, cols].copy(),
        damping[rows, cols].copy(),
    )
    user = (
        np.zeros(0, dtype=np.int64),
        np.zeros(1),
        np.zeros(1, dtype=np.int64),
        np.zeros((len(PACKED_NAMES), 4), dtype=np.int64),
        np.zeros(2),  # the packed contact tables' types (never read here)
        np.zeros(0, dtype=np.uint8),
        np.zeros(0),
    )
    times, sizes = step_times(end_time, steps)
    consts = np.array(
        [*alpha_constants(spectral_radius), absolute_tolerance, RELATIVE_TOLERANCE, 0.5]
    )
    run, _ = _run_steps(
        (lin, np.zeros(n), mass),
        user,
        np.zeros((1, 2)),
        (np.zeros((0, 0)), np.zeros((0, 2), dtype=np.int64)),
        (np.asarray(q0, float), np.asarray(v0, float)),
        (times, sizes, np.ones(len(times), dtype=bool)),
        consts,
        None,
        (np.zeros((1, 3, 1)), np.zeros((1, 1, 1))),
        (
            None if stop is None else (lambda k, state: stop(k, state[0].copy())),
            max(1, int(stop_every)),
        ),
    )
    return run


def _run_steps(
    system, user, record, per_time, start, clock, consts, progress, recorded, stop=(None, 1)
):
    """The run (:func:`integrate`, :func:`integrate_linear`): initial accelerations, then
    every step in chunks (``progress`` between them, and ``stop = (watch, every)``'s
    ``watch(k, state)`` before every every-th step k: False ends the run after step k); the
    run and its final state."""
    (lin, force, mass), (prep, segments), (times, sizes, stored) = system, per_time, clock
    n = len(force)
    state = np.zeros((4, n))
    state[0], state[1] = start
    work = np.zeros((8, n))
    norecord = np.zeros((1, 2))
    samples = int(stored.sum())
    out_q, out_v, out_a = (np.zeros((samples, n)) for _ in range(3))
    piv = np.zeros(n, dtype=np.int64)
    _prepare(0, user[1], prep, segments)
    jac = np.zeros((n, n))
    # the fill-reducing order first: the contacts' last evaluation before the first step is
    # then the initial state's (what a stop reads at k = 0, as in Exudyn's run)
    fac = _factors(jac, state, lin, consts, user, work, float(sizes[1]))
    if not _start(state, lin, force, user, norecord, work[4], work[6], mass.copy(), piv):
        raise RuntimeError("singular mass matrix")  # _run: a PassageFailure
    if record.shape[0] > 1:  # the start's contacts (a call at t = 0 left pending instead
        # was stored after the steps' rows by VehicleContacts.recorded: a rewind to t = 0
        # that gave the record up, the columns evaluated again after the run)
        record_kernel(0.0, recorded[0], recorded[1], record)
    out_q[0], out_v[0], out_a[0] = state[0], state[1], state[2]
    flags = np.array([1, 1], dtype=np.int64)
    counts = np.zeros(3, dtype=np.int64)
    counts[0] = 1
    total = len(times) - 1
    chunk = max(1, total // 50) if progress is not None else total
    watch, every = stop
    failed = -1
    k0, mark = 0, 0
    while k0 < total and failed < 0:
        if progress is not None and k0 >= mark:
            progress(float(times[k0]))
            mark = k0 + chunk
        k1 = min(mark if progress is not None else total, total)
        if watch is not None:
            if k0 % every == 0 and not watch(k0, state):
                k1 = total = k0 + 1  # the run ends after this step
            else:
                k1 = min(k1, (k0 // every + 1) * every)
        failed = _integrate(
            k0,
            k1,
            times,
            sizes,
            stored,
            state,
            work,
            lin,
            force,
            consts,
            user,
            record,
            norecord,
            recorded,
            prep,
            segments,
            jac,
            fac,
            flags,
            counts,
            out_q,
            out_v,
            out_a,
        )
        k0 = k1
    rows = int(flags[1])
    run = StepperRun(
        times[stored][:rows],
        out_q[:rows],
        out_v[:rows],
        out_a[:rows],
        total if failed < 0 else failed,
        int(counts[0]),
        int(counts[1]),
        int(counts[2]),
        math.nan if failed < 0 else float(times[failed + 1]),
    )
    return run, state
