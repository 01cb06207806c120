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
from exudyn_turnout.fe.mesh import FEOptions, Mesh, build_mesh
from exudyn_turnout.fe.model import assemble
from exudyn_turnout.inputs.turnout import Turnout

__all__ = ["StiffnessProfile", "static_stiffness_profile", "CSV_COLUMNS"]

_DEFAULT_OPTIONS = FEOptions()

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
        """The rows of one rail, in increasing x.

        Parameters
        ----------
        rail_id : str
            Layout rail id.

        Returns
        -------
        x : numpy.ndarray
            Sleeper positions (m).
        K_z, K_y : numpy.ndarray
            Vertical and lateral static stiffness there (N/m).

        Raises
        ------
        KeyError
            The profile has no row of that rail.
        """
        selected = np.array([row_rail == rail_id for row_rail in self.rail])
        if not selected.any():
            raise KeyError(
                f"rail {rail_id!r} is not in the profile (rails: {', '.join(self.rails)})"
            )
        order = np.argsort(self.x[selected])
        return self.x[selected][order], self.K_z[selected][order], self.K_y[selected][order]

    def at(self, rail_id: str, x: float) -> tuple[float, float, float]:
        """Static stiffness of a rail at the sleeper nearest to a position.

        Parameters
        ----------
        rail_id : str
            Layout rail id.
        x : float
            Position from the switch toe (m).

        Returns
        -------
        x_sleeper : float
            Position of that sleeper (m).
        K_z, K_y : float
            Vertical and lateral static stiffness there (N/m).
        """
        x_sleepers, K_z, K_y = self.of(rail_id)
        nearest = int(np.argmin(np.abs(x_sleepers - x)))
        return float(x_sleepers[nearest]), float(K_z[nearest]), float(K_y[nearest])

    def to_csv(self, path: str | Path) -> None:
        """Write ``x_m,rail,K_z_N_per_m,K_y_N_per_m``, one row per rail and sleeper.

        Parameters
        ----------
        path : str or Path
            CSV file to write (overwritten).
        """
        with open(path, "w", newline="", encoding="utf-8") as fh:
            writer = csv.writer(fh)
            writer.writerow(CSV_COLUMNS)
            for x, rail, K_z, K_y in zip(self.x, self.rail, self.K_z, self.K_y):
                writer.writerow([f"{x:.4f}", rail, f"{K_z:.6e}", f"{K_y:.6e}"])


def _points(mesh: Mesh, layout: Layout) -> list[tuple[str, float]]:
    """(rail id, sleeper x) of every pad inside the layout, sorted by x then rail order."""
    x = mesh.node_x[mesh.pad_rail_node]
    inside = (x >= layout.x_start - 1e-9) & (x <= layout.x_end + 1e-9)
    pads = {
        (int(rail_index), round(float(x_pad), 9))
        for rail_index, x_pad in zip(mesh.pad_rail[inside], x[inside])
    }
    by_x_then_rail = sorted(pads, key=lambda pad: (pad[1], pad[0]))
    return [(layout.rails[rail_index].id, x_pad) for rail_index, x_pad in by_x_then_rail]


def static_stiffness_profile(
    turnout: Turnout,
    layout: Layout | None = None,
    options: FEOptions = _DEFAULT_OPTIONS,
    frequency_hz: float = 1.0,
) -> StiffnessProfile:
    """Static stiffness of every rail at every sleeper of the layout, both directions.

    Parameters
    ----------
    turnout : Turnout
        Table 1 properties and, unless ``layout`` is given, the ``[layout]`` section.
    layout : Layout, optional
        Default :func:`~exudyn_turnout.fe.layout.load_layout` of the turnout.
    options : FEOptions
        Discretisation, rail damping and model ends.
    frequency_hz : float
        K = 1 / |H(frequency_hz)|; the paper uses 1 Hz.

    Returns
    -------
    StiffnessProfile
        One row per rail and sleeper inside the layout.
    """
    layout = layout or load_layout(turnout)
    mesh = build_mesh(turnout, layout, options)
    points = _points(mesh, layout)
    K: dict[str, np.ndarray] = {}
    n_dof: dict[str, int] = {}
    for direction in ("vertical", "lateral"):
        model = assemble(turnout, mesh, direction)
        K[direction] = 1.0 / np.abs(point_receptances(model, points, frequency_hz))
        n_dof[direction] = model.n_dof
    return StiffnessProfile(
        np.array([x for _, x in points]),
        tuple(rail_id for rail_id, _ in points),
        K["vertical"],
        K["lateral"],
        frequency_hz,
        {rail.id: rail.name for rail in layout.rails},
        n_dof,
    )
