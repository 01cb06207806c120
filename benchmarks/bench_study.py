"""Study execution: 1 worker vs 2 workers, and a Dask LocalCluster vs the process pool.

A 24-case study of the default profile contact (2 track models x 6 speeds x 2 rail pad
stiffnesses, the through route from -5 to 60 m) is run into fresh directories, by default
with the full Manchester vehicle (``--vehicle manchester``, what ``simulate`` and
``simulate_passage`` run by default: ~2.4 s CPU a case), or with the single wheelset
(``--vehicle wheelset``, a study's default vehicle: ~1 s a case). This process is warmed
first (imports, the route's contact tables, compiled kernels: timed apart, as every pool
row starts from it). Then: serially in this process; on ``run_study``'s own process pool of
2 workers (warmed, the longest cases first; forked on Linux); on the same kind of pool with
1 worker (``process_pool(cases, 1)``, its start timed as the 2-worker row's); spawned (each
worker imports and warms up itself); and on a Dask LocalCluster of 2 worker processes
(cluster start-up timed apart). Each run alternates with the yardstick
(``benchmarks/yardstick.py``).

The table gives per row: wall time, yardstick units, CPU time of this process and of the
worker processes (``resource.getrusage(RUSAGE_CHILDREN)``, taken after the pool's shutdown;
a Dask cluster's after it closed), the sum of the cases' own CPU time (each worker's
``time.process_time`` around the case) and the rest (worker start, warm-up, waiting,
pickling), the wall speed-up over 1 worker, the CPU over 1 worker's, and whether the
results equal the serial run's to the bit. The machine's own 2-process figures (the
yardstick in 2 processes at once: throughput gain and CPU time per run over alone) are
measured before and after the pool rows: on a shared machine the study cannot beat them.

Last, the shortest case is run alone and in both workers at once, interleaved with the
yardstick run the same way (``--pairs`` rounds): the CPU time of a case in 2 processes at
once over alone, beside the yardstick's.

Run: ``python benchmarks/bench_study.py [--vehicle manchester|wheelset] [--quick]
[--cases-dir DIR] [--no-spawn] [--no-dask] [--pairs N] [--alternate N]`` (needs
dask[distributed] for the Dask row; ``--alternate N``: only the two pools, in turn, with
the speed-up on idle cores estimated from the cases' CPU times). Issue 24's goal: 2 workers
>= 1.8x 1 worker.

Measured 2026-12-02 11:04-11:58 UTC, alternating with the base 95eeea5 (a ``git archive``
copy, its numba caches filled first) on the 2-core AMD EPYC VM, shared with other jobs: load
average 1.1-7, so most wall speed-ups say nothing (0.6-1.5); the estimates for idle cores
come from CPU times. ``python benchmarks/study_timeline.py --trees BASE . --rounds N`` (the
performance table's study: 24 single-wheelset passages, 4 pad stiffnesses, as fresh
``exudyn-turnout study`` processes; 10 rounds each): 1 -> 2 workers x1.72 at the base
(rounds 1.48-1.89), x1.78 here (1.62-1.99), medians; in the rounds that ran undisturbed
(wall = CPU time with 1 worker, both cores busy with 2): base x1.73 (26.8 vs 15.4 s wall),
here x1.69 (27.0 vs 15.9 s) and x1.88 (24.9 vs 13.3 s). What changed: the
parent's warm-up before the fork 1.57-1.71 s CPU (3 kinds: the route's tables loaded 3
times, the 4th pad file's once more in a worker) -> 0.72-1.12 s (one kind: the pad
stiffness no longer keys the tables); the serial run's cases 24.7 -> 23.5 s CPU (tables
loaded once, not 4 times); the exit 0.3-1.6 s -> 0.04-0.09 s (objects frozen at exit, not
collected). Left serial in a 2-worker run: imports 0.9-1.1 s, study and cases 0.15 s,
warm-up 0.7-1.1 s, writing cases and table 0.04 s; the workers end 0.03-0.7 s apart. What
keeps it below x1.8: the cases' CPU in 2 workers over 1, 1.04-1.10 (threads, garbage
collection and copy-on-write ruled out: extra threads 0 s CPU, one young collection a case,
~4000 page faults in a worker's first case, as in this process). ``--alternate 1 --vehicle
wheelset`` (pools from a warm parent, so the warm-up is not in it; 2 rounds per tree):
x1.83, 1.76 at the base, x1.80, 2.18 here on idle cores; the cases' CPU in 2 workers over
1: 1.07-1.10 (0.92 once), the same at the base and here.
"""

import argparse
import os
import resource
import shutil
import tempfile
import time
from pathlib import Path

# One BLAS/OpenMP thread per process in every row (run_study's pool and a Dask nanny set
# this for their workers; the serial row gets it from here).
for _name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

import numpy as np  # noqa: E402
from yardstick import Yardstick, machine_line, parallel_cost, workload  # noqa: E402

STUDY = """
[study]
name = "benchmark, {n} cases"

[base]
contact = "profile"
route = "through"
vehicle = "{vehicle}"
x_start = {x_start}
x_end = {x_end}
output_step = 1e-3

[factors]
track = ["2-layer", "3-layer"]
speed_kmh = {speeds}
"turnout.rail_types.stock.pad.k_z" = [100e6, 140e6]
"""


def _children_cpu() -> float:
    """s, CPU time (user + system) of the child processes waited for so far."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def study_text(vehicle: str, quick: bool) -> str:
    """The benchmark's study file (24 cases, or 8 short ones with ``quick``)."""
    speeds = [80.0, 100.0] if quick else [60.0, 70.0, 80.0, 90.0, 100.0, 110.0]
    return STUDY.format(
        n=4 * len(speeds),
        vehicle=vehicle,
        x_start=40.0 if quick else -5.0,
        x_end=50.0 if quick else 60.0,
        speeds=str(speeds),
    )


def main(argv=None):
    """Run the study on each executor and print the table."""
    from exudyn_turnout.studies import load_study, run_study
    from exudyn_turnout.studies.run import default_start_method, process_pool, warm_up

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--vehicle",
        choices=("manchester", "wheelset"),
        default="manchester",
        help="the full Manchester vehicle (simulate's default) or the single wheelset",
    )
    parser.add_argument("--cases-dir", help="where the runs are stored (default: a temp dir)")
    parser.add_argument("--quick", action="store_true", help="8 short cases (a smoke run)")
    parser.add_argument("--no-spawn", action="store_true", help="leave out the spawned pool")
    parser.add_argument("--no-dask", action="store_true", help="leave out the Dask cluster")
    parser.add_argument(
        "--alternate",
        type=int,
        default=0,
        metavar="N",
        help="only the 2-worker and 1-worker pools, N times in turn (with the machine's "
        "2-process gain each time): the wall speed-up per round on a load that drifts",
    )
    parser.add_argument(
        "--pairs",
        type=int,
        default=3,
        metavar="N",
        help="rounds of one case (and the yardstick) alone and in 2 processes at once "
        "(default 3; 0: none)",
    )
    args = parser.parse_args(argv)
    root = Path(args.cases_dir or tempfile.mkdtemp(prefix="bench_study_"))
    shutil.rmtree(root, ignore_errors=True)
    root.mkdir(parents=True)
    (root / "study.toml").write_text(study_text(args.vehicle, args.quick), encoding="utf-8")
    study = load_study(root / "study.toml")
    cases = study.cases()
    start, cpu = time.perf_counter(), time.process_time()
    warm_up(cases)
    warm_wall, warm_cpu = time.perf_counter() - start, time.process_time() - cpu
    if args.alternate:
        alternate(study, root, args.alternate)
        shutil.rmtree(root, ignore_errors=True)
        return
    stick = Yardstick()
    rows = []

    def timed(label, folder, pool_workers=None, **kwargs):
        out = {}

        def run():
            if pool_workers is None:
                out["result"] = run_study(study, out=root / folder, **kwargs)
            else:  # the pool's start inside the timed call, as run_study's own pool
                with process_pool(cases, pool_workers) as pool:
                    out["result"] = run_study(study, out=root / folder, executor=pool)

        parent, children = time.process_time(), _children_cpu()
        t = stick.measure(run, repeats=1, warm_up=False)
        parent = time.process_time() - parent - stick.cpu_times[-1] - stick.cpu_times[-2]
        children = _children_cpu() - children
        result = out["result"]
        assert result.failed == 0, result.table["error"]
        rows.append((label, t, result, parent, children))
        return t

    method = default_start_method()
    pool2, pool1 = f"process pool ({method}), 2 workers", f"process pool ({method}), 1 worker"
    timed("serial, in this process", "serial", workers=1)
    machine_before = parallel_cost(2, rounds=3)
    timed(pool2, "pool2", workers=2)
    timed(pool1, "pool1", pool_workers=1)
    machine_after = parallel_cost(2, rounds=3)
    if method != "spawn" and not args.no_spawn:
        timed("process pool (spawn), 2 workers", "spawn2", workers=2, start_method="spawn")
    dask_start = None
    try:
        if args.no_dask:
            raise ImportError
        from distributed import Client, LocalCluster
    except ImportError:
        print("no Dask row (--no-dask, or dask[distributed] not installed)")
    else:
        start = time.perf_counter()
        before = (time.process_time(), _children_cpu())
        cluster = LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
        )
        with cluster, Client(cluster) as client:
            dask_start = time.perf_counter() - start
            timed("Dask LocalCluster, 2 workers", "dask", executor=client.get_executor())
        # the cluster's workers are counted when the cluster has closed: the whole cluster's
        # CPU (start-up included) goes to the row
        label, t, result, parent, children = rows[-1]
        rows[-1] = (label, t, result, parent, _children_cpu() - before[1])
    n = rows[0][2].n_cases
    reference = rows[0][2].table
    walls = {label: t.seconds for label, t, *_ in rows}
    cpus = {label: parent + children for label, _, _, parent, children in rows}
    one = walls[pool1]
    print(
        f"\n{n} cases, profile contact, {args.vehicle} vehicle, "
        f"{study.base['x_start']}..{study.base['x_end']} m; {machine_line()}"
    )
    print(
        f"this process warmed up first (imports, contact tables, kernels): {warm_wall:.1f} s "
        f"wall, {warm_cpu:.1f} s CPU; yardstick median {stick.median:.3f} s wall, "
        f"{stick.cpu_median:.3f} s CPU\n"
    )
    print(
        f"{'executor':<34}{'wall s':>8}{'units':>7}{'CPU s':>8}{'cases':>8}{'rest':>7}"
        f"{'case CPU':>9}{'wall x':>8}{'CPU x':>7}{'same':>6}"
    )
    for label, t, result, parent, children in rows:
        same = all(
            np.array_equal(result.table[c], reference[c], equal_nan=reference[c].dtype.kind == "f")
            for c in reference
            if c.startswith(("peak_", "max_", "rms_", "static_", "contact_"))
        )
        in_cases = float(np.sum(result.table["case_cpu_time_s"]))
        total = parent + children
        print(
            f"{label:<34}{t.seconds:>8.1f}{t.units:>7.1f}{total:>8.1f}{in_cases:>8.1f}"
            f"{total - in_cases:>7.1f}{in_cases / n:>9.3f}{one / t.seconds:>8.2f}"
            f"{total / cpus[pool1]:>7.2f}{str(same):>6}"
        )
    print(
        "  CPU s: this process (the yardstick's runs taken out) + its worker processes; "
        "cases: the sum of the cases' own CPU; rest: CPU s - cases; wall x: 1 worker's wall "
        "over the row's; CPU x: the row's CPU over 1 worker's"
    )
    if dask_start is not None:
        overhead = (walls["Dask LocalCluster, 2 workers"] - walls[pool2]) / n
        print(
            f"\nDask LocalCluster start-up {dask_start:.1f} s (wall, not in its row's wall; its "
            f"CPU is); Dask over the 2-worker pool: {overhead * 1e3:+.0f} ms per case"
        )
    gains = f"x{machine_before[0]:.2f} before, x{machine_after[0]:.2f} after"
    ratios = f"x{machine_before[1]:.2f} before, x{machine_after[1]:.2f} after"
    print(
        f"1 -> 2 workers (process pool): wall x{one / walls[pool2]:.2f} (goal >= 1.8), "
        f"CPU x{cpus[pool2] / cpus[pool1]:.2f}, CPU in the cases "
        f"x{_case_cpu(rows, pool2) / _case_cpu(rows, pool1):.2f}; the yardstick in 2 "
        f"processes at once: throughput {gains}, CPU per run {ratios}"
    )
    if args.pairs:
        from exudyn_turnout.studies.run import estimated_cost

        shortest = min(cases, key=estimated_cost)
        case_ratio, stick_ratio = pair_cost(shortest, args.pairs)
        print(
            f"CPU of one case (case {shortest.index}) in 2 processes at once over alone: "
            f"x{case_ratio:.2f}; the yardstick's, interleaved with it: x{stick_ratio:.2f} "
            f"(medians of {args.pairs} rounds)"
        )
    serial_part = next(r[3] for r in rows if r[0] == pool2)
    print(
        f"an idle 2-core machine, from this run's CPU times (the serial row's cases handed "
        f"out in the pool's order, this process's {serial_part:.1f} s CPU in the 2-worker row "
        f"taken as serial): x{idle_speedup(cases, rows[0][2].table, serial_part, 2):.2f}"
    )
    shutil.rmtree(root, ignore_errors=True)


def alternate(study, root: Path, rounds: int) -> None:
    """The 2-worker and the 1-worker pool in turn, ``rounds`` times; print each round."""
    import statistics

    from exudyn_turnout.studies import run_study
    from exudyn_turnout.studies.run import process_pool

    cases = study.cases()
    print(f"{len(cases)} cases; {machine_line()}")
    print(
        f"{'round':>5}{'2 workers s':>13}{'1 worker s':>12}{'wall x':>8}{'machine x':>11}"
        f"{'idle x':>8}{'case CPU x':>12}"
    )
    gains, idles = [], []
    for i in range(rounds):
        walls, tables = {}, {}
        for workers in (2, 1):
            start = time.perf_counter()
            with process_pool(cases, workers) as pool:
                result = run_study(study, out=root / f"alt-{i}-{workers}", executor=pool)
            walls[workers] = time.perf_counter() - start
            tables[workers] = result.table
        machine_gain, _ = parallel_cost(2, rounds=1)
        gains.append(walls[1] / walls[2])
        one = float(np.sum(tables[1]["case_cpu_time_s"]))
        idles.append(one / makespan(cases, tables[2], 2))
        inflation = float(np.sum(tables[2]["case_cpu_time_s"])) / one
        print(
            f"{i:>5}{walls[2]:>13.1f}{walls[1]:>12.1f}{gains[-1]:>8.2f}{machine_gain:>11.2f}"
            f"{idles[-1]:>8.2f}{inflation:>12.2f}"
        )
    print(
        f"median wall speed-up x{statistics.median(gains):.2f} (goal >= 1.8); on idle cores, "
        f"from the cases' CPU times: x{statistics.median(idles):.2f}"
    )
    print(
        "  idle x: the 1-worker run's case CPU over the 2-worker run's case CPU handed out "
        "longest first to 2 idle cores; case CPU x: the cases' CPU in 2 workers over 1"
    )


def makespan(cases, table, workers: int) -> float:
    """s, the cases' CPU times (``table``) handed out in the pool's order to idle workers.

    Parameters
    ----------
    cases : list of Case
    table : dict
        A run's results table (``case``, ``case_cpu_time_s``).
    workers : int

    Returns
    -------
    float
        The last worker's finish.
    """
    import heapq

    from exudyn_turnout.studies.run import hand_out_order

    cpu = {int(i): float(t) for i, t in zip(table["case"], table["case_cpu_time_s"])}
    free = [0.0] * workers
    for case in hand_out_order(cases):
        heapq.heapreplace(free, free[0] + cpu[case.index])
    return max(free)


def _cpu_of(task) -> float:
    """s, CPU time of ``task()`` in this (worker) process."""
    start = time.process_time()
    task()
    return time.process_time() - start


def _run_case_cpu(case) -> float:
    from exudyn_turnout.studies.run import run_case

    return _cpu_of(lambda: run_case(case))


def _yardstick_cpu(_: int) -> float:
    return _cpu_of(workload)


def pair_cost(case, rounds: int = 3) -> tuple[float, float]:
    """CPU time of a case, and of the yardstick, run in 2 processes at once over alone.

    On a forked 2-worker pool (warm): ``rounds`` times the case alone, then the same case
    in both workers at once, and the same for the yardstick, interleaved. The extra CPU a
    2-worker study takes per case is the machine's when the two ratios agree.

    Parameters
    ----------
    case : Case
        One of the study's cases.
    rounds : int

    Returns
    -------
    tuple of float
        (case: CPU together / alone, -; yardstick: CPU together / alone, -), medians.
    """
    import statistics

    from exudyn_turnout.studies.run import process_pool

    case_ratios, stick_ratios = [], []
    with process_pool([case], 2) as pool:
        list(pool.map(_run_case_cpu, [case, case]))  # both workers have run it once
        for _ in range(rounds):
            alone = pool.submit(_run_case_cpu, case).result()
            together = list(pool.map(_run_case_cpu, [case, case]))
            case_ratios.append(statistics.mean(together) / alone)
            alone = pool.submit(_yardstick_cpu, 0).result()
            together = list(pool.map(_yardstick_cpu, [0, 1]))
            stick_ratios.append(statistics.mean(together) / alone)
    return statistics.median(case_ratios), statistics.median(stick_ratios)


def idle_speedup(cases, table, serial: float, workers: int) -> float:
    """The speed-up of ``workers`` over 1 on idle cores, from measured CPU times.

    The cases' CPU times (``table["case_cpu_time_s"]``, by case index) are handed out in the
    pool's order (:func:`~exudyn_turnout.studies.run.hand_out_order`), each to the first
    worker free; ``serial`` s of the calling process's work come before and after.

    Parameters
    ----------
    cases : list of Case
    table : dict
        A run's results table.
    serial : float
        s.
    workers : int

    Returns
    -------
    float
        (serial + sum of the cases) / (serial + the last worker's finish).
    """
    import heapq

    from exudyn_turnout.studies.run import hand_out_order

    cpu = {int(i): float(t) for i, t in zip(table["case"], table["case_cpu_time_s"])}
    free = [0.0] * workers
    for case in hand_out_order(cases):
        heapq.heapreplace(free, free[0] + cpu[case.index])
    return (serial + sum(cpu.values())) / (serial + max(free))


def _case_cpu(rows, label: str) -> float:
    """s, the sum of the cases' own CPU time in the row ``label``."""
    return next(float(np.sum(r[2].table["case_cpu_time_s"])) for r in rows if r[0] == label)


if __name__ == "__main__":
    main()
