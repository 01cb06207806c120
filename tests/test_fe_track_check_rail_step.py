"""The FE track's finer step where its check rail carries load (issue 22, follow-up):
exudyn_turnout.passage.fe_track.common (loaded_windows, refined_pieces, StepGrid,
check_rail_plan, check_rail_steps, solve_in_pieces) and the step change of the FE planes
(PlaneStepper.set_step, FECoSimulation.set_step).

Reference values and their sources:
- the check rail is loaded above CHECK_RAIL_LOADED (1 %) of the static wheel load, the
  finer window runs CHECK_RAIL_LEAD before the first load to CHECK_RAIL_MARGIN after the
  last, at h / ceil(h / check_rail_time_step) (the module docstring of fe_track/common.py);
- the diverging route at 80 km/h, single wheelset on the FE track, x 45.0..45.6 m: its
  front wheel meets the end of the check rail's entry flare at 45.29 m
  (tests/test_check_rail_step.py); the through route's check rail carries 0 N there.
- measured at this commit (x 42..52 m, sampled every 1e-4 s): 51.18 kN at 1e-4 s unrefined,
  52.09 kN refined, 52.09 / 51.95 kN at 2.5e-5 / 1.25e-5 s throughout.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from exudyn_turnout.inputs.routes import load_route
from exudyn_turnout.passage.check_rail_steps import CHECK_RAIL_MARGIN, CheckRailStepWarning
from exudyn_turnout.passage.fe_track.common import (
    CHECK_RAIL_LEAD,
    FIRST_RUN_SHARE,
    StepGrid,
    check_rail_plan,
    check_rail_steps,
    loaded_windows,
    refined_pieces,
    two_run_progress,
)
from exudyn_turnout.passage.fe_track.planes import (
    PlaneStepper,
    build_fe_planes,
    generalized_alpha,
)
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings

W = 57e3  #: N, a static wheel load (the threshold is 1 % of it: 570 N)
V = 80.0 / 3.6  #: m/s


def _columns(force, t=None, label=""):
    t = np.linspace(0.0, 0.1, 1001) if t is None else t
    return {
        "t_s": t,
        "x_m": 44.0 + V * t,
        f"Fy_{label}right_r3_N": force(t),
        f"Fz_{label}right_r3_N": np.zeros(len(t)),
    }


# ----------------------------------------------------------------------------- pure functions


def test_loaded_windows_threshold_split_and_labels():
    pairs = (("right", "r3"),)
    t = np.linspace(0.0, 1.0, 10001)
    # loaded 0.2-0.3 s and 0.7-0.75 s (a second bogie), grazing (100 N) in between
    force = np.where((t >= 0.2) & (t <= 0.3), 4e4, 100.0)
    force = np.where((t >= 0.7) & (t <= 0.75), 2e4, force)
    cols = _columns(lambda _: force, t, "ws2_")
    windows = loaded_windows(cols, pairs, 0.01 * W, ("ws1_", "ws2_"))
    assert [(round(a, 4), round(b, 4)) for a, b, _ in windows] == [(0.2, 0.3), (0.7, 0.75)]
    assert [p for *_, p in windows] == [4e4, 2e4]
    assert loaded_windows(cols, pairs, 0.01 * W, ("ws1_",)) == []  # no such column: none
    assert loaded_windows(_columns(lambda t: 0 * t), pairs, 0.01 * W) == []


def test_refined_pieces_lead_margin_grid_and_merge():
    h, n = 1e-4, 1000
    pieces = refined_pieces(n, h, 2.5e-5, [(0.03, 0.04, 1.0)])
    a = math.floor((0.03 - CHECK_RAIL_LEAD) / h + 1e-9)
    b = math.ceil((0.04 + CHECK_RAIL_MARGIN) / h - 1e-9)
    assert pieces == ((0, a, 1), (a, b, 4), (b, n, 1))
    # two windows closer than lead + margin merge; a window near the end runs to the end
    merged = refined_pieces(n, h, 2.5e-5, [(0.03, 0.04, 1.0), (0.048, 0.05, 1.0)])
    assert merged[1][2] == 4 and merged[1][1] == math.ceil((0.05 + CHECK_RAIL_MARGIN) / h)
    assert refined_pieces(n, h, 2.5e-5, [(0.09, 0.097, 1.0)])[-1] == (
        math.floor((0.09 - CHECK_RAIL_LEAD) / h + 1e-9),
        n,
        4,
    )
    # a step that does not divide: m = ceil(h / fine), every m-th fine step on the grid
    assert refined_pieces(n, h, 3e-5, [(0.03, 0.04, 1.0)])[1][2] == 4
    # pieces tile the grid
    for p in (pieces, merged):
        assert p[0][0] == 0 and p[-1][1] == n
        assert all(p[i][1] == p[i + 1][0] for i in range(len(p) - 1))


def test_step_grid_samples_only_on_the_grid():
    grid = StepGrid(every=2)
    sampled = [grid.step()]  # the start
    plan = ((1, 3), (4, 8), (1, 3))  # grid points 1..3, 4..5, 6..8
    for i, (substeps, steps) in enumerate(plan):
        grid.substeps = substeps
        final = i == len(plan) - 1
        sampled += [grid.step(last=final and k == steps - 1) for k in range(steps)]
    # samples at grid points 0, 2, 4, 6, 8 (the last) and nowhere between
    expected = [True, False, True, False, False, False, False, True, False, False, False]
    expected += [False, True, False, True]
    assert sampled == expected
    assert grid.index == 8


def test_step_grid_every_fine_step_when_asked():
    grid = StepGrid(every=2, every_fine_step=True)
    sampled = [grid.step()]
    for substeps, steps in ((1, 2), (4, 8), (1, 2)):  # grid points 1..2, 3..4, 5..6
        grid.substeps = substeps
        sampled += [grid.step() for _ in range(steps)]
    # the grid's output steps (0, 2, 4, 6) and every step of the finer piece
    assert sampled == [True, False, True] + [True] * 8 + [False, True]


# ----------------------------------------------------------------------- plan and bookkeeping


def test_plan_only_where_a_check_rail_carried_load(turnout):
    diverging, through = load_route(turnout, "diverging"), load_route(turnout, "through")
    loaded = _columns(lambda t: np.where((t > 0.05) & (t < 0.06), 5e4, 0.0))
    s = PassageSettings(route="diverging")
    pieces = check_rail_plan(s, diverging, W, loaded, 1000, 1e-4)
    assert pieces is not None and [m for *_, m in pieces] == [1, 4, 1]
    # the through route's check rail (left r3) carried 0 N: no plan, nothing rerun
    quiet = {"t_s": loaded["t_s"], "Fy_left_r3_N": np.zeros(1001)}
    assert check_rail_plan(PassageSettings(), through, W, quiet, 1000, 1e-4) is None
    # refining off, or the run's step already fine enough
    off = PassageSettings(route="diverging", check_rail_time_step=None)
    assert check_rail_plan(off, diverging, W, loaded, 1000, 1e-4) is None
    fine = PassageSettings(route="diverging", time_step=2.5e-5)
    assert check_rail_plan(fine, diverging, W, loaded, 4000, 2.5e-5) is None


def test_summary_keys_and_warning_only_where_refining_is_off(turnout):
    route = load_route(turnout, "diverging")
    cols = _columns(lambda t: np.where((t > 0.05) & (t < 0.06), 5e4, 0.0))
    summary: dict = {}
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # refined over the load: no warning
        check_rail_steps(
            PassageSettings(route="diverging"),
            route,
            W,
            cols,
            summary,
            refined=[(0.04, 0.07, 2.5e-5)],
        )
    assert summary["check_rail_time_step_s"] == 2.5e-5
    window = summary["check_rail_refined"]
    assert len(window) == 1 and window[0]["time_step_s"] == 2.5e-5
    assert window[0]["x_m"] == pytest.approx([44.0 + V * 0.04, 44.0 + V * 0.07], abs=1e-4)
    assert "check_rail_step_warning" not in summary
    summary = {}
    with pytest.warns(CheckRailStepWarning, match="FE track refines .* only with"):
        check_rail_steps(
            PassageSettings(route="diverging", check_rail_time_step=None), route, W, cols, summary
        )
    assert summary["check_rail_refined"] == [] and "check_rail_step_warning" in summary


# ---------------------------------------------------------------------------- the step change


def test_plane_set_step_is_a_fresh_factor_at_the_new_step_with_the_state_kept(turnout):
    planes = build_fe_planes(turnout)
    ga = generalized_alpha(0.8)
    model, D = planes.vertical, planes.D_vertical
    stepper = PlaneStepper(model, D, 1e-4, ga)
    rng = np.random.default_rng(1)
    stepper.u, stepper.v = rng.normal(0, 1e-4, model.n_dof), rng.normal(0, 1e-3, model.n_dof)
    stepper.a = stepper.qdd = rng.normal(0, 1.0, model.n_dof)
    state = [x.copy() for x in (stepper.u, stepper.v, stepper.a, stepper.qdd)]
    b = rng.normal(0, 1.0, model.n_dof)
    coarse = stepper.solve(b)
    stepper.set_step(2.5e-5)
    fresh = PlaneStepper(model, D, 2.5e-5, ga)
    assert np.allclose(stepper.solve(b), fresh.solve(b), rtol=1e-10, atol=0)
    assert not np.allclose(stepper.solve(b), coarse, rtol=1e-3)
    for kept, now in zip(state, (stepper.u, stepper.v, stepper.a, stepper.qdd)):
        assert np.array_equal(kept, now)
    stepper.set_step(1e-4)
    assert np.allclose(stepper.solve(b), coarse, rtol=1e-10, atol=0)


# -------------------------------------------------------------------------------- passages


@pytest.mark.slow
def test_fe_wheelset_refines_a_loaded_check_rail_by_default(turnout):
    # x 44.29..45.6 m (the check rail's flare and its end at 45.29 m): the default run, a
    # run at its refined window's step h / 4 throughout sampled on its grid (the same
    # times), and the run at h unrefined. Measured at this commit: check-rail force within
    # 75 N of the fine run from the window's start on (51 212 against 51 205 N at the
    # peak), unrefined 4.9 kN off (49 180 N at the peak).
    base = dict(route="diverging", speed_kmh=80.0, x_start=44.29, x_end=45.6)
    duration = (45.6 - 44.29) / V
    h = duration / math.ceil(duration / 1e-4 - 1e-9)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        seen: list[float] = []
        refined = simulate_passage(
            turnout,
            PassageSettings(**base),
            "wheelset",
            progress=lambda f, x: seen.append(f),
            track="fe",
        )
        fine = simulate_passage(
            turnout,
            PassageSettings(**base, time_step=h / 4, output_step=h),
            "wheelset",
            track="fe",
        )
        coarse = simulate_passage(
            turnout, PassageSettings(**base, check_rail_time_step=None), "wheelset", track="fe"
        )
    r, c = refined.summary, coarse.summary
    assert len(r["check_rail_refined"]) == 1
    window = r["check_rail_refined"][0]
    assert window["time_step_s"] == pytest.approx(h / 4, rel=1e-9)
    assert "check_rail_step_warning" not in r and "steps_first_run" in r["wall_time_parts_s"]
    assert c["check_rail_refined"] == [] and "check_rail_step_warning" in c
    warned = [w for w in caught if issubclass(w.category, CheckRailStepWarning)]
    assert len(warned) == 1  # the unrefined run's only
    # the samples keep the coarse run's times; in the window the fine run's forces
    assert np.allclose(refined.columns["t_s"], coarse.columns["t_s"], rtol=0, atol=1e-12)
    assert np.allclose(refined.columns["t_s"], fine.columns["t_s"], rtol=0, atol=1e-12)
    inside = refined.columns["x_m"] >= window["x_m"][0]
    force = {
        k: np.nan_to_num(run.columns["Fy_right_r3_N"])[inside]
        for k, run in (("refined", refined), ("fine", fine), ("coarse", coarse))
    }
    assert np.max(np.abs(force["refined"] - force["fine"])) < 300.0  # N, of ~51 kN
    # unrefined 2.73 kN off since the kernel's patch along x (along_x.patch_along_x: the
    # flare's end truncates the flange back's patch, a softer contact); 4.9 kN before
    assert np.max(np.abs(force["coarse"] - force["fine"])) > 2e3
    assert np.max(force["refined"]) == pytest.approx(np.max(force["fine"]), rel=2e-3)
    # the progress line goes on through the second run: never back, past the first run's
    # share, to its end
    assert seen and np.all(np.diff(seen) >= 0.0)
    assert seen[0] < 0.05 and seen[-1] > 0.95
    assert any(f <= FIRST_RUN_SHARE for f in seen) and any(0.5 < f < 0.95 for f in seen)


@pytest.mark.slow
def test_fe_through_route_untouched(turnout):
    # its check rail carries 0 N: one run, the same numbers with refining on and off
    s = PassageSettings(route="through", speed_kmh=100.0, x_start=45.0, x_end=45.4)
    seen: list[float] = []
    with warnings.catch_warnings():
        warnings.simplefilter("error", CheckRailStepWarning)
        on = simulate_passage(
            turnout, s, "wheelset", progress=lambda f, x: seen.append(f), track="fe"
        )
        off = simulate_passage(
            turnout,
            PassageSettings(**{**s.__dict__, "check_rail_time_step": None}),
            "wheelset",
            track="fe",
        )
    assert on.summary["check_rail_refined"] == []
    assert "steps_first_run" not in on.summary["wall_time_parts_s"]
    for key in ("Fz_right_N", "Fy_left_N", "y_wheelset_m"):
        assert np.array_equal(on.columns[key], off.columns[key])
    # no second run: the line goes from the first run's share to its end
    assert np.all(np.diff(seen) >= 0.0) and max(seen[:-1]) <= FIRST_RUN_SHARE
    assert seen[-1] == 1.0


def test_two_run_progress_splits_the_line_only_where_a_second_run_may_follow(turnout):
    """Through the first run 0..FIRST_RUN_SHARE, through the second the rest; the whole
    line to the first where no check rail is on the route or refining is off."""
    seen: list[tuple[float, float]] = []

    def report(f, x):
        seen.append((f, x))

    diverging = load_route(turnout, "diverging")
    first, second = two_run_progress(report, PassageSettings(route="diverging"), diverging)
    assert first is not None and second is not None
    first(0.5, 1.0)
    second(0.0, 2.0)
    second(1.0, 3.0)
    assert seen == [(0.5 * FIRST_RUN_SHARE, 1.0), (FIRST_RUN_SHARE, 2.0), (1.0, 3.0)]
    off = PassageSettings(route="diverging", check_rail_time_step=None)
    assert two_run_progress(report, off, diverging) == (report, None)
    assert two_run_progress(None, PassageSettings(route="diverging"), diverging) == (None, None)
