"""A killed ``simulate`` never leaves an earlier run's output looking finished (issue 25):
``--out`` is cleared and marked RUNNING before any file is read; the marker goes when the
run ends (written, or failed with exit 2 or 3)."""

from __future__ import annotations

import pytest

import exudyn_turnout.cli.passage as cli_passage
from exudyn_turnout.cli.main import main
from exudyn_turnout.cli.passage import RUNNING_MARKER, safety_text

EARLIER = ("summary.json", "timeseries.csv", "forces.png", "safety.png")
ARGV = ["simulate", "--vehicle", "wheelset", "--layers", "2", "--x-start", "46.5", "--x-end", "48"]
ARGV += ["--no-plot"]


def _earlier_run(tmp_path):
    out = tmp_path / "run"
    out.mkdir()
    for name in EARLIER:
        (out / name).write_text("from an earlier run")
    return out


class Killed(BaseException):
    """Stands for SIGKILL / Ctrl-C: nothing in the command handles it."""


def _kill(*args, **kwargs):
    raise Killed


@pytest.mark.parametrize("where", ["turnout_from_args", "simulate_passage"])
def test_killed_run_leaves_no_finished_looking_output(tmp_path, monkeypatch, where):
    """Killed while reading the turnout file (the first second) or while running."""
    out = _earlier_run(tmp_path)
    monkeypatch.setattr(cli_passage, where, _kill)
    with pytest.raises(Killed):
        main([*ARGV, "--out", str(out)])
    names = sorted(p.name for p in out.iterdir())
    assert names == [RUNNING_MARKER], names
    assert "killed" in (out / RUNNING_MARKER).read_text()


def test_finished_run_removes_the_marker(tmp_path, capsys):
    out = _earlier_run(tmp_path)
    assert main([*ARGV, "--out", str(out)]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["summary.json", "timeseries.csv"]
    lines = capsys.readouterr().out.splitlines()
    assert lines[-1].startswith("safety limits"), lines


def test_bad_input_with_an_existing_out_leaves_it_empty(tmp_path, capsys):
    out = _earlier_run(tmp_path)
    assert main([*ARGV, "--route", "nowhere", "--out", str(out)]) == 2
    assert sorted(p.name for p in out.iterdir()) == []


def test_safety_text():
    assert safety_text({"safety_exceeded": []}) == "safety limits: none exceeded"
    summary = {
        "safety_exceeded": [
            {"wheel": "right wheel", "region": "crossing", "quantity": "Delta Q/Q0",
             "value": 0.92, "limit": 0.6, "x_m": 47.43},
            {"wheel": "wheelset ws2", "region": "switch", "quantity": "sum Y (2 m mean), N",
             "value": 80.3e3, "limit": 39.4e3, "x_m": 10.0},
        ]
    }  # fmt: skip
    text = safety_text(summary)
    assert text.startswith("safety limits exceeded: wheelset ws2, switch, sum Y (2 m mean) 80.3")
    assert "right wheel, crossing, Delta Q/Q0 0.92 > 0.6 at x = 47.43 m" in text
