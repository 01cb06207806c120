"""Run a study's cases on one core, a process pool, or any executor (a Dask cluster).

Each case is stored under ``OUT/cases/<key>/case.json`` (its inputs, results or error,
wall time, and :func:`code_digest` of the code that computed it; the key hashes every
input, files' content and the package version), with the
case's modified turnout/vehicle file, its decimated histories (``history.npz``) and its
whole time series (``timeseries.npz``, every column of the passage at its output step) when
asked; both NPZ files are compressed. A rerun skips the cases already stored (an
interrupted study resumes), unless another code of the package computed them (a changed
source file: they are computed again, with one warning). At the end one table is written:
``results.csv`` (with ``results.meta.json``, the provenance) and ``results.npz`` (the same
columns and the provenance as JSON text).

Workers receive the case with the files' content (nothing on the output disk is needed
there, so a cluster's workers need not share a file system) and return a record, its
histories already compressed (the bytes of their NPZ files); only the calling process
writes. Each record carries the case's CPU time (``case_cpu_time_s`` in the table).

Workers are reused across cases. A worker keeps the files it loaded (by content), and the
route's contact tables, kept in memory for the last few routes and keyed by what they are
built from (not the track's stiffness, damping or masses), are built or read once per
worker, not once per case (they took ~2.5 s of a ~3 s case before); the default pool
warms each worker once at its start (a 5 cm passage of each kind of case: imports,
contact tables, compiled kernels; a process that already ran a kind is not warmed for it
again). Cases run or are handed out by contact tables (:func:`hand_out_order`: the cases
of the same tables together, so that they are loaded once per process, not once per
case), the longest first within a group and the groups in the order of their longest case
(estimated from the x range, speed, time step, wheelsets and track), so that no worker is
left alone with a long case at the end.
"""

from __future__ import annotations

import contextlib
import csv
import dataclasses
import functools
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

from exudyn_turnout.studies.study import (
    Case,
    Study,
    StudyError,
    checked_turnout,
    load_study,
    load_study_vehicle,
)

__all__ = [
    "StudyResult",
    "run_case",
    "case_results",
    "run_study",
    "load_results",
    "estimated_cost",
    "hand_out_order",
    "warm_up",
    "process_pool",
    "default_start_method",
    "one_blas_thread",
    "code_digest",
    "RESULTS_FILES",
]

#: Files of the results table in the output directory.
RESULTS_FILES = ("results.csv", "results.npz", "results.meta.json")

#: Folders of the package whose code does not compute a case (left out of :func:`code_digest`).
_NOT_COMPUTING = ("cli", "report", "plotting")


@functools.lru_cache(maxsize=1)
def code_digest() -> str:
    """SHA-256 of the package's code that computes a case, stored with each case.

    Every ``*.py`` file of the package outside ``cli/``, ``report/`` and ``plotting/``
    (their paths and bytes, with lengths first). A stored case whose digest differs was
    computed by other code: :func:`run_study` computes it again. Read once per process
    (~200 files, ~10 ms).

    Returns
    -------
    str
        64 hex digits.
    """
    import hashlib

    root = Path(__file__).resolve().parents[1]
    digest = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        name = path.relative_to(root).as_posix()
        if name.split("/", 1)[0] in _NOT_COMPUTING:
            continue
        data = path.read_bytes()
        digest.update(f"{len(name)}:{len(data)}:".encode() + name.encode() + data)
    return digest.hexdigest()


#: Columns of the results table that are not inputs or results.
_HEAD = ("case", "key", "status")
_TAIL = ("case_wall_time_s", "case_cpu_time_s", "warnings", "error")


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

    From the summary (:func:`~exudyn_turnout.passage.summary.passage_summary`): every peak
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

    from exudyn_turnout.passage.settings import PassageSettings

    settings = PassageSettings(**case.settings)
    if case.irregularity is not None:
        settings = replace(settings, irregularity=case.irregularity)
    return settings


@functools.lru_cache(maxsize=8)
def _case_files(
    turnout_name: str,
    turnout_text: str,
    vehicle_name: str,
    vehicle_text: str,
    parameters_name: str,
    parameters_text: str,
    turnout_dir: str = "",
    vehicle_dir: str = "",
) -> tuple[Any, Any]:
    """The case's turnout and vehicle, loaded by the package's loaders; kept per process.

    The same content gives the same objects, so everything keyed by them (the route's
    contact tables in memory) is reused by the next case of the same files. The loaded
    files' ``source`` is their place in ``turnout_dir`` / ``vehicle_dir`` (the study's
    folders), where the design files they name (rail profiles, slices, wheel profile) are.
    """
    import tempfile

    from exudyn_turnout.inputs.turnout import load_turnout
    from exudyn_turnout.inputs.vehicle import Vehicle

    with tempfile.TemporaryDirectory(prefix="exudyn-turnout-case-") as tmp:
        turnout_path = Path(tmp) / turnout_name
        vehicle_path = Path(tmp) / f"vehicle-{vehicle_name}"
        turnout_path.write_text(turnout_text, encoding="utf-8")
        vehicle_path.write_text(vehicle_text, encoding="utf-8")
        # as the study's check loaded it here (the same name and text), else loaded now
        turnout = checked_turnout(turnout_name, turnout_text)
        if turnout is None:
            turnout = load_turnout(turnout_path)
        vehicle = load_study_vehicle(vehicle_path)
        if parameters_text:
            from exudyn_turnout.corunning.fitted import load_fitted

            parameters_path = Path(tmp) / parameters_name
            parameters_path.write_text(parameters_text, encoding="utf-8")
            turnout = load_fitted(turnout, parameters_path)
    if turnout_dir:
        turnout = dataclasses.replace(turnout, source=str(Path(turnout_dir) / turnout_name))
    if vehicle_dir and isinstance(vehicle, Vehicle):
        vehicle = dataclasses.replace(vehicle, source=str(Path(vehicle_dir) / vehicle_name))
    return turnout, vehicle


def _files_of(case: Case) -> tuple[Any, Any]:
    return _case_files(
        case.turnout_name,
        case.turnout_text,
        case.vehicle_name,
        case.vehicle_text,
        case.parameters_name,
        case.parameters_text,
        case.turnout_dir,
        case.vehicle_dir,
    )


def run_case(case: Case) -> dict[str, Any]:
    """Run one case (in whatever process calls it) and return its record.

    The case's turnout and vehicle files are loaded with the package's loaders (once per
    process for the same content); a failure of any kind is recorded, not raised.

    Parameters
    ----------
    case : Case

    Returns
    -------
    dict
        ``key``, ``index``, ``inputs``, ``status`` ("ok" or "failed"), ``error`` (one
        line, "" if ok), ``results`` (:func:`case_results`), ``warnings`` (list of str),
        ``wall_time_s``, ``cpu_time_s`` (s, of the process that ran it), ``history``
        (decimated columns) if the case asks for it, and ``timeseries`` (every column) if
        ``case.keep_timeseries``.
    """
    import warnings

    start, cpu_start = time.perf_counter(), time.process_time()
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
        from exudyn_turnout.passage.run import simulate_passage

        turnout, vehicle = _files_of(case)
        settings = _settings_with_irregularity(case)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            result = simulate_passage(turnout, settings, vehicle, track=case.track)
        record["warnings"] = sorted({str(w.message) for w in caught})
        record["results"] = case_results(result)
        if case.history_step is not None:
            record["history"] = _decimate(result.columns, case.history_step)
        if case.keep_timeseries:
            record["timeseries"] = {k: np.asarray(v) for k, v in result.columns.items()}
        record["status"] = "ok"
        _warm_state(_kind(case))["warm"] = True  # this process has run this kind now
    except Exception as err:  # noqa: BLE001  (a failed case is recorded, the others go on)
        text = " ".join(str(err).split()) or type(err).__name__
        record["error"] = f"{type(err).__name__}: {text}"
    record["wall_time_s"] = time.perf_counter() - start
    record["cpu_time_s"] = time.process_time() - cpu_start
    return record


#: Settings that change what a worker's warm-up must load or compile (the x range, speed,
#: steps and irregularity do not).
_WARM_KEYS = ("route", "layers", "contact", "source", "track_mechanism")


@functools.lru_cache(maxsize=64)
def _tables_of(turnout_text: str) -> str:
    """SHA-256 of what a turnout file's contact tables are built from.

    Its :data:`~exudyn_turnout.passage.contact.route_cache.CONTACT_SECTIONS` (the sections the
    route's contact tables in memory are keyed by): turnout files that differ in the track's
    stiffness, damping or masses only share their tables. A file that is not TOML: its whole
    text (the case reports the error).
    """
    import tomllib

    from exudyn_turnout.passage.contact.route_cache import CONTACT_SECTIONS

    try:
        data = tomllib.loads(turnout_text)
    except tomllib.TOMLDecodeError:
        return _sha_text(turnout_text)
    sections = {name: data.get(name) for name in CONTACT_SECTIONS}
    return _sha_text(json.dumps(sections, sort_keys=True, default=str))


def _kind(case: Case) -> tuple:
    """What a warm-up of ``case`` loads: its turnout's contact tables (:func:`_tables_of`),
    its vehicle and parameter files, track and :data:`_WARM_KEYS` settings."""
    return (
        _tables_of(case.turnout_text),
        _sha_text(case.vehicle_text),
        _sha_text(case.parameters_text),
        case.track,
        tuple(str(case.settings.get(k)) for k in _WARM_KEYS),
    )


@functools.lru_cache(maxsize=256)
def _warm_state(kind: tuple) -> dict[str, bool]:
    """This process's note on a kind of case: ``warm`` once a passage of that kind ran here.

    Kept per process (a forked worker inherits its parent's notes), so that a process that
    already ran a kind is not warmed for it again.
    """
    return {"warm": False}


def _warm_cases(cases: Sequence[Case], limit: int = 3, here: bool = True) -> list[Case]:
    """One case of each kind (at most ``limit`` kinds); with ``here``, of the kinds not warm
    in this process (else for a new process: a spawned worker)."""
    kinds: dict[tuple, Case] = {}
    for case in cases:
        kind = _kind(case)
        cold = not (here and _warm_state(kind)["warm"])
        if kind not in kinds and len(kinds) < limit and cold:
            kinds[kind] = case
    return list(kinds.values())


def _sha_text(text: str) -> str:
    import hashlib

    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _warm_worker(cases: Sequence[Case]) -> None:
    """Pool initializer: run a 5 cm passage of each case given (results dropped)."""
    for case in cases:
        if _warm_state(_kind(case))["warm"]:
            continue
        try:
            turnout, _ = _files_of(case)
            x0 = case.settings.get("x_start")
            x0 = float(turnout.x_min if x0 is None else x0)
            settings = {**case.settings, "x_start": x0, "x_end": x0 + 0.05, "output_step": None}
            short = dataclasses.replace(
                case,
                settings=settings,
                irregularity=None,
                irregularity_spec="",
                history_step=None,
                keep_timeseries=False,
            )
            run_case(short)
        except Exception:  # noqa: BLE001, S112  (a warm-up only: the case itself reports)
            continue


def warm_up(cases: Sequence[Case], kinds: int = 3) -> int:
    """Warm this process for ``cases``: a 5 cm passage of each kind of case not run here yet.

    A kind is the case's contact tables (the turnout file's sections they are built from,
    :func:`_tables_of`: not its track stiffness, damping or masses), vehicle and parameter
    files, track, route, contact, parameter source and spring mechanism (what the x range,
    speed, steps and irregularity do not change): the first
    ``kinds`` kinds that this process has not run yet (as a case or a warm-up) load the
    imports, the route's contact tables and the compiled kernels once.
    :func:`process_pool` calls it (in this process before it forks, or in each spawned
    worker); call it before making another executor's workers from this process.

    Parameters
    ----------
    cases : sequence of Case
    kinds : int
        At most this many kinds are warmed.

    Returns
    -------
    int
        Kinds warmed now (0 when this process has run every kind chosen already).
    """
    chosen = _warm_cases(cases, kinds)
    _warm_worker(chosen)
    return len(chosen)


def estimated_cost(case: Case) -> float:
    """A case's relative cost: simulated steps, times the wheelsets, times 50 on the FE track.

    Used to hand the longest cases out first. Only the order matters.

    Parameters
    ----------
    case : Case

    Returns
    -------
    float
        -, proportional to the expected run time.
    """
    s = case.settings
    x_a, x_b = s.get("x_start"), s.get("x_end")
    wheelsets = 1
    try:
        turnout, vehicle = _files_of(case)
        x_a = turnout.x_min if x_a is None else x_a
        x_b = turnout.x_max if x_b is None else x_b
        wheelsets = int(getattr(vehicle, "n_wheelsets", 1))
    except Exception:  # noqa: BLE001  (a bad file fails in the case, not here)
        x_a = 0.0 if x_a is None else x_a
        x_b = 100.0 if x_b is None else x_b
    speed = float(s.get("speed_kmh") or 100.0) / 3.6
    step = float(s.get("time_step") or 1e-4)
    steps = max(float(x_b) - float(x_a), 0.0) / max(speed, 1e-3) / max(step, 1e-7)
    return steps * wheelsets * (50.0 if case.track == "fe" else 1.0)


def hand_out_order(cases: Sequence[Case]) -> list[Case]:
    """The order :func:`run_study` runs or hands out cases: by contact tables, longest first.

    Cases that use the same contact tables (:func:`_tables_of` of the turnout file, the
    vehicle file, the route) come one after the other, so that a process loads a route's
    tables once, not once per case: a process keeps the last few routes' tables, and a study
    that cycled through more of them than that reloaded them for every case (10 m wheelset
    cases: 0.27 -> 0.94 s CPU a case). Files that differ in the track only (pad stiffness,
    ballast, masses) share their tables: their cases form one group. Within a group the
    longest case (:func:`estimated_cost`) comes first, and the groups in the order of their
    longest case, so that the last cases handed out are short (longest processing time
    first: a worker free takes the longest case left).

    Parameters
    ----------
    cases : sequence of Case

    Returns
    -------
    list of Case
        The same cases, reordered.
    """
    cost = {id(case): estimated_cost(case) for case in cases}
    group = {
        id(case): "/".join(
            (
                _tables_of(case.turnout_text),
                _sha_text(case.vehicle_text),
                str(case.settings.get("route")),
            )
        )
        for case in cases
    }
    longest: dict[str, float] = {}
    for case in cases:
        longest[group[id(case)]] = max(longest.get(group[id(case)], 0.0), cost[id(case)])
    rank = {g: i for i, g in enumerate(sorted(longest, key=lambda g: -longest[g]))}
    return sorted(cases, key=lambda c: (rank[group[id(c)]], -cost[id(c)]))


def _case_dir(out: Path, key: str) -> Path:
    return out / "cases" / key


def _npz_bytes(columns: Mapping[str, np.ndarray]) -> bytes:
    """The content of a compressed NPZ file of ``columns``."""
    import io

    buffer = io.BytesIO()
    np.savez_compressed(buffer, **columns)  # type: ignore[arg-type]  # numpy's stub: **kwds
    return buffer.getvalue()


def _study_case(case: Case) -> dict[str, Any]:
    """What :func:`run_study` runs for a case: :func:`run_case`, its histories packed.

    The decimated histories and the whole time series are compressed here, into the bytes
    of their NPZ files (``history_npz``, ``timeseries_npz``): in the worker, so that the
    workers compress in parallel and send the calling process (which only writes the
    bytes) a fraction of the columns.
    """
    record = run_case(case)
    for name in ("history", "timeseries"):
        columns = record.pop(name, None)
        if columns is not None:
            record[f"{name}_npz"] = _npz_bytes(columns)
    return record


def _write_record(out: Path, case: Case, record: dict[str, Any]) -> None:
    """Write a case's files; ``case.json`` last (its presence marks the case done)."""
    from exudyn_turnout.provenance import write_json

    folder = _case_dir(out, case.key)
    folder.mkdir(parents=True, exist_ok=True)
    if case.turnout_modified:
        (folder / case.turnout_name).write_text(case.turnout_text, encoding="utf-8")
    if case.vehicle_modified:
        (folder / f"vehicle-{case.vehicle_name}").write_text(case.vehicle_text, encoding="utf-8")
    for name in ("history", "timeseries"):
        packed = record.pop(f"{name}_npz", None)
        columns = record.pop(name, None)
        if packed is None and columns is not None:  # a record of run_case itself
            packed = _npz_bytes(columns)
        if packed is not None:
            tmp = folder / f".{name}.partial.npz"
            tmp.write_bytes(packed)
            os.replace(tmp, folder / f"{name}.npz")
    stored = dict(record)
    stored["irregularity"] = case.irregularity_spec
    stored["settings"] = dict(case.settings)
    stored["track"] = case.track
    stored["code"] = code_digest()
    write_json(folder / "case.json", stored)


def _stored(out: Path, case: Case, stale: list[int] | None = None) -> dict[str, Any] | None:
    path = _case_dir(out, case.key) / "case.json"
    if not path.is_file():
        return None
    try:
        record = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if record.get("code") != code_digest():  # computed by other code: run it again
        if stale is not None:
            stale.append(case.index)
        return None
    series = _case_dir(out, case.key) / "timeseries.npz"
    if case.keep_timeseries and record.get("status") == "ok" and not series.is_file():
        return None  # stored without its time series, now asked for: run it again
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
    table["case_cpu_time_s"] = _column([r.get("cpu_time_s") for r in records])
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


def _study_provenance(
    study: Study, n_cases: int, executor_name: str, keep_timeseries: bool
) -> dict[str, Any]:
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
        "keep_timeseries": keep_timeseries,
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


#: The thread-count setters a BLAS or OpenMP library exports, by build: NumPy's and SciPy's
#: OpenBLAS wheels (with and without the 64-bit integer suffix), a plain OpenBLAS, MKL's
#: runtime, an OpenMP runtime. The first one a library has is called.
_THREAD_SETTERS = (
    "scipy_openblas_set_num_threads64_",
    "scipy_openblas_set_num_threads",
    "openblas_set_num_threads64_",
    "openblas_set_num_threads",
    "MKL_Set_Num_Threads",
    "omp_set_num_threads",
)
#: Parts of the file names of the libraries asked (lower case).
_THREADED_LIBRARIES = ("openblas", "mkl_rt", "libgomp", "libomp", "libiomp")


def one_blas_thread() -> int:
    """Set every BLAS and OpenMP library loaded in this process to one thread.

    A forked pool worker keeps its parent's BLAS thread count (the thread pool is rebuilt
    after the fork with as many threads as before), and the environment variables
    (``OPENBLAS_NUM_THREADS`` ...) are read only when a library loads, before the fork.
    So the forked worker asks each loaded library itself, through the setter its build
    exports (:data:`_THREAD_SETTERS`): the libraries are found in the process's memory
    map (``/proc/self/maps``, Linux: where the pool forks), as ``threadpoolctl`` does,
    which is not a dependency. One thread per worker: the pool already has one process per
    core, more threads only compete (as a Dask nanny's workers get).

    Returns
    -------
    int
        Libraries set (0 where none is found, e.g. without ``/proc``).
    """
    import ctypes

    try:
        with open("/proc/self/maps", encoding="utf-8") as maps:
            paths = sorted({line.split()[-1] for line in maps if "/" in line})
    except OSError:
        return 0
    count = 0
    for path in paths:
        if not any(part in os.path.basename(path).lower() for part in _THREADED_LIBRARIES):
            continue
        try:
            library = ctypes.CDLL(path)
        except OSError:
            continue
        for name in _THREAD_SETTERS:
            setter = getattr(library, name, None)
            if setter is not None:
                setter(1)
                count += 1
                break
    return count


def default_start_method() -> str:
    """How :func:`process_pool` starts its workers here: ``fork`` on Linux, else ``spawn``.

    Returns
    -------
    str
        ``"fork"`` where the platform forks safely (Linux); ``"spawn"`` elsewhere (macOS,
        Windows: fork is unsafe or missing there).
    """
    import multiprocessing
    import sys

    forks = sys.platform.startswith("linux") and "fork" in multiprocessing.get_all_start_methods()
    return "fork" if forks else "spawn"


def process_pool(cases: Sequence[Case], workers: int, start_method: str | None = None):
    """The default executor of :func:`run_study`: worker processes warmed for ``cases``.

    The workers start warm: a 5 cm passage of each kind of case (at most three kinds:
    contact tables, vehicle, route, contact, track; :func:`warm_up`) loads imports, contact
    tables and compiled kernels once.
    ``fork`` (default on Linux) warms this process and forks the workers from it, so the
    warm-up is paid once, not once per worker, and the workers skip the imports (~3 s a
    worker; each sets its BLAS libraries to one thread, :func:`one_blas_thread`); ``spawn``
    starts fresh interpreters (one BLAS/OpenMP thread each by the environment, unless set)
    that each warm up in an initializer.

    Parameters
    ----------
    cases : sequence of Case
        The cases the pool will run (their kinds are warmed).
    workers : int
        Processes.
    start_method : {"fork", "spawn"}, optional
        Default: :func:`default_start_method`.

    Returns
    -------
    concurrent.futures.ProcessPoolExecutor
        To be shut down by the caller (or used as a context manager).
    """
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    method = start_method or default_start_method()
    if method not in ("fork", "spawn"):
        raise StudyError(f"start_method must be 'fork' or 'spawn', got {method!r}")
    if method == "fork":
        warm_up(cases)  # here: the forked workers inherit it
        return ProcessPoolExecutor(
            int(workers),
            mp_context=multiprocessing.get_context("fork"),
            initializer=one_blas_thread,
        )
    with _one_thread_per_worker(True):
        pool = ProcessPoolExecutor(
            int(workers),
            mp_context=multiprocessing.get_context("spawn"),
            initializer=_warm_worker,
            initargs=(_warm_cases(cases, here=False),),
        )
        # a worker process starts (and reads the environment) at a submit that finds no idle
        # worker: start all of them now, while the environment is set
        for _ in range(int(workers)):
            pool.submit(int, 0)
    return pool


def run_study(
    study: Study | str | Path,
    executor: Executor | None = None,
    workers: int | None = None,
    *,
    out: str | Path,
    progress: Callable[[int, int, float | None], None] | None = None,
    retry_failed: bool = False,
    keep_timeseries: bool | None = None,
    start_method: str | None = None,
) -> StudyResult:
    """Run every case of a study that is not stored yet; write the results table.

    Parameters
    ----------
    study : Study or str or Path
        A study, or its file.
    executor : concurrent.futures.Executor, optional
        Where the cases run, e.g. a Dask distributed client's ``get_executor()``; it is
        not shut down here. Default: :func:`process_pool` of ``workers`` processes (warmed,
        forked on Linux, spawned elsewhere).
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
    keep_timeseries : bool, optional
        Store every case's whole time series, ``cases/<key>/timeseries.npz`` (compressed);
        default: the study file's ``[output] keep_timeseries``. A stored case without them
        is run again when they are asked for.
    start_method : {"fork", "spawn"}, optional
        How the default pool starts its workers (:func:`process_pool`).

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
    keep = study.keep_timeseries if keep_timeseries is None else bool(keep_timeseries)
    if keep != study.keep_timeseries:
        cases = [dataclasses.replace(c, keep_timeseries=keep) for c in cases]
    out_dir = Path(out)
    (out_dir / "cases").mkdir(parents=True, exist_ok=True)
    records: dict[int, dict[str, Any]] = {}
    todo: list[Case] = []
    stale: list[int] = []
    for case in cases:
        stored = _stored(out_dir, case, stale)
        if stored is not None and (stored.get("status") == "ok" or not retry_failed):
            records[case.index] = stored
        else:
            todo.append(case)
    if stale:
        import warnings

        warnings.warn(
            f"{len(stale)} case(s) stored in {out_dir} were computed by other code of the "
            "package (a source file changed since): computed again",
            UserWarning,
            2,
        )
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
        for case in hand_out_order(todo):
            finished(case, _study_case(case))
    elif todo:
        # ordered before the pool forks: the files loaded for the order (each case's turnout
        # and vehicle) are then inherited by the workers, not loaded again in each of them
        order = hand_out_order(todo)
        own = executor is None
        if own:
            n = min(int(workers or os.cpu_count() or 1), len(todo))
            method = start_method or default_start_method()
            executor = process_pool(todo, n, method)
            pool_name = f"process pool ({method}), {n} workers"
        else:
            pool_name = type(executor).__name__
        assert executor is not None
        futures: dict[Future, Case] = {}
        try:
            futures = {executor.submit(_study_case, case): case for case in order}
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
                        "cpu_time_s": math.nan,
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
    paths = _write_table(out_dir, table, _study_provenance(study, total, pool_name, keep))
    failed = int(np.count_nonzero(table["status"] != "ok"))
    return StudyResult(
        table=table,
        computed=len(todo) if len(records) == total else len(records) - reused,
        reused=reused,
        failed=failed,
        paths=paths,
        wall_time=time.perf_counter() - start,
    )
