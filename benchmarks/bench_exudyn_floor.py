"""Benchmark: the floor of a time step of Exudyn's implicit solver with a Python force function.

Run: ``python benchmarks/bench_exudyn_floor.py [--coordinates N] [--steps N] [--repeats N]``.

Why (issue 24): the full vehicle's co-running passage puts all its nonlinear forces (the
contacts, the track springs, the bumpstops) into one ``ObjectGenericODE2`` whose force is a
Python function calling the compiled residual. Exudyn's generalized-alpha solver calls that
function at least twice per step (once for the predictor's residual and once after every
Newton iteration; Exudyn's Newton never stops before its first iteration). This script
measures what those calls cost when the function does nothing: a linear system of N
coordinates (default 103, the full vehicle's) stepped at h = 1e-4 s with modified Newton and
the sparse LU, once alone and once with a Python force function that returns a prepared
list of zeros and a constant sparse Jacobian. The difference is the floor that no faster
residual can remove while Exudyn steps: per call, the lists passed to Python and back and
the Python call itself.

Printed: us per step and calls per step of both, the floor per call, and each run in
yardstick units (``benchmarks/yardstick.py``, run alternately).

Measured (2026-12-02, 2 cores, idle; 23,400 steps, 103 coordinates): 5.9 us per step alone,
15.5-16.0 us per step with the function (2.00 calls per step): ~5 us per call. The full
vehicle's real residual costs ~30 us per call at 2.3 calls per step, so Exudyn's stepping
of the README case cannot come below ~0.5x real time by a faster residual alone, which is
why the compiled stepper (``exudyn_turnout/passage/corunning_track/stepper.py``) exists.
"""

from __future__ import annotations

import argparse
import time

import exudyn as exu
import numpy as np
from exudyn.itemInterface import NodeGenericODE2, ObjectGenericODE2
from yardstick import Yardstick, machine_line


def _sparse(matrix: np.ndarray):
    """An Exudyn sparse MatrixContainer of a dense array."""
    container = exu.MatrixContainer()
    rows, cols = np.nonzero(matrix)
    triplets = np.column_stack([rows, cols, matrix[rows, cols]]).tolist()
    container.SetWithSparseMatrixCSR(*matrix.shape, triplets, useDenseMatrix=False)
    return container


def step_cost(n: int, steps: int, with_function: bool, h: float = 1e-4) -> tuple[float, float]:
    """CPU us per step and force-function calls per step of a linear chain of n coordinates.

    Parameters
    ----------
    n : int
        Coordinates.
    steps : int
        Time steps of h.
    with_function : bool
        Add an ObjectGenericODE2 whose force is a Python function returning zeros.
    h : float
        s, time step.

    Returns
    -------
    (float, float)
        us of CPU per step, calls per step.
    """
    container = exu.SystemContainer()
    mbs = container.AddSystem()
    zeros = [0.0] * n
    node = int(
        mbs.AddNode(
            NodeGenericODE2(
                referenceCoordinates=zeros,
                initialCoordinates=zeros,
                initialCoordinates_t=zeros,
                numberOfODE2Coordinates=n,
            )
        )
    )
    stiffness = np.diag(np.full(n, 1e7)) - 1e6 * (np.eye(n, k=1) + np.eye(n, k=-1))
    mbs.AddObject(
        ObjectGenericODE2(
            nodeNumbers=[node],
            massMatrix=_sparse(np.diag(np.full(n, 100.0))),
            stiffnessMatrix=_sparse(stiffness),
            dampingMatrix=_sparse(1e-4 * stiffness),
        )
    )
    calls = [0]
    jacobian = _sparse(np.diag(np.full(n, 1e-30)))

    def force(mbs, t, item, q, q_t):
        calls[0] += 1
        return zeros

    def force_jacobian(mbs, t, item, q, q_t, f_q, f_q_t):
        return jacobian

    if with_function:
        mbs.AddObject(
            ObjectGenericODE2(
                nodeNumbers=[node], forceUserFunction=force, jacobianUserFunction=force_jacobian
            )
        )
    mbs.Assemble()
    settings = exu.SimulationSettings()
    settings.timeIntegration.numberOfSteps = steps
    settings.timeIntegration.endTime = steps * h
    settings.timeIntegration.verboseMode = 0
    settings.timeIntegration.adaptiveStep = False
    settings.timeIntegration.newton.absoluteTolerance = 5.0
    settings.solution.file.write = False
    settings.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    exu.config.printToConsole = False
    start = time.process_time()
    mbs.SolveDynamic(settings)
    return (time.process_time() - start) / steps * 1e6, calls[0] / steps


def main() -> None:
    """Print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--coordinates", type=int, default=103)
    parser.add_argument("--steps", type=int, default=23400)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    stick = Yardstick()
    rows = []
    for with_function in (False, True):
        costs = []
        timing = stick.measure(
            lambda w=with_function, out=costs: out.append(
                step_cost(args.coordinates, args.steps, w)
            ),
            args.repeats,
        )
        us = float(np.median([c[0] for c in costs]))
        rows.append((with_function, us, costs[0][1], timing.units))
    print(machine_line())
    print(
        f"{args.coordinates} coordinates, {args.steps} steps of 1e-4 s, medians of {args.repeats}"
    )
    print()
    print("| system | CPU us / step | force calls / step | yardstick units |")
    print("|---|---:|---:|---:|")
    for with_function, us, calls, units in rows:
        name = "linear + no-op Python force function" if with_function else "linear only"
        print(f"| {name} | {us:.1f} | {calls:.2f} | {units:.2f} |")
    floor = (rows[1][1] - rows[0][1]) / rows[1][2]
    print(f"\nfloor per Python call: {floor:.1f} us")


if __name__ == "__main__":
    main()
