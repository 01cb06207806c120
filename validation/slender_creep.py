"""Creep forces on slender Hertz ellipses: exact theory, the creep table and FASTSIM (issue 22).

Run: ``python validation/slender_creep.py`` (prints a Markdown table; ~3 minutes on a
shared core).  Run it with another tree first on ``PYTHONPATH`` to compare revisions.

For a / b = 5 ... 50 and b / a = 5 ... 50 (a: semi-axis in the rolling direction), a
patch of sqrt(a b) = 5 mm, N = 10 kN, mu = 0.3, G = 81 GPa, nu = 0.28:

* the linear coefficients C11, C22, C23 of Kalker's exact theory (the package's solver,
  :mod:`exudyn_turnout.wheel_rail.exact_rolling`, full stick, 32 x 32 elements on the
  ellipse), of the creep table's path (:func:`.creep_table.table_creep_forces` at
  creepages 1e-9, 1e-9, 1e-7 / sqrt(a b)), of direct FASTSIM
  (:func:`.fastsim.fastsim_ellipse`, 40 strips x 60 elements) and
  :func:`.creep.kalker_coefficients`;
* the lateral force F_y / (mu N) in partial and full slip, without and with spin, at
  creepages normalised with the exact theory's coefficients (so that the inputs are the
  same in every revision): ``eta' = G a b C22 eta / (3 mu N)``, ``phi' = G (a b)^1.5 C23
  phi / (3 mu N)``, ``xi'`` likewise; exact theory on 24 x 24 elements (its saturated
  forces change by under 0.2 % from 16 on, exact_rolling's docstring).
"""

from __future__ import annotations

import math

from exudyn_turnout.wheel_rail.creep import kalker_coefficients
from exudyn_turnout.wheel_rail.creep_table import creep_table, table_creep_forces
from exudyn_turnout.wheel_rail.exact_rolling import exact_creep_forces_ellipse
from exudyn_turnout.wheel_rail.fastsim import fastsim_ellipse

G, NU, N, MU, ROOT = 8.1e10, 0.28, 1e4, 0.3, 5e-3
RATIOS = (5.0, 10.0, 15.0, 20.0, 30.0, 50.0, 1 / 5, 1 / 10, 1 / 15, 1 / 20, 1 / 30, 1 / 50)
#: (xi', eta', phi') of the saturated cases, in the exact theory's normalisation
CASES = ((0.0, 0.5, 0.0), (0.0, 2.0, 0.0), (0.0, 0.5, 0.5), (0.5, 0.0, 0.5))


def main() -> None:
    """Print the comparison as Markdown."""
    table = creep_table()
    head = "| a/b | C11 exact / table / FASTSIM / Kalker | C22 ... | C23 ... |"
    lines = [head, "|---|---|---|---|"]
    sat = ["| a/b | " + " | ".join(f"fy at {c} exact / table / FASTSIM" for c in CASES) + " |",
           "|---|" + "---|" * len(CASES)]  # fmt: skip
    for ratio in RATIOS:
        a, b = ROOT * math.sqrt(ratio), ROOT / math.sqrt(ratio)
        lin = (G * a * b, G * a * b, G * (a * b) ** 1.5)
        steps = ((1e-9, 0.0, 0.0), (0.0, 1e-9, 0.0), (0.0, 0.0, 1e-7 / math.sqrt(a * b)))
        exact, tab, fast = [], [], []
        for k, (xi, eta, phi) in enumerate(steps):
            step = (xi, eta, phi)[k]
            big = (xi * 1e3, eta * 1e3, phi * 1e3)  # the solver's full stick at 1e-6
            f = exact_creep_forces_ellipse(a, b, *big, N, 1e3, G, NU, n=32)
            exact.append(-f[0 if k == 0 else 1] / (lin[k] * step * 1e3))
            t = table_creep_forces(table, xi, eta, phi, a, b, N, MU, G)
            d = fastsim_ellipse(xi, eta, phi, a, b, N, MU, G, NU, 40, 60)
            tab.append(-float(t.longitudinal if k == 0 else t.lateral) / (lin[k] * step))
            fast.append(-float(d.longitudinal if k == 0 else d.lateral) / (lin[k] * step))
        c = kalker_coefficients(a, b, NU)
        kalker = (float(c.c11), float(c.c22), float(c.c23))
        cells = [
            f"{exact[k]:.2f} / {tab[k]:.2f} / {fast[k]:.2f} / {kalker[k]:.2f}" for k in range(3)
        ]
        lines.append(f"| {ratio:.3g} | " + " | ".join(cells) + " |")
        row = []
        for xi_n, eta_n, phi_n in CASES:
            scale = 3.0 * MU * N
            xi, eta, phi = (xi_n * scale / (lin[0] * exact[0]), eta_n * scale / (lin[1] * exact[1]),
                            phi_n * scale / (lin[2] * exact[2]))  # fmt: skip
            f = exact_creep_forces_ellipse(a, b, xi, eta, phi, N, MU, G, NU, n=24)
            t = table_creep_forces(table, xi, eta, phi, a, b, N, MU, G)
            d = fastsim_ellipse(xi, eta, phi, a, b, N, MU, G, NU, 40, 60)
            values = (f[1], float(t.lateral), float(d.lateral))
            row.append(" / ".join(f"{v / (MU * N):+.3f}" for v in values))
        sat.append(f"| {ratio:.3g} | " + " | ".join(row) + " |")
        print(lines[-1], flush=True)
    print("\n".join(lines))
    print()
    print("\n".join(sat))


if __name__ == "__main__":
    main()
