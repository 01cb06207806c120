"""The contact law's two sensitivity knobs (``packed_tables.scale_contact_law``,
``PassageSettings.creep_reduction`` and ``normal_stiffness_factor``).

References:
- normal: the node law N = F_REF (delta / DELTA_REF)^n is linear in F_REF, so the factor
  multiplies the force and the stiffness dN/d(delta) at the same state exactly, and leaves
  the semi-axes (geometry at that penetration) alone;
- creep: far below saturation Kalker's linear theory F_x = -G a b C11 xi (Kalker 1967) is
  linear in C11, so the creep reduction factor multiplies the force; in full slip the force
  is mu N whatever the coefficients (Coulomb);
- both at 1: the tables themselves (the default passage is untouched).
"""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_turnout.inputs.vehicle import load_vehicle
from exudyn_turnout.passage.common import check_settings
from exudyn_turnout.passage.settings import PassageError, PassageSettings
from exudyn_turnout.wheel_rail import kernel, packed_tables
from exudyn_turnout.wheel_rail.geometry import WheelsetSetup

SETUP = WheelsetSetup()
N_Q = 11  # y_w, z_w, phi, psi, beta, y_s, z_s, then left rail (7, 8), right rail (9, 10)
G = 8.1e10  # Pa, steel
V, R0, MU = 27.0, 0.46, 0.4  # m/s, m, -


@pytest.fixture(scope="module")
def plain(plain_packed):
    """S1002 on plain UIC60 track, packed (conftest.py)."""
    return plain_packed


def _rows(packed, v: float = V, xi: float | None = None, mu: float = MU) -> np.ndarray:
    """The loaded contact rows of the wheelset 0.25 mm down (68 um into both rails: it first
    touches 0.18 mm down) at speed v; ``xi``: the spin rate that gives both wheels this
    longitudinal creepage (None: beta_t = 0)."""
    q = np.zeros(N_Q)
    q[1] = -2.5e-4
    q_t = np.zeros(N_Q)

    def rows():
        forces = np.zeros(N_Q)
        details = np.zeros((packed.n_bodies * packed.n_candidates, len(kernel.DETAIL_FIELDS)))
        kernel.contact_forces(
            5.0, q, q_t, np.zeros(4), packed.values, packed.blendable, packed.x, packed.layout,
            packed.bounds, np.array([v, R0, mu, G, 0.0, 0.0]), forces, details,
        )  # fmt: skip
        return details[details[:, kernel.DETAIL_FIELDS.index("normal")] > 0]

    if xi is None:
        return rows()
    r = rows()[:, kernel.DETAIL_FIELDS.index("radius")].mean()
    q_t[4] = (1.0 - xi) * v / r - v / R0  # xi = 1 - (v / R0 + beta_t) r / v
    return rows()


def _col(name: str) -> int:
    return kernel.DETAIL_FIELDS.index(name)


def test_factors_of_one_return_the_tables_themselves(plain):
    assert packed_tables.scale_contact_law(plain) is plain
    assert packed_tables.scale_contact_law(plain, 1.0, 1.0) is plain


@pytest.mark.parametrize("factor", [0.7, 1.35])
def test_normal_factor_multiplies_force_and_stiffness_not_the_patch(plain, factor):
    base = _rows(plain, v=0.0)  # at rest: no creep force in Fz
    scaled = _rows(packed_tables.scale_contact_law(plain, normal=factor), v=0.0)
    assert len(base) == len(scaled) == 2
    for name in ("normal", "Fz", "Fy", "stiffness"):
        np.testing.assert_allclose(scaled[:, _col(name)], factor * base[:, _col(name)], 1e-12)
    for name in ("a", "b", "delta", "y_rail", "angle"):
        np.testing.assert_array_equal(scaled[:, _col(name)], base[:, _col(name)])
    assert plain.values is not packed_tables.scale_contact_law(plain, normal=factor).values


@pytest.mark.parametrize("factor", [0.6, 1.3])
def test_creep_reduction_scales_the_linear_force_and_keeps_saturation(plain, factor):
    """Linear: xi = -1e-5 at mu = 100 (no slip anywhere, also not from the treads' spin);
    full slip: xi = -0.05 at mu = 0.4."""
    scaled_tables = packed_tables.scale_contact_law(plain, creep=factor)
    base = _rows(plain, xi=-1e-5, mu=100.0)
    scaled = _rows(scaled_tables, xi=-1e-5, mu=100.0)
    assert len(base) == len(scaled) == 2
    np.testing.assert_array_equal(scaled[:, _col("normal")], base[:, _col("normal")])
    np.testing.assert_allclose(scaled[:, _col("Fx")], factor * base[:, _col("Fx")], rtol=1e-3)
    for rows in (_rows(plain, xi=-0.05), _rows(scaled_tables, xi=-0.05)):
        assert len(rows) == 2
        resultant = np.hypot(rows[:, _col("Fx")], rows[:, _col("Ft")])
        np.testing.assert_allclose(resultant, MU * rows[:, _col("normal")], rtol=1e-3)


@pytest.mark.parametrize("bad", [0.0, -1.0, float("nan"), float("inf")])
def test_a_factor_that_is_not_positive_is_refused(plain, bad):
    with pytest.raises(ValueError, match="must be a number > 0"):
        packed_tables.scale_contact_law(plain, normal=bad)
    with pytest.raises(ValueError, match="creep"):
        packed_tables.scale_contact_law(plain, creep=bad)


@pytest.mark.parametrize(
    "changes, words",
    [
        ({"creep_reduction": 0.0}, "creep_reduction must be > 0"),
        ({"normal_stiffness_factor": float("nan")}, "normal_stiffness_factor must be > 0"),
        ({"normal_stiffness_factor": 11.0}, "normal_stiffness_factor must be > 0 and <= 10"),
        ({"creep_reduction": 0.8, "contact": "height-table"}, "contact='profile'"),
    ],
)
def test_bad_factors_give_one_line(turnout, changes, words):
    settings = PassageSettings(x_start=10.0, x_end=12.0, **changes)
    with pytest.raises(PassageError, match=words) as err:
        check_settings(settings, turnout, load_vehicle())
    assert "\n" not in str(err.value)


def test_a_stiffer_normal_law_asks_a_finer_time_step(turnout):
    """The limit is ten steps per period of the linear Hertz spring, whose stiffness grows
    as the factor^(2/3): the step's limit shrinks as factor^(-1/3)."""
    vehicle = load_vehicle()
    limit = None
    for step in np.geomspace(1e-5, 1e-3, 200):
        try:
            check_settings(PassageSettings(x_start=10, x_end=12, time_step=step), turnout, vehicle)
        except PassageError:
            break
        limit = step
    assert limit is not None
    stiff = PassageSettings(x_start=10, x_end=12, time_step=limit, normal_stiffness_factor=8.0)
    with pytest.raises(PassageError, match="too large"):
        check_settings(stiff, turnout, vehicle)
    half = PassageSettings(
        x_start=10, x_end=12, time_step=0.49 * limit, normal_stiffness_factor=8.0
    )
    check_settings(half, turnout, vehicle)  # 8^(-1/3) = 0.5


@pytest.mark.parametrize(
    "option, value", [("--creep-reduction", "0"), ("--normal-stiffness-factor", "-2")]
)
def test_the_command_refuses_a_bad_factor_in_one_line(tmp_path, capsys, option, value):
    from exudyn_turnout.cli.main import main

    argv = ["simulate", "--vehicle", "wheelset", "--x-start", "46.5", "--x-end", "48"]
    assert main([*argv, option, value, "--no-plot", "--out", str(tmp_path / "run")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and option[2:].replace("-", "_") in err[0]


def test_the_factors_reach_the_passage(turnout):
    """The single wheelset over the crossing nose (through, 100 km/h): the static start
    carries the same wheel load with any law (equilibrium), and a stiffer normal law raises
    the nose's impact force (the full vehicle's: +4.9 % at 1.34 on the 3-layer track,
    validation/contact_law_sensitivity.md), a lower creep coefficient changes the creep
    forces."""
    from exudyn_turnout.passage import simulate_passage

    window = {"x_start": 40.0, "x_end": 47.6}  # starts before the crossing region

    def run(**changes):
        settings = PassageSettings(**window, **changes)
        return simulate_passage(turnout, settings, "wheelset").columns

    base, stiff, slack = run(), run(normal_stiffness_factor=1.34), run(creep_reduction=0.5)
    fz = "Fz_right_N"
    # equal within the static start's residual (settled: <= 100 N, the StartWarning's
    # criterion); measured 3.3 N
    assert stiff[fz][0] == pytest.approx(base[fz][0], abs=100.0)
    assert 1.01 < np.nanmax(stiff[fz]) / np.nanmax(base[fz]) < 1.3
    fx = [name for name in base if name.startswith("cp_right_") and name.endswith("_Fx_N")]
    assert fx and any(
        not np.allclose(slack[name], base[name], rtol=1e-3, atol=1.0, equal_nan=True) for name in fx
    )
