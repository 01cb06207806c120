"""Figures of the wheel/rail geometry of :mod:`exudyn_turnout.wheel_rail`.

- :func:`plot_contact_band`: contact positions on wheel and rail against the wheelset's
  lateral displacement, or along x (the classic contact-band plot);
- :func:`plot_sections`: rail sections at chosen x with the wheel in contact;
- :func:`plot_wheel_path`: the dip the wheel's path sees across a crossing;
- :func:`plot_contact_band_along_x`: contact positions on rail and wheel along x, coloured by
  rail body (from contact tables or a simulation);
- :func:`plot_body_sections`: several rail bodies' sections at chosen x with the wheel at
  its contact height;
- :func:`plot_dip`: the wheel's path over two rail bodies, which body carries it, the
  transfer position and the dip, for several lateral shifts.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from exudyn_turnout.plotting.backend import place_axes, pyplot, save_options
from exudyn_turnout.wheel_rail.geometry import WheelGrid, WheelsetContact, wheel_heights_on_grid
from exudyn_turnout.wheel_rail.sections import SectionGrid, section_at
from exudyn_turnout.wheel_rail.transfer import DipSummary, WheelPath

__all__ = [
    "plot_contact_band",
    "plot_sections",
    "plot_wheel_path",
    "plot_contact_band_along_x",
    "plot_body_sections",
    "plot_dip",
]


def plot_contact_band(result: WheelsetContact, path: str | Path) -> Path:
    """Contact band: contact points on wheel and rail, rolling-radius difference, angle.

    Parameters
    ----------
    result : WheelsetContact
        From :func:`.geometry.solve_wheelset`.
    path : str or Path
        PNG file to write.

    Returns
    -------
    Path
    """
    plt = pyplot()
    figure, axes = plt.subplots(3, 1, figsize=(7, 8), sharex=True)
    y_mm = result.y * 1e3
    axes[0].plot(y_mm, result.s_left * 1e3, ".", label="left wheel, on wheel")
    axes[0].plot(
        y_mm,
        (result.y_rail_left - np.median(result.y_rail_left)) * 1e3,
        ".",
        label="left wheel, on rail (from its centre contact)",
    )
    axes[0].set_ylabel("contact position (mm)")
    axes[0].legend(fontsize=8)
    axes[1].plot(y_mm, result.delta_r * 1e3)
    axes[1].set_ylabel("r_left - r_right (mm)")
    axes[2].plot(y_mm, np.degrees(result.angle_left), label="left")
    axes[2].plot(y_mm, np.degrees(result.angle_right), label="right")
    axes[2].set_ylabel("contact angle (deg)")
    axes[2].set_xlabel("wheelset lateral displacement y (mm, + left)")
    axes[2].legend(fontsize=8)
    for axis in axes:
        axis.grid(True, alpha=0.3)
    figure.tight_layout()
    path = Path(path)
    figure.savefig(path, dpi=120)
    plt.close(figure)
    return path


def plot_sections(
    sections: SectionGrid,
    positions: list,
    wheel: WheelGrid,
    taping_line: float,
    path: str | Path,
    shift: float = 0.0,
    lifts: list | None = None,
) -> Path:
    """Rail sections at chosen x with the wheel drawn at its contact height.

    Parameters
    ----------
    sections : SectionGrid
        Sections along x.
    positions : list of float
        m, positions to draw.
    wheel : WheelGrid
        The wheel.
    taping_line : float
        m, nominal lateral position of the taping line.
    path : str or Path
        PNG file to write.
    shift : float
        m, lateral shift of the wheel.
    lifts : list of float, optional
        m, wheel heights per position (e.g. :attr:`.transfer.WheelPath.height`); 0 if
        not given.

    Returns
    -------
    Path
    """
    plt = pyplot()
    figure, axes = plt.subplots(
        len(positions), 1, figsize=(7, 2.2 * len(positions)), sharex=True, squeeze=False
    )
    for k, x in enumerate(positions):
        axis = axes[k][0]
        rail = section_at(sections, x)
        lift = 0.0 if lifts is None else lifts[k]
        heights, _s = wheel_heights_on_grid(wheel, sections.y, taping_line, shift, lift)
        axis.plot(sections.y * 1e3, rail * 1e3, "k", label="rail")
        axis.plot(sections.y * 1e3, heights * 1e3, "r", label="wheel")
        axis.set_ylim(-30, 8)
        axis.set_ylabel("z (mm)")
        axis.set_title(f"x = {x:.3f} m", fontsize=9)
        axis.grid(True, alpha=0.3)
    axes[-1][0].set_xlabel("y (mm, towards the field side)")
    axes[0][0].legend(fontsize=8)
    figure.tight_layout()
    path = Path(path)
    figure.savefig(path, dpi=120)
    plt.close(figure)
    return path


def plot_wheel_path(paths: list[WheelPath], path: str | Path) -> Path:
    """Height of the wheel's path and the carrying rail along x, for several shifts.

    Parameters
    ----------
    paths : list of WheelPath
        From :func:`.transfer.wheel_path`.
    path : str or Path
        PNG file to write.

    Returns
    -------
    Path
    """
    plt = pyplot()
    figure, axes = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    for wheel_path in paths:
        label = f"shift {wheel_path.shift * 1e3:+.0f} mm"
        axes[0].plot(wheel_path.x, wheel_path.height * 1e3, label=label)
        axes[1].plot(wheel_path.x, wheel_path.y_rail * 1e3, ".", markersize=3, label=label)
    axes[0].set_ylabel("wheel height (mm)")
    axes[1].set_ylabel("contact on rail y (mm)")
    axes[1].set_xlabel("x (m)")
    for axis in axes:
        axis.grid(True, alpha=0.3)
        axis.legend(fontsize=8)
    figure.tight_layout()
    path = Path(path)
    figure.savefig(path, dpi=120)
    plt.close(figure)
    return path


def plot_contact_band_along_x(
    x,
    y_rail,
    s_wheel,
    body,
    path: str | Path,
    title: str = "",
    x_ranges: list | None = None,
) -> Path:
    """The classic contact-band plot: contact positions on the rail and on the wheel along x.

    One point per contact; points are coloured by the rail body that carries them.

    Parameters
    ----------
    x : array_like
        m, position of each contact along the track.
    y_rail : array_like
        m, lateral position of the contact on the rail (side coordinates: from the track
        centre towards the wheel's field side); NaN points are skipped.
    s_wheel : array_like
        m, lateral position of the contact on the wheel from its taping line (field side
        positive).
    body : array_like of str
        Label of the rail body of each contact.
    path : str or Path
        PNG file to write.
    title : str
        Figure title.
    x_ranges : list of (float, float), optional
        m, one column of panels per x range (e.g. switch and crossing); default: all x.

    Returns
    -------
    Path
    """
    plt = pyplot()
    x, y_rail, s_wheel = (np.asarray(v, float) for v in (x, y_rail, s_wheel))
    body = np.asarray(body, dtype=object)
    ranges = x_ranges or [(float(np.nanmin(x)), float(np.nanmax(x)))]
    figure, axes = plt.subplots(
        2, len(ranges), figsize=(5 * len(ranges) + 2, 6), sharey="row", squeeze=False
    )
    labels = list(dict.fromkeys(body.tolist()))
    colours = {label: f"C{k}" for k, label in enumerate(labels)}
    for column, (low, high) in enumerate(ranges):
        inside = (x >= low) & (x <= high) & np.isfinite(y_rail) & np.isfinite(s_wheel)
        for label in labels:
            mine = inside & (body == label)
            if not np.any(mine):
                continue
            for row, values in enumerate((y_rail, s_wheel)):
                axes[row][column].plot(
                    x[mine],
                    values[mine] * 1e3,
                    ".",
                    markersize=3,
                    color=colours[label],
                    label=str(label),
                )
        axes[1][column].set_xlabel("x (m)")
        for row in range(2):
            axes[row][column].set_xlim(low, high)
            axes[row][column].grid(True, alpha=0.3)
    axes[0][0].set_ylabel("on the rail, y from track centre (mm)")
    axes[1][0].set_ylabel("on the wheel, from taping line (mm)")
    handles = [
        plt.Line2D([], [], marker=".", linestyle="", color=colours[k], label=k) for k in labels
    ]
    axes[0][-1].legend(handles=handles, fontsize=7)
    if title:
        figure.suptitle(title, fontsize=10)
    # fixed margins (in): room for the tick labels, the long y labels and the title; what
    # tight_layout measured, without its second layout of every text (~0.2 s a figure)
    place_axes(figure, 0.75, 0.25, 0.55, 0.45 if title else 0.2, wspace=0.08, hspace=0.18)
    path = Path(path)
    figure.savefig(path, dpi=120, **save_options(path))
    plt.close(figure)
    return path


def plot_body_sections(
    sections: list,
    labels: list,
    positions: list,
    wheel: WheelGrid,
    taping_line: float,
    path: str | Path,
    shift: float = 0.0,
    lifts: list | None = None,
) -> Path:
    """Several rail bodies' sections at chosen x, with the wheel at its contact height.

    Parameters
    ----------
    sections : list of SectionGrid
        One per rail body, same lateral grid (side coordinates of the wheel).
    labels : list of str
        Body labels.
    positions : list of float
        m, positions to draw (one panel each).
    wheel : WheelGrid
        The wheel.
    taping_line : float
        m, nominal lateral position of the taping line.
    path : str or Path
        PNG file to write.
    shift : float
        m, lateral shift of the wheel towards the field side.
    lifts : list of float, optional
        m, wheel height per position (e.g. :attr:`.transfer.WheelPath.height` there).

    Returns
    -------
    Path
    """
    plt = pyplot()
    figure, axes = plt.subplots(
        len(positions), 1, figsize=(7, 2.3 * len(positions)), sharex=True, squeeze=False
    )
    y = sections[0].y
    for k, x in enumerate(positions):
        axis = axes[k][0]
        for k_body, grid in enumerate(sections):
            if grid.x[0] - 1e-9 <= x <= grid.x[-1] + 1e-9:
                axis.plot(grid.y * 1e3, section_at(grid, x) * 1e3, color=f"C{k_body}")
        lift = 0.0 if lifts is None else lifts[k]
        heights, _s = wheel_heights_on_grid(wheel, y, taping_line, shift, lift)
        axis.plot(y * 1e3, heights * 1e3, "k--", label="wheel")
        axis.set_ylim(-30, 8)
        axis.set_ylabel("z (mm)")
        axis.set_title(f"x = {x:.3f} m", fontsize=9)
        axis.grid(True, alpha=0.3)
    axes[-1][0].set_xlabel("y from the track centre, towards the field side (mm)")
    handles = [plt.Line2D([], [], color=f"C{k}", label=label) for k, label in enumerate(labels)]
    handles.append(plt.Line2D([], [], color="k", linestyle="--", label="wheel"))
    axes[0][0].legend(handles=handles, fontsize=7)
    figure.tight_layout()
    path = Path(path)
    figure.savefig(path, dpi=120)
    plt.close(figure)
    return path


def plot_dip(
    paths: list[WheelPath],
    summaries: list[DipSummary],
    path: str | Path,
    title: str = "",
) -> Path:
    """The dip seen by the wheel: its path's height over two rail bodies, per lateral shift.

    Parameters
    ----------
    paths : list of WheelPath
        From :func:`.transfer.two_rail_path` (carrier 1: first body, 0: second).
    summaries : list of DipSummary
        :func:`.transfer.dip_summary` of each path (the transfer is marked).
    path : str or Path
        PNG file to write.
    title : str
        Figure title.

    Returns
    -------
    Path
    """
    plt = pyplot()
    figure, axes = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for wheel_path, summary in zip(paths, summaries):
        label = f"shift {wheel_path.shift * 1e3:+.0f} mm"
        (line,) = axes[0].plot(wheel_path.x, wheel_path.height * 1e3, label=label)
        axes[0].axvline(summary.transfer_x, color=line.get_color(), linestyle=":")
        axes[1].plot(wheel_path.x, wheel_path.second_gap * 1e3, color=line.get_color())
    axes[0].set_ylabel("wheel height (mm)")
    axes[1].set_ylabel("gap of the other rail (mm)")
    axes[1].set_xlabel("x (m); dotted: load transfer")
    axes[1].set_ylim(0.0, 3.0)
    axes[0].legend(fontsize=8)
    for axis in axes:
        axis.grid(True, alpha=0.3)
    if title:
        axes[0].set_title(title, fontsize=10)
    figure.tight_layout()
    path = Path(path)
    figure.savefig(path, dpi=120)
    plt.close(figure)
    return path
