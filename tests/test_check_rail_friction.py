"""The check rail's own friction coefficient, ``[check_rail] friction`` (issue: a lubricated
check rail, mu 0.1-0.2, against the wheel/rail mu 0.4 of ``data/manchester_wheelset.toml``).

- input: absent = the vehicle's mu (``CheckRailDesign.friction`` 0); a bad value is one
  line naming the file and the field;
- kernel: a body's ``bounds[:, 5]`` replaces ``constants[2]`` for that body only, exactly;
- cache: the route's contact key follows the friction;
- passage (slow): friction written equal to the vehicle's mu gives bit-identical columns;
  0.1 bounds every check-rail contact's creep force by 0.1 N.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from exudyn_turnout.cli.main import main
from exudyn_turnout.inputs.turnout import TurnoutFileError, default_turnout_path, load_turnout
from exudyn_turnout.inputs.vehicle import default_vehicle_path, load_vehicle
from exudyn_turnout.passage.contact import route_cache
from exudyn_turnout.wheel_rail import kernel, packed_tables
from exudyn_turnout.wheel_rail.data import s1002_wheel, standard_track
from exudyn_turnout.wheel_rail.geometry import WheelsetSetup
from exudyn_turnout.wheel_rail.tables import build_contact_table
from exudyn_turnout.wheel_rail.turnout_design import rail_geometry

SETUP = WheelsetSetup()
N_Q = 11  # y_w, z_w, phi, psi, beta, y_s, z_s, then left rail (7, 8), right rail (9, 10)
G = 8.1e10  # Pa, steel
ANCHOR = 'flare_shape = "straight"'  # the packaged file's last [check_rail] field


def _turnout_file(tmp_path: Path, line: str | None) -> Path:
    """The packaged turnout with ``line`` added to its ``[check_rail]`` (None: unchanged)."""
    src = default_turnout_path().read_text()
    assert src.count(ANCHOR) == 1
    path = tmp_path / "t.toml"
    path.write_text(src if line is None else src.replace(ANCHOR, f"{ANCHOR}\n{line}", 1))
    return path


def test_friction_is_read_and_absent_means_the_vehicles(tmp_path):
    assert rail_geometry(load_turnout()).check_rail.friction == 0.0  # packaged: absent
    path = _turnout_file(tmp_path, "friction = 0.15")
    assert rail_geometry(load_turnout(path)).check_rail.friction == 0.15


@pytest.mark.parametrize(
    "value, message",
    [
        ("0.0", "check_rail.friction must be"),
        ("-0.1", "check_rail.friction must be"),
        ("2.5", "check_rail.friction"),
        ('"low"', "check_rail.friction must be a number"),
        ("nan", "check_rail.friction must be finite"),
    ],
)
def test_bad_friction_is_one_line_naming_file_and_field(tmp_path, capsys, value, message):
    path = _turnout_file(tmp_path, f"friction = {value}")
    with pytest.raises(TurnoutFileError, match=message.replace(".", r"\.")) as err:
        load_turnout(path)
    assert "t.toml" in str(err.value) and "\n" not in str(err.value)
    assert main(["params", "--turnout", str(path), "--zone", "1"]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and "t.toml" in lines[0] and "check_rail.friction" in lines[0]


def test_limit_two_is_accepted(tmp_path):
    # the plausibility bound is inclusive (mu <= 2: dry steel on steel in vacuum ~ 1)
    assert (
        rail_geometry(load_turnout(_turnout_file(tmp_path, "friction = 2"))).check_rail.friction
        == 2.0
    )


def test_the_route_contact_key_follows_the_friction(tmp_path):
    vehicle = load_vehicle(default_vehicle_path())
    keys = {}
    for label, line in (("absent", None), ("0.1", "friction = 0.1"), ("0.2", "friction = 0.2")):
        sub = tmp_path / label
        sub.mkdir()
        turnout = load_turnout(_turnout_file(sub, line))
        keys[label] = route_cache.route_contact_key(turnout, "diverging", vehicle)
    assert len(set(keys.values())) == 3


@pytest.fixture(scope="module")
def plain(tmp_path_factory):
    track = standard_track(SETUP, np.array([-10.0, 70.0]))
    return build_contact_table(
        s1002_wheel(SETUP), track, SETUP.taping_line, cache_dir=tmp_path_factory.mktemp("t")
    )


def _evaluate(packed, q, q_t, mu):
    forces = np.zeros(N_Q)
    details = np.zeros((packed.n_bodies * packed.n_candidates, len(kernel.DETAIL_FIELDS)))
    constants = np.array([20.0, SETUP.nominal_radius, mu, G, 0.0, 0.0])
    kernel.contact_forces(
        5.0, q, q_t, np.zeros(4), packed.values, packed.blendable, packed.x, packed.layout,
        packed.bounds, constants, forces, details,
    )  # fmt: skip
    return forces, details


@pytest.mark.parametrize("creep_law", ["fastsim", "polach"])
def test_a_bodys_friction_replaces_the_vehicles_for_that_body_only(plain, creep_law):
    args = ([plain, plain], [1, -1], [(7, 8), (9, 10)], [(-10.0, 70.0)] * 2)
    own = packed_tables.pack_tables(*args, creep_law=creep_law, friction=[0.1, 0.0])
    default = packed_tables.pack_tables(*args, creep_law=creep_law)
    assert default.bounds.shape[1] == 6 and np.all(default.bounds[:, 5] == 0.0)
    np.testing.assert_array_equal(own.bounds[:, :5], default.bounds[:, :5])
    q, q_t = np.zeros(N_Q), np.zeros(N_Q)
    q[1] = -3e-4  # both wheels pressed 0.3 mm down (176 kN each, as in test_wheel_rail_kernel)
    q_t[0] = 1.0  # 1 m/s sideways at 20 m/s: eta ~ 0.05, creep forces saturated
    _, mixed = _evaluate(own, q, q_t, 0.4)
    _, low = _evaluate(default, q, q_t, 0.1)
    _, high = _evaluate(default, q, q_t, 0.4)
    n_c = own.n_candidates
    # exactly the run with mu 0.1 on the left body, and with 0.4 on the right one
    np.testing.assert_array_equal(mixed[:n_c], low[:n_c])
    np.testing.assert_array_equal(mixed[n_c:], high[n_c:])
    col = kernel.DETAIL_FIELDS.index
    normal = mixed[:, col("normal")]
    creep = np.hypot(mixed[:, col("Fx")], mixed[:, col("Ft")])
    assert normal[:n_c].max() > 1e4 and normal[n_c:].max() > 1e4
    # |F| <= mu N by construction (Coulomb guard); saturated here: near mu N
    assert np.all(creep[:n_c] <= 0.1 * normal[:n_c] * (1 + 1e-12))
    assert creep[:n_c].max() > 0.08 * normal[:n_c].max()
    assert creep[n_c:].max() > 0.2 * normal[n_c:].max()
    # an explicit friction equal to the vehicle's mu changes nothing, bit for bit
    same = packed_tables.pack_tables(*args, creep_law=creep_law, friction=[0.4, 0.4])
    for a, b in zip(_evaluate(same, q, q_t, 0.4), _evaluate(default, q, q_t, 0.4), strict=True):
        np.testing.assert_array_equal(a, b)


def test_pack_tables_refuses_a_friction_list_of_the_wrong_length(plain):
    with pytest.raises(ValueError, match="one coefficient"):
        packed_tables.pack_tables([plain], [1], [(7, 8)], [(-10.0, 70.0)], friction=[0.1, 0.2])
    with pytest.raises(ValueError, match="one coefficient"):
        packed_tables.pack_tables([plain], [1], [(7, 8)], [(-10.0, 70.0)], friction=[math.nan])


CHECK_STEM = "cp_right_r3_right_wheel_against_the_check_rail_"  # the front wheelset's


@pytest.fixture(scope="module")
def passages(tmp_path_factory):
    """The full vehicle on the diverging route at 80 km/h, front wheelset 44-46 m (the check
    rail's entry, where its flange-back contact lifts the leading right wheel, Delta Q/Q0 = 1
    at x = 45.35 m with mu 0.4), the friction absent, written as the vehicle's 0.4, 0.1, 0.8."""
    from exudyn_turnout.inputs.vehicle_model import load_vehicle_model
    from exudyn_turnout.passage.run import simulate_passage
    from exudyn_turnout.passage.settings import PassageSettings

    model = load_vehicle_model()
    # the contact law's mu 0.4, data/manchester_wheelset.toml (the full vehicle's contact)
    assert load_vehicle(default_vehicle_path()).contact.mu == 0.4
    settings = PassageSettings(
        route="diverging", speed_kmh=80.0, layers=2, x_start=44.0, x_end=46.0
    )
    out = {}
    runs = [(label, f"friction = {label}") for label in ("0.4", "0.1", "0.8")]
    for label, line in [("absent", None), *runs]:
        folder = tmp_path_factory.mktemp(label.replace(".", "_"))
        out[label] = simulate_passage(load_turnout(_turnout_file(folder, line)), settings, model)
    return out


@pytest.mark.slow
def test_the_vehicles_mu_written_out_changes_nothing_bit_for_bit(passages):
    a, b = passages["absent"].columns, passages["0.4"].columns
    assert set(a) == set(b) and len(a) > 100
    for name in a:
        assert np.array_equal(a[name], b[name], equal_nan=True), name


@pytest.mark.slow
def test_a_lubricated_check_rail_bounds_its_creep_forces_and_lifts_less(passages):
    cols = passages["0.1"].columns
    stems = {n[: -len("_N_N")] for n in cols if n.startswith(CHECK_STEM) and n.endswith("_N_N")}
    assert stems  # the check rail carries load in this window
    for stem in stems:
        # NaN where the wheelset's contact element has no check rail (before its zone)
        there = np.isfinite(cols[f"{stem}_N_N"])
        normal = cols[f"{stem}_N_N"][there]
        creep = np.hypot(cols[f"{stem}_Fx_N"][there], cols[f"{stem}_Ft_N"][there])
        assert there.sum() > 100 and normal.max() > 1e4 and np.all(np.isfinite(creep))
        # |F| <= mu N (the creep laws' Coulomb bound), round-off allowed
        assert np.all(creep <= 0.1 * normal * (1.0 + 1e-9) + 1e-9), stem
        assert creep.max() > 0.05 * normal.max()  # it does slide: the bound is reached
    # the friction's share of the check rail's push on the wheel's flange back is upward: with
    # 0.1 the check rail's vertical force and the front right wheel's unloading are smaller
    lube, dry = passages["0.1"], passages["0.4"]
    up = {k: np.nanmax(p.columns["Fz_ws1_right_r3_N"]) for k, p in (("0.1", lube), ("0.4", dry))}
    assert up["0.1"] < 0.7 * up["0.4"]
    q0 = dry.summary["static_wheel_load_N"]
    unloading = {
        k: np.max(1.0 - p.columns["Fz_ws1_right_N"] / q0) for k, p in (("0.1", lube), ("0.4", dry))
    }
    assert unloading["0.4"] == pytest.approx(1.0)  # lifted (the Delta Q/Q0 = 1)
    assert unloading["0.1"] < unloading["0.4"] - 0.03


@pytest.mark.slow
def test_a_check_rail_rougher_than_the_wheel_rail_contact_raises_no_false_alarm(passages):
    # Nadal's limit (the climbing stop) is the running rail's, with the vehicle's mu: a check
    # rail's mu 0.8 must not lower it (0.4 -> Nadal 1.12 at 70.13 deg; 0.8 would give 0.61)
    rough, plain = passages["0.8"].summary, passages["absent"].summary
    assert rough["safety_limits"] == plain["safety_limits"]
    assert rough["safety_limits"]["friction"] == 0.4
    # the run went to its end (a stop raises PassageFailure in the fixture)
    assert passages["0.8"].columns["x_m"][-1] == pytest.approx(46.0, abs=1e-3)
