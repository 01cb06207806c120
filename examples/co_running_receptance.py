"""Receptance of the switch rail and the crossing rail: the FE reference against the two- and
three-layer co-running models.

The layout of the paper's Figs 5 (vertical) and 6 (lateral): panel (a) the switch rail,
panel (b) the crossing rail, each with the FE reference's receptance at the same position,
rail and direction (our FE model of the turnout, ``exudyn_turnout.fe``; the paper's is an
Ansys model; lateral: the planar FE, force and response at the rail, the paper's kind and the
validation report's reference for these claims) and the two co-running models derived
from it. The FE curves take most of the
run (about 0.15 s per frequency and curve; ``--fe-points``, ``--no-fe``). The paper shows
them "where the load is transferring at the switch and crossing" (Section 3.3), so the
defaults are the load transfer positions of the packaged through route: x = 4 m on the
switch blade (the wheel passes from the stock rail to the blade near 3.9 m) and, on the
crossing nose, where the wheel meets the nose (0.27 m after the nose tip that the
turnout's plan puts at 46.9 m: x = 47.2 m). Both are rail slot r2.

Run::

    python examples/co_running_receptance.py --out results/receptance [--source published]

Writes ``fig5_vertical_receptance.png``, ``fig6_lateral_receptance.png`` and one CSV per
curve to the output directory, prints the eigenfrequencies of both models there and, per
panel, each model's static stiffness against the FE's.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from exudyn_turnout.corunning.modal import co_running_modes, co_running_receptance
from exudyn_turnout.fe.frf import fe_receptance
from exudyn_turnout.inputs.geometry import turnout_plan
from exudyn_turnout.inputs.turnout import Turnout, load_turnout
from exudyn_turnout.receptance import log_frequencies

FIGURES = {"vertical": "fig5_vertical_receptance.png", "lateral": "fig6_lateral_receptance.png"}
#: Log-spaced frequencies of each FE curve, 1-2000 Hz (the co-running curves have 600).
FE_POINTS = 200


def eigenfrequency_table(
    turnout: Turnout, cases: dict[str, float], source: str, count: int = 6
) -> str:
    """Text table: the first undamped eigenfrequencies and the oscillating damped modes."""
    lines = [
        f"{'case':<28}{'model':<9}"
        "first undamped eigenfrequencies (Hz) | oscillating modes, damped (Hz)"
    ]
    for name, x in cases.items():
        for layers in (2, 3):
            modes = co_running_modes(turnout, layers, x=x, source=source)
            f_d, _ = modes.damped()
            undamped = " ".join(f"{f:6.1f}" for f in modes.frequency_hz[:count])
            damped = " ".join(f"{f:6.1f}" for f in f_d[:count])
            lines.append(f"{name + f' (x = {x:.1f} m)':<28}{layers}-layer  {undamped} | {damped}")
    return "\n".join(lines)


def plot_direction(
    turnout: Turnout,
    cases: dict[str, float],
    direction: str,
    source: str,
    frequencies: np.ndarray,
    out_dir: Path,
    fe_frequencies: np.ndarray | None = None,
) -> Path:
    """One figure, a panel per case, both models (and the FE) in each; CSVs beside it."""
    import matplotlib.pyplot as plt

    from exudyn_turnout.plotting.curves import plot_receptance

    fig, axes = plt.subplots(1, len(cases), figsize=(5.2 * len(cases), 4.2), squeeze=False)
    for ax, (letter, (name, x)) in zip(axes[0], zip("abcdef", cases.items())):
        curves = [
            co_running_receptance(
                turnout, layers, "r2", direction, x=x, source=source, frequencies=frequencies
            )
            for layers in (2, 3)
        ]
        labels = [curve.model for curve in curves]
        stem = f"{name.replace(' ', '_')}_{direction}"
        if fe_frequencies is not None:
            # lateral: the planar FE (force and response at the rail), the paper's kind and
            # the reference of the report's receptance claims; the torsion-aware FE (the
            # rail rolls on its pads, gauge corner) is ours: `exudyn-turnout fe frf`
            fe = fe_receptance(turnout, "r2", direction, x, fe_frequencies, torsion=False)
            fe.to_csv(out_dir / f"{stem}_FE.csv")
            ratios = ", ".join(
                f"{c.model} {c.static_stiffness / fe.static_stiffness:.2f}" for c in curves
            )
            print(f"{name}, {direction}: static stiffness against the FE's: {ratios}")
            curves, labels = [fe, *curves], ["FE", *labels]
        for curve in curves:
            if curve.model != "FE":
                curve.to_csv(out_dir / f"{stem}_{curve.model}.csv")
        plot_receptance(
            curves,
            ax=ax,
            labels=labels,
            title=f"({letter}) {name}, x = {x:.1f} m, {direction}",
        )
    fig.tight_layout()
    path = out_dir / FIGURES[direction]
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def main(
    out_dir: str | Path,
    turnout_path: str | None = None,
    source: str = "derived",
    x_switch: float = 4.0,
    x_crossing: float | None = None,
    fe_points: int | None = FE_POINTS,
) -> list[Path]:
    """Print the eigenfrequencies, write both figures and the CSVs; returns the figure paths.

    ``x_crossing`` defaults to where the wheel meets the nose: 0.267 m after the plan's nose
    tip (the packaged profiles' 3 and 6 mrad lines meet there). ``fe_points``: frequencies
    of each FE curve (None: no FE curve).
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    turnout = load_turnout(turnout_path)
    if x_crossing is None:
        x_crossing = turnout_plan(turnout).nose_tip_x + 0.267
    cases = {"switch rail": x_switch, "crossing rail": x_crossing}
    print(f"{turnout.name}, {source} parameters")
    print(eigenfrequency_table(turnout, cases, source))
    frequencies = log_frequencies(1.0, 2000.0, 600)
    fe_frequencies = None if fe_points is None else log_frequencies(1.0, 2000.0, fe_points)
    return [
        plot_direction(turnout, cases, direction, source, frequencies, out, fe_frequencies)
        for direction in FIGURES
    ]


if __name__ == "__main__":
    import matplotlib

    matplotlib.use("Agg")
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="receptance_results", help="output directory")
    parser.add_argument("--turnout", help="turnout file (default: packaged UIC60-760-1:15)")
    parser.add_argument("--source", choices=("derived", "published"), default="derived")
    parser.add_argument("--x-switch", type=float, default=4.0, help="switch-rail position (m)")
    parser.add_argument(
        "--x-crossing",
        type=float,
        default=None,
        help="crossing-rail position (m; default: where the wheel meets the nose)",
    )
    parser.add_argument(
        "--fe-points",
        type=int,
        default=FE_POINTS,
        help=f"frequencies of each FE curve (default {FE_POINTS})",
    )
    parser.add_argument("--no-fe", action="store_true", help="leave the FE curves out")
    args = parser.parse_args()
    fe_points = None if args.no_fe else args.fe_points
    for written in main(
        args.out, args.turnout, args.source, args.x_switch, args.x_crossing, fe_points
    ):
        print(f"wrote {written}")
