"""Benchmark: wall time of wheelset passages on the co-running track (printed table).

Run: ``python benchmarks/bench_passage.py [--repeat N]``. The 65 m passage (-5 m to 60 m)
at 100 km/h is 2.34 s of simulated time. Targets: the three-layer passage with profile
contact (the default) at most 0.25 x real time (0.59 s, issue 12) and no slower than the
height-table contact it replaces. Each case runs ``--repeat`` times alternating with the
yardstick (``benchmarks/yardstick.py``): the median wall time and the median yardstick
units are printed, and the ratios are of yardstick units (they carry over between machines
and loads). The contact tables are built (or loaded from the cache) before timing; their
build time is printed.
"""

import argparse
import time
from dataclasses import replace

from yardstick import Yardstick, machine_line

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage.contact import height_table as wheelrail
from exudyn_turnout.passage.contact import profile as profile_contact
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings


def _timed(stick, turnout, settings, repeat):
    """Timing over ``repeat`` runs (median, yardstick units), and contact calls per step."""
    calls = [0]
    original = wheelrail.WheelRailElement.__call__

    def counted(self, *args):
        calls[0] += 1
        return original(self, *args)

    original_profile = profile_contact.ProfileContactElement.__call__

    def counted_profile(self, *args):
        calls[0] += 1
        return original_profile(self, *args)

    def run():
        calls[0] = 0
        return simulate_passage(turnout, settings, "wheelset")

    wheelrail.WheelRailElement.__call__ = counted
    profile_contact.ProfileContactElement.__call__ = counted_profile
    try:
        timing = stick.measure(run, repeat, warm_up=False)
    finally:
        wheelrail.WheelRailElement.__call__ = original
        profile_contact.ProfileContactElement.__call__ = original_profile
    result = timing.result
    steps = result.summary["simulated_time_s"] / settings.time_step
    return timing, result, calls[0] / steps


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--repeat", type=int, default=3, help="runs per case, median taken (default 3)"
    )
    args = parser.parse_args(argv)
    turnout = load_turnout()
    from exudyn_turnout.inputs.vehicle import load_vehicle

    vehicle = load_vehicle()
    for route in ("through", "diverging"):
        t0 = time.perf_counter()
        contact = profile_contact.route_contact(turnout, route, vehicle)
        print(
            f"contact tables, {route}: {time.perf_counter() - t0:.2f} s "
            f"(built or loaded in {contact.build_seconds:.2f} s, {contact.tables.n_bodies} "
            f"bodies, {contact.tables.values.nbytes / 1e6:.0f} MB)"
        )
    simulate_passage(
        turnout, PassageSettings(x_start=-5.0, x_end=-4.9), vehicle="wheelset"
    )  # compile, warm up
    stick = Yardstick()
    table = PassageSettings(contact="height-table")
    cases = [
        ("through, 2-layer", PassageSettings(layers=2)),
        ("through, 3-layer", PassageSettings(layers=3)),
        ("through, 2-layer, height-table contact", replace(table, layers=2)),
        ("through, 3-layer, height-table contact", replace(table, layers=3)),
        (
            "through, 3-layer, python track springs",
            PassageSettings(layers=3, track_mechanism="python"),
        ),
        ("diverging, 2-layer", PassageSettings(route="diverging", layers=2)),
        ("diverging, 3-layer", PassageSettings(route="diverging", layers=3)),
    ]
    rows, walls = {}, {}
    print(
        f"{'case (100 km/h, -5..60 m, h = 1e-4 s)':<42}{'wall s':>9}{'yardstick':>11}"
        f"{'wall/sim s':>12}{'us/step':>9}{'calls/step':>12}"
    )
    for name, settings in cases:
        timing, result, calls = _timed(stick, turnout, settings, args.repeat)
        wall = timing.seconds
        sim = result.summary["simulated_time_s"]
        rows[name], walls[name] = timing.units, wall
        microseconds_per_step = 1e6 * wall / (sim / settings.time_step)
        print(
            f"{name:<42}{wall:>9.2f}{timing.units:>11.2f}{wall / sim:>12.2f}"
            f"{microseconds_per_step:>9.0f}{calls:>12.2f}"
        )
    print(
        f"{'ratio 3-layer / 2-layer, through':<42}"
        f"{rows['through, 3-layer'] / rows['through, 2-layer']:>9.2f}"
        "   (paper: about 1.10)"
    )
    print(
        f"{'ratio 3-layer / 2-layer, diverging':<42}"
        f"{rows['diverging, 3-layer'] / rows['diverging, 2-layer']:>9.2f}"
    )
    print(
        f"{'ratio python / symbolic track springs':<42}"
        f"{rows['through, 3-layer, python track springs'] / rows['through, 3-layer']:>9.2f}"
    )
    print(
        f"{'ratio profile / height-table contact, 3L':<42}"
        f"{rows['through, 3-layer'] / rows['through, 3-layer, height-table contact']:>9.2f}"
    )
    print(
        f"{'target: 3-layer through wall <= 0.59 s':<42}"
        f"{'met' if walls['through, 3-layer'] <= 0.585 else 'missed':>9}"
        "   (seconds: on this machine at this load)"
    )
    print(f"\nratios of yardstick units; yardstick median {stick.median:.3f} s")
    print(machine_line())


if __name__ == "__main__":
    main()
