"""Section 1 of the validation report: track stiffness along the turnout (Fig. 1 analogue).

The FE static stiffness at every sleeper of every rail (cached on disk), its polynomial fits
against the paper's Eqs 10 and 14, the numbers behind the paper's Section 2 statements,
and the 2-layer co-running model's static stiffness against FE's (:func:`stiffness_section`).
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from exudyn_turnout.corunning.modal import co_running_receptance
from exudyn_turnout.corunning.parameters import reference_support
from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.report.cache import RESULT_STAGES, ResultCache, code_fingerprint, input_key
from exudyn_turnout.report.config import ReportConfig, log, turnout_fingerprint
from exudyn_turnout.report.settings import (
    ReportSettings,
    check_rails,
    report_settings,
    stock_rails,
)

__all__ = ["paper_stiffness_profiles", "stiffness_statements", "stiffness_section"]


def paper_stiffness_profiles(turnout: Turnout, x: np.ndarray) -> dict[str, list[float] | float]:
    """Eqs 10 and 14 of the turnout file (N/m) at x, and the stock rail's Eq 2 values K_st (N/m).

    Parameters
    ----------
    turnout : Turnout
    x : ndarray
        m, where the equations are evaluated.

    Returns
    -------
    dict
        JSON-ready: ``x_m``, ``K_sw_N_per_m``, ``K_sh_N_per_m`` (lists), ``K_st_z_N_per_m``,
        ``K_st_y_N_per_m``.
    """
    ref = reference_support(turnout)
    return {
        "x_m": [float(v) for v in x],
        "K_sw_N_per_m": [turnout.K_sw(float(v)) for v in x],
        "K_sh_N_per_m": [turnout.K_sh(float(v)) for v in x],
        "K_st_z_N_per_m": ref.K_st_z,
        "K_st_y_N_per_m": ref.K_st_y,
    }


def _cached_stiffness(turnout: Turnout, config: ReportConfig, cache: ResultCache):
    """FE static stiffness profile (computed or from the cache) and where it came from."""
    from exudyn_turnout.fe.stiffness import StiffnessProfile, static_stiffness_profile

    key = input_key(
        "fe_stiffness",
        turnout_fingerprint(turnout),
        code_fingerprint(RESULT_STAGES),
        config.fe_options,
    )
    hit = cache.load(key)
    if hit is not None:
        a, meta = hit
        profile = StiffnessProfile(
            a["x"],
            tuple(meta["rail"]),
            a["K_z"],
            a["K_y"],
            meta["frequency_hz"],
            meta["rail_names"],
            meta["n_dof"],
        )
        return profile, {
            "cached": True,
            "wall_time_s": meta["wall_time_s"],
            "computed": meta["computed"],
        }
    t0 = time.perf_counter()
    profile = static_stiffness_profile(turnout, options=config.fe_options)
    info = {
        "cached": False,
        "wall_time_s": time.perf_counter() - t0,
        "computed": time.strftime("%Y-%m-%d %H:%M"),
    }
    cache.save(
        key,
        {"x": profile.x, "K_z": profile.K_z, "K_y": profile.K_y},
        {
            "rail": list(profile.rail),
            "frequency_hz": profile.frequency_hz,
            "rail_names": dict(profile.rail_names),
            "n_dof": dict(profile.n_dof),
            **info,
        },
    )
    return profile, info


def _fit_metrics(fit, paper) -> dict[str, Any]:
    xs = np.linspace(fit.x_min, fit.x_max, 3)
    return {
        "rail": fit.rail,
        "coefficients": list(fit.coefficients),
        "x_range_m": [fit.x_min, fit.x_max],
        "r_squared": fit.r_squared,
        "n_points": fit.n_points,
        "paper_coefficients": list(paper.coefficients),
        "at_x": [
            {
                "x_m": float(x),
                "fit_N_per_m": fit(float(x)),
                "paper_N_per_m": paper(float(x)),
                "ratio": fit(float(x)) / paper(float(x)),
            }
            for x in xs
        ],
    }


def _rail_metrics(profile) -> dict[str, Any]:
    out = {}
    for rail in profile.rails:
        xs, kz, ky = profile.of(rail)
        out[rail] = {
            "name": profile.rail_names.get(rail, rail),
            "x_range_m": [float(xs[0]), float(xs[-1])],
            "K_z_min": float(kz.min()),
            "K_z_max": float(kz.max()),
            "K_y_min": float(ky.min()),
            "K_y_max": float(ky.max()),
            "n_sleepers": len(xs),
        }
    return out


def stiffness_statements(
    profile, turnout: Turnout, settings: ReportSettings | None = None, layout=None
) -> dict[str, Any]:
    """The numbers behind the paper's Section 2 statements on Fig. 1(b,c), from the FE profile.

    Stock rails: spread of K_z relative to the plain-track value (mean before the toe); switch
    rail (layout's reference switch rail): K_z at its first sleeper and at the end of the
    Eq 10 polynomial (``K_sw.x_max``, 22 m for the UIC60 turnout) against the stock rail's
    there; crossing panel (the crossing region of ``[regions]``): mean K_z of the
    switch-rail line over the stock rail's; lateral K_y at the end of the turnout (last
    sleeper of the crossing region; after it lies plain track) over the first sleeper from
    the toe; check rails' K_y over the running rail's.

    Parameters
    ----------
    profile : StiffnessProfile
        FE static stiffness per rail
        (:func:`~exudyn_turnout.fe.stiffness.static_stiffness_profile`).
    turnout : Turnout
    settings : ReportSettings, optional
        Default :func:`~exudyn_turnout.report.settings.report_settings` of the turnout.
    layout : Layout, optional
        Default :func:`~exudyn_turnout.fe.layout.load_layout` of the turnout.

    Returns
    -------
    dict
        JSON-ready numbers (N/m, m, ratios).
    """
    from exudyn_turnout.fe.layout import load_layout

    settings = settings or report_settings(turnout)
    layout = layout or load_layout(turnout)
    refs = turnout.raw.get("layout", {}).get("reference_rails", {})
    stock = refs.get("stock", layout.fits["K_sh"].rail)
    switch = refs.get("switch", layout.fits["K_sw"].rail)
    xs, kz, ky = profile.of(stock)
    toe = _toe_x(layout)
    plain = float(kz[xs < toe].mean()) if (xs < toe).any() else float(kz[0])
    xw, kzw, kyw = profile.of(switch)
    x0, x1 = settings.regions["crossing"]
    in_cross = (xw >= x0) & (xw <= x1)
    stock_at = lambda x: float(np.interp(x, xs, kz))  # noqa: E731
    stocks = set(stock_rails(settings, layout))
    rails = dict.fromkeys([stock] + [r for r in profile.rails if r in stocks] + [switch])
    lateral = {r: _end_over_start(profile, r, x1, toe) for r in rails}
    checks = [r for r in profile.rails if r in set(check_rails(settings, layout, turnout))]
    check_ratio = {
        r: float(np.mean(profile.of(r)[2]) / np.interp(np.mean(profile.of(r)[0]), xw, kyw))
        for r in checks
    }
    x_sw = settings.switch_claim_x
    return {
        "stock_rail": stock,
        "switch_rail": switch,
        "stock_plain_K_z": plain,
        "stock_K_z_spread": [float(kz.min() / plain - 1), float(kz.max() / plain - 1)],
        "switch_toe": {"x_m": float(xw[0]), "K_z": float(kzw[0]), "stock_K_z": stock_at(xw[0])},
        "switch_plateau": {
            "x_m": x_sw,
            "K_z": float(np.interp(x_sw, xw, kzw)),
            "stock_K_z": stock_at(x_sw),
        },
        "crossing_over_stock_K_z": float(kzw[in_cross].mean() / kz[(xs >= x0) & (xs <= x1)].mean()),
        "crossing_x_range_m": [x0, x1],
        "lateral_end_over_start": lateral,
        "check_over_running_K_y": check_ratio,
    }


def _toe_x(layout) -> float:
    """x (m) of the switch toe: where the first curved centreline of the layout leaves the
    straight one (0 by the file format's convention when there is none)."""
    starts = [c.curve_start_x for c in layout.routes.values() if math.isfinite(c.curve_start_x)]
    return float(min(starts)) if starts else 0.0


def _end_over_start(profile, rail: str, x_end: float, toe: float = 0.0) -> float:
    """K_y at the last sleeper up to x_end over K_y at the first sleeper from the toe (x >= toe)."""
    xs, _, ky = profile.of(rail)
    sel = (xs >= toe) & (xs <= x_end)
    return float(ky[sel][-1] / ky[sel][0]) if sel.any() else math.nan


def _co_running_static(turnout: Turnout, xs: np.ndarray, slot: str) -> dict[str, list[float]]:
    """Static stiffness 1/|H(1 Hz)| (N/m) of the 2-layer co-running rail ``slot`` at xs."""
    f = np.array([1.0])

    def k(d: str, x: float) -> float:
        return co_running_receptance(turnout, 2, slot, d, x=x, frequencies=f).static_stiffness

    return {d: [k(d, float(x)) for x in xs] for d in ("vertical", "lateral")}


def stiffness_section(
    turnout: Turnout,
    config: ReportConfig,
    cache: ResultCache,
    settings: ReportSettings | None = None,
) -> tuple[dict[str, Any], Any]:
    """FE static stiffness along the turnout with its fits, and the paper's Eqs 10, 14.

    The co-running comparison uses ``report.receptance_slot`` of the turnout's settings.

    Parameters
    ----------
    turnout : Turnout
    config : ReportConfig
        FE mesh.
    cache : ResultCache
        Where the FE profile is stored.
    settings : ReportSettings, optional
        Default :func:`~exudyn_turnout.report.settings.report_settings` of the turnout.

    Returns
    -------
    (dict, dict or None)
        JSON-ready metrics, and the plot data (FE profile, fits, the co-running static
        stiffness) or None when the FE profile is not available.
    """
    settings = settings or report_settings(turnout)
    x = np.linspace(turnout.x_min, turnout.x_max, 131)
    out: dict[str, Any] = {
        "paper": paper_stiffness_profiles(turnout, x),
        "available": False,
        "reference_rail_type": settings.reference_rail_type,
    }
    try:
        from exudyn_turnout.fe.fits import fit_turnout_profiles

        profile, info = _cached_stiffness(turnout, config, cache)
    except ImportError as err:
        out["note"] = f"FE static stiffness profile not available in this version ({err})"
        return out, None
    fits = fit_turnout_profiles(profile, turnout)
    xw = profile.of(fits.K_sw.rail)[0]
    slot = settings.receptance_slot
    zones = [z for z in turnout.zones if slot in z.active_rails]
    xw = xw[xw <= max(z.x_end for z in zones)]
    co = _co_running_static(turnout, xw, slot)
    ratio = {
        d: [
            c / k
            for c, k in zip(
                co[d], profile.of(fits.K_sw.rail)[1 if d == "vertical" else 2][: len(xw)]
            )
        ]
        for d in co
    }
    out.update(
        {
            "available": True,
            "fe": info,
            "fe_n_dof": dict(profile.n_dof),
            "rails": _rail_metrics(profile),
            "fits": {
                "K_sw": _fit_metrics(fits.K_sw, turnout.K_sw),
                "K_sh": _fit_metrics(fits.K_sh, turnout.K_sh),
            },
            "statements": stiffness_statements(profile, turnout, settings),
            "co_running_over_FE": {d: [float(min(v)), float(max(v))] for d, v in ratio.items()},
            "co_running_slot": slot,
            "co_running_zones": [z.index for z in zones],
        }
    )
    log(
        f"stiffness profile: FE {info['wall_time_s']:.1f} s"
        + (" (cached)" if info["cached"] else "")
    )
    return out, {"profile": profile, "fits": fits, "co_running_x": xw, "co_running": co}
