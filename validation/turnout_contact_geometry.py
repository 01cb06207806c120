"""The turnout's rail geometry for profile contact: bodies, tables, load transfer and dips.

Run: ``python validation/turnout_contact_geometry.py [TURNOUT_FILE]`` (default: the
packaged UIC60-760-1:15); ``... --handovers [TURNOUT_FILE ...]`` only prints the hand-over
table of each file (default: both packaged turnouts).  Writes
``turnout_contact_geometry.md`` and its PNG figures next to this script.  Everything comes
from the turnout file's ``[wheel_rail]`` design data and the ``sections`` of its route
contacts (exudyn_turnout.wheel_rail.turnout_sections), with the S1002 wheel and the UIC60
1:40 rail of the Manchester benchmark (CONTACT's data, Apache-2.0).  Tables are built into
a fresh temporary cache (cold build), then loaded again (warm) to time both.
"""

from __future__ import annotations

import math
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from exudyn_turnout.inputs.routes import dip_angle, load_route, route_names
from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.plotting.wheel_rail import (
    plot_body_sections,
    plot_contact_band_along_x,
    plot_dip,
)
from exudyn_turnout.wheel_rail.data import s1002_wheel
from exudyn_turnout.wheel_rail.geometry import WheelsetSetup
from exudyn_turnout.wheel_rail.handovers import (
    DIP_BASELINE,
    handover_windows,
    rest_path,
    route_transfers,
    table_rest_path,
)
from exudyn_turnout.wheel_rail.tables import build_contact_table, lookup
from exudyn_turnout.wheel_rail.turnout_design import blade_lowering, rail_geometry, stock_setback
from exudyn_turnout.wheel_rail.turnout_sections import (
    body_table_settings,
    envelope_sections,
    route_contact_tables,
    route_rail_bodies,
)

HERE = Path(__file__).resolve().parent
OUT = HERE / "turnout_contact_geometry.md"
SHIFTS = (-0.003, 0.0, 0.003)
#: m, candidates within this of the lowest vertical gap count as touching (rigid contact)
TOUCH = 5e-5


def _bodies_section(turnout, lines: list) -> dict:
    lines += [
        "## Rail bodies",
        "",
        "One body per route contact entry; x nodes only where the section changes "
        "(`section_tolerance`, `min_step` of `[wheel_rail]`).",
        "",
        "| route | body | wheel | slot | x from (m) | x to (m) | x nodes | envelope |",
        "|---|---|---|---|---|---|---|---|",
    ]
    out = {}
    for route in route_names(turnout):
        start = time.perf_counter()
        bodies = route_rail_bodies(turnout, route)
        elapsed = time.perf_counter() - start
        out[route] = bodies
        for body in bodies:
            lines.append(
                f"| {route} | {body.name} | {body.wheel} | {body.rail} | {body.x_from:.3f} | "
                f"{body.x_to:.3f} | {len(body.sections.x)} | {'yes' if body.enveloped else 'no'} |"
            )
        lines.append(f"| {route} | *sections built in* | | | | | {elapsed:.2f} s | |")
    fine = dict(turnout.raw)
    fine["wheel_rail"] = {**turnout.raw.get("wheel_rail", {}), "section_tolerance": 1e-4}
    first = route_names(turnout)[0]
    nodes_fine = sum(
        len(b.sections.x) for b in route_rail_bodies(replace(turnout, raw=fine), first)
    )
    nodes = sum(len(b.sections.x) for b in out[first])
    lines += [
        "",
        f"Nodes of route {first}: {nodes} with `section_tolerance` = "
        f"{rail_geometry(turnout).section_tolerance * 1e3:.1f} mm, {nodes_fine} with 0.1 mm.",
        "",
    ]
    return out


def _tables_section(turnout, wheel, setup, lines: list) -> dict:
    lines += [
        "## Contact tables (build and load)",
        "",
        "Cold: built into an empty cache; warm: the same call again (sections rebuilt, "
        "tables loaded from the `.npz` cache). ~139 kB of interpolation coefficients per x "
        "node and 121 shifts.",
        "",
        "| route | body | x nodes | shifts | build (s) | coefficients (MB) |",
        "|---|---|---|---|---|---|",
    ]
    out = {}
    with tempfile.TemporaryDirectory() as cache:
        for route in route_names(turnout):
            start = time.perf_counter()
            tables = route_contact_tables(turnout, route, wheel, setup, cache_dir=cache)
            cold = time.perf_counter() - start
            start = time.perf_counter()
            route_contact_tables(turnout, route, wheel, setup, cache_dir=cache)
            warm = time.perf_counter() - start
            out[route] = tables
            total = 0.0
            for body, table in tables:
                size = table.coefficients.nbytes / 1e6
                total += size
                lines.append(
                    f"| {route} | {body.name} | {len(table.x)} | {len(table.shift)} | "
                    f"{table.build_seconds:.2f} | {size:.1f} |"
                )
            lines.append(
                f"| {route} | **whole route** | | | cold {cold:.1f} s, warm {warm:.1f} s | "
                f"{total:.0f} |"
            )
    lines.append("")
    return out


def _transfer_section(turnout, wheel, setup, bodies: dict, lines: list) -> dict:
    geometry = rail_geometry(turnout)
    tip = geometry.crossing.nose_tip
    lines += [
        "## Load transfer and dips (geometry only)",
        "",
        "Rigid wheel (S1002, r = 0.46 m, enveloped over +-0.1 m) over both bodies, at a "
        "lateral shift of the wheel towards its field side (a wheelset offset of +3 mm to the "
        "left shifts the left wheel +3 mm and the right wheel -3 mm).  Transfer: first x "
        "where the second body (blade, nose) carries the wheel.  Depth: below the chord of "
        "the path's end levels; dip angle: steepest fall + steepest rise (2 alpha).",
        "",
        f"Plan: toe at x = 0, nose tip at x = {tip:.3f} m, crossing 1:"
        f"{geometry.crossing.crossing_number:.2f}.",
        "",
        "| route | place | wheel | shift (mm) | transfer x (m) | after toe / tip (m) | depth (mm) "
        "| at x (m) | fall (mrad) | rise (mrad) | dip angle (mrad) |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    out = {}
    for route in route_names(turnout):
        start = time.perf_counter()
        transfers = route_transfers(
            turnout, route, wheel, setup, shifts=SHIFTS, step=0.005, bodies=bodies[route]
        )
        elapsed = time.perf_counter() - start
        out[route] = transfers
        for transfer in transfers:
            origin = 0.0 if transfer.place == "switch" else tip
            for s in transfer.summaries:
                lines.append(
                    f"| {route} | {transfer.place} | {transfer.wheel} | {s.shift * 1e3:+.0f} | "
                    f"{s.transfer_x:.3f} | {s.transfer_x - origin:+.3f} | {s.depth * 1e3:.2f} | "
                    f"{s.depth_x:.3f} | {s.falling_slope * 1e3:.2f} | "
                    f"{s.rising_slope * 1e3:.2f} | {s.dip_angle * 1e3:.2f} |"
                )
        lines.append(f"| {route} | *computed in* {elapsed:.1f} s | | | | | | | | | |")
    lines += [
        "",
        "The same, from the route's height tables (`[[routes.*.contacts]] x, z`, the "
        "co-running contact's stand-in; `exudyn_turnout.inputs.routes.dip_angle`, lowest "
        "point of the upper envelope of the rail heights):",
        "",
        "| route | wheel | place | lowest at x (m) | depth (mm) | 2 alpha (mrad) |",
        "|---|---|---|---|---|---|",
    ]
    for route in route_names(turnout):
        r = load_route(turnout, route)
        side = next(t.wheel for t in out[route])
        for place, (a, b) in (("switch", (0.0, 8.0)), ("crossing", (tip - 1.0, tip + 1.5))):
            x, depth, two_alpha = dip_angle(r, side, a, b)
            lines.append(
                f"| {route} | {side} | {place} | {x:.3f} | {depth * 1e3:.2f} | "
                f"{two_alpha * 1e3:.2f} |"
            )
    lines.append("")
    return out


def _contact_band(tables, route: str, side: str, x: np.ndarray, shift: float):
    """Touching contacts of one wheel over all its bodies along x (rigid contact, lift 0)."""
    xs, ys, ss, labels = [], [], [], []
    mine = [(body, table) for body, table in tables if body.wheel == side]
    for xi in x:
        found = []
        for body, table in mine:
            if not body.x_from <= xi <= body.x_to:
                continue
            hit = lookup(table, [xi], [shift])
            for k in np.flatnonzero(hit.valid[0]):
                vertical = hit.gap[0, k] / max(math.cos(hit.angle[0, k]), 1e-3)
                found.append((vertical, hit.y_rail[0, k], hit.s_wheel[0, k], body.name))
        if not found:
            continue
        lowest = min(f[0] for f in found)
        for vertical, y, s, name in found:
            if vertical <= lowest + TOUCH:
                xs.append(xi)
                ys.append(y)
                ss.append(s)
                labels.append(name)
    return np.array(xs), np.array(ys), np.array(ss), labels


def _steps(height: np.ndarray) -> np.ndarray:
    """Per x step: how much its change differs from both neighbouring steps' (m)."""
    d = np.diff(height)
    inner = np.minimum(np.abs(d[1:-1] - d[:-2]), np.abs(d[1:-1] - d[2:]))
    return np.concatenate(([0.0], inner, [0.0]))


def _no_twist_tables(turnout, route, tables, wheel, setup, cache) -> tuple:
    """The route's tables with ``inclination_transition = 0`` (only the noses rebuilt)."""
    raw = dict(turnout.raw)
    wheel_rail = dict(raw.get("wheel_rail", {}))
    wheel_rail["crossing"] = {**wheel_rail.get("crossing", {}), "inclination_transition": 0.0}
    raw["wheel_rail"] = wheel_rail
    stepped = replace(turnout, raw=raw)
    geometry = rail_geometry(stepped)
    out = []
    for body, (_, table) in zip(route_rail_bodies(stepped, route), tables):
        if any(seg.kind == "nose" for seg in body.segments):
            table = build_contact_table(
                wheel,
                envelope_sections(body, geometry, setup.nominal_radius),
                setup.taping_line,
                body_table_settings(body, geometry),
                cache,
            )
        out.append((body, table))
    return tuple(out)


def _handover_section(turnout, wheel, setup, bodies: dict, tables: dict, lines: list) -> None:
    geometry = rail_geometry(turnout)
    step = 0.005
    lines += [
        "## Hand-overs: no step in the wheel's rest height",
        "",
        "Rigid rest height of the wheel (the lift at which its nearest candidate touches, over "
        "all its running-rail bodies present at x) every 5 mm over +-0.1 m around each x "
        "where a body or segment of that wheel begins or ends, and over the nose's twist "
        "(`inclination_transition`).  Step: the largest change over one 5 mm step that "
        "differs from the changes over both neighbouring steps (a slope or a kink is not a "
        "step).  Sections: `rest_path` (vertical search on the sections at each x); tables: "
        "`table_rest_path` (as the passage reads them; shifts +-0.1 mm, the middles of the "
        "two shift cells next to zero).  *No twist*: `inclination_transition = 0`, the "
        "upright nose meets the inclined plain rail (tables: only the noses rebuilt).  "
        "Check: `tests/test_turnout_sections.py` (0.02 mm).",
        "",
        "| route | wheel | window (m) | no twist: sections (mm) | no twist: tables (mm) "
        "| sections (mm) | tables (mm) | at x (m) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    raw = dict(turnout.raw)
    raw["wheel_rail"] = {
        **raw.get("wheel_rail", {}),
        "crossing": {
            **raw.get("wheel_rail", {}).get("crossing", {}),
            "inclination_transition": 0.0,
        },
    }
    stepped = replace(turnout, raw=raw)
    with tempfile.TemporaryDirectory() as cache:
        for route in route_names(turnout):
            plain = _no_twist_tables(turnout, route, tables[route], wheel, setup, cache)
            stepped_bodies = tuple(b for b, _ in plain)
            for side in ("left", "right"):
                for lo, hi in handover_windows(bodies[route], side, geometry):
                    x = np.round(np.arange(lo, hi + 0.5 * step, step), 9)
                    row = []
                    for these, pairs, geo in (
                        (stepped_bodies, plain, rail_geometry(stepped)),
                        (bodies[route], tables[route], geometry),
                    ):
                        exact = rest_path(these, geo, wheel, setup, side, x).height
                        by_table = [
                            _steps(table_rest_path(pairs, side, x, shift).height)
                            for shift in (-1e-4, 1e-4)
                        ]
                        worst = np.maximum(*by_table)
                        row += [float(np.max(_steps(exact))), float(np.max(worst))]
                        at = float(x[int(np.argmax(worst))])
                    lines.append(
                        f"| {route} | {side} | {lo:.3f}..{hi:.3f} | {1e3 * row[0]:.3f} | "
                        f"{1e3 * row[1]:.3f} | {1e3 * row[2]:.3f} | {1e3 * row[3]:.3f} | "
                        f"{at:.3f} |"
                    )
    lines.append("")


def _setback(geometry, x: float) -> float:
    return stock_setback(x, geometry.switch, geometry.stock_set_length)


def _lowering(geometry, x: float) -> float:
    return blade_lowering(x, geometry.switch)


def print_handovers(files: list[str]) -> None:
    """Print the hand-over table of each turnout file (default: both packaged ones).

    Tables come from the user's cache (built there if missing, as a passage would); nothing
    is written next to this script.
    """
    setup = WheelsetSetup()
    wheel = s1002_wheel(setup)
    data = Path(__file__).resolve().parents[1] / "exudyn_turnout" / "data"
    for name in files or ["uic60_760_1_15.toml", "ew54_190_1_9.toml"]:
        path = Path(name) if Path(name).exists() else data / name
        turnout = load_turnout(path)
        bodies = {route: route_rail_bodies(turnout, route) for route in route_names(turnout)}
        tables = {
            route: route_contact_tables(turnout, route, wheel, setup)
            for route in route_names(turnout)
        }
        lines = [f"# {turnout.name} ({path.name})", ""]
        _handover_section(turnout, wheel, setup, bodies, tables, lines)
        print("\n".join(lines))


def main(argv: list[str]) -> None:
    if argv[:1] == ["--handovers"]:
        print_handovers(argv[1:])
        return
    turnout = load_turnout(argv[0] if argv else None)
    setup = WheelsetSetup()
    wheel = s1002_wheel(setup)
    geometry = rail_geometry(turnout)
    tip = geometry.crossing.nose_tip
    lines = [
        f"# Rail geometry for profile contact: {turnout.name}",
        "",
        "Written by `python validation/turnout_contact_geometry.py` (numbers measured in one "
        "run on the shared 2-core machine; timings are noisy).  Sections from `[wheel_rail]` "
        "and the `sections` of every route contact (README, 'Rail geometry for contact').",
        "",
    ]
    bodies = _bodies_section(turnout, lines)
    tables = _tables_section(turnout, wheel, setup, lines)
    transfers = _transfer_section(turnout, wheel, setup, bodies, lines)
    _handover_section(turnout, wheel, setup, bodies, tables, lines)

    first = route_names(turnout)[0]
    crossing = next(t for t in transfers[first] if t.place == "crossing")
    switch = next(t for t in transfers[first] if t.place == "switch")
    c0, s0 = crossing.summaries[1], switch.summaries[1]
    lines += [
        "## Reading",
        "",
        f"- Switch: the blade takes the centred wheel {s0.transfer_x:.2f} m after the toe, "
        f"where the stock rail has moved {1e3 * _setback(geometry, s0.transfer_x):.0f} mm "
        "to the field side and the blade is still "
        f"{1e3 * _lowering(geometry, s0.transfer_x):.2f} mm low; dip {1e3 * s0.depth:.2f} mm "
        f"/ {1e3 * s0.dip_angle:.2f} mrad, close to what the height tables assumed.",
        f"- Crossing: the nose takes the centred wheel {c0.transfer_x - tip:.3f} m after its "
        f"tip; the wheel falls {1e3 * c0.depth:.2f} mm while its contact runs out on the "
        "wing rail, which flares away at 1:N from the throat (the S1002 tread falls off "
        f"beyond ~30 mm from the taping line), dip angle {1e3 * c0.dip_angle:.1f} mrad.  The "
        "height tables' 1.4 mm / 9 mrad at 0.27 m after the tip is shallower and later: "
        "their wing rail falls 3 mm over 1 m and their nose is full height 0.5 m after "
        "its tip, the design's wing rail follows the flare and its nose is lowered over "
        "the same 0.5 m but narrow (and so lower) near its tip.  No wing-rail rise is in "
        "the design data; real crossings often raise the wing rail to shorten this fall.",
        "- Shifting the wheel towards its field side moves the nose transfer earlier (the "
        "tread reaches the widening nose sooner); at the switch the transfer moves by less "
        "than 0.1 m.",
        f"- Dip angles are chords over {1e3 * DIP_BASELINE:.0f} mm (`DIP_BASELINE`); the "
        "path is piecewise linear between the x nodes, and between 0.1 and 0.2 mm "
        "`section_tolerance` the nose's rising slope moved by ~10 %.",
        "- Hand-overs: the upright nose met the inclined plain rail with a 0.36 mm step in "
        "the wheel's rest height (contact 740 -> 753 mm, angle 0.074 -> 0.024 rad); the "
        "nose's twist over `inclination_transition` makes the height continuous (0.36 mm "
        "over 2 m), its contact point still jumps 10 mm in one place of the twist (two-point "
        "contact of S1002 on a rail between upright and 1:40), where the tables hold a "
        "cell: 0.017 mm.  Away from the hand-overs, held cells still step where the "
        "contact point jumps (not in this table): 0.03 mm at the start of the stock rail's "
        "set and of the wing rail's flare, 0.07-0.08 mm on the rising blade's 0.125 m "
        "nodes just after the stock rail -> blade transfer.",
        "- The diverging route's bodies are the through route's in its own frame (module "
        "docstring of `turnout_sections`), so its numbers equal the through route's and "
        "its tables come from the same cache entries.",
        "",
    ]
    lines += ["## Figures", ""]
    for transfer in transfers[first]:
        name = f"turnout_contact_dip_{transfer.place}.png"
        plot_dip(
            list(transfer.paths),
            list(transfer.summaries),
            HERE / name,
            f"{first}, {transfer.wheel} wheel: {transfer.first} -> {transfer.second}",
        )
        lines += [f"![dip at the {transfer.place}]({name})", ""]
    side = transfers[first][0].wheel
    x = np.concatenate((np.arange(-1.0, 8.0, 0.01), np.arange(tip - 1.0, tip + 1.5, 0.005)))
    for shift in (0.0,):
        xs, ys, ss, labels = _contact_band(tables[first], first, side, x, shift)
        name = "turnout_contact_band.png"
        plot_contact_band_along_x(
            xs,
            ys,
            ss,
            labels,
            HERE / name,
            f"{first} route, {side} wheel, shift {shift * 1e3:+.0f} mm (from the tables)",
            x_ranges=[(-1.0, 8.0), (tip - 1.0, tip + 1.5)],
        )
        lines += [f"![contact band]({name})", ""]
    by_name = {body.name: body for body in bodies[first] if body.wheel == side}
    for label, transfer, positions in (
        ("switch", switch, [1.0, switch.summaries[1].transfer_x, 6.0]),
        ("crossing", crossing, [tip - 0.3, tip + 0.05, crossing.summaries[1].transfer_x]),
    ):
        pair = [by_name[transfer.first], by_name[transfer.second]]
        grids = [envelope_sections(b, geometry, setup.nominal_radius) for b in pair]
        centred = transfer.paths[1]
        lifts = [float(np.interp(p, centred.x, centred.height)) for p in positions]
        name = f"turnout_contact_sections_{label}.png"
        plot_body_sections(
            grids,
            [b.name for b in pair],
            positions,
            wheel,
            setup.taping_line,
            HERE / name,
            lifts=lifts,
        )
        lines += [f"![sections at the {label}]({name})", ""]
    OUT.write_text("\n".join(lines) + "\n", encoding="utf-8")
    print("\n".join(lines))


if __name__ == "__main__":
    main(sys.argv[1:])
