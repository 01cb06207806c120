"""Figures of a study's results table (:func:`exudyn_turnout.studies.run_study`).

- :func:`plot_peak_vs_factor`: a peak against a factor, one curve per value (or
  combination of values) of the other factors; where seeds vary too the curve is their
  mean with the range shaded; a Latin-hypercube factor is drawn as points;
- :func:`plot_peak_distribution`: the distribution of a peak over the cases (e.g. over
  irregularity seeds): histogram and empirical cumulative distribution, one per value of
  the other factors (never pooled over them);
- :func:`study_figures`: the figures a study's command writes, one per factor (paired
  factors are one factor) and, with seeds, the distribution;
- :func:`factor_label`, :func:`result_label`: axis labels with units (``speed (km/h)``,
  ``rail pad k_z, stock rail (MN/m)``, ``largest Fz, crossing (kN)``).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from exudyn_turnout.plotting.backend import pyplot

__all__ = [
    "plot_peak_vs_factor",
    "plot_peak_distribution",
    "study_figures",
    "save_study_figure",
    "factor_label",
    "factor_groups",
    "result_label",
    "DEFAULT_PEAK",
    "MAX_CURVES",
]

#: The peak drawn by default: the largest vertical force at the crossing (either wheel).
DEFAULT_PEAK = "max_Fz_crossing_N"

#: Most curves (or distributions) in one figure; more combinations are pooled (said so).
MAX_CURVES = 8

#: Passage settings and study columns: name -> (words, unit shown, scale from SI to it).
_NAMED = {
    "speed_kmh": ("speed", "km/h", 1.0),
    "time_step": ("time step", "ms", 1e3),
    "output_step": ("output step", "ms", 1e3),
    "x_start": ("start position x", "m", 1.0),
    "x_end": ("end position x", "m", 1.0),
    "spectral_radius": ("spectral radius rho_inf", "-", 1.0),
    "layers": ("co-running track layers", "-", 1.0),
    "seed": ("irregularity seed", "-", 1.0),
}

#: SI unit of a file field, by its last part (exact names, then prefixes); shown in
#: a readable multiple: unit -> (shown, scale).
_LEAF_UNITS = {
    "density": "kg/m^3",
    "youngs_modulus": "Pa",
    "area": "m^2",
    "mass": "kg",
    "mu": "-",
    "poisson": "-",
    "shear_coefficient": "-",
    "conicity": "-",
    "clearance": "m",
    "back_to_back": "m",
    "wheel_radius": "m",
    "sleeper_length": "m",
    "sleeper_spacing": "m",
}
_PREFIX_UNITS = (
    ("k_", "N/m"),
    ("c_", "N s/m"),
    ("I_", "m^4"),
    ("x_", "m"),
)
_SUFFIX_UNITS = (
    ("_inertia", "kg m^2"),
    ("_stiffness", "N/m"),
    ("_damping", "N s/m"),
    ("_factor", "-"),
    ("_length", "m"),
    ("_spacing", "m"),
    ("_kmh", "km/h"),
    ("_mm", "mm"),
    ("_deg", "deg"),
    ("_m", "m"),
    ("_s", "s"),
    ("_N", "N"),
)
_SHOWN = {
    "N/m": ("MN/m", 1e-6),
    "N s/m": ("kN s/m", 1e-3),
    "Pa": ("GPa", 1e-9),
    "N": ("kN", 1e-3),
}


def _leaf_unit(leaf: str) -> str | None:
    if leaf in _LEAF_UNITS:
        return _LEAF_UNITS[leaf]
    if leaf in ("k", "stiffness"):
        return "N/m"
    if leaf in ("c", "damping"):
        return "N s/m"
    for prefix, unit in _PREFIX_UNITS:
        if leaf.startswith(prefix):
            return unit
    for suffix, unit in _SUFFIX_UNITS:
        if leaf.endswith(suffix):
            return unit
    return None


def _words(kind: str, parts: list[str]) -> str:
    """Readable words of a dotted file path (after its ``turnout.`` / ``vehicle.``)."""
    if kind == "turnout" and len(parts) == 4 and parts[0] == "rail_types" and parts[2] == "pad":
        rails = parts[1]
        return f"rail pad {parts[3]}, {rails} rail{'s' if '/' in rails else ''}"
    if parts and parts[0] == "rail_types":
        parts = parts[1:]
    head = [p.replace("_", " ") for p in parts[:-1]]
    return " ".join(([] if kind == "turnout" else [kind]) + head + parts[-1:])


def _merged_parts(names: Sequence[str]) -> list[str] | None:
    """Dotted paths that differ in one part only, that part joined by ``/``."""
    split = [n.split(".") for n in names]
    if len({len(p) for p in split}) != 1 or len(split[0]) < 3:
        return None
    differ = [i for i in range(len(split[0])) if len({p[i] for p in split}) > 1]
    if len(differ) != 1:
        return None
    merged = list(split[0])
    merged[differ[0]] = "/".join(dict.fromkeys(p[differ[0]] for p in split))
    return merged


def factor_label(name: str | Sequence[str]) -> tuple[str, float]:
    """An axis label with its unit for a factor (or paired factors), and the scale to it.

    Parameters
    ----------
    name : str or sequence of str
        A column of the results table (``speed_kmh``,
        ``turnout.rail_types.stock.pad.k_z``); several paired factors get one label
        (``rail pad k_z, stock/switch/crossing/check rails (MN/m)``).

    Returns
    -------
    label : str
        Words and unit, e.g. ``speed (km/h)``; ``(SI)`` where the unit is not known.
    scale : float
        Multiply the column's SI values by it to draw them in the label's unit.
    """
    names = [name] if isinstance(name, str) else list(name)
    first = names[0]
    extra = ""
    if len(names) > 1:
        merged = _merged_parts(names)
        if merged is not None:
            first = ".".join(merged)
        else:
            extra = f", paired with {', '.join(names[1:])}"
    if first in _NAMED:
        named = _NAMED[first]
        return f"{named[0]} ({named[1]}){extra}", named[2]
    kind, _, path = first.partition(".")
    if kind in ("turnout", "vehicle") and path:
        parts = path.split(".")
        words = _words(kind, parts)
        unit = _leaf_unit(parts[-1])
    else:
        words, unit = first.replace("_", " "), _leaf_unit(first)
    if unit is None:
        return f"{words} (SI){extra}", 1.0
    shown, scale = _SHOWN.get(unit, (unit, 1.0))
    return f"{words} ({shown}){extra}", scale


def result_label(name: str) -> tuple[str, float]:
    """An axis label with its unit for a result column, and the scale to it.

    Parameters
    ----------
    name : str
        E.g. ``max_Fz_crossing_N`` -> ``largest Fz, crossing (kN)``,
        ``rms_dyn_Fz_right_N`` -> ``RMS of dynamic Fz, right (kN)``.

    Returns
    -------
    label : str
    scale : float
        From the column's SI values to the label's unit.
    """
    stem, unit = name, None
    for suffix, u in (("_N", "N"), ("_m", "m"), ("_s", "s")):
        if name.endswith(suffix):
            stem, unit = name[: -len(suffix)], u
            break
    lead = ""
    for prefix, words in (
        ("max_", "largest "),
        ("peak_", "peak "),
        ("rms_dyn_", "RMS of dynamic "),
    ):
        if stem.startswith(prefix):
            stem, lead = stem[len(prefix) :], words
            break
    else:
        if stem.startswith("rms_"):
            stem, lead = stem[4:], "RMS of "
    if lead:
        quantity, _, rest = stem.partition("_")
        words = f"{lead}{quantity}" + (f", {rest.replace('_', ', ')}" if rest else "")
    else:
        words = stem.replace("_", " ")
    if unit is None:
        return (f"{words} (-)" if name == "contact_losses" else words), 1.0
    shown, scale = _SHOWN.get(unit, (unit, 1.0))
    return f"{words} ({shown})", scale


def _ok(table: Mapping[str, np.ndarray]) -> np.ndarray:
    status = table.get("status")
    n = len(table["case"])
    return np.ones(n, bool) if status is None else np.asarray(status) == "ok"


def _as_list(names) -> list:
    if names is None:
        return []
    return [names] if isinstance(names, str) else list(names)


def _column_of(group: str | Sequence[str]) -> str:
    return group if isinstance(group, str) else group[0]


def _value_text(name: str | Sequence[str], value) -> str:
    """``speed = 80 km/h``, ``route = through`` for a legend."""
    if isinstance(value, (int, float, np.number)):
        label, scale = factor_label(name)
        words, _, unit = label.rpartition(" (")
        words = words.split(",")[0]  # "rail pad k_z, stock rail" -> "rail pad k_z"
        unit = unit.split(")")[0]
        unit_text = "" if unit in ("-", "SI") else f" {unit}"
        return f"{words} = {float(value) * scale:g}{unit_text}"
    return f"{_column_of(name)} = {value}"


def _combinations(
    table: Mapping[str, np.ndarray], names: Sequence, sel: np.ndarray
) -> list[tuple[np.ndarray, str]]:
    """(mask, legend text) per combination of the values of ``names`` present in ``sel``.

    An item of ``names`` is a column or a list of paired columns (values of the first).
    """
    if not names:
        return [(sel, "")]
    columns = [np.asarray(table[_column_of(n)]) for n in names]
    values = [list(dict.fromkeys(c[sel].tolist())) for c in columns]
    out = []
    for combo in itertools.product(*values):
        mask = sel.copy()
        for c, v in zip(columns, combo):
            mask &= c == v
        if mask.any():
            out.append((mask, ", ".join(_value_text(n, v) for n, v in zip(names, combo))))
    return out


def plot_peak_vs_factor(
    table: Mapping[str, np.ndarray],
    factor: str | Sequence[str],
    peak: str = DEFAULT_PEAK,
    curves: str | Sequence | None = None,
    ax=None,
    points: bool = False,
):
    """A peak against a numeric factor, one curve per value (combination) of ``curves``.

    Cases with the same x and curve (seeds, factors not named) give the mean, their range
    shaded.

    Parameters
    ----------
    table : mapping
        The results table (column -> array).
    factor : str or sequence of str
        Numeric input column on the x axis (e.g. ``speed_kmh``); paired factors as a list
        (the first is drawn, the label names them all).
    peak : str
        Result column (N columns drawn in kN).
    curves : str or sequence, optional
        Input columns whose values (combinations) make separate curves (e.g. ``route``);
        an item may be a list of paired columns (one legend label for them).
    ax : matplotlib Axes, optional
    points : bool
        Markers only, each case a point (a Latin-hypercube factor).

    Returns
    -------
    (figure, axes)
    """
    plt = pyplot()
    if ax is None:
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
    else:
        fig = ax.figure
    names = _as_list(factor)
    x_label, x_scale = factor_label(names)
    y_label, y_scale = result_label(peak)
    ok = _ok(table) & np.isfinite(np.asarray(table[peak], dtype=float))
    x_all = np.asarray(table[names[0]], dtype=float)
    y_all = np.asarray(table[peak], dtype=float) * y_scale
    groups = _combinations(table, _as_list(curves), ok)
    spread = False
    for sel, label in groups:
        if points:
            ax.plot(x_all[sel] * x_scale, y_all[sel], "o", label=label or None)
            continue
        xs = np.unique(x_all[sel])
        stats = [y_all[sel & (x_all == x)] for x in xs]
        mean = np.array([s.mean() for s in stats])
        (line,) = ax.plot(xs * x_scale, mean, marker="o", label=label or None)
        if any(s.size > 1 for s in stats):
            spread = True
            low = np.array([s.min() for s in stats])
            high = np.array([s.max() for s in stats])
            ax.fill_between(xs * x_scale, low, high, color=line.get_color(), alpha=0.2)
    ax.set_xlabel(x_label)
    ax.set_ylabel(y_label + ("\n(mean, range shaded)" if spread else ""))
    ax.grid(True, alpha=0.3)
    if any(label for _, label in groups):
        _legend(ax, len(groups))
    return fig, ax


def _legend(ax, n: int) -> None:
    """Inside the axes for a few entries, beside them for more (never over the data)."""
    if n <= 4:
        ax.legend(fontsize="small")
    else:
        ax.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.02, 1.0))


def plot_peak_distribution(
    table: Mapping[str, np.ndarray],
    peak: str = DEFAULT_PEAK,
    by: str | Sequence | None = None,
    bins: int | None = None,
    axes=None,
):
    """Distribution of a peak over the cases: histogram and empirical CDF.

    Parameters
    ----------
    table : mapping
        The results table.
    peak : str
        Result column.
    by : str or sequence, optional
        Input columns whose values (combinations) get separate distributions (e.g. a pad
        stiffness): seeds of different stiffnesses are not pooled. An item may be a list
        of paired columns.
    bins : int, optional
        Histogram bins (default: about sqrt(n)).
    axes : (Axes, Axes), optional

    Returns
    -------
    (figure, axes)
    """
    plt = pyplot()
    if axes is None:
        fig, axes = plt.subplots(1, 2, figsize=(9.0, 3.8))
    else:
        fig = axes[0].figure
    label_text, scale = result_label(peak)
    values = np.asarray(table[peak], dtype=float) * scale
    ok = _ok(table) & np.isfinite(values)
    for sel, group in _combinations(table, _as_list(by), ok):
        v = np.sort(values[sel])
        if v.size == 0:
            continue
        label = f"{group} (n = {v.size})" if group else f"n = {v.size}"
        n_bins = bins or max(3, int(math.sqrt(v.size)))
        axes[0].hist(v, bins=n_bins, alpha=0.5, label=label)
        axes[1].step(v, np.arange(1, v.size + 1) / v.size, where="post", label=label)
    axes[0].set_xlabel(label_text)
    axes[0].set_ylabel("cases")
    axes[1].set_xlabel(label_text)
    axes[1].set_ylabel("fraction of cases <= value")
    for a in axes:
        a.grid(True, alpha=0.3)
    _legend(axes[1], len(axes[1].get_lines()))
    return fig, axes


def save_study_figure(fig, path) -> None:
    """Save a figure (format from the suffix; directory created) and close it.

    Parameters
    ----------
    fig : matplotlib Figure
    path : str or Path
    """
    plt = pyplot()
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(target, dpi=110, bbox_inches="tight")
    plt.close(fig)


def factor_groups(
    table: Mapping[str, np.ndarray], varied: Sequence[str], paired: Sequence[str] = ()
) -> list[list[str]]:
    """The study's factors as the figures see them: paired factors are one, seeds apart.

    Parameters
    ----------
    table : mapping
        The results table (factors that take one value only are left out).
    varied : sequence of str
        ``Study.varied``.
    paired : sequence of str
        The names in the study's ``[paired]`` (varied together: one group).

    Returns
    -------
    list of list of str
        Each group's columns, in study order; ``seed`` is not in any.
    """
    groups: list[list[str]] = []
    paired_group = [n for n in varied if n in paired]
    for name in varied:
        if name == "seed" or name not in table:
            continue
        if name in paired:
            if name == paired_group[0]:
                groups.append(paired_group)
            continue
        groups.append([name])
    return [g for g in groups if len(set(np.asarray(table[g[0]]).tolist())) > 1]


def _numeric(table: Mapping[str, np.ndarray], name: str) -> bool:
    return np.asarray(table[name]).dtype.kind in "fiu"


def _safe(name: str) -> str:
    return name.replace(".", "_").replace("/", "_")


def study_figures(
    table: Mapping[str, np.ndarray],
    varied: Sequence[str],
    out_dir,
    peak: str = DEFAULT_PEAK,
    paired: Sequence[str] = (),
    sampled: Sequence[str] = (),
) -> list[str]:
    """The figures of a study: the peak against each numeric factor, its distribution.

    For each numeric factor (paired factors count as one) that takes more than one value:
    ``peak_vs_<factor>.png``, one curve per combination of the other factors' values (up
    to :data:`MAX_CURVES`; beyond, the text factors such as route or track make the
    curves and the rest is pooled into the shaded range), seeds as mean and range,
    Latin-hypercube factors as points. With irregularity seeds: ``peak_distribution.png``,
    one distribution per combination of the other factors (not pooled over them).

    Parameters
    ----------
    table : mapping
        The results table.
    varied : sequence of str
        The study's varied factors (``Study.varied``).
    out_dir : str or Path
        Directory the PNG files are written to.
    peak : str
        Result column drawn.
    paired : sequence of str
        The study's paired factors (``Study.paired``): one figure for all of them.
    sampled : sequence of str
        The study's Latin-hypercube factors (``Study.lhs_ranges``): drawn as points, never
        as curves.

    Returns
    -------
    list of str
        Paths written.
    """
    out = Path(out_dir)
    if peak not in table or not _ok(table).any():
        return []
    groups = factor_groups(table, varied, paired)
    paths = []
    for group in groups:
        x = next((n for n in group if _numeric(table, n)), None)
        if x is None:
            continue
        others = [g for g in groups if g is not group and g[0] not in sampled]
        curves = others
        if _n_combinations(table, curves) > MAX_CURVES:
            curves = [g for g in others if not _numeric(table, g[0])]
            if _n_combinations(table, curves) > MAX_CURVES:
                curves = []
        fig, _ = plot_peak_vs_factor(
            table, [x] + [n for n in group if n != x], peak, curves=curves, points=x in sampled
        )
        _say_pooled(fig, [g for g in others if g not in curves])
        path = out / f"peak_vs_{_safe(x)}.png"
        save_study_figure(fig, path)
        paths.append(str(path))
    if "seed" in varied:
        by = [g for g in groups if g[0] not in sampled]
        if _n_combinations(table, by) > MAX_CURVES:
            by = by[:1] if _n_combinations(table, by[:1]) <= MAX_CURVES else []
        fig, _ = plot_peak_distribution(table, peak, by=by)
        _say_pooled(fig, [g for g in groups if g not in by])
        path = out / "peak_distribution.png"
        save_study_figure(fig, path)
        paths.append(str(path))
    return paths


def _say_pooled(fig, groups: Sequence[Sequence[str]]) -> None:
    if groups:
        words = "; ".join(factor_label(g)[0] for g in groups)
        fig.suptitle(f"pooled over: {words}", fontsize="small")


def _n_combinations(table: Mapping[str, np.ndarray], groups: Sequence) -> int:
    if not groups:
        return 1
    columns = [np.asarray(table[_column_of(g)]) for g in groups]
    return len({tuple(c[i] for c in columns) for i in range(len(table["case"]))})
