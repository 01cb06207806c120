"""Benchmark: contact-geometry table build and the vectorised lookup.

Run: ``python benchmarks/bench_contact_geometry.py [--repeat N] [--quick]``.  Prints one
table: the build time of each table (no cache; wall and CPU time, which differ when other
jobs share the machine), the time to load it back from the disk
cache, and the lookup time per call for a step's batch of contacts (4 = two wheels on two
rails each; 8; 100) and per contact.  Tables are cached in a temporary folder that is
removed afterwards.  Targets: a build of a few seconds, then cached; a lookup of a few
microseconds per contact, since a passage makes ~25 000 steps with ~3 calls each. The
yardstick (``benchmarks/yardstick.py``) runs before and after each table: "build yst" is
the build in yardstick units, "lookup ppm" the lookup per contact (100) in millionths of
a yardstick; both carry over between machines and loads.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from functools import partial

import numpy as np
from yardstick import Yardstick, machine_line

from exudyn_turnout.wheel_rail.data import profile_path, s1002_wheel, standard_track
from exudyn_turnout.wheel_rail.geometry import WheelsetSetup
from exudyn_turnout.wheel_rail.profiles import read_slices
from exudyn_turnout.wheel_rail.sections import (
    gauge_point,
    lateral_grid,
    slice_sections,
    wheel_envelope,
)
from exudyn_turnout.wheel_rail.tables import TableSettings, build_contact_table, lookup_values


def best_of(function, repeat: int) -> float:
    """Shortest wall time (s) of ``repeat`` calls."""
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times)


def crossing_sections(setup: WheelsetSetup, step: float):
    """UK crossing slices, wheel-enveloped every ``step`` over the transfer zone."""
    slices = read_slices(profile_path("uk_crossing.slcs"))
    grid = lateral_grid(-0.08, 0.12, setup.grid_step)
    sections = slice_sections(slices, grid, name="UK crossing 1:9.25")
    x = np.arange(-0.5, 1.0 + 1e-9, step)
    taping = gauge_point(slices.profiles[3]) + setup.taping_line - 0.5 * setup.gauge
    return wheel_envelope(sections, x, setup.nominal_radius, reach=0.1, step=0.002), taping


def main() -> None:
    """Build and time the tables, print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=200)
    parser.add_argument("--quick", action="store_true", help="coarser crossing table")
    args = parser.parse_args()
    setup = WheelsetSetup()
    wheel = s1002_wheel(setup)
    settings = TableSettings()
    start = time.perf_counter()
    crossing, taping = crossing_sections(setup, 0.05 if args.quick else 0.01)
    envelope_time = time.perf_counter() - start
    cases = [
        ("plain UIC60 1:40", standard_track(setup), setup.taping_line),
        ("UK crossing (enveloped)", crossing, taping),
    ]
    rng = np.random.default_rng(1)
    print(
        f"{'table':26s} {'nodes':>8s} {'build s':>8s} {'cpu s':>6s} {'load s':>7s} "
        f"{'lookup us/call (4 / 8 / 100)':>30s} {'us/contact (100)':>17s} {'build yst':>9s} "
        f"{'lookup ppm':>10s}"
    )
    stick = Yardstick()
    stick.run()
    with tempfile.TemporaryDirectory() as cache:
        for name, sections, taping_line in cases:
            cpu = time.process_time()
            table = build_contact_table(wheel, sections, taping_line, settings, cache_dir=cache)
            cpu = time.process_time() - cpu
            load = best_of(
                partial(
                    build_contact_table, wheel, sections, taping_line, settings, cache_dir=cache
                ),
                3,
            )
            per_call = []
            for n in (4, 8, 100):
                x = rng.uniform(sections.x[0], sections.x[-1], n)
                shift = rng.uniform(-0.008, 0.008, n)
                lift = rng.uniform(-4e-4, 0.0, n)
                per_call.append(
                    best_of(partial(lookup_values, table, x, shift, lift), args.repeat) * 1e6
                )
            nodes = table.values.shape[0] * table.values.shape[1]
            stick.run()
            print(
                f"{name:26s} {nodes:8d} {table.build_seconds:8.2f} {cpu:6.2f} {load:7.3f} "
                f"{per_call[0]:10.1f} / {per_call[1]:5.1f} / {per_call[2]:6.1f} "
                f"{per_call[2] / 100:17.2f} {stick.units(table.build_seconds):9.2f} "
                f"{stick.units(per_call[2] / 100):10.2f}"
            )
    print(
        f"(crossing sections: reading 148 slices and the wheel envelope took {envelope_time:.2f} s)"
    )
    print(f"yardstick median {stick.median:.3f} s; {machine_line()}")


if __name__ == "__main__":
    main()
