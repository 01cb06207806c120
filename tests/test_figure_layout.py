"""The passage figures of ``simulate`` place their axes with fixed margins (issue 24: in
place of tight_layout, half of a figure's time); every text still lies inside the figure
and no axes title runs into the axes above.

No reference values: the checks are geometric (text boxes against the figure's box).
"""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_turnout.passage.results import PassageResult
from exudyn_turnout.passage.settings import DEFAULT_SETTINGS
from exudyn_turnout.plotting.backend import place_axes, pyplot
from exudyn_turnout.plotting.curves import plot_passage_forces
from exudyn_turnout.plotting.vehicle import plot_vehicle_bodies, plot_wheelset_forces

N = 6000
TITLE = "UIC60-760-1:15 turnout, through route, 100 km/h, Manchester benchmark vehicle 1"


def _result(x0: float = -5.0) -> PassageResult:
    """A full vehicle's columns over 60 m, forces of -150..150 kN (wide tick labels)."""
    t = np.arange(N) * 5e-4
    x = x0 + 65.0 * t / t[-1]
    cols: dict[str, np.ndarray] = {"t_s": t, "x_m": x}
    for wheel in ("right", "left"):
        cols[f"Fz_{wheel}_N"] = 1.5e5 * np.sin(9 * t)
        cols[f"Fy_{wheel}_N"] = -1.5e5 * np.cos(7 * t)
    for k, offset in enumerate((0.0, -2.56, -19.0, -21.56)):
        label = f"ws{k + 1}"
        cols[f"x_{label}_m"] = x + offset
        for wheel in ("right", "left"):
            cols[f"Fz_{label}_{wheel}_N"] = cols[f"Fz_{wheel}_N"]
            cols[f"Fy_{label}_{wheel}_N"] = cols[f"Fy_{wheel}_N"]
    for point in ("car_front", "car_centre", "car_rear", "bogie1", "bogie2"):
        cols[f"y_{point}_m"], cols[f"z_{point}_m"] = 1e-3 * np.sin(t), -1e-3 * t
        cols[f"ay_{point}_mps2"], cols[f"az_{point}_mps2"] = -0.15 * np.sin(9 * t), 0.1 * t
    for point in ("car_front", "car_centre", "car_rear"):
        cols[f"ay_floor_{point}_mps2"] = 0.2 * np.sin(12 * t)
    cols["Fz_primary_ws1_right_N"] = 4.56e4 - 3e3 * t
    cols["Fy_secondary_b1_left_N"] = -2e3 * t
    summary = {
        "static_wheel_load_N": 5.45e4,
        "static_wheel_load_left_N": 5.45e4,
        "switch_region_m": [0.0, 10.0],
        "crossing_region_m": [44.29, 51.0],
        "ride_comfort_note": "EN 12299 Wd (lateral) and Wb (vertical) weighted floor "
        "accelerations over 2.34 s; the comfort index N_MV (95th percentiles of 5 s rms "
        "values over 5 min) and Cc (5 s rms) need >= 5 s of running: not defined here",
    }
    return PassageResult(DEFAULT_SETTINGS, cols, summary)


def _inside(extent, box, what) -> None:
    assert extent.x0 >= box.x0 - 1 and extent.x1 <= box.x1 + 1, what
    assert extent.y0 >= box.y0 - 1 and extent.y1 <= box.y1 + 1, what


def _texts_inside(fig) -> None:
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    suptitle = fig.get_suptitle()
    texts = [t for t in fig.texts if t.get_text()] + [a.get_legend() for a in fig.get_axes()]
    for text in texts:
        if text is not None:
            _inside(text.get_window_extent(renderer), fig.bbox, suptitle)
    for ax in fig.get_axes():  # the drawn tick labels, axis labels and title of each axes
        _inside(ax.get_tightbbox(renderer), fig.bbox, ax.get_ylabel() or ax.get_title())
    axes = fig.get_axes()
    for ax in axes:  # an axes title stays below the top of the figure and above its axes
        title = ax.title
        if title.get_text():
            extent = title.get_window_extent(renderer)
            assert extent.y0 >= ax.get_window_extent(renderer).y1 - 1
            for other in axes:
                if other is not ax:
                    assert not extent.overlaps(other.get_window_extent(renderer)), title


@pytest.mark.parametrize("title", [None, TITLE, TITLE + "\nsecond line"])
def test_forces_figure_texts_inside(title):
    fig, _ = plot_passage_forces([_result()], title=title)
    _texts_inside(fig)
    pyplot().close(fig)


def test_forces_figure_with_a_missing_region_note_inside():
    fig, _ = plot_passage_forces([_result(x0=40.0)], title=TITLE)  # no switch: a note
    assert "no panel: switch" in fig.get_suptitle()  # wrapped to the figure width
    _texts_inside(fig)
    pyplot().close(fig)


@pytest.mark.parametrize("draw", [plot_wheelset_forces, plot_vehicle_bodies])
def test_vehicle_figures_texts_inside(draw):
    fig, _ = draw(_result(), title=TITLE)
    _texts_inside(fig)
    pyplot().close(fig)


def test_place_axes_margins_are_inches():
    fig = pyplot().figure(figsize=(10.0, 5.0))
    fig.add_subplot(1, 1, 1)
    place_axes(fig, 1.0, 0.5, 0.5, 1.0)
    pars = fig.subplotpars
    assert (pars.left, pars.right, pars.bottom, pars.top) == pytest.approx((0.1, 0.95, 0.1, 0.8))
    pyplot().close(fig)
