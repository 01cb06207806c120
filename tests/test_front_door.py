"""The front door: ``import exudyn_turnout as et`` gives the pipeline, the README's Python
quick start runs, result objects plot and save, ``draw`` makes the model's figures."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import matplotlib
import numpy as np
import pytest

import exudyn_turnout as et
from exudyn_turnout.cli.main import main

matplotlib.use("Agg")

README = Path(__file__).resolve().parents[1] / "README.md"


def test_import_is_light():
    """Importing the package loads neither Exudyn nor matplotlib (they load on first use)."""
    code = (
        "import sys, exudyn_turnout as et; "
        "print('exudyn' in sys.modules, 'matplotlib' in sys.modules)"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout.split()
    assert out == ["False", "False"]


def test_every_public_name_resolves():
    for name in et.__all__:
        assert getattr(et, name) is not None, name
    with pytest.raises(AttributeError):
        et.no_such_name  # noqa: B018


def test_readme_python_quick_start_runs(tmp_path, monkeypatch, capsys):
    block = re.search(r"## In Python\n\n```python\n(.*?)```", README.read_text(), re.S)
    assert block is not None
    monkeypatch.chdir(tmp_path)
    exec(compile(block.group(1), "README.md", "exec"), {})
    printed = capsys.readouterr().out.splitlines()
    assert float(printed[0]) == pytest.approx(
        et.co_running_parameters(et.load_turnout(), zone=2, layers=3).at(47.2)["k_rt2_z"]
    )
    assert printed[1].startswith("Receptance(3-layer, r2 vertical at x = 47.2 m")
    # the default vehicle: the full Manchester vehicle, its front wheelset's forces
    assert printed[2].startswith(
        "PassageResult(3-layer, Manchester benchmark vehicle 1 (front wheelset), "
        "route 'through', 100 km/h, x 40 to 50"
    )
    assert float(printed[3]) > 1.2 * 54.5e3  # an impact at the nose
    assert (tmp_path / "forces.png").read_bytes()[:4] == b"\x89PNG"
    summary = json.loads((tmp_path / "passage_out" / "summary.json").read_text())
    assert summary["peak_Fz_crossing_N"] == pytest.approx(float(printed[3]), rel=1e-6)
    series = np.load(tmp_path / "passage_out" / "timeseries.npz")
    assert series["x_m"][0] == pytest.approx(40.0)


def test_track_argument_selects_the_model(turnout):
    settings = et.PassageSettings(x_start=-5.0, x_end=-4.9)
    two = et.simulate_passage(turnout, settings, track="2-layer", vehicle="wheelset")
    assert two.model == "2-layer" and two.settings.layers == 2
    with pytest.raises(et.PassageError, match="track must be one of 2-layer, 3-layer, fe"):
        et.simulate_passage(turnout, settings, track="4-layer", vehicle="wheelset")


def test_receptance_plots_and_saves(turnout, tmp_path):
    h = et.co_running_receptance(
        turnout, 2, "r1", "vertical", x=-3.0, frequencies=et.log_frequencies(1.0, 100.0, 20)
    )
    fig, axes = h.plot()
    assert axes is not None
    h.save(tmp_path / "h.csv")
    back = et.Receptance.from_csv(tmp_path / "h.csv")
    assert np.allclose(back.H, h.H, rtol=1e-7)
    matplotlib.pyplot.close("all")


def test_draw_section_writes_the_figure(tmp_path, capsys):
    out = tmp_path / "section.png"
    assert main(["draw", "section", "--zone", "2", "--out", str(out)]) == 0
    assert out.read_bytes()[:4] == b"\x89PNG"
    assert "zone 2" in capsys.readouterr().out
    assert main(["draw", "section", "--zone", "9", "--out", str(out)]) == 2
    assert main(["draw", "section", "--zone", "2", "--out", str(tmp_path / "s.jpg")]) == 2
    err = capsys.readouterr().err
    assert "zone 9 does not exist" in err and "must end in .png" in err
