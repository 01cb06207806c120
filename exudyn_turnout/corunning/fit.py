"""Co-running parameters fitted to a reference receptance (the FE model's): the ``fitted`` source.

The paper derives its co-running parameters from Eqs 1-19 and names fitting them to the FE
receptance as another route (its reference [8]). This module does that fit, keeping the
paper's model structure (the springs, dampers and masses of Figs 2, 3; only their values
change):

Objective (:func:`fit_position`)
    For each target (a rail slot and a direction, with the reference receptance H_FE at
    x), the level difference d(f) = 20 log10(|H_model(f)| / |H_FE(f)|) (dB) is grouped in
    one-third-octave bands (base 10, centres 10^(n/10) Hz, IEC 61260) from ``f_min`` to
    ``f_max``; each band contributes its mean square d^2 once, however many frequencies
    it holds, with weight 1, or ``pinned_pinned_weight`` for the band holding the
    target's pinned-pinned frequency and ``pinned_pinned_neighbours`` bands either side
    (the co-running model has no discrete supports, so it cannot have that resonance).
    A static term, d at the lowest frequency with the weight of ten bands
    (``static_weight``), holds the static stiffness 1/|H(f_min)|. The sum over targets
    (vertical and lateral of every loaded rail) is minimised: a weighted band RMS.
Parameters and bounds
    Every spring and damper of the rails with a target (k_rt, c_rt, k_0, c_0 in both
    directions), the ballast springs and dampers of the sleeper, and the masses m_rj, m_t
    (J_t scales with m_t, Eq 19) and m_0. Stiffness and damping stay within a factor
    ``stiffness_factor`` (default 10) of the start (derived) value, masses within
    ``mass_factor`` (default 3): positive and physical by construction.
Optimiser
    :func:`scipy.optimize.least_squares`, method ``"trf"`` (trust-region reflective), on
    the natural logarithms of the parameters: the residuals are level differences in dB,
    nearly linear in log-parameters; the parameters span eight decades (2.5 kg to 1e9
    N/m), which log scaling equalises; "trf" handles the box bounds directly (Levenberg-
    Marquardt does not), and with a forward-difference Jacobian, one start (the derived
    set) and no random restarts the fit is deterministic: the same inputs give the same
    numbers, bit for bit, on the same machine.
Along the turnout (:func:`fit_zone`)
    Each position of a zone is fitted on its own; then the masses are fixed at their
    median over the zone's positions (masses are constant per zone, as in the paper)
    and the springs and dampers refitted. The result is a table per entry, piecewise
    linear in the relative zone position (:class:`~exudyn_turnout.corunning.fitted.TableEntry`).

The reference receptances are inputs: this module does not compute them (``fe/`` comes
after ``corunning/`` in the package's stage order); ``exudyn_turnout.cli.fit`` takes them
from the FE model.
"""

from __future__ import annotations

import dataclasses
import math
import statistics
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.optimize

from exudyn_turnout.corunning.fitted import FittedSet, TableEntry
from exudyn_turnout.corunning.modal import (
    TrackMatrices,
    assemble_track_matrices,
    receptance_from_matrices,
    wheel_dof,
)
from exudyn_turnout.corunning.parameters import CoRunningParameters
from exudyn_turnout.inputs.turnout import RAIL_SLOTS, Entry
from exudyn_turnout.receptance import Receptance

__all__ = [
    "FitOptions",
    "FitTarget",
    "TargetResidual",
    "PositionFit",
    "ZoneFit",
    "OPTIMISER",
    "third_octave_centres",
    "band_rms_db",
    "range_rms_db",
    "free_parameters",
    "parameters_with_values",
    "model_receptance",
    "fit_position",
    "fit_zone",
    "fitted_set",
]

#: What the fit uses, for the provenance of a fitted file.
OPTIMISER = (
    "scipy.optimize.least_squares, method trf (trust-region reflective), log-parameters "
    "with box bounds, forward-difference Jacobian, start: derived set"
)

_HALF_BAND = 10.0 ** (1.0 / 20.0)  # upper edge / centre of a base-10 one-third-octave band


@dataclass(frozen=True)
class FitOptions:
    """Frequency range, weights, bounds and stopping rules of a fit."""

    f_min: float = 1.0  #: Hz, nominal lowest band centre
    f_max: float = 2000.0  #: Hz, nominal highest band centre
    pinned_pinned_weight: float = 0.1  #: -, weight of the pinned-pinned bands (others 1)
    pinned_pinned_neighbours: int = 1  #: bands either side of the pinned-pinned band
    #: -, weight of the static term (a band's is 1): the static stiffness is a goal of its
    #: own (within 5 % of FE), and at 10 it costs < 0.15 dB in any range (measured at x = 29.1 m)
    static_weight: float = 10.0
    stiffness_factor: float = 10.0  #: -, springs and dampers within start / f .. start * f
    mass_factor: float = 3.0  #: -, masses within start / f .. start * f
    max_nfev: int = 400  #: most residual evaluations (Jacobian evaluations not counted)
    tolerance: float = 1e-8  #: -, ftol, xtol and gtol of least_squares


@dataclass(frozen=True)
class FitTarget:
    """A receptance the model should match: a rail slot and direction at the fit position."""

    rail: str  #: rail slot "r1".."r4"
    direction: str  #: "vertical" or "lateral"
    reference: Receptance  #: m/N, the reference (FE) point receptance at the position
    pinned_pinned_hz: float | None = None  #: Hz, its bands are down-weighted; None: none


@dataclass(frozen=True)
class TargetResidual:
    """Band RMS (dB) of 20 log10(|H_model| / |H_ref|) of one target, start and fitted set."""

    rail: str  #: rail slot
    direction: str  #: "vertical" or "lateral"
    band_centres_hz: tuple[float, ...]  #: Hz, bands that hold frequencies
    start_db: tuple[float, ...]  #: dB, start (derived) set, per band
    fitted_db: tuple[float, ...]  #: dB, fitted set, per band
    pinned_pinned_bands_hz: tuple[float, ...]  #: Hz, the down-weighted band centres
    static_ratio_start: float  #: -, static stiffness of the start set / reference's
    static_ratio_fitted: float  #: -, static stiffness of the fitted set / reference's

    def range_rms(
        self, lo: float, hi: float, fitted: bool = True, exclude_pp: bool = True
    ) -> float:
        """RMS (dB) over the bands whose centre lies in a nominal range.

        Parameters
        ----------
        lo, hi : float
            Hz, nominal range of band centres (e.g. 125, 500).
        fitted : bool
            The fitted set (True) or the start set.
        exclude_pp : bool
            Leave out the pinned-pinned bands.

        Returns
        -------
        float
            dB; NaN when no band is left.
        """
        values = dict(zip(self.band_centres_hz, self.fitted_db if fitted else self.start_db))
        exclude = self.pinned_pinned_bands_hz if exclude_pp else ()
        return range_rms_db(values, lo, hi, exclude)


@dataclass(frozen=True)
class PositionFit:
    """The fit at one position: values, what was free, residuals, optimiser outcome."""

    zone: int  #: zone index
    x: float  #: m, position from the switch toe
    values: Mapping[str, float]  #: SI, every entry of the set after the fit
    start: Mapping[str, float]  #: SI, the start (derived) values
    free: tuple[str, ...]  #: names of the fitted entries (J_t follows m_t)
    cost_start: float  #: dB^2, weighted objective at the start
    cost: float  #: dB^2, weighted objective after the fit
    nfev: int  #: residual evaluations
    message: str  #: the optimiser's termination message
    residuals: tuple[TargetResidual, ...]  #: per target


@dataclass(frozen=True)
class ZoneFit:
    """The fits of one zone along x (masses fixed per zone in the final pass)."""

    zone: int  #: zone index
    x_start: float  #: m, zone start
    x_end: float  #: m, zone end
    positions: tuple[PositionFit, ...]  #: final fits, increasing x
    names: tuple[str, ...]  #: fitted entry names (with J_t if m_t was fitted)
    masses: Mapping[str, float] = field(default_factory=dict)  #: kg, fixed per zone

    @property
    def s(self) -> tuple[float, ...]:
        """Relative zone positions (-) of the fits."""
        return tuple((p.x - self.x_start) / (self.x_end - self.x_start) for p in self.positions)

    def entries(self) -> dict[str, Entry]:
        """The fitted entries: tables in s, masses (and single positions) constants.

        Returns
        -------
        dict of str to Entry
            Name to :class:`~exudyn_turnout.corunning.fitted.TableEntry` or a constant
            :class:`~exudyn_turnout.inputs.turnout.Entry`.
        """
        out: dict[str, Entry] = {}
        for name in self.names:
            values = [p.values[name] for p in self.positions]
            if name in self.masses or len(values) == 1 or len(set(values)) == 1:
                out[name] = Entry("const", float(values[0]))
            else:
                out[name] = TableEntry.of(self.s, values)
        return out


def third_octave_centres(f_min: float, f_max: float) -> np.ndarray:
    """Base-10 one-third-octave centres 10^(n/10) (Hz) whose nominal value lies in the range.

    IEC 61260; the bounds match nominal values (125 Hz is 10^2.1 = 125.9 Hz).

    Parameters
    ----------
    f_min, f_max : float
        Hz, nominal range.

    Returns
    -------
    numpy.ndarray
        Hz, ascending.
    """
    n_lo = math.ceil(10.0 * math.log10(f_min) - 0.5)
    n_hi = math.floor(10.0 * math.log10(f_max) + 0.5)
    return 10.0 ** (np.arange(n_lo, n_hi + 1) / 10.0)


def _band_members(frequency: np.ndarray, centres: np.ndarray) -> list[tuple[float, np.ndarray]]:
    """(centre, indices of the frequencies in [centre / 10^0.05, centre * 10^0.05)), non-empty."""
    out = []
    for c in centres:
        sel = np.nonzero((frequency >= c / _HALF_BAND) & (frequency < c * _HALF_BAND))[0]
        if sel.size:
            out.append((float(c), sel))
    return out


def band_rms_db(
    frequency_hz: np.ndarray, H_model: np.ndarray, H_ref: np.ndarray, f_min: float, f_max: float
) -> dict[float, float]:
    """Per one-third-octave band, the RMS (dB) of 20 log10(|H_model| / |H_ref|).

    Parameters
    ----------
    frequency_hz : array_like
        Hz, the frequencies of both receptances.
    H_model, H_ref : array_like
        Complex receptances (m/N).
    f_min, f_max : float
        Hz, nominal range of band centres.

    Returns
    -------
    dict
        Band centre (Hz) -> RMS (dB), bands without a frequency left out.
    """
    f = np.asarray(frequency_hz, float)
    d = 20.0 * np.log10(np.abs(np.asarray(H_model)) / np.abs(np.asarray(H_ref)))
    return {
        c: float(np.sqrt(np.mean(d[sel] ** 2)))
        for c, sel in _band_members(f, third_octave_centres(f_min, f_max))
    }


def range_rms_db(
    band_values: Mapping[float, float], lo: float, hi: float, exclude: Sequence[float] = ()
) -> float:
    """RMS (dB) of the band values whose centre lies in a nominal range, some bands left out.

    Parameters
    ----------
    band_values : mapping
        Band centre (Hz) -> band RMS (dB).
    lo, hi : float
        Hz, nominal range of centres (:func:`third_octave_centres`).
    exclude : sequence of float
        Band centres (Hz) to leave out.

    Returns
    -------
    float
        dB; NaN when no band is left.
    """
    wanted = third_octave_centres(lo, hi)
    values = [
        v
        for c, v in band_values.items()
        if np.any(np.isclose(c, wanted, rtol=1e-9))
        and not np.any(np.isclose(c, np.asarray(exclude, float), rtol=1e-9))
    ]
    return float(np.sqrt(np.mean(np.square(values)))) if values else math.nan


def _pinned_pinned_bands(f_pp: float | None, neighbours: int) -> tuple[float, ...]:
    if f_pp is None or not math.isfinite(f_pp) or f_pp <= 0:
        return ()
    n = round(10.0 * math.log10(f_pp))
    return tuple(float(10.0 ** (k / 10.0)) for k in range(n - neighbours, n + neighbours + 1))


def free_parameters(params: CoRunningParameters, rails: Sequence[str]) -> tuple[str, ...]:
    """Entries a fit adjusts: those of the loaded rails, the sleeper's ballast and the masses.

    Parameters
    ----------
    params : CoRunningParameters
        The start set (its layers decide whether k_0, c_0, m_0 exist).
    rails : sequence of str
        Rail slots with a target.

    Returns
    -------
    tuple of str
        Entry names in Table 2 order; J_t is not among them (it follows m_t, Eq 19).
    """
    names: set[str] = set()
    for rail in rails:
        j = rail[1:]
        names.update(f"{p}{j}_{d}" for p in ("k_rt", "c_rt", "k_0", "c_0") for d in ("z", "y"))
        names.add(f"m_r{j}")
    names.update(("k_tg1_z", "c_tg1_z", "k_tg2_z", "c_tg2_z", "k_tg_y", "c_tg_y", "m_t", "m_0"))
    return tuple(n for n in params.entries if n in names)


def parameters_with_values(
    params: CoRunningParameters, values: Mapping[str, float]
) -> CoRunningParameters:
    """The set with every entry a constant of the given values (the model at one position).

    Parameters
    ----------
    params : CoRunningParameters
        Zone, layers and entry names to keep.
    values : mapping
        SI value of every entry name.

    Returns
    -------
    CoRunningParameters
        Same zone and layers, constant entries.
    """
    return dataclasses.replace(
        params, entries={name: Entry("const", float(values[name])) for name in params.entries}
    )


def model_receptance(
    params: CoRunningParameters, x: float, rail: str, direction: str, frequency_hz: np.ndarray
) -> np.ndarray:
    """Point receptance (m/N) of a rail of the co-running model, as the fit evaluates it.

    The same computation as :func:`~exudyn_turnout.corunning.modal.co_running_receptance`
    (matrices assembled by hand, modal superposition).

    Parameters
    ----------
    params : CoRunningParameters
        Any parameter set.
    x : float
        m, position (in the set's zone).
    rail : str
        Rail slot.
    direction : {"vertical", "lateral"}
        Direction.
    frequency_hz : array_like
        Hz.

    Returns
    -------
    numpy.ndarray
        Complex receptance (m/N).
    """
    matrices = assemble_track_matrices(params, x)
    return receptance_from_matrices(
        matrices, wheel_dof(rail, direction, params.layers), np.asarray(frequency_hz, float)
    )


@dataclass(frozen=True)
class _Weights:
    """Residual weights of one target: per frequency (bands) and of the static term."""

    target: FitTarget
    frequency: np.ndarray  #: Hz, the frequencies used
    H_ref: np.ndarray  #: m/N
    scale: np.ndarray  #: per frequency, sqrt(w_b / (n_b W))
    static_scale: float  #: sqrt(w_static / W)
    members: tuple[tuple[float, np.ndarray], ...]  #: bands and their frequency indices
    pp_bands: tuple[float, ...]  #: Hz


def _weights(target: FitTarget, options: FitOptions) -> _Weights:
    f, H = np.asarray(target.reference.frequency_hz, float), np.asarray(target.reference.H)
    members = _band_members(f, third_octave_centres(options.f_min, options.f_max))
    if not members:
        raise ValueError(
            f"target {target.rail} {target.direction}: no frequency in the bands "
            f"{options.f_min:g}-{options.f_max:g} Hz"
        )
    pp = _pinned_pinned_bands(target.pinned_pinned_hz, options.pinned_pinned_neighbours)
    used = np.concatenate([sel for _, sel in members])
    band_w = [
        options.pinned_pinned_weight if np.any(np.isclose(c, pp, rtol=1e-6)) else 1.0
        for c, _ in members
    ]
    total = sum(band_w) + options.static_weight
    scale = np.zeros(len(f))
    for (_, sel), w in zip(members, band_w):
        scale[sel] = math.sqrt(w / (len(sel) * total))
    keep = np.sort(used)
    members_kept = tuple((c, np.searchsorted(keep, sel)) for c, sel in members)
    return _Weights(
        target,
        f[keep],
        H[keep],
        scale[keep],
        math.sqrt(options.static_weight / total),
        members_kept,
        pp,
    )


def _level(H: np.ndarray, H_ref: np.ndarray) -> np.ndarray:
    return 20.0 * np.log10(np.abs(H) / np.abs(H_ref))


def _receptances(
    matrices: TrackMatrices, dofs: Sequence[str], frequencies: Sequence[np.ndarray]
) -> list[np.ndarray]:
    """Point receptances at several coordinates from one eigen-decomposition.

    The modal sum of :func:`~exudyn_turnout.corunning.modal.receptance_from_matrices`
    (H(s) = sum_k c_k b_k / (s - lambda_k) of the first-order system), shared by all
    coordinates and summed with einsum (a complex matrix-vector product through BLAS took
    ~100 times longer on the shared 2-core machine); a direct solve where the
    eigenvectors are nearly dependent.
    """
    M, K, D = matrices.M, matrices.K, matrices.D
    n = M.shape[0]
    Minv = np.linalg.inv(M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ D]])
    lam, V = scipy.linalg.eig(A)
    if np.linalg.cond(V) > 1e10:
        return [
            receptance_from_matrices(matrices, dof, f, method="direct")
            for dof, f in zip(dofs, frequencies)
        ]
    index = [matrices.index(dof) for dof in dofs]
    B = np.zeros((2 * n, len(index)))
    B[n:, :] = Minv[:, index]
    residue = V[index, :].T * np.linalg.solve(V, B)  # (2n, targets)
    return [
        np.einsum("fm,m->f", 1.0 / (2j * math.pi * f[:, None] - lam[None, :]), residue[:, j])
        for j, f in enumerate(frequencies)
    ]


def _residual_vector(
    params: CoRunningParameters, x: float, values: Mapping[str, float], weights: Sequence[_Weights]
) -> np.ndarray:
    matrices = assemble_track_matrices(parameters_with_values(params, values), x)
    dofs = [wheel_dof(w.target.rail, w.target.direction, params.layers) for w in weights]
    parts = []
    for w, H in zip(weights, _receptances(matrices, dofs, [w.frequency for w in weights])):
        d = _level(H, w.H_ref)
        parts.append(w.scale * d)
        parts.append(np.array([w.static_scale * d[0]]))
    return np.concatenate(parts)


def _target_residual(
    params: CoRunningParameters,
    x: float,
    start: Mapping[str, float],
    fitted: Mapping[str, float],
    w: _Weights,
) -> TargetResidual:
    bands, ratios = {}, {}
    for key, values in (("start", start), ("fitted", fitted)):
        H = model_receptance(
            parameters_with_values(params, values),
            x,
            w.target.rail,
            w.target.direction,
            w.frequency,
        )
        d = _level(H, w.H_ref)
        bands[key] = tuple(float(np.sqrt(np.mean(d[sel] ** 2))) for _, sel in w.members)
        ratios[key] = float(abs(w.H_ref[0]) / abs(H[0]))
    return TargetResidual(
        w.target.rail,
        w.target.direction,
        tuple(c for c, _ in w.members),
        bands["start"],
        bands["fitted"],
        w.pp_bands,
        ratios["start"],
        ratios["fitted"],
    )


def _check_targets(params: CoRunningParameters, targets: Sequence[FitTarget]) -> None:
    if not targets:
        raise ValueError("a fit needs at least one target receptance")
    for t in targets:
        if t.rail not in RAIL_SLOTS or t.rail not in params.active_rails:
            raise ValueError(
                f"target rail {t.rail!r} is not active in zone {params.zone.index} "
                f"(active rails: {' '.join(params.active_rails)})"
            )
        if t.direction not in ("vertical", "lateral"):
            raise ValueError(f"target direction must be vertical or lateral, got {t.direction!r}")


def fit_position(
    params: CoRunningParameters,
    x: float,
    targets: Sequence[FitTarget],
    options: FitOptions = FitOptions(),
    *,
    start: Mapping[str, float] | None = None,
    fixed: Mapping[str, float] | None = None,
) -> PositionFit:
    """Fit the co-running parameters at one position to reference receptances.

    See the module docstring for the objective, the parameters, the bounds and the
    optimiser. The bounds are taken about ``params.at(x)`` (the derived set), whatever
    ``start`` is.

    Parameters
    ----------
    params : CoRunningParameters
        The set to start from and whose structure is kept (usually ``source="derived"``).
    x : float
        m, the position (inside the set's zone).
    targets : sequence of FitTarget
        Reference receptances at x: rail slot, direction, pinned-pinned frequency.
    options : FitOptions
        Range, weights, bounds.
    start : mapping, optional
        Start values (SI) of some entries (default: ``params.at(x)``).
    fixed : mapping, optional
        Entries held at these values (SI), e.g. masses fixed per zone.

    Returns
    -------
    PositionFit
        The fitted values, the residuals per target and band, start and final cost.

    Raises
    ------
    ValueError
        No target, a target on a rail that is not active, or no frequency in the range.
    """
    _check_targets(params, targets)
    at = params.at(x)
    base = {name: at[name] for name in params.entries}
    fixed = dict(fixed or {})
    initial = dict(base)
    initial.update({k: v for k, v in (start or {}).items() if k in base})
    initial.update({k: v for k, v in fixed.items() if k in base})
    if "m_t" in fixed and "J_t" in base:
        initial["J_t"] = base["J_t"] * fixed["m_t"] / base["m_t"]
    free = tuple(
        n for n in free_parameters(params, sorted({t.rail for t in targets})) if n not in fixed
    )
    weights = [_weights(t, options) for t in targets]
    lo = np.array([math.log(base[n] / _factor(n, options)) for n in free])
    hi = np.array([math.log(base[n] * _factor(n, options)) for n in free])
    theta0 = np.clip(np.log([initial[n] for n in free]), lo, hi)

    def values_of(theta: np.ndarray) -> dict[str, float]:
        values = dict(initial)
        values.update(zip(free, np.exp(theta).tolist()))
        if "m_t" in free and "J_t" in base:  # Eq 19: J_t proportional to m_t
            values["J_t"] = base["J_t"] * values["m_t"] / base["m_t"]
        return values

    def residuals(theta: np.ndarray) -> np.ndarray:
        return _residual_vector(params, x, values_of(theta), weights)

    r0 = residuals(theta0)
    if free:
        result = scipy.optimize.least_squares(
            residuals,
            theta0,
            bounds=(lo, hi),
            method="trf",
            jac="2-point",
            x_scale=1.0,
            ftol=options.tolerance,
            xtol=options.tolerance,
            gtol=options.tolerance,
            max_nfev=options.max_nfev,
        )
        theta, cost, nfev, message = result.x, 2.0 * result.cost, result.nfev, result.message
    else:
        theta, cost, nfev, message = theta0, float(r0 @ r0), 0, "nothing to fit"
    fitted = values_of(theta)
    names = free + (("J_t",) if "m_t" in free and "J_t" in base else ())
    return PositionFit(
        params.zone.index,
        float(x),
        fitted,
        base,
        names,
        float(r0 @ r0),
        float(cost),
        int(nfev),
        str(message),
        tuple(_target_residual(params, x, base, fitted, w) for w in weights),
    )


def _factor(name: str, options: FitOptions) -> float:
    return options.mass_factor if name.startswith(("m_", "J_")) else options.stiffness_factor


def fit_zone(
    params: CoRunningParameters,
    positions: Sequence[float],
    targets: Sequence[Sequence[FitTarget]],
    options: FitOptions = FitOptions(),
    progress: Callable[[str], None] | None = None,
) -> ZoneFit:
    """Fit a zone at several positions; masses constant over the zone.

    Pass 1 fits every position on its own (masses free); the masses are then fixed at their
    median over the positions and pass 2 refits the springs and dampers from the pass-1
    values. With one position there is one pass. A rail without a target at a position
    (e.g. the switch rail slot ahead of the toe, where the FE model has no switch rail)
    keeps its start values there.

    Parameters
    ----------
    params : CoRunningParameters
        Start set of the zone (usually derived).
    positions : sequence of float
        m, strictly increasing positions inside the zone.
    targets : sequence of sequence of FitTarget
        The reference receptances at each position.
    options : FitOptions
        Range, weights, bounds.
    progress : callable(str), optional
        Called with a short message after each position's fit.

    Returns
    -------
    ZoneFit
        The final fits; :meth:`ZoneFit.entries` gives the entries as functions of x.

    Raises
    ------
    ValueError
        Positions not increasing or outside the zone, or a target problem.
    """
    xs = [float(x) for x in positions]
    if len(xs) != len(targets) or not xs:
        raise ValueError("give one list of targets per position (and at least one position)")
    if any(b <= a for a, b in zip(xs, xs[1:])):
        raise ValueError(f"positions must increase, got {xs}")
    zone = params.zone
    for x in xs:
        if not zone.contains(x):
            raise ValueError(f"x = {x:g} m is outside zone {zone.index}")

    def fit_all(label: str, **kwargs: Any) -> list[PositionFit]:
        out = []
        for i, (x, t) in enumerate(zip(xs, targets)):
            extra = {k: v[i] if isinstance(v, list) else v for k, v in kwargs.items()}
            out.append(fit_position(params, x, t, options, **extra))
            if progress is not None:
                progress(
                    f"zone {zone.index} {label}: x = {x:g} m ({i + 1}/{len(xs)}), "
                    f"objective {out[-1].cost_start:.2f} -> {out[-1].cost:.2f} dB^2"
                )
        return out

    first = fit_all("pass 1")
    names = tuple(n for n in params.entries if any(n in p.free for p in first))
    masses: dict[str, float] = {}
    final = first
    if len(xs) > 1:
        masses = {
            n: float(statistics.median(p.values[n] for p in first if n in p.free))
            for n in names
            if n.startswith("m_")
        }
        final = fit_all("pass 2 (masses fixed)", start=[p.values for p in first], fixed=masses)
        if "m_t" in masses and "J_t" in params.entries:
            masses["J_t"] = final[0].values["J_t"]
    return ZoneFit(zone.index, zone.x_start, zone.x_end, tuple(final), names, masses)


def fitted_set(
    zone_fits: Sequence[ZoneFit],
    layers: int,
    provenance: Mapping[str, object],
    options: FitOptions = FitOptions(),
) -> FittedSet:
    """The fitted set of a turnout from its zone fits (what ``exudyn-turnout fit`` writes).

    Parameters
    ----------
    zone_fits : sequence of ZoneFit
        From :func:`fit_zone`, one per zone fitted.
    layers : {2, 3}
        The model fitted.
    provenance : mapping
        Turnout file and hash, FE options, route, command... (written to ``[fitted]``).
    options : FitOptions
        The options used (recorded with the provenance).

    Returns
    -------
    FittedSet
        Entries per zone, positions, residuals per position, rail, direction and band.
    """
    entries, positions, residuals = {}, {}, {}
    for zf in zone_fits:
        entries[zf.zone] = zf.entries()
        positions[zf.zone] = (zf.s, tuple(p.x for p in zf.positions))
        residuals[zf.zone] = tuple(
            {
                "x_m": p.x,
                "rail": r.rail,
                "direction": r.direction,
                "band_centres_hz": list(r.band_centres_hz),
                "derived_db": list(r.start_db),
                "fitted_db": list(r.fitted_db),
                "pinned_pinned_bands_hz": list(r.pinned_pinned_bands_hz),
                "static_ratio_derived": r.static_ratio_start,
                "static_ratio_fitted": r.static_ratio_fitted,
                "cost_derived": p.cost_start,
                "cost_fitted": p.cost,
            }
            for p in zf.positions
            for r in p.residuals
        )
    record = dict(provenance)
    record.update(
        {
            "optimiser": OPTIMISER,
            "fit_options": {k: v for k, v in dataclasses.asdict(options).items() if v is not None},
        }
    )
    centres = third_octave_centres(options.f_min, options.f_max)
    return FittedSet(layers, entries, positions, record, tuple(centres.tolist()), residuals)
