"""Studies (exudyn_turnout.studies): study files, cases, keys, executors, resume, failures.

The tiny study: 4 cases of 3 m of track around the crossing (45-48 m), the height-table
contact and a 0.15 ms step (each case ~0.2 s). Reference values: the same study computed
serially in this process (the pool and the Dask cluster must give the very same numbers:
the same code on the same inputs), and the study's own definition (number of cases, Latin
hypercube strata, factor values).
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

from exudyn_turnout.cli.main import main
from exudyn_turnout.studies import StudyError, load_results, load_study, run_study
from exudyn_turnout.studies.study import study_from_dict
from exudyn_turnout.studies.toml_writer import dumps

TINY = """
[study]
name = "tiny"
history_step = 0.002

[base]
contact = "height-table"
x_start = 45.0
x_end = 48.0
time_step = 1e-4
output_step = 1e-3

[factors]
speed_kmh = [80.0, 100.0]
"turnout.rail_types.stock.pad.k_z" = [100e6, 140e6]
"""

#: Columns that are timings (differ from run to run by nature).
TIMINGS = ("wall_time_s", "case_wall_time_s", "case_cpu_time_s")


def _write(tmp_path: Path, text: str, name: str = "study.toml") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("serial")
    result = run_study(_write(tmp, TINY), workers=1, out=tmp / "out")
    return tmp, result


def _assert_same_numbers(a: dict, b: dict) -> None:
    assert list(a) == list(b)
    for name in a:
        if name in TIMINGS:
            continue
        if a[name].dtype.kind == "f":
            np.testing.assert_array_equal(a[name], b[name], err_msg=name)  # NaN == NaN here
        else:
            assert list(a[name]) == list(b[name]), name


def test_serial_study_table(serial):
    tmp, result = serial
    t = result.table
    assert result.n_cases == 4 and result.computed == 4 and result.failed == 0
    assert list(t["status"]) == ["ok"] * 4
    assert list(t["speed_kmh"]) == [80.0, 80.0, 100.0, 100.0]
    assert list(t["turnout.rail_types.stock.pad.k_z"]) == [100e6, 140e6, 100e6, 140e6]
    for column in (
        "peak_Fz_crossing_right_N",
        "peak_Fz_crossing_right_r2_N",
        "peak_Fy_crossing_left_N",
        "max_Fz_crossing_N",
        "rms_dyn_Fz_right_N",
        "rms_dyn_Fz_crossing_right_N",
        "contact_losses",
        "wall_time_s",
    ):
        assert column in t, column
    # the dynamic load at the crossing grows with speed (the dip's impact, paper Fig. 8)
    assert np.all(t["max_Fz_crossing_N"][2:] > t["max_Fz_crossing_N"][:2])
    assert np.all(t["max_Fz_crossing_N"] > t["static_wheel_load_N"])
    # the files: one table, one folder per case with its modified turnout file
    assert (
        load_results(tmp / "out")["max_Fz_crossing_N"].tolist() == t["max_Fz_crossing_N"].tolist()
    )
    header = (tmp / "out" / "results.csv").read_text(encoding="utf-8").splitlines()[0]
    assert header.startswith("case,key,status,speed_kmh,turnout.rail_types.stock.pad.k_z,")
    for key, k_z in zip(t["key"], t["turnout.rail_types.stock.pad.k_z"]):
        folder = tmp / "out" / "cases" / key
        data = tomllib.loads((folder / "uic60_760_1_15.toml").read_text(encoding="utf-8"))
        assert data["rail_types"]["stock"]["pad"]["k_z"] == k_z
        with np.load(folder / "history.npz") as history:
            # decimated to history_step: the stored samples (every ~1 ms) nearest to 2 ms steps
            dt = np.diff(history["t_s"])
            assert abs(np.mean(dt) - 0.002) < 1e-4 and np.all(np.abs(dt - 0.002) <= 0.00105)
    with np.load(tmp / "out" / "results.npz") as data:
        assert "package_version" in str(data["provenance"])


@pytest.mark.slow
@pytest.mark.parametrize("start_method", ["fork", "spawn"])
def test_process_pool_gives_identical_numbers(serial, tmp_path, start_method):
    import multiprocessing

    if start_method not in multiprocessing.get_all_start_methods():
        pytest.skip(f"no {start_method} start method on this platform")
    tmp, reference = serial
    pool = run_study(
        tmp / "study.toml", workers=2, out=tmp_path / "pool", start_method=start_method
    )
    assert pool.computed == 4
    _assert_same_numbers(reference.table, pool.table)
    meta = (tmp_path / "pool" / "results.meta.json").read_text(encoding="utf-8")
    assert f"process pool ({start_method}), 2 workers" in meta
    # the histories, compressed in the workers, hold the serial run's samples
    for key in reference.table["key"]:
        with (
            np.load(tmp / "out" / "cases" / key / "history.npz") as serial_history,
            np.load(tmp_path / "pool" / "cases" / key / "history.npz") as pool_history,
        ):
            assert serial_history.files == pool_history.files
            for name in serial_history.files:
                np.testing.assert_array_equal(serial_history[name], pool_history[name])


def test_process_pool_start_methods():
    from exudyn_turnout.studies.run import default_start_method, process_pool

    assert default_start_method() in ("fork", "spawn")
    with pytest.raises(StudyError, match="start_method must be 'fork' or 'spawn', got 'thread'"):
        process_pool([], 1, "thread")


def _openblas_threads(count: int | None = None) -> int:
    """NumPy's OpenBLAS thread count (set to ``count`` first, if given); -1 if not found."""
    import ctypes

    with open("/proc/self/maps", encoding="utf-8") as maps:
        paths = sorted({line.split()[-1] for line in maps if "openblas" in line.lower()})
    for path in paths:
        library = ctypes.CDLL(path)
        for suffix in ("64_", ""):
            getter = getattr(library, f"scipy_openblas_get_num_threads{suffix}", None)
            if getter is not None:
                if count is not None:
                    getattr(library, f"scipy_openblas_set_num_threads{suffix}")(count)
                return int(getter())
    return -1


def test_forked_pool_workers_have_one_blas_thread():
    """The forked workers inherit the parent's BLAS thread count unless they set it: the parent
    is set to 2 threads here, its workers must report 1 (issue 24: the fork pool inherited
    the BLAS threads)."""
    import multiprocessing
    import sys

    from exudyn_turnout.studies.run import process_pool

    forks = "fork" in multiprocessing.get_all_start_methods()
    if not (sys.platform.startswith("linux") and forks):
        pytest.skip("the pool forks on Linux only")
    before = _openblas_threads()
    if before < 0:
        pytest.skip("NumPy's BLAS here is not the OpenBLAS wheel")
    try:
        assert _openblas_threads(2) == 2
        with process_pool([], 2, "fork") as pool:
            counts = {pool.submit(_openblas_threads).result() for _ in range(4)}
        assert counts == {1}
        assert _openblas_threads() == 2  # the parent keeps its own
    finally:
        _openblas_threads(before)


@pytest.mark.slow
def test_dask_local_cluster_gives_identical_numbers(serial, tmp_path):
    tmp, reference = serial
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        pytest.skip("dask[distributed] is not installed (the cluster extra); CI installs it")
    with (
        LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
        ) as cluster,
        Client(cluster) as client,
    ):
        dask = run_study(tmp / "study.toml", executor=client.get_executor(), out=tmp_path / "dask")
    assert dask.computed == 4
    _assert_same_numbers(reference.table, dask.table)


def test_resume_computes_only_the_rest(serial, tmp_path):
    tmp, reference = serial
    seen = []

    def stop_after_two(done, total, eta):
        seen.append(done)
        if done == 2:
            raise KeyboardInterrupt  # the user stops the study after two cases

    with pytest.raises(KeyboardInterrupt):
        run_study(tmp / "study.toml", workers=1, out=tmp_path, progress=stop_after_two)
    assert seen == [0, 1, 2]
    again = run_study(tmp / "study.toml", workers=1, out=tmp_path)
    assert (again.computed, again.reused) == (2, 2)
    _assert_same_numbers(reference.table, again.table)
    third = run_study(tmp / "study.toml", workers=1, out=tmp_path)
    assert (third.computed, third.reused) == (0, 4)


def test_cases_stored_by_other_code_are_computed_again(serial, tmp_path, monkeypatch):
    import shutil
    import warnings

    import exudyn_turnout.studies.run as study_run

    tmp, reference = serial
    shutil.copytree(tmp / "out", tmp_path / "out")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the same code: reused without a word
        same = run_study(tmp / "study.toml", workers=1, out=tmp_path / "out")
    assert (same.computed, same.reused) == (0, 4)
    # a source file changed since the cases were stored
    monkeypatch.setattr(study_run, "code_digest", lambda: "0" * 64)
    with pytest.warns(UserWarning, match="4 case.* computed by other code.*computed again"):
        again = run_study(tmp / "study.toml", workers=1, out=tmp_path / "out")
    assert (again.computed, again.reused) == (4, 0)
    _assert_same_numbers(reference.table, again.table)  # (the code did not really change)
    third = run_study(tmp / "study.toml", workers=1, out=tmp_path / "out")
    assert (third.computed, third.reused) == (0, 4)  # stored now under the new digest


def test_code_digest_covers_the_computing_code_only():
    from exudyn_turnout.studies.run import code_digest

    assert len(code_digest()) == 64 and code_digest() == code_digest()


def test_failed_case_is_recorded_and_the_others_run(tmp_path):
    # 1 ms is above the contact's time-step limit (common.max_time_step: ~0.12 ms here, the
    # check rail's 41.5 kg bracket-derived mass, corunning.check_rail)
    text = TINY.replace('"turnout.rail_types.stock.pad.k_z" = [100e6, 140e6]', "")
    text = text.replace("time_step = 1e-4\n", "").replace(
        "[factors]", "[factors]\ntime_step = [1e-4, 1e-3]"
    )
    study = _write(tmp_path, text.replace("speed_kmh = [80.0, 100.0]", ""))
    result = run_study(study, workers=1, out=tmp_path / "out")
    assert list(result.table["status"]) == ["ok", "failed"]
    assert "time step" in result.table["error"][1] and "\n" not in result.table["error"][1]
    assert np.isnan(result.table["max_Fz_crossing_N"][1])
    rerun = run_study(study, workers=1, out=tmp_path / "out")
    assert (rerun.computed, rerun.reused, rerun.failed) == (0, 2, 1)
    retry = run_study(study, workers=1, out=tmp_path / "out", retry_failed=True)
    assert (retry.computed, retry.reused, retry.failed) == (1, 1, 1)


def test_keys_follow_inputs_and_file_content(tmp_path):
    study = load_study(_write(tmp_path, TINY))
    keys = [c.key for c in study.cases()]
    assert len(set(keys)) == 4 and keys == [c.key for c in study.cases()]
    # the same scenario on a copy of the turnout file, and on one with another value: new keys
    from exudyn_turnout.inputs.turnout import default_turnout_path

    text = default_turnout_path().read_text(encoding="utf-8")
    (tmp_path / "copy.toml").write_text(text, encoding="utf-8")
    edited_text = text.replace("clearance = 0.004", "clearance = 0.005")
    assert edited_text != text
    (tmp_path / "edited.toml").write_text(edited_text, encoding="utf-8")
    copy = load_study(_write(tmp_path, TINY + '\n[paired]\nturnout = ["copy.toml"]\n', "c.toml"))
    edited = load_study(
        _write(tmp_path, TINY + '\n[paired]\nturnout = ["edited.toml"]\n', "e.toml")
    )
    copy_keys = [c.key for c in copy.cases()]
    assert copy_keys != [c.key for c in edited.cases()]
    # the content is hashed, not the name: a copy of the packaged file gives the same keys
    assert copy_keys == keys


def test_latin_hypercube_and_seeds():
    study = study_from_dict(
        {
            "latin_hypercube": {
                "samples": 5,
                "seed": 2,
                "ranges": {"speed_kmh": [50.0, 100.0], "turnout.sleeper.density": [2200.0, 2600.0]},
            },
            "repetitions": {"irregularity": "psd:ERRI-low,band=2-50", "seeds": 3},
        }
    )
    rows = study.combinations()
    assert len(rows) == 15 and [r["seed"] for r in rows[:3]] == [1, 2, 3]
    speeds = np.array([r["speed_kmh"] for r in rows[::3]])
    # Latin hypercube (McKay et al. 1979): exactly one sample in each of the 5 strata
    assert sorted(np.floor((speeds - 50.0) / 10.0).astype(int)) == [0, 1, 2, 3, 4]
    assert rows == study.combinations()  # the seed makes it reproducible
    assert study.varied == ("speed_kmh", "turnout.sleeper.density", "seed")
    assert study._irregularity_spec({"seed": 2}) == "psd:ERRI-low,band=2-50,seed=2"
    cases = study.cases()
    assert [c.irregularity_spec for c in cases[:2]] == [
        "psd:ERRI-low,band=2-50,seed=1",
        "psd:ERRI-low,band=2-50,seed=2",
    ]
    assert cases[0].irregularity is not None and cases[1].irregularity is not None
    assert not np.allclose(cases[0].irregularity.vertical_left, cases[1].irregularity.vertical_left)
    assert len({c.key for c in cases}) == 15


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("[factors]\nspeed = [80.0]", "unknown factor 'speed'"),
        ("[factors]\nspeed_kmh = 80.0", "speed_kmh must be a non-empty list"),
        ('[factors]\nspeed_kmh = ["fast"]', "speed_kmh = 'fast': must be a finite number"),
        ('[base]\ntrack = "4-layer"', "track = '4-layer': must be one of"),
        ("[paired]\nspeed_kmh = [80.0, 90.0]\nlayers = [2]", "the lists must have one length"),
        ("[latin_hypercube]\nsamples = 4\nranges = { speed_kmh = [90.0, 80.0] }", "low < high"),
        ('[repetitions]\nseeds = 3\nirregularity = "dip:x=1"', "psd: part"),
        ("[plan]\nx = 1", "unknown section [plan]"),
        ('[factors]\n"turnout.rail_types.stock.pad.kz" = [1e8]', "no field 'kz'"),
        ('[factors]\n"turnout.rail_types.stock.pad.k_z" = ["stiff"]', "holds a float"),
        ('[factors]\n"turnout.rail_types.stock.pad.k_z" = [-1e8]', "k_z"),
        ('[factors]\nroute = ["sideways"]', "has no such route"),
        ('[base]\nirregularity = "dip:x=47,depth=0.002"', "length is missing"),
    ],
)
def test_bad_study_files_give_one_line(tmp_path, text, message):
    path = _write(tmp_path, text)
    with pytest.raises(StudyError, match=message.replace("[", r"\[")) as info:
        load_study(path).cases()
    assert str(info.value).startswith("study.toml: ") and "\n" not in str(info.value)


def test_cli_study_exit_codes_and_figures(serial, tmp_path, capsys):
    tmp, _ = serial
    # the serial fixture's output: every case is stored, nothing is computed again
    assert (
        main(["study", str(tmp / "study.toml"), "--out", str(tmp / "out"), "--workers", "1"]) == 0
    )
    assert "4 cases, 0 computed, 4 stored before, 0 failed" in capsys.readouterr().out
    assert (tmp / "out" / "peak_vs_speed_kmh.png").stat().st_size > 0
    bad = _write(tmp_path, "[factors]\nspeed = [1.0]")
    assert main(["study", str(bad), "--out", str(tmp_path / "o")]) == 2
    assert "unknown factor 'speed'" in capsys.readouterr().err


def test_toml_writer_round_trips_the_packaged_files():
    from exudyn_turnout.inputs.turnout import default_turnout_path
    from exudyn_turnout.inputs.vehicle import default_vehicle_path

    for path in (default_turnout_path(), default_vehicle_path()):
        data = tomllib.loads(path.read_text(encoding="utf-8"))
        assert tomllib.loads(dumps(data)) == data
    odd = {"a b": [1, 2.5, "x"], "t": {"inline": [{"k": float("inf")}]}, "flag": True}
    assert tomllib.loads(dumps(odd)) == odd


def test_fitted_parameter_source_in_a_study(tmp_path):
    """Issue 16: `source = "fitted"` with a fitted file (here the packaged one) in studies;
    the fitted set's crossing peak differs from the derived set's (its track is stiffer:
    validation/fitted_parameters.md)."""
    # the fitted rail masses are about half the derived ones: 0.1 ms (the study's step, the
    # package's default) still resolves the contact resonance with the lighter rail
    text = TINY.replace(
        '[factors]\nspeed_kmh = [80.0, 100.0]\n"turnout.rail_types.stock.pad.k_z" = [100e6, 140e6]',
        '[paired]\nsource = ["derived", "fitted"]\nparameters = ["", "uic60_760_1_15_fitted.toml"]',
    )
    result = run_study(_write(tmp_path, text), workers=1, out=tmp_path / "out")
    t = result.table
    assert list(t["status"]) == ["ok", "ok"], list(t["error"])
    derived, fitted = t["max_Fz_crossing_N"]
    assert abs(fitted / derived - 1) > 0.005
    bad = text.replace('parameters = ["", "uic60_760_1_15_fitted.toml"]', 'parameters = ["", ""]')
    with pytest.raises(StudyError, match="source = 'fitted' and a parameters file go together"):
        load_study(_write(tmp_path, bad, "bad.toml")).cases()


# --- issue 24: studies scale; issue 25: studies you can read ------------------------------

#: Two short cases of the default profile contact (the crossing's dip, 44.5-46 m).
PROFILE = """
[study]
name = "profile"

[base]
x_start = 44.5
x_end = 46.0
output_step = 2e-3

[factors]
speed_kmh = [80.0, 100.0]
"""


def test_cases_of_the_same_files_share_the_contact_tables(tmp_path, monkeypatch):
    """A worker builds (or reads) a route's contact tables once, not once per case: before
    issue 24 each case loaded its files from a new temporary folder, the in-memory tables
    missed, and ~2.5 s of a ~3 s case went to rebuilding them."""
    from exudyn_turnout.studies import run_case
    from exudyn_turnout.wheel_rail import turnout_sections

    calls = []
    original = turnout_sections.route_contact_tables

    def counted(*args, **kwargs):
        calls.append(args[1])
        return original(*args, **kwargs)

    monkeypatch.setattr(turnout_sections, "route_contact_tables", counted)
    cases = load_study(_write(tmp_path, PROFILE)).cases()
    records = [run_case(case) for case in cases]
    assert [r["status"] for r in records] == ["ok", "ok"], [r["error"] for r in records]
    assert len(calls) <= 1  # 0 if an earlier test of this process loaded the same route


def test_longest_cases_are_handed_out_first():
    from exudyn_turnout.studies.run import estimated_cost

    study = study_from_dict(
        {
            "base": {"x_start": 40.0, "x_end": 50.0},
            "factors": {"speed_kmh": [50.0, 100.0], "track": ["3-layer", "fe"]},
        }
    )
    cost = {(c.inputs["speed_kmh"], c.inputs["track"]): estimated_cost(c) for c in study.cases()}
    # 10 m at 50 km/h is twice the steps of 10 m at 100 km/h; the FE track costs more
    assert cost[50.0, "3-layer"] == pytest.approx(2 * cost[100.0, "3-layer"])
    assert cost[100.0, "fe"] > cost[50.0, "3-layer"]


def test_keep_timeseries_stores_each_case_compressed(tmp_path):
    import zipfile

    path = _write(tmp_path, PROFILE.replace("[80.0, 100.0]", "[100.0]"))
    first = run_study(path, workers=1, out=tmp_path / "out")
    key = first.table["key"][0]
    folder = tmp_path / "out" / "cases" / key
    assert not (folder / "timeseries.npz").exists()  # not asked for
    # asked for now (the option): the stored case lacks them, so it runs again
    again = run_study(path, workers=1, out=tmp_path / "out", keep_timeseries=True)
    assert (again.computed, again.reused) == (1, 0)
    with zipfile.ZipFile(folder / "timeseries.npz") as archive:
        assert {i.compress_type for i in archive.infolist()} == {zipfile.ZIP_DEFLATED}
    with np.load(folder / "timeseries.npz") as series:
        t, x = series["t_s"], series["x_m"]
        # every stored sample of the passage: 1.5 m at 100 km/h, one every 2 ms
        assert t.size == pytest.approx(1.5 / (100 / 3.6) / 2e-3 + 1, abs=1)
        assert x[0] == pytest.approx(44.5) and x[-1] == pytest.approx(46.0, abs=0.06)
        assert series["Fz_right_N"].shape == t.shape
        # the study's RMS of the dynamic load comes from these very samples (to 1 mN: the
        # table keeps 9 digits, so its static load of ~1e5 N is rounded to 1e-4 N)
        fz = series["Fz_right_N"] - again.table["static_wheel_load_N"][0]
        rms = np.sqrt(np.mean(fz[np.isfinite(fz)] ** 2))
        assert rms == pytest.approx(again.table["rms_dyn_Fz_right_N"][0], abs=1e-3)
    # the same from the study file's [output] section; stored with them: nothing to run
    path.write_text(
        PROFILE.replace("[80.0, 100.0]", "[100.0]") + "\n[output]\nkeep_timeseries = true\n"
    )
    assert load_study(path).keep_timeseries
    third = run_study(path, workers=1, out=tmp_path / "out")
    assert (third.computed, third.reused) == (0, 1)
    with pytest.raises(StudyError, match=r"\[output\]: unknown field 'keep'"):
        study_from_dict({"output": {"keep": True}})
    with pytest.raises(StudyError, match="keep_timeseries = 'yes' must be true or false"):
        study_from_dict({"output": {"keep_timeseries": "yes"}})


def test_progress_lines_in_a_log_and_a_bar_on_a_terminal():
    import io

    from exudyn_turnout.cli.study import ProgressLines

    now = [0.0]
    log = io.StringIO()
    show = ProgressLines(log, clock=lambda: now[0])
    for done, eta, t in ((1, None, 0.0), (1, None, 0.0), (2, 30.0, 10.0), (4, 0.0, 41.0)):
        now[0] = t
        show(done, 4, eta)
    show.end()
    # one plain line per finished case (a repeated count is not repeated), no carriage return
    assert log.getvalue().splitlines() == [
        "study: 1/4 cases, 0 s, ETA --",
        "study: 2/4 cases, 10 s, ETA 0:30",
        "study: 4/4 cases, 41 s, ETA 0:00",
    ]

    class Terminal(io.StringIO):
        def isatty(self):
            return True

    tty = Terminal()
    bar = ProgressLines(tty, clock=lambda: 0.0)
    bar(2, 4, 5.0)
    assert tty.getvalue().startswith("\r[###############...............] 2/4 cases")
    assert "\n" not in tty.getvalue()
    bar.end()
    assert tty.getvalue().endswith("\n")


def _synthetic_table():
    """A study's table without passages: 3 paired pad levels x 2 speeds x 3 seeds."""
    pads = [f"turnout.rail_types.{r}.pad.k_z" for r in ("stock", "switch", "crossing", "check")]
    rows = [(k, v, s) for k in (96e6, 120e6, 144e6) for v in (80.0, 100.0) for s in (1, 2, 3)]
    n = len(rows)
    table = {
        "case": np.arange(n, dtype=float),
        "status": np.array(["ok"] * n),
        "speed_kmh": np.array([r[1] for r in rows]),
        "seed": np.array([float(r[2]) for r in rows]),
        # a made-up peak: grows with pad stiffness and speed, a spread over the seeds
        "max_Fz_crossing_N": np.array([1e5 + r[0] * 1e-4 + 100 * r[1] + 50 * r[2] for r in rows]),
    }
    for name in pads:
        table[name] = np.array([r[0] for r in rows])
    varied = ["speed_kmh", *pads, "seed"]
    return table, varied, pads


def test_study_figures_one_per_factor_with_units(tmp_path, monkeypatch):
    from exudyn_turnout.plotting import studies as figures

    table, varied, pads = _synthetic_table()
    saved = {}

    def keep(fig, path):
        saved[Path(path).name] = fig

    monkeypatch.setattr(figures, "save_study_figure", keep)
    paths = figures.study_figures(table, varied, tmp_path, paired=pads)
    # four paired pad factors make one figure, not four identical ones
    assert sorted(saved) == [
        "peak_distribution.png",
        "peak_vs_speed_kmh.png",
        "peak_vs_turnout_rail_types_stock_pad_k_z.png",
    ]
    assert len(paths) == 3
    pad_ax = saved["peak_vs_turnout_rail_types_stock_pad_k_z.png"].axes[0]
    assert pad_ax.get_xlabel() == "rail pad k_z, stock/switch/crossing/check rails (MN/m)"
    assert pad_ax.get_ylabel().startswith("largest Fz, crossing (kN)")
    # one curve per speed (the other factor), the seeds as mean and range; x in MN/m
    assert [t.get_text() for t in pad_ax.get_legend().get_texts()] == [
        "speed = 80 km/h",
        "speed = 100 km/h",
    ]
    np.testing.assert_allclose(pad_ax.get_lines()[0].get_xdata(), [96.0, 120.0, 144.0])
    speed_ax = saved["peak_vs_speed_kmh.png"].axes[0]
    assert speed_ax.get_xlabel() == "speed (km/h)"
    assert len(speed_ax.get_lines()) == 3  # one per pad level
    # the distribution over seeds split by the other factors: 3 pads x 2 speeds, 3 seeds each
    cdf_ax = saved["peak_distribution.png"].axes[1]
    labels = [t.get_text() for t in cdf_ax.get_legend().get_texts()]
    assert len(labels) == 6 and all(label.endswith("(n = 3)") for label in labels)
    assert labels[0] == "speed = 80 km/h, rail pad k_z = 96 MN/m (n = 3)"


def test_factor_and_result_labels_carry_units():
    from exudyn_turnout.plotting.studies import factor_label, result_label

    assert factor_label("speed_kmh") == ("speed (km/h)", 1.0)
    assert factor_label("time_step") == ("time step (ms)", 1e3)
    assert factor_label("vehicle.primary_suspension.c_z") == (
        "vehicle primary suspension c_z (kN s/m)",
        1e-3,
    )
    assert factor_label("turnout.sleeper.density")[0] == "sleeper density (kg/m^3)"
    assert factor_label("turnout.something_odd")[0].endswith("(SI)")  # unknown: said so
    assert result_label("peak_Fz_crossing_right_r2_N") == (
        "peak Fz, crossing, right, r2 (kN)",
        1e-3,
    )
    assert result_label("rms_dyn_Fz_right_N")[0] == "RMS of dynamic Fz, right (kN)"


@pytest.mark.slow
def test_profile_contact_pool_and_dask_give_the_serial_numbers(tmp_path):
    """The default contact: serial, the process pool (warmed workers, longest case first)
    and a Dask cluster give the very same table, to the bit."""
    path = _write(tmp_path, PROFILE)
    serial_run = run_study(path, workers=1, out=tmp_path / "serial")
    pool = run_study(path, workers=2, out=tmp_path / "pool")
    assert pool.computed == 2 and pool.failed == 0
    _assert_same_numbers(serial_run.table, pool.table)
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        pytest.skip("dask[distributed] is not installed (the cluster extra); CI installs it")
    with (
        LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
        ) as cluster,
        Client(cluster) as client,
    ):
        dask = run_study(path, executor=client.get_executor(), out=tmp_path / "dask")
    assert dask.computed == 2
    _assert_same_numbers(pool.table, dask.table)


def test_turnout_naming_its_own_rail_profile_beside_it(tmp_path):
    """A study's turnout file that names a rail profile lying beside it (not packaged) runs:
    each case's copy of the turnout resolves the profile in the study's folder, and a changed
    profile file gives new case keys (the case's results depend on it)."""
    from exudyn_turnout.inputs.turnout import default_turnout_path
    from exudyn_turnout.wheel_rail.data import data_dir

    text = default_turnout_path().read_text(encoding="utf-8")
    own = text.replace('profile = "MBench_UIC60_v3.prr"', 'profile = "my_rail.prr"')
    assert own != text
    (tmp_path / "t.toml").write_text(own, encoding="utf-8")
    rail = (data_dir() / "profiles" / "MBench_UIC60_v3.prr").read_bytes()
    (tmp_path / "my_rail.prr").write_bytes(rail)
    study_text = TINY.replace('contact = "height-table"', 'contact = "profile"')
    study_text = study_text.replace("x_end = 48.0", "x_end = 45.5")
    study_text = study_text.replace("speed_kmh = [80.0, 100.0]\n", "").replace(
        '"turnout.rail_types.stock.pad.k_z" = [100e6, 140e6]', 'turnout = ["t.toml"]'
    )
    study = _write(tmp_path, study_text)
    result = run_study(study, workers=1, out=tmp_path / "out")
    assert list(result.table["status"]) == ["ok"], result.table["error"]
    assert result.table["max_Fz_crossing_N"][0] > 0.0
    keys = [c.key for c in load_study(study).cases()]
    (tmp_path / "my_rail.prr").write_bytes(rail + b"\n")
    assert [c.key for c in load_study(study).cases()] != keys
