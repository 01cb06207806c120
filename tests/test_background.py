"""A passage's figures drawn in a forked child while the time series is written.

Reference: the same task run in the caller (``fork=False``), which is what the package did
before; the child must give the same files, the same warnings and, when it fails, the
same error raised in the caller.
"""

from __future__ import annotations

import os
import sys
import time
import warnings

import numpy as np
import pytest

from exudyn_turnout.passage.background import NO_FORK_VARIABLE, ForkedTask, can_fork
from exudyn_turnout.passage.results import PassageResult, write_passage
from exudyn_turnout.passage.settings import DEFAULT_SETTINGS

linux_only = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="fork: Linux only")


@linux_only
def test_task_runs_in_a_child_and_writes_its_files(tmp_path):
    seen = []

    def task():
        seen.append(os.getpid())
        (tmp_path / "done.txt").write_text(str(os.getpid()))

    job = ForkedTask(task, fork=True)
    job.join()
    assert job.ran_in_child
    assert seen == []  # the child's memory, not the caller's
    assert int((tmp_path / "done.txt").read_text()) != os.getpid()


def test_without_fork_the_task_runs_at_join(tmp_path):
    seen = []
    job = ForkedTask(lambda: seen.append(os.getpid()), fork=False)
    assert seen == []
    job.join()
    assert seen == [os.getpid()] and not job.ran_in_child


@linux_only
def test_child_warnings_are_issued_again_in_the_caller():
    def task():
        warnings.warn("a figure's warning", UserWarning, stacklevel=1)

    job = ForkedTask(task, fork=True)
    with pytest.warns(UserWarning, match="a figure's warning"):
        job.join()
    assert job.ran_in_child


@linux_only
def test_failing_child_leaves_the_task_to_the_caller_which_raises(tmp_path):
    calls = tmp_path / "calls"

    def task():
        with open(calls, "a") as fh:
            fh.write(f"{os.getpid()}\n")
        raise ValueError("cannot draw")

    job = ForkedTask(task, fork=True)
    with pytest.raises(ValueError, match="cannot draw"):
        job.join()
    pids = calls.read_text().split()
    assert len(pids) == 2 and pids[1] == str(os.getpid()) != pids[0]  # child, then caller


@linux_only
def test_stop_ends_a_running_child(tmp_path):
    job = ForkedTask(lambda: time.sleep(30), fork=True)
    pid = job.pid
    assert pid is not None
    job.stop()
    assert job.pid is None
    with pytest.raises(ProcessLookupError):  # killed and reaped: no such process
        os.kill(pid, 0)


def test_no_fork_variable(monkeypatch):
    monkeypatch.setenv(NO_FORK_VARIABLE, "1")
    assert not can_fork()
    monkeypatch.setenv(NO_FORK_VARIABLE, "0")
    assert can_fork() == (sys.platform.startswith("linux") and len(os.sched_getaffinity(0)) > 1)


def _result() -> PassageResult:
    t = np.arange(300) * 1e-4
    columns = {"t_s": t, "x_m": 27.8 * t, "Fz_right_N": 5.45e4 + np.sin(t * 100) * 1e3}
    summary = {"static_wheel_load_N": 5.45e4, "static_wheel_load_left_N": 5.45e4}
    return PassageResult(DEFAULT_SETTINGS, columns, summary)


def _figure(directory) -> None:
    """A stand-in for the figures: a file written from the result."""
    (directory / "figure.txt").write_text(f"{np.sum(_result().columns['Fz_right_N']):.9g}")


def _second_figure(directory) -> None:
    (directory / "second.txt").write_text(f"{np.max(_result().columns['x_m']):.9g}")


@pytest.mark.parametrize("parallel", [False, pytest.param(True, marks=linux_only)])
@pytest.mark.parametrize("groups", [1, 2])
def test_write_passage_files_are_the_same_drawn_beside_or_after(tmp_path, parallel, groups):
    figure = _figure if groups == 1 else [_figure, _second_figure]
    write_passage(_result(), tmp_path / "ref", figure=figure, parallel=False)
    write_passage(_result(), tmp_path / "run", figure=figure, parallel=parallel)
    names = sorted(p.name for p in (tmp_path / "ref").iterdir())
    expected = ["figure.txt", "summary.json", "timeseries.csv"]
    assert names == sorted(expected + ([] if groups == 1 else ["second.txt"]))
    assert sorted(p.name for p in (tmp_path / "run").iterdir()) == names
    for name in names:
        assert (tmp_path / "run" / name).read_bytes() == (tmp_path / "ref" / name).read_bytes()


@linux_only
def test_write_passage_failing_figure_raises_and_leaves_no_partial_files(tmp_path):
    def bad(directory):
        (directory / "half.png").write_bytes(b"")
        raise RuntimeError("figure failed")

    with pytest.raises(RuntimeError, match="figure failed"):
        write_passage(_result(), tmp_path, figure=[_figure, bad], parallel=True)
    assert list(tmp_path.iterdir()) == []
