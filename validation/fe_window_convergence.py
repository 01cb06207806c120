"""Window-length convergence of the FE track under the single wheelset (issue 24).

Run: ``python validation/fe_window_convergence.py [--lengths 12 20 30] [--out PATH]``.
Writes ``validation/fe_window_convergence.md``: the peak vertical and lateral wheel forces
(largest |Fz|, |Fy| of either wheel) over the switch (0-5 m) and the crossing (44-49 m) of
the through route at 100 km/h, on the whole FE model (80,694 DOFs over 138 m, the
reference) and on moving windows of each length (``FEPassageOptions.window_length``), with
the deviation from the whole model and the CPU time of each run in one process.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage.fe_track.options import FEPassageOptions
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings

CASES = {"switch": (0.0, 5.0), "crossing": (44.0, 49.0)}
KEYS = {"Fz": ("Fz_right_N", "Fz_left_N"), "Fy": ("Fy_right_N", "Fy_left_N")}


def peaks(result) -> dict[str, float]:
    """Largest |F| of either wheel, vertical and lateral (N)."""
    c = result.columns
    return {k: float(max(np.max(np.abs(c[a])) for a in keys)) for k, keys in KEYS.items()}


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lengths", type=float, nargs="+", default=[12.0, 20.0, 30.0])
    parser.add_argument("--out", default=str(Path(__file__).with_suffix(".md")))
    args = parser.parse_args(argv)
    turnout = load_turnout()
    simulate_passage(
        turnout, PassageSettings(x_start=-5.0, x_end=-4.9), vehicle="wheelset"
    )  # tables, numba
    rows = []
    for region, (a, b) in CASES.items():
        settings = PassageSettings(x_start=a, x_end=b)
        c0 = time.process_time()
        simulate_passage(turnout, settings, track="3-layer", vehicle="wheelset")
        cpu_3l = time.process_time() - c0
        results = {}
        for length in [None, *args.lengths]:
            c0 = time.process_time()
            r = simulate_passage(
                turnout,
                settings,
                track="fe",
                fe_options=FEPassageOptions(window_length=length),
                vehicle="wheelset",
            )
            results[length] = (peaks(r), time.process_time() - c0)
        ref = results[None][0]
        for length, (p, cpu) in results.items():
            dev = {k: 100.0 * (p[k] / ref[k] - 1.0) for k in p}
            name = "whole model" if length is None else f"{length:g} m"
            rows.append(
                f"| {region} {a:g}-{b:g} m | {name} | {p['Fz'] / 1e3:.3f} | {dev['Fz']:+.3f} | "
                f"{p['Fy'] / 1e3:.3f} | {dev['Fy']:+.3f} | {cpu:.1f} | {cpu / cpu_3l:.0f} |"
            )
    text = "\n".join(
        [
            "# FE window-length convergence (issue 24)",
            "",
            f"Written by `python validation/{Path(__file__).name}`. Single wheelset, through "
            "route, 100 km/h, h = 1e-4 s, profile contact; peaks: largest |F| of either wheel. "
            "Window: `FEPassageOptions.window_length` about the wheelset, cut every "
            f"{FEPassageOptions().window_shift:g} m, absorbing ends "
            f"{FEPassageOptions().window_absorbing_length:g} m to loss factor "
            f"{FEPassageOptions().window_eta_max:g}. CPU: the whole `simulate_passage` (build, "
            "static, steps) after a warm-up; 'x 3L': in units of the 3-layer co-running run "
            "of the same case measured in the same process.",
            "",
            "| case | FE track | peak Fz kN | dev % | peak Fy kN | dev % | CPU s | x 3L |",
            "|---|---|---|---|---|---|---|---|",
            *rows,
            "",
        ]
    )
    Path(args.out).write_text(text)
    print(text)


if __name__ == "__main__":
    main()
