"""Cost per call of the creep table's compiled law (``creep_table.table_creep_scalar``).

The kernel calls it once per loaded contact.  200,000 random contacts (creepages to 0.05,
spin to 10 1/m, a / b 0.05 ... 20, loads 1-100 kN, mu 0.1-0.6) are fed to it from a
compiled loop, as the kernel does.

Rows: this table (Catmull-Rom in the spin angle, the default), the same table
interpolated linearly in the spin angle (the packed header's flag), and, with
``--baseline FILE``, the creep_table.py of an older revision (``git show
<rev>:exudyn_turnout/wheel_rail/creep_table.py > FILE``) with its own default table.
Yardstick: Polach's compiled law (``kernel.polach_scalar``) on the same inputs in the
same run, rounds alternating (the least time of each kept).

Run: ``python benchmarks/bench_creep_table.py [--calls N] [--rounds R] [--baseline FILE]``.
"""

from __future__ import annotations

import argparse
import importlib.util
import math
import sys
import time

import numba
import numpy as np


def _inputs(n: int) -> tuple[np.ndarray, ...]:
    rng = np.random.default_rng(7)

    def log_uniform(lo: float, hi: float) -> np.ndarray:
        return 10.0 ** rng.uniform(math.log10(lo), math.log10(hi), n)

    def signed(lo: float, hi: float) -> np.ndarray:
        return rng.choice([-1.0, 1.0], n) * log_uniform(lo, hi)

    a = log_uniform(1e-3, 1e-2)
    b = a / log_uniform(0.05, 20.0)
    return (signed(1e-6, 0.05), signed(1e-6, 0.05), signed(1e-3, 10.0), a, b,
            log_uniform(1e3, 1e5), rng.uniform(0.1, 0.6, n))  # fmt: skip


def _loop(law, with_table: bool):
    """A compiled loop over the inputs calling ``law`` (a table law or Polach's)."""
    if with_table:

        @numba.njit
        def run_table(packed, xi, eta, phi, a, b, q, mu, c11, c22, c23):  # pragma: no cover
            total = 0.0
            for k in range(xi.shape[0]):
                fx, fy = law(packed, 0, xi[k], eta[k], phi[k], a[k], b[k], q[k], mu[k], 8.1e10,
                             c11[k], c22[k], c23[k])  # fmt: skip
                total += fx + fy
            return total

        return run_table

    @numba.njit
    def run_law(packed, xi, eta, phi, a, b, q, mu, c11, c22, c23):  # pragma: no cover
        total = 0.0
        for k in range(xi.shape[0]):
            fx, fy = law(xi[k], eta[k], phi[k], a[k], b[k], q[k], mu[k], 8.1e10, c11[k],
                         c22[k], c23[k])  # fmt: skip
            total += fx + fy
        return total

    return run_law


def main(argv: list[str] | None = None) -> int:
    """Print the cost per call of the table laws and of the yardstick."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=200_000)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--baseline", help="creep_table.py of an older revision")
    args = parser.parse_args(argv)

    from exudyn_turnout.wheel_rail import creep_table as ct
    from exudyn_turnout.wheel_rail.creep import kalker_coefficients
    from exudyn_turnout.wheel_rail.kernel import polach_scalar

    inputs = _inputs(args.calls)
    c = kalker_coefficients(inputs[3], inputs[4], 0.28)
    coefficients = (np.asarray(c.c11, float), np.asarray(c.c22, float), np.asarray(c.c23, float))
    table = ct.creep_table()
    linear = table.packed.copy()
    linear[6] = 0.0  # the header's flag: linear in the spin angle
    cases = [
        ("this table, Catmull-Rom in beta", _loop(ct.table_creep_scalar, True), table.packed),
        ("this table, linear in beta", _loop(ct.table_creep_scalar, True), linear),
    ]
    if args.baseline:
        spec = importlib.util.spec_from_file_location("baseline_creep_table", args.baseline)
        assert spec is not None and spec.loader is not None
        old = importlib.util.module_from_spec(spec)
        sys.modules["baseline_creep_table"] = old
        spec.loader.exec_module(old)
        cases.append((f"baseline ({args.baseline})", _loop(old.table_creep_scalar, True),
                      old.creep_table().packed))  # fmt: skip
    cases.append(("yardstick: Polach's law (kernel.polach_scalar)", _loop(polach_scalar, False),
                  np.zeros(1)))  # fmt: skip
    best = [math.inf] * len(cases)
    for _ in range(args.rounds):  # alternating, so that load from elsewhere hits all alike
        for k, (_name, run, packed) in enumerate(cases):
            run(packed, *(v[:10] for v in inputs), *(v[:10] for v in coefficients))  # compile
            start = time.perf_counter()
            run(packed, *inputs, *coefficients)
            best[k] = min(best[k], (time.perf_counter() - start) / args.calls)
    print(f"creep law per call, {args.calls} random contacts, least of {args.rounds} rounds")
    print("| law | ns per call | ratio to Polach |")
    print("|---|---|---|")
    for (name, _run, _packed), cost in zip(cases, best, strict=True):
        print(f"| {name} | {cost * 1e9:.0f} | {cost / best[-1]:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
