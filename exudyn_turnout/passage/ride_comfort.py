"""Ride comfort of a passage: EN 12299's frequency-weighted car-body floor accelerations.

Pure numpy, the filters' recursion compiled (numba); no scipy (``scipy.signal`` takes
0.5-1.3 s to import, more than the filtering).  EN 12299:2009 (Railway applications -
Ride comfort for passengers - Measurement and evaluation) weights the floor's
accelerations (clause 6.5.3, filtering; Annex A, the weighting functions) with

- ``Wb`` for the vertical direction (z), and
- ``Wd`` for the horizontal directions (x, y),

each a product of analogue transfer functions in s = j 2 pi f (the definitions of
ISO 2631-1:1997 Annex A, whose parameters ISO 8041:2005 tabulates with the exact Q1 = Q2 =
1/sqrt(2)): a band limit (:func:`band_limit_high`, :func:`band_limit_low`), an
acceleration-velocity transition (:func:`transition`) and, for Wb, an upward step
(:func:`upward_step`), times a gain K. Parameters (:data:`WB`, :data:`WD`; Hz):

======  ====  ====  ====  ====  ====  ====  ====  ====  ====  =====
        f1    f2    f3    f4    Q4    f5    Q5    f6    Q6    K
======  ====  ====  ====  ====  ====  ====  ====  ====  ====  =====
Wb      0.4   100   16    16    0.55  2.5   0.9   4.0   0.95  1.024
Wd      0.4   100   2     2     0.63  -     -     -     -     1
======  ====  ====  ====  ====  ====  ====  ====  ====  ====  =====

The filters run in the time domain: the analogue poles and zeros mapped by the bilinear
transform at the output's sampling rate (at 10 kHz the 100 Hz band limit is off by 0.03 %;
:func:`bilinear_zpk`), grouped into second-order sections (:func:`second_order_sections`:
each pole pair, the one closest to the unit circle last, with its nearest zeros) and run
as a cascade of direct form II transposed sections (:func:`sections_filter`), started in
the steady state of the first sample (:func:`sections_steady_state`; the passage starts
in the steady state at speed, :mod:`~exudyn_turnout.passage.vehicle.start`; a weighting
passes no constant, so a steady curving acceleration at the start gives no transient).

What is reported (:func:`comfort_summary`): the rms and the peak of the weighted floor
accelerations over the passage, per floor point. Not reported: the mean comfort index
N_MV = 6 sqrt((a_XP95^Wd)^2 + (a_YP95^Wd)^2 + (a_ZP95^Wb)^2) (EN 12299 clause 6.7.2) takes
the 95th percentiles of 5 s rms values over a 5 min test section (60 blocks), and the
continuous comfort Cc (clause 6.7.1) running 5 s rms values; a turnout passage lasts a few
seconds (the through route, -5 to 60 m at 100 km/h: 2.3 s), less than one 5 s block, so
neither index exists for it. The rms over the passage is a severity measure of the
turnout, not a comfort rating.

The four filter steps follow ``scipy.signal``'s ``bilinear_zpk``, ``zpk2sos`` (pairing
"nearest"), ``sosfilt_zi`` and ``sosfilt`` operation for operation: the sections and the
weighted signals equal scipy's to round-off (tests/test_ride_comfort.py compares them).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numba
import numpy as np

__all__ = [
    "Q_BAND",
    "Weighting",
    "WB",
    "WD",
    "MIN_SAMPLING_RATE",
    "band_limit_high",
    "band_limit_low",
    "transition",
    "upward_step",
    "weighting_response",
    "weighting_zpk",
    "bilinear_zpk",
    "second_order_sections",
    "sections_steady_state",
    "sections_filter",
    "weighted",
    "comfort_columns",
    "comfort_summary",
]

#: Q of the band-limiting filters (second-order Butterworth, ISO 8041:2005: exactly 1/sqrt 2).
Q_BAND = 1.0 / math.sqrt(2.0)

#: Hz, lowest sampling rate the filters are applied at: 10 x the 100 Hz band limit (the
#: bilinear transform is then 3 % off at 100 Hz; at the passage's default 10 kHz, 0.03 %).
MIN_SAMPLING_RATE = 1000.0


@dataclass(frozen=True)
class Weighting:
    """Parameters of a frequency weighting (EN 12299:2009 Annex A; ISO 2631-1 Annex A)."""

    name: str  #: "Wb", "Wd"
    f1: float  #: Hz, high-pass band limit
    f2: float  #: Hz, low-pass band limit
    f3: float  #: Hz, acceleration-velocity transition, numerator
    f4: float  #: Hz, acceleration-velocity transition, denominator
    q4: float  #: -, its quality factor
    f5: float | None = None  #: Hz, upward step, numerator (None: no step)
    q5: float = 1.0  #: -
    f6: float | None = None  #: Hz, upward step, denominator
    q6: float = 1.0  #: -
    gain: float = 1.0  #: -, K


#: Vertical weighting (EN 12299:2009 Annex A; ISO 8041:2005 table of weightings).
WB = Weighting("Wb", 0.4, 100.0, 16.0, 16.0, 0.55, 2.5, 0.9, 4.0, 0.95, 1.024)

#: Horizontal weighting (EN 12299:2009 Annex A; ISO 2631-1:1997 Table A.2).
WD = Weighting("Wd", 0.4, 100.0, 2.0, 2.0, 0.63)


def _omega(f: float) -> float:
    return 2.0 * math.pi * f


def band_limit_high(s: np.ndarray, f1: float) -> np.ndarray:
    """High-pass band limit H_h = s^2 / (s^2 + w1 s / Q1 + w1^2) (EN 12299 Annex A;
    ISO 2631-1:1997 Eq. A.1), w1 = 2 pi f1, Q1 = 1/sqrt 2.

    Parameters
    ----------
    s : numpy.ndarray
        rad/s, complex frequency (j 2 pi f).
    f1 : float
        Hz.

    Returns
    -------
    numpy.ndarray
        Complex gain.
    """
    w = _omega(f1)
    return s**2 / (s**2 + w * s / Q_BAND + w**2)


def band_limit_low(s: np.ndarray, f2: float) -> np.ndarray:
    """Low-pass band limit H_l = w2^2 / (s^2 + w2 s / Q1 + w2^2) (EN 12299 Annex A;
    ISO 2631-1:1997 Eq. A.2), w2 = 2 pi f2.

    Parameters
    ----------
    s : numpy.ndarray
        rad/s, complex frequency.
    f2 : float
        Hz.

    Returns
    -------
    numpy.ndarray
        Complex gain.
    """
    w = _omega(f2)
    return w**2 / (s**2 + w * s / Q_BAND + w**2)


def transition(s: np.ndarray, f3: float, f4: float, q4: float) -> np.ndarray:
    """Acceleration-velocity transition H_t = (1 + s/w3) / (1 + s/(Q4 w4) + s^2/w4^2)
    (EN 12299 Annex A; ISO 2631-1:1997 Eq. A.3).

    Parameters
    ----------
    s : numpy.ndarray
        rad/s, complex frequency.
    f3, f4 : float
        Hz.
    q4 : float
        -.

    Returns
    -------
    numpy.ndarray
        Complex gain.
    """
    w3, w4 = _omega(f3), _omega(f4)
    return (1.0 + s / w3) / (1.0 + s / (q4 * w4) + s**2 / w4**2)


def upward_step(s: np.ndarray, f5: float, q5: float, f6: float, q6: float) -> np.ndarray:
    """Upward step H_s = (1 + s/(Q5 w5) + s^2/w5^2) / (1 + s/(Q6 w6) + s^2/w6^2) (w5/w6)^2
    (EN 12299 Annex A; ISO 2631-1:1997 Eq. A.4).

    Parameters
    ----------
    s : numpy.ndarray
        rad/s, complex frequency.
    f5, f6 : float
        Hz.
    q5, q6 : float
        -.

    Returns
    -------
    numpy.ndarray
        Complex gain.
    """
    w5, w6 = _omega(f5), _omega(f6)
    num = 1.0 + s / (q5 * w5) + s**2 / w5**2
    den = 1.0 + s / (q6 * w6) + s**2 / w6**2
    return num / den * (w5 / w6) ** 2


def weighting_response(weighting: Weighting, f) -> np.ndarray:
    """The weighting's complex gain K H_h H_l H_t H_s at frequencies f.

    Parameters
    ----------
    weighting : Weighting
    f : array_like
        Hz.

    Returns
    -------
    numpy.ndarray
        Complex; its modulus is the weighting factor (ISO 2631-1 Table 3 lists it x 1000).
    """
    w = weighting
    s = 2j * math.pi * np.asarray(f, dtype=float)
    h = band_limit_high(s, w.f1) * band_limit_low(s, w.f2) * transition(s, w.f3, w.f4, w.q4)
    if w.f5 is not None and w.f6 is not None:
        h = h * upward_step(s, w.f5, w.q5, w.f6, w.q6)
    return w.gain * h


def weighting_zpk(weighting: Weighting) -> tuple[np.ndarray, np.ndarray, float]:
    """Analogue zeros, poles and gain of the weighting (each factor's quadratic solved).

    Parameters
    ----------
    weighting : Weighting

    Returns
    -------
    (zeros, poles, gain)
        rad/s; the transfer function is gain prod(s - z) / prod(s - p).
    """
    w = weighting
    w1, w2, w3, w4 = (_omega(f) for f in (w.f1, w.f2, w.f3, w.f4))
    zeros = [0.0, 0.0, -w3]
    poles = list(np.roots([1.0, w1 / Q_BAND, w1**2])) + list(np.roots([1.0, w2 / Q_BAND, w2**2]))
    poles += list(np.roots([1.0 / w4**2, 1.0 / (w.q4 * w4), 1.0]))
    # H_l's numerator w2^2; H_t = (w4^2 / w3) (s + w3) / (s^2 + w4 s / Q4 + w4^2)
    gain = w.gain * w2**2 * w4**2 / w3
    if w.f5 is not None and w.f6 is not None:
        w5, w6 = _omega(w.f5), _omega(w.f6)
        zeros += list(np.roots([1.0, w5 / w.q5, w5**2]))
        poles += list(np.roots([1.0, w6 / w.q6, w6**2]))
        # (1 + ... + s^2/w5^2)/(1 + ... + s^2/w6^2) (w5/w6)^2 = monic quadratics' ratio
    return np.array(zeros, dtype=complex), np.array(poles, dtype=complex), float(gain)


def weighted(signal: np.ndarray, fs: float, weighting: Weighting) -> np.ndarray:
    """A signal filtered with the weighting (bilinear transform), from the steady state of
    its first sample (module docstring).

    Parameters
    ----------
    signal : numpy.ndarray
        m/s^2, uniformly sampled.
    fs : float
        Hz, the sampling rate (>= :data:`MIN_SAMPLING_RATE`).
    weighting : Weighting

    Returns
    -------
    numpy.ndarray
        m/s^2, the weighted signal.

    Raises
    ------
    ValueError
        fs below :data:`MIN_SAMPLING_RATE`, or a non-finite sample.
    """
    x = np.asarray(signal, dtype=float)
    # the same round-off allowance as ride_comfort's: an output step of exactly 1e-3 s
    # gives 1 / (t[1] - t[0]) a few ulp below 1000 Hz
    if fs < MIN_SAMPLING_RATE * (1.0 - 1e-9):
        raise ValueError(
            f"ride comfort needs >= {MIN_SAMPLING_RATE:g} Hz samples (an output step <= "
            f"{1.0 / MIN_SAMPLING_RATE:g} s), got {fs:.4g} Hz"
        )
    if not np.all(np.isfinite(x)):
        raise ValueError("ride comfort: the acceleration has non-finite samples")
    sos = second_order_sections(*bilinear_zpk(*weighting_zpk(weighting), fs))
    return sections_filter(sos, x, sections_steady_state(sos) * x[0])


def bilinear_zpk(
    zeros: np.ndarray, poles: np.ndarray, gain: float, fs: float
) -> tuple[np.ndarray, np.ndarray, float]:
    """Digital zeros, poles and gain of an analogue filter by the bilinear transform.

    ``z = (2 fs + s) / (2 fs - s)``; the zeros at infinity (as many as poles exceed zeros)
    go to z = -1 (Nyquist), and the gain keeps the response at s = 0 (z = 1)
    (``scipy.signal.bilinear_zpk``'s operations).

    Parameters
    ----------
    zeros, poles : numpy.ndarray
        rad/s, analogue (:func:`weighting_zpk`); no more zeros than poles.
    gain : float
        Analogue gain.
    fs : float
        Hz, sampling rate.

    Returns
    -------
    (zeros, poles, gain)
        Digital, as many zeros as poles.
    """
    z = np.atleast_1d(np.asarray(zeros))
    p = np.atleast_1d(np.asarray(poles))
    fs2 = 2.0 * fs
    z_z = np.concatenate(((fs2 + z) / (fs2 - z), -np.ones(len(p) - len(z))))
    p_z = (fs2 + p) / (fs2 - p)
    return z_z, p_z, float(gain * np.real(np.prod(fs2 - z) / np.prod(fs2 - p)))


def _conjugate_halves(values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Complex values of positive imaginary part (each pair averaged with its conjugate)
    and the real ones, each sorted (``scipy.signal``'s ``_cplxreal``)."""
    z = np.atleast_1d(np.asarray(values, dtype=complex))
    z = z[np.lexsort((abs(z.imag), z.real))]
    tol = 100 * np.finfo(float).eps
    real = abs(z.imag) <= tol * abs(z)
    upper, lower = z[~real & (z.imag > 0)], z[~real & (z.imag < 0)]
    if len(upper) != len(lower) or np.any(abs(upper - lower.conj()) > tol * abs(lower)):
        raise ValueError("second-order sections: a complex value has no conjugate")
    return (upper + lower.conj()) / 2, z[real].real


def _poly(roots) -> np.ndarray:
    """Coefficients of the monic polynomial of two roots (real for a conjugate pair)."""
    return np.real(np.poly(np.asarray(roots, dtype=complex)))


def second_order_sections(zeros: np.ndarray, poles: np.ndarray, gain: float) -> np.ndarray:
    """A digital filter of complex-conjugate pole pairs as cascaded second-order sections.

    Every pole pair makes a section, the pair closest to the unit circle the last one, with
    the zero (or pair) nearest to its pole and, for a real zero, the next nearest real one;
    the gain goes to the first section (``scipy.signal.zpk2sos``, pairing "nearest", for
    filters whose poles are all complex: the weightings' quality factors exceed 1/2).

    Parameters
    ----------
    zeros, poles : numpy.ndarray
        Digital, as many zeros as poles (:func:`bilinear_zpk`).
    gain : float
        Digital gain.

    Returns
    -------
    numpy.ndarray
        (n_sections, 6): ``b0, b1, b2, 1, a1, a2`` per section.

    Raises
    ------
    ValueError
        A real pole, or zeros and poles not in equal numbers.
    """
    z_c, z_r = _conjugate_halves(zeros)
    p_c, p_r = _conjugate_halves(poles)
    if len(p_r) or len(zeros) != len(poles):
        raise ValueError("second-order sections: needs complex pole pairs, as many zeros")
    z = np.concatenate((z_c, z_r)).astype(complex)
    p = p_c
    sos = np.zeros((len(p), 6))
    for section in range(len(p) - 1, -1, -1):
        worst = int(np.argmin(np.abs(1 - np.abs(p))))
        pole = p[worst]
        p = np.delete(p, worst)
        nearest = int(np.argsort(np.abs(z - pole))[0])
        zero = z[nearest]
        z = np.delete(z, nearest)
        if zero.imag != 0.0:
            pair = [zero, zero.conj()]
        else:
            order = np.argsort(np.abs(z - pole))
            other = int(order[np.nonzero(np.isreal(z[order]))[0][0]])
            pair = [zero, z[other]]
            z = np.delete(z, other)
        sos[section, :3] = _poly(pair)
        sos[section, 3:] = _poly([pole, pole.conj()])
    sos[0, :3] *= gain
    return sos


def sections_steady_state(sos: np.ndarray) -> np.ndarray:
    """States of the sections in the steady state of a unit step (``scipy.signal.sosfilt_zi``).

    Each section's state solves ``zi = A zi + B`` (its companion matrix A), scaled by the
    static gain of the sections before it.

    Parameters
    ----------
    sos : numpy.ndarray
        (n_sections, 6), :func:`second_order_sections`.

    Returns
    -------
    numpy.ndarray
        (n_sections, 2); times the first sample: the filter starts in its steady state.
    """
    zi = np.empty((sos.shape[0], 2))
    scale = 1.0
    for section in range(sos.shape[0]):
        b = sos[section, :3] / sos[section, 3]
        a = sos[section, 3:] / sos[section, 3]
        companion = np.array([[-a[1], -a[2]], [1.0, 0.0]])
        zi[section] = scale * np.linalg.solve(np.eye(2) - companion.T, b[1:] - a[1:] * b[0])
        scale *= np.sum(b) / np.sum(a)
    return zi


@numba.njit(cache=True)
def _cascade(sos, x, zi):  # pragma: no cover (compiled; tested through sections_filter)
    y = np.empty_like(x)
    state = zi.copy()
    for n in range(x.shape[0]):
        x_cur = x[n]
        for s in range(sos.shape[0]):
            x_new = sos[s, 0] * x_cur + state[s, 0]
            state[s, 0] = sos[s, 1] * x_cur - sos[s, 4] * x_new + state[s, 1]
            state[s, 1] = sos[s, 2] * x_cur - sos[s, 5] * x_new
            x_cur = x_new
        y[n] = x_cur
    return y


def sections_filter(sos: np.ndarray, x: np.ndarray, zi: np.ndarray) -> np.ndarray:
    """A signal through cascaded second-order sections, direct form II transposed
    (``scipy.signal.sosfilt``'s recursion; compiled).

    Parameters
    ----------
    sos : numpy.ndarray
        (n_sections, 6) with ``a0 = 1`` (:func:`second_order_sections`).
    x : numpy.ndarray
        The signal, 1-D.
    zi : numpy.ndarray
        (n_sections, 2), the initial states (:func:`sections_steady_state` times ``x[0]``).

    Returns
    -------
    numpy.ndarray
        The filtered signal.
    """
    return _cascade(
        np.ascontiguousarray(sos, dtype=float),
        np.ascontiguousarray(x, dtype=float),
        np.ascontiguousarray(zi, dtype=float),
    )


def _uniform(t: np.ndarray) -> tuple[np.ndarray, bool]:
    """A uniform time axis of the run's median step over its span, and whether t is it."""
    step = float(np.median(np.diff(t)))
    grid = t[0] + step * np.arange(int(round((t[-1] - t[0]) / step)) + 1)
    same = grid.size == t.size and bool(np.max(np.abs(grid - t)) <= 1e-6 * step)
    return grid, same


def _floor_points(columns: Mapping[str, np.ndarray]) -> list[str]:
    return [
        n[len("ay_floor_") : -len("_mps2")]
        for n in columns
        if n.startswith("ay_floor_") and n.endswith("_mps2")
    ]


def comfort_columns(columns: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
    """The weighted floor accelerations of a full vehicle's run.

    Parameters
    ----------
    columns : mapping
        ``t_s`` and per car-body floor point ``ay_floor_<point>_mps2`` and
        ``az_<point>_mps2`` (:mod:`~exudyn_turnout.passage.vehicle.body_outputs`).

    Returns
    -------
    dict
        ``awd_y_<point>_mps2`` (Wd of the lateral), ``awb_z_<point>_mps2`` (Wb of the
        vertical); empty if the run has no floor points or is sampled below
        :data:`MIN_SAMPLING_RATE`. A run whose steps differ (its segments between zone
        boundaries each have their own step, ~0.5 % apart) is filtered on a uniform grid of
        its median step (linear interpolation there and back).
    """
    points = _floor_points(columns)
    if not points or "t_s" not in columns or len(columns["t_s"]) < 3:
        return {}
    t = np.asarray(columns["t_s"], dtype=float)
    grid, same = _uniform(t)
    fs = 1.0 / (grid[1] - grid[0])
    if fs < MIN_SAMPLING_RATE * (1.0 - 1e-9):
        return {}

    def filtered(values, weighting):
        if same:
            return weighted(values, fs, weighting)
        y = weighted(np.interp(grid, t, np.asarray(values, dtype=float)), fs, weighting)
        return np.interp(t, grid, y)

    out = {}
    for point in points:
        lateral, vertical = columns[f"ay_floor_{point}_mps2"], columns.get(f"az_{point}_mps2")
        out[f"awd_y_{point}_mps2"] = filtered(lateral, WD)
        if vertical is not None:
            out[f"awb_z_{point}_mps2"] = filtered(vertical, WB)
    return out


def comfort_summary(columns: Mapping[str, np.ndarray]) -> dict[str, object]:
    """Rms and peak of the weighted floor accelerations over the passage (module docstring).

    Parameters
    ----------
    columns : mapping
        As :func:`comfort_columns` (its weighted columns are used if present, else made).

    Returns
    -------
    dict
        ``ride_awd_y_rms_<point>_mps2``, ``ride_awd_y_peak_<point>_mps2`` (largest
        magnitude), the same for ``awb_z``, ``ride_duration_s`` and ``ride_comfort_note``
        (why N_MV is not given, or why nothing is).
    """
    points = _floor_points(columns)
    if not points:
        return {}
    weighted_cols = {n: v for n, v in columns.items() if n.startswith(("awd_", "awb_"))}
    if not weighted_cols:
        weighted_cols = comfort_columns(columns)
    t = np.asarray(columns["t_s"], dtype=float)
    duration = float(t[-1] - t[0]) if t.size else 0.0
    out: dict[str, object] = {"ride_duration_s": duration}
    if not weighted_cols:
        out["ride_comfort_note"] = (
            f"not computed: EN 12299 filters need samples at >= "
            f"{MIN_SAMPLING_RATE:g} Hz (--output-step <= {1.0 / MIN_SAMPLING_RATE:g} s)"
        )
        return out
    for name, values in weighted_cols.items():
        kind, point = name[: len("awd_y")], name[len("awd_y_") : -len("_mps2")]
        v = np.asarray(values, dtype=float)
        out[f"ride_{kind}_rms_{point}_mps2"] = float(np.sqrt(np.mean(v**2)))
        out[f"ride_{kind}_peak_{point}_mps2"] = float(v[np.argmax(np.abs(v))])
    out["ride_comfort_note"] = (
        f"EN 12299 Wd (lateral) and Wb (vertical) weighted floor accelerations over "
        f"{duration:.2f} s; the comfort index N_MV (95th percentiles of 5 s rms values over "
        f"5 min) and Cc (5 s rms) need >= 5 s of running: not defined for this passage"
    )
    return out
