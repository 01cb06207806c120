"""The check rail's flares and support fields (exudyn_turnout/inputs/check_rail.py)."""

from __future__ import annotations

import math

import pytest

from exudyn_turnout.cli.main import main
from exudyn_turnout.inputs.check_rail import (
    entry_lateral_velocity,
    flare_opening,
    flare_slope,
)
from exudyn_turnout.inputs.routes import load_route
from exudyn_turnout.inputs.turnout import TurnoutFileError, default_turnout_path, load_turnout


def test_flare_shapes_closed_form():
    L, o = 1.0, 0.015
    # straight: linear from o at the end to 0 at L; tangential: o (1 - d/L)^2
    assert flare_opening(0.0, L, o) == pytest.approx(o)
    assert flare_opening(0.25, L, o) == pytest.approx(0.75 * o)
    assert flare_opening(0.25, L, o, "tangential") == pytest.approx(0.5625 * o)
    assert flare_opening(1.0, L, o, "tangential") == 0.0 == flare_opening(2.0, L, o)
    assert flare_opening(0.3, 0.0, o) == 0.0  # no flare
    # issue 23: a flanging leading wheelset 2.3 mm outside the check line at 80 km/h meets a
    # straight 1:67 flare at v / 67 = 0.33 m/s; the tangential run-in where its opening is
    # 2.3 mm, slope 2 sqrt(15 * 2.3) mm / 1 m
    v = 80 / 3.6
    assert entry_lateral_velocity(v, 0.0023, L, o) == pytest.approx(v * o / L)
    assert flare_slope(0.0023, L, o, "tangential") == pytest.approx(2 * math.sqrt(o * 0.0023))
    assert flare_slope(0.0023, L, o, "tangential") < flare_slope(0.0023, L, o)
    # the tangential slope at the remaining opening delta is the derivative of its opening
    d = L * (1 - math.sqrt(0.0023 / o))
    h = 1e-7
    numeric = flare_opening(d - h, L, o, "tangential") - flare_opening(d + h, L, o, "tangential")
    assert numeric / (2 * h) == pytest.approx(flare_slope(0.0023, L, o, "tangential"), rel=1e-6)
    with pytest.raises(ValueError, match="flare shape must be one of"):
        flare_opening(0.1, L, o, "curved")


def _file(tmp_path, text_from, text_to):
    src = default_turnout_path().read_text()
    assert text_from in src
    path = tmp_path / "t.toml"
    path.write_text(src.replace(text_from, text_to, 1))
    return path


def test_route_uses_the_flare_shape(tmp_path):
    path = _file(
        tmp_path,
        'flare_shape = "straight"',
        'flare_shape = "tangential"',
    )
    route = load_route(load_turnout(path), "diverging")
    pair = [p for p in route.pairs if p.check][0]
    x0 = pair.check[0]
    assert route.check_flare_shape == "tangential"
    assert route.check_clearance_at(pair, x0 + 0.25) == pytest.approx(0.004 + 0.5625 * 0.015)
    straight = load_route(load_turnout(), "diverging")
    assert straight.check_clearance_at(pair, x0 + 0.25) == pytest.approx(0.004 + 0.75 * 0.015)


@pytest.mark.parametrize(
    "text_from, text_to, message",
    [
        ('flare_shape = "straight"', 'flare_shape = "curvy"', "check_rail.flare_shape must be one"),
        ("flare_length = 1.0 ", "flare_lenght = 1.0 ", "did you mean 'flare_length'"),
    ],
)
def test_bad_check_rail_fields(tmp_path, capsys, text_from, text_to, message):
    path = _file(tmp_path, text_from, text_to)
    with pytest.raises(TurnoutFileError, match=message.replace(".", r"\.").replace("(", r"\(")):
        load_turnout(path)
    assert main(["params", "--turnout", str(path), "--zone", "1"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "t.toml" in err[0]


def test_bad_support_refused_at_load(tmp_path):
    path = _file(tmp_path, "k_roll = 0.5e6", "k_roll = -1.0")
    with pytest.raises(TurnoutFileError, match=r"check_rail\.support.*k_roll must be >= 0"):
        load_turnout(path)
