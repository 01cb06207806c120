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
    """n logarithmically spaced frequencies (Hz) from f_min to f_max; ValueError if invalid."""
    if not (0 < f_min < f_max) or not np.isfinite(f_max):
        raise ValueError(f"need 0 < fmin < fmax, got fmin = {f_min:g} Hz, fmax = {f_max:g} Hz")
    if n < 2:
        raise ValueError(f"need at least 2 frequencies, got n = {n}")
    return np.geomspace(f_min, f_max, int(n))


@dataclass(frozen=True)
class Receptance:
    """Point receptance of one rail (m/N) over frequency."""

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

    def to_csv(self, path: str | Path) -> None:
        """Write ``frequency_hz,real,imag,magnitude`` (m/N), one row per frequency."""
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
        """Read a file written by :meth:`to_csv`."""
        data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
        return cls(data[:, 0], data[:, 1] + 1j * data[:, 2], rail, direction, x, model)
