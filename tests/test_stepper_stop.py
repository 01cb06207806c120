"""The compiled stepper's stop (passage/corunning_track/stepper.py ``integrate(stop=...)``):
the check rail's predicted fine piece ended where its load has ended
(:class:`~exudyn_turnout.passage.check_rail_steps.CheckRailStop`), as Exudyn's pre-step function
returning False ends Exudyn's run.

1. The chunks alone, on the linear 2-DOF oscillator of tests/test_stepper.py: the stop is
   called before every stop_every-th step only, with the state at that step's start (the
   uninterrupted run's), the run ends after the step where it returns False, and the
   samples are the uninterrupted run's up to there, bit for bit.
2. The full vehicle on a short diverging window (the check rail's start to past the
   leading wheelset's load on it, :data:`WINDOW`): the default (compiled) run with its
   stop against ``solver="exudyn"`` (Exudyn's pre-step function): the same predicted and
   refined windows, no re-run, and every force column within Newton's tolerance (both
   solvers stop at ||r|| <= eps = NEWTON_TOLERANCE_FACTOR x newton_tolerance(4) = 5 N: each
   contact force within eps of the exactly converged one, so within 2 eps of each other).
"""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_turnout.passage.common import newton_tolerance
from exudyn_turnout.passage.corunning_track import stepper
from exudyn_turnout.passage.corunning_track import vehicle as full_vehicle
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings

#: kg, N/m: the 2-DOF chain of tests/test_stepper.py (masses 2 and 1 kg)
MASS = np.diag([2.0, 1.0])
STIFFNESS = np.array([[300.0, -100.0], [-100.0, 100.0]])
DAMPING = 1e-3 * STIFFNESS + 0.1 * MASS
Q0 = np.array([0.01, -0.005])  #: m


def _linear(steps: int = 40, **kw) -> stepper.StepperRun:
    return stepper.integrate_linear(
        MASS, STIFFNESS, DAMPING, Q0, np.zeros(2), 0.04 * steps / 40, steps, 0.8, **kw
    )


def test_stop_called_every_m_steps_with_the_state_of_the_steps_start():
    whole = _linear()
    calls: list[tuple[int, np.ndarray]] = []

    def stop(k: int, q: np.ndarray) -> bool:
        calls.append((k, q))
        return True

    run = _linear(stop=stop, stop_every=3)
    assert [k for k, _ in calls] == list(range(0, 40, 3))
    for k, q in calls:  # the uninterrupted run's state at times[k], bit for bit
        assert np.array_equal(q, whole.q[k]), k
    assert run.steps == whole.steps == 40 and np.array_equal(run.q, whole.q)


def test_stop_returning_false_ends_the_run_after_that_step():
    whole = _linear()
    run = _linear(stop=lambda k, q: k < 12, stop_every=4)  # False before step 12
    assert run.steps == 13 and np.isnan(run.failed_at)  # steps 0..12 taken
    assert run.times[-1] == pytest.approx(whole.times[13])
    assert np.array_equal(run.q, whole.q[:14]) and np.array_equal(run.q_t, whole.q_t[:14])


# ------------------------------------------------------------------------------- passages

#: the check rail's start to past the leading wheelset's last load on it (47.39 m,
#: tests/test_check_rail_predict.py) plus the margin and the quiet time (0.035 s, 0.78 m):
#: two predicted segments (the second wheelset reaches the check rail at 46.85 m), the
#: second's fine piece stopped early, the rest at the run's step from the kept state
WINDOW = dict(route="diverging", speed_kmh=80.0, layers=2, x_start=44.29, x_end=48.6)


@pytest.mark.slow
def test_predicted_fine_piece_stopped_alike(turnout, monkeypatch):
    runs: list[tuple[int, stepper.StepperRun]] = []  #: (planned steps, run)
    integrate = stepper.integrate

    def spy(*args, **kwargs):
        runs.append((args[3], integrate(*args, **kwargs)))
        return runs[-1][1]

    monkeypatch.setattr(stepper, "integrate", spy)
    exudyn = simulate_passage(turnout, PassageSettings(**WINDOW, solver="exudyn"))
    assert not runs
    compiled = simulate_passage(turnout, PassageSettings(**WINDOW))  # the default: compiled
    assert compiled.summary["stepping"] == "compiled" and exudyn.summary["stepping"] == "exudyn"
    # a fine piece ended early by its stop: fewer steps than its planned length
    assert any(run.steps < planned for planned, run in runs), [(p, r.steps) for p, r in runs]
    for key in ("check_rail_predicted", "check_rail_refined", "check_rail_rerun"):
        assert compiled.summary[key] == exudyn.summary[key], key
    assert compiled.summary["check_rail_rerun"] == []
    a, c = exudyn.columns, compiled.columns
    assert np.array_equal(a["t_s"], c["t_s"])
    eps = full_vehicle.NEWTON_TOLERANCE_FACTOR * newton_tolerance(4)
    forces = [n for n in a if n.startswith(("Fz_", "Fy_")) and n.endswith("_N")]
    assert len(forces) > 40
    for name in forces:
        assert np.array_equal(np.isnan(a[name]), np.isnan(c[name])), name
        assert np.nanmax(np.abs(a[name] - c[name]), initial=0.0) <= 2 * eps, name
    peak = "peak_Fy_check_rail_N"
    assert abs(exudyn.summary[peak]) > 50e3  # loaded (tests/test_check_rail_predict.py)
    assert compiled.summary[peak] == pytest.approx(exudyn.summary[peak], abs=2 * eps)


def test_cli_solver_default_is_compiled():
    import argparse

    from exudyn_turnout.cli.passage import build, settings_from_args

    top = argparse.ArgumentParser()
    build(top.add_subparsers(dest="command"))
    given = ["simulate", "--route", "through", "--out", "unused"]  # parsed only: no files
    args = top.parse_args(given)
    assert args.solver == "compiled" and settings_from_args(args).solver == "compiled"
    args = top.parse_args([*given, "--solver", "exudyn"])
    assert settings_from_args(args).solver == "exudyn"
