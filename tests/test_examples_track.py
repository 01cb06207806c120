"""examples/co_running_receptance.py runs into a temporary directory (layout of Figs 5, 6).

Checks that both figures and the eight CSVs (2 rails x 2 directions x 2 models) are written
and that the printed table lists both models at both positions; with the FE curves (a few
frequencies), four more CSVs and each model's static stiffness against the FE's. The
numbers themselves are tested in test_receptance.py and the FE tests.
"""

import importlib.util
from pathlib import Path

import pytest

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "co_running_receptance.py"


@pytest.fixture(scope="module")
def example():
    spec = importlib.util.spec_from_file_location("co_running_receptance_example", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)  # only definitions run: the script's work is under __main__
    return module


def test_example_writes_figures_and_csvs(example, tmp_path, capsys):
    written = example.main(tmp_path / "out", fe_points=None)
    printed = capsys.readouterr().out
    assert [p.name for p in written] == [
        "fig5_vertical_receptance.png",
        "fig6_lateral_receptance.png",
    ]
    for p in written:
        assert p.read_bytes()[:4] == b"\x89PNG"
    csvs = sorted(p.name for p in (tmp_path / "out").glob("*.csv"))
    assert len(csvs) == 8 and "crossing_rail_vertical_3-layer.csv" in csvs
    # x of the crossing case: 0.267 m after the plan's nose tip, 46.898 m (test_geometry.py)
    for case in ("switch rail (x = 4.0 m)", "crossing rail (x = 47.2 m)"):
        assert f"{case}" in printed
    assert printed.count("2-layer") == 2 and printed.count("3-layer") == 2


@pytest.mark.slow
def test_example_overlays_the_fe(example, tmp_path, capsys):
    out = tmp_path / "out"
    example.main(out, fe_points=5)
    printed = capsys.readouterr().out
    fe = sorted(p.name for p in out.glob("*_FE.csv"))
    assert fe == [
        "crossing_rail_lateral_FE.csv",
        "crossing_rail_vertical_FE.csv",
        "switch_rail_lateral_FE.csv",
        "switch_rail_vertical_FE.csv",
    ]
    rows = (out / "switch_rail_vertical_FE.csv").read_text().splitlines()
    assert rows[0] == "frequency_hz,real,imag,magnitude" and len(rows) == 1 + 5
    assert printed.count("static stiffness against the FE's") == 4


def test_example_module_does_no_work_on_import(example, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    importlib.util.spec_from_file_location("again", EXAMPLE).loader.exec_module(
        type(example)("again")
    )
    assert list(tmp_path.iterdir()) == []
