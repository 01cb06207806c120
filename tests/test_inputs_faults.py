"""Inputs that issue 25 found accepted (or ending in a traceback / exit 3): one line, exit 2.

Each case edits a packaged file (turnout, vehicle, fitted set, profile), runs the command
line through :func:`exudyn_turnout.cli.main.main` and asserts exit 2 with a single line on
stderr naming the file and the field or fault, and no traceback. The accepted limiting
case (an undamped pad, c_z = 0) and the warnings (a fitted file without its turnout hash)
follow the table.
"""

import math
import re

import pytest

from exudyn_turnout.cli.main import main
from exudyn_turnout.inputs.turnout import default_turnout_path, load_turnout
from exudyn_turnout.inputs.vehicle import default_vehicle_path
from exudyn_turnout.wheel_rail.data import profile_path

TURNOUT = default_turnout_path().read_text(encoding="utf-8")
VEHICLE = default_vehicle_path().read_text(encoding="utf-8")
FITTED_PATH = default_turnout_path().with_name("uic60_760_1_15_fitted.toml")
FITTED = FITTED_PATH.read_text(encoding="utf-8")
EW54 = default_turnout_path().with_name("ew54_190_1_9.toml")


def _sub(text: str, pattern: str, repl: str) -> str:
    new, n = re.subn(pattern, repl, text, count=1, flags=re.M | re.S)
    assert n == 1, f"pattern not in the packaged file: {pattern!r}"
    return new


def _old_format(text: str) -> str:
    """The turnout file as it was before the contacts listed their sections (0.2.0)."""
    return re.sub(r"^sections = \[.*?\]\n(?=\n|\[)", "", text, flags=re.M | re.S)


def _one_line_exit_2(argv, capsys, *fragments):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    assert code == 2, err
    assert err.count("\n") == 1 and err.startswith("error: "), err
    assert "Traceback" not in err
    for fragment in fragments:
        assert fragment in err, err
    return err


PARAMS = ["params", "--zone", "1", "--turnout"]

# (id, edit of the turnout file, fragments of the message)
TURNOUT_CASES = [
    (
        "old format (contacts without sections)",
        _old_format,
        ("routes.through.contacts[0].sections is missing", "previous format"),
    ),
    (
        "misspelled section",
        lambda t: _sub(t, r"^\[wheel_rail\]$", "[wheel_rails]"),
        ("[wheel_rails] is not a section", "did you mean 'wheel_rail'"),
    ),
    (
        "misspelled key",
        lambda t: _sub(t, r"^(\[sleeper\]\n)density", r"\1densty"),
        ("sleeper.densty is not a key", "did you mean 'density'"),
    ),
    (
        "regions without crossing",
        lambda t: _sub(t, r"^(\[regions\].*?)^crossing = [^\n]*\n", r"\1"),
        ("regions.crossing is missing",),
    ),
    (
        "contact on an inactive rail",
        lambda t: _sub(t, r"check = \[44\.29, 51\.0\]", "check = [40.0, 51.0]"),
        ("routes.through.contacts[5]", "zone 1 has no such active rail"),
    ),
    (
        "negative pad damping",
        lambda t: _sub(t, r"c_z = 25e3", "c_z = -25e3"),
        ("rail_types.stock.pad.c_z must be >= 0",),
    ),
]


@pytest.mark.parametrize("what,edit,fragments", TURNOUT_CASES, ids=[c[0] for c in TURNOUT_CASES])
def test_bad_turnout_file_one_line_exit_2(tmp_path, capsys, what, edit, fragments):
    path = tmp_path / "bad.toml"
    path.write_text(edit(TURNOUT), encoding="utf-8")
    _one_line_exit_2(PARAMS + [path], capsys, "bad.toml", *fragments)


def test_old_format_in_validate_and_simulate(tmp_path, capsys):
    """Every command, validate included (was: PassageError traceback, exit 1)."""
    path = tmp_path / "old.toml"
    path.write_text(_old_format(TURNOUT), encoding="utf-8")
    for argv in (
        ["validate", "--quick", "--no-cache", "--out", tmp_path / "report", "--turnout", path],
        ["simulate", "--no-plot", "--out", tmp_path / "run", "--turnout", path],
        ["draw", "section", "--x", "10", "--out", tmp_path / "s.png", "--turnout", path],
    ):
        _one_line_exit_2(argv, capsys, "old.toml", "sections is missing")


def test_undamped_pad_is_accepted(tmp_path, capsys):
    """c_z = c_y = 0 in every pad: a limiting case (the ballast still damps), finite values."""
    path = tmp_path / "undamped.toml"
    text = re.sub(r"c_z = 25e3", "c_z = 0.0", TURNOUT)
    path.write_text(re.sub(r"c_y = (10e3|25e3)", "c_y = 0.0", text), encoding="utf-8")
    code = main(PARAMS + [str(path), "--format", "json"])
    out, err = capsys.readouterr()
    assert code == 0, err
    assert "nan" not in out.lower() and "inf" not in out.lower()
    turnout = load_turnout(path)
    assert all(t.pad.c_z == 0.0 for t in turnout.rail_types.values())


SIM = ["simulate", "--no-plot", "--x-start", "0", "--x-end", "1"]

# (id, edit of the vehicle file, fragments)
VEHICLE_CASES = [
    (
        "negative primary damping",
        lambda t: _sub(t, r"^c_z = 4\.0e3", "c_z = -4.0e3"),
        ("primary_suspension.c_z must be >= 0",),
    ),
    (
        "primary k_z 1e3 N/m",
        lambda t: _sub(t, r"^k_z = 1\.22e6", "k_z = 1.22e3"),
        ("primary_suspension.k_z must be >= 100000 N/m",),
    ),
    (
        "misspelled vehicle key",
        lambda t: _sub(t, r"^wheel_radius", "wheel_radus"),
        ("wheelset.wheel_radus is not a key", "did you mean 'wheel_radius'"),
    ),
    (
        "rail profile as the wheel profile",
        lambda t: _sub(t, r'^wheel_profile = "[^"]*"', 'wheel_profile = "MBench_UIC60_v3.prr"'),
        ("MBench_UIC60_v3.prr", "is a rail profile", "a wheel profile is needed"),
    ),
]


@pytest.mark.parametrize("what,edit,fragments", VEHICLE_CASES, ids=[c[0] for c in VEHICLE_CASES])
def test_bad_vehicle_file_one_line_exit_2(tmp_path, capsys, what, edit, fragments):
    path = tmp_path / "bad_vehicle.toml"
    path.write_text(edit(VEHICLE), encoding="utf-8")
    argv = SIM + ["--out", tmp_path / "run", "--vehicle", path]
    _one_line_exit_2(argv, capsys, *fragments)


def _cut_short(name: str, tmp_path):
    """A profile cut in the middle of its points (no point.end)."""
    lines = profile_path(name).read_text(encoding="utf-8").splitlines(keepends=True)
    start = next(i for i, line in enumerate(lines) if "point.begin" in line)
    end = next(i for i, line in enumerate(lines) if "point.end" in line)
    path = tmp_path / f"short_{name}"
    path.write_text("".join(lines[: (start + end) // 2]), encoding="utf-8")
    return path


def test_truncated_wheel_profile(tmp_path, capsys):
    """Was: exit 3 "static equilibrium not found", naming neither file nor fault."""
    short = _cut_short("MBench_S1002_v3.prw", tmp_path)
    vehicle = tmp_path / "vehicle.toml"
    vehicle.write_text(
        _sub(VEHICLE, r'^wheel_profile = "[^"]*"', f'wheel_profile = "{short.name}"'),
        encoding="utf-8",
    )
    argv = SIM + ["--out", tmp_path / "run", "--vehicle", vehicle]
    _one_line_exit_2(argv, capsys, "short_MBench_S1002_v3.prw", "cut short")


@pytest.mark.parametrize(
    "profile, fragments",
    [
        ("MBench_S1002_v3.prw", ("MBench_S1002_v3.prw", "is a wheel profile")),
        ("short", ("short_MBench_UIC60_v3.prr", "cut short")),
    ],
)
def test_bad_rail_profile(tmp_path, capsys, profile, fragments):
    """A wheel .prw as the rail profile ran with exit 0 (crossing peak 9 % low)."""
    if profile == "short":
        profile = _cut_short("MBench_UIC60_v3.prr", tmp_path).name
    path = tmp_path / "t.toml"
    text = _sub(TURNOUT, r'^profile = "MBench_UIC60_v3.prr"', f'profile = "{profile}"')
    path.write_text(text, encoding="utf-8")
    argv = SIM + ["--out", tmp_path / "run", "--turnout", path]
    _one_line_exit_2(argv, capsys, "t.toml", "wheel_rail.profile", *fragments)


def test_stock_set_length_zero(tmp_path, capsys):
    path = tmp_path / "t.toml"
    path.write_text(
        _sub(TURNOUT, r"^stock_set_length = 1\.0", "stock_set_length = 0.0"), encoding="utf-8"
    )
    argv = SIM + ["--out", tmp_path / "run", "--turnout", path]
    _one_line_exit_2(argv, capsys, "t.toml", "stock_set_length must be > 0")


def test_irregularity_outside_the_turnout(tmp_path, capsys):
    argv = SIM + ["--out", tmp_path / "run", "--irregularity", "dip:x=1e9,depth=0.002,length=1"]
    _one_line_exit_2(argv, capsys, "--irregularity", "x=1e+09 m is outside")


FIT = ["params", "--zone", "1", "--source", "fitted", "--parameters"]


@pytest.mark.parametrize(
    "edit, fragments",
    [
        (lambda t: _sub(t, r"^format = 2", "format = 99"), ("fitted.format", "= 99")),
        (
            lambda t: _sub(t, r"^x_m = \[-4\.5, -2\.1,", "x_m = [-2.1, -4.5,"),
            ("zone1.x_m must increase",),
        ),
        (
            lambda t: _sub(t, r'^turnout_model_sha256 = "[0-9a-f]+"', 'turnout_model_sha256 = "0"'),
            ("fitted.turnout_model_sha256 does not match uic60_760_1_15.toml",),
        ),
    ],
    ids=["format 99", "x_m unsorted", "hash of another turnout"],
)
def test_bad_fitted_file(tmp_path, capsys, edit, fragments):
    path = tmp_path / "fitted.toml"
    path.write_text(edit(FITTED), encoding="utf-8")
    _one_line_exit_2(FIT + [path], capsys, "fitted.toml", *fragments)


def test_fitted_file_of_another_turnout(capsys):
    """The packaged UIC60 set on the EW54 turnout ran with exit 0 and a vague warning."""
    _one_line_exit_2(
        FIT + [FITTED_PATH, "--turnout", EW54],
        capsys,
        "uic60_760_1_15_fitted.toml",
        "fitted to another turnout",
    )


def test_fitted_file_keeps_its_hash_when_other_sections_change(tmp_path, capsys):
    """Comments and [check_rail] do not enter the hash: the packaged set still loads."""
    path = tmp_path / "t.toml"
    text = _sub(TURNOUT, r"^clearance = [^\s#]+", "clearance = 0.05") + "\n# a comment\n"
    path.write_text(text, encoding="utf-8")
    code = main(FIT + [str(FITTED_PATH), "--turnout", str(path)])
    out, err = capsys.readouterr()
    assert code == 0 and err == "", err


def test_old_fitted_file_without_hash_warns(tmp_path, capsys):
    path = tmp_path / "old_fitted.toml"
    old = _sub(FITTED, r'^turnout_model_sha256 = "[0-9a-f]+"\n', "")
    path.write_text(_sub(old, r"^format = 2", "format = 1"), encoding="utf-8")
    code = main(FIT + [str(path), "--format", "json"])
    out, err = capsys.readouterr()
    assert code == 0, err
    assert err.count("\n") == 1 and err.startswith("warning: old_fitted.toml has no"), err
    assert "cannot be checked" in err and math.isfinite(len(out))
