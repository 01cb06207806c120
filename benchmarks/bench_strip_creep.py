"""Cost per call of FASTSIM on a Kik-Piotrowski patch strip by strip (``wheel_rail/kp_creep``).

The five KP patches of CONTACT's reference cases (``references.contact_at_reference``, at
CONTACT's FN and creepages) are given to :func:`.kp_creep.fastsim_patch`, strip by strip
(50-120 strips of 0.02 mm, 60 and 120 elements along x each), through its compiled core
:func:`.fastsim.strip_forces`.  Yardsticks in the same run: the same compiled core on the
40 strips of the patch's equivalent ellipse (what :func:`.fastsim.fastsim_ellipse`
computes), and the kernel's creep law, the compiled creep-table lookup on that ellipse
(:func:`.creep_table.table_creep_scalar`), all called the same way from Python.  The
passage kernel evaluates every contact of a step in about 3-8 us a call
(``bench_contact_kernel.py``): a creep law computed strip by strip per step would have
to be tabulated per node instead.

Run: ``python benchmarks/bench_strip_creep.py [--calls N]``.
"""

from __future__ import annotations

import argparse
import sys
import time
from functools import partial


def _best(call, calls: int, rounds: int = 3) -> float:
    call()  # compile and warm up
    best = float("inf")
    for _ in range(rounds):
        start = time.perf_counter()
        for _ in range(calls):
            call()
        best = min(best, (time.perf_counter() - start) / calls)
    return best


def main(argv: list[str] | None = None) -> int:
    """Print the cost per call of the three creep laws on the five reference patches."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=200)
    args = parser.parse_args(argv)

    import numpy as np

    from exudyn_turnout.wheel_rail.creep import kalker_coefficients
    from exudyn_turnout.wheel_rail.creep_table import creep_table, table_creep_scalar
    from exudyn_turnout.wheel_rail.data import data_dir, s1002_wheel
    from exudyn_turnout.wheel_rail.fastsim import (
        DEFAULT_ELEMENTS,
        DEFAULT_STRIPS,
        kalker_flexibilities,
        strip_forces,
    )
    from exudyn_turnout.wheel_rail.references import (
        REFERENCE_FILES,
        contact_at_reference,
        read_reference_output,
    )

    wheel, folder = s1002_wheel(), data_dir()
    packed = creep_table().packed
    print(f"creep law per call (us, compiled), {args.calls} calls, best of 3 rounds")
    print("| case | strips | FASTSIM, KP strips | FASTSIM, ellipse | table | strips / table |")
    print("|---|---|---|---|---|---|")
    n_e = DEFAULT_STRIPS  # the ellipse's strips (fastsim._ellipse_strips), y = b sin(theta)
    theta = -0.5 * np.pi + (np.arange(n_e) + 0.5) * np.pi / n_e
    for name in REFERENCE_FILES:
        for case in read_reference_output(folder / "reference_outputs" / f"{name}.ref_out"):
            patch = case.patches[0]
            result = contact_at_reference(case, wheel, folder / "profiles")
            strips = result.kp_strips
            creep = (patch.cksi, patch.ceta, patch.cphi)
            load, mu, g = patch.normal_force, case.friction, case.shear_modulus
            a, b = result.semi_hertz.a, result.semi_hertz.b
            flex = tuple(float(f) for f in kalker_flexibilities(a, b, g, case.poisson))
            c = kalker_coefficients(a, b, case.poisson)
            share = strips.half_length**3  # fastsim_patch's parabolic loads
            loads = share * load / float(np.sum(share * strips.width))
            half_e = a * np.cos(theta)
            loads_e = half_e**3 * load / float(np.sum(half_e**3 * b * np.cos(theta)))
            laws = (
                partial(strip_forces, strips.t - strips.centre, strips.width,
                        strips.half_length, loads, False, *flex, *creep, mu, DEFAULT_ELEMENTS,
                        strips.x_centre),
                partial(strip_forces, b * np.sin(theta), b * np.cos(theta) * np.pi / n_e,
                        half_e, loads_e, False, *flex, *creep, mu, DEFAULT_ELEMENTS,
                        np.zeros(n_e)),
                partial(table_creep_scalar, packed, 0, *creep, a, b, load, mu, g,
                        float(c.c11), float(c.c22), float(c.c23)),
            )  # fmt: skip
            costs = [_best(law, args.calls) for law in laws]
            print(
                f"| {name}#{case.case} | {strips.t.size} | "
                + " | ".join(f"{c * 1e6:.1f}" for c in costs)
                + f" | {costs[0] / costs[2]:.0f} |"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
