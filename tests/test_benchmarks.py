"""The benchmarks' shared parts: the yardstick's bookkeeping and the README's performance table.

No timing is asserted here (timings live in ``benchmarks/``): the yardstick is replaced by
a function that does nothing measurable, and the table is written from given numbers.
"""

from __future__ import annotations

import importlib
import math
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture
def bench(monkeypatch):
    """The modules of ``benchmarks/`` (a folder of scripts, not a package)."""
    monkeypatch.syspath_prepend(str(ROOT / "benchmarks"))
    return importlib.import_module("yardstick"), importlib.import_module("performance_table")


def test_readme_has_the_table_markers_once_in_the_performance_section(bench):
    _, table = bench
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    assert text.count(table.START) == 1 and text.count(table.END) == 1
    performance = text.index("## Performance")
    assert performance < text.index(table.START) < text.index(table.END)
    assert text.index(table.END) < text.index("## Development")
    # the README names the command that rewrites the table
    assert table.COMMAND in text


def test_table_written_from_given_numbers(bench):
    yardstick, table = bench
    info = {
        "cpu": "Test CPU",
        "cores": 2,
        "load_average": (1.5, 2.25, 3.0),
        "system": "Linux",
        "python": "3.11.7",
        "numpy": "2.4",
        "scipy": "1.17",
        "exudyn": "1.13.6",
        "numba": "0.68",
        "date": "2026-12-02 03:00 UTC",
    }
    rows = [
        table.Row("single wheelset, 3-layer", "1.29", "1.02", "0.44", "3.01", "a note"),
        table.Row("study", "40.0 vs 70.0", "80 vs 70", "", "90.0 vs 160.0", "speed-up 1.75"),
    ]
    block = table.render_table(rows, info, 0.4321, 0.1502, quick=False)
    lines = block.splitlines()
    assert "Test CPU, 2 cores, load average 1.50, 2.25, 3.00" in lines[0]
    assert "exudyn 1.13.6" in lines[0] and "2026-12-02 03:00 UTC" in lines[0]
    assert "0.432 s wall, 0.150 s CPU (medians)" in lines[0] and "--quick" not in lines[0]
    assert lines[2] == "| case | wall s | CPU s | x real time | yardstick units | note |"
    assert lines[4] == "| single wheelset, 3-layer | 1.29 | 1.02 | 0.44 | 3.01 | a note |"
    assert lines[5] == "| study | 40.0 vs 70.0 | 80 vs 70 |  | 90.0 vs 160.0 | speed-up 1.75 |"
    assert "--quick" in table.render_table(rows, info, 0.4, 0.1, quick=True).splitlines()[0]
    readme = f"# x\n\n## Performance\n{table.START}\nold\n{table.END}\n\n## Development\n"
    new = table.replace_table(readme, block)
    assert "old" not in new and block in new
    assert new.startswith("# x\n\n## Performance\n") and new.endswith("\n\n## Development\n")
    assert table.replace_table(new, block) == new  # rewriting is idempotent
    with pytest.raises(ValueError, match="expected one"):
        table.replace_table("# no markers\n", block)
    with pytest.raises(ValueError, match="comes before"):
        table.replace_table(f"{table.END}\n{table.START}\n", block)


def test_yardstick_interleaves_and_takes_the_median_ratio(bench):
    yardstick, _ = bench
    order = []
    stick = yardstick.Yardstick(lambda: order.append("y"))
    timing = stick.measure(lambda: order.append("c") or 7, repeats=3)
    # warm-up, then yardstick / case / yardstick / case ... / yardstick
    assert order == ["c", "y", "c", "y", "c", "y", "c", "y"]
    assert timing.repeats == 3 and len(timing.samples) == 3 and len(stick.times) == 4
    assert len(stick.cpu_times) == 4 and timing.cpu_seconds >= 0.0
    assert timing.result == 7 and timing.units > 0 and math.isfinite(timing.units)
    with pytest.raises(ValueError, match="repeats"):
        stick.measure(lambda: None, repeats=0)


def test_yardstick_workload_is_fixed(bench):
    yardstick, _ = bench
    # the same work every time (same checksum), independent of this package
    source = (ROOT / "benchmarks" / "yardstick.py").read_text(encoding="utf-8")
    assert "exudyn_turnout" not in source.split('"""', 2)[2]
    assert yardstick.workload() == yardstick.workload()
    info = yardstick.machine()
    assert {"cpu", "cores", "load_average", "python", "numpy", "exudyn", "date"} <= set(info)
    assert "cores" in yardstick.machine_line(info)


def test_table_study_is_a_valid_profile_contact_study(bench):
    _, table = bench
    from exudyn_turnout.studies.study import study_from_dict

    for quick, n in ((True, 4), (False, 24)):
        study = study_from_dict(tomllib.loads(table.study_text(quick)))
        assert len(study.combinations()) == n
        assert study.base["contact"] == "profile"


def test_versus_passage_rejects_a_folder_without_the_package(monkeypatch, tmp_path, capsys):
    """benchmarks/versus_passage.py: one error line and exit 2, no run, for bad arguments."""
    monkeypatch.syspath_prepend(str(ROOT / "benchmarks"))
    versus = importlib.import_module("versus_passage")
    assert versus.main(["--versus", str(tmp_path)]) == 2
    assert capsys.readouterr().err.strip().startswith("error: --versus DIR")
    assert versus.main(["--versus", str(ROOT), "--cases", "nope"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "unknown case" in err[0]


def test_main_job_commands_do_not_import_the_working_directory(monkeypatch):
    """bench_main_job runs ``python -P -m exudyn_turnout``: with ``-m`` alone the working
    directory's package came first on sys.path, so ``--versus`` run from inside a checkout
    timed that checkout twice (found in session 11)."""
    monkeypatch.syspath_prepend(str(ROOT / "benchmarks"))
    job = importlib.import_module("bench_main_job")
    argv = job.command("a", Path("out"))
    assert argv[1:4] == ["-P", "-m", "exudyn_turnout"]
    table = importlib.import_module("performance_table")
    assert table._cli("simulate")[1:3] == ["-P", "-m"]
