"""The one module that imports matplotlib: every figure function gets it from here.

matplotlib is imported when a figure is drawn, not when the package or a plotting module
is imported (so the command line and the compute functions start fast, and a machine
without a display is fine: matplotlib picks a non-interactive backend there, and
``MPLBACKEND`` is respected).
"""

from __future__ import annotations

from typing import Any

__all__ = [
    "pyplot",
    "patches",
    "pillow_writer",
    "place_axes",
    "TITLE_LINE",
    "PNG_COMPRESS_LEVEL",
    "save_options",
]

#: in, height of one line of a figure title in the default (medium) font, with its spacing.
TITLE_LINE = 0.2

#: zlib level of the PNG files the package writes: 1 writes a passage figure's same pixels
#: ~0.1 s faster than Pillow's default 6, the file ~4 % larger (bodies.png of the full
#: vehicle's main job: 0.37 against 0.49 CPU s, 357 against 343 kB).
PNG_COMPRESS_LEVEL = 1


def pyplot() -> Any:
    """``matplotlib.pyplot``, imported on first use.

    Returns
    -------
    module
        ``matplotlib.pyplot``.
    """
    import matplotlib.pyplot as plt

    return plt


def save_options(path) -> dict:
    """Keyword arguments of ``savefig`` for a file: the PNG's compression level.

    Parameters
    ----------
    path : str or Path
        The file; its suffix sets the format.

    Returns
    -------
    dict
        ``{"pil_kwargs": {"compress_level": PNG_COMPRESS_LEVEL}}`` for ``.png``, else empty
        (other formats take no Pillow options).
    """
    if str(path).lower().endswith(".png"):
        return {"pil_kwargs": {"compress_level": PNG_COMPRESS_LEVEL}}
    return {}


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


def place_axes(
    fig: Any,
    left: float,
    right: float,
    bottom: float,
    top: float,
    wspace: float = 0.2,
    hspace: float = 0.2,
) -> None:
    """Place a figure's grid of axes with fixed margins, in inches.

    In place of ``fig.tight_layout()`` for figures whose layout is known in advance (the
    passage figures of ``simulate``): tight_layout lays out every tick label and title once
    more to measure them, ~45 % of the time of such a figure (issue 24: 3.1 against 1.7
    CPU s for the five figures of the full vehicle's main job).

    Parameters
    ----------
    fig : matplotlib Figure
    left, right, bottom, top : float
        in, from the figure's edges to the grid of axes (room for tick labels, axis labels
        and the title: :data:`TITLE_LINE` per line).
    wspace, hspace : float
        Space between axes as a fraction of the mean axes width and height.
    """
    width, height = fig.get_size_inches()
    fig.subplots_adjust(
        left=left / width,
        right=1.0 - right / width,
        bottom=bottom / height,
        top=1.0 - top / height,
        wspace=wspace,
        hspace=hspace,
    )
