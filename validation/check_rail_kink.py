"""The check rail's flare end (a kink of its face in plan): the gap along the track there.

Writes check_rail_kink.md.  Run: ``python validation/check_rail_kink.py`` (~2 min).

At the instants of the check rail's peak (the diverging route at 80 km/h, the runs of
validation/peak_contact.py) the wheel's normal gap to the check rail is taken along the
track, row by row at X ahead of the wheel's axle (the minimum over the profile of each
row, along the passage's contact normal; ``passage.post_contact``'s 3-D gap of the yawed
body of revolution, without the contact plane's pitch), on two rail surfaces:

* **3-D, exact sections**: the check rail's section computed exactly every 1 mm
  (``wheel_rail.turnout_sections``' own section of the body at x) near the wheel;
* **3-D, the body's sections**: its sections at the tables' x nodes, heights blended
  linearly between them (what ``passage.post_contact`` uses; on the 1:67 flare the face
  moves 0.93 mm between nodes 62.5 mm apart and the blend is no face at all).

Beside them the models of the contact's gap along x (the rail's gap ``g(x + X)`` from the
route's contact table at the state's shift and lift, piecewise linear between its nodes):

* **first order**: the passage's kernel before issue 22, the gap at the yaw's lead x_yaw to
  first order along x, ``g(x) + x_yaw g'(x) - closing`` (``wheel_rail.lead``);
* **parabola**: the minimum over X of ``g(x + X) + (X - x_yaw)^2 / (2 R_x) - closing``,
  ``R_x = r / cos(gamma)``: the yawed wheel's gap along x to second order (issue 22's
  proposal; equal to a 3-D search for a cone against a rail corner, the wheel's generator
  straight: tests in the branch h-kink);
* **parabola + profile**: plus ``(h sin(gamma))^2 / (2 (rho_w + rho_r))``, ``h = X^2 /
  (2 r)``: the point X ahead lies h higher, which moves the wheel's profile along the
  contact's tangent by ``h sin(gamma)`` and, with the profiles' lateral radii of curvature
  rho_w, rho_r at the contact (the table's), opens the gap by that much (two circles
  translated along their common tangent); the kernel's since issue 22.

Last, the exact contact of ``passage.post_contact`` (validation/peak_contact.py's columns)
at the same instants on both rail surfaces: the normal law's error and the 3-D surfaces'.
Since the patch's law along x (``wheel_rail.along_x.patch_along_x``) the passage's N is the
node law times the truncated patch's ratio; the column "node law at delta" is the node's
law alone at the same delta (the kernel before it), beside "N at delta", the exact force.
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np

import exudyn_turnout.passage.post_contact as post
import exudyn_turnout.wheel_rail.turnout_sections as sections_module
from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.inputs.vehicle import load_vehicle
from exudyn_turnout.passage import simulate_passage
from exudyn_turnout.passage.contact.profile import wheel_and_setup
from exudyn_turnout.passage.settings import PassageSettings
from exudyn_turnout.wheel_rail.geometry import prepare_wheel
from exudyn_turnout.wheel_rail.lead import contact_lead
from exudyn_turnout.wheel_rail.node_laws import DELTA_REF
from exudyn_turnout.wheel_rail.sections import SectionGrid
from exudyn_turnout.wheel_rail.tables import lookup_values

HERE = Path(__file__).resolve().parent
RUNS = (("manchester", 2), ("manchester", 3), ("wheelset", 2), ("wheelset", 3))
ROWS = np.arange(-0.03, 0.1105, 0.001)  #: m, X ahead of the axle
TANGENT = np.arange(-0.01, 0.01, 5e-5)  #: m, across the profile, about the contact point
FLARE_END = 45.29  #: m, the packaged check rail's flare meets its check line


def _exact_sections(turnout, body, x_ws: float) -> SectionGrid:
    """The body's sections plus its exact section every 1 mm around the wheel."""
    return sections_module.exact_sections_between(turnout, body, x_ws - 0.04, x_ws + 0.12)


def _post_contact(turnout, result, stem, index, body, surfaces):
    """``post.post_contact`` on the rail's exact sections every 1 mm (``surfaces`` given:
    its default) or on the body's own sections blended between its nodes (None)."""
    if surfaces is None:
        return post.post_contact(turnout, result, stem, index, section_step=None)
    return post.post_contact(turnout, result, stem, index)


def _node_law(table, fields, state) -> float:
    """N (N) of the node's law alone at the passage's penetration (the kernel before
    ``patch_along_x``): ``N_ref (delta / DELTA_REF)^n`` looked up at the contact's x and
    shift in the slot of its angle (``tables.lookup_values``)."""
    found = lookup_values(table, [state.x], [state.shift], [state.lift])[0]
    slot = int(np.argmin(np.abs(found[:, fields["angle"]] - state.angle)))
    reference, exponent = (
        found[slot, fields["patch_force"]],
        found[slot, fields["patch_force_exponent"]],
    )
    return float(reference * (state.approach / DELTA_REF) ** exponent)


def _minimum(values: np.ndarray) -> tuple[float, float]:
    """(gap um, X mm) of the smallest value over ROWS."""
    i = int(np.argmin(values))
    return 1e6 * float(values[i]), 1e3 * float(ROWS[i])


def main() -> None:
    """Run the passages, take the gap along x at their check-rail peaks, write the page."""
    started = time.perf_counter()
    turnout = load_turnout()
    vehicle = load_vehicle()
    wheel, setup = wheel_and_setup(turnout, vehicle)
    prepared = prepare_wheel(wheel, setup.taping_line, 0.0, ())
    y_p, z_p = post.smooth_wheel(prepared.y, prepared.z)
    points = (y_p, z_p, vehicle.r0 - z_p)
    body = next(
        b for b in sections_module.route_rail_bodies(turnout, "diverging") if b.back_of_flange
    )
    pairs = sections_module.route_contact_tables(turnout, "diverging", wheel, setup)
    table = next(t for b, t in pairs if b.back_of_flange)
    fields = {name: k for k, name in enumerate(table.fields)}
    lines = []
    profiles = []
    exact_rows = []
    for name, layers in RUNS:
        result = simulate_passage(
            turnout, PassageSettings(route="diverging", speed_kmh=80.0, layers=layers), name
        )
        columns = result.columns
        index = int(np.nanargmax(np.abs(columns["Fy_right_r3_N"])))
        stem = next(s for s in post.contact_stems(result, "right") if "_r3_" in s)
        state = post.rebuild_contact(turnout, result, stem, index, vehicle)
        instant = post._Instant(
            side=state.side, shift=state.shift, lift=state.lift, yaw=state.yaw,
            angle=state.angle, y_c=state.y_rail, z_c=state.z_rail, x_c=state.x_contact,
            r0=vehicle.r0, taping_line=setup.taping_line,
        )  # fmt: skip
        exact = _exact_sections(turnout, body, state.x)
        gap_exact = post._gap(instant, exact, points, state.x, ROWS, TANGENT).min(axis=1)
        gap_body = post._gap(instant, body.sections, points, state.x, ROWS, TANGENT).min(axis=1)
        n = ROWS.size
        found = lookup_values(
            table, state.x + ROWS, np.full(n, state.shift), np.full(n, state.lift)
        )
        slot = int(np.argmin(np.abs(found[ROWS.size // 2, :, fields["angle"]] - state.angle)))
        rail = found[:, slot, fields["gap"]]
        here = found[np.argmin(np.abs(ROWS)), slot]
        radius, gamma = here[fields["radius"]], state.angle
        x_yaw, closing = (float(v) for v in contact_lead(radius, gamma, state.side, state.yaw))
        radius_x = radius / math.cos(gamma)
        slope = float(np.interp(1e-3, ROWS, rail) - np.interp(0.0, ROWS, rail)) / 1e-3
        kernel_gap = float(np.interp(0.0, ROWS, rail)) + x_yaw * slope - closing
        parabola = rail + (ROWS - x_yaw) ** 2 / (2.0 * radius_x) - closing
        k_w, k_r = here[fields["curvature_wheel"]], here[fields["curvature_rail"]]
        radii = (1.0 / k_w if k_w != 0.0 else math.inf) + (1.0 / k_r if k_r != 0.0 else math.inf)
        rise = ROWS**2 / (2.0 * radius)
        profile = parabola + (rise * math.sin(gamma)) ** 2 / (2.0 * radii)
        run = f"{name}, {layers}-layer"
        cells = [
            _minimum(gap_exact), _minimum(gap_body), (1e6 * kernel_gap, 1e3 * x_yaw),
            _minimum(parabola), _minimum(profile),
        ]  # fmt: skip
        lines.append(
            f"| {run} | {state.x:.3f} | {1e3 * state.yaw:+.2f} | {math.degrees(gamma):.1f} | "
            f"{1e3 * radii:.0f} | {-1e6 * state.approach:.1f} | "
            + " | ".join(f"{g:+.1f} at {xm:+.1f}" for g, xm in cells)
            + " |"
        )
        profiles.append((run, state.x, gap_exact, gap_body, rail - closing, parabola, profile))
        print(lines[-1], flush=True)
        for label, surfaces in (("exact sections", exact), ("the body's sections", None)):
            contact = _post_contact(turnout, result, stem, index, body, surfaces)
            node_law = _node_law(table, fields, state)
            exact_rows.append(
                f"| {run} | {label} | {contact.normal / 1e3:.1f} | {node_law / 1e3:.1f} "
                f"| {1e6 * contact.approach:.1f} "
                f"| {1e6 * contact.exact_approach:.1f} "
                f"| {contact.exact_normal_at_approach / 1e3:.1f} "
                f"| {1e6 * contact.interpenetration:.1f} "
                f"| {contact.exact_normal_at_state / 1e3:.1f} "
                f"| {1e3 * contact.x_contact:.1f} / {1e3 * contact.x_contact_exact:.1f} "
                f"| {1e3 * contact.length:.1f} / {1e3 * contact.exact_length:.1f} |"
            )
            print(exact_rows[-1], flush=True)
    out = [
        "# The check rail's flare end: the contact's gap along the track",
        "",
        "Written by `python validation/check_rail_kink.py` (methods in its docstring); run "
        f"time {time.perf_counter() - started:.0f} s.  The packaged turnout's check rail "
        f"flares 1:67 to x = {FLARE_END} m, where its face meets the check line (a convex "
        "kink of the face in plan); at the check rail's peak the wheel's flange back "
        "touches it there.",
        "",
        "## The smallest gap along the track and where it lies (um at mm ahead of the axle)",
        "",
        "Negative: interpenetration.  The passage's own gap is its penetration with the sign "
        "turned (the column before; the kernel's is `parabola + profile`); "
        "rho_w + rho_r the profiles' lateral radii of curvature at the contact (the "
        "table's).",
        "",
        "| run | x (m) | yaw (mrad) | gamma (deg) | rho_w + rho_r (mm) | passage -delta (um) "
        "| 3-D, exact sections | 3-D, the body's sections | first order | parabola "
        "| parabola + profile |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
        *lines,
        "",
        "## The exact contact at these instants",
        "",
        "`passage.post_contact` on each rail surface (its method: the passage's normal force "
        "N and penetration delta; the exact approach at N, the exact force at delta, the 3-D "
        "surfaces' interpenetration and the exact force there; the contact's and the exact "
        "force centre's x ahead of the axle; the passage's ellipse length 2a and the exact "
        "patch's).",
        "",
        "| run | rail surface | N (kN) | node law at delta (kN) | delta (um) "
        "| approach at N (um) | N at delta (kN) "
        "| interpenetration (um) | N at state (kN) | x passage / exact (mm) "
        "| length passage / exact (mm) |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
        *exact_rows,
        "",
        "## The gap along the track at the first run's instant (um)",
        "",
        "| X (mm) | 3-D, exact sections | 3-D, the body's sections | table g(x + X) - closing "
        "| parabola | parabola + profile |",
        "|---|---|---|---|---|---|",
    ]
    run, x_ws, *series = profiles[0]
    for k in range(0, ROWS.size, 5):
        out.append(
            f"| {1e3 * ROWS[k]:+.0f} | " + " | ".join(f"{1e6 * s[k]:+.1f}" for s in series) + " |"
        )
    (HERE / "check_rail_kink.md").write_text("\n".join(out) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
