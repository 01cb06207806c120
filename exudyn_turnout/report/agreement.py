"""Agreement metrics between models: receptance level differences, peaks, force signals.

Small pure functions on numpy arrays (no model code), used by the validation report
(:mod:`exudyn_turnout.report.metrics`):

- :func:`third_octave_centres`, :func:`band_edges`: base-10 one-third-octave bands
  (IEC 61260: centres 10^(n/10) Hz, edges centre * 10^(+-1/20));
- :func:`level_difference_db`: 20 log10(|H_model| / |H_ref|) at every frequency;
- :func:`band_rms_db`: per band, the RMS of that level difference over the frequencies in
  the band; :func:`range_rms_db`: the RMS of those band values over the bands whose centre
  lies in a frequency range (every band counts once, however many frequencies it holds);
- :func:`peak_frequencies`: the main peaks of |H| (local maxima of the level in dB with a
  minimum prominence);
- :func:`running_mean`, :func:`dynamic_rms`, :func:`rms_difference`: the slow part of a
  force signal along x, the RMS of what oscillates about it, the RMS difference of two
  signals on a common x grid, and :func:`max_trend_difference` of their running means.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

import numpy as np
import scipy.signal

__all__ = [
    "third_octave_centres",
    "band_edges",
    "level_difference_db",
    "band_rms_db",
    "range_rms_db",
    "bands_near",
    "peak_frequencies",
    "relative_difference",
    "running_mean",
    "dynamic_rms",
    "rms_difference",
    "max_trend_difference",
    "paired_median_ratio",
]

_HALF_BAND = 10.0 ** (1.0 / 20.0)  # ratio of a one-third-octave band's upper edge to its centre


def third_octave_centres(f_min: float, f_max: float) -> np.ndarray:
    """Exact base-10 one-third-octave centre frequencies 10^(n/10) (Hz) in [f_min, f_max].

    The bounds are compared with a tolerance of 1/20 decade, so nominal values work:
    ``third_octave_centres(1, 125)`` ends at 125.9 Hz (nominal 125 Hz).

    Parameters
    ----------
    f_min, f_max : float
        Hz, the (nominal) range.

    Returns
    -------
    numpy.ndarray
        Hz, ascending centres.
    """
    n_lo = math.ceil(10.0 * math.log10(f_min) - 0.5)
    n_hi = math.floor(10.0 * math.log10(f_max) + 0.5)
    return 10.0 ** (np.arange(n_lo, n_hi + 1) / 10.0)


def band_edges(centre: float) -> tuple[float, float]:
    """Lower and upper edge (Hz) of the one-third-octave band of this centre.

    Parameters
    ----------
    centre : float
        Hz, a band centre.

    Returns
    -------
    (float, float)
        Hz, lower and upper edge.
    """
    return centre / _HALF_BAND, centre * _HALF_BAND


def level_difference_db(H_model: np.ndarray, H_ref: np.ndarray) -> np.ndarray:
    """20 log10(|H_model| / |H_ref|) (dB) per frequency; both on the same frequencies.

    Parameters
    ----------
    H_model, H_ref : array_like
        Complex (or real) receptances on the same frequencies.

    Returns
    -------
    numpy.ndarray
        dB per frequency.
    """
    return 20.0 * np.log10(np.abs(np.asarray(H_model)) / np.abs(np.asarray(H_ref)))


def band_rms_db(
    frequency_hz: np.ndarray, diff_db: np.ndarray, centres: Iterable[float]
) -> dict[float, float]:
    """RMS (dB) of ``diff_db`` over the frequencies inside each band.

    Bands without a frequency are left out.

    Parameters
    ----------
    frequency_hz : array_like
        Hz, the frequencies of ``diff_db``.
    diff_db : array_like
        dB, e.g. :func:`level_difference_db`.
    centres : iterable of float
        Hz, band centres (:func:`third_octave_centres`); a frequency belongs to the band
        [lower edge, upper edge).

    Returns
    -------
    dict
        centre (Hz) -> RMS (dB).
    """
    f, d = np.asarray(frequency_hz, float), np.asarray(diff_db, float)
    out = {}
    for c in centres:
        lo, hi = band_edges(c)
        sel = (f >= lo) & (f < hi)
        if sel.any():
            out[float(c)] = float(np.sqrt(np.mean(d[sel] ** 2)))
    return out


def range_rms_db(
    band_values: dict[float, float], f_min: float, f_max: float, exclude: Sequence[float] = ()
) -> float:
    """RMS (dB) of the band values whose centre lies in [f_min, f_max] (nominal bounds).

    Parameters
    ----------
    band_values : dict
        centre (Hz) -> band RMS (dB), from :func:`band_rms_db`.
    f_min, f_max : float
        Hz, nominal range; centres are matched with :func:`third_octave_centres`.
    exclude : sequence of float
        Band centres (Hz) to leave out (e.g. :func:`bands_near` a resonance).

    Returns
    -------
    float
        dB; NaN when no band is left.
    """
    wanted = third_octave_centres(f_min, f_max)
    values = [
        v
        for c, v in band_values.items()
        if np.any(np.isclose(c, wanted, rtol=1e-9))
        and not np.any(np.isclose(c, exclude, rtol=1e-9))
    ]
    return float(np.sqrt(np.mean(np.square(values)))) if values else math.nan


def bands_near(frequency: float, neighbours: int = 1) -> tuple[float, ...]:
    """Centres (Hz) of the third-octave band holding ``frequency`` and ``neighbours`` either side.

    Parameters
    ----------
    frequency : float
        Hz, e.g. a resonance.
    neighbours : int
        Bands either side to include.

    Returns
    -------
    tuple of float
        Hz, ascending band centres.
    """
    n = round(10.0 * math.log10(frequency))
    return tuple(float(10.0 ** (k / 10.0)) for k in range(n - neighbours, n + neighbours + 1))


def peak_frequencies(
    frequency_hz: np.ndarray, H: np.ndarray, prominence_db: float = 1.0, n_max: int = 4
) -> tuple[float, ...]:
    """Frequencies (Hz, ascending) of the main peaks of |H|.

    A peak is a local maximum of 20 log10 |H| whose prominence is at least
    ``prominence_db``; of those the ``n_max`` most prominent are returned.

    Parameters
    ----------
    frequency_hz : array_like
        Hz, the frequencies of ``H``.
    H : array_like
        Receptance (complex or magnitude).
    prominence_db : float
        dB, minimum prominence of a peak.
    n_max : int
        Most peaks returned.

    Returns
    -------
    tuple of float
        Hz, ascending.
    """
    level = 20.0 * np.log10(np.abs(np.asarray(H)))
    idx, props = scipy.signal.find_peaks(level, prominence=prominence_db)
    best = idx[np.argsort(props["prominences"])[::-1][:n_max]]
    return tuple(float(f) for f in np.sort(np.asarray(frequency_hz, float)[best]))


def relative_difference(value: float, reference: float) -> float:
    """(value - reference) / |reference| (-); NaN if either is NaN or the reference is 0.

    Parameters
    ----------
    value, reference : float

    Returns
    -------
    float
        The relative difference (-), or NaN.
    """
    if not (math.isfinite(value) and math.isfinite(reference)) or reference == 0:
        return math.nan
    return (value - reference) / abs(reference)


def running_mean(x: np.ndarray, signal: np.ndarray, window: float) -> np.ndarray:
    """Mean of ``signal`` over [x - window/2, x + window/2] at every x (x increasing, m).

    Near the ends the window is cut to the data. Uses the trapezoidal integral, so uneven
    spacing of x is allowed.

    Parameters
    ----------
    x : array_like
        m, increasing positions of the samples.
    signal : array_like
        The samples.
    window : float
        m, window length.

    Returns
    -------
    numpy.ndarray
        The running mean at every x.
    """
    x, s = np.asarray(x, float), np.asarray(signal, float)
    integral = np.concatenate(([0.0], np.cumsum(0.5 * (s[1:] + s[:-1]) * np.diff(x))))
    lo, hi = np.maximum(x - 0.5 * window, x[0]), np.minimum(x + 0.5 * window, x[-1])
    span = hi - lo
    mean = (np.interp(hi, x, integral) - np.interp(lo, x, integral)) / np.where(span > 0, span, 1.0)
    return np.where(span > 0, mean, s)


def dynamic_rms(
    x: np.ndarray, signal: np.ndarray, window: float, x_range: tuple[float, float]
) -> float:
    """RMS of ``signal`` minus its :func:`running_mean` over ``window`` (m), inside ``x_range``.

    The running mean is taken over the whole signal before cutting to ``x_range``, so the
    range's ends see a full window where the data allow. NaN if no sample lies in the range.

    Parameters
    ----------
    x : array_like
        m, increasing positions.
    signal : array_like
        The samples (e.g. a force in N).
    window : float
        m, running-mean window.
    x_range : (float, float)
        m, where the RMS is taken.

    Returns
    -------
    float
        In the unit of ``signal``; NaN if no sample lies in the range.
    """
    x, s = np.asarray(x, float), np.asarray(signal, float)
    fluct = s - running_mean(x, s, window)
    sel = (x >= x_range[0]) & (x <= x_range[1])
    return float(np.sqrt(np.mean(fluct[sel] ** 2))) if sel.any() else math.nan


def rms_difference(
    x_a: np.ndarray,
    a: np.ndarray,
    x_b: np.ndarray,
    b: np.ndarray,
    x_range: tuple[float, float],
    dx: float = 1e-3,
) -> float:
    """RMS of a(x) - b(x) on a common grid of spacing ``dx`` (m) over ``x_range``.

    Both signals are interpolated linearly onto the grid.

    The grid covers the part of ``x_range`` that both signals span; NaN if there is none.

    Parameters
    ----------
    x_a, a : array_like
        Positions (m, increasing) and samples of the first signal.
    x_b, b : array_like
        The same for the second signal.
    x_range : (float, float)
        m, where the difference is taken.
    dx : float
        m, spacing of the common grid.

    Returns
    -------
    float
        In the unit of the signals; NaN if they do not overlap in the range.
    """
    lo = max(x_range[0], float(np.min(x_a)), float(np.min(x_b)))
    hi = min(x_range[1], float(np.max(x_a)), float(np.max(x_b)))
    if hi <= lo:
        return math.nan
    grid = np.arange(lo, hi + 0.5 * dx, dx)
    d = np.interp(grid, x_a, a) - np.interp(grid, x_b, b)
    return float(np.sqrt(np.mean(d**2)))


def max_trend_difference(
    x_a: np.ndarray,
    a: np.ndarray,
    x_b: np.ndarray,
    b: np.ndarray,
    window: float,
    x_range: tuple[float, float],
    dx: float = 1e-3,
) -> float:
    """Largest |running_mean(a) - running_mean(b)| over the common part of ``x_range``.

    In the unit of a and b.

    Each signal's running mean over ``window`` (m) is taken on its own samples, then both
    are compared on a grid of spacing ``dx``; NaN if the signals do not overlap in the range.

    Parameters
    ----------
    x_a, a : array_like
        Positions (m, increasing) and samples of the first signal.
    x_b, b : array_like
        The same for the second signal.
    window : float
        m, running-mean window.
    x_range : (float, float)
        m, where the difference is taken.
    dx : float
        m, spacing of the common grid.

    Returns
    -------
    float
        In the unit of the signals; NaN if they do not overlap in the range.
    """
    lo = max(x_range[0], float(np.min(x_a)), float(np.min(x_b)))
    hi = min(x_range[1], float(np.max(x_a)), float(np.max(x_b)))
    if hi <= lo:
        return math.nan
    grid = np.arange(lo, hi + 0.5 * dx, dx)
    ma = np.interp(grid, x_a, running_mean(x_a, a, window))
    mb = np.interp(grid, x_b, running_mean(x_b, b, window))
    return float(np.max(np.abs(ma - mb)))


def paired_median_ratio(a: Sequence[float], b: Sequence[float]) -> float:
    """Median of a[i] / b[i] over pairs (e.g. wall times of two models run one after the other).

    Parameters
    ----------
    a, b : sequence of float
        Paired values (same length, not empty).

    Returns
    -------
    float
        median(a[i] / b[i]).

    Raises
    ------
    ValueError
        The sequences differ in length or are empty.
    """
    if len(a) != len(b) or not len(a):
        raise ValueError(
            f"need two sequences of the same non-zero length, got {len(a)} and {len(b)}"
        )
    return float(np.median(np.asarray(a, float) / np.asarray(b, float)))
