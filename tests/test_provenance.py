"""Outputs say how they were made (provenance) and show the user what was run.

summary.json carries versions, input files by name with SHA-256, every setting, the
command line without absolute paths and the date; two runs with different options
never give indistinguishable summaries; floats are rounded to 9 significant digits.
CSV outputs keep their plain table and get a ``<stem>.meta.json`` sidecar.
"""

import hashlib
import json
import re

import numpy as np
import pytest

from exudyn_turnout.cli.main import main
from exudyn_turnout.inputs.turnout import default_turnout_path
from exudyn_turnout.inputs.vehicle import default_vehicle_path
from exudyn_turnout.provenance import provenance, reduce_argv, round_floats

SHORT = ["simulate", "--vehicle", "wheelset", "--layers", "2", "--no-plot"]
SHORT += ["--x-start", "45.2", "--x-end", "45.6"]


def _simulate(capsys, out, *extra):
    code = main(SHORT + ["--out", str(out)] + list(extra))
    text = capsys.readouterr()
    assert code == 0, text.err
    return (
        json.loads((out / "summary.json").read_text()),
        (out / "summary.json").read_text(),
        text.out,
    )


def test_round_floats_and_argv():
    assert round_floats({"a": 2.3399999999999808, "b": [float("nan"), 1e-20 / 3], "c": -0.0}) == {
        "a": 2.34,
        "b": [None, 3.33333333e-21],
        "c": 0.0,
    }
    assert reduce_argv(
        ["--out", "/home/me/run", "--turnout=/x/y/t.toml", "rel/dir", "--x", "3"]
    ) == ["--out", "run", "--turnout=t.toml", "rel/dir", "--x", "3"]
    rec = provenance({"speed": 100.0}, turnout=default_turnout_path(), argv=["params"])
    assert (
        rec["inputs"]["turnout"]["sha256"]
        == hashlib.sha256(default_turnout_path().read_bytes()).hexdigest()
    )
    assert rec["command_line"] == "exudyn-turnout params" and rec["date_utc"].endswith("+00:00")


def test_summary_provenance_and_different_options_differ(tmp_path, capsys):
    a, text_a, line = _simulate(capsys, tmp_path / "a")
    b, _, _ = _simulate(capsys, tmp_path / "b", "--output-step", "2e-4")
    c, _, _ = _simulate(capsys, tmp_path / "c", "--speed", "90")
    p = a["provenance"]
    for key in (
        "package_version",
        "exudyn_version",
        "python_version",
        "date_utc",
        "argv",
        "command_line",
    ):
        assert p[key]
    assert p["inputs"]["turnout"] == {
        "name": "uic60_760_1_15.toml",
        "sha256": hashlib.sha256(default_turnout_path().read_bytes()).hexdigest(),
    }
    assert p["inputs"]["vehicle"]["name"] == "manchester_wheelset.toml"
    s = p["settings"]
    assert (
        s["route"],
        s["speed_kmh"],
        s["layers"],
        s["source"],
        s["profiles"],
        s["x_start"],
        s["x_end"],
        s["time_step"],
        s["format"],
    ) == ("through", 100.0, 2, "derived", "paper", 45.2, 45.6, 1e-4, "csv")
    assert "track_mechanism" in s and "output_step" in s
    assert str(tmp_path) not in text_a and "/" not in " ".join(p["argv"])
    # no float printed with more than 9 significant digits
    assert not [
        t
        for t in re.findall(r"-?\d+\.\d+(?:e-?\d+)?", text_a)
        if len(re.sub(r"[^0-9]", "", t.split("e")[0]).lstrip("0")) > 9
    ]
    strip = ("wall_time_s", "provenance")
    dicts = [{k: v for k, v in d.items() if k not in strip} for d in (a, b, c)]
    assert dicts[0] != dicts[1] and dicts[0] != dicts[2] and dicts[1] != dicts[2]
    assert a["output_step_s"] == 1e-4 and b["output_step_s"] == 2e-4
    assert b["provenance"]["settings"]["output_step"] == 2e-4
    rows = [len((tmp_path / d / "timeseries.csv").read_text().splitlines()) for d in "ab"]
    assert rows[1] - 1 == pytest.approx((rows[0] - 1) / 2, abs=2)  # every other step stored
    assert "right wheel on r2" in line


def test_npz_format(tmp_path, capsys):
    out = tmp_path / "npz"
    summary, _, _ = _simulate(capsys, out, "--format", "npz")
    assert sorted(p.name for p in out.iterdir()) == ["summary.json", "timeseries.npz"]
    data = np.load(out / "timeseries.npz")
    assert json.loads(str(data["summary"]))["provenance"]["settings"]["format"] == "npz"
    assert data["t_s"].shape == data["Fz_right_N"].shape and data["x_m"][0] == pytest.approx(45.2)
    assert summary["peak_Fz_crossing_N"] == pytest.approx(
        float(np.max(data["Fz_right_N"])), rel=1e-8
    )


def test_diverging_route_names_the_left_wheel(tmp_path, capsys):
    """On the diverging route the crossing is met by the left wheel: summary and console say so."""
    summary, _, line = _simulate(
        capsys, tmp_path / "d", "--route", "diverging", "--x-start", "44.5", "--x-end", "48.0"
    )
    assert summary["max_Fz_crossing_wheel"] == "left" and summary["max_Fz_crossing_rail"] == "r2"
    assert (
        summary["max_Fz_crossing_N"]
        == summary["peak_Fz_crossing_left_N"]
        == summary["peak_Fz_crossing_left_r2_N"]
    )
    assert (
        summary["peak_Fz_crossing_left_N"] > summary["peak_Fz_crossing_N"]
    )  # right wheel: plain rail
    assert "at the crossing (left wheel on r2, x = 4" in line


def test_vehicle_option(tmp_path, capsys):
    heavier = default_vehicle_path().read_text().replace("mass = 9307.5", "mass = 12000.0")
    path = tmp_path / "heavy.toml"
    path.write_text(heavier)
    summary, _, _ = _simulate(capsys, tmp_path / "v", "--vehicle", str(path))
    W = (1813.0 + 12000.0) * 9.81 / 2
    assert summary["static_wheel_load_N"] + summary["static_wheel_load_left_N"] == pytest.approx(
        2 * W, rel=1e-3
    )
    assert summary["provenance"]["inputs"]["vehicle"]["name"] == "heavy.toml"


def test_frf_sidecar_keeps_the_csv_plain(tmp_path, capsys):
    out = tmp_path / "h.csv"
    assert (
        main(
            [
                "frf",
                "--layers",
                "2",
                "--rail",
                "r2",
                "--direction",
                "vertical",
                "--zone",
                "1",
                "--n",
                "5",
                "--out",
                str(out),
            ]
        )
        == 0
    )
    assert np.loadtxt(out, delimiter=",", skiprows=1).shape == (5, 4)
    meta = json.loads((tmp_path / "h.meta.json").read_text())
    assert meta["settings"]["rail"] == "r2" and meta["settings"]["layers"] == 2
    assert meta["inputs"]["turnout"]["name"] == "uic60_760_1_15.toml" and str(
        tmp_path
    ) not in json.dumps(meta)
    capsys.readouterr()


def test_params_carries_its_provenance(capsys):
    assert main(["params", "--zone", "1", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["turnout_file"] == "uic60_760_1_15.toml" and len(data["turnout_sha256"]) == 64
    assert data["command_line"] == "exudyn-turnout params --zone 1 --format json"


def test_implausible_dynamics_stop_with_time_and_x(tmp_path, capsys, monkeypatch):
    """A force beyond the limit during the run: exit 3 naming t, x and the quantity, no output."""
    from exudyn_turnout.passage import settings as passage

    monkeypatch.setitem(passage.PLAUSIBLE, "force_over_static", 2.0)  # the nose impact is ~3 W
    code = main(
        SHORT
        + [
            "--out",
            str(tmp_path / "f"),
            "--route",
            "diverging",
            "--x-start",
            "44.5",
            "--x-end",
            "48.0",
        ]
    )
    err = capsys.readouterr().err
    assert code == 3 and re.search(
        r"implausible run stopped at t = [0-9.]+ s, x = 4\d\.\d+ m", err
    ), err
    assert "normal force" in err and not (tmp_path / "f" / "summary.json").exists()
