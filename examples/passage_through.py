"""Through route: contact forces of the right wheel at the switch and the crossing nose,
two-layer vs three-layer co-running track (the layout of the paper's Fig. 7).

The vehicle is the package's default, the full Manchester benchmark vehicle, and the figure
shows its front wheelset, as the paper's Fig. 7 shows the front axle; ``--vehicle wheelset``
runs the single wheelset under its sprung share (about half the time).

The first passage in a Python process also pays a one-time warm-up (imports, loading the
compiled contact kernel, reading or building the route's contact tables). The example runs
a short warm-up passage first and reports it separately, so that the wall times of the two
models compare the models, not the order they ran in.

Run: ``python examples/passage_through.py [--out DIR] [--speed KMH] [--wheel right|left]
[--vehicle manchester|wheelset]``.
"""

import argparse
import time
from pathlib import Path

from exudyn_turnout.inputs.routes import load_route
from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage.run import compare_tracks, simulate_passage
from exudyn_turnout.passage.settings import PassageSettings
from exudyn_turnout.plotting.curves import save_figure

#: m, length of the warm-up passage (its results are not used).
WARM_UP_LENGTH = 0.5


def warm_up(turnout, route: str, speed_kmh: float, vehicle=None) -> float:
    """Run a short passage on the route once; its wall time (s), the one-time warm-up."""
    start = time.perf_counter()
    x0 = turnout.x_min
    settings = PassageSettings(
        route=route, speed_kmh=speed_kmh, x_start=x0, x_end=x0 + WARM_UP_LENGTH
    )
    simulate_passage(turnout, settings, vehicle, track="3-layer")
    return time.perf_counter() - start


def default_speed(turnout, route: str) -> float:
    """km/h: 100, or the route's permitted speed where the turnout file sets a lower one."""
    permitted = load_route(turnout, route).permitted_speed_kmh
    return 100.0 if permitted is None else min(100.0, permitted)


def run(
    out_dir,
    route="through",
    speed_kmh=None,
    x_start=None,
    x_end=None,
    wheel="right",
    vehicle=None,
):
    """Warm up, run both models, print the peaks, save the figure; the PassageComparison.

    ``speed_kmh`` defaults to :func:`default_speed`; ``wheel`` is the wheel tabulated and
    plotted (the paper's Figs 7 and 8 show the right wheel); ``vehicle`` a packaged name
    (default: the full Manchester vehicle, its front wheelset tabulated and plotted).
    """
    turnout = load_turnout()
    speed_kmh = default_speed(turnout, route) if speed_kmh is None else speed_kmh
    warm = warm_up(turnout, route, speed_kmh, vehicle)
    print(f"warm-up (first passage in this process): {warm:.1f} s")
    settings = PassageSettings(route=route, speed_kmh=speed_kmh, x_start=x_start, x_end=x_end)
    comparison = compare_tracks(turnout, settings, ("2-layer", "3-layer"), vehicle)
    print(f"{turnout.name}, {route} route, {speed_kmh:g} km/h; peaks of the {wheel} wheel:")
    print(comparison.table(wheel))
    walls = ", ".join(
        f"{track} {float(result.summary['wall_time_s']):.2f} s"
        for track, result in comparison.items()
    )
    print(f"wall time of each passage, after the warm-up: {walls}")
    fig, _ = comparison.plot(
        wheel=wheel, title=f"{turnout.name}, {route} route, {speed_kmh:g} km/h, {wheel} wheel"
    )
    Path(out_dir).mkdir(parents=True, exist_ok=True)
    path = Path(out_dir) / f"{route}_2_vs_3_layers.png"
    save_figure(fig, path, dpi=120)
    print(f"wrote {path} ({wheel} wheel)")
    return comparison


def main(route="through", doc=__doc__):
    """Command line of this example (and of ``passage_diverging.py``, with its ``doc``)."""
    parser = argparse.ArgumentParser(description=" ".join(doc.split("\n\n")[0].split()))
    parser.add_argument("--out", default="out", help="output directory (default: out)")
    parser.add_argument(
        "--speed",
        type=float,
        default=None,
        help="km/h (default 100, or the route's permitted speed if lower)",
    )
    parser.add_argument(
        "--wheel",
        choices=("right", "left"),
        default="right",
        help="the wheel tabulated and plotted (default right, as the paper's figures)",
    )
    parser.add_argument(
        "--vehicle",
        choices=("manchester", "wheelset"),
        default="manchester",
        help="manchester: the full Manchester vehicle, its front wheelset shown (default); "
        "wheelset: the single wheelset under its sprung share",
    )
    args = parser.parse_args()
    run(args.out, route, args.speed, wheel=args.wheel, vehicle=args.vehicle)


if __name__ == "__main__":
    main()
