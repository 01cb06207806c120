"""Figures of the wheel/rail geometry of :mod:`exudyn_turnout.wheel_rail`.

- :func:`plot_contact_band`: contact positions on wheel and rail against the wheelset's
  lateral displacement, or along x (the classic contact-band plot);
- :func:`plot_sections`: rail sections at chosen x with the wheel in contact;
- :func:`plot_wheel_path`: the dip the wheel's path sees across a crossing.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from exudyn_turnout.wheel_rail.geometry import WheelGrid, WheelsetContact, wheel_heights_on_grid
from exudyn_turnout.wheel_rail.sections import SectionGrid, section_at
from exudyn_turnout.wheel_rail.transfer import WheelPath

__all__ = ["plot_contact_band", "plot_sections", "plot_wheel_path"]


def _pyplot():
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt


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
    plt = _pyplot()
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
    plt = _pyplot()
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
    plt = _pyplot()
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
