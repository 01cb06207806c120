"""Validation report: metric functions against hand-computed values, claims, cache, quick report.

References:
- one-third-octave bands, base 10 (IEC 61260-1): centres 10^(n/10) Hz, edges centre * 10^(+-1/20);
- a constant receptance ratio r gives 20 log10 r dB in every band (r = 2: 6.0206 dB);
- a single-DOF receptance 1/(k - w^2 m + i w c) peaks at f0 = sqrt(k/m)/(2 pi) (light damping);
- the mean of sin over whole periods is 0 and its RMS is amplitude/sqrt(2).
"""

import json
import math
import re

import numpy as np
import pytest

from exudyn_turnout.cli.main import main
from exudyn_turnout.report import agreement as ag
from exudyn_turnout.report.cache import ResultCache, input_key
from exudyn_turnout.report.claims import FE_REFERENCES, evaluate_claims
from exudyn_turnout.report.criteria import FAILS, HOLDS, NOT_CHECKED, Criteria
from exudyn_turnout.report.markdown_format import claims_table

# --- metric functions -----------------------------------------------------------------


def test_third_octave_centres_are_base_10():
    c = ag.third_octave_centres(1.0, 125.0)
    assert len(c) == 22 and c[0] == pytest.approx(1.0) and c[-1] == pytest.approx(10**2.1)
    assert ag.third_octave_centres(500.0, 2000.0) == pytest.approx(10 ** (np.arange(27, 34) / 10))
    lo, hi = ag.band_edges(1000.0)
    assert (lo, hi) == pytest.approx((891.25, 1122.02), rel=1e-5)


def test_band_rms_of_a_constant_ratio_is_its_level():
    f = np.geomspace(1, 2000, 400)
    d = ag.level_difference_db(2.0 * np.exp(1j * f), np.ones_like(f))
    bands = ag.band_rms_db(f, d, ag.third_octave_centres(1, 2000))
    assert len(bands) == 34
    assert all(v == pytest.approx(6.0206, abs=1e-4) for v in bands.values())
    assert ag.range_rms_db(bands, 125, 500) == pytest.approx(6.0206, abs=1e-4)


def test_band_rms_by_hand():
    """Band 100 Hz holds 95 and 105 Hz (diffs 3, -4 dB): sqrt((9 + 16)/2).

    Band 1000 Hz holds 1000 Hz (2 dB)."""
    bands = ag.band_rms_db(
        [95.0, 105.0, 1000.0], [3.0, -4.0, 2.0], ag.third_octave_centres(1, 2000)
    )
    assert bands == pytest.approx({100.0: math.sqrt(12.5), 1000.0: 2.0})
    # range RMS: every band once, whatever its number of frequencies: sqrt((12.5 + 4)/2)
    assert ag.range_rms_db(bands, 1, 2000) == pytest.approx(math.sqrt(8.25))
    assert ag.range_rms_db(bands, 1, 2000, exclude=ag.bands_near(1000.0, 1)) == pytest.approx(
        math.sqrt(12.5)
    )
    assert math.isnan(ag.range_rms_db(bands, 125, 500))


def test_bands_near_a_frequency():
    assert ag.bands_near(1000.0, 1) == pytest.approx((10**2.9, 1000.0, 10**3.1))
    assert ag.bands_near(770.0, 0) == pytest.approx((10**2.9,))


def test_peak_of_a_single_dof_receptance():
    m, k, c = 100.0, 4e7, 2e3
    f = np.geomspace(1, 2000, 2000)
    w = 2 * np.pi * f
    H = 1 / (k - w**2 * m + 1j * w * c)
    (peak,) = ag.peak_frequencies(f, H)
    assert peak == pytest.approx(math.sqrt(k / m) / (2 * math.pi), rel=5e-3)
    assert ag.peak_frequencies(f, 1 / (k + 1j * w * c)) == ()


def test_running_mean_dynamic_rms_and_differences():
    x = np.linspace(0.0, 10.0, 10001)
    line = 3.0 * x + 1.0
    inner = (x > 1) & (x < 9)
    assert ag.running_mean(x, line, 1.0)[inner] == pytest.approx(line[inner])
    wave = 5.0 + 2.0 * np.sin(2 * np.pi * x / 0.1)  # ten periods per 1 m window
    assert ag.dynamic_rms(x, wave, 1.0, (2.0, 8.0)) == pytest.approx(2.0 / math.sqrt(2), rel=1e-3)
    assert ag.rms_difference(x, line + 0.5, x, line, (2.0, 8.0)) == pytest.approx(0.5)
    assert ag.max_trend_difference(x, wave, x, wave - 0.25, 1.0, (2.0, 8.0)) == pytest.approx(0.25)
    assert ag.relative_difference(110.0, 100.0) == pytest.approx(0.1)
    # a load that doubles both times after the first pair leaves the paired median at the true ratio
    # 1.1
    assert ag.paired_median_ratio([1.1, 2.2, 2.2], [1.0, 2.0, 2.0]) == pytest.approx(1.1)
    with pytest.raises(ValueError):
        ag.paired_median_ratio([1.0], [])
    assert math.isnan(ag.relative_difference(1.0, float("nan")))


# --- claims ---------------------------------------------------------------------------


def _receptance_metrics(low_2l: float) -> dict:
    ranges = {"1-125 Hz": low_2l, "125-500 Hz": 8.0, "500-2000 Hz": 12.0}
    r3 = {"1-125 Hz": 1.0, "125-500 Hz": 2.0, "500-2000 Hz": 2.5}

    def model(r):
        out = dict(r)
        out.update({k + " excl. pinned-pinned": v for k, v in r.items()})
        out["1-2000 Hz excl. pinned-pinned"] = max(r.values())
        return {"range_rms_db": out, "pinned_pinned_bands_rms_db": 5.0}

    def stiffness(out):
        out.update(
            {"peaks_hz": [], "static_stiffness_N_per_m": 5e7, "static_stiffness_ratio_to_FE": 1.0}
        )
        return out

    case = {
        "pinned_pinned_hz": 1000.0,
        "excluded_bands_hz": [794.3, 1000.0, 1259.0],
        "models": {
            "2-layer": stiffness(model(ranges)),
            "3-layer": stiffness(model(r3)),
            "FE": stiffness({}),
        },
        "fe_peak_near_pinned_pinned_hz": 1010.0,
        "fe_dip_near_pinned_pinned_hz": None,
        "rail": "r2",
        "direction": "vertical",
        "x_m": 3.9,
        "zone": 1,
        "rail_type": "switch",
        "distance_to_sleeper_m": 0.01,
        "fe": {"cached": True, "wall_time_s": 1.0, "computed": "2026-12-01 12:00"},
        "co_running_wall_time_s": 0.01,
        "fe_n_dof": 1000,
    }
    return {
        "positions": {"switch rail": {"rail": "r2", "x_m": 3.9}},
        "cases": {f"case {i}": case for i in range(4)},
        "frequencies": {"n": 48, "f_min_hz": 1.0, "f_max_hz": 2000.0},
    }


def _verdicts(metrics: dict) -> dict:
    return {c.id: c.verdict for c in evaluate_claims(metrics, Criteria())}


def test_receptance_claims_follow_the_criteria():
    v = _verdicts({"receptance": _receptance_metrics(2.9)})
    assert (
        v["R1"] == HOLDS
        and v["R2"] == HOLDS
        and v["R3"] == HOLDS
        and v["R4"] == HOLDS
        and v["R5"] == HOLDS
    )
    assert _verdicts({"receptance": _receptance_metrics(3.1)})["R1"] == FAILS


def test_claims_without_data_are_not_checked():
    v = _verdicts({})
    assert set(v) >= {"S1", "R1", "F1", "F4", "C1", "C3"}
    assert all(x == NOT_CHECKED for x in v.values())


def test_every_claim_names_its_fe_reference():
    """S and R claims against the planar FE (the paper's kind), F and C against the passages'
    torsion-aware FE track (issue 23: state which lateral FE reference each claim uses)."""
    claims = evaluate_claims({})
    by_id = {c.id: c.fe_reference for c in claims}
    assert all(by_id[i] == FE_REFERENCES["planar"] for i in by_id if i[0] in "SR")
    assert all(by_id[i] == FE_REFERENCES["passage"] for i in by_id if i[0] in "FC")
    assert "planar" in FE_REFERENCES["planar"] and "torsion" in FE_REFERENCES["passage"]
    table = "\n".join(claims_table(claims, "receptance"))
    assert "| FE reference |" in table and FE_REFERENCES["planar"] in table


def _lateral_passage_metrics(p2: float, p3: float, pfe: float) -> dict:
    """Passage metrics of one route whose lateral crossing force is plotted (as Fig. 8)."""

    def model(peak: float, fe: bool) -> dict:
        out = {
            "peaks_N": {"Fy_crossing": peak},
            "dynamic_rms_N": {"Fy_crossing": 1e3},
            "contact_losses": 0,
            "static_wheel_load_N": 54e3,
            "wall_time_s": 1.0,
            "simulated_time_s": 0.1,
        }
        if not fe:
            rel = abs(peak) / abs(pfe) - 1
            out["vs_FE"] = {
                "peak_relative": {"Fy_crossing": rel},
                "rms_difference_N": {"Fy_crossing": abs(peak - pfe)},
                "trend_deviation": {"Fy_crossing": 0.01},
            }
        return out

    models = {"2-layer": model(p2, False), "3-layer": model(p3, False), "FE": model(pfe, True)}
    route = {
        "signals": ["Fy_crossing"],
        "fe": {"cached": False, "computed": "2026-12-01 12:00"},
        "models": models,
        "fe_compared": ["Fy_crossing"],
        "co_running_wall_times_s": {"2-layer": [1.0], "3-layer": [1.1]},
    }
    return _passage_metrics(routes={"diverging": route}, lateral_route="diverging")


def _passage_metrics(**given) -> dict:
    """A passage section of metrics.json: ``given`` keys, the others empty."""
    empty = {
        "speeds_kmh": {},
        "regions_m": {},
        "routes": {},
        "steady_lateral_acceleration_m_s2": {},
        "fe_available": True,
        "fe_note": "",
        "x_range_m": [0.0, 1.0],
    }
    return empty | given


def test_lateral_crossing_claim_follows_the_criterion():
    """F6 (Sec. 4.2: 'overestimates the peak impact forces at the crossing panel despite a
    lower vehicle speed', the diverging route of Fig. 8): |peak Fy| of the 2-layer model more
    than 5 % above FE's; the signed peaks (force on the rail, + left) compare by magnitude."""
    v = _verdicts({"passage": _lateral_passage_metrics(-9.0e3, -7.5e3, -7.0e3)})
    assert v["F6"] == HOLDS  # 9.0 / 7.0 - 1 = +28.6 % > 5 %
    # the lateral signal also gets the verdicts of the claims on every plotted signal
    assert v["F2"] == HOLDS and v["F5"] == HOLDS  # 1 % trend; 3-layer 0.5 vs 2-layer 2.0 kN
    assert _verdicts({"passage": _lateral_passage_metrics(-7.2e3, -7.1e3, -7.0e3)})["F6"] == FAILS
    assert _verdicts({"passage": _passage_metrics()})["F6"] == NOT_CHECKED
    no_fe = _passage_metrics(fe_available=False, fe_note="switched off")
    assert [c.evidence for c in evaluate_claims({"passage": no_fe}) if c.id == "F6"] == [
        "FE passage not available: switched off"
    ]


def test_cost_claim_range():
    cost = {
        k: {}
        for k in (
            "wall_time_s",
            "median_wall_time_s",
            "simulated_time_s",
            "best_ratio_3_over_2",
            "ratio_FE_over_3",
            "fe_run",
            "dof_per_zone",
            "receptance_wall_time_s",
        )
    }
    cost.update({"repeats": 5, "ratio_3_over_2": {"through": 1.1}, "extra_dof_per_zone": {"2": 8}})
    assert _verdicts({"cost": cost})["C1"] == HOLDS and _verdicts({"cost": cost})["C2"] == HOLDS
    cost["ratio_3_over_2"]["through"] = 1.3
    assert _verdicts({"cost": cost})["C1"] == FAILS


# --- cache ----------------------------------------------------------------------------


def test_cache_round_trip_and_keys(tmp_path):
    cache = ResultCache(tmp_path / "c")
    key = input_key("x", np.arange(3.0), {"a": 1})
    assert key != input_key("x", np.arange(3.0) + 1e-12, {"a": 1}) and key == input_key(
        "x", np.arange(3.0), {"a": 1}
    )
    assert cache.load(key) is None
    cache.save(key, {"H": np.array([1 + 2j, 3j])}, {"wall_time_s": 1.5})
    arrays, meta = cache.load(key)
    assert arrays["H"] == pytest.approx(np.array([1 + 2j, 3j])) and meta == {"wall_time_s": 1.5}
    assert ResultCache(None).load(key) is None


def test_fe_passage_cache_key_changes_with_contact_vehicle_and_version(turnout, monkeypatch):
    """An FE passage of the height-table contact, or of another vehicle, is never reused."""
    from dataclasses import replace

    import exudyn_turnout.report.metrics as rm
    import exudyn_turnout.report.passages as rp
    from exudyn_turnout.passage.settings import PassageSettings

    settings = PassageSettings(route="through", x_start=46.0, x_end=47.0, contact="profile")
    wheelset = rm.ReportConfig(vehicle="wheelset")
    key = rp.fe_passage_cache_key(turnout, settings, wheelset)
    assert key == rp.fe_passage_cache_key(turnout, settings, wheelset)  # deterministic
    others = {
        rp.fe_passage_cache_key(turnout, replace(settings, contact="height-table"), wheelset),
        rp.fe_passage_cache_key(turnout, settings, rm.ReportConfig(vehicle="full")),
        rp.fe_passage_cache_key(turnout, replace(settings, speed_kmh=90.0), wheelset),
    }
    monkeypatch.setattr(rp, "FE_PASSAGE_VERSION", rp.FE_PASSAGE_VERSION + 1)
    others.add(rp.fe_passage_cache_key(turnout, settings, wheelset))
    assert key not in others and len(others) == 4


def test_report_vehicle_option_and_fe_availability(turnout):
    """vehicle is "full" (default) or "wheelset"; the FE passage is available for both unless
    switched off."""
    import exudyn_turnout.report.metrics as rm
    import exudyn_turnout.report.passages as rp

    assert (
        rm.ReportConfig().vehicle == "full" and rm.report_config(quick=True).vehicle == "wheelset"
    )
    with pytest.raises(ValueError, match="ReportConfig.vehicle must be one of full, wheelset"):
        rm.ReportConfig(vehicle="bogie")
    assert rp.fe_availability(rm.ReportConfig(vehicle="full")) == (True, "")
    assert rp.fe_availability(rm.ReportConfig(vehicle="wheelset")) == (True, "")
    off = rp.fe_availability(rm.ReportConfig(fe_passage=False))
    assert off == (False, "FE passage switched off in this report")
    # the static wheel loads the report checks: M g / 8 = 44 482 x 9.81 / 8 (issue 13) and
    # (m_w + m_s) g / 2 of the single wheelset
    assert rp.vehicle_static_load("full") == pytest.approx(44482 * 9.81 / 8, rel=1e-3)


# --- the quick report -----------------------------------------------------------------

_NUMBER = r"[+-]?(?:\d+\.?\d*|\.\d+)(?:e[+-]?\d+)?"
_CELL = re.compile(rf"^({_NUMBER})\s*(%|kN|dB|Hz|MN/m|s|m)?$")


def _leaves(value):
    if isinstance(value, dict):
        for v in value.values():
            yield from _leaves(v)
    elif isinstance(value, list):
        for v in value:
            yield from _leaves(v)
    elif isinstance(value, (int, float)) and not isinstance(value, bool):
        yield float(value)


def _numeric_cells(markdown: str):
    """Table cells that are numbers (or comma-separated numbers) with a point or exponent."""
    for line in markdown.splitlines():
        if not line.startswith("| ") or set(line) <= set("|-"):
            continue
        for cell in line.strip("|").split(" | "):
            parts = [p.strip() for p in cell.split(",")]
            matches = [_CELL.match(p) for p in parts]
            if all(matches):
                yield from (m.group(1) for m in matches if re.search(r"[.e]", m.group(1)))


def _resolution(token: str) -> float:
    mantissa, _, exponent = token.lower().partition("e")
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    return 0.5 * 10.0 ** (int(exponent or 0) - decimals)


@pytest.fixture(scope="module")
def quick_report(tmp_path_factory):
    out = tmp_path_factory.mktemp("report")
    code = main(["validate", "--out", str(out), "--quick", "--cache", str(out / ".cache")])
    return code, out


@pytest.mark.slow
def test_quick_report_writes_its_files(quick_report):
    code, out = quick_report
    assert code == 0
    md = (out / "report.md").read_text()
    for png in re.findall(r"!\[[^\]]*\]\(([^)]+)\)", md):
        assert (out / png).stat().st_size > 1000
    pngs = {p.name for p in out.glob("*.png")}
    assert {
        "receptance_vertical.png",
        "receptance_lateral.png",
        "forces_through.png",
        "forces_diverging.png",
        "stiffness.png",
    } <= pngs
    # each route's figure is embedded with its caption (lateral sign convention)
    for route in ("through", "diverging"):
        assert f"(forces_{route}.png)" in md and f"`forces_{route}.png`" in md
    assert "force on the rail, + left" in md
    metrics = json.loads((out / "metrics.json").read_text())
    for section in (
        "parameters",
        "stiffness",
        "receptance",
        "passage",
        "cost",
        "convergence",
        "checks",
        "claims",
    ):
        assert section in metrics
    assert {c["verdict"] for c in metrics["claims"]} <= {HOLDS, FAILS, NOT_CHECKED}
    assert all(c["id"] in md for c in metrics["claims"]) and "## Summary" in md


@pytest.mark.slow
def test_quick_report_has_fe_lateral_references(quick_report):
    """Profile contact and the same single wheelset on all three tracks; the FE passage gives
    finite vertical and lateral peaks at the crossing on both routes (the quick window covers
    the crossing only), each compared with the 2-layer and 3-layer runs, and the claims on
    lateral forces (diverging route, Fig. 8) get verdicts."""
    _, out = quick_report
    metrics = json.loads((out / "metrics.json").read_text())
    md = (out / "report.md").read_text()
    passage = metrics["passage"]
    assert passage["contact"] == "profile" and passage["vehicle"] == "wheelset"
    assert passage["fe_available"] and passage["lateral_route"] == "diverging"
    for route in ("through", "diverging"):
        rt = passage["routes"][route]
        assert set(rt["models"]) == {"2-layer", "3-layer", "FE"}
        fe_peaks = rt["models"]["FE"]["peaks_N"]
        # a wheel load of tens of kN, a lateral force of some kN (not zero, not absurd)
        assert 20e3 < fe_peaks["Fz_crossing"] < 400e3
        assert 0.1e3 < abs(fe_peaks["Fy_crossing"]) < 100e3
        for m in ("2-layer", "3-layer"):
            rel = rt["models"][m]["vs_FE"]["peak_relative"]
            assert {"Fz_crossing", "Fy_crossing"} <= set(rel)
            assert all(math.isfinite(rel[k]) for k in ("Fz_crossing", "Fy_crossing"))
    claims = {c["id"]: c for c in metrics["claims"]}
    assert claims["F6"]["verdict"] in (HOLDS, FAILS)
    for cid in ("F2", "F5"):  # judged on every plotted signal, the diverging Fy among them
        assert claims[cid]["verdict"] in (HOLDS, FAILS)
        assert "diverging Fy_crossing" in claims[cid]["evidence"]
    assert "profile contact for all three tracks" in md and "fe_track/coupling.py" in md
    assert "torsion-aware" in md


@pytest.mark.slow
def test_report_opens_with_the_summary_and_ends_with_the_appendix(quick_report):
    """Top-down: title, a one-screen summary (every claim's verdict, headline numbers and
    figures), the sections, and the long parameter table last as an appendix."""
    _, out = quick_report
    md = (out / "report.md").read_text()
    headings = [line for line in md.splitlines() if line.startswith("## ")]
    assert headings[0] == "## Summary"
    assert headings[-1].startswith("## Appendix A Parameters")
    assert sum(h.startswith("## Appendix") for h in headings) == 1
    summary = md.split("## Summary")[1].split("\n## ")[0]
    claims = json.loads((out / "metrics.json").read_text())["claims"]
    rows = [line for line in summary.splitlines() if line.startswith("| ") and "---" not in line]
    assert [r.split(" | ")[0].strip("| ") for r in rows[1:]] == [c["id"] for c in claims]
    assert "Headline numbers" in summary and "Headline figures" in summary
    assert "(receptance_vertical.png)" in summary
    # one screen: the title line, the summary's few paragraphs, one row per claim
    assert len(summary.strip().splitlines()) <= len(claims) + 20
    # the static stiffness of the co-running models over FE's is stated with the receptance
    receptance = md.split("## 2 Receptance")[1].split("\n## ")[0]
    assert "Static stiffness against FE" in receptance and "K / K_FE" in receptance


@pytest.mark.slow
def test_every_number_in_the_tables_is_in_metrics(quick_report):
    _, out = quick_report
    values = np.array(list(_leaves(json.loads((out / "metrics.json").read_text()))))
    tokens = list(_numeric_cells((out / "report.md").read_text()))
    assert len(tokens) > 100
    missing = []
    for token in tokens:
        v, tol = float(token), _resolution(token) * (1 + 1e-9) + 1e-12
        if not any(np.any(np.abs(values * scale - v) <= tol) for scale in (1.0, 1e-3, 1e-6, 100.0)):
            missing.append(token)
    assert not missing, f"numbers in report.md tables not in metrics.json: {missing[:10]}"


@pytest.mark.slow
def test_tables_keep_their_columns(quick_report):
    """Every row of a Markdown table has its header's number of cells.

    A "|" inside a cell is escaped."""
    _, out = quick_report
    columns = None
    for line in (out / "report.md").read_text().splitlines():
        if not line.startswith("|"):
            columns = None
            continue
        n = len(re.split(r"(?<!\\)\|", line))
        columns = columns or n
        assert n == columns, line


def test_cache_and_no_cache_are_exclusive(capsys, tmp_path):
    assert (
        main(
            ["validate", "--out", str(tmp_path), "--quick", "--cache", str(tmp_path), "--no-cache"]
        )
        == 2
    )
    assert "not both" in capsys.readouterr().err


# --- report settings: everything turnout-specific from the file or the model ---------------


def _without_report(turnout, **report):
    """The turnout with its [report] section replaced (or removed when ``report`` is empty)."""
    import dataclasses

    raw = {k: v for k, v in turnout.raw.items() if k != "report"}
    if report:
        raw["report"] = report
    return dataclasses.replace(turnout, raw=raw)


def test_default_report_settings_are_the_former_constants(turnout):
    """The packaged file's [report] and model give what the report used to hard-code.

    Except the quick passage window, which used to be 44.0-47.5 m and now follows the nose.
    """
    from exudyn_turnout.fe.layout import load_layout
    from exudyn_turnout.report.metrics import receptance_positions
    from exudyn_turnout.report.settings import (
        check_rails,
        quick_passage_x,
        report_settings,
        stock_rails,
    )

    s = report_settings(turnout)
    assert s.speeds_kmh == (("through", 100.0), ("diverging", 80.0))
    assert [r.signals for r in s.routes] == [
        (("Fz", "switch"), ("Fz", "crossing")),
        (("Fy", "switch"), ("Fy", "crossing")),
    ]
    assert {r.wheel for r in s.routes} == {"right"} and s.impact_route == "through"
    assert s.crossing_plot_window == (0.8, 2.2)
    # quick passages: 3.5 m centred on the wheel's dip onto the nose, on a 0.1 m grid
    x_dip = receptance_positions(turnout, settings=s)["crossing rail"][1]
    assert s.quick_passage_x is None
    x0, x1 = quick_passage_x(turnout, s)
    assert x0 <= x_dip - 1.75 < x0 + 0.1 and x1 - 0.1 < x_dip + 1.75 <= x1
    # the crossing region is the crossing panel, zone 2
    assert s.regions == {"switch": (0.0, 10.0), "crossing": (44.29, 51.0)}
    assert s.switch_claim_x == 22.0 and s.reference_rail_type == "stock"
    assert (s.receptance_route, s.receptance_wheel, s.receptance_slot) == ("through", "right", "r2")
    layout = load_layout(turnout)
    assert stock_rails(s, layout) == ("stock_left", "stock_right")
    assert check_rails(s, layout, turnout) == ("check_through", "check_diverging")


def test_report_defaults_without_a_report_section(turnout):
    """Defaults: every route; 100 km/h straight; sqrt(0.65 x 760) x 3.6 = 80.0 km/h on 760 m."""
    from exudyn_turnout.report.settings import quick_passage_x, report_settings

    t = _without_report(turnout)
    s = report_settings(t)
    assert s.speeds_kmh == (("through", 100.0), ("diverging", 80.0))
    assert s.route("through").forces == ("Fz",) and s.route("diverging").forces == ("Fy",)
    assert s.route("diverging").radius == pytest.approx(760.0, rel=1e-6)
    x0, x1 = quick_passage_x(t, s)
    # 3.5 m about the dip, rounded outwards to 0.1 m
    assert x1 - x0 == pytest.approx(3.6, abs=0.11) and x0 < 47.0 < x1
    assert "by the report's default" in s.speeds_note


@pytest.mark.parametrize(
    "report, field",
    [
        ({"routes": {"through": {"wheel": "middle"}}}, "report.routes.through.wheel"),
        ({"routes": {"through": {"speed_kmh": -5.0}}}, "report.routes.through.speed_kmh"),
        ({"routes": {"through": {"forces": ["Fx"]}}}, "report.routes.through.forces"),
        ({"routes": {"main": {}}}, "report.routes.main"),
        ({"routes": {"through": {"speeed_kmh": 90.0}}}, "report.routes.through.speeed_kmh"),
        ({"quick_passage_x": [50.0, 70.0]}, "report.quick_passage_x"),
        ({"crossing_plot_window": [1.0]}, "report.crossing_plot_window"),
        ({"receptance_slot": "r7"}, "report.receptance_slot"),
        ({"stock_rail": ["stock_left"]}, "report.stock_rail"),
    ],
)
def test_bad_report_settings_name_file_and_field(turnout, report, field):
    from exudyn_turnout.inputs.turnout import TurnoutFileError
    from exudyn_turnout.report.settings import report_settings

    with pytest.raises(TurnoutFileError, match=rf"^uic60_760_1_15\.toml: {re.escape(field)} "):
        report_settings(_without_report(turnout, **report))


def test_unknown_report_rail_ids_are_named(turnout):
    from exudyn_turnout.fe.layout import load_layout
    from exudyn_turnout.inputs.turnout import TurnoutFileError
    from exudyn_turnout.report.settings import report_settings, stock_rails

    s = report_settings(_without_report(turnout, stock_rails=["stock_left", "nonesuch"]))
    with pytest.raises(TurnoutFileError, match="report.stock_rails names rail 'nonesuch'"):
        stock_rails(s, load_layout(turnout))
