"""Named modes of the vehicle linearised on straight track at speed (issue 23, root locus)."""

from __future__ import annotations

import pytest

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage.hunting import linear_modes, mode_name


def test_mode_names_from_energy_shares():
    assert mode_name({"car_body.y": 0.8, "car_body.roll": 0.2}) == "car body lower sway"
    assert mode_name({"car_body.roll": 0.6, "car_body.y": 0.4}) == "car body upper sway"
    assert mode_name({"wheelset.y": 0.9, "bogie.y": 0.1}) == "wheelset kinematic"
    assert mode_name({"wheelset.y": 0.44, "bogie.y": 0.4, "car_body.y": 0.16}) == "bogie hunting"
    assert mode_name({"bogie.y": 0.8, "bogie.roll": 0.2}) == "bogie lateral"
    assert mode_name({"bogie.z": 0.5, "bogie.pitch": 0.5}) == "vertical/other"


@pytest.mark.slow
def test_least_damped_mode_below_and_at_the_critical_speed():
    turnout = load_turnout()

    # below the critical speed, below 2 Hz: the car body's lower sway, 0.58 Hz undamped /
    # damping ratio 0.21 on rigid track without creep (validation/vehicle_modes.md)
    def least_damped_lateral(kmh, f_max=20.0):
        modes = [
            m
            for m in linear_modes(turnout, kmh)
            if m.name != "vertical/other" and m.frequency_hz < f_max
        ]
        return min(modes, key=lambda m: m.damping_ratio)

    low = least_damped_lateral(100.0, f_max=2.0)  # the band of the decaying runs
    assert low.name == "car body lower sway"
    assert 0.5 < low.frequency_hz < 0.7
    assert 0.15 < low.damping_ratio < 0.25
    # at 340 km/h the bogie hunting mode is at the stability limit: linear critical speed
    # with the kernel's FASTSIM creep table measured 340 km/h, 4.29 Hz (damping ratio
    # +0.0066 / -0.0000 / -0.0065 at 335 / 340 / 345 km/h).  With Polach's law it was
    # 425-430 km/h, 5.13 Hz (validation/hunting.md, written with Polach: to be regenerated);
    # FASTSIM's creep forces saturate earlier at moderate creepage (Vermeulen-Johnson's
    # curve, tests/test_wheel_rail_fastsim.py), and its slopes at the tread's spin
    # operating point are 3-5 % below Polach's.
    high = least_damped_lateral(340.0)
    assert high.name == "bogie hunting"
    assert abs(high.damping_ratio) < 0.02
    assert 4.0 < high.frequency_hz < 6.5
