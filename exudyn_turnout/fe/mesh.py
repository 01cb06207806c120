"""Mesh of the FE turnout model: rail nodes and elements, sleepers, rail pads.

Plane-independent geometry (the vertical and lateral models share it):

- every rail is a chain of beam elements no longer than ``element_length``, with vertex
  nodes at every sleeper it crosses, at its segment boundaries and ends (the element's
  interior nodes of order p are added by the model); rails that start or end on another
  rail share that rail's node (rigid joint);
- rails that reach the ends of the layout continue as plain track for ``extension``
  metres and then for ``absorbing_length`` metres more, over which a loss factor grows
  quadratically from 0 to ``eta_max`` (an absorbing end: waves leaving the turnout die
  out there instead of being reflected by the rail ends). The ramp is long and gentle
  because of the pinned-pinned resonance: there the wave is at the edge of a stop band,
  travels slowly and decays only through the rail's own loss, so the peak height feels
  any change of the track far away, a steep absorber included (12 m + 12 m with
  eta_max = 1 moved the lateral peak of plain track by 0.7 dB when the extension
  doubled; 12 m + 24 m with 0.1 by 0.26 dB, and by < 0.1 dB elsewhere, 1-2000 Hz);
- every rail has the structural loss factor ``rail_loss_factor`` (Table 1 gives no rail
  damping; without it the pinned-pinned peak, where the pads do not move, is unbounded);
- every sleeper position x_i = sleeper_x0 + i L_s carries one sleeper per track present
  (the turnout's bearer, and e.g. the diverging track's own sleeper), a beam along y with
  vertex nodes at its ends and under every rail it carries (rails closer than 1 cm share
  one), elements no longer than ``sleeper_element_length``;
- a rail pad joins each rail node above a sleeper to the sleeper node below it.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from exudyn_turnout.fe.layout import Layout, LayoutRail
from exudyn_turnout.inputs.turnout import Turnout, TurnoutFileError

__all__ = ["FEOptions", "Mesh", "build_mesh"]

_TOL = 1e-6  # m, positions closer than this are the same point
_MERGE_Y = 0.01  # m, rails closer than this on a sleeper share its node (e.g. at the switch toe)


@dataclass(frozen=True)
class FEOptions:
    """Discretisation, damping and model-end options of the FE model."""

    element_order: int = 4  #: polynomial order p of the beam and bar elements
    element_length: float = 0.2  #: m, longest rail element (three quartic elements per 0.6 m bay)
    sleeper_element_length: float = 0.5  #: m, longest sleeper element
    extension: float = 12.0  #: m, plain track beyond each end of the layout, undamped
    absorbing_length: float = 24.0  #: m, then the absorbing end, loss factor ramp
    eta_max: float = 0.1  #: loss factor added to the rail at the model ends (-)
    rail_loss_factor: float = 0.01  #: structural loss factor of every rail (-), not in Table 1

    def __post_init__(self):
        if not (isinstance(self.element_order, int) and 1 <= self.element_order <= 8):
            raise ValueError(
                f"FEOptions.element_order must be an integer 1..8, got {self.element_order!r}"
            )
        for name in ("element_length", "sleeper_element_length", "absorbing_length"):
            if not getattr(self, name) > 0:
                raise ValueError(f"FEOptions.{name} must be > 0, got {getattr(self, name)!r}")
        if not (self.extension >= 0 and self.eta_max >= 0 and self.rail_loss_factor >= 0):
            raise ValueError("FEOptions.extension, eta_max and rail_loss_factor must be >= 0")


@dataclass(frozen=True)
class Mesh:
    """Nodes, elements and pads of the turnout; indices are 0-based."""

    layout: Layout
    options: FEOptions
    x_min: float  #: m, first x of the model (with extensions)
    x_max: float  #: m, last x
    node_x: np.ndarray  #: m, x of each rail node
    elem_nodes: np.ndarray  #: (n, 2) rail nodes of each rail element
    elem_type: tuple[str, ...]  #: rail type name of each rail element
    elem_rail: np.ndarray  #: index into layout.rails of each rail element
    elem_eta: np.ndarray  #: loss factor of each rail element, rail + absorbing end (-)
    rail_nodes: Mapping[str, np.ndarray]  #: rail id -> its node indices, increasing x
    rail_elems: Mapping[str, np.ndarray]  #: rail id -> its element indices, increasing x
    sleeper_x: np.ndarray  #: m, x of each sleeper
    sleeper_centre: np.ndarray  #: m, y of each sleeper's centre
    sleeper_length: np.ndarray  #: m
    sleeper_track: tuple[str, ...]  #: track of each sleeper
    snode_y: np.ndarray  #: m, y of each sleeper node
    selem_nodes: np.ndarray  #: (n, 2) sleeper nodes of each sleeper element
    pad_rail_node: np.ndarray  #: rail node of each pad
    pad_sleeper_node: np.ndarray  #: sleeper node of each pad
    pad_sleeper: np.ndarray  #: sleeper index of each pad
    pad_rail: np.ndarray  #: index into layout.rails of each pad
    pad_type: tuple[str, ...]  #: rail type (Table 1 pad values) of each pad

    @property
    def n_rail_nodes(self) -> int:
        """Number of rail vertex nodes (all rails)."""
        return len(self.node_x)

    @property
    def n_sleeper_nodes(self) -> int:
        """Number of sleeper vertex nodes (all sleepers)."""
        return len(self.snode_y)

    def node_at(self, rail_id: str, x: float) -> int:
        """Rail vertex node of a rail at a position.

        Give the position to :func:`build_mesh` (``points``) to have a node there.

        Parameters
        ----------
        rail_id : str
            Layout rail id.
        x : float
            Position from the switch toe (m).

        Returns
        -------
        int
            Index of the rail node (into ``node_x``).

        Raises
        ------
        ValueError
            x is not on the rail, or the rail has no node there.
        """
        nodes = self.rail_nodes[rail_id]
        x_nodes = self.node_x[nodes]
        if not x_nodes[0] - _TOL <= x <= x_nodes[-1] + _TOL:
            raise ValueError(
                f"x = {x:g} m is not on rail {rail_id} ({x_nodes[0]:g} to {x_nodes[-1]:g} m)"
            )
        nearest = int(np.argmin(np.abs(x_nodes - x)))
        if abs(x_nodes[nearest] - x) > _TOL:
            raise ValueError(
                f"rail {rail_id} has no node at x = {x:g} m (nearest {x_nodes[nearest]:g} m); "
                "add the point to the mesh (build_mesh(points=...))"
            )
        return int(nodes[nearest])


def _extended(rail: LayoutRail, layout: Layout, reach: float) -> tuple[float, float]:
    a = rail.x_from - reach if rail.x_from <= layout.x_start + _TOL else rail.x_from
    b = rail.x_to + reach if rail.x_to >= layout.x_end - _TOL else rail.x_to
    return a, b


def _subdivide(points: np.ndarray, h: float, merge: float = 1e-9) -> np.ndarray:
    """Sorted points, those closer than ``merge`` merged, every gap split into parts <= h."""
    pts = np.sort(np.asarray(points, float))
    pts = pts[np.concatenate([[True], np.diff(pts) > merge])]
    out = [pts[:1]]
    for a, b in zip(pts[:-1], pts[1:]):
        n = max(1, math.ceil((b - a) / h - 1e-9))
        out.append(np.linspace(a, b, n + 1)[1:])
    return np.concatenate(out)


def _rail_positions(
    layout: Layout,
    sleepers: np.ndarray,
    h: float,
    reach: float,
    points: Mapping[str, Sequence[float]],
) -> dict[str, np.ndarray]:
    forced: dict[str, list[float]] = {
        r.id: [float(x) for x in points.get(r.id, ())] for r in layout.rails
    }
    for r in layout.rails:
        if r.start_joins:
            forced[r.start_joins].append(r.x_from)
        if r.end_joins:
            forced[r.end_joins].append(r.x_to)
    out = {}
    for r in layout.rails:
        a, b = _extended(r, layout, reach)
        inner = [s.x_from for s in r.segments[1:]] + forced[r.id]
        on = sleepers[(sleepers > a + _TOL) & (sleepers < b - _TOL)]
        out[r.id] = _subdivide(np.concatenate([[a, b], inner, on]), h)
    return out


def _rail_nodes(
    layout: Layout, positions: dict[str, np.ndarray]
) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    start = np.cumsum([0] + [len(positions[r.id]) for r in layout.rails])
    ids = {r.id: np.arange(start[i], start[i + 1]) for i, r in enumerate(layout.rails)}
    xs = np.concatenate([positions[r.id] for r in layout.rails])

    def node_of(rail_id: str, x: float) -> int:
        k = int(np.argmin(np.abs(positions[rail_id] - x)))
        return int(ids[rail_id][k])

    for r in layout.rails:  # joined ends take the other rail's node
        if r.start_joins:
            ids[r.id][0] = node_of(r.start_joins, r.x_from)
        if r.end_joins:
            ids[r.id][-1] = node_of(r.end_joins, r.x_to)
    used = np.unique(np.concatenate(list(ids.values())))
    renumber = np.full(len(xs), -1)
    renumber[used] = np.arange(len(used))
    return xs[used], {k: renumber[v] for k, v in ids.items()}


def _eta(x: np.ndarray, layout: Layout, o: FEOptions, L_s: float) -> np.ndarray:
    """Loss factor at x: the rail's, plus the absorbing ramp taken at the middle of the
    sleeper bay (one value per bay keeps a bay's loss proportional to its stiffness, which
    the solver's modal elimination of rail bays needs)."""
    bay = layout.sleeper_x0 + (np.floor((x - layout.sleeper_x0) / L_s) + 0.5) * L_s
    depth = np.maximum(layout.x_start - o.extension - bay, bay - layout.x_end - o.extension)
    return o.rail_loss_factor + o.eta_max * np.clip(depth / o.absorbing_length, 0.0, 1.0) ** 2


def _rail_elements(layout, node_x, rail_nodes, options, L_s):
    nodes, types, rails = [], [], []
    for i, r in enumerate(layout.rails):
        n = rail_nodes[r.id]
        nodes.append(np.column_stack([n[:-1], n[1:]]))
        xm = 0.5 * (node_x[n[:-1]] + node_x[n[1:]])
        types += [r.segment_at(float(np.clip(x, r.x_from, r.x_to))).rail_type for x in xm]
        rails.append(np.full(len(xm), i))
    elem_nodes = np.concatenate(nodes)
    xm = node_x[elem_nodes].mean(axis=1)
    counts = np.cumsum([0] + [len(a) for a in rails])
    rail_elems = {r.id: np.arange(counts[i], counts[i + 1]) for i, r in enumerate(layout.rails)}
    return (
        elem_nodes,
        tuple(types),
        np.concatenate(rails),
        _eta(xm, layout, options, L_s),
        rail_elems,
    )


def _bearer(
    turnout: Turnout, layout: Layout, track, x: float, ys: np.ndarray
) -> tuple[float, float]:
    """Centre (m) and length (m) of the sleeper of ``track`` at x carrying rails at ys."""
    if track.sleeper_length is None:
        L, c = turnout.sleeper.length(x), 0.5 * (ys.min() + ys.max())
    else:
        L, c = track.sleeper_length, float(layout.routes[track.route].y(x))
    if min(ys.min() - (c - L / 2), (c + L / 2) - ys.max()) < layout.min_overhang - _TOL:
        what = (
            "sleeper.length"
            if track.sleeper_length is None
            else f"layout.tracks.{track.name}.sleeper_length"
        )
        raise TurnoutFileError(
            f"{layout.source}: {what} = {L:g} m at x = {x:g} m is too short for the rails of "
            f"track {track.name!r} (y from {ys.min():.3f} to {ys.max():.3f} m, "
            f"overhang >= {layout.min_overhang:g} m)"
        )
    return c, L


def build_mesh(
    turnout: Turnout,
    layout: Layout,
    options: FEOptions = FEOptions(),
    points: Mapping[str, Sequence[float]] | None = None,
) -> Mesh:
    """Mesh the layout (see the module docstring).

    Parameters
    ----------
    turnout : Turnout
        Sleeper spacing and lengths, rail types.
    layout : Layout
        From :func:`~exudyn_turnout.fe.layout.load_layout` or ``plain_track_layout``.
    options : FEOptions
        Element order and lengths, extensions and absorbing ends, rail loss factor.
    points : mapping rail id -> positions (m), optional
        Extra rail nodes, e.g. where a receptance is wanted: a point load must sit on a
        node (under it the shear force jumps, which no element polynomial represents).

    Returns
    -------
    Mesh
        Rail and sleeper nodes and elements, and the pads joining them.

    Raises
    ------
    ValueError
        A point is not on its rail.
    """
    points = points or {}
    for rail_id, x_points in points.items():
        rail = layout.rail(rail_id)
        for x in x_points:
            if not rail.x_from - _TOL <= x <= rail.x_to + _TOL:
                raise ValueError(
                    f"x = {x:g} m is not on rail {rail_id} ({rail.x_from:g} to {rail.x_to:g} m)"
                )
    reach = options.extension + options.absorbing_length
    x_min, x_max = layout.x_start - reach, layout.x_end + reach
    L_s = turnout.sleeper.spacing
    i0, i1 = (
        math.ceil((x_min - layout.sleeper_x0) / L_s - 1e-9),
        math.floor((x_max - layout.sleeper_x0) / L_s + 1e-9),
    )
    sleepers = layout.sleeper_x0 + L_s * np.arange(i0, i1 + 1)
    positions = _rail_positions(layout, sleepers, options.element_length, reach, points)
    node_x, rail_nodes = _rail_nodes(layout, positions)
    elem_nodes, elem_type, elem_rail, elem_eta, rail_elems = _rail_elements(
        layout, node_x, rail_nodes, options, L_s
    )
    s = _sleepers(turnout, layout, options, sleepers, positions, rail_nodes, reach)
    return Mesh(
        layout,
        options,
        x_min,
        x_max,
        node_x,
        elem_nodes,
        elem_type,
        elem_rail,
        elem_eta,
        rail_nodes,
        rail_elems,
        **s,
    )


def _one_sleeper(turnout, layout, options, x, track, on, positions, rail_nodes):
    """Centre, length, node positions of the sleeper of ``track`` at x carrying the rails
    ``on`` ((index, LayoutRail) pairs), and its pads (rail node, local sleeper node, rail
    index, rail type); a rail end joined to another rail's node gets no second pad."""
    ys = np.array([float(layout.rail_y(r.id, x)) for _, r in on])
    c, L = _bearer(turnout, layout, track, x, ys)
    y_nodes = _subdivide(
        np.concatenate([[c - L / 2, c + L / 2], ys]), options.sleeper_element_length, merge=_MERGE_Y
    )
    pads, seen = [], set()
    for (i, r), y in zip(on, ys):
        node = int(rail_nodes[r.id][np.argmin(np.abs(positions[r.id] - x))])
        if node not in seen:
            seen.add(node)
            pads.append(
                (
                    node,
                    int(np.argmin(np.abs(y_nodes - y))),
                    i,
                    r.segment_at(float(np.clip(x, r.x_from, r.x_to))).rail_type,
                )
            )
    return c, L, y_nodes, pads


def _sleepers(turnout, layout, options, sleepers, positions, rail_nodes, reach) -> dict:
    """Sleeper and pad fields of :class:`Mesh` for every sleeper position and track."""
    extents = {r.id: _extended(r, layout, reach) for r in layout.rails}
    rows: list[tuple[float, float, float, str]] = []  # x, centre, length, track per sleeper
    y_all: list[np.ndarray] = []
    elems: list[np.ndarray] = []
    pads: list[tuple[int, int, int, int, str]] = []
    n_nodes = 0
    for x in sleepers:
        present = [
            (i, r)
            for i, r in enumerate(layout.rails)
            if extents[r.id][0] - _TOL <= x <= extents[r.id][1] + _TOL
        ]
        for track in layout.tracks.values():
            on = [
                (i, r)
                for i, r in present
                if r.segment_at(float(np.clip(x, r.x_from, r.x_to))).track == track.name
            ]
            if not on:
                continue
            c, L, y_nodes, sleeper_pads = _one_sleeper(
                turnout, layout, options, x, track, on, positions, rail_nodes
            )
            local = np.arange(len(y_nodes))
            elems.append(n_nodes + np.column_stack([local[:-1], local[1:]]))
            pads += [(node, n_nodes + j, len(rows), i, t) for node, j, i, t in sleeper_pads]
            rows.append((x, c, L, track.name))
            y_all.append(y_nodes)
            n_nodes += len(y_nodes)
    sx, sc, sl, st = zip(*rows)
    prn, psn, psl, prl, ptp = zip(*pads)
    return dict(
        sleeper_x=np.array(sx),
        sleeper_centre=np.array(sc),
        sleeper_length=np.array(sl),
        sleeper_track=tuple(st),
        snode_y=np.concatenate(y_all),
        selem_nodes=np.concatenate(elems),
        pad_rail_node=np.array(prn),
        pad_sleeper_node=np.array(psn),
        pad_sleeper=np.array(psl),
        pad_rail=np.array(prl),
        pad_type=tuple(ptp),
    )
