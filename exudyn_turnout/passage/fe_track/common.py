"""What the wheelset's and the full vehicle's passages on the FE track share: a wheelset's
FE contact element, the coupled run's settings, failure reasons, output columns and the
summary of the FE track."""

from __future__ import annotations

import warnings
from dataclasses import asdict

import numpy as np

from exudyn_turnout.inputs.routes import Route
from exudyn_turnout.inputs.vehicle import Vehicle
from exudyn_turnout.passage.common import CheckRailSteps
from exudyn_turnout.passage.fe_track.coupling import COUPLING_STALL_TOLERANCE
from exudyn_turnout.passage.fe_track.planes import generalized_alpha
from exudyn_turnout.passage.settings import DEFAULT_SETTINGS, PassageError, PassageSettings

__all__ = [
    "fe_contact_element",
    "coupled_run_settings",
    "failure_reason",
    "fe_columns",
    "fe_summary",
    "check_rail_steps",
]


def fe_contact_element(route_contact, vehicle: Vehicle, route: Route, x0: float, v: float, irr):
    """The profile contact element with one (y, z) coordinate pair per rail body of the route.

    Parameters
    ----------
    route_contact : RouteContact
        The route's rail bodies and tables
        (:func:`~exudyn_turnout.passage.contact.profile.route_contact`).
    vehicle : Vehicle
    route : Route
    x0, v : float
        m, m/s: position at t = 0 and speed (0: static).
    irr : Irregularity or None

    Returns
    -------
    ProfileContactElement

    Raises
    ------
    PassageError
        Both wheels touch one rail slot.
    """
    from exudyn_turnout.passage.contact.profile import N_VEHICLE_COORDINATES, ProfileContactElement

    n_bodies = route_contact.tables.n_bodies
    for slot in set(route_contact.rails):
        wheels = {w for w, r in zip(route_contact.wheels, route_contact.rails) if r == slot}
        if len(wheels) > 1:
            raise PassageError(f"route {route.name}: rail {slot} is touched by both wheels")
    coordinates = [
        (N_VEHICLE_COORDINATES + 2 * k, N_VEHICLE_COORDINATES + 2 * k + 1) for k in range(n_bodies)
    ]
    return ProfileContactElement(
        vehicle,
        route,
        route_contact.tables.select(range(n_bodies), coordinates),
        list(zip(route_contact.wheels, route_contact.rails)),
        x0,
        v,
        irr,
    )


def coupled_run_settings(duration: float, n_steps: int, settings: PassageSettings, tolerance):
    """Exudyn's settings of a run coupled to the FE track: fixed steps, the run's rho_inf.

    Parameters
    ----------
    duration : float
        s.
    n_steps : int
        Steps (the FE side's h = duration / n_steps: no adaptive step).
    settings : PassageSettings
        ``spectral_radius``.
    tolerance : float
        N, Newton's absolute tolerance.

    Returns
    -------
    exudyn.SimulationSettings
    """
    from exudyn_turnout.corunning.track import simulation_settings

    sim = simulation_settings(duration, duration / n_steps)
    sim.timeIntegration.numberOfSteps = n_steps
    sim.timeIntegration.generalizedAlpha.spectralRadius = settings.spectral_radius
    sim.timeIntegration.newton.absoluteTolerance = tolerance
    sim.timeIntegration.adaptiveStep = False
    return sim


def failure_reason(err: Exception) -> str:
    """The one line of an Exudyn error that says what went wrong (a user function's own).

    Parameters
    ----------
    err : Exception

    Returns
    -------
    str
    """
    lines = [line.strip() for line in str(err).splitlines() if line.strip()]
    for line in lines:
        if line.startswith(("RuntimeError:", "ArithmeticError:", "ValueError:")):
            return line.split(":", 1)[1].strip()
    return lines[0] if lines else type(err).__name__


def fe_columns(element, t, q, q_t, x0: float, v: float) -> dict[str, np.ndarray]:
    """Output columns: the co-running passage's names, rail columns per slot from the FE.

    ``t``: sample times (s); ``q``, ``q_t``: the element's full coordinates per sample.

    Parameters
    ----------
    element : ProfileContactElement
        The wheelset's FE contact element.
    t : numpy.ndarray
        s.
    q, q_t : numpy.ndarray
        Stored element coordinates and velocities (samples x n).
    x0, v : float
        m, m/s.

    Returns
    -------
    dict
    """
    t, q, q_t = np.asarray(t, float), np.asarray(q, float), np.asarray(q_t, float)
    cols: dict[str, np.ndarray] = {"t_s": t, "x_m": x0 + v * t}
    cols.update(element.columns(t, q, q_t))
    names = ("y_wheelset_m", "z_wheelset_m", "roll_wheelset_rad", "yaw_wheelset_rad")
    for i, name in enumerate(names + ("spin_wheelset_rad",)):
        cols[name] = q[:, i]
    x = cols["x_m"]
    bounds = element.tables.bounds
    for slot in dict.fromkeys(b.rail for b in element.bodies):
        y, z = np.full(len(t), np.nan), np.full(len(t), np.nan)
        for k, b in enumerate(element.bodies):
            if b.rail != slot:
                continue
            inside = (x >= bounds[k, 2] - 1e-9) & (x <= bounds[k, 3] + 1e-9) & np.isnan(y)
            y[inside], z[inside] = q[inside, b.i_y], q[inside, b.i_z]
        cols[f"y_rail_{slot}_m"], cols[f"z_rail_{slot}_m"] = y, z
    return cols


def fe_summary(planes, settings, track, h, n_steps, static_s, steps_s) -> dict[str, object]:
    """What the summary of an FE passage adds: the FE model, its integrator, the costs.

    Parameters
    ----------
    planes : FETrackPlanes
    settings : PassageSettings
    track : FECoSimulation
    h : float
        s, time step.
    n_steps : int
    static_s, steps_s : float
        s, wall time of the static solve and of the steps.

    Returns
    -------
    dict
    """
    ga = generalized_alpha(settings.spectral_radius)
    all_settings = asdict(settings)
    not_fe = ("layers", "source", "track_mechanism")
    parts = dict(track.timings, build=planes.build_s, static=static_s, steps=steps_s)
    if track.stalls[0]:
        warnings.warn(
            f"FE coupling stalled on a kink of the contact forces in {track.stalls[0]} step(s); "
            f"accepted with residuals up to {track.stalls[1]:.2g} m (limit "
            f"{COUPLING_STALL_TOLERANCE:g} m, summary['coupling_stalls'])",
            RuntimeWarning,
            stacklevel=2,
        )
    return {
        "settings": {k: val for k, val in all_settings.items() if k not in not_fe},
        "model": "FE",
        "layers": None,
        "source": "Table 1 (FE model)",
        "lateral": "FE lateral plane with rail torsion (roll and warping)"
        if planes.lateral.torsion is not None
        else "FE lateral plane, bending only",
        "n_dof": planes.vertical.n_dof + planes.lateral.n_dof,
        "n_dof_vertical": planes.vertical.n_dof,
        "n_dof_lateral": planes.lateral.n_dof,
        "time_integration": (
            f"generalized-alpha (Exudyn's), rho_inf {settings.spectral_radius:g}: alpha_m = "
            f"{ga.alpha_m:.4f}, alpha_f = {ga.alpha_f:.4f}, beta = {ga.beta:.4f}, gamma = "
            f"{ga.gamma:.4f}; FE track co-simulated with exact one-step coupling"
        ),
        "time_step_s": float(h),
        "n_steps": int(n_steps),
        "fe_options": asdict(planes.vertical.mesh.options),
        "fe_window": (
            "whole model"
            if track.window is None
            else (
                f"{track.window.window_length:g} m about each wheelset, cut every "
                f"{track.window.window_shift:g} m ({track.window_cuts} cuts, "
                f"{min(track.window_dofs)}-{max(track.window_dofs)} DOFs), absorbing ends "
                f"{track.window.window_absorbing_length:g} m to loss factor "
                f"{track.window.window_eta_max:g}"
            )
        ),
        "wall_time_parts_s": {k.removesuffix("_s"): float(t) for k, t in parts.items()},
        "coupling_stalls": {
            "count": int(track.stalls[0]),
            "largest_residual_m": float(track.stalls[1]),
        },
    }


def check_rail_steps(
    settings: PassageSettings,
    route: Route,
    static_wheel_load: float,
    columns: dict,
    summary: dict,
    wheelsets: int = 0,
    stacklevel: int = 2,
) -> None:
    """Record the check rail's step in an FE passage's summary, and warn where a check-rail
    contact carried load at a step coarser than ``settings.check_rail_time_step``.

    The FE track steps its whole run (its planes' integrators included) at one step, so a
    loaded window is not run again finer as on the co-running track
    (:class:`~exudyn_turnout.passage.common.CheckRailSteps`): on the diverging route at
    80 km/h the single wheelset's check-rail force is 48.6 / 62.9 / 63.8 kN at 1e-4 / 5e-5
    / 2.5e-5 s (24 % low at the default step), so it says so
    (:class:`~exudyn_turnout.passage.common.CheckRailStepWarning`, summary key
    ``check_rail_step_warning``).

    Parameters
    ----------
    settings : PassageSettings
    route : Route
    static_wheel_load : float
        N.
    columns : dict
        The run's columns.
    summary : dict
        Its summary (changed in place).
    wheelsets : int
        0: the single wheelset; n: the full vehicle's n wheelsets.
    stacklevel : int
        Of the warning, counted from the caller of this function.
    """
    limit = settings.check_rail_time_step or DEFAULT_SETTINGS.check_rail_time_step
    where = f"the FE track steps its whole run at one step: give it --time-step <= {limit:g} s"
    check = CheckRailSteps(settings, route, static_wheel_load, wheelsets, where)
    window = check.window(columns)
    if window is not None:
        check.unrefined(window, columns)
    check.record(summary, stacklevel + 1)
