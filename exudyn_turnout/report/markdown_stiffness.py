"""Section 1 of ``report.md``: track stiffness along the turnout (the paper's Fig. 1 analogue).

The FE static stiffness per rail, its polynomial fits against the paper's Eqs 10 and 14,
and the 2-layer co-running model's static stiffness over FE's (:func:`stiffness_lines`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from exudyn_turnout.report.criteria import Claim
from exudyn_turnout.report.markdown_format import (
    claims_table,
    fe_source,
    figure,
    fmt,
    span,
    table,
)
from exudyn_turnout.report.metrics_types import StiffnessMetrics

__all__ = ["stiffness_lines"]


def _rail_rows(stiffness: StiffnessMetrics) -> list[list[str]]:
    return [
        [f"`{r}`", v.name, f"{v.x_range_m[0]:g}-{v.x_range_m[1]:g}"]
        + [fmt(k, ".1f", 1e-6) for k in (v.K_z_min, v.K_z_max, v.K_y_min, v.K_y_max)]
        for r, v in (stiffness.rails or {}).items()
    ]


def _polynomial(coefficients: Sequence[float]) -> str:
    return " + ".join(f"{c:.3g} x^{k}" for k, c in enumerate(coefficients))


def _fit_rows(stiffness: StiffnessMetrics) -> list[list[str]]:
    rows = []
    fits = stiffness.fits or {}
    for name, eq in (("K_sw", "Eq 10"), ("K_sh", "Eq 14")):
        f = fits[name]
        at = "; ".join(
            f"{p.x_m:g} m: {fmt(p.fit_N_per_m, '.1f', 1e-6)} vs "
            f"{fmt(p.paper_N_per_m, '.1f', 1e-6)} ({fmt(p.ratio, '.3f')})"
            for p in f.at_x
        )
        rows.append(
            [
                f"{name} ({eq})",
                f"`{f.rail}`",
                f"{f.x_range_m[0]:g}-{f.x_range_m[1]:g}",
                _polynomial(f.coefficients),
                _polynomial(f.paper_coefficients),
                fmt(f.r_squared, ".3f"),
                str(f.n_points),
                at,
            ]
        )
    return rows


def _available(stiffness: StiffnessMetrics, figures: Mapping[str, str]) -> list[str]:
    co_running = stiffness.co_running_over_FE or {}
    zones = ", ".join(str(z) for z in stiffness.co_running_zones or ()) or "n/a"
    n_dof = stiffness.fe_n_dof or {}
    assert stiffness.fe is not None  # an available profile says where it came from
    return (
        [
            "FE: K = 1/|H(1 Hz)| at every sleeper of every rail (as the paper), "
            f"{n_dof['vertical']} / {n_dof['lateral']} coordinates "
            f"(vertical / lateral), {fmt(stiffness.fe.wall_time_s, '.1f')} s, "
            f"{fe_source(stiffness.fe)}.",
            "",
        ]
        + figure(figures, "stiffness", "static stiffness along the turnout")
        + ["FE static stiffness per rail (MN/m):", ""]
        + table(
            ["rail", "description", "x (m)", "K_z min", "K_z max", "K_y min", "K_y max"],
            _rail_rows(stiffness),
        )
        + [
            "Polynomial fits of the FE stiffness (N/m, x in m) against the paper's; values in "
            "MN/m (fit vs paper, ratio):",
            "",
        ]
        + table(
            ["fit", "rail", "x (m)", "ours", "paper", "R^2", "sleepers", "fit vs paper"],
            _fit_rows(stiffness),
        )
        + [
            "The 2-layer co-running model's static stiffness of "
            f"{stiffness.co_running_slot or 'r2'} (Delta_z, Delta_y from the paper's Eqs 10, "
            "14) over the FE value of the same rail, along the zones where it is active "
            f"({zones}): vertical {span(co_running['vertical'], '.3f')}, lateral "
            f"{span(co_running['lateral'], '.3f')}.",
            "",
        ]
    )


def stiffness_lines(
    stiffness: StiffnessMetrics, claims: Sequence[Claim], figures: Mapping[str, str]
) -> list[str]:
    """Section 1: the paper's equations, the FE profile (or why it is missing), the claims.

    Parameters
    ----------
    stiffness : StiffnessMetrics
        The report's stiffness section.
    claims : sequence of Claim
        The report's claims (those on track stiffness are tabled).
    figures : mapping
        Figure name -> file name relative to report.md.

    Returns
    -------
    list of str
        Lines.
    """
    paper = stiffness.paper
    lines = [
        "## 1 Track stiffness along the turnout (Fig. 1 analogue)",
        "",
        "Paper: Eq 10 K_sw(x) (switch rail, vertical) and Eq 14 K_sh(x) (lateral), as stored in "
        "the turnout file; reference (plain-track) rail type "
        f"`{stiffness.reference_rail_type or 'stock'}`: K_st,z = "
        f"{fmt(paper.K_st_z_N_per_m, '.4g', 1e-6)} MN/m and K_st,y = "
        f"{fmt(paper.K_st_y_N_per_m, '.4g', 1e-6)} MN/m from Eq 2.",
        "",
    ]
    if stiffness.available:
        lines += _available(stiffness, figures)
    else:
        lines += [f"**FE static stiffness profile: not available.** {stiffness.note}.", ""]
    return lines + claims_table(claims, "track stiffness")
