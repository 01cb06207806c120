"""The diverging route's lateral forces under a creep force reduction factor.

Simpack and GENSYS users lower Kalker's creep coefficients to match measured creep curves
(a reduction factor of about 0.6 ... 1.0, lower on wet or contaminated rail). Here the
full Manchester vehicle passes the packaged turnout's crossing on the diverging route at
its permitted 80 km/h, on the 3-layer co-running track, once per factor
(``PassageSettings.creep_reduction``; ``exudyn-turnout simulate --creep-reduction F``), and
the front wheelset's lateral peaks are tabulated: the check rail's force, the wheelset's
sum of lateral forces (Prud'homme) and the largest Y/Q (the right wheel's, beyond 3, is the
check rail's: its contact lifts the wheel's tread, which the run's safety summary flags,
``check_rail_tread_unloaded``). The factor scales the creep
forces' initial slopes, not their saturation at mu N. What the contact law's measured
errors are worth in the report's peaks: ``validation/contact_law_sensitivity.md``.

Run: ``python examples/creep_reduction.py [--factors 1 0.8 0.6] [--layers 3]``.
"""

from __future__ import annotations

import argparse

from exudyn_turnout.inputs.turnout import load_turnout
from exudyn_turnout.passage import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings

#: the front wheelset's lateral peaks shown (label, summary key, unit factor)
PEAKS = (
    ("check rail Fy (kN)", "peak_Fy_check_rail_N", 1e-3),
    ("sum Y (kN)", "sumY_peak_run_N", 1e-3),
    ("Y/Q right", "YQ_peak_run_right", 1.0),
    ("Y/Q left", "YQ_peak_run_left", 1.0),
)


def run(factors=(1.0, 0.8, 0.6), layers=3, x_start=30.0, x_end=50.0, vehicle=None):
    """One diverging passage per creep reduction factor; {factor: PassageResult}.

    Parameters
    ----------
    factors : sequence of float
        Creep force reduction factors (1: Kalker's coefficients as they are).
    layers : {2, 3}
        Co-running track.
    x_start, x_end : float
        m, the front wheelset's range (the default starts before the crossing region and
        covers the check rail).
    vehicle : str, optional
        A packaged vehicle (default: the full Manchester vehicle).

    Returns
    -------
    dict
        {factor: PassageResult}.
    """
    turnout = load_turnout()
    results = {}
    for factor in factors:
        settings = PassageSettings(
            route="diverging",
            speed_kmh=80.0,
            layers=layers,
            x_start=x_start,
            x_end=x_end,
            creep_reduction=factor,
        )
        results[factor] = simulate_passage(turnout, settings, vehicle)
    return results


def table(results) -> str:
    """The lateral peaks per factor as a text table, changes against the first factor."""
    factors = list(results)
    lines = [f"{'creep reduction':<20}" + "".join(f"{f:>14g}" for f in factors)]
    for label, key, scale in PEAKS:
        values = [results[f].summary.get(key) for f in factors]
        first = values[0]
        cells = []
        for k, value in enumerate(values):
            if not isinstance(value, (int, float)):
                cells.append(f"{'-':>14}")
                continue
            text = f"{value * scale:.2f}"
            if k > 0 and isinstance(first, (int, float)) and first:
                text += f" ({100.0 * (abs(value) / abs(first) - 1.0):+.0f}%)"
            cells.append(f"{text:>14}")
        lines.append(f"{label:<20}" + "".join(cells))
    return "\n".join(lines)


def main(argv=None) -> int:
    """Run the factors and print the table.

    Parameters
    ----------
    argv : list of str, optional
        ``--factors``, ``--layers``.

    Returns
    -------
    int
        0.
    """
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--factors", type=float, nargs="+", default=[1.0, 0.8, 0.6])
    parser.add_argument("--layers", type=int, choices=(2, 3), default=3)
    args = parser.parse_args(argv)
    results = run(tuple(args.factors), args.layers)
    print(f"diverging route, 80 km/h, {args.layers}-layer track, front wheelset:")
    print(table(results))
    for factor, result in results.items():
        if result.summary.get("check_rail_tread_unloaded"):
            print(f"creep reduction {factor:g}: the check rail's contact unloads the tread")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
