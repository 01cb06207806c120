"""The Manchester benchmark vehicle 1 as data and in Exudyn (the full vehicle's groundwork).

Sources of the reference numbers:

- static wheel load 44 482 kg x 9.81 / 8 = 54.55 kN on level track: the benchmark's data
  (Iwnicki (ed.) 1998, VSD 30(3-4) 295-313, as in ``data/manchester_vehicle.toml``);
- single wheelset: (1813 + 9307.5) kg x 9.81 / 2, the package's single-wheelset model
  (README "simulate": wheelset 1813 kg with 9307.5 kg of bogie and car body);
- natural frequencies: the hand calculations of ``vehicle_model`` (first principles,
  Garg & Dukkipati 1984, Iwnicki's handbook), each with its tolerance and the reason the
  Exudyn value may differ.
"""

from __future__ import annotations

import math
from dataclasses import FrozenInstanceError, replace

import exudyn as exu
import numpy as np
import pytest

from exudyn_turnout.inputs.vehicle_model import (
    GRAVITY,
    VehicleModelError,
    carbody_bounce_frequency,
    carbody_pitch_frequency,
    carbody_sway_frequencies,
    carbody_yaw_frequency,
    default_vehicle_model_path,
    hand_frequencies,
    load_vehicle_model,
    series,
    single_wheelset_share,
    sway_frequencies,
)
from exudyn_turnout.passage.vehicle.builder import (
    RigidTrack,
    add_vehicle_model,
    connector_forces_at_reference,
    dynamic_settings,
    rigid_track_support,
    solve_static,
    support_wheel_loads,
    vehicle_modes,
)

#: N, the data sheet's static wheel load: 44 482 kg x 9.81 / 8.
SHEET_WHEEL_LOAD = 44482.0 * 9.81 / 8
#: N, the single-wheelset model's static wheel load: (1813 + 9307.5) kg x 9.81 / 2.
SINGLE_WHEEL_LOAD = (1813.0 + 9307.5) * 9.81 / 2

#: The single-wheelset layout of the same file format (values of data/manchester_wheelset.toml).
SINGLE_WHEELSET_TOML = """
[vehicle]
name = "Manchester benchmark wheelset with its sprung share"
description = "one wheelset under car body / 4 + bogie frame / 2"
reference = "Iwnicki (ed.) 1998, Vehicle System Dynamics 30(3-4) 295-313"
wheelsets = 1
bogies = 0

[wheelset]
mass = 1813.0
roll_inertia = 1120.0
spin_inertia = 112.0
yaw_inertia = 1120.0
wheel_radius = 0.46
back_to_back = 1.360
contact_semi_spacing = 0.75
x = [0.0]

[sprung_mass]
mass = 9307.5          # kg = 32000 / 4 + 2615 / 2
height = 0.46          # m, at the primary springs

[primary_suspension]
k_x = 31.391e6
k_y = 3.884e6
k_z = 1.22e6
c_x = 0.0
c_y = 0.0
c_z = 4.0e3
semi_spacing = 1.0
height = 0.46

[contact]              # not read by the vehicle model (the contact law's own table)
mu = 0.4
"""


@pytest.fixture(scope="module")
def model():
    return load_vehicle_model()


def _system(model, track=None, **options):
    """The vehicle on rigid-track supports (default :class:`RigidTrack`), assembled."""
    mbs = exu.SystemContainer().AddSystem()
    build = add_vehicle_model(mbs, model, **options)
    support = rigid_track_support(mbs, build, track if track is not None else RigidTrack())
    mbs.Assemble()
    return mbs, build, support


@pytest.fixture(scope="module", params=["linear", "rigid"])
def static_vehicle(request, model):
    """The full vehicle on rigid track at static equilibrium, and its modes."""
    mbs, build, support = _system(model, representation=request.param)
    solve_static(mbs)
    return mbs, build, support, vehicle_modes(mbs, build)


# ------------------------------------------------------------------------------- the file
def test_packaged_vehicle_file(model):
    assert (model.n_wheelsets, model.n_bogies) == (4, 2)
    assert model.wheelset.x == (0.0, -2.56, -19.0, -21.56)
    assert model.total_mass == pytest.approx(44482.0, abs=1e-9)  # the sheet's total mass
    assert model.unsprung_mass_per_wheel == 906.5  # the sheet's unsprung mass per wheel
    assert model.bogie.x == (-1.28, -20.28) and model.car_body.x == (-10.78,)
    text = default_vehicle_model_path().read_text(encoding="utf-8")
    assert "doi:10.1080/00423119808969454" in text
    lines = text.splitlines()
    # the values the sheet says to confirm are marked so (on their line or the next)
    for field in ("k_z = 1.22e6", "c_x = 0.0", "c_y = 0.0", "[anti_roll]", "clearance = 0.025"):
        i = next(k for k, line in enumerate(lines) if line.startswith(field))
        assert "TO CONFIRM" in lines[i] + lines[i + 1], field
    with pytest.raises(FrozenInstanceError):
        model.car_body.mass = 1.0  # type: ignore[misc]


def test_static_wheel_loads_from_the_data(model):
    """Lever rule on the data: every wheel 54.55 kN (the sheet's 44 482 x 9.81 / 8)."""
    loads = np.array(model.static_wheel_loads())
    assert np.all(np.abs(loads / SHEET_WHEEL_LOAD - 1) < 1e-3)
    assert model.static_wheel_load == pytest.approx(SHEET_WHEEL_LOAD, rel=1e-12)


def test_static_wheel_loads_on_rigid_track(static_vehicle):
    """Exudyn: every one of the 8 wheels carries 54.55 kN within 0.1 % (data sheet)."""
    mbs, build, support, _ = static_vehicle
    loads = support_wheel_loads(mbs, support)
    assert loads.shape == (4, 2)
    assert np.all(np.abs(loads / SHEET_WHEEL_LOAD - 1) < 1e-3), loads


@pytest.mark.parametrize(
    "options",
    [{}, {"wheelset_spin": True}, {"bumpstop": "python"}],
    ids=["default", "spin", "python-bumpstop"],
)
def test_every_connector_force_free_at_rest(model, options):
    """Rigid representation: each Connector* reads zero force/torque with all coordinates 0."""
    mbs, build, _ = _system(model, RigidTrack(k_x=1e7), representation="rigid", **options)
    forces = connector_forces_at_reference(mbs)
    # 8 primary + 4 secondary + 2 torsion (yaw, anti-roll) + 2 bumpstops + 8 track supports
    assert len(forces) == 24
    kinds = {mbs.GetObject(i)["objectType"] for i in forces}
    assert kinds == {"ConnectorCartesianSpringDamper", "ConnectorRigidBodySpringDamper"}
    for i, f in forces.items():
        assert np.max(np.abs(f)) < 1e-6, f"connector {i} carries {f} at rest"


def test_single_wheelset_connectors_force_free(tmp_path):
    path = tmp_path / "single.toml"
    path.write_text(SINGLE_WHEELSET_TOML, encoding="utf-8")
    mbs, _, _ = _system(load_vehicle_model(path), representation="rigid")
    forces = connector_forces_at_reference(mbs)
    assert len(forces) == 4  # two axleboxes (with their offsets), two wheel supports
    assert all(np.max(np.abs(f)) < 1e-6 for f in forces.values())


def test_linear_model_is_the_rigid_model_linearised(model):
    """Same static equilibrium (to round-off) and the same modes (to 0.1 %: the linear model
    leaves out the wheel-support preload's geometric roll term, -2 r0 Q = -50 kN m/rad)."""
    rigid_mbs, rigid, _ = _system(model, representation="rigid")
    q_rigid = solve_static(rigid_mbs)
    lin_mbs, linear, _ = _system(model)
    q_lin = solve_static(lin_mbs)
    for a, b in zip(rigid.bodies(), linear.bodies()):
        for name, k in b.dof.items():
            qa = q_rigid[rigid_mbs.GetNodeODE2Index(a.node) + a.dof[name]]
            qb = q_lin[lin_mbs.GetNodeODE2Index(b.node) + k]
            assert qb == pytest.approx(qa, abs=1e-9), f"{b.name}.{name}"
    f_rigid = [m.frequency_hz for m in vehicle_modes(rigid_mbs, rigid)]
    f_lin = [m.frequency_hz for m in vehicle_modes(lin_mbs, linear)]
    assert np.allclose(f_lin, f_rigid, rtol=1e-3)


def test_linear_builds_of_one_vehicle_share_the_rigid_linearisation(model):
    """The linear representation's M, K, D, static state and force vector, kept for a model
    (the passage builds one vehicle per segment), equal a first build's bit for bit; a
    changed model gets its own (its stiffer primary springs change K)."""

    def matrices(m):
        mbs, build, _ = _system(m)
        item = build.items["suspension"]
        return [
            np.array(mbs.GetObjectParameter(item, name).GetPythonObject(), dtype=float)
            for name in ("massMatrix", "stiffnessMatrix", "dampingMatrix")
        ] + [np.array(mbs.GetObjectParameter(item, "forceVector")), np.array(build.static_state)]

    first, again = matrices(model), matrices(model)
    for a, b in zip(first, again):
        assert np.array_equal(a, b)
    stiffer = replace(model, primary=replace(model.primary, k_z=2.0 * model.primary.k_z))
    assert not np.array_equal(matrices(stiffer)[1], first[1])
    assert np.array_equal(matrices(model)[1], first[1])  # the first one still served


def test_bumpstop_characteristic(model):
    stop = model.bumpstop
    assert stop.lateral_force(0.0) == 0.0 and stop.lateral_force(0.025) == 0.0
    for u, f in zip(stop.displacement, stop.force):
        assert stop.lateral_force(u) == pytest.approx(f, rel=1e-12)
        assert stop.lateral_force(-u) == pytest.approx(-f, rel=1e-12)
    last = (stop.force[-1] - stop.force[-2]) / (stop.displacement[-1] - stop.displacement[-2])
    assert stop.lateral_force(0.07) == pytest.approx(stop.force[-1] + 0.005 * last)


def test_bumpstop_same_in_both_representations(model):
    """Car body released 40 mm off centre (bumpstops engaged): both representations give the
    same car-body motion over 0.2 s (they differ by the rigid model's finite rotations and
    the support preload term only)."""
    out = []
    for rep in ("linear", "rigid"):
        mbs, build, _ = _system(model, representation=rep)
        solve_static(mbs)
        q = np.array(mbs.systemData.GetODE2Coordinates(exu.ConfigurationType.Initial))
        i_y = mbs.GetNodeODE2Index(build.car_body.node) + build.car_body.dof["y"]
        q[i_y] += 0.04
        mbs.systemData.SetODE2Coordinates(q, exu.ConfigurationType.Initial)
        previous, exu.config.printToConsole = exu.config.printToConsole, False
        try:
            mbs.SolveDynamic(dynamic_settings(0.2, 2e-4))
        finally:
            exu.config.printToConsole = previous
        out.append(mbs.systemData.GetODE2Coordinates()[i_y] - q[i_y] + 0.04)
    assert abs(out[0] - 0.04) > 5e-3  # it moved (the bumpstop pushed it back)
    assert out[0] == pytest.approx(out[1], abs=2e-5)


# ---------------------------------------------------------------- frequencies vs hand values
def _by_kind(modes, kind: str, directions: tuple[str, ...], f_max: float = 100.0) -> list[float]:
    return sorted(
        m.frequency_hz
        for m in modes
        if m.body.rstrip("0123456789") == kind
        and m.direction in directions
        and m.frequency_hz < f_max
    )


#: (hand key, body kind, dominant directions, which of the sorted matches, tolerance, reason)
FREQUENCY_CHECKS = [
    (
        "carbody_bounce",
        "car_body",
        ("z",),
        0,
        0.01,
        "hand: secondary in series with primary and track, bogie mass neglected",
    ),
    ("carbody_pitch", "car_body", ("pitch",), 0, 0.01, "as bounce"),
    (
        "carbody_yaw",
        "car_body",
        ("yaw",),
        0,
        0.03,
        "hand: bogies held; Exudyn: bogies yaw/shift on primary + track springs",
    ),
    (
        "carbody_lower_sway",
        "car_body",
        ("y", "roll"),
        0,
        0.05,
        "hand: quasi-static series of secondary and primary; Exudyn: bogie lateral-roll coupled",
    ),
    ("carbody_upper_sway", "car_body", ("y", "roll"), -1, 0.05, "as lower sway"),
    ("bogie_bounce", "bogie", ("z",), 0, 0.02, "hand: car body held (it is 12x heavier)"),
    ("bogie_pitch", "bogie", ("pitch",), 0, 0.02, "hand: car body held"),
    (
        "bogie_lower_sway",
        "bogie",
        ("y", "roll"),
        0,
        0.04,
        "hand: car body and wheelsets held; Exudyn: wheelsets on track springs",
    ),
    ("bogie_upper_sway", "bogie", ("y", "roll"), -1, 0.04, "as bogie lower sway"),
    ("wheelset_bounce", "wheelset", ("z",), 0, 0.01, "hand: bogie held"),
]


@pytest.mark.parametrize(
    "key, kind, directions, pick, tolerance, reason",
    FREQUENCY_CHECKS,
    ids=[c[0] for c in FREQUENCY_CHECKS],
)
def test_frequency_vs_hand(static_vehicle, model, key, kind, directions, pick, tolerance, reason):
    *_, modes = static_vehicle
    track = RigidTrack()
    hand = hand_frequencies(model, track.k_z, track.k_y)[key]
    found = _by_kind(modes, kind, directions, f_max=20.0 if kind != "wheelset" else 100.0)
    assert found, f"no {kind} {directions} mode"
    exudyn_value = found[pick]
    assert exudyn_value == pytest.approx(hand, rel=tolerance), reason


def test_car_body_modes_exact_on_held_bogies(model):
    """With primary and track springs at 1e11 N/m the bogies are held: the car body's modes
    then equal the textbook hand values (secondary suspension alone) to 1e-4 (measured
    5e-6), in both representations: a check of every lever arm, height and the
    gravitational term."""
    stiff = replace(model, primary=replace(model.primary, k_x=1e11, k_y=1e11, k_z=1e11))
    lower, upper = carbody_sway_frequencies(stiff, bogies_held=True)
    hand = {
        "y": lower,
        "roll": upper,
        "z": carbody_bounce_frequency(stiff),
        "pitch": carbody_pitch_frequency(stiff),
        "yaw": carbody_yaw_frequency(stiff),
    }
    for representation in ("linear", "rigid"):
        mbs, build, _ = _system(
            stiff, RigidTrack(k_z=1e11, k_y=1e11), representation=representation
        )
        solve_static(mbs)
        body = {
            m.direction: m.frequency_hz for m in vehicle_modes(mbs, build) if m.body == "car_body"
        }
        assert body == pytest.approx(hand, rel=1e-4), representation


def test_car_body_modes_are_damped(static_vehicle):
    *_, modes = static_vehicle
    body = [m for m in modes if m.body == "car_body"]
    assert len(body) == 5
    assert all(0.05 < m.damping_ratio < 0.8 for m in body)


def test_hand_formulas_limits():
    assert series(2.0, 2.0) == 1.0 and series(3.0, math.inf) == 3.0
    lo, hi = sway_frequencies(4.0, 1.0, 16.0, 0.0, 36.0)  # uncoupled: sqrt(k/m) / 2 pi
    assert (lo, hi) == pytest.approx((2 / (2 * math.pi), 6 / (2 * math.pi)))


def test_default_rigid_track_is_hertz_in_series_with_plain_track():
    """RigidTrack.k_z: 1.5 C_H^(2/3) N^(1/3) (C_H 9e10, N 54.55 kN) in series with 6.37e7."""
    k_hertz = 1.5 * 9.0e10 ** (2 / 3) * SHEET_WHEEL_LOAD ** (1 / 3)
    assert RigidTrack().k_z == pytest.approx(series(k_hertz, 6.3694e7), rel=2e-3)


# ------------------------------------------------------------ single wheelset, same code path
def test_single_wheelset_through_the_same_loader(tmp_path, model):
    path = tmp_path / "single.toml"
    path.write_text(SINGLE_WHEELSET_TOML, encoding="utf-8")
    single = load_vehicle_model(path)
    assert (single.n_wheelsets, single.n_bogies, single.car_body) == (1, 0, None)
    assert single.static_wheel_load == pytest.approx(SINGLE_WHEEL_LOAD, rel=1e-12)
    derived = single_wheelset_share(model)
    assert derived.sprung_mass.mass == pytest.approx(9307.5, rel=1e-12)
    assert derived.static_wheel_loads() == pytest.approx(single.static_wheel_loads(), rel=1e-12)
    assert derived.primary == single.primary
    for representation in ("linear", "rigid"):
        mbs, build, support = _system(single, representation=representation)
        solve_static(mbs)
        loads = support_wheel_loads(mbs, support)
        assert loads.shape == (1, 2)
        assert np.all(np.abs(loads / SINGLE_WHEEL_LOAD - 1) < 1e-3), (representation, loads)
        assert build.wheelsets[0].x == 0.0 and not build.bogies


def test_wheelset_handles(model):
    mbs, build, _ = _system(model)
    assert [ws.x for ws in build.wheelsets] == [0.0, -2.56, -19.0, -21.56]
    assert dict(build.wheelsets[0].dof) == {"y": 0, "z": 1, "roll": 2, "yaw": 3}
    assert build.wheelsets[0].wheel_positions == ((-0.75, -0.46, 0.0), (0.75, -0.46, 0.0))
    mbs, build, _ = _system(model, representation="rigid")
    assert all(len(ws.wheel_markers) == 2 for ws in build.wheelsets)


# ------------------------------------------------------------------------------- bad files
def _variant(tmp_path, old: str, new: str):
    text = default_vehicle_model_path().read_text(encoding="utf-8")
    assert old in text
    path = tmp_path / "bad.toml"
    path.write_text(text.replace(old, new, 1), encoding="utf-8")
    return path


@pytest.mark.parametrize(
    "old, new, field",
    [
        ("mass = 32000.0", "mass = nan", "car_body.mass"),
        ("mass = 32000.0", "mass = inf", "car_body.mass"),
        ("mass = 2615.0", "mass = -2615.0", "bogie.mass"),
        ("mass = 1813.0", "mass = 0.0", "wheelset.mass"),
        ("mass = 1813.0", "mass = '1813'", "wheelset.mass"),
        ("k_z = 430.0e3", "k_z = 4.3e13", "secondary_suspension.k_z"),
        ("c_y = 32.0e3", "c_y = -1.0", "secondary_suspension.c_y"),
        ("cog_height = 1.8", "cog_heigth = 1.8", "car_body.cog_height"),
        ("wheelsets = 4", "wheelsets = 3", "wheelset.x"),
        ("bogies = 2", "bogies = 1", "vehicle.bogies"),
        ("wheelsets = 4", "wheelsets = 4.0", "vehicle.wheelsets"),
        ("x = [0.0, -2.56,", "x = [0.5, -2.56,", "wheelset.x"),
        ("bogie = [1, 1, 2, 2]", "bogie = [1, 1, 1, 2]", "wheelset.bogie"),
        ("wheel_radius = 0.46", "wheel_radius = 4.6", "wheelset.wheel_radius"),
        ("force = [0.6e3,", "force = [6e3,", "lateral_bumpstop.force"),
        ("x = -10.78", "x = -30.0", "car_body.x"),
    ],
)
def test_bad_vehicle_file(tmp_path, old, new, field):
    with pytest.raises(VehicleModelError) as err:
        load_vehicle_model(_variant(tmp_path, old, new))
    message = str(err.value)
    assert "\n" not in message and message.startswith("bad.toml: ") and field in message, message
    assert isinstance(err.value, ValueError)


def test_unreadable_vehicle_files(tmp_path):
    with pytest.raises(VehicleModelError, match="missing.toml: cannot be read"):
        load_vehicle_model(tmp_path / "missing.toml")
    (tmp_path / "latin.toml").write_bytes("name = 'caf\xe9'".encode("latin-1"))
    with pytest.raises(VehicleModelError, match="latin.toml: is not UTF-8"):
        load_vehicle_model(tmp_path / "latin.toml")
    (tmp_path / "broken.toml").write_text("[vehicle\n", encoding="utf-8")
    with pytest.raises(VehicleModelError, match="broken.toml: is not valid TOML"):
        load_vehicle_model(tmp_path / "broken.toml")
    text = SINGLE_WHEELSET_TOML + "\n[car_body]\nmass = 1.0\n"
    (tmp_path / "mixed.toml").write_text(text, encoding="utf-8")
    with pytest.raises(VehicleModelError, match=r"mixed.toml: \[car_body\] must be absent"):
        load_vehicle_model(tmp_path / "mixed.toml")


def test_gravity_constant_matches_the_sheet():
    assert GRAVITY == 9.81
