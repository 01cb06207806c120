"""The turnout file chooses the co-running check rail: ``[check_rail.co_running] model``.

``model = "table1"`` builds slot r3 from Eqs 1-19 on Table 1 (the paper's) for every command
and passage, without Python; ``"bracket"`` (the default of a file with the table) from the
FE values. A bad value is one line naming the file and the field, exit 2.
"""

from __future__ import annotations

import json

import pytest

from exudyn_turnout.cli.main import main
from exudyn_turnout.corunning.check_rail import check_rail_model
from exudyn_turnout.corunning.parameters import co_running_parameters
from exudyn_turnout.inputs.check_rail import CO_RUNNING_MODELS, co_running_model_from_section
from exudyn_turnout.inputs.turnout import TurnoutFileError, default_turnout_path, load_turnout
from exudyn_turnout.passage.common import lightest_rail_mass

#: the packaged file's choice in [check_rail.co_running]; the tests put theirs in its place
MODEL_LINE = 'model = "bracket"\n'


def _with_model(tmp_path, line: str):
    src = default_turnout_path().read_text()
    assert src.count(MODEL_LINE) == 1
    path = tmp_path / "t.toml"
    path.write_text(src.replace(MODEL_LINE, f"{line}\n", 1))
    return path


def test_section_reader():
    assert CO_RUNNING_MODELS == ("bracket", "table1")
    assert co_running_model_from_section({}) is None
    assert co_running_model_from_section({"co_running": {"rail": "c"}}) is None
    assert co_running_model_from_section({"co_running": {"model": "table1"}}) == "table1"
    with pytest.raises(ValueError, match=r"model must be one of bracket, table1.*'table1'"):
        co_running_model_from_section({"co_running": {"model": "tabel1"}})
    with pytest.raises(ValueError, match="model must be one of"):
        co_running_model_from_section({"co_running": {"model": 1}})


def test_file_key_selects_table1(tmp_path):
    packaged = load_turnout()
    assert packaged.raw["check_rail"]["co_running"]["model"] == "bracket"
    table1 = load_turnout(_with_model(tmp_path, 'model = "table1"'))
    bracket = load_turnout(_with_model(tmp_path, 'model = "bracket"'))
    assert check_rail_model(packaged, None) == "bracket"
    assert check_rail_model(table1, None) == "table1"
    assert check_rail_model(bracket, None) == "bracket"
    # an explicit argument still wins over the file
    assert check_rail_model(table1, "bracket") == "bracket"
    at = co_running_parameters(table1, x=46.0).at(46.0)
    # Table 1 values of the check rail: 109.4 kg (validation/check_rail_support.md, "before";
    # the same value tests/test_corunning_check_rail.py pins for check_rail="table1")
    assert at["m_r3"] == pytest.approx(109.4, abs=0.1)
    assert at == co_running_parameters(packaged, x=46.0, check_rail="table1").at(46.0)
    assert co_running_parameters(bracket, x=46.0).at(46.0) == (
        co_running_parameters(packaged, x=46.0).at(46.0)
    )
    # the passage's parameter sets follow the file (the lightest rail mass of a crossing
    # run is the check rail's: 109.4 kg with Table 1, < 50 kg from the bracket)
    assert lightest_rail_mass(table1, 44.5, 50.0, 3, "derived") > 100.0
    assert lightest_rail_mass(packaged, 44.5, 50.0, 3, "derived") < 50.0


def test_command_line_follows_the_file(tmp_path, capsys):
    path = _with_model(tmp_path, 'model = "table1"')
    assert main(["params", "--turnout", str(path), "--x", "46", "--format", "json"]) == 0
    out = json.loads(capsys.readouterr().out)
    text = json.dumps(out)
    assert "m_r3" in text
    values = out if "m_r3" in out else next(v for v in out.values() if "m_r3" in v)
    assert float(values["m_r3"]) == pytest.approx(109.4, abs=0.1)


@pytest.mark.parametrize(
    "line, message",
    [
        ('model = "tabel1"', "check_rail.co_running model must be one of bracket, table1"),
        ("model = 3", "check_rail.co_running model must be one of bracket, table1"),
        ('modle = "table1"', "did you mean 'model'"),
    ],
)
def test_bad_model_is_one_line_exit_2(tmp_path, capsys, line, message):
    path = _with_model(tmp_path, line)
    with pytest.raises(TurnoutFileError, match=message.replace(".", r"\.")):
        load_turnout(path)
    assert main(["params", "--turnout", str(path), "--zone", "1"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "t.toml" in err[0] and "check_rail.co_running" in err[0]


def test_a_study_can_vary_the_model(tmp_path):
    """The packaged file states its model, so a study factor can vary it by dotted path."""
    from exudyn_turnout.studies import load_study

    path = tmp_path / "s.toml"
    path.write_text(
        '[study]\nname = "check rail"\n[base]\nroute = "diverging"\nspeed_kmh = 60.0\n'
        "[factors]\n"
        '"turnout.check_rail.co_running.model" = ["bracket", "table1"]\n'
    )
    assert len(load_study(path).cases()) == 2
    path.write_text(path.read_text().replace('"table1"]', '"tabel1"]'))
    with pytest.raises(ValueError, match="check_rail.co_running model must be one of"):
        load_study(path).cases()


@pytest.mark.slow
def test_simulate_follows_the_file(tmp_path, capsys):
    """End to end: the passage's check-rail force follows the file's model.

    Measured at 357a1bf (single wheelset, diverging, 80 km/h, 3-layer, x 40-47 m):
    peak check-rail Fy 54.6 kN with "bracket", 76.8 kN with "table1" (Table 1's check rail
    is 3-5x stiffer laterally, corunning/check_rail.py); the test asserts only the sign and
    a 10 % margin of that difference.
    """
    peaks = {}
    for model in ("bracket", "table1"):
        path = _with_model(tmp_path, f'model = "{model}"')
        out = tmp_path / model
        argv = ["simulate", "--turnout", str(path), "--route", "diverging", "--speed", "80"]
        argv += ["--layers", "3", "--x-start", "40", "--x-end", "47", "--no-plot", "--quiet"]
        assert main([*argv, "--out", str(out)]) == 0, capsys.readouterr().err
        summary = json.loads((out / "summary.json").read_text())
        peaks[model] = abs(float(summary["peak_Fy_check_rail_N"]))
    assert peaks["table1"] > 1.1 * peaks["bracket"] > 0.0, peaks
