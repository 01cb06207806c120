"""Run a study's cases on one core, a process pool, or any executor (a Dask cluster).

Each case is stored under ``OUT/cases/<key>/case.json`` (its inputs, results or error,
wall time; the key hashes every input, files' content and the package version), with the
case's modified turnout/vehicle file and its decimated histories (``history.npz``) when
asked. A rerun skips the cases already stored (an interrupted study resumes). At the end
one table is written: ``results.csv`` (with ``results.meta.json``, the provenance) and
``results.npz`` (the same columns and the provenance as JSON text).

Workers receive the case with the files' content (nothing on the output disk is needed
there, so a cluster's workers need not share a file system) and return a record; only
the calling process writes.
"""

from __future__ import annotations

import contextlib
import csv
import json
import math
import os
import time
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import Executor, Future, as_completed
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from exudyn_turnout.studies.study import Case, Study, StudyError, load_study

__all__ = [
    "StudyResult",
    "run_case",
    "case_results",
    "run_study",
    "load_results",
    "RESULTS_FILES",
]

#: Files of the results table in the output directory.
RESULTS_FILES = ("results.csv", "results.npz", "results.meta.json")

#: Columns of the results table that are not inputs or results.
_HEAD = ("case", "key", "status")
_TAIL = ("case_wall_time_s", "warnings", "error")


@dataclass(frozen=True)
class StudyResult:
    """What :func:`run_study` did and the results table.

    Parameters
    ----------
    table : dict
        Column name -> ndarray (float, or str for text columns), one row per case in
        case order.
    computed, reused, failed : int
        Cases computed in this run, taken from an earlier run, failed (of either).
    paths : dict
        Files written: ``csv``, ``npz``, ``meta``, ``cases`` (the cases' folder).
    wall_time : float
        s, of this run.
    """

    table: dict[str, np.ndarray]
    computed: int
    reused: int
    failed: int
    paths: dict[str, str] = field(default_factory=dict)
    wall_time: float = 0.0  #: s

    @property
    def n_cases(self) -> int:
        """Number of cases of the study."""
        return int(len(self.table["case"]))


def _rms(values: np.ndarray) -> float:
    finite = values[np.isfinite(values)]
    return float(np.sqrt(np.mean(finite**2))) if finite.size else math.nan


def case_results(result: Any) -> dict[str, Any]:
    """The numbers a study keeps of one passage.

    From the summary (:func:`~exudyn_turnout.passage.results.passage_summary`): every peak
    per region, wheel and contact (``peak_Fz_crossing_right_r2_N`` ...), the largest
    force of each region with its wheel, rail and x (``max_*``), the contact losses, the
    static wheel loads and the solver's wall time. Computed here from the time series:
    the dynamic RMS per wheel of Fz minus its static load and of Fy, over the whole run
    and per region (``rms_dyn_Fz_<wheel>_N``, ``rms_dyn_Fz_<region>_<wheel>_N``,
    ``rms_Fy_<wheel>_N`` ...).

    Parameters
    ----------
    result : PassageResult

    Returns
    -------
    dict
        Name -> float, int or str.
    """
    s = result.summary
    out: dict[str, Any] = {}
    for key, value in s.items():
        keep = key.startswith(("peak_", "max_")) or key in (
            "contact_losses",
            "static_wheel_load_N",
            "static_wheel_load_left_N",
            "wall_time_s",
        )
        if not keep:
            continue
        if value is None:
            out[key] = math.nan
        elif isinstance(value, (bool, int, float, str)):
            out[key] = value
    cols = result.columns
    x = np.asarray(cols["x_m"])
    regions = {"": (-math.inf, math.inf)}
    for where in ("switch", "crossing"):
        rng = s.get(f"{where}_region_m")
        if isinstance(rng, (list, tuple)) and len(rng) == 2:
            regions[f"{where}_"] = (float(rng[0]), float(rng[1]))
    loads = {"right": s.get("static_wheel_load_N"), "left": s.get("static_wheel_load_left_N")}
    for wheel in ("right", "left"):
        fz, fy = cols.get(f"Fz_{wheel}_N"), cols.get(f"Fy_{wheel}_N")
        load = loads[wheel]
        for prefix, (a, b) in regions.items():
            sel = (x >= a) & (x <= b)
            if fz is not None and isinstance(load, (int, float)):
                dyn = np.asarray(fz)[sel] - float(load)
                out[f"rms_dyn_Fz_{prefix}{wheel}_N"] = _rms(dyn)
            if fy is not None:
                out[f"rms_Fy_{prefix}{wheel}_N"] = _rms(np.asarray(fy)[sel])
    return out


def _decimate(columns: Mapping[str, np.ndarray], step: float) -> dict[str, np.ndarray]:
    """Every column at the stored samples nearest to multiples of ``step`` (s) from the start."""
    t = np.asarray(columns["t_s"], dtype=float)
    if t.size < 2:
        return {k: np.asarray(v, dtype=float) for k, v in columns.items()}
    wanted = np.arange(t[0], t[-1] + 0.5 * step, step)
    right = np.clip(np.searchsorted(t, wanted), 1, t.size - 1)
    nearer_left = (wanted - t[right - 1]) <= (t[right] - wanted)
    index = np.unique(np.where(nearer_left, right - 1, right))
    return {k: np.asarray(v, dtype=float)[index] for k, v in columns.items()}


def _settings_with_irregularity(case: Case):
    from dataclasses import replace

    from exudyn_turnout.passage.results import PassageSettings

    settings = PassageSettings(**case.settings)
    if case.irregularity is not None:
        settings = replace(settings, irregularity=case.irregularity)
    return settings


def run_case(case: Case) -> dict[str, Any]:
    """Run one case (in whatever process calls it) and return its record.

    The case's turnout and vehicle files are written to a temporary directory and loaded
    with the package's loaders; a failure of any kind is recorded, not raised.

    Parameters
    ----------
    case : Case

    Returns
    -------
    dict
        ``key``, ``index``, ``inputs``, ``status`` ("ok" or "failed"), ``error`` (one
        line, "" if ok), ``results`` (:func:`case_results`), ``warnings`` (list of str),
        ``wall_time_s``, and ``history`` (decimated columns) if the case asks for it.
    """
    import tempfile
    import warnings

    start = time.perf_counter()
    record: dict[str, Any] = {
        "key": case.key,
        "index": case.index,
        "inputs": dict(case.inputs),
        "status": "failed",
        "error": "",
        "results": {},
        "warnings": [],
    }
    try:
        from exudyn_turnout.inputs.turnout import load_turnout
        from exudyn_turnout.inputs.vehicle import load_vehicle
        from exudyn_turnout.passage.run import simulate_passage

        with tempfile.TemporaryDirectory(prefix="exudyn-turnout-case-") as tmp:
            turnout_path = Path(tmp) / case.turnout_name
            vehicle_path = Path(tmp) / f"vehicle-{case.vehicle_name}"
            turnout_path.write_text(case.turnout_text, encoding="utf-8")
            vehicle_path.write_text(case.vehicle_text, encoding="utf-8")
            turnout = load_turnout(turnout_path)
            vehicle = load_vehicle(vehicle_path)
            if case.parameters_text:
                from exudyn_turnout.corunning.fitted import load_fitted

                parameters_path = Path(tmp) / case.parameters_name
                parameters_path.write_text(case.parameters_text, encoding="utf-8")
                turnout = load_fitted(turnout, parameters_path)
        settings = _settings_with_irregularity(case)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            result = simulate_passage(turnout, settings, vehicle, track=case.track)
        record["warnings"] = sorted({str(w.message) for w in caught})
        record["results"] = case_results(result)
        if case.history_step is not None:
            record["history"] = _decimate(result.columns, case.history_step)
        record["status"] = "ok"
    except Exception as err:  # noqa: BLE001  (a failed case is recorded, the others go on)
        text = " ".join(str(err).split()) or type(err).__name__
        record["error"] = f"{type(err).__name__}: {text}"
    record["wall_time_s"] = time.perf_counter() - start
    return record


def _case_dir(out: Path, key: str) -> Path:
    return out / "cases" / key


def _write_record(out: Path, case: Case, record: dict[str, Any]) -> None:
    """Write a case's files; ``case.json`` last (its presence marks the case done)."""
    from exudyn_turnout.provenance import write_json

    folder = _case_dir(out, case.key)
    folder.mkdir(parents=True, exist_ok=True)
    if case.turnout_modified:
        (folder / case.turnout_name).write_text(case.turnout_text, encoding="utf-8")
    if case.vehicle_modified:
        (folder / f"vehicle-{case.vehicle_name}").write_text(case.vehicle_text, encoding="utf-8")
    history = record.pop("history", None)
    if history is not None:
        np.savez(folder / "history.npz", **history)
    stored = dict(record)
    stored["irregularity"] = case.irregularity_spec
    stored["settings"] = dict(case.settings)
    stored["track"] = case.track
    write_json(folder / "case.json", stored)


def _stored(out: Path, case: Case) -> dict[str, Any] | None:
    path = _case_dir(out, case.key) / "case.json"
    if not path.is_file():
        return None
    try:
        record = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    record["index"], record["inputs"] = case.index, dict(case.inputs)
    return record


def _column(values: list[Any]) -> np.ndarray:
    """A float column if every value is a number (None: NaN), else a str column."""
    numeric = all(
        v is None or (isinstance(v, (int, float)) and not isinstance(v, bool)) for v in values
    )
    if numeric:
        return np.array([math.nan if v is None else float(v) for v in values], dtype=float)
    return np.array(["" if v is None else str(v) for v in values], dtype=str)


def _table(records: Sequence[dict[str, Any]], study: Study) -> dict[str, np.ndarray]:
    inputs = list(study.varied)
    results: list[str] = []
    for r in records:
        for k in r.get("results", {}):
            if k not in results:
                results.append(k)
    results = sorted(results)
    table = {
        "case": _column([r["index"] for r in records]),
        "key": _column([r["key"] for r in records]),
        "status": _column([r["status"] for r in records]),
    }
    for name in inputs:
        table[name] = _column([r["inputs"].get(name) for r in records])
    for name in results:
        table[name] = _column([r.get("results", {}).get(name) for r in records])
    table["case_wall_time_s"] = _column([r.get("wall_time_s") for r in records])
    table["warnings"] = _column(["; ".join(r.get("warnings", [])) for r in records])
    table["error"] = _column([r.get("error", "") for r in records])
    return table


def _write_table(out: Path, table: Mapping[str, np.ndarray], record: dict) -> dict[str, str]:
    from exudyn_turnout.provenance import round_floats, write_json

    names = list(table)
    tmp = out / ".results.partial.csv"
    with open(tmp, "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(names)
        for i in range(len(table["case"])):
            row = []
            for n in names:
                v = table[n][i]
                if isinstance(v, (float, np.floating)):
                    row.append(f"{v:.9g}" if math.isfinite(v) else "")
                else:
                    row.append(str(v))
            w.writerow(row)
    os.replace(tmp, out / "results.csv")
    arrays = {n: np.asarray(v) for n, v in table.items()}
    arrays["provenance"] = np.array(json.dumps(round_floats(record)))
    tmp_npz = out / ".results.partial.npz"
    np.savez(tmp_npz, **arrays)  # type: ignore[arg-type]  # numpy's stub: **kwds
    os.replace(tmp_npz, out / "results.npz")
    write_json(out / "results.meta.json", record)
    return {
        "csv": str(out / "results.csv"),
        "npz": str(out / "results.npz"),
        "meta": str(out / "results.meta.json"),
        "cases": str(out / "cases"),
    }


def load_results(out_dir: str | Path) -> dict[str, np.ndarray]:
    """The results table of a study's output directory (from ``results.npz``).

    Parameters
    ----------
    out_dir : str or Path

    Returns
    -------
    dict
        Column -> ndarray, as :attr:`StudyResult.table`; ``provenance`` is left out.
    """
    with np.load(Path(out_dir) / "results.npz", allow_pickle=False) as data:
        return {k: data[k] for k in data.files if k != "provenance"}


def _study_provenance(study: Study, n_cases: int, executor_name: str) -> dict[str, Any]:
    from exudyn_turnout.provenance import provenance

    settings = {
        "study": study.name,
        "cases": n_cases,
        "base": study.base,
        "factors": study.factors,
        "paired": study.paired,
        "latin_hypercube": {
            "samples": study.lhs_samples,
            "seed": study.lhs_seed,
            "ranges": {k: list(v) for k, v in study.lhs_ranges.items()},
        },
        "seeds": list(study.seeds),
        "repetition_irregularity": study.repetition_irregularity,
        "history_step_s": study.history_step,
        "executor": executor_name,
    }
    files = {"study": study.source} if study.source else {}
    for kind in ("turnout", "vehicle"):
        if isinstance(study.base.get(kind), str):
            files[kind] = str(study.directory / study.base[kind])
    return provenance(settings, files=files)


#: Environment of the pool's worker processes: one BLAS/OpenMP thread each (as a Dask
#: nanny's workers get; the pool already has one process per core, more threads only compete).
_WORKER_ENVIRONMENT = (
    ("OMP_NUM_THREADS", "1"),
    ("OPENBLAS_NUM_THREADS", "1"),
    ("MKL_NUM_THREADS", "1"),
)


@contextlib.contextmanager
def _one_thread_per_worker(active: bool):
    """Set :data:`_WORKER_ENVIRONMENT` (where not set) while the pool spawns its workers."""
    added = []
    if active:
        for name, value in _WORKER_ENVIRONMENT:
            if name not in os.environ:
                os.environ[name] = value
                added.append(name)
    try:
        yield
    finally:
        for name in added:
            os.environ.pop(name, None)


def run_study(
    study: Study | str | Path,
    executor: Executor | None = None,
    workers: int | None = None,
    *,
    out: str | Path,
    progress: Callable[[int, int, float | None], None] | None = None,
    retry_failed: bool = False,
) -> StudyResult:
    """Run every case of a study that is not stored yet; write the results table.

    Parameters
    ----------
    study : Study or str or Path
        A study, or its file.
    executor : concurrent.futures.Executor, optional
        Where the cases run, e.g. a Dask distributed client's ``get_executor()``; it is
        not shut down here. Default: a process pool (spawn start method) of ``workers``
        processes.
    workers : int, optional
        Processes of the default pool (default: all cores); 1 runs the cases one after
        the other in this process.
    out : str or Path
        Output directory (created): ``cases/<key>/``, ``results.csv``, ``results.npz``,
        ``results.meta.json``.
    progress : callable(done, total, eta_s), optional
        Called after each case (done counts the stored cases too; eta_s None until a
        case was computed).
    retry_failed : bool
        Run stored failed cases again (default: keep their record).

    Returns
    -------
    StudyResult

    Raises
    ------
    StudyError
        A bad study file, factor or value (before any case runs).
    """
    from exudyn_turnout.provenance import round_floats

    start = time.perf_counter()
    if not isinstance(study, Study):
        study = load_study(study)
    if workers is not None and (int(workers) != workers or workers < 1):
        raise StudyError(f"workers must be an integer >= 1, got {workers!r}")
    cases = study.cases()
    out_dir = Path(out)
    (out_dir / "cases").mkdir(parents=True, exist_ok=True)
    records: dict[int, dict[str, Any]] = {}
    todo: list[Case] = []
    for case in cases:
        stored = _stored(out_dir, case)
        if stored is not None and (stored.get("status") == "ok" or not retry_failed):
            records[case.index] = stored
        else:
            todo.append(case)
    reused = len(records)
    total = len(cases)
    computed_start = time.perf_counter()

    def finished(case: Case, record: dict[str, Any], persist: bool = True) -> None:
        if persist:  # not a lost worker: that case runs again on a rerun
            _write_record(out_dir, case, record)
        # as stored (9 digits): a resumed study's table equals an uninterrupted one's
        record["results"] = round_floats(record.get("results", {}))
        records[case.index] = record
        if progress is not None:
            n_done = len(records) - reused
            elapsed = time.perf_counter() - computed_start
            eta = elapsed / n_done * (len(todo) - n_done) if n_done else None
            progress(len(records), total, eta)

    if progress is not None:
        progress(len(records), total, None)
    pool_name = "serial"
    if todo and executor is None and (workers == 1 or len(todo) == 1):
        for case in todo:
            finished(case, run_case(case))
    elif todo:
        own = executor is None
        if own:
            import multiprocessing
            from concurrent.futures import ProcessPoolExecutor

            n = min(int(workers or os.cpu_count() or 1), len(todo))
            executor = ProcessPoolExecutor(n, mp_context=multiprocessing.get_context("spawn"))
            pool_name = f"process pool, {n} workers"
        else:
            pool_name = type(executor).__name__
        assert executor is not None
        futures: dict[Future, Case] = {}
        try:
            with _one_thread_per_worker(own):
                futures = {executor.submit(run_case, case): case for case in todo}
            for future in as_completed(futures):
                case = futures[future]
                try:
                    record = future.result()
                except Exception as err:  # noqa: BLE001  (a worker that died, a lost future)
                    record = {
                        "key": case.key,
                        "index": case.index,
                        "inputs": dict(case.inputs),
                        "status": "failed",
                        "error": f"{type(err).__name__}: {' '.join(str(err).split())}",
                        "results": {},
                        "warnings": [],
                        "wall_time_s": math.nan,
                    }
                    finished(case, record, persist=False)
                    continue
                finished(case, record)
        finally:
            for future in futures:
                future.cancel()
            if own:
                executor.shutdown(wait=True, cancel_futures=True)
    ordered = [records[i] for i in sorted(records)]
    table = _table(ordered, study)
    paths = _write_table(out_dir, table, _study_provenance(study, total, pool_name))
    failed = int(np.count_nonzero(table["status"] != "ok"))
    return StudyResult(
        table=table,
        computed=len(todo) if len(records) == total else len(records) - reused,
        reused=reused,
        failed=failed,
        paths=paths,
        wall_time=time.perf_counter() - start,
    )
