"""Wheelset passage on the co-running track: static state, curving, impact, convergence.

Reference values and their sources:
- static wheel load (m_w + m_s) g / 2 with the Manchester benchmark's masses
  (Iwnicki 1998): (1813 + 32000/4 + 2615/2) * 9.81 / 2 = 54546 N;
- static rail deflection u = K^-1 f, K the co-running model's stiffness matrix assembled
  by hand from the parameter set (exudyn_turnout.corunning.modal), f the two wheel loads;
- steady curving: the lateral forces on the rails balance (m_w + m_s) v^2 / R (R = 760 m,
  no cant; paper Section 4), within 2 % (issue 12's check) at the permitted 80 km/h;
- P2-type crossing impact forces grow with speed (Jenkins et al. 1974, Railway Engineering
  Journal 3(1)); time-step convergence is checked against the run with half the step.
"""

import math

import numpy as np
import pytest

from exudyn_turnout.cli.main import main
from exudyn_turnout.corunning.modal import assemble_track_matrices, wheel_dof
from exudyn_turnout.corunning.parameters import co_running_parameters
from exudyn_turnout.inputs.geometry import turnout_plan
from exudyn_turnout.inputs.vehicle import load_vehicle
from exudyn_turnout.passage.results import write_passage
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageError, PassageSettings

W = (1813 + 32000 / 4 + 2615 / 2) * 9.81 / 2
X_RANGE = ["--x-start", "46.5", "--x-end", "48"]


@pytest.fixture(scope="module")
def plain(turnout):
    """Zone 3 is plain track (stock rails only, Table 3): 51 m to 60 m at 100 km/h."""
    return simulate_passage(
        turnout, PassageSettings(layers=3, x_start=51.0, x_end=60.0), vehicle="wheelset"
    )


def test_static_wheel_loads(plain):
    assert load_vehicle().static_wheel_load == pytest.approx(W, rel=1e-12)
    assert plain.summary["static_wheel_load_N"] == pytest.approx(W, rel=0.005)
    assert plain.summary["static_wheel_load_left_N"] == pytest.approx(W, rel=0.005)


@pytest.mark.parametrize("layers", [2, 3])
def test_static_rail_deflection_is_load_over_track_stiffness(turnout, layers):
    x = 55.0
    res = simulate_passage(
        turnout, PassageSettings(layers=layers, x_start=x, x_end=x + 0.05), vehicle="wheelset"
    )
    params = co_running_parameters(turnout, x=x, layers=layers)
    m = assemble_track_matrices(params, x)
    f = np.zeros(len(m.dof))
    for rail, wheel in (("r1", "right"), ("r4", "left")):
        f[m.index(wheel_dof(rail, "vertical", layers))] = -res.summary[
            f"static_wheel_load{'' if wheel == 'right' else '_left'}_N"
        ]
    u = np.linalg.solve(m.K, f)
    for rail in ("r1", "r4"):
        expected = u[m.index(wheel_dof(rail, "vertical", layers))]
        assert res.columns[f"z_rail_{rail}_m"][0] == pytest.approx(expected, rel=1e-4)


def test_plain_track_force_is_constant_after_0_1_s(plain):
    c = plain.columns
    late = c["t_s"] >= c["t_s"][0] + 0.1
    for wheel in ("right", "left"):
        fz = c[f"Fz_{wheel}_N"][late]
        assert np.max(np.abs(fz / W - 1)) < 0.01


@pytest.fixture(scope="module")
def diverging(turnout):
    return simulate_passage(
        turnout,
        PassageSettings(route="diverging", layers=2, x_start=-5.0, x_end=40.0, speed_kmh=80.0),
        vehicle="wheelset",
    )


def test_steady_curving_lateral_force(diverging):
    """The rails take the vehicle's centrifugal force, outwards (to the left of a curve to
    the right): sum of lateral forces on the rails = (m_w + m_s) v^2 / R within 2 %."""
    c = diverging.columns
    sel = (c["x_m"] > 25.0) & (c["x_m"] < 40.0)
    total = (c["Fy_right_N"] + c["Fy_left_N"])[sel].mean()
    veh = load_vehicle()
    assert total == pytest.approx((veh.m_w + veh.m_s) * (80 / 3.6) ** 2 / 760, rel=0.02)


def test_crossing_peak_grows_with_speed(turnout):
    nose = turnout_plan(turnout).nose_tip_x
    peaks = [
        simulate_passage(
            turnout,
            PassageSettings(layers=2, speed_kmh=v, x_start=44.5, x_end=nose + 0.6),
            vehicle="wheelset",
        ).summary["peak_Fz_crossing_N"]
        for v in (50.0, 100.0, 150.0)
    ]
    assert peaks[0] < peaks[1] < peaks[2]
    # the design geometry's dip (2 alpha ~ 14 mrad, validation/turnout_contact_geometry.md)
    # gives a real impact already at 50 km/h
    assert peaks[0] > 1.2 * W


def test_halving_the_time_step_changes_the_crossing_peak_by_less_than_1_percent(turnout):
    """Issue 12's check, on the profile contact (measured: 0.1 %, validation/profile_contact.md)."""
    nose = turnout_plan(turnout).nose_tip_x
    peaks = [
        simulate_passage(
            turnout,
            PassageSettings(layers=3, time_step=h, x_start=nose - 0.5, x_end=nose + 1.1),
            vehicle="wheelset",
        ).summary["peak_Fz_crossing_N"]
        for h in (1e-4, 5e-5)
    ]
    assert abs(peaks[0] / peaks[1] - 1) < 0.01


# At 51.0 m the zone-2 cross-section (check rail, rails at their crossing positions) holds
# the wheelset at y = 0.12 mm, roll -0.22 mrad in static equilibrium (wheel loads 55.5 /
# 53.6 kN at 50.9 m), zone 3 (plain track) at y = 0 (54.5 / 54.5 kN); the carried-over
# wheelset starts between the two and the profile contact turns its 0.04 mm of lateral
# offset into ~1.3 kN (2.4 % of W) of load transfer between the wheels, which then decays.
# Measured at 20 and 100 km/h alike, so a static difference of the zone models, not an
# impact; the height-table contact (no lateral-vertical coupling) stays below 0.2 %.
@pytest.mark.parametrize(
    "x_from,x_to,boundary,tolerance", [(43.3, 44.9, 44.29, 0.02), (50.0, 52.0, 51.0, 0.03)]
)
def test_no_force_jump_at_zone_boundary_on_plain_geometry(
    turnout, x_from, x_to, boundary, tolerance
):
    """Both boundaries lie where the rails do not change (the wing flares from the throat
    at 46.1 m; the nose ends in the plain rail's section at 51 m)."""
    res = simulate_passage(
        turnout, PassageSettings(layers=3, x_start=x_from, x_end=x_to), vehicle="wheelset"
    )
    c = res.columns
    i = int(np.searchsorted(c["x_m"], boundary))
    for wheel in ("right", "left"):
        jump = np.max(np.abs(np.diff(c[f"Fz_{wheel}_N"][i - 2 : i + 3])))
        assert jump < tolerance * W, (wheel, jump)


def test_outputs(tmp_path, plain):
    paths = write_passage(plain, tmp_path)
    header = open(paths["timeseries"]).readline().strip().split(",")
    for name in (
        "t_s",
        "x_m",
        "Fz_right_r1_N",
        "Fy_left_r4_N",
        "Fz_right_N",
        "Fy_right_N",
        "Fz_left_N",
        "Fy_left_N",
        "z_wheelset_m",
        "z_rail_r1_m",
    ):
        assert name in header
    import json

    summary = json.loads(open(paths["summary"]).read())
    for key in (
        "static_wheel_load_N",
        "peak_Fz_switch_N",
        "peak_Fz_crossing_N",
        "peak_Fy_switch_N",
        "peak_Fy_crossing_N",
        "contact_losses",
        "time_step_s",
        "simulated_time_s",
        "wall_time_s",
    ):
        assert key in summary
    assert (
        "NaN" not in open(paths["timeseries"]).read() and "NaN" not in open(paths["summary"]).read()
    )


@pytest.mark.parametrize(
    "argv,fragment",
    [
        (["--speed", "0"], "speed must be > 0"),
        (["--speed", "-10"], "speed must be > 0"),
        (["--route", "sideways"], "--route sideways: uic60_760_1_15.toml has no such route"),
        (["--x-start", "-20"], "must lie within the turnout"),
        (["--x-start", "30", "--x-end", "20"], "x_start < x_end"),
        (["--time-step", "0.01"], "too large to resolve the wheel/rail contact"),
    ],
)
def test_cli_bad_input(tmp_path, capsys, argv, fragment):
    assert main(["simulate", "--out", str(tmp_path / "o")] + argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and fragment in err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("contact", ["profile", "height-table"])
def test_solver_failure_names_time_and_position(turnout, monkeypatch, contact):
    from exudyn_turnout.passage.contact import height_table as contact_element
    from exudyn_turnout.passage.contact import profile as profile_contact

    element = {
        "profile": profile_contact.ProfileContactElement,
        "height-table": contact_element.WheelRailElement,
    }[contact]
    original = element.__call__

    def failing(self, mbs, t, i, q, q_t):
        f = original(self, mbs, t, i, q, q_t)
        return [math.nan] * len(f) if self.v > 0 and t > 0.01 else f

    monkeypatch.setattr(element, "__call__", failing)
    with pytest.raises(PassageError, match=r"at t = 0\.01\d* s, x = 5[0-9.]* m \(zone 3"):
        simulate_passage(
            turnout,
            PassageSettings(layers=2, x_start=52.0, x_end=53.0, contact=contact),
            vehicle="wheelset",
        )


def test_cli_simulate_writes_files(tmp_path, capsys):
    out = tmp_path / "run"
    assert (
        main(["simulate", "--vehicle", "wheelset", "--layers", "2", *X_RANGE, "--out", str(out)])
        == 0
    )
    assert {p.name for p in out.iterdir()} == {
        "timeseries.csv",
        "summary.json",
        "forces.png",
        "contact_band.png",  # profile contact: where the wheel touches, along x
        "safety.png",  # Y/Q with Nadal, sum Y with Prud'homme, Delta Q/Q0
    }
    out = capsys.readouterr().out
    assert "peak Fz n/a (region not in the run) at the switch" in out and "nan" not in out


def _five_zone_file(tmp_path):
    """The packaged turnout with zone 1 split into three zones (masses from Eqs 17, 18 at each
    zone's middle via mass_at_x) and no published Table 2 (which has three zones)."""
    from exudyn_turnout.inputs.turnout import default_turnout_path

    lines, out, skip = default_turnout_path().read_text(encoding="utf-8").splitlines(), [], False
    for line in lines:
        if line.startswith("[published."):
            skip = True
        elif skip and (line.startswith("[") or line.startswith("# ---")):
            skip = False
        if not skip:
            out.append(line)
    text = "\n".join(out).replace(
        'continues = [{ zone = 3, slot = "r1", from = "r2" }]',
        'continues = [{ zone = 5, slot = "r1", from = "r2" }]',
    )
    text = text.replace(
        'continues = [{ zone = 3, slot = "r4", from = "r2" }]',
        'continues = [{ zone = 5, slot = "r4", from = "r2" }]',
    )
    zone1 = text[text.index("[[zones]]") : text.index("[[zones]]", text.index("[[zones]]") + 1)]
    parts = []
    for a, b in ((-5.0, 10.0), (10.0, 25.0), (25.0, 44.29)):
        parts.append(
            zone1.replace("x_start = -5.0", f"x_start = {a}")
            .replace("x_end = 44.29", f"x_end = {b}")
            .replace(
                'ballast_rail_type = "switch"',
                f'ballast_rail_type = "switch"\nmass_at_x = {(a + b) / 2}',
            )
        )
    path = tmp_path / "five_zones.toml"
    path.write_text(text.replace(zone1, "".join(parts)), encoding="utf-8")
    return path


def test_more_zones_than_three(tmp_path):
    """The paper's future work: more zones, masses per zone from Eqs 17, 18 (Delta at the zone
    middle)."""
    from exudyn_turnout.inputs.turnout import load_turnout

    turnout = load_turnout(_five_zone_file(tmp_path))
    assert len(turnout.zones) == 5 and not turnout.published
    masses = [co_running_parameters(turnout, zone=z).entries["m_r2"].a for z in (1, 2, 3)]
    assert masses[0] < masses[1] < masses[2]  # the switch rail builds up mass from the toe (Eq 17)
    res = simulate_passage(
        turnout, PassageSettings(layers=3, x_start=8.0, x_end=12.0), vehicle="wheelset"
    )
    c = res.columns
    i = int(np.searchsorted(c["x_m"], 10.0))
    assert np.max(np.abs(np.diff(c["Fz_right_N"][i - 2 : i + 3]))) < 0.02 * W
    with pytest.raises(ValueError, match="no published parameters for zone 1"):
        co_running_parameters(turnout, zone=1, source="published")
