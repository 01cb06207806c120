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
time_step = 1.5e-4
output_step = 1e-3

[factors]
speed_kmh = [80.0, 100.0]
"turnout.rail_types.stock.pad.k_z" = [100e6, 140e6]
"""

#: Columns that are timings (differ from run to run by nature).
TIMINGS = ("wall_time_s", "case_wall_time_s")


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
def test_process_pool_gives_identical_numbers(serial, tmp_path):
    tmp, reference = serial
    pool = run_study(tmp / "study.toml", workers=2, out=tmp_path / "pool")
    assert pool.computed == 4
    _assert_same_numbers(reference.table, pool.table)


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


def test_failed_case_is_recorded_and_the_others_run(tmp_path):
    # 1 ms is above the contact's time-step limit (simulate.max_time_step: ~0.18 ms here)
    text = TINY.replace('"turnout.rail_types.stock.pad.k_z" = [100e6, 140e6]', "")
    text = text.replace("time_step = 1.5e-4\n", "").replace(
        "[factors]", "[factors]\ntime_step = [1.5e-4, 1e-3]"
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
    # the fitted rail masses are about half the derived ones: the passage refuses 0.15 ms
    # (too coarse for the contact resonance with the lighter rail), 0.1 ms resolves it
    text = TINY.replace("time_step = 1.5e-4", "time_step = 1e-4").replace(
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
