"""Validation report: two-layer vs three-layer co-running track vs the FE reference.

:func:`build_report` computes every number of the report as data (nested dicts of
floats, the ``metrics`` written to ``metrics.json``) together with the curves and time
histories it plots; :func:`write_report` writes ``report.md`` (rendered by
:mod:`exudyn_turnout.report.markdown`), the PNG figures it embeds and ``metrics.json``.
The paper's claims are judged by :mod:`exudyn_turnout.report.claims` on those metrics.

Sections of the report (as numbered in ``report.md``, after a summary of the verdicts):
1 track stiffness along the turnout (FE static stiffness, fits, Eqs 10, 14), 2 receptance
(Figs 5, 6 analogue, with the static stiffness of the co-running models against FE's),
3 contact forces (Figs 7, 8 analogue), 4 computing cost, 5 convergence and static checks;
appendix A: parameters (derived vs published Table 2). One module computes each:
:mod:`~exudyn_turnout.report.stiffness_section`,
:mod:`~exudyn_turnout.report.receptance_section`, :mod:`~exudyn_turnout.report.passages`,
:mod:`~exudyn_turnout.report.cost_section`, :mod:`~exudyn_turnout.report.checks_section`,
:mod:`~exudyn_turnout.report.parameters_section`; the configuration lives in
:mod:`~exudyn_turnout.report.config`. This module puts them together.

Everything turnout-specific (routes, speeds, wheels, plotted forces, regions, where the
receptances are taken, the quick passage window, the stock and check rails of the FE
statements) comes from the turnout file's ``[report]`` section or from the model, through
:func:`~exudyn_turnout.report.settings.report_settings`; another turnout is another file.

FE results (receptances, static stiffness profile, FE passage) are cached on disk
(:mod:`exudyn_turnout.report.cache`) keyed by a hash of their inputs and of the package's
stage folders whose code computes them. Parts of the FE reference that are not in the
package yet are reported as "not available".
"""

from __future__ import annotations

import dataclasses
import time
from pathlib import Path
from typing import Any

from exudyn_turnout.inputs.turnout import Turnout, load_turnout
from exudyn_turnout.report.cache import ResultCache
from exudyn_turnout.report.checks_section import convergence_metrics, static_checks
from exudyn_turnout.report.claims import evaluate_claims
from exudyn_turnout.report.config import (
    Report,
    ReportConfig,
    log,
    report_config,
    resolve_config,
    turnout_fingerprint,
)
from exudyn_turnout.report.cost_section import cost_metrics
from exudyn_turnout.report.metrics_types import PassageMetrics, ReceptanceMetrics
from exudyn_turnout.report.parameters_section import parameters_metrics
from exudyn_turnout.report.passages import passage_section
from exudyn_turnout.report.receptance_section import receptance_positions, receptance_section
from exudyn_turnout.report.settings import report_settings
from exudyn_turnout.report.stiffness_section import stiffness_section

__all__ = [
    "build_report",
    "write_report",
    # re-exported: imported from here by the command line, validation scripts and tests
    "ReportConfig",
    "report_config",
    "receptance_positions",
]


# --- the report -----------------------------------------------------------------------


def build_report(turnout: Turnout | None = None, config: ReportConfig = ReportConfig()) -> Report:
    """Compute every section's numbers and evaluate the claims (no files written).

    Parameters
    ----------
    turnout : Turnout, optional
        Default: the packaged turnout. Its ``[report]`` section (and model) give routes,
        speeds, regions and positions (:func:`~exudyn_turnout.report.settings.report_settings`).
    config : ReportConfig
        How much and how finely; resolved against the turnout (:func:`resolve_config`).

    Returns
    -------
    Report
    """
    t0 = time.perf_counter()
    turnout = turnout or load_turnout()
    settings = report_settings(turnout)
    config = resolve_config(config, settings, turnout)
    cache = ResultCache(None if config.cache_dir is None else Path(config.cache_dir))
    # file name and content hash, no path of the machine that ran it
    metrics: dict[str, Any] = {
        "turnout": turnout.name,
        "turnout_file": Path(str(turnout.source)).name,
        "turnout_sha256": turnout_fingerprint(turnout),
        "config": _config_metrics(config),
        "criteria": dataclasses.asdict(config.criteria),
    }
    metrics["parameters"] = parameters_metrics(turnout)
    metrics["stiffness"], profile = stiffness_section(turnout, config, cache, settings)
    metrics["receptance"], curves = receptance_section(turnout, config, cache, settings)
    metrics["passage"], passages = passage_section(turnout, config, cache, settings)
    # the later sections read the earlier ones typed
    receptance = ReceptanceMetrics.from_dict(metrics["receptance"], "receptance")
    passage = PassageMetrics.from_dict(metrics["passage"], "passage")
    metrics["cost"] = cost_metrics(turnout, passages, receptance, passage, config)
    metrics["convergence"] = convergence_metrics(turnout, passages, config, settings)
    metrics["checks"] = static_checks(
        turnout, passages, receptance, config.criteria, config.vehicle
    )
    claims = tuple(evaluate_claims(metrics, config.criteria))
    metrics["claims"] = [c.to_dict() for c in claims]
    metrics["compute_wall_time_s"] = time.perf_counter() - t0
    return Report(config, metrics, claims, curves, passages, profile, settings)


def _config_metrics(config: ReportConfig) -> dict[str, Any]:
    d = dataclasses.asdict(config)
    d.pop("criteria")
    d["speeds_kmh"] = dict(config.speeds_kmh or ())
    home = str(Path.home())
    if d["cache_dir"] and d["cache_dir"].startswith(home + "/"):  # no home path in metrics.json
        d["cache_dir"] = "~" + d["cache_dir"][len(home) :]
    return d


def _source_links(out: Path, files: tuple[str, ...]) -> dict[str, str]:
    """Repository path -> path relative to ``out`` of the package's source files, when the
    report is written inside the repository holding the package (none otherwise)."""
    import os

    root = Path(__file__).resolve().parents[2]  # the folder holding exudyn_turnout/
    try:
        Path(out).resolve().relative_to(root)
    except ValueError:
        return {}
    return {
        f: Path(os.path.relpath(root / f, Path(out).resolve())).as_posix()
        for f in files
        if (root / f).is_file()
    }


def write_report(
    out_dir: str | Path, config: ReportConfig = ReportConfig(), turnout: Turnout | None = None
) -> Report:
    """Build the report and write ``report.md``, its PNG figures and ``metrics.json`` into out_dir.

    Parameters
    ----------
    out_dir : str or Path
        Output directory (created).
    config : ReportConfig
        How much and how finely (:func:`report_config`).
    turnout : Turnout, optional
        Default: the packaged turnout.

    Returns
    -------
    Report
        The built report (``metrics`` as written).
    """
    from exudyn_turnout.report.figures import write_figures, write_model_figure
    from exudyn_turnout.report.markdown import render_markdown
    from exudyn_turnout.report.markdown_format import to_json

    t0 = time.perf_counter()
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    report = build_report(turnout, config)
    figures = write_figures(report, out)
    figures.update(write_model_figure(report, turnout or load_turnout(), out))
    report.metrics["report_wall_time_s"] = time.perf_counter() - t0
    (out / "metrics.json").write_text(to_json(report.metrics), encoding="utf-8")
    links = _source_links(out, ("exudyn_turnout/passage/fe_track/coupling.py",))
    (out / "report.md").write_text(render_markdown(report, figures, links), encoding="utf-8")
    log(f"wrote {out / 'report.md'} in {report.metrics['report_wall_time_s']:.0f} s")
    return report
