"""The check rail's support: FE (planar, torsion on pads, torsion on the L-bracket) vs co-running.

Run: ``python validation/check_rail_support.py``; writes ``validation/check_rail_support.md``.
``--toml`` prints the ``[check_rail.co_running]`` block of the turnout file instead (the FE
values the co-running check rail is derived from); ``--turnout FILE --rail ID`` for another
turnout (e.g. ``exudyn_turnout/data/ew54_190_1_9.toml --rail guard_branch``).

The paper (Sec. 2) puts check rails on stiff L-brackets and gives their lateral support as
the check rail type's pad values of Table 1 (k_y = 120 MN/m). The torsion-aware FE
reference lets rails roll on their pads; a check rail whose lateral support acted at its
foot rolled so freely that its head moved 2.2 mm under 31 kN near its end (issue 23). With
the bracket (``[check_rail.support]``, :mod:`exudyn_turnout.fe.check_rail`) the lateral
support acts at the web's bolts and the bracket's leg holds the roll. This script gives the
lateral static stiffness (1 / |H(1 Hz)|, as the paper's Fig. 1) and the receptance at a few
frequencies, at the diverging route's check rail, for:

- FE planar (the paper's own kind of FE: no roll, load at the rail),
- FE with rail torsion, the check rail on its pads only (support at the foot, no leg),
- FE with rail torsion on the L-bracket (the package's default, the FE passages' track),
- the co-running 2- and 3-layer models' slot r3, before (``check_rail="table1"``: Eqs 1-19
  on Table 1, like a running rail) and after (``"bracket"``, the default: derived from the
  bracket FE, :mod:`exudyn_turnout.corunning.check_rail`).

Torsion-aware values are at the gauge corner (14 mm below the top of rail: where the back
of the flange bears on the check rail's face) and at the shear centre.
"""

from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path

import numpy as np

from exudyn_turnout.corunning.check_rail import check_rail_lateral
from exudyn_turnout.corunning.fit import model_receptance
from exudyn_turnout.corunning.parameters import co_running_parameters
from exudyn_turnout.fe.check_rail_receptance import (
    check_rail_lateral_points,
    check_rail_positions,
    co_running_section_toml,
)
from exudyn_turnout.fe.frf import sweep_vectors
from exudyn_turnout.fe.layout import load_layout
from exudyn_turnout.fe.mesh import FEOptions, build_mesh
from exudyn_turnout.fe.model import assemble
from exudyn_turnout.fe.torsion import UIC60_SECTION as S
from exudyn_turnout.inputs.turnout import load_turnout

HERE = Path(__file__).parent
RAIL = "check_diverging"
XS = (44.5, 45.2, 46.0, 47.0, 48.0, 50.0)  # the entry (44.29-45.29 m flare) and along it
FREQ = np.array([1.0, 50.0, 100.0, 300.0, 1000.0])
Z_HEAD = S.height - S.contact_depth - S.shear_centre_height


def fe_stiffness(turnout, x: float, rail: str = RAIL) -> dict[str, np.ndarray]:
    """1 / |H| (N/m) at FREQ: planar; torsion on pads (foot); torsion on the bracket."""
    mesh = build_mesh(turnout, load_layout(turnout), FEOptions(), points={rail: [x]})
    planar = assemble(turnout, mesh, "lateral")
    out = {"FE planar": 1 / np.abs(sweep_vectors(planar, planar.point_vector(rail, x), FREQ)[:, 0])}
    raw = dict(turnout.raw)
    raw["check_rail"] = {**raw.get("check_rail", {}), "support": {"height": 0.0, "k_roll": 0.0}}
    foot = dataclasses.replace(turnout, raw=raw)
    for name, t in (("FE torsion, pads only", foot), ("FE torsion, L-bracket", turnout)):
        model = assemble(t, mesh, "lateral", torsion=S)
        B = np.column_stack([model.head_vector(rail, x, z) for z in (Z_HEAD, 0.0)])
        H = sweep_vectors(model, B, FREQ)
        out[name + ", gauge corner"] = 1 / np.abs(H[:, 0])
        out[name + ", shear centre"] = 1 / np.abs(H[:, 1])
    return out


def co_running(turnout, x: float) -> dict[str, np.ndarray]:
    """1 / |H| (N/m) at FREQ of the co-running models' slot r3, Table 1 and bracket."""
    out = {}
    for model, label in (("table1", "Table 1 (before)"), ("bracket", "bracket (default)")):
        for layers in (2, 3):
            params = co_running_parameters(turnout, x=x, layers=layers, check_rail=model)
            H = model_receptance(params, x, "r3", "lateral", FREQ)
            out[f"co-running {layers}-layer, {label}"] = 1 / np.abs(H)
    return out


def parameter_rows(turnout) -> list[str]:
    """The check rail's co-running lateral entries, Table 1 vs bracket, at XS."""
    lines = [
        "| x (m) | layers | k_rt3_y MN/m | c_rt3_y kN s/m | m_r3 kg | (Table 1: k, c, m) |",
        "|---|---|---|---|---|---|",
    ]
    for x in XS:
        for layers in (2, 3):
            new = co_running_parameters(turnout, x=x, layers=layers).at(x)
            old = co_running_parameters(turnout, x=x, layers=layers, check_rail="table1").at(x)
            lines.append(
                f"| {x:g} | {layers} | {new['k_rt3_y'] / 1e6:.1f} | {new['c_rt3_y'] / 1e3:.1f} | "
                f"{new['m_r3']:.1f} | {old['k_rt3_y'] / 1e6:.1f}, {old['c_rt3_y'] / 1e3:.1f}, "
                f"{old['m_r3']:.1f} |"
            )
    return lines


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--toml", action="store_true", help="print [check_rail.co_running]")
    ap.add_argument("--turnout", help="turnout file (default: the packaged UIC60-760-1:15)")
    ap.add_argument("--rail", default=RAIL, help=f"layout id of the check rail ({RAIL})")
    args = ap.parse_args(argv)
    turnout = load_turnout(args.turnout)
    if args.toml:
        positions = check_rail_positions(turnout, args.rail)
        print(co_running_section_toml(check_rail_lateral_points(turnout, args.rail, positions)))
        return
    lateral = check_rail_lateral(turnout)
    lines = [
        "# The check rail's support: FE vs co-running",
        "",
        "Written by `python validation/check_rail_support.py` (see its docstring). Lateral "
        f"dynamic stiffness 1 / |H(f)| in MN/m of the diverging route's check rail "
        f"(`{RAIL}`, slot r3), f = " + ", ".join(f"{f:g}" for f in FREQ) + " Hz. The "
        "static stiffness is the 1 Hz column, as the paper's Fig. 1. Co-running *Table 1 "
        "(before)*: slot r3 from Eqs 1-19 on Table 1 like a running rail "
        '(`check_rail="table1"`); *bracket (default)*: derived from the bracket FE\'s '
        "static stiffness, lateral resonance and its depth at the gauge corner "
        "(`exudyn_turnout.corunning.check_rail`, values of `[check_rail.co_running]`, "
        f"{len(lateral.x) if lateral else 0} positions of `{lateral.rail if lateral else '-'}`"
        ": its sleepers and free-end overhang).",
        "",
        "## The co-running check rail's lateral entries",
        "",
        *parameter_rows(turnout),
        "",
    ]
    static: dict[str, list[float]] = {}
    for x in XS:
        values = {**fe_stiffness(turnout, x), **co_running(turnout, x)}
        lines += [
            f"## x = {x:g} m",
            "",
            "| model | " + " | ".join(f"{f:g} Hz" for f in FREQ) + " |",
        ]
        lines += ["|---" * (len(FREQ) + 1) + "|"]
        for name, k in values.items():
            lines.append(f"| {name} | " + " | ".join(f"{v / 1e6:.1f}" for v in k) + " |")
            static.setdefault(name, []).append(float(k[0]))
        lines.append("")
    bracket = np.array(static["FE torsion, L-bracket, gauge corner"])
    pads = np.array(static["FE torsion, pads only, gauge corner"])
    before = np.array(static["co-running 3-layer, Table 1 (before)"])
    after = np.array(static["co-running 3-layer, bracket (default)"])
    lines += [
        "## Summary",
        "",
        "Static lateral stiffness at the gauge corner, L-bracket over pads only: "
        + ", ".join(f"{x:g} m {b / p:.2f}" for x, b, p in zip(XS, bracket, pads))
        + ". Co-running 3-layer over FE (L-bracket, gauge corner), before -> after: "
        + ", ".join(
            f"{x:g} m {t / b:.2f} -> {a / b:.2f}" for x, t, a, b in zip(XS, before, after, bracket)
        )
        + ". The bracket-derived check rail matches the FE's static stiffness exactly at "
        "the table's positions (sleepers and overhang) and interpolates linearly between "
        "them, so mid-bay (every x above) it is the neighbouring sleepers' value: "
        "up to 16 % above the FE's mid-bay value (the bay's own bending, which a co-running "
        "model without discrete supports cannot have). The co-running models know no roll: "
        "the bracket-derived check rail takes the torsion-aware FE at the gauge corner; the "
        "FE planar column is the paper's own kind of FE.",
        "",
    ]
    (HERE / "check_rail_support.md").write_text("\n".join(lines))
    print("\n".join(lines))


if __name__ == "__main__":
    main()
