"""How wrong is the passage's contact law at the instants that make the paper's peaks?

Writes peak_contact.md.  Run: ``python validation/peak_contact.py`` (run time in the page).

The packaged turnout (UIC60-760-1:15), the default vehicle (the full Manchester vehicle,
profile contact, its front wheelset: the plain columns) and the single wheelset
(``--vehicle`` picks), the default runs of the validation report: the through route at 100
km/h and the diverging route at 80 km/h, on the 3-layer and the 2-layer co-running track,
each over the whole turnout (cheaper than windows that would need a settled start; the
page gives the passages' time). In every run the instants of the paper's peaks of the
front right wheel (the paper's Figs 7, 8): the largest Fz and the largest |Fy| in the
switch and in the crossing regions of ``[regions]`` (``report.settings``), and the largest
|Fy| on a check rail (slot r3). At each instant every contact point of that wheel carrying
more than :data:`MIN_LOAD` goes through
:func:`exudyn_turnout.passage.post_contact.post_contact`: the passage's contact rebuilt by
its own kernel on the recorded coordinates, then our exact contact on the 3-D surfaces at
the passage's normal force and creepages (method and choices in that module's docstring).

Reading the columns (passage vs exact; a difference in per cent is exact / passage - 1,
for two forces of one sign the change of their magnitude):

* **delta**: the passage's penetration and the exact approach at the passage's N;
* **N at delta**: the exact normal force at the passage's penetration (taken as approach
  beyond first touch of the 3-D surfaces): the normal law's error as a force, the answer
  to "would the peak change if the normal law were exact, the wheel and rail where they
  were";
* **N at state**: the exact force at the 3-D surfaces' own interpenetration at the
  recorded positions (adds the difference of the tables' 2-D enveloped geometry);
* **2a, 2b, PMAX**: the passage's creep-law ellipse (Hertz, or Kik-Piotrowski's equivalent
  ellipse) and its Hertzian peak 3 N / (2 pi a b), against the exact patch's extent and
  its largest element pressure;
* **FX, FS**: the recorded creep forces (FASTSIM table) against Kalker's exact steady
  rolling at the same creepages, on the exact pressure at the same N; and Kalker's exact
  theory on the passage's own ellipse with Hertz's pressure (the creep law's error alone,
  the difference to the exact patch's being the patch's);
* **dy, dx**: the exact force centre minus the recorded contact position, on the rail and
  along the track.

The wheel forces' change (last table) adds the contacts of the wheel:
``dFz = sum(cos(gamma) dN + s sin(gamma) dFt)`` and ``dFy = sum(s sin(gamma) dN - cos(gamma) dFt)``
(forces on the rail, the kernel's frame), with dN the exact force at the passage's
penetration minus the passage's and dFt the exact FS minus the recorded.  This is the
change at frozen positions, the quasi-static upper bound: in the dynamics the contact
spring is in series with the wheel's and rail's compliance, which takes part of any change
of the contact's stiffness.
"""

from __future__ import annotations

import argparse
import math
import os
import time
from pathlib import Path

import numpy as np

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage import simulate_passage
from exudyn_turnout.passage.post_contact import (
    ELEMENTS_ACROSS,
    SHEAR_MODULUS,
    PostContact,
    contact_stems,
    post_contact,
)
from exudyn_turnout.passage.settings import PassageSettings
from exudyn_turnout.report.settings import report_settings
from exudyn_turnout.wheel_rail.exact_rolling import exact_creep_forces_ellipse
from exudyn_turnout.wheel_rail.fastsim import fastsim_solver
from exudyn_turnout.wheel_rail.turnout_design import rail_geometry
from exudyn_turnout.wheel_rail.turnout_sections import route_rail_bodies

HERE = Path(__file__).resolve().parent
#: (route, speed km/h, layers): the validation report's co-running runs
#: the packaged vehicles run: the full vehicle (the default of a passage) and the wheelset
VEHICLES = ("manchester", "wheelset")
RUNS = (
    ("through", 100.0, 3),
    ("through", 100.0, 2),
    ("diverging", 80.0, 3),
    ("diverging", 80.0, 2),
)
#: N, contacts carrying less at the instant are left out
MIN_LOAD = 1000.0
WHEEL = "right"
#: peaks of the 3-layer runs whose contacts are solved again on finer elements
CONVERGENCE_PEAKS = ("Fz switch", "Fz crossing", "Fy check rail (right)")
#: elements across each axis of the patch in that check (the default: ``ELEMENTS_ACROSS``)
FINE_ELEMENTS = 40


def _instants(result, regions) -> list[tuple[str, int]]:
    """(label, sample index) of the peaks of the front right wheel and of a check rail."""
    cols = result.columns
    x = cols["x_m"]
    out = []
    for region in ("switch", "crossing"):
        lo, hi = regions[region]
        inside = np.flatnonzero((x >= lo) & (x <= hi))
        if inside.size == 0:
            continue
        fz = np.nan_to_num(cols[f"Fz_{WHEEL}_N"][inside])
        fy = np.nan_to_num(cols[f"Fy_{WHEEL}_N"][inside])
        out.append((f"Fz {region}", int(inside[np.argmax(fz)])))
        out.append((f"Fy {region}", int(inside[np.argmax(np.abs(fy))])))
    for wheel in ("right", "left"):
        name = f"Fy_{wheel}_r3_N"
        if name in cols and np.nanmax(np.abs(cols[name])) > MIN_LOAD:
            out.append((f"Fy check rail ({wheel})", int(np.nanargmax(np.abs(cols[name])))))
    return out


def _wheel_of(stem: str) -> str:
    return stem.split("_")[1]


def _short(stem: str) -> str:
    """``cp_right_r2_right_wheel_on_crossing_nose_0`` -> ``r2 crossing nose #0``."""
    parts = stem.split("_")
    body = "_".join(parts[3:-1]).replace(f"{parts[1]}_wheel_on_", "").replace("_", " ")
    return f"{parts[2]} {body} #{parts[-1]}"


def _pct(new: float, old: float) -> str:
    """``new / old - 1`` in per cent (for two forces of one sign: the change of magnitude)."""
    if not (math.isfinite(new) and math.isfinite(old)) or old == 0.0:
        return "-"
    return f"{100.0 * (new / old - 1.0):+.1f} %"


def _peak_contacts(label: str, found: list[PostContact]) -> list[PostContact]:
    """The contacts whose forces make the peak: a check rail's alone, else the wheel's."""
    return [c for c in found if "_r3_" in c.stem] if "check" in label else found


def _wheel_change(found: list[PostContact]) -> dict[str, float]:
    """Rebuilt Fz, Fy on the rail of the contacts and their changes (module docstring).

    ``n``: the part of the normal forces at the passage's penetrations, ``t``: the part of
    the creep forces at its creepages and normal forces.
    """
    out = dict.fromkeys(("Fz", "Fy", "Fz_n", "Fz_t", "Fy_n", "Fy_t"), 0.0)
    for c in found:
        s = 1.0 if _wheel_of(c.stem) == "left" else -1.0
        cg, sg = math.cos(c.angle), math.sin(c.angle)
        out["Fz"] += cg * c.normal + s * sg * c.fs
        out["Fy"] += s * sg * c.normal - cg * c.fs
        dn, dft = c.force_difference, c.exact_fs - c.fs
        out["Fz_n"] += cg * dn
        out["Fz_t"] += s * sg * dft
        out["Fy_n"] += s * sg * dn
        out["Fy_t"] += -cg * dft
    return out


def _magnitude(change: float, peak: float) -> str:
    """Relative change of a peak's magnitude."""
    if peak == 0.0 or not math.isfinite(change):
        return "-"
    return f"{100.0 * (abs(peak + change) - abs(peak)) / abs(peak):+.1f} %"


def main(argv=None) -> None:
    """Run the passages, post-process their peaks, write peak_contact.md.

    Parameters
    ----------
    argv : list of str, optional
        Command-line arguments (``--runs N``: only the first N runs of each vehicle, for a
        quick look; ``--vehicle``: the packaged vehicles; ``--out``: the page).
    """
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=len(RUNS))
    parser.add_argument("--out", type=Path, default=HERE / "peak_contact.md")
    parser.add_argument(
        "--vehicle", nargs="+", default=list(VEHICLES), help="packaged vehicles to run"
    )
    args = parser.parse_args(argv)
    started = time.perf_counter()
    cpu_started = time.process_time()
    turnout = load_turnout()
    regions = report_settings(turnout).regions
    records = []  # (run label, peak label, x, wheel force, [PostContact])
    passage_seconds = exact_seconds = 0.0
    finer = []  # (run, label, contact, its result and sample): the element-size check
    runs = [(v, *r) for v in args.vehicle for r in RUNS[: args.runs]]
    for vehicle, route, speed, layers in runs:
        t0 = time.perf_counter()
        result = simulate_passage(
            turnout, PassageSettings(route=route, speed_kmh=speed, layers=layers), vehicle
        )
        passage_seconds += time.perf_counter() - t0
        run = f"{vehicle}, {route} {speed:.0f} km/h, {layers}-layer"
        for label, i in _instants(result, regions):
            wheel = "left" if "(left)" in label else WHEEL
            found = []
            for stem in contact_stems(result, wheel):
                if result.columns[f"{stem}_N_N"][i] > MIN_LOAD:
                    found.append(post_contact(turnout, result, stem, i))
                    exact_seconds += found[-1].seconds
                    first = vehicle == args.vehicle[0]
                    if first and layers == 3 and label in CONVERGENCE_PEAKS and "_r1_" not in stem:
                        finer.append((run, label, found[-1], result, i))
            column = f"Fy_{wheel}_r3_N" if "check" in label else f"{label[:2]}_{wheel}_N"
            force = result.columns[column][i]
            records.append((run, label, float(result.columns["x_m"][i]), float(force), found))
            print(run, label, f"x = {result.columns['x_m'][i]:.3f}", len(found), "contact(s)")
    convergence = []
    for run, label, coarse, result, i in finer:
        fine = post_contact(turnout, result, coarse.stem, i, elements=FINE_ELEMENTS)
        exact_seconds += fine.seconds
        convergence.append((run, label, coarse, fine))
    wall = time.perf_counter() - started
    cpu = time.process_time() - cpu_started
    check = next(b for b in route_rail_bodies(turnout, "diverging") if b.back_of_flange)
    flare_end = check.x_from + rail_geometry(turnout).check_rail.flare_length
    _write(args.out, records, convergence, (wall, cpu, passage_seconds, exact_seconds), flare_end)


def _write(path: Path, records, convergence, seconds, flare_end: float) -> None:
    wall, cpu, passage_seconds, exact_seconds = seconds
    lines = [
        "# The passage's contact law against the exact contact at the paper's peaks",
        "",
        "Written by `python validation/peak_contact.py` (methods, frames and the meaning of "
        "every column in its docstring; the post-processing in "
        "`exudyn_turnout/passage/post_contact.py`).  The full Manchester vehicle "
        "(`manchester`, its front wheelset) and the single wheelset (`wheelset`), the "
        "packaged UIC60 turnout, whole-turnout runs; a difference in per cent is exact / "
        "passage - 1 (for forces of one sign: the change of magnitude).  "
        f"Run time: {wall:.0f} s wall ({cpu:.0f} s CPU of this process; passages "
        f"{passage_seconds:.0f} s, exact contacts {exact_seconds:.0f} s wall, "
        f"OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS', 'unset')}) on a "
        "shared 2-core machine.",
        "",
        "## Normal contact at the peak instants",
        "",
        "| run | peak | x (m) | contact | gamma (deg) | KP weight | N passage (kN) "
        "| delta passage (um) | delta exact at N | N exact at delta (kN) | N exact at state "
        "| dy, dx (mm) | elements, s |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for run, label, x, _force, found in records:
        for c in found:
            lines.append(
                f"| {run} | {label} | {x:.3f} | {_short(c.stem)} | {math.degrees(c.angle):.1f} "
                f"| {c.semi_hertzian:.2f} | {c.normal / 1e3:.1f} | {c.approach * 1e6:.1f} "
                f"| {c.exact_approach * 1e6:.1f} ({_pct(c.exact_approach, c.approach)}) "
                f"| {c.exact_normal_at_approach / 1e3:.1f} "
                f"({_pct(c.exact_normal_at_approach, c.normal)}) "
                f"| {c.exact_normal_at_state / 1e3:.1f} "
                f"({_pct(c.exact_normal_at_state, c.normal)}) "
                f"| {(c.y_rail_exact - c.y_rail) * 1e3:+.2f}, "
                f"{(c.x_contact_exact - c.x_contact) * 1e3:+.2f} "
                f"| {c.elements}, {c.seconds:.1f} |"
            )
    lines += [
        "",
        "## The normal law's error by source",
        "",
        "Each contact's approach at the passage's N: the passage's penetration, the exact "
        "solution on the 2-D lateral gap at the contact's x (`g(t) + A x^2`, the gap a "
        "semi-Hertzian method sees: against the 3-D one, the error of any method on the 2-D "
        "slice) and on the 3-D surfaces; the force at the passage's penetration: the passage's "
        "law, Kik-Piotrowski on that 2-D gap (what the tables would store with KP's weight "
        "1) and the exact 3-D one; the widths of the patches.  Where the KP weight is 0 "
        "and KP is much nearer the exact force than the passage, the tables' Hertz criterion "
        "kept Hertz on a gap that is not Hertzian (it tests whether the ellipse overshoots "
        "the region of interpenetration, not whether the region is much wider than the "
        "ellipse: a conformal gap).",
        "",
        "| run | peak | contact | KP weight | delta passage / exact 2-D / exact 3-D at N (um) "
        "| N passage / KP / exact 3-D at delta (kN) | 2b passage / KP / exact 2-D / exact 3-D "
        "(mm) |",
        "|---|---|---|---|---|---|---|",
    ]
    for run, label, _x, _force, found in records:
        for c in found:
            lines.append(
                f"| {run} | {label} | {_short(c.stem)} | {c.semi_hertzian:.2f} "
                f"| {c.approach * 1e6:.1f} / {c.exact_2d_approach * 1e6:.1f} / "
                f"{c.exact_approach * 1e6:.1f} "
                f"| {c.normal / 1e3:.1f} / {c.kp_normal_at_approach / 1e3:.1f} "
                f"({_pct(c.kp_normal_at_approach, c.exact_normal_at_approach)} of exact) / "
                f"{c.exact_normal_at_approach / 1e3:.1f} "
                f"({_pct(c.normal, c.exact_normal_at_approach)} of exact) "
                f"| {c.width * 1e3:.1f} / {c.kp_width * 1e3:.1f} / {c.exact_2d_width * 1e3:.1f} "
                f"/ {c.exact_width * 1e3:.1f} |"
            )
    lines += [
        "",
        "## Patch and creep forces at the peak instants",
        "",
        "| run | peak | contact | 2a passage / exact (mm) | 2b passage / exact (mm) "
        "| PMAX passage / exact (MPa) | xi, eta, spin (1/m) | FX passage / exact (N) "
        "| FS passage / exact (N) | FX, FS exact on the passage's ellipse (N) |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for run, label, _x, _force, found in records:
        for c in found:
            lines.append(
                f"| {run} | {label} | {_short(c.stem)} "
                f"| {c.length * 1e3:.1f} / {c.exact_length * 1e3:.1f} "
                f"({_pct(c.exact_length, c.length)}) "
                f"| {c.width * 1e3:.1f} / {c.exact_width * 1e3:.1f} "
                f"({_pct(c.exact_width, c.width)}) "
                f"| {c.p_max / 1e6:.0f} / {c.exact_p_max / 1e6:.0f} "
                f"({_pct(c.exact_p_max, c.p_max)}) "
                f"| {c.xi:.2e}, {c.eta:.2e}, {c.spin:.3f} "
                f"| {c.fx:.0f} / {c.exact_fx:.0f} ({_pct(c.exact_fx, c.fx)}) "
                f"| {c.fs:.0f} / {c.exact_fs:.0f} ({_pct(c.exact_fs, c.fs)}) "
                f"| {c.ellipse_fx:.0f} ({_pct(c.ellipse_fx, c.fx)}), "
                f"{c.ellipse_fs:.0f} ({_pct(c.ellipse_fs, c.fs)}) |"
            )
    lines += [
        "",
        "## What it does to the peaks",
        "",
        "Recorded force of the peak; the same rebuilt from the contacts' N, FS and angles "
        "(a check of the frames); its change if the normal law were exact at the "
        "passage's penetrations (normal part) and the creep forces exact at its creepages "
        "and normal forces (creep part), both at frozen positions; the change of the "
        "peak's magnitude at frozen positions, and the normal part's effect on a peak made "
        "by an impact on the contact spring (half the relative change of the contact's "
        "force at equal approach: an impact's peak on a spring alone grows as the square "
        "root of its stiffness, on Hertz's law as its 2/5 power; the wheel's and rail's "
        "compliance in series take more).  For a quasi-static peak the normal law's error "
        "is an approach (first table), not a force: the wheel load is the vehicle's.",
        "",
        "| run | peak | x (m) | recorded (kN) | rebuilt Fz, Fy (kN) | normal part (kN) "
        "| creep part (kN) | peak, frozen | peak, impact on the contact |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for run, label, x, force, found in records:
        w = _wheel_change(_peak_contacts(label, found))
        key = label[:2]
        normal_part, creep_part = w[f"{key}_n"], w[f"{key}_t"]
        lines.append(
            f"| {run} | {label} | {x:.3f} | {force / 1e3:.1f} "
            f"| {w['Fz'] / 1e3:.1f}, {w['Fy'] / 1e3:.1f} | {normal_part / 1e3:+.2f} "
            f"| {creep_part / 1e3:+.2f} | {_magnitude(normal_part + creep_part, force)} "
            f"| {_magnitude(0.5 * normal_part, force)} |"
        )
    lines += [
        "",
        "## Element size",
        "",
        f"Some contacts again with {FINE_ELEMENTS} instead of {ELEMENTS_ACROSS} elements "
        "across the patch (change in per cent):",
        "",
        "| run | peak | contact | approach at N | N at approach | length | width | PMAX "
        "| FX | FS |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for run, label, c, f in convergence:
        pairs = (
            (f.exact_approach, c.exact_approach),
            (f.exact_normal_at_approach, c.exact_normal_at_approach),
            (f.exact_length, c.exact_length),
            (f.exact_width, c.exact_width),
            (f.exact_p_max, c.exact_p_max),
            (f.exact_fx, c.exact_fx),
            (f.exact_fs, c.exact_fs),
        )
        cells = " | ".join(_pct(new, old) for new, old in pairs)
        lines.append(f"| {run} | {label} | {_short(c.stem)} | {cells} |")
    lines += ["", *_reading(records, flare_end), ""]
    path.write_text("\n".join(lines))


def _span(values, fmt: str = "{:+.1f}") -> str:
    """``lo ... hi`` of some numbers (one number alone)."""
    lo, hi = min(values), max(values)
    return fmt.format(lo) if abs(hi - lo) < 1e-12 else f"{fmt.format(lo)} ... {fmt.format(hi)}"


def _classes(records) -> dict[str, list]:
    """Records by peak class (``Fz switch through``...): the check rail's own class."""
    out: dict[str, list] = {}
    for record in records:
        run, label = record[0], record[1]
        key = "Fy check rail" if "check" in label else label
        route = run.split(", ")[1].split()[0]
        out.setdefault(f"{key}, {route}", []).append(record)
    return out


def _slender_check(contacts: list[PostContact]) -> str:
    """FASTSIM against the exact theory in the linear range on the most slender ellipse."""
    c = max(contacts, key=lambda c: c.length / c.width)
    a, b = 0.5 * c.length, 0.5 * c.width
    creep = -1e-5
    fastsim = fastsim_solver(a, b, creep, 0.0, 0.0, c.normal, c.friction, SHEAR_MODULUS, 0.28)
    exact = exact_creep_forces_ellipse(a, b, creep, 0.0, 0.0, c.normal, c.friction, n=30)
    return (
        f"On the most slender of them ({_short(c.stem)} at x = {c.x:.3f} m, a / b = "
        f"{a / b:.0f}) at xi = {creep:g} alone, in the linear range, FASTSIM "
        f"(`wheel_rail/fastsim.py`, not the table) gives FX = {fastsim[0]:.0f} N, the exact "
        f"theory {exact[0]:.0f} N ({100 * (fastsim[0] / exact[0] - 1):+.0f} %): beyond "
        "a / b = 10 Kalker's coefficients (`creep.kalker_coefficients`) follow his "
        "slender-ellipse asymptotes (`creep.slender_asymptotes`, "
        "validation/slender_creep.md); until session 11 they were held at a / b = 10 there "
        "and this FX was about 3 times too small."
    )


def _reading(records, flare_end: float) -> list[str]:
    """The page's short reading, from the numbers above."""
    contacts = [c for *_, found in records for c in found]
    if not contacts:
        return ["No contact carried load at the instants."]
    lines = ["## Reading", ""]
    for name, group in _classes(records).items():
        found = [c for record in group for c in _peak_contacts(record[1], record[4])]
        if not found:
            continue
        changes = []
        for _run, label, _x, force, peak_found in group:
            w = _wheel_change(_peak_contacts(label, peak_found))
            key = label[:2]
            total = w[f"{key}_n"] + w[f"{key}_t"]
            changes.append(100.0 * (abs(force + total) - abs(force)) / abs(force))
        kinds = sorted({_short(c.stem).rsplit(" #", 1)[0] for c in found})
        lines.append(
            f"- **{name}** ({', '.join(kinds)}; {len(group)} run(s), peak "
            f"{_span([abs(r[3]) / 1e3 for r in group], '{:.1f}')} kN): approach at the "
            f"passage's N {_span([100 * (c.exact_approach / c.approach - 1) for c in found])} "
            f"%, force at the passage's approach "
            f"{_span([100 * (c.exact_normal_at_approach / c.normal - 1) for c in found])} %, "
            f"patch width {_span([100 * (c.exact_width / c.width - 1) for c in found], '{:+.0f}')}"
            f" %, FS {_span([100 * (c.exact_fs / c.fs - 1) for c in found], '{:+.0f}')} % (the "
            f"creep law alone on the passage's ellipse "
            f"{_span([100 * (c.ellipse_fs / c.fs - 1) for c in found], '{:+.0f}')} %); the "
            f"peak's magnitude at frozen positions {_span(changes)} %."
        )
    slender = [c for c in contacts if c.length > 10.0 * c.width]
    if slender:
        lines += ["", _slender_check(slender)]
    lines += ["", *_conclusions(records, flare_end)]
    return lines


def _impact(records, name: str) -> str:
    """The impact estimate of a class's peaks (last table's last column), as a span."""
    values = []
    for _run, label, _x, force, found in _classes(records).get(name, []):
        w = _wheel_change(_peak_contacts(label, found))
        values.append(100.0 * (abs(force + 0.5 * w[f"{label[:2]}_n"]) - abs(force)) / abs(force))
    return _span(values) + " %" if values else "-"


def _contacts_of(records, name: str) -> list[PostContact]:
    """The peak-making contacts of a class."""
    return [c for r in _classes(records).get(name, []) for c in _peak_contacts(r[1], r[4])]


def _conclusions(records, flare_end: float) -> list[str]:
    """What the numbers say about the paper's peaks."""
    blade = _contacts_of(records, "Fz switch, through")
    lowered = _span([1e6 * (c.approach - c.exact_approach) for c in blade], "{:.0f}")
    wider = _span([c.exact_width / c.width for c in blade], "{:.1f}")
    nose = _contacts_of(records, "Fy crossing, through")
    ratio = _span([c.exact_fs / c.fs for c in nose], "{:.1f}")
    law_alone = _span([100 * (c.ellipse_fs / c.fs - 1) for c in nose], "{:+.0f}")
    nose_wider = _span([c.exact_width / c.width for c in nose], "{:.1f}")
    slender = _span([c.length / c.width for c in nose], "{:.0f}")
    fall = []
    for _run, label, _x, force, found in _classes(records).get("Fy crossing, through", []):
        w = _wheel_change(_peak_contacts(label, found))
        fall.append(100.0 * (1.0 - abs(force + w["Fy_n"] + w["Fy_t"]) / abs(force)))
    check = _contacts_of(records, "Fy check rail, diverging")
    at = _span([c.x + c.x_contact for c in check], "{:.3f}")
    off = max((abs(c.x + c.x_contact - flare_end) for c in check), default=math.nan)
    ahead = _span([1e3 * (c.x_contact_exact - c.x_contact) for c in check], "{:.0f}")
    law = _span([100 * (c.exact_normal_at_approach / c.normal - 1) for c in check], "{:+.0f}")
    state = _span([100 * (c.exact_normal_at_state / c.normal - 1) for c in check], "{:+.0f}")
    shorter = _span([c.exact_length / c.length for c in check], "{:.2f}")
    return [
        "What it means for the paper's numbers.",
        "",
        "- *Vertical crossing peak* (Fig. 7, claim F4): the nose contact is a Hertz node "
        "and its normal law is within a few per cent of the exact one at equal approach; "
        "as an impact on the contact spring the peak would change by "
        f"{_impact(records, 'Fz crossing, through')} with the exact law, well inside the "
        "2-layer/3-layer/FE differences of the validation report.",
        "- *Vertical switch peaks* are quasi-static (the wheel load plus a few kN): there "
        f"the law's error is the approach ({lowered} um of wheel height on the blade, where "
        f"the exact patch is {wider} times as wide as the passage's ellipse: the blade's "
        "gap is flat over several millimetres up to an edge, which the tables' Hertz/KP "
        "criterion let through as Hertz), not the force.",
        "- *Lateral crossing peak* (Fig. 8): made by the creep force on the nose, and there "
        "the passage's patch is the weak part, not its normal law: the nose's ellipse is "
        f"long and narrow (a / b = {slender}); on that ellipse the exact lateral creep "
        f"force differs from the passage's by {law_alone} % (the creep law), but the exact "
        f"patch is {nose_wider} times as wide, and on it the exact lateral creep force is "
        f"{ratio} times the passage's; at frozen positions and creepages the peak's "
        f"magnitude would change by {_span([-f for f in fall], '{:+.0f}')} % (the "
        "creepages themselves would change with another patch: this is no prediction of "
        "the peak, only the contact's error at it).",
        "- *Check-rail peak* (diverging): the passage's contact lies at x = "
        f"{at} m, within {1e3 * off:.0f} mm of the flare's end at {flare_end:.3f} m (where "
        "the straight 1:67 flare meets the check line: a kink of the face along the track); "
        "the kernel puts it at the minimum along x of the yawed wheel's distance to the "
        "rail's gap (issue 22, `wheel_rail.along_x.lead_along_x`), and on the 3-D surfaces "
        f"the exact force centre lies {ahead} mm ahead of it.  The exact force at the "
        f"passage's approach differs by {law} % and the 3-D surfaces' own "
        f"interpenetration at the recorded positions gives {state} %; the exact patch is "
        f"{shorter} times as long as the passage's ellipse (the flare opens the gap behind "
        "the kink: the node law of the tables' prismatic sections does not know it, "
        "`along_x.patch_along_x` corrects it along x since session 13, before which the "
        "exact force was 36-57 % below the passage's).  The 3-D rail of this page has the rail's "
        "exact section every 1 mm around each contact (`post_contact`'s `section_step`; "
        "a linear blend of the tables' x nodes, 62.5 mm apart on the flare, is no face "
        "there: -79 to -81 % instead of this page's figures until session 13); "
        "validation/check_rail_kink.md compares both at the same instants.",
    ]


if __name__ == "__main__":
    main()
