"""Where a study's wall time goes: a timeline per process of ``exudyn-turnout study``.

Runs the performance table's study (``performance_table.study_text``: 24 single-wheelset
passages of the profile contact, 3-layer track, 6 speeds x 4 pad stiffnesses, -5..60 m) as
``exudyn-turnout study --workers N --no-plot`` in a fresh process each, with hooks around
the study's steps (nothing in the package changes): the parent's imports, reading the study
and its cases, the warm-up before the pool forks, the pool's start, each case's start and
end in its worker (wall and CPU), the parent's writing of each case, the results table, and
the process's exit. Prints per run the breakdown: the parent's serial parts, each worker's
start, busy time, the CPU time of its cases, and its idle time until the pool shut down.

Run: ``python benchmarks/study_timeline.py [--workers 1 2] [--rounds N] [--quick]
[--trees DIR ...] [--brief] [--vehicle wheelset|manchester] [--output-step S]
[--bytecode]``. The runs alternate (``--workers 1 2`` twice: 1, 2, 1, 2; with ``--trees
OLD NEW`` each round runs OLD's pair, then NEW's), with the yardstick
(``benchmarks/yardstick.py``) run between them; the load (``os.getloadavg``) is printed.
After each round the yardstick's own 2-process speed-up (``yardstick.parallel_speedup``:
what the machine gives two processes at that time) is measured, and the summary gives per
tree the median 1 -> 2 worker speed-up, the median yardstick speed-up and the median of
their per-round ratio (speed-up / yardstick's: 1.0 means the study scales as well as the
machine allows).

Measured 2026-12-02 13:43-14:36 UTC (issue 24), the 2-core AMD EPYC VM shared with other
jobs: load average 2-7 throughout, the yardstick's own 2-process speed-up 0.89-1.85 from
round to round, so the wall speed-ups (0.5-1.5) and their ratios to the yardstick's say
nothing; the CPU-based figures do. ``--rounds 6 --trees BASE NEW --brief`` (BASE = 3273b6f):
the calling process's start CPU with 2 workers 2.09 -> 1.60 s, with 1 worker (until its
first case) 0.98 -> 0.92 s; idle-core estimate x1.75 -> x1.76 (rounds 1.68-1.80 -> 1.73-1.83;
the change is within the rounds' spread). Where the 2-worker run's wall goes that the
1-worker run does not spend (a quieter round, 13:48): the fork and the workers' start
0.01 s, the workers ending 0.02-0.15 s apart, the pool's shutdown 0.01-0.04 s; the parent's
5 cm warm-up passage itself 0.01 s (the rest of the warm-up, 0.7-1.0 s CPU, is the route's
contact tables and the compiled kernels, which the 1-worker run loads in its first case:
1.8 s CPU against 0.85 s for the same case later). A case costs the same CPU in a forked
worker as in the serial run (per case 0.96-1.07 of it, sum 14.93 vs 14.89 s without the
first case's loading; garbage collection < 1 ms a case). So the rest is the process's
serial start, which only one core works through: before 1.8 s (interpreter 0.05, imports
0.6, the study's cases 0.06 twice, ``scipy.signal`` 0.34 for the transfer nodes' design
wheel, the track's imports 0.08, the route's contact 0.4, numba's first use 0.22), now
1.4 s, against C = 14.9 s of cases: (S + C) / (S + C/2 + 0.1 s of tail) = 1.78 -> 1.82
without contention, 1.74 -> 1.77 with the yardstick's own 3.5 % loss in 2 processes (x1.93).

Measured 2026-12-02 16:16-17:06 UTC (issue 24, against BASE = 9e99960: scipy.interpolate
imported where sections are built, the study's edited files not parsed again, the hand-out
order before the fork, a case's turnout the one the study's check loaded), load average
2-6 (other jobs kept a core busy: the yardstick's own 2-process gain 0.95-1.3 in most
rounds), so the wall speed-ups (0.6-1.8) say nothing.
``--rounds 8`` and ``--rounds 6 --trees BASE NEW --brief``: start CPU with 2 workers 1.32 ->
1.30 s and 1.29 -> 1.28 s, with 1 worker 0.95 -> 0.92 and 0.93 -> 0.90 s; idle-core
estimate x1.82 -> x1.81 and x1.84 -> x1.78 (within the rounds' spread). The start alone
(a process importing the command and the studies, then ``load_study(...).cases()``,
``hand_out_order`` and ``warm_up``: its CPU time at the point of the fork), 12 pairs
alternating BASE and NEW: 1.18 -> 1.10 s (medians; lower in every pair, by 0.02-0.30 s):
by the arithmetic above worth ~+0.01 on the speed-up. ``--bytecode``
(4 rounds): start CPU with 2 workers 1.13 and 1.14 s, with 1 worker 0.85 and 0.80 s: the
environment's ``PYTHONDONTWRITEBYTECODE=1`` (each process compiles the package from
source) costs ~0.17 s of the 2-worker start. ``--vehicle manchester --output-step 5e-4``
(3 rounds, NEW): cases 34 s CPU, start 1.35 s, idle-core estimate x1.99 (rounds 1.73,
1.99, 2.00; wall x1.96 in the one quiet round). The 2-worker start (CPU, cProfile and
imports apart): numpy 0.11 s, scipy.optimize 0.31 s (the turnout plan's ``brentq``, which
every case calls; the rest of scipy adds 0.03 s), numba 0.15 s and its first use 0.25 s
(typing registries), exudyn 0.03 s, the package's modules ~0.15 s, the cases and their
order 0.12 s (0.09 s now: each turnout file was loaded twice and parsed 5 times), the route's
contact tables 0.1 s (an npz read): all but ~0.05 s is work every process running a case
needs, so a fork earlier (each worker warming itself) would run it on both cores at once
for the same wall time.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent


def _child(workers: int, study: str, out: str, events: str) -> int:
    """In the measured process: install the hooks and run the CLI."""
    born = time.perf_counter()
    log = Path(events)

    def note(what: str, **extra) -> None:
        entry = {"t": time.perf_counter(), "cpu": time.process_time(), "pid": os.getpid()}
        entry.update(what=what, **extra)
        with open(log / f"{os.getpid()}.jsonl", "a", encoding="utf-8") as fh:
            fh.write(json.dumps(entry) + "\n")

    note("born", t0=born)
    import exudyn_turnout.cli.main as cli
    import exudyn_turnout.studies as studies
    from exudyn_turnout.studies import run

    note("imported")

    def around(module, name, before, after=None):
        inner = getattr(module, name)

        def wrapper(*args, **kwargs):
            note(before, **(_case_of(args) or {}))
            try:
                return inner(*args, **kwargs)
            finally:
                if after:
                    note(after, **(_case_of(args) or {}))

        wrapper.__module__, wrapper.__qualname__ = inner.__module__, inner.__qualname__
        wrapper.__name__ = inner.__name__
        setattr(module, name, wrapper)

    def _case_of(args):
        case = args[0] if args else None
        index = getattr(case, "index", None)
        return {"case": index} if isinstance(index, int) else None

    inner_load = studies.load_study

    def load_study(path):
        note("load_study")
        study = inner_load(path)
        cases = type(study).cases

        def timed_cases(self):
            note("cases")
            try:
                return cases(self)
            finally:
                note("cases_done")

        type(study).cases = timed_cases  # type: ignore[method-assign]
        return study

    studies.load_study = load_study  # type: ignore[assignment]
    around(run, "warm_up", "warm_up", "warm_up_done")
    around(run, "process_pool", "pool", "pool_done")
    around(run, "one_blas_thread", "worker_start")
    around(run, "_study_case", "case_start", "case_end")
    around(run, "_write_record", "write_record", "write_record_done")
    around(run, "_table", "table")
    around(run, "_write_table", "write_table", "write_table_done")
    code = cli.main(["study", study, "--out", out, "--workers", str(workers), "--no-plot"])
    note("end")
    return code


def _events(folder: Path) -> list[dict]:
    out = []
    for path in folder.glob("*.jsonl"):
        out += [json.loads(line) for line in path.read_text(encoding="utf-8").splitlines()]
    return sorted(out, key=lambda e: e["t"])


def breakdown(events: list[dict], wall: float, launched: float) -> list[str]:
    """Lines describing one run's timeline (times from the command's launch).

    Parameters
    ----------
    events : list of dict
        The hooks' notes (``t`` s perf_counter, ``cpu`` s, ``pid``, ``what``, ``case``).
    wall : float
        s, the command's wall time measured outside it.
    launched : float
        s, perf_counter at the launch.

    Returns
    -------
    list of str
    """
    parent = events[0]["pid"]

    def first(what, pid=parent):
        return next((e for e in events if e["what"] == what and e["pid"] == pid), None)

    def last(what, pid=parent):
        found = [e for e in events if e["what"] == what and e["pid"] == pid]
        return found[-1] if found else None

    def at(e):
        return e["t"] - launched if e else float("nan")

    lines = []
    born, imported = first("born"), first("imported")
    lines.append(f"  interpreter start {born['t0'] - launched:6.2f} s")
    lines.append(f"  imports           {imported['t'] - born['t0']:6.2f} s")
    load, cases_done = first("load_study"), last("cases_done")
    lines.append(f"  study + cases     {cases_done['t'] - load['t']:6.2f} s")
    warm, warm_done = first("warm_up"), first("warm_up_done")
    if warm and warm_done:
        lines.append(
            f"  warm-up (parent)  {warm_done['t'] - warm['t']:6.2f} s "
            f"({warm_done['cpu'] - warm['cpu']:.2f} s CPU)"
        )
    pool, pool_done = first("pool"), first("pool_done")
    if pool and pool_done:
        lines.append(f"  pool made         {pool_done['t'] - pool['t']:6.2f} s (warm-up included)")
    runners = sorted({e["pid"] for e in events if e["what"] == "case_start"})
    ends = []
    table = first("table")
    for pid in runners:
        starts = [e for e in events if e["pid"] == pid and e["what"] == "case_start"]
        stops = [e for e in events if e["pid"] == pid and e["what"] == "case_end"]
        busy = sum(b["t"] - a["t"] for a, b in zip(starts, stops))
        cpu = sum(b["cpu"] - a["cpu"] for a, b in zip(starts, stops))
        ws = first("worker_start", pid)
        ends.append(stops[-1]["t"])
        lines.append(
            f"  process {pid}: {'started ' + format(at(ws), '.2f') + ' s, ' if ws else ''}"
            f"first case {at(starts[0]):.2f} s, last case ends {at(stops[-1]):.2f} s; "
            f"{len(starts)} cases, busy {busy:.2f} s wall, {cpu:.2f} s CPU"
        )
    if len(runners) > 1:
        lines.append(f"  tail: workers end {max(ends) - min(ends):.2f} s apart")
    writes = [e for e in events if e["pid"] == parent and e["what"].startswith("write_record")]
    spent = sum(b["t"] - a["t"] for a, b in zip(writes[::2], writes[1::2]))
    lines.append(f"  writing cases (parent, {len(writes) // 2}) {spent:6.2f} s")
    done = first("write_table_done")
    lines.append(
        f"  last case end -> pool shut, table built {at(table) - at({'t': max(ends)}):6.2f} s"
    )
    lines.append(f"  results table     {done['t'] - first('write_table')['t']:6.2f} s")
    end = last("end")
    lines.append(f"  after the table   {end['t'] - done['t']:6.2f} s; exit {wall - at(end):.2f} s")
    lines.append(f"  total             {wall:6.2f} s wall")
    return lines


def idle_estimate(events: list[dict], workers: int, exit_wall: float) -> float:
    """s, the run's wall time on idle cores, from its CPU times.

    The calling process's CPU up to the pool's start (or to the first case) and after the
    last case, its exit's wall time, and the cases' CPU times handed out in the order they
    started to whichever of ``workers`` is free first (the longest-first order of the pool).

    Parameters
    ----------
    events : list of dict
        The hooks' notes of one run.
    workers : int
    exit_wall : float
        s, from the process's last note to its exit.

    Returns
    -------
    float
    """
    import heapq

    parent = events[0]["pid"]
    mine = [e for e in events if e["pid"] == parent]
    start = next((e for e in mine if e["what"] == "pool_done"), None)
    if start is None:
        start = next(e for e in mine if e["what"] == "case_start")
    table = next(e for e in mine if e["what"] == "table")
    end = [e for e in mine if e["what"] == "end"][-1]
    before = start["cpu"]
    starts = {(e["pid"], e["case"]): e for e in events if e["what"] == "case_start" and "case" in e}
    cases = []
    for e in events:
        if e["what"] == "case_end" and "case" in e:
            s0 = starts[e["pid"], e["case"]]
            cases.append((s0["t"], e["cpu"] - s0["cpu"]))
    free = [0.0] * workers
    for _, cpu in sorted(cases):
        heapq.heapreplace(free, free[0] + cpu)
    return before + max(free) + (end["cpu"] - table["cpu"]) + exit_wall


def start_cpu(events: list[dict]) -> float:
    """s, CPU time of the calling process until its workers could start.

    Up to the pool's start (its warm-up included) or, without a pool (1 worker), up to the
    first case: the serial start that no number of workers shares (imports, the study and
    its cases, the route's contact tables and compiled kernels with a pool; with 1 worker
    the first case loads the tables and kernels itself).

    Parameters
    ----------
    events : list of dict
        The hooks' notes of one run.

    Returns
    -------
    float
    """
    parent = events[0]["pid"]
    mine = [e for e in events if e["pid"] == parent]
    start = next((e for e in mine if e["what"] == "pool_done"), None)
    if start is None:
        start = next(e for e in mine if e["what"] == "case_start")
    return float(start["cpu"])


def main(argv=None) -> None:
    """Run the study with each worker count (and tree) in turn and print the timelines."""
    import resource
    import statistics

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--rounds", type=int, default=1)
    parser.add_argument("--quick", action="store_true", help="4 short cases")
    parser.add_argument(
        "--vehicle",
        choices=("wheelset", "manchester"),
        help="the study's vehicle (default: none named, the study's default, the single "
        "wheelset, as the performance table runs it); manchester: the full vehicle",
    )
    parser.add_argument(
        "--output-step",
        type=float,
        metavar="S",
        help="s, the study's output step (default: the performance table's 1e-3; the full "
        "vehicle's ride comfort rejects some 1e-3 grids as below 1000 Hz by rounding: 5e-4)",
    )
    parser.add_argument(
        "--bytecode",
        action="store_true",
        help="let the measured processes read and write bytecode (.pyc) in a temporary "
        "PYTHONPYCACHEPREFIX, as an installed package has it (default: the environment's "
        "setting; with PYTHONDONTWRITEBYTECODE=1 every process compiles the package's "
        "modules from source); a --quick study per tree fills it before the rounds",
    )
    parser.add_argument(
        "--trees",
        nargs="+",
        default=[str(HERE.parent)],
        metavar="DIR",
        help="checkouts of the package, run in turn (default: this one)",
    )
    parser.add_argument("--brief", action="store_true", help="no timeline, the summary only")
    parser.add_argument("--child", nargs=4, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child:
        workers, study, out, events = args.child
        sys.exit(_child(int(workers), study, out, events))
    sys.path.insert(0, str(HERE))
    from performance_table import study_text
    from yardstick import Yardstick, machine_line, parallel_speedup

    stick = Yardstick()
    print(machine_line())
    rows: dict[tuple[str, int], list[tuple[float, float, float, float]]] = {}
    machine_gains: dict[str, list[float]] = {}
    with tempfile.TemporaryDirectory(prefix="study_timeline_") as tmp:
        root = Path(tmp)
        study = root / "study.toml"
        text = study_text(args.quick)
        if args.output_step:
            text = text.replace("output_step = 1e-3", f"output_step = {args.output_step!r}")
        if args.vehicle:
            text = text.replace("[base]\n", f'[base]\nvehicle = "{args.vehicle}"\n', 1)
        study.write_text(text, encoding="utf-8")
        env_of = {tree: dict(os.environ, PYTHONPATH=tree) for tree in args.trees}
        if args.bytecode:
            prime = root / "prime.toml"
            prime.write_text(study_text(True), encoding="utf-8")
            for t, tree in enumerate(args.trees):
                env_of[tree].pop("PYTHONDONTWRITEBYTECODE", None)
                env_of[tree]["PYTHONPYCACHEPREFIX"] = str(root / f"pycache-{t}")
                command = [sys.executable, "-m", "exudyn_turnout", "study", str(prime)]
                command += ["--out", str(root / f"prime-{t}"), "--workers", "1", "--no-plot"]
                subprocess.run(command, capture_output=True, check=True, env=env_of[tree])
        print(
            f"study: {text.splitlines()[1]}, vehicle {args.vehicle or '(default)'}; "
            f"bytecode {'cached' if args.bytecode else 'as the environment has it'} "
            f"(PYTHONDONTWRITEBYTECODE={os.environ.get('PYTHONDONTWRITEBYTECODE', '')!r})"
        )
        for r in range(args.rounds):
            for t, tree in enumerate(args.trees):
                for workers in args.workers:
                    name = f"{r}-{t}-{workers}"
                    out, events = root / f"out-{name}", root / f"events-{name}"
                    events.mkdir()
                    command = [sys.executable, __file__, "--child", str(workers), str(study)]
                    command += [str(out), str(events)]
                    env = env_of[tree]
                    stick.measure(workload_none, repeats=1, warm_up=False)
                    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
                    launched = time.perf_counter()
                    done = subprocess.run(
                        command, capture_output=True, text=True, check=False, env=env
                    )
                    wall = time.perf_counter() - launched
                    after = resource.getrusage(resource.RUSAGE_CHILDREN)
                    cpu = after.ru_utime + after.ru_stime - usage.ru_utime - usage.ru_stime
                    if done.returncode:
                        sys.exit(f"study failed: {done.stderr[-2000:]}")
                    notes = _events(events)
                    exit_wall = wall - (
                        [e for e in notes if e["what"] == "end"][-1]["t"] - launched
                    )
                    idle = idle_estimate(notes, workers, exit_wall)
                    start = start_cpu(notes)
                    rows.setdefault((tree, workers), []).append((wall, cpu, idle, start))
                    load = ", ".join(f"{x:.2f}" for x in os.getloadavg())
                    print(
                        f"\nround {r}, {tree}, --workers {workers}: {wall:.2f} s wall, "
                        f"{cpu:.2f} s CPU, idle-core estimate {idle:.2f} s (load {load})",
                        flush=True,
                    )
                    if not args.brief:
                        print("\n".join(breakdown(notes, wall, launched)), flush=True)
                gain = parallel_speedup(2)
                machine_gains.setdefault(tree, []).append(gain)
                print(f"round {r}, {tree}: the yardstick in 2 processes x{gain:.2f}", flush=True)
    print(f"\nyardstick median {stick.median:.3f} s wall; {machine_line()}")
    print(f"{'tree':<40}{'workers':>8}{'wall s':>8}{'CPU s':>8}{'idle s':>8}{'start s':>8}")
    for (tree, workers), values in rows.items():
        med = [statistics.median(v[i] for v in values) for i in range(4)]
        print(f"{tree:<40}{workers:>8}{med[0]:>8.2f}{med[1]:>8.2f}{med[2]:>8.2f}{med[3]:>8.2f}")
    print("(medians; idle: the idle-core estimate; start: the calling process's CPU until its")
    print(" workers could start, the pool's warm-up included; with 1 worker, until its first case)")
    if 1 in args.workers and 2 in args.workers:
        for tree in args.trees:
            one, two = rows[tree, 1], rows[tree, 2]
            wall = [a[0] / b[0] for a, b in zip(one, two)]
            idle = [a[2] / b[2] for a, b in zip(one, two)]
            cpu = [b[1] / a[1] for a, b in zip(one, two)]
            gains = machine_gains[tree]
            ratios = [w / g for w, g in zip(wall, gains)]
            print(
                f"{tree}: 1 -> 2 workers, wall x{statistics.median(wall):.2f} "
                f"(rounds: {', '.join(f'{x:.2f}' for x in wall)}); the yardstick in 2 "
                f"processes x{statistics.median(gains):.2f} "
                f"(rounds: {', '.join(f'{x:.2f}' for x in gains)}); speed-up / yardstick's "
                f"{statistics.median(ratios):.3f} (rounds: "
                f"{', '.join(f'{x:.3f}' for x in ratios)}); idle-core estimate "
                f"x{statistics.median(idle):.2f}; CPU of 2 workers / 1: "
                f"{statistics.median(cpu):.2f}"
            )


def workload_none() -> None:
    """Nothing: the yardstick runs around it (the load before each run)."""


if __name__ == "__main__":
    main()
