"""What a passage gives: the result object and its files.

Pure data and numpy (no Exudyn): the drivers of every track (:mod:`exudyn_turnout.passage.run`)
fill a :class:`PassageResult`, summarise it with
:func:`~exudyn_turnout.passage.summary.passage_summary` and write it with
:func:`write_passage` (the files' formats in :mod:`~exudyn_turnout.passage.output_files`);
the settings are in :mod:`~exudyn_turnout.passage.settings`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from exudyn_turnout.passage.output_files import (
    OUTPUT_DTYPES,
    keeps_float64,
    save_npz,
    without_empty_columns,
    write_csv,
)
from exudyn_turnout.passage.ride_comfort import comfort_columns
from exudyn_turnout.passage.safety import (
    safety_columns,
)
from exudyn_turnout.passage.settings import (
    PassageSettings,
)
from exudyn_turnout.passage.summary import (
    static_loads_of,
)

__all__ = [
    "PassageResult",
    "write_passage",
    "peaks_table",
]


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
