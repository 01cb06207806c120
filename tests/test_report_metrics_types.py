"""The report's typed metrics (:mod:`exudyn_turnout.report.metrics_types`) read and write the
committed ``metrics.json`` files unchanged, and ``report.md`` renders from them."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from exudyn_turnout.report.claims import evaluate_claims
from exudyn_turnout.report.config import Report, ReportConfig
from exudyn_turnout.report.criteria import Claim, Criteria
from exudyn_turnout.report.markdown import render_markdown
from exudyn_turnout.report.markdown_format import to_json
from exudyn_turnout.report.metrics_types import PassageModel, ReportMetrics

VALIDATION = Path(__file__).resolve().parents[1] / "validation"
COMMITTED = sorted(
    [VALIDATION / "report" / "metrics.json"] + list(VALIDATION.glob("second_turnout/*metrics.json"))
)


def _load(path: Path) -> dict:
    return json.loads(path.read_text(encoding="utf-8"))


@pytest.mark.parametrize("path", COMMITTED, ids=lambda p: p.parent.name)
def test_committed_metrics_round_trip(path):
    """metrics.json -> typed records -> dict is the same dict, key order included, and the
    same JSON text as the report writes it."""
    data = _load(path)
    typed = ReportMetrics.from_dict(data)
    back = typed.to_dict()
    assert back == data
    assert json.dumps(back) == json.dumps(data)  # same key order
    assert json.loads(to_json(back)) == data
    # attributes carry the file's numbers
    route = next(iter(data["passage"]["routes"]))
    model = typed.passage.routes[route].models["2-layer"]
    assert isinstance(model, PassageModel)
    peak = data["passage"]["routes"][route]["models"]["2-layer"]["peaks_N"]["Fz_crossing"]
    assert model.peaks_N["Fz_crossing"] == peak
    assert typed.criteria.agree_db == data["criteria"]["agree_db"]
    assert [c.id for c in typed.claims or ()] == [c["id"] for c in data["claims"]]


@pytest.mark.parametrize("path", COMMITTED, ids=lambda p: p.parent.name)
def test_claims_of_committed_metrics_are_the_committed_claims(path):
    """The claims judged on the committed metrics, as a dict or typed, are the committed ones
    (the claims read the typed records and judge as the report did)."""
    data = _load(path)
    criteria = Criteria(**data["criteria"])
    for metrics in (data, ReportMetrics.from_dict(data)):
        claims = [c.to_dict() for c in evaluate_claims(metrics, criteria)]
        for new, old in zip(claims, data["claims"]):
            if "fe_reference" not in old:  # a report written before the references were stated
                new.pop("fe_reference")
        assert json.loads(to_json({"claims": claims}))["claims"] == data["claims"]


def test_unknown_or_missing_keys_are_errors():
    """A key the schema does not know, or a required one missing, fails loudly (the schema
    cannot drift from the report silently)."""
    data = _load(COMMITTED[0])
    route = next(iter(data["passage"]["routes"]))
    data["passage"]["routes"][route]["models"]["2-layer"]["peak_typo_N"] = 1.0
    with pytest.raises(ValueError, match="unknown keys \\['peak_typo_N'\\] for PassageModel"):
        ReportMetrics.from_dict(data)
    data = _load(COMMITTED[0])
    del data["cost"]["repeats"]
    with pytest.raises(ValueError, match="missing key 'repeats' of CostMetrics"):
        ReportMetrics.from_dict(data)
    data = _load(COMMITTED[0])
    data.pop("provenance", None)  # optional: absent stays absent
    data["passage"]["impact_route"] = None  # optional: present as null stays null
    back = ReportMetrics.from_dict(data).to_dict()
    assert "provenance" not in back and back["passage"]["impact_route"] is None
    assert back == data


def _markdown(directory: Path) -> str:
    """report.md of the committed metrics.json of ``directory`` with its committed figures."""
    metrics = _load(directory / "metrics.json")
    claims = tuple(Claim(**c) for c in metrics["claims"])
    figures = {p.stem: p.name for p in directory.glob("*.png")}
    if "model_cross_section" in figures:
        figures["model"] = figures.pop("model_cross_section")
    module = "exudyn_turnout/passage/fe_track/coupling.py"
    links = {module: f"../../{module}"}
    return render_markdown(Report(ReportConfig(), metrics, claims), figures, links)


@pytest.mark.skipif(
    not (VALIDATION / "second_turnout" / "report.md").is_file(), reason="no second report"
)
def test_committed_second_turnout_report_renders_byte_identical():
    """report.md of the second turnout, rendered from its committed metrics.json, is the
    committed report.md byte for byte (both written by one run of the report)."""
    directory = VALIDATION / "second_turnout"
    assert _markdown(directory) == (directory / "report.md").read_text(encoding="utf-8")


def test_committed_report_renders():
    """The UIC60 report renders from its committed metrics.json with every section."""
    md = _markdown(VALIDATION / "report")
    for title in ("## Summary", "## 1 Track", "## 2 Receptance", "## 3 Contact", "## 4 Comput"):
        assert title in md
    assert "## 5 Convergence and checks" in md and "## Appendix A" in md
