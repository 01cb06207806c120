"""Benchmark of the FE reference model (printed table): receptance sweep and static profile.

Run: ``python benchmarks/bench_fe.py [--n 400] [--x 46.0]``. Measures, on the packaged
UIC60-760-1:15 turnout with the default FE options:

- the model: DOFs of each plane, build time (mesh, assembly), condensation set-up;
- the point receptance of slot r2 at x (the crossing rail by default), vertical and
  lateral, n log-spaced frequencies 1-2000 Hz: wall and CPU time, split into the block
  elimination (Schur complement), the sparse LU and the solve with its residual check;
- the lateral receptance with rail torsion (60E1 roll + warping DOFs, force at the gauge
  corner; the default of ``fe_receptance`` for the lateral plane), same point and
  frequencies, and its cost relative to the planar lateral model;
- the static stiffness profile of every rail at every sleeper, both planes;
- the peak memory of the process (ru_maxrss). Targets: receptance <= 10 s,
  < 2 GB; profile <= 60 s. The timings are of this one run on this machine.

The yardstick (``benchmarks/yardstick.py``, a fixed workload independent of this package)
runs before and after each group: the "yardstick units" rows give the group's time in its
units, which carry over between machines and loads.

``--solver``: only the passage's step-matrix solves, SuperLU (minimum degree on A + A^T, no
pivoting: the passage's factor before issue 24) against CHOLMOD (``cholespy``, the
passage's factor now), interleaved in this process; the ratio is what carries over.
"""

from __future__ import annotations

import argparse
import resource
import time

import numpy as np
import scipy.sparse.linalg as sla
from yardstick import Yardstick, machine_line

from exudyn_turnout.fe.frf import sweep, sweep_vectors
from exudyn_turnout.fe.layout import load_layout
from exudyn_turnout.fe.mesh import FEOptions, build_mesh
from exudyn_turnout.fe.model import assemble
from exudyn_turnout.fe.solver import condense, default_keep
from exudyn_turnout.fe.stiffness import static_stiffness_profile
from exudyn_turnout.fe.torsion import UIC60_SECTION
from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.receptance import log_frequencies


class Clock:
    """Wall and CPU seconds of a block."""

    def __enter__(self):
        self.wall, self.cpu = time.perf_counter(), time.process_time()
        return self

    def __exit__(self, *exc):
        self.wall, self.cpu = time.perf_counter() - self.wall, time.process_time() - self.cpu


def _parts(system, b, f) -> dict[str, float]:
    """Wall seconds of the three steps of CondensedSystem.solve over all frequencies."""
    out = {
        "block elimination (Schur)": 0.0,
        "sparse LU (SuperLU)": 0.0,
        "solve + residual check": 0.0,
    }
    for fk in f:
        w = 2 * np.pi * fk
        t0 = time.perf_counter()
        S = system.schur(w)
        t1 = time.perf_counter()
        lu = sla.splu(S, permc_spec="COLAMD")
        t2 = time.perf_counter()
        x = lu.solve(b)
        np.linalg.norm(b - S @ x)
        t3 = time.perf_counter()
        out["block elimination (Schur)"] += t1 - t0
        out["sparse LU (SuperLU)"] += t2 - t1
        out["solve + residual check"] += t3 - t2
    return out


def receptance_rows(turnout, layout, direction, x, f, stick) -> list[tuple[str, str]]:
    rail = layout.slot_rail("r2", x)
    with Clock() as build:
        mesh = build_mesh(turnout, layout, FEOptions(), points={rail: [x]})
        model = assemble(turnout, mesh, direction)
    b_full = model.point_vector(rail, x)
    with Clock() as prep:
        system = condense(model, np.union1d(default_keep(model), np.nonzero(b_full)[0]))
    with Clock() as run:
        H = sweep(model, rail, x, f)
    stick.run()
    total = stick.units(build.wall + run.wall)
    b = system.restrict(b_full).astype(complex)
    parts = _parts(system, b, f)
    rows = [
        (f"{direction}: DOFs (full / kept after condensation)", f"{model.n_dof} / {system.n_keep}"),
        (f"{direction}: build mesh + assemble K, G, D, M", f"{build.wall:.2f} s"),
        (f"{direction}: condensation set-up (blocks, modes)", f"{prep.wall:.2f} s"),
        (
            f"{direction}: receptance r2 ({rail}) x = {x:g} m, {len(f)} freq.",
            f"{run.wall:.2f} s wall, {run.cpu:.2f} s CPU, {1e3 * run.wall / len(f):.1f} ms/freq.",
        ),
        (
            f"{direction}: total (build + sweep)",
            f"{build.wall + run.wall:.2f} s = {total:.1f} yardstick units",
        ),
    ]
    rows += [
        (f"{direction}:   {k}", f"{v:.2f} s ({100 * v / sum(parts.values()):.0f}%)")
        for k, v in parts.items()
    ]
    rows.append((f"{direction}: static stiffness 1/|H(1 Hz)|", f"{1 / abs(H[0]):.4g} N/m"))
    return rows


def torsion_rows(turnout, layout, x, f, planar_wall: float, stick) -> list[tuple[str, str]]:
    """Lateral model with rail torsion: DOFs, build and sweep time, ratio to the planar one."""
    rail = layout.slot_rail("r2", x)
    with Clock() as build:
        mesh = build_mesh(turnout, layout, FEOptions(), points={rail: [x]})
        model = assemble(turnout, mesh, "lateral", torsion=UIC60_SECTION)
    b = model.head_vector(rail, x, UIC60_SECTION.gauge_corner_height)
    keep = np.union1d(default_keep(model), np.nonzero(b)[0])
    with Clock() as run:
        sweep_vectors(model, b[:, None], f)
    stick.run()
    return [
        (
            "lateral + torsion: DOFs (full / kept after condensation)",
            f"{model.n_dof} / {len(keep)}",
        ),
        ("lateral + torsion: build mesh + assemble", f"{build.wall:.2f} s"),
        (
            f"lateral + torsion: receptance at the gauge corner, {len(f)} freq.",
            f"{run.wall:.2f} s wall, {run.cpu:.2f} s CPU, {1e3 * run.wall / len(f):.1f} ms/freq.",
        ),
        ("lateral + torsion: sweep, yardstick units", f"{stick.units(run.wall):.1f}"),
        ("lateral + torsion: sweep time / planar lateral sweep", f"{run.wall / planar_wall:.2f}"),
    ]


def solver_rows(turnout, repeats: int = 20) -> list[tuple[str, str]]:
    """SuperLU vs CHOLMOD on the FE passage's step matrices (h = 1e-4 s, rho_inf 0.8)."""
    from exudyn_turnout.passage.fe_track.planes import (
        CholeskyFactor,
        build_fe_planes,
        generalized_alpha,
    )

    planes = build_fe_planes(turnout)
    ga, h = generalized_alpha(0.8), 1e-4
    rows = []
    for name, m, D in (
        ("vertical", planes.vertical, planes.D_vertical),
        ("lateral", planes.lateral, planes.D_lateral),
    ):
        A = (m.M + ga.gamma_eff * h * D + ga.beta_eff * h * h * m.K).tocsc()
        lu = sla.splu(
            A,
            permc_spec="MMD_AT_PLUS_A",
            options=dict(SymmetricMode=True, DiagPivotThresh=0.0),
        )
        chol = CholeskyFactor(A)
        b = np.random.default_rng(0).standard_normal(m.n_dof)
        t_lu = t_ch = 0.0
        for _ in range(repeats):  # interleaved: both see the same machine load
            with Clock() as c:
                x_lu = lu.solve(b)
            t_lu += c.cpu
            with Clock() as c:
                x_ch = chol.solve(b)
            t_ch += c.cpu
        dev = np.max(np.abs(x_ch - x_lu)) / np.max(np.abs(x_lu))
        rows.append(
            (
                f"step matrix {name} ({m.n_dof} DOFs): CHOLMOD / SuperLU solve CPU",
                f"{t_ch / t_lu:.2f} ({1e3 * t_ch / repeats:.2f} / {1e3 * t_lu / repeats:.2f} "
                f"ms), solutions equal to {dev:.1e}",
            )
        )
    return rows


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=400, help="frequencies, 1-2000 Hz (default 400)")
    parser.add_argument(
        "--x", type=float, default=46.0, help="position of the r2 receptance (m, default 46)"
    )
    parser.add_argument("--solver", action="store_true", help="only SuperLU vs CHOLMOD")
    args = parser.parse_args(argv)
    turnout = load_turnout()
    if args.solver:
        for k, v in solver_rows(turnout):
            print(f"{k:<62}  {v}")
        print(f"(a ratio of two solvers interleaved: it carries over as it is); {machine_line()}")
        return
    layout = load_layout(turnout)
    f = log_frequencies(1.0, 2000.0, args.n)
    stick = Yardstick()
    stick.run()
    rows = [("FE options", str(FEOptions()))]
    for direction in ("vertical", "lateral"):
        rows += receptance_rows(turnout, layout, direction, args.x, f, stick)
    planar_wall = float(next(v for k, v in rows if k.startswith("lateral: receptance")).split()[0])
    rows += torsion_rows(turnout, layout, args.x, f, planar_wall, stick)
    with Clock() as prof:
        profile = static_stiffness_profile(turnout, layout)
    stick.run()
    rows += [
        (
            "static stiffness profile, both planes",
            f"{prof.wall:.2f} s wall = {stick.units(prof.wall):.1f} yardstick units, "
            f"{prof.cpu:.2f} s CPU, {len(profile.x)} rail positions, {len(profile.rails)} rails",
        )
    ]
    rows += [
        (
            "peak memory of the process (ru_maxrss)",
            f"{resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB",
        )
    ]
    width = max(len(k) for k, _ in rows)
    print(f"{'quantity':<{width}}  value")
    print("-" * (width + 60))
    for k, v in rows:
        print(f"{k:<{width}}  {v}")
    print(f"yardstick median {stick.median:.3f} s; {machine_line()}")


if __name__ == "__main__":
    main()
