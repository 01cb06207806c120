"""Polach's creep law against Kalker's exact theory on Hertz ellipses: writes
exact_vs_polach.md.

Run: ``python validation/exact_vs_polach.py [--elements N]``.  A grid over the ellipse
ratio a/b and the normalised creepages (F / (mu N) of a Hertz ellipse depends only on a/b,
nu and ``G a b xi / (mu N)``, ``G a b eta / (mu N)``, ``G (a b)^1.5 phi / (mu N)``):
a = sqrt(a b) sqrt(a/b) with sqrt(a b) = 5 mm, N = 10 kN, mu = 0.3, G = 81 GPa,
nu = 0.28.  Per point the exact forces (``wheel_rail.exact_rolling``, n x n elements,
20 by default: linear coefficients within 2.5 % of Kalker's at a/b = 1, saturated forces
within 0.2 %, benchmarks/bench_exact_rolling.py) and Polach's
(``creep.polach_creep_forces``, k_A = k_S = 1), and the difference |F_Polach - F_exact| in
units of mu N.  No tolerance: this is a map of where Polach's law stands, for choosing
the kernel's creep model (issue 22); FASTSIM or a creep table can be put beside it.
"""

from __future__ import annotations

import argparse
import os

for _name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

from exudyn_turnout.wheel_rail.creep import polach_creep_forces  # noqa: E402
from exudyn_turnout.wheel_rail.exact_rolling import exact_creep_forces_ellipse  # noqa: E402

OUT = Path(__file__).with_suffix(".md")
G, NU, N, MU, C = 8.1e10, 0.28, 1.0e4, 0.3, 5e-3
RATIOS = (0.1, 0.3, 1.0, 3.0, 10.0)
#: normalised creepages (xi', eta', phi') = G c^2 (xi, eta) / (mu N), G c^3 phi / (mu N)
CREEPAGES = (
    (0.1, 0.0, 0.0),
    (0.5, 0.0, 0.0),
    (0.0, 0.5, 0.0),
    (0.3, 0.3, 0.0),
    (0.0, 0.0, 0.2),
    (0.0, 0.0, 1.0),
    (0.3, 0.0, 0.5),
    (0.0, -0.3, 0.5),
    (0.0, 0.3, 0.5),
    (0.3, -0.2, 1.0),
)


def _f(value: float) -> str:
    """A force in mu N, three decimals, round-off zeros without a sign flip."""
    return f"{round(value, 3) + 0.0:+.3f}"


def main(argv: list[str] | None = None) -> int:
    """Write exact_vs_polach.md (and print it)."""
    parser = argparse.ArgumentParser(description="Polach against Kalker's exact theory")
    parser.add_argument("--elements", type=int, default=20)
    args = parser.parse_args(argv)
    lines = [
        "# Polach's creep law against Kalker's exact theory (Hertz ellipses)",
        "",
        f"Written by `python validation/exact_vs_polach.py --elements {args.elements}`"
        " (grid and normalisation in its docstring).  Forces in units of mu N; primes are"
        " the normalised creepages G c^2 xi / (mu N), G c^2 eta / (mu N),"
        " G c^3 phi / (mu N), c = sqrt(a b).",
        "",
        "| a/b | xi' | eta' | phi' | exact Fx | exact Fy | Polach Fx | Polach Fy"
        " | abs. difference |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    worst: dict[str, float] = {"no spin": 0.0, "with spin": 0.0}
    for ratio in RATIOS:
        a, b = C * np.sqrt(ratio), C / np.sqrt(ratio)
        unit = MU * N / (G * a * b)
        for xi_n, eta_n, phi_n in CREEPAGES:
            xi, eta, phi = xi_n * unit, eta_n * unit, phi_n * unit / np.sqrt(a * b)
            fx, fy = exact_creep_forces_ellipse(a, b, xi, eta, phi, N, MU, G, NU, args.elements)
            polach = polach_creep_forces(xi, eta, phi, a, b, N, MU, shear_modulus=G, poisson=NU)
            px, py = float(polach.longitudinal), float(polach.lateral)
            difference = float(np.hypot(px - fx, py - fy)) / (MU * N)
            key = "with spin" if phi_n else "no spin"
            worst[key] = max(worst[key], difference)
            lines.append(
                f"| {ratio:g} | {xi_n:g} | {eta_n:g} | {phi_n:g} | {_f(fx / (MU * N))} "
                f"| {_f(fy / (MU * N))} | {_f(px / (MU * N))} | {_f(py / (MU * N))} "
                f"| {difference:.3f} |"
            )
    lines += [
        "",
        "| creepages | largest difference (mu N) |",
        "|---|---|",
        *(f"| {k} | {v:.3f} |" for k, v in worst.items()),
        "",
    ]
    OUT.write_text("\n".join(lines), encoding="utf-8")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
