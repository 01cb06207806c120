"""``exudyn-turnout fe simulate`` (cli/fe_passage.py): the wheelset over the FE track with the
profile contact, bad input as one-line usage errors."""

from __future__ import annotations

import argparse
import json

import numpy as np
import pytest

from exudyn_turnout.cli.main import UsageError


def _fe_parser() -> argparse.ArgumentParser:
    from exudyn_turnout.cli.fe_passage import add_simulate

    parser = argparse.ArgumentParser(prog="exudyn-turnout")
    fe = parser.add_subparsers(dest="command").add_parser("fe").add_subparsers(dest="fe_command")
    add_simulate(fe)
    return parser


@pytest.mark.parametrize(
    "argv, text",
    [
        (["--speed", "-10"], "speed"),
        (["--route", "sideways"], "route"),
        (["--x-start", "70"], "x range"),
    ],
)
def test_cli_bad_input_is_a_usage_error(tmp_path, argv, text):
    args = _fe_parser().parse_args(["fe", "simulate", "--out", str(tmp_path)] + argv)
    with pytest.raises(UsageError, match=text):
        args.run(args)


def test_the_height_table_contact_is_not_an_fe_option(tmp_path, capsys):
    """The vertical-only FE passage with the height-table contact was retired (issue 21)."""
    with pytest.raises(SystemExit) as err:
        _fe_parser().parse_args(
            ["fe", "simulate", "--out", str(tmp_path), "--contact", "height-table"]
        )
    assert err.value.code == 2


def test_the_door_refuses_the_height_table_contact_on_the_fe_track(turnout):
    from exudyn_turnout.passage.run import simulate_passage
    from exudyn_turnout.passage.settings import PassageError, PassageSettings

    settings = PassageSettings(x_start=55.0, x_end=55.02, contact="height-table")
    with pytest.raises(PassageError, match="profile contact only"):
        simulate_passage(turnout, settings, track="fe", vehicle="wheelset")


def test_cli_writes_the_passage_files(tmp_path):
    args = _fe_parser().parse_args(
        ["fe", "simulate", "--x-start", "55", "--x-end", "55.02", "--out", str(tmp_path)]
        + ["--no-plot"]
    )
    assert args.run(args) == 0
    header = (tmp_path / "timeseries.csv").read_text().splitlines()[0].split(",")
    data = np.genfromtxt(tmp_path / "timeseries.csv", delimiter=",", skip_header=1)
    for name in ("t_s", "x_m", "Fz_right_N", "Fz_left_N", "Fy_right_N", "y_wheelset_m"):
        column = data[:, header.index(name)]
        assert np.all(np.isfinite(column)), name
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["model"] == "FE"
    # both wheels carry about the static wheel load on plain track (within 5 %)
    static = summary["static_wheel_load_N"]
    fz = data[:, header.index("Fz_right_N")]
    assert abs(fz.mean() / static - 1.0) < 0.05
