"""The one module that imports matplotlib: every figure function gets it from here.

matplotlib is imported when a figure is drawn, not when the package or a plotting module
is imported (so the command line and the compute functions start fast, and a machine
without a display is fine: matplotlib picks a non-interactive backend there, and
``MPLBACKEND`` is respected).
"""

from __future__ import annotations

from typing import Any

__all__ = ["pyplot", "patches", "pillow_writer"]


def pyplot() -> Any:
    """``matplotlib.pyplot``, imported on first use.

    Returns
    -------
    module
        ``matplotlib.pyplot``.
    """
    import matplotlib.pyplot as plt

    return plt


def patches() -> Any:
    """``matplotlib.patches`` (Rectangle, Polygon, FancyArrowPatch, ...).

    Returns
    -------
    module
        ``matplotlib.patches``.
    """
    import matplotlib.patches as mpatches

    return mpatches


def pillow_writer(fps: float) -> Any:
    """A GIF writer (``matplotlib.animation.PillowWriter``).

    Parameters
    ----------
    fps : float
        Frames per second.

    Returns
    -------
    matplotlib.animation.PillowWriter
    """
    from matplotlib.animation import PillowWriter

    # matplotlib's stub says int; PillowWriter only computes int(1000 / fps): a float works
    return PillowWriter(fps=fps)  # type: ignore[arg-type]
