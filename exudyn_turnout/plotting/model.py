"""Pictures of the model: the co-running cross-section drawn as built (paper Figs 2, 3).

:func:`draw_cross_section` draws what :func:`~.cross_section.cross_section_geometry`
lists (bodies and spring-dampers of the co-running cross-section of a zone at x, from the
Exudyn builder's own spring list, values at x). Only the drawing uses matplotlib (from
:mod:`.backend`, when it draws).

The cross-section's data and labels (:mod:`.cross_section`) and the passage animation
(:mod:`.animation`) are re-exported here.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from exudyn_turnout.corunning.parameters import CoRunningParameters
from exudyn_turnout.inputs.routes import Route
from exudyn_turnout.inputs.turnout import RAIL_SLOTS
from exudyn_turnout.inputs.vehicle import Vehicle
from exudyn_turnout.plotting.animation import animate_passage, passage_frames
from exudyn_turnout.plotting.backend import patches, pyplot
from exudyn_turnout.plotting.cross_section import (
    Body,
    Contact,
    CrossSection,
    DrawingLevels,
    SpringDamper,
    cross_section_geometry,
    entry_symbol,
    format_damping,
    format_stiffness,
    lateral_map,
    spring_label,
)

__all__ = [
    "Body",
    "Contact",
    "CrossSection",
    "SpringDamper",
    "animate_passage",
    "cross_section_geometry",
    "draw_cross_section",
    "entry_symbol",
    "format_damping",
    "format_stiffness",
    "passage_frames",
    "spring_label",
]


def _spring_symbol(
    ax: Any,
    start: tuple[float, float],
    end: tuple[float, float],
    offset: float,
    color: str = "0.15",
    coils: int = 4,
    lw: float = 1.0,
) -> None:
    """A spring || dashpot pair between two points (vertical or horizontal)."""
    (y0, z0), (y1, z1) = start, end
    vertical = abs(y1 - y0) < 1e-12
    along0, along1 = (z0, z1) if vertical else (y0, y1)
    across = y0 if vertical else z0

    def line(a: Sequence[float], c: Sequence[float]) -> None:
        pts = (np.array(c), np.array(a)) if vertical else (np.array(a), np.array(c))
        ax.plot(*pts, color=color, lw=lw, solid_capstyle="butt")

    length = along1 - along0
    # common end plates
    line([along0, along0], [across - offset, across + offset])
    line([along1, along1], [across - offset, across + offset])
    # spring branch at -offset
    a = np.linspace(along0 + 0.2 * length, along0 + 0.8 * length, 2 * coils + 1)
    zig = np.array([0.0] + [(-1) ** k * 0.45 * offset for k in range(1, 2 * coils)] + [0.0])
    line([along0, *a, along1], [across - offset, *(across - offset + zig), across - offset])
    # dashpot branch at +offset: rod, cylinder (open towards the piston side), piston
    c = across + offset
    w = 0.45 * offset
    line([along0, along0 + 0.35 * length], [c, c])
    line([along0 + 0.35 * length, along0 + 0.35 * length], [c - w, c + w])
    line([along0 + 0.35 * length, along0 + 0.65 * length], [c - w, c - w])
    line([along0 + 0.35 * length, along0 + 0.65 * length], [c + w, c + w])
    line([along0 + 0.52 * length, along0 + 0.52 * length], [c - 0.7 * w, c + 0.7 * w])
    line([along0 + 0.52 * length, along1], [c, c])


def _hatch(ax: Any, y0: float, y1: float, z: float, dz: float, vertical: bool = False) -> None:
    """Ground symbol: a line with short hatches below (or, vertical, to the left)."""
    if vertical:
        ax.plot([y0, y0], [z - dz, z + dz], color="0.2", lw=1.2)
        for zz in np.linspace(z - dz, z + dz, 7):
            ax.plot([y0 - 0.06, y0], [zz - 0.06, zz], color="0.4", lw=0.7)
        return
    ax.plot([y0, y1], [z, z], color="0.2", lw=1.2)
    for yy in np.arange(y0, y1, 0.08):
        ax.plot([yy, yy + 0.05], [z - dz, z], color="0.4", lw=0.7)


def _block(springs: Sequence[SpringDamper]) -> str:
    return "\n".join(
        f"{entry_symbol(s.k_name)} = {format_stiffness(s.k)}\n"
        f"{entry_symbol(s.c_name)} = {format_damping(s.c)}"
        for s in springs
    )


def draw_cross_section(
    params: CoRunningParameters,
    x: float,
    route: Route | str | None = None,
    vehicle: Vehicle | None = None,
    ax: Any = None,
    *,
    min_gap: float = 1.25,
    fontsize: float = 8.0,
) -> Any:
    """Draw the co-running cross-section of a zone at x as it is built (paper Figs 2, 3).

    Every body and spring-damper comes from :func:`cross_section_geometry` (the Exudyn
    builder's spring list, values at x): sleeper, active rails, m_0 layer (three
    layers), ballast springs to ground, lateral ballast spring, rail pads, and with a
    vehicle the wheelset, its primary suspension and sprung mass. Each spring || dashpot
    is labelled with its entry names and values (MN/m, kN s/m).

    Parameters
    ----------
    params : CoRunningParameters
        Parameter set of the zone (2 or 3 layers, derived or published).
    x : float
        Position (m) in the zone.
    route : Route or str, optional
        Route whose rail positions (and contacts, with a vehicle) are drawn.
    vehicle : Vehicle, optional
        Draw the wheelset above the track.
    ax : matplotlib Axes, optional
        Axes to draw into; a new figure if None.
    min_gap : float
        Smallest drawn distance (m) between rails.
    fontsize : float
        Label font size (points).

    Returns
    -------
    matplotlib Axes
        The axes drawn into.
    """
    plt = pyplot()
    Rectangle = patches().Rectangle

    geo = cross_section_geometry(params, x, route, vehicle, min_gap)
    lv = DrawingLevels()
    ground = geo.body("ground")
    y_lo, y_hi = ground.y_drawn - 0.5 * ground.width, ground.y_drawn + 0.5 * ground.width
    if ax is None:
        top = max(b.z + 0.5 * b.height for b in geo.bodies)
        _, ax = plt.subplots(figsize=(2.0 * (y_hi - y_lo) + 0.6, 1.25 * top + 1.4))
    label = {"fontsize": fontsize, "va": "center", "linespacing": 1.25}
    box = {"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.85}
    colours = {
        "sleeper": "#c9b48f",
        "rail": "#8fa9c9",
        "layer": "#c98f8f",
        "wheelset": "#b0b0b0",
        "sprung_mass": "#d9d9d9",
    }
    _hatch(ax, y_lo, y_hi, lv.ground, 0.08)
    for b in geo.bodies:
        if b.name == "ground":
            continue
        kind = "rail" if b.name in RAIL_SLOTS else "layer" if b.name.startswith("m0_") else b.name
        if b.name == "wheelset":
            _draw_wheelset(ax, b, geo, lv, colours["wheelset"], fontsize)
            continue
        ax.add_patch(
            Rectangle(
                (b.y_drawn - 0.5 * b.width, b.z - 0.5 * b.height),
                b.width,
                b.height,
                fc=colours[kind],
                ec="0.2",
                lw=1.0,
                zorder=3,
            )
        )
        if kind == "rail":
            slot, rest = b.label.split("\n", 1)
            ax.text(
                b.y_drawn,
                b.z,
                slot.split()[0],
                ha="center",
                va="center",
                fontsize=fontsize,
                weight="bold",
                zorder=4,
            )
            ax.text(
                b.y_drawn + 0.5 * b.width + 0.04,
                b.z,
                f"{slot.split()[1]} rail\n{rest}",
                ha="left",
                **{**label, "fontsize": fontsize - 0.5},
                zorder=5,
            )
        elif kind == "layer":
            ax.text(b.y_drawn + 0.5 * b.width + 0.04, b.z, b.label, ha="left", **label, zorder=5)
        else:
            ax.text(b.y_drawn, b.z, b.label, ha="center", **label, zorder=4)
    sleeper = geo.body("sleeper")  # its centre, where the lateral ballast spring acts
    ax.plot(
        [_centre_mark(geo, sleeper.y)],
        [sleeper.z - 0.5 * sleeper.height],
        marker="^",
        color="k",
        ms=5,
        zorder=5,
    )
    _draw_springs(ax, geo.springs, {b.name: b for b in geo.bodies}, label, box)
    _draw_suspension(ax, geo.suspension, label, box)
    for c in geo.contacts:
        ax.plot(
            *zip(c.from_point, c.to_point, strict=True), color="tab:red", ls=":", lw=1.4, zorder=2
        )
    where = f", {geo.route} route" if geo.route else ""
    ax.set_title(
        f"{geo.turnout}: co-running cross-section, zone {geo.zone} ({geo.zone_name}), "
        f"x = {geo.x:g} m\n{geo.layers}-layer model, {geo.source} parameters{where}",
        fontsize=fontsize + 2,
    )
    note = (
        "Lateral positions from the model (y in m, positive left, looking along x); "
        "heights schematic (the model has every body at z = 0).\n"
        "Each connector acts in z and y between the same two points; the lateral ballast "
        "spring acts at the sleeper centre (triangle)."
    )
    if geo.contacts:
        note += " Red dotted: wheel/rail (Hertz) contacts active at x."
    if geo.spread_rails:
        note += f" Rails {', '.join(geo.spread_rails)} are drawn apart (model y in their labels)."
    ax.text(
        0.0,
        -0.01,
        note,
        transform=ax.transAxes,
        ha="left",
        va="top",
        fontsize=fontsize - 1,
        color="0.3",
        wrap=True,
    )
    ax.set_xlim(y_lo - 0.05, y_hi + 0.05)
    ax.set_ylim(lv.ground - 0.15, max(b.z + 0.5 * b.height for b in geo.bodies) + 0.15)
    ax.set_axis_off()
    return ax


def _centre_mark(geo: CrossSection, centre_model_y: float) -> float:
    """Drawn position of the sleeper centre (model y), through the same lateral map."""
    model = {b.name: b.y for b in geo.bodies if b.name in RAIL_SLOTS}
    drawn = {b.name: b.y_drawn for b in geo.bodies if b.name in RAIL_SLOTS}
    return lateral_map(model, drawn)(centre_model_y)


def _draw_springs(
    ax: Any, springs: Sequence[SpringDamper], bodies: Mapping[str, Body], label: dict, box: dict
) -> None:
    by_connector: dict[str, list[SpringDamper]] = {}
    for s in springs:
        by_connector.setdefault(s.name, []).append(s)
    for parts in by_connector.values():
        for s in parts:
            if s.direction == "z":
                _spring_symbol(ax, s.from_point, s.to_point, offset=0.045)
            else:
                _spring_symbol(ax, s.from_point, s.to_point, offset=0.06, coils=3)
                if s.bodies[0] == "ground":
                    _hatch(
                        ax, s.from_point[0], s.from_point[0], s.from_point[1], 0.18, vertical=True
                    )
                else:  # post on the lower body (a bracket from its top left corner for a rail)
                    y, z = s.from_point
                    lower = bodies[s.bodies[0]]
                    top = lower.z + 0.5 * lower.height
                    ys, zs = [y, y], [top, z + 0.09]
                    if s.bodies[0] != "sleeper":
                        ys, zs = [lower.y_drawn - 0.5 * lower.width, *ys], [top, *zs]
                    ax.plot(ys, zs, color="0.2", lw=1.6, zorder=2)
        vertical = [s for s in parts if s.direction == "z"]
        if vertical:  # one block right of the vertical symbol: z lines, then y lines
            s = vertical[0]
            mid = 0.5 * (s.from_point[1] + s.to_point[1])
            ax.text(
                s.from_point[0] + 0.1, mid, _block(parts), ha="left", bbox=box, zorder=6, **label
            )
        else:  # lateral ballast spring: label above it
            s = parts[0]
            ax.text(
                0.5 * (s.from_point[0] + s.to_point[0]) - 0.1,
                s.from_point[1] - 0.2,
                _block(parts),
                ha="center",
                va="top",
                bbox=box,
                zorder=6,
                **{k: v for k, v in label.items() if k != "va"},
            )


def _draw_suspension(ax: Any, springs: Sequence[SpringDamper], label: dict, box: dict) -> None:
    vertical = [s for s in springs if s.direction == "z"]
    for s in vertical:
        _spring_symbol(ax, s.from_point, s.to_point, offset=0.05)
        parts = [p for p in springs if p.name == s.name]
        text = (
            _block(parts)
            .replace("k_{z}", "k_{p,z}")
            .replace("c_{z}", "c_{p,z}")
            .replace("k_{y}", "k_{p,y}")
            .replace("c_{y}", "c_{p,y}")
        )
        side = "left" if s.name.endswith("left") else "right"
        mid = 0.5 * (s.from_point[1] + s.to_point[1])
        dy = 0.12 if side == "left" else -0.12
        ax.text(
            s.from_point[0] + dy,
            mid,
            f"primary, {side}\n{text}",
            ha="left" if side == "left" else "right",
            bbox=box,
            zorder=6,
            **label,
        )


def _draw_wheelset(
    ax: Any, b: Body, geo: CrossSection, lv: DrawingLevels, colour: str, fontsize: float
) -> None:
    Polygon, Rectangle = patches().Polygon, patches().Rectangle

    half = 0.5 * (b.width - lv.wheel_width)
    bottom = b.z - 0.5 * b.height
    for side in (-1.0, 1.0):
        y = b.y_drawn + side * half
        w = lv.wheel_width
        inner = -side  # flange on the inner side of each wheel
        flange_y = y + inner * 0.5 * w
        pts = [
            (y - 0.5 * w, bottom),
            (y + 0.5 * w, bottom),
            (y + 0.5 * w, bottom + b.height),
            (y - 0.5 * w, bottom + b.height),
        ]
        ax.add_patch(Polygon(pts, closed=True, fc=colour, ec="0.2", lw=1.0, zorder=3))
        ax.add_patch(
            Polygon(
                [
                    (flange_y, bottom + 0.1),
                    (flange_y, bottom - 0.12),
                    (flange_y - inner * 0.05, bottom + 0.05),
                ],
                closed=True,
                fc=colour,
                ec="0.2",
                lw=1.0,
                zorder=3,
            )
        )
    ax.add_patch(
        Rectangle(
            (b.y_drawn - half, b.z - 0.06), 2 * half, 0.12, fc=colour, ec="0.2", lw=1.0, zorder=2
        )
    )
    ax.text(
        b.y_drawn,
        b.z + 0.5 * b.height + 0.05,
        b.label,
        ha="center",
        va="bottom",
        fontsize=fontsize,
        bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.85},
        zorder=6,
    )
