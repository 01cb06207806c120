"""A study's serial start: what the calling process imports and reads before its workers run.

The start is the part of a study that more workers do not share (issue 24: 2 workers
>= 1.8x 1 worker needs it short), so it loads nothing a case does not need.
"""

import subprocess
import sys
from pathlib import Path

from exudyn_turnout.studies import load_study

#: What ``exudyn-turnout study`` imports before its pool forks (the command, the studies,
#: a passage of the profile contact on the co-running track: ``run_case``'s imports).
_START = (
    "exudyn_turnout.cli.main",
    "exudyn_turnout.cli.study",
    "exudyn_turnout.studies",
    "exudyn_turnout.passage.run",
    "exudyn_turnout.passage.corunning_track",
    "exudyn_turnout.passage.contact.profile",
)


def test_the_start_does_not_import_scipy_interpolate():
    """scipy.interpolate (~0.03 s CPU) is imported only where rail sections are built, which
    a passage whose route tables are stored never does; a fresh interpreter, since this test
    process may have imported it for another test."""
    code = (
        "import sys\n"
        + "".join(f"import {name}\n" for name in _START)
        + "print('scipy.interpolate' in sys.modules, 'scipy.optimize' in sys.modules)\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=120
    )
    # scipy.optimize is imported (the plan's brentq, needed by every case): the check is live
    assert done.stdout.split() == ["False", "True"], done.stderr[-2000:]


def test_a_dotted_profile_factor_keys_the_profile_file_it_names(tmp_path: Path):
    """A factor that renames the turnout's rail profile to a file beside it: the case key
    hashes that file's content (read from the edited file's data, not the text parsed again),
    so a changed profile file gives a new key."""
    from exudyn_turnout.inputs.turnout import default_turnout_path
    from exudyn_turnout.wheel_rail.data import data_dir

    (tmp_path / "t.toml").write_text(
        default_turnout_path().read_text(encoding="utf-8"), encoding="utf-8"
    )
    rail = (data_dir() / "profiles" / "MBench_UIC60_v3.prr").read_bytes()
    (tmp_path / "my_rail.prr").write_bytes(rail)
    (tmp_path / "study.toml").write_text(
        '[study]\nname = "profile factor"\n\n[base]\nturnout = "t.toml"\n'
        'contact = "profile"\nroute = "through"\nx_start = 44.0\nx_end = 45.0\n\n'
        '[factors]\n"turnout.wheel_rail.profile" = ["my_rail.prr", "MBench_UIC60_v3.prr"]\n',
        encoding="utf-8",
    )
    before = [c.key for c in load_study(tmp_path / "study.toml").cases()]
    (tmp_path / "my_rail.prr").write_bytes(rail + b"\n")
    after = [c.key for c in load_study(tmp_path / "study.toml").cases()]
    assert after[0] != before[0]  # the edited file names my_rail.prr: its content counts
    assert after[1] == before[1]  # the other names the packaged profile, not beside t.toml


def test_a_case_runs_with_the_turnout_the_check_loaded(tmp_path: Path):
    """``Study.cases`` loads each distinct turnout file once to check it; the cases' runs in
    this process (and workers forked from it) take that turnout instead of loading the same
    text again, and a text the check did not load is not found."""
    from exudyn_turnout.studies.study import checked_turnout

    (tmp_path / "study.toml").write_text(
        '[study]\nname = "two pads"\n\n[base]\ncontact = "profile"\nroute = "through"\n'
        'x_start = 44.0\nx_end = 45.0\n\n[factors]\n"turnout.rail_types.stock.pad.k_z" = '
        "[101e6, 139e6]\n",
        encoding="utf-8",
    )
    cases = load_study(tmp_path / "study.toml").cases()
    loaded = [checked_turnout(c.turnout_name, c.turnout_text) for c in cases]
    assert all(t is not None for t in loaded)
    assert loaded[0] is not loaded[1]  # two files (pad stiffness 101 and 139 MN/m)
    assert loaded[0].rail_types["stock"].pad.k_z == 101e6
    assert loaded[1].rail_types["stock"].pad.k_z == 139e6
    assert checked_turnout(cases[0].turnout_name, cases[0].turnout_text + "\n") is None
