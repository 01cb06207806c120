"""Co-running track model of a turnout in Exudyn (paper Section 3, Figs 2 and 3).

:func:`add_co_running_track` adds the cross-section that travels with a wheelset to an
Exudyn ``MainSystem``; :func:`linearized_matrices` returns its M, K, D from Exudyn's
linearization (compare :func:`exudyn_turnout.corunning.modal.assemble_track_matrices`, the same
model assembled by hand). Exudyn's 2-D items work in its X-Y plane: here X is the
track's lateral y (positive left) and Y the vertical z (positive up), so a rotation about
Exudyn's Z is a roll about the track's x (running direction).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.advancedUtilities import CreateSymbolicUserFunction
from exudyn.itemInterface import (
    CartesianSpringDamper,
    MarkerBodyPosition,
    MarkerNodePosition,
    MassPoint2D,
    NodePoint2D,
    NodeRigidBody2D,
    ObjectGenericODE2,
    ObjectGround,
    RigidBody2D,
)

from exudyn_turnout.corunning.cross_section import CrossSectionSpring, cross_section_springs
from exudyn_turnout.corunning.fitted import TableEntry
from exudyn_turnout.corunning.modal import TrackMatrices, dof_names
from exudyn_turnout.corunning.parameters import CoRunningParameters, reference_support
from exudyn_turnout.corunning.track_kernel import TrackPlacement, track_force
from exudyn_turnout.inputs.turnout import RAIL_SLOTS, Entry, Polynomial

__all__ = [
    "MECHANISMS",
    "EntryLaw",
    "TrackHandles",
    "add_co_running_track",
    "linearized_matrices",
    "simulation_settings",
]

#: How position-dependent stiffness and damping are evaluated during a simulation.
MECHANISMS = ("symbolic", "python", "constant", "compiled")

_KEEPALIVE = "exudyn_turnout.corunning.track.symbolic_functions"  # mbs.variables key


@dataclass(frozen=True)
class EntryLaw:
    """Entries of a co-running parameter set as expressions of the wheelset position x.

    ``value(entry, x)`` gives the same numbers as
    :meth:`~exudyn_turnout.corunning.parameters.CoRunningParameters.at` (Eqs 10, 11, 14, 15,
    Table 2's ranges, linear over the zone, and fitted tables, piecewise linear over it:
    :class:`~exudyn_turnout.corunning.fitted.TableEntry`), written with + - * and min/max
    only, so that x may be a float (Python user functions) or an Exudyn symbolic expression.
    """

    K_sw: Polynomial  #: Eq 10, N/m
    K_sh: Polynomial  #: Eq 14, N/m
    inv_K_st_z: float  #: 1/(N/m), Eq 11's denominator inverted
    inv_K_st_y: float  #: 1/(N/m), Eq 15's denominator inverted
    x_start: float  #: m, zone start (ramps)
    x_end: float  #: m, zone end (ramps)

    @classmethod
    def of(cls, params: CoRunningParameters) -> EntryLaw:
        """The laws of a parameter set's zone.

        Parameters
        ----------
        params : CoRunningParameters
            Parameter set whose turnout gives the fits K_sw, K_sh (Eqs 10, 14) and whose zone
            gives the range of Table 2's ramps.

        Returns
        -------
        EntryLaw
            The laws, with K_st of the reference rail (Eqs 11, 15) inverted.
        """
        turnout, zone = params.turnout, params.zone
        reference = reference_support(turnout)  # Delta = K(x) / K_st (Eqs 11, 15)
        return cls(
            turnout.K_sw,
            turnout.K_sh,
            1.0 / reference.K_st_z,
            1.0 / reference.K_st_y,
            zone.x_start,
            zone.x_end,
        )

    def value(self, entry: Entry, x: Any, lib: Any = None) -> Any:
        """An entry's value at a position.

        Parameters
        ----------
        entry : Entry
            A parameter entry (``const``, ``Delta_z``, ``Delta_y``, ``ramp`` or a fitted
            ``table``, a sum of clamped ramps).
        x : float or exudyn.symbolic.Real
            Wheelset position from the switch toe (m), a number or a symbolic expression.
        lib : module, optional
            Provides ``min`` and ``max``: None for Python's builtins, ``exudyn.symbolic``
            for a symbolic x.

        Returns
        -------
        float or exudyn.symbolic.Real
            The entry's value (SI units), of the same kind as x.
        """
        lo, hi = (min, max) if lib is None else (lib.min, lib.max)
        if entry.kind == "Delta_z":
            return entry.a * _support_factor(self.K_sw, self.inv_K_st_z, x, lo, hi)
        if entry.kind == "Delta_y":
            return entry.a * _support_factor(self.K_sh, self.inv_K_st_y, x, lo, hi)
        if entry.kind == "ramp":
            zone_fraction = lo(
                hi((x - self.x_start) * (1.0 / (self.x_end - self.x_start)), 0.0), 1.0
            )
            return entry.a + (entry.b - entry.a) * zone_fraction
        if isinstance(entry, TableEntry):
            s = (x - self.x_start) * (1.0 / (self.x_end - self.x_start))
            v0, ramps = entry.ramps()
            acc: Any = v0
            for s_i, inv_ds, dv in ramps:
                acc = acc + dv * lo(hi((s - s_i) * inv_ds, 0.0), 1.0)
            return acc
        return entry.a


def _support_factor(
    profile: Polynomial, inv_K_st: float, x: Any, lo: Callable, hi: Callable
) -> Any:
    """Delta(x) of Eqs 11, 15 with plain track ahead of the toe, with min/max only.

    Equals :func:`exudyn_turnout.corunning.parameters.delta_z` / ``delta_y``: with the blend
    weight w = clamp((x - plain_track_end) / (x_min - plain_track_end), 0, 1), Delta is
    (1 - w) + w K(x) / K_st (K held at its end values outside [x_min, x_max]).
    """
    ratio = inv_K_st * _horner(profile, x, lo, hi)
    plain_end = profile.plain_track_end
    if plain_end is None:
        return ratio
    w = lo(hi((x - plain_end) * (1.0 / (profile.x_min - plain_end)), 0.0), 1.0)
    return (1.0 - w) + w * ratio


def _horner(profile: Polynomial, x: Any, lo: Callable, hi: Callable) -> Any:
    """The polynomial at x clamped to its range, by Horner's scheme (min/max, + and * only)."""
    x_clamped = lo(hi(x, profile.x_min), profile.x_max)
    acc: Any = profile.coefficients[-1]
    for coefficient in reversed(profile.coefficients[:-1]):
        acc = acc * x_clamped + coefficient
    return acc


@dataclass(frozen=True)
class TrackHandles:
    """Exudyn indices of a co-running track added by :func:`add_co_running_track`.

    Node, body and marker maps are keyed by rail slot (active rails only). A wheel
    attaches to ``wheel_markers[rail]``: the rail mass for two layers, the m_0 above it
    for three. ``connectors`` maps ``ballast_z1``, ``ballast_z2``, ``ballast_y``,
    ``pad_rj`` and ``layer_rj`` to their CartesianSpringDamper objects (none for the
    ``compiled`` mechanism: ``force_object`` holds all springs);
    ``position_dependent`` names those whose stiffness or damping follows x.
    """

    params: CoRunningParameters
    x0: float  #: m, position at t = 0
    v: float  #: m/s, speed (x = x0 + v t unless x_coordinate is given)
    mechanism: str  #: one of MECHANISMS
    dof: tuple[str, ...]  #: coordinate names (exudyn_turnout.corunning.modal order)
    ground: int  #: ground object
    sleeper_node: int  #: NodeRigidBody2D of the sleeper (y_t, z_t, phi_t)
    sleeper_body: int  #: RigidBody2D of the sleeper
    rail_nodes: Mapping[str, int]  #: NodePoint2D per active rail (y_rj, z_rj)
    rail_bodies: Mapping[str, int]  #: MassPoint2D per active rail
    rail_markers: Mapping[str, int]  #: MarkerNodePosition per active rail
    layer_nodes: Mapping[str, int]  #: m_0 nodes (three layers; empty for two)
    layer_bodies: Mapping[str, int]  #: m_0 mass points
    layer_markers: Mapping[str, int]  #: m_0 markers
    wheel_markers: Mapping[str, int]  #: per rail, the marker a wheel attaches to
    connectors: Mapping[str, int]  #: CartesianSpringDamper objects by spring name
    position_dependent: tuple[str, ...]  #: names of the connectors that follow x
    x_coordinate: tuple[int, int] | None = None  #: (node, local index) carrying q, x = x0 + q
    #: ObjectGenericODE2 holding every spring (``compiled`` mechanism), or None
    force_object: int | None = None
    _position: list = field(default_factory=lambda: [math.nan], repr=False)  # x read at step start
    _symbol: Any = field(default=None, repr=False)  # exudyn.symbolic.Real holding that x

    @property
    def wheel_nodes(self) -> Mapping[str, int]:
        """Per rail, the node a wheel loads (rail mass, or m_0 for three layers)."""
        return self.layer_nodes if self.params.layers == 3 else self.rail_nodes

    def coordinate_indices(self, mbs: exu.MainSystem) -> dict[str, int]:
        """Global ODE2 index of every track coordinate.

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system the track was added to, after ``mbs.Assemble()``.

        Returns
        -------
        dict of str to int
            Coordinate name (``handles.dof``) to its index in the system's ODE2 coordinates.
        """
        pairs = [(self.sleeper_node, local) for local in range(3)]
        for nodes in (self.rail_nodes, self.layer_nodes):
            pairs += [
                (nodes[rail], local) for rail in RAIL_SLOTS if rail in nodes for local in (0, 1)
            ]
        return {
            name: mbs.GetNodeODE2Index(node) + local for name, (node, local) in zip(self.dof, pairs)
        }

    def update_position(self, mbs: exu.MainSystem) -> None:
        """Read x = x0 + q from ``x_coordinate`` into the user functions (call at step start).

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system the track was added to.
        """
        if self.x_coordinate is None:
            return
        node, index = self.x_coordinate
        x = self.x0 + float(mbs.GetNodeOutput(node, exu.OutputVariableType.Coordinates)[index])
        self._position[0] = x
        if self._symbol is not None:
            self._symbol.SetValue(x)


def add_co_running_track(
    mbs: exu.MainSystem,
    params: CoRunningParameters,
    x0: float,
    v: float = 0.0,
    *,
    mechanism: str = "symbolic",
    x_coordinate: tuple[int, int] | None = None,
    install_pre_step: bool = True,
    force_object: bool = True,
) -> TrackHandles:
    r"""Add the two- or three-layer co-running cross-section (Figs 2, 3) to ``mbs``.

    Seen in the running direction (x into the page), zone 2 layout (all four rails)::

        z ^        [m_0]            [m_0]              [m_0]  [m_0]   <- three layers only:
          |          |                |                  |      |        k_0j,z || c_0j,z and
          +--> y     #  k_01          #  k_02            # k_03 # k_04   k_0j,y || c_0j,y
         (left)    [m_r1]           [m_r2]             [m_r3] [m_r4]  <- rails at zone.rail_y
                     |                |                  |      |        rail pads:
                     #  k_rt1         #  k_rt2           # k_rt3# k_rt4  k_rtj,z || c_rtj,z and
            ==========================================================   k_rtj,y || c_rtj,y
            sleeper m_t, J_t: y_t, z_t, roll phi_t about its centre (zone.sleeper_y)
            ==========================================================
                           |                          |
                           #  k_tg1,z || c_tg1,z      #  k_tg2,z || c_tg2,z
                           |  at zone.ballast_y[0]    |  at zone.ballast_y[1]
            ////////////////////////////////////////////////////////// ground
            lateral: sleeper centre --- k_tg,y || c_tg,y --- ground

    j = 1..4 is the rail slot; "#" is a spring || dashpot pair, acting vertically and
    laterally between rail masses and layers. Only the zone's active rails (Table 3) get
    masses and coordinates. Every spring is a CartesianSpringDamper along the global
    axes: vertical springs attached to the sleeper at lateral distance a from its centre
    act on z_t + a phi_t; all springs attach at the sleeper's centre height, so lateral
    forces do not roll it. All reference positions are at z = 0 and the model carries no
    gravity: coordinates are displacements from the static position under the track's
    own weight.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system to add the track to.
    params : CoRunningParameters
        From :func:`~exudyn_turnout.corunning.parameters.co_running_parameters` (2 or 3 layers).
    x0 : float
        Wheelset position (m) at t = 0; must lie in ``params.zone``. Masses are the zone's.
        A wheelset that leaves the zone keeps the zone's laws (polynomials held at their
        end values, Table 2 ranges at theirs): build the next zone's track there.
    v : float
        Speed (m/s): x = x0 + v t.
    mechanism : {"symbolic", "python", "constant"}
        How entries depending on x (``params.depends_on_x``) follow the wheelset:
        ``symbolic`` (default) Exudyn symbolic user functions, evaluated in C++;
        ``python`` Python ``springForceUserFunction`` (same numbers, several times slower
        per step, see ``benchmarks/bench_receptance.py``);
        ``constant`` built-in springs fixed at their value at x0;
        ``compiled`` no connectors: all springs of the cross-section in one
        ``ObjectGenericODE2`` whose force is one compiled call
        (:mod:`~exudyn_turnout.corunning.track_kernel`: the same laws and kinematics,
        the Jacobian linear), x = x0 + v t.
    x_coordinate : (node, index), optional
        Read the position from an ODE2 coordinate q instead: x = x0 + q, taken at the
        start of each time step (:meth:`TrackHandles.update_position`).
    install_pre_step : bool
        With ``x_coordinate``: install a pre-step function calling ``update_position``
        (it replaces any pre-step function of ``mbs``; pass False and call
        ``handles.update_position(mbs)`` from your own instead).
    force_object : bool
        With ``compiled``: add the springs' object. False: add the bodies only, and put the
        springs (:func:`~exudyn_turnout.corunning.track_kernel.track_force` of this track)
        into an object of your own, e.g. with other forces in one Python call.

    Returns
    -------
    TrackHandles
        Exudyn indices of the nodes, bodies, markers and connectors added.

    Raises
    ------
    ValueError
        For an unknown mechanism, x0 outside the zone, or ``compiled`` with x_coordinate.
    """
    if mechanism not in MECHANISMS:
        raise ValueError(f"mechanism must be one of {', '.join(MECHANISMS)}, got {mechanism!r}")
    if mechanism == "compiled" and x_coordinate is not None:
        raise ValueError("the compiled mechanism follows x = x0 + v t; x_coordinate needs another")
    values = params.at(x0)
    items = _add_bodies(mbs, params, values)
    position: list = [float(x0)]
    symbol = (
        # exudyn's stub does not declare the symbolic submodule (it exists at run time)
        exu.symbolic.Real(f"x_track_{id(position)}", float(x0))  # type: ignore[attr-defined]
        if (x_coordinate is not None and mechanism == "symbolic")
        else None
    )
    x_of = _position_functions(x0, v, x_coordinate, position, symbol)
    compiled = None
    if mechanism == "compiled":
        connectors: dict[str, int] = {}
        dependent = _dependent_springs(params)
        if force_object:
            compiled = _add_compiled_springs(mbs, params, items, float(x0), float(v))
    else:
        connectors, dependent = _add_springs(mbs, params, items, values, mechanism, x_of)
    handles = TrackHandles(
        params,
        float(x0),
        float(v),
        mechanism,
        dof_names(params.active_rails, params.layers),
        connectors=connectors,
        position_dependent=dependent,
        x_coordinate=x_coordinate,
        force_object=compiled,
        _position=position,
        _symbol=symbol,
        **items,
    )
    if x_coordinate is not None and install_pre_step:
        mbs.SetPreStepUserFunction(_pre_step(handles))
    return handles


def _add_springs(
    mbs: exu.MainSystem,
    params: CoRunningParameters,
    items: Mapping,
    values: Mapping[str, float],
    mechanism: str,
    x_of: Callable,
) -> tuple[dict[str, int], tuple[str, ...]]:
    """All spring-dampers at their values at x0; user functions on those that follow x."""
    law = EntryLaw.of(params)
    connectors, dependent = {}, []
    keep = mbs.variables.setdefault(_KEEPALIVE, [])  # symbolic functions must outlive the run
    for spring in cross_section_springs(params):
        connectors[spring.name] = connector = _add_spring(mbs, items, spring, values)
        entries = [params.entries[name] if name else None for name in spring.k + spring.c]
        varies = any(entry is not None and entry.kind != "const" for entry in entries)
        if mechanism != "constant" and varies:
            keep.append(_attach_user_function(mbs, connector, law, entries, mechanism, x_of))
            dependent.append(spring.name)
    return connectors, tuple(dependent)


def _dependent_springs(params: CoRunningParameters) -> tuple[str, ...]:
    """Names of the springs with an entry that is not constant."""
    return tuple(
        spring.name
        for spring in cross_section_springs(params)
        if any(n is not None and params.entries[n].kind != "const" for n in spring.k + spring.c)
    )


def _track_nodes(items: Mapping) -> list[int]:
    """The track's nodes in :func:`~exudyn_turnout.corunning.modal.dof_names` order."""
    return (
        [items["sleeper_node"]]
        + [items["rail_nodes"][r] for r in RAIL_SLOTS if r in items["rail_nodes"]]
        + [items["layer_nodes"][r] for r in RAIL_SLOTS if r in items["layer_nodes"]]
    )


def _add_compiled_springs(
    mbs: exu.MainSystem, params: CoRunningParameters, items: Mapping, x0: float, v: float
) -> int:
    """One ObjectGenericODE2 over the track's coordinates with the compiled springs."""
    dof = dof_names(params.active_rails, params.layers)
    force = track_force([TrackPlacement(params, x0, v, {name: i for i, name in enumerate(dof)})])
    n = len(dof)
    out = np.zeros(n)

    def forceUserFunction(mbs, t, itemNumber, q, q_t):
        out[:] = 0.0
        force.add_forces(t, np.asarray(q, float), np.asarray(q_t, float), out)
        return out

    def jacobianUserFunction(mbs, t, itemNumber, q, q_t, f_q, f_q_t):
        jac = np.zeros((n, n))
        force.add_jacobian(t, f_q, f_q_t, jac)
        return jac

    keep = mbs.variables.setdefault(_KEEPALIVE, [])
    keep.append((force, forceUserFunction, jacobianUserFunction))
    return int(
        mbs.AddObject(
            ObjectGenericODE2(
                nodeNumbers=_track_nodes(items),
                forceUserFunction=forceUserFunction,
                jacobianUserFunction=jacobianUserFunction,
            )
        )
    )


def _pre_step(handles: TrackHandles) -> Callable:
    def pre_step(mbs: exu.MainSystem, t: float) -> bool:
        handles.update_position(mbs)
        return True

    return pre_step


def _add_bodies(
    mbs: exu.MainSystem, params: CoRunningParameters, values: Mapping[str, float]
) -> dict:
    """Ground, sleeper, rail masses and (three layers) m_0 masses with their markers."""
    zone = params.zone
    ground = int(mbs.AddObject(ObjectGround()))
    sleeper_node = int(
        mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[zone.sleeper_y, 0.0, 0.0]))
    )
    sleeper_body = int(
        mbs.AddObject(
            RigidBody2D(nodeNumber=sleeper_node, mass=values["m_t"], inertia=values["J_t"])
        )
    )
    out: dict[str, Any] = {
        "ground": ground,
        "sleeper_node": sleeper_node,
        "sleeper_body": sleeper_body,
    }
    rails = [r for r in RAIL_SLOTS if r in params.active_rails]
    for prefix, mass_of in (
        ("rail", lambda r: values[f"m_r{r[1:]}"]),
        ("layer", lambda r: values["m_0"]),
    ):
        nodes, bodies, markers = {}, {}, {}
        for rail in rails if (prefix == "rail" or params.layers == 3) else ():
            nodes[rail] = int(
                mbs.AddNode(NodePoint2D(referenceCoordinates=[zone.rail_y[rail], 0.0]))
            )
            bodies[rail] = int(
                mbs.AddObject(MassPoint2D(nodeNumber=nodes[rail], mass=mass_of(rail)))
            )
            markers[rail] = int(mbs.AddMarker(MarkerNodePosition(nodeNumber=nodes[rail])))
        out.update(
            {f"{prefix}_nodes": nodes, f"{prefix}_bodies": bodies, f"{prefix}_markers": markers}
        )
    out["wheel_markers"] = dict(out["layer_markers"] if params.layers == 3 else out["rail_markers"])
    return out


def _add_spring(
    mbs: exu.MainSystem, items: Mapping, spring: CrossSectionSpring, values: Mapping[str, float]
) -> int:
    markers = []
    if spring.ground_y is not None:
        markers.append(
            mbs.AddMarker(
                MarkerBodyPosition(
                    bodyNumber=items["ground"], localPosition=[spring.ground_y, 0.0, 0.0]
                )
            )
        )
    if spring.sleeper_y is not None:
        markers.append(
            mbs.AddMarker(
                MarkerBodyPosition(
                    bodyNumber=items["sleeper_body"], localPosition=[spring.sleeper_y, 0.0, 0.0]
                )
            )
        )
    for end in spring.nodes:
        markers.append(
            items["layer_markers"][end[3:]] if end.startswith("m0_") else items["rail_markers"][end]
        )
    stiffness = [values[name] if name else 0.0 for name in spring.k] + [0.0]
    damping = [values[name] if name else 0.0 for name in spring.c] + [0.0]
    return int(
        mbs.AddObject(
            CartesianSpringDamper(markerNumbers=markers, stiffness=stiffness, damping=damping)
        )
    )


def _position_functions(x0: float, v: float, x_coordinate, cell: list, symbol) -> Callable:
    """x(t) for the user functions: x0 + v t, or the value read at the step start."""
    if x_coordinate is None:
        return lambda t: x0 + v * t
    if symbol is not None:
        return lambda t: symbol
    return lambda t: cell[0]


def _attach_user_function(
    mbs: exu.MainSystem,
    connector: int,
    law: EntryLaw,
    entries: list,
    mechanism: str,
    x_of: Callable,
) -> Any:
    """Make a connector's stiffness and damping follow x.

    Returns the symbolic user function, which must be kept alive, or None (Python one).
    """
    # exudyn's stub does not declare the symbolic submodule (it exists at run time)
    lib = exu.symbolic if mechanism == "symbolic" else None  # type: ignore[attr-defined]
    ky, kz, cy, cz = entries

    def value(entry: Entry | None, x: Any) -> Any:
        return 0.0 if entry is None else law.value(entry, x, lib)

    def springForceUserFunction(
        mbs, t, itemNumber, displacement, velocity, stiffness, damping, offset
    ):
        x = x_of(t)
        return [
            value(ky, x) * (displacement[0] - offset[0]) + value(cy, x) * velocity[0],
            value(kz, x) * (displacement[1] - offset[1]) + value(cz, x) * velocity[1],
            0.0,
        ]

    if mechanism == "python":
        mbs.SetObjectParameter(connector, "springForceUserFunction", springForceUserFunction)
        return None
    # exudyn's stub imports ObjectIndex without re-exporting it (it is public at run time)
    object_index = exu.ObjectIndex(connector)  # type: ignore[attr-defined]
    symbolic = CreateSymbolicUserFunction(
        mbs, springForceUserFunction, "springForceUserFunction", object_index
    )
    mbs.SetObjectParameter(connector, "springForceUserFunction", symbolic)
    return symbolic


def linearized_matrices(mbs: exu.MainSystem, handles: TrackHandles) -> TrackMatrices:
    """The track's M, K, D from Exudyn's ``ComputeLinearizedSystem`` at the current state.

    Rows and columns are the track's coordinates in ``handles.dof`` order (other items of
    ``mbs`` are left out). Assembles ``mbs`` if needed. User-function springs are
    linearised by Exudyn with finite differences, at the current time (x = x0 + v t).

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system holding the track.
    handles : TrackHandles
        From :func:`add_co_running_track` on ``mbs``.

    Returns
    -------
    TrackMatrices
        M (kg), K (N/m), D (N s/m) restricted to the track's coordinates.
    """
    M, K, D = mbs.ComputeLinearizedSystem(simulation_settings(1.0, 1.0))
    index = handles.coordinate_indices(mbs)
    selected = [index[name] for name in handles.dof]
    return TrackMatrices(
        M[selected][:, selected], K[selected][:, selected], D[selected][:, selected], handles.dof
    )


def simulation_settings(
    end_time: float,
    step_size: float,
    sensor_period: float | None = None,
    newton_absolute_tolerance: float = 1e-4,
) -> exu.SimulationSettings:
    """Headless, quiet settings: no console output, no solution files, sensors every step.

    Also set ``exudyn.config.printToConsole = False`` to silence Exudyn's own messages.

    Parameters
    ----------
    end_time : float
        Simulated time (s).
    step_size : float
        Time step (s); the number of steps is end_time / step_size rounded (at least 1).
    sensor_period : float, optional
        Period at which sensors store values (s); default every step.
    newton_absolute_tolerance : float
        Newton residual tolerance (N per coordinate). Replaces Exudyn's 1e-10, which lies
        below the round-off of residuals made of 1e8 N/m springs and 1e5 N wheel loads:
        once the track comes to rest Newton would fail and cut the step.

    Returns
    -------
    exudyn.SimulationSettings
        Settings for ``mbs.SolveDynamic`` and ``ComputeLinearizedSystem``.
    """
    settings = exu.SimulationSettings()
    settings.timeIntegration.newton.absoluteTolerance = newton_absolute_tolerance
    settings.timeIntegration.endTime = end_time
    settings.timeIntegration.numberOfSteps = max(1, int(round(end_time / step_size)))
    settings.timeIntegration.verboseMode = 0
    settings.staticSolver.verboseMode = 0
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = step_size if sensor_period is None else sensor_period
    return settings
