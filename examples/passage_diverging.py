"""Diverging route (760 m curve, no cant): contact forces of the right wheel at the switch
and the crossing, two-layer vs three-layer co-running track (the layout of the paper's
Fig. 8), at the route's permitted speed (80 km/h in the packaged turnout file).

The right wheel, as the paper's figure; ``--wheel left`` tabulates and plots the left wheel,
which meets the crossing nose on this route.

The vehicle is the package's default, the full Manchester benchmark vehicle (its front
wheelset shown); ``--vehicle wheelset`` runs the single wheelset under its sprung share.

Run: ``python examples/passage_diverging.py [--out DIR] [--speed KMH] [--wheel right|left]
[--vehicle manchester|wheelset]``.
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import passage_through  # noqa: E402  (the same comparison, another route)


def run(out_dir, speed_kmh=None, x_start=None, x_end=None, wheel="right", vehicle=None):
    """Run both models on the diverging route; the PassageComparison.

    ``speed_kmh`` defaults to the route's permitted speed (80 km/h); ``vehicle`` a packaged
    name (default: the full Manchester vehicle).
    """
    return passage_through.run(out_dir, "diverging", speed_kmh, x_start, x_end, wheel, vehicle)


if __name__ == "__main__":
    passage_through.main("diverging", __doc__)
