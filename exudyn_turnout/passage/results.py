"""What a passage is asked and what it gives: settings, result, peaks, summary.

Pure data and numpy (no Exudyn): the drivers of every track (:mod:`exudyn_turnout.passage.run`)
fill a :class:`PassageResult`,
summarise it with :func:`passage_summary` and write it with :func:`write_passage` (the files'
formats in :mod:`~exudyn_turnout.passage.output_files`).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np

from exudyn_turnout.inputs.turnout import Turnout
from exudyn_turnout.inputs.vehicle_model import VehicleModel
from exudyn_turnout.passage.events import event_summary, peak_in
from exudyn_turnout.passage.output_files import (
    OUTPUT_DTYPES,
    keeps_float64,
    save_npz,
    without_empty_columns,
    write_csv,
)
from exudyn_turnout.passage.ride_comfort import comfort_columns, comfort_summary
from exudyn_turnout.passage.safety import (
    SAFETY_LIMITS,
    SafetyLimits,
    SafetyStop,
    check_safety,
    derailment_message,
    first_derailment,
    limits_record,
    safety_columns,
    safety_summary,
    wheel_labels,
)

__all__ = [
    "settings_record",
    "TRACKS",
    "PLAUSIBLE",
    "PassageError",
    "PassageFailure",
    "PassageSettings",
    "DEFAULT_SETTINGS",
    "PassageResult",
    "check_plausible",
    "stop_on_derailment",
    "passage_summary",
    "write_passage",
    "peaks_table",
    "vehicle_summary",
    "body_summary",
    "static_loads_of",
]


class PassageError(RuntimeError):
    """Bad passage settings, or a solver failure (the message says when and where)."""


class PassageFailure(PassageError):
    """A run that failed, diverged or left every physical state (the CLI's exit code 3).

    The message gives the time, the position and what went wrong.
    """


#: Plausibility limits of a passage: beyond any of them the run stops with a
#: :class:`PassageFailure`. m: wheelset vertical and lateral displacement (a wheel 50 mm
#: up or down has derailed or fallen through the track); m: rail deflection; -: contact
#: force over the static wheel load.
PLAUSIBLE = {"wheelset_m": 0.05, "rail_m": 0.02, "force_over_static": 50.0}


@dataclass(frozen=True)
class PassageSettings:
    """Settings of a passage (SI units but the speed in km/h)."""

    route: str = "through"
    speed_kmh: float = 100.0  #: km/h
    layers: int = 3
    source: str = "derived"
    x_start: float | None = None  #: m, default: the turnout's start
    x_end: float | None = None  #: m, default: the turnout's end
    #: s; converged on the through route (<= 0.16 % against 2.5e-5 s), not for the 2-layer
    #: check-rail force on the diverging route (-14.9 %): validation/vehicle_step_convergence.md
    time_step: float = 1e-4
    output_step: float | None = None  #: s, default: every time step
    spectral_radius: float = 0.8  #: generalized-alpha rho_inf
    #: how track springs follow x: "compiled" (one numba call for all springs), "symbolic",
    #: "python" or "constant" (corunning.track.MECHANISMS)
    track_mechanism: str = "compiled"
    #: wheel/rail contact: "profile" (S1002 on the turnout's rail sections, multi-point,
    #: semi-Hertzian normal contact, FASTSIM creep table with spin) or "height-table" (the
    #: route's rail height tables on a conical tread with flange springs: a simplification
    #: kept for comparison)
    contact: str = "profile"
    #: track irregularity (:class:`~exudyn_turnout.inputs.irregularity.Irregularity`) added
    #: to the rails' heights and lateral positions; None: the design geometry
    irregularity: Any = None
    #: time integration of the full vehicle on the co-running track: "exudyn" (Exudyn's
    #: generalized-alpha) or "compiled" (the same scheme in one numba loop,
    #: :mod:`~exudyn_turnout.passage.corunning_track.stepper`; other runs reject it)
    solver: str = "exudyn"

    @property
    def v(self) -> float:
        """Speed in m/s."""
        return self.speed_kmh / 3.6


def settings_record(settings: PassageSettings) -> dict[str, Any]:
    """The settings as plain data for summaries and provenance.

    Parameters
    ----------
    settings : PassageSettings

    Returns
    -------
    dict
        Every field; the irregularity as its source (spec or file name), not its samples.
    """
    record = {f.name: getattr(settings, f.name) for f in fields(settings)}
    irregularity = record.get("irregularity")
    if irregularity is not None:
        record["irregularity"] = str(getattr(irregularity, "source", "") or "given")
    return record


#: The default scenario (frozen, so one instance serves as every function's default).
DEFAULT_SETTINGS = PassageSettings()


#: Track models of :func:`simulate_passage`.
TRACKS = ("2-layer", "3-layer", "fe")


@dataclass(frozen=True, repr=False)
class PassageResult:
    """Time histories and peaks of a passage (SI units, see :func:`simulate_passage`).

    Compute returns this data object; :meth:`plot` draws it (delegating to
    :mod:`exudyn_turnout.plotting`), :meth:`save` writes it, :meth:`peaks` lists its peaks.
    """

    settings: PassageSettings
    columns: Mapping[str, np.ndarray]  #: "t_s", "x_m", forces (N), displacements (m, rad)
    summary: Mapping[str, object]
    #: m, x where each run segment began
    zone_starts: tuple[float, ...] = field(default_factory=tuple)

    def __post_init__(self) -> None:
        """Add the safety columns (Y/Q per wheel, sum Y per wheelset) and, for a full vehicle,
        the EN 12299 weighted floor accelerations
        (:func:`~exudyn_turnout.passage.ride_comfort.comfort_columns`) if they are missing,
        and drop columns without a single value
        (:func:`~exudyn_turnout.passage.output_files.without_empty_columns`).

        Derived from the wheel forces and the summary's static wheel loads
        (:func:`~exudyn_turnout.passage.safety.safety_columns`), so that every track's
        result, its CSV and its NPZ carry the same names.
        """
        loads = static_loads_of(self.summary, self.columns)
        extra = {
            k: v for k, v in safety_columns(self.columns, loads).items() if k not in self.columns
        }
        columns = {**self.columns, **extra}
        if not any(n.startswith(("awd_", "awb_")) for n in columns):
            extra.update(comfort_columns(columns))  # full vehicle: EN 12299 weighted
            columns.update(extra)
        kept = without_empty_columns(columns)
        if extra or len(kept) != len(self.columns):
            object.__setattr__(self, "columns", kept)

    @property
    def model(self) -> str:
        """The track model: ``"2-layer"``, ``"3-layer"`` or ``"FE"``."""
        return str(self.summary.get("model", f"{self.settings.layers}-layer"))

    def peaks(self) -> dict[str, float]:
        """Peak forces (N) of the summary: per region, per wheel and per contact.

        Returns
        -------
        dict
            ``peak_<Fz|Fy>_<region>[_<wheel>[_<rail>]]_N`` -> N (NaN where a region or a
            contact is not in the run). ``Fz`` peaks are maxima, ``Fy`` the largest
            magnitude with its sign.
        """
        out = {}
        for key, value in self.summary.items():
            if key.startswith("peak_") and isinstance(value, (int, float)):
                out[key] = float(value)
            elif key.startswith("peak_") and value is None:
                out[key] = math.nan
        return out

    def plot(self, wheel: str | None = None, title: str | None = None):
        """Contact forces against x at the switch and at the crossing (Figs 7, 8 layout).

        Parameters
        ----------
        wheel : {"right", "left"}, optional
            Default: the right wheel, as the paper's figures.
        title : str, optional
            Figure title.

        Returns
        -------
        (figure, axes)
            From :func:`exudyn_turnout.plotting.plot_passage_forces`.
        """
        from exudyn_turnout.plotting.curves import plot_passage_forces

        return plot_passage_forces([self], wheel=wheel or "right", title=title)

    def plot_wheelsets(self, title: str | None = None):
        """A full vehicle's wheel forces, one row per wheelset, against each one's own x.

        Parameters
        ----------
        title : str, optional

        Returns
        -------
        (figure, axes)
            From :func:`exudyn_turnout.plotting.vehicle.plot_wheelset_forces`.
        """
        from exudyn_turnout.plotting.vehicle import plot_wheelset_forces

        return plot_wheelset_forces(self, title=title)

    def plot_bodies(self, title: str | None = None):
        """A full vehicle's car body and bogies: motion, weighted floor accelerations,
        suspension forces.

        Parameters
        ----------
        title : str, optional

        Returns
        -------
        (figure, axes)
            From :func:`exudyn_turnout.plotting.vehicle.plot_vehicle_bodies`.
        """
        from exudyn_turnout.plotting.vehicle import plot_vehicle_bodies

        return plot_vehicle_bodies(self, title=title)

    def contact_points(self, wheel: str = "right") -> dict[str, np.ndarray]:
        """Every loaded contact point of a wheel over the run (profile contact).

        Parameters
        ----------
        wheel : {"right", "left"}

        Returns
        -------
        dict
            Flat arrays, one entry per (sample, contact point) carrying load: ``x`` (m),
            ``y_rail`` (m, on the rail, side coordinates), ``s_wheel`` (m, on the wheel from
            its taping line), ``normal`` (N), ``angle`` (rad), ``body`` (rail body label).
            Empty for the height-table contact.
        """
        out: dict[str, list] = {k: [] for k in ("x", "y_rail", "s_wheel", "normal", "angle")}
        out["body"] = []
        x = self.columns["x_m"]
        for name, normal in self.columns.items():
            if not (name.startswith(f"cp_{wheel}_") and name.endswith("_N_N")):
                continue
            stem = name[: -len("_N_N")]
            loaded = normal > 0.0
            label = stem[len(f"cp_{wheel}_") :].rsplit("_", 1)[0].replace("_", " ")
            missing = np.full(len(x), np.nan)  # a column without values is not kept

            def quantity(suffix: str, stem: str = stem, missing: np.ndarray = missing):
                return np.asarray(self.columns.get(f"{stem}_{suffix}", missing))

            out["x"].append(x[loaded])
            out["y_rail"].append(quantity("y_rail_m")[loaded])
            out["s_wheel"].append(quantity("s_wheel_m")[loaded])
            out["normal"].append(normal[loaded])
            out["angle"].append(quantity("angle_rad")[loaded])
            out["body"].append(np.full(int(loaded.sum()), label, dtype=object))
        return {
            k: (np.concatenate(v) if v else np.zeros(0, dtype=object if k == "body" else float))
            for k, v in out.items()
        }

    def plot_contact_band(self, path, wheel: str = "right", title: str = ""):
        """The contact-band plot of a wheel: contact positions on rail and wheel along x.

        Parameters
        ----------
        path : str or Path
            PNG file to write.
        wheel : {"right", "left"}
        title : str

        Returns
        -------
        Path
            Delegates to :func:`exudyn_turnout.plotting.wheel_rail.plot_contact_band_along_x`
            (switch and crossing regions as panels where the run covers them).
        """
        from exudyn_turnout.plotting.wheel_rail import plot_contact_band_along_x

        points = self.contact_points(wheel)
        if not len(points["x"]):
            raise ValueError("no contact points: the run used the height-table contact")
        ranges = []
        for key in ("switch_region_m", "crossing_region_m"):
            region = self.summary.get(key)
            if not isinstance(region, (list, tuple)) or len(region) != 2:
                continue
            lo = max(float(region[0]), float(points["x"].min()))
            hi = min(float(region[1]), float(points["x"].max()))
            if hi > lo:
                ranges.append((lo, hi))
        return plot_contact_band_along_x(
            points["x"],
            points["y_rail"],
            points["s_wheel"],
            points["body"],
            path,
            title=title or f"{wheel} wheel",
            x_ranges=ranges or None,
        )

    def save(
        self,
        directory,
        format: str = "csv",  # noqa: A002
        dtype: str = "float64",
    ) -> dict[str, str]:
        """Write the time series (``timeseries.csv`` or ``.npz``) and ``summary.json``.

        Parameters
        ----------
        directory : str or Path
            Output directory (created if missing).
        format : {"csv", "npz"}
            Format of the time series (:func:`write_passage`).
        dtype : {"float64", "float32"}
            NPZ only: the arrays' type (time and positions stay float64).

        Returns
        -------
        dict
            Paths of the files written, by kind.
        """
        return write_passage(self, directory, fmt=format, dtype=dtype)

    def __repr__(self) -> str:
        s = self.settings
        x = self.columns["x_m"]
        crossing = self.summary.get("peak_Fz_crossing_N")
        peak = (
            f", peak Fz crossing {crossing / 1e3:.1f} kN"
            if isinstance(crossing, (int, float)) and math.isfinite(crossing)
            else ""
        )
        vehicle = self.summary.get("vehicle")  # a full vehicle: its name, the front wheelset
        who = f", {vehicle} (front wheelset)" if isinstance(vehicle, str) and vehicle else ""
        return (
            f"PassageResult({self.model}{who}, route {s.route!r}, {s.speed_kmh:g} km/h, "
            f"x {x[0]:g} to {x[-1]:g} m, {len(x)} samples{peak})"
        )


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


def write_passage(
    result: PassageResult,
    out_dir,
    fmt: str = "csv",
    provenance: Mapping | None = None,
    figure: Callable | Sequence[Callable] | None = None,
    dtype: str = "float64",
    parallel: bool | None = None,
) -> dict[str, str]:
    """Write the time series and ``summary.json`` into out_dir; return their paths.

    Files are written into a temporary directory inside out_dir and moved into place
    (``summary.json`` last), so that out_dir never holds a partial or mixed set.

    Layout: one column per quantity, the names of ``result.columns`` in CSV and NPZ alike,
    no column empty from top to bottom
    (:func:`~exudyn_turnout.passage.output_files.without_empty_columns`). Cells are empty
    (CSV) or NaN (NPZ) only where the quantity does not exist at that sample: a rail slot's
    force and motion while that rail is not part of the current zone, a contact point's
    position, angle and creepages while it carries no load (its forces are 0 then), a
    contact point on a rail body before or after the run meets that body. Kept wide (not
    one row per contact point) so that every file reads as one table with the names of
    the Python result; the empty cells cost one byte each (the default run, the full vehicle
    through the turnout: 0.9 of 58.5 MB; the single wheelset's: 0.8 of 15.4 MB). The size
    is in the digits: for a smaller file use ``--output-step``, or the NPZ (compressed;
    float32 on request).

    Parameters
    ----------
    result : PassageResult
    out_dir : str or Path
        Created if missing.
    fmt : {"csv", "npz"}
        ``timeseries.csv`` (:data:`~exudyn_turnout.passage.output_files.CSV_DIGITS`
        significant digits, :func:`~exudyn_turnout.passage.output_files.csv_text`) or
        ``timeseries.npz`` (compressed, :func:`~exudyn_turnout.passage.output_files.save_npz`:
        one array per column and ``summary``,
        the summary as a JSON string; the default run (full vehicle, through): 30.5 MB
        float64, 14.3 MB float32; the single wheelset's 7.4 and 3.5 MB).
    provenance : mapping, optional
        Stored as ``summary["provenance"]`` (see :mod:`exudyn_turnout.provenance`).
    figure : callable(directory) or sequence of them, optional
        Draws further files (``forces.png``) into the temporary directory before the move;
        each in a forked child process while the time series is written (``parallel``),
        else one after the other.
    dtype : {"float64", "float32"}
        NPZ only (one of :data:`~exudyn_turnout.passage.output_files.OUTPUT_DTYPES`): the
        arrays' type; time and longitudinal positions stay float64
        (:func:`~exudyn_turnout.passage.output_files.keeps_float64`).
    parallel : bool, optional
        Draw the figures in a child process beside the writing of the time series
        (:class:`~exudyn_turnout.passage.background.ForkedTask`: the larger of the two
        times on two cores instead of their sum; a child that fails leaves the figures to
        this process, which raises their error). Default
        :func:`~exudyn_turnout.passage.background.can_fork` (Linux, more than one CPU);
        False: one after the other, in this process.

    Returns
    -------
    dict
        ``{"timeseries": path, "summary": path}`` (and ``"figure"`` with ``figure``).

    Raises
    ------
    ValueError
        An unknown format or dtype, or dtype float32 with the CSV.
    """
    import json
    import os
    import shutil
    import tempfile
    from functools import partial
    from pathlib import Path

    from exudyn_turnout.passage.background import ForkedTask
    from exudyn_turnout.provenance import round_floats

    if fmt not in ("csv", "npz"):
        raise ValueError(f"format must be csv or npz, got {fmt!r}")
    if dtype not in OUTPUT_DTYPES:
        raise ValueError(f"dtype must be one of {', '.join(OUTPUT_DTYPES)}, got {dtype!r}")
    if fmt == "csv" and dtype != "float64":
        raise ValueError("dtype float32 is for the npz format (the CSV writes digits)")
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    summary = dict(result.summary)
    if provenance is not None:
        summary["provenance"] = dict(provenance)
    summary_text = json.dumps(round_floats(summary), indent=1)
    columns = without_empty_columns(result.columns)
    tmp = Path(tempfile.mkdtemp(prefix=".partial-", dir=out))
    try:
        series = tmp / f"timeseries.{fmt}"
        groups = [] if figure is None else [figure] if callable(figure) else list(figure)
        drawings = [ForkedTask(partial(draw, tmp), fork=parallel) for draw in groups]
        try:
            if fmt == "csv":
                write_csv(series, columns)
            else:
                arrays = {
                    n: np.asarray(v, dtype=float if keeps_float64(n) else dtype)
                    for n, v in columns.items()
                }
                arrays["summary"] = np.array(summary_text)
                save_npz(series, arrays)
            (tmp / "summary.json").write_text(summary_text + "\n", encoding="utf-8")
            for drawing in drawings:
                drawing.join()
        except BaseException:
            for drawing in drawings:
                drawing.stop()
            raise
        files = [series.name]
        if drawings:
            written = (series.name, "summary.json")
            files += sorted(p.name for p in tmp.iterdir() if p.name not in written)
        for name in files + ["summary.json"]:
            os.replace(tmp / name, out / name)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    paths = {"timeseries": str(out / f"timeseries.{fmt}"), "summary": str(out / "summary.json")}
    if figure is not None:
        paths["figure"] = str(out / "forces.png")
    return paths


def peaks_table(results: Mapping[str, PassageResult]) -> str:
    """Plain-text table of the right wheel's peak forces (kN) of labelled results.

    Parameters
    ----------
    results : mapping
        Label -> PassageResult.

    Returns
    -------
    str
    """
    keys = ("peak_Fz_switch_N", "peak_Fz_crossing_N", "peak_Fy_switch_N", "peak_Fy_crossing_N")
    lines = [f"{'model':<28}" + "".join(f"{k[5:-2]:>18}" for k in keys) + f"{'wall (s)':>10}"]
    for label, r in results.items():
        lines.append(
            f"{label:<28}"
            + "".join(f"{float(r.summary[k]) / 1e3:>18.1f}" for k in keys)  # type: ignore[arg-type]
            + f"{float(r.summary['wall_time_s']):>10.2f}"  # type: ignore[arg-type]
        )
    return "\n".join(lines)


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
        :func:`~exudyn_turnout.passage.results.passage_summary` of the front wheelset plus
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
