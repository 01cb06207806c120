"""Packaged wheel/rail data (CONTACT's profiles and reference outputs, Apache-2.0).

See ``exudyn_turnout/data/wheel_rail/NOTICE.md`` for the licence notice and the origin of
every file.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from exudyn_turnout.wheel_rail.geometry import WheelGrid, WheelsetSetup, grid_wheel
from exudyn_turnout.wheel_rail.profile_grid import wheel_surface
from exudyn_turnout.wheel_rail.profiles import Profile, read_simpack_profile
from exudyn_turnout.wheel_rail.sections import (
    SectionGrid,
    lateral_grid,
    place_rail,
    plain_rail_sections,
)

__all__ = [
    "data_dir",
    "profile_path",
    "reference_output_path",
    "s1002_wheel",
    "s1002_surface",
    "uic60_rail",
    "standard_track",
]

#: The Manchester benchmark's wheelset dimensions, the default of the loaders below
#: (a frozen dataclass, so one shared instance is safe).
_BENCHMARK_SETUP = WheelsetSetup()


def data_dir() -> Path:
    """Folder of the packaged wheel/rail data.

    Returns
    -------
    Path
        ``exudyn_turnout/data/wheel_rail``.
    """
    return Path(__file__).resolve().parent.parent / "data" / "wheel_rail"


def profile_path(name: str) -> Path:
    """Path of a packaged profile or slice file, e.g. ``"MBench_S1002_v3.prw"``.

    Parameters
    ----------
    name : str
        File name relative to ``profiles/``.

    Returns
    -------
    Path
    """
    return data_dir() / "profiles" / name


def reference_output_path(name: str) -> Path:
    """Path of a packaged CONTACT input or reference output, e.g. ``"wing_brute.ref_out"``.

    Parameters
    ----------
    name : str
        File name relative to ``reference_outputs/``.

    Returns
    -------
    Path
    """
    return data_dir() / "reference_outputs" / name


def s1002_wheel(setup: WheelsetSetup = _BENCHMARK_SETUP) -> WheelGrid:
    """The Manchester benchmark's S1002 wheel, gridded.

    Parameters
    ----------
    setup : WheelsetSetup
        Grid step and nominal radius (default: the benchmark's ``WheelsetSetup()``).

    Returns
    -------
    WheelGrid
    """
    profile = read_simpack_profile(profile_path("MBench_S1002_v3.prw"), kind="wheel")
    return grid_wheel(profile, step=setup.grid_step, nominal_radius=setup.nominal_radius)


def s1002_surface(step: float = 1e-4) -> tuple[np.ndarray, np.ndarray]:
    """The Manchester benchmark's S1002 wheel on a lateral grid, heights only.

    Equal, bit for bit, to ``s1002_wheel()``'s ``s`` and ``z`` at the same grid step, without
    its slopes and curvatures (and so without importing ``scipy.signal``).

    Parameters
    ----------
    step : float
        m, lateral grid step.

    Returns
    -------
    s, z : numpy.ndarray
        m, lateral coordinate and surface height (:func:`.profile_grid.wheel_surface`).
    """
    profile = read_simpack_profile(profile_path("MBench_S1002_v3.prw"), kind="wheel")
    return wheel_surface(profile, step)


def uic60_rail(setup: WheelsetSetup = _BENCHMARK_SETUP) -> Profile:
    """The Manchester benchmark's UIC60 rail placed in side coordinates.

    The file is already inclined 1:40; other inclinations rotate it by the difference, so
    ``setup.inclination`` is the inclination of the result.

    Parameters
    ----------
    setup : WheelsetSetup
        Gauge, inclination, gauge-point depth (default: the benchmark's ``WheelsetSetup()``).

    Returns
    -------
    Profile
        Top at z = 0, gauge point at ``gauge / 2``.
    """
    profile = read_simpack_profile(profile_path("MBench_UIC60_v3.prr"), kind="rail")
    extra = float(np.tan(np.arctan(setup.inclination) - np.arctan(1.0 / 40.0)))
    return place_rail(profile, gauge=setup.gauge, inclination=extra, gauge_depth=setup.gauge_depth)


def standard_track(
    setup: WheelsetSetup = _BENCHMARK_SETUP, x: np.ndarray | None = None
) -> SectionGrid:
    """Plain UIC60 track sections (one rail, side coordinates) for the S1002 wheel.

    Parameters
    ----------
    setup : WheelsetSetup
        Dimensions.
    x : numpy.ndarray, optional
        m, positions (default: two sections, 0 and 1 m).

    Returns
    -------
    SectionGrid
    """
    grid = lateral_grid(setup.taping_line - 0.11, setup.taping_line + 0.09, setup.grid_step)
    positions = np.array([0.0, 1.0]) if x is None else np.asarray(x, float)
    return plain_rail_sections(uic60_rail(setup), positions, grid, name="UIC60 plain track")
