"""Monte-Carlo study: peak crossing force against rail pad stiffness (+-20 %) over 20 seeds
of random track irregularity (ERRI low level), on all cores.

Run: ``python examples/monte_carlo_study.py [--out DIR] [--workers N] [--keep-timeseries]``;
writes the results table and two figures (the peak against the pad stiffness with the
seeds' range, and the peak's distribution over the seeds, one per stiffness) into DIR and
prints the mean and range per stiffness. A rerun resumes: only the cases not stored yet
are computed. ``--keep-timeseries`` also stores each case's time series
(``DIR/cases/<key>/timeseries.npz``).
"""

import argparse
from pathlib import Path

import numpy as np

from exudyn_turnout.plotting.studies import (
    plot_peak_distribution,
    plot_peak_vs_factor,
    save_study_figure,
)
from exudyn_turnout.studies import run_study

STUDY = Path(__file__).with_name("monte_carlo_study.toml")
#: The four pad stiffnesses, paired in the study file (varied together): one factor.
PADS = [f"turnout.rail_types.{r}.pad.k_z" for r in ("stock", "switch", "crossing", "check")]
K_Z = PADS[0]
PEAK = "max_Fz_crossing_N"


def main(argv=None):
    """Run the study, print the table of peaks, save the figures."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="monte_carlo_study", help="output directory")
    parser.add_argument("--workers", type=int, help="processes (default: all cores)")
    parser.add_argument(
        "--keep-timeseries", action="store_true", help="store each case's time series"
    )
    args = parser.parse_args(argv)

    def show(done, total, eta):
        print(f"{done}/{total} cases" + (f", {eta:.0f} s left" if eta else ""), flush=True)

    result = run_study(
        STUDY,
        workers=args.workers,
        out=args.out,
        progress=show,
        keep_timeseries=args.keep_timeseries or None,
    )
    print(f"{result.computed} computed, {result.reused} stored before, {result.failed} failed")
    t = result.table
    ok = t["status"] == "ok"
    print(f"\n{'pad k_z (MN/m)':>15} {'mean (kN)':>10} {'min':>8} {'max':>8} {'std':>7}")
    for k_z in np.unique(t[K_Z]):
        v = t[PEAK][ok & (t[K_Z] == k_z)] / 1e3
        print(
            f"{k_z / 1e6:>15.0f} {v.mean():>10.1f} {v.min():>8.1f} {v.max():>8.1f} {v.std():>7.1f}"
        )
    fig, _ = plot_peak_vs_factor(t, PADS, PEAK)  # x: "rail pad k_z, stock/.../check rails"
    save_study_figure(fig, Path(args.out) / "peak_vs_pad_stiffness.png")
    fig, _ = plot_peak_distribution(t, PEAK, by=[PADS])  # one distribution per stiffness
    save_study_figure(fig, Path(args.out) / "peak_distribution_by_pad.png")


if __name__ == "__main__":
    main()
