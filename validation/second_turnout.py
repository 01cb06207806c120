"""Validation report of the second turnout, EW 54E1-190-1:9 (``data/ew54_190_1_9.toml``).

``python validation/second_turnout.py [--quick] [--out DIR] [--cache DIR | --no-cache]``

The same as ``exudyn-turnout validate --turnout exudyn_turnout/data/ew54_190_1_9.toml``:
the whole pipeline (parameters, FE stiffness, receptances, 2-layer / 3-layer / FE passages
on the file's routes ``main`` and ``branch``, cost, convergence, claims) on a turnout that
differs from the packaged one in every property a file can change (another turnout is
another file, for every command).
Default output: ``validation/second_turnout/`` (the committed copy). The full report runs
the full Manchester vehicle with the profile contact on the 2-layer, 3-layer and FE tracks
(most of its time the FE passages over the whole turnout, cached afterwards); ``--quick``
runs the single wheelset over the crossing (~1 min on 2 shared cores).
"""

import sys
from pathlib import Path

from exudyn_turnout.cli.main import main

HERE = Path(__file__).resolve().parent
SECOND = HERE.parent / "exudyn_turnout" / "data" / "ew54_190_1_9.toml"

if __name__ == "__main__":
    argv = sys.argv[1:]
    if "--out" not in argv:
        argv += ["--out", str(HERE / "second_turnout")]
    sys.exit(main(["validate", "--turnout", str(SECOND)] + argv))
