"""The check-rail contact patch of the diverging route's check-rail event: prints a table.

Run: ``python validation/check_rail_patch.py [--layers 2] [--vehicle manchester]
[--x-start 43.3] [--x-end 47]``.

A single-wheelset (or, with ``--vehicle manchester``, the full vehicle's) passage
(packaged turnout, diverging route at 80 km/h) runs through the check rail's entry.  At the
sample where the check-rail contact carries its largest normal force N, the wheel's contact
point (position on the rail and the wheel, contact angle) is searched again on the check
rail's section at that x, and the patch that carries N there is printed by both
normal-contact methods:

- Hertz (:func:`.hertz.hertz_contact`) with the point's curvature sums (floored as in the
  tables): semi-axes a (rolling), b (lateral), peak pressure p0;
- Kik-Piotrowski (:func:`.nonhertz.kik_piotrowski`) on the point's undeformed normal gap:
  half-length, width along the tangent, peak pressure;
- the wheel's lateral curvature at the point (what the Hertz patch's narrow width comes
  from at the back of the flange);
- the lead of the contact (``x_lead``, from the passage's ``cp_*_x_m`` column) and what the
  check rail's table gives at x + x_lead instead of the wheelset's x (the kernel takes the
  table at x): the normal gap's change there, over the whole check-rail region the largest
  such change along the run (issue 22's open item).

Nothing is written; the numbers are compared before and after a change of the wheel's
flange-back geometry (:func:`.geometry.prepare_wheel`).
"""

from __future__ import annotations

import argparse
import math

import numpy as np


def _solve(force: float, evaluate) -> float:
    """Penetration at which the increasing ``evaluate(delta)`` equals ``force`` (bisection)."""
    low, high = 1e-8, 2e-3
    for _ in range(60):
        mid = math.sqrt(low * high)
        if evaluate(mid) < force:
            low = mid
        else:
            high = mid
    return math.sqrt(low * high)


def main(argv: list[str] | None = None) -> int:
    """Run the passage, find the check-rail peak and print its patch (see the docstring)."""
    import exudyn_turnout as et
    from exudyn_turnout.inputs.vehicle import load_vehicle
    from exudyn_turnout.passage.contact.profile import wheel_and_setup
    from exudyn_turnout.passage.events import check_rail_event
    from exudyn_turnout.wheel_rail.geometry import (
        CHECK_RAIL_DIRECTION,
        prepare_rail,
        prepare_wheel,
        search_candidates,
        surface_derivatives,
    )
    from exudyn_turnout.wheel_rail.hertz import curvature_sums, effective_modulus, hertz_contact
    from exudyn_turnout.wheel_rail.nonhertz import kik_piotrowski, normal_gap_function
    from exudyn_turnout.wheel_rail.tables import lookup
    from exudyn_turnout.wheel_rail.turnout_design import rail_geometry
    from exudyn_turnout.wheel_rail.turnout_sections import (
        envelope_sections,
        route_contact_tables,
        route_rail_bodies,
    )

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--layers", type=int, default=2)
    parser.add_argument("--speed", type=float, default=80.0, help="km/h")
    parser.add_argument("--x-start", type=float, default=None, help="m (default: entry - 1)")
    parser.add_argument("--x-end", type=float, default=None, help="m (default: entry + 2.7)")
    parser.add_argument("--vehicle", default=None, help="vehicle (default: the wheelset)")
    args = parser.parse_args(argv)

    turnout = et.load_turnout()
    event = check_rail_event(turnout, "diverging")
    assert event is not None
    x0 = float(event["region_m"][0])  # type: ignore[index]
    wheel_name, slot = str(event["wheel"]), str(event["rail"])
    settings = et.PassageSettings(
        route="diverging",
        speed_kmh=args.speed,
        layers=args.layers,
        x_start=args.x_start if args.x_start is not None else x0 - 1.0,
        x_end=args.x_end if args.x_end is not None else x0 + 2.7,
    )
    result = et.simulate_passage(
        turnout, settings, vehicle=args.vehicle, track=f"{args.layers}-layer"
    )
    columns = result.columns
    prefix = next(
        k[: -len("_N_N")]
        for k in columns
        if k.startswith(f"cp_{wheel_name}_{slot}_") and k.endswith("_0_N_N")
    )
    normal = np.asarray(columns[f"{prefix}_N_N"])
    i = int(np.nanargmax(normal))
    x = float(columns["x_m"][i])
    y_rail = float(columns[f"{prefix}_y_rail_m"][i])
    s_wheel = float(columns[f"{prefix}_s_wheel_m"][i])
    angle = float(columns[f"{prefix}_angle_rad"][i])
    force = float(normal[i])
    lead = np.asarray(columns[f"{prefix}_x_m"])

    wheel, setup = wheel_and_setup(turnout, load_vehicle())
    geometry = rail_geometry(turnout)
    body = next(b for b in route_rail_bodies(turnout, "diverging") if b.back_of_flange)
    section = envelope_sections(body, geometry, setup.nominal_radius, x=np.array([x]))
    derivatives = surface_derivatives(section)
    directions = (CHECK_RAIL_DIRECTION,)
    rail = prepare_rail(
        section.z[0], derivatives.slope[0], derivatives.curvature[0], section.y, directions
    )
    prepared = prepare_wheel(wheel, setup.taping_line, 0.0, directions)
    shift = y_rail - setup.taping_line - s_wheel
    found = search_candidates(rail, prepared, shift=shift, max_gap=1.0)
    k = int(np.argmin(np.abs(found.y_rail - y_rail) + np.abs(found.angle - angle)))
    modulus = effective_modulus()
    a_sum, b_sum = curvature_sums(
        found.radius, found.angle, found.curvature_wheel, found.curvature_rail
    )
    hertz = hertz_contact(a_sum[k], b_sum[k], force, modulus)
    gap = normal_gap_function(
        rail, prepared, [shift], found.y_rail[k : k + 1], found.z_rail[k : k + 1],
        found.angle[k : k + 1],
    )  # fmt: skip

    def kp(delta: float):
        return kik_piotrowski(gap, 1e-4, a_sum[k], delta, modulus)

    patch = kp(_solve(force, lambda d: float(kp(d).normal_force[0])))
    print(
        f"diverging {args.speed:g} km/h, {args.layers}-layer, {args.vehicle or 'wheelset'}; "
        f"check-rail peak ({prefix})"
    )
    print(f"x = {x:.3f} m, N = {force / 1e3:.1f} kN, angle {math.degrees(angle):.1f} deg,")
    print(f"  on the rail y = {y_rail * 1e3:.2f} mm, on the wheel s = {s_wheel * 1e3:.2f} mm")
    print(
        f"  re-searched: s = {found.s_wheel[k] * 1e3:.2f} mm, angle "
        f"{math.degrees(found.angle[k]):.1f} deg, wheel curvature "
        f"{found.curvature_wheel[k]:.1f} 1/m, rail curvature {found.curvature_rail[k]:.1f} 1/m"
    )
    print("| method | a (mm) | b (mm) | p0 (GPa) |")
    print("|---|---|---|---|")
    print(f"| Hertz | {hertz.a * 1e3:.2f} | {hertz.b * 1e3:.2f} | {hertz.p0 / 1e9:.2f} |")
    print(
        f"| Kik-Piotrowski | {patch.half_length[0] * 1e3:.2f} | "
        f"{0.5 * (patch.t_high[0] - patch.t_low[0]) * 1e3:.2f} | {patch.p_max[0] / 1e9:.2f} |"
    )
    # the lead: the table at x + x_lead against the table at x, along the run where the
    # check-rail contact carries load (the table's x_offset is 0 on a check rail)
    table = next(tab for b, tab in route_contact_tables(turnout, "diverging", wheel, setup)
                 if b.back_of_flange)  # fmt: skip
    loaded = np.flatnonzero(normal > 0.0)
    xs = np.asarray(columns["x_m"])[loaded]
    shifts = np.asarray(columns[f"{prefix}_y_rail_m"])[loaded] - setup.taping_line
    shifts -= np.asarray(columns[f"{prefix}_s_wheel_m"])[loaded]
    at_x = lookup(table, xs, shifts)
    ahead = lookup(table, xs + lead[loaded], shifts)
    slot = np.argmin(np.abs(at_x.angle - angle), axis=1)
    rows = np.arange(len(xs))
    change = ahead.gap[rows, slot] - at_x.gap[rows, slot]
    j = int(np.argmax(np.abs(change)))
    print(
        f"lead at the peak: x_lead = {lead[i] * 1e3:.1f} mm; along the loaded run "
        f"({len(xs)} samples, x {xs.min():.2f}-{xs.max():.2f} m) the table's normal gap at "
        f"x + x_lead differs from that at x by up to {change[j] * 1e3:+.3f} mm "
        f"(x = {xs[j]:.3f} m, x_lead = {lead[loaded][j] * 1e3:.1f} mm); at the peak "
        f"{change[int(np.argmin(np.abs(xs - x)))] * 1e3:+.3f} mm"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
