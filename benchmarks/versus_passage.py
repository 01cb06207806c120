"""The performance table's passage rows for two checkouts, measured in one run (issue 24).

Run: ``python benchmarks/versus_passage.py --versus DIR [--rounds N] [--cases ws3,ws2,full,fe]``.

``DIR`` is another checkout of the package (e.g. the issue's baseline:
``git worktree add /tmp/base 8bb37b5``). Every case runs in a fresh process with the
checkout's ``PYTHONPATH``: one untimed call (contact tables, compiled kernels, the FE
model's factors), then the timed call, whose CPU and wall seconds the process prints. The
two checkouts alternate (``versus, this`` in odd rounds, ``this, versus`` in even ones),
each process between two yardstick runs (``benchmarks/yardstick.py``), so both see the same
load; the table gives medians over ``--rounds`` in seconds, x real time (from CPU s) and
yardstick units (wall s over the yardstick's median wall s of the run), and new / old.

Cases (the README's performance table, :mod:`performance_table`): the single wheelset on
the 3-layer (``ws3``) and 2-layer (``ws2``) co-running track and the full Manchester
vehicle on the 3-layer track (``full``), through route, 100 km/h, front wheelset
-5..60 m, profile contact, h = 1e-4 s, each checkout's default stepping; the FE track
under the single wheelset over the crossing, 44..49 m, with the 3-layer run of the same
window beside it (``fe``: the row's ratio of CPU times). The call adapts to the package's
API: ``passage.run.simulate_passage`` with a vehicle name (issue 21 on), or
``passage.simulate.simulate_passage`` and ``passage.full_vehicle_passage.
simulate_vehicle_passage`` (before).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from yardstick import Yardstick, machine_line

__all__ = ["CASES", "run_case", "main"]

HERE = Path(__file__).resolve().parent
THIS = HERE.parent
#: case -> (label, vehicle, track, x_start, x_end).
CASES = {
    "ws3": ("single wheelset, 3-layer, -5..60 m", "wheelset", "3-layer", -5.0, 60.0),
    "ws2": ("single wheelset, 2-layer, -5..60 m", "wheelset", "2-layer", -5.0, 60.0),
    "full": ("full Manchester vehicle, 3-layer, -5..60 m", "manchester", "3-layer", -5.0, 60.0),
    "fe": ("FE track, single wheelset, 44..49 m", "wheelset", "fe", 44.0, 49.0),
    "fe3": ("3-layer track, single wheelset, 44..49 m", "wheelset", "3-layer", 44.0, 49.0),
}


def _call(case: str):
    """A function running ``case`` once with the imported package's API.

    Parameters
    ----------
    case : str
        Key of :data:`CASES`.

    Returns
    -------
    callable
        No arguments.
    """
    from exudyn_turnout.inputs.turnout import load_turnout

    _, vehicle, track, x_a, x_b = CASES[case]
    turnout = load_turnout()
    try:
        from exudyn_turnout.passage.run import simulate_passage
        from exudyn_turnout.passage.settings import PassageSettings
    except ImportError:  # the package before the passage's rebuild (issue 21)
        from exudyn_turnout.passage.results import PassageSettings  # type: ignore
        from exudyn_turnout.passage.simulate import simulate_passage  # type: ignore

        settings = PassageSettings(route="through", speed_kmh=100.0, x_start=x_a, x_end=x_b)
        if vehicle == "manchester":
            from exudyn_turnout.inputs.vehicle_model import load_vehicle_model
            from exudyn_turnout.passage.full_vehicle_passage import (  # type: ignore
                simulate_vehicle_passage,
            )

            model = load_vehicle_model()
            return lambda: simulate_vehicle_passage(turnout, settings, model, track=track)
        return lambda: simulate_passage(turnout, settings, track=track)
    settings = PassageSettings(route="through", speed_kmh=100.0, x_start=x_a, x_end=x_b)
    return lambda: simulate_passage(turnout, settings, vehicle, track=track)


def run_case(case: str) -> dict:
    """Run ``case`` once untimed, once timed; CPU and wall seconds of the timed run.

    Parameters
    ----------
    case : str
        Key of :data:`CASES`.

    Returns
    -------
    dict
        ``cpu``, ``wall`` (s) and ``package`` (the imported package's folder).
    """
    import exudyn_turnout

    run = _call(case)
    run()
    wall, cpu = time.perf_counter(), time.process_time()
    run()
    cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
    return {"cpu": cpu, "wall": wall, "package": str(Path(exudyn_turnout.__file__).parent)}


def _subprocess(case: str, checkout: Path) -> dict:
    env = dict(os.environ, PYTHONPATH=str(checkout), OMP_NUM_THREADS="1")
    env.setdefault("MPLBACKEND", "Agg")
    with tempfile.TemporaryDirectory() as work:
        out = subprocess.run(
            [sys.executable, str(Path(__file__).resolve()), "--worker", case],
            env=env,
            cwd=work,
            capture_output=True,
            text=True,
            check=False,
        )
    if out.returncode != 0:
        tail = (out.stderr.strip().splitlines() or ["no output"])[-1]
        raise SystemExit(f"error: case {case} failed in {checkout}: {tail}")
    result = json.loads(out.stdout.strip().splitlines()[-1])
    if not result["package"].startswith(str(checkout)):
        raise SystemExit(f"error: case {case} imported {result['package']}, not {checkout}")
    return result


def main(argv: list[str] | None = None) -> int:
    """Command line; see the module docstring.

    Parameters
    ----------
    argv : list of str, optional

    Returns
    -------
    int
        Exit status.
    """
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--versus", type=Path, help="the other checkout (its top folder)")
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--cases", default="ws3,ws2,full,fe")
    p.add_argument("--worker", help=argparse.SUPPRESS)
    a = p.parse_args(argv)
    if a.worker:
        print(json.dumps(run_case(a.worker)))
        return 0
    if a.versus is None or not (a.versus / "exudyn_turnout").is_dir():
        print("error: --versus DIR must be a checkout holding exudyn_turnout/", file=sys.stderr)
        return 2
    cases = [c.strip() for c in a.cases.split(",") if c.strip()]
    unknown = [c for c in cases if c not in CASES]
    if unknown or a.rounds < 1:
        print(f"error: unknown case(s) {unknown} or rounds < 1", file=sys.stderr)
        return 2
    if "fe" in cases and "fe3" not in cases:
        cases.append("fe3")
    stick = Yardstick()
    checkouts = {"old": a.versus.resolve(), "new": THIS}
    times: dict[tuple[str, str], list[dict]] = {}
    for k in range(a.rounds):
        for case in cases:
            order = ("old", "new") if k % 2 == 0 else ("new", "old")
            for which in order:
                stick.run()
                print(f"... round {k + 1}, {case}, {which}", file=sys.stderr, flush=True)
                times.setdefault((case, which), []).append(_subprocess(case, checkouts[which]))
        stick.run()
    y_wall = stick.median
    print(machine_line())
    print(f"\nold: {checkouts['old']}; new: {checkouts['new']}; yardstick {y_wall:.3f} s wall\n")
    print(
        "| case | old CPU s | new CPU s | old x real time | new x real time "
        "| old units | new units | new / old (units) |"
    )
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    med = {
        key: (
            statistics.median(r["cpu"] for r in rs),
            statistics.median(r["wall"] for r in rs),
        )
        for key, rs in times.items()
    }
    v = 100.0 / 3.6
    for case in cases:
        label, _, _, x_a, x_b = CASES[case]
        simulated = (x_b - x_a) / v
        (c0, w0), (c1, w1) = med[(case, "old")], med[(case, "new")]
        print(
            f"| {label} | {c0:.2f} | {c1:.2f} | {c0 / simulated:.2f} | {c1 / simulated:.2f} "
            f"| {w0 / y_wall:.2f} | {w1 / y_wall:.2f} | {w1 / w0:.2f} |"
        )
    if "fe" in cases:
        for which in ("old", "new"):
            ratio = med[("fe", which)][0] / med[("fe3", which)][0]
            print(f"\nFE / 3-layer CPU over the crossing, {which}: {ratio:.0f}x (goal <= 50x)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
