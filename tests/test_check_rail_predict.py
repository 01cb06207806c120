"""The check rail's predicted segments (issue 22 follow-ups; exudyn_turnout.passage.common
CheckRailSteps.predict / run_predicted, CheckRailStop, monotone_progress; used by
corunning_track/vehicle.py): a segment that may load the check rail runs at its fine step
directly, the after-the-fact re-run stays as a safety net, the progress never goes back.

Reference values: the packaged turnout (exudyn_turnout/data/uic60_760_1_15.toml): both
routes have a check rail r3 over x = 44.29..51 m (diverging: right wheel; through: left
wheel), clearance 4 mm, flares 1 m long opening 15 mm. The Manchester vehicle's wheelsets
at 0, -2.56, -19, -21.56 m. Measured at this commit (2 layers, diverging, 80 km/h, 20..55 m):
the leading wheelset runs 6.22 mm to the left at 44.29 m and 4.98 mm at 46.85 m, the second
1.29 mm at 51 m; its check rail is loaded from 45.17 to 47.39 m.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from exudyn_turnout.inputs.routes import load_route
from exudyn_turnout.passage.check_rail_steps import (
    CHECK_RAIL_MARGIN,
    CHECK_RAIL_QUIET,
    CheckRailSteps,
    CheckRailStop,
)
from exudyn_turnout.passage.common import monotone_progress, pick_rows
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings

OFFSETS = (0.0, -2.56, -19.0, -21.56)  #: m, the Manchester vehicle's wheelsets
V = 80.0 / 3.6  #: m/s
W = 54546.0  #: N, the Manchester vehicle's static wheel load (CHECK_RAIL_LOADED of it: 545 N)


def _check(turnout, route: str, **kw) -> CheckRailSteps:
    settings = PassageSettings(route=route, speed_kmh=80.0, layers=2, **kw)
    return CheckRailSteps(settings, load_route(turnout, route), W, 4)


# ------------------------------------------------------------------------------ prediction


def test_diverging_leading_wheelset_on_the_check_rail_is_predicted(turnout):
    check = _check(turnout, "diverging")
    # the segment from the check rail's start (a zone boundary) to the second wheelset's
    # crossing of it; the leading wheelset 6.22 mm to the left (towards the right wheel's
    # check rail): fine from the segment's start
    assert check.predict(44.29, 46.85, OFFSETS, (6.22e-3, 2.4e-3, 5.96e-3, 2.04e-3)) == 0.0
    assert check.predict(46.85, 51.0, OFFSETS, (4.98e-3, 2.42e-3, 5.96e-3, 2.04e-3)) == 0.0


def test_diverging_segments_off_the_check_rail_or_centred_are_not_predicted(turnout):
    check = _check(turnout, "diverging")
    # before the check rail: the leading wheelset reaches it at the segment's end only
    assert check.predict(20.0, 44.29, OFFSETS, (6.23e-3, 2.43e-3, 7.12e-3, 6.14e-3)) is None
    # the second wheelset on it, 1.29 mm over (less than half the 4 mm clearance)
    assert check.predict(51.0, 53.56, OFFSETS, (-0.72e-3, 1.29e-3, 5.97e-3, 2.05e-3)) is None
    # displaced the other way (away from the right wheel's check rail)
    assert check.predict(44.29, 46.85, OFFSETS, (-6.0e-3, 0.0, 0.0, 0.0)) is None


def test_flares_open_the_clearance_the_prediction_compares_with(turnout):
    check = _check(turnout, "diverging")
    # within the entry flare only (44.29..44.79 m): the clearance there is >= 4 mm + 7.5 mm
    # (half the 15 mm opening), so 5 mm does not reach half of it; 6 mm does
    ys = (5.0e-3, 0.0, 0.0, 0.0)
    assert check.predict(44.29, 44.79, OFFSETS, ys) is None
    assert check.predict(44.29, 44.79, OFFSETS, (6.0e-3, 0.0, 0.0, 0.0)) == 0.0
    assert check.predict(44.29, 46.0, OFFSETS, ys) == 0.0  # reaches the check line


def test_fine_stepping_starts_where_the_check_rail_does(turnout):
    check = _check(turnout, "diverging")
    start = check.predict(43.0, 46.0, OFFSETS, (6.0e-3, 0.0, 0.0, 0.0))
    assert start == pytest.approx((44.29 - 43.0) / V, rel=1e-12)


def test_through_route_predicts_none(turnout):
    check = _check(turnout, "through")
    assert check.check_pairs  # it has a check rail (left wheel, r3)...
    # ...but its wheelsets run centred: nothing predicted, whatever the segment
    for x0, x1 in ((20.0, 44.29), (44.29, 46.85), (46.85, 51.0), (51.0, 53.56)):
        assert check.predict(x0, x1, OFFSETS, (1e-4, -1e-4, 1e-4, 0.0)) is None
    # a wheelset pushed 3 mm to the right would be: the left wheel's check rail is at -y
    assert check.predict(44.29, 46.85, OFFSETS, (-3e-3, 0.0, 0.0, 0.0)) == 0.0


def test_nothing_predicted_where_nothing_is_refined(turnout):
    check = _check(turnout, "diverging", check_rail_time_step=None)
    assert check.predict(44.29, 46.85, OFFSETS, (6.22e-3, 0.0, 0.0, 0.0)) is None


# ---------------------------------------------------------------------- the fine run's stop


def _stop(n_load: list[int], steps: int = 400) -> tuple[CheckRailStop, int, list]:
    """A stop over a 0.1 s segment at 1e-4 s refined to 2.5e-5 s, loaded at the grid
    indices ``n_load``; returns it, the fine steps taken and the states it kept."""
    stop = CheckRailStop(0.1, 1e-4, 2.5e-5, 0, 500.0)
    kept = []
    for k in range(steps * stop.m):
        j = k // stop.m

        def state(j=j):
            kept.append(j)
            return {"at": j}

        if not stop((lambda j=j: 1e4 if j in n_load else 0.0), state):
            return stop, k + 1, kept
    return stop, steps * stop.m, kept


def test_stop_ends_a_margin_after_the_last_load_and_keeps_that_state():
    margin = math.ceil(CHECK_RAIL_MARGIN / 1e-4 - 1e-9)  # 50 grid steps
    quiet = math.ceil(CHECK_RAIL_QUIET / 1e-4 - 1e-9)  # 300
    stop, steps, kept = _stop([100, 101, 120], steps=1000)
    assert (stop.n, stop.m, stop.last, stop.end) == (1000, 4, 120, 120 + margin)
    assert kept == [120 + margin] and stop.state == {"at": 120 + margin}
    # it ran on for the quiet time (to see no load came back) and stopped
    assert steps == 4 * (120 + margin + quiet) + 1


def test_stop_moves_on_with_a_load_within_the_quiet_time():
    stop, steps, kept = _stop([100, 300], steps=1000)
    margin = math.ceil(CHECK_RAIL_MARGIN / 1e-4 - 1e-9)
    # the state kept at 150 is dropped when the load at 300 comes: the end moves to 350
    assert kept == [100 + margin, 300 + margin] and stop.end == 300 + margin
    assert stop.state == {"at": 300 + margin}


def test_stop_never_loaded_or_loaded_to_the_end_runs_through():
    stop, steps, kept = _stop([], steps=1000)
    assert stop.last is None and stop.state is None and steps == 4000 and kept == []
    stop, steps, kept = _stop([990], steps=1000)  # less than a margin left: to the end
    assert stop.end == 1000 and stop.state is None and steps == 4000


def test_monotone_progress_never_goes_back():
    seen: list[float] = []
    report = monotone_progress(lambda f, x: seen.append(f))
    for f in (0.1, 0.3, 0.2, 0.25, 0.3, 0.5):  # a segment run again: 0.2, 0.25 again
        report(f, 0.0)
    assert seen == [0.1, 0.3, 0.3, 0.5]
    assert monotone_progress(None) is None


# ------------------------------------------------------------------------------- passages

WINDOW = dict(route="diverging", speed_kmh=80.0, layers=2, x_start=44.29, x_end=45.6)


@pytest.fixture(scope="module")
def predicted_and_net(turnout):
    """The short diverging window (the check rail's start to past its flare's end), once
    predicted and once with the prediction switched off (the safety net's path: run at
    1e-4 s, found loaded, run again), with their progress reports."""
    reports: dict[str, list[float]] = {"predicted": [], "net": []}
    predicted = simulate_passage(
        turnout, PassageSettings(**WINDOW), progress=lambda f, x: reports["predicted"].append(f)
    )
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(CheckRailSteps, "predict", lambda self, *a: None)
        net = simulate_passage(
            turnout, PassageSettings(**WINDOW), progress=lambda f, x: reports["net"].append(f)
        )
    return predicted, net, reports


def test_predicted_segment_covers_the_load_without_a_rerun(predicted_and_net):
    predicted, _, _ = predicted_and_net
    summary = predicted.summary
    assert summary["check_rail_predicted"] == [{"x_m": [44.29, 45.6], "loaded": True}]
    assert summary["check_rail_rerun"] == []  # the prediction covered the load
    (window,) = summary["check_rail_refined"]
    assert window["x_m"][0] == pytest.approx(44.29) and window["time_step_s"] < 2.5e-5 + 1e-12
    # the flare's end: loaded, far above CHECK_RAIL_LOADED (1 % of the ~54 kN wheel load);
    # 85.8 kN measured since the contact's lead along x (issue 22), 126 kN before it
    assert abs(summary["peak_Fy_check_rail_N"]) > 50e3


def test_safety_net_reruns_and_gives_the_same_forces(predicted_and_net):
    predicted, net, _ = predicted_and_net
    (rerun,) = net.summary["check_rail_rerun"]
    assert rerun["peak_N"] > 50e3 and net.summary["check_rail_predicted"] == []
    (w_net,), (w_pred,) = (r.summary["check_rail_refined"] for r in (net, predicted))
    # the same start and step; the end a margin after the last load, which the net takes
    # from its run at 1e-4 s and the prediction from its fine run: at most one grid step
    # (2.2 mm) apart, either way (45.4779 against 45.4757 m before the contact's lead along
    # x, issue 22; 45.4535 against 45.4557 m since)
    grid = (WINDOW["x_end"] - WINDOW["x_start"]) / math.ceil((1.31 / V) / 1e-4 - 1e-9)
    assert w_net["x_m"][0] == w_pred["x_m"][0] and w_net["time_step_s"] == w_pred["time_step_s"]
    assert abs(w_net["x_m"][1] - w_pred["x_m"][1]) <= 1.01 * grid
    # the same fine piece from the same start: the same forces inside both windows (to
    # round-off: the fine run's step is its length over its steps, a longer length here)
    assert len(net.columns["t_s"]) == len(predicted.columns["t_s"])
    at = pick_rows(predicted.columns, net.columns["t_s"])
    inside = net.columns["x_m"] <= min(w_pred["x_m"][1], w_net["x_m"][1]) + 1e-9
    for name in ("Fy_ws1_right_r3_N", "Fz_ws1_left_N", "Fy_ws1_right_N"):
        a, b = np.nan_to_num(net.columns[name]), np.nan_to_num(at[name])
        assert np.max(np.abs(a - b)[inside]) <= 1e-6 * np.max(np.abs(a)), name
    assert abs(net.summary["peak_Fy_check_rail_N"]) == pytest.approx(
        abs(predicted.summary["peak_Fy_check_rail_N"]), rel=1e-9
    )


def test_progress_never_goes_back(predicted_and_net):
    _, _, reports = predicted_and_net
    for name, fractions in reports.items():
        assert len(fractions) > 10, name
        assert all(b >= a for a, b in zip(fractions, fractions[1:])), name
        assert fractions[-1] <= 1.0


def test_through_route_bit_for_bit_without_prediction(turnout):
    through = dict(route="through", speed_kmh=100.0, layers=2, x_start=44.29, x_end=45.6)
    on = simulate_passage(turnout, PassageSettings(**through))
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(CheckRailSteps, "predict", lambda self, *a: None)
        off = simulate_passage(turnout, PassageSettings(**through))
    assert on.summary["check_rail_predicted"] == [] and on.summary["check_rail_rerun"] == []
    for name, column in on.columns.items():
        assert np.array_equal(column, off.columns[name], equal_nan=True), name


def test_single_wheelset_predicted_and_safety_net(turnout):
    # the single wheelset's zone 44.29..51 m: predicted, fine from its start; with the
    # prediction off the safety net runs it twice, the progress reported once
    predicted = simulate_passage(turnout, PassageSettings(**WINDOW), vehicle="wheelset")
    assert predicted.summary["check_rail_predicted"] == [{"x_m": [44.29, 45.6], "loaded": True}]
    assert predicted.summary["check_rail_rerun"] == []
    fractions: list[float] = []
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(CheckRailSteps, "predict", lambda self, *a: None)
        net = simulate_passage(
            turnout,
            PassageSettings(**WINDOW),
            vehicle="wheelset",
            progress=lambda f, x: fractions.append(f),
        )
    assert len(net.summary["check_rail_rerun"]) == 1
    assert net.summary["check_rail_refined"][0]["x_m"][0] == 44.29
    assert abs(net.summary["peak_Fy_check_rail_N"]) == pytest.approx(
        abs(predicted.summary["peak_Fy_check_rail_N"]), rel=1e-9
    )
    assert len(fractions) > 10
    assert all(b >= a for a, b in zip(fractions, fractions[1:]))


# ------------------------------------------------------- run_predicted's pieces (a fake run)


def _fake_run(loads: list[tuple[float, float]], calls: list, t_offset: float = 1.0):
    """A run_piece that steps a check-rail force of 10 kN on the absolute time ranges
    ``loads`` (else 0): sampled every step, the stop asked before each step."""

    def force_at(t: float) -> float:
        return 1e4 if any(a - 1e-12 <= t <= b + 1e-12 for a, b in loads) else 0.0

    def run_piece(t_from, length, x_from, settings, stop=None):
        h = settings.time_step
        steps = max(1, int(math.ceil(length / h - 1e-9)))
        step = length / steps
        calls.append((round(t_from, 9), round(length, 9), h, stop is not None))
        times = [t_offset + t_from]
        for k in range(steps):
            t = times[-1]
            go = True if stop is None else stop(lambda t=t: force_at(t), lambda t=t: {"t": t})
            times.append(t_offset + t_from + (k + 1) * step)
            if not go:
                break
        t = np.array(times)
        fy = np.array([force_at(x) for x in t])
        return {"t_s": t, "x_m": 10.0 + V * (t - t_offset), "Fy_ws1_right_r3_N": fy}

    return run_piece


def test_run_predicted_fine_to_the_loads_end_then_the_run_step(turnout):
    check, calls = _check(turnout, "diverging"), []
    run = _fake_run([(1.02, 1.03)], calls)
    cols, last = check.run_predicted(0.1, 1.0, 10.0, 0.0, run)
    h = 1e-4
    # the segment's grid times, every one once
    assert np.allclose(cols["t_s"], 1.0 + h * np.arange(1001), atol=1e-12, rtol=0)
    end = 300 + math.ceil(CHECK_RAIL_MARGIN / h - 1e-9)  # last load at 0.03 s + margin
    assert [c[3] for c in calls] == [True, False]  # the fine piece (stopped), then the rest
    assert calls[1][:3] == (round(end * h, 9), round((1000 - end) * h, 9), h)
    assert calls[0][2] == pytest.approx(h / 4)
    assert last == pytest.approx((1000 - end) * h)
    assert check.refined == [(10.0, pytest.approx(10.0 + V * end * h), pytest.approx(h / 4))]
    assert check.predicted == [(10.0, pytest.approx(10.0 + V * 0.1), True)] and not check.reruns


def test_run_predicted_load_after_the_fine_piece_runs_it_again(turnout):
    # a second load after the quiet time: the rest (at 1e-4 s) finds it, the fine piece runs
    # again from its start to that load's end (the safety net), then the rest
    check, calls = _check(turnout, "diverging"), []
    run = _fake_run([(1.02, 1.03), (1.07, 1.072)], calls)
    cols, last = check.run_predicted(0.1, 1.0, 10.0, 0.0, run)
    h, margin = 1e-4, math.ceil(CHECK_RAIL_MARGIN / 1e-4 - 1e-9)
    assert [(c[0], c[3]) for c in calls] == [(0.0, True), (round(0.035, 9), False), (0.0, False),
                                            (round((720 + margin) * h, 9), False)]  # fmt: skip
    assert len(check.reruns) == 1 and check.reruns[0][2] == 1e4
    assert check.refined[-1][1] == pytest.approx(10.0 + V * (720 + margin) * h)
    assert np.allclose(cols["t_s"], 1.0 + h * np.arange(1001), atol=1e-12, rtol=0)


def test_run_predicted_from_where_the_check_rail_starts(turnout):
    check, calls = _check(turnout, "diverging"), []
    run = _fake_run([(1.02, 1.03)], calls)
    check.run_predicted(0.1, 1.0, 10.0, 0.0153, run)
    # at the run's step to the grid point before the predicted start, then fine
    assert [(c[0], c[3]) for c in calls[:2]] == [(0.0, False), (round(0.0153, 9), True)]
    assert check.refined[0][0] == pytest.approx(10.0 + V * 0.0153)
    # a load before the predicted start (the safety net): fine from the segment's start
    check, calls = _check(turnout, "diverging"), []
    check.run_predicted(0.1, 1.0, 10.0, 0.0153, _fake_run([(1.01, 1.03)], calls))
    assert [(c[0], c[3]) for c in calls[:2]] == [(0.0, False), (0.0, True)]
    assert len(check.reruns) == 1 and check.refined[0][0] == 10.0
