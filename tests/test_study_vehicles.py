"""Studies of the full vehicle: ``vehicle = "manchester"`` (a packaged name) or a full-vehicle
file, next to the single wheelset (the study default).

Reference values: the study's own definition (the packaged files, the case count), and the
passage itself (:func:`~exudyn_turnout.passage.run.simulate_passage` run directly on the same
turnout, settings and vehicle must give the case's numbers: the same code on the same inputs).
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import pytest

from exudyn_turnout.studies import StudyError, load_study, run_case
from exudyn_turnout.studies.toml_writer import dumps

#: Half a metre past the crossing nose (x = 44-44.5 m): a short profile-contact passage.
SHORT = """
[study]
name = "vehicles"

[base]
contact = "profile"
route = "through"
x_start = 44.0
x_end = 44.5
output_step = 1e-3

[factors]
vehicle = {vehicles}
"""


def _study(tmp_path: Path, vehicles: str):
    path = tmp_path / "study.toml"
    path.write_text(SHORT.format(vehicles=vehicles), encoding="utf-8")
    return load_study(path)


def test_packaged_vehicle_names_select_the_files(tmp_path):
    from exudyn_turnout.inputs.vehicle import Vehicle
    from exudyn_turnout.inputs.vehicle_data import VehicleModel
    from exudyn_turnout.inputs.vehicle_names import packaged_vehicle_path
    from exudyn_turnout.studies.run import estimated_cost
    from exudyn_turnout.studies.study import load_study_vehicle

    cases = _study(tmp_path, '["wheelset", "manchester"]').cases()
    assert [c.vehicle_name for c in cases] == [
        "manchester_wheelset.toml",
        "manchester_vehicle.toml",
    ]
    for case, name in zip(cases, ("wheelset", "manchester")):
        assert case.vehicle_text == packaged_vehicle_path(name).read_text(encoding="utf-8")
    assert cases[0].key != cases[1].key
    assert isinstance(load_study_vehicle(packaged_vehicle_path("wheelset")), Vehicle)
    model = load_study_vehicle(packaged_vehicle_path("manchester"))
    assert isinstance(model, VehicleModel) and model.n_wheelsets == 4
    # the four wheelsets of the full vehicle: four times the wheelset's steps to compute
    assert estimated_cost(cases[1]) == pytest.approx(4 * estimated_cost(cases[0]))


def test_a_file_named_like_a_packaged_vehicle_beside_the_study_comes_first(tmp_path):
    from exudyn_turnout.inputs.vehicle_names import packaged_vehicle_path

    text = packaged_vehicle_path("wheelset").read_text(encoding="utf-8")
    (tmp_path / "manchester").write_text(text, encoding="utf-8")
    case = _study(tmp_path, '["manchester"]').cases()[0]
    assert case.vehicle_text == text


def test_full_vehicle_dotted_factor_and_bad_value(tmp_path):
    study = _study(tmp_path, '["manchester"]')
    text = SHORT.format(vehicles='["manchester"]') + '"vehicle.car_body.mass" = [30000.0]\n'
    (tmp_path / "study.toml").write_text(text, encoding="utf-8")
    case = load_study(tmp_path / "study.toml").cases()[0]
    assert tomllib.loads(case.vehicle_text)["car_body"]["mass"] == 30000.0
    assert case.vehicle_modified and case.key != study.cases()[0].key
    bad = text.replace("[30000.0]", "[-1.0]")
    (tmp_path / "study.toml").write_text(bad, encoding="utf-8")
    with pytest.raises(StudyError, match=r"vehicle\.car_body\.mass = -1\.0: .*car_body\.mass"):
        load_study(tmp_path / "study.toml").cases()


def test_toml_writer_round_trips_the_full_vehicle_file():
    from exudyn_turnout.inputs.vehicle_names import packaged_vehicle_path

    data = tomllib.loads(packaged_vehicle_path("manchester").read_text(encoding="utf-8"))
    assert tomllib.loads(dumps(data)) == data


@pytest.mark.slow
def test_full_vehicle_case_gives_the_passage_numbers(tmp_path):
    from exudyn_turnout.inputs.turnout import load_turnout
    from exudyn_turnout.passage.run import simulate_passage
    from exudyn_turnout.passage.settings import PassageSettings
    from exudyn_turnout.studies.run import case_results

    case = _study(tmp_path, '["manchester"]').cases()[0]
    record = run_case(case)
    assert record["status"] == "ok", record["error"]
    assert record["cpu_time_s"] > 0 and record["wall_time_s"] > 0
    direct = simulate_passage(load_turnout(), PassageSettings(**case.settings), "manchester")
    expected = case_results(direct)
    got = record["results"]
    assert set(got) == set(expected)
    for name, value in expected.items():
        if name == "wall_time_s":
            continue
        if isinstance(value, float) and math.isnan(value):
            assert math.isnan(got[name]), name
        else:
            assert got[name] == value, name
    # the front wheelset's static load: a quarter of the vehicle's weight at most
    # the front wheel's static load: an eighth of the vehicle's weight (car body centred
    # between the bogies; masses of the packaged file, Iwnicki 1998): 54.5 kN
    from exudyn_turnout.inputs.vehicle_data import GRAVITY
    from exudyn_turnout.inputs.vehicles import packaged_vehicle

    weight = packaged_vehicle("manchester").total_mass * GRAVITY
    assert got["static_wheel_load_N"] == pytest.approx(weight / 8, rel=2e-3)
