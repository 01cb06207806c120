"""The full vehicle through the turnout, a co-running track under every wheelset (issue 13).

The vehicle of a :class:`~exudyn_turnout.inputs.vehicle_model.VehicleModel` (car body,
bogies, wheelsets; :func:`~exudyn_turnout.passage.vehicle.builder.add_vehicle_model`,
linear representation, wheelset spin free) runs at constant speed along a route. Every
wheelset has

- its own co-running track (``settings.layers``), evaluated at that wheelset's x and built
  with the parameters of the zone containing it;
- its own profile contact element: the same
  :class:`~exudyn_turnout.passage.contact.profile.ProfileContactElement` as the single
  wheelset's passage, given a Vehicle whose sprung mass ``m_s`` is 0 (the car body and the
  bogies get their own curving load here, so the element applies -m_w v^2 kappa to its
  wheelset only). The element's two sprung-mass coordinates sit on a decoupled dummy node
  (1 kg on 1e6 N/m) that stays at rest.

Track-following frame: every body's lateral coordinate and yaw are relative to the track
centreline and tangent at that body's own x. A vehicle whose suspension is unstrained in a
curve then has y_i = -e_i, psi_i = -theta_i, where e_i is the centreline's offset at x_i
from the tangent at the car body's x and theta_i the change of heading (both integrals of
the route's curvature): the suspension gets the extra force K q_geo (K its stiffness
matrix), which gives the wheelsets' geometric angle of attack in the bogie and the bogies'
offset under the car body. Car body and bogies get -m v^2 kappa(x) at their CoG
(d'Alembert in the track-following frame); while q_geo changes (entering a curve) the
suspension dampers see D q_geo_t as well, and every body's yaw the Euler load
-J v^2 dkappa/dx of the frame's changing yaw rate (car body and bogies in frames smoothed
over 0.5 m; :mod:`~exudyn_turnout.passage.vehicle.track_frame`). Left out: for the
wheelsets everything the single wheelset's element leaves out.

Zones: a wheelset's track and contact are in the zone containing its x. When any wheelset
crosses a zone boundary the system is rebuilt with the new zone for that wheelset and the
state carried over: vehicle bodies unchanged, that wheelset's track re-based as
``simulate._carry_over`` does (the old zone's static deflection under the current wheel
loads replaced by the new zone's, the dynamic part and velocities kept; the wheelset moved
with the static deflection under its wheels so that no wheel load jumps), the other
tracks copied. Wheelsets behind the turnout's x_min are on plain track: zone 1's parameters
and the contact at x clamped to x_min (the plain-track blend of zone 1 at its start is
plain track; the rail sections there are the plain rail). Likewise past x_max: the last
zone and the contact at x clamped to x_max (plain track in the packaged files), so the
front wheelset may run up to x_max plus the vehicle's length and the rear wheelsets pass
the whole turnout. A segment's system and the carry-over are
:mod:`~exudyn_turnout.passage.corunning_track.vehicle_system`'s.

The check rail (issue 22): a segment where a check-rail contact carries load
(:func:`~exudyn_turnout.passage.check_rail_steps.check_rail_window`) while the run's step is coarser
than ``settings.check_rail_time_step`` runs at the finer step (the segment's step over an
integer) from its start, or from where the check rail starts, to the load's end and a margin,
then at its own step
(:func:`~exudyn_turnout.passage.check_rail_steps.refine_pieces`), sampled at the
segment's grid times (:func:`~exudyn_turnout.passage.common.pick_rows`; the compiled
residual's record of every fine step is read at those times). Which segments: predicted
before the run
(:meth:`~exudyn_turnout.passage.check_rail_steps.CheckRailSteps.predict`: a wheelset on
the check rail's x range, displaced towards it by half its clearance at the segment's start),
those run at the fine step directly, the fine stepping ended during the run where the load
has ended (:class:`~exudyn_turnout.passage.check_rail_steps.CheckRailStop`: Exudyn's pre-step
function, or the compiled stepper's stop between its chunks at the grid times: on the diverging
route, 80 km/h, 20..55 m, 2 and 3 layers, the same windows and the summary's peaks within 2e-9 of
each other, relative; tests/test_stepper_stop.py). The after-the-fact check stays as a
safety net: a segment that loads its check rail where not predicted runs at its step first,
then again from its start as before (``summary["check_rail_rerun"]``). The progress never
goes back. ``summary["check_rail_refined"]`` gives the windows, ``check_rail_predicted`` the
predicted segments. The diverging route at 80 km/h, 2 layers, 20..55 m (measured before
issue 22's contact lead along x): the check-rail force 109.1 kN at 1e-4 s, 129.2 kN refined
over 44.29-47.50 m (128.1 / 126.5 kN at 2.5e-5 / 6.25e-6 s throughout), every column the
same as the after-the-fact method's to the bit up to the window's end and within 2e-9 of
its largest value after it, for 0.91x that method's CPU time (6 rounds alternating in fresh
processes, medians 1.90 -> 1.72 s). Since the lead along x: 87.9 kN at 1e-4 s, 86.3 kN
refined and at 6.25e-6 s throughout (validation/vehicle_step_convergence.md). The window's
end comes from the fine run's own samples, not from a run at 1e-4 s: on 44.29..45.6 m it
ends within one grid step (2.2 mm) of the after-the-fact method's. The through route's
check rail carries no load: its run is unchanged bit for bit.

Exudyn objects of the user functions (speed, issue 24): the four contact elements are one
ObjectGenericODE2 (one Python call per residual evaluation) with a forward-difference
Jacobian per wheelset (Exudyn's own steps, a block each instead of the whole object's
numerical one); the bumpstops ride on it (on q - q_geo), and in a curve the body loads
(K q_geo, D q_geo_t, curving loads; tabulated along the run) too. With the ``compiled``
track mechanism (the default) the four co-running tracks' springs ride on the contacts'
object too (their masses stay Exudyn bodies;
:mod:`~exudyn_turnout.corunning.track_kernel`), and at speed the object's whole residual
is one numba call (:class:`~exudyn_turnout.passage.contact.vehicle_kernel.CompiledResidual`).
The run uses Exudyn's sparse LU (EigenSparse): each track couples to its wheelset only. A
run's Newton tolerance is :data:`NEWTON_TOLERANCE_FACTOR` x :func:`newton_tolerance`.

Where a step's time goes (the README's case: through, 100 km/h, -5..60 m; measured with
``benchmarks/bench_vehicle_passage.py --phases``, Exudyn's solver timers and a numba loop
over 996 recorded states of the contacts' object; issue 24, on the 2-core machine at load
3-4, CPU time): 2.30 residual calls per step, one at the predictor and one after each of
1.30 Newton iterations (Exudyn's Newton never stops before its first iteration); Exudyn's
ODE2RHS, the residual evaluations with the user function, is 86 % of the stepping (its
Newton solves 5 %, the sensors 4 %). One evaluation, ~18 us, is ~8 us of Exudyn's own and
pybind11's (the objects' coordinates and forces, Exudyn's two 103-coordinate lists to
Python and the list back), ~2.5 us of Python (packing the lists into the kernel's buffer
~1.2 us, numba's dispatch of the eight arguments ~0.4 us, the returned list ~0.7 us) and
~7.5 us the numba residual: the four contacts ~4.5 us (of it the FASTSIM creep table ~2 us
for ~8 loaded contacts, the tables' geometry ~1.5 us), the track springs, their laws and
the bumpstops ~1 us, the packed views and the recording of each time's contacts the rest.
Issue 24 took out, bit for bit: a reshape per 2-D packed view (~20 ns, ~20 a call), the
interpolation of the empty candidate slots' other 21 fields, the recording at every call
(once per time now), a Python frame per call and the per-time generators; after the run
the safety checks' sliding means (one compiled loop, ~15x) and the body outputs' look-ups.
Measured alternately against 3273b6f (7 rounds, fresh processes, medians): CPU 1.38 ->
1.25 s (0.59 -> 0.53 x real time; stepping 1.12 -> 1.04 s, the rest 0.23 -> 0.17 s; at
load 4-5 with the 3-D views reshaped again 1.49 -> 1.31 s), the forces and summary
unchanged to the bit. What is left is mostly Exudyn's side of the call, out of this
package's reach (the compiled stepper, now the default, avoids it). A fresh Jacobian each
step would need 1.0 iterations, but one costs ~1-2 ms (its Exudyn side alone ~1 ms), and a
Jacobian every 200 steps (1.28 iterations, 132 Jacobians) about broke even; Newton's
relative tolerance at 1e-3 (2.23 calls per step) moved a lateral peak by 0.12 % (rejected).
The contacts'
forces and details of the output columns are recorded during the run
(:meth:`~exudyn_turnout.passage.contact.vehicle_contacts.VehicleContacts.start_record`),
not evaluated again after it.

By default (``settings.solver == "compiled"``, issue 24) every run segment steps with
:mod:`~exudyn_turnout.passage.corunning_track.stepper` instead of Exudyn's ``SolveDynamic``:
the same generalized-alpha scheme, modified Newton, tolerances and sensor samples, with the
compiled residual called from numba (no Python call per step). The same Newton iterations
and residual calls per step as Exudyn's; the README case costs ~35 % less in all (stepping
~2x faster; ``benchmarks/bench_stepper.py``), its wheel-force peaks within 0.013 %. A
segment with anything the stepper does not model
(:func:`~exudyn_turnout.passage.corunning_track.stepper.unsupported`: loads, e.g. the
curving loads when not folded into the contacts' object) runs in Exudyn as before;
``summary["stepping"]`` says what stepped the run and why not compiled
(:data:`STEPPING_KEY`). ``solver="exudyn"`` asks for Exudyn's integrator throughout.

The run starts in the steady state at speed (at rest in the track-following frame): first
the static equilibrium at rest (lateral position and spin held, as the single wheelset's),
then a static solve with the creep forces of speed v (spin held); where that fails (in a
curve: saturated creep) a dynamic relaxation with x frozen (:data:`RELAX_TIME` s at
:data:`~exudyn_turnout.passage.vehicle.start.RELAX_STEP` s, curving loads ramped up over
the first second, then 1 s chunks until
every body's velocity is below 1e-5 m/s) reaches it. ``summary["start"]`` says which, and
``summary["start_residual"]`` (N) what is left unbalanced: the static solve's tolerance
after it (the torque its spin holds release is in the start string), the bodies' largest
mass x lateral acceleration after the relaxation
(:mod:`~exudyn_turnout.passage.vehicle.start`, whose warning names a region reached before
the vehicle settled).
"""

from __future__ import annotations

import functools
import gc
import math
import time
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from exudyn_turnout.inputs.routes import Route
from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.inputs.vehicle import load_vehicle
from exudyn_turnout.inputs.vehicle_model import VehicleModel
from exudyn_turnout.passage.check_rail_steps import CheckRailSteps, CheckRailStop
from exudyn_turnout.passage.common import (
    QuietExudyn,
    join_segments,
    monotone_progress,
    newton_tolerance,
    progress_function,
)
from exudyn_turnout.passage.contact.profile import STATIC_SPIN_STIFFNESS, RouteContact
from exudyn_turnout.passage.contact.vehicle_contacts import wheelset_columns
from exudyn_turnout.passage.corunning_track.carry_over import set_named_state
from exudyn_turnout.passage.corunning_track.relax import relax_frozen
from exudyn_turnout.passage.corunning_track.vehicle_system import (
    VARIABLES_KEY,
    SegmentSystem,
    WheelsetPlace,
    build_segment,
    carry_over_state,
    element_vector,
    named_state,
    place_of,
)
from exudyn_turnout.passage.results import PassageResult
from exudyn_turnout.passage.safety import limits_for_friction
from exudyn_turnout.passage.settings import PassageFailure, PassageSettings
from exudyn_turnout.passage.summary import check_plausible, vehicle_summary
from exudyn_turnout.passage.vehicle.body_sensors import recorded_body_columns
from exudyn_turnout.passage.vehicle.start import (
    record_start,
    steady_description,
)
from exudyn_turnout.passage.vehicle.track_frame import contact_vehicle

__all__ = ["simulate_vehicle", "NEWTON_TOLERANCE_FACTOR", "STEPPER_KEY", "STEPPING_KEY"]

#: ``mbs.variables`` key of a segment's compiled run (its
#: :class:`~exudyn_turnout.passage.corunning_track.stepper.StepperRun`: samples, statistics)
STEPPER_KEY = "exudyn_turnout.corunning_track.stepper"
#: ``mbs.variables`` key of what stepped a segment: "compiled", "exudyn" (asked for) or
#: "exudyn (compiled stepper: <why not>)" (the fallback;
#: :func:`~exudyn_turnout.passage.corunning_track.stepper.unsupported`)
STEPPING_KEY = "exudyn_turnout.corunning_track.stepping"
#: s, first part of the dynamic relaxation to the steady state at speed (where the static
#: solve fails, e.g. in a curve): the car body's lateral mode (~0.7 Hz, damping ratio ~0.45)
#: settles in it; a slower drift does not (the car body still moved at 1.4 mm/s after 8 s in
#: the 760 m curve at 80 km/h), so the relaxation goes on in chunks until settled
#: (:mod:`~exudyn_turnout.passage.vehicle.start`: 18 s there, residual 3 N)
RELAX_TIME = 8.0
#: N, the static solves' Newton tolerance (the start residual after the solve at speed)
STATIC_TOLERANCE = 1e-4
#: Newton's absolute residual tolerance of a run in units of the passage's
#: (:func:`~exudyn_turnout.passage.common.newton_tolerance`: 2 N for four wheelsets, so 5 N).
#: Exudyn's Newton always takes one iteration; a second one is needed where the kept
#: Jacobian leaves more than the tolerance after it. Measured against 1 (issue 24, README
#: case: through, 100 km/h, 3 layers, -5..60 m): Newton iterations per step 1.48 -> 1.30,
#: residual calls per step 2.48 -> 2.30; the 224 per-wheelset peaks of the summary (Fz, Fy
#: per wheel at switch and crossing, ...) of the through route at 100 km/h and the diverging
#: route at 80 km/h (check rail), 2 and 3 layers, within 0.058 % (Fz, Fy; the largest a
#: lateral peak at the switch), their positions within 6 mm. 5.0 (10 N) moved a lateral peak
#: by 0.11 %.
NEWTON_TOLERANCE_FACTOR = 2.5
#: Exudyn's ``modifiedNewtonContractivity`` in a run: the Jacobian is recomputed when a
#: Newton iteration reduces the residual by less than this factor (Exudyn's default 0.5).
#: Where contact points move fast (switch, crossing) the kept Jacobian converges slowly;
#: the contact Jacobian is cheap (~1 ms): recomputing it sooner saves iterations
#: (benchmarks/bench_vehicle_passage.py: Newton iterations per step).
_NEWTON_CONTRACTIVITY = 0.1


def _solve_static(system: SegmentSystem, what: str, load_steps: int = 1) -> None:
    import exudyn as exu

    from exudyn_turnout.corunning.track import simulation_settings

    sim = simulation_settings(1.0, 1.0)
    sim.staticSolver.numberOfLoadSteps = load_steps
    sim.staticSolver.newton.absoluteTolerance = STATIC_TOLERANCE
    sim.staticSolver.newton.maxIterations = 50
    try:
        system.mbs.SolveStatic(sim, updateInitialValues=True)
    except (exu.SolverError, RuntimeError) as err:
        raise PassageFailure(
            f"{what} not found with the front wheelset at x = {system.x_front:g} m: {err}"
        ) from None


def _relax(system: SegmentSystem, model: VehicleModel) -> tuple[float, float]:
    """Relax with x frozen (the curving loads ramped up over the first second) until the
    vehicle is at rest in the track-following frame: the steady state at speed
    (:func:`~exudyn_turnout.passage.corunning_track.relax.relax_frozen`: :data:`RELAX_TIME`
    s first, then chunks). Return the residual (N: the largest mass x lateral acceleration
    left on a body) and the time relaxed (s)."""
    loads = system.body_loads
    sizes = np.diff(np.append(loads.starts, loads.n))
    lateral, moving = [], []  #: (index, mass) of each body's y; indices of its coordinates
    for name, start, i_y, size in zip(loads.names, loads.starts, loads.i_y, sizes):
        if name == "car_body" and model.car_body is not None:
            mass = model.car_body.mass
        elif name.startswith("bogie") and model.bogie is not None:
            mass = model.bogie.mass
        else:
            mass = model.wheelset.mass
        i = system.mbs.GetNodeODE2Index(system.names[name])
        lateral.append((i + int(i_y - start), mass))
        spin = 4 if name.startswith("ws") else -1  # the element's beta: its rate is steady
        moving += [i + k for k in range(int(size)) if k != spin]
    where = f"with the front wheelset at x = {system.x_front:g} m"
    return relax_frozen(system.mbs, moving, lateral, where, first=RELAX_TIME, carry_time=True)


def _held_spin_torque(system: SegmentSystem) -> float:
    """N m: the largest torque the static solve's spin holds carry (what the run releases)."""
    torque = 0.0
    for i in range(len(system.elements)):
        beta = system.mbs.GetNodeOutput(system.names[f"ws{i + 1}"], _coordinates())
        torque = max(torque, STATIC_SPIN_STIFFNESS * abs(float(np.atleast_1d(beta)[4])))
    return torque


def _coordinates():
    import exudyn as exu

    return exu.OutputVariableType.Coordinates


def _run(
    system: SegmentSystem,
    duration: float,
    settings: PassageSettings,
    t_offset: float,
    total: float,
    progress: Callable | None,
    static_load: float,
    stop: CheckRailStop | None = None,
) -> dict[str, np.ndarray]:
    """Run a built segment for ``duration`` seconds (the compiled stepper or Exudyn's
    ``SolveDynamic``) and return its columns; ``stop`` (the predicted check rail's fine
    piece, ``CheckRailSteps.run_predicted``: Exudyn's pre-step function, or the stepper's
    stop at the grid times) may end the run early."""
    import exudyn as exu

    from exudyn_turnout.corunning.track import simulation_settings

    h = settings.time_step
    sim = simulation_settings(duration, h, 0.999 * (settings.output_step or h))
    sim.timeIntegration.numberOfSteps = max(1, int(math.ceil(duration / h - 1e-9)))
    sim.timeIntegration.generalizedAlpha.spectralRadius = settings.spectral_radius
    sim.timeIntegration.newton.absoluteTolerance = NEWTON_TOLERANCE_FACTOR * newton_tolerance(
        len(system.elements)
    )
    sim.timeIntegration.newton.modifiedNewtonContractivity = _NEWTON_CONTRACTIVITY
    # sparse LU: each track couples to its wheelset only (measured on the full vehicle's
    # through passage: Exudyn's own share of the run -35 %, the run -18 %)
    sim.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    v = settings.v
    contacts = system.mbs.variables[VARIABLES_KEY][0]
    reason: str | None = "not asked for"
    if settings.solver == "compiled":
        from exudyn_turnout.passage.corunning_track import stepper

        reason = stepper.unsupported(system.mbs, contacts)
    system.mbs.variables[STEPPING_KEY] = (
        "compiled"
        if reason is None
        else "exudyn"
        if settings.solver == "exudyn"
        else f"exudyn (compiled stepper: {reason})"
    )
    report = None
    if progress is not None:
        report = progress_function(progress, t_offset, total, system.x_front, v)
    pre_step = report
    at_grid: Callable[[int, Callable[[], None]], bool] | None = None
    if stop is not None:
        watch, force = stop, _check_force(system, contacts, stop.pairs)
        state = functools.partial(named_state, system)

        def pre_step(mbs, t):
            if report is not None:
                report(mbs, t)
            return watch(force, state)

        def grid_watch(k: int, current: Callable[[], None]) -> bool:
            """The compiled stepper's stop: called before the fine steps at the grid times
            only (k: the fine step's index), ``current`` writes its state into Exudyn's."""

            def state_at() -> Any:
                current()
                return named_state(system)

            return watch(force, state_at, k)

        at_grid = grid_watch

    if pre_step is not None and reason is not None:
        system.mbs.SetPreStepUserFunction(pre_step)
    # no garbage collection while stepping: the residual calls allocate lists of floats only
    # (no reference cycles), yet every ~700 of them started a collection (3 % of a run)
    collecting = gc.isenabled()
    gc.disable()
    # the contacts' forces and details of every step, recorded by the compiled residual at
    # Newton's last call of each time: the output columns without evaluating them again
    contacts.start_record(int(sim.timeIntegration.numberOfSteps) + 1)
    stored_data = system.mbs.GetSensorStoredData
    try:
        if reason is None:  # the compiled stepper (settings.solver == "compiled")
            run = stepper.integrate(
                system.mbs,
                contacts,
                duration,
                int(sim.timeIntegration.numberOfSteps),
                sim.solution.sensors.writePeriod,
                settings.spectral_radius,
                sim.timeIntegration.newton.absoluteTolerance,
                _NEWTON_CONTRACTIVITY,
                None if report is None else functools.partial(report, system.mbs),
                at_grid,
                1 if stop is None else stop.m,
            )
            system.mbs.variables[STEPPER_KEY] = run
            if not math.isnan(run.failed_at):
                raise PassageFailure(
                    f"solver failed at t = {t_offset + run.failed_at:.5f} s, front wheelset "
                    f"at x = {system.x_front + v * run.failed_at:.3f} m: Newton did not "
                    "converge (compiled stepper)"
                )
            stored_data = functools.partial(run.sensor_data, system.mbs)
        else:
            system.mbs.SolveDynamic(sim)
    except (exu.SolverError, RuntimeError) as err:
        t = system.mbs.systemData.GetTime()
        raise PassageFailure(
            f"solver failed at t = {t_offset + t:.5f} s, front wheelset at x = "
            f"{system.x_front + v * t:.3f} m: {str(err).strip()}"
        ) from None
    finally:
        if collecting:
            gc.enable()
    cols: dict[str, np.ndarray] = {}
    times = np.asarray(stored_data(system.sensors[0][0][0]))[:, 0]
    recorded = contacts.recorded(times)
    for i, (element, (pos, vel)) in enumerate(zip(system.elements, system.sensors)):
        stored = [stored_data(s) for s in pos]
        stored_t = [stored_data(s) for s in vel]
        t = stored[0][:, 0]
        zeros = np.zeros((len(t), 2))
        q = np.hstack([stored[0][:, 1:], zeros] + [a[:, 1:] for a in stored[1:]])
        q_t = np.hstack([stored_t[0][:, 1:], zeros] + [a[:, 1:] for a in stored_t[1:]])
        if not (np.all(np.isfinite(q)) and np.all(np.isfinite(q_t))):
            bad = t[~np.all(np.isfinite(q), axis=1)][0]
            raise PassageFailure(
                f"solution diverged at t = {t_offset + bad:.5f} s, front wheelset at x = "
                f"{system.x_front + v * bad:.3f} m: reduce the time step"
            )
        label = f"ws{i + 1}"
        x_i = system.x_front + _offset_of(system, i) + v * t
        element_columns = (
            element.columns(t, q, q_t) if recorded is None else element.columns_of(*recorded[i])
        )
        if i == 0:
            cols["t_s"], cols["x_m"] = t + t_offset, system.x_front + v * t
            cols.update(element_columns)
            for k, name in enumerate(
                ("y_wheelset_m", "z_wheelset_m", "roll_wheelset_rad", "yaw_wheelset_rad")
            ):
                cols[name] = q[:, k]
            for j, slot in enumerate(system.slots[0]):
                base = element.n_vehicle + 2 * j
                cols[f"y_rail_{slot}_m"], cols[f"z_rail_{slot}_m"] = q[:, base], q[:, base + 1]
        own = wheelset_columns(element, t, q, q_t, label, element_columns)
        own[f"x_{label}_m"] = x_i
        plausible = {
            "t_s": t + t_offset,
            "x_m": x_i,
            "y_wheelset_m": q[:, 0],
            "z_wheelset_m": q[:, 1],
            "Fz_right_N": own[f"Fz_{label}_right_N"],
            "Fz_left_N": own[f"Fz_{label}_left_N"],
            "Fy_right_N": own[f"Fy_{label}_right_N"],
            "Fy_left_N": own[f"Fy_{label}_left_N"],
        }
        for j, slot in enumerate(system.slots[i]):
            plausible[f"z_rail_{slot}_m"] = q[:, element.n_vehicle + 2 * j + 1]
        mu = element.vehicle.contact.mu
        check_plausible(plausible, static_load, f"wheelset {i + 1}", limits_for_friction(mu))
        cols.update(own)
    cols.update(recorded_body_columns(system.mbs, cols["t_s"] - t_offset, stored_data))
    return cols


def _lateral(state: Mapping, wheelsets: int) -> list[float]:
    """m, every wheelset's lateral displacement y in a named state."""
    return [float(state[f"ws{i + 1}"][0][0]) for i in range(wheelsets)]


def _check_force(
    system: SegmentSystem, contacts: Any, pairs: tuple[tuple[str, str], ...]
) -> Callable[[], float | None]:
    """A function giving the check rails' largest contact force (N, |(Fy, Fz)| of each
    wheelset's check-rail contact, as ``check_rail_window`` takes it from the columns) at
    the contacts' last evaluation."""
    picks = []  #: per element and check pair: (element index, y indices, z indices)
    for k, element in enumerate(system.elements):
        for wheel, slot in pairs:
            seen = {
                (b.i_y, b.i_z)
                for b in element.bodies
                if b.rail == slot and element.wheel_of.get(slot) == wheel
            }
            if seen:
                iy, iz = zip(*sorted(seen))
                picks.append((k, np.array(iy), np.array(iz)))

    def force() -> float | None:
        forces = contacts.last_forces()
        if forces is None:
            return None
        largest = 0.0
        for k, iy, iz in picks:
            f = forces[k]
            largest = max(largest, math.hypot(float(f[iy].sum()), float(f[iz].sum())))
        return largest

    return force


def _offset_of(system: SegmentSystem, i: int) -> float:
    """Longitudinal offset (m) of wheelset i (0-based) behind the front one (<= 0)."""
    return system.elements[i].x0 - system.x_front


def _events(turnout: Turnout, offsets: tuple[float, ...], x_a: float, x_b: float) -> list[float]:
    """Front positions where any wheelset crosses x_min, a zone boundary or x_max, with x_a
    and x_b."""
    bounds = [turnout.x_min] + [z.x_start for z in turnout.zones[1:]] + [turnout.x_max]
    xs = {x_a, x_b}
    for o in offsets:
        for b in bounds:
            if x_a + 1e-9 < b - o < x_b - 1e-9:
                xs.add(b - o)
    return sorted(xs)


def simulate_vehicle(
    turnout: Turnout,
    settings: PassageSettings,
    model: VehicleModel,
    contact: RouteContact,
    route: Route,
    x_range: tuple[float, float],
    progress: Callable[[float, float], None] | None = None,
    options: None = None,
) -> PassageResult:
    """Run the full vehicle through the turnout, a co-running track under every wheelset
    (module docstring); the door is :func:`exudyn_turnout.passage.run.simulate_passage`,
    which checks the settings first.

    Parameters
    ----------
    turnout : Turnout
    settings : PassageSettings
        Route, speed, layers, source, time step, output step, spring mechanism.
    model : VehicleModel
        A full vehicle (car body, bogies).
    contact : RouteContact
        The route's profile contact, made for the single-wheelset file's contact law and
        wheel profile.
    route : Route
        ``settings.route`` of the turnout.
    x_range : tuple of float
        m, the front wheelset's start and end (checked).
    progress : callable(fraction, x), optional
        Called about every 2 % of each segment's run.
    options : None
        The co-running track has no options (the FE track's interface has them).

    Returns
    -------
    PassageResult
        Columns: ``t_s``, ``x_m`` (front wheelset), per wheelset k = 1..n ``Fz_wsk_<wheel>_N``,
        ``Fy_wsk_<wheel>_N`` (per rail slot too), ``x_wsk_m``, ``y_wsk_m``, ``z_wsk_m``,
        ``roll_wsk_rad``, ``yaw_wsk_rad``; the front wheelset also under the single-wheelset
        names (``Fz_right_N``, contact points, ``y_wheelset_m``, ``z_rail_<slot>_m``...).
        Summary: :func:`~exudyn_turnout.passage.summary.passage_summary` of the front
        wheelset, plus per wheelset ``peak_<Fz|Fy>_<region>_wsk_<wheel>_N`` (region by that
        wheelset's own x) and ``static_wheel_load_wsk_<wheel>_N``.

    Raises
    ------
    PassageFailure
        A solver failure (time and position).
    """
    del options
    wall = time.perf_counter()
    x_a, x_b = x_range
    with QuietExudyn():
        return _simulate(turnout, settings, model, contact, route, x_a, x_b, progress, wall)


def _simulate(turnout, settings, model, contact, route, x_a, x_b, progress, wall):
    vehicle = contact_vehicle(load_vehicle(), model)
    offsets = tuple(model.wheelset.x)
    events = _events(turnout, offsets, x_a, x_b)
    x_range = (x_a + min(offsets), x_b)
    v = settings.v

    def places(x_lo: float, x_hi: float) -> tuple[WheelsetPlace, ...]:
        return tuple(place_of(turnout, 0.5 * (x_lo + x_hi) + o) for o in offsets)

    first = places(events[0], events[1])
    parameters: dict = {}  # every zone's co-running parameters, shared by the builds
    build = functools.partial(build_segment, parameters=parameters)
    args = (turnout, route, model, vehicle, contact, settings)
    rest = build(*args, first, x_a, 0.0, True, x_range)
    _solve_static(rest, "static equilibrium at rest")
    state = named_state(rest)
    static_loads = [
        el.wheel_loads(el.x_at(0.0), element_vector(rest, state, i, 0))
        for i, el in enumerate(rest.elements)
    ]
    moving = build(*args, first, x_a, v, True, x_range)
    set_named_state(moving.mbs, moving.names, state)  # the rest state has K q_geo balanced already
    curvature = max(abs(float(route.curvature(x_a + o))) for o in offsets)
    start = steady_description(settings.speed_kmh, curvature)
    try:
        for el in moving.elements:
            el.hold_spin = True
        _solve_static(moving, "steady state at speed", 10)
        # converged: the lateral forces balance within the solve's tolerance (the spin
        # holds' torque is released in ~1 ms: spin inertia over the creep's damping)
        residual = STATIC_TOLERANCE
        start += f" (static solve, spin holds release {_held_spin_torque(moving):.3g} N m)"
    except PassageFailure:  # e.g. in a curve: relax dynamically with x frozen
        moving = build(*args, first, x_a, v, True, x_range)
        set_named_state(moving.mbs, moving.names, state)
        residual, relaxed = _relax(moving, model)
        start += f" (relaxed {relaxed:g} s with x frozen)"
    state, previous = named_state(moving), moving
    t_prev = 0.0
    segments, t_offset, total = [], 0.0, (x_b - x_a) / v
    starts = []
    tables: dict = {}  # the running loads' table, shared by the segments
    check = CheckRailSteps(settings, route, model.static_wheel_load, len(offsets))
    stepping: set[str] = set()  # what stepped the segments (STEPPING_KEY)
    progress = monotone_progress(progress)  # a segment run again reports its times again
    load = model.static_wheel_load
    for k in range(len(events) - 1):
        x0, x1 = events[k], events[k + 1]
        at = places(x0, x1)
        duration = (x1 - x0) / v
        #: the pieces' start states by their start time (s from the segment's start): a
        #: piece run again starts where it started before, a new one where the last ended
        begun: dict[float, list] = {}
        carried = [state, previous, t_prev]

        def run_piece(t_from, length, x_p, step_settings, stop=None, at=at, t0=t_offset,
                      carried=carried, begun=begun):  # fmt: skip
            origin = begun.setdefault(t_from, list(carried))
            system = build(*args, at, x_p, v, False, x_range, tables)
            carry_over_state(*origin[:2], system, route, settings.layers, x_p, origin[2])
            piece = _run(system, length, step_settings, t0 + t_from, total, progress, load, stop)
            stepping.add(system.mbs.variables[STEPPING_KEY])
            if stop is not None and stop.state is not None:  # the fine piece ends at stop.end
                carried[:] = [stop.state, system, (stop.end - stop.first) * stop.h]
            else:
                carried[:] = [named_state(system), system, length]
            return piece

        # predicted to load a check rail: the fine step directly, ended where the load has
        # ended (CheckRailStop: Exudyn's pre-step function or the compiled stepper's stop)
        fine_from = check.predict(x0, x1, offsets, _lateral(state, len(offsets)))
        if fine_from is not None:
            cols, t_prev = check.run_predicted(duration, t_offset, x0, fine_from, run_piece)
            system = carried[1]
        else:
            cols = run_piece(0.0, duration, x0, settings)
            system = carried[1]
            window = check.window(cols)
            if window is not None and check.step is not None:  # again, the window finer
                cols, t_prev = check.rerun_unpredicted(
                    cols, window, duration, t_offset, x0, run_piece
                )
                system = carried[1]
            else:
                if window is not None:
                    check.unrefined(window, cols)
                t_prev = duration
        segments.append(cols if k == 0 else {n: c[1:] for n, c in cols.items()})
        starts.append(x0)
        state, previous = named_state(system), system
        t_offset += duration
    columns = join_segments(segments)
    summary = vehicle_summary(
        turnout,
        settings,
        model,
        columns,
        static_loads,
        wall,
        limits_for_friction(vehicle.contact.mu),
    )
    record_start(summary, turnout, x_a, v, start, residual, stacklevel=4)
    check.record(summary, stacklevel=4)
    summary["stepping"] = "; ".join(sorted(stepping))
    return PassageResult(settings, columns, summary, tuple(starts))
