"""FE reference vs 2- and 3-layer co-running passages: through route, 100 km/h (paper Fig. 7).

Run: ``python validation/fe_vs_co_running_through_100.py [--out DIR]``. Runs the three
passages (-5 m to 60 m), prints the right wheel's peak vertical forces at the switch and
the crossing nose with their differences from the FE reference, and saves
``fe_vs_co_running_through_100.png`` (vertical force of the right wheel at the switch and
at the crossing nose, three models overlaid) and each run's timeseries.csv / summary.json
into DIR (default ``validation/out``).
"""

import argparse
from pathlib import Path

from exudyn_turnout.inputs.routes import dip_angle, load_route
from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage.results import write_passage
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings

#: x windows (m) of the overlay: the load transfer at the switch and the crossing nose.
WINDOWS = (("switch: stock rail to switch blade", (1.0, 8.0)), ("crossing nose", (46.0, 48.5)))


def run_all(turnout, speed_kmh: float = 100.0) -> dict:
    """{"FE": result, "2-layer": result, "3-layer": result} of the through route."""
    out = {
        "FE": simulate_passage(
            turnout, PassageSettings(speed_kmh=speed_kmh), track="fe", vehicle="wheelset"
        )
    }
    for layers in (2, 3):
        out[f"{layers}-layer"] = simulate_passage(
            turnout, PassageSettings(speed_kmh=speed_kmh, layers=layers), vehicle="wheelset"
        )
    return out


def peak_table(results) -> str:
    keys = (("switch", "peak_Fz_switch_N"), ("crossing", "peak_Fz_crossing_N"))
    fe = results["FE"].summary
    lines = [
        "| model | static (kN) | peak Fz switch (kN) | vs FE | peak Fz crossing (kN) | vs FE | "
        "wall (s) |",
        "|---|---|---|---|---|---|---|",
    ]
    for name, r in results.items():
        s = r.summary
        cells = [f"{s[k] / 1e3:.1f} | {100 * (s[k] / fe[k] - 1):+.1f} %" for _, k in keys]
        lines.append(
            f"| {name} | {s['static_wheel_load_N'] / 1e3:.1f} | "
            + " | ".join(cells)
            + f" | {s['wall_time_s']:.1f} |"
        )
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--out", default=str(Path(__file__).with_name("out")), help="output directory"
    )
    args = parser.parse_args(argv)
    turnout = load_turnout()
    results = run_all(turnout)
    out = Path(args.out)
    for name, r in results.items():
        write_passage(r, out / f"through_100_{name}")
    x, depth, two_alpha = dip_angle(load_route(turnout, "through"), "right", 46.0, 48.5)
    print(
        f"through route, 100 km/h, right wheel; crossing dip at x = {x:.2f} m, depth "
        f"{1e3 * depth:.2f} mm, 2 alpha = {1e3 * two_alpha:.1f} mrad; FE: "
        f"{results['FE'].summary['n_dof']} DOFs\n"
    )
    print(peak_table(results))
    ratio = results["FE"].summary["wall_time_s"] / results["3-layer"].summary["wall_time_s"]
    print(f"\ncost ratio FE / 3-layer: {ratio:.0f}")
    from exudyn_turnout.plotting.curves import plot_force_signals

    fig, _ = plot_force_signals(
        [(title, results, "Fz_right_N", rng) for title, rng in WINDOWS],
        ylabel="vertical force on rail, right wheel (kN)",
    )
    fig.savefig(out / "fe_vs_co_running_through_100.png", dpi=130)
    print(f"\nplot -> {out / 'fe_vs_co_running_through_100.png'}")


if __name__ == "__main__":
    main()
