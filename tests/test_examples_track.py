"""examples/co_running_receptance.py runs into a temporary directory (layout of Figs 5, 6).

Checks that both figures and the eight CSVs (2 rails x 2 directions x 2 models) are written
and that the printed table lists both models at both positions; the numbers themselves are
tested in test_receptance.py.
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
    written = example.main(tmp_path / "out")
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


def test_example_module_does_no_work_on_import(example, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    importlib.util.spec_from_file_location("again", EXAMPLE).loader.exec_module(
        type(example)("again")
    )
    assert list(tmp_path.iterdir()) == []
