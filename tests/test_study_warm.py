"""A study's serial work in the calling process, which the workers wait for (issue 24):
warming a process that already ran a kind of case, and writing the same modified file again.

Reference values: counts from the study's own definition (kinds of case, distinct edits).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from exudyn_turnout.studies import load_study, run_case
from exudyn_turnout.studies.run import warm_up

#: 4 cases of 3 m, the height-table contact (cheap); a pad stiffness no other test uses, so
#: that its kinds are new to this process.
STUDY = """
[base]
contact = "height-table"
x_start = 45.0
x_end = 48.0
time_step = 1e-4
output_step = 1e-3

[factors]
speed_kmh = [80.0, 100.0]
"turnout.rail_types.stock.pad.k_z" = [{k_a}, {k_b}]
"""


def _cases(tmp_path: Path, k_a: float, k_b: float):
    path = tmp_path / "study.toml"
    path.write_text(STUDY.format(k_a=k_a, k_b=k_b), encoding="utf-8")
    return load_study(path).cases()


def test_a_process_is_warmed_once_per_kind(tmp_path):
    """Two kinds (two turnout files, one track): warmed once; a process that ran a case of a
    kind (a serial study before a pool is made from it) is not warmed for that kind again."""
    cases = _cases(tmp_path, 101.234e6, 141.234e6)
    assert warm_up(cases) == 2
    assert warm_up(cases) == 0
    others = _cases(tmp_path, 102.345e6, 142.345e6)
    record = run_case(others[0])  # kind of k_z = 102.345e6
    assert record["status"] == "ok", record["error"]
    assert warm_up(others) == 1  # only the kind of k_z = 142.345e6 is new
    assert warm_up(others, kinds=5) == 0


def test_each_modified_file_is_written_once(tmp_path, monkeypatch):
    """2 speeds x 2 pad stiffnesses: two modified turnout files, each written once."""
    from exudyn_turnout.studies import study as study_module

    calls = []
    original = study_module.dumps

    def counted(data):
        calls.append(1)
        return original(data)

    monkeypatch.setattr(study_module, "dumps", counted)
    cases = _cases(tmp_path, 100e6, 140e6)
    assert len(cases) == 4 and len(calls) == 2
    assert cases[0].turnout_text == cases[2].turnout_text != cases[1].turnout_text


@pytest.mark.slow
def test_spawned_workers_are_warmed_though_this_process_is_warm(tmp_path):
    """This process's notes do not hold for a new interpreter: a spawned worker is warmed
    for the kinds by its initializer even when this process has run them all."""
    import multiprocessing

    from exudyn_turnout.studies.run import process_pool

    if "spawn" not in multiprocessing.get_all_start_methods():
        pytest.skip("no spawn start method here")
    cases = _cases(tmp_path, 103.456e6, 143.456e6)
    warm_up(cases)
    assert warm_up(cases) == 0  # warm here
    with process_pool(cases, 1, "spawn") as pool:
        assert pool.submit(warm_up, cases).result() == 0  # warm there too, by the initializer
