"""Hunting stability of the full vehicle on straight rigid plain track (issue 13).

The vehicle of a :class:`~exudyn_turnout.inputs.vehicle_model.VehicleModel` (car body,
bogies, wheelsets; :func:`~exudyn_turnout.passage.vehicle.builder.add_vehicle_model`,
linear representation, wheelset spin free, lateral bumpstops) runs at constant speed v on
straight, rigid plain track: the plain rail section of the turnout's route at its start
x_min (UIC60 1:40 in the packaged turnout), constant along x. Every wheel is in contact
with it through the package's profile contact
(:class:`~exudyn_turnout.passage.contact.profile.ProfileContactElement`: contact points
from the S1002/UIC60 tables, the node's normal law per point (Hertz where its ellipse fits
the surfaces, else Kik-Piotrowski), FASTSIM's creep forces with
spin from the kernel's creep table, or Polach's: :data:`CREEP_LAWS`), the rails held fixed
(rigid track). The run starts from the steady state at speed (the symmetric static
equilibrium, the wheelsets spinning at free rolling, xi = 0) with a lateral
offset of the leading wheelset (or of all), and the lateral motion of the wheelsets is
measured: :func:`decay_analysis` fits the decay rate of its extrema, their amplitude
ratio per cycle and the frequency. :func:`find_hunting_onset` bisects the speed above
which the offset no longer decays.

Sanity reference: Klingel's kinematic frequency of a free wheelset,
f = v / (2 pi) sqrt(lambda / (r0 b)) (:func:`kinematic_frequency`), and of a rigid bogie
of semi-wheelbase a, f / sqrt(1 + (a / b)^2) (:func:`bogie_kinematic_frequency`).
:func:`linear_hunting` gives the eigenvalues of the system linearised at the centred
steady state (Exudyn's ``ComputeLinearizedSystem``: creep and contact geometry linearised
at y = 0).

The contact geometry is nonlinear (equivalent conicity 0.37 at 1 mm amplitude, 0.18 at
3 mm), so the onset depends on the perturbation: ``python validation/hunting.py`` gives
the onsets per perturbation and the linearised system's critical speed
(validation/hunting.md; linearised: 315 km/h with the FASTSIM table, 319 km/h with
Polach's method, validation/creep_table_resolution.md, tests/test_vehicle_linear.py).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from types import SimpleNamespace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from exudyn_turnout.inputs.routes import load_route
from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.inputs.vehicle import load_vehicle
from exudyn_turnout.inputs.vehicle_model import VehicleModel, load_vehicle_model
from exudyn_turnout.passage.contact.profile import (
    RigidRailContact,
    RouteContact,
    route_contact,
)
from exudyn_turnout.wheel_rail.creep_table import CreepTableSettings, creep_table
from exudyn_turnout.wheel_rail.kernel import DETAIL_FIELDS

__all__ = [
    "HuntingSettings",
    "DecayFit",
    "HuntingRun",
    "kinematic_frequency",
    "bogie_kinematic_frequency",
    "decay_analysis",
    "simulate_hunting",
    "find_hunting_onset",
    "LinearHunting",
    "HuntingOnset",
    "linear_hunting",
    "linear_critical_speed",
    "LinearMode",
    "mode_name",
    "linear_modes",
    "OFFSET_WHEELSETS",
    "MIN_DECAY_RATE",
    "CREEP_LAWS",
]

#: Which wheelsets start off centre: the leading one or all.
OFFSET_WHEELSETS = ("leading", "all")
#: Creep laws of the contact kernel (``wheel_rail.packed_tables.pack_tables``): FASTSIM's forces
#: from the creep table (the kernel's default) or Polach's method.
CREEP_LAWS = ("fastsim", "polach")
#: 1/s, smallest decay rate counted as decaying: a limit cycle fits |sigma| < 0.01 1/s
#: (measured), a decaying run at the speeds below the onset > 0.8 1/s (validation/hunting.md)
MIN_DECAY_RATE = 0.05


@dataclass(frozen=True)
class HuntingSettings:
    """One straight-track run: speed, duration, initial offset, integrator.

    Raises ValueError (one line naming the field) on bad values.
    """

    speed_kmh: float  #: km/h, constant running speed
    duration: float = 4.0  #: s, simulated time
    initial_offset: float = 3e-3  #: m, lateral offset (positive left) at t = 0
    offset_wheelsets: str = "leading"  #: one of OFFSET_WHEELSETS
    time_step: float = 5e-4  #: s, generalized-alpha step (fixed)
    spectral_radius: float = 0.9  #: -, generalized-alpha rho_inf (numerical damping)
    output_step: float = 2e-3  #: s, sampling of the stored wheelset coordinates
    route: str = "through"  #: route whose plain rail section at x_min is the track
    #: -, part of the run skipped by the decay fit (the transient of the faster modes)
    skip_fraction: float = 0.25

    def __post_init__(self) -> None:
        checks = (
            ("speed_kmh", self.speed_kmh > 0.0, "must be > 0 km/h"),
            ("duration", self.duration > 0.0, "must be > 0 s"),
            ("initial_offset", abs(self.initial_offset) <= 0.02, "must be within +-0.02 m"),
            (
                "offset_wheelsets",
                self.offset_wheelsets in OFFSET_WHEELSETS,
                f"must be one of {OFFSET_WHEELSETS}",
            ),
            ("time_step", 0.0 < self.time_step <= 5e-3, "must be in (0, 5e-3] s"),
            ("spectral_radius", 0.0 <= self.spectral_radius <= 1.0, "must be in [0, 1]"),
            (
                "output_step",
                self.time_step <= self.output_step <= 0.05,
                "must be in [time_step, 0.05] s",
            ),
            ("skip_fraction", 0.0 <= self.skip_fraction < 0.9, "must be in [0, 0.9)"),
        )
        for name, ok, text in checks:
            value = getattr(self, name)
            if isinstance(value, float) and not math.isfinite(value):
                ok = False
            if not ok:
                raise ValueError(f"hunting settings: {name} = {value!r} {text}")

    @property
    def v(self) -> float:
        """Speed in m/s.

        Returns
        -------
        float
            m/s.
        """
        return self.speed_kmh / 3.6


@dataclass(frozen=True)
class DecayFit:
    """Decay of an oscillation from its extrema (one per half-cycle), see :func:`decay_analysis`."""

    decay_rate: float  #: 1/s, sigma of the envelope A exp(-sigma t); > 0 decays, < 0 grows
    amplitude_ratio: float  #: -, ratio of successive same-sign peaks, exp(-sigma T)
    frequency_hz: float  #: Hz, from the zero crossings (0 if it does not oscillate)
    n_extrema: int  #: -, half-cycle extrema used (0: no oscillation, envelope of |y|)
    first_amplitude: float  #: m (or the signal's unit), |first extremum| in the window
    last_amplitude: float  #: m (or the signal's unit), |last extremum| in the window

    @property
    def decays(self) -> bool:
        """True if the amplitude decays (decay rate > 0).

        Returns
        -------
        bool
        """
        return self.decay_rate > 0.0


def kinematic_frequency(v: float, conicity: float, r0: float, b: float) -> float:
    """Klingel's kinematic frequency of a free wheelset, f = v / (2 pi) sqrt(lambda / (r0 b)).

    Klingel (1883); e.g. Iwnicki (ed.), Handbook of Railway Vehicle Dynamics (2006), ch. 8:
    wavelength L = 2 pi sqrt(r0 b / lambda).

    Parameters
    ----------
    v : float
        m/s, speed.
    conicity : float
        -, equivalent conicity lambda.
    r0 : float
        m, nominal rolling radius.
    b : float
        m, semi-distance of the contact points.

    Returns
    -------
    float
        Hz.
    """
    return v / (2.0 * math.pi) * math.sqrt(conicity / (r0 * b))


def bogie_kinematic_frequency(v: float, conicity: float, r0: float, b: float, a: float) -> float:
    """Kinematic frequency of a rigid two-axle bogie (wheelsets rigidly held in yaw).

    f = f_w / sqrt(1 + (a / b)^2), f_w of :func:`kinematic_frequency` (Wickens 2003,
    Fundamentals of Rail Vehicle Dynamics, sec. 2.4; Iwnicki (ed.) 2006, ch. 8).

    Parameters
    ----------
    v, conicity, r0, b : float
        As :func:`kinematic_frequency` (m/s, -, m, m).
    a : float
        m, semi-wheelbase of the bogie.

    Returns
    -------
    float
        Hz.
    """
    return kinematic_frequency(v, conicity, r0, b) / math.sqrt(1.0 + (a / b) ** 2)


def _zero_crossings(t: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Times where y changes sign (linear interpolation)."""
    s = np.signbit(y)
    i = np.nonzero(s[1:] != s[:-1])[0]
    y0, y1 = y[i], y[i + 1]
    return t[i] + (t[i + 1] - t[i]) * y0 / (y0 - y1)


def _extremum(t: np.ndarray, y: np.ndarray, k: int) -> tuple[float, float]:
    """Time and |value| of the extremum at sample k, refined by a parabola through k-1..k+1."""
    a = np.abs(y)
    if 0 < k < len(y) - 1:
        y0, y1, y2 = a[k - 1], a[k], a[k + 1]
        den = y0 - 2.0 * y1 + y2
        if den < 0.0:
            d = 0.5 * (y0 - y2) / den
            return float(t[k] + d * (t[k + 1] - t[k])), float(y1 - 0.25 * (y0 - y2) * d)
    return float(t[k]), float(a[k])


def decay_analysis(t: ArrayLike, y: ArrayLike, t_start: float = -math.inf) -> DecayFit:
    """Decay rate, amplitude ratio per cycle and frequency of an oscillation about 0.

    From ``t_start`` on, the signal is cut into half-cycles at its zero crossings; the
    largest |y| of each complete half-cycle (parabola-refined) is an extremum. The decay
    rate is minus the slope of the least-squares line through log|extremum| over its time;
    the frequency is 1 / (2 x mean spacing of the crossings). For a damped sine
    A exp(-sigma t) sin(omega t + phi) both are exact: its extrema are T / 2 apart and
    shrink by exp(-sigma T / 2) each. With fewer than 3 extrema (no oscillation) the rate
    is fitted to log|y| over the window itself and the frequency is 0.

    Parameters
    ----------
    t : array_like
        s, increasing sample times.
    y : array_like
        The signal (e.g. m), oscillating about 0.
    t_start : float
        s, start of the analysed window.

    Returns
    -------
    DecayFit

    Raises
    ------
    ValueError
        Fewer than 8 samples in the window, t not increasing, or non-finite values.
    """
    ts, ys = np.asarray(t, float), np.asarray(y, float)
    if ts.shape != ys.shape or ts.ndim != 1:
        raise ValueError("decay analysis: t and y must be 1-D arrays of the same length")
    keep = ts >= t_start
    ts, ys = ts[keep], ys[keep]
    if len(ts) < 8:
        raise ValueError(f"decay analysis: {len(ts)} samples after t_start, at least 8 needed")
    if not (np.all(np.isfinite(ts)) and np.all(np.isfinite(ys))):
        raise ValueError("decay analysis: t and y must be finite")
    if np.any(np.diff(ts) <= 0.0):
        raise ValueError("decay analysis: t must increase")
    crossings = _zero_crossings(ts, ys)
    sign = np.signbit(ys)
    edges = np.nonzero(sign[1:] != sign[:-1])[0] + 1  # first sample of each new half-cycle
    times, values = [], []
    for lo, hi in zip(edges[:-1], edges[1:]):
        k = lo + int(np.argmax(np.abs(ys[lo:hi])))
        tk, ak = _extremum(ts, ys, k)
        if ak > 0.0:
            times.append(tk)
            values.append(ak)
    if len(values) >= 3:
        slope = float(np.polyfit(times, np.log(values), 1)[0])
        period = 2.0 * float(np.mean(np.diff(crossings)))
        sigma = -slope
        return DecayFit(
            sigma, math.exp(-sigma * period), 1.0 / period, len(values), values[0], values[-1]
        )
    a = np.abs(ys)
    good = a > 0.0
    slope = float(np.polyfit(ts[good], np.log(a[good]), 1)[0])
    return DecayFit(-slope, 0.0, 0.0, 0, float(a[0]), float(a[-1]))


@dataclass(frozen=True, eq=False)
class HuntingRun:
    """One straight-track run (:func:`simulate_hunting`) and the decay of its wheelsets."""

    settings: HuntingSettings
    t: np.ndarray  #: s, sample times
    y: np.ndarray  #: m, (wheelsets, samples) lateral displacement, positive left
    yaw: np.ndarray  #: rad, (wheelsets, samples)
    y_bodies: dict  #: m, "car_body", "bogie1", ... -> lateral displacement (samples)
    fits: tuple  #: DecayFit per wheelset (front first)
    conicity: float  #: -, equivalent conicity used for the kinematic frequencies
    kinematic_hz: float  #: Hz, free wheelset (Klingel)
    bogie_kinematic_hz: float  #: Hz, rigid bogie
    x_section: float  #: m, route position of the rail section used (the turnout's x_min)
    wall_seconds: float  #: s, wall time of the run
    steps: int  #: -, time steps

    @property
    def decay_rate(self) -> float:
        """Smallest decay rate over the wheelsets (1/s): the least damped one decides.

        Returns
        -------
        float
            1/s.
        """
        return min(f.decay_rate for f in self.fits)

    @property
    def stable(self) -> bool:
        """True if every wheelset's lateral motion decays (decay rate > MIN_DECAY_RATE).

        Returns
        -------
        bool
        """
        return self.decay_rate > MIN_DECAY_RATE

    @property
    def critical_fit(self) -> DecayFit:
        """The DecayFit with the smallest decay rate.

        Returns
        -------
        DecayFit
        """
        return min(self.fits, key=lambda f: f.decay_rate)

    def __repr__(self) -> str:
        f = self.critical_fit
        return (
            f"HuntingRun({self.settings.speed_kmh:g} km/h, decay rate {f.decay_rate:.3f} 1/s, "
            f"ratio {f.amplitude_ratio:.3f}, {f.frequency_hz:.2f} Hz, "
            f"{'stable' if self.stable else 'not decaying'})"
        )


@dataclass
class _Straight:
    """The vehicle on straight rigid plain track, built and at its static equilibrium."""

    container: Any
    mbs: Any
    build: Any  #: VehicleBuild
    forces: list  #: RigidRailContact per wheelset
    sensors: list  #: coordinate sensor per body (build.bodies() order)
    r0: float  #: m, wheel radius of the contact
    b: float  #: m, contact semi-spacing
    x_section: float  #: m


def _with_creep_law(
    contact: RouteContact, creep_law: str, creep_settings: CreepTableSettings | None = None
) -> RouteContact:
    """The route's contact with the kernel's creep law set (the last packed value is the
    law, 1 FASTSIM table, 0 Polach, the one before it the creep table's index:
    ``wheel_rail.packed_tables.pack_tables``); ``creep_settings``: that creep table instead of
    the default one (FASTSIM)."""
    if creep_law not in CREEP_LAWS:
        raise ValueError(f"hunting: creep_law = {creep_law!r} must be one of {CREEP_LAWS}")
    values = contact.tables.values.copy()
    if creep_settings is not None and creep_law == "fastsim":
        start = int(values[-2])
        table = creep_table(creep_settings).packed
        values = np.concatenate((values[:start], table, values[-2:]))
    values[-1] = 1.0 if creep_law == "fastsim" else 0.0
    return replace(contact, tables=replace(contact.tables, values=values))


def _roll_freely(system: _Straight, v: float) -> None:
    """Spin every wheelset at the speed of rolling without longitudinal creepage.

    The element turns the wheels at v / r0 + beta_t; the centred contact rolls on the
    table's radius r (0.45991 m against r0 = 0.46 m on S1002 / UIC60 1:40), so beta_t = 0
    leaves xi = 1 - r / r0 ~ 2e-4 on every wheel, a braking torque the static solve's spin
    spring held. Free, the wheelset spins up to xi = 0 within milliseconds; the steady state
    at speed is that one. beta_t is set (Initial and Current) to xi v / r, which zeroes xi
    (xi is linear in beta_t, slope -r / v).
    """
    import exudyn as exu

    mbs = system.mbs
    i_normal, i_xi = DETAIL_FIELDS.index("normal"), DETAIL_FIELDS.index("xi")
    i_radius = DETAIL_FIELDS.index("radius")
    q = np.array(mbs.systemData.GetODE2Coordinates(exu.ConfigurationType.Initial))
    q_t = np.array(mbs.systemData.GetODE2Coordinates_t(exu.ConfigurationType.Initial))
    for ws, force in zip(system.build.wheelsets, system.forces):
        i = mbs.GetNodeODE2Index(ws.node)
        for _ in range(2):  # the second pass only checks (round-off)
            full_q, full_q_t = force.full(q[i : i + force.n], q_t[i : i + force.n])
            _, details = force.element.evaluate(force.x, full_q, full_q_t)
            loaded = details[:, i_normal] > 0.0
            if not np.any(loaded):
                break
            xi = float(np.mean(details[loaded, i_xi]))
            radius = float(np.mean(details[loaded, i_radius]))
            q_t[i + ws.dof["spin"]] += xi * v / radius
    for configuration in (exu.ConfigurationType.Initial, exu.ConfigurationType.Current):
        mbs.systemData.SetODE2Coordinates_t(q_t.tolist(), configuration)


def _straight(
    turnout: Turnout,
    route_name: str,
    model: VehicleModel,
    v: float,
    creep_law: str = "fastsim",
    creep_settings: CreepTableSettings | None = None,
) -> _Straight:
    """Build the vehicle on rigid plain track at speed v and solve its static equilibrium
    (lateral position and spin held by springs, released afterwards); the wheelsets then
    spin at free rolling (:func:`_roll_freely`)."""
    import exudyn as exu
    from exudyn.itemInterface import ObjectGenericODE2, SensorNode

    from exudyn_turnout.passage.vehicle.builder import add_vehicle_model, static_settings
    from exudyn_turnout.passage.vehicle.track_frame import (
        contact_vehicle,
        set_initial_vehicle,
    )

    if model.car_body is None:
        raise ValueError(f"{model.name}: not a full vehicle (no car body)")
    base = load_vehicle()
    route = load_route(turnout, route_name)
    x_section = turnout.x_min
    kappa = float(np.interp(x_section, route.curvature.x, route.curvature.value))
    if kappa != 0.0:
        raise ValueError(f"route {route.name}: curved at x_min = {x_section:g} m, not straight")
    contact = _with_creep_law(route_contact(turnout, route.name, base), creep_law, creep_settings)
    vehicle = contact_vehicle(base, model)
    container = exu.SystemContainer()
    mbs = container.AddSystem()
    build = add_vehicle_model(
        mbs, model, representation="linear", wheelset_spin=True, bumpstop="auto"
    )
    forces = []
    for ws in build.wheelsets:
        if tuple(ws.dof) != ("y", "z", "roll", "yaw", "spin"):
            raise ValueError(f"unexpected wheelset coordinates {tuple(ws.dof)}")
        element, _ = contact.element(vehicle, route, turnout.zones[0], x_section, v)
        force = RigidRailContact(element, x_section, len(ws.dof))
        zero = np.zeros((force.n, force.n))
        mbs.AddObject(
            ObjectGenericODE2(
                nodeNumbers=[ws.node],
                massMatrix=zero,
                stiffnessMatrix=zero,
                forceUserFunction=force,
            )
        )
        forces.append(force)
    mbs.variables["exudyn_turnout.hunting"] = forces  # keeps the user functions alive
    sensors = [
        mbs.AddSensor(
            SensorNode(
                nodeNumber=body.node,
                storeInternal=True,
                writeToFile=False,
                outputVariableType=exu.OutputVariableType.Coordinates,
            )
        )
        for body in build.bodies()
    ]
    mbs.Assemble()
    set_initial_vehicle(
        SimpleNamespace(mbs=mbs, elements=[f.element for f in forces]),
        build,
        [f.x for f in forces],
    )
    for f in forces:
        f.static = True
    sim = static_settings()
    sim.staticSolver.newton.absoluteTolerance = 1e-4
    sim.staticSolver.newton.maxIterations = 50
    try:
        mbs.SolveStatic(sim, updateInitialValues=True)
    except (exu.SolverError, RuntimeError) as err:
        raise ValueError(f"hunting: static equilibrium not found: {str(err).strip()}") from None
    for f in forces:
        f.static = False
    system = _Straight(container, mbs, build, forces, sensors, vehicle.r0, vehicle.b, x_section)
    _roll_freely(system, v)
    return system


class _Quiet:
    """Exudyn's console output off inside the block."""

    def __enter__(self):
        import exudyn as exu

        self.previous = exu.config.printToConsole
        exu.config.printToConsole = False
        return self

    def __exit__(self, *exc):
        import exudyn as exu

        exu.config.printToConsole = self.previous
        return False


def simulate_hunting(
    turnout: Turnout,
    settings: HuntingSettings,
    vehicle_model: VehicleModel | None = None,
    conicity: float = 0.18,
) -> HuntingRun:
    """Run the full vehicle on straight rigid plain track from a lateral offset.

    ::

        plan view (x forward, to the right), rigid rails of the plain section at x_min

        ====================================================================  left rail
             ws4     ws3      bogie 2   car body       bogie 1    ws2    ws1
             |o|     |o|   +---------------------------------+     |o|    |o|  -> v
             |o|     |o|   +---------------------------------+     |o|   /|o|/  y0
        ====================================================================  right rail
                                                                    initial offset y0
        Each wheel: profile contact on its rail (Hertz per contact point, FASTSIM creep),
        rails fixed; suspension: the linear vehicle model (primary, secondary, bumpstops).

    The vehicle starts in the steady state at speed (static equilibrium, lateral position
    and spin held, then released; the wheelsets spinning at free rolling) with the leading
    wheelset (``offset_wheelsets = "leading"``) or every wheelset moved sideways by
    ``initial_offset``; the wheelsets'
    lateral motion is then fitted by :func:`decay_analysis` from ``skip_fraction`` of the
    run on.

    Parameters
    ----------
    turnout : Turnout
        Its route ``settings.route`` gives the plain rail section at x_min.
    settings : HuntingSettings
    vehicle_model : VehicleModel, optional
        A full vehicle (default: the packaged Manchester vehicle 1).
    conicity : float
        -, equivalent conicity for the kinematic frequencies (sanity reference only; 0.18
        for S1002 / UIC60 1:40 / 1435 / 1360 at 3 mm, validation/contact_geometry.md).

    Returns
    -------
    HuntingRun

    Raises
    ------
    ValueError
        Not a full vehicle, a curved section at x_min, a conicity outside (0, 1], or a
        solver failure (one line).
    """
    import exudyn as exu

    from exudyn_turnout.passage.vehicle.builder import dynamic_settings

    if not (math.isfinite(conicity) and 0.0 < conicity <= 1.0):
        raise ValueError(f"hunting: conicity = {conicity!r} must be in (0, 1]")
    model = load_vehicle_model() if vehicle_model is None else vehicle_model
    wall = time.perf_counter()
    with _Quiet():
        system = _straight(turnout, settings.route, model, settings.v)
        mbs, build = system.mbs, system.build
        q = np.array(mbs.systemData.GetODE2Coordinates(exu.ConfigurationType.Initial))
        offset = [build.wheelsets[0]] if settings.offset_wheelsets == "leading" else build.wheelsets
        for ws in offset:
            q[mbs.GetNodeODE2Index(ws.node) + ws.dof["y"]] += settings.initial_offset
        mbs.systemData.SetODE2Coordinates(q.tolist(), exu.ConfigurationType.Initial)
        # velocities: zero but the wheelsets' spin at free rolling (_roll_freely)
        q_t = np.array(mbs.systemData.GetODE2Coordinates_t(exu.ConfigurationType.Initial))
        spin = np.zeros(len(q), bool)
        for ws in build.wheelsets:
            spin[mbs.GetNodeODE2Index(ws.node) + ws.dof["spin"]] = True
        q_t[~spin] = 0.0
        mbs.systemData.SetODE2Coordinates_t(q_t.tolist(), exu.ConfigurationType.Initial)
        sim = dynamic_settings(settings.duration, settings.time_step)
        sim.timeIntegration.generalizedAlpha.spectralRadius = settings.spectral_radius
        sim.solution.sensors.writePeriod = 0.999 * settings.output_step
        try:
            mbs.SolveDynamic(sim)
        except (exu.SolverError, RuntimeError) as err:
            t_fail = mbs.systemData.GetTime()
            raise ValueError(
                f"hunting at {settings.speed_kmh:g} km/h: solver failed at t = {t_fail:.4f} s: "
                f"{str(err).strip()}"
            ) from None
        stored = {
            b.name: np.asarray(mbs.GetSensorStoredData(s))
            for b, s in zip(build.bodies(), system.sensors)
        }
    wall = time.perf_counter() - wall
    wheelsets = build.wheelsets
    t = stored[wheelsets[0].name][:, 0]
    y = np.array([stored[ws.name][:, 1 + ws.dof["y"]] for ws in wheelsets])
    yaw = np.array([stored[ws.name][:, 1 + ws.dof["yaw"]] for ws in wheelsets])
    if not (np.all(np.isfinite(y)) and np.all(np.isfinite(yaw))):
        raise ValueError(f"hunting at {settings.speed_kmh:g} km/h: the solution diverged")
    ws_names = {ws.name for ws in wheelsets}
    y_bodies = {
        b.name: stored[b.name][:, 1 + b.dof["y"]] for b in build.bodies() if b.name not in ws_names
    }
    t_start = settings.skip_fraction * settings.duration
    fits = tuple(decay_analysis(t, row, t_start) for row in y)
    a = 0.5 * abs(wheelsets[0].x - wheelsets[1].x)
    v = settings.v
    return HuntingRun(
        settings,
        t,
        y,
        yaw,
        y_bodies,
        fits,
        conicity,
        kinematic_frequency(v, conicity, system.r0, system.b),
        bogie_kinematic_frequency(v, conicity, system.r0, system.b, a),
        system.x_section,
        wall,
        int(sim.timeIntegration.numberOfSteps),
    )


@dataclass(frozen=True, eq=False)
class LinearHunting:
    """Eigenvalues of the vehicle linearised at the centred steady state at speed v."""

    speed_kmh: float  #: km/h
    eigenvalues: np.ndarray  #: 1/s, oscillatory eigenvalues (Im > 0) in the frequency band
    growth_rate: float  #: 1/s, largest real part among them (> 0: unstable)
    frequency_hz: float  #: Hz, Im / 2 pi of that eigenvalue
    damping_ratio: float  #: -, -Re / |lambda| of that eigenvalue

    @property
    def stable(self) -> bool:
        """True if every oscillatory mode in the band is damped (growth rate < 0).

        Returns
        -------
        bool
        """
        return self.growth_rate < 0.0


@dataclass(frozen=True, eq=False)
class HuntingOnset:
    """Bisection of the speed above which the initial offset no longer decays."""

    runs: tuple  #: HuntingRun of every speed tried, by increasing speed
    bracket_kmh: tuple  #: km/h, (highest speed that decays, lowest that does not)
    tolerance_kmh: float  #: km/h, the bracket's width at most

    @property
    def onset_kmh(self) -> float:
        """Middle of the bracket (km/h).

        Returns
        -------
        float
            km/h.
        """
        return 0.5 * (self.bracket_kmh[0] + self.bracket_kmh[1])


def linear_hunting(
    turnout: Turnout,
    speed_kmh: float,
    vehicle_model: VehicleModel | None = None,
    route: str = "through",
    band_hz: tuple[float, float] = (0.1, 50.0),
    creep_law: str = "fastsim",
    creep_settings: CreepTableSettings | None = None,
) -> LinearHunting:
    """Eigenvalues of the straight-track system linearised at its centred steady state.

    M, K, D from Exudyn's ``ComputeLinearizedSystem`` (finite differences of the contact
    force function in coordinates and velocities, forward differences of a relative step
    1e-7, at least 1e-9: the creep forces linearised at free rolling with the centred
    contact's spin, and the contact geometry's slopes at the centred position); state-space
    eigenvalues of [[0, I], [-M^-1 K, -M^-1 D]]. Oscillatory ones (Im > 0) with frequency
    in ``band_hz`` are kept (the vertical Hertz modes near 200 Hz are outside).

    Parameters
    ----------
    turnout : Turnout
        Its route gives the plain rail section at x_min (as :func:`simulate_hunting`).
    speed_kmh : float
        km/h.
    vehicle_model : VehicleModel, optional
        Default: the packaged Manchester vehicle 1.
    route : str
        Route name.
    band_hz : (float, float)
        Hz, frequency band of the modes considered.
    creep_law : str
        One of :data:`CREEP_LAWS`: the kernel's FASTSIM table (default) or Polach's method.
    creep_settings : CreepTableSettings, optional
        Grid of the FASTSIM table (default: the kernel's, ``CreepTableSettings()``); for
        the table's convergence (validation/creep_table_resolution.py).

    Returns
    -------
    LinearHunting

    Raises
    ------
    ValueError
        Speed not positive, or as :func:`simulate_hunting`.
    """
    from exudyn_turnout.passage.vehicle.builder import static_settings

    if not (math.isfinite(speed_kmh) and speed_kmh > 0.0):
        raise ValueError(f"linear hunting: speed_kmh = {speed_kmh!r} must be > 0 km/h")
    model = load_vehicle_model() if vehicle_model is None else vehicle_model
    with _Quiet():
        system = _straight(turnout, route, model, speed_kmh / 3.6, creep_law, creep_settings)
        m, k, d = (np.asarray(a) for a in system.mbs.ComputeLinearizedSystem(static_settings()))
    lam = _state_space_eigenvalues(m, k, d)
    f = lam.imag / (2.0 * math.pi)
    lam = lam[(lam.imag > 0.0) & (f >= band_hz[0]) & (f <= band_hz[1])]
    worst = lam[int(np.argmax(lam.real))]
    return LinearHunting(
        float(speed_kmh),
        np.sort_complex(lam),
        float(worst.real),
        float(worst.imag / (2.0 * math.pi)),
        float(-worst.real / abs(worst)),
    )


@dataclass(frozen=True, eq=False)
class LinearMode:
    """One oscillatory mode of the vehicle linearised on straight rigid track at speed v."""

    speed_kmh: float  #: km/h
    eigenvalue: complex  #: 1/s, lambda (Im > 0)
    frequency_hz: float  #: Hz, Im(lambda) / 2 pi (damped)
    damping_ratio: float  #: -, -Re(lambda) / |lambda|
    name: str  #: mode name from the energy shares (:func:`mode_name`)
    shares: dict  #: "car_body.y", "bogie.yaw", "wheelset.y", ... -> kinetic-energy share


def mode_name(shares: dict) -> str:
    """Name a lateral mode of the vehicle from its kinetic-energy shares.

    Running gear = the wheelsets' and bogies' y and yaw. Rules, in order: car body y, roll
    or yaw the largest share: car body lower sway, upper sway, yaw; wheelsets (y + yaw)
    >= 0.7: wheelset kinematic; wheelsets >= 0.25 and bogies (y + yaw) >= 0.15: bogie
    hunting (the kinematic mode of the bogie with its wheelsets); then the bogies' largest
    share: bogie lateral, bogie yaw, bogie sway (roll); anything else (z, pitch, spin):
    vertical/other.

    Parameters
    ----------
    shares : dict
        "<kind>.<direction>" -> share (kinds car_body, bogie, wheelset), summing to 1.

    Returns
    -------
    str
    """
    top = max(shares, key=lambda k: shares[k])
    car = {"car_body.y": "car body lower sway", "car_body.roll": "car body upper sway"}
    car["car_body.yaw"] = "car body yaw"
    if top in car:
        return car[top]
    wheelsets = shares.get("wheelset.y", 0.0) + shares.get("wheelset.yaw", 0.0)
    bogies = shares.get("bogie.y", 0.0) + shares.get("bogie.yaw", 0.0)
    if wheelsets >= 0.7:
        return "wheelset kinematic"
    if wheelsets >= 0.25 and bogies >= 0.15:
        return "bogie hunting"
    bogie = {"bogie.y": "bogie lateral", "bogie.yaw": "bogie yaw", "bogie.roll": "bogie sway"}
    return bogie.get(top, "vertical/other")


def linear_modes(
    turnout: Turnout,
    speed_kmh: float,
    vehicle_model: VehicleModel | None = None,
    route: str = "through",
    band_hz: tuple[float, float] = (0.1, 20.0),
    creep_law: str = "fastsim",
) -> tuple[LinearMode, ...]:
    """Oscillatory modes of the vehicle linearised at the centred steady state (named).

    As :func:`linear_hunting` (Exudyn's ``ComputeLinearizedSystem`` of the straight-track
    system); each state-space eigenvector's displacement part v gives the kinetic-energy
    share of each coordinate, |conj(v_i) (M v)_i|, summed per body kind and direction.

    Parameters
    ----------
    turnout : Turnout
    speed_kmh : float
        km/h.
    vehicle_model : VehicleModel, optional
        Default: the packaged Manchester vehicle 1.
    route : str
    band_hz : (float, float)
        Hz, frequency band kept.
    creep_law : str
        One of :data:`CREEP_LAWS` (as :func:`linear_hunting`).

    Returns
    -------
    tuple of LinearMode
        By increasing frequency.

    Raises
    ------
    ValueError
        As :func:`linear_hunting`.
    """
    from exudyn_turnout.passage.vehicle.builder import static_settings

    if not (math.isfinite(speed_kmh) and speed_kmh > 0.0):
        raise ValueError(f"linear modes: speed_kmh = {speed_kmh!r} must be > 0 km/h")
    model = load_vehicle_model() if vehicle_model is None else vehicle_model
    with _Quiet():
        system = _straight(turnout, route, model, speed_kmh / 3.6, creep_law)
        mbs = system.mbs
        m, k, d = (np.asarray(a) for a in mbs.ComputeLinearizedSystem(static_settings()))
    n = len(m)
    groups = [""] * n
    for body in system.build.bodies():
        start = mbs.GetNodeODE2Index(body.node)
        kind = "wheelset" if body.name.startswith("wheelset") else body.name.rstrip("0123456789")
        for dname, j in body.dof.items():
            if start + j < n:
                groups[start + j] = f"{kind}.{dname}"
    a = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(m, k), -np.linalg.solve(m, d)]])
    lam, vec = np.linalg.eig(a)
    out = []
    for i in np.flatnonzero(lam.imag > 0.0):
        f = lam[i].imag / (2.0 * math.pi)
        if not band_hz[0] <= f <= band_hz[1]:
            continue
        v = vec[:n, i]
        energy = np.abs(np.conj(v) * (m @ v))
        shares: dict[str, float] = {}
        for g, e in zip(groups, energy):
            if g:
                shares[g] = shares.get(g, 0.0) + float(e)
        total = sum(shares.values()) or 1.0
        shares = {g: e / total for g, e in shares.items() if e / total >= 0.01}
        out.append(
            LinearMode(
                float(speed_kmh),
                complex(lam[i]),
                float(f),
                float(-lam[i].real / abs(lam[i])),
                mode_name(shares),
                dict(sorted(shares.items(), key=lambda kv: -kv[1])),
            )
        )
    return tuple(sorted(out, key=lambda mode: mode.frequency_hz))


def _state_space_eigenvalues(m: np.ndarray, k: np.ndarray, d: np.ndarray) -> np.ndarray:
    """Eigenvalues of M q'' + D q' + K q = 0 as a first-order system."""
    n = len(m)
    a = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(m, k), -np.linalg.solve(m, d)]])
    return np.linalg.eigvals(a)


def _bisect(
    stable_at: Callable[[float], bool], low: float, high: float, tolerance: float
) -> tuple[float, float]:
    """(highest stable, lowest unstable) speed, ``stable_at(low)`` True and
    ``stable_at(high)`` False already checked."""
    while high - low > tolerance:
        mid = 0.5 * (low + high)
        if stable_at(mid):
            low = mid
        else:
            high = mid
    return low, high


def linear_critical_speed(
    turnout: Turnout,
    low_kmh: float,
    high_kmh: float,
    tolerance_kmh: float = 5.0,
    vehicle_model: VehicleModel | None = None,
    route: str = "through",
    creep_law: str = "fastsim",
    creep_settings: CreepTableSettings | None = None,
) -> tuple[float, float]:
    """Bracket of the speed where the linearised system (:func:`linear_hunting`) turns unstable.

    Parameters
    ----------
    turnout : Turnout
    low_kmh, high_kmh : float
        km/h, a speed where it is stable and one where it is not.
    tolerance_kmh : float
        km/h, width of the returned bracket at most.
    vehicle_model : VehicleModel, optional
    route : str
    creep_law : str
        One of :data:`CREEP_LAWS` (as :func:`linear_hunting`).
    creep_settings : CreepTableSettings, optional
        Grid of the FASTSIM table (as :func:`linear_hunting`).

    Returns
    -------
    (float, float)
        km/h, highest stable and lowest unstable speed found.

    Raises
    ------
    ValueError
        The bracket does not hold (stable at ``high_kmh`` or unstable at ``low_kmh``).
    """
    model = load_vehicle_model() if vehicle_model is None else vehicle_model

    def stable_at(kmh: float) -> bool:
        return linear_hunting(
            turnout, kmh, model, route, creep_law=creep_law, creep_settings=creep_settings
        ).stable

    _check_bracket(low_kmh, high_kmh, tolerance_kmh)
    if not stable_at(low_kmh):
        raise ValueError(f"linear hunting: already unstable at low_kmh = {low_kmh:g} km/h")
    if stable_at(high_kmh):
        raise ValueError(f"linear hunting: still stable at high_kmh = {high_kmh:g} km/h")
    return _bisect(stable_at, low_kmh, high_kmh, tolerance_kmh)


def _check_bracket(low: float, high: float, tolerance: float) -> None:
    if not (math.isfinite(low) and math.isfinite(high) and 0.0 < low < high):
        raise ValueError(f"hunting onset: need 0 < low_kmh < high_kmh, got {low!r}, {high!r}")
    if not (math.isfinite(tolerance) and tolerance > 0.0):
        raise ValueError(f"hunting onset: tolerance_kmh = {tolerance!r} must be > 0")


def find_hunting_onset(
    turnout: Turnout,
    low_kmh: float,
    high_kmh: float,
    settings: HuntingSettings | None = None,
    tolerance_kmh: float = 5.0,
    vehicle_model: VehicleModel | None = None,
    progress: Callable[[HuntingRun], None] | None = None,
) -> HuntingOnset:
    """Bisect the speed above which the lateral offset does not decay.

    A run "decays" when the least damped wheelset's decay rate exceeds
    :data:`MIN_DECAY_RATE` (a limit cycle fits |sigma| < 0.01 1/s). The result holds for the
    perturbation of ``settings`` (offset, wheelsets): the vehicle's nonlinear contact
    geometry makes it depend on it.

    Parameters
    ----------
    turnout : Turnout
    low_kmh, high_kmh : float
        km/h, a speed where the offset decays and one where it does not.
    settings : HuntingSettings, optional
        Everything but the speed (default: :class:`HuntingSettings` defaults).
    tolerance_kmh : float
        km/h, width of the final bracket at most.
    vehicle_model : VehicleModel, optional
        Default: the packaged Manchester vehicle 1.
    progress : callable(HuntingRun), optional
        Called after every run.

    Returns
    -------
    HuntingOnset

    Raises
    ------
    ValueError
        A bad bracket (it does not hold at its ends) or settings.
    """
    _check_bracket(low_kmh, high_kmh, tolerance_kmh)
    template = HuntingSettings(speed_kmh=low_kmh) if settings is None else settings
    model = load_vehicle_model() if vehicle_model is None else vehicle_model
    runs: list[HuntingRun] = []

    def stable_at(kmh: float) -> bool:
        run = simulate_hunting(turnout, replace(template, speed_kmh=kmh), model)
        runs.append(run)
        if progress is not None:
            progress(run)
        return run.stable

    if not stable_at(low_kmh):
        raise ValueError(f"hunting onset: the offset does not decay at low_kmh = {low_kmh:g} km/h")
    if stable_at(high_kmh):
        raise ValueError(f"hunting onset: the offset still decays at high_kmh = {high_kmh:g} km/h")
    bracket = _bisect(stable_at, low_kmh, high_kmh, tolerance_kmh)
    runs.sort(key=lambda r: r.settings.speed_kmh)
    return HuntingOnset(tuple(runs), bracket, tolerance_kmh)
