"""Validation report, the same as ``exudyn-turnout validate``.

Usage: ``python validation/report.py [--out DIR] [--quick] [--cache DIR | --no-cache]``;
the default output is ``validation/report/`` (the committed copy of the full report).
The full report runs the full Manchester vehicle (``ReportConfig.vehicle = "full"``) on the
2-layer, 3-layer and FE tracks with the profile contact; ``--quick`` the single wheelset.
"""

import sys
from pathlib import Path

from exudyn_turnout.cli.main import main

if __name__ == "__main__":
    argv = sys.argv[1:]
    if "--out" not in argv:
        argv += ["--out", str(Path(__file__).resolve().parent / "report")]
    sys.exit(main(["validate"] + argv))
