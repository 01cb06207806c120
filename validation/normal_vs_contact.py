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
  vertical gap times cos(contact angle) on the lateral tangent;
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

import numpy as np  # noqa: E402

from exudyn_turnout.wheel_rail.data import data_dir, s1002_wheel  # noqa: E402
from exudyn_turnout.wheel_rail.exact_normal import (  # noqa: E402
    solve_normal,
    solve_on_lateral_gap,
)
from exudyn_turnout.wheel_rail.geometry import (  # noqa: E402
    FLANGE_DIRECTION,
    prepare_rail,
    prepare_wheel,
    search_candidates,
    surface_derivatives,
)
from exudyn_turnout.wheel_rail.hertz import curvature_sums, effective_modulus  # noqa: E402
from exudyn_turnout.wheel_rail.nonhertz import (  # noqa: E402
    DELTA_REF,
    GAP_STEP,
    kik_piotrowski,
    node_centre,
    normal_gap_function,
    patch_law,
)
from exudyn_turnout.wheel_rail.profiles import read_slices  # noqa: E402
from exudyn_turnout.wheel_rail.references import (  # noqa: E402
    REFERENCE_FILES,
    ReferenceCase,
    read_reference_output,
)
from exudyn_turnout.wheel_rail.sections import (  # noqa: E402
    lateral_grid,
    slice_sections,
    wheel_envelope,
)

OUT = Path(__file__).with_suffix(".md")
#: m, sample step and half-width of the gap function (as references.contact_at_reference)
STEP, WINDOW = 2e-5, 0.02
#: m, step and reach of the rigid-wheel envelope along x, CONTACT's NOMRAD
ENVELOPE_STEP, REACH, NOMINAL_RADIUS = 2.5e-4, 0.1, 0.46


@dataclass(frozen=True)
class Normal:
    """One method's normal solution at CONTACT's FN (SI units)."""

    approach: float  #: m
    length: float  #: m, extent along x
    width: float  #: m, extent along the lateral tangent
    p_max: float  #: Pa
    y_rail: float  #: m, where the normal force acts on the rail profile
    z_rail: float  #: m, its height


@dataclass(frozen=True)
class CaseGeometry:
    """Our geometry at a CONTACT case: the candidate nearest CONTACT's patch."""

    gap: np.ndarray  #: m, normal gap along the lateral tangent, sampled at STEP
    table_gap: np.ndarray  #: m, the same sampled at GAP_STEP (the tables' sampling)
    a_sum: float  #: 1/m, relative curvature along x (floored as in the tables)
    a_raw: float  #: 1/m, unfloored
    b_raw: float  #: 1/m, unfloored relative lateral curvature
    angle: float  #: rad, contact angle
    y_rail: float  #: m, deepest point on the rail
    z_rail: float  #: m, its height (at the envelope's x)
    interpenetration: float  #: m, undeformed interpenetration at CONTACT's position
    x_offset: float  #: m, where along x the rigid wheel meets the rail (envelope)
    wheel_y: np.ndarray  #: m, the wheel's surface points at zero shift (lateral)
    wheel_z: np.ndarray  #: m, their heights at zero lift


def case_geometry(case: ReferenceCase, wheel, profiles: Path) -> CaseGeometry:
    """Our undeformed geometry at a case, built as ``references.contact_at_reference``."""
    slices = read_slices(profiles / Path(case.rail_file).name)
    grid = lateral_grid(-0.08, 0.30, wheel.s[1] - wheel.s[0])
    offsets = np.arange(-REACH, REACH + 0.5 * ENVELOPE_STEP, ENVELOPE_STEP)
    sections = slice_sections(slices, grid, x=case.s + offsets, interpolation="auto")
    enveloped = wheel_envelope(
        sections, np.array([case.s]), NOMINAL_RADIUS, reach=REACH, step=ENVELOPE_STEP
    )
    derivatives = surface_derivatives(enveloped)
    rail = prepare_rail(enveloped.z[0], derivatives.slope[0], derivatives.curvature[0], grid)
    prepared = prepare_wheel(wheel, 0.0, 0.0, (FLANGE_DIRECTION,))
    found = search_candidates(rail, prepared, shift=case.y, lift=case.wheel_height)
    k = int(np.argmin(np.abs(found.y_rail - case.y_contact_rail)))
    row = slice(k, k + 1)
    args = (rail, prepared, np.array([case.y]), found.y_rail[row], found.z_rail[row],
            found.angle[row])  # fmt: skip
    gap = normal_gap_function(*args, step=STEP, window=WINDOW, lift=case.wheel_height)[0]
    table_gap = normal_gap_function(*args, lift=case.wheel_height)[0]
    a_sum, _b = curvature_sums(
        found.radius[row], found.angle[row], found.curvature_wheel[row],
        found.curvature_rail[row],
    )  # fmt: skip
    index = int(round((found.y_rail[k] - grid[0]) / (grid[1] - grid[0])))
    assert enveloped.x_offset is not None
    dx = float(enveloped.x_offset[0, index])
    return CaseGeometry(
        gap=gap,
        table_gap=table_gap,
        a_sum=float(a_sum[0]),
        a_raw=float(0.5 * np.cos(found.angle[k]) / found.radius[k]),
        b_raw=float(
            0.5 * (np.nan_to_num(found.curvature_wheel[k]) + np.nan_to_num(found.curvature_rail[k]))
        ),
        angle=float(found.angle[k]),
        y_rail=float(found.y_rail[k]),
        z_rail=float(found.z_rail[k]) + dx * dx / (2 * NOMINAL_RADIUS),
        interpenetration=-float(found.gap[k]),
        x_offset=dx,
        wheel_y=prepared.y,
        wheel_z=prepared.z,
    )


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


def surface_gap(case: ReferenceCase, geometry: CaseGeometry, profiles: Path, x, t):
    """m, the undeformed normal gap of the 3-D surfaces on the grid (x, t), negative where
    they interpenetrate at CONTACT's wheel position.

    The rail is the slice set interpolated along the track at every ``S + x`` (no
    envelope, no 2-D slice), the wheel its profile at the case's shift and height with
    the drop ``x^2 / (2 r)`` of its circle (r = NOMRAD); the vertical gap at ``y = y_c +
    t cos(gamma)`` times ``cos(gamma)`` is the normal gap, as
    ``nonhertz.normal_gap_function`` takes it in the vertical frame.
    """
    slices = read_slices(profiles / Path(case.rail_file).name)
    cosine = math.cos(geometry.angle)
    y = geometry.y_rail + t * cosine
    rail = slice_sections(slices, y, x=case.s + x, interpolation="auto").z
    order = np.argsort(geometry.wheel_y)
    wheel = np.interp(y - case.y, geometry.wheel_y[order], geometry.wheel_z[order])
    vertical = wheel[None, :] + case.wheel_height + x[:, None] ** 2 / (2 * NOMINAL_RADIUS) - rail
    return np.where(np.isfinite(vertical), cosine * vertical, 1.0)  # no rail: 1 m apart


def exact_surface(case, geometry, profiles, force, modulus, dx, ds, reach):
    """The exact solution on the 3-D gap (:func:`surface_gap`) at FN, and the force at our
    undeformed interpenetration; the grid spans ``reach`` (x, t half-widths, m) around
    the envelope's contact point and grows while the contact touches its edge."""
    half_x, half_t = reach
    for _ in range(6):
        nx, ny = 2 * int(half_x / dx) + 1, 2 * int(half_t / ds) + 1
        x = geometry.x_offset + (np.arange(nx) - 0.5 * (nx - 1)) * dx
        t = (np.arange(ny) - 0.5 * (ny - 1)) * ds
        h = surface_gap(case, geometry, profiles, x, t)
        lowest = float(np.min(h))
        solved = solve_normal(h - lowest, dx, ds, modulus, force=force)
        rows, cols = np.nonzero(solved.pressure)
        if rows.min() > 0 and cols.min() > 0 and rows.max() < nx - 1 and cols.max() < ny - 1:
            break
        half_x, half_t = 1.5 * half_x, 1.5 * half_t
    at_geometry = solve_normal(h - lowest, dx, ds, modulus, approach=-lowest).normal_force
    t_centre = solved.y_centre + float(t[0] - solved.y[0])
    y_r, z_r = _at(geometry, t_centre)
    normal = Normal(solved.approach, solved.length, solved.width, solved.p_max, y_r, z_r)
    return normal, solved, at_geometry, -lowest


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
        f" {(geometry.x_offset + solved.x_centre) * 1e3:.2f} mm), contact angle"
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
