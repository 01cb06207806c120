"""A second, materially different turnout (data/ew54_190_1_9.toml) through every command.

Another turnout is another file, for every command. The EW 54E1-190-1:9
file differs from the packaged UIC60-760-1:15 in rail section, sleepers (timber, 0.65 m),
pads, ballast, geometry (R = 190 m, 1:9, ~34 m), four zones, rail-type names (no
"stock", "switch", "crossing"), route names (main / branch) and report settings. Quick
settings throughout: short x ranges, coarse output, few frequencies.

Hand values: the branch's default report speed is sqrt(0.65 m/s^2 x 190 m) = 11.11 m/s =
40.0 km/h, rounded down to 5 km/h; a tangential 190 m curve that turns straight at its
tangent point R sin(atan(1/9)) = 20.98 m meets the main route's gauge line at a 1:9
angle; the static wheel load is (1813 + 9307.5) x 9.81 / 2 = 54546 N.
"""

import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest

import exudyn_turnout
from exudyn_turnout.cli.main import main
from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.report.settings import check_rails, report_settings, stock_rails

SECOND = Path(exudyn_turnout.__file__).parent / "data" / "ew54_190_1_9.toml"
STATIC_WHEEL_LOAD = (1813.0 + 9307.5) * 9.81 / 2
#: What code outside the report cannot do yet with route names other than through/diverging.


@pytest.fixture(scope="module")
def second():
    return load_turnout(SECOND)


def _run(argv, capsys) -> tuple[int, str, str]:
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


# --- the file ---------------------------------------------------------------------------


def test_second_turnout_is_materially_different(second, turnout):
    from exudyn_turnout.inputs.geometry import turnout_plan

    assert len(second.zones) == 4 and len(turnout.zones) == 3
    assert not {"stock", "switch", "crossing"} & set(second.rail_types)
    assert set(second.raw["routes"]) == {"main", "branch"}
    assert second.sleeper.spacing == 0.65 and turnout.sleeper.spacing == 0.6
    assert second.rail_types["plain"].pad.k_z != turnout.rail_types["stock"].pad.k_z
    assert second.ballast.s_b_z != turnout.ballast.s_b_z
    assert second.sleeper.youngs_modulus < 0.5 * turnout.sleeper.youngs_modulus  # timber
    assert second.x_max - second.x_min < 40.0 < turnout.x_max - turnout.x_min
    plan = turnout_plan(second)
    assert plan.crossing_angle_n == pytest.approx(9.0, rel=1e-3)
    crossing_panel = second.zone(3)
    assert crossing_panel.x_start < plan.crossing_point_x < plan.nose_tip_x < crossing_panel.x_end


def test_report_settings_come_from_the_file_and_the_model(second):
    from exudyn_turnout.fe.layout import load_layout

    s = report_settings(second)
    main_route, branch = s.route("main"), s.route("branch")
    assert (main_route.speed_kmh, branch.speed_kmh) == (100.0, 40.0)  # defaults, see the docstring
    assert math.isinf(main_route.radius) and branch.radius == pytest.approx(190.0)
    assert (main_route.wheel, branch.wheel) == ("right", "left")
    assert branch.signals == (
        ("Fz", "switch"),
        ("Fz", "crossing"),
        ("Fy", "switch"),
        ("Fy", "crossing"),
    )
    assert (main_route.fe_slots, branch.fe_slots) == ("main", "branch")
    assert (
        s.impact_route == "main" and s.receptance_route == "main" and s.receptance_wheel == "right"
    )
    assert s.switch_claim_x == second.K_sw.x_max == 9.0
    assert s.regions == {"switch": (0.0, 6.0), "crossing": (22.0, 26.5)}
    assert s.reference_rail_type == "plain" and s.quick_passage_x == (23.2, 24.8)
    layout = load_layout(second)
    assert stock_rails(s, layout) == ("left_stock", "right_stock")
    assert check_rails(s, layout, second) == ("guard_main", "guard_branch")


# --- params, frf, simulate ---------------------------------------------------------------


def test_params_in_every_zone(capsys):
    for zone in range(1, 5):
        code, out, err = _run(
            ["params", "--turnout", SECOND, "--zone", zone, "--format", "json"], capsys
        )
        assert code == 0, err
        p = json.loads(out)
        assert p["zone"] == zone and p["k_rt1_z"] > 0
    code, out, err = _run(["params", "--turnout", SECOND, "--x", 23.7, "--format", "json"], capsys)
    assert code == 0, err
    p = json.loads(out)
    # plain 54E1 on this file's pads: k_rt,z = k_p,z L_eff,r / L_s (Eq 6) with L_eff,r from Eq 1
    assert p["k_rt1_z"] == pytest.approx(300e6 * p["L_eff_r_z"] / 0.65, rel=1e-6)


def test_frf(tmp_path, capsys):
    out = tmp_path / "frf.csv"
    code, _, err = _run(
        [
            "frf",
            "--turnout",
            SECOND,
            "--zone",
            3,
            "--layers",
            3,
            "--rail",
            "r2",
            "--direction",
            "vertical",
            "--n",
            20,
            "--out",
            out,
        ],
        capsys,
    )
    assert code == 0, err
    rows = list(csv.DictReader(out.open()))
    assert len(rows) == 20 and all(float(r["magnitude"]) > 0 for r in rows)


@pytest.mark.slow
@pytest.mark.parametrize(
    "route, speed, x_range", [("main", 100, (22.8, 24.8)), ("branch", 40, (-2.0, 3.0))]
)
def test_simulate(tmp_path, capsys, route, speed, x_range):
    out = tmp_path / route
    code, _, err = _run(
        [
            "simulate",
            "--vehicle",
            "wheelset",
            "--turnout",
            SECOND,
            "--route",
            route,
            "--speed",
            speed,
            "--x-start",
            x_range[0],
            "--x-end",
            x_range[1],
            "--output-step",
            1e-3,
            "--out",
            out,
            "--no-plot",
        ],
        capsys,
    )
    assert code == 0, err
    s = json.loads((out / "summary.json").read_text())
    assert s["static_wheel_load_N"] + s["static_wheel_load_left_N"] == pytest.approx(
        2 * STATIC_WHEEL_LOAD, rel=1e-3
    )
    if route == "main":  # the right wheel meets the nose
        assert s["peak_Fz_crossing_N"] > 1.5 * STATIC_WHEEL_LOAD
    else:  # load transfer stock rail -> curved blade near 2 m, left wheel
        assert STATIC_WHEEL_LOAD < s["peak_Fz_switch_left_N"] < 1.5 * STATIC_WHEEL_LOAD


# --- FE ------------------------------------------------------------------------------------


@pytest.mark.slow
def test_fe_stiffness(tmp_path, capsys):
    out = tmp_path / "stiffness.csv"
    code, _, err = _run(["fe", "stiffness", "--turnout", SECOND, "--out", out], capsys)
    assert code == 0, err
    rows = list(csv.DictReader(out.open()))
    k = {}
    for r in rows:
        k.setdefault(r["rail"], []).append((float(r["x_m"]), float(r["K_z_N_per_m"])))
    assert {"left_stock", "right_stock", "main_blade", "branch_blade", "guard_main"} <= set(k)
    blade = np.array(k["main_blade"])
    stock = np.array(k["left_stock"])
    in_crossing = (blade[:, 0] > 22.0) & (blade[:, 0] < 26.5)
    plain = stock[(stock[:, 0] > 27.0), 1].mean()
    assert blade[0, 1] < plain < blade[in_crossing, 1].mean()  # slender blade tip, stiff crossing


@pytest.mark.slow
def test_fe_frf(tmp_path, capsys):
    out = tmp_path / "fe_frf.csv"
    code, _, err = _run(
        [
            "fe",
            "frf",
            "--turnout",
            SECOND,
            "--rail",
            "main_blade",
            "--direction",
            "vertical",
            "--x",
            23.7,
            "--n",
            5,
            "--out",
            out,
        ],
        capsys,
    )
    assert code == 0, err
    assert len(list(csv.DictReader(out.open()))) == 5
    code, _, err = _run(
        [
            "fe",
            "frf",
            "--turnout",
            SECOND,
            "--rail",
            "r2",
            "--route",
            "main",
            "--direction",
            "vertical",
            "--x",
            23.7,
            "--n",
            5,
            "--out",
            tmp_path / "slot.csv",
        ],
        capsys,
    )
    assert code == 0, err


@pytest.mark.slow
def test_fe_simulate(tmp_path, capsys):
    out = tmp_path / "fe"
    code, _, err = _run(
        [
            "fe",
            "simulate",
            "--turnout",
            SECOND,
            "--route",
            "main",
            "--x-start",
            23.2,
            "--x-end",
            24.4,
            "--output-step",
            1e-3,
            "--out",
            out,
            "--no-plot",
        ],
        capsys,
    )
    assert code == 0, err
    assert json.loads((out / "summary.json").read_text())["peak_Fz_crossing_N"] > STATIC_WHEEL_LOAD


# --- validate ------------------------------------------------------------------------------


@pytest.mark.slow
def test_validate_quick(tmp_path, capsys):
    out = tmp_path / "report"
    code, _, err = _run(
        ["validate", "--turnout", SECOND, "--out", out, "--quick", "--cache", tmp_path / "cache"],
        capsys,
    )
    assert code == 0, err
    m = json.loads((out / "metrics.json").read_text())
    assert m["turnout"] == "EW 54E1-190-1:9"
    p = m["passage"]
    assert list(p["routes"]) == ["main", "branch"] and p["speeds_kmh"] == {
        "main": 100.0,
        "branch": 40.0,
    }
    assert p["x_range_m"] == [23.2, 24.8] and p["impact_route"] == "main"
    assert p["routes"]["branch"]["wheel"] == "left"
    assert m["stiffness"]["statements"]["switch_plateau"]["x_m"] == 9.0
    assert m["stiffness"]["statements"]["crossing_x_range_m"] == [22.0, 26.5]
    assert m["receptance"]["route"] == "main"
    # the FE passage runs on both routes (through the [report] fe_slots mapping), with the
    # profile contact vertical and lateral (issue 14)
    assert p["routes"]["main"]["fe_compared"] == [
        "Fz_crossing",
        "Fy_crossing",
        "Fz_nose",  # the nose event (passage/events.py), F6 is judged there
        "Fy_nose",
    ]
    assert "Fz_crossing" in p["routes"]["branch"]["fe_compared"]
    verdicts = {c["id"]: c["verdict"] for c in m["claims"]}
    assert verdicts["F4"] != "not checked" and verdicts["S2"] != "not checked"
    md = (out / "report.md").read_text()
    # no published set: appendix A lists the derived set per zone, each cell from metrics.json
    derived = m["parameters"]["derived"]
    assert m["parameters"]["entries"] == 0 and list(derived) == ["1", "2", "3", "4"]
    rows = [
        line
        for line in md.split("## Appendix A Parameters")[1].split("\n## ")[0].splitlines()
        if line.startswith("| `")
    ]
    assert len(rows) == len(derived["3"])
    for row in rows:
        name, *cells = (c.strip(" `") for c in row.strip("|").split("|"))
        assert cells == [
            f"{derived[z][name]:.4g}" if name in derived[z] else "n/a" for z in derived
        ]
    assert "EW 54E1-190-1:9" in md and "760 m" not in md and "through route" not in md
    assert {"forces_main.png", "forces_branch.png", "stiffness.png"} <= {
        f.name for f in out.glob("*.png")
    }
