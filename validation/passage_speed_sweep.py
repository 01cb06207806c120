"""Peak contact forces of the right wheel for both routes, both track models, 50-160 km/h.

Run: ``python validation/passage_speed_sweep.py [--speeds 50 80 100 130 160]``; prints a
Markdown table (kN) and the crossing dip angle of the route profiles.
"""

import argparse
import warnings

from exudyn_turnout.inputs.routes import dip_angle, load_route
from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage.results import PassageSettings
from exudyn_turnout.passage.simulate import simulate_passage


def sweep(speeds, routes=("through", "diverging"), layers=(2, 3)):
    """{(route, layers, speed): summary} for every combination."""
    turnout = load_turnout()
    return {
        (route, n, v): simulate_passage(
            turnout, PassageSettings(route=route, layers=n, speed_kmh=v)
        ).summary
        for route in routes
        for n in layers
        for v in speeds
    }


def markdown(results) -> str:
    keys = ("peak_Fz_switch_N", "peak_Fz_crossing_N", "peak_Fy_switch_N", "peak_Fy_crossing_N")
    lines = [
        "| route | layers | km/h | Fz switch | Fz crossing | Fy switch | Fy crossing | largest Fz "
        "at the crossing (wheel, rail) | contact losses | wall s |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for (route, n, v), s in results.items():
        lines.append(
            f"| {route} | {n} | {v:g} | "
            + " | ".join(f"{s[k] / 1e3:.1f}" for k in keys)
            + f" | {s['max_Fz_crossing_N'] / 1e3:.1f} ({s['max_Fz_crossing_wheel']}, "
            f"{s['max_Fz_crossing_rail']})" + f" | {s['contact_losses']} | {s['wall_time_s']:.2f} |"
        )
    return "\n".join(lines)


def main(argv=None):
    """Print the sweep as Markdown (speed warnings above the permitted speed silenced)."""
    warnings.simplefilter("ignore", category=UserWarning)
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--speeds", type=float, nargs="+", default=[50.0, 80.0, 100.0, 130.0, 160.0]
    )
    args = parser.parse_args(argv)
    turnout = load_turnout()
    for route, wheel in (("through", "right"), ("diverging", "left")):
        x, depth, two_alpha = dip_angle(load_route(turnout, route), wheel, 46.0, 48.5)
        print(
            f"{route}: crossing dip of the {wheel} wheel's path at x = {x:.2f} m, depth "
            f"{1e3 * depth:.2f} mm, 2 alpha = {1e3 * two_alpha:.1f} mrad"
        )
    print(
        "\nright wheel peaks (kN, forces on the rail, as the paper's figures), and the largest "
        "vertical force at the crossing of either wheel (on the diverging route the left wheel "
        "meets the nose); speeds above the diverging route's permitted 80 km/h are run as a "
        "sensitivity study:\n"
    )
    print(markdown(sweep(args.speeds)))


if __name__ == "__main__":
    main()
