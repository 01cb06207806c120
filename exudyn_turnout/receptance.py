"""Point receptance (FRF) data object, shared by the co-running and the FE models.

A :class:`Receptance` holds H(f) = displacement / force (m/N, complex) at one rail, one
direction and one position, with the model that produced it. CSV columns are
``frequency_hz,real,imag,magnitude`` (m/N) for every model, so curves compare directly.
"""

from __future__ import annotations

import csv
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

__all__ = ["Receptance", "log_frequencies", "CSV_COLUMNS", "DIRECTIONS"]

CSV_COLUMNS = ("frequency_hz", "real", "imag", "magnitude")
DIRECTIONS = ("vertical", "lateral")


def log_frequencies(f_min: float = 1.0, f_max: float = 2000.0, n: int = 400) -> np.ndarray:
    """n logarithmically spaced frequencies (Hz) from f_min to f_max.

    Parameters
    ----------
    f_min, f_max : float
        First and last frequency (Hz), 0 < f_min < f_max.
    n : int
        Number of frequencies (>= 2).

    Returns
    -------
    numpy.ndarray
        The frequencies (Hz).

    Raises
    ------
    ValueError
        Invalid range or count (the message names the values).
    """
    if not (0 < f_min < f_max) or not np.isfinite(f_max):
        raise ValueError(f"need 0 < fmin < fmax, got fmin = {f_min:g} Hz, fmax = {f_max:g} Hz")
    if n < 2:
        raise ValueError(f"need at least 2 frequencies, got n = {n}")
    return np.geomspace(f_min, f_max, int(n))


@dataclass(frozen=True, repr=False)
class Receptance:
    """Point receptance of one rail (m/N) over frequency.

    Compute functions (:func:`~exudyn_turnout.corunning.modal.co_running_receptance`,
    :func:`~exudyn_turnout.fe.frf.fe_receptance`) return this data object; :meth:`plot`
    draws it (delegating to :mod:`exudyn_turnout.plotting`), :meth:`save` writes its CSV.
    """

    frequency_hz: np.ndarray  #: Hz, increasing
    H: np.ndarray  #: m/N, complex displacement / force
    rail: str  #: rail slot "r1".."r4"
    direction: str  #: "vertical" or "lateral"
    x: float  #: m, position from the switch toe
    model: str  #: e.g. "2-layer", "3-layer", "FE"
    metadata: Mapping[str, object] = field(default_factory=dict)

    @property
    def magnitude(self) -> np.ndarray:
        """|H| (m/N)."""
        return np.abs(self.H)

    @property
    def static_stiffness(self) -> float:
        """1 / |H| at the lowest frequency (N/m); the paper takes it at 1 Hz."""
        return float(1.0 / abs(self.H[0]))

    def plot(self, ax=None, *, phase: bool = False, title: str | None = None):
        """Log-log |H| over frequency (and the phase below it, if asked).

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Axes to draw into (two for ``phase=True``); default: a new figure.
        phase : bool
            Draw the phase too.
        title : str, optional
            Axes title.

        Returns
        -------
        (figure, axes)
            From :func:`exudyn_turnout.plotting.plot_receptance`.
        """
        from exudyn_turnout.plotting.curves import plot_receptance

        return plot_receptance(self, ax, phase=phase, title=title)

    def save(self, path: str | Path) -> None:
        """Write the CSV (``frequency_hz,real,imag,magnitude``, m/N); same as :meth:`to_csv`.

        Parameters
        ----------
        path : str or Path
            The CSV file.
        """
        self.to_csv(path)

    def __repr__(self) -> str:
        f = self.frequency_hz
        return (
            f"Receptance({self.model}, {self.rail} {self.direction} at x = {self.x:g} m, "
            f"{len(f)} frequencies {f[0]:g}-{f[-1]:g} Hz, "
            f"static stiffness {self.static_stiffness / 1e6:.1f} MN/m)"
        )

    def to_csv(self, path: str | Path) -> None:
        """Write ``frequency_hz,real,imag,magnitude`` (m/N), one row per frequency.

        Parameters
        ----------
        path : str or Path
            The CSV file.
        """
        with open(path, "w", newline="", encoding="utf-8") as fh:
            w = csv.writer(fh)
            w.writerow(CSV_COLUMNS)
            for f, h in zip(self.frequency_hz, self.H):
                w.writerow([f"{f:.8g}", f"{h.real:.8e}", f"{h.imag:.8e}", f"{abs(h):.8e}"])

    @classmethod
    def from_csv(
        cls,
        path: str | Path,
        rail: str = "",
        direction: str = "",
        x: float = float("nan"),
        model: str = "",
    ) -> Receptance:
        """Read a file written by :meth:`to_csv`.

        Parameters
        ----------
        path : str or Path
            The CSV file (``frequency_hz,real,imag,magnitude``).
        rail, direction : str
            Rail slot and direction to record (the CSV does not hold them).
        x : float
            Position (m) to record.
        model : str
            Model name to record.

        Returns
        -------
        Receptance
        """
        data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
        return cls(data[:, 0], data[:, 1] + 1j * data[:, 2], rail, direction, x, model)
