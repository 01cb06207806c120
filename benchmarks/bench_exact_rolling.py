"""Cost of one Hertzian-ellipse solve by Kalker's exact theory (``wheel_rail.exact_rolling``),
its accuracy against the grid, and the time to fill a creep table with it.

Run: ``python benchmarks/bench_exact_rolling.py [--repeats N]``.  BLAS and OpenMP are held
to one thread before numpy loads (the dense LU of a few thousand unknowns per Newton step
gains little from a second, busy core).

Per grid (n x n elements across the ellipse): the time of one solve in partial slip with
spin (a = 5 mm, b = 3 mm, N = 10 kN, mu = 0.3, xi = 1e-3, eta = -5e-4, phi = 0.3 1/m), in
seconds and in yardstick units (``benchmarks/yardstick.py``, run interleaved), the Newton
iterations, and the error of the linear coefficients C11, C22, C23 of a circle at nu = 0.25
against Kalker's Table E3 (4.12, 3.67, 1.47; J.J. Kalker, *Three-dimensional elastic bodies
in rolling contact*, Kluwer 1990).

Table estimate: F / (mu N) of a Hertz ellipse depends only on a/b, nu and the normalised
creepages ``G a b xi / (mu N)``, ``G a b eta / (mu N)``, ``G (a b)^1.5 phi / (mu N)``
(the tractions scale with mu p0 and p0 = 3 N / (2 pi a b)), so a 4-D table over a/b and
those three covers every load, size and friction at one nu.  Fx is odd in xi and Fy odd in
(eta, phi) together, so half the creepage space is enough.
"""

import argparse
import os

for _name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_name] = "1"

from yardstick import Yardstick, machine_line  # noqa: E402

from exudyn_turnout.wheel_rail.exact_rolling import (  # noqa: E402
    exact_creep_forces_ellipse,
    hertz_pressure_grid,
    solve_steady_rolling,
)

G, NU = 8.1e10, 0.28
CASE = dict(a=5e-3, b=3e-3, xi=1e-3, eta=-5e-4, phi=0.3, N=1e4, mu=0.3)
KALKER = (4.12, 3.67, 1.47)  # circle, nu = 0.25, Table E3
TABLE_AXES = (10, 15, 15, 15)  # a/b, xi', eta', phi'


def _solve(n: int):
    pressure, dx, dy, x0, y0 = hertz_pressure_grid(CASE["a"], CASE["b"], CASE["N"], n)
    return solve_steady_rolling(
        pressure, dx, dy, x0, y0, CASE["xi"], CASE["eta"], CASE["phi"], CASE["mu"], G, NU
    )


def _linear_error(n: int) -> float:
    c = 5e-3
    fx = exact_creep_forces_ellipse(c, c, 1e-6, 0.0, 0.0, 1e4, 1e3, G, 0.25, n)[0]
    fy = exact_creep_forces_ellipse(c, c, 0.0, 1e-6, 0.0, 1e4, 1e3, G, 0.25, n)[1]
    fs = exact_creep_forces_ellipse(c, c, 0.0, 0.0, 1e-4, 1e4, 1e3, G, 0.25, n)[1]
    found = (-fx / (G * c**2 * 1e-6), -fy / (G * c**2 * 1e-6), -fs / (G * c**3 * 1e-4))
    return max(abs(f / k - 1.0) for f, k in zip(found, KALKER, strict=True))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--grids", type=int, nargs="+", default=[16, 24, 32, 40])
    args = parser.parse_args()
    stick = Yardstick()
    entries = TABLE_AXES[0] * TABLE_AXES[1] * TABLE_AXES[2] * TABLE_AXES[3] // 2
    print(
        f"{'n':>4} {'elements':>8} {'Newton':>6} {'solve s':>8} {'solve yst':>9} "
        f"{'|F|/muN':>8} {'max lin. err':>12} {'table h':>8}"
    )
    for n in args.grids:
        timing = stick.measure(lambda n=n: _solve(n), repeats=args.repeats)
        solved = timing.result
        force = (solved.fx**2 + solved.fy**2) ** 0.5 / (CASE["mu"] * CASE["N"])
        print(
            f"{n:>4} {int(solved.contact.sum()):>8} {solved.iterations:>6} "
            f"{timing.seconds:>8.3f} {timing.units:>9.2f} {force:>8.4f} "
            f"{_linear_error(n) * 100:>11.1f}% {entries * timing.seconds / 3600:>8.1f}"
        )
    print(
        f"table: {' x '.join(map(str, TABLE_AXES))} (a/b x normalised xi, eta, phi) / 2 by"
        f" symmetry = {entries} solves, 'table h' = that x the solve time, one core"
    )
    print(f"yardstick median {stick.median:.3f} s; {machine_line()}")


if __name__ == "__main__":
    main()
