"""Route geometry and contact laws.

Reference values:
- dip angle at the crossing = wing slope + nose slope of the packaged profiles,
  3 mrad + 6 mrad = 9 mrad, meeting point where -3e-3 (d + 0.2) = -3e-3 + 6e-3 d, d the
  distance after the nose tip: d = 0.2667 m, depth 1.4 mm (hand solution of the two lines
  in the file); the nose tip from the plan (tests/test_geometry.py: 46.898 m);
- Hertz: F = C_H delta^1.5 (Johnson, Contact Mechanics, 1985, ch. 4);
- Johnson-Vermeulen saturation (Johnson & Vermeulen 1964): F_sat = mu N (u - u^2/3 + u^3/27),
  u < 3; equals mu N from u = 3 on;
- steady curving of a conical wheelset (Wickens, Fundamentals of Rail Vehicle Dynamics,
  2003, ch. 3): zero longitudinal creep at y = -b kappa r0 / gamma.
"""

import pytest

from exudyn_turnout.inputs.geometry import turnout_plan
from exudyn_turnout.inputs.routes import dip_angle, load_route
from exudyn_turnout.inputs.turnout import TurnoutFileError, default_turnout_path, load_turnout
from exudyn_turnout.wheel_rail import laws as contact


def test_crossing_dip_of_packaged_profiles(turnout):
    nose = turnout_plan(turnout).nose_tip_x
    x, depth, two_alpha = dip_angle(load_route(turnout, "through"), "right", nose - 0.5, nose + 1.0)
    assert x - nose == pytest.approx(0.2667, abs=2e-3)
    assert depth == pytest.approx(1.4e-3, rel=0.01)
    assert two_alpha == pytest.approx(9e-3, rel=0.01)


def test_diverging_route_mirrors_the_through_route(turnout):
    r = load_route(turnout, "diverging")
    assert r.rail_y["r2"] == 0.75 and r.continues == {3: {"r4": "r2"}}
    assert r.curvature(20.0) == pytest.approx(-1 / 760, rel=1e-6) and r.curvature(-2.0) == 0.0


@pytest.mark.parametrize(
    "old,new,message",
    [
        (
            'rail = "r3"\ncheck = [44.29, 51.0]',
            'rail = "r3"\ncheck = [40.0, 51.0]',
            "uses rail r3 over 40..44.29 m, where zone 1 has no such active rail",
        ),
        (
            "x = [-5.0, 60.0]\nz = [0.0, 0.0]\nflange = [-5.0, 60.0]",
            "x = [-5.0, 61.0]\nz = [0.0, 0.0]\nflange = [-5.0, 60.0]",
            "is outside the turnout",
        ),
        ("z = [-0.003, 0.0, 0.0]", "z = [-0.3, 0.0, 0.0]", "heights must be within"),
        (
            'wheel = "left"\nrail = "r4"',
            'wheel = "middle"\nrail = "r4"',
            "wheel must be one of left, right",
        ),
    ],
)
def test_route_errors_name_the_field(tmp_path, old, new, message):
    text = default_turnout_path().read_text(encoding="utf-8")
    assert old in text
    path = tmp_path / "t.toml"
    path.write_text(text.replace(old, new, 1), encoding="utf-8")
    with pytest.raises(TurnoutFileError, match="t.toml: routes.through.contacts"):
        load_route(load_turnout(path), "through")
    with pytest.raises(TurnoutFileError) as err:
        load_route(load_turnout(path), "through")
    assert message in str(err.value)


def test_unknown_route(turnout):
    with pytest.raises(TurnoutFileError, match="no route 'sideways'"):
        load_route(turnout, "sideways")


def test_hertz():
    assert contact.hertz_force(1e-4, 9e10) == pytest.approx(9e10 * 1e-6)
    assert contact.hertz_force(-1e-5, 9e10) == 0.0
    d = 9.2e-5
    assert contact.hertz_stiffness(d, 9e10) == pytest.approx(
        (contact.hertz_force(d * 1.0001, 9e10) - contact.hertz_force(d * 0.9999, 9e10))
        / (2e-4 * d),
        rel=1e-6,
    )


@pytest.mark.parametrize("u", [0.01, 0.5, 1.0, 2.0, 2.999])
def test_saturation_below_three(u):
    mu_N = 2e4
    assert contact.saturation_factor(u * mu_N, mu_N) * u * mu_N == pytest.approx(
        mu_N * (u - u**2 / 3 + u**3 / 27)
    )


def test_saturation_limits():
    assert contact.saturation_factor(1.0, 2e4) == pytest.approx(1.0, abs=1e-4)
    assert contact.saturation_factor(10 * 2e4, 2e4) * 10 * 2e4 == pytest.approx(2e4)
    assert contact.saturation_factor(3 * 2e4, 2e4) * 3 * 2e4 == pytest.approx(2e4)


def test_steady_curving_has_no_longitudinal_creep():
    b, r0, gamma, kappa = 0.75, 0.46, 0.15, -1 / 760
    y = -b * kappa * r0 / gamma
    assert y > 0  # a right-hand curve pushes the wheelset to the left (outwards)
    for side in (1, -1):
        assert contact.longitudinal_creepage(
            side, y, 0.0, 27.8, b, r0, gamma, kappa
        ) == pytest.approx(0, abs=1e-15)


def test_flange_force_one_sided():
    assert contact.flange_force(-1e-3, 0.1, 2e8, 2e4) == 0.0
    assert contact.flange_force(1e-3, 0.0, 2e8, 2e4) == pytest.approx(2e5)
    assert contact.flange_force(1e-6, -1.0, 2e8, 2e4) == 0.0  # never pulls
