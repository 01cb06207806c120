"""Convergence of the FE passage: time step, mesh, model ends (through route, 100 km/h).

Run: ``python validation/fe_passage_convergence.py [--quick]``; prints Markdown tables.

- time step: peak vertical force of the right wheel at the switch (x 2-6 m) and at the
  crossing nose (x 44-48 m) for h = 1e-4, 5e-5, 2.5e-5 s on the default mesh, relative to
  the smallest step;
- mesh: the same peaks for rail elements of 0.3, 0.2 (default) and 0.1 m (order 4) and
  0.2 m of order 6, at the default step, relative to the finest mesh;
- model ends: the start of the passage (x -5 to -1 m, 1 m from the turnout's first rail
  end) with the default plain-track extension (12 m + 12 m absorbing) and with twice the
  extension: the largest difference of the force history, relative to the static load.

Each window starts from its own static equilibrium (a steady start, see
:mod:`exudyn_turnout.passage.fe_track.vertical_legacy`), so the windows stand for the full
passage there.
"""

import argparse
from dataclasses import replace

import numpy as np

from exudyn_turnout.fe.mesh import FEOptions
from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage.fe_track.options import FEPassageOptions
from exudyn_turnout.passage.fe_track.vertical_legacy import simulate_fe_passage
from exudyn_turnout.passage.results import PassageSettings

#: (name, x_start, x_end, summary key) of the windows (m).
WINDOWS = (("switch", 2.0, 6.0, "peak_Fz_switch_N"), ("crossing", 44.0, 48.0, "peak_Fz_crossing_N"))


def peaks(turnout, time_step: float, mesh: FEOptions) -> dict[str, float]:
    """Right-wheel peak force (N) in each window."""
    out = {}
    for name, x0, x1, key in WINDOWS:
        settings = PassageSettings(speed_kmh=100.0, x_start=x0, x_end=x1, time_step=time_step)
        out[name] = simulate_fe_passage(
            turnout, settings, options=FEPassageOptions(mesh=mesh)
        ).summary[key]
    return out


def table(rows: dict[str, dict[str, float]], reference: str) -> str:
    lines = [
        "| case | switch peak (kN) | vs ref | crossing peak (kN) | vs ref |",
        "|---|---|---|---|---|",
    ]
    ref = rows[reference]
    for case, p in rows.items():
        lines.append(
            f"| {case} | {p['switch'] / 1e3:.2f} | {100 * (p['switch'] / ref['switch'] - 1):+.2f} "
            f"% | {p['crossing'] / 1e3:.2f} | {100 * (p['crossing'] / ref['crossing'] - 1):+.2f} % "
            "|"
        )
    return "\n".join(lines)


def time_step_study(turnout, steps) -> dict[str, dict[str, float]]:
    return {f"h = {h:g} s": peaks(turnout, h, FEOptions()) for h in steps}


def mesh_study(turnout, meshes) -> dict[str, dict[str, float]]:
    return {
        f"{m.element_length:g} m, p = {m.element_order}": peaks(turnout, 1e-4, m) for m in meshes
    }


def ends_study(turnout) -> tuple[float, float]:
    """Largest |F_default - F_long| / W (right wheel) and the static load W (N), x -5 to -1 m."""
    settings = PassageSettings(speed_kmh=100.0, x_start=-5.0, x_end=-1.0)
    base = FEOptions()
    runs = [
        simulate_fe_passage(turnout, settings, options=FEPassageOptions(mesh=m))
        for m in (base, replace(base, extension=2 * base.extension))
    ]
    W = runs[0].summary["static_wheel_load_N"]
    return float(
        np.max(np.abs(runs[0].columns["Fz_right_N"] - runs[1].columns["Fz_right_N"])) / W
    ), W


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="two steps and two meshes only")
    args = parser.parse_args(argv)
    turnout = load_turnout()
    steps = (1e-4, 5e-5) if args.quick else (1e-4, 5e-5, 2.5e-5)
    rows = time_step_study(turnout, steps)
    print("time step (default mesh: 0.2 m quartic elements)\n")
    print(table(rows, f"h = {steps[-1]:g} s"))
    meshes = [FEOptions(element_length=0.3), FEOptions()] + (
        [] if args.quick else [FEOptions(element_order=6), FEOptions(element_length=0.1)]
    )
    rows = mesh_study(turnout, meshes)
    print("\nmesh (h = 1e-4 s)\n")
    print(table(rows, list(rows)[-1]))
    diff, W = ends_study(turnout)
    print(
        "\nmodel ends: x -5 to -1 m, extension 12 m vs 24 m: largest force difference "
        f"{100 * diff:.3f} % of the static load {W / 1e3:.1f} kN"
    )


if __name__ == "__main__":
    main()
