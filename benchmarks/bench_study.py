"""Study execution: 1 worker vs 2 workers, and a Dask LocalCluster vs the process pool.

A 24-case study (2 routes x 2 track models x 6 speeds, the crossing panel 30-60 m with the
height-table contact, about a second per case) is run four times into fresh directories:
serially in this process, on a process pool of 2 workers (spawn), on a Dask LocalCluster
of 2 worker processes (cluster start-up timed apart), and on 1 pool worker. Prints a table:
wall time, per case, speed-up over 1 worker, and the Dask overhead per case over the pool.

Run: ``python benchmarks/bench_study.py [--cases-dir DIR]`` (needs dask[distributed] for
the Dask row; the machine's other load shows in the numbers: run it on a quiet machine).
"""

import argparse
import multiprocessing
import os
import shutil
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

# One BLAS/OpenMP thread per process in every row (run_study's pool and a Dask nanny set
# this for their workers; the serial row and the 1-worker pool get it from here).
for _name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

import numpy as np  # noqa: E402

STUDY = """
[study]
name = "benchmark, 24 cases"

[base]
contact = "height-table"
x_start = 30.0
x_end = 60.0
output_step = 1e-3

[factors]
route = ["through", "diverging"]
track = ["2-layer", "3-layer"]
speed_kmh = [50.0, 60.0, 70.0, 80.0, 90.0, 100.0]
"""


def _timed(label, out, **kwargs):
    from exudyn_turnout.studies import run_study

    start = time.perf_counter()
    result = run_study(out.parent / "study.toml", out=out, **kwargs)
    wall = time.perf_counter() - start
    assert result.failed == 0, result.table["error"]
    return label, wall, result


def main(argv=None):
    """Run the study on each executor and print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases-dir", help="where the runs are stored (default: a temp dir)")
    args = parser.parse_args(argv)
    root = Path(args.cases_dir or tempfile.mkdtemp(prefix="bench_study_"))
    shutil.rmtree(root, ignore_errors=True)
    root.mkdir(parents=True)
    (root / "study.toml").write_text(STUDY, encoding="utf-8")
    rows = [_timed("serial, in process", root / "serial", workers=1)]
    rows.append(_timed("process pool, 2 workers", root / "pool2", workers=2))
    with ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) as one:
        rows.append(_timed("process pool, 1 worker", root / "pool1", executor=one))
    dask_start = None
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        print("dask[distributed] not installed: no Dask row")
    else:
        start = time.perf_counter()
        with (
            LocalCluster(
                n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
            ) as cluster,
            Client(cluster) as client,
        ):
            dask_start = time.perf_counter() - start
            rows.append(
                _timed(
                    "Dask LocalCluster, 2 workers", root / "dask", executor=client.get_executor()
                )
            )
    n = rows[0][2].n_cases
    reference = rows[0][2].table["max_Fz_crossing_N"]
    walls = {label: wall for label, wall, _ in rows}
    one = walls["process pool, 1 worker"]
    print(f"\n{n} cases, {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}\n")
    print(f"{'executor':<32}{'wall (s)':>10}{'per case (s)':>14}{'speed-up vs 1':>15}{'same':>6}")
    for label, wall, result in rows:
        same = np.array_equal(result.table["max_Fz_crossing_N"], reference)
        print(f"{label:<32}{wall:>10.1f}{wall / n:>14.3f}{one / wall:>15.2f}{str(same):>6}")
    if dask_start is not None:
        overhead = (walls["Dask LocalCluster, 2 workers"] - walls["process pool, 2 workers"]) / n
        print(
            f"\nDask LocalCluster start-up {dask_start:.1f} s (not in its row); "
            f"Dask over the 2-worker pool: {overhead * 1e3:+.0f} ms per case"
        )
    print(f"1 -> 2 workers (process pool): x{one / walls['process pool, 2 workers']:.2f}")
    shutil.rmtree(root, ignore_errors=True)


if __name__ == "__main__":
    main()
