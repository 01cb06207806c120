"""The vehicle on rigid track: support, static state, connector forces, linearisation, modes.

Used by :mod:`~exudyn_turnout.passage.vehicle.builder` (its linear representation is the
rigid-body model linearised at the static state on rigid track) and by the checks of the
vehicle (natural frequencies, force-free reference configuration).
"""

from __future__ import annotations

import math

import exudyn as exu
import numpy as np
import scipy.linalg
from exudyn.itemInterface import (
    CartesianSpringDamper,
    MarkerBodyPosition,
    ObjectGenericODE2,
)

from exudyn_turnout.passage.vehicle.handles import (
    RigidTrack,
    TrackSupport,
    VehicleBuild,
    VehicleMode,
    point_transform,
)

__all__ = [
    "rigid_track_support",
    "support_wheel_loads",
    "static_settings",
    "dynamic_settings",
    "solve_static",
    "connector_forces_at_reference",
    "vehicle_modes",
]

#: Connector outputs read by :func:`connector_forces_at_reference` (those a type has).
_FORCE_OUTPUTS = (
    exu.OutputVariableType.Force,
    exu.OutputVariableType.ForceLocal,
    exu.OutputVariableType.Torque,
    exu.OutputVariableType.TorqueLocal,
)


def rigid_track_support(
    mbs: exu.MainSystem, build: VehicleBuild, track: RigidTrack = RigidTrack()
) -> TrackSupport:
    """Put every wheel on linear springs to ground at its contact point (rigid track).

    Rigid representation: a ``CartesianSpringDamper`` per wheel from a ground point at the
    nominal contact point (y = -+b, z = 0, x of the wheelset) to the wheel's contact marker,
    stiffness (k_y, k_z, k_x), force-free in the reference configuration. Linear: the same
    springs (small-angle transform of the contact points) as one ObjectGenericODE2 on the
    wheelset nodes.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system the vehicle was added to (not yet assembled).
    build : VehicleBuild
        The vehicle, as returned by :func:`add_vehicle_model`.
    track : RigidTrack
        Support stiffness and damping per wheel.

    Returns
    -------
    TrackSupport
        The support items, for :func:`support_wheel_loads`.
    """
    k3 = np.diag([track.k_y, track.k_z, track.k_x])
    c3 = np.diag([track.c_y, track.c_z, 0.0])
    if build.representation == "rigid":
        items = []
        for ws in build.wheelsets:
            for marker, local in zip(ws.wheel_markers, ws.wheel_positions):
                ground = int(
                    mbs.AddMarker(
                        MarkerBodyPosition(
                            bodyNumber=build.ground, localPosition=[local[0], 0.0, ws.x]
                        )
                    )
                )
                items.append(
                    int(
                        mbs.AddObject(
                            CartesianSpringDamper(
                                markerNumbers=[ground, marker],
                                stiffness=np.diag(k3).tolist(),
                                damping=np.diag(c3).tolist(),
                            )
                        )
                    )
                )
        return TrackSupport(track, tuple(items), build)
    n = sum(len(ws.dof) for ws in build.wheelsets)
    k, d = np.zeros((n, n)), np.zeros((n, n))
    start = 0
    for ws in build.wheelsets:
        sl = slice(start, start + len(ws.dof))
        for r in ws.wheel_positions:
            t = point_transform(list(ws.dof), r)
            k[sl, sl] += t.T @ k3 @ t
            d[sl, sl] += t.T @ c3 @ t
        start += len(ws.dof)
    item = int(
        mbs.AddObject(
            ObjectGenericODE2(
                nodeNumbers=[ws.node for ws in build.wheelsets],
                massMatrix=np.zeros((n, n)),
                stiffnessMatrix=k,
                dampingMatrix=d,
            )
        )
    )
    return TrackSupport(track, (item,), build)


def support_wheel_loads(mbs: exu.MainSystem, support: TrackSupport) -> np.ndarray:
    """Vertical wheel loads (N, positive pressing the rail) carried by the rigid-track supports.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The assembled system holding the supports.
    support : TrackSupport
        As returned by :func:`rigid_track_support`.

    Returns
    -------
    numpy.ndarray
        Shape (n_wheelsets, 2): (right, left) per wheelset, at the current state.
    """
    build = support.build
    if build.representation == "rigid":
        f = [-float(mbs.GetObjectOutput(o, exu.OutputVariableType.Force)[1]) for o in support.items]
        return np.array(f).reshape(-1, 2)
    out = []
    for ws in build.wheelsets:
        q = np.array(mbs.GetNodeOutput(ws.node, exu.OutputVariableType.Coordinates))
        out.append(
            [
                -support.track.k_z * (point_transform(list(ws.dof), r) @ q)[1]
                for r in ws.wheel_positions
            ]
        )
    return np.array(out)


def static_settings() -> exu.SimulationSettings:
    """Quiet static-solver settings: Newton tolerance in force units, no files.

    Returns
    -------
    exudyn.SimulationSettings
        Verbose off, Newton relative tolerance 1e-10 and absolute 1e-6 N, one load step,
        no solution file.
    """
    settings = exu.SimulationSettings()
    settings.staticSolver.verboseMode = 0
    settings.staticSolver.newton.relativeTolerance = 1e-10
    settings.staticSolver.newton.absoluteTolerance = 1e-6
    settings.staticSolver.numberOfLoadSteps = 1
    settings.solution.file.write = False
    settings.timeIntegration.verboseMode = 0
    return settings


def dynamic_settings(end_time: float, step: float) -> exu.SimulationSettings:
    """Quiet generalized-alpha settings (spectral radius 0.8, modified Newton, fixed step).

    Parameters
    ----------
    end_time : float
        s, end of the time integration.
    step : float
        s, time step (also the sensors' write period).

    Returns
    -------
    exudyn.SimulationSettings
        :func:`static_settings` plus the time-integration settings above.
    """
    s = static_settings()
    s.timeIntegration.endTime = end_time
    s.timeIntegration.numberOfSteps = max(1, int(round(end_time / step)))
    s.timeIntegration.generalizedAlpha.spectralRadius = 0.8
    s.timeIntegration.newton.useModifiedNewton = True
    s.timeIntegration.newton.absoluteTolerance = 1e-4
    s.timeIntegration.adaptiveStep = False
    s.solution.sensors.writePeriod = step
    return s


def solve_static(mbs: exu.MainSystem) -> np.ndarray:
    """Static equilibrium under gravity; it becomes the initial state. Quiet, no files.

    ``mbs`` must be assembled.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The assembled system; its initial values are replaced by the equilibrium.

    Returns
    -------
    numpy.ndarray
        ODE2 coordinates (m, rad) at static equilibrium.
    """
    previous = exu.config.printToConsole
    exu.config.printToConsole = False
    try:
        ok = mbs.SolveStatic(static_settings(), updateInitialValues=True)
    finally:
        exu.config.printToConsole = previous
    if not ok:
        raise RuntimeError("static solver did not converge")
    return np.array(mbs.systemData.GetODE2Coordinates())


def connector_forces_at_reference(mbs: exu.MainSystem) -> dict[int, np.ndarray]:
    """Force and torque outputs of every ``Connector*`` spring-damper with all ODE2
    coordinates and velocities zero (the reference configuration).

    Reads ``OutputVariableType.Force``, ``ForceLocal``, ``Torque``, ``TorqueLocal``, those
    the connector type has (``RigidBodySpringDamper`` has only the local ones); coordinate
    constraints (``ConnectorCoordinate``) have no force law and are skipped. Leaves the
    current state at zero. ``mbs`` must be assembled.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The assembled system.

    Returns
    -------
    dict of int to numpy.ndarray
        Object index -> concatenated force (and torque) components.
    """
    data = mbs.systemData
    n = len(data.GetODE2Coordinates())
    data.SetODE2Coordinates([0.0] * n, exu.ConfigurationType.Current)
    data.SetODE2Coordinates_t([0.0] * n, exu.ConfigurationType.Current)
    out = {}
    for i in range(data.NumberOfObjects()):
        kind = mbs.GetObject(i)["objectType"]
        if not kind.startswith("Connector") or kind == "ConnectorCoordinate":
            continue
        parts = []
        for output in _FORCE_OUTPUTS:
            try:
                parts.append(np.atleast_1d(mbs.GetObjectOutput(i, output)))
            except ValueError:  # exudyn.ExudynValueError: the type has no such output
                pass
        if not parts:
            raise ValueError(f"connector {i} ({kind}) has no force or torque output")
        out[i] = np.concatenate(parts)
    return out


def linearized_matrices(mbs: exu.MainSystem) -> list[np.ndarray]:
    previous = exu.config.printToConsole
    exu.config.printToConsole = False
    try:
        return [np.asarray(a) for a in mbs.ComputeLinearizedSystem(static_settings())]
    finally:
        exu.config.printToConsole = previous


def _coordinate_names(mbs: exu.MainSystem, build: VehicleBuild) -> list[str]:
    n = len(mbs.systemData.GetODE2Coordinates())
    names = [""] * n
    for handles in build.bodies():
        start = mbs.GetNodeODE2Index(handles.node)
        for dname, k in handles.dof.items():
            names[start + k] = f"{handles.name}.{dname}"
    return names


def vehicle_modes(mbs: exu.MainSystem, build: VehicleBuild) -> tuple[VehicleMode, ...]:
    """Vibration modes of a vehicle-alone system, linearised at its initial state.

    Call after :func:`solve_static` (the equilibrium is then the initial state). M, K, D
    come from ``mbs.ComputeLinearizedSystem()``; held coordinates and coordinates of other
    items are removed. The undamped frequencies solve K v = w^2 M v; each undamped mode is
    paired with the damped mode (state-space eigenvalue lambda) of highest modal assurance
    criterion for its damping ratio.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The assembled system holding the vehicle alone (e.g. on :func:`rigid_track_support`).
    build : VehicleBuild
        The vehicle, as returned by :func:`add_vehicle_model`: names the coordinates.

    Returns
    -------
    tuple of VehicleMode
        Sorted by frequency.
    """
    m, k, d = linearized_matrices(mbs)
    names = _coordinate_names(mbs, build)
    removed = {mbs.GetNodeODE2Index(n) + c for n, c in build.held}
    keep = [i for i, name in enumerate(names) if name and i not in removed]
    m, k, d = (a[np.ix_(keep, keep)] for a in (m, k, d))
    names = [names[i] for i in keep]
    w2, vectors = scipy.linalg.eig(k, m)
    order = np.argsort(w2.real)
    w2, vectors = w2.real[order], vectors.real[:, order]
    n = len(keep)
    a = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(m, k), -np.linalg.solve(m, d)]])
    lam, psi = scipy.linalg.eig(a)
    upper = lam.imag > 1e-9
    lam, psi = lam[upper], psi[:n, upper]
    modes = []
    for col in range(n):
        v = vectors[:, col]
        energy = np.abs(v * (m @ v))
        energy = energy / np.sum(energy)
        top = int(np.argmax(energy))
        body, direction = names[top].split(".")
        f_d, zeta = math.nan, math.nan
        if len(lam):
            mac = np.abs(psi.conj().T @ v) ** 2 / (np.sum(np.abs(psi) ** 2, axis=0) * (v @ v))
            best = int(np.argmax(mac))
            f_d = abs(lam[best]) / (2 * math.pi)
            zeta = -lam[best].real / abs(lam[best])
        part = {names[i]: float(energy[i]) for i in np.argsort(-energy) if energy[i] >= 0.01}
        modes.append(
            VehicleMode(
                math.sqrt(max(w2[col], 0.0)) / (2 * math.pi),
                float(f_d),
                float(zeta),
                body,
                direction,
                float(energy[top]),
                part,
            )
        )
    return tuple(modes)
