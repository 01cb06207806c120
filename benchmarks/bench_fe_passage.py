"""Benchmark: the FE passage against the three-layer co-running passage (printed table).

Run: ``python benchmarks/bench_fe_passage.py [--repeat N]``. Both runs are the through
route's 65 m passage (-5 m to 60 m) at 100 km/h, 2.34 s of simulated time, time step
1e-4 s, measured in this one run; the co-running passage is the best of N runs, the FE
passage runs once (minutes). The FE passage's wall time is split into its parts (from
its summary): assembly, factorisation, static start, and per step the triangular solve,
the sparse products, the influence vectors and the contact solve, and the rest (Python
per step: contact geometry, state update, recording).
"""

import argparse
import time

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage.fe_track.vertical_legacy import simulate_fe_passage
from exudyn_turnout.passage.results import PassageSettings
from exudyn_turnout.passage.run import simulate_passage

#: Parts of the FE passage's wall time (summary ``wall_time_parts_s``) and what they are.
PARTS = (
    ("assemble", "assemble M, D, K (FE model and wheelset)"),
    ("factorise", "factorise the effective matrix once (SuperLU)"),
    ("static", "static start: two static solves, K and M factorised"),
    ("solve", "one triangular solve per step"),
    ("products", "two sparse matrix-vector products per step"),
    ("influence", "influence vectors when a wheel enters an element"),
    ("contact", "influence combination + contact Newton per step"),
)


def best_co_running(turnout, repeat: int):
    best = None
    for _ in range(repeat):
        r = simulate_passage(turnout, PassageSettings(layers=3))
        if best is None or r.summary["wall_time_s"] < best.summary["wall_time_s"]:
            best = r
    return best


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--repeat", type=int, default=3, help="co-running runs, best taken (default 3)"
    )
    args = parser.parse_args(argv)
    turnout = load_turnout()
    co = best_co_running(turnout, args.repeat)
    t0 = time.perf_counter()
    fe = simulate_fe_passage(turnout, PassageSettings())
    fe_wall = time.perf_counter() - t0
    sim = fe.summary["simulated_time_s"]
    print(
        f"{'passage (through, 100 km/h, -5..60 m, h = 1e-4 s)':<52}{'wall s':>9}"
        f"{'wall/sim s':>12}{'DOFs':>8}"
    )
    print(
        f"{'3-layer co-running (Exudyn)':<52}{co.summary['wall_time_s']:>9.2f}"
        f"{co.summary['wall_time_s'] / sim:>12.2f}{'21-25':>8}"
    )
    print(
        f"{'FE track (numpy/scipy, HHT-alpha)':<52}{fe_wall:>9.1f}{fe_wall / sim:>12.1f}"
        f"{fe.summary['n_dof']:>8}"
    )
    print(f"{'ratio FE / 3-layer':<52}{fe_wall / co.summary['wall_time_s']:>9.0f}")
    parts = fe.summary["wall_time_parts_s"]
    steps = fe.summary["n_steps"]
    print(
        f"\nFE passage: {steps} steps, {1e3 * parts['steps'] / steps:.2f} ms per step; where the "
        "time goes:"
    )
    accounted = 0.0
    for key, text in PARTS:
        accounted += parts[key]
        print(f"  {key:<10}{parts[key]:>8.1f} s {100 * parts[key] / fe_wall:>5.1f} %  {text}")
    rest = fe_wall - accounted
    print(
        f"  {'rest':<10}{rest:>8.1f} s {100 * rest / fe_wall:>5.1f} %  Python per step: contact "
        "geometry, state update, recording"
    )


if __name__ == "__main__":
    main()
