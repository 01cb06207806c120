"""The same passage on several tracks: their peaks side by side and one overlaid figure.

:class:`PassageComparison` holds the results of one scenario run on several tracks
(2-layer, 3-layer, FE), as :func:`~exudyn_turnout.passage.run.compare_tracks` returns
them and ``exudyn-turnout simulate --track 2-layer,3-layer`` writes them: ``plot()`` overlays
them in the layout of the paper's Figs 7 and 8, ``record()`` is ``comparison.json``,
``table()`` the console table, with each track's peak against the 2-layer track's in %
(the paper's Section 4 compares the 3-layer with the 2-layer model this way) and, where
the FE reference was run, against the FE's.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass

from exudyn_turnout.passage.results import PassageResult

__all__ = ["PEAK_KEYS", "PassageComparison", "difference_percent", "peak_keys"]

#: Summary keys compared, the right wheel's peaks as the paper's Figs 7, 8 (N).
PEAK_KEYS = ("peak_Fz_switch_N", "peak_Fz_crossing_N", "peak_Fy_switch_N", "peak_Fy_crossing_N")


def peak_keys(wheel: str = "right") -> tuple[str, ...]:
    """The summary keys of a wheel's peaks at the switch and the crossing (N).

    Parameters
    ----------
    wheel : {"right", "left"}

    Returns
    -------
    tuple of str
        :data:`PEAK_KEYS` for the right wheel; ``peak_Fz_switch_left_N``... for the left.
    """
    if wheel not in ("right", "left"):
        raise ValueError(f"wheel must be right or left, got {wheel!r}")
    return PEAK_KEYS if wheel == "right" else tuple(k[:-2] + "_left_N" for k in PEAK_KEYS)


def difference_percent(value: float, reference: float) -> float | None:
    """How much larger a peak's magnitude is than the reference's: 100 (|v| - |r|) / |r|.

    Magnitudes, so that a lateral peak of -15 kN against -22 kN is a smaller peak (-32 %),
    whatever the sign convention of the lateral force.

    Parameters
    ----------
    value, reference : float
        The peak and the reference peak (same unit).

    Returns
    -------
    float or None
        %; None where either is missing (not finite) or the reference is zero.
    """
    if not (math.isfinite(value) and math.isfinite(reference)) or reference == 0.0:
        return None
    return 100.0 * (abs(value) - abs(reference)) / abs(reference)


def _peak(result: PassageResult, key: str) -> float:
    value = result.summary.get(key)
    return float(value) if isinstance(value, (int, float)) else math.nan


@dataclass(frozen=True)
class PassageComparison(Mapping):
    """One scenario on several tracks: track name -> PassageResult, in run order.

    A read-only mapping (``comparison["3-layer"]``) with the figure, table and record of
    the comparison.
    """

    #: track name ("2-layer", "3-layer", "fe") -> its result, in run order (-).
    results: Mapping[str, PassageResult]

    def __getitem__(self, track: str) -> PassageResult:
        return self.results[track]

    def __iter__(self) -> Iterator[str]:
        return iter(self.results)

    def __len__(self) -> int:
        return len(self.results)

    def pairs(self) -> list[tuple[str, str]]:
        """The (track, reference) pairs compared: each co-running track against the 2-layer
        track (the paper's Section 4), and each co-running track against the FE reference
        where it was run.

        Returns
        -------
        list of (str, str)
        """
        out = []
        if "2-layer" in self.results:
            out += [(t, "2-layer") for t in self.results if t not in ("2-layer", "fe")]
        if "fe" in self.results:
            out += [(t, "fe") for t in self.results if t != "fe"]
        return out

    def differences(self, wheel: str = "right") -> dict[str, dict[str, float | None]]:
        """Peak magnitudes of each track against its reference (:meth:`pairs`), in %.

        Parameters
        ----------
        wheel : {"right", "left"}

        Returns
        -------
        dict
            ``{"3-layer vs 2-layer": {"peak_Fz_crossing_N": -21.4, ...}}`` (None where a
            peak is missing, e.g. a region outside the run); empty for one track.
        """
        return {
            f"{track} vs {ref}": {
                key: difference_percent(
                    _peak(self.results[track], key), _peak(self.results[ref], key)
                )
                for key in peak_keys(wheel)
            }
            for track, ref in self.pairs()
        }

    def record(self, wheel: str = "right") -> dict:
        """The comparison as ``comparison.json``: peaks per track (N) and differences (%).

        Parameters
        ----------
        wheel : {"right", "left"}
            Whose peaks (default the right wheel, as the paper's Figs 7, 8).

        Returns
        -------
        dict
            ``tracks``: per track the :func:`peak_keys` (N, None where not reached),
            ``wall_time_s`` (the first track's includes the process's one-time warm-up)
            and ``simulated_time_s``; ``difference_percent``: :meth:`differences` (peak
            magnitudes, :func:`difference_percent`); ``wheel``.
        """
        tracks: dict[str, dict[str, float | None]] = {}
        for track, result in self.results.items():
            row: dict[str, float | None] = {}
            for key in peak_keys(wheel) + ("wall_time_s", "simulated_time_s"):
                value = _peak(result, key)
                row[key] = value if math.isfinite(value) else None
            tracks[track] = row
        return {"wheel": wheel, "tracks": tracks, "difference_percent": self.differences(wheel)}

    def table(self, wheel: str = "right") -> str:
        """Plain-text table: peaks (kN) per track, then each track against the reference (%).

        No wall times: in one process the first run also pays the one-time warm-up
        (compilation, contact tables), so they would compare the order, not the tracks.

        Parameters
        ----------
        wheel : {"right", "left"}
            Whose peaks; named in the table's first line.

        Returns
        -------
        str
        """
        keys = peak_keys(wheel)
        heads = [key[len("peak_") :].replace("_left", "")[: -len("_N")] for key in keys]
        diffs = self.differences(wheel)
        names = list(self.results) + list(diffs) + [f"{wheel} wheel"]
        width = max(len(n) for n in names) + 2
        lines = [f"{wheel + ' wheel':<{width}}" + "".join(f"{h:>14}" for h in heads)]
        for track, result in self.results.items():
            cells = []
            for key in keys:
                value = _peak(result, key)
                cells.append(f"{value / 1e3:>11.1f} kN" if math.isfinite(value) else f"{'-':>14}")
            lines.append(f"{track:<{width}}" + "".join(cells))
        for name, row in diffs.items():
            cells = [f"{d:>+13.1f}%" if d is not None else f"{'-':>14}" for d in row.values()]
            lines.append(f"{name:<{width}}" + "".join(cells))
        return "\n".join(lines)

    def plot(self, wheel: str = "right", title: str | None = None):
        """Every track's contact forces overlaid, at the switch and the crossing (Figs 7, 8).

        Parameters
        ----------
        wheel : {"right", "left"}
        title : str, optional

        Returns
        -------
        (figure, axes)
            From :func:`exudyn_turnout.plotting.curves.plot_passage_forces`.
        """
        from exudyn_turnout.plotting.curves import plot_passage_forces

        return plot_passage_forces(list(self.results.values()), wheel=wheel, title=title)
