"""The README's performance table: its cases, measured against the yardstick, and its writer.

Run: ``python benchmarks/performance_table.py [--update-readme] [--quick] [--repeats N]``.
Prints the table (markdown); ``--update-readme`` also rewrites it in README.md between
``<!-- perf-table:start -->`` and ``<!-- perf-table:end -->``. ``--quick`` is a smoke run
(short x ranges, a 4-case study, one repeat): its numbers are not the table's.

Every case runs once untimed (contact tables, compiled kernels, the FE model's factors),
then ``--repeats`` times interleaved with the yardstick (``benchmarks/yardstick.py``): each
is reported in seconds and in yardstick units, which carry over between machines and
loads. The cases (issue 24):

- the single wheelset (its sprung share) on the 3-layer and the 2-layer co-running track,
  through route, 100 km/h, front wheelset -5..60 m (2.34 s simulated), profile contact,
  h = 1e-4 s: cost as x real time and in yardstick units;
- the full Manchester vehicle (4 wheelsets, a co-running track under each), same case;
- the FE track under the single wheelset over the crossing (44-49 m) against the 3-layer
  track, same case: the ratio of CPU times (the goal is <= 50);
- the warm main job on one track, ``exudyn-turnout simulate --layers 3 --route through
  --speed 100 --out DIR`` as a fresh process (wall, after one untimed run that fills the
  caches), with the default vehicle (the full Manchester vehicle since issue 24) and with
  ``--vehicle wheelset`` (the single wheelset, named);
- a study of the profile contact, ``exudyn-turnout study`` with ``--workers 2`` against
  ``--workers 1`` (each a fresh process; the speed-up goal is >= 1.8), three rounds with
  the order alternating, each beside the speed-up the machine gives the yardstick itself
  in 2 processes at the time: the medians of both and their ratio (one pair of runs on a
  shared machine swung 0.95-1.74 in the yardstick's own speed-up).

The main job's and the study's fresh processes read and write bytecode (``.pyc``) in a
temporary ``PYTHONPYCACHEPREFIX``, filled by their untimed first run, as an installed
package has it (pip compiles it at install): the machine the table was first made on sets
``PYTHONDONTWRITEBYTECODE=1``, and there every process compiled the package from its source,
~0.17 s of a study's serial start (``benchmarks/study_timeline.py --bytecode``). Rows made
before this (session 12) include that compilation.
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from yardstick import Timing, Yardstick, machine, machine_line, parallel_speedup

__all__ = ["Row", "render_table", "replace_table", "study_text", "measure", "main"]

README = Path(__file__).resolve().parents[1] / "README.md"
START = "<!-- perf-table:start -->"
END = "<!-- perf-table:end -->"
COMMAND = "python benchmarks/performance_table.py --update-readme"


@dataclass(frozen=True)
class Row:
    """One row of the table, its cells already formatted.

    Parameters
    ----------
    case : str
        What runs.
    seconds : str
        Wall time, s.
    cpu : str
        CPU time (this process and the child processes it waited for), s.
    real_time : str
        Cost as x real time, from the CPU time ("" where it does not apply).
    units : str
        Yardstick units.
    note : str
        Ratio, goal, remark.
    """

    case: str
    seconds: str
    cpu: str
    real_time: str
    units: str
    note: str = ""


def render_table(
    rows: Sequence[Row], info: dict, yardstick_seconds: float, yardstick_cpu: float, quick: bool
) -> str:
    """The markdown block written between the README's markers.

    Parameters
    ----------
    rows : sequence of Row
    info : dict
        :func:`yardstick.machine` at the start of the run.
    yardstick_seconds : float
        s, median wall time of the yardstick runs.
    yardstick_cpu : float
        s, median CPU time of the yardstick runs.
    quick : bool
        A ``--quick`` run (said in the text).

    Returns
    -------
    str
        The lines between the markers (no markers), ending with a newline.
    """
    lines = [
        f"Measured by `{COMMAND}`{' --quick (smoke run, short cases)' if quick else ''} on "
        f"{machine_line(info)}. The yardstick (`benchmarks/yardstick.py`, a fixed "
        f"NumPy/SciPy/Python workload) took {yardstick_seconds:.3f} s wall, "
        f"{yardstick_cpu:.3f} s CPU (medians) in this run. A case's yardstick units are its "
        "wall time over the yardstick's, run alternately: they carry over to another machine "
        "or load far better than the seconds. On a loaded machine the CPU time is the "
        "closer to the wall time on an idle one; x real time is taken from it.",
        "",
        "| case | wall s | CPU s | x real time | yardstick units | note |",
        "|---|---:|---:|---:|---:|---|",
    ]
    for r in rows:
        lines.append(f"| {r.case} | {r.seconds} | {r.cpu} | {r.real_time} | {r.units} | {r.note} |")
    return "\n".join(lines) + "\n"


def replace_table(readme_text: str, table: str) -> str:
    """The README's text with the block between the markers replaced by ``table``.

    Parameters
    ----------
    readme_text : str
    table : str
        From :func:`render_table`.

    Returns
    -------
    str

    Raises
    ------
    ValueError
        The markers are missing, repeated or out of order.
    """
    if readme_text.count(START) != 1 or readme_text.count(END) != 1:
        raise ValueError(f"README: expected one {START} and one {END}")
    head, rest = readme_text.split(START)
    if END not in rest:
        raise ValueError(f"README: {END} comes before {START}")
    _, tail = rest.split(END)
    return f"{head}{START}\n{table}{END}{tail}"


def _passage_rows(stick: Yardstick, repeats: int, quick: bool) -> tuple[list[Row], dict]:
    from dataclasses import replace

    from exudyn_turnout.inputs.turnout import load_turnout
    from exudyn_turnout.passage.run import simulate_passage
    from exudyn_turnout.passage.settings import PassageSettings

    turnout = load_turnout()
    x_a, x_b = (40.0, 45.0) if quick else (-5.0, 60.0)
    base = PassageSettings(route="through", speed_kmh=100.0, x_start=x_a, x_end=x_b)
    simulated = (x_b - x_a) / base.v
    span = f"through, 100 km/h, x {x_a:g}..{x_b:g} m ({simulated:.2f} s simulated)"
    rows, raw = [], {}
    exudyn = replace(base, solver="exudyn")
    for label, vehicle, track, settings in (
        ("single wheelset, 3-layer", "wheelset", "3-layer", base),
        ("single wheelset, 2-layer", "wheelset", "2-layer", base),
        ("full Manchester vehicle (4 wheelsets), 3-layer", "manchester", "3-layer", base),
        (
            "full Manchester vehicle, 3-layer, `--solver exudyn`",
            "manchester",
            "3-layer",
            exudyn,
        ),
    ):
        print(f"... {label}", file=sys.stderr, flush=True)
        if vehicle == "manchester":  # the first call may compile the stepper: untimed
            simulate_passage(turnout, replace(settings, x_end=x_a + 1.0), vehicle, track=track)
        t = stick.measure(
            lambda vehicle=vehicle, track=track, settings=settings: simulate_passage(
                turnout, settings, vehicle, track=track
            ),
            repeats,
        )
        raw[label] = t
        rows.append(
            Row(
                f"{label}, {span}",
                f"{t.seconds:.2f}",
                f"{t.cpu_seconds:.2f}",
                f"{t.cpu_seconds / simulated:.2f}",
                f"{t.units:.2f}",
            )
        )
    rows[0] = replace(rows[0], note="issue 24 before: 0.16-0.17x real time, quiet machine")
    w1, w3 = raw["single wheelset, 2-layer"], raw["single wheelset, 3-layer"]
    rows[1] = replace(rows[1], note=f"3-layer / 2-layer {w3.units / w1.units:.2f} (paper: ~1.10)")
    full = raw["full Manchester vehicle (4 wheelsets), 3-layer"]
    rows[2] = replace(
        rows[2],
        note=f"{full.units / w3.units:.1f}x the wheelset; goal <= 0.5x real time (quiet machine); "
        "the package's compiled stepper, the default since session 13",
    )
    slow = raw["full Manchester vehicle, 3-layer, `--solver exudyn`"]
    rows[3] = replace(
        rows[3],
        note=f"Exudyn's own integrator: {slow.units / full.units:.2f}x the default's units "
        "(peaks within Newton's tolerance of each other, tests/test_stepper.py)",
    )
    fe_a, fe_b = (44.0, 44.5) if quick else (44.0, 49.0)
    crossing = replace(base, x_start=fe_a, x_end=fe_b)
    print("... FE track over the crossing", file=sys.stderr, flush=True)
    co = stick.measure(lambda: simulate_passage(turnout, crossing, "wheelset", track="3-layer"), 3)
    fe = stick.measure(
        lambda: simulate_passage(turnout, crossing, "wheelset", track="fe"), max(1, repeats - 1)
    )
    sim_fe = (fe_b - fe_a) / base.v
    rows.append(
        Row(
            f"FE track, single wheelset over the crossing, x {fe_a:g}..{fe_b:g} m, 100 km/h",
            f"{fe.seconds:.2f}",
            f"{fe.cpu_seconds:.2f}",
            f"{fe.cpu_seconds / sim_fe:.1f}",
            f"{fe.units:.2f}",
            f"CPU {fe.cpu_seconds / co.cpu_seconds:.0f}x the 3-layer run's "
            f"{co.cpu_seconds:.2f} s; yardstick units {fe.units / co.units:.0f}x "
            "(goal <= 50x; 567x at 8bb37b5)",
        )
    )
    return rows, raw


def _cli(*args: str) -> list[str]:
    # -P: the package on _package_path(), not the working directory's (``-m`` puts it first)
    return [sys.executable, "-P", "-m", "exudyn_turnout", *args]


def _package_path() -> str:
    """The folder holding the exudyn_turnout this process imports (its rows' package)."""
    import exudyn_turnout

    return str(Path(exudyn_turnout.__file__).resolve().parents[1])


def _run(command: list[str], pycache: Path | None = None) -> None:
    env = dict(os.environ, PYTHONPATH=_package_path())
    if pycache is not None:  # bytecode read and written there, as an installed package has it
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        env["PYTHONPYCACHEPREFIX"] = str(pycache)
    done = subprocess.run(command, capture_output=True, text=True, check=False, env=env)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(command)}: exit {done.returncode}: {done.stderr[-2000:]}")


def _main_job_rows(stick: Yardstick, repeats: int, quick: bool, work: Path) -> list[Row]:
    extra = ["--x-start", "40", "--x-end", "45"] if quick else []
    job = ["--layers", "3", "--route", "through", "--speed", "100"]
    rows = []
    for vehicle, goal in (
        (["--vehicle", "wheelset"], "goal <= 5 s; 23.5 s at 8bb37b5"),
        ([], "goal <= 8 s (the default since issue 24: the full Manchester vehicle)"),
    ):
        command = _cli("simulate", *vehicle, *job, *extra) + ["--out", str(work / "simulate")]
        shown = " ".join(["exudyn-turnout simulate", *vehicle, *job, "--out DIR"])
        print(f"... main job {' '.join(vehicle) or '(default vehicle)'}", file=sys.stderr)
        # the untimed warm-up run writes the bytecode the timed runs read
        t = stick.measure(lambda command=command: _run(command, work / "pycache"), repeats)
        rows.append(
            Row(
                f"warm main job: `{shown}`{' (x 40..45 m)' if quick else ''}, a fresh process "
                "(bytecode cached)",
                f"{t.seconds:.1f}",
                f"{t.cpu_seconds:.1f}",
                "",
                f"{t.units:.1f}",
                goal,
            )
        )
    return rows


def study_text(quick: bool) -> str:
    """The study the table's scaling row runs (profile contact, the package's default).

    Parameters
    ----------
    quick : bool
        4 short cases instead of 24 whole passages.

    Returns
    -------
    str
        A study file.
    """
    if quick:
        span, speeds, pads = "x_start = 44.0\nx_end = 47.0", "[80.0, 100.0]", "[100e6, 140e6]"
    else:
        span = "x_start = -5.0\nx_end = 60.0"
        speeds = "[60.0, 70.0, 80.0, 90.0, 100.0, 110.0]"
        pads = "[96e6, 108e6, 132e6, 144e6]"
    return f"""[study]
name = "performance table: scaling"

[base]
contact = "profile"
route = "through"
track = "3-layer"
{span}
output_step = 1e-3

[factors]
speed_kmh = {speeds}
"turnout.rail_types.stock.pad.k_z" = {pads}
"""


def _study_row(stick: Yardstick, quick: bool, work: Path) -> Row:
    study = work / "study.toml"
    study.write_text(study_text(quick), encoding="utf-8")
    n_cases = 4 if quick else 24
    walls: dict[int, list[Timing]] = {}
    runs = [0]
    rounds = 1 if quick else 3

    def run(workers: int, file: Path = study) -> None:
        runs[0] += 1
        out = work / f"study-{workers}-{runs[0]}"
        command = _cli("study", str(file), "--out", str(out), "--workers", str(workers))
        _run(command + ["--no-plot"], work / "pycache")
        shutil.rmtree(out, ignore_errors=True)

    prime = work / "prime.toml"  # untimed: the bytecode of every module a study imports
    prime.write_text(study_text(True), encoding="utf-8")
    run(1, prime)
    gains, machine_gains = [], []
    for k in range(rounds):
        for workers in (1, 2) if k % 2 == 0 else (2, 1):
            print(f"... study, {workers} worker(s), round {k + 1}", file=sys.stderr, flush=True)
            t = stick.measure(lambda workers=workers: run(workers), 1, warm_up=False)
            walls.setdefault(workers, []).append(t)
        gains.append(walls[1][-1].seconds / walls[2][-1].seconds)
        print("... the yardstick in 2 processes", file=sys.stderr, flush=True)
        machine_gains.append(parallel_speedup(2))
    gain, machine_gain = statistics.median(gains), statistics.median(machine_gains)
    one, two = (min(walls[w], key=lambda t: t.seconds) for w in (1, 2))
    return Row(
        f"study, {n_cases} passages, profile contact: `exudyn-turnout study --workers 2` "
        f"vs `--workers 1`, fresh processes, {rounds} round{'s' if rounds > 1 else ''} "
        "alternating, bytecode cached",
        f"{two.seconds:.1f} vs {one.seconds:.1f}",
        f"{two.cpu_seconds:.1f} vs {one.cpu_seconds:.1f}",
        "",
        f"{two.units:.1f} vs {one.units:.1f}",
        f"speed-up {gain:.2f} (median of the rounds' "
        f"{', '.join(f'{g:.2f}' for g in gains)}; goal >= 1.8); the yardstick itself in 2 "
        f"processes in the same rounds: {machine_gain:.2f} (median), so "
        f"{gain / machine_gain:.2f} of what the machine gave; CPU of 2 workers / 1: "
        f"{two.cpu_seconds / one.cpu_seconds:.2f} (the fastest run of each)",
    )


def measure(repeats: int, quick: bool) -> tuple[list[Row], dict, Yardstick]:
    """Run every case of the table.

    Parameters
    ----------
    repeats : int
        Timed runs per passage case.
    quick : bool
        Short smoke cases.

    Returns
    -------
    rows : list of Row
    info : dict
        The machine (:func:`yardstick.machine`; the load average at the end).
    stick : Yardstick
        With every yardstick run.
    """
    info = machine()
    stick = Yardstick()
    rows, _ = _passage_rows(stick, repeats, quick)
    work = Path(tempfile.mkdtemp(prefix="perf-table-"))
    try:
        rows.extend(_main_job_rows(stick, repeats, quick, work))
        rows.append(_study_row(stick, quick, work))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    info["load_average"] = machine()["load_average"]  # at the end: the 5 and 15 min cover the run
    return rows, info, stick


def main(argv: Sequence[str] | None = None) -> int:
    """Measure, print the table, rewrite the README's table if asked."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--update-readme", action="store_true", help="rewrite README.md's table")
    parser.add_argument("--quick", action="store_true", help="a smoke run (short cases)")
    parser.add_argument("--repeats", type=int, default=3, help="timed runs per case (default 3)")
    args = parser.parse_args(argv)
    if args.repeats < 1:
        parser.error(f"--repeats {args.repeats}: must be >= 1")
    repeats = 1 if args.quick else args.repeats
    rows, info, stick = measure(repeats, args.quick)
    table = render_table(rows, info, stick.median, stick.cpu_median, args.quick)
    print(table)
    if args.update_readme:
        text = README.read_text(encoding="utf-8")
        README.write_text(replace_table(text, table), encoding="utf-8")
        print(f"rewrote the table in {README}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
