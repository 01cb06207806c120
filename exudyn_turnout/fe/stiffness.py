"""Static stiffness along the turnout from the FE model: the data of the paper's Fig. 1(b,c).

As the paper does (Section 2), the static stiffness is K = 1 / |H(1 Hz)|, the inverse
point receptance at 1 Hz, at every sleeper position for every rail present there,
vertical and lateral. One sparse factorisation per plane serves all points.
"""

from __future__ import annotations

import csv
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from exudyn_turnout.fe.frf import point_receptances
from exudyn_turnout.fe.layout import Layout, load_layout
from exudyn_turnout.fe.mesh import FEOptions, build_mesh
from exudyn_turnout.fe.model import assemble
from exudyn_turnout.inputs.turnout import Turnout

__all__ = ["StiffnessProfile", "static_stiffness_profile", "CSV_COLUMNS"]

#: Columns of :meth:`StiffnessProfile.to_csv`.
CSV_COLUMNS = ("x_m", "rail", "K_z_N_per_m", "K_y_N_per_m")


@dataclass(frozen=True)
class StiffnessProfile:
    """Static point stiffness of every rail at every sleeper."""

    x: np.ndarray  #: m, sleeper position of each row
    rail: tuple[str, ...]  #: layout rail id of each row
    K_z: np.ndarray  #: N/m, vertical static stiffness 1/|H_z(f)|
    K_y: np.ndarray  #: N/m, lateral static stiffness 1/|H_y(f)|
    frequency_hz: float  #: Hz, where |H| was taken (1 Hz, as in the paper)
    rail_names: Mapping[str, str]  #: rail id -> description
    n_dof: Mapping[str, int]  #: DOFs of the vertical and lateral models

    @property
    def rails(self) -> tuple[str, ...]:
        """Rail ids in order of first appearance."""
        return tuple(dict.fromkeys(self.rail))

    def of(self, rail_id: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """x (m), K_z, K_y (N/m) of one rail, increasing x; KeyError if it has no rows."""
        sel = np.array([r == rail_id for r in self.rail])
        if not sel.any():
            raise KeyError(
                f"rail {rail_id!r} is not in the profile (rails: {', '.join(self.rails)})"
            )
        order = np.argsort(self.x[sel])
        return self.x[sel][order], self.K_z[sel][order], self.K_y[sel][order]

    def at(self, rail_id: str, x: float) -> tuple[float, float, float]:
        """(x_sleeper, K_z, K_y) at the sleeper of ``rail_id`` nearest to x."""
        xs, kz, ky = self.of(rail_id)
        k = int(np.argmin(np.abs(xs - x)))
        return float(xs[k]), float(kz[k]), float(ky[k])

    def to_csv(self, path: str | Path) -> None:
        """Write ``x_m,rail,K_z_N_per_m,K_y_N_per_m``, one row per rail and sleeper."""
        with open(path, "w", newline="", encoding="utf-8") as fh:
            w = csv.writer(fh)
            w.writerow(CSV_COLUMNS)
            for x, r, kz, ky in zip(self.x, self.rail, self.K_z, self.K_y):
                w.writerow([f"{x:.4f}", r, f"{kz:.6e}", f"{ky:.6e}"])


def _points(mesh, layout: Layout) -> list[tuple[str, float]]:
    """(rail id, sleeper x) of every pad inside the layout, sorted by x then rail order."""
    x = mesh.node_x[mesh.pad_rail_node]
    inside = (x >= layout.x_start - 1e-9) & (x <= layout.x_end + 1e-9)
    pts = {(int(i), round(float(xx), 9)) for i, xx in zip(mesh.pad_rail[inside], x[inside])}
    return [(layout.rails[i].id, xx) for i, xx in sorted(pts, key=lambda p: (p[1], p[0]))]


def static_stiffness_profile(
    turnout: Turnout,
    layout: Layout | None = None,
    options: FEOptions = FEOptions(),
    frequency_hz: float = 1.0,
) -> StiffnessProfile:
    """Static stiffness of every rail at every sleeper of the layout, both directions.

    Parameters
    ----------
    turnout : Turnout
    layout : Layout, optional
        Default :func:`~exudyn_turnout.fe.layout.load_layout` of the turnout.
    options : FEOptions
    frequency_hz : float
        K = 1 / |H(frequency_hz)|; the paper uses 1 Hz.

    Returns
    -------
    StiffnessProfile
    """
    layout = layout or load_layout(turnout)
    mesh = build_mesh(turnout, layout, options)
    points = _points(mesh, layout)
    K, n_dof = {}, {}
    for direction in ("vertical", "lateral"):
        model = assemble(turnout, mesh, direction)
        K[direction] = 1.0 / np.abs(point_receptances(model, points, frequency_hz))
        n_dof[direction] = model.n_dof
    return StiffnessProfile(
        np.array([p[1] for p in points]),
        tuple(p[0] for p in points),
        K["vertical"],
        K["lateral"],
        frequency_hz,
        {r.id: r.name for r in layout.rails},
        n_dof,
    )
