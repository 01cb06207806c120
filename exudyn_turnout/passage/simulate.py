"""A wheelset passing through the turnout on a co-running track (paper Section 4).

The wheelset (:mod:`~exudyn_turnout.inputs.vehicle`) runs at constant speed along a route
(:mod:`~exudyn_turnout.inputs.routes`) over a two- or three-layer co-running track
(:mod:`~exudyn_turnout.corunning.track`) whose position-dependent stiffness and damping
follow the wheelset's x, coupled by the penalty wheel/rail contact of
:mod:`~exudyn_turnout.passage.contact_element`.

The run starts from static equilibrium at ``x_start`` and is split at the zone boundaries
(Table 3): in each zone a new Exudyn system is built with that zone's masses and active
rails, and the state of everything that continues (vehicle, sleeper, rails present in
both zones, or a rail slot that a route says continues another) is carried over.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from exudyn_turnout.corunning.parameters import CoRunningParameters, co_running_parameters
from exudyn_turnout.inputs.routes import Route, SpeedWarning, load_route, speed_warnings
from exudyn_turnout.inputs.turnout import Turnout, Zone
from exudyn_turnout.inputs.vehicle import Vehicle, load_vehicle
from exudyn_turnout.passage.contact_element import BoundPair, WheelRailElement
from exudyn_turnout.passage.vehicle import add_vehicle

__all__ = [
    "TRACKS",
    "PassageSettings",
    "PassageResult",
    "PassageError",
    "PassageFailure",
    "simulate_passage",
    "max_time_step",
    "contact_resonance",
    "passage_summary",
    "write_passage",
    "compare_layers",
    "peaks_table",
    "lightest_rail_mass",
    "check_plausible",
    "OUTPUT_FILES",
    "PLAUSIBLE",
]


#: N: Newton's absolute residual tolerance in a passage (see benchmarks/bench_passage.py).
NEWTON_ABSOLUTE_TOLERANCE = 1.0


class PassageError(RuntimeError):
    """Bad passage settings, or a solver failure (the message says when and where)."""


class PassageFailure(PassageError):
    """A run that failed, diverged or left every physical state (the CLI's exit code 3).

    The message gives the time, the position and what went wrong.
    """


#: Plausibility limits of a passage: beyond any of them the run stops with a
#: :class:`PassageFailure`. m: wheelset vertical and lateral displacement (a wheel 50 mm
#: up or down has derailed or fallen through the track); m: rail deflection; -: contact
#: force over the static wheel load.
PLAUSIBLE = {"wheelset_m": 0.05, "rail_m": 0.02, "force_over_static": 50.0}


@dataclass(frozen=True)
class PassageSettings:
    """Settings of a passage (SI units but the speed in km/h)."""

    route: str = "through"
    speed_kmh: float = 100.0  #: km/h
    layers: int = 3
    source: str = "derived"
    x_start: float | None = None  #: m, default: the turnout's start
    x_end: float | None = None  #: m, default: the turnout's end
    time_step: float = 1e-4  #: s, converged: halving it moves the crossing peak < 0.4 %
    output_step: float | None = None  #: s, default: every time step
    spectral_radius: float = 0.8  #: generalized-alpha rho_inf
    track_mechanism: str = (
        "symbolic"  #: how track springs follow x: "symbolic", "python" or "constant"
    )

    @property
    def v(self) -> float:
        """Speed in m/s."""
        return self.speed_kmh / 3.6


#: Track models of :func:`simulate_passage`.
TRACKS = ("2-layer", "3-layer", "fe")


@dataclass(frozen=True, repr=False)
class PassageResult:
    """Time histories and peaks of a passage (SI units, see :func:`simulate_passage`).

    Compute returns this data object; :meth:`plot` draws it (delegating to
    :mod:`exudyn_turnout.plotting`), :meth:`save` writes it, :meth:`peaks` lists its peaks.
    """

    settings: PassageSettings
    columns: Mapping[str, np.ndarray]  #: "t_s", "x_m", forces (N), displacements (m, rad)
    summary: Mapping[str, object]
    #: m, x where each run segment began
    zone_starts: tuple[float, ...] = field(default_factory=tuple)

    @property
    def model(self) -> str:
        """The track model: ``"2-layer"``, ``"3-layer"`` or ``"FE"``."""
        return str(self.summary.get("model", f"{self.settings.layers}-layer"))

    def peaks(self) -> dict[str, float]:
        """Peak forces (N) of the summary: per region, per wheel and per contact.

        Returns
        -------
        dict
            ``peak_<Fz|Fy>_<region>[_<wheel>[_<rail>]]_N`` -> N (NaN where a region or a
            contact is not in the run). ``Fz`` peaks are maxima, ``Fy`` the largest
            magnitude with its sign.
        """
        out = {}
        for key, value in self.summary.items():
            if key.startswith("peak_") and isinstance(value, (int, float)):
                out[key] = float(value)
            elif key.startswith("peak_") and value is None:
                out[key] = math.nan
        return out

    def plot(self, wheel: str | None = None, title: str | None = None):
        """Contact forces against x at the switch and at the crossing (Figs 7, 8 layout).

        Parameters
        ----------
        wheel : {"right", "left"}, optional
            Default: the right wheel, as the paper's figures.
        title : str, optional
            Figure title.

        Returns
        -------
        (figure, axes)
            From :func:`exudyn_turnout.plotting.plot_passage_forces`.
        """
        from exudyn_turnout.plotting.curves import plot_passage_forces

        return plot_passage_forces([self], wheel=wheel or "right", title=title)

    def save(self, directory, format: str = "csv") -> dict[str, str]:  # noqa: A002
        """Write the time series (``timeseries.csv`` or ``.npz``) and ``summary.json``.

        Parameters
        ----------
        directory : str or Path
            Output directory (created if missing).
        format : {"csv", "npz"}
            Format of the time series.

        Returns
        -------
        dict
            Paths of the files written, by kind.
        """
        return write_passage(self, directory, fmt=format)

    def __repr__(self) -> str:
        s = self.settings
        x = self.columns["x_m"]
        crossing = self.summary.get("peak_Fz_crossing_N")
        peak = (
            f", peak Fz crossing {crossing / 1e3:.1f} kN"
            if isinstance(crossing, (int, float)) and math.isfinite(crossing)
            else ""
        )
        return (
            f"PassageResult({self.model}, route {s.route!r}, {s.speed_kmh:g} km/h, "
            f"x {x[0]:g} to {x[-1]:g} m, {len(x)} samples{peak})"
        )


def contact_resonance(vehicle: Vehicle, m_contact: float) -> float:
    """Wheel-on-rail resonance (Hz): half the wheelset on the linear Hertz spring over m_contact.

    Parameters
    ----------
    vehicle : Vehicle
    m_contact : float
        kg, the mass of rail under the wheel.

    Returns
    -------
    float
        Hz.
    """
    W = vehicle.static_wheel_load
    k_H = 1.5 * vehicle.contact.C_H ** (2.0 / 3.0) * W ** (1.0 / 3.0)  # dF/d delta at F = W
    m_w = 0.5 * vehicle.m_w
    return math.sqrt(k_H * (1.0 / m_w + 1.0 / m_contact)) / (2.0 * math.pi)


def max_time_step(vehicle: Vehicle, m_rail: float) -> float:
    """Largest time step (s) that resolves the wheel/rail contact: 10 steps per period.

    Parameters
    ----------
    vehicle : Vehicle
    m_rail : float
        kg, the lightest rail mass of the run (:func:`lightest_rail_mass`).

    Returns
    -------
    float
        s.
    """
    return 1.0 / (10.0 * contact_resonance(vehicle, m_rail))


def lightest_rail_mass(
    turnout: Turnout, x_a: float, x_b: float, layers: int = 3, source: str = "derived"
) -> float:
    """Lightest co-running rail mass m_r (kg) of the active rails between x_a and x_b.

    Evaluated from the actual parameter set (``layers``, ``source``) at both ends of each
    zone's part of the range; it sets the time-step limit (:func:`max_time_step`).

    Parameters
    ----------
    turnout : Turnout
    x_a, x_b : float
        Range of the run (m).
    layers : {2, 3}
    source : {"derived", "published"}

    Returns
    -------
    float
        kg.

    Raises
    ------
    PassageError
        The parameter set does not exist (e.g. ``source="published"`` without Table 2 for a zone).
    """
    masses = []
    for zone in _zones_of_run(turnout, x_a, x_b):
        try:
            p = co_running_parameters(turnout, zone=zone.index, layers=layers, source=source)
        except (KeyError, ValueError) as err:
            name = turnout.source.replace("\\", "/").rsplit("/", 1)[-1]
            raise PassageError(
                f"--source {source}: {name} has no parameter set for zone {zone.index} "
                f"({str(err).rsplit(': ', 1)[-1]})"
            ) from None
        for x in (max(zone.x_start, x_a), min(zone.x_end, x_b)):
            values = p.at(x)
            masses += [values[f"m_r{slot[1:]}"] for slot in zone.active_rails]
    return float(min(masses))


def _check(settings: PassageSettings, turnout: Turnout, vehicle: Vehicle) -> tuple[float, float]:
    s = settings
    if not (math.isfinite(s.speed_kmh) and 0 < s.speed_kmh <= 400):
        raise PassageError(f"speed must be > 0 and <= 400 km/h, got {s.speed_kmh:g} km/h")
    x_a = turnout.x_min if s.x_start is None else s.x_start
    x_b = turnout.x_max if s.x_end is None else s.x_end
    if not (turnout.x_min <= x_a < x_b <= turnout.x_max):
        raise PassageError(
            f"x range {x_a:g}..{x_b:g} m must lie within the turnout "
            f"({turnout.x_min:g}..{turnout.x_max:g} m) with x_start < x_end"
        )
    m_rail = lightest_rail_mass(turnout, x_a, x_b, s.layers, s.source)
    h_max = max_time_step(vehicle, m_rail)
    if not (math.isfinite(s.time_step) and 0 < s.time_step <= h_max):
        raise PassageError(
            f"time step {s.time_step:g} s is too large to resolve the wheel/rail contact "
            f"(~{contact_resonance(vehicle, m_rail):.0f} Hz with the lightest rail, "
            f"{m_rail:.4g} kg): use a step <= {h_max:.2g} s"
        )
    _check_output_step(s, (x_b - x_a) / s.v)
    return x_a, x_b


def _check_output_step(s: PassageSettings, duration: float) -> None:
    if s.output_step is None:
        return
    if not (math.isfinite(s.output_step) and s.time_step <= s.output_step <= duration):
        raise PassageError(
            f"output step {s.output_step:g} s must be >= the time step "
            f"({s.time_step:g} s) and <= the run's duration ({duration:.4g} s)"
        )


def check_plausible(columns: Mapping[str, np.ndarray], static_load: float, what: str = "") -> None:
    """Stop a run that left every physical state (limits in :data:`PLAUSIBLE`).

    Parameters
    ----------
    columns : mapping
        Columns of a passage (or of one zone's part): ``t_s``, ``x_m``, ``z_wheelset_m``,
        ``y_wheelset_m``, ``z_rail_<slot>_m``, ``Fz_<wheel>_N``.
    static_load : float
        Static wheel load (N); forces above ``PLAUSIBLE["force_over_static"]`` times it stop
        the run.
    what : str
        Where (e.g. "zone 2, crossing panel"), put into the message.

    Raises
    ------
    PassageFailure
        At the first sample beyond a limit: its time, x, the quantity and its value.
    """
    t, x = columns["t_s"], columns["x_m"]
    checks = []
    for name in ("z_wheelset_m", "y_wheelset_m"):
        if name in columns:
            label = "wheelset " + name[0]
            checks.append((name, label, columns[name], PLAUSIBLE["wheelset_m"], "m"))
    for name, values in columns.items():
        if name.startswith("z_rail_"):
            checks.append((name, f"rail {name[7:-2]} deflection", values, PLAUSIBLE["rail_m"], "m"))
    limit = PLAUSIBLE["force_over_static"] * abs(static_load)
    for wheel in ("right", "left"):
        if f"Fz_{wheel}_N" in columns and limit > 0:
            label = f"{wheel} wheel's normal force"
            checks.append((wheel, label, columns[f"Fz_{wheel}_N"], limit, "N"))
    first = None
    for _, label, values, bound, unit in checks:
        with np.errstate(invalid="ignore"):
            bad = np.nonzero(np.abs(np.nan_to_num(values, nan=0.0)) > bound)[0]
        if bad.size and (first is None or bad[0] < first[0]):
            first = (int(bad[0]), label, float(values[bad[0]]), bound, unit)
    if first is None:
        return
    i, label, value, bound, unit = first
    where = f" ({what})" if what else ""
    raise PassageFailure(
        f"implausible run stopped at t = {t[i]:.5f} s, x = {x[i]:.3f} m{where}: "
        f"{label} {value:.4g} {unit} is beyond the physical limit {bound:.4g} {unit}"
    )


def _pair_key(wheel: str, rail: str) -> str:
    return f"{wheel}_{rail}"


def _segment_columns(
    element: WheelRailElement,
    t: np.ndarray,
    q: np.ndarray,
    force: np.ndarray,
    rails: Mapping[str, int],
) -> dict[str, np.ndarray]:
    """Forces and displacements of one zone's run.

    ``q``: stored element coordinates (samples x n); ``force``: the element's stored
    generalised forces, the left-hand side K q - f_user of its equations, so that the force
    a wheel puts on a rail is +force[z] (pressing down) and -force[y] (lateral, on the
    rail); ``rails``: slot -> index of its y in the element.
    """
    cols: dict[str, np.ndarray] = {"t_s": t, "x_m": element.x0 + element.v * t}
    wheel_of = {bp.pair.rail: bp.pair.wheel for bp in element.pairs}
    for wheel in ("right", "left"):
        for name in ("Fz", "Fy"):
            cols[f"{name}_{wheel}_N"] = np.zeros_like(t)
    for slot, i in rails.items():
        key = _pair_key(wheel_of[slot], slot)
        cols[f"Fz_{key}_N"], cols[f"Fy_{key}_N"] = force[:, i + 1].copy(), -force[:, i]
        cols[f"Fz_{wheel_of[slot]}_N"] += cols[f"Fz_{key}_N"]
        cols[f"Fy_{wheel_of[slot]}_N"] += cols[f"Fy_{key}_N"]
    for i, name in enumerate(
        ("y_wheelset_m", "z_wheelset_m", "roll_wheelset_rad", "yaw_wheelset_rad")
    ):
        cols[name] = q[:, i]
    for slot, i in rails.items():
        cols[f"y_rail_{slot}_m"], cols[f"z_rail_{slot}_m"] = q[:, i], q[:, i + 1]
    return cols


def _join(segments: list[dict[str, np.ndarray]]) -> dict[str, np.ndarray]:
    """Concatenate zone segments; a column missing in a segment is NaN there (rail not present)."""
    names: list[str] = []
    for seg in segments:
        names += [n for n in seg if n not in names]
    out = {}
    for n in names:
        out[n] = np.concatenate([seg.get(n, np.full(len(seg["t_s"]), np.nan)) for seg in segments])
    return out


def _peak(
    cols: Mapping[str, np.ndarray], name: str, x_range: tuple[float, float], signed: bool = False
) -> float:
    x = cols["x_m"]
    sel = (x >= x_range[0]) & (x <= x_range[1])
    if not sel.any():
        return math.nan
    values = cols[name][sel]
    return float(values[np.argmax(np.abs(values))] if signed else values.max())


def _contact_losses(fz: np.ndarray) -> int:
    """Number of times a wheel lost all contact (its total normal force fell to zero)."""
    loaded = fz > 0.0
    return int(np.count_nonzero(loaded[:-1] & ~loaded[1:]))


@dataclass
class _ZoneSystem:
    """One zone's Exudyn system and what the passage needs of it."""

    container: Any  #: exudyn.SystemContainer
    mbs: Any  #: exudyn.MainSystem
    zone: Zone
    element: WheelRailElement
    names: dict  #: node name ("wheelset", "yaw", "sprung", "sleeper", "rail_r1", "m0_r1") -> node
    rails: dict  #: rail slot touched by a wheel -> index of its y in the element
    sensors: list  #: sensors of the coordinates of the element's nodes, in element order
    params: CoRunningParameters  #: the zone's set, with the route's cross-section
    force_sensor: int  #: stores the contact element's generalised forces every step

    @property
    def sleeper_y(self) -> float:
        return self.params.zone.sleeper_y


def _initial_guess(vehicle: Vehicle) -> tuple[float, float]:
    """Wheelset and sprung-mass z (m) with the contacts closed, so Hertz springs have stiffness."""
    W = vehicle.static_wheel_load
    z_w = -3.0 * (W / vehicle.contact.C_H) ** (2.0 / 3.0)
    return z_w, z_w - 0.5 * vehicle.m_s * 9.81 / vehicle.k_z


def _build(
    turnout: Turnout,
    route: Route,
    vehicle: Vehicle,
    zone: Zone,
    settings: PassageSettings,
    x0: float,
    v: float,
) -> _ZoneSystem:
    from dataclasses import replace

    import exudyn as exu
    from exudyn.itemInterface import ObjectGenericODE2, SensorBody, SensorNode

    from exudyn_turnout.corunning.track import add_co_running_track

    container = exu.SystemContainer()
    mbs = container.AddSystem()
    params = co_running_parameters(
        turnout, zone=zone.index, layers=settings.layers, source=settings.source
    )
    params = replace(params, zone=route.zone(params.zone))
    track = add_co_running_track(mbs, params, x0, v, mechanism=settings.track_mechanism)
    veh = add_vehicle(mbs, vehicle, track.ground, *_initial_guess(vehicle))
    pairs = [p for p in route.pairs_in(zone) if p.rail in zone.active_rails]
    slots = [r for r in zone.active_rails if any(p.rail == r for p in pairs)]
    for r in slots:
        if len({p.wheel for p in pairs if p.rail == r}) > 1:
            raise PassageError(
                f"route {route.name}: rail {r} is touched by both wheels in zone {zone.index}"
            )
    rails = {r: 6 + 2 * i for i, r in enumerate(slots)}
    element = WheelRailElement(
        vehicle, route, [BoundPair(p, rails[p.rail], rails[p.rail] + 1) for p in pairs], x0, v
    )
    nodes = [veh.wheelset_node, veh.yaw_node, veh.sprung_node] + [
        track.wheel_nodes[r] for r in slots
    ]
    M, K = np.zeros((element.n, element.n)), np.zeros((element.n, element.n))
    M[3, 3], K[3, 3] = vehicle.J_yaw, vehicle.k_yaw
    contact = mbs.AddObject(
        ObjectGenericODE2(
            nodeNumbers=nodes, massMatrix=M, stiffnessMatrix=K, forceUserFunction=element
        )
    )
    force_sensor = mbs.AddSensor(
        SensorBody(
            bodyNumber=contact,
            storeInternal=True,
            writeToFile=False,
            outputVariableType=exu.OutputVariableType.Force,
        )
    )
    sensors = [
        mbs.AddSensor(
            SensorNode(
                nodeNumber=n,
                storeInternal=True,
                writeToFile=False,
                outputVariableType=exu.OutputVariableType.Coordinates,
            )
        )
        for n in nodes
    ]
    names = {
        "wheelset": veh.wheelset_node,
        "yaw": veh.yaw_node,
        "sprung": veh.sprung_node,
        "sleeper": track.sleeper_node,
    }
    names.update({f"rail_{r}": n for r, n in track.rail_nodes.items()})
    names.update({f"m0_{r}": n for r, n in track.layer_nodes.items()})
    mbs.Assemble()
    return _ZoneSystem(container, mbs, zone, element, names, rails, sensors, params, force_sensor)


def _node_state(system: _ZoneSystem) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    import exudyn as exu

    data = system.mbs.systemData
    q = np.asarray(data.GetODE2Coordinates(exu.ConfigurationType.Current))
    q_t = np.asarray(data.GetODE2Coordinates_t(exu.ConfigurationType.Current))
    out = {}
    for name, node in system.names.items():
        i = system.mbs.GetNodeODE2Index(node)
        k = np.atleast_1d(system.mbs.GetNodeOutput(node, exu.OutputVariableType.Coordinates)).size
        out[name] = (q[i : i + k].copy(), q_t[i : i + k].copy())
    return out


_NODE_DOF = {"sleeper": ("y_t", "z_t", "phi_t")}


def _dof_of(name: str) -> tuple[str, ...]:
    """Coordinate names (corunning.modal) of a track node ("rail_r1", "m0_r1", "sleeper")."""
    if name in _NODE_DOF:
        return _NODE_DOF[name]
    kind, _, slot = name.partition("_")
    return (f"y_{slot}", f"z_{slot}") if kind == "rail" else (f"y_m0_{slot}", f"z_m0_{slot}")


def _track_vector(state: dict, system: _ZoneSystem, index: int) -> dict[str, float]:
    """Track coordinates (index 0) or velocities (1) of ``state`` by coordinate name."""
    out: dict[str, float] = {}
    for name in system.names:
        if name in ("wheelset", "yaw", "sprung"):
            continue
        out.update(zip(_dof_of(name), state[name][index]))
    return out


def _wheel_rail_loads(
    system: _ZoneSystem, state: dict, layers: int
) -> dict[str, tuple[float, float]]:
    """Total (vertical, lateral) force on each rail slot touched, from the element at ``state``."""
    q = np.concatenate([state[n][0] for n in _element_nodes(system, layers)])
    q_t = np.concatenate([state[n][1] for n in _element_nodes(system, layers)])
    el, x = system.element, system.element.x_at(system.mbs.systemData.GetTime())
    loads: dict[str, list[float]] = {}
    for bp, pf in zip(el.pairs, el.all_pair_forces(x, q, q_t)):
        acc = loads.setdefault(bp.pair.rail, [0.0, 0.0])
        acc[0], acc[1] = acc[0] + pf.N, acc[1] + pf.F_y
    return {r: (v[0], v[1]) for r, v in loads.items()}


def _static_deflection(
    params, x: float, loads: Mapping[str, tuple[float, float]], layers: int
) -> dict[str, float]:
    """u = K^-1 f of the co-running track (by coordinate name) under the vertical wheel loads.

    Lateral loads are left out on purpose: the two rails' lateral deflections change in
    opposite directions at a zone boundary, which a rigid wheelset cannot follow, and on a
    conical tread that would turn into a vertical load step; lateral states carry over.
    """
    from exudyn_turnout.corunning.modal import assemble_track_matrices, wheel_dof

    m = assemble_track_matrices(params, x)
    f = np.zeros(len(m.dof))
    for rail, (N, _) in loads.items():
        if rail in params.active_rails:
            f[m.index(wheel_dof(rail, "vertical", layers))] -= N
    return dict(zip(m.dof, np.linalg.solve(m.K, f)))


def _carry_over(
    state: dict,
    old: _ZoneSystem,
    new: _ZoneSystem,
    continues: Mapping[str, str],
    layers: int,
    x: float,
) -> None:
    """Set the new zone's initial state from the old zone's final ``state``.

    The static part of the track's deflection is re-based: the old zone's static deflection
    under the current wheel loads is replaced by the new zone's (its parameters differ),
    and the wheelset and sprung mass move with the rails they stand on, so that no wheel
    load jumps; the dynamic deviation from static equilibrium and all velocities carry
    over. A rail that appears starts with the sleeper's motion under it.
    """
    import exudyn as exu

    loads_old = _wheel_rail_loads(old, state, layers)
    source = {slot: continues.get(slot, slot) for slot in new.params.active_rails}
    loads_new = {slot: loads_old[src] for slot, src in source.items() if src in loads_old}
    u_old = _static_deflection(old.params, x, loads_old, layers)
    u_new = _static_deflection(new.params, x, loads_new, layers)
    q_old, v_old = _track_vector(state, old, 0), _track_vector(state, old, 1)
    dyn = {n: q_old[n] - u_old[n] for n in q_old}
    shift = new.sleeper_y - old.sleeper_y  # the sleeper's reference point moved with the zone
    dyn["z_t"] += shift * dyn["phi_t"]
    v_old["z_t"] += shift * v_old["phi_t"]
    q_new, v_new = {}, {}
    for name in u_new:
        axis, _, rest = name.partition("_")
        slot = rest.rsplit("_", 1)[-1]
        src = (
            name.replace(slot, source[slot]) if slot in source else name
        )  # sleeper names have no slot
        if src in dyn:
            q_new[name], v_new[name] = u_new[name] + dyn[src], v_old[src]
        else:  # a rail that appears: the sleeper's motion under it
            arm = new.params.zone.rail_y[slot] - new.sleeper_y
            k = 0 if axis == "y" else 1
            q_new[name] = u_new[name] + (dyn["y_t"] if k == 0 else dyn["z_t"] + arm * dyn["phi_t"])
            v_new[name] = v_old["y_t"] if k == 0 else v_old["z_t"] + arm * v_old["phi_t"]
    vehicle_shift = _vehicle_shift(old, u_old, u_new, loads_old, source, layers)
    mbs, data = new.mbs, new.mbs.systemData
    q = np.asarray(data.GetODE2Coordinates(exu.ConfigurationType.Initial)).copy()
    q_t = np.zeros_like(q)
    for name, node in new.names.items():
        i = mbs.GetNodeODE2Index(node)
        if name in ("wheelset", "yaw", "sprung"):
            values, rates = state[name][0] + vehicle_shift[name], state[name][1]
        else:
            dofs = _dof_of(name)
            values, rates = np.array([q_new[d] for d in dofs]), np.array([v_new[d] for d in dofs])
        q[i : i + len(values)], q_t[i : i + len(values)] = values, rates
    data.SetODE2Coordinates(q, exu.ConfigurationType.Initial)
    data.SetODE2Coordinates_t(q_t, exu.ConfigurationType.Initial)


def _vehicle_shift(
    old: _ZoneSystem,
    u_old: dict,
    u_new: dict,
    loads: Mapping,
    source: Mapping[str, str],
    layers: int,
) -> dict[str, np.ndarray]:
    """Move wheelset and sprung mass with the change of static rail deflection under each wheel."""
    from exudyn_turnout.corunning.modal import wheel_dof

    b = old.element.vehicle.b
    dz: dict[str, list[float]] = {"left": [], "right": []}
    dy: dict[str, list[float]] = {"left": [], "right": []}
    new_slot = {
        src: slot for slot, src in source.items()
    }  # source holds the new zone's active slots only
    for bp in old.element.pairs:
        rail, N = bp.pair.rail, loads.get(bp.pair.rail, (0.0, 0.0))[0]
        if N <= 0.0 or rail not in new_slot:
            continue
        for axis, acc in (("vertical", dz), ("lateral", dy)):
            a, b_ = wheel_dof(rail, axis, layers), wheel_dof(new_slot[rail], axis, layers)
            if a in u_old and b_ in u_new:
                acc[bp.pair.wheel].append(u_new[b_] - u_old[a])
    mean = {
        w: (float(np.mean(dz[w])) if dz[w] else 0.0, float(np.mean(dy[w])) if dy[w] else 0.0)
        for w in dz
    }
    z, y = 0.5 * (mean["left"][0] + mean["right"][0]), 0.5 * (mean["left"][1] + mean["right"][1])
    roll = (mean["left"][0] - mean["right"][0]) / (2.0 * b)
    return {"wheelset": np.array([y, z, roll]), "yaw": np.zeros(1), "sprung": np.array([y, z])}


def _element_nodes(system: _ZoneSystem, layers: int) -> list[str]:
    body = "m0" if layers == 3 else "rail"
    return ["wheelset", "yaw", "sprung"] + [f"{body}_{r}" for r in system.rails]


def _wheel_loads(system: _ZoneSystem, state: dict, layers: int) -> dict[str, float]:
    """Total normal force (N) on each wheel in ``state``."""
    q = np.concatenate([state[n][0] for n in _element_nodes(system, layers)])
    el, loads = system.element, {"left": 0.0, "right": 0.0}
    for bp, pf in zip(el.pairs, el.all_pair_forces(el.x0, q, np.zeros_like(q))):
        loads[bp.pair.wheel] += pf.N
    return loads


def _solve_static(system: _ZoneSystem) -> None:
    import exudyn as exu

    from exudyn_turnout.corunning.track import simulation_settings

    sim = simulation_settings(1.0, 1.0)
    sim.staticSolver.newton.absoluteTolerance = 1e-4
    try:
        system.mbs.SolveStatic(sim, updateInitialValues=True)
    except (exu.SolverError, RuntimeError) as err:
        raise PassageFailure(
            f"static equilibrium not found at x = {system.element.x0:g} m "
            f"(zone {system.zone.index}): {err}"
        ) from None


def _progress_function(
    progress: Callable[[float, float], None], t_offset: float, total: float, x0: float, v: float
) -> Callable:
    due = [0.0]

    def pre_step(mbs, t):
        if t >= due[0]:
            due[0] = t + 0.02 * total
            progress(min((t_offset + t) / total, 1.0), x0 + v * t)
        return True

    return pre_step


def _run(
    system: _ZoneSystem,
    duration: float,
    settings: PassageSettings,
    t_offset: float,
    total: float,
    progress: Callable | None,
) -> dict[str, np.ndarray]:
    """Integrate one zone for ``duration`` s; return its columns (time shifted by t_offset)."""
    import exudyn as exu

    from exudyn_turnout.corunning.track import simulation_settings

    h = settings.time_step
    sim = simulation_settings(
        duration, h, 0.999 * (settings.output_step or h)
    )  # every step: no rounding skips
    sim.timeIntegration.numberOfSteps = max(1, int(math.ceil(duration / h - 1e-9)))
    sim.timeIntegration.generalizedAlpha.spectralRadius = settings.spectral_radius
    # 1 N residual: 2e-5 of a wheel load; peaks equal those at 1e-4 N to 0.2 N, with half
    # the iterations
    sim.timeIntegration.newton.absoluteTolerance = NEWTON_ABSOLUTE_TOLERANCE
    el = system.element
    if progress is not None:
        system.mbs.SetPreStepUserFunction(
            _progress_function(progress, t_offset, total, el.x0, el.v)
        )
    try:
        system.mbs.SolveDynamic(sim)
    except (exu.SolverError, RuntimeError) as err:
        t = system.mbs.systemData.GetTime()
        raise PassageFailure(
            f"solver failed at t = {t_offset + t:.5f} s, x = {el.x_at(t):.3f} m "
            f"(zone {system.zone.index}, {system.zone.name}): {str(err).strip()}"
        ) from None
    stored = [system.mbs.GetSensorStoredData(sensor) for sensor in system.sensors]
    t = stored[0][:, 0]
    q = np.hstack([a[:, 1:] for a in stored])
    force = system.mbs.GetSensorStoredData(system.force_sensor)[:, 1:]
    finite = np.all(np.isfinite(q), axis=1) & np.all(np.isfinite(force), axis=1)
    if not finite.all():
        bad = t[~finite][0]
        raise PassageFailure(
            f"solution diverged at t = {t_offset + bad:.5f} s, x = {el.x_at(bad):.3f} m "
            f"(zone {system.zone.index}): reduce the time step"
        )
    cols = _segment_columns(el, t, q, force, system.rails)
    cols["t_s"] = t + t_offset
    return cols


def _zones_of_run(turnout: Turnout, x_a: float, x_b: float) -> list[Zone]:
    return [z for z in turnout.zones if min(z.x_end, x_b) - max(z.x_start, x_a) > 1e-9]


def simulate_passage(
    turnout: Turnout,
    settings: PassageSettings = PassageSettings(),
    vehicle: Vehicle | None = None,
    progress: Callable[[float, float], None] | None = None,
    *,
    track: str | None = None,
    fe_options=None,
) -> PassageResult:
    """Run the vehicle through the turnout on a co-running track or on the FE track.

    One entry point whatever the track: ``track="2-layer"`` or ``"3-layer"`` (the paper's
    co-running models, Figs 2, 3) or ``"fe"`` (the FE reference,
    :func:`~exudyn_turnout.passage.fe_track.simulate_fe_passage`, vertical only for now).

    Parameters
    ----------
    turnout : Turnout
        From :func:`~exudyn_turnout.inputs.turnout.load_turnout`.
    settings : PassageSettings
        The scenario: route, speed, x range, time step, output step; for the co-running
        tracks also the parameter source and the spring mechanism.
    vehicle : Vehicle, optional
        Default: the packaged Manchester benchmark wheelset.
    progress : callable(fraction, x), optional
        Called about every 2 % of the run.
    track : {"2-layer", "3-layer", "fe"}, optional
        Default: ``settings.layers`` layers of co-running track.
    fe_options : FEPassageOptions, optional
        Mesh and solver options of the FE track (``track="fe"`` only).

    Returns
    -------
    PassageResult
        ``columns``: ``t_s``, ``x_m``; per wheel and rail ``Fz_<wheel>_<rail>_N`` (normal force
        pressing the rail down) and ``Fy_<wheel>_<rail>_N`` (lateral force on the rail, positive
        left); per wheel ``Fz_<wheel>_N``, ``Fy_<wheel>_N``; wheelset ``y``, ``z``, ``roll``,
        ``yaw``; per rail touched, the contact body's ``y_rail_<rail>_m``, ``z_rail_<rail>_m``
        (NaN where that rail is not part of the zone). ``summary``: peaks (see
        :func:`passage_summary`).

    Raises
    ------
    PassageError
        Bad settings (one line naming the problem) or a solver failure (time and position).
    """
    if track is not None and track not in TRACKS:
        raise PassageError(f"track must be one of {', '.join(TRACKS)}, got {track!r}")
    if track == "fe":
        from exudyn_turnout.passage.fe_track import simulate_fe_passage

        return simulate_fe_passage(turnout, settings, vehicle, fe_options, progress=progress)
    if track is not None:
        settings = replace(settings, layers=int(track[0]))
    vehicle = vehicle or load_vehicle()
    x_a, x_b = _check(settings, turnout, vehicle)
    route = load_route(turnout, settings.route)
    for text in speed_warnings(route, settings.speed_kmh, x_a, x_b):
        warnings.warn(text, SpeedWarning, stacklevel=2)
    zones = _zones_of_run(turnout, x_a, x_b)
    wall = time.perf_counter()
    with _QuietExudyn():
        return _simulate(turnout, settings, vehicle, route, zones, x_a, x_b, progress, wall)


def _simulate(
    turnout: Turnout,
    settings: PassageSettings,
    vehicle: Vehicle,
    route: Route,
    zones: list[Zone],
    x_a: float,
    x_b: float,
    progress: Callable | None,
    wall: float,
) -> PassageResult:
    v = settings.v
    static = _build(turnout, route, vehicle, zones[0], settings, x_a, 0.0)
    _solve_static(static)
    state = _node_state(static)
    static_loads = _wheel_loads(static, state, settings.layers)
    _check_static(state, static_loads, x_a, vehicle)
    W = 0.5 * (static_loads["left"] + static_loads["right"])
    segments, x, t_offset, previous, total = [], x_a, 0.0, static, (x_b - x_a) / v
    for k, zone in enumerate(zones):
        system = _build(turnout, route, vehicle, zone, settings, x, v)
        _carry_over(
            state,
            previous,
            system,
            route.continues.get(zone.index, {}) if k else {},
            settings.layers,
            x,
        )
        duration = (min(zone.x_end, x_b) - x) / v
        cols = _run(system, duration, settings, t_offset, total, progress)
        check_plausible(cols, W, f"zone {zone.index}, {zone.name}")
        segments.append(cols if k == 0 else {n: c[1:] for n, c in cols.items()})
        state, previous = _node_state(system), system
        x, t_offset = min(zone.x_end, x_b), t_offset + duration
    columns = _join(segments)
    summary = passage_summary(columns, turnout, settings, static_loads, time.perf_counter() - wall)
    return PassageResult(settings, columns, summary, tuple(max(z.x_start, x_a) for z in zones))


def _check_static(
    state: Mapping[str, tuple[np.ndarray, np.ndarray]],
    loads: Mapping[str, float],
    x: float,
    vehicle: Vehicle,
) -> None:
    """Stop on an absurd static state: deflections beyond :data:`PLAUSIBLE`, or wheel loads
    that do not carry the vehicle (their sum off the weight by more than 20 %)."""
    cols = {
        "t_s": np.zeros(1),
        "x_m": np.full(1, x),
        "z_wheelset_m": state["wheelset"][0][1:2],
        "y_wheelset_m": state["wheelset"][0][0:1],
    }
    for name, (q, _) in state.items():
        if name.startswith("rail_"):
            cols[f"z_{name}_m"] = q[1:2]
    try:
        check_plausible(cols, vehicle.static_wheel_load, "static equilibrium")
    except PassageFailure as err:
        message = str(err).replace("implausible run stopped", "absurd static state")
        raise PassageFailure(message) from None
    total = loads["left"] + loads["right"]
    if not abs(total - 2.0 * vehicle.static_wheel_load) <= 0.2 * 2.0 * vehicle.static_wheel_load:
        raise PassageFailure(
            f"absurd static state at x = {x:g} m: the wheel loads sum to {total:.4g} N, "
            f"the vehicle weighs {2.0 * vehicle.static_wheel_load:.4g} N"
        )


def _regions(turnout: Turnout) -> dict[str, tuple[float, float]]:
    """Regions of the turnout file where peaks are taken (``switch``, ``crossing``)."""
    return {name: turnout.regions[name] for name in ("switch", "crossing")}


def _argpeak(
    cols: Mapping[str, np.ndarray], name: str, x_range: tuple[float, float], signed: bool
) -> tuple[float, float]:
    """(peak, x of the peak) of column ``name`` in x_range; (nan, nan) if none (or all NaN)."""
    x = cols["x_m"]
    values = np.where((x >= x_range[0]) & (x <= x_range[1]), cols[name], np.nan)
    if not np.isfinite(values).any():
        return math.nan, math.nan
    i = int(np.nanargmax(np.abs(values)) if signed else np.nanargmax(values))
    return float(values[i]), float(x[i])


def _contact_peaks(
    columns: Mapping[str, np.ndarray], regions: Mapping[str, tuple[float, float]]
) -> dict[str, object]:
    """Peaks per wheel and per contact (rail slot), and which wheel and rail carry each largest one.

    Keys: ``peak_<Fz|Fy>_<region>_<wheel>_<slot>_N`` (every wheel/rail pair of the run),
    ``peak_<Fz|Fy>_<region>_<wheel>_N`` (per wheel, both wheels), and for the largest
    (|Fy| for Fy) of the region ``max_<Fz|Fy>_<region>_N``, ``_wheel``, ``_rail``, ``_x_m``.
    """
    out: dict[str, object] = {}
    pairs = [n[3:-2].split("_") for n in columns if n.startswith("Fz_") and n.count("_") == 3]
    for q, signed in (("Fz", False), ("Fy", True)):
        for where, rng in regions.items():
            best = None
            for wheel in ("right", "left"):
                peak = _argpeak(columns, f"{q}_{wheel}_N", rng, signed)[0]
                out[f"peak_{q}_{where}_{wheel}_N"] = peak
            for wheel, slot in pairs:
                name = f"{q}_{wheel}_{slot}_N"
                if name not in columns:
                    continue
                value, x = _argpeak(columns, name, rng, signed)
                out[f"peak_{q}_{where}_{wheel}_{slot}_N"] = value
                if math.isfinite(value) and (best is None or abs(value) > abs(best[0])):
                    best = (value, wheel, slot, x)
            value, wheel_of, rail_of, x_of = best or (math.nan, None, None, math.nan)
            out[f"max_{q}_{where}_N"], out[f"max_{q}_{where}_wheel"] = value, wheel_of
            out[f"max_{q}_{where}_rail"], out[f"max_{q}_{where}_x_m"] = rail_of, x_of
    return out


def passage_summary(
    columns: Mapping[str, np.ndarray],
    turnout: Turnout,
    settings: PassageSettings,
    static_loads: Mapping[str, float],
    wall_time: float,
) -> dict[str, object]:
    """Peaks at the switch and crossing, per wheel and per contact, and the run's settings.

    ``peak_Fz_switch_N`` etc. are the right wheel's (as the paper's Figs 7, 8), ``_left``
    keys the left wheel's; per wheel ``peak_Fz_crossing_<wheel>_N``, per wheel and contact
    (rail slot) ``peak_Fz_crossing_<wheel>_<slot>_N``, and ``max_Fz_crossing_N`` with
    ``_wheel``, ``_rail``, ``_x_m``: which wheel and rail carry the largest force (on the
    diverging route the left wheel meets the crossing); the same for Fy (largest |Fy|).

    Parameters
    ----------
    columns : mapping
        The passage's columns.
    turnout : Turnout
        Its ``[regions]``.
    settings : PassageSettings
        Stored under ``settings``.
    static_loads : mapping
        Static load (N) of each wheel, "left" and "right".
    wall_time : float
        s.

    Returns
    -------
    dict
    """
    from dataclasses import asdict

    regions = _regions(turnout)
    out: dict[str, object] = {
        "route": settings.route,
        "layers": settings.layers,
        "source": settings.source,
        "speed_kmh": settings.speed_kmh,
        "static_wheel_load_N": float(static_loads["right"]),
        "static_wheel_load_left_N": float(static_loads["left"]),
    }
    for wheel, suffix in (("right", ""), ("left", "_left")):
        for where, rng in regions.items():
            out[f"peak_Fz_{where}{suffix}_N"] = _peak(columns, f"Fz_{wheel}_N", rng)
            out[f"peak_Fy_{where}{suffix}_N"] = _peak(columns, f"Fy_{wheel}_N", rng, signed=True)
    out.update(_contact_peaks(columns, regions))
    out["contact_losses"] = sum(_contact_losses(columns[f"Fz_{w}_N"]) for w in ("right", "left"))
    out["time_step_s"] = settings.time_step
    h_out = settings.output_step
    out["output_step_s"] = h_out if h_out is not None else settings.time_step
    out["x_start_m"], out["x_end_m"] = float(columns["x_m"][0]), float(columns["x_m"][-1])
    out["simulated_time_s"] = float(columns["t_s"][-1] - columns["t_s"][0])
    out["wall_time_s"] = wall_time
    out["switch_region_m"], out["crossing_region_m"] = (
        list(regions["switch"]),
        list(regions["crossing"]),
    )
    out["settings"] = asdict(settings)
    return out


class _QuietExudyn:
    """Silence Exudyn's console warnings (e.g. on user-function memory use) during a solve."""

    def __enter__(self):
        import exudyn as exu

        self._saved = exu.config.suppressWarnings, exu.config.printToConsole
        exu.config.suppressWarnings, exu.config.printToConsole = True, False

    def __exit__(self, *exc):
        import exudyn as exu

        exu.config.suppressWarnings, exu.config.printToConsole = self._saved
        return False


#: Files a passage command writes into its output directory (cleared before a run).
OUTPUT_FILES = ("timeseries.csv", "timeseries.npz", "summary.json", "forces.png")


def write_passage(
    result: PassageResult,
    out_dir,
    fmt: str = "csv",
    provenance: Mapping | None = None,
    figure: Callable | None = None,
) -> dict[str, str]:
    """Write the time series and ``summary.json`` into out_dir; return their paths.

    Files are written into a temporary directory inside out_dir and moved into place
    (``summary.json`` last), so that out_dir never holds a partial or mixed set.

    Parameters
    ----------
    result : PassageResult
    out_dir : str or Path
        Created if missing.
    fmt : {"csv", "npz"}
        ``timeseries.csv`` (columns of a rail that is not part of a zone are empty there,
        no NaN in the file; 9 significant digits) or ``timeseries.npz`` (one float64 array
        per column, NaN where a rail is not part of a zone, and ``summary``: the summary
        as a JSON string).
    provenance : mapping, optional
        Stored as ``summary["provenance"]`` (see :mod:`exudyn_turnout.provenance`).
    figure : callable(directory), optional
        Draws further files (``forces.png``) into the temporary directory before the move.

    Returns
    -------
    dict
        ``{"timeseries": path, "summary": path}`` (and ``"figure"`` with ``figure``).
    """
    import csv
    import json
    import os
    import shutil
    import tempfile
    from pathlib import Path

    from exudyn_turnout.provenance import round_floats

    if fmt not in ("csv", "npz"):
        raise ValueError(f"format must be csv or npz, got {fmt!r}")
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    summary = dict(result.summary)
    if provenance is not None:
        summary["provenance"] = dict(provenance)
    summary_text = json.dumps(round_floats(summary), indent=1)
    names = list(result.columns)
    tmp = Path(tempfile.mkdtemp(prefix=".partial-", dir=out))
    try:
        series = tmp / f"timeseries.{fmt}"
        if fmt == "csv":
            data = np.column_stack([result.columns[n] for n in names])
            with open(series, "w", newline="", encoding="utf-8") as fh:
                w = csv.writer(fh)
                w.writerow(names)
                for row in data:
                    w.writerow(["" if not math.isfinite(v) else f"{v:.9g}" for v in row])
        else:
            arrays = {n: np.asarray(result.columns[n], dtype=float) for n in names}
            arrays["summary"] = np.array(summary_text)
            np.savez(series, **arrays)  # type: ignore[arg-type]  # numpy's stub: **kwds
        (tmp / "summary.json").write_text(summary_text + "\n", encoding="utf-8")
        files = [series.name]
        if figure is not None:
            figure(tmp)
            written = (series.name, "summary.json")
            files += sorted(p.name for p in tmp.iterdir() if p.name not in written)
        for name in files + ["summary.json"]:
            os.replace(tmp / name, out / name)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    paths = {"timeseries": str(out / f"timeseries.{fmt}"), "summary": str(out / "summary.json")}
    if figure is not None:
        paths["figure"] = str(out / "forces.png")
    return paths


def compare_layers(
    turnout: Turnout, settings: PassageSettings = PassageSettings(), vehicle: Vehicle | None = None
) -> dict[int, PassageResult]:
    """The same passage on the two-layer and the three-layer track.

    Parameters
    ----------
    turnout : Turnout
    settings : PassageSettings
        ``layers`` is replaced.
    vehicle : Vehicle, optional

    Returns
    -------
    dict
        {2: PassageResult, 3: PassageResult}.
    """
    from dataclasses import replace

    return {
        layers: simulate_passage(turnout, replace(settings, layers=layers), vehicle)
        for layers in (2, 3)
    }


def peaks_table(results: Mapping[str, PassageResult]) -> str:
    """Plain-text table of the right wheel's peak forces (kN) of labelled results.

    Parameters
    ----------
    results : mapping
        Label -> PassageResult.

    Returns
    -------
    str
    """
    keys = ("peak_Fz_switch_N", "peak_Fz_crossing_N", "peak_Fy_switch_N", "peak_Fy_crossing_N")
    lines = [f"{'model':<28}" + "".join(f"{k[5:-2]:>18}" for k in keys) + f"{'wall (s)':>10}"]
    for label, r in results.items():
        lines.append(
            f"{label:<28}"
            + "".join(f"{float(r.summary[k]) / 1e3:>18.1f}" for k in keys)  # type: ignore[arg-type]
            + f"{float(r.summary['wall_time_s']):>10.2f}"  # type: ignore[arg-type]
        )
    return "\n".join(lines)
