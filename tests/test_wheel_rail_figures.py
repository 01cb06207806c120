"""Figures of the wheel/rail geometry are written (smoke test, files in tmp_path only)."""

import numpy as np

from exudyn_turnout.plotting.wheel_rail import plot_contact_band, plot_sections, plot_wheel_path
from exudyn_turnout.wheel_rail.data import s1002_wheel, standard_track
from exudyn_turnout.wheel_rail.geometry import (
    WheelsetSetup,
    rail_row,
    solve_wheelset,
    surface_derivatives,
)
from exudyn_turnout.wheel_rail.transfer import wheel_path


def test_figures_are_written(tmp_path):
    setup = WheelsetSetup()
    wheel = s1002_wheel(setup)
    track = standard_track(setup)
    row = rail_row(track, surface_derivatives(track))
    result = solve_wheelset(np.array([-0.002, 0.0, 0.002]), wheel, row, row, setup)
    band = plot_contact_band(result, tmp_path / "band.png")
    sections = plot_sections(
        track,
        [0.0, 1.0],
        wheel,
        setup.taping_line,
        tmp_path / "sections.png",
        lifts=[-1.8e-4, -1.8e-4],
    )
    path = plot_wheel_path(
        [wheel_path(track, wheel, setup.taping_line, 0.0)], tmp_path / "path.png"
    )
    for figure in (band, sections, path):
        assert figure.stat().st_size > 10_000
