"""Running-safety and wear quantities of a passage, their limits, and the climbing stop.

Numpy on the columns of a passage (:class:`~exudyn_turnout.passage.results.PassageResult`);
the sliding means' integrals are one compiled loop.

Sign conventions
----------------
The passage's ``Fy_<wheel>_N`` is the lateral force of the wheel *on its rails*, in track
axes, positive to the left; ``Fz_<wheel>_N`` the vertical force pressing the rails down.
Here

- ``Q`` = ``Fz_<wheel>_N`` (the wheel's vertical force);
- ``Y`` = the wheel's lateral force in the *flange sense*: positive when it pushes its rail
  outwards, towards the field side (right wheel: ``Y = -Fy_right``; left wheel:
  ``Y = +Fy_left``). A flanging wheel has Y > 0; a tread creep force can have either sign;
  the back of the flange on a check rail gives Y < 0. The peaks of Y/Q are the largest
  magnitude, with its sign (a wheel can climb its running rail with Y > 0, or a check rail
  with the back of its flange, Y < 0);
- ``sum Y`` of a wheelset = ``Fy_left + Fy_right`` in track axes (positive left): the net
  lateral force of the wheelset on the track, Prud'homme's track-shifting force.

Limits (:class:`SafetyLimits`)
------------------------------
- Y/Q against Nadal's limit (Nadal 1908; EN 14363:2016, Annex on flange climbing;
  Iwnicki (ed.), *Handbook of Railway Vehicle Dynamics*, 2006, ch. "Derailment"):
  ``(tan g - mu) / (1 + mu tan g)`` at the wheel's flange angle g (the steepest point of
  the flange, which a climbing contact must pass: S1002 70.13 deg,
  ``validation/contact_geometry.md``) and the contact law's friction mu.
- The 2 m sliding mean: EN 14363:2016 processes Y/Q and sum Y as sliding means over 2 m of
  track (clause on the processing of the on-track assessment quantities; the clause number
  is not quoted here because the standard's text was not at hand). Here the window is
  centred on each sample (a step of one sample, finer than the standard's 0.5 m, so the
  maximum is never below the standard's); only windows lying wholly inside the run are
  evaluated, and a region's 2 m value is the maximum over windows *centred* in the region
  (they may reach outside it). A run shorter than 2 m has no 2 m value (None).
- Sum Y against Prud'homme's limit ``alpha (10 kN + P/3)``, P the static axle load
  (Prud'homme, Rev. Gén. Chemins de Fer, 1970; EN 14363:2016 limit of the sum of guiding
  forces, alpha = 1.0 for passenger coaches and 0.85 for freight wagons; default 0.85,
  the smaller).
- Wheel unloading Delta Q / Q0 = (Q0 - Q) / Q0 with Q0 the static wheel load, limit 0.6
  (the "allowable" wheel load reduction rate of GB 5599-85; its "dangerous" limit is 0.65).
- Contact-loss length: the metres of track over which a wheel's total Fz is 0.
- T-gamma (wear number): the sum over a wheel's contacts of tangential force times creepage,
  N (per-contact columns ``cp_*_Tgamma_N``); reported, no limit (Burstow's RCF damage
  function takes T-gamma per contact patch: initiation above about 15 N).

The stop (:func:`check_safety`)
-------------------------------
A run stops with :class:`~exudyn_turnout.passage.settings.PassageFailure` (exit 3) on

- **wheel lift**: a wheel without any contact (total Fz <= 0) over more than
  ``lift_length_m`` = 2 m of track (the length of EN 14363's assessment window: what lasts
  that long is no bounce; a wheel hopping at a crossing nose lands within centimetres);
- **flange climb**: the mean of |Y/Q| over the last 2 m of track above Nadal's limit at the
  flange angle, while the wheel touches its rail with its flange (a loaded contact at an
  angle >= ``flange_contact_deg``, where the contact angles are recorded). Nadal's limit
  is the ratio at which the flange contact slides up the flange; a wheel ratio (tread plus
  flange) above it over 2 m of track is climbing.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import asdict, dataclass, replace

import numba
import numpy as np

from exudyn_turnout.wheel_rail.conicity import nadal_limit

__all__ = [
    "SafetyLimits",
    "SAFETY_LIMITS",
    "SafetyStop",
    "prudhomme_limit",
    "sliding_mean",
    "flange_force",
    "y_over_q",
    "wheel_unloading",
    "contact_loss_length",
    "longest_contact_loss",
    "wheel_labels",
    "safety_columns",
    "safety_summary",
    "check_safety",
    "first_derailment",
    "derailment_message",
    "limits_record",
    "limits_for_friction",
]

WHEELS = ("right", "left")


@dataclass(frozen=True)
class SafetyLimits:
    """Limits of the safety quantities and of the climbing stop (sources: module docstring)."""

    #: -, friction coefficient at the flange for Nadal's limit (the packaged contact law's
    #: mu, ``data/manchester_wheelset.toml``)
    friction: float = 0.4
    #: deg, the wheel's flange angle (S1002: 70.13, ``validation/contact_geometry.md``)
    flange_angle_deg: float = 70.13
    #: deg, a loaded contact at this angle or steeper is on the flange
    flange_contact_deg: float = 45.0
    window_m: float = 2.0  #: m, sliding-mean window (EN 14363)
    prudhomme_alpha: float = 0.85  #: -, Prud'homme's alpha (0.85 freight, 1.0 coaches)
    unloading: float = 0.6  #: -, limit of Delta Q / Q0 (GB 5599-85 allowable)
    #: -, Y/Q uses Q no smaller than this share of the static wheel load (Y/Q of a wheel
    #: about to lift is then finite and large, never a division by zero)
    q_floor_over_static: float = 0.05
    lift_length_m: float = 2.0  #: m, a wheel without contact for longer stops the run
    #: -, a contact counts for the flange angle when it carries this share of Q0
    contact_load_over_static: float = 0.01

    @property
    def nadal(self) -> float:
        """Nadal's limit Y/Q at the flange angle and friction (-)."""
        return nadal_limit(math.radians(self.flange_angle_deg), self.friction)


#: The default limits.
SAFETY_LIMITS = SafetyLimits()


def limits_for_friction(friction: float, limits: SafetyLimits = SAFETY_LIMITS) -> SafetyLimits:
    """The limits with the vehicle's wheel/rail friction in Nadal's limit.

    Parameters
    ----------
    friction : float
        -, the contact law's mu (``[contact] mu`` of the vehicle file).
    limits : SafetyLimits
        The other limits.

    Returns
    -------
    SafetyLimits
    """
    return replace(limits, friction=float(friction))


def limits_record(limits: SafetyLimits = SAFETY_LIMITS) -> dict[str, float]:
    """The limits as plain data for the summary, with Nadal's limit.

    Parameters
    ----------
    limits : SafetyLimits

    Returns
    -------
    dict
        Every field, and ``nadal`` (-).
    """
    return dict(asdict(limits), nadal=limits.nadal)


class SafetyStop(Exception):
    """A climbing or lifting wheel; the message says when, where, which wheel and what.

    Raised by :func:`check_safety`; the passage turns it into its ``PassageFailure``.
    """


def prudhomme_limit(axle_load: float, alpha: float = 0.85) -> float:
    """Prud'homme's limit of the sum of guiding forces, alpha (10 kN + P / 3).

    Prud'homme (1970), EN 14363:2016 (limit of the sum of guiding forces (sum Y)_2m).

    Parameters
    ----------
    axle_load : float
        N, static axle load P.
    alpha : float
        -, 0.85 (freight wagons, Prud'homme's original) or 1.0 (passenger coaches).

    Returns
    -------
    float
        N.
    """
    return alpha * (10e3 + axle_load / 3.0)


def sliding_mean(
    x: np.ndarray, values: np.ndarray, window: float = 2.0, trailing: bool = False
) -> np.ndarray:
    """Mean of ``values`` over a window of track at each sample (trapezoidal integral in x).

    Parameters
    ----------
    x : ndarray
        m, non-decreasing positions of the samples.
    values : ndarray
        The signal at each sample.
    window : float
        m, window length (EN 14363: 2 m).
    trailing : bool
        False: window centred on each sample; True: the ``window`` of track behind it.

    Returns
    -------
    ndarray
        The mean at each sample; NaN where the window does not lie wholly inside
        ``[x[0], x[-1]]`` (all NaN for a run shorter than the window).

    Raises
    ------
    ValueError
        x decreasing, shapes differing, or a window <= 0.
    """
    x = np.asarray(x, dtype=float)
    v = np.asarray(values, dtype=float)
    if x.shape != v.shape or x.ndim != 1:
        raise ValueError("sliding_mean: x and values must be 1-D of the same length")
    if not window > 0:
        raise ValueError(f"sliding_mean: window must be > 0 m, got {window}")
    if x.size and np.any(np.diff(x) < 0):
        raise ValueError("sliding_mean: x must be non-decreasing")
    out = np.full(x.shape, np.nan)
    if x.size < 2:
        return out
    tol = 1e-9 * max(1.0, abs(window))
    if np.isfinite(x).all():
        return _sliding_mean(x, v, float(window), bool(trailing), tol)
    # NaN or inf positions: numpy's binary search, as before
    lo, hi = (x - window, x) if trailing else (x - 0.5 * window, x + 0.5 * window)
    inside = (lo >= x[0] - tol) & (hi <= x[-1] + tol)
    lo, hi = np.clip(lo, x[0], x[-1]), np.clip(hi, x[0], x[-1])
    cumulative = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(x))])
    integral = _integral_to(x, v, cumulative, hi) - _integral_to(x, v, cumulative, lo)
    out[inside] = integral[inside] / window
    return out


@numba.njit(cache=True)
def _sliding_mean(x, v, window, trailing, tol):  # pragma: no cover (compiled; tested)
    """:func:`sliding_mean` of finite positions (at least two): its numpy arithmetic,
    operation for operation (the same floats), in one loop; the window ends' cells are
    found by walking along x instead of a binary search per end (the post-run safety
    checks take ~100 sliding means)."""
    n = x.shape[0]
    cumulative = np.empty(n)
    cumulative[0] = 0.0
    total = 0.0
    for k in range(n - 1):  # np.cumsum adds in order
        total += 0.5 * (v[k + 1] + v[k]) * (x[k + 1] - x[k])
        cumulative[k + 1] = total
    first, last = x[0], x[n - 1]
    out = np.empty(n)
    j_lo = 0  # searchsorted(x, end, side="right"): the count of x <= end
    j_hi = 0
    for m in range(n):
        if trailing:
            lo, hi = x[m] - window, x[m]
        else:
            lo, hi = x[m] - 0.5 * window, x[m] + 0.5 * window
        inside = lo >= first - tol and hi <= last + tol
        lo = min(max(lo, first), last)  # np.clip
        hi = min(max(hi, first), last)
        while j_lo < n and x[j_lo] <= lo:
            j_lo += 1
        while j_hi < n and x[j_hi] <= hi:
            j_hi += 1
        if inside:
            integral = _integral_at(x, v, cumulative, hi, j_hi)
            integral -= _integral_at(x, v, cumulative, lo, j_lo)
            out[m] = integral / window
        else:
            out[m] = np.nan
    return out


@numba.njit(cache=True, inline="always")
def _integral_at(x, v, cumulative, at, count):  # pragma: no cover (compiled)
    """:func:`_integral_to` at one ``at`` whose count of x <= at is ``count``."""
    i = min(max(count - 1, 0), x.shape[0] - 2)
    dx = x[i + 1] - x[i]
    s = (at - x[i]) / dx if dx > 0 else 0.0
    v_at = v[i] + s * (v[i + 1] - v[i])
    return cumulative[i] + 0.5 * (v[i] + v_at) * (at - x[i])


def _integral_to(x: np.ndarray, v: np.ndarray, cumulative: np.ndarray, at: np.ndarray):
    """Integral of the piecewise-linear signal from x[0] to each ``at`` (exact)."""
    i = np.clip(np.searchsorted(x, at, side="right") - 1, 0, x.size - 2)
    dx = x[i + 1] - x[i]
    s = np.where(dx > 0, (at - x[i]) / np.where(dx > 0, dx, 1.0), 0.0)
    v_at = v[i] + s * (v[i + 1] - v[i])
    return cumulative[i] + 0.5 * (v[i] + v_at) * (at - x[i])


def flange_force(fy_on_rail: np.ndarray, wheel: str) -> np.ndarray:
    """Y in the flange sense: the lateral force pushing the wheel's rail outwards (N).

    Parameters
    ----------
    fy_on_rail : ndarray
        N, ``Fy_<wheel>_N``: lateral force on the rail in track axes, positive left.
    wheel : {"right", "left"}

    Returns
    -------
    ndarray
        N, positive towards the field side of that wheel's rail.
    """
    if wheel not in WHEELS:
        raise ValueError(f"wheel must be right or left, got {wheel!r}")
    return (-1.0 if wheel == "right" else 1.0) * np.asarray(fy_on_rail, dtype=float)


def y_over_q(y: np.ndarray, q: np.ndarray, static_load: float, q_floor: float = 0.05):
    """Y/Q with Q no smaller than ``q_floor`` times the static wheel load.

    Parameters
    ----------
    y, q : ndarray
        N, lateral (flange sense) and vertical wheel forces.
    static_load : float
        N, Q0.
    q_floor : float
        -, share of Q0 below which Q is taken as that share (a lifting wheel's Y/Q stays
        finite; its unloading and contact loss are reported on their own).

    Returns
    -------
    ndarray
        -.
    """
    floor = q_floor * abs(static_load)
    return np.asarray(y, dtype=float) / np.maximum(np.asarray(q, dtype=float), floor)


def wheel_unloading(q: np.ndarray, static_load: float) -> np.ndarray:
    """Delta Q / Q0 = (Q0 - Q) / Q0: 0 at the static load, 1 with the wheel off its rail.

    Parameters
    ----------
    q : ndarray
        N, vertical wheel force.
    static_load : float
        N, Q0 (> 0).

    Returns
    -------
    ndarray
        -.
    """
    return (static_load - np.asarray(q, dtype=float)) / static_load


def _sample_lengths(x: np.ndarray) -> np.ndarray:
    """m of track each sample stands for (half the distance to each neighbour)."""
    if x.size < 2:
        return np.zeros(x.shape)
    d = np.diff(x)
    return 0.5 * (np.concatenate([[0.0], d]) + np.concatenate([d, [0.0]]))


def contact_loss_length(x: np.ndarray, q: np.ndarray) -> float:
    """Metres of track over which a wheel carried no load (total Fz <= 0).

    Parameters
    ----------
    x : ndarray
        m, positions of the samples.
    q : ndarray
        N, the wheel's total vertical force.

    Returns
    -------
    float
        m (each sample stands for half the distance to each neighbour).
    """
    x = np.asarray(x, dtype=float)
    return float(np.sum(_sample_lengths(x)[np.asarray(q) <= 0.0]))


def longest_contact_loss(x: np.ndarray, q: np.ndarray, limit: float) -> int | None:
    """The first sample at which a wheel has been without contact for more than ``limit``.

    Parameters
    ----------
    x : ndarray
        m, non-decreasing positions.
    q : ndarray
        N, the wheel's total vertical force.
    limit : float
        m.

    Returns
    -------
    int or None
        Index of the sample, or None if no stretch without contact is that long.
    """
    x = np.asarray(x, dtype=float)
    lifted = np.concatenate([[False], np.asarray(q) <= 0.0, [False]]).astype(np.int8)
    edges = np.diff(lifted)
    starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)  # [start, end)
    for a, b in zip(starts, ends):
        beyond = np.flatnonzero(x[a:b] - x[a] > limit)
        if beyond.size:
            return int(a + beyond[0])
    return None


def wheel_labels(columns: Mapping[str, np.ndarray]) -> list[str]:
    """The wheelset labels of a passage's columns: ``""`` (single) and ``ws1``, ``ws2``...

    Parameters
    ----------
    columns : mapping

    Returns
    -------
    list of str
        ``""`` if ``Fz_right_N`` is a column, then every ``ws<i>`` with ``Fz_ws<i>_right_N``.
    """
    labels = [""] if "Fz_right_N" in columns else []
    i = 1
    while f"Fz_ws{i}_right_N" in columns:
        labels.append(f"ws{i}")
        i += 1
    return labels


def _name(quantity: str, label: str, wheel: str = "", unit: str = "") -> str:
    parts = [quantity] + [p for p in (label, wheel) if p]
    return "_".join(parts) + (f"_{unit}" if unit else "")


def _x_of(columns: Mapping[str, np.ndarray], label: str) -> np.ndarray:
    return np.asarray(columns.get(f"x_{label}_m", columns["x_m"]) if label else columns["x_m"])


def safety_columns(
    columns: Mapping[str, np.ndarray],
    static_loads: Mapping[str, Mapping[str, float]],
    limits: SafetyLimits = SAFETY_LIMITS,
) -> dict[str, np.ndarray]:
    """Time series of Y/Q per wheel and sum Y per wheelset (finite everywhere).

    Parameters
    ----------
    columns : mapping
        The passage's columns (``Fy_[<ws>_]<wheel>_N``, ``Fz_[<ws>_]<wheel>_N``).
    static_loads : mapping
        Wheelset label (:func:`wheel_labels`) -> {"right", "left"} -> static load (N).
    limits : SafetyLimits

    Returns
    -------
    dict
        ``YQ_[<ws>_]<wheel>`` (-, flange sense) and ``sumY_[<ws>_]N`` (N, track axes,
        positive left), for each wheelset label of ``static_loads`` found in ``columns``.
    """
    out: dict[str, np.ndarray] = {}
    for label, loads in static_loads.items():
        if _name("Fy", label, "right", "N") not in columns:
            continue
        for wheel in WHEELS:
            fy = columns[_name("Fy", label, wheel, "N")]
            q = columns[_name("Fz", label, wheel, "N")]
            y = flange_force(fy, wheel)
            out[_name("YQ", label, wheel)] = y_over_q(
                y, q, loads[wheel], limits.q_floor_over_static
            )
        out[_name("sumY", label, unit="N")] = np.asarray(
            columns[_name("Fy", label, "left", "N")], dtype=float
        ) + np.asarray(columns[_name("Fy", label, "right", "N")], dtype=float)
    return out


def _contact_stems(columns: Mapping[str, np.ndarray], wheel: str) -> list[str]:
    """Stems ``cp_<wheel>_<slot>_<label>_<k>_`` of a wheel's per-contact columns."""
    return [
        n[: -len("N_N")] for n in columns if n.startswith(f"cp_{wheel}_") and n.endswith("_N_N")
    ]


def _flange_angle(columns, wheel: str, static_load: float, limits: SafetyLimits):
    """deg, the steepest loaded contact angle of a wheel per sample (None: not recorded)."""
    stems = [s for s in _contact_stems(columns, wheel) if f"{s}angle_rad" in columns]
    if not stems:
        return None
    floor = limits.contact_load_over_static * abs(static_load)
    angles = [
        np.where(np.asarray(columns[f"{s}N_N"]) > floor, np.abs(columns[f"{s}angle_rad"]), 0.0)
        for s in stems
    ]
    return np.degrees(np.nan_to_num(np.max(angles, axis=0), nan=0.0))


def _tgamma(columns, wheel: str):
    """N, a wheel's T-gamma per sample (sum over its contacts), or None."""
    names = [f"{s}Tgamma_N" for s in _contact_stems(columns, wheel)]
    names = [n for n in names if n in columns]
    if not names:
        return None
    return np.nan_to_num(np.sum([np.asarray(columns[n], dtype=float) for n in names], axis=0))


def _argmax_abs(values: np.ndarray, x: np.ndarray, sel: np.ndarray) -> tuple[float, float]:
    """(value of largest magnitude, its x) over the finite selected samples; (nan, nan)."""
    v = np.where(sel & np.isfinite(values), values, np.nan)
    if not np.isfinite(v).any():
        return math.nan, math.nan
    i = int(np.nanargmax(np.abs(v)))
    return float(v[i]), float(x[i])


def safety_summary(
    columns: Mapping[str, np.ndarray],
    static_loads: Mapping[str, Mapping[str, float]],
    regions: Mapping[str, tuple[float, float]],
    limits: SafetyLimits = SAFETY_LIMITS,
) -> tuple[dict[str, object], list[dict[str, object]]]:
    """Safety and wear quantities per wheel, wheelset and region, and the limits exceeded.

    Parameters
    ----------
    columns : mapping
        The passage's columns (with those of :func:`safety_columns`, or they are computed).
    static_loads : mapping
        Wheelset label -> {"right", "left"} -> static wheel load Q0 (N).
    regions : mapping
        Region name -> (x_from, x_to) m; ``"run"`` (the whole run) is added.
    limits : SafetyLimits

    Returns
    -------
    summary : dict
        Per region R, wheelset label L (omitted for the single wheelset) and wheel W:
        ``YQ_peak_R_[L_]W`` (-, largest |Y/Q| with its sign) and ``_x_m``,
        ``YQ_2m_peak_R_[L_]W`` and ``_x_m``, ``flange_angle_max_R_[L_]W_deg`` (steepest
        loaded contact, where recorded), ``dQ_Q0_max_R_[L_]W`` (-),
        ``contact_loss_R_[L_]W_m``, ``Tgamma_peak_R_[L_]W_N`` and ``Tgamma_mean_R_[L_]W_N``
        (where recorded); per wheelset ``sumY_peak_R_[L_]N``, ``sumY_2m_peak_R_[L_]N`` (N,
        largest magnitude with its sign) and ``prudhomme_limit_[L_]N``; ``nadal_limit``.
        A quantity a region's samples cannot give is None.
    exceeded : list of dict
        One entry per wheel (or wheelset), region and quantity beyond its limit (``run``
        only where its peak lies outside every region):
        ``wheel``, ``region``, ``quantity``, ``value``, ``limit``, ``x_m``.
    """
    derived = safety_columns(columns, static_loads, limits)
    cols = {**columns, **derived}
    all_regions = {**regions, "run": (-math.inf, math.inf)}
    nadal = limits.nadal
    out: dict[str, object] = {"nadal_limit": nadal}
    exceeded: list[dict[str, object]] = []

    def put(key: str, value: float) -> None:
        out[key] = value if math.isfinite(value) else None

    def flag(who: str, where: str, quantity: str, value: float, limit: float, x: float):
        in_region = any(lo <= x <= hi for lo, hi in regions.values())
        if where == "run" and in_region:  # listed under its region
            return
        if math.isfinite(value) and abs(value) > limit:
            exceeded.append(
                {"wheel": who, "region": where, "quantity": quantity, "value": value,
                 "limit": limit, "x_m": x}
            )  # fmt: skip

    for label, loads in static_loads.items():
        if _name("YQ", label, "right") not in cols:
            continue
        x = _x_of(cols, label)
        axle = float(loads["right"]) + float(loads["left"])
        prud = prudhomme_limit(axle, limits.prudhomme_alpha)
        put(_name("prudhomme_limit", label, unit="N"), prud)
        sum_y = cols[_name("sumY", label, unit="N")]
        sum_y_2m = sliding_mean(x, sum_y, limits.window_m)
        per_wheel = {}
        for wheel in WHEELS:
            q0 = float(loads[wheel])
            q = np.asarray(cols[_name("Fz", label, wheel, "N")], dtype=float)
            yq = cols[_name("YQ", label, wheel)]
            own = label == "" or (label == "ws1" and "Fz_right_N" not in columns)
            per_wheel[wheel] = (
                q0,
                q,
                yq,
                sliding_mean(x, yq, limits.window_m),
                _flange_angle(cols, wheel, q0, limits) if own else None,
                _tgamma(cols, wheel) if own else None,
            )
        who_set = f"wheelset {label}" if label else "wheelset"
        for where, (lo, hi) in all_regions.items():
            sel = (x >= lo) & (x <= hi)
            value, x_at = _argmax_abs(sum_y, x, sel)
            put(_name(f"sumY_peak_{where}", label, unit="N"), value)
            value, x_at = _argmax_abs(sum_y_2m, x, sel)
            put(_name(f"sumY_2m_peak_{where}", label, unit="N"), value)
            flag(who_set, where, "sum Y (2 m mean), N", value, prud, x_at)
            for wheel, (q0, q, yq, yq_2m, angle, tgamma) in per_wheel.items():
                who = f"{label} {wheel} wheel".strip()
                value, x_at = _argmax_abs(yq, x, sel)
                put(_name(f"YQ_peak_{where}", label, wheel), value)
                put(_name(f"YQ_peak_{where}", label, wheel, "x_m"), x_at)
                value, x_at = _argmax_abs(yq_2m, x, sel)
                put(_name(f"YQ_2m_peak_{where}", label, wheel), value)
                put(_name(f"YQ_2m_peak_{where}", label, wheel, "x_m"), x_at)
                flag(who, where, "Y/Q (2 m mean)", value, nadal, x_at)
                unloading = np.where(sel, wheel_unloading(q, q0), np.nan)
                value, x_at = math.nan, math.nan
                if np.isfinite(unloading).any():
                    i = int(np.nanargmax(unloading))
                    value, x_at = float(unloading[i]), float(x[i])
                put(_name(f"dQ_Q0_max_{where}", label, wheel), value)
                flag(who, where, "Delta Q/Q0", value, limits.unloading, x_at)
                loss = contact_loss_length(x[sel], q[sel]) if sel.any() else math.nan
                put(_name(f"contact_loss_{where}", label, wheel, "m"), loss)
                if angle is not None:
                    a = angle[sel]
                    put(_name(f"flange_angle_max_{where}", label, wheel, "deg"),
                        float(a.max()) if a.size else math.nan)  # fmt: skip
                if tgamma is not None:
                    tg = tgamma[sel]
                    put(_name(f"Tgamma_peak_{where}", label, wheel, "N"),
                        float(tg.max()) if tg.size else math.nan)  # fmt: skip
                    put(_name(f"Tgamma_mean_{where}", label, wheel, "N"),
                        float(tg.mean()) if tg.size else math.nan)  # fmt: skip
    return out, exceeded


def check_safety(
    columns: Mapping[str, np.ndarray],
    static_load: float,
    what: str = "",
    limits: SafetyLimits = SAFETY_LIMITS,
) -> None:
    """Stop a lifting or climbing wheel (criteria in the module docstring).

    Parameters
    ----------
    columns : mapping
        ``t_s``, ``x_m`` (or ``x_<ws>_m``) and, per wheel, ``Fz_[<ws>_]<wheel>_N``
        (wheel lift) and ``Fy_[<ws>_]<wheel>_N`` (flange climb; with the ``cp_*``
        contact angles where recorded). Missing columns leave their check out.
    static_load : float
        N, static wheel load Q0 of every wheel checked.
    what : str
        Where (e.g. "wheelset 2"), put into the message.
    limits : SafetyLimits

    Raises
    ------
    SafetyStop
        At the first sample beyond a limit: its time, x, the wheel and the quantity.
    """
    found = first_derailment(columns, static_load, limits)
    if found is not None:
        raise SafetyStop(derailment_message(found, what))


def derailment_message(found: tuple[float, float, str], what: str = "") -> str:
    """The one line a derailment stop says.

    Parameters
    ----------
    found : (float, float, str)
        t (s), x (m) and the wheel and quantity, from :func:`first_derailment`.
    what : str
        Where (e.g. "zone 2, crossing panel"), put into the message.

    Returns
    -------
    str
        ``"derailment stopped at t = ... s, x = ... m (what): ..."``.
    """
    t_i, x_i, message = found
    where = f" ({what})" if what else ""
    return f"derailment stopped at t = {t_i:.5f} s, x = {x_i:.3f} m{where}: {message}"


def first_derailment(
    columns: Mapping[str, np.ndarray],
    static_load: float,
    limits: SafetyLimits = SAFETY_LIMITS,
) -> tuple[float, float, str] | None:
    """The first lifting or climbing wheel of :func:`check_safety`, or None.

    Parameters
    ----------
    columns : mapping
        As :func:`check_safety`.
    static_load : float
        N, static wheel load Q0.
    limits : SafetyLimits

    Returns
    -------
    (t, x, what) or None
        s, m, and the wheel and quantity in words.
    """
    t = np.asarray(columns["t_s"])
    first: tuple[float, int, str, float] | None = None  # (t, sample, message, x)
    for label in wheel_labels(columns) or [""]:
        x = _x_of(columns, label)
        for wheel in WHEELS:
            q_name = _name("Fz", label, wheel, "N")
            if q_name not in columns:
                continue
            who = f"{label + ' ' if label else ''}{wheel} wheel"
            q = np.asarray(columns[q_name], dtype=float)
            i = longest_contact_loss(x, q, limits.lift_length_m)
            if i is not None and (first is None or t[i] < first[0]):
                message = f"{who} lifted: no contact over more than {limits.lift_length_m:g} m"
                first = (float(t[i]), i, message, float(x[i]))
            y_name = _name("Fy", label, wheel, "N")
            if y_name not in columns or x.size < 2:
                continue
            yq = y_over_q(
                flange_force(columns[y_name], wheel), q, static_load, limits.q_floor_over_static
            )
            mean = sliding_mean(x, yq, limits.window_m, trailing=True)
            climbing = np.abs(np.nan_to_num(mean)) > limits.nadal
            angle = _flange_angle(columns, wheel, static_load, limits) if label == "" else None
            if angle is not None:
                climbing &= angle >= limits.flange_contact_deg
            hits = np.flatnonzero(climbing)
            if hits.size and (first is None or t[hits[0]] < first[0]):
                k = int(hits[0])
                message = (
                    f"{who} climbing its flange: Y/Q over the last {limits.window_m:g} m "
                    f"{mean[k]:.4f} is above Nadal's limit {limits.nadal:.4f}"
                )
                first = (float(t[k]), k, message, float(x[k]))
    if first is None:
        return None
    return first[0], first[3], first[2]
