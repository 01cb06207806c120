"""Benchmark: size and writing time of a passage's output files.

Run: ``python benchmarks/bench_outputs.py [--repeat N] [--quick]``. Two runs (issue 24 and
25's cases): the main job (single wheelset, 3-layer, through route, 100 km/h, -5 to 60 m)
and the full Manchester vehicle on the diverging route (80 km/h, front wheelset 30 to 60 m);
``--quick`` shortens both to 1 m. Each run's columns are written by

- the previous writer, the yardstick: :mod:`csv`, one formatted value at a time (the code
  of :func:`~exudyn_turnout.passage.results.write_passage` before its rewrite, kept here);
- the previous NPZ: ``np.savez``, float64, uncompressed;
- today's :func:`~exudyn_turnout.passage.results.write_passage`: CSV, NPZ (compressed),
  NPZ float32;

interleaved ``--repeat`` times, best time kept, reported in seconds and in yardstick units
(the ratios are what carries over to another machine), with the file sizes and the number
of empty CSV cells.
"""

from __future__ import annotations

import argparse
import csv
import math
import tempfile
import time
from pathlib import Path

import numpy as np

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage.results import write_passage
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings


def previous_csv(columns, path: Path) -> None:
    """The CSV writer before the rewrite (the yardstick)."""
    names = list(columns)
    data = np.column_stack([columns[n] for n in names])
    with open(path, "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(names)
        for row in data:
            w.writerow(["" if not math.isfinite(v) else f"{v:.9g}" for v in row])


def previous_npz(columns, path: Path) -> None:
    """The NPZ writer before the rewrite: float64, uncompressed."""
    np.savez(path, **{n: np.asarray(v, dtype=float) for n, v in columns.items()})


def best(fn, repeat: int) -> float:
    """Shortest wall time (s) of ``repeat`` calls."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def rows_of(label: str, result, repeat: int) -> list[tuple]:
    """(case, writer, seconds, yardstick units, MB, empty cells) per writer."""
    out = []
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        writers = {
            "previous CSV (yardstick)": (
                lambda: previous_csv(result.columns, d / "p.csv"),
                "p.csv",
            ),
            "previous NPZ (float64)": (lambda: previous_npz(result.columns, d / "p.npz"), "p.npz"),
            "CSV": (lambda: write_passage(result, d / "c", "csv"), "c/timeseries.csv"),
            "NPZ compressed": (lambda: write_passage(result, d / "n", "npz"), "n/timeseries.npz"),
            "NPZ compressed float32": (
                lambda: write_passage(result, d / "f", "npz", dtype="float32"),
                "f/timeseries.npz",
            ),
        }
        times = {name: [] for name in writers}
        for _ in range(repeat):  # interleaved: a noisy machine hits every writer alike
            for name, (fn, _) in writers.items():
                times[name].append(best(fn, 1))
        yard = min(times["previous CSV (yardstick)"])
        for name, (_, file) in writers.items():
            path = d / file
            empty = ""
            if path.suffix == ".csv":
                with open(path, newline="", encoding="utf-8") as fh:
                    empty = str(sum(row.count("") for row in csv.reader(fh)))
            seconds = min(times[name])
            out.append((label, name, seconds, seconds / yard, path.stat().st_size / 1e6, empty))
    return out


def main(argv=None) -> None:
    """Print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--quick", action="store_true", help="1 m runs")
    args = parser.parse_args(argv)
    turnout = load_turnout()
    through = PassageSettings(x_end=-4.0 if args.quick else None)
    diverging = PassageSettings(
        route="diverging", speed_kmh=80.0, x_start=30.0, x_end=31.0 if args.quick else 60.0
    )
    cases = (
        ("through, wheelset", simulate_passage(turnout, through, vehicle="wheelset")),
        ("diverging, Manchester", simulate_passage(turnout, diverging, "manchester")),
    )
    print(f"{'case':<22}{'writer':<26}{'s':>8}{'x yardstick':>13}{'MB':>8}{'empty cells':>13}")
    for label, result in cases:
        n = len(result.columns["t_s"])
        print(f"# {label}: {len(result.columns)} columns x {n} rows")
        for row in rows_of(label, result, args.repeat):
            case, name, seconds, ratio, mb, empty = row
            print(f"{case:<22}{name:<26}{seconds:>8.3f}{ratio:>13.2f}{mb:>8.2f}{empty:>13}")


if __name__ == "__main__":
    main()
