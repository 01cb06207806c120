"""``exudyn-turnout params``: JSON is a flat object of the documented names in SI units.

Reference values: Table 2 of Shih, Ambur & Dixon (2023) (zone 1, published) and the
derived plain-track values of Eqs 1-9 (k_rt1,z = 369.4e6 N/m, see test_equations.py).
"""

import csv
import io
import json

import pytest

from exudyn_turnout.cli.main import main


def _run(capsys, *argv):
    code = main(list(argv))
    out = capsys.readouterr()
    return code, out.out, out.err


def test_zone1_json_derived_is_flat_table2_form(capsys):
    code, out, _ = _run(capsys, "params", "--zone", "1", "--format", "json")
    data = json.loads(out)
    assert code == 0
    assert all(not isinstance(v, (dict, list)) for v in data.values())
    assert data["k_rt1_z"] == pytest.approx(369e6, rel=0.02)
    assert data["k_rt2_z_factor"] == "Delta_z" and data["k_rt2_z"] == pytest.approx(369e6, rel=0.02)
    assert data["K_st_z"] == pytest.approx(6.4e7, rel=0.01)
    assert data["active_rails"] == "r1 r2 r4"


def test_zone1_json_published_is_the_paper(capsys):
    _, out, _ = _run(capsys, "params", "--zone", "1", "--format", "json", "--source", "published")
    data = json.loads(out)
    assert (data["c_01_z"], data["m_t"], data["J_t"], data["k_tg_y"]) == (315e3, 500.0, 265.0, 56e6)
    assert data["k_tg_y_factor"] == "Delta_y"


def test_x_mode_evaluates_delta(capsys):
    """At x = 10 m, k_rt2,z = 369.4e6 * Delta_z(10) = 369.4e6 * 0.96712 (Eqs 6, 10, 11)."""
    _, out, _ = _run(capsys, "params", "--x", "10", "--format", "json")
    data = json.loads(out)
    assert data["Delta_z"] == pytest.approx(0.96712, rel=1e-4)
    assert data["k_rt2_z"] == pytest.approx(data["k_rt1_z"] * 0.96712, rel=1e-4)


def test_two_layers_has_no_extra_layer(capsys):
    _, out, _ = _run(capsys, "params", "--x", "47", "--layers", "2", "--format", "csv")
    names = [row["name"] for row in csv.DictReader(io.StringIO(out))]
    assert "k_rt3_z" in names and not [n for n in names if n.startswith(("k_0", "c_0", "m_0"))]


def test_table_format_shows_factors(capsys):
    _, out, _ = _run(capsys, "params", "--zone", "2", "--source", "published")
    assert "4.48e+08 -> 4.53e+08 (linear in x)" in out
    assert "* Delta_y" in out


@pytest.mark.parametrize(
    "argv,fragment",
    [
        (["params", "--zone", "4"], "zone 4 does not exist"),
        (["params", "--x", "-6"], "x = -6 m is outside the turnout"),
        (["params", "--x", "nan"], "--x"),
        (["params", "--zone", "1", "--x", "3"], "not allowed with argument"),
        (["params", "--zone", "1", "--layers", "4"], "--layers"),
        (["params", "--zone", "1", "--source", "fe"], "--source"),
        (["params", "--zone", "1", "--frobnicate"], "unrecognized arguments: --frobnicate"),
        (["nosuchcommand"], "invalid choice"),
    ],
)
def test_bad_input_one_line_exit_2(capsys, argv, fragment):
    code, out, err = _run(capsys, *argv)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and fragment in err


@pytest.mark.slow
def test_fe_fitted_profiles(capsys):
    """--profiles fe-fit: Delta_z(x) = K_sw,fit(x) / K_st, the FE fit (fe/fits.py) for Eq 10."""
    from exudyn_turnout.corunning.parameters import reference_support
    from exudyn_turnout.fe.fits import fit_turnout_profiles
    from exudyn_turnout.fe.stiffness import static_stiffness_profile
    from exudyn_turnout.inputs.turnout import load_turnout

    code, out, _ = _run(capsys, "params", "--x", "10", "--format", "json", "--profiles", "fe-fit")
    t = load_turnout()
    fits = fit_turnout_profiles(static_stiffness_profile(t), t)
    assert code == 0
    assert json.loads(out)["Delta_z"] == pytest.approx(
        fits.K_sw(10.0) / reference_support(t).K_st_z, rel=1e-9
    )
    assert json.loads(out)["Delta_z"] != pytest.approx(0.96712, rel=1e-3)  # Eq 10's value differs
