"""Cost per call of the compiled contact kernel (``wheel_rail.kernel.contact_forces``).

The diverging route's contact tables of the packaged turnout and vehicle (both wheels:
stock rails, switch blade, crossing nose, check rail) are packed as a passage packs them,
and ``contact_forces`` is called for wheelset states swept along the route (lateral shift
-11 ... +11 mm, tread penetration about 0.1 mm, a small yaw and speed 80 km/h, so that
tread, flange and check-rail contacts all carry load somewhere).

Rows: this kernel with its default creep law (FASTSIM's forces from the creep table of
``wheel_rail/creep_table.py``) and with Polach's law (``pack_tables(..., creep_law=
"polach")``), the cost of the creep law alone.
Yardstick: the same calls with every node's law replaced by Hertz's (exponents 1.5, 0.5,
0.5; the packed arrays are otherwise identical), and, with ``--baseline FILE``, the kernel
of an older revision (``git show <rev>:exudyn_turnout/wheel_rail/kernel.py > FILE``),
loaded beside this one and fed the same tables (without the per-node law fields if it
predates them), all in the same run.

Run: ``python benchmarks/bench_contact_kernel.py [--calls N] [--baseline FILE]``.
"""

from __future__ import annotations

import argparse
import importlib.util
import sys
import time
from types import SimpleNamespace

import numpy as np


def _states(n: int, x_from: float, x_to: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(1)
    x = np.linspace(x_from, x_to, n)
    q = np.zeros((n, 7))
    q_t = np.zeros((n, 7))
    q[:, 0] = rng.uniform(-0.011, 0.011, n)  # lateral displacement
    q[:, 1] = -1e-4  # 0.1 mm into the tread
    q[:, 3] = rng.uniform(-3e-3, 3e-3, n)  # yaw
    q_t[:, 0] = rng.uniform(-0.05, 0.05, n)
    return x, q, q_t


def _time(call, x, q, q_t, forces, details) -> tuple[float, int]:
    loaded = 0
    for i in range(min(50, len(x))):  # compile and warm up
        call(x[i], q[i], q_t[i], forces, details)
    start = time.perf_counter()
    for i in range(len(x)):
        loaded += call(x[i], q[i], q_t[i], forces, details)
    return (time.perf_counter() - start) / len(x), loaded


def _packed_caller(module, packed, constants):
    irregularity = np.zeros(4)

    def call(x, q, q_t, forces, details):
        return module.contact_forces(
            float(x), q, q_t, irregularity, packed.values, packed.blendable, packed.x,
            packed.layout, packed.bounds, constants, forces, details,
        )  # fmt: skip

    return call


def main(argv: list[str] | None = None) -> int:
    """Print the cost per call, ours and the yardsticks."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=20000)
    parser.add_argument("--baseline", help="kernel.py of an older revision")
    parser.add_argument("--rounds", type=int, default=3, help="alternating rounds (min kept)")
    args = parser.parse_args(argv)

    from exudyn_turnout.inputs.turnout import load_turnout
    from exudyn_turnout.inputs.vehicle import load_vehicle
    from exudyn_turnout.passage.contact.profile import wheel_and_setup
    from exudyn_turnout.wheel_rail import kernel, packed_tables
    from exudyn_turnout.wheel_rail.nonhertz import PATCH_FIELDS
    from exudyn_turnout.wheel_rail.turnout_sections import route_contact_tables

    turnout = load_turnout()
    wheel, setup = wheel_and_setup(turnout, load_vehicle())
    pairs = route_contact_tables(turnout, "diverging", wheel, setup)
    bodies = [body for body, _ in pairs]
    tables = [table for _, table in pairs]
    sides = [1 if b.wheel == "left" else -1 for b in bodies]
    ranges = [(b.x_from, b.x_to) for b in bodies]
    coordinates = [(5, 6)] * len(bodies)
    packed = packed_tables.pack_tables(tables, sides, coordinates, ranges)
    hertz_tables = []
    for table in tables:  # the same table with Hertz's law at every node
        values = table.values
        index = {name: k for k, name in enumerate(table.fields)}
        hertz_tables.append(
            SimpleNamespace(
                values=np.delete(values, [index[n] for n in PATCH_FIELDS], axis=-1),
                fields=tuple(n for n in table.fields if n not in PATCH_FIELDS),
                blendable=table.blendable,
                x=table.x,
                shift=table.shift,
            )
        )
    hertz_packed = packed_tables.pack_tables(hertz_tables, sides, coordinates, ranges)
    x_from = min(r[0] for r in ranges)
    x_to = max(r[1] for r in ranges)
    x, q, q_t = _states(args.calls, max(x_from, 0.0), x_to)
    constants = np.array([80 / 3.6, setup.nominal_radius, 0.4, 8.1e10, 0.0, 1 / 760.0])
    n_rows = packed.n_bodies * packed.n_candidates
    forces = np.zeros(7)
    details = np.zeros((n_rows, len(kernel.DETAIL_FIELDS)))
    polach_packed = packed_tables.pack_tables(
        tables, sides, coordinates, ranges, creep_law="polach"
    )
    callers = [
        ("this kernel, per-node laws (KP where Hertz does not fit)", kernel, packed, details),
        ("this kernel, per-node laws, Polach's creep law", kernel, polach_packed, details),
        ("this kernel, Hertz at every node", kernel, hertz_packed, details),
    ]
    if args.baseline:
        spec = importlib.util.spec_from_file_location("baseline_kernel", args.baseline)
        assert spec is not None and spec.loader is not None
        old = importlib.util.module_from_spec(spec)
        sys.modules["baseline_kernel"] = old
        spec.loader.exec_module(old)
        if hasattr(old, "PATCH_FIELDS"):  # a kernel with per-node laws: the same tables
            old_packed = old.pack_tables(tables, sides, coordinates, ranges)
        else:
            old_tables = [
                SimpleNamespace(values=t.values, blendable=t.blendable, x=t.x, shift=t.shift)
                for t in hertz_tables
            ]
            old_packed = old.pack_tables(old_tables, sides, coordinates, ranges)
        old_details = np.zeros((n_rows, len(old.DETAIL_FIELDS)))
        callers.append((f"baseline kernel ({args.baseline})", old, old_packed, old_details))
    best = [np.inf] * len(callers)
    counts = [0] * len(callers)
    for _ in range(args.rounds):  # alternating, so that load from elsewhere hits all alike
        for k, (_name, module, pack, rows_k) in enumerate(callers):
            call = _packed_caller(module, pack, constants)
            cost, counts[k] = _time(call, x, q, q_t, forces, rows_k)
            best[k] = min(best[k], cost)
    rows = [(c[0], best[k], counts[k]) for k, c in enumerate(callers)]
    print(f"contact_forces, {args.calls} calls, {len(bodies)} rail bodies, diverging route")
    print(f"| kernel | us per call | loaded contacts | ratio to {rows[-1][0][:16]}... |")
    print("|---|---|---|---|")
    for name, cost, n in rows:
        print(f"| {name} | {cost * 1e6:.2f} | {n} | {cost / rows[-1][1]:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
