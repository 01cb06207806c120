"""The normal contact problem against CONTACT's reference outputs: method error or geometry
error?  Writes normal_vs_contact.md.

Run: ``python validation/normal_vs_contact.py``.  For every packaged CONTACT case (S1002
wheel on CONTACT's artificial wing rail, crossing nose, nose + wing rail, the interrupted
nose + wing rail; Apache-2.0, see exudyn_turnout/data/wheel_rail/NOTICE.md) at CONTACT's
wheel position and normal force FN, four normal solutions of ours against CONTACT's:

- **KP**: Kik-Piotrowski (``wheel_rail/nonhertz.kik_piotrowski``) on our gap function
  sampled at 0.02 mm, solved for the penetration that carries FN (as
  ``references.contact_at_reference`` and validation/contact_vs_contact.md do);
- **table law**: what the passage's contact tables store at this point
  (``nonhertz.patch_law`` on the gap sampled at ``GAP_STEP``: Hertz where its ellipse fits
  the surfaces, KP where it does not, blended in between; a power law in the penetration
  through DELTA_LOW and DELTA_HIGH), inverted for FN; its patch is the law's ellipse
  (length 2a, width 2b, PMAX = 3 FN / (2 pi a b)) at KP's force centre;
- **exact, 2-D gap**: the exact half-space solution (``wheel_rail/exact_normal.py``,
  Boussinesq influence coefficients, Polonsky-Keer iteration) on the *same* gap KP works
  on, ``h(x, t) = g(t) + A x^2``: the lateral gap of the 2-D section at the deepest point
  (the rigid-wheel envelope of the slices along the track) and a constant curvature along x;
- **exact, 3-D gap**: the same solver on the gap of the 3-D surfaces: the slices
  interpolated along the track at every ``S + x`` of the grid, the wheel profile at the
  case's shift and height plus the drop ``x^2 / (2 r)`` of its circle (r = NOMRAD),
  vertical gap times cos(contact angle) on the lateral tangent (the ``"linear"``
  surfaces of ``reference_normal``: the same profile polygons as the 2-D slice, so that
  the split below compares like with like; the spline surfaces, the wheel as a body of
  revolution and the tangential problem are in validation/detailed_vs_contact.md);
- **CONTACT**: its APPROACH, PMAX, reference location YCP(R), ZCP(R), and the extent of its
  printed contact map (columns x DX, rows x DS).

The approach error against CONTACT is split into three parts that add up (to first
order): KP minus exact 2-D (KP's method alone, same gap), exact 2-D minus exact 3-D (the
2-D slice: what the 2-D section and its constant curvature along x lose of the 3-D
surfaces, e.g. a rail that ends along x inside the patch), exact 3-D minus CONTACT (the
rest: our profiles and slice interpolation against CONTACT's splines, the grids, the
wheel radius).  The largest is named per case.  The exact solutions are solved on
CONTACT's element size DX x DS and again on half of it; where PMAX changes by more than
:data:`PMAX_CONVERGED` between the two it is called not grid-converged (our profiles
are interpolated linearly between their points, ``sections.surface_on_grid``, so our gap
has corners, and at a corner the exact pressure is singular).  For a prescribed-position
case the exact solution at our undeformed interpenetration (approach prescribed) gives
the FN our geometry produces at CONTACT's wheel position: the vertical part of the
geometry difference.

Lengths and widths are counted in whole elements for the exact solution and CONTACT (one
element: 0.2 mm along x, 0.05 mm across); KP's are its continuous extents.  Material:
CONTACT's G and nu for all methods.
"""

from __future__ import annotations

import os

for _name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

import math  # noqa: E402
from dataclasses import dataclass  # noqa: E402
from pathlib import Path  # noqa: E402

from exudyn_turnout.wheel_rail.data import data_dir, s1002_wheel  # noqa: E402
from exudyn_turnout.wheel_rail.exact_normal import (  # noqa: E402
    solve_on_lateral_gap,
)
from exudyn_turnout.wheel_rail.hertz import effective_modulus  # noqa: E402
from exudyn_turnout.wheel_rail.node_laws import DELTA_REF, node_centre  # noqa: E402
from exudyn_turnout.wheel_rail.nonhertz import GAP_STEP, kik_piotrowski, patch_law  # noqa: E402
from exudyn_turnout.wheel_rail.reference_normal import (  # noqa: E402
    GAP_SAMPLE_STEP,
    CaseGeometry,
    case_geometry,
    exact_on_surface,
)
from exudyn_turnout.wheel_rail.references import (  # noqa: E402
    REFERENCE_FILES,
    ReferenceCase,
    read_reference_output,
)

OUT = Path(__file__).with_suffix(".md")
STEP = GAP_SAMPLE_STEP  # m, sample step of the lateral gap function


@dataclass(frozen=True)
class Normal:
    """One method's normal solution at CONTACT's FN (SI units)."""

    approach: float  #: m
    length: float  #: m, extent along x
    width: float  #: m, extent along the lateral tangent
    p_max: float  #: Pa
    y_rail: float  #: m, where the normal force acts on the rail profile
    z_rail: float  #: m, its height


def _at(geometry: CaseGeometry, t_centre: float) -> tuple[float, float]:
    """A point t along the lateral tangent from the deepest point, on the rail profile."""
    return (
        geometry.y_rail + t_centre * math.cos(geometry.angle),
        geometry.z_rail + t_centre * math.sin(geometry.angle),
    )


def kp_normal(geometry: CaseGeometry, force: float, modulus: float) -> Normal:
    """Kik-Piotrowski at FN (bisection on the penetration, as contact_at_reference)."""

    def solve(delta: float):
        return kik_piotrowski(geometry.gap[None, :], STEP, geometry.a_sum, delta, modulus)

    low, high = 1e-8, 2e-3
    for _ in range(60):
        mid = math.sqrt(low * high)
        low, high = (mid, high) if solve(mid).normal_force[0] < force else (low, mid)
    delta = math.sqrt(low * high)
    patch = solve(delta)
    y, z = _at(geometry, float(patch.t_centre[0]))
    return Normal(
        approach=delta,
        length=2.0 * float(patch.half_length[0]),
        width=float(patch.t_high[0] - patch.t_low[0]),
        p_max=float(patch.p_max[0]),
        y_rail=y,
        z_rail=z,
    )


def table_normal(geometry: CaseGeometry, force: float, modulus: float) -> tuple[Normal, float]:
    """The tables' per-node law at FN, and its weight of KP (0: Hertz)."""
    law = patch_law(geometry.table_gap[None, :], GAP_STEP, geometry.a_raw, geometry.b_raw,
                    modulus)[0]  # fmt: skip
    delta = DELTA_REF * (force / law[0]) ** (1.0 / law[1])
    a = law[2] * (delta / DELTA_REF) ** law[3]
    b = law[4] * (delta / DELTA_REF) ** law[5]
    y, z = _at(geometry, float(node_centre(law[7], law[8], delta)))
    normal = Normal(delta, 2.0 * a, 2.0 * b, 3.0 * force / (2.0 * math.pi * a * b), y, z)
    return normal, float(law[6])


def exact_normal(geometry: CaseGeometry, force: float, modulus: float, dx: float, ds: float):
    """The exact solution on KP's gap at FN, on a grid of dx x ds."""
    solved = solve_on_lateral_gap(geometry.gap, STEP, geometry.a_sum, force, modulus, dx, ds)
    y, z = _at(geometry, solved.y_centre)
    normal = Normal(solved.approach, solved.length, solved.width, solved.p_max, y, z)
    return normal, solved


def exact_surface(case, geometry, profiles, force, modulus, dx, ds, reach):
    """The exact solution on the 3-D gap at FN (``reference_normal.exact_on_surface``)."""
    found = exact_on_surface(
        case, geometry, profiles, force, modulus, dx, ds, reach, surface="linear"
    )
    solved = found.solution
    y_r, z_r = _at(geometry, solved.y_centre)
    normal = Normal(solved.approach, solved.length, solved.width, solved.p_max, y_r, z_r)
    return normal, solved, found.force_at_geometry, found.interpenetration


def _pct(ours: float, reference: float) -> str:
    return f"{(ours / reference - 1.0) * 100:+.1f} %"


def _mm(ours: float, reference: float) -> str:
    return f"{(ours - reference) * 1e3:+.3f} mm"


#: (label, Normal field, scale, unit, difference) of the per-case table
ROWS = (
    ("approach at FN", "approach", 1e3, "mm", "pct"),
    ("patch length along x", "length", 1e3, "mm", "pct"),
    ("patch width along s", "width", 1e3, "mm", "pct"),
    ("PMAX", "p_max", 1e-6, "MPa", "pct"),
    ("YCP(R), force centre on rail", "y_rail", 1e3, "mm", "mm"),
    ("ZCP(R), its height", "z_rail", 1e3, "mm", "mm"),
)
#: Relative change of PMAX with half the element size above which it is called not
#: grid-converged (a corner of the gap: the pressure is singular there)
PMAX_CONVERGED = 0.05


def _diff(kind: str, ours: float, reference: float) -> str:
    return _pct(ours, reference) if kind == "pct" else _mm(ours, reference)


def case_lines(
    name: str, case: ReferenceCase, wheel, profiles: Path, summary: list, tally: dict
) -> list:
    """The section of one case; its summary row is appended to ``summary``, and ``tally``
    counts per method the approaches within 5 % of CONTACT's (issue 22)."""
    patch = case.patches[0]
    force = patch.normal_force
    modulus = effective_modulus(2.0 * case.shear_modulus * (1.0 + case.poisson), case.poisson)
    geometry = case_geometry(case, wheel, profiles)
    kp = kp_normal(geometry, force, modulus)
    table, weight = table_normal(geometry, force, modulus)
    flat, flat_solved = exact_normal(geometry, force, modulus, case.dx, case.ds)
    flat_fine, _ = exact_normal(geometry, force, modulus, 0.5 * case.dx, 0.5 * case.ds)
    reach = (0.5 * flat.length + 2e-3, 0.5 * flat.width + 1e-3)
    surface, solved, force_at_geometry, interpenetration = exact_surface(
        case, geometry, profiles, force, modulus, case.dx, case.ds, reach
    )
    fine_reach = (
        0.5 * solved.pressure.shape[0] * case.dx,
        0.5 * solved.pressure.shape[1] * case.ds,
    )
    surface_fine, *_ = exact_surface(
        case, geometry, profiles, force, modulus, 0.5 * case.dx, 0.5 * case.ds, fine_reach
    )
    reference = Normal(patch.approach, patch.length, patch.width, patch.p_max,
                       patch.y_contact_rail, patch.z_contact_rail)  # fmt: skip
    methods = (("KP", kp), ("table law", table), ("exact, 2-D gap", flat),
               ("exact, 3-D gap", surface))  # fmt: skip
    converged = {
        label: abs(fine.p_max / coarse.p_max - 1.0) <= PMAX_CONVERGED
        for label, coarse, fine in (("2-D", flat, flat_fine), ("3-D", surface, surface_fine))
    }
    lines = [
        f"## {name} case {case.case}",
        "",
        f"Wheel at S = {case.s * 1e3:.1f} mm, Y = {case.y * 1e3:.1f} mm, prescribed"
        f" {case.prescribed}; CONTACT FN = {force:.0f} N.  Our deepest point on the rail at"
        f" y = {geometry.y_rail * 1e3:.2f} mm, x = {geometry.x_offset * 1e3:.2f} mm (CONTACT's"
        f" XCP(TR) {patch.x_contact * 1e3:.2f} mm; the 3-D solution's force centre at x ="
        f" {solved.x_centre * 1e3:.2f} mm), contact angle"
        f" {math.degrees(geometry.angle):.1f} deg, A = {geometry.a_sum:.3f} 1/m; the table"
        f" law's weight of KP: {weight:.2f} (0: Hertz).  Exact solutions on elements of"
        f" {case.dx * 1e3:.2f} x {case.ds * 1e3:.3f} mm (CONTACT's DX x DS): 2-D gap"
        f" {flat_solved.pressure.shape[0]} x {flat_solved.pressure.shape[1]} elements,"
        f" {flat_solved.iterations} iterations; 3-D gap {solved.pressure.shape[0]} x"
        f" {solved.pressure.shape[1]}, {solved.iterations} iterations.  With half the element"
        f" size: approach {_pct(flat_fine.approach, flat.approach)} (2-D),"
        f" {_pct(surface_fine.approach, surface.approach)} (3-D); PMAX"
        f" {_pct(flat_fine.p_max, flat.p_max)} (2-D), {_pct(surface_fine.p_max, surface.p_max)}"
        f" (3-D)"
        + (
            "."
            if all(converged.values())
            else f": PMAX of the {' and '.join(k for k, v in converged.items() if not v)} gap"
            " is not grid-converged (a corner in our gap, where the exact pressure is"
            " singular)."
        ),
        "",
        "| quantity | CONTACT | " + " | ".join(f"{m} | error" for m, _ in methods) + " |",
        "|---|---|" + "---|---|" * len(methods),
    ]
    for label, field, scale, unit, kind in ROWS:
        ref = getattr(reference, field)
        cells = [f"{ref * scale:.4g} {unit}"]
        for _method, normal in methods:
            value = getattr(normal, field)
            cells += [f"{value * scale:.4g}", _diff(kind, value, ref)]
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    lines.append("")
    if case.prescribed == "position":
        lines += [
            f"At CONTACT's wheel position our undeformed surfaces interpenetrate by"
            f" {interpenetration * 1e3:.4f} mm (3-D; the 2-D slice's deepest point"
            f" {geometry.interpenetration * 1e3:.4f} mm) against CONTACT's approach"
            f" {patch.approach * 1e3:.4f} mm; the exact solution there carries"
            f" {force_at_geometry / 1e3:.3f} kN against CONTACT's {force / 1e3:.3f} kN"
            f" ({_pct(force_at_geometry, force)}): the vertical part of the geometry"
            " difference.",
            "",
        ]
    errors = {
        "KP's method (KP - exact 2-D)": kp.approach / flat.approach - 1.0,
        "the 2-D slice (exact 2-D - exact 3-D)": flat.approach / surface.approach - 1.0,
        "the rest (exact 3-D - CONTACT)": surface.approach / patch.approach - 1.0,
    }
    largest = max(errors, key=lambda key: abs(errors[key]))
    lines += [
        "Approach error by source: "
        + "; ".join(f"{key} {value * 100:+.1f} %" for key, value in errors.items())
        + f".  The largest: **{largest}**.",
        "",
    ]
    for key, normal in (("KP", kp), ("table law", table), ("exact 2-D", flat),
                        ("exact 3-D", surface)):  # fmt: skip
        tally[key] = tally.get(key, 0) + (abs(normal.approach / patch.approach - 1) <= 0.05)
    summary.append(
        f"| {name}#{case.case} | {_pct(kp.approach, patch.approach)}"
        f" | {_pct(table.approach, patch.approach)} | {_pct(flat.approach, patch.approach)}"
        f" | {_pct(surface.approach, patch.approach)} | "
        + " | ".join(f"{value * 100:+.1f} %" for value in errors.values())
        + f" | {kp.length * 1e3:.2f} / {flat.length * 1e3:.2f} / {surface.length * 1e3:.2f}"
        f" / {patch.length * 1e3:.2f}"
        f" | {kp.width * 1e3:.2f} / {flat.width * 1e3:.2f} / {surface.width * 1e3:.2f}"
        f" / {patch.width * 1e3:.2f}"
        f" | {kp.p_max / 1e6:.0f} / {flat.p_max / 1e6:.0f} / {surface.p_max / 1e6:.0f}"
        f" / {patch.p_max / 1e6:.0f} |"
    )
    return lines


def main() -> int:
    """Write normal_vs_contact.md (and print it)."""
    wheel = s1002_wheel()
    folder = data_dir()
    summary: list[str] = []
    body: list[str] = []
    tally: dict[str, int] = {}
    for name in REFERENCE_FILES:
        path = folder / "reference_outputs" / f"{name}.ref_out"
        for case in read_reference_output(path):
            body += case_lines(name, case, wheel, folder / "profiles", summary, tally)
    lines = [
        "# The normal problem against CONTACT: method error or geometry error",
        "",
        "Written by `python validation/normal_vs_contact.py` (methods in its docstring)."
        "  KP: Kik-Piotrowski on our gap function; table law: what the passage's contact"
        " tables store at the point (Hertz where it fits, else KP, as a power law);"
        " exact, 2-D gap: the exact half-space solution (`wheel_rail/exact_normal.py`) on"
        " the gap KP works on, `g(t) + A x^2` (the lateral gap at the envelope's deepest"
        " point); exact, 3-D gap: the same solver on the gap of the 3-D surfaces (the"
        " slices interpolated along the track at every x, the wheel's circle).  All at"
        " CONTACT's FN; errors relative to CONTACT.",
        "",
        "## Summary",
        "",
        "Approach at CONTACT's FN, and its error split by source: KP's method (KP against"
        " the exact solution on the same gap), the 2-D slice (the exact solution on the"
        " slice's gap against that on the 3-D surfaces), the rest (the exact solution on"
        " our 3-D surfaces against CONTACT: profiles, slice interpolation, CONTACT's"
        " discretisation).  Lengths, widths and PMAX: KP / exact 2-D / exact 3-D /"
        " CONTACT.",
        "",
        "| case | KP | table law | exact 2-D | exact 3-D | KP's method | 2-D slice | rest"
        " | length (mm) | width (mm) | PMAX (MPa) |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
        *summary,
        "",
        f"Approach within 5 % of CONTACT's (issue 22) in {len(summary)} cases: "
        + ", ".join(f"{key} {count}" for key, count in tally.items())
        + ".",
        "",
        *body,
    ]
    OUT.write_text("\n".join(lines), encoding="utf-8")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
