"""Track irregularities: the deviation of each rail from its design position along x.

An :class:`Irregularity` holds four channels sampled at increasing x (m): the vertical
deviation of the left and right rail tops (m, positive up) and the lateral deviation of
the left and right rails (m, positive towards the left, i.e. track y). Between samples
it is interpolated linearly, outside its x range it is zero.

Where they come from:

- a standard power spectral density (PSD) with a seed and a wavelength band
  (:func:`irregularity_from_psd`, spectra in :mod:`.track_spectra`, re-exported here):
  vertical profile, alignment, cross-level and gauge are drawn independently and combined
  into the four rail channels (:func:`rail_channels`);
- a CSV of measured irregularities (:func:`irregularity_from_csv`);
- local defects: a dipped joint of total angle 2 alpha (:func:`dipped_joint`), a dip or a
  bump of given depth and length (:func:`local_defect`);
- a sum of any of these (:func:`sum_irregularities`, or ``a + b``);
- a compact text spec, as given on the command line (:func:`irregularity_from_spec`).

Pure numpy; the passage puts the channels into the contact geometry of the rail they
belong to.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from exudyn_turnout.inputs.toml_fields import X_LIMIT
from exudyn_turnout.inputs.track_spectra import (
    PSD_COMPONENTS,
    SPECTRUM_NAMES,
    TrackSpectrum,
    psd_cross_level_erri,
    psd_cross_level_fra,
    psd_gauge_erri,
    psd_profile_erri,
    psd_profile_fra,
    track_spectrum,
)

__all__ = [
    "Irregularity",
    "TrackSpectrum",
    "CHANNELS",
    "SPECTRUM_NAMES",
    "PSD_COMPONENTS",
    "psd_profile_erri",
    "psd_cross_level_erri",
    "psd_gauge_erri",
    "psd_profile_fra",
    "psd_cross_level_fra",
    "track_spectrum",
    "rail_channels",
    "irregularity_from_psd",
    "irregularity_from_csv",
    "dipped_joint",
    "local_defect",
    "sum_irregularities",
    "irregularity_from_spec",
]

#: The four channels of an irregularity, in the order of :meth:`Irregularity.at`.
CHANNELS = ("vertical_left", "vertical_right", "lateral_left", "lateral_right")


@dataclass(frozen=True, eq=False)
class Irregularity:
    """Deviation of the left and right rails from their design position, along x.

    Parameters
    ----------
    x : ndarray
        m, strictly increasing sample positions (at least two).
    vertical_left, vertical_right : ndarray
        m, rail top height deviation of each rail at x, positive up.
    lateral_left, lateral_right : ndarray
        m, lateral deviation of each rail at x, positive towards the left (track y).
    source : str
        Where it came from (a spec, a file name); recorded with the results.
    """

    x: np.ndarray  #: m, strictly increasing
    vertical_left: np.ndarray  #: m, left rail top, positive up
    vertical_right: np.ndarray  #: m, right rail top, positive up
    lateral_left: np.ndarray  #: m, left rail, positive towards the left (track y)
    lateral_right: np.ndarray  #: m, right rail, positive towards the left (track y)
    source: str = field(default="")  #: where it came from (spec or file name)

    def __post_init__(self) -> None:
        x = np.array(self.x, dtype=float)
        if x.ndim != 1 or x.size < 2:
            raise ValueError(f"irregularity {self.source or ''}: x needs at least two samples")
        if not np.all(np.isfinite(x)) or np.any(np.diff(x) <= 0):
            raise ValueError(
                f"irregularity {self.source or ''}: x must be finite and strictly increasing"
            )
        x.setflags(write=False)
        object.__setattr__(self, "x", x)
        for name in CHANNELS:
            values = np.array(getattr(self, name), dtype=float)
            if values.shape != x.shape:
                raise ValueError(
                    f"irregularity {self.source or ''}: {name} has {values.size} samples, "
                    f"x has {x.size}"
                )
            if not np.all(np.isfinite(values)):
                raise ValueError(f"irregularity {self.source or ''}: {name} is not finite")
            values.setflags(write=False)
            object.__setattr__(self, name, values)

    def at(self, x: float) -> tuple[float, float, float, float]:
        """The four channels at one position (zero outside the x range).

        Parameters
        ----------
        x : float
            m.

        Returns
        -------
        tuple of float
            m: vertical_left, vertical_right, lateral_left, lateral_right.
        """
        v = self.at_array(np.array([float(x)]))[:, 0]
        return float(v[0]), float(v[1]), float(v[2]), float(v[3])

    def at_array(self, x: np.ndarray) -> np.ndarray:
        """The four channels at many positions (linear interpolation, zero outside).

        Parameters
        ----------
        x : ndarray
            m, any shape (flattened).

        Returns
        -------
        ndarray
            (4, n), m: rows in the order of :data:`CHANNELS`.
        """
        xs = np.asarray(x, dtype=float).ravel()
        inside = (xs >= self.x[0]) & (xs <= self.x[-1])
        out = np.zeros((4, xs.size))
        for i, name in enumerate(CHANNELS):
            out[i] = np.where(inside, np.interp(xs, self.x, getattr(self, name)), 0.0)
        return out

    def __add__(self, other: Irregularity) -> Irregularity:
        """The sum of two irregularities (see :func:`sum_irregularities`).

        Parameters
        ----------
        other : Irregularity

        Returns
        -------
        Irregularity
        """
        return sum_irregularities([self, other])

    def __repr__(self) -> str:
        peak = max(float(np.max(np.abs(getattr(self, n)))) for n in CHANNELS)
        return (
            f"Irregularity({self.source or 'unnamed'}, x {self.x[0]:g} to {self.x[-1]:g} m, "
            f"{self.x.size} samples, largest |deviation| {1e3 * peak:.3g} mm)"
        )


# --- Random irregularities from a spectrum -----------------------------------------------


def rail_channels(
    vertical: np.ndarray, lateral: np.ndarray, cross_level: np.ndarray, gauge: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The four rail channels from vertical profile, alignment, cross-level and gauge.

    Vertical profile and alignment are the mean of the two rails, cross-level the left
    minus the right rail height, gauge the widening (left rail to the left, right rail to
    the right): z_left = v + c/2, z_right = v - c/2, y_left = a + g/2, y_right = a - g/2
    (EN 13848-1 definitions, y positive to the left).

    Parameters
    ----------
    vertical, lateral, cross_level, gauge : ndarray
        m.

    Returns
    -------
    tuple of ndarray
        m: vertical_left, vertical_right, lateral_left, lateral_right.
    """
    v, a = np.asarray(vertical, float), np.asarray(lateral, float)
    c, g = np.asarray(cross_level, float), np.asarray(gauge, float)
    return v + 0.5 * c, v - 0.5 * c, a + 0.5 * g, a - 0.5 * g


def _random_profile(
    psd: np.ndarray, Omega: np.ndarray, n: int, dOmega: float, seed: int, stream: int
) -> np.ndarray:
    """A Gaussian random profile of one-sided PSD ``psd`` on the FFT grid (n samples).

    z(x) = sum_k a_k cos(Omega_k x) + b_k sin(Omega_k x), a_k, b_k ~ N(0, S_k dOmega)
    independent (spectral representation: Shinozuka & Deodatis, Appl. Mech. Rev. 44(4)
    1991, 191-204, with Gaussian amplitudes), so var z = sum_k S_k dOmega = int S dOmega.
    """
    rng = np.random.default_rng([int(seed), stream])
    g = rng.standard_normal((2, Omega.size))
    sigma = np.sqrt(psd * dOmega)
    spectrum = 0.5 * n * sigma * (g[0] - 1j * g[1])
    return np.fft.irfft(spectrum, n)


def irregularity_from_psd(
    spectrum: str | TrackSpectrum,
    seed: int,
    band: tuple[float, float] = (1.0, 70.0),
    x_start: float = -50.0,
    x_end: float = 150.0,
    step: float = 0.1,
    components: tuple[str, ...] = PSD_COMPONENTS,
    scale: float = 1.0,
) -> Irregularity:
    """A random irregularity of a standard spectrum: same seed, same profile.

    Each component (vertical profile, alignment, cross-level, gauge) is an independent
    Gaussian sample of its one-sided PSD restricted to the wavelength band, on a grid of
    period ``n step`` (:func:`_random_profile`; each component draws from its own stream
    of the seed, so leaving one out does not change the others). They are combined into
    the rail channels by :func:`rail_channels`.

    Parameters
    ----------
    spectrum : str or TrackSpectrum
        See :func:`track_spectrum`.
    seed : int
        Random seed (>= 0).
    band : (float, float)
        m, shortest and longest wavelength kept.
    x_start, x_end : float
        m, the range covered (the profile is zero outside).
    step : float
        m, sample spacing; at most a quarter of the shortest wavelength.
    components : tuple of str
        Which of :data:`PSD_COMPONENTS` to include (the others are zero).
    scale : float
        -, amplitude factor (1: the spectrum's level).

    Returns
    -------
    Irregularity

    Raises
    ------
    ValueError
        A bad band, range, step, seed or component (one line naming it).
    """
    spec = spectrum if isinstance(spectrum, TrackSpectrum) else track_spectrum(spectrum)
    lam_min, lam_max = float(band[0]), float(band[1])
    if not (0 < lam_min < lam_max and math.isfinite(lam_max)):
        raise ValueError(f"band: need 0 < shortest < longest wavelength, got {band}")
    if not (math.isfinite(x_start) and math.isfinite(x_end) and x_end > x_start):
        raise ValueError(f"range: need x_start < x_end, got {x_start:g}..{x_end:g} m")
    if not (0 < step <= lam_min / 4):
        raise ValueError(
            f"step: must be > 0 and <= a quarter of the shortest wavelength "
            f"({lam_min / 4:g} m), got {step:g} m"
        )
    if int(seed) != seed or seed < 0:
        raise ValueError(f"seed: must be an integer >= 0, got {seed!r}")
    bad = [c for c in components if c not in PSD_COMPONENTS]
    if bad:
        raise ValueError(f"components: unknown {bad[0]!r} (known: {', '.join(PSD_COMPONENTS)})")
    if not (math.isfinite(scale) and scale >= 0):
        raise ValueError(f"scale: must be >= 0, got {scale:g}")
    n = int(math.ceil((x_end - x_start) / step)) + 1
    n = max(n, int(math.ceil(lam_max / step)) + 1)  # the period holds the longest wavelength
    n += n % 2
    dOmega = 2.0 * math.pi / (n * step)
    Omega = dOmega * np.arange(n // 2 + 1)
    in_band = (Omega >= 2.0 * math.pi / lam_max) & (Omega <= 2.0 * math.pi / lam_min)
    in_band[0] = in_band[-1] = False  # no mean, no Nyquist term
    parts = {}
    for stream, name in enumerate(PSD_COMPONENTS):
        if name not in components:
            parts[name] = np.zeros(n)
            continue
        psd = np.zeros_like(Omega)
        psd[in_band] = spec.psd(name, Omega[in_band])
        parts[name] = scale * _random_profile(psd, Omega, n, dOmega, int(seed), stream)
    x = x_start + step * np.arange(n)
    keep = x <= x_end + 0.5 * step
    left_z, right_z, left_y, right_y = rail_channels(
        parts["vertical"][keep],
        parts["lateral"][keep],
        parts["cross-level"][keep],
        parts["gauge"][keep],
    )
    source = f"psd:{spec.name},seed={int(seed)},band={lam_min:g}-{lam_max:g}"
    return Irregularity(x[keep], left_z, right_z, left_y, right_y, source=source)


def irregularity_from_csv(path: str | Path) -> Irregularity:
    """Measured irregularities from a CSV file.

    A header row names the columns: ``x_m`` and any of ``vertical_left_m``,
    ``vertical_right_m``, ``lateral_left_m``, ``lateral_right_m`` (a channel not given is
    zero; the ``_m`` suffix may be left out); lines starting with ``#`` are comments.
    x strictly increasing, all values in metres, lateral positive to the left.

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    Irregularity

    Raises
    ------
    ValueError
        Unreadable file, missing x column, unknown column, a value that is not a number
        (the message names the file, line and column).
    """
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except OSError as err:
        raise ValueError(f"{p.name}: cannot read ({err.strerror or err})") from None
    rows = [r for r in csv.reader(line for line in text.splitlines() if line.strip())]
    rows = [r for r in rows if not r[0].lstrip().startswith("#")]
    if not rows:
        raise ValueError(f"{p.name}: empty file (a header row x_m,vertical_left_m,... is needed)")
    names = [h.strip().removesuffix("_m") for h in rows[0]]
    known = ("x",) + CHANNELS
    for h in names:
        if h not in known:
            raise ValueError(f"{p.name}: unknown column {h!r} (known: {', '.join(known)}, in m)")
    if "x" not in names:
        raise ValueError(f"{p.name}: no x_m column")
    data = np.zeros((len(rows) - 1, len(names)))
    for i, row in enumerate(rows[1:]):
        if len(row) != len(names):
            raise ValueError(f"{p.name}: line {i + 2}: {len(row)} values, {len(names)} columns")
        for j, value in enumerate(row):
            try:
                data[i, j] = float(value)
            except ValueError:
                raise ValueError(
                    f"{p.name}: line {i + 2}, column {rows[0][j].strip()}: "
                    f"{value!r} is not a number"
                ) from None
    columns = {h: data[:, j] for j, h in enumerate(names)}
    zero = np.zeros(data.shape[0])
    try:
        vl, vr, ll, lr = (columns.get(c, zero) for c in CHANNELS)
        return Irregularity(columns["x"], vl, vr, ll, lr, source=p.name)
    except ValueError as err:
        raise ValueError(f"{p.name}: {str(err).split(': ', 1)[-1]}") from None


_RAILS = ("left", "right", "both")
_DIRECTIONS = ("vertical", "lateral")


def _defect(
    x: np.ndarray, shape: np.ndarray, rail: str, direction: str, source: str
) -> Irregularity:
    """Put ``shape`` (m) on the channels of ``rail`` in ``direction``."""
    if rail not in _RAILS:
        raise ValueError(f"rail: must be one of {', '.join(_RAILS)}, got {rail!r}")
    if direction not in _DIRECTIONS:
        raise ValueError(f"direction: must be one of {', '.join(_DIRECTIONS)}, got {direction!r}")
    zero = np.zeros_like(shape)
    channels = []
    for name in CHANNELS:
        side = name.split("_")[1]
        hit = name.startswith(direction) and rail in (side, "both")
        channels.append(shape if hit else zero)
    vl, vr, ll, lr = channels
    return Irregularity(x, vl, vr, ll, lr, source=source)


def dipped_joint(
    x: float, angle: float, length: float = 1.0, rail: str = "both", direction: str = "vertical"
) -> Irregularity:
    """A dipped joint: a V of total angle 2 alpha centred at x over a given length.

    Each rail end dips with slope alpha towards the joint: z = -alpha (length/2 - |s - x|)
    for |s - x| < length/2 (the dipped-joint model of Jenkins et al., Railway Engineering
    Journal 3(1) 1974, 2-16), depth alpha length / 2.

    Parameters
    ----------
    x : float
        m, position of the joint.
    angle : float
        rad, the total angle 2 alpha (> 0).
    length : float
        m, length over which the rails dip (> 0).
    rail : {"left", "right", "both"}
    direction : {"vertical", "lateral"}
        Vertical (down) or lateral (towards the right, -y).

    Returns
    -------
    Irregularity
    """
    if not (math.isfinite(angle) and 0 < angle < 0.5):
        raise ValueError(f"angle: the total angle 2 alpha must be in (0, 0.5) rad, got {angle:g}")
    if not (math.isfinite(length) and length > 0):
        raise ValueError(f"length: must be > 0, got {length:g} m")
    if not math.isfinite(x):
        raise ValueError(f"x: must be finite, got {x}")
    depth = 0.5 * angle * 0.5 * length
    s = np.array([x - 0.5 * length, x, x + 0.5 * length])
    shape = np.array([0.0, -depth, 0.0])
    return _defect(s, shape, rail, direction, f"joint:x={x:g},angle={angle:g},length={length:g}")


def local_defect(
    x: float,
    depth: float,
    length: float,
    rail: str = "both",
    direction: str = "vertical",
    samples: int = 65,
) -> Irregularity:
    """A dip (depth > 0) or a bump (depth < 0) of cosine shape centred at x.

    z = -depth (1 - cos(2 pi (s - x + length/2) / length)) / 2 for |s - x| <= length/2:
    the versine local defect used for isolated track faults (e.g. EN 13848-5's isolated
    defects; Zhai 2020, Sect. 2.4.2, cosine-shaped local irregularity).

    Parameters
    ----------
    x : float
        m, centre.
    depth : float
        m, positive: a dip (downwards / towards -y), negative: a bump.
    length : float
        m, wavelength of the defect (> 0).
    rail : {"left", "right", "both"}
    direction : {"vertical", "lateral"}
    samples : int
        Samples over the length (odd: one at the centre).

    Returns
    -------
    Irregularity
    """
    if not (math.isfinite(depth) and depth != 0 and abs(depth) < 0.05):
        raise ValueError(f"depth: must be non-zero and below 0.05 m in size, got {depth:g} m")
    if not (math.isfinite(length) and length > 0):
        raise ValueError(f"length: must be > 0, got {length:g} m")
    if not math.isfinite(x):
        raise ValueError(f"x: must be finite, got {x}")
    s = x - 0.5 * length + length * np.linspace(0.0, 1.0, max(int(samples), 3))
    shape = -0.5 * depth * (1.0 - np.cos(2.0 * math.pi * (s - x + 0.5 * length) / length))
    kind = "dip" if depth > 0 else "bump"
    return _defect(
        s, shape, rail, direction, f"{kind}:x={x:g},depth={abs(depth):g},length={length:g}"
    )


def sum_irregularities(items) -> Irregularity:
    """The sum of irregularities, exact: on the union of their samples.

    Each term is zero outside its range; points a rounding step outside each end keep
    those steps sharp.

    Parameters
    ----------
    items : iterable of Irregularity
        At least one.

    Returns
    -------
    Irregularity
    """
    items = list(items)
    if not items:
        raise ValueError("sum of irregularities: nothing to add")
    if len(items) == 1:
        return items[0]
    xs = [it.x for it in items]
    for it in items:
        xs.append(np.array([np.nextafter(it.x[0], -np.inf), np.nextafter(it.x[-1], np.inf)]))
    x = np.unique(np.concatenate(xs))
    total = np.sum([it.at_array(x) for it in items], axis=0)
    source = " + ".join(it.source or "unnamed" for it in items)
    return Irregularity(x, total[0], total[1], total[2], total[3], source=source)


def _fields(text: str, kind: str, required: tuple[str, ...], allowed: tuple[str, ...]) -> dict:
    out: dict[str, str] = {}
    for part in (p.strip() for p in text.split(",") if p.strip()):
        key, eq, value = part.partition("=")
        key = key.strip()
        if not eq:
            raise ValueError(f"{kind}: {part!r} is not key=value")
        if key not in allowed:
            raise ValueError(f"{kind}: unknown field {key!r} (fields: {', '.join(allowed)})")
        out[key] = value.strip()
    for key in required:
        if key not in out:
            raise ValueError(f"{kind}: field {key} is missing")
    return out


def _number(kind: str, key: str, text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"{kind}: {key}={text!r} is not a number") from None
    if not math.isfinite(value):
        raise ValueError(f"{kind}: {key}={text!r} is not finite")
    return value


def _band(kind: str, text: str) -> tuple[float, float]:
    low, dash, high = text.partition("-")
    if not dash:
        raise ValueError(f"{kind}: band={text!r} must be SHORTEST-LONGEST wavelength in m")
    return _number(kind, "band", low), _number(kind, "band", high)


def _inside(kind: str, x: float, x_range: tuple[float, float] | None) -> None:
    """A defect's position: within the run's x range if given, else within |x| <= X_LIMIT."""
    lo, hi = x_range if x_range is not None else (-X_LIMIT, X_LIMIT)
    if not lo <= x <= hi:
        where = "the route" if x_range is not None else "any turnout"
        raise ValueError(f"{kind}: x={x:g} m is outside {where} ({lo:g}..{hi:g} m)")


def _one_spec(
    text: str, base_dir: Path | None, x_range: tuple[float, float] | None = None
) -> Irregularity:
    kind, colon, rest = text.partition(":")
    kind = kind.strip().lower()
    if colon and kind == "psd":
        name, _, options = rest.partition(",")
        if not name.strip():
            raise ValueError("psd: the spectrum name is missing (e.g. psd:ERRI-low,seed=1)")
        allowed = ("seed", "band", "from", "to", "step", "components", "scale")
        f = _fields(options, "psd", ("seed",), allowed)
        seed = _number("psd", "seed", f["seed"])
        if seed != int(seed) or seed < 0:
            raise ValueError(f"psd: seed={f['seed']!r} must be an integer >= 0")
        comps = tuple(c.strip() for c in f.get("components", "/".join(PSD_COMPONENTS)).split("/"))
        try:
            spectrum = track_spectrum(name)
        except ValueError as err:
            raise ValueError(f"psd: {err}") from None
        try:
            return irregularity_from_psd(
                spectrum,
                int(seed),
                band=_band("psd", f.get("band", "1-70")),
                x_start=_number("psd", "from", f.get("from", "-50")),
                x_end=_number("psd", "to", f.get("to", "150")),
                step=_number("psd", "step", f.get("step", "0.1")),
                components=comps,
                scale=_number("psd", "scale", f.get("scale", "1")),
            )
        except ValueError as err:
            raise ValueError(f"psd: {err}") from None
    if colon and kind in ("dip", "bump", "joint"):
        common = ("x", "length", "rail", "direction")
        size = "angle" if kind == "joint" else "depth"
        f = _fields(rest, kind, ("x", size, "length"), (size,) + common)
        x, length = _number(kind, "x", f["x"]), _number(kind, "length", f["length"])
        _inside(kind, x, x_range)
        value = _number(kind, size, f[size])
        rail, direction = f.get("rail", "both"), f.get("direction", "vertical")
        try:
            if kind == "joint":
                return dipped_joint(x, value, length, rail, direction)
            if value <= 0:
                raise ValueError(f"depth: must be > 0 (a {kind} of that size), got {value:g} m")
            return local_defect(x, value if kind == "dip" else -value, length, rail, direction)
        except ValueError as err:
            raise ValueError(f"{kind}: {err}") from None
    path = Path(text.strip())
    if base_dir is not None and not path.is_absolute():
        path = base_dir / path
    if path.suffix.lower() == ".csv" or path.exists():
        if not path.is_file():
            raise ValueError(f"irregularity file {text.strip()}: no such file")
        measured = irregularity_from_csv(path)
        lo, hi = x_range if x_range is not None else (-X_LIMIT, X_LIMIT)
        if measured.x[-1] < lo or measured.x[0] > hi:
            where = "the route" if x_range is not None else "any turnout"
            raise ValueError(
                f"{path.name}: x {measured.x[0]:g}..{measured.x[-1]:g} m lies outside "
                f"{where} ({lo:g}..{hi:g} m)"
            )
        return measured
    raise ValueError(
        f"irregularity {text.strip()!r}: not a CSV file nor a spec "
        "(psd:NAME,seed=N[,band=1-70] | dip:x=..,depth=..,length=.. | "
        "bump:... | joint:x=..,angle=..,length=..; several joined by ';')"
    )


def irregularity_from_spec(
    text: str, base_dir: str | Path | None = None, x_range: tuple[float, float] | None = None
) -> Irregularity:
    """An irregularity from a compact text spec (the ``--irregularity`` option).

    Forms, several joined by ``;`` are summed:

    - ``psd:NAME,seed=N[,band=LMIN-LMAX][,from=X0][,to=X1][,step=DX][,scale=F]``
      ``[,components=vertical/lateral/cross-level/gauge]``: :func:`irregularity_from_psd`
      (defaults: band 1-70 m, x -50 to 150 m, step 0.1 m, all four components);
    - ``dip:x=X,depth=D,length=L[,rail=left|right|both][,direction=vertical|lateral]``,
      ``bump:`` the same upwards: :func:`local_defect`;
    - ``joint:x=X,angle=TWO_ALPHA,length=L[,rail=...]``: :func:`dipped_joint`;
    - a CSV file: :func:`irregularity_from_csv`.

    Parameters
    ----------
    text : str
        The spec.
    base_dir : str or Path, optional
        Directory relative CSV paths are taken from (default: the working directory).
    x_range : (float, float), optional
        m, the x range of the route or run: a dip, bump or joint must lie inside it, a CSV
        file overlap it. Without it the bound is that of any turnout, ``|x| <= X_LIMIT``.

    Returns
    -------
    Irregularity

    Raises
    ------
    ValueError
        One line naming the bad field.

    Examples
    --------
    ``psd:ERRI-low,seed=3,band=1-70``, ``dip:x=47,depth=0.002,length=1.0``,
    ``psd:FRA-5,seed=1;joint:x=47.2,angle=0.009,length=1``.
    """
    parts = [p for p in str(text).split(";") if p.strip()]
    if not parts:
        raise ValueError("irregularity: empty spec")
    base = Path(base_dir) if base_dir is not None else None
    return sum_irregularities(_one_spec(p, base, x_range) for p in parts)
