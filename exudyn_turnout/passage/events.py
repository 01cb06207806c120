"""Named events of a passage taken from the turnout's geometry: the crossing nose, the check rail.

The turnout file's ``[regions]`` are x ranges drawn by hand; on the UIC60-760-1:15 turnout
the "crossing" region (44.29-51 m) holds both the check rail's entry (44.29 m, where the
back of the flange of a wheelset curving towards the crossing meets the flare) and the
wing-rail-to-nose transfer (about 47 m). Their forces have different causes and different
remedies, so a peak taken over the whole region names neither. Two events are taken from
the geometry instead:

``nose``
    From :data:`NOSE_BEFORE` before the nose tip (the plan's
    :attr:`~exudyn_turnout.inputs.geometry.TurnoutPlan.nose_tip_x`) to :data:`NOSE_AFTER`
    after it: the wheel's descent on the wing rail, the transfer to the nose and the
    rebound (the paper's Figs 7 and 8 look there).
``check_rail``
    The check range of the route's check-rail contact (``[[routes.<route>.contacts]]``
    with ``check``): peak lateral force on the check rail, where, on which wheel, its
    impulse, whether the wheel's tread unloaded meanwhile.

Keys added to a passage summary (:func:`event_summary`): ``nose_region_m``,
``peak_Fz_nose_N`` / ``peak_Fy_nose_N`` (right wheel) and ``..._left_N``; with a check
rail ``check_rail_region_m``, ``check_rail_entry_m`` (the entry flare), ``check_rail_wheel``,
``check_rail_rail`` (slot), ``peak_Fy_check_rail_N`` (signed, largest magnitude, on the
check-rail contact), ``peak_Fy_check_rail_x_m``, ``check_rail_impulse_Ns`` (the integral of
|Fy| on the check rail over time), ``check_rail_min_tread_Fz_N`` (the least vertical force
of that wheel's other contacts in the region) and ``check_rail_tread_unloaded``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import SupportsFloat, cast

import numpy as np

from exudyn_turnout.inputs.geometry import turnout_plan
from exudyn_turnout.inputs.routes import load_route, route_names
from exudyn_turnout.inputs.turnout import Turnout, TurnoutFileError

__all__ = [
    "NOSE_BEFORE",
    "NOSE_AFTER",
    "TREAD_UNLOADED",
    "nose_region",
    "check_rail_event",
    "event_summary",
    "event_line",
    "peak_in",
]

#: m, the nose region starts this far before the nose tip: a wheel running on the wing rail
#: starts to descend where the wing rail falls away, ~0.5-1 m before the tip of a 1:9-1:15
#: crossing (the wing rail's fall over that length in ``validation/turnout_contact_geometry``).
NOSE_BEFORE = 1.0
#: m, and ends this far after it: the load moves onto the nose where the nose is ~20-40 mm
#: wide, 0.3-0.6 m after the tip of a 1:15 crossing (width x N), and the track's rebound
#: decays within ~1 m more at 80-100 km/h (the report's Fig. 7/8 panels).
NOSE_AFTER = 2.0
#: Fraction of the static wheel load below which a tread counts as unloaded.
TREAD_UNLOADED = 0.01


def nose_region(turnout: Turnout) -> tuple[float, float] | None:
    """x range (m) of the crossing-nose event; None without a ``[layout]`` (no plan).

    Parameters
    ----------
    turnout : Turnout
        With a ``[layout]`` section (the plan gives the nose tip).

    Returns
    -------
    (float, float) or None
        m, ``(nose_tip - NOSE_BEFORE, nose_tip + NOSE_AFTER)``; it starts later where a
        check rail's entry flare ends later (the EW54-190-1:9's: 22.75 m, 0.84 m before its
        nose tip), so that no entry impact falls inside it.
    """
    try:
        tip = turnout_plan(turnout).nose_tip_x
    except TurnoutFileError:
        return None
    start = tip - NOSE_BEFORE
    for route in route_names(turnout):
        check = check_rail_event(turnout, route)
        entry = cast(list, check["entry_m"]) if check is not None else None
        if entry is not None and entry[0] < tip:
            start = max(start, float(entry[1]))
    return (start, tip + NOSE_AFTER)


def check_rail_event(turnout: Turnout, route: str) -> dict[str, object] | None:
    """The route's check-rail contact: wheel, rail slot, x range, entry flare; None if none.

    Parameters
    ----------
    turnout : Turnout
    route : str
        A route of the turnout.

    Returns
    -------
    dict or None
        ``wheel``, ``rail`` (slot), ``region_m`` (the check range), ``entry_m`` (the first
        flare: ``[x_from, x_from + flare_length]``).
    """
    r = load_route(turnout, route)
    pairs = [p for p in r.pairs if p.check]
    if not pairs:
        return None
    pair = pairs[0]
    assert pair.check is not None
    x0, x1 = pair.check
    length = min(r.check_flare[0], x1 - x0)
    return {
        "wheel": pair.wheel,
        "rail": pair.rail,
        "region_m": [float(x0), float(x1)],
        "entry_m": [float(x0), float(x0 + length)],
    }


def peak_in(
    x: np.ndarray, values: np.ndarray, x_range: Sequence[float], signed: bool = True
) -> tuple[float, float]:
    """(peak, x of the peak) of ``values`` over ``x_range``; (nan, nan) if none is finite there.

    Parameters
    ----------
    x : numpy.ndarray
        m, positions of the samples.
    values : numpy.ndarray
        The signal.
    x_range : (float, float)
        m, closed range.
    signed : bool
        True: the value of largest magnitude, with its sign; False: the largest value.

    Returns
    -------
    (float, float)
    """
    sel = (x >= x_range[0]) & (x <= x_range[1]) & np.isfinite(values)
    if not sel.any():
        return math.nan, math.nan
    inside = np.flatnonzero(sel)
    i = inside[int(np.argmax(np.abs(values[sel]) if signed else values[sel]))]
    return float(values[i]), float(x[i])


def event_summary(
    columns: Mapping[str, np.ndarray],
    turnout: Turnout,
    route: str,
    static_loads: Mapping[str, float],
) -> dict[str, object]:
    """Summary keys of the nose and check-rail events (see the module docstring).

    Parameters
    ----------
    columns : mapping
        A passage's columns (``t_s``, ``x_m``, ``Fz_<wheel>_N``, ``Fy_<wheel>_N`` and per
        contact ``Fz_<wheel>_<slot>_N``, ``Fy_<wheel>_<slot>_N``).
    turnout : Turnout
    route : str
        The passage's route.
    static_loads : mapping
        N, static load of each wheel ("left", "right").

    Returns
    -------
    dict
        JSON-ready; peaks NaN where the run does not reach an event.
    """
    out: dict[str, object] = {}
    x = np.asarray(columns["x_m"])
    nose = nose_region(turnout)
    if nose is not None:
        out["nose_region_m"] = [float(nose[0]), float(nose[1])]
        for wheel, suffix in (("right", ""), ("left", "_left")):
            fz, fy = (np.asarray(columns[f"{q}_{wheel}_N"]) for q in ("Fz", "Fy"))
            out[f"peak_Fz_nose{suffix}_N"] = peak_in(x, fz, nose, signed=False)[0]
            out[f"peak_Fy_nose{suffix}_N"] = peak_in(x, fy, nose)[0]
    check = check_rail_event(turnout, route)
    if check is None:
        return out
    wheel, slot = str(check["wheel"]), str(check["rail"])
    rng = cast(list, check["region_m"])
    out["check_rail_region_m"] = rng
    out["check_rail_entry_m"] = check["entry_m"]
    out["check_rail_wheel"], out["check_rail_rail"] = wheel, slot
    fy_name, fz_name = f"Fy_{wheel}_{slot}_N", f"Fz_{wheel}_{slot}_N"
    if fy_name not in columns:  # a run without per-contact columns (height-table contact)
        return out
    fy = np.asarray(columns[fy_name])
    peak, x_peak = peak_in(x, fy, rng)
    out["peak_Fy_check_rail_N"], out["peak_Fy_check_rail_x_m"] = peak, x_peak
    t = np.asarray(columns["t_s"])
    sel = (x >= rng[0]) & (x <= rng[1])
    both = sel[:-1] & sel[1:]
    impulse = 0.5 * (np.abs(fy[:-1]) + np.abs(fy[1:])) * np.diff(t)
    out["check_rail_impulse_Ns"] = float(np.nansum(impulse[both])) if both.any() else math.nan
    tread = np.asarray(columns[f"Fz_{wheel}_N"]) - np.nan_to_num(np.asarray(columns[fz_name]))
    if sel.any() and np.isfinite(tread[sel]).any():
        least = float(np.nanmin(tread[sel]))
        out["check_rail_min_tread_Fz_N"] = least
        out["check_rail_tread_unloaded"] = bool(
            least <= TREAD_UNLOADED * abs(float(static_loads[wheel]))
        )
    else:
        out["check_rail_min_tread_Fz_N"] = math.nan
        out["check_rail_tread_unloaded"] = False
    return out


def event_line(summary: Mapping[str, object]) -> str | None:
    """One console line on the check-rail event; None if the run has none.

    Parameters
    ----------
    summary : mapping
        A passage summary with the keys of :func:`event_summary`.

    Returns
    -------
    str or None
        E.g. ``check rail (right wheel, r3, 44.29-51 m): peak Fy -31.2 kN at x = 45.21 m,
        impulse 519 N s, tread unloaded``.
    """
    peak = _number(summary, "peak_Fy_check_rail_N")
    if not math.isfinite(peak):
        return None
    region = summary["check_rail_region_m"]
    assert isinstance(region, (list, tuple))
    where = (
        f"check rail ({summary['check_rail_wheel']} wheel, {summary['check_rail_rail']}, "
        f"{region[0]:g}-{region[1]:g} m)"
    )
    if not _number(summary, "check_rail_impulse_Ns") > 0.0:
        return f"{where}: no contact"
    tread = "tread unloaded" if summary.get("check_rail_tread_unloaded") else "tread loaded"
    return (
        f"check rail ({summary['check_rail_wheel']} wheel, {summary['check_rail_rail']}, "
        f"{region[0]:g}-{region[1]:g} m): peak Fy {peak / 1e3:+.1f} kN at x = "
        f"{_number(summary, 'peak_Fy_check_rail_x_m'):.2f} m, impulse "
        f"{_number(summary, 'check_rail_impulse_Ns'):.0f} N s, {tread}"
    )


def _number(summary: Mapping[str, object], key: str) -> float:
    value = summary.get(key)
    return float(cast(SupportsFloat, value)) if value is not None else math.nan
