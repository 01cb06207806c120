"""Section 3 of the validation report: contact forces (the paper's Figs 7, 8 analogue).

The 2-layer, 3-layer and FE passages of every report route with one vehicle (the full
Manchester vehicle or the single wheelset) and the profile contact, the FE passage cached
on disk; peaks, dynamic RMS and the differences against the FE reference, vertical and
lateral, at the switch and the crossing (:func:`passage_section`).
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from dataclasses import replace
from typing import Any, SupportsFloat, SupportsInt, cast

import numpy as np

from exudyn_turnout.inputs.routes import load_route
from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.inputs.vehicle import load_vehicle
from exudyn_turnout.report import agreement as ag
from exudyn_turnout.report.cache import (
    RESULT_STAGES,
    ResultCache,
    code_fingerprint,
    input_key,
)
from exudyn_turnout.report.config import (
    FENotAvailable,
    ReportConfig,
    log,
    turnout_fingerprint,
)
from exudyn_turnout.report.criteria import Criteria
from exudyn_turnout.report.passage_api import (
    PassageResult,
    PassageSettings,
    fe_passage_options,
    nose_region,
    run_track_passage,
)
from exudyn_turnout.report.settings import (
    FORCES,
    REGIONS,
    ReportSettings,
    report_settings,
)

__all__ = [
    "passage_section",
    "passage_model_metrics",
    "fe_availability",
    "vehicle_static_load",
    "run_passage",
    "fe_passage_cache_key",
    "FE_PASSAGE_VERSION",
    "EVENT_REGIONS",
    "signal_key",
    "peak_key",
    "summary_float",
    "vehicle_mass",
]

#: Version of the report's FE passage (a new value invalidates every cached FE passage):
#: 2 = the FE track under the co-running passage's vehicle and profile contact, vertical and
#: lateral (:mod:`exudyn_turnout.passage.fe_track`); 1 was the vertical height-table one.
FE_PASSAGE_VERSION = 2


def _settings(turnout: Turnout, config: ReportConfig, route: str, layers: int) -> PassageSettings:
    """The report's passage on every track: the profile contact (S1002 on the turnout's rail
    sections), as the FE passage has it too, so that 2-layer, 3-layer and FE differ only in
    the track."""
    x = config.passage_x or (turnout.x_min, turnout.x_max)
    return PassageSettings(
        contact="profile",
        route=route,
        layers=layers,
        speed_kmh=_speeds(config)[route],
        x_start=x[0],
        x_end=x[1],
        time_step=config.time_step,
    )


def _fe_options(config: ReportConfig):
    """The FE passage's options with the report's FE mesh."""
    return fe_passage_options(config.fe_options)


def fe_availability(config: ReportConfig) -> tuple[bool, str]:
    """Whether the report's FE passage can run, and why not.

    Parameters
    ----------
    config : ReportConfig
        ``fe_passage`` and ``vehicle``.

    Returns
    -------
    (bool, str)
        True and "" when it can; False and the reason (one sentence) when not.
    """
    if not config.fe_passage:
        return False, "FE passage switched off in this report"
    return True, ""


def run_passage(
    turnout: Turnout, config: ReportConfig, route: str, track: str, settings=None
) -> PassageResult:
    """One passage of the report: ``config.vehicle`` on ``track`` with the profile contact.

    Parameters
    ----------
    turnout : Turnout
    config : ReportConfig
        Resolved (:func:`resolve_config`): speeds, x range, time step, vehicle, FE mesh.
    route : str
        A report route.
    track : {"2-layer", "3-layer", "fe"}
        The track under the vehicle.
    settings : PassageSettings, optional
        Default: the report's settings of the route (profile contact); given, e.g., with a
        halved time step for the convergence check.

    Returns
    -------
    PassageResult
        The single wheelset's, or the full vehicle's (the front wheelset's forces under the
        single-wheelset column names).

    """
    layers = 3 if track == "fe" else int(track[0])
    settings = replace(settings or _settings(turnout, config, route, layers), layers=layers)
    return run_track_passage(turnout, settings, config.vehicle, track, config.fe_options)


def _timed_co_running(
    turnout: Turnout, config: ReportConfig, route: str
) -> tuple[dict[str, PassageResult], dict[str, list[float]]]:
    """2- and 3-layer passages, each run ``timing_repeats`` times interleaved: the run with the best
    wall time per model, and every run's wall time (s)."""
    best: dict[str, PassageResult] = {}
    walls: dict[str, list[float]] = {"2-layer": [], "3-layer": []}
    # one untimed run first: it loads the route's contact tables (built once per machine,
    # then read from disk), which would otherwise count against the first timed run
    run_passage(turnout, config, route, "2-layer", _warm_up_settings(turnout, config, route))
    for _ in range(config.timing_repeats):
        for name in ("2-layer", "3-layer"):
            r = run_passage(turnout, config, route, name)
            walls[name].append(summary_float(r.summary, "wall_time_s"))
            if name not in best or summary_float(r.summary, "wall_time_s") < summary_float(
                best[name].summary, "wall_time_s"
            ):
                best[name] = r
    return best, walls


def _warm_up_settings(turnout: Turnout, config: ReportConfig, route: str) -> PassageSettings:
    """The report's settings of the route over its first 0.2 m (loads what the runs share)."""
    settings = _settings(turnout, config, route, 2)
    assert settings.x_start is not None
    return replace(settings, x_end=min(settings.x_start + 0.2, settings.x_end or turnout.x_max))


def fe_passage_cache_key(
    turnout: Turnout, settings: PassageSettings, config: ReportConfig, fe_slots: str | None = None
) -> str:
    """Cache key of the report's FE passage.

    The turnout file's content, the passage settings (route, speed, x range, time step and
    the contact model), the vehicle (``config.vehicle`` and, for the full vehicle, its
    packaged file's content), the FE passage's options (mesh), :data:`FE_PASSAGE_VERSION`
    and every file of the stage folders a passage can execute
    (:func:`~exudyn_turnout.report.cache.code_fingerprint` of
    :data:`~exudyn_turnout.report.cache.RESULT_STAGES`): a height-table FE result, one of
    another vehicle, or one of other code, is never reused.

    Parameters
    ----------
    turnout : Turnout
    settings : PassageSettings
        The FE passage's settings.
    config : ReportConfig
        ``vehicle`` and ``fe_options``.
    fe_slots : str, optional
        The route's ``[layout.slots]`` key (default: the route's name).

    Returns
    -------
    str
        64 hex digits (:func:`~exudyn_turnout.report.cache.input_key`).
    """
    fe_slots = fe_slots or settings.route
    parts = () if fe_slots == settings.route else (fe_slots,)
    return input_key(
        "fe_passage",
        FE_PASSAGE_VERSION,
        turnout_fingerprint(turnout),
        code_fingerprint(RESULT_STAGES),
        settings,
        config.vehicle,
        _vehicle_fingerprint(config.vehicle),
        _fe_options(config),
        *parts,
    )


def _vehicle_fingerprint(vehicle: str) -> str:
    """SHA-256 of the vehicle file the report loads ("" for the packaged wheelset, whose data
    are in the code of :mod:`exudyn_turnout.inputs.vehicle`, part of the source fingerprint)."""
    if vehicle != "full":
        return ""
    from exudyn_turnout.inputs.vehicle_model import load_vehicle_model

    return input_key(load_vehicle_model())


def _cached_fe_passage(
    turnout: Turnout,
    settings: PassageSettings,
    config: ReportConfig,
    cache: ResultCache,
    fe_slots: str | None = None,
) -> tuple[PassageResult, dict[str, Any]]:
    """FE passage (computed or from the cache); ``fe_slots``: the route's ``[layout.slots]`` key."""
    if fe_slots and fe_slots != settings.route:
        raise FENotAvailable(
            f"the FE passage couples to [layout.slots.{settings.route}]; the report's fe_slots "
            f"{fe_slots!r} is not supported by the FE passage with the profile contact"
        )
    key = fe_passage_cache_key(turnout, settings, config, fe_slots)
    hit = cache.load(key)
    if hit is not None:
        arrays, meta = hit
        result = PassageResult(
            settings,
            {k: np.asarray(v) for k, v in arrays.items()},
            meta["summary"],
            tuple(meta["zone_starts"]),
        )
        return result, {"cached": True, "computed": meta["computed"]}
    result = run_passage(turnout, config, settings.route, "fe", settings)
    info = {"cached": False, "computed": time.strftime("%Y-%m-%d %H:%M")}
    cache.save(
        key,
        dict(result.columns),
        {"summary": dict(result.summary), "zone_starts": list(result.zone_starts), **info},
    )
    return result, info


#: Event regions taken from the geometry (:mod:`exudyn_turnout.passage.events`) whose peaks
#: the passage summary carries beside the file's ``[regions]``: the crossing nose.
EVENT_REGIONS = ("nose",)


def signal_key(q: str, where: str) -> str:
    """Name of a force signal in the metrics, e.g. ``"Fz_crossing"``.

    Parameters
    ----------
    q : {"Fz", "Fy"}
        The force.
    where : {"switch", "crossing"}
        The region.

    Returns
    -------
    str
    """
    return f"{q}_{where}"


def _column(q: str, wheel: str) -> str:
    """Time-history column of force ``q`` ("Fz", "Fy") on ``wheel`` ("right", "left")."""
    return f"{q}_{wheel}_N"


def peak_key(q: str, where: str, wheel: str) -> str:
    """Passage summary key of the peak of ``q`` in region ``where`` for ``wheel``.

    Parameters
    ----------
    q : {"Fz", "Fy"}
        The force.
    where : {"switch", "crossing"}
        The region.
    wheel : {"right", "left"}

    Returns
    -------
    str
        E.g. ``"peak_Fz_crossing_N"`` (right wheel), ``"peak_Fz_crossing_left_N"``.
    """
    return f"peak_{q}_{where}_N" if wheel == "right" else f"peak_{q}_{where}_{wheel}_N"


def passage_model_metrics(
    result: PassageResult,
    signals,
    regions: Mapping[str, tuple[float, float]],
    criteria: Criteria,
    static_load: float,
    reference: PassageResult | None = None,
    wheel: str = "right",
) -> dict:
    """Peaks, oscillation (dynamic RMS) and, given the FE ``reference``, the differences from it.

    Parameters
    ----------
    result : PassageResult
    signals : sequence of (str, str)
        (force "Fz"/"Fy", region "switch"/"crossing") of ``wheel``.
    regions : mapping
        region -> (x_from, x_to) in m.
    criteria : Criteria
        ``trend_window`` for the running mean.
    static_load : float
        N, the static wheel load the trend deviation is relative to.
    reference : PassageResult, optional
    wheel : {"right", "left"}
        The wheel whose forces are taken (the report route's ``wheel``).

    Returns
    -------
    dict
        JSON-ready: ``peaks_N``, ``dynamic_rms_N``, contact losses, static load, times and,
        with a reference, ``vs_FE``.
    """
    s, c, w = result.summary, result.columns, criteria.trend_window
    events = tuple(e for e in EVENT_REGIONS if f"{e}_region_m" in s)
    out: dict[str, Any] = {
        "peaks_N": {
            signal_key(q, r): _number(s, peak_key(q, r, wheel))
            for q in FORCES
            for r in REGIONS + events
        },
        "dynamic_rms_N": {
            signal_key(q, r): ag.dynamic_rms(c["x_m"], c[_column(q, wheel)], w, regions[r])
            if _column(q, wheel) in c
            else math.nan
            for q, r in signals
        },
        "contact_losses": int(cast(SupportsInt, s.get("contact_losses", -1))),
        "static_wheel_load_N": _number(s, "static_wheel_load_N"),
        "wall_time_s": _number(s, "wall_time_s"),
        "simulated_time_s": _number(s, "simulated_time_s"),
    }
    if "peak_Fy_check_rail_N" in s:
        out["check_rail"] = {
            "wheel": s["check_rail_wheel"],
            "rail": s["check_rail_rail"],
            "region_m": list(cast(list, s["check_rail_region_m"])),
            "peak_Fy_N": _number(s, "peak_Fy_check_rail_N"),
            "x_m": _number(s, "peak_Fy_check_rail_x_m"),
            "impulse_Ns": _number(s, "check_rail_impulse_Ns"),
            "min_tread_Fz_N": _number(s, "check_rail_min_tread_Fz_N"),
            "tread_unloaded": bool(s.get("check_rail_tread_unloaded")),
        }
    if reference is not None:
        out["vs_FE"] = _vs_reference(result, reference, signals, regions, w, static_load, wheel)
        for e in events:  # the events' peaks against FE (F6 is judged at the nose)
            for q in FORCES:
                key, ref = peak_key(q, e, wheel), _number(reference.summary, peak_key(q, e, wheel))
                if math.isfinite(ref) and math.isfinite(_number(s, key)):
                    out["vs_FE"]["peak_relative"][signal_key(q, e)] = ag.relative_difference(
                        abs(_number(s, key)), abs(ref)
                    )
    return out


def summary_float(summary: Mapping[str, object], key: str) -> float:
    """summary[key] as a float: a passage summary holds numbers and text, this key a number.

    Parameters
    ----------
    summary : mapping
        A passage's summary.
    key : str
        A key of a number.

    Returns
    -------
    float
    """
    return float(cast(SupportsFloat, summary[key]))


def _speeds(config: ReportConfig) -> dict[str, float]:
    """km/h per route of a config resolved by :func:`resolve_config` (which fills them)."""
    assert config.speeds_kmh is not None, "report config not resolved (resolve_config)"
    return dict(config.speeds_kmh)


def _number(summary: Mapping[str, Any], key: str) -> float:
    """summary[key] as a float; NaN if absent or None (lateral peaks of a vertical-only model)."""
    v = summary.get(key)
    return math.nan if v is None else float(v)


def _vs_reference(
    result, reference, signals, regions, window, static_load, wheel: str = "right"
) -> dict[str, Any]:
    """Differences from the reference for the signals it has (a finite peak and the column)."""
    c, rc, rs = result.columns, reference.columns, reference.summary
    pairs = [
        (signal_key(q, r), _column(q, wheel), regions[r], peak_key(q, r, wheel))
        for q, r in signals
        if _column(q, wheel) in rc and math.isfinite(_number(rs, peak_key(q, r, wheel)))
    ]
    return {
        # |peak| / |peak_FE| - 1: the lateral peaks are signed (largest magnitude), so a
        # larger force in the negative direction counts as larger, as a vertical one would
        "peak_relative": {
            k: ag.relative_difference(abs(float(result.summary[p])), abs(float(rs[p])))
            for k, _, _, p in pairs
        },
        "rms_difference_N": {
            k: ag.rms_difference(c["x_m"], c[col], rc["x_m"], rc[col], rng)
            for k, col, rng, _ in pairs
        },
        "trend_deviation": {
            k: ag.max_trend_difference(c["x_m"], c[col], rc["x_m"], rc[col], window, rng)
            / static_load
            for k, col, rng, _ in pairs
        },
    }


def passage_section(
    turnout: Turnout,
    config: ReportConfig,
    cache: ResultCache,
    settings: ReportSettings | None = None,
) -> tuple[dict, dict]:
    """Every report route, 2-layer, 3-layer and (if available) FE: (metrics, route -> model -> run).

    Parameters
    ----------
    turnout : Turnout
    config : ReportConfig
        Resolved (:func:`resolve_config`): its speeds name every report route.
    cache : ResultCache
        Where FE passages are stored.
    settings : ReportSettings, optional
        Default :func:`~exudyn_turnout.report.settings.report_settings` of the turnout: the
        routes, their wheel, plotted forces and ``[layout.slots]`` key, the regions.

    Returns
    -------
    (dict, dict)
        JSON-ready metrics, and route -> model ("2-layer", "3-layer", "FE") -> PassageResult.
    """
    settings = settings or report_settings(turnout)
    fe_ok, why = fe_availability(config)
    regions = dict(settings.regions)
    nose = nose_region(turnout)
    static = vehicle_static_load(config.vehicle)
    every = tuple((q, r) for q in FORCES for r in REGIONS)
    metrics: dict[str, Any] = {
        "speeds_kmh": _speeds(config),
        "regions_m": {**regions, **({"nose": nose} if nose is not None else {})},
        "routes": {},
        "steady_lateral_acceleration_m_s2": _lateral_acceleration(turnout, config),
        "radius_m": {r.name: r.radius for r in settings.routes},
        "speeds_note": settings.speeds_note,
        "impact_route": settings.impact_route,
        "lateral_route": settings.lateral_route,
        "fe_available": fe_ok,
        "fe_note": why,
        "wheel": {r.name: r.wheel for r in settings.routes},
        "x_range_m": list(config.passage_x or (turnout.x_min, turnout.x_max)),
        "contact": "profile",
        "vehicle": config.vehicle,
        "vehicle_name": _vehicle_name(config.vehicle),
        "static_wheel_load_N": static,
        "fe_coupling": "exact one-step co-simulation (exudyn_turnout.passage.fe_track.coupling)",
    }
    results: dict[str, dict[str, PassageResult]] = {}
    for rr in settings.routes:
        route = rr.name
        results[route], walls = _timed_co_running(turnout, config, route)
        fe_info = None
        if fe_ok:
            fe_result, fe_info = _run_fe_passage(
                turnout, _settings(turnout, config, route, 3), config, cache, rr.fe_slots
            )
            if fe_result is not None:
                results[route]["FE"] = fe_result
        ref = results[route].get("FE")
        models = {
            m: passage_model_metrics(
                res, every, regions, config.criteria, static, ref if m != "FE" else None, rr.wheel
            )
            for m, res in results[route].items()
        }
        metrics["routes"][route] = {
            "signals": [signal_key(q, r) for q, r in rr.signals],
            "all_signals": [signal_key(q, r) for q, r in every],
            "fe": fe_info,
            "models": models,
            "wheel": rr.wheel,
            "fe_compared": list(models["2-layer"].get("vs_FE", {}).get("peak_relative", {})),
            "co_running_wall_times_s": walls,
        }
        log(
            f"passages {route}: "
            + ", ".join(f"{m} {r.summary['wall_time_s']:.1f} s" for m, r in results[route].items())
        )
    return metrics, results


def vehicle_static_load(vehicle: str) -> float:
    """Static wheel load (N) of the report's vehicle on level track.

    Parameters
    ----------
    vehicle : {"full", "wheelset"}
        The full Manchester vehicle (M g / 8) or the single wheelset ((m_w + m_s) g / 2).

    Returns
    -------
    float
        N.
    """
    if vehicle == "full":
        from exudyn_turnout.inputs.vehicle_model import load_vehicle_model

        return float(load_vehicle_model().static_wheel_load)
    return float(load_vehicle().static_wheel_load)


def vehicle_mass(vehicle: str) -> float:
    """The mass the report's vehicle puts on the track.

    Parameters
    ----------
    vehicle : {"full", "wheelset"}

    Returns
    -------
    float
        kg, the full vehicle's total mass, or the single wheelset's m_w + m_s.
    """
    if vehicle == "full":
        from exudyn_turnout.inputs.vehicle_model import load_vehicle_model

        return float(load_vehicle_model().total_mass)
    v = load_vehicle()
    return float(v.m_w + v.m_s)


def _vehicle_name(vehicle: str) -> str:
    if vehicle == "full":
        from exudyn_turnout.inputs.vehicle_model import load_vehicle_model

        m = load_vehicle_model()
        return f"{m.name} ({m.n_wheelsets} wheelsets, {m.total_mass:.0f} kg)"
    return "Manchester benchmark wheelset under its sprung share"


def _lateral_acceleration(turnout: Turnout, config: ReportConfig) -> dict[str, float]:
    """v^2 |curvature|max (m/s^2) per route at the report's speeds (no cant)."""
    out = {}
    for route, v in _speeds(config).items():
        kappa = max(abs(k) for k in load_route(turnout, route).curvature.value)
        out[route] = (v / 3.6) ** 2 * kappa
    return out


def _run_fe_passage(turnout, settings, config, cache, fe_slots=None):
    try:
        return _cached_fe_passage(turnout, settings, config, cache, fe_slots)
    except FENotAvailable as err:
        log(f"FE passage n/a: {err}")
        return None, {"note": str(err)}
    except Exception as err:  # an FE passage that fails must not stop the report
        log(f"FE passage failed: {err!r}")
        return None, {"error": _one_line(err)}


def _one_line(err: Exception) -> str:
    """The error's type and message on one line, without a traceback that Exudyn appends
    (its ``At:`` block) to an error raised in a user function."""
    text = str(err).split("\nAt:")[0]
    lines = [x.strip() for x in text.splitlines() if x.strip()]
    return f"{type(err).__name__}: " + " ".join(lines)
