"""Validation report: two-layer vs three-layer co-running track vs the FE reference.

:func:`build_report` computes every number of the report as data (nested dicts of
floats, the ``metrics`` written to ``metrics.json``) together with the curves and time
histories it plots; :func:`write_report` writes ``report.md`` (rendered by
:mod:`exudyn_turnout.report.markdown`), the PNG figures it embeds and ``metrics.json``.
The paper's claims are judged by :mod:`exudyn_turnout.report.claims` on those metrics.

Sections of the report (as numbered in ``report.md``, after a summary of the verdicts):
1 track stiffness along the turnout (FE static stiffness, fits, Eqs 10, 14), 2 receptance
(Figs 5, 6 analogue, with the static stiffness of the co-running models against FE's),
3 contact forces (Figs 7, 8 analogue), 4 computing cost, 5 convergence and static checks;
appendix A: parameters (derived vs published Table 2). Section 3 is computed by
:mod:`~exudyn_turnout.report.passages`; the configuration lives in
:mod:`~exudyn_turnout.report.config` (both re-exported here).

Everything turnout-specific (routes, speeds, wheels, plotted forces, regions, where the
receptances are taken, the quick passage window, the stock and check rails of the FE
statements) comes from the turnout file's ``[report]`` section or from the model, through
:func:`~exudyn_turnout.report.settings.report_settings`; another turnout is another file.

FE results (receptances, static stiffness profile, FE passage) are cached on disk
(:mod:`exudyn_turnout.report.cache`) keyed by a hash of their inputs and of the code that
computes them. Parts of the FE reference that are not in the package yet are reported as
"not available".
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Mapping
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from exudyn_turnout.corunning.comparison import TOLERANCE, compare_with_table2
from exudyn_turnout.corunning.modal import co_running_receptance, dof_names
from exudyn_turnout.corunning.parameters import reference_support
from exudyn_turnout.inputs.routes import dip_angle, load_route
from exudyn_turnout.inputs.turnout import Turnout, load_turnout
from exudyn_turnout.inputs.vehicle import load_vehicle
from exudyn_turnout.receptance import Receptance
from exudyn_turnout.report import agreement as ag
from exudyn_turnout.report.cache import (
    FE_STAGES,
    ResultCache,
    code_fingerprint,
    input_key,
)
from exudyn_turnout.report.claims import RANGES, Criteria, evaluate_claims
from exudyn_turnout.report.config import (
    FENotAvailable,
    Report,
    ReportConfig,
    log,
    report_config,
    resolve_config,
    turnout_fingerprint,
)
from exudyn_turnout.report.passage_api import PassageResult
from exudyn_turnout.report.passages import (
    fe_availability,
    fe_passage_cache_key,
    passage_model_metrics,
    passage_section,
    peak_key,
    run_passage,
    signal_key,
    summary_float,
    vehicle_mass,
    vehicle_static_load,
)
from exudyn_turnout.report.settings import (
    ReportSettings,
    check_rails,
    report_settings,
    stock_rails,
)

__all__ = [
    "ReportConfig",
    "report_config",
    "Report",
    "resolve_config",
    "receptance_positions",
    "pinned_pinned_frequency",
    "receptance_case_metrics",
    "passage_model_metrics",
    "FENotAvailable",
    "fe_availability",
    "vehicle_static_load",
    "run_passage",
    "fe_passage_cache_key",
    "build_report",
    "write_report",
]


# --- 1 parameters ---------------------------------------------------------------------


def parameters_metrics(turnout: Turnout) -> dict[str, Any]:
    """Derived vs published Table 2 (at each zone's middle, SI), with ratio and explanation."""
    rows = compare_with_table2(turnout)
    table = [
        {
            "zone": r.zone,
            "name": r.name,
            "derived": r.derived,
            "published": r.published,
            "published_text": r.published_text,
            "as_printed": r.as_printed,
            "ratio_min": r.ratio_min,
            "ratio_max": r.ratio_max,
            "reproduced": r.reproduced,
            "explanation": r.explanation,
            "reading_value": r.reading_value,
        }
        for r in rows
    ]
    out = {
        "tolerance": TOLERANCE,
        "rows": table,
        "reproduced": sum(r.reproduced for r in rows),
        "entries": len(rows),
        "published_zones": sorted(turnout.published),
    }
    if not rows:  # no published set to compare with: the derived set, zone by zone
        out["derived"] = {str(z.index): _derived_at_middle(turnout, z.index) for z in turnout.zones}
    return out


def _derived_at_middle(turnout: Turnout, zone: int) -> dict[str, float]:
    """The derived 3-layer co-running entries of a zone at its middle (SI units)."""
    from exudyn_turnout.corunning.parameters import co_running_parameters
    from exudyn_turnout.inputs.turnout import PARAMETER_NAMES

    z = turnout.zone(zone)
    values = co_running_parameters(turnout, zone=zone, layers=3).at(0.5 * (z.x_start + z.x_end))
    return {n: float(values[n]) for n in PARAMETER_NAMES if n in values}


# --- 2 stiffness along the turnout ----------------------------------------------------


def paper_stiffness_profiles(turnout: Turnout, x: np.ndarray) -> dict[str, list[float] | float]:
    """Eqs 10 and 14 of the turnout file (N/m) at x, and the stock rail's Eq 2 values K_st (N/m)."""
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
        "fe_stiffness", turnout_fingerprint(turnout), code_fingerprint(FE_STAGES), config.fe_options
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

    Returns (metrics, plot data); the co-running comparison uses ``report.receptance_slot``
    of the turnout's settings (default :func:`~exudyn_turnout.report.settings.report_settings`).
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


# --- 3 receptance ---------------------------------------------------------------------


def receptance_positions(
    turnout: Turnout,
    route: str | None = None,
    wheel: str | None = None,
    settings: ReportSettings | None = None,
) -> dict[str, tuple[str, float]]:
    """Where the receptances are taken: label -> (rail slot, x in m).

    The switch rail where the wheel's load passes from the stock rail to the switch blade,
    and the crossing rail where it passes from the wing rail to the nose: the lowest point
    of the wheel's path (:func:`~exudyn_turnout.inputs.routes.dip_angle`) in the switch and
    crossing regions (``[regions]``), on the rail slot ``report.receptance_slot`` (r2:
    switch rail in the switch panel, crossing in the crossing panel, Table 3).

    Parameters
    ----------
    turnout : Turnout
    route, wheel : str, optional
        Default ``report.receptance_route`` and ``report.receptance_wheel`` of the file.
    settings : ReportSettings, optional
        Default :func:`~exudyn_turnout.report.settings.report_settings` of the turnout.

    Returns
    -------
    dict
        "switch rail" and "crossing rail" -> (rail slot, x in m).
    """
    settings = settings or report_settings(turnout)
    r = load_route(turnout, route or settings.receptance_route)
    wheel = wheel or settings.receptance_wheel
    return {
        label: (settings.receptance_slot, dip_angle(r, wheel, *settings.regions[where])[0])
        for label, where in (("switch rail", "switch"), ("crossing rail", "crossing"))
    }


def pinned_pinned_frequency(turnout: Turnout, rail_type: str, x: float, direction: str) -> float:
    """Pinned-pinned frequency (Hz).

    The first mode of a simply supported Timoshenko beam of one sleeper bay.

    Section of ``rail_type`` at x in the bending plane of ``direction``, span = sleeper spacing.

    Parameters
    ----------
    turnout : Turnout
    rail_type : str
        A rail type of the turnout.
    x : float
        m, where its section is taken.
    direction : {"vertical", "lateral"}

    Returns
    -------
    float
        Hz.
    """
    from exudyn_turnout.fe.analytic import simply_supported_timoshenko_frequency
    from exudyn_turnout.fe.model import rail_section

    s = {
        k: float(np.ravel(v)[0])
        for k, v in rail_section(turnout, rail_type, np.array([x]), direction).items()
    }
    return simply_supported_timoshenko_frequency(
        turnout.sleeper.spacing, s["EI"], s["kGA"], s["rhoA"], s["rhoI"]
    )


def _cached_fe_receptance(
    turnout: Turnout,
    rail: str,
    direction: str,
    x: float,
    config: ReportConfig,
    cache: ResultCache,
    fe_slots: str,
) -> tuple[Receptance, dict[str, Any]]:
    """FE receptance of co-running ``rail`` at x, the FE rail from ``[layout.slots.<fe_slots>]``."""
    from exudyn_turnout.fe.frf import fe_receptance

    f = config.frequencies
    key = input_key(
        "fe_receptance",
        turnout_fingerprint(turnout),
        code_fingerprint(FE_STAGES),
        rail,
        direction,
        x,
        f,
        config.fe_options,
        fe_slots,
    )
    hit = cache.load(key)
    if hit is not None:
        arrays, meta = hit
        return (
            Receptance(arrays["f"], arrays["H"], rail, direction, x, "FE", meta["metadata"]),
            {"cached": True, "wall_time_s": meta["wall_time_s"], "computed": meta["computed"]},
        )
    t0 = time.perf_counter()
    r = fe_receptance(turnout, rail, direction, x, f, route=fe_slots, options=config.fe_options)
    info = {
        "cached": False,
        "wall_time_s": time.perf_counter() - t0,
        "computed": time.strftime("%Y-%m-%d %H:%M"),
    }
    cache.save(key, {"f": r.frequency_hz, "H": r.H}, {"metadata": dict(r.metadata), **info})
    return r, info


def _peak_near(peaks: tuple[float, ...], f0: float) -> float | None:
    """The peak within one third octave of f0 (closest in log frequency), or None."""
    near = [p for p in peaks if abs(math.log10(p / f0)) <= 0.1]
    return min(near, key=lambda p: abs(math.log10(p / f0))) if near else None


def receptance_case_metrics(
    curves: Mapping[str, Receptance], f_pp: float, criteria: Criteria
) -> dict[str, Any]:
    """Band RMS of each co-running model against FE, peaks, static stiffness, pinned-pinned bands.

    Parameters
    ----------
    curves : mapping
        "2-layer", "3-layer", "FE" -> Receptance on the same frequencies.
    f_pp : float
        Hz, pinned-pinned frequency; its band and ``criteria.pinned_pinned_neighbours``
        bands either side are left out of the ``excl. pinned-pinned`` ranges.
    criteria : Criteria

    Returns
    -------
    dict
        JSON-ready: per model the range and band RMS (dB), peaks (Hz), static stiffness;
        the pinned-pinned frequency and the FE peak and dip near it.
    """
    fe, f = curves["FE"], curves["FE"].frequency_hz
    excluded = ag.bands_near(f_pp, criteria.pinned_pinned_neighbours)
    centres = ag.third_octave_centres(RANGES[0][0], RANGES[-1][1])
    peaks = {m: ag.peak_frequencies(f, r.H, criteria.peak_prominence_db) for m, r in curves.items()}
    models: dict[str, Any] = {}
    for m in ("2-layer", "3-layer"):
        bands = ag.band_rms_db(f, ag.level_difference_db(curves[m].H, fe.H), centres)
        ranges = {
            f"{lo:g}-{hi:g} Hz": ag.range_rms_db(bands, lo, hi)
            for lo, hi in RANGES + ((1.0, 2000.0),)
        }
        ranges.update(
            {
                f"{lo:g}-{hi:g} Hz excl. pinned-pinned": ag.range_rms_db(bands, lo, hi, excluded)
                for lo, hi in RANGES + ((1.0, 2000.0),)
            }
        )
        models[m] = {
            "range_rms_db": ranges,
            "band_rms_db": {f"{c:.4g}": v for c, v in bands.items()},
        }
    for m, r in curves.items():
        models.setdefault(m, {}).update(
            {
                "peaks_hz": list(peaks[m]),
                "static_stiffness_N_per_m": r.static_stiffness,
                "static_stiffness_ratio_to_FE": r.static_stiffness / fe.static_stiffness,
            }
        )
    for m in ("2-layer", "3-layer"):
        bands = {float(k): v for k, v in models[m]["band_rms_db"].items()}
        near = [v for c, v in bands.items() if np.any(np.isclose(c, excluded, rtol=1e-3))]
        models[m]["pinned_pinned_bands_rms_db"] = (
            float(np.sqrt(np.mean(np.square(near)))) if near else math.nan
        )
    all_peaks = ag.peak_frequencies(f, fe.H, criteria.peak_prominence_db, n_max=len(f))
    all_dips = ag.peak_frequencies(f, 1.0 / fe.H, criteria.peak_prominence_db, n_max=len(f))
    return {
        "pinned_pinned_hz": f_pp,
        "excluded_bands_hz": list(excluded),
        "models": models,
        "fe_peak_near_pinned_pinned_hz": _peak_near(all_peaks, f_pp),
        "fe_dip_near_pinned_pinned_hz": _peak_near(all_dips, f_pp),
    }


def _receptance_case(
    turnout: Turnout,
    rail: str,
    x: float,
    direction: str,
    config: ReportConfig,
    cache: ResultCache,
    fe_slots: str,
) -> tuple[dict[str, Any], dict[str, Receptance]]:
    f = config.frequencies
    t0 = time.perf_counter()
    curves = {
        f"{n}-layer": co_running_receptance(turnout, n, rail, direction, x=x, frequencies=f)
        for n in (2, 3)
    }
    co_wall = (time.perf_counter() - t0) / 2
    curves["FE"], info = _cached_fe_receptance(turnout, rail, direction, x, config, cache, fe_slots)
    zone = turnout.zone_at(x)
    rail_type = zone.rail_types[rail]
    f_pp = pinned_pinned_frequency(turnout, rail_type, x, direction)
    m = receptance_case_metrics(curves, f_pp, config.criteria)
    m.update(
        {
            "rail": rail,
            "direction": direction,
            "x_m": x,
            "zone": zone.index,
            "rail_type": rail_type,
            "distance_to_sleeper_m": _distance_to_sleeper(turnout, x),
            "fe": info,
            "co_running_wall_time_s": co_wall,
            "fe_n_dof": curves["FE"].metadata.get("n_dof"),
        }
    )
    return m, curves


def _distance_to_sleeper(turnout: Turnout, x: float) -> float:
    """Distance (m) from x to the nearest sleeper of the FE layout (sleepers at x0 + i L_s)."""
    x0 = float(turnout.raw.get("layout", {}).get("sleeper_x0", 0.0))
    s = turnout.sleeper.spacing
    d = (x - x0) % s
    return float(min(d, s - d))


def receptance_section(
    turnout: Turnout,
    config: ReportConfig,
    cache: ResultCache,
    settings: ReportSettings | None = None,
) -> tuple[dict, dict]:
    """All four receptance cases (switch/crossing rail x vertical/lateral): (metrics, curves).

    Positions from :func:`receptance_positions`; the FE rail from the receptance route's
    ``[layout.slots]`` table (its ``fe_slots`` in the turnout's ``[report]``).
    """
    settings = settings or report_settings(turnout)
    fe_slots = next(
        (r.fe_slots for r in settings.routes if r.name == settings.receptance_route),
        settings.receptance_route,
    )
    metrics: dict[str, Any] = {
        "positions": {},
        "cases": {},
        "frequencies": {
            "n": config.n_frequencies,
            "f_min_hz": config.f_min,
            "f_max_hz": config.f_max,
        },
        "route": settings.receptance_route,
        "wheel": settings.receptance_wheel,
    }
    curves: dict[str, dict[str, Receptance]] = {}
    for label, (rail, x) in receptance_positions(turnout, settings=settings).items():
        metrics["positions"][label] = {"rail": rail, "x_m": x}
        for direction in ("vertical", "lateral"):
            case = f"{label}, {direction}"
            metrics["cases"][case], curves[case] = _receptance_case(
                turnout, rail, x, direction, config, cache, fe_slots
            )
            log(
                f"receptance {case}: FE {metrics['cases'][case]['fe']['wall_time_s']:.1f} s"
                + (" (cached)" if metrics["cases"][case]["fe"]["cached"] else "")
            )
    return metrics, curves


# --- 4 contact forces -----------------------------------------------------------------


# --- 5 computing cost, 6 checks -------------------------------------------------------


def cost_metrics(
    turnout: Turnout,
    passages: Mapping[str, Mapping[str, PassageResult]],
    receptance: Mapping,
    passage_metrics: Mapping,
    config: ReportConfig,
) -> dict[str, Any]:
    """Wall times measured in this run, ratios, coordinates per zone, receptance times.

    The 3-layer / 2-layer ratio is the median over the interleaved repeats of (3-layer run /
    the 2-layer run just before it): neighbouring runs see the same load of a shared
    machine, so the ratio is robust to load that changes during the report. Best and median
    wall times per model are reported beside it. FE / 3-layer uses the 3-layer median.
    """
    wall = {
        route: {m: summary_float(r.summary, "wall_time_s") for m, r in res.items()}
        for route, res in passages.items()
    }
    runs = {route: rt["co_running_wall_times_s"] for route, rt in passage_metrics["routes"].items()}
    median = {route: {m: float(np.median(v)) for m, v in w.items()} for route, w in runs.items()}
    dof = {
        str(z.index): {f"{n}-layer": len(dof_names(z.active_rails, n)) for n in (2, 3)}
        for z in turnout.zones
    }
    out = {
        "repeats": config.timing_repeats,
        "wall_time_s": wall,
        "median_wall_time_s": median,
        "simulated_time_s": {
            route: summary_float(res["3-layer"].summary, "simulated_time_s")
            for route, res in passages.items()
        },
        "ratio_3_over_2": {
            route: ag.paired_median_ratio(w["3-layer"], w["2-layer"]) for route, w in runs.items()
        },
        "best_ratio_3_over_2": {route: w["3-layer"] / w["2-layer"] for route, w in wall.items()},
        "ratio_FE_over_3": {
            route: w["FE"] / median[route]["3-layer"] for route, w in wall.items() if "FE" in w
        },
        "fe_run": {
            route: {
                "n_dof": res["FE"].summary.get("n_dof"),
                "time_step_s": res["FE"].summary.get("time_step_s"),
                "n_steps": res["FE"].summary.get("n_steps"),
                "wall_time_parts_s": res["FE"].summary.get("wall_time_parts_s"),
            }
            for route, res in passages.items()
            if "FE" in res
        },
        "dof_per_zone": dof,
        "extra_dof_per_zone": {z: d["3-layer"] - d["2-layer"] for z, d in dof.items()},
        "receptance_wall_time_s": {
            case: {
                "co-running": c["co_running_wall_time_s"],
                "FE": c["fe"]["wall_time_s"],
                "FE_cached": c["fe"]["cached"],
            }
            for case, c in receptance["cases"].items()
        },
    }
    return out


def convergence_metrics(
    turnout: Turnout,
    passages: Mapping[str, Mapping[str, PassageResult]],
    config: ReportConfig,
    settings: ReportSettings | None = None,
) -> dict[str, Any]:
    """Peak forces of the co-running passages at the report's time step and at half of it.

    Parameters
    ----------
    turnout : Turnout
    passages : mapping
        route -> model -> PassageResult of :func:`passage_section`.
    config : ReportConfig
        Resolved; ``time_step`` is halved.
    settings : ReportSettings, optional
        The report routes' signals and wheels (default: the turnout's).

    Returns
    -------
    dict
        Per run and signal the peaks at h and h/2 and their relative change.
    """
    settings = settings or report_settings(turnout)
    out: dict[str, Any] = {
        "time_step_s": config.time_step,
        "half_step_s": 0.5 * config.time_step,
        "runs": {},
    }
    for rr in settings.routes:
        route = rr.name
        for layers in (2, 3):
            base = passages[route][
                f"{layers}-layer"
            ]  # the report's run, same settings but the step
            half = run_passage(
                turnout,
                config,
                route,
                f"{layers}-layer",
                replace(base.settings, time_step=0.5 * config.time_step),
            )
            peaks = {}
            for q, r in rr.signals:
                k = peak_key(q, r, rr.wheel)
                a, b = summary_float(base.summary, k), summary_float(half.summary, k)
                peaks[signal_key(q, r)] = {
                    "h_N": a,
                    "h_half_N": b,
                    "relative_change": ag.relative_difference(b, a),
                }
            out["runs"][f"{route}, {layers}-layer"] = peaks
    worst = [
        abs(p["relative_change"])
        for run in out["runs"].values()
        for p in run.values()
        if math.isfinite(p["relative_change"])
    ]
    out["max_relative_change"] = max(worst) if worst else math.nan
    out["converged"] = out["max_relative_change"] <= config.criteria.converged if worst else None
    return out


def static_checks(
    turnout: Turnout,
    passages: Mapping[str, Mapping[str, PassageResult]],
    receptance: Mapping,
    criteria: Criteria,
    vehicle: str = "wheelset",
) -> dict[str, Any]:
    """Static wheel loads at the start of every passage vs the vehicle's static wheel load.

    The single wheelset's is (m_w + m_s) g / 2, the full vehicle's M g / 8 (front wheelset).
    And the co-running models' static stiffness relative to FE's.

    The criterion is on the mean of the two wheels (vertical equilibrium of the vehicle);
    each wheel's own difference (the split between them) is reported beside it.
    """
    v = load_vehicle()
    expected = vehicle_static_load(vehicle)
    loads = {}
    for route, res in passages.items():
        for m, r in res.items():
            right, left = (
                summary_float(r.summary, "static_wheel_load_N"),
                summary_float(r.summary, "static_wheel_load_left_N"),
            )
            loads[f"{route}, {m}"] = {
                "right_N": right,
                "left_N": left,
                "mean_N": 0.5 * (right + left),
                "right_relative": ag.relative_difference(right, expected),
                "left_relative": ag.relative_difference(left, expected),
                "mean_relative": ag.relative_difference(0.5 * (right + left), expected),
            }
    ok = all(abs(x["mean_relative"]) <= criteria.static_tolerance for x in loads.values())
    stiff = {
        case: {m: c["models"][m]["static_stiffness_ratio_to_FE"] for m in ("2-layer", "3-layer")}
        for case, c in receptance["cases"].items()
    }
    starts: dict[str, float] = {}
    for route, res in passages.items():
        if res:
            x_start = next(iter(res.values())).settings.x_start
            assert x_start is not None  # the report's passages start at config.passage_x[0]
            starts[route] = x_start
    rail_y = {
        route: {
            k: float(y)
            for k, y in load_route(turnout, route).zone(turnout.zone_at(x)).rail_y.items()
        }
        for route, x in starts.items()
    }
    return {
        "vehicle": vehicle,
        "m_w_kg": v.m_w,
        "m_s_kg": v.m_s,
        "vehicle_mass_kg": vehicle_mass(vehicle),
        "expected_static_wheel_load_N": expected,
        "static_wheel_load": loads,
        "static_wheel_load_ok": ok,
        "start_x_m": starts,
        "start_rail_y_m": rail_y,
        "max_split_relative": max(
            (max(abs(x["right_relative"]), abs(x["left_relative"])) for x in loads.values()),
            default=math.nan,
        ),
        "static_stiffness_ratio_to_FE": stiff,
    }


# --- the report -----------------------------------------------------------------------


def build_report(turnout: Turnout | None = None, config: ReportConfig = ReportConfig()) -> Report:
    """Compute every section's numbers and evaluate the claims (no files written).

    Parameters
    ----------
    turnout : Turnout, optional
        Default: the packaged turnout. Its ``[report]`` section (and model) give routes,
        speeds, regions and positions (:func:`~exudyn_turnout.report.settings.report_settings`).
    config : ReportConfig
        How much and how finely; resolved against the turnout (:func:`resolve_config`).

    Returns
    -------
    Report
    """
    t0 = time.perf_counter()
    turnout = turnout or load_turnout()
    settings = report_settings(turnout)
    config = resolve_config(config, settings, turnout)
    cache = ResultCache(None if config.cache_dir is None else Path(config.cache_dir))
    # file name and content hash, no path of the machine that ran it
    metrics: dict[str, Any] = {
        "turnout": turnout.name,
        "turnout_file": Path(str(turnout.source)).name,
        "turnout_sha256": turnout_fingerprint(turnout),
        "config": _config_metrics(config),
        "criteria": dataclasses.asdict(config.criteria),
    }
    metrics["parameters"] = parameters_metrics(turnout)
    metrics["stiffness"], profile = stiffness_section(turnout, config, cache, settings)
    metrics["receptance"], curves = receptance_section(turnout, config, cache, settings)
    metrics["passage"], passages = passage_section(turnout, config, cache, settings)
    metrics["cost"] = cost_metrics(
        turnout, passages, metrics["receptance"], metrics["passage"], config
    )
    metrics["convergence"] = convergence_metrics(turnout, passages, config, settings)
    metrics["checks"] = static_checks(
        turnout, passages, metrics["receptance"], config.criteria, config.vehicle
    )
    claims = tuple(evaluate_claims(metrics, config.criteria))
    metrics["claims"] = [dataclasses.asdict(c) for c in claims]
    metrics["compute_wall_time_s"] = time.perf_counter() - t0
    return Report(config, metrics, claims, curves, passages, profile, settings)


def _config_metrics(config: ReportConfig) -> dict[str, Any]:
    d = dataclasses.asdict(config)
    d.pop("criteria")
    d["speeds_kmh"] = dict(config.speeds_kmh or ())
    home = str(Path.home())
    if d["cache_dir"] and d["cache_dir"].startswith(home + "/"):  # no home path in metrics.json
        d["cache_dir"] = "~" + d["cache_dir"][len(home) :]
    return d


def _source_links(out: Path, files: tuple[str, ...]) -> dict[str, str]:
    """Repository path -> path relative to ``out`` of the package's source files, when the
    report is written inside the repository holding the package (none otherwise)."""
    import os

    root = Path(__file__).resolve().parents[2]  # the folder holding exudyn_turnout/
    try:
        Path(out).resolve().relative_to(root)
    except ValueError:
        return {}
    return {
        f: Path(os.path.relpath(root / f, Path(out).resolve())).as_posix()
        for f in files
        if (root / f).is_file()
    }


def write_report(
    out_dir: str | Path, config: ReportConfig = ReportConfig(), turnout: Turnout | None = None
) -> Report:
    """Build the report and write ``report.md``, its PNG figures and ``metrics.json`` into out_dir.

    Parameters
    ----------
    out_dir : str or Path
        Output directory (created).
    config : ReportConfig
        How much and how finely (:func:`report_config`).
    turnout : Turnout, optional
        Default: the packaged turnout.

    Returns
    -------
    Report
        The built report (``metrics`` as written).
    """
    from exudyn_turnout.report.figures import write_figures, write_model_figure
    from exudyn_turnout.report.markdown import render_markdown
    from exudyn_turnout.report.markdown_format import to_json

    t0 = time.perf_counter()
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    report = build_report(turnout, config)
    figures = write_figures(report, out)
    figures.update(write_model_figure(report, turnout or load_turnout(), out))
    report.metrics["report_wall_time_s"] = time.perf_counter() - t0
    (out / "metrics.json").write_text(to_json(report.metrics), encoding="utf-8")
    links = _source_links(out, ("exudyn_turnout/passage/fe_coupling.py",))
    (out / "report.md").write_text(render_markdown(report, figures, links), encoding="utf-8")
    log(f"wrote {out / 'report.md'} in {report.metrics['report_wall_time_s']:.0f} s")
    return report
