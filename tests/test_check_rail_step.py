"""The check rail's finer step (issue 22): a co-running run segment where a check-rail contact
carried load runs again at ``PassageSettings.check_rail_time_step`` from its start to the end
of that load (exudyn_turnout.passage.common, corunning_track.vehicle / wheelset).

Reference values: the short window 44.29..45.6 m of the diverging route at 80 km/h, 2 layers,
full vehicle, starts at the check rail's (and the crossing panel's) start; its front wheelset
meets the end of the check rail's entry flare at 45.29 m. Measured at this commit (the
kernel's contact at its minimum along x, issue 22: the flange back touches the flare's end
~35 mm ahead of the axle): the check rail's peak lateral force 85.79 kN refined (1e-4 s,
window at 1e-4 / 4 s), the same bit for bit at 1e-4 / 4 s throughout, 87.18 kN at 1e-4 s
unrefined (+1.6 %). The full diverging run (20..55 m): 87.91 kN at 1e-4 s, 86.31 kN refined,
86.43 / 86.34 / 86.32 kN at 2.5e-5 / 1.25e-5 / 6.25e-6 s throughout (simulate_passage with
check_rail_time_step=None; before issue 22's change 109.1 kN at 1e-4 s, 126.6 kN refined,
128.1 / 127.1 / 126.5 kN, validation/vehicle_step_convergence.md); with the patch along x
(along_x.patch_along_x: the flare truncates the flange back's patch) 83.60 kN at 1e-4 s,
82.10 kN refined, 82.10 / 82.03 / 82.01 kN throughout.
"""

from __future__ import annotations

import argparse
import math
import warnings

import numpy as np
import pytest

from exudyn_turnout.cli.passage import settings_from_args
from exudyn_turnout.passage.check_rail_steps import (
    CHECK_RAIL_MARGIN,
    CheckRailSteps,
    CheckRailStepWarning,
    check_rail_step,
    check_rail_window,
    piece_times,
    refine_pieces,
    refined_line,
)
from exudyn_turnout.passage.common import pick_rows
from exudyn_turnout.passage.fe_track.common import check_rail_steps
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import DEFAULT_SETTINGS, PassageError, PassageSettings

#: m, the short window over the flare's end (module docstring)
WINDOW = (44.29, 45.6)
V_DIVERGING = 80.0 / 3.6  #: m/s


def _grid_step(x_a: float, x_b: float, v: float, h: float = 1e-4) -> float:
    """s, the step of the run's one segment (its duration over ceil(duration / h) steps)."""
    duration = (x_b - x_a) / v
    return duration / math.ceil(duration / h - 1e-9)


def _diverging(**kw) -> PassageSettings:
    base = dict(route="diverging", speed_kmh=80.0, layers=2, x_start=WINDOW[0], x_end=WINDOW[1])
    return PassageSettings(**{**base, **kw})


# ----------------------------------------------------------------------------- pure functions


def test_refine_pieces_fine_from_the_start_to_the_load_end_plus_margin():
    # 0.1 s at 1e-4 s: 1000 steps; load until 0.03 s: fine up to 0.03 + margin on the grid
    pieces = refine_pieces(0.1, 1e-4, 2.5e-5, 0.03)
    assert len(pieces) == 2
    (a0, b0, h0), (a1, b1, h1) = pieces
    assert (a0, a1, b1) == (0, b0, 1000)
    assert b0 == math.ceil((0.03 + CHECK_RAIL_MARGIN) / 1e-4 - 1e-9)
    assert h0 == pytest.approx(2.5e-5, rel=1e-12) and h1 == pytest.approx(1e-4, rel=1e-12)


def test_refine_pieces_to_the_end_when_less_than_a_margin_is_left():
    pieces = refine_pieces(0.1, 1e-4, 2.5e-5, 0.1 - 0.5 * CHECK_RAIL_MARGIN)
    assert pieces == ((0, 1000, pytest.approx(2.5e-5, rel=1e-12)),)


def test_refine_pieces_fine_step_divides_the_grid_step():
    # a grid step that is not a multiple of the fine one: m = ceil(h / fine), h / m <= fine
    (_, _, h_fine), *_ = refine_pieces(0.0123, 1e-4, 3e-5, 0.001)
    h = 0.0123 / 123
    assert h_fine == pytest.approx(h / 4, rel=1e-12) and h_fine <= 3e-5


def test_pick_rows_and_piece_times():
    t = np.arange(0, 41) * 2.5e-5  # a fine run, every step
    cols = {"t_s": t, "f": t * 2.0}
    wanted = np.arange(0, 11) * 1e-4 + 1e-12  # the coarse grid, with round-off
    picked = pick_rows(cols, wanted)
    assert np.array_equal(picked["t_s"], t[::4])
    assert np.array_equal(picked["f"], 2.0 * t[::4])
    with pytest.raises(ValueError):
        pick_rows(cols, np.array([1.25e-5]))
    coarse = np.arange(0, 11) * 1e-4
    # a later piece does not repeat its start (the piece before gives it)
    assert np.array_equal(piece_times(coarse, 0.0, 4, 10, 1e-4, 2.5e-5), coarse[5:])
    assert np.array_equal(piece_times(coarse, 0.0, 0, 4, 1e-4, 2.5e-5), coarse[:5])


def test_check_rail_window_threshold_and_labels():
    t = np.linspace(0.0, 1.0, 11)
    fy = np.array([0, 0, 100, 900, 2000, 50, 0, np.nan, 700, 0, 0], float)
    cols = {"t_s": t, "Fy_ws2_right_r3_N": fy, "Fz_ws2_right_r3_N": np.zeros(11)}
    # the ws2 contact above 600 N from t = 0.3 to 0.8 s, peak 2 kN
    assert check_rail_window(cols, [("right", "r3")], 600.0, ("ws1_", "ws2_")) == (
        pytest.approx(0.3),
        pytest.approx(0.8),
        2000.0,
    )
    assert check_rail_window(cols, [("right", "r3")], 2500.0, ("ws1_", "ws2_")) is None
    assert check_rail_window(cols, [("right", "r3")], 600.0, ("",)) is None  # other names


def test_check_rail_step_only_when_finer_than_the_run():
    assert check_rail_step(PassageSettings()) == 2.5e-5
    assert check_rail_step(PassageSettings(time_step=2.5e-5)) is None
    assert check_rail_step(PassageSettings(check_rail_time_step=None)) is None


def test_fe_track_warns_where_a_check_rail_carried_load(turnout):
    # the FE track steps its whole run at one step: it warns instead of refining
    from exudyn_turnout.inputs.routes import load_route

    route = load_route(turnout, "diverging")
    t = np.linspace(0.0, 0.1, 101)
    cols = {"t_s": t, "x_m": 44.0 + V_DIVERGING * t, "Fy_right_r3_N": np.where(t > 0.05, 5e4, 0)}
    summary: dict = {}
    with pytest.warns(CheckRailStepWarning, match="FE track"):
        check_rail_steps(_diverging(), route, 57e3, cols, summary)
    assert "check_rail_step_warning" in summary and summary["check_rail_refined"] == []
    summary = {}
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # converged step: no warning
        check_rail_steps(_diverging(time_step=2.5e-5), route, 57e3, cols, summary)
    assert "check_rail_step_warning" not in summary


def test_settings_check_rail_time_step_checked(turnout):
    with pytest.raises(PassageError, match="check_rail_time_step"):
        simulate_passage(turnout, _diverging(check_rail_time_step=-1.0), vehicle="wheelset")


def test_cli_time_step_given_is_used_everywhere():
    args = argparse.Namespace(route="diverging", speed=80.0, x_start=None, x_end=None)
    assert settings_from_args(args).check_rail_time_step == DEFAULT_SETTINGS.check_rail_time_step
    args.time_step = 1e-4  # given (even the default's value): no finer windows, it warns
    settings = settings_from_args(args)
    assert settings.time_step == 1e-4 and settings.check_rail_time_step is None


def test_record_merges_touching_windows_and_says_so(turnout):
    from exudyn_turnout.inputs.routes import load_route

    check = CheckRailSteps(PassageSettings(), load_route(turnout, "diverging"), 57e3, 4)
    check.refined += [(44.29, 46.85, 2.5e-5), (46.85, 47.49, 2.4993e-5)]
    summary: dict = {"settings": {"time_step": 1e-4}}
    check.record(summary)
    assert summary["check_rail_refined"] == [{"x_m": [44.29, 47.49], "time_step_s": 2.5e-5}]
    assert refined_line(summary) == (
        "check rail loaded: stepped finer over x = 44.29-47.49 m at 2.5e-05 s "
        "(the run's step 0.0001 s)"
    )


# ------------------------------------------------------------------------------- passages


@pytest.fixture(scope="module")
def diverging_runs(turnout):
    """The short diverging window: unrefined at 1e-4 s (with its warnings), refined, and at
    the refined window's step throughout (the same grid)."""
    h_fine = _grid_step(*WINDOW, V_DIVERGING) / 4
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        coarse = simulate_passage(turnout, _diverging(check_rail_time_step=None))
    refined = simulate_passage(turnout, _diverging())
    fine = simulate_passage(turnout, _diverging(time_step=h_fine))
    return coarse, refined, fine, caught


def test_refined_window_reproduces_the_fine_run_and_the_coarse_run_does_not(diverging_runs):
    coarse, refined, fine, _ = diverging_runs
    name = "Fy_ws1_right_r3_N"
    # the same output times as the unrefined run (to round-off)
    assert len(refined.columns["t_s"]) == len(coarse.columns["t_s"])
    assert np.max(np.abs(refined.columns["t_s"] - coarse.columns["t_s"])) < 1e-12
    at = pick_rows(fine.columns, refined.columns["t_s"])
    x = refined.columns["x_m"]
    end = refined.summary["check_rail_refined"][0]["x_m"][1]
    inside = x <= end
    # the fine piece runs the fine run's steps: the same forces bit for bit inside the window
    a, b = np.nan_to_num(refined.columns[name]), np.nan_to_num(at[name])
    assert np.array_equal(a[inside], b[inside])
    peak_fine = float(np.max(np.abs(b)))
    assert peak_fine > 80e3  # the flare's end reached: a loaded check rail (85.79 kN)
    assert abs(refined.summary["peak_Fy_check_rail_N"]) == pytest.approx(peak_fine, rel=1e-12)
    # at 1e-4 s the peak is 1.6 % high here (87.18 against 85.79 kN; 3.3 % low before the
    # kernel's contact at its minimum along x, issue 22, 120.49 against 124.64 kN)
    assert abs(abs(coarse.summary["peak_Fy_check_rail_N"]) / peak_fine - 1.0) > 0.01
    # after the window (back at 1e-4 s) the other wheel's force stays within 0.6 % of a
    # wheel load of the fine run's (the restart at the window's end: 324 N measured; 259 N
    # and a 0.5 % bound before issue 22's contact along x: the window now ends at 45.45 m,
    # as the right wheel's tread takes its load back after the check rail's, where the two
    # steps differ by more than the restart alone)
    late = ~inside
    fz = "Fz_ws1_left_N"
    assert np.max(np.abs(refined.columns[fz][late] - at[fz][late])) < 0.006 * 57e3


def test_summary_and_warning_record_the_check_rail_step(diverging_runs):
    coarse, refined, fine, caught = diverging_runs
    (window,) = refined.summary["check_rail_refined"]
    assert window["x_m"][0] == pytest.approx(WINDOW[0])  # from the segment's start
    # to the load's end (after the flare's end at 45.29 m) and its margin, before x_end
    assert 45.29 + V_DIVERGING * CHECK_RAIL_MARGIN < window["x_m"][1] < WINDOW[1]
    assert window["time_step_s"] == pytest.approx(_grid_step(*WINDOW, V_DIVERGING) / 4)
    assert refined.summary["check_rail_time_step_s"] == 2.5e-5
    assert "check_rail_step_warning" not in refined.summary
    assert refined_line(refined.summary).startswith("check rail loaded: stepped finer over x = ")
    assert coarse.summary["check_rail_refined"] == []
    assert fine.summary["check_rail_refined"] == [] and "check_rail_step_warning" not in (
        fine.summary
    )
    messages = [str(w.message) for w in caught if issubclass(w.category, CheckRailStepWarning)]
    assert len(messages) == 1 and "at a time step of 0.0001 s" in messages[0]
    assert coarse.summary["check_rail_step_warning"] == messages[0]


def test_through_route_untouched(turnout):
    # the through route's check rail (left wheel, r3) carries no load: nothing refined, the
    # run bit for bit the one without the setting
    through = dict(route="through", speed_kmh=100.0, layers=2, x_start=44.29, x_end=45.6)
    on = simulate_passage(turnout, PassageSettings(**through))
    off = simulate_passage(turnout, PassageSettings(**through, check_rail_time_step=None))
    assert on.summary["check_rail_refined"] == []
    assert np.nanmax(np.abs(on.columns["Fy_ws1_left_r3_N"]), initial=0.0) == 0.0
    assert on.columns.keys() == off.columns.keys()
    for name, column in on.columns.items():
        assert np.array_equal(column, off.columns[name], equal_nan=True), name


def test_single_wheelset_refined_window_reproduces_the_fine_run(turnout):
    h_fine = _grid_step(*WINDOW, V_DIVERGING) / 4
    refined = simulate_passage(turnout, _diverging(), vehicle="wheelset")
    fine = simulate_passage(turnout, _diverging(time_step=h_fine), vehicle="wheelset")
    (window,) = refined.summary["check_rail_refined"]
    assert window["time_step_s"] == pytest.approx(h_fine)
    at = pick_rows(fine.columns, refined.columns["t_s"])
    inside = refined.columns["x_m"] <= window["x_m"][1]
    a, b = (np.nan_to_num(c["Fy_right_r3_N"]) for c in (refined.columns, at))
    assert np.max(np.abs(b)) > 10e3  # loaded
    assert np.array_equal(a[inside], b[inside])


@pytest.mark.slow
def test_compiled_stepper_refines_alike(turnout, diverging_runs):
    _, refined, _, _ = diverging_runs  # the default: the compiled stepper
    exudyn = simulate_passage(turnout, _diverging(solver="exudyn"))
    # both end the predicted fine piece while they run (CheckRailStop: Exudyn's pre-step
    # function, the stepper's stop at the grid times): the same window, to the bit
    assert refined.summary["stepping"] == "compiled"
    for key in ("check_rail_refined", "check_rail_predicted", "check_rail_rerun"):
        assert refined.summary[key] == exudyn.summary[key], key
    # the stepper's Newton within the tolerance of Exudyn's (5 N)
    assert refined.summary["peak_Fy_check_rail_N"] == pytest.approx(
        exudyn.summary["peak_Fy_check_rail_N"], abs=5.0
    )


@pytest.mark.slow
def test_diverging_default_run_within_two_percent_of_the_converged_force(turnout):
    # diverging-2L (20..55 m), measured with the kernel's patch along x (along_x.patch_along_x,
    # module docstring): the check rail's force 82.096 / 82.026 / 82.009 kN at 2.5e-5 /
    # 1.25e-5 / 6.25e-6 s throughout, 83.599 kN at 1e-4 s throughout (+1.9 %), 82.098 kN
    # refined; the package's default run refines the loaded window
    result = simulate_passage(turnout, _diverging(x_start=20.0, x_end=55.0))
    peak = abs(result.summary["peak_Fy_check_rail_N"])
    assert 0.98 * 82.009e3 <= peak <= 1.02 * 82.096e3
    windows = result.summary["check_rail_refined"]
    assert windows and windows[0]["x_m"][0] == pytest.approx(44.29)  # the check rail's start
    assert windows[-1]["x_m"][1] < 51.0  # not the whole check rail: its load ends before
