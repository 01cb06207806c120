"""Turnout-file validation: every bad field gives one message naming file and field.

Each case edits the packaged file's text (one replacement) and checks the loader's
message and the CLI's exit code 2 with a one-line message on stderr.
"""

import re
import subprocess
import sys

import pytest

from exudyn_turnout.cli.main import main
from exudyn_turnout.inputs.turnout import TurnoutFileError, default_turnout_path, load_turnout

PACKAGED = default_turnout_path().read_text(encoding="utf-8")

CASES = [
    # (description, old text, new text, expected message fragment)
    (
        "negative spacing",
        "spacing = 0.6",
        "spacing = -0.6",
        "sleeper.spacing must be > 0, got -0.6",
    ),
    (
        "zero sleeper mass density",
        "density = 2400.0",
        "density = 0.0",
        "sleeper.density must be > 0, got 0",
    ),
    (
        "negative pad stiffness",
        "pad = { k_z = 120e6, c_z = 25e3, k_y = 25e6, c_y = 10e3 }\nlateral_factor",
        "pad = { k_z = -120e6, c_z = 25e3, k_y = 25e6, c_y = 10e3 }\nlateral_factor",
        "rail_types.stock.pad.k_z must be > 0, got -1.2e+08",
    ),
    ("zero rail area", "area = 0.023", "area = 0.0", "rail_types.crossing.area must be > 0, got 0"),
    (
        "zero extra mass",
        "m_0 = 2.5                 #",
        "m_0 = 0.0                 #",
        "extra_layer.m_0 must be > 0",
    ),
    (
        "missing field",
        "s_b_z = 20e6     # N/m^2, vertical stiffness per unit sleeper length\n",
        "",
        "ballast.s_b_z is missing",
    ),
    (
        "zones overlap",
        "x_start = 44.29\nx_end = 51.0",
        "x_start = 40.0\nx_end = 51.0",
        "zones 1 and 2 overlap",
    ),
    (
        "zones leave a gap",
        "x_start = 51.0\nx_end = 60.0",
        "x_start = 52.0\nx_end = 60.0",
        "zones 2 and 3 leave a gap",
    ),
    (
        "active rail undefined",
        'active_rails = ["r1", "r4"]',
        'active_rails = ["r1", "r4", "r5"]',
        "zones[3].active_rails names rail 'r5'",
    ),
    (
        "rail type undefined",
        'r2 = "crossing"',
        'r2 = "frog"',
        "zones[2].rail_types.r2 names rail type 'frog'",
    ),
    (
        "polynomial range inverted",
        "x_min = 0.0\nx_max = 22.0",
        "x_min = 22.0\nx_max = 0.0",
        "stiffness_profiles.K_sw range is inverted",
    ),
    (
        "bad Table 2 formula",
        'k_rt2_z = "369e6 * Delta_z"',
        'k_rt2_z = "369e6 * Delta_q"',
        "published.zone1.k_rt2_z must be a number",
    ),
    (
        "sleeper length table not increasing",
        "length = { x = [8.0, 20.0,",
        "length = { x = [20.0, 8.0,",
        "sleeper.length.x must be increasing",
    ),
    ("not TOML", "[turnout]", "[turnout", "is not valid TOML"),
]


def _write(tmp_path, old, new):
    assert old in PACKAGED, f"test case text not in the packaged file: {old!r}"
    path = tmp_path / "uic60.toml"
    path.write_text(PACKAGED.replace(old, new, 1), encoding="utf-8")
    return path


@pytest.mark.parametrize("what,old,new,message", CASES, ids=[c[0] for c in CASES])
def test_loader_names_file_and_field(tmp_path, what, old, new, message):
    path = _write(tmp_path, old, new)
    with pytest.raises(TurnoutFileError) as err:
        load_turnout(path)
    assert str(err.value).startswith("uic60.toml: ")
    assert message in str(err.value)


@pytest.mark.parametrize(
    "what,old,new,message", CASES[:3] + CASES[6:8], ids=[c[0] for c in CASES[:3] + CASES[6:8]]
)
def test_cli_exits_2_with_one_line(tmp_path, capsys, what, old, new, message):
    path = _write(tmp_path, old, new)
    assert main(["params", "--zone", "1", "--turnout", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err


def test_missing_file(tmp_path, capsys):
    assert main(["params", "--zone", "1", "--turnout", str(tmp_path / "none.toml")]) == 2
    assert "none.toml: cannot be read" in capsys.readouterr().err


def test_packaged_file_loads_in_si_units():
    t = load_turnout()
    assert t.sleeper.spacing == 0.6 and t.rail_types["stock"].youngs_modulus == 207e9
    assert (t.x_min, t.x_max) == (-5.0, 60.0)
    assert [z.active_rails for z in t.zones] == [
        ("r1", "r2", "r4"),
        ("r1", "r2", "r3", "r4"),
        ("r1", "r4"),
    ]


def test_installed_console_script_reports_bad_input():
    """The entry point from setup.cfg: exit 2, one line, no traceback."""
    proc = subprocess.run(
        [sys.executable, "-m", "exudyn_turnout.cli.main", "params", "--zone", "9"],
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr and re.fullmatch(r"error: .*zone 9.*\n", proc.stderr)
