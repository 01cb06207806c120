"""Our own detailed (CONTACT-like) contact: exact normal and exact tangential solution.

A *reference tool*, not the passage's contact: it solves one contact in seconds (the
passage's contact tables and creep law take microseconds), to measure what the passage's
methods lose, the way CONTACT (E.A.H. Vollebregt and J.J. Kalker, open-source version,
github eve70a/CONTACT at d431cdb) is used in the literature.

* **Normal problem**: the exact half-space solution (:mod:`.exact_normal`) on the gap of
  our 3-D surfaces (:func:`.reference_normal.exact_on_surface`: spline profiles, the
  wheel a body of revolution, the contact plane pitched by the wheel's slope), at a
  prescribed normal force, on elements of ``dx`` x ``ds``.
* **Tangential problem**: Kalker's exact theory of steady rolling
  (:func:`.exact_rolling.solve_steady_rolling`) on the *same* elements and that pressure
  (:func:`rolling_on_normal`), at given creepages and friction.  The creepages are taken
  about the normal solution's force centre (CONTACT's reference point is "centred within
  the contact patch in a weighted sense", its user guide, section "Contact patches"); the
  grid's x is the rolling direction in the contact plane, its y the lateral tangent
  towards the field side (CONTACT's x and s for its right rail), forces on the wheel
  with CONTACT's signs (``validation/contact_vs_contact.md`` checks the conventions on
  CONTACT's own areas).

Equal materials: the normal and tangential problems decouple (Kalker 1990, ch. 1), so the
normal pressure is solved first and held.  Cost: one dense LU of 2 m unknowns per Newton
iteration for m elements in contact (:mod:`.exact_rolling`); on CONTACT's five reference
cases at its element size (469-1281 elements) the tangential problem took 0.2-4.9 s of
CPU (0.5-15 s wall on a loaded 2-core machine) and the normal one 1.3-3.6 s wall
(``benchmarks/bench_detailed_contact.py``); at half the element size 23-160 s wall.  Run it
with one BLAS thread on a shared machine: two threads made the tangential problem 1.1-5
times slower there.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from exudyn_turnout.wheel_rail.exact_normal import NormalSolution
from exudyn_turnout.wheel_rail.exact_rolling import RollingSolution, solve_steady_rolling
from exudyn_turnout.wheel_rail.hertz import effective_modulus
from exudyn_turnout.wheel_rail.reference_normal import (
    CaseGeometry,
    SurfaceContact,
    exact_on_surface,
)
from exudyn_turnout.wheel_rail.references import ReferenceCase

__all__ = ["rolling_on_normal", "DetailedContact", "detailed_contact"]


def rolling_on_normal(
    solution: NormalSolution,
    xi: float,
    eta: float,
    phi: float,
    friction: float,
    shear_modulus: float,
    poisson: float,
) -> RollingSolution:
    """Kalker's exact steady rolling on an exact normal solution's elements and pressure.

    The grid is cut to the contact's bounding box plus one empty element on every side
    (the upwind derivative reads the element ahead); the spin and the moment are taken
    about the normal force's centre.

    Parameters
    ----------
    solution : NormalSolution
        From :func:`.exact_normal.solve_normal` (or :func:`.reference_normal.exact_on_surface`);
        axis 0 the rolling direction (rolling in +x), axis 1 lateral.
    xi, eta : float
        Longitudinal and lateral creepage (-), of body 1 relative to body 2.
    phi : float
        1/m, spin creepage.
    friction : float
        Coefficient of friction.
    shear_modulus : float
        Pa, G of both bodies.
    poisson : float
        Poisson's ratio of both bodies.

    Returns
    -------
    RollingSolution
        Forces on body 1; its tractions on the cut grid.

    Raises
    ------
    ValueError
        If the solution carries no pressure.
    """
    p = np.asarray(solution.pressure, float)
    total = float(p.sum())
    if not total > 0.0:
        raise ValueError("rolling_on_normal: the normal solution carries no pressure")
    rows, cols = np.nonzero(p > 0.0)
    i0, i1 = max(rows.min() - 1, 0), rows.max() + 2
    j0, j1 = max(cols.min() - 1, 0), cols.max() + 2
    cut = np.zeros((i1 - i0, j1 - j0))
    inside = p[i0:i1, j0:j1]
    cut[: inside.shape[0], : inside.shape[1]] = inside
    # the force centre in element indices, then the cut grid's corner from it
    i_c = float(np.sum(p.sum(axis=1) * np.arange(p.shape[0]))) / total
    j_c = float(np.sum(p.sum(axis=0) * np.arange(p.shape[1]))) / total
    x0 = (i0 - 0.5 - i_c) * solution.dx
    y0 = (j0 - 0.5 - j_c) * solution.dy
    return solve_steady_rolling(
        cut, solution.dx, solution.dy, x0, y0, xi, eta, phi, friction, shear_modulus, poisson
    )


@dataclass(frozen=True, eq=False)
class DetailedContact:
    """Our detailed contact at a CONTACT case: exact normal, then exact tangential."""

    normal: SurfaceContact  #: the exact normal solution on the 3-D gap (SI, see its class)
    rolling: RollingSolution  #: the exact steady-rolling solution on its pressure
    fx: float  #: N, longitudinal tangential force on the wheel (CONTACT's FX)
    fs: float  #: N, lateral tangential force in the contact plane (CONTACT's FS)


def detailed_contact(
    case: ReferenceCase,
    geometry: CaseGeometry,
    profiles_dir: str | Path,
    dx: float,
    ds: float,
    surface: str = "spline",
    reach: tuple[float, float] = (6e-3, 3e-3),
) -> DetailedContact:
    """Our detailed contact at a CONTACT case's wheel position, FN, creepages and material.

    The normal problem at CONTACT's FN of the first patch
    (:func:`.reference_normal.exact_on_surface`), then the tangential one at its CKSI,
    CETA, CPHI and FSTAT, with its G and nu (:func:`rolling_on_normal`).

    Parameters
    ----------
    case : ReferenceCase
        The CONTACT case.
    geometry : CaseGeometry
        Our geometry there (:func:`.reference_normal.case_geometry`).
    profiles_dir : str or Path
        Folder holding the slice files.
    dx, ds : float
        m, element size along x and the lateral tangent.
    surface : str
        Which 3-D surfaces (:data:`.reference_normal.SURFACES`).
    reach : (float, float)
        m, first half-widths of the normal problem's grid.

    Returns
    -------
    DetailedContact
    """
    patch = case.patches[0]
    modulus = effective_modulus(2.0 * case.shear_modulus * (1.0 + case.poisson), case.poisson)
    normal = exact_on_surface(
        case, geometry, profiles_dir, patch.normal_force, modulus, dx, ds, reach, surface
    )
    rolling = rolling_on_normal(
        normal.solution, patch.cksi, patch.ceta, patch.cphi, case.friction,
        case.shear_modulus, case.poisson,
    )  # fmt: skip
    return DetailedContact(normal, rolling, rolling.fx, rolling.fy)


if __name__ == "__main__":
    from exudyn_turnout.wheel_rail.data import data_dir, s1002_wheel
    from exudyn_turnout.wheel_rail.reference_normal import case_geometry
    from exudyn_turnout.wheel_rail.references import read_reference_output

    folder = data_dir()
    first = read_reference_output(folder / "reference_outputs" / "wing_brute.ref_out")[0]
    shape = case_geometry(first, s1002_wheel(), folder / "profiles")
    found = detailed_contact(first, shape, folder / "profiles", first.dx, first.ds)
    print(f"FX {found.fx:.0f} N (CONTACT {first.patches[0].fx:.0f}),"
          f" FS {found.fs:.0f} N (CONTACT {first.patches[0].fs:.0f})")  # fmt: skip
