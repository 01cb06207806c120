"""Stage 6, the validation report: 2-layer vs 3-layer vs FE against the paper's claims.

- :mod:`.settings`: what the report needs of a turnout (``[report]`` of the file);
- :mod:`.config`: what a report runs (:class:`~.config.ReportConfig`) and what it gives
  (:class:`~.config.Report`);
- :mod:`.metrics`: :func:`build_report` and :func:`write_report`, from the sections:
  :mod:`.stiffness_section`, :mod:`.receptance_section`, :mod:`.passages` (contact forces),
  :mod:`.cost_section`, :mod:`.checks_section`, :mod:`.parameters_section`;
- :mod:`.passage_api`: the report's one door to :mod:`exudyn_turnout.passage`;
- :mod:`.metrics_types`: the metrics as typed records (the schema of ``metrics.json``), read
  and written by :mod:`.record`;
- :mod:`.agreement`: agreement metrics (receptance level difference in 1/3-octave bands,
  peaks, force-signal metrics);
- :mod:`.criteria`, :mod:`.claims`: the criteria, and the paper's claims with their verdicts;
- :mod:`.markdown` (with its ``markdown_*`` sections), :mod:`.figures`: the report's text and
  PNG figures;
- :mod:`.cache`: on-disk cache of the expensive FE results, keyed by their inputs and the
  package's code.
"""

from exudyn_turnout.report.metrics import build_report, write_report

__all__ = ["build_report", "write_report"]
