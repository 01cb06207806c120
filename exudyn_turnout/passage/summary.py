"""What a passage gives, in numbers: the plausibility stop, peaks and summaries.

Pure numpy (no Exudyn): :func:`check_plausible` and :func:`stop_on_derailment` (stop a run
that left every physical state or derailed), :func:`passage_summary` (peaks per region,
contact losses, safety and comfort), :func:`vehicle_summary` and :func:`body_summary` (the
full vehicle's wheelsets and bodies), :func:`static_loads_of` (the static wheel loads a
summary or its columns give).
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping

import numpy as np

from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.inputs.vehicle_model import VehicleModel
from exudyn_turnout.passage.events import event_summary, peak_in
from exudyn_turnout.passage.ride_comfort import comfort_summary
from exudyn_turnout.passage.safety import (
    SAFETY_LIMITS,
    SafetyLimits,
    SafetyStop,
    check_safety,
    derailment_message,
    first_derailment,
    limits_record,
    safety_summary,
    wheel_labels,
)
from exudyn_turnout.passage.settings import (
    PLAUSIBLE,
    PassageFailure,
    PassageSettings,
    settings_record,
)

__all__ = [
    "check_plausible",
    "stop_on_derailment",
    "passage_summary",
    "static_loads_of",
    "vehicle_summary",
    "body_summary",
]


def check_plausible(
    columns: Mapping[str, np.ndarray],
    static_load: float,
    what: str = "",
    limits: SafetyLimits = SAFETY_LIMITS,
) -> None:
    """Stop a run that left every physical state (limits in :data:`PLAUSIBLE`).

    Parameters
    ----------
    columns : mapping
        Columns of a passage (or of one zone's part): ``t_s``, ``x_m``, ``z_wheelset_m``,
        ``y_wheelset_m``, ``z_rail_<slot>_m``, ``Fz_<wheel>_N``.
    static_load : float
        Static wheel load (N); forces above ``PLAUSIBLE["force_over_static"]`` times it stop
        the run.
    what : str
        Where (e.g. "zone 2, crossing panel"), put into the message.
    limits : SafetyLimits
        Of the climbing and lift stop (the vehicle's friction:
        :func:`~exudyn_turnout.passage.safety.limits_for_friction`).

    Raises
    ------
    PassageFailure
        At the first sample beyond a limit: its time, x, the quantity and its value; or a
        lifting or climbing wheel (:func:`~exudyn_turnout.passage.safety.check_safety`:
        no contact over more than 2 m of track, or Y/Q over the last 2 m above Nadal's
        limit with the flange in contact), naming the wheel.
    """
    t, x = columns["t_s"], columns["x_m"]
    checks = []
    for name in ("z_wheelset_m", "y_wheelset_m"):
        if name in columns:
            label = "wheelset " + name[0]
            checks.append((name, label, columns[name], PLAUSIBLE["wheelset_m"], "m"))
    for name, values in columns.items():
        if name.startswith("z_rail_"):
            checks.append((name, f"rail {name[7:-2]} deflection", values, PLAUSIBLE["rail_m"], "m"))
    limit = PLAUSIBLE["force_over_static"] * abs(static_load)
    for wheel in ("right", "left"):
        if f"Fz_{wheel}_N" in columns and limit > 0:
            label = f"{wheel} wheel's normal force"
            checks.append((wheel, label, columns[f"Fz_{wheel}_N"], limit, "N"))
    first = None
    for _, label, values, bound, unit in checks:
        with np.errstate(invalid="ignore"):
            bad = np.nonzero(np.abs(np.nan_to_num(values, nan=0.0)) > bound)[0]
        if bad.size and (first is None or bad[0] < first[0]):
            first = (int(bad[0]), label, float(values[bad[0]]), bound, unit)
    derailment = first_derailment(columns, static_load, limits) if static_load > 0 else None
    if first is not None and (derailment is None or t[first[0]] <= derailment[0]):
        i, label, value, bound, unit = first
        where = f" ({what})" if what else ""
        raise PassageFailure(
            f"implausible run stopped at t = {t[i]:.5f} s, x = {x[i]:.3f} m{where}: "
            f"{label} {value:.4g} {unit} is beyond the physical limit {bound:.4g} {unit}"
        )
    if derailment is not None:
        raise PassageFailure(derailment_message(derailment, what))


def stop_on_derailment(
    columns: Mapping[str, np.ndarray],
    static_load: float,
    what: str = "",
    limits: SafetyLimits = SAFETY_LIMITS,
) -> None:
    """Stop a lifting or climbing wheel (:func:`~exudyn_turnout.passage.safety.check_safety`).

    Parameters
    ----------
    columns : mapping
        ``t_s``, ``x_m`` and the wheel forces of a passage or of a part of it.
    static_load : float
        N, static wheel load.
    what : str
        Where, put into the message.
    limits : SafetyLimits

    Raises
    ------
    PassageFailure
        Naming t, x, the wheel and the quantity (the CLI's exit 3).
    """
    if static_load <= 0 or "t_s" not in columns:
        return
    try:
        check_safety(columns, static_load, what, limits)
    except SafetyStop as err:
        raise PassageFailure(str(err)) from None


def _peak(
    cols: Mapping[str, np.ndarray], name: str, x_range: tuple[float, float], signed: bool = False
) -> float:
    x = cols["x_m"]
    sel = (x >= x_range[0]) & (x <= x_range[1])
    if not sel.any():
        return math.nan
    values = cols[name][sel]
    return float(values[np.argmax(np.abs(values))] if signed else values.max())


def _contact_losses(fz: np.ndarray) -> int:
    """Number of times a wheel lost all contact (its total normal force fell to zero)."""
    loaded = fz > 0.0
    return int(np.count_nonzero(loaded[:-1] & ~loaded[1:]))


def _regions(turnout: Turnout) -> dict[str, tuple[float, float]]:
    """Regions of the turnout file where peaks are taken (``switch``, ``crossing``)."""
    return {name: turnout.regions[name] for name in ("switch", "crossing")}


def _argpeak(
    cols: Mapping[str, np.ndarray], name: str, x_range: tuple[float, float], signed: bool
) -> tuple[float, float]:
    """(peak, x of the peak) of column ``name`` in x_range; (nan, nan) if none (or all NaN)."""
    return peak_in(np.asarray(cols["x_m"]), np.asarray(cols[name]), x_range, signed)


def _contact_peaks(
    columns: Mapping[str, np.ndarray], regions: Mapping[str, tuple[float, float]]
) -> dict[str, object]:
    """Peaks per wheel and per contact (rail slot), and which wheel and rail carry each largest one.

    Keys: ``peak_<Fz|Fy>_<region>_<wheel>_<slot>_N`` (every wheel/rail pair of the run),
    ``peak_<Fz|Fy>_<region>_<wheel>_N`` (per wheel, both wheels), and for the largest
    (|Fy| for Fy) of the region ``max_<Fz|Fy>_<region>_N``, ``_wheel``, ``_rail``, ``_x_m``.
    """
    out: dict[str, object] = {}
    pairs = [n[3:-2].split("_") for n in columns if n.startswith("Fz_") and n.count("_") == 3]
    for q, signed in (("Fz", False), ("Fy", True)):
        for where, rng in regions.items():
            best = None
            for wheel in ("right", "left"):
                peak = _argpeak(columns, f"{q}_{wheel}_N", rng, signed)[0]
                out[f"peak_{q}_{where}_{wheel}_N"] = peak
            for wheel, slot in pairs:
                name = f"{q}_{wheel}_{slot}_N"
                if name not in columns:
                    continue
                value, x = _argpeak(columns, name, rng, signed)
                out[f"peak_{q}_{where}_{wheel}_{slot}_N"] = value
                if wheel not in ("right", "left"):  # a full vehicle's ws<k>_<side> total:
                    continue  # its peak is kept, the largest is the front wheelset's contact
                if math.isfinite(value) and (best is None or abs(value) > abs(best[0])):
                    best = (value, wheel, slot, x)
            value, wheel_of, rail_of, x_of = best or (math.nan, None, None, math.nan)
            out[f"max_{q}_{where}_N"], out[f"max_{q}_{where}_wheel"] = value, wheel_of
            out[f"max_{q}_{where}_rail"], out[f"max_{q}_{where}_x_m"] = rail_of, x_of
    return out


def passage_summary(
    columns: Mapping[str, np.ndarray],
    turnout: Turnout,
    settings: PassageSettings,
    static_loads: Mapping[str, float],
    wall_time: float,
    limits: SafetyLimits = SAFETY_LIMITS,
) -> dict[str, object]:
    """Peaks at the switch and crossing, per wheel and per contact, safety, the settings.

    ``peak_Fz_switch_N`` etc. are the right wheel's (as the paper's Figs 7, 8), ``_left``
    keys the left wheel's; per wheel ``peak_Fz_crossing_<wheel>_N``, per wheel and contact
    (rail slot) ``peak_Fz_crossing_<wheel>_<slot>_N``, and ``max_Fz_crossing_N`` with
    ``_wheel``, ``_rail``, ``_x_m``: which wheel and rail carry the largest force (on the
    diverging route the left wheel meets the crossing); the same for Fy (largest |Fy|).

    Parameters
    ----------
    columns : mapping
        The passage's columns.
    turnout : Turnout
        Its ``[regions]``.
    settings : PassageSettings
        Stored under ``settings``.
    static_loads : mapping
        Static load (N) of each wheel, "left" and "right".
    wall_time : float
        s.
    limits : SafetyLimits
        Limits of the safety quantities and of the derailment stop.

    Returns
    -------
    dict
        Also the safety and wear quantities per wheel and region (``run`` the whole run) of
        :func:`~exudyn_turnout.passage.safety.safety_summary` (``YQ_peak_<region>_<wheel>``,
        ``YQ_2m_peak_...``, ``sumY_2m_peak_<region>_N``, ``dQ_Q0_max_...``,
        ``contact_loss_..._m``, ``Tgamma_peak_..._N``...), ``safety_exceeded`` (list of
        the limits exceeded: wheel, region, quantity, value, limit, x_m) and
        ``safety_limits``.

    Raises
    ------
    PassageFailure
        A wheel lifted or climbing (:func:`stop_on_derailment` on the whole run).
    """

    regions = _regions(turnout)
    out: dict[str, object] = {
        "route": settings.route,
        "layers": settings.layers,
        "source": settings.source,
        "speed_kmh": settings.speed_kmh,
        "static_wheel_load_N": float(static_loads["right"]),
        "static_wheel_load_left_N": float(static_loads["left"]),
    }
    for wheel, suffix in (("right", ""), ("left", "_left")):
        for where, rng in regions.items():
            out[f"peak_Fz_{where}{suffix}_N"] = _peak(columns, f"Fz_{wheel}_N", rng)
            out[f"peak_Fy_{where}{suffix}_N"] = _peak(columns, f"Fy_{wheel}_N", rng, signed=True)
    out.update(_contact_peaks(columns, regions))
    out.update(event_summary(columns, turnout, settings.route, static_loads))
    out["contact_losses"] = sum(_contact_losses(columns[f"Fz_{w}_N"]) for w in ("right", "left"))
    out["time_step_s"] = settings.time_step
    h_out = settings.output_step
    out["output_step_s"] = h_out if h_out is not None else settings.time_step
    out["x_start_m"], out["x_end_m"] = float(columns["x_m"][0]), float(columns["x_m"][-1])
    out["simulated_time_s"] = float(columns["t_s"][-1] - columns["t_s"][0])
    out["wall_time_s"] = wall_time
    out["switch_region_m"], out["crossing_region_m"] = (
        list(regions["switch"]),
        list(regions["crossing"]),
    )
    out["settings"] = settings_record(settings)
    loads = {"": {w: float(static_loads[w]) for w in ("right", "left")}}
    _add_safety(out, columns, loads, regions, limits)
    stop_on_derailment(columns, 0.5 * (loads[""]["right"] + loads[""]["left"]), "", limits)
    return out


def _add_safety(
    out: dict[str, object],
    columns: Mapping[str, np.ndarray],
    loads: Mapping[str, Mapping[str, float]],
    regions: Mapping[str, tuple[float, float]],
    limits: SafetyLimits,
) -> None:
    """Put the safety quantities, the limits exceeded and the limits into a summary."""
    values, exceeded = safety_summary(columns, loads, regions, limits)
    out.update(values)
    out["safety_exceeded"] = exceeded
    out["safety_limits"] = limits_record(limits)


def static_loads_of(
    summary: Mapping[str, object], columns: Mapping[str, np.ndarray]
) -> dict[str, dict[str, float]]:
    """Static wheel loads per wheelset label, as the summary records them.

    Parameters
    ----------
    summary : mapping
        ``static_wheel_load_N``, ``static_wheel_load_left_N`` and (full vehicle)
        ``static_wheel_load_ws<i>_<wheel>_N``.
    columns : mapping
        The passage's columns (which wheelsets there are).

    Returns
    -------
    dict
        ``""`` (the single or front wheelset) and ``ws<i>`` -> {"right", "left"} -> N;
        only labels whose loads are in the summary and are > 0.
    """
    out: dict[str, dict[str, float]] = {}
    keys: dict[str, tuple[str, ...]] = {"": ("static_wheel_load_N", "static_wheel_load_left_N")}
    for label in wheel_labels(columns):
        if label:
            keys[label] = tuple(f"static_wheel_load_{label}_{w}_N" for w in ("right", "left"))
    for label, (right, left) in keys.items():
        r, lft = summary.get(right), summary.get(left)
        if isinstance(r, (int, float)) and isinstance(lft, (int, float)) and r > 0 and lft > 0:
            out[label] = {"right": float(r), "left": float(lft)}
    return out


def vehicle_summary(
    turnout: Turnout,
    settings: PassageSettings,
    model: VehicleModel,
    columns: Mapping[str, np.ndarray],
    static_loads: list,
    wall: float,
    limits: SafetyLimits = SAFETY_LIMITS,
) -> dict:
    """Summary of a full vehicle's passage: the front wheelset's, then per wheelset peaks.

    Parameters
    ----------
    turnout : Turnout
    settings : PassageSettings
    model : VehicleModel
    columns : mapping
        The run's columns (``Fz_wsk_<wheel>_N``, ``x_wsk_m``...).
    static_loads : list of dict
        Per wheelset, "left" and "right" static wheel loads (N).
    wall : float
        s, ``time.perf_counter()`` at the start of the run.
    limits : SafetyLimits
        Of the safety quantities (the vehicle's friction:
        :func:`~exudyn_turnout.passage.safety.limits_for_friction`).

    Returns
    -------
    dict
        :func:`~exudyn_turnout.passage.summary.passage_summary` of the front wheelset plus
        ``peak_<Fz|Fy>_<region>_wsk_<wheel>_N``, ``static_wheel_load_wsk_<wheel>_N``,
        the safety quantities of every wheelset (``YQ_peak_<region>_wsk_<wheel>``...,
        ``safety_exceeded`` naming ``wsk``), the body accelerations' and suspension forces'
        peaks (:func:`body_summary`), the ride comfort
        (:func:`~exudyn_turnout.passage.ride_comfort.comfort_summary`), ``vehicle`` and
        ``wheelsets``.

    Raises
    ------
    PassageFailure
        A wheel of any wheelset lifted or climbing (:func:`stop_on_derailment`).
    """
    front = static_loads[0]
    summary = passage_summary(columns, turnout, settings, front, time.perf_counter() - wall, limits)
    regions = {name: turnout.regions[name] for name in ("switch", "crossing")}
    for i, loads in enumerate(static_loads):
        label = f"ws{i + 1}"
        own = {"x_m": columns[f"x_{label}_m"]}
        for wheel in ("right", "left"):
            summary[f"static_wheel_load_{label}_{wheel}_N"] = float(loads[wheel])
            for q, signed in (("Fz", False), ("Fy", True)):
                own[f"{q}_{wheel}"] = columns[f"{q}_{label}_{wheel}_N"]
                for where, rng in regions.items():
                    summary[f"peak_{q}_{where}_{label}_{wheel}_N"] = _peak(
                        own, f"{q}_{wheel}", rng, signed
                    )
    loads = {
        f"ws{i + 1}": {w: float(ld[w]) for w in ("right", "left")}
        for i, ld in enumerate(static_loads)
    }
    _add_safety(summary, columns, loads, regions, limits)  # the list: per wsk
    for label, ld in loads.items():
        own = {"t_s": columns["t_s"], "x_m": columns[f"x_{label}_m"]}
        for q in ("Fz", "Fy"):
            for wheel in ("right", "left"):
                own[f"{q}_{wheel}_N"] = columns[f"{q}_{label}_{wheel}_N"]
        stop_on_derailment(own, 0.5 * (ld["right"] + ld["left"]), f"wheelset {label[2:]}", limits)
    summary.update(body_summary(columns))
    summary.update(comfort_summary(columns))
    summary["vehicle"] = model.name
    summary["wheelsets"] = len(static_loads)
    return summary


def body_summary(columns: Mapping[str, np.ndarray]) -> dict[str, float]:
    """Peaks of the full vehicle's body accelerations and suspension forces over the run.

    Parameters
    ----------
    columns : mapping
        A full vehicle's columns
        (:mod:`~exudyn_turnout.passage.vehicle.body_outputs`).

    Returns
    -------
    dict
        ``peak_ay_<point>_mps2``, ``peak_az_<point>_mps2`` (the largest magnitude, with its
        sign) per body point; over all axleboxes (primary) and all bogie sides (secondary):
        ``Fz_<primary|secondary>_min_N``, ``Fz_<...>_max_N`` (least and most load carried),
        ``Fy_<...>_peak_N`` (largest magnitude, signed); ``Fy_bumpstop_peak_N``. Empty
        without body columns.
    """

    def signed_peak(values: np.ndarray) -> float:
        v = np.nan_to_num(np.asarray(values, dtype=float))
        return float(v[np.argmax(np.abs(v))]) if v.size else math.nan

    out: dict[str, float] = {}
    for name, values in columns.items():
        if name.startswith(("ay_", "az_")) and name.endswith("_mps2"):
            out[f"peak_{name}"] = signed_peak(values)
    for stage in ("primary", "secondary"):
        vertical = [
            np.asarray(v, float) for n, v in columns.items() if n.startswith(f"Fz_{stage}_")
        ]
        lateral = [np.asarray(v, float) for n, v in columns.items() if n.startswith(f"Fy_{stage}_")]
        if vertical:
            out[f"Fz_{stage}_min_N"] = float(min(np.nanmin(v) for v in vertical))
            out[f"Fz_{stage}_max_N"] = float(max(np.nanmax(v) for v in vertical))
        if lateral:
            out[f"Fy_{stage}_peak_N"] = signed_peak(np.concatenate(lateral))
    stops = [np.asarray(v, float) for n, v in columns.items() if n.startswith("Fy_bumpstop_")]
    if stops:
        out["Fy_bumpstop_peak_N"] = signed_peak(np.concatenate(stops))
    return out
