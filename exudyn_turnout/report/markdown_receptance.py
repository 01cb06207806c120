"""Section 2 of ``report.md``: receptance (the paper's Figs 5, 6 analogue).

Where the receptances are taken, the co-running models' static stiffness against FE's,
band RMS of the level differences per frequency range, the pinned-pinned frequency and
the main peaks (:func:`receptance_lines`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

from exudyn_turnout.report.criteria import RANGES, Claim
from exudyn_turnout.report.markdown_format import (
    EXCL,
    claims_table,
    fe_source,
    figure,
    fmt,
    span,
    table,
)
from exudyn_turnout.report.metrics_types import ReceptanceMetrics, ReceptanceModel
from exudyn_turnout.report.receptance_section import FE_TORSION

__all__ = ["receptance_lines"]


def _intro(receptance: ReceptanceMetrics) -> list[str]:
    sw, cr, frequencies = (
        receptance.positions["switch rail"],
        receptance.positions["crossing rail"],
        receptance.frequencies,
    )
    where = f"rail slot {sw.rail} on the {receptance.route or 'through'} route"
    return [
        "## 2 Receptance (Figs 5, 6 analogue)",
        "",
        f"Point receptance of {where}, {frequencies.n} log-spaced frequencies "
        f"{frequencies.f_min_hz:g}-{frequencies.f_max_hz:g} Hz; force and response on the "
        "rail (2-layer: rail mass; 3-layer: the m_0 above it, where the wheel acts). **FE "
        "reference**: the claims (R1-R5) are judged against the FE the paper had: the vertical "
        "plane, and the planar lateral plane with force and response at the rail (*FE* in the "
        "figures and tables). Our torsion-aware lateral FE (roll of the rail on its pads and "
        "warping, `exudyn_turnout.fe.torsion`; force and response at the gauge corner of the "
        "rail head: the FE track of the passages) goes beyond the paper: it is drawn beside "
        "it (*FE torsion*) and the co-running models are compared with it in the table *Beyond "
        "the paper* below. "
        "**Where**: "
        "the paper's caption says 'at the crossing panel', its text 'at the most crucial "
        "locations, where the load is transferring at the switch and crossing'; the co-running "
        "model has no switch rail in the crossing panel (Table 3), so we take the switch rail "
        "where the wheel's load passes from the stock rail to the switch blade (x = "
        f"{sw.x_m:.3f} m) and the crossing rail where it passes from the wing rail to the nose "
        f"(x = {cr.x_m:.3f} m): the lowest point of the {receptance.wheel or 'right'} "
        "wheel's path in the turnout file's height profiles, within its switch and crossing "
        "regions.",
        "",
    ]


def _ranges(model: ReceptanceModel) -> Mapping[str, float]:
    """A co-running model's band RMS per range (a co-running model always has them)."""
    assert model.range_rms_db is not None
    return model.range_rms_db


def _band_rows(receptance: ReceptanceMetrics) -> list[list[str]]:
    keys = [f"{lo:g}-{hi:g} Hz" for lo, hi in RANGES]
    rows = []
    for case, c in receptance.cases.items():
        for m in ("2-layer", "3-layer"):
            rr = _ranges(c.models[m])
            rows.append(
                [case, m]
                + [fmt(rr[k], ".2f") for k in keys]
                + [fmt(rr[k + EXCL], ".2f") for k in keys]
                + [fmt(rr["1-2000 Hz" + EXCL], ".2f")]
            )
    return rows


def _peak_rows(receptance: ReceptanceMetrics) -> list[list[str]]:
    rows = []
    for case, c in receptance.cases.items():
        peaks = [
            ", ".join(fmt(f, ".1f") for f in c.models[m].peaks_hz) or "none"
            for m in ("FE", "2-layer", "3-layer")
        ]
        rows.append(
            [
                case,
                fmt(c.x_m, ".3f"),
                fmt(c.distance_to_sleeper_m, ".3f"),
                fmt(c.pinned_pinned_hz, ".1f"),
                fmt(c.fe_peak_near_pinned_pinned_hz, ".1f"),
                fmt(c.fe_dip_near_pinned_pinned_hz, ".1f"),
                fmt(c.models["3-layer"].pinned_pinned_bands_rms_db, ".2f"),
            ]
            + peaks
            + [fmt(c.models["FE"].static_stiffness_N_per_m, ".4g", 1e-6)]
        )
    return rows


def _static_stiffness(receptance: ReceptanceMetrics) -> list[str]:
    """The co-running models' static stiffness over FE's: the low-frequency offset of |H|."""
    models = ("2-layer", "3-layer")
    ratios = {
        m: [c.models[m].static_stiffness_ratio_to_FE for c in receptance.cases.values()]
        for m in models
    }
    finite = [v for m in models for v in ratios[m] if v is not None and math.isfinite(v) and v > 0]
    # a stiffness ratio K/K_FE shifts 20 log10|H| below the first resonance by -20 log10(K/K_FE)
    offsets = {
        m: [-20 * math.log10(v) for v in ratios[m] if v is not None and math.isfinite(v) and v > 0]
        for m in models
    }
    if finite and max(finite) < 1:
        softer = (
            "the co-running track is softer, which lifts its receptance below the first resonance"
        )
    elif finite and min(finite) > 1:
        softer = (
            "the co-running track is stiffer, which lowers its receptance below the first resonance"
        )
    else:
        softer = (
            "the co-running track is softer at some points, stiffer at others, which shifts its "
            "receptance"
        )
    rows = [
        [case, fmt(c.models["FE"].static_stiffness_N_per_m, ".4g", 1e-6)]
        + [fmt(c.models[m].static_stiffness_ratio_to_FE, ".3f") for m in models]
        for case, c in receptance.cases.items()
    ]
    return [
        "**Static stiffness against FE.** At the receptance points the static stiffness K = "
        f"1/|H(1 Hz)| of the co-running models is {span(ratios['2-layer'], '.3f')} (2-layer) and "
        f"{span(ratios['3-layer'], '.3f')} (3-layer) times FE's: {softer} by |20 log10(K/K_FE)| = "
        f"{span([abs(v) for v in offsets['2-layer']])} dB (2-layer) and "
        f"{span([abs(v) for v in offsets['3-layer']])} dB (3-layer), part of the 1-125 Hz band "
        "RMS below.",
        "",
    ] + table(["case", "K_FE(1 Hz) (MN/m)", "2-layer K / K_FE", "3-layer K / K_FE"], rows)


def _beyond_the_paper(receptance: ReceptanceMetrics) -> list[str]:
    """The lateral cases against the torsion-aware FE (ours), beside the planar one."""
    keys = [f"{lo:g}-{hi:g} Hz" for lo, hi in RANGES]
    rows = []
    for case, c in receptance.cases.items():
        if not c.vs_fe_torsion:
            continue
        planar = c.vs_fe_torsion.get("FE planar")
        torsion = c.models.get(FE_TORSION)
        for m in ("2-layer", "3-layer"):
            rr = _ranges(c.vs_fe_torsion[m])
            rows.append(
                [case, m]
                + [fmt(rr[k + EXCL], ".2f") for k in keys]
                + [
                    fmt(c.vs_fe_torsion[m].static_stiffness_ratio_to_FE, ".3f"),
                    fmt(c.models[m].static_stiffness_ratio_to_FE, ".3f"),
                    fmt(torsion.static_stiffness_N_per_m, ".4g", 1e-6) if torsion else "-",
                    fmt(planar.static_stiffness_ratio_to_FE, ".3f") if planar else "-",
                ]
            )
    if not rows:
        return []
    head = (
        ["case", "model"]
        + [k + " excl. pp vs FE torsion" for k in keys]
        + [
            "K / K_FE torsion",
            "K / K_FE planar",
            "K_FE torsion (MN/m)",
            "K_FE planar / K_FE torsion",
        ]
    )
    return [
        "**Beyond the paper: the torsion-aware lateral FE.** Band RMS (dB) of the "
        "co-running models against the torsion-aware FE at the gauge corner (pinned-pinned "
        "bands left out) and the static stiffness ratios against both FE references. Not "
        "used for the paper's claims (their FE reference is the planar one above).",
        "",
    ] + table(head, rows)


def _check_rail(receptance: ReceptanceMetrics) -> list[str]:
    """The check rail's lateral dynamic stiffness at its entry, FE vs co-running."""
    c = receptance.check_rail
    if c is None:
        return []
    head = ["model"] + [f"{f:g} Hz" for f in c.frequencies_hz]
    rows = [
        [name] + [fmt(v, ".1f", 1e-6) for v in values]
        for name, values in c.dynamic_stiffness_N_per_m.items()
    ]
    return [
        f"**Check rail** (`{c.fe_rail}`, slot {c.rail}, {c.route} route, x = {c.x_m:.2f} m: "
        "the end of its entry flare, where the wheel strikes it). Lateral dynamic stiffness "
        "1 / |H(f)| (MN/m) at the gauge corner; 1 Hz is the static stiffness. FE: the "
        "torsion-aware FE with the check rail on its L-bracket (the FE passages' track); "
        "*bracket*: the co-running check rail derived from it (its static stiffness, lateral "
        "resonance and the resonance's depth, `exudyn_turnout.corunning.check_rail`); *Table "
        "1*: Eqs 1-19 like a running rail (the paper's).",
        "",
    ] + table(head, rows)


def _tables(receptance: ReceptanceMetrics) -> list[str]:
    keys = [f"{lo:g}-{hi:g} Hz" for lo, hi in RANGES]
    head = ["case", "model"] + keys + [k + " excl. pp" for k in keys] + ["1-2000 Hz excl. pp"]
    return (
        [
            "Band RMS of 20 log10(|H_model|/|H_FE|) (dB) per range; *excl. pp*: pinned-pinned "
            "band and its neighbours left out.",
            "",
        ]
        + table(head, _band_rows(receptance))
        + [
            "Pinned-pinned frequency f_pp (Hz, Timoshenko beam over one sleeper bay), the FE peak "
            "and dip within one third octave of it (Hz; above a sleeper the pinned-pinned mode "
            "shows as a dip, mid-span as a peak), the 3-layer model's band RMS (dB) over the "
            "pinned-pinned bands; main peaks (Hz); distance from the receptance point to the "
            "nearest sleeper (m); FE static stiffness (MN/m).",
            "",
        ]
        + table(
            [
                "case",
                "x (m)",
                "to sleeper (m)",
                "f_pp",
                "FE peak near f_pp",
                "FE dip near f_pp",
                "3-layer pp bands (dB)",
                "FE peaks",
                "2-layer peaks",
                "3-layer peaks",
                "K_FE(1 Hz) (MN/m)",
            ],
            _peak_rows(receptance),
        )
    )


def receptance_lines(
    receptance: ReceptanceMetrics,
    agree_db: float,
    claims: Sequence[Claim],
    figures: Mapping[str, str],
) -> list[str]:
    """Section 2: where, the figures, static stiffness, band and peak tables, the claims.

    Parameters
    ----------
    receptance : ReceptanceMetrics
        The report's receptance section.
    agree_db : float
        dB, the agreement band drawn in the figures (``Criteria.agree_db``).
    claims : sequence of Claim
        The report's claims (those on receptance are tabled).
    figures : mapping
        Figure name -> file name relative to report.md.

    Returns
    -------
    list of str
        Lines.
    """
    fe = [
        f"{case}: {fmt(c.fe.wall_time_s, '.1f')} s, {fe_source(c.fe)}, {c.fe_n_dof} FE coordinates"
        for case, c in receptance.cases.items()
    ]
    return (
        _intro(receptance)
        + [
            "The three-layer model at the crossing receptance point as it is built (every "
            "spring-damper of the Exudyn model with its value; `exudyn-turnout draw section` "
            "draws any zone, `exudyn-turnout draw passage` animates a passage):",
            "",
        ]
        + figure(figures, "model", "co-running cross-section at the crossing")
        + figure(figures, "receptance_vertical", "vertical receptance")
        + figure(figures, "receptance_lateral", "lateral receptance")
        + [
            f"Grey band in the lower plots: +-{agree_db:g} dB; green dotted line: f_pp; thin grey "
            "lines: 125 and 500 Hz.",
            "",
        ]
        + _static_stiffness(receptance)
        + _tables(receptance)
        + _beyond_the_paper(receptance)
        + _check_rail(receptance)
        + ["FE receptances: " + "; ".join(fe) + ".", ""]
        + claims_table(claims, "receptance")
    )
