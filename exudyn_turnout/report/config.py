"""The validation report's configuration and result containers.

:class:`ReportConfig` (what a report runs: FE mesh, frequencies, passage window, vehicle,
criteria, cache) and :class:`Report` (its metrics, curves and histories), shared by the
report's sections (:mod:`~exudyn_turnout.report.metrics`,
:mod:`~exudyn_turnout.report.passages`).
"""

from __future__ import annotations

import sys
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from exudyn_turnout.fe.mesh import FEOptions
from exudyn_turnout.inputs.turnout import Turnout, load_turnout
from exudyn_turnout.receptance import Receptance, log_frequencies
from exudyn_turnout.report.cache import (
    default_cache_dir,
    file_fingerprint,
    input_key,
)
from exudyn_turnout.report.criteria import Claim, Criteria
from exudyn_turnout.report.metrics_types import ReportMetrics
from exudyn_turnout.report.passage_api import PassageResult
from exudyn_turnout.report.settings import (
    ReportSettings,
    quick_passage_x,
)

__all__ = [
    "FENotAvailable",
    "ReportConfig",
    "report_config",
    "resolve_config",
    "Report",
    "VEHICLES",
    "log",
    "turnout_fingerprint",
]

#: Vehicles the report can run: the full Manchester vehicle (front wheelset's wheel plotted,
#: as the paper) or the single benchmark wheelset under its sprung share (fast).
VEHICLES = ("full", "wheelset")
#: s, the full report's time step (:func:`report_config`): a reference's. At 1e-4 s the full
#: vehicle's peaks move by up to 1.8 % against it (validation/vehicle_step_convergence.md:
#: the 2-layer lateral crossing peak on the through route, the check-rail force on the
#: diverging route 87.9 against 86.4 kN); at 6.25e-6 s by up to 0.16 %. The quick report
#: keeps 1e-4 s. (Before issue 22's contact lead along x the check-rail force read 14.9 %
#: low at 1e-4 s on the co-running track and 24 % between the FE track's samples.)
FULL_REPORT_TIME_STEP = 2.5e-5


class FENotAvailable(RuntimeError):
    """The FE passage cannot run in this version for this vehicle (reported as n/a)."""


@dataclass(frozen=True)
class ReportConfig:
    """What the report computes and how finely (see :func:`report_config`)."""

    quick: bool = False  #: reduced report for CI
    n_frequencies: int = 400  #: log-spaced receptance frequencies from f_min to f_max
    f_min: float = 1.0  #: Hz
    f_max: float = 2000.0  #: Hz
    fe_options: FEOptions = FEOptions()  #: FE discretisation and model ends
    #: km/h per route; None: the turnout's ``[report]`` speeds
    speeds_kmh: tuple[tuple[str, float], ...] | None = None
    #: m, passage x range; None: the whole turnout, or ``report.quick_passage_x`` if quick
    passage_x: tuple[float, float] | None = None
    time_step: float = 1e-4  #: s, co-running passages (the convergence check halves it)
    timing_repeats: int = 5  #: runs per co-running passage, best wall time taken
    fe_passage: bool = True  #: run the FE passage when the package has one
    #: "full": the Manchester vehicle (its front wheelset's wheel is plotted, as the paper);
    #: "wheelset": the single benchmark wheelset under its sprung share (fast, for tests)
    vehicle: str = "full"
    criteria: Criteria = Criteria()
    cache_dir: str | None = None  #: None: no cache

    def __post_init__(self):
        if self.vehicle not in VEHICLES:
            raise ValueError(
                f"ReportConfig.vehicle must be one of {', '.join(VEHICLES)}, got {self.vehicle!r}"
            )

    @property
    def frequencies(self) -> np.ndarray:
        """Hz, the receptance frequencies."""
        return log_frequencies(self.f_min, self.f_max, self.n_frequencies)


def report_config(quick: bool = False, cache_dir: str | Path | None = "default") -> ReportConfig:
    """Full report (default) or the reduced CI report (``quick``).

    ``cache_dir`` ``"default"`` is :func:`~exudyn_turnout.report.cache.default_cache_dir`;
    None disables the cache. Quick: 48 frequencies, a coarse FE mesh (quadratic elements,
    0.6 m, 6 m extensions), passages over the crossing only (the turnout file's
    ``report.quick_passage_x``, resolved by :func:`resolve_config`), one timing run, the
    single wheelset (the full report runs the full Manchester vehicle).

    Parameters
    ----------
    quick : bool
        The reduced report.
    cache_dir : str, Path or None
        Directory of the FE result cache, ``"default"`` or None.

    Returns
    -------
    ReportConfig
        Unresolved: speeds and the quick window come from the turnout
        (:func:`resolve_config`).
    """
    cache = (
        str(default_cache_dir())
        if cache_dir == "default"
        else (None if cache_dir is None else str(cache_dir))
    )
    if not quick:
        return ReportConfig(cache_dir=cache, time_step=FULL_REPORT_TIME_STEP)
    coarse = FEOptions(
        element_order=2,
        element_length=0.6,
        sleeper_element_length=1.0,
        extension=6.0,
        absorbing_length=6.0,
    )
    return ReportConfig(
        quick=True,
        n_frequencies=48,
        fe_options=coarse,
        timing_repeats=1,
        cache_dir=cache,
        vehicle="wheelset",
    )


def resolve_config(
    config: ReportConfig, settings: ReportSettings, turnout: Turnout | None = None
) -> ReportConfig:
    """``config`` with the turnout's speeds and, for a quick report, its quick passage window.

    Speeds not given in ``config`` are the turnout's ``[report]`` speeds; a quick report
    without ``passage_x`` runs the passages over
    :func:`~exudyn_turnout.report.settings.quick_passage_x` (the file's
    ``report.quick_passage_x`` or 3.5 m about the crossing dip). A route of
    ``config.speeds_kmh`` that the report does not run is an error (ValueError).

    Parameters
    ----------
    config : ReportConfig
        What the report computes (:func:`report_config`).
    settings : ReportSettings
        The turnout's report settings (:func:`~exudyn_turnout.report.settings.report_settings`).
    turnout : Turnout, optional
        The turnout of ``settings``; needed when its quick window is derived (default: the
        packaged turnout).

    Returns
    -------
    ReportConfig
        With ``speeds_kmh`` for every report route and ``passage_x`` resolved.
    """
    speeds = dict(settings.speeds_kmh)
    for route, v in config.speeds_kmh or ():
        if route not in speeds:
            raise ValueError(
                f"report speed given for route {route!r}, which the report does "
                f"not run ({', '.join(speeds)})"
            )
        speeds[route] = float(v)
    x = config.passage_x
    if x is None and config.quick:
        x = quick_passage_x(turnout or load_turnout(), settings)
    return replace(
        config, speeds_kmh=tuple(speeds.items()), passage_x=None if x is None else (x[0], x[1])
    )


@dataclass(frozen=True)
class Report:
    """The report's numbers (``metrics``, JSON-ready), claims, and what its figures draw."""

    config: ReportConfig  #: resolved (:func:`resolve_config`)
    metrics: dict[str, Any]  #: every number in report.md, SI units
    claims: tuple[Claim, ...]
    #: case -> model -> curve
    receptances: Mapping[str, Mapping[str, Receptance]] = field(default_factory=dict)
    #: route -> model -> run
    passages: Mapping[str, Mapping[str, PassageResult]] = field(default_factory=dict)
    #: dict with the FE "profile", its "fits" and the co-running r2 static stiffness; or None
    stiffness: Any = None
    settings: ReportSettings | None = None  #: the turnout's report settings

    @property
    def typed_metrics(self) -> ReportMetrics:
        """``metrics`` read as typed records (a new object per call: ``metrics`` may grow).

        Returns
        -------
        ReportMetrics
        """
        return ReportMetrics.from_dict(self.metrics)


def log(message: str) -> None:
    """Print a progress line of the report on stderr.

    Parameters
    ----------
    message : str
        One line, printed after ``[report]``.
    """
    print(f"[report] {message}", file=sys.stderr, flush=True)


def turnout_fingerprint(turnout: Turnout) -> str:
    """SHA-256 of the turnout's file, or of its parsed content when it has no file.

    Parameters
    ----------
    turnout : Turnout

    Returns
    -------
    str
        Hex digits (part of the cache keys and of ``metrics.json``).
    """
    path = Path(str(turnout.source))
    return file_fingerprint(path) if path.is_file() else input_key(dict(turnout.raw))
