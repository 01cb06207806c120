"""Section 5 of ``report.md``: convergence and static checks.

Peak forces at the report's time step and at half of it, static wheel loads at the start
of every passage against the vehicle's, and the co-running static stiffness against FE's
(:func:`checks_lines`).
"""

from __future__ import annotations

from exudyn_turnout.report.markdown_format import fmt, span, table
from exudyn_turnout.report.metrics_types import CheckMetrics, ConvergenceMetrics

__all__ = ["checks_lines"]


def _convergence(convergence: ConvergenceMetrics) -> list[str]:
    rows = [
        [
            run,
            sig,
            fmt(v.h_N, ".2f", 1e-3),
            fmt(v.h_half_N, ".2f", 1e-3),
            fmt(v.relative_change, "+.2%"),
        ]
        for run, sigs in convergence.runs.items()
        for sig, v in sigs.items()
    ]
    conv = {True: "converged", False: "**not converged**", None: "n/a"}[convergence.converged]
    return [
        f"Time step {fmt(convergence.time_step_s, 'g')} s vs "
        f"{fmt(convergence.half_step_s, 'g')} s, peak forces (kN), co-running passages of "
        "section 3 (the FE passage is not re-run). Largest change "
        f"{fmt(convergence.max_relative_change, '.2%')}: {conv}.",
        "",
    ] + table(["run", "signal", "h", "h/2", "change"], rows)


def _static_formula(checks: CheckMetrics) -> str:
    """The expected static wheel load W with its formula (single wheelset or full vehicle)."""
    w = fmt(checks.expected_static_wheel_load_N, ".1f")
    if checks.vehicle == "full":
        return (
            f"; the full vehicle's front wheelset) vs W = M g / 8 = "
            f"{fmt(checks.vehicle_mass_kg, 'g')} x 9.81 / 8 = {w} N"
        )
    return (
        f") vs W = (m_w + m_s) g / 2 = ({fmt(checks.m_w_kg, 'g')} + "
        f"{fmt(checks.m_s_kg, 'g')}) x 9.81 / 2 = {w} N"
    )


def _static(checks: CheckMetrics) -> list[str]:
    loads = [
        [
            k,
            fmt(v.right_N, ".1f"),
            fmt(v.left_N, ".1f"),
            fmt(v.right_relative, "+.2%"),
            fmt(v.left_relative, "+.2%"),
            fmt(v.mean_relative, "+.2e"),
        ]
        for k, v in checks.static_wheel_load.items()
    ]
    starts = "; ".join(
        f"{route}, x = {checks.start_x_m[route]:g} m: right rail y = {fmt(y.get('r1'), '+.2f')} "
        f"m, left rail y = {fmt(y.get('r4'), '+.2f')} m"
        for route, y in checks.start_rail_y_m.items()
    )
    stiff = checks.static_stiffness_ratio_to_FE
    return (
        [
            "Static wheel loads at the start of each passage (static equilibrium"
            + _static_formula(checks)
            + ". The mean of the two "
            "wheels (vertical equilibrium) is "
            + ("within" if checks.static_wheel_load_ok else "**outside**")
            + " the tolerance; "
            "the split between the wheels differs by up to "
            f"{fmt(checks.max_split_relative, '.2%')} where the cross-section is not symmetric "
            f"({starts}).",
            "",
        ]
        + table(["passage", "right (N)", "left (N)", "right vs W", "left vs W", "mean vs W"], loads)
        + [
            "Static stiffness of the co-running models relative to FE at the receptance points: "
            f"2-layer {span([v['2-layer'] for v in stiff.values()], '.3f')}, 3-layer "
            f"{span([v['3-layer'] for v in stiff.values()], '.3f')} (per case in section 2, where "
            "the receptance is discussed).",
            "",
        ]
    )


def checks_lines(convergence: ConvergenceMetrics, checks: CheckMetrics) -> list[str]:
    """Section 5: time-step convergence and the static checks.

    Parameters
    ----------
    convergence : ConvergenceMetrics
        The report's convergence section.
    checks : CheckMetrics
        The report's static checks.

    Returns
    -------
    list of str
        Lines.
    """
    return ["## 5 Convergence and checks", ""] + _convergence(convergence) + _static(checks)
