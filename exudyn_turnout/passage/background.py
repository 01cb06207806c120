"""A task run in a forked child process while the caller goes on: a passage's figures.

Writing a passage's files is two independent jobs: the time series (formatting and writing
tens of MB of CSV) and the figures (importing matplotlib and drawing up to five figures).
Both are CPU-bound Python; in one process they take their sum, on two cores in two
processes about the larger of the two. :class:`ForkedTask` runs a task in a child forked
from the caller, which then has every array of the result without copying or pickling it,
and the caller does the other job meanwhile.

Where forking is not possible or not useful (not Linux: macOS frameworks and Windows do not
fork safely; one CPU available; ``EXUDYN_TURNOUT_NO_FORK`` set), the task runs in the
caller at :meth:`ForkedTask.join`, as before. A child that fails (an exception, a signal)
leaves the task to be run again in the caller at :meth:`~ForkedTask.join`, so that its
error is raised there as it would be without the child; warnings the child issues are
issued again in the caller, with their category, file and line.
"""

from __future__ import annotations

import gc
import os
import pickle
import signal
import sys
import tempfile
import warnings
from collections.abc import Callable
from pathlib import Path

__all__ = ["ForkedTask", "can_fork", "NO_FORK_VARIABLE"]

#: Environment variable: set (to anything but "" or "0"), tasks run in the caller.
NO_FORK_VARIABLE = "EXUDYN_TURNOUT_NO_FORK"


def can_fork() -> bool:
    """Whether a task can run in a forked child here, beside the caller.

    Returns
    -------
    bool
        On Linux with ``os.fork``, more than one CPU available to this process and
        :data:`NO_FORK_VARIABLE` not set.
    """
    if os.environ.get(NO_FORK_VARIABLE, "") not in ("", "0"):
        return False
    if not sys.platform.startswith("linux") or not hasattr(os, "fork"):
        return False
    try:
        return len(os.sched_getaffinity(0)) > 1
    except (AttributeError, OSError):
        return (os.cpu_count() or 1) > 1


class ForkedTask:
    """Start ``task()`` in a forked child (see the module docstring); :meth:`join` ends it.

    Use as a context manager: leaving the block early (an exception in the caller) stops
    the child and waits for it.

    Parameters
    ----------
    task : callable()
        The work; its result is not returned (it writes files).
    fork : bool, optional
        Run it in a child (default :func:`can_fork`); False: run it at :meth:`join`.
    """

    def __init__(self, task: Callable[[], object], fork: bool | None = None) -> None:
        self.task = task
        self.pid: int | None = None
        self.ran_in_child = False
        self._report = ""
        if fork is None:
            fork = can_fork()
        if fork:
            self._start()

    def _start(self) -> None:
        handle, self._report = tempfile.mkstemp(prefix="exudyn-turnout-task-", suffix=".pkl")
        os.close(handle)
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (AttributeError, OSError, ValueError):
                pass
        with warnings.catch_warnings():  # Python >= 3.12 warns of fork with threads
            warnings.simplefilter("ignore", DeprecationWarning)
            try:
                pid = os.fork()
            except OSError:  # no process to be had: the task runs at join
                Path(self._report).unlink(missing_ok=True)
                return
        if pid == 0:  # the child: run, report, never return into the caller's code
            code = 1
            # the caller's objects out of the collector's reach: a collection walking them
            # would write to (and so copy) every page of the caller's heap
            gc.freeze()
            try:
                with warnings.catch_warnings(record=True) as caught:
                    warnings.simplefilter("always")  # the caller's filters decide
                    self.task()
                issued = [
                    (str(w.message), w.category, w.filename, w.lineno)
                    for w in caught
                    if isinstance(w.category, type)
                ]
                with open(self._report, "wb") as report:
                    pickle.dump(issued, report)
                code = 0
            except BaseException:  # noqa: S110 - the caller runs the task again and raises
                pass
            finally:
                os._exit(code)
        self.pid = pid

    def join(self) -> None:
        """Wait for the child; run the task here if there was none or it failed."""
        if self.pid is None:
            self.task()
            return
        _, status = os.waitpid(self.pid, 0)
        self.pid = None
        try:
            if os.waitstatus_to_exitcode(status) == 0:
                with open(self._report, "rb") as report:
                    issued = pickle.load(report)  # noqa: S301 - written by our own child
                for message, category, filename, lineno in issued:
                    warnings.warn_explicit(message, category, filename, lineno)
                self.ran_in_child = True
                return
        finally:
            Path(self._report).unlink(missing_ok=True)
        self.task()  # failed in the child: here, so that its error is raised here

    def stop(self) -> None:
        """Stop the child if it runs (the caller failed); the task is not run."""
        if self.pid is None:
            return
        pid, self.pid = self.pid, None
        try:
            os.kill(pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        os.waitpid(pid, 0)
        Path(self._report).unlink(missing_ok=True)

    def __enter__(self) -> ForkedTask:
        return self

    def __exit__(self, kind, value, traceback) -> None:
        if kind is not None:
            self.stop()
