"""A study's serial work in the calling process, which the workers wait for (issue 24):
warming a process that already ran a kind of case, and writing the same modified file again.

Reference values: counts from the study's own definition (kinds of case, distinct edits).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from exudyn_turnout.studies import load_study, run_case
from exudyn_turnout.studies.run import warm_up

#: 3 m cases, the height-table contact (cheap): 2 check-rail clearances (what the contact
#: tables are built from; values no other test uses, so that the kinds are new to this
#: process) x 2 pad stiffnesses (the track only: the same kind) x 2 speeds.
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


def _cases(tmp_path: Path, k_a: float, k_b: float, c_a: float | None = None, c_b: float = 0.0):
    """The study's cases; without ``c_a`` the packaged clearance only."""
    text = STUDY.format(k_a=k_a, k_b=k_b)
    if c_a is not None:
        text += f'"turnout.check_rail.clearance" = [{c_a}, {c_b}]\n'
    path = tmp_path / "study.toml"
    path.write_text(text, encoding="utf-8")
    return load_study(path).cases()


def test_a_process_is_warmed_once_per_kind(tmp_path):
    """Two kinds (two check-rail clearances; the pad stiffness does not make a kind: files that
    differ in the track only share the contact tables): warmed once; a process that ran a
    case of a kind (a serial study before a pool is made from it) is not warmed for that
    kind again."""
    cases = _cases(tmp_path, 101e6, 141e6, 0.0041234, 0.0042234)
    assert len({c.turnout_text for c in cases}) == 4  # 4 turnout files, 2 kinds
    assert warm_up(cases) == 2
    assert warm_up(cases) == 0
    others = _cases(tmp_path, 101e6, 141e6, 0.0043456, 0.0044456)
    record = run_case(others[0])  # kind of clearance 0.0043456
    assert record["status"] == "ok", record["error"]
    assert warm_up(others) == 1  # only the kind of clearance 0.0044456 is new
    assert warm_up(others, kinds=5) == 0


def test_each_modified_file_is_written_once(tmp_path, monkeypatch):
    """2 speeds x 2 pad stiffnesses (x 1 clearance): two modified turnout files, each written
    once."""
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
    cases = _cases(tmp_path, 103e6, 143e6, 0.0045678, 0.0046678)
    warm_up(cases)
    assert warm_up(cases) == 0  # warm here
    with process_pool(cases, 1, "spawn") as pool:
        assert pool.submit(warm_up, cases).result() == 0  # warm there too, by the initializer


def test_cases_are_handed_out_by_contact_tables_longest_first(tmp_path):
    """3 speeds x 2 check-rail clearances x 2 pad stiffnesses (4 turnout files, 2 sets of
    contact tables): the cases of a clearance together (its pad stiffnesses mixed: they share
    the tables), the slowest (longest) speed first within each; every case once."""
    from exudyn_turnout.studies.run import estimated_cost, hand_out_order
    from exudyn_turnout.studies.study import study_from_dict

    study = study_from_dict(
        {
            "base": {"x_start": 40.0, "x_end": 50.0},
            "factors": {
                "speed_kmh": [100.0, 50.0, 80.0],
                "turnout.check_rail.clearance": [0.004, 0.005],
                "turnout.rail_types.stock.pad.k_z": [100e6, 140e6],
            },
        }
    )
    cases = study.cases()
    order = hand_out_order(cases)
    assert sorted(c.index for c in order) == list(range(12))
    clearance = [c.inputs["turnout.check_rail.clearance"] for c in order]
    assert clearance in ([0.004] * 6 + [0.005] * 6, [0.005] * 6 + [0.004] * 6)
    assert [c.inputs["speed_kmh"] for c in order] == [50.0] * 2 + [80.0] * 2 + [100.0] * 2 + [
        50.0
    ] * 2 + [80.0] * 2 + [100.0] * 2
    costs = [estimated_cost(c) for c in order]
    assert costs[0] == pytest.approx(2 * costs[-1])  # 10 m at 50 km/h: twice the steps


@pytest.mark.slow
def test_a_serial_study_loads_a_routes_contact_tables_once(tmp_path, monkeypatch):
    """5 pad stiffnesses x 2 tracks: 5 turnout files, more than the 4 routes a process keeps
    in memory. In case order (the stiffness varies fastest) each case loaded its tables
    again; by file, once per file (5); keyed by what the tables are built from (the pad
    stiffness is not), once."""
    from exudyn_turnout.passage.contact import route_cache
    from exudyn_turnout.studies import run_study
    from exudyn_turnout.wheel_rail import turnout_sections

    calls = []
    original = turnout_sections.route_contact_tables

    def counted(*args, **kwargs):
        calls.append(args[1])
        return original(*args, **kwargs)

    monkeypatch.setattr(turnout_sections, "route_contact_tables", counted)
    monkeypatch.setattr(route_cache, "_RECENT", route_cache._RecentContacts())  # none in memory yet
    # nor a packed route on disk
    monkeypatch.setattr(route_cache, "_packed_cache_path", lambda key, d=None: tmp_path / "r.npz")
    path = tmp_path / "study.toml"
    path.write_text(
        """
[base]
contact = "profile"
x_start = 44.0
x_end = 44.3

[factors]
track = ["2-layer", "3-layer"]
"turnout.rail_types.stock.pad.k_z" = [100.5e6, 110.5e6, 120.5e6, 130.5e6, 140.5e6]
""",
        encoding="utf-8",
    )
    result = run_study(path, workers=1, out=tmp_path / "out")
    assert result.failed == 0, result.table["error"]
    assert len(calls) == 1


@pytest.mark.parametrize("register", [False, True])
def test_the_study_command_freezes_the_objects_at_exit(register):
    """The exit's collection of every object left (0.3-0.6 s of a study's wall time) is
    skipped: the command registers ``gc.freeze`` to run at exit (seen by a handler that runs
    after it, in a fresh interpreter); nothing is frozen before."""
    import subprocess
    import sys

    code = (
        "import atexit, gc\n"
        "atexit.register(lambda: print('frozen at exit', gc.get_freeze_count()))\n"
        "from exudyn_turnout.cli.study import _quick_exit\n"
        f"if {register}:\n"
        "    _quick_exit()\n"
        "    _quick_exit()\n"
        "print('frozen before', gc.get_freeze_count())\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    before, at_exit = (int(line.split()[-1]) for line in done.stdout.splitlines())
    assert before == 0
    assert (at_exit > 0) == register


def test_the_transfer_nodes_design_wheel_is_the_gridded_wheel_to_the_bit():
    """The rail bodies' transfer nodes use the S1002 wheel's heights only: gridded without its
    Savitzky-Golay slopes (``s1002_surface``), they must equal ``s1002_wheel``'s ``s`` and
    ``z`` bit for bit (reference: the same profile file and grid step), at the default grid
    step and another."""
    from exudyn_turnout.wheel_rail.data import s1002_surface, s1002_wheel
    from exudyn_turnout.wheel_rail.geometry import WheelsetSetup

    for step in (1e-4, 2.5e-4):
        wheel = s1002_wheel(WheelsetSetup(grid_step=step))
        s, z = s1002_surface(step)
        assert s.dtype == wheel.s.dtype and z.dtype == wheel.z.dtype
        assert s.tobytes() == wheel.s.tobytes()
        assert z.tobytes() == wheel.z.tobytes()


def test_a_routes_rail_bodies_need_no_scipy_signal():
    """Every study process (and every worker of a spawned pool) builds its route's rail
    bodies before its first case; their transfer nodes imported ``scipy.signal`` for the
    design wheel's slopes, which they do not use (0.3-0.6 s of serial start that no number
    of workers shares: issue 24's study scaling). In a fresh interpreter, after both routes'
    bodies, ``scipy.signal`` must not be loaded."""
    import subprocess
    import sys

    code = (
        "import sys\n"
        "from exudyn_turnout.inputs.turnout import load_turnout\n"
        "from exudyn_turnout.wheel_rail.turnout_sections import route_rail_bodies\n"
        "turnout = load_turnout()\n"
        "bodies = [route_rail_bodies(turnout, r) for r in ('through', 'diverging')]\n"
        "assert all(bodies)\n"
        "print('scipy.signal' in sys.modules)\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=False, timeout=120
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip() == "False"


def test_the_study_command_reads_the_cases_once(tmp_path, monkeypatch, capsys):
    """``exudyn-turnout study`` made the cases (every file loaded, edited, hashed: 0.06 s of
    serial start for the performance table's study) to check them, and ``run_study`` made them
    again: once now; a bad value still stops it with one line (exit 2) before any case
    is stored."""
    from exudyn_turnout.cli.main import main
    from exudyn_turnout.studies.study import Study

    calls = []
    original = Study.cases

    def counted(self):
        calls.append(1)
        return original(self)

    monkeypatch.setattr(Study, "cases", counted)
    text = STUDY.format(k_a=100e6, k_b=140e6).replace("[80.0, 100.0]", "[100.0]")
    path = tmp_path / "study.toml"
    path.write_text(text.replace("x_end = 48.0", "x_end = 45.5"), encoding="utf-8")
    out = tmp_path / "out"
    assert main(["study", str(path), "--out", str(out), "--workers", "1", "--no-plot"]) == 0
    assert "2 cases, 2 computed" in capsys.readouterr().out
    assert len(calls) == 1
    bad = tmp_path / "bad.toml"
    bad.write_text(STUDY.format(k_a=100e6, k_b=-1e8), encoding="utf-8")
    assert main(["study", str(bad), "--out", str(tmp_path / "o"), "--workers", "1"]) == 2
    err = capsys.readouterr().err.strip()
    assert "k_z" in err and "\n" not in err
    assert not (tmp_path / "o" / "cases").exists()
