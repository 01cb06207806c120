"""A passage animated: a GIF of the wheelset and rails moving in the cross-section.

:func:`animate_passage` writes a GIF of a passage's cross-section (wheelset and rails at
their computed displacements, magnified, contact forces as arrows); :func:`passage_frames`
picks its samples. matplotlib comes from :mod:`.backend` when a GIF is drawn.
"""

from __future__ import annotations

import itertools
import math
from pathlib import Path
from typing import Any

import numpy as np

from exudyn_turnout.inputs.routes import load_route
from exudyn_turnout.inputs.turnout import RAIL_SLOTS, Turnout
from exudyn_turnout.inputs.vehicle import Vehicle
from exudyn_turnout.plotting.backend import patches, pillow_writer, pyplot

__all__ = ["animate_passage", "passage_frames"]


def passage_frames(n_samples: int, every: int | None = None, max_frames: int = 150) -> np.ndarray:
    """Sample indices of an animation's frames: every ``every``-th sample from the first.

    Parameters
    ----------
    n_samples : int
        Number of output samples of the passage.
    every : int, optional
        Take every ``every``-th sample; default: the smallest step giving at most
        ``max_frames`` frames.
    max_frames : int
        Frame budget used when ``every`` is None.

    Returns
    -------
    numpy.ndarray of int
        Increasing indices into the passage's output samples, starting at 0.
    """
    if n_samples < 1:
        raise ValueError("a passage without samples cannot be animated")
    step = max(1, math.ceil(n_samples / max_frames)) if every is None else int(every)
    if step < 1:
        raise ValueError(f"every must be >= 1, got {every}")
    return np.arange(0, n_samples, step)


def _rail_outline(y: float, z: float) -> np.ndarray:
    """A UIC60-like rail section (m): head 72 mm, web 16.5 mm, foot 150 mm, height 172 mm."""
    h = [
        (-0.036, 0.0),
        (0.036, 0.0),
        (0.036, -0.05),
        (0.008, -0.06),
        (0.008, -0.15),
        (0.075, -0.16),
        (0.075, -0.172),
        (-0.075, -0.172),
        (-0.075, -0.16),
        (-0.008, -0.15),
        (-0.008, -0.06),
        (-0.036, -0.05),
    ]
    return np.array([(y + a, z + b) for a, b in h])


def _wheelset_outline(b: float, r0: float) -> list[np.ndarray]:
    """Wheel sections (tread contact at (+-b, 0), flange inside) and axle (m, wheelset frame)."""
    out = []
    for side in (-1.0, 1.0):
        c, i = side * b, -side  # i points towards the track centre
        out.append(
            np.array(
                [
                    (c - i * 0.075, 0.03),
                    (c - i * 0.075, 0.004),
                    (c + i * 0.035, 0.0),
                    (c + i * 0.045, -0.028),
                    (c + i * 0.06, -0.03),
                    (c + i * 0.068, 0.0),
                    (c + i * 0.068, 0.06),
                    (c + i * 0.025, 0.1),
                    (c + i * 0.025, r0 - 0.12),
                    (c + i * 0.06, r0 - 0.1),
                    (c + i * 0.06, r0 + 0.1),
                    (c - i * 0.035, r0 + 0.1),
                    (c - i * 0.035, 0.1),
                    (c - i * 0.075, 0.06),
                ]
            )
        )
    out.append(
        np.array(
            [
                (-b + 0.06, r0 - 0.07),
                (b - 0.06, r0 - 0.07),
                (b - 0.06, r0 + 0.07),
                (-b + 0.06, r0 + 0.07),
            ]
        )
    )
    return out


def _nice(value: float) -> float:
    """The largest of 1, 2, 5 x 10^n not above value."""
    e = 10.0 ** math.floor(math.log10(value))
    return max(m * e for m in (1.0, 2.0, 5.0) if m * e <= value)


def animate_passage(
    result: Any,
    path: str | Path,
    every: int | None = None,
    scale: float = 200.0,
    fps: float = 15.0,
    *,
    turnout: Turnout | None = None,
    vehicle: Vehicle | None = None,
    max_frames: int = 150,
    dpi: float = 90.0,
    force_scale: float | None = None,
) -> Path:
    """Write a GIF of a passage's cross-section: wheelset and rails moving, forces as arrows.

    Each frame shows the wheelset (a rigid axle with two wheels, at its y, z and roll about
    its reference point at contact height, as in
    :mod:`~exudyn_turnout.passage.contact.height_table`),
    the rails the wheels touch (y, z, and the route's rail height under the wheel) with
    their unloaded outlines dashed, all displacements multiplied by ``scale``, and the
    contact forces on the rails as arrows (kN, with a scale key); the title gives x, t and
    the zone.

    Parameters
    ----------
    result : PassageResult
        From :func:`~exudyn_turnout.passage.run.simulate_passage` (co-running track).
    path : str or Path
        GIF file to write (replaced if it exists).
    every : int, optional
        Take every ``every``-th output sample (:func:`passage_frames`); default: at most
        ``max_frames`` frames.
    scale : float
        Displacement magnification (200: 1 mm is drawn as 0.2 m).
    fps : float
        Frames per second of the GIF.
    turnout : Turnout, optional
        The turnout of the run (rail positions and height profiles); default the packaged one.
    vehicle : Vehicle, optional
        The vehicle of the run (wheel radius, b); default the packaged one.
    max_frames : int
        Frame budget when ``every`` is None.
    dpi : float
        Resolution of the frames (dots per inch of a 7 x 5.4 inch frame).
    force_scale : float, optional
        Arrow length per force (m/kN); default: the largest normal force drawn 0.6 m long.

    Returns
    -------
    Path
        The GIF written.
    """
    plt = pyplot()
    FancyArrowPatch, Polygon = patches().FancyArrowPatch, patches().Polygon

    from exudyn_turnout.inputs.turnout import load_turnout
    from exudyn_turnout.inputs.vehicle import load_vehicle

    turnout = load_turnout() if turnout is None else turnout
    vehicle = load_vehicle() if vehicle is None else vehicle
    route = load_route(turnout, result.settings.route)
    cols = result.columns
    frames = [int(i) for i in passage_frames(len(cols["t_s"]), every, max_frames)]
    slots = [r for r in RAIL_SLOTS if f"z_rail_{r}_m" in cols]
    forces = [
        tuple(n.split("_")[1:3])
        for n in cols
        if n.startswith("Fz_") and n.count("_") == 3 and n.split("_")[2] in slots
    ]
    peak = max([float(np.nanmax(np.abs(cols[f"Fz_{w}_{r}_N"]))) for w, r in forces] + [1.0])
    per_kn = force_scale if force_scale is not None else 0.6 / (peak / 1e3)
    key = _nice(0.5 * peak / 1e3)
    ys = [-vehicle.b, vehicle.b]
    for i in frames:  # lateral extent: the rails drawn in some frame
        zone = route.zone(turnout.zone_at(float(cols["x_m"][i])))
        ys += [
            zone.rail_y[r]
            for r in slots
            if r in zone.active_rails and math.isfinite(float(cols[f"z_rail_{r}_m"][i]))
        ]
    y_lo, y_hi = min(ys) - 0.75, max(ys) + 0.75
    z_lo, z_hi = -1.05, vehicle.r0 + 0.3
    width = 7.0
    fig, ax = plt.subplots(figsize=(width, width * (z_hi - z_lo + 0.5) / (y_hi - y_lo) + 0.3))
    ax.set_xlim(y_lo, y_hi)
    ax.set_ylim(z_lo, z_hi)
    ax.set_aspect("equal")
    ax.set_xlabel("y (m, positive left); vertical and lateral displacements magnified", fontsize=8)
    ax.tick_params(labelsize=7)
    ax.set_yticks([])
    outline = _wheelset_outline(vehicle.b, vehicle.r0)
    for poly in outline:
        ax.add_patch(Polygon(poly, closed=True, fill=False, ec="0.6", ls="--", lw=0.8))
    wheel_parts = [
        Polygon(poly, closed=True, fc="#b0b0b0", ec="0.2", lw=0.9, zorder=3) for poly in outline
    ]
    for part in wheel_parts:
        ax.add_patch(part)
    rails = {}  # slot -> (unloaded outline, moved outline, label)
    for r in slots:
        nominal = Polygon(
            _rail_outline(0.0, 0.0), closed=True, fill=False, ec="0.6", ls="--", lw=0.8
        )
        moved = Polygon(
            _rail_outline(0.0, 0.0), closed=True, fc="#8fa9c9", ec="0.2", lw=0.9, zorder=2
        )
        ax.add_patch(nominal)
        ax.add_patch(moved)
        rails[r] = (
            nominal,
            moved,
            ax.text(0.0, -0.5, r, ha="center", va="top", fontsize=8, color="0.3"),
        )
    arrows = {}
    for wheel, r in forces:
        arrow = FancyArrowPatch(
            (0, 0),
            (0, 0),
            arrowstyle="-|>",
            mutation_scale=11,
            color="tab:red",
            lw=1.6,
            zorder=5,
        )
        ax.add_patch(arrow)
        text = ax.text(
            0,
            0,
            "",
            fontsize=7.5,
            color="tab:red",
            va="center",
            ha="right" if wheel == "right" else "left",
            zorder=6,
        )
        arrows[(wheel, r)] = (arrow, text)
    ky = y_lo + 0.1
    ax.add_patch(
        FancyArrowPatch(
            (ky, z_lo + 0.12),
            (ky + key * per_kn, z_lo + 0.12),
            arrowstyle="-|>",
            mutation_scale=11,
            color="tab:red",
            lw=1.6,
        )
    )
    ax.text(
        ky,
        z_lo + 0.18,
        f"{key:g} kN (force on the rail)",
        fontsize=7.5,
        color="tab:red",
        va="bottom",
    )
    ax.text(
        y_hi - 0.05,
        z_lo + 0.08,
        f"displacements x{scale:g} (1 mm drawn as {scale / 1e3:g} m)\ndashed: unloaded position",
        ha="right",
        va="bottom",
        fontsize=7.5,
        color="0.3",
    )
    title = ax.set_title("", fontsize=9, family="monospace")
    settings = result.settings
    head = (
        f"{turnout.name}, {route.name} route, {settings.layers}-layer, {settings.speed_kmh:g} km/h"
    )

    def top_of(r: str, x: float) -> float:
        heights = [p.height(x) for p in route.pairs if p.rail == r and p.tread_active(x)]
        return max(heights) if heights else 0.0

    def draw(i: int) -> list:
        x, t = float(cols["x_m"][i]), float(cols["t_s"][i])
        zone = route.zone(turnout.zone_at(x))
        place = {}
        for r, (nominal, moved, label) in rails.items():
            y_r, z_r = float(cols[f"y_rail_{r}_m"][i]), float(cols[f"z_rail_{r}_m"][i])
            shown = r in zone.active_rails and math.isfinite(y_r) and math.isfinite(z_r)
            for artist in (nominal, moved, label):
                artist.set_visible(shown)
            if shown:
                y0 = zone.rail_y[r]
                place[r] = (y0 + scale * y_r, scale * (z_r + top_of(r, x)))
                nominal.set_xy(_rail_outline(y0, 0.0))
                moved.set_xy(_rail_outline(*place[r]))
                label.set_position((y0, -0.5))
                label.set_horizontalalignment("center")
        shown_y = sorted((zone.rail_y[r], r) for r in place)
        for (ya, ra), (yb, rb) in itertools.pairwise(shown_y):
            # close rails (a check rail, a blade beside its stock rail): labels apart
            if yb - ya < 0.2:
                rails[ra][2].set_horizontalalignment("right")
                rails[ra][2].set_position((ya - 0.02, -0.5))
                rails[rb][2].set_horizontalalignment("left")
                rails[rb][2].set_position((yb + 0.02, -0.5))
        yw, zw, roll = (
            float(cols[n][i]) for n in ("y_wheelset_m", "z_wheelset_m", "roll_wheelset_rad")
        )
        cos_roll, sin_roll = math.cos(scale * roll), math.sin(scale * roll)
        rot = np.array([[cos_roll, -sin_roll], [sin_roll, cos_roll]])
        for poly, part in zip(outline, wheel_parts, strict=True):
            # roll about the contact-level centre
            part.set_xy(poly @ rot.T + [scale * yw, scale * zw])
        for (wheel, r), (arrow, text) in arrows.items():
            fz, fy = float(cols[f"Fz_{wheel}_{r}_N"][i]), float(cols[f"Fy_{wheel}_{r}_N"][i])
            shown = r in place and math.hypot(fz, fy) >= 100.0
            arrow.set_visible(shown)
            text.set_visible(shown)
            if shown:
                y0, z0 = place[r]
                tip = (y0 + fy / 1e3 * per_kn, z0 - fz / 1e3 * per_kn)
                arrow.set_positions((y0, z0), tip)
                side = -1.0 if wheel == "right" else 1.0
                text.set_position(
                    (
                        min(y0, tip[0]) - 0.1 if side < 0 else max(y0, tip[0]) + 0.1,
                        0.5 * (z0 + tip[1]),
                    )
                )
                text.set_text(
                    f"{wheel} wheel on {r}\nFz = {fz / 1e3:.1f} kN\nFy = {fy / 1e3:.1f} kN"
                )
        title.set_text(f"{head}\nx = {x:7.3f} m   t = {t * 1e3:6.1f} ms   zone {zone.index}")
        return []

    fig.tight_layout()
    out = Path(path)
    # PillowWriter only computes int(1000 / fps): a float fps works
    writer = pillow_writer(fps)
    try:
        with writer.saving(fig, str(out), dpi):
            for i in frames:
                draw(i)
                writer.grab_frame()
    finally:
        plt.close(fig)
    return out
