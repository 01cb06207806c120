"""The report's metrics as typed, frozen records: the schema of ``metrics.json``.

:class:`ReportMetrics` is the whole document; one record per section (configuration,
parameters, stiffness, receptance, passages, cost, convergence, checks) and per repeated
object in it. Each is read from the parsed JSON by
:meth:`~exudyn_turnout.report.record.Record.from_dict` and written back by
:meth:`~exudyn_turnout.report.record.Record.to_dict`, which gives the same dict: the file's
format is the report's (:func:`~exudyn_turnout.report.metrics.build_report`), these records
only name and type it. Fields are in the file's order, SI units (named in the ``#:``
comments); forces in N, stiffness in N/m, times in s, lengths in m. Optional fields are keys
that older reports, or reports without an FE result, leave out.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from exudyn_turnout.report.criteria import Claim, Criteria
from exudyn_turnout.report.record import Record, optional

__all__ = [
    "CheckRailEvent",
    "ReportMetrics",
    "ConfigMetrics",
    "ParameterRow",
    "ParameterMetrics",
    "PaperStiffness",
    "FEInfo",
    "RailStiffness",
    "FitPoint",
    "StiffnessFit",
    "StiffnessAt",
    "StiffnessStatements",
    "StiffnessMetrics",
    "ReceptancePosition",
    "FrequencyGrid",
    "ReceptanceModel",
    "ReceptanceCase",
    "ReceptanceMetrics",
    "VsFE",
    "PassageModel",
    "PassageRoute",
    "PassageMetrics",
    "FERun",
    "ReceptanceWallTime",
    "CostMetrics",
    "PeakChange",
    "ConvergenceMetrics",
    "StaticWheelLoad",
    "CheckMetrics",
]


@dataclass(frozen=True, kw_only=True)
class ConfigMetrics(Record):
    """What the report ran (its :class:`~exudyn_turnout.report.config.ReportConfig`)."""

    quick: bool  #: the reduced (CI) report
    n_frequencies: int  #: number of receptance frequencies
    f_min: float  #: Hz
    f_max: float  #: Hz
    fe_options: dict[str, Any]  #: FE mesh options (``FEOptions`` fields)
    speeds_kmh: dict[str, float]  #: km/h per route
    passage_x: list[float] | None  #: m, passage x range; None: the whole turnout
    time_step: float  #: s, co-running passages
    timing_repeats: int  #: runs per co-running passage
    fe_passage: bool  #: whether the FE passage was asked for
    vehicle: str  #: "full" or "wheelset"
    cache_dir: str | None  #: FE result cache (home as ``~``), None: disabled


@dataclass(frozen=True, kw_only=True)
class ParameterRow(Record):
    """One co-running parameter, derived against the published Table 2."""

    zone: int  #: zone index
    name: str  #: parameter name, e.g. ``k_01_z``
    derived: float  #: SI (N/m, N s/m, kg, kg m^2), at the zone's middle
    published: float | None  #: SI, Table 2
    published_text: str  #: Table 2 as printed
    as_printed: float | None  #: SI, the derived value in the paper's reading
    ratio_min: float  #: derived/published, min over the zone's start, middle, end
    ratio_max: float  #: derived/published, max over the zone's start, middle, end
    reproduced: bool  #: within the tolerance
    explanation: str  #: why not reproduced ("" if it is)
    reading_value: Any  #: the value of an alternative reading of the paper, if any


@dataclass(frozen=True, kw_only=True)
class ParameterMetrics(Record):
    """Appendix A: derived vs published parameters."""

    tolerance: float  #: relative, reproduced if |ratio - 1| <= tolerance
    rows: list[ParameterRow]  #: one per entry of Table 2
    reproduced: int  #: entries reproduced
    entries: int  #: entries compared
    published_zones: list[int]  #: zones with a published set
    #: zone -> parameter -> SI value (a turnout without a published set)
    derived: dict[str, dict[str, float]] | None = optional()


@dataclass(frozen=True, kw_only=True)
class PaperStiffness(Record):
    """The paper's Eqs 10, 14 on the report's x grid, and Eq 2 of the plain track."""

    x_m: list[float]  #: m
    K_sw_N_per_m: list[float]  #: N/m, Eq 10
    K_sh_N_per_m: list[float]  #: N/m, Eq 14
    K_st_z_N_per_m: float  #: N/m, Eq 2 vertical
    K_st_y_N_per_m: float  #: N/m, Eq 2 lateral


@dataclass(frozen=True, kw_only=True)
class FEInfo(Record):
    """Where an FE result came from: computed in this run, the cache, or why it is missing."""

    cached: bool | None = optional()  #: read from the cache
    wall_time_s: float | None = optional()  #: s, when it was computed
    computed: str | None = optional()  #: date and time it was computed
    note: str | None = optional()  #: why it is not available
    error: str | None = optional()  #: why it failed (one line)


@dataclass(frozen=True, kw_only=True)
class RailStiffness(Record):
    """FE static stiffness range of one rail."""

    name: str  #: description of the rail
    x_range_m: list[float]  #: m, first and last sleeper
    K_z_min: float  #: N/m
    K_z_max: float  #: N/m
    K_y_min: float  #: N/m
    K_y_max: float  #: N/m
    n_sleepers: int  #: sleepers under the rail


@dataclass(frozen=True, kw_only=True)
class FitPoint(Record):
    """A fit of the FE stiffness against the paper's at one x."""

    x_m: float  #: m
    fit_N_per_m: float  #: N/m, our fit
    paper_N_per_m: float  #: N/m, the paper's polynomial
    ratio: float  #: fit / paper


@dataclass(frozen=True, kw_only=True)
class StiffnessFit(Record):
    """A polynomial fit of the FE stiffness (N/m, x in m) against the paper's."""

    rail: str  #: the rail fitted
    coefficients: list[float]  #: N/m per m^k, k = 0, 1, ...
    x_range_m: list[float]  #: m
    r_squared: float  #: coefficient of determination
    n_points: int  #: sleepers fitted
    paper_coefficients: list[float]  #: N/m per m^k, the paper's
    at_x: list[FitPoint]  #: comparison at three x


@dataclass(frozen=True, kw_only=True)
class StiffnessAt(Record):
    """Vertical stiffness of a rail and of the stock rail at one x."""

    x_m: float  #: m
    K_z: float  #: N/m
    stock_K_z: float  #: N/m


@dataclass(frozen=True, kw_only=True)
class StiffnessStatements(Record):
    """The numbers behind the paper's Section 2 statements on Fig. 1(b,c)."""

    stock_rail: str  #: the reference stock rail
    switch_rail: str  #: the reference switch rail
    stock_plain_K_z: float  #: N/m, mean before the toe
    stock_K_z_spread: list[float]  #: relative to the plain value, min and max
    switch_toe: StiffnessAt  #: first sleeper of the switch rail
    switch_plateau: StiffnessAt  #: end of the Eq 10 polynomial
    crossing_over_stock_K_z: float  #: ratio in the crossing region
    crossing_x_range_m: list[float]  #: m
    lateral_end_over_start: dict[str, float]  #: rail -> K_y ratio end/start
    check_over_running_K_y: dict[str, float]  #: check rail -> K_y ratio to the running rail


@dataclass(frozen=True, kw_only=True)
class StiffnessMetrics(Record):
    """Section 1: FE static stiffness along the turnout, fits, the paper's equations."""

    paper: PaperStiffness
    available: bool  #: whether the FE profile was computed
    reference_rail_type: str | None = optional()  #: plain-track rail type of Eq 2
    note: str | None = optional()  #: why the FE profile is not available
    fe: FEInfo | None = optional()  #: where the FE profile came from
    fe_n_dof: dict[str, int] | None = optional()  #: "vertical"/"lateral" -> coordinates
    rails: dict[str, RailStiffness] | None = optional()  #: rail -> ranges
    fits: dict[str, StiffnessFit] | None = optional()  #: "K_sw", "K_sh" -> fit
    statements: StiffnessStatements | None = optional()
    #: "vertical"/"lateral" -> [min, max] of 2-layer over FE static stiffness
    co_running_over_FE: dict[str, list[float]] | None = optional()
    co_running_slot: str | None = optional()  #: the co-running rail slot compared
    co_running_zones: list[int] | None = optional()  #: zones where it is active


@dataclass(frozen=True, kw_only=True)
class ReceptancePosition(Record):
    """Where a receptance is taken."""

    rail: str  #: co-running rail slot
    x_m: float  #: m


@dataclass(frozen=True, kw_only=True)
class FrequencyGrid(Record):
    """The receptance frequencies."""

    n: int  #: number, log-spaced
    f_min_hz: float  #: Hz
    f_max_hz: float  #: Hz


@dataclass(frozen=True, kw_only=True)
class ReceptanceModel(Record):
    """One model's receptance against FE (the band levels of FE itself are absent)."""

    range_rms_db: dict[str, float] | None = optional()  #: dB per frequency range
    band_rms_db: dict[str, float] | None = optional()  #: dB per 1/3-octave band centre
    peaks_hz: list[float]  #: Hz, main peaks
    static_stiffness_N_per_m: float  #: N/m, 1/|H(1 Hz)|
    static_stiffness_ratio_to_FE: float  #: over FE's
    pinned_pinned_bands_rms_db: float | None = optional()  #: dB over the pinned-pinned bands


@dataclass(frozen=True, kw_only=True)
class ReceptanceCase(Record):
    """One receptance case (rail x direction): the three models and the pinned-pinned mode."""

    pinned_pinned_hz: float  #: Hz
    excluded_bands_hz: list[float]  #: Hz, band centres left out near f_pp
    models: dict[str, ReceptanceModel]  #: "2-layer", "3-layer", "FE" (+ "FE torsion")
    fe_peak_near_pinned_pinned_hz: float | None  #: Hz, None: no FE peak near f_pp
    fe_dip_near_pinned_pinned_hz: float | None  #: Hz, None: no FE dip near f_pp
    #: the FE the models are compared with ("FE"): the paper's kind (planar lateral)
    fe_reference: str | None = optional()
    #: lateral cases: the co-running models and the planar FE against the torsion-aware FE
    #: at the gauge corner (ours, beyond the paper), as ``models`` against "FE"
    vs_fe_torsion: dict[str, ReceptanceModel] | None = optional()
    rail: str  #: rail slot
    direction: str  #: "vertical" or "lateral"
    x_m: float  #: m
    zone: int  #: zone index at x
    rail_type: str  #: rail type at x
    distance_to_sleeper_m: float  #: m, to the nearest FE sleeper
    fe: FEInfo  #: where the FE receptance came from
    co_running_wall_time_s: float  #: s, one co-running receptance
    fe_n_dof: int | None  #: FE coordinates


@dataclass(frozen=True, kw_only=True)
class CheckRailReceptance(Record):
    """The check rail's lateral dynamic stiffness at its entry: FE vs co-running."""

    route: str  #: the report route whose check rail it is
    rail: str  #: co-running slot
    fe_rail: str  #: FE layout rail id
    x_m: float  #: m, the end of the entry flare
    frequencies_hz: list[float]  #: Hz (1 Hz: the static stiffness)
    #: N/m, 1 / |H(f)| per model ("FE (L-bracket, gauge corner)", "2-layer, bracket", ...)
    dynamic_stiffness_N_per_m: dict[str, list[float]]


@dataclass(frozen=True, kw_only=True)
class ReceptanceMetrics(Record):
    """Section 2: the receptance cases."""

    positions: dict[str, ReceptancePosition]  #: "switch rail", "crossing rail"
    cases: dict[str, ReceptanceCase]  #: "<position>, <direction>"
    frequencies: FrequencyGrid
    route: str | None = optional()  #: the receptance route
    wheel: str | None = optional()  #: the wheel whose path gives the positions
    check_rail: CheckRailReceptance | None = optional()  #: the check rail at its entry


@dataclass(frozen=True, kw_only=True)
class VsFE(Record):
    """A co-running passage against the FE passage, per signal."""

    peak_relative: dict[str, float]  #: |peak| / |peak_FE| - 1
    rms_difference_N: dict[str, float]  #: N
    trend_deviation: dict[str, float]  #: running-mean difference over the static load


@dataclass(frozen=True, kw_only=True)
class CheckRailEvent(Record):
    """A passage's check-rail event (:func:`~exudyn_turnout.passage.events.event_summary`)."""

    wheel: str  #: the wheel whose flange back meets the check rail
    rail: str  #: rail slot of the check rail
    region_m: list[float]  #: m, the check range
    peak_Fy_N: float  #: N, signed, largest |Fy| on the check rail
    x_m: float  #: m, where
    impulse_Ns: float  #: N s, integral of |Fy| on the check rail over time
    min_tread_Fz_N: float  #: N, least vertical force on that wheel's other contacts
    tread_unloaded: bool  #: whether that tread unloaded (below 1 % of its static load)


@dataclass(frozen=True, kw_only=True)
class PassageModel(Record):
    """One passage (a route on one track)."""

    peaks_N: dict[str, float]  #: N per signal ("Fz_crossing"...), Fy signed
    dynamic_rms_N: dict[str, float]  #: N per signal, about the running mean
    contact_losses: int  #: both wheels
    static_wheel_load_N: float  #: N, at the start
    wall_time_s: float  #: s
    simulated_time_s: float  #: s
    check_rail: CheckRailEvent | None = optional()  #: the check-rail event, if the run has one
    vs_FE: VsFE | None = optional()  #: co-running passages with an FE reference


@dataclass(frozen=True, kw_only=True)
class PassageRoute(Record):
    """The passages of one report route."""

    signals: list[str]  #: signals the claims are judged on
    all_signals: list[str] | None = optional()  #: every signal in the tables
    fe: FEInfo | None  #: where the FE passage came from; None: not run
    models: dict[str, PassageModel]  #: "2-layer", "3-layer", "FE"
    wheel: str | None = optional()  #: the plotted wheel
    fe_compared: list[str]  #: signals with an FE reference
    co_running_wall_times_s: dict[str, list[float]]  #: s, every timed run per model


@dataclass(frozen=True, kw_only=True)
class PassageMetrics(Record):
    """Section 3: contact forces of the report's passages."""

    speeds_kmh: dict[str, float]  #: km/h per route
    regions_m: dict[str, list[float]]  #: m, "switch"/"crossing" -> [from, to]
    routes: dict[str, PassageRoute]
    steady_lateral_acceleration_m_s2: dict[str, float]  #: m/s^2 per route
    radius_m: dict[str, float | None] | None = optional()  #: m per route, None: straight
    speeds_note: str | None = optional()  #: where the speeds come from
    impact_route: str | None = optional()  #: route of the crossing impact claims
    lateral_route: str | None = optional()  #: route of the lateral claim (Fig. 8)
    fe_available: bool  #: whether the FE passage could run
    fe_note: str  #: why not ("" if it could)
    wheel: dict[str, str] | str | None = optional()  #: plotted wheel per route (older: one)
    x_range_m: list[float]  #: m, front wheelset
    contact: str | None = optional()  #: "profile" or "height-table"
    vehicle: str | None = optional()  #: "full" or "wheelset"
    vehicle_name: str | None = optional()  #: description of the vehicle
    static_wheel_load_N: float | None = optional()  #: N, the vehicle's
    fe_coupling: str | None = optional()  #: how the FE track is coupled


@dataclass(frozen=True, kw_only=True)
class FERun(Record):
    """Size and wall-time split of one FE passage."""

    n_dof: int | None  #: FE coordinates
    time_step_s: float | None  #: s
    n_steps: int | None  #: time steps
    wall_time_parts_s: dict[str, float] | None  #: s per part of the run


@dataclass(frozen=True, kw_only=True)
class ReceptanceWallTime(Record):
    """Wall times of one receptance case."""

    co_running: float = field(metadata={"key": "co-running"})  #: s, one co-running model
    FE: float  #: s, the FE receptance (when it was computed)
    FE_cached: bool  #: read from the cache


@dataclass(frozen=True, kw_only=True)
class CostMetrics(Record):
    """Section 4: computing cost."""

    repeats: int  #: timed runs per co-running passage
    wall_time_s: dict[str, dict[str, float]]  #: s, route -> model -> best run
    median_wall_time_s: dict[str, dict[str, float]]  #: s, route -> model -> median
    simulated_time_s: dict[str, float]  #: s per route
    ratio_3_over_2: dict[str, float]  #: paired median per route
    best_ratio_3_over_2: dict[str, float]  #: of the best runs per route
    ratio_FE_over_3: dict[str, float]  #: FE over the 3-layer median per route
    fe_run: dict[str, FERun]  #: per route with an FE passage
    dof_per_zone: dict[str, dict[str, int]]  #: zone -> model -> coordinates
    extra_dof_per_zone: dict[str, int]  #: zone -> 3-layer minus 2-layer coordinates
    receptance_wall_time_s: dict[str, ReceptanceWallTime]  #: per receptance case


@dataclass(frozen=True, kw_only=True)
class PeakChange(Record):
    """A peak force at the report's time step and at half of it."""

    h_N: float  #: N
    h_half_N: float  #: N
    relative_change: float  #: h/2 over h, minus 1


@dataclass(frozen=True, kw_only=True)
class ConvergenceMetrics(Record):
    """Section 5: time-step convergence of the co-running passages."""

    time_step_s: float  #: s
    half_step_s: float  #: s
    runs: dict[str, dict[str, PeakChange]]  #: "<route>, <model>" -> signal -> change
    max_relative_change: float  #: largest |relative change|
    converged: bool | None  #: None: nothing to compare


@dataclass(frozen=True, kw_only=True)
class StaticWheelLoad(Record):
    """Static wheel loads at the start of one passage against the expected one W."""

    right_N: float  #: N
    left_N: float  #: N
    mean_N: float  #: N
    right_relative: float  #: right / W - 1
    left_relative: float  #: left / W - 1
    mean_relative: float  #: mean / W - 1


@dataclass(frozen=True, kw_only=True)
class CheckMetrics(Record):
    """Section 5: static checks."""

    vehicle: str | None = optional()  #: "full" or "wheelset"
    m_w_kg: float  #: kg, wheelset mass
    m_s_kg: float  #: kg, sprung share of the single wheelset
    vehicle_mass_kg: float | None = optional()  #: kg, the report vehicle's
    expected_static_wheel_load_N: float  #: N, W
    static_wheel_load: dict[str, StaticWheelLoad]  #: "<route>, <model>" -> loads
    static_wheel_load_ok: bool  #: every mean within the tolerance
    start_x_m: dict[str, float]  #: m per route
    start_rail_y_m: dict[str, dict[str, float]]  #: m, route -> rail slot -> y at the start
    max_split_relative: float  #: largest single-wheel |relative difference|
    #: receptance case -> model -> static stiffness over FE's
    static_stiffness_ratio_to_FE: dict[str, dict[str, float]]


@dataclass(frozen=True, kw_only=True)
class ReportMetrics(Record):
    """The whole ``metrics.json`` of a report."""

    turnout: str  #: the turnout's name
    turnout_file: str  #: its file name
    turnout_sha256: str  #: SHA-256 of its file
    config: ConfigMetrics
    criteria: Criteria
    parameters: ParameterMetrics
    stiffness: StiffnessMetrics
    receptance: ReceptanceMetrics
    passage: PassageMetrics
    cost: CostMetrics
    convergence: ConvergenceMetrics
    checks: CheckMetrics
    claims: list[Claim] | None = optional()  #: the verdicts (absent before they are judged)
    compute_wall_time_s: float | None = optional()  #: s, computing the numbers
    report_wall_time_s: float | None = optional()  #: s, with figures and files
    provenance: dict[str, Any] | None = optional()  #: what ran, where, when (the CLI's)
