"""Section 2 of the validation report: receptance (Figs 5, 6 analogue).

Where the receptances are taken (:func:`receptance_positions`), the pinned-pinned
frequency, the FE receptance (cached on disk) and the co-running ones, and their agreement
per frequency range (:func:`receptance_case_metrics`, :func:`receptance_section`).
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from typing import Any

import numpy as np

from exudyn_turnout.corunning.modal import co_running_receptance
from exudyn_turnout.inputs.routes import dip_angle, load_route
from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.receptance import Receptance
from exudyn_turnout.report import agreement as ag
from exudyn_turnout.report.cache import RESULT_STAGES, ResultCache, code_fingerprint, input_key
from exudyn_turnout.report.config import ReportConfig, log, turnout_fingerprint
from exudyn_turnout.report.criteria import RANGES, Criteria
from exudyn_turnout.report.settings import (
    ReportSettings,
    report_settings,
)

__all__ = [
    "FE_TORSION",
    "FE_REFERENCE_OF_CASE",
    "receptance_positions",
    "pinned_pinned_frequency",
    "receptance_case_metrics",
    "receptance_section",
    "CHECK_RAIL_FREQUENCIES",
    "check_rail_receptance_metrics",
]

#: Hz, where the check rail's lateral dynamic stiffness is tabled (1 Hz: the static one)
CHECK_RAIL_FREQUENCIES = (1.0, 50.0, 100.0, 300.0, 1000.0)


#: Name of the torsion-aware FE curve of a lateral case (ours, beyond the paper).
FE_TORSION = "FE torsion"

#: The FE reference ("FE") of a case's claims, by direction: the paper's kind of FE.
FE_REFERENCE_OF_CASE = {
    "vertical": "FE vertical plane at the rail (the paper's kind)",
    "lateral": "planar lateral FE, force and response at the rail (the paper's kind)",
}


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
    torsion: bool = False,
) -> tuple[Receptance, dict[str, Any]]:
    """FE receptance of co-running ``rail`` at x, the FE rail from ``[layout.slots.<fe_slots>]``.

    Lateral: planar at the rail (the paper's kind of FE) or, with ``torsion``, the
    torsion-aware FE at the gauge corner (ours).
    """
    from exudyn_turnout.fe.frf import fe_receptance

    f = config.frequencies
    key = input_key(
        "fe_receptance",
        turnout_fingerprint(turnout),
        code_fingerprint(RESULT_STAGES),
        rail,
        direction,
        x,
        f,
        config.fe_options,
        fe_slots,
        "torsion" if torsion else "planar",
    )
    hit = cache.load(key)
    if hit is not None:
        arrays, meta = hit
        return (
            Receptance(arrays["f"], arrays["H"], rail, direction, x, "FE", meta["metadata"]),
            {"cached": True, "wall_time_s": meta["wall_time_s"], "computed": meta["computed"]},
        )
    t0 = time.perf_counter()
    r = fe_receptance(
        turnout, rail, direction, x, f, route=fe_slots, options=config.fe_options, torsion=torsion
    )
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
    m["fe_reference"] = FE_REFERENCE_OF_CASE[direction]
    if direction == "lateral":  # ours, beyond the paper: the torsion-aware FE beside it
        torsion, _ = _cached_fe_receptance(
            turnout, rail, direction, x, config, cache, fe_slots, torsion=True
        )
        beyond = receptance_case_metrics(
            {**curves, "FE": torsion, "FE planar": curves["FE"]}, f_pp, config.criteria
        )
        m["vs_fe_torsion"] = beyond["models"]
        curves[FE_TORSION] = torsion
        m["models"][FE_TORSION] = {
            "peaks_hz": beyond["models"]["FE"]["peaks_hz"],
            "static_stiffness_N_per_m": torsion.static_stiffness,
            "static_stiffness_ratio_to_FE": (
                torsion.static_stiffness / curves["FE"].static_stiffness
            ),
        }
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

    Parameters
    ----------
    turnout : Turnout
    config : ReportConfig
        Frequencies, FE mesh, criteria.
    cache : ResultCache
        Where FE receptances are stored.
    settings : ReportSettings, optional
        Default :func:`~exudyn_turnout.report.settings.report_settings` of the turnout.

    Returns
    -------
    (dict, dict)
        JSON-ready metrics, and case -> model -> Receptance.
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
    check = check_rail_receptance_metrics(turnout, config, cache, settings)
    if check is not None:
        metrics["check_rail"] = check
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


def check_rail_receptance_metrics(
    turnout: Turnout,
    config: ReportConfig,
    cache: ResultCache,
    settings: ReportSettings | None = None,
) -> dict[str, Any] | None:
    """The check rail's lateral dynamic stiffness, FE (bracket) vs co-running, at its entry.

    At the end of the entry flare of the first report route that has a check-rail contact
    (where the wheel strikes it, :func:`~exudyn_turnout.passage.events.check_rail_event`;
    routes whose lateral force is plotted first),
    1 / |H(f)| at :data:`CHECK_RAIL_FREQUENCIES` of: the torsion-aware FE check rail on its
    L-bracket at the gauge corner (the FE passages' track), and the co-running slot with
    the check rail derived from it (``check_rail="bracket"``, the default when the file
    has ``[check_rail.co_running]``) and from Table 1 like a running rail (``"table1"``).

    Parameters
    ----------
    turnout : Turnout
    config : ReportConfig
        FE mesh.
    cache : ResultCache
        Where the FE values are stored.
    settings : ReportSettings, optional

    Returns
    -------
    dict or None
        JSON-ready; None when no report route has a check rail.
    """
    from exudyn_turnout.corunning.check_rail import check_rail_model
    from exudyn_turnout.corunning.fit import model_receptance
    from exudyn_turnout.corunning.parameters import co_running_parameters
    from exudyn_turnout.fe.check_rail_receptance import check_rail_receptance
    from exudyn_turnout.fe.frf import resolve_rail
    from exudyn_turnout.fe.layout import load_layout
    from exudyn_turnout.passage.events import check_rail_event

    settings = settings or report_settings(turnout)
    # the routes whose lateral force is plotted first (the paper's Fig. 8: the diverging one)
    routes = sorted(settings.routes, key=lambda r: "Fy" not in r.forces)
    found = next(
        ((r, e) for r in routes if (e := check_rail_event(turnout, r.name)) is not None), None
    )
    if found is None:
        return None
    route, event = found
    slot, x = str(event["rail"]), float(event["entry_m"][1])  # type: ignore[index]
    rail_id = resolve_rail(load_layout(turnout), slot, x, route.fe_slots)
    f = np.asarray(CHECK_RAIL_FREQUENCIES)
    key = input_key(
        "fe_check_rail",
        turnout_fingerprint(turnout),
        code_fingerprint(RESULT_STAGES),
        rail_id,
        x,
        f,
        config.fe_options,
    )
    hit = cache.load(key)
    if hit is not None:
        H_fe = hit[0]["H"][:, 0]
    else:
        H = check_rail_receptance(turnout, rail_id, [x], f, config.fe_options)
        cache.save(key, {"H": H}, {"computed": time.strftime("%Y-%m-%d %H:%M")})
        H_fe = H[:, 0]
    models = {"FE (L-bracket, gauge corner)": [float(v) for v in 1.0 / np.abs(H_fe)]}
    kinds = [("bracket", "bracket")] if check_rail_model(turnout, None) == "bracket" else []
    for model, label in kinds + [("table1", "Table 1")]:
        for layers in (2, 3):
            params = co_running_parameters(turnout, x=x, layers=layers, check_rail=model)
            H = model_receptance(params, x, slot, "lateral", f)
            models[f"{layers}-layer, {label}"] = [float(v) for v in 1.0 / np.abs(H)]
    return {
        "route": route.name,
        "rail": slot,
        "fe_rail": rail_id,
        "x_m": x,
        "frequencies_hz": list(CHECK_RAIL_FREQUENCIES),
        "dynamic_stiffness_N_per_m": models,
    }
