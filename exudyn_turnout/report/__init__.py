"""Stage 6, the validation report: 2-layer vs 3-layer vs FE against the paper's claims.

- :mod:`.settings`: what the report needs of a turnout (``[report]`` of the file);
- :mod:`.agreement`: agreement metrics (receptance level difference in 1/3-octave bands,
  peaks, force-signal metrics);
- :mod:`.claims`: the paper's claims, the criteria and their verdicts;
- :mod:`.metrics`: the report's numbers (receptance, stiffness, passages, cost);
- :mod:`.markdown`, :mod:`.figures`: the report's text and PNG figures;
- :mod:`.cache`: on-disk cache of the expensive FE results.
"""

from exudyn_turnout.report.metrics import build_report, write_report

__all__ = ["build_report", "write_report"]
