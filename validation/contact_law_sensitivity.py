"""What the passage's remaining contact-law errors are worth in the passage's peaks.

Writes contact_law_sensitivity.md.  Run: ``python validation/contact_law_sensitivity.py``
(``--no-fe``: the co-running tracks only, about a minute; with the FE track about 15 min on
a 2-core machine).

The passage's contact law (2-D slices, semi-Hertzian normal law, FASTSIM creep table) misses
exact contact by measured amounts:

* the normal law's force at the passage's penetration, against the exact half-space
  solution on the 3-D surfaces at the paper's peak instants: -6.6 % (the check rail) to
  +33.9 % (the switch blade's closure) for the full vehicle (``validation/peak_contact.md``,
  column "N exact at delta"); the approach of the tables' law at CONTACT's five reference
  cases: -15.5 % to +6.2 % (``validation/normal_vs_contact.md``, column "table law"), a
  force factor of ``(1 + e)^-1.5`` = 1.29 to 0.91.  :data:`NORMAL_FACTORS` brackets both;
* the creep forces of the kernel's FASTSIM table on the passage's patch, against CONTACT's
  FX and FS: -14.9 % to +29.2 % outside the cut patch of cw_interrupt#2
  (``validation/contact_vs_contact.md``, column "kernel (FASTSIM table), KP"), and -8.5 % to
  +2.9 % against Kalker's exact theory at the peak instants (``validation/peak_contact.md``).
  :data:`CREEP_FACTORS` brackets them (a creep force reduction factor scales the creep
  forces' initial slopes, not their saturation at mu N).

Each factor is applied to every contact of the run (``PassageSettings.normal_stiffness_factor``
and ``creep_reduction``, :func:`exudyn_turnout.wheel_rail.packed_tables.scale_contact_law`), so the
changes here bound what an error of that size *everywhere* does; the errors measured differ
from contact to contact.  The runs are the validation report's: the full Manchester vehicle
(its front wheelset, the paper's Figs 7, 8), the through route at 100 km/h and the diverging
route at 80 km/h, whole turnout, on the 2-layer, the 3-layer and the FE track.  The last
table asks whether the paper's comparisons of the tracks (3-layer against FE, 2-layer against
3-layer) survive the contact law's uncertainty: the same difference under every factor.
"""

from __future__ import annotations

import argparse
import math
import os
import time
from pathlib import Path

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings

HERE = Path(__file__).resolve().parent
#: (route, speed km/h): the validation report's passages
ROUTES = (("through", 100.0), ("diverging", 80.0))
TRACKS = ("2-layer", "3-layer", "fe")
#: normal law's force factors (module docstring: the measured errors they bracket)
NORMAL_FACTORS = (0.91, 1.34)
#: creep force reduction factors (module docstring)
CREEP_FACTORS = (0.7, 1.3)
#: (label, summary key, unit scale, unit): the front wheelset's peaks the report gives, and
#: the safety quantities; "max" keys take the larger of the two wheels
QUANTITIES = (
    ("Fz switch", "peak_Fz_switch_N", 1e-3, "kN"),
    ("Fz crossing", "peak_Fz_crossing_N", 1e-3, "kN"),
    ("Fy switch", "peak_Fy_switch_N", 1e-3, "kN"),
    ("Fy crossing", "peak_Fy_crossing_N", 1e-3, "kN"),
    ("Fy check rail", "peak_Fy_check_rail_N", 1e-3, "kN"),
    ("sum Y", "sumY_peak_run_N", 1e-3, "kN"),
    ("Y/Q", "max YQ_peak_run", 1.0, "-"),
    ("Delta Q/Q0", "max dQ_Q0_max_run", 1.0, "-"),
)


def variants() -> list[tuple[str, dict]]:
    """(label, PassageSettings changes): the baseline and one factor at a time."""
    out = [("baseline", {})]
    out += [(f"N x {f:g}", {"normal_stiffness_factor": f}) for f in NORMAL_FACTORS]
    out += [(f"creep x {f:g}", {"creep_reduction": f}) for f in CREEP_FACTORS]
    return out


def quantity(summary: dict, key: str) -> float:
    """A summary value (NaN where absent); ``"max <stem>"``: the larger of the two wheels."""
    if key.startswith("max "):
        stem = key[4:]
        values = [quantity(summary, f"{stem}_{wheel}") for wheel in ("right", "left")]
        finite = [abs(v) for v in values if math.isfinite(v)]
        return max(finite) if finite else math.nan
    value = summary.get(key)
    return float(value) if isinstance(value, (int, float)) else math.nan


def change(new: float, old: float) -> float:
    """``|new| / |old| - 1`` in per cent (NaN where either is missing or old is 0)."""
    if not (math.isfinite(new) and math.isfinite(old)) or old == 0.0:
        return math.nan
    return 100.0 * (abs(new) / abs(old) - 1.0)


def _pct(value: float) -> str:
    return "-" if not math.isfinite(value) else f"{value:+.1f} %"


def run_all(tracks, progress=print) -> tuple[dict, float]:
    """Every (route, track, variant) passage's summary quantities, and the passages' wall s."""
    turnout = load_turnout()
    results = {}
    started = time.perf_counter()
    for route, speed in ROUTES:
        for track in tracks:
            for label, changes in variants():
                t0 = time.perf_counter()
                settings = PassageSettings(route=route, speed_kmh=speed, **changes)
                summary = simulate_passage(turnout, settings, track=track).summary
                results[route, track, label] = {
                    name: quantity(summary, key) for name, key, _, _ in QUANTITIES
                }
                progress(f"{route} {track} {label}: {time.perf_counter() - t0:.1f} s")
    return results, time.perf_counter() - started


def largest_changes(results: dict, tracks) -> dict:
    """Per (variant, quantity): the largest |change| against the baseline over routes and
    tracks, with where it happened."""
    out = {}
    for label, _ in variants()[1:]:
        for name, _, _, _ in QUANTITIES:
            best = (math.nan, "")
            for route, _ in ROUTES:
                for track in tracks:
                    d = change(results[route, track, label][name],
                               results[route, track, "baseline"][name])  # fmt: skip
                    if math.isfinite(d) and not abs(d) <= abs(best[0]):
                        best = (d, f"{route}, {track}")
            out[label, name] = best
    return out


def _write(path: Path, results: dict, tracks, seconds: float) -> None:
    labels = [label for label, _ in variants()]
    lines = [
        "# What the contact law's remaining errors are worth in the passage's peaks",
        "",
        "Written by `python validation/contact_law_sensitivity.py` (the errors each factor "
        "brackets, with their pages, in its docstring).  The full Manchester vehicle, its "
        "front wheelset; the validation report's runs (through 100 km/h, diverging 80 km/h, "
        "whole turnout); every contact's normal law times `N x` "
        "(`PassageSettings.normal_stiffness_factor`) or its creep coefficients times "
        "`creep x` (`PassageSettings.creep_reduction`), one at a time.  Changes are of the "
        "magnitude, against the baseline.  "
        f"Passages: {seconds:.0f} s wall on a shared 2-core machine "
        f"(OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS', 'unset')}).",
        "",
        "## Largest change over both routes and all tracks",
        "",
        "| quantity | " + " | ".join(labels[1:]) + " |",
        "|---|" + "---|" * (len(labels) - 1),
    ]
    largest = largest_changes(results, tracks)
    for name, _, _, _ in QUANTITIES:
        cells = []
        for label in labels[1:]:
            d, where = largest[label, name]
            cells.append("-" if not where else f"{_pct(d)} ({where})")
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
    for route, speed in ROUTES:
        lines += [
            "",
            f"## {route}, {speed:.0f} km/h",
            "",
            "| quantity | track | baseline | " + " | ".join(labels[1:]) + " |",
            "|---|---|---|" + "---|" * (len(labels) - 1),
        ]
        for name, _, scale, unit in QUANTITIES:
            for track in tracks:
                base = results[route, track, "baseline"][name]
                if not math.isfinite(base) or base == 0.0:  # absent, or no contact
                    continue
                cells = [
                    _pct(change(results[route, track, label][name], base)) for label in labels[1:]
                ]
                value = f"{base * scale:.3g} {unit}" if unit != "-" else f"{base:.3g}"
                lines.append(f"| {name} | {track} | {value} | " + " | ".join(cells) + " |")
    pairs = [("3-layer", "fe"), ("2-layer", "3-layer")]
    pairs = [p for p in pairs if p[0] in tracks and p[1] in tracks]
    if pairs:
        lines += [
            "",
            "## The tracks' comparisons under every factor",
            "",
            "The difference of the first track's peak against the second's "
            "(first / second - 1 of the magnitudes), at the baseline and under each factor: "
            "a comparison the contact law's uncertainty cannot overturn keeps its sign and "
            "about its size in every column.",
            "",
            "| route | quantity | tracks | " + " | ".join(labels) + " |",
            "|---|---|---|" + "---|" * len(labels),
        ]
        for route, _ in ROUTES:
            for name, _, _, _ in QUANTITIES:
                for first, second in pairs:
                    cells = [
                        _pct(
                            change(
                                results[route, first, label][name],
                                results[route, second, label][name],
                            )
                        )  # fmt: skip
                        for label in labels
                    ]
                    if all(c == "-" for c in cells):
                        continue
                    lines.append(
                        f"| {route} | {name} | {first} vs {second} | " + " | ".join(cells) + " |"
                    )
    path.write_text("\n".join(lines) + "\n")


def main(argv=None) -> int:
    """Run the passages and write the page.

    Parameters
    ----------
    argv : list of str, optional
        ``--no-fe``: the co-running tracks only; ``--out``: the page.

    Returns
    -------
    int
        0.
    """
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-fe", action="store_true", help="co-running tracks only")
    parser.add_argument("--out", type=Path, default=HERE / "contact_law_sensitivity.md")
    args = parser.parse_args(argv)
    tracks = TRACKS[:2] if args.no_fe else TRACKS
    results, seconds = run_all(tracks)
    _write(args.out, results, tracks, seconds)
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
