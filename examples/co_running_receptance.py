"""Receptance of the switch rail and the crossing rail, two- and three-layer co-running models.

The layout of the paper's Figs 5 (vertical) and 6 (lateral), without the FE curve: panel
(a) the switch rail, panel (b) the crossing rail. The paper shows them "where the load is
transferring at the switch and crossing" (Section 3.3), so the defaults are the load
transfer positions of the packaged through route: x = 4 m on the switch blade (the wheel
passes from the stock rail to the blade near 3.9 m) and, on the crossing nose, where the
wheel meets the nose (0.27 m after the nose tip that the turnout's plan puts at 46.9 m:
x = 47.2 m). Both are rail slot r2.

Run::

    python examples/co_running_receptance.py --out results/receptance [--source published]

Writes ``fig5_vertical_receptance.png``, ``fig6_lateral_receptance.png`` and one CSV per
curve to the output directory and prints the eigenfrequencies of both models there.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from exudyn_turnout.corunning.modal import co_running_modes, co_running_receptance
from exudyn_turnout.inputs.geometry import turnout_plan
from exudyn_turnout.inputs.turnout import Turnout, load_turnout
from exudyn_turnout.receptance import log_frequencies

FIGURES = {"vertical": "fig5_vertical_receptance.png", "lateral": "fig6_lateral_receptance.png"}


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
) -> Path:
    """One figure, a panel per case, both models in each; CSVs beside it."""
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
        for curve in curves:
            curve.to_csv(out_dir / f"{name.replace(' ', '_')}_{direction}_{curve.model}.csv")
        plot_receptance(
            curves,
            ax=ax,
            labels=[curve.model for curve in curves],
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
) -> list[Path]:
    """Print the eigenfrequencies, write both figures and the CSVs; returns the figure paths.

    ``x_crossing`` defaults to where the wheel meets the nose: 0.267 m after the plan's nose
    tip (the packaged profiles' 3 and 6 mrad lines meet there).
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
    return [
        plot_direction(turnout, cases, direction, source, frequencies, out) for direction in FIGURES
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
    args = parser.parse_args()
    for written in main(args.out, args.turnout, args.source, args.x_switch, args.x_crossing):
        print(f"wrote {written}")
