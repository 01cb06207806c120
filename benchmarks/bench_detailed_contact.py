"""Cost of our detailed contact (``wheel_rail.detailed_contact``) at CONTACT's five cases.

Run: ``python benchmarks/bench_detailed_contact.py [--threads N] [--repeats N]``.  BLAS and
OpenMP are held to ``--threads`` threads (default 1) before numpy loads: run it with 1 and
with 2 to see what a second core buys the dense LU of the tangential problem.

Per case, at CONTACT's element size DX x DS: the geometry (our envelope and the 2-D slice,
``reference_normal.case_geometry``), the exact normal solution on the 3-D spline surfaces
(``reference_normal.exact_on_surface``) and Kalker's exact steady rolling on its pressure
(``detailed_contact.rolling_on_normal``), in seconds and in yardstick units
(``benchmarks/yardstick.py``, run interleaved), with the elements in contact and the Newton
iterations.  A reference tool: the passage's creep law takes microseconds per contact.
"""

import argparse
import os
import sys


def _threads() -> str:
    """The --threads value, read before numpy is imported."""
    for k, arg in enumerate(sys.argv):
        if arg == "--threads" and k + 1 < len(sys.argv):
            return sys.argv[k + 1]
        if arg.startswith("--threads="):
            return arg.split("=", 1)[1]
    return "1"


for _name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_name] = _threads()

from yardstick import Yardstick, machine_line  # noqa: E402

from exudyn_turnout.wheel_rail.data import data_dir, s1002_wheel  # noqa: E402
from exudyn_turnout.wheel_rail.detailed_contact import rolling_on_normal  # noqa: E402
from exudyn_turnout.wheel_rail.hertz import effective_modulus  # noqa: E402
from exudyn_turnout.wheel_rail.reference_normal import (  # noqa: E402
    case_geometry,
    exact_on_surface,
)
from exudyn_turnout.wheel_rail.references import (  # noqa: E402
    REFERENCE_FILES,
    read_reference_output,
)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--threads", type=int, default=1, help="BLAS/OpenMP threads")
    parser.add_argument("--repeats", type=int, default=1)
    args = parser.parse_args()
    folder = data_dir()
    profiles = folder / "profiles"
    wheel = s1002_wheel()
    stick = Yardstick()
    print(f"BLAS threads: {args.threads}")
    print(
        f"{'case':<16} {'elements':>8} {'Newton':>6} {'geometry s':>10} {'normal s':>9}"
        f" {'tangential s':>12} {'its CPU s':>9} {'tangential yst':>14}"
    )
    for name in REFERENCE_FILES:
        for case in read_reference_output(folder / "reference_outputs" / f"{name}.ref_out"):
            patch = case.patches[0]
            modulus = effective_modulus(
                2.0 * case.shear_modulus * (1.0 + case.poisson), case.poisson
            )
            geo = stick.measure(
                lambda c=case: case_geometry(c, wheel, profiles), args.repeats, False
            )
            geometry = geo.result
            normal = stick.measure(
                lambda c=case, g=geometry, p=patch, m=modulus: exact_on_surface(
                    c, g, profiles, p.normal_force, m, c.dx, c.ds
                ),
                args.repeats,
                False,
            )
            solution = normal.result.solution
            rolling = stick.measure(
                lambda c=case, p=patch, s=solution: rolling_on_normal(
                    s, p.cksi, p.ceta, p.cphi, c.friction, c.shear_modulus, c.poisson
                ),
                args.repeats,
                False,
            )
            solved = rolling.result
            print(
                f"{name + '#' + str(case.case):<16} {int(solved.contact.sum()):>8}"
                f" {solved.iterations:>6} {geo.seconds:>10.2f} {normal.seconds:>9.2f}"
                f" {rolling.seconds:>12.2f} {rolling.cpu_seconds:>9.2f} {rolling.units:>14.1f}"
            )
    print(f"yardstick median {stick.median:.3f} s; {machine_line()}")


if __name__ == "__main__":
    main()
