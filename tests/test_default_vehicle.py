"""The full Manchester vehicle is the default of ``simulate`` and ``simulate_passage``; the
single wheelset stays, named ``"wheelset"`` (issue 24).

Reference values: the packaged vehicles' names and files
(``exudyn_turnout/inputs/vehicle_names.py``: ``manchester`` -> ``manchester_vehicle.toml``,
four wheelsets; ``wheelset`` -> ``manchester_wheelset.toml``); the single wheelset's static
wheel load, (m_w + m_s) g / 2 with the masses of ``manchester_wheelset.toml``
(``tests/test_corunning_track_wheelset.py``'s ``W``).
"""

from __future__ import annotations

import csv
import json

import pytest

from exudyn_turnout.cli.main import main
from exudyn_turnout.inputs.vehicle import Vehicle, load_vehicle
from exudyn_turnout.inputs.vehicle_model import VehicleModel
from exudyn_turnout.passage.run import DEFAULT_VEHICLE, simulate_passage, vehicle_of
from exudyn_turnout.passage.settings import PassageSettings

#: A short run in plain track of zone 2 for every wheelset of the full vehicle (front at
#: 20 m, the rear wheelsets about 19 m behind, inside the turnout).
SHORT = ["--x-start", "20", "--x-end", "20.02", "--no-plot", "--quiet"]


def _header(path) -> list[str]:
    with open(path, encoding="utf-8", newline="") as fh:
        return next(csv.reader(fh))


def test_the_default_vehicle_is_the_full_manchester_vehicle():
    assert DEFAULT_VEHICLE == "manchester"
    model = vehicle_of(None)
    assert isinstance(model, VehicleModel)
    assert model.name == vehicle_of("manchester").name
    assert model.n_wheelsets == 4
    single = vehicle_of("wheelset")
    assert isinstance(single, Vehicle) and not isinstance(single, VehicleModel)


def test_cli_default_and_fe_simulate_default_parse():
    import argparse

    from exudyn_turnout.cli.fe_passage import add_simulate
    from exudyn_turnout.cli.passage import build

    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers(dest="command")
    build(sub)
    add_simulate(sub.add_parser("fe").add_subparsers(dest="fe_command"))
    assert parser.parse_args(["simulate", "--out", "o"]).vehicle == "manchester"
    fe = parser.parse_args(["fe", "simulate", "--out", "o"])
    assert fe.vehicle is None  # fe simulate: the single wheelset (load_vehicle(None))


def test_height_table_with_the_default_names_the_way_out(tmp_path, capsys):
    code = main(["simulate", "--contact", "height-table", *SHORT, "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1
    assert "--vehicle wheelset" in err
    assert not (tmp_path / "o").exists()


@pytest.mark.slow
def test_api_default_runs_the_full_vehicle(turnout):
    settings = PassageSettings(x_start=20.0, x_end=20.02)
    result = simulate_passage(turnout, settings, track="3-layer")
    cols = result.columns
    assert {f"x_ws{k}_m" for k in (1, 2, 3, 4)} <= set(cols)
    # the plain columns are the front wheelset's (the paper's Figs 7, 8 show the front axle)
    assert (cols["Fz_right_N"] == cols["Fz_ws1_right_N"]).all()
    assert (cols["x_m"] == cols["x_ws1_m"]).all()


@pytest.mark.slow
def test_cli_default_is_the_full_vehicle_and_wheelset_by_name(tmp_path, capsys):
    full = tmp_path / "full"
    assert main(["simulate", *SHORT, "--out", str(full)]) == 0
    line = capsys.readouterr().out
    assert "full vehicle, front wheelset" in line
    summary = json.loads((full / "summary.json").read_text())
    assert summary["provenance"]["inputs"]["vehicle"]["name"] == "manchester_vehicle.toml"
    assert "Fz_ws4_right_N" in _header(full / "timeseries.csv")

    single = tmp_path / "single"
    assert main(["simulate", "--vehicle", "wheelset", *SHORT, "--out", str(single)]) == 0
    line = capsys.readouterr().out
    assert "full vehicle" not in line
    summary = json.loads((single / "summary.json").read_text())
    assert summary["provenance"]["inputs"]["vehicle"]["name"] == "manchester_wheelset.toml"
    assert not any("_ws" in name for name in _header(single / "timeseries.csv"))
    wheelset = load_vehicle()
    weight = (wheelset.m_w + wheelset.m_s) * 9.81 / 2
    assert summary["static_wheel_load_N"] == pytest.approx(weight, rel=0.01)
