"""The main job's wall time, warm and cold, and where a run spends it (issue 24).

Run: ``python benchmarks/bench_main_job.py [--repeats N] [--cases a,b,c] [--cold]
[--sections] [--checkout DIR] [--versus DIR]``.

Cases, each ``exudyn-turnout simulate ... --route through --speed 100 --out DIR`` as a
fresh process (the whole run: interpreter, imports, files, contact set-up, static start,
passage, CSV, figures):

- ``a``: one track, the single wheelset (``--vehicle wheelset --layers 3``);
- ``b``: one track, the full Manchester vehicle (``--vehicle manchester --layers 3``);
- ``c``: the README's main job, ``--track 2-layer,3-layer``, the full vehicle (the default
  from issue 24 on; ``--vehicle manchester`` is passed, so that an older checkout whose
  default was the wheelset runs the same job);
- ``c1``: the same two tracks under the single wheelset (the main job before issue 24).

*Warm*: after one untimed run (contact tables and numba kernels cached), ``--repeats``
runs interleaved with the yardstick (``benchmarks/yardstick.py``). *Cold* (``--cold``):
every run with an empty cache (``XDG_CACHE_HOME`` a fresh directory: contact tables, the
creep table and matplotlib's font cache are built; the numba kernels stay compiled, they
are cached next to the package). Goals (issue 24): warm
<= 5 s (single wheelset), <= 8 s (full vehicle); cold <= 30 s.

``--sections``: one more warm run per case in a fresh process (with ``--cold`` a cold one
as well), with the wall time of each stage (import, contact set-up and in it the contact
tables and the wait for the creep table, track runs, CSV, figures) measured by wrapping
the package's public functions; printed as a table (figures drawn in forked children, as
from issue 24 on, are timed only within "writing"; the creep table built in a background
thread from the cold-start change on is timed only as the wait for it). ``--checkout
DIR``: time the package of another checkout (its ``PYTHONPATH``), e.g. an earlier commit
unpacked with ``git archive``. ``--versus DIR``: time that checkout as well, run for run
alternating with this one (``versus, this, versus, this, ...``, each run between two
yardstick runs), so that both see the same load: the before/after of a change, measured
in one run.

CPU s is that of the command and of every process it waited for (the figures' children
included): on a loaded machine the closest to the cost on an idle one.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from yardstick import Yardstick, machine_line

__all__ = ["CASES", "command", "main"]

#: case -> (label, options of ``simulate``).
CASES = {
    "a": ("1 track, single wheelset", ["--vehicle", "wheelset", "--layers", "3"]),
    "b": ("1 track, full vehicle", ["--vehicle", "manchester", "--layers", "3"]),
    "c": ("2 tracks (README main job), full vehicle", ["--vehicle", "manchester"]),
    "c1": ("2 tracks, single wheelset", ["--vehicle", "wheelset"]),
}
TWO_TRACKS = ["--track", "2-layer,3-layer"]

#: Run in a fresh process with ``--sections``: the CLI with its stages timed (public names).
SECTIONS = r"""
import json, sys, time
T0 = time.perf_counter()
import exudyn_turnout.cli.main as cli
times = {"import (package, CLI)": time.perf_counter() - T0}

def timed(owner, name, label):
    original = getattr(owner, name, None)
    if original is None:  # an older checkout
        return
    def wrapper(*args, **kwargs):
        start = time.perf_counter()
        try:
            return original(*args, **kwargs)
        finally:
            times[label] = times.get(label, 0.0) + time.perf_counter() - start
    setattr(owner, name, wrapper)

import exudyn_turnout.passage.contact.profile as profile
import exudyn_turnout.passage.corunning_track as corunning
import exudyn_turnout.wheel_rail.kernel as kernel
import exudyn_turnout.wheel_rail.turnout_sections as turnout_sections
import exudyn_turnout.passage.results as results
import exudyn_turnout.plotting.curves as curves
import exudyn_turnout.plotting.backend as backend
times["import (Exudyn, numba kernels)"] = time.perf_counter() - T0 - sum(times.values())
timed(profile, "route_contact", "contact set-up (tables from the cache, wheel grid)")
timed(turnout_sections, "route_contact_tables", "  of it: contact tables (build or read)")
timed(kernel, "creep_table", "  of it: creep table (read, or wait for its build)")
timed(corunning, "simulate_wheelset", "track runs (model, static start, passage)")
timed(corunning, "simulate_vehicle", "track runs (model, static start, passage)")
timed(results, "csv_text", "CSV (text; write_csv: text and file)")
timed(results, "write_csv", "CSV (text; write_csv: text and file)")
timed(curves, "save_figure", "figures: render and save (PNG)")
timed(results, "write_passage", "writing (CSV, summary, figures)")
writer = results.write_passage

try:  # from issue 24 on the figures are drawn in forked children: no import here
    import exudyn_turnout.passage.background
    FORKED = True
except ImportError:
    FORKED = False

def write_passage(*args, **kwargs):
    drawn_here = kwargs.get("figure") is not None and not FORKED
    if drawn_here and "matplotlib.pyplot" not in sys.modules:
        start = time.perf_counter()
        backend.pyplot()  # the figures' first call would import it
        times["figures: import matplotlib"] = time.perf_counter() - start
    return writer(*args, **kwargs)

results.write_passage = write_passage
code = cli.main(sys.argv[1:])
times["whole process after start-up"] = time.perf_counter() - T0
print(json.dumps(times), file=sys.stderr)
sys.exit(code)
"""


def command(case: str, out: Path) -> list[str]:
    """The ``simulate`` command line of a case.

    Parameters
    ----------
    case : str
        A key of :data:`CASES`.
    out : Path
        ``--out``.

    Returns
    -------
    list of str
    """
    options = CASES[case][1] + (TWO_TRACKS if case.startswith("c") else [])
    return [
        sys.executable,
        "-P",  # not the working directory's package first on sys.path: the PYTHONPATH's
        "-m",
        "exudyn_turnout",
        "simulate",
        *options,
        "--route",
        "through",
        "--speed",
        "100",
        "--quiet",
        "--out",
        str(out),
    ]


def _run(argv: list[str], env: dict) -> str:
    done = subprocess.run(argv, capture_output=True, text=True, env=env, check=False)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(argv)}: exit {done.returncode}: {done.stderr[-2000:]}")
    return done.stderr


def _cold(argv: list[str], env: dict) -> None:
    """Run with an empty contact-table cache (a fresh ``XDG_CACHE_HOME``)."""
    cache = Path(tempfile.mkdtemp(prefix="main-job-cache-"))
    try:
        _run(argv, dict(env, XDG_CACHE_HOME=str(cache)))
    finally:
        shutil.rmtree(cache, ignore_errors=True)


def _sections(case: str, work: Path, env: dict, cold: bool = False) -> dict:
    argv = command(case, work / f"sections-{case}")
    argv[1:3] = ["-c", SECTIONS]  # python -c SECTIONS simulate ...
    cache = Path(tempfile.mkdtemp(prefix="main-job-cache-")) if cold else None
    try:
        err = _run(argv, env if cache is None else dict(env, XDG_CACHE_HOME=str(cache)))
    finally:
        if cache is not None:
            shutil.rmtree(cache, ignore_errors=True)
    return json.loads(err.strip().splitlines()[-1])


def _summary(timings: list) -> tuple[float, float, float, list[float]]:
    """Median wall s, CPU s and yardstick units of single-run timings; the wall samples."""
    walls = [t.seconds for t in timings]
    return (
        statistics.median(walls),
        statistics.median(t.cpu_seconds for t in timings),
        statistics.median(t.units for t in timings),
        walls,
    )


def main(argv: list[str] | None = None) -> int:
    """Measure the cases; print a markdown table (and the sections with ``--sections``).

    Parameters
    ----------
    argv : list of str, optional
        Command-line options (default ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit code.
    """
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--cases", default="a,b,c")
    parser.add_argument("--cold", action="store_true", help="also cold (empty table cache)")
    parser.add_argument("--sections", action="store_true", help="stage times of one run")
    parser.add_argument("--checkout", help="time this checkout's package (PYTHONPATH)")
    parser.add_argument(
        "--versus",
        metavar="DIR",
        help="also time this checkout (e.g. the commit before), run for run alternating "
        "with the other one, each run between two yardstick runs",
    )
    args = parser.parse_args(argv)
    cases = [c.strip() for c in args.cases.split(",")]
    unknown = [c for c in cases if c not in CASES]
    if unknown:
        parser.error(f"unknown case(s) {unknown}; cases: {', '.join(CASES)}")
    # "this": the checkout holding this script (or --checkout), on PYTHONPATH; the commands
    # run with -P, so the working directory's package cannot stand in for either checkout
    # (it did: `-m` puts the working directory first, and a run from inside a checkout
    # timed that checkout twice)
    this = Path(args.checkout).resolve() if args.checkout else Path(__file__).resolve().parents[1]
    checkouts = {"this": dict(os.environ, PYTHONPATH=str(this))}
    if args.versus:
        checkouts = {
            "versus": dict(os.environ, PYTHONPATH=str(Path(args.versus).resolve())),
            **checkouts,
        }
    stick = Yardstick()
    work = Path(tempfile.mkdtemp(prefix="main-job-"))
    rows = []
    sections: dict[str, dict] = {}
    try:
        for case in cases:
            argv_case = command(case, work / case)
            kinds = [("warm", _run)] + ([("cold", _cold)] if args.cold else [])
            for kind, runner in kinds:
                print(f"... {case}: {CASES[case][0]}, {kind}", file=sys.stderr, flush=True)
                if kind == "warm":
                    for env in checkouts.values():  # untimed: tables cached, kernels compiled
                        _run(argv_case, env)
                timings: dict[str, list] = {name: [] for name in checkouts}
                for _ in range(args.repeats):
                    for name, env in checkouts.items():
                        timings[name].append(
                            stick.measure(
                                lambda r=runner, a=argv_case, e=env: r(a, e), 1, warm_up=False
                            )
                        )
                for name in checkouts:
                    rows.append((case, kind, name, _summary(timings[name])))
            if args.sections:
                for kind in ["warm"] + (["cold"] if args.cold else []):
                    for name, env in checkouts.items():
                        label = f"{case} {kind}" + (f" ({name})" if args.versus else "")
                        sections[label] = _sections(case, work, env, cold=kind == "cold")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print(machine_line())
    where = {"this": args.checkout or "this one", "versus": args.versus}
    print("checkouts: " + "; ".join(f"{n}: {where[n]}" for n in checkouts), end="")
    print(f"; repeats {args.repeats}\n")
    print(
        "| case | cache | checkout | wall s (median) | CPU s | yardstick units | wall samples s |"
    )
    print("|---|---|---|---|---|---|---|")
    for case, kind, name, (wall, cpu, units, samples) in rows:
        text = ", ".join(f"{s:.1f}" for s in samples)
        print(
            f"| {case}: {CASES[case][0]} | {kind} | {name} | {wall:.1f} | {cpu:.1f} | "
            f"{units:.1f} | {text} |"
        )
    yard = sorted(stick.times)
    print(f"\nyardstick: {len(yard)} runs, median {yard[len(yard) // 2]:.3f} s wall")
    if sections:
        names = list(dict.fromkeys(name for times in sections.values() for name in times))
        print("\n| stage (wall s, one run) | " + " | ".join(sections) + " |")
        print("|---|" + "---|" * len(sections))
        for name in names:
            cells = [f"{times[name]:.2f}" if name in times else "" for times in sections.values()]
            print(f"| {name} | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
