"""The one-screen summary at the top of ``report.md``.

Verdict counts, the table of every claim, the headline numbers of sections 1-5 and links
to the headline figures (:func:`summary_lines`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from exudyn_turnout.report.claims import FE_REFERENCE_NOTE
from exudyn_turnout.report.criteria import FAILS, HOLDS, NOT_CHECKED, Claim
from exudyn_turnout.report.markdown_format import EXCL, fmt, span, table, verdict_text
from exudyn_turnout.report.metrics_types import PassageMetrics, PassageModel, ReportMetrics

__all__ = ["summary_lines"]

#: Figures linked from the summary (name in ``figures``, link text), in reading order.
_HEADLINE_FIGURES = (
    ("stiffness", "track stiffness along the turnout"),
    ("receptance_vertical", "vertical receptance"),
    ("receptance_lateral", "lateral receptance"),
)


def _ids(claims: Sequence[Claim], verdict: str, prefix: str) -> str:
    ids = [c.id for c in claims if c.verdict == verdict and c.id.startswith(prefix)]
    return ", ".join(ids) if ids else "none"


def _closing_receptance(m: ReportMetrics, claims: Sequence[Claim]) -> tuple[str, str]:
    cases = list(m.receptance.cases.values())
    verdicts = {x.id: x.verdict for x in claims}

    def rr(model: str, *keys: str) -> list[float]:
        return [(cs.models[model].range_rms_db or {})[k] for cs in cases for k in keys]

    stiff = (
        f"Track stiffness (our FE): holds {_ids(claims, HOLDS, 'S')}; does not hold here "
        f"{_ids(claims, FAILS, 'S')}. "
    )
    low = (
        stiff
        + f"Receptance 1-125 Hz: band RMS vs FE {span(rr('2-layer', '1-125 Hz'))} dB (2-layer), "
        f"{span(rr('3-layer', '1-125 Hz'))} dB (3-layer) over the four cases; R1 {verdicts['R1']}."
    )
    high = (
        f"Receptance 125-2000 Hz: 2-layer {span(rr('2-layer', '125-500 Hz', '500-2000 Hz'))} dB "
        f"(R2 {verdicts['R2']}); 3-layer "
        f"{span(rr('3-layer', '125-500 Hz' + EXCL, '500-2000 Hz' + EXCL))} dB without the "
        f"pinned-pinned bands (R3 {verdicts['R3']}; R4 {verdicts['R4']}); the 3-layer model is the "
        f"closer one (R5 {verdicts['R5']})."
    )
    return low, high


def _models(passage: PassageMetrics, route: str | None) -> Mapping[str, PassageModel]:
    """The passages of ``route`` by model (none for a route without passages)."""
    return passage.routes[route].models if route and route in passage.routes else {}


def _closing_forces(passage: PassageMetrics, claims: Sequence[Claim]) -> str:
    verdicts = {x.id: x.verdict for x in claims}
    route = passage.impact_route
    models = _models(passage, route)
    if "2-layer" not in models:
        return "Contact forces: no passage with the vertical force at the crossing."
    assert route is not None  # a route with passages
    peak = {m: fmt(d.peaks_N["Fz_crossing"], ".1f", 1e-3) for m, d in models.items()}
    fe = (
        f"against FE ({peak.get('FE', 'n/a')} kN): F2 {verdicts['F2']}, F3 {verdicts['F3']}, F4 "
        f"{verdicts['F4']}, F5 {verdicts['F5']}"
        if passage.fe_available
        else f"no FE passage ({passage.fe_note}), so F2-F6 are not checked"
    )
    return (
        f"Contact forces: crossing peak ({route}, {passage.speeds_kmh[route]:g} km/h) "
        f"{peak['2-layer']} kN (2-layer) vs {peak['3-layer']} kN (3-layer); F1 (2-layer oscillates "
        f"more) {verdicts['F1']}; {fe}.{_closing_lateral(passage, verdicts)}"
    )


def _closing_lateral(passage: PassageMetrics, verdicts: Mapping[str, str]) -> str:
    """The lateral crossing peak of ``lateral_route`` (Fig. 8) and F6, or "" without one."""
    route = passage.lateral_route
    models = _models(passage, route)
    if "2-layer" not in models:
        return ""
    assert route is not None  # a route with passages
    nose = all("Fy_nose" in d.peaks_N for d in models.values())
    signal, where = ("Fy_nose", "at the crossing nose") if nose else ("Fy_crossing", "crossing")
    peak = {m: fmt(d.peaks_N[signal], "+.2f", 1e-3) for m, d in models.items()}
    text = (
        f" Lateral peak {where} ({route}, {passage.speeds_kmh[route]:g} km/h): "
        f"{peak['2-layer']} kN (2-layer), {peak['3-layer']} kN (3-layer), "
        f"{peak.get('FE', 'n/a')} kN (FE); F6 {verdicts.get('F6', NOT_CHECKED)}."
    )
    events = {m: d.check_rail for m, d in models.items() if d.check_rail is not None}
    if events and any(e.impulse_Ns > 0 for e in events.values()):
        text += " Check-rail event: peak Fy " + ", ".join(
            f"{fmt(e.peak_Fy_N, '+.1f', 1e-3)} kN ({m})" for m, e in events.items()
        )
        text += " (" + ("tread unloaded" if any(e.tread_unloaded for e in events.values())
                        else "tread loaded") + ")."  # fmt: skip
    return text


def _closing_cost(m: ReportMetrics, claims: Sequence[Claim]) -> str:
    cost, verdicts = m.cost, {x.id: x.verdict for x in claims}
    ratios = ", ".join(f"{k} {v:.2f}" for k, v in cost.ratio_3_over_2.items())
    fe = ", ".join(f"{k} {v:.0f}" for k, v in cost.ratio_FE_over_3.items()) or "n/a"
    return (
        f"Cost: 3-layer / 2-layer wall time {ratios} (C1 {verdicts['C1']}); up to "
        f"{max(cost.extra_dof_per_zone.values())} more coordinates (C2 {verdicts['C2']}); FE / "
        f"3-layer {fe} (C3 {verdicts['C3']})."
    )


def _closing_checks(m: ReportMetrics) -> str:
    checks = m.checks
    balance = max(abs(v.mean_relative) for v in checks.static_wheel_load.values())
    ratios = [100 * v for d in checks.static_stiffness_ratio_to_FE.values() for v in d.values()]
    return (
        "Checks: halving the time step changes the co-running peaks by at most "
        f"{fmt(m.convergence.max_relative_change, '.2%')}; the static wheel loads "
        + ("balance" if checks.static_wheel_load_ok else "**do not balance**")
        + f" (m_w + m_s) g to {fmt(balance, '.1e')}; the co-running static stiffness is "
        f"{span(ratios)} % of FE's at the receptance points."
    )


def _verdict_count(claims: Sequence[Claim]) -> str:
    counts = {v: sum(c.verdict == v for c in claims) for v in (HOLDS, FAILS, NOT_CHECKED)}
    return (
        f"The paper's {len(claims)} claims tested against the FE reference: **{counts[HOLDS]} "
        f"hold**, **{counts[FAILS]} do not hold here**, {counts[NOT_CHECKED]} not checked "
        "(criteria: section *Criteria*; the evidence: sections 1-5)."
    )


def _headline_figures(m: ReportMetrics, figures: Mapping[str, str]) -> str:
    names = [(name, text) for name, text in _HEADLINE_FIGURES]
    names += [(f"forces_{route}", f"contact forces, {route} route") for route in m.passage.routes]
    links = [f"[{text}]({figures[name]})" for name, text in names if name in figures]
    return "Headline figures: " + (", ".join(links) if links else "none drawn") + "."


def summary_lines(
    m: ReportMetrics, claims: Sequence[Claim], figures: Mapping[str, str]
) -> list[str]:
    """The summary: verdict counts and table, the headline numbers and figures.

    Parameters
    ----------
    m : ReportMetrics
        The report's metrics.
    claims : sequence of Claim
        The report's claims.
    figures : mapping
        Figure name -> file name relative to report.md.

    Returns
    -------
    list of str
        Lines.
    """
    low, high = _closing_receptance(m, claims)
    rows = [
        [c.id, c.statement, c.fe_reference or "-", verdict_text(c.verdict), c.evidence]
        for c in claims
    ]
    return (
        ["## Summary", "", _verdict_count(claims), "", FE_REFERENCE_NOTE, ""]
        + table(["id", "paper's claim", "FE reference", "verdict", "numbers"], rows)
        + [
            "Headline numbers:",
            "",
            f"1. {low}",
            f"2. {high}",
            f"3. {_closing_forces(m.passage, claims)}",
            f"4. {_closing_cost(m, claims)}",
            f"5. {_closing_checks(m)}",
            "",
            _headline_figures(m, figures),
            "",
        ]
    )
