"""Zone carry-over on the co-running track: when a wheelset enters a new zone its track is
rebuilt with the new zone's parameters, and the state re-based so that no wheel load jumps.

The old zone's static deflection under the current wheel loads is replaced by the new
zone's, the dynamic deviation from static equilibrium and all velocities carry over, and
the wheelset moves with the static deflection under its wheels."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from exudyn_turnout.corunning.parameters import CoRunningParameters
from exudyn_turnout.inputs.turnout import Zone

__all__ = [
    "dof_of",
    "static_deflection",
    "vehicle_shift",
    "inside_zone",
    "rebase_track",
    "set_named_state",
]

_NODE_DOF = {"sleeper": ("y_t", "z_t", "phi_t")}


def dof_of(name: str) -> tuple[str, ...]:
    """Coordinate names (corunning.modal) of a track node.

    Parameters
    ----------
    name : str
        "rail_r1", "m0_r1" or "sleeper".

    Returns
    -------
    tuple of str
    """
    if name in _NODE_DOF:
        return _NODE_DOF[name]
    kind, _, slot = name.partition("_")
    return (f"y_{slot}", f"z_{slot}") if kind == "rail" else (f"y_m0_{slot}", f"z_m0_{slot}")


def static_deflection(
    params,
    x: float,
    loads: Mapping[str, tuple[float, float]],
    layers: int,
    lateral: bool = False,
) -> dict[str, float]:
    """u = K^-1 f of the co-running track (by coordinate name) under the wheel loads.

    Vertical loads always; lateral loads only with ``lateral`` (the profile contact, whose
    lateral forces at rest are the real N tan(gamma) of each contact point, so that the new
    zone starts in lateral equilibrium too). For the height-table contact lateral loads are
    left out on purpose: the two rails' lateral deflections change in opposite directions at
    a zone boundary, which a rigid wheelset cannot follow, and on its conical tread that
    would turn into a vertical load step; lateral states carry over.

    Parameters
    ----------
    params : CoRunningParameters
        The zone's parameter set.
    x : float
        m, where the track's parameters are evaluated.
    loads : mapping
        Rail slot -> (vertical, lateral) wheel load, N.
    layers : {2, 3}
    lateral : bool
        Apply the lateral loads too.

    Returns
    -------
    dict
        Coordinate name -> static deflection, m (rad for the sleeper's roll).
    """
    from exudyn_turnout.corunning.modal import assemble_track_matrices, wheel_dof

    m = assemble_track_matrices(params, x)
    f = np.zeros(len(m.dof))
    for rail, (N, F_y) in loads.items():
        if rail in params.active_rails:
            f[m.index(wheel_dof(rail, "vertical", layers))] -= N
            if lateral:
                f[m.index(wheel_dof(rail, "lateral", layers))] += F_y
    return dict(zip(m.dof, np.linalg.solve(m.K, f)))


def vehicle_shift(
    element: Any,
    u_old: dict,
    u_new: dict,
    loads: Mapping,
    source: Mapping[str, str],
    layers: int,
) -> dict[str, np.ndarray]:
    """Move wheelset and sprung mass with the change of static rail deflection under each wheel.

    Parameters
    ----------
    element : ContactElement
        The old zone's contact element of the wheelset.
    u_old, u_new : dict
        m, the old and the new zone's static deflections by coordinate name.
    loads : mapping
        Rail slot -> (vertical, lateral) load, N.
    source : mapping
        New zone's rail slot -> the old zone's slot it continues.
    layers : {2, 3}

    Returns
    -------
    dict
        "wheelset" (y, z, roll), "yaw" (zeros), "sprung" (y, z) shifts, m and rad.
    """
    from exudyn_turnout.corunning.modal import wheel_dof

    b = element.vehicle.b
    dz: dict[str, list[float]] = {"left": [], "right": []}
    dy: dict[str, list[float]] = {"left": [], "right": []}
    new_slot = {
        src: slot for slot, src in source.items()
    }  # source holds the new zone's active slots only
    for rail, wheel in element.wheel_of.items():
        N = loads.get(rail, (0.0, 0.0))[0]
        if N <= 0.0 or rail not in new_slot:
            continue
        for axis, acc in (("vertical", dz), ("lateral", dy)):
            a, b_ = wheel_dof(rail, axis, layers), wheel_dof(new_slot[rail], axis, layers)
            if a in u_old and b_ in u_new:
                acc[wheel].append(u_new[b_] - u_old[a])
    mean = {
        w: (float(np.mean(dz[w])) if dz[w] else 0.0, float(np.mean(dy[w])) if dy[w] else 0.0)
        for w in dz
    }
    z, y = 0.5 * (mean["left"][0] + mean["right"][0]), 0.5 * (mean["left"][1] + mean["right"][1])
    roll = (mean["left"][0] - mean["right"][0]) / (2.0 * b)
    # profile contact: a roll moves the running surfaces sideways by r0 roll; move the
    # wheelset back by as much so the wheels stay where they touch
    y -= element.running_surface_depth * roll
    n_yaw = element.n_vehicle - 5  # yaw (and spin) coordinates
    return {"wheelset": np.array([y, z, roll]), "yaw": np.zeros(n_yaw), "sprung": np.array([y, z])}


def inside_zone(zone: Zone, x: float) -> float:
    """x moved into the zone's range [x_start, x_end] (by round-off at its boundary).

    Parameters
    ----------
    zone : Zone
    x : float
        m.

    Returns
    -------
    float
        m.
    """
    return min(max(x, zone.x_start), zone.x_end)


def rebase_track(
    old_params: CoRunningParameters,
    new_params: CoRunningParameters,
    x_old: float,
    x_new: float,
    loads_old: Mapping[str, tuple[float, float]],
    continues: Mapping[str, str],
    q_old: Mapping[str, float],
    v_old: Mapping[str, float],
    layers: int,
    lateral: bool,
) -> tuple[dict[str, float], dict[str, float], dict[str, float], dict[str, float], dict]:
    """A wheelset's track state re-based from its old zone to its new one (module docstring).

    The old zone's static deflection under the current wheel loads is replaced by the new
    zone's; the dynamic deviation from it and the velocities carry over (the sleeper's
    reference point moves with the zone: its heave takes the roll's share). A rail that
    appears starts with the sleeper's motion under it.

    Parameters
    ----------
    old_params, new_params : CoRunningParameters
        The old and the new zone's parameter sets (with the route's cross-section).
    x_old, x_new : float
        m, where each set's static deflection is evaluated (the boundary, inside each
        zone's own range).
    loads_old : mapping
        Rail slot -> (vertical, lateral) wheel load on the old zone's rails, N.
    continues : mapping
        New zone's rail slot -> the old zone's slot it continues (the route's).
    q_old, v_old : mapping
        The old track's coordinates and velocities by coordinate name.
    layers : {2, 3}
    lateral : bool
        The lateral loads are real static loads (profile contact).

    Returns
    -------
    q_new, v_new : dict
        The new track's coordinates and velocities by coordinate name.
    u_old, u_new : dict
        The two static deflections by coordinate name.
    source : dict
        New zone's rail slot -> the old zone's slot it takes its loads from.
    """
    source = {slot: continues.get(slot, slot) for slot in new_params.active_rails}
    loads_new = {slot: loads_old[src] for slot, src in source.items() if src in loads_old}
    u_old = static_deflection(old_params, x_old, loads_old, layers, lateral)
    u_new = static_deflection(new_params, x_new, loads_new, layers, lateral)
    v = dict(v_old)
    dyn = {n: q_old[n] - u_old[n] for n in q_old}
    shift = new_params.zone.sleeper_y - old_params.zone.sleeper_y
    dyn["z_t"] += shift * dyn["phi_t"]
    v["z_t"] += shift * v["phi_t"]
    q_new, v_new = {}, {}
    for name in u_new:
        axis, _, rest = name.partition("_")
        slot = rest.rsplit("_", 1)[-1]
        src = name.replace(slot, source[slot]) if slot in source else name  # sleeper: no slot
        if src in dyn:
            q_new[name], v_new[name] = u_new[name] + dyn[src], v[src]
        else:  # a rail that appears: the sleeper's motion under it
            arm = new_params.zone.rail_y[slot] - new_params.zone.sleeper_y
            if axis == "y":
                q_new[name], v_new[name] = u_new[name] + dyn["y_t"], v["y_t"]
            else:
                q_new[name] = u_new[name] + dyn["z_t"] + arm * dyn["phi_t"]
                v_new[name] = v["z_t"] + arm * v["phi_t"]
    return q_new, v_new, u_old, u_new, source


def set_named_state(
    mbs: Any, names: Mapping[str, int], state: Mapping[str, tuple[np.ndarray, np.ndarray]]
) -> None:
    """Set an Exudyn system's initial coordinates and velocities node by node.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The assembled system.
    names : mapping
        Node name -> node number, every node whose state is set.
    state : mapping
        Node name -> (coordinates, velocities) of that node (its sizes); the coordinates of
        nodes not named keep their initial values, every velocity not given is zero.
    """
    import exudyn as exu

    data = mbs.systemData
    q = np.asarray(data.GetODE2Coordinates(exu.ConfigurationType.Initial)).copy()
    q_t = np.zeros_like(q)
    for name, node in names.items():
        i = mbs.GetNodeODE2Index(node)
        a, b = state[name]
        q[i : i + len(a)], q_t[i : i + len(a)] = a, b
    data.SetODE2Coordinates(q, exu.ConfigurationType.Initial)
    data.SetODE2Coordinates_t(q_t, exu.ConfigurationType.Initial)
