"""Study execution: 1 worker vs 2 workers, and a Dask LocalCluster vs the process pool.

A 24-case study of the default profile contact (2 track models x 6 speeds x 2 rail pad
stiffnesses, the through route from -5 to 60 m, about 1-2 s a case) is run into fresh
directories: serially in this process, on ``run_study``'s own process pool of 2 workers
(warmed once, the longest cases first; forked on Linux, and spawned: each spawned worker
imports and warms up itself), on the same kind of pool with 1 worker
(``process_pool(cases, 1)``), and on a Dask LocalCluster of 2 worker processes (cluster
start-up timed apart). Each run alternates with the yardstick
(``benchmarks/yardstick.py``): the table gives wall time, yardstick units, per case,
speed-up over 1 worker, and whether the peaks equal the serial run's to the bit. The
machine's own 2-process speed-up (the yardstick run in 2 processes at once) is printed
beside: on a shared machine, the study cannot beat it.

Run: ``python benchmarks/bench_study.py [--cases-dir DIR] [--quick]`` (needs
dask[distributed] for the Dask row). Issue 24's goal: 2 workers >= 1.8x 1 worker.
"""

import argparse
import os
import shutil
import tempfile
from pathlib import Path

# One BLAS/OpenMP thread per process in every row (run_study's pool and a Dask nanny set
# this for their workers; the serial row gets it from here).
for _name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

import numpy as np  # noqa: E402
from yardstick import Yardstick, machine_line, parallel_speedup  # noqa: E402

STUDY = """
[study]
name = "benchmark, 24 cases"

[base]
contact = "profile"
route = "through"
x_start = {x_start}
x_end = {x_end}
output_step = 1e-3

[factors]
track = ["2-layer", "3-layer"]
speed_kmh = {speeds}
"turnout.rail_types.stock.pad.k_z" = [100e6, 140e6]
"""


def main(argv=None):
    """Run the study on each executor and print the table."""
    from exudyn_turnout.studies import load_study, run_study
    from exudyn_turnout.studies.run import default_start_method, process_pool

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases-dir", help="where the runs are stored (default: a temp dir)")
    parser.add_argument("--quick", action="store_true", help="8 short cases (a smoke run)")
    args = parser.parse_args(argv)
    root = Path(args.cases_dir or tempfile.mkdtemp(prefix="bench_study_"))
    shutil.rmtree(root, ignore_errors=True)
    root.mkdir(parents=True)
    text = STUDY.format(
        x_start=44.0 if args.quick else -5.0,
        x_end=47.0 if args.quick else 60.0,
        speeds="[80.0, 100.0]" if args.quick else "[60.0, 70.0, 80.0, 90.0, 100.0, 110.0]",
    )
    (root / "study.toml").write_text(text, encoding="utf-8")
    study = load_study(root / "study.toml")
    stick = Yardstick()
    rows = []

    def timed(label, folder, **kwargs):
        out = {}

        def run():
            out["result"] = run_study(study, out=root / folder, **kwargs)

        t = stick.measure(run, repeats=1, warm_up=False)
        result = out["result"]
        assert result.failed == 0, result.table["error"]
        rows.append((label, t, result))
        return t

    timed("serial, in this process", "serial", workers=1)
    method = default_start_method()
    timed(f"process pool ({method}), 2 workers", "pool2", workers=2)
    with process_pool(study.cases(), 1) as one:
        timed(f"process pool ({method}), 1 worker", "pool1", executor=one)
    if method != "spawn":
        timed("process pool (spawn), 2 workers", "spawn2", workers=2, start_method="spawn")
    dask_start = None
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        print("dask[distributed] not installed: no Dask row")
    else:
        import time

        start = time.perf_counter()
        with (
            LocalCluster(
                n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
            ) as cluster,
            Client(cluster) as client,
        ):
            dask_start = time.perf_counter() - start
            timed("Dask LocalCluster, 2 workers", "dask", executor=client.get_executor())
    machine_gain = parallel_speedup(2)
    n = rows[0][2].n_cases
    reference = rows[0][2].table
    walls = {label: t.seconds for label, t, _ in rows}
    one = walls[f"process pool ({method}), 1 worker"]
    print(f"\n{n} cases, profile contact; {machine_line()}")
    print(f"yardstick median {stick.median:.3f} s\n")
    print(
        f"{'executor':<32}{'wall s':>9}{'yardstick':>11}{'per case s':>12}"
        f"{'speed-up vs 1':>15}{'same':>6}"
    )
    for label, t, result in rows:
        same = all(
            np.array_equal(result.table[c], reference[c], equal_nan=reference[c].dtype.kind == "f")
            for c in reference
            if c.startswith(("peak_", "max_", "rms_"))
        )
        print(
            f"{label:<32}{t.seconds:>9.1f}{t.units:>11.1f}{t.seconds / n:>12.3f}"
            f"{one / t.seconds:>15.2f}{str(same):>6}"
        )
    if dask_start is not None:
        pool2 = walls[f"process pool ({method}), 2 workers"]
        overhead = (walls["Dask LocalCluster, 2 workers"] - pool2) / n
        print(
            f"\nDask LocalCluster start-up {dask_start:.1f} s (not in its row); "
            f"Dask over the 2-worker pool: {overhead * 1e3:+.0f} ms per case"
        )
    print(
        f"1 -> 2 workers (process pool): x{one / walls[f'process pool ({method}), 2 workers']:.2f} "
        f"(goal >= 1.8); the yardstick in 2 processes at the time: x{machine_gain:.2f}"
    )
    shutil.rmtree(root, ignore_errors=True)


if __name__ == "__main__":
    main()
