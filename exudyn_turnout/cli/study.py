"""``exudyn-turnout study``: run a study file on one core, a process pool or a Dask cluster.

Writes ``results.csv``, ``results.npz``, ``results.meta.json`` and ``cases/<key>/`` into
``--out`` (a rerun resumes: stored cases are not computed again) and, unless
``--no-plot``, the study's figures (:mod:`exudyn_turnout.plotting.studies`). Exit 0 when
every case ran, 2 for a bad study file or option, 3 when some case failed (each failed
case's error is in the table).
"""

from __future__ import annotations

import argparse
import sys
import time

from exudyn_turnout.cli.main import RunFailure, UsageError, check_out_dir

__all__ = ["build", "eta_text", "ProgressLines"]


def eta_text(seconds: float | None) -> str:
    """A remaining time as ``ETA 1:02:03`` (``ETA --`` when unknown).

    Parameters
    ----------
    seconds : float or None
        s.

    Returns
    -------
    str
    """
    if seconds is None or seconds != seconds or seconds < 0:
        return "ETA --"
    s = int(round(seconds))
    h, rest = divmod(s, 3600)
    m, s = divmod(rest, 60)
    return f"ETA {h}:{m:02d}:{s:02d}" if h else f"ETA {m}:{s:02d}"


def build(sub: argparse._SubParsersAction) -> None:
    """Register the command on the ``exudyn-turnout`` subcommand parsers.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subcommand parsers of ``exudyn-turnout``; ``study`` is added to them.
    """
    parser = sub.add_parser(
        "study",
        help="run a study file (factors, Latin hypercube, irregularity seeds) in parallel",
        description="Run every case of a study file (a base scenario and the factors varied "
        "around it) on all cores (default), N processes, or a Dask scheduler; write "
        "results.csv/.npz and figures into --out. A rerun computes only the cases that are "
        "not stored yet.",
    )
    parser.add_argument("study", metavar="STUDY.toml", help="the study file")
    parser.add_argument("--out", required=True, metavar="DIR", help="output directory")
    where = parser.add_mutually_exclusive_group()
    where.add_argument(
        "--workers",
        type=int,
        metavar="N",
        help="processes (default: all cores); 1 runs the cases one after the other",
    )
    where.add_argument(
        "--scheduler",
        metavar="tcp://HOST:PORT",
        help="a Dask distributed scheduler (needs the cluster extra: dask[distributed])",
    )
    parser.add_argument(
        "--retry-failed", action="store_true", help="run the stored failed cases again"
    )
    parser.add_argument(
        "--keep-timeseries",
        action="store_true",
        help="store every case's whole time series, cases/<key>/timeseries.npz (compressed; "
        "also [output] keep_timeseries = true in the study file)",
    )
    parser.add_argument("--no-plot", action="store_true", help="skip the figures")
    parser.set_defaults(run=_run)


class ProgressLines:
    """The study's progress: a bar on a terminal, else one plain line per finished case.

    A batch log (stderr not a terminal) gets ``study: 3/24 cases, 41 s, ETA 4:52`` for the
    cases stored before (once) and for each case finished, so it is never silent for long.

    Parameters
    ----------
    stream : text stream
        Usually ``sys.stderr``.
    clock : callable, optional
        s, a monotonic clock (tests pass their own).
    """

    def __init__(self, stream, clock=time.perf_counter):
        self.stream = stream
        self.clock = clock
        self.start = clock()
        self.terminal = bool(stream.isatty())
        self.last = -1

    def __call__(self, done: int, total: int, eta: float | None) -> None:
        """Show ``done`` of ``total`` cases (``run_study``'s ``progress``)."""
        elapsed = self.clock() - self.start
        if self.terminal:
            n = int(30 * done / total) if total else 30
            bar = f"[{'#' * n}{'.' * (30 - n)}]"
            self.stream.write(f"\r{bar} {done}/{total} cases, {elapsed:.0f} s, {eta_text(eta)}")
        elif done != self.last:
            self.stream.write(f"study: {done}/{total} cases, {elapsed:.0f} s, {eta_text(eta)}\n")
        self.last = done
        self.stream.flush()

    def end(self) -> None:
        """Finish the bar's line on a terminal (nothing in a log)."""
        if self.terminal:
            self.stream.write("\n")
            self.stream.flush()


def _client(address: str):
    try:
        from distributed import Client
    except ImportError:
        raise UsageError(
            '--scheduler: dask distributed is not installed (pip install "exudyn_turnout[cluster]")'
        ) from None
    try:
        return Client(address, timeout=10)
    except (OSError, TimeoutError, ValueError) as err:
        raise UsageError(f"--scheduler {address}: cannot connect ({err})") from None


def _run(args: argparse.Namespace) -> int:
    from exudyn_turnout.studies import StudyError, load_study, run_study

    _quick_exit()
    out = check_out_dir(args.out)
    if args.workers is not None and args.workers < 1:
        raise UsageError(f"--workers {args.workers}: must be >= 1")
    try:
        study = load_study(args.study)
        if args.scheduler:  # checked before connecting; else run_study checks them first
            study.cases()  # (every file and value, before anything runs: a StudyError)
    except StudyError as err:
        raise UsageError(str(err)) from None
    client = _client(args.scheduler) if args.scheduler else None
    bar = ProgressLines(sys.stderr)
    try:
        result = run_study(
            study,
            executor=client.get_executor() if client is not None else None,
            workers=args.workers,
            out=out,
            progress=bar,
            retry_failed=args.retry_failed,
            keep_timeseries=True if args.keep_timeseries else None,
        )
    except StudyError as err:
        raise UsageError(str(err)) from None
    except OSError as err:
        raise UsageError(f"--out {args.out}: cannot write: {err.strerror or err}") from None
    finally:
        bar.end()
        if client is not None:
            client.close()
    figures = [] if args.no_plot else _figures(result.table, study, out)
    print(
        f"wrote {result.paths['csv']}, {result.paths['npz']}"
        + (f", {len(figures)} figures" if figures else "")
        + f": {result.n_cases} cases, {result.computed} computed, {result.reused} stored "
        f"before, {result.failed} failed, {result.wall_time:.1f} s"
    )
    if result.failed:
        first = next(e for e, s in zip(result.table["error"], result.table["status"]) if s != "ok")
        raise RunFailure(f"{result.failed} of {result.n_cases} cases failed, e.g. {first}")
    return 0


def _quick_exit() -> None:
    """At the interpreter's exit, skip collecting the objects left (nothing is written then).

    The exit's garbage collection walks every object of the process (the route's contact
    tables, the loaded modules): 0.3-0.6 s of a study's wall time, after its last file was
    written, in the serial and the parallel run alike; frozen (:func:`gc.freeze`) they are
    left to the operating system. Registered once per process; at exit only, so a process
    that runs the command in-process (a test) is not changed before it ends.
    """
    import atexit
    import gc

    atexit.unregister(gc.freeze)
    atexit.register(gc.freeze)


def _figures(table, study, out) -> list[str]:
    from exudyn_turnout.plotting.studies import study_figures

    return study_figures(
        table, study.varied, out, paired=list(study.paired), sampled=list(study.lhs_ranges)
    )
