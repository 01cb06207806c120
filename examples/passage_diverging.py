"""Diverging route (760 m curve, no cant): lateral contact force of the right wheel at the
switch and the crossing, two-layer vs three-layer co-running track (the layout of the
paper's Fig. 8).

Run: ``python examples/passage_diverging.py [--out DIR] [--speed KMH]``.
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import passage_through  # noqa: E402  (the same comparison, another route)


def run(out_dir, speed_kmh=100.0, x_start=None, x_end=None):
    """Run both models on the diverging route; return {layers: PassageResult}."""
    return passage_through.run(out_dir, "diverging", speed_kmh, x_start, x_end)


if __name__ == "__main__":
    passage_through.main("diverging")
