"""``simulate --track 2-layer,3-layer``: several tracks in one call, overlaid (issue 25), and
the progress line on stderr (issue 24).

Reference for the direction of the 2-layer/3-layer difference: the paper's Section 4
(Shih, Ambur & Dixon 2023), where the two-layer model overestimates the crossing impact;
checked here as a property of our two models, not as the paper's number.
"""

from __future__ import annotations

import io
import json

import numpy as np
import pytest

from exudyn_turnout.cli.main import main
from exudyn_turnout.cli.passage import COMPARISON_FILE, StatusLine, track_list
from exudyn_turnout.passage.comparison import PassageComparison, difference_percent
from exudyn_turnout.passage.results import PassageResult
from exudyn_turnout.passage.settings import PassageSettings
from exudyn_turnout.plotting.curves import decimate_min_max, missing_region_note

SHORT = ["--vehicle", "wheelset", "--x-start", "46.5", "--x-end", "48"]


def test_track_list_reads_one_or_several():
    assert track_list("3-layer") == ("3-layer",)
    assert track_list("2-layer, 3-layer,fe") == ("2-layer", "3-layer", "fe")


@pytest.mark.parametrize(
    "value, words", [("2-layer,4-layer", "unknown track '4-layer'"), ("fe,fe", "named twice")]
)
def test_bad_track_list_is_one_line_exit_2(tmp_path, capsys, value, words):
    code = main(["simulate", "--track", value, "--out", str(tmp_path / "o"), "--no-plot"])
    err = capsys.readouterr().err
    assert code == 2 and words in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "o").exists()


@pytest.mark.slow
def test_two_tracks_one_call(tmp_path, capsys):
    out = tmp_path / "run"
    out.mkdir()
    (out / "summary.json").write_text("from an earlier single-track run")
    code = main(["simulate", "--track", "2-layer,3-layer", *SHORT, "--quiet", "--out", str(out)])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    # --quiet: no progress, only the warnings (a start inside the crossing region)
    assert all(line.startswith("warning: ") for line in captured.err.splitlines())
    assert sorted(p.name for p in out.iterdir()) == [
        "2-layer",
        "3-layer",
        COMPARISON_FILE,
        "forces.png",
    ]  # the earlier flat summary.json is gone: no mixed layout
    for track in ("2-layer", "3-layer"):
        summary = json.loads((out / track / "summary.json").read_text())
        assert summary["layers"] == int(track[0])
        assert (out / track / "timeseries.csv").exists()
        assert not (out / track / "forces.png").exists()  # the overlaid one is in --out
    assert (out / "forces.png").read_bytes()[:4] == b"\x89PNG"
    record = json.loads((out / COMPARISON_FILE).read_text())
    two, three = (record["tracks"][t]["peak_Fz_crossing_N"] for t in ("2-layer", "3-layer"))
    assert three < two  # Section 4: the 2-layer model overestimates the crossing impact
    diff = record["difference_percent"]["3-layer vs 2-layer"]["peak_Fz_crossing_N"]
    assert diff == pytest.approx(100 * (three - two) / two, rel=1e-6)
    assert record["tracks"]["2-layer"]["peak_Fz_switch_N"] is None  # 46.5-48 m: no switch
    assert "3-layer vs 2-layer" in captured.out and captured.out.count("wrote ") == 3
    # a single track into the same --out: the folders' results go, the flat layout returns
    code = main(["simulate", *SHORT, "--no-plot", "--quiet", "--out", str(out)])
    assert code == 0
    assert not (out / COMPARISON_FILE).exists()
    assert not (out / "2-layer" / "summary.json").exists()
    assert (out / "summary.json").exists()


def test_difference_is_of_magnitudes():
    assert difference_percent(-15.0, -20.0) == pytest.approx(-25.0)
    assert difference_percent(110.0, 100.0) == pytest.approx(10.0)
    assert difference_percent(float("nan"), 100.0) is None
    assert difference_percent(1.0, 0.0) is None


def _fake(x0, x1, layers=3, force=50e3, n=500):
    """A hand-made result: constant forces over x0..x1, the packaged turnout's regions."""
    x = np.linspace(x0, x1, n)
    columns = {"t_s": x / 27.8, "x_m": x}
    for q in ("Fz", "Fy"):
        for wheel in ("right", "left"):
            columns[f"{q}_{wheel}_N"] = np.full(n, force if q == "Fz" else 0.0)
    summary = {
        "switch_region_m": [0.0, 10.0],  # data/uic60_760_1_15.toml [regions]
        "crossing_region_m": [44.29, 51.0],
        "static_wheel_load_N": force,
        "static_wheel_load_left_N": force,
        "peak_Fz_crossing_N": force * layers,
        "peak_Fz_switch_N": float("nan"),
    }
    return PassageResult(PassageSettings(layers=layers), columns, summary)


def test_a_region_outside_the_run_has_no_panel_and_a_note():
    run = _fake(40.0, 50.0)
    assert missing_region_note([run], "crossing") is None
    note = missing_region_note([run], "switch")
    assert note == "switch 0-10 m outside the run's x range 40-50 m"
    fig, axes = run.plot()
    assert axes.shape == (2, 1)
    assert "crossing" in axes[0, 0].get_title()
    assert note in fig._suptitle.get_text()


def test_a_run_reaching_no_region_is_drawn_whole_with_notes():
    fig, axes = _fake(20.0, 30.0).plot()
    assert axes.shape == (2, 1) and "x 20-30 m" in axes[0, 0].get_title()
    text = fig._suptitle.get_text()
    assert "switch 0-10 m outside" in text and "crossing 44.29-51 m outside" in text


def test_comparison_overlays_and_tabulates():
    comparison = PassageComparison({"2-layer": _fake(40, 50, 2), "3-layer": _fake(40, 50, 3)})
    fig, axes = comparison.plot()
    assert len(axes[0, 0].get_lines()) == 2
    table = comparison.table()
    assert "+50.0%" in table  # 3 * F against 2 * F
    assert comparison.record()["tracks"]["3-layer"]["peak_Fz_switch_N"] is None
    with_fe = PassageComparison(
        {"2-layer": _fake(40, 50, 2), "3-layer": _fake(40, 50, 3), "fe": _fake(40, 50, 4)}
    )
    assert with_fe.pairs() == [("3-layer", "2-layer"), ("2-layer", "fe"), ("3-layer", "fe")]
    diffs = with_fe.differences()
    assert diffs["2-layer vs fe"]["peak_Fz_crossing_N"] == pytest.approx(-50.0)  # 2F vs 4F
    assert PassageComparison({"3-layer": _fake(40, 50, 3)}).differences() == {}


def test_decimation_keeps_every_peak():
    rng = np.random.default_rng(1)
    x = np.arange(100_000, dtype=float)
    y = rng.normal(size=x.size)
    y[12_345] = 50.0  # one isolated spike
    y[77_777] = -40.0
    xs, ys = decimate_min_max(x, y, 2000)
    assert len(xs) <= 2000 and np.all(np.diff(xs) > 0)
    assert ys.max() == 50.0 and ys.min() == -40.0
    short = np.arange(10.0)
    assert len(decimate_min_max(short, short)[0]) == 10


class _Tty(io.StringIO):
    def isatty(self):
        return True


def test_status_line_plain_in_a_log_and_a_bar_on_a_terminal():
    log = io.StringIO()
    status = StatusLine(log)
    status.stage("writing")
    status.setup("3-layer track", "contact tables")
    show = status.run("3-layer track")
    assert log.getvalue() == "writing\n"  # the set-up is printed when it has ended
    for i in range(51):
        show(i / 50, 2.0 * i)
    status.end()
    lines = log.getvalue().splitlines()
    assert "\r" not in log.getvalue()
    assert lines[1].startswith("3-layer track: set up in") and "(contact tables)" in lines[1]
    assert lines[-1].startswith("3-layer track: set up and ran in")
    assert [line.split(":")[1].split("%")[0].strip() for line in lines[2:-1]] == [
        "0",
        "26",
        "50",
        "76",
        "100",
    ]  # every 25 %, at the first report past each quarter
    assert "s left" in lines[3]
    tty = _Tty()
    status = StatusLine(tty)
    status.setup("3-layer track", "contact tables")
    assert tty.getvalue().endswith("preparing the 3-layer track: contact tables")
    bar = status.run("3-layer track")
    bar(0.0, 0.0)
    bar(0.5, 10.0)
    status.end()
    assert "\r" in tty.getvalue() and "[###############" in tty.getvalue()
    failed = io.StringIO()
    status = StatusLine(failed)
    status.setup("3-layer track", "contact tables")
    status.run("3-layer track")
    status.clear()  # bad input found in the set-up: the error will be the one line
    status.end()
    assert failed.getvalue() == ""
    quiet = io.StringIO()
    status = StatusLine(quiet, quiet=True)
    status.stage("x")
    status.run("y")(0.5, 1.0)
    status.end()
    assert quiet.getvalue() == ""


def test_a_full_vehicle_window_names_the_front_wheelset():
    run = _fake(60.0, 70.0)
    columns = dict(run.columns, x_ws2_m=run.columns["x_m"] - 2.5)  # a second wheelset
    vehicle = PassageResult(run.settings, columns, run.summary)
    note = missing_region_note([vehicle], "crossing")
    assert note == "crossing 44.29-51 m outside the front wheelset's x range 60-70 m"
