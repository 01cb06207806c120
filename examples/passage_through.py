"""Through route: vertical contact force of the right wheel at the switch and the crossing
nose, two-layer vs three-layer co-running track (the layout of the paper's Fig. 7).

Run: ``python examples/passage_through.py [--out DIR] [--speed KMH]``.
"""

import argparse
from pathlib import Path

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage.results import PassageSettings, peaks_table
from exudyn_turnout.passage.run import compare_layers
from exudyn_turnout.plotting.curves import plot_passage_forces


def run(out_dir, route="through", speed_kmh=100.0, x_start=None, x_end=None):
    """Run both models, print the peaks, save the figure; return {layers: PassageResult}."""
    turnout = load_turnout()
    settings = PassageSettings(route=route, speed_kmh=speed_kmh, x_start=x_start, x_end=x_end)
    results = compare_layers(turnout, settings)
    print(
        peaks_table(
            {
                f"{layers}-layer, {route}, {speed_kmh:g} km/h": result
                for layers, result in results.items()
            }
        )
    )
    fig, _ = plot_passage_forces(
        results.values(), title=f"{turnout.name}, {route} route, {speed_kmh:g} km/h"
    )
    Path(out_dir).mkdir(parents=True, exist_ok=True)
    fig.savefig(Path(out_dir) / f"{route}_2_vs_3_layers.png", dpi=120)
    return results


def main(route="through"):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="out", help="output directory (default: out)")
    parser.add_argument("--speed", type=float, default=100.0, help="km/h (default 100)")
    args = parser.parse_args()
    run(args.out, route, args.speed)


if __name__ == "__main__":
    main()
