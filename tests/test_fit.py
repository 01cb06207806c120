"""Co-running parameters fitted to a receptance (issue 16): corunning.fit, corunning.fitted, CLI.

References: the co-running model's own receptance (modal superposition of the hand-assembled
M, K, D, exudyn_turnout.corunning.modal), which a fit to it must reproduce exactly; the FE
receptance of exudyn_turnout.fe (coarse mesh, see below); the band RMS of
20 log10(|H_model|/|H_FE|) over one-third-octave bands (IEC 61260 base-10 centres) and
the ranges 1-125, 125-500, 500-2000 Hz of the validation report. Exudyn runs headless and
quiet; files only under tmp_path.

Speed: the FE reference here is the quick report's coarse mesh (quadratic elements of
0.6 m, 6 m model ends) at 60 frequencies and one position (the switch receptance point), and
the fit uses the switch rail r2 only; the full fit (fine mesh, 400 frequencies, every rail,
along the turnout) is in validation/fitted_parameters.py.
"""

import dataclasses
import math

import numpy as np
import pytest

from exudyn_turnout.cli.main import main
from exudyn_turnout.corunning import fit as F
from exudyn_turnout.corunning.fitted import (
    FittedSet,
    TableEntry,
    read_fitted,
    with_fitted,
    write_fitted,
)
from exudyn_turnout.corunning.modal import co_running_receptance
from exudyn_turnout.corunning.parameters import co_running_parameters
from exudyn_turnout.receptance import Receptance, log_frequencies

X_SWITCH = 3.889  # m, the switch receptance point of the validation report (zone 1)
RANGES = ((1.0, 125.0), (125.0, 500.0), (500.0, 2000.0))  # Hz, the goal ranges


def _run(capsys, *argv):
    code = main([str(a) for a in argv])
    out = capsys.readouterr()
    return code, out.out, out.err


def test_fit_recovers_known_parameters(turnout):
    """A fit to the model's own receptance recovers the parameter set that made it.

    Known set: the derived set at x = 3.9 m with every free entry scaled by a factor of
    0.77-1.3 (a pattern, not random); start: the derived set, i.e. 13-30 % off. Targets:
    r2 vertical and lateral, 120 frequencies 1-2000 Hz, noise-free. The entries of the
    other rails and the r4-side ballast spring k_tg2 are held (r2's receptance sees k_tg2
    only through the sleeper's roll). Tolerance 1e-6 relative: the data are exact, so
    the fit must reach round-off (measured 2e-12) up to the optimiser's stopping rule
    (ftol = xtol = gtol = 1e-8 on log-parameters).
    """
    x = 3.9
    params = co_running_parameters(turnout, x=x, layers=3)
    base = {n: v for n, v in params.at(x).items() if n in params.entries}
    free = [n for n in F.free_parameters(params, ["r2"]) if not n.startswith(("k_tg2", "c_tg2"))]
    assert {"k_rt2_z", "c_02_y", "m_0", "m_t", "m_r2", "k_tg_y"} <= set(free)
    factors = (1.25, 0.8, 1.15, 0.87, 1.3, 0.77)
    truth = dict(base)
    truth.update({n: base[n] * factors[i % len(factors)] for i, n in enumerate(free)})
    truth["J_t"] = base["J_t"] * truth["m_t"] / base["m_t"]  # Eq 19: J_t follows m_t
    f = log_frequencies(1.0, 2000.0, 120)
    known = F.parameters_with_values(params, truth)
    targets = [
        F.FitTarget(
            "r2", d, Receptance(f, F.model_receptance(known, x, "r2", d, f), "r2", d, x, "known")
        )
        for d in ("vertical", "lateral")
    ]
    fixed = {n: v for n, v in base.items() if n not in free and n != "J_t"}
    result = F.fit_position(params, x, targets, fixed=fixed)
    assert result.cost_start > 1.0  # the start is far off (dB^2)
    for name in free:
        assert result.values[name] == pytest.approx(truth[name], rel=1e-6), name
    assert result.values["J_t"] == pytest.approx(truth["J_t"], rel=1e-6)


N_FE = 60  # FE frequencies of the coarse reference (log-spaced 1-2000 Hz)


@pytest.fixture(scope="module")
def switch_targets(turnout):
    """Coarse FE receptances of r2 (vertical, lateral) at the switch point, as fit targets."""
    from exudyn_turnout.cli.fit import coarse_fe_options, fe_fit_targets

    zone = turnout.zone_at(X_SWITCH)
    f = log_frequencies(1.0, 2000.0, N_FE)
    targets, rails = fe_fit_targets(turnout, zone, [X_SWITCH], f, coarse_fe_options(), rails=["r2"])
    assert rails == ("r2",) and [t.reference.model for t in targets[0]] == ["FE", "FE"]
    return targets


@pytest.fixture(scope="module")
def switch_fit(turnout, switch_targets):
    """Fit of r2 (vertical and lateral) at the switch point to the coarse FE receptance."""
    params = co_running_parameters(turnout, x=X_SWITCH, layers=3)
    return params, F.fit_zone(params, [X_SWITCH], switch_targets)


def test_fitted_band_rms_at_most_derived_in_every_range(switch_fit):
    """Fitted vs derived 3-layer model against FE at the switch point, r2 both directions.

    In each range 1-125, 125-500, 500-2000 Hz (pinned-pinned band and one band either side
    left out, as the report's claim R3), the fitted model's band RMS is at most the
    derived one's; and the static stiffness 1/|H(1 Hz)| is within 5 % of FE's (the
    issue's goal; derived: 0.80 and 0.89 of FE). Per single one-third-octave band this is
    not guaranteed (a least-squares trade-off): measured, the pinned-pinned bands and the
    2 kHz lateral band (+0.1 dB) get worse; that is reported in
    validation/fitted_parameters.md, not asserted here.
    """
    _, zone_fit = switch_fit
    (position,) = zone_fit.positions
    assert position.cost < 0.5 * position.cost_start
    assert {(r.rail, r.direction) for r in position.residuals} == {
        ("r2", "vertical"),
        ("r2", "lateral"),
    }
    for r in position.residuals:
        for lo, hi in RANGES:
            derived, fitted = r.range_rms(lo, hi, fitted=False), r.range_rms(lo, hi)
            assert math.isfinite(derived) and fitted <= derived, (r.direction, lo, hi)
        assert r.static_ratio_fitted == pytest.approx(1.0, abs=0.05), r.direction
        assert abs(r.static_ratio_start - 1.0) > 0.05  # the derived set misses it


def test_round_trip_of_a_fitted_file(turnout, switch_fit, tmp_path):
    """Written and read back, the fitted set gives the same receptance to 1e-12 (relative).

    The set: the switch-point fit (constants) plus a three-point table for k_rt2_z and
    c_0_2y; receptances of r2, vertical and lateral, at the fit point and between table
    points, through co_running_receptance(source="fitted"). Floats are written with
    repr(), which round-trips exactly; the 1e-12 allows for round-off only.
    """
    params, zone_fit = switch_fit
    zone = params.zone
    entries = dict(zone_fit.entries())
    s_points = (0.1, 0.2, 0.9)
    base_k, base_c = entries["k_rt2_z"].a, entries["c_02_y"].a
    entries["k_rt2_z"] = TableEntry.of(s_points, (base_k, 1.3 * base_k, 0.8 * base_k))
    entries["c_02_y"] = TableEntry.of(s_points, (base_c, 0.5 * base_c, 2.0 * base_c))
    fitted = F.fitted_set([zone_fit], 3, {"turnout_file": "uic60_760_1_15.toml"})
    fitted = dataclasses.replace(fitted, entries={zone.index: entries})
    path = tmp_path / "fitted.toml"
    write_fitted(path, fitted)
    back = read_fitted(path, turnout)
    assert back.layers == 3 and back.entries[zone.index].keys() == entries.keys()
    assert isinstance(back.entries[zone.index]["k_rt2_z"], TableEntry)
    before, after = with_fitted(turnout, fitted), with_fitted(turnout, back)
    f = log_frequencies(1.0, 2000.0, 50)
    for x in (X_SWITCH, zone.x_start + 0.5 * (zone.x_end - zone.x_start)):
        for d in ("vertical", "lateral"):
            h0 = co_running_receptance(before, 3, "r2", d, x=x, source="fitted", frequencies=f)
            h1 = co_running_receptance(after, 3, "r2", d, x=x, source="fitted", frequencies=f)
            np.testing.assert_allclose(h1.H, h0.H, rtol=1e-12, atol=0)
    # the fitted values are what the set evaluates to at the fit point
    at = co_running_parameters(after, x=X_SWITCH, layers=3, source="fitted").at(X_SWITCH)
    (position,) = zone_fit.positions
    for name in ("m_0", "m_r2", "k_tg1_z", "k_02_y"):
        assert at[name] == pytest.approx(position.values[name], rel=1e-15)
    # a table entry: linear in s between its points, held outside them
    s_mid = 0.15
    x_mid = zone.x_start + s_mid * (zone.x_end - zone.x_start)
    k_mid = co_running_parameters(after, x=x_mid, layers=3, source="fitted").at(x_mid)["k_rt2_z"]
    assert k_mid == pytest.approx(1.15 * base_k, rel=1e-12)
    assert co_running_parameters(after, zone=1, source="fitted").at(zone.x_end)[
        "k_rt2_z"
    ] == pytest.approx(0.8 * base_k, rel=1e-12)


def test_table_entries_in_the_exudyn_track_follow_x(turnout, tmp_path, monkeypatch):
    """EntryLaw evaluates a table entry for floats and symbolic x as CoRunningParameters.at.

    Reference: the hand-assembled K of corunning.modal at the same x. Exudyn linearises the
    user-function springs by finite differences: 1e-6 of the largest entry, as
    tests/test_track.py.
    """
    exu = pytest.importorskip("exudyn")
    from exudyn_turnout.corunning.modal import assemble_track_matrices
    from exudyn_turnout.corunning.track import (
        EntryLaw,
        add_co_running_track,
        linearized_matrices,
    )

    monkeypatch.chdir(tmp_path)
    zone = turnout.zone(2)
    derived = co_running_parameters(turnout, zone=2, layers=3)
    values = derived.at(47.0)
    entries = {
        name: TableEntry.of((0.0, 0.4, 1.0), (values[name], 2.0 * values[name], values[name]))
        for name in ("k_rt2_z", "c_rt2_z", "k_02_y", "k_tg1_z")
    }
    entries["m_0"] = dataclasses.replace(derived.entries["m_0"])
    fitted = FittedSet(3, {2: entries}, {2: ((0.0, 0.4, 1.0), ())})
    params = co_running_parameters(with_fitted(turnout, fitted), zone=2, source="fitted")
    law = EntryLaw.of(params)
    for x in (zone.x_start - 1.0, 45.5, 47.0, 50.2, zone.x_end + 1.0):
        s = (x - zone.x_start) / (zone.x_end - zone.x_start)
        for name in entries:
            assert law.value(params.entries[name], x) == pytest.approx(
                params.entries[name].value(1.0, 1.0, s), rel=1e-13
            )
    was = exu.config.printToConsole
    exu.config.printToConsole = False
    try:
        for x0 in (45.5, 47.0):
            mbs = exu.SystemContainer().AddSystem()
            handles = add_co_running_track(mbs, params, x0, 0.0, mechanism="symbolic")
            mbs.Assemble()
            assert "pad_r2" in handles.position_dependent
            K = linearized_matrices(mbs, handles).K
            hand = assemble_track_matrices(params, x0).K
            assert np.max(np.abs(K - hand)) <= 1e-6 * np.max(np.abs(hand))
    finally:
        exu.config.printToConsole = was
    assert list(tmp_path.iterdir()) == []


def test_cli_fit_then_source_fitted(capsys, tmp_path, monkeypatch, switch_targets):
    """``fit`` writes a file that ``params`` and ``frf`` use with --source fitted.

    The FE sweep is the one of the ``switch_targets`` fixture (same mesh, frequencies,
    position and rail, checked below), handed to the command in place of its own
    ``fe_fit_targets`` call to keep the test fast; everything after it is the command's.
    """
    import exudyn_turnout.cli.fit as cli_fit

    def cached_targets(turnout, zone, positions, frequencies, options, route, rails, lateral):
        assert (zone.index, list(positions), list(rails), route, lateral) == (
            1,
            [X_SWITCH],
            ["r2"],
            "through",
            "torsion",  # the default: the FE passages' lateral track
        )
        assert options == cli_fit.coarse_fe_options() and len(frequencies) == N_FE
        np.testing.assert_allclose(frequencies, switch_targets[0][0].reference.frequency_hz)
        return switch_targets, ("r2",)

    monkeypatch.setattr(cli_fit, "fe_fit_targets", cached_targets)
    out = tmp_path / "fitted.toml"
    code, stdout, _ = _run(
        capsys,
        "fit",
        "--out",
        out,
        "--positions",
        X_SWITCH,
        "--rails",
        "r2",
        "--coarse",
        "--n",
        N_FE,
    )
    assert code == 0, stdout
    assert "wrote" in stdout and "zone 1" in stdout
    fitted = read_fitted(out)
    assert fitted.provenance["turnout_file"] == "uic60_760_1_15.toml"
    assert len(fitted.provenance["turnout_sha256"]) == 64
    assert fitted.provenance["fe_options"]["element_order"] == 2
    assert fitted.provenance["n_frequencies"] == N_FE
    assert fitted.provenance["lateral_fe"] == "torsion"
    assert "# FE reference: vertical: FE vertical plane" in out.read_text().splitlines()[2]
    assert fitted.residuals[1] and "fitted_db" in fitted.residuals[1][0]
    code, stdout, _ = _run(
        capsys,
        "params",
        "--source",
        "fitted",
        "--parameters",
        out,
        "--x",
        X_SWITCH,
        "--format",
        "json",
    )
    assert code == 0 and '"source": "fitted"' in stdout
    import json

    values = json.loads(stdout)
    assert values["m_0"] == pytest.approx(fitted.entries[1]["m_0"].a, rel=1e-8)
    csv_out = tmp_path / "h.csv"
    code, stdout, _ = _run(
        capsys,
        "frf",
        "--source",
        "fitted",
        "--parameters",
        out,
        "--x",
        X_SWITCH,
        "--layers",
        "3",
        "--rail",
        "r2",
        "--direction",
        "lateral",
        "--n",
        "20",
        "--out",
        csv_out,
    )
    assert code == 0 and csv_out.is_file()
    # the 3-layer fit is not a 2-layer set: one line, exit 2
    code, _, err = _run(
        capsys, "params", "--source", "fitted", "--parameters", out, "--zone", "1", "--layers", "2"
    )
    assert code == 2 and "3-layer" in err and len(err.strip().splitlines()) == 1
    # a zone without fitted parameters: one line, exit 2
    code, _, err = _run(capsys, "params", "--source", "fitted", "--parameters", out, "--zone", "2")
    assert code == 2 and "no fitted parameters for zone 2" in err


@pytest.mark.parametrize(
    "content,expected",
    [
        (None, "--source fitted needs --parameters"),
        ("this is not toml [", "not valid TOML"),
        ("[fitted]\nlayers = 3\n", "[zoneN] is missing"),
        ("[fitted]\nlayers = 4\n[zone1]\ns = [0.5]\n", "fitted.layers must be 2 or 3"),
        (
            "[fitted]\nlayers = 3\n[zone1]\ns = [0.5]\n[zone1.entries]\nm_0 = 2.5\n"
            "k_rt2_z = -1.0\n",
            "zone1.entries.k_rt2_z must be > 0",
        ),
        (
            "[fitted]\nlayers = 3\n[zone1]\ns = [0.2, 0.5]\n[zone1.entries]\nm_0 = 2.5\n"
            "k_rt2_z = [1e8]\n",
            "zone1.entries.k_rt2_z must be a list of 2 numbers",
        ),
        (
            "[fitted]\nlayers = 3\n[zone9]\ns = [0.5]\n[zone9.entries]\nm_0 = 2.5\n",
            "zone9 names no zone",
        ),
        (
            "[fitted]\nlayers = 3\n[zone1]\ns = [0.5]\n[zone1.entries]\nm_0 = 2.5\nk_x = 1.0\n",
            "zone1.entries.k_x is not a co-running parameter name",
        ),
    ],
)
def test_bad_fitted_input_is_one_line_exit_2(capsys, tmp_path, content, expected):
    """Bad input: one line on stderr naming the option, or the file and the field; exit 2."""
    argv = ["params", "--source", "fitted", "--zone", "1"]
    if content is not None:
        path = tmp_path / "bad.toml"
        path.write_text(content, encoding="utf-8")
        argv += ["--parameters", str(path)]
    code, stdout, err = _run(capsys, *argv)
    assert code == 2 and stdout == ""
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert expected in err
    if content is not None:
        assert "bad.toml" in err


def test_packaged_fitted_file(turnout):
    """The packaged fitted set (``exudyn-turnout fit --every 4``) reads and serves every zone.

    Checks on the shipped file: three layers, zones 1-3, every entry positive and finite
    at each zone's start, middle and end; and its stored residuals: at every fit position
    the fit's objective (weighted band RMS of all targets, final pass with masses fixed per
    zone) is below the derived set's, and for the switch rail / crossing slot r2 at every
    position and direction the band RMS over 1-2000 Hz (pinned-pinned bands left out) is
    at most the derived one's. Not asserted, reported: 4 of 180 rows (r1 vertical at
    33.9-44.1 m, where r1 and r2 share the sleeper end and its ballast spring) end up to
    0.04 dB worse than derived, a trade for r2's static stiffness.
    """
    from importlib import resources

    path = resources.files("exudyn_turnout") / "data" / "uic60_760_1_15_fitted.toml"
    fitted = read_fitted(str(path), turnout)
    assert fitted.layers == 3 and sorted(fitted.entries) == [1, 2, 3]
    assert fitted.provenance["fe_options"]["element_order"] == 4  # the full FE mesh
    carrying = with_fitted(turnout, fitted)
    for zone in turnout.zones:
        params = co_running_parameters(carrying, zone=zone.index, source="fitted")
        for x in (zone.x_start, 0.5 * (zone.x_start + zone.x_end), zone.x_end):
            values = params.at(x)
            assert all(math.isfinite(v) and v > 0 for k, v in values.items() if k in params.entries)
    rows = [row for zone_rows in fitted.residuals.values() for row in zone_rows]
    assert len(rows) > 100
    for row in rows:
        assert row["cost_fitted"] < row["cost_derived"], row["x_m"]
    r2_rows = [row for row in rows if row["rail"] == "r2"]
    assert len(r2_rows) >= 40  # 20 switch-rail and 4 crossing positions, two directions
    for row in r2_rows:
        centres = np.array(row["band_centres_hz"])
        keep = ~np.isclose(centres[:, None], np.array(row["pinned_pinned_bands_hz"] or [0.0])).any(
            1
        )
        derived = np.sqrt(np.mean(np.square(row["derived_db"])[keep]))
        fitted_db = np.sqrt(np.mean(np.square(row["fitted_db"])[keep]))
        assert fitted_db <= derived, (row["x_m"], row["rail"], row["direction"])
