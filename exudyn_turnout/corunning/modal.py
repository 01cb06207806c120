"""Linear co-running track: M, K, D by hand, eigenfrequencies, and point receptance (FRF).

The co-running cross-section (paper Figs 2, 3; drawn in :mod:`exudyn_turnout.corunning.track`) is
linear, so its receptance follows from its mass, stiffness and damping matrices alone.
This module assembles them directly from a co-running parameter set (numpy only, no
Exudyn), and computes from any M, K, D (hand-assembled or Exudyn's linearization):

- :func:`modes`: undamped eigenfrequencies, modal damping ratios and the eigenvalues of
  the damped system;
- :func:`receptance_from_matrices`: H(f) = displacement / force (m/N) at one coordinate,
  by modal superposition of the first-order (state-space) system, or by a direct solve;
- :func:`co_running_receptance`: the receptance of a rail of the turnout at x (or in a
  zone), returned as a :class:`~exudyn_turnout.receptance.Receptance`.

Coordinates (all displacements from the unloaded reference, SI units), in this order:
``y_t, z_t, phi_t`` (sleeper lateral, vertical, roll about +x), then ``y_rj, z_rj`` of
each active rail in slot order, then (three layers) ``y_m0_rj, z_m0_rj`` of the m_0
above each active rail. y is lateral (positive left), z vertical (positive up); a roll
phi_t > 0 lifts the left (+y) side of the sleeper.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import scipy.linalg

from exudyn_turnout.corunning.parameters import (
    DEFAULT_READINGS,
    CoRunningParameters,
    Readings,
    co_running_parameters,
)
from exudyn_turnout.inputs.turnout import RAIL_SLOTS, Turnout, Zone
from exudyn_turnout.receptance import DIRECTIONS, Receptance, log_frequencies

__all__ = [
    "TrackMatrices",
    "Modes",
    "dof_names",
    "dof_rails",
    "wheel_dof",
    "zone_position",
    "assemble_track_matrices",
    "modes",
    "receptance_from_matrices",
    "co_running_parameters_at",
    "co_running_receptance",
    "co_running_modes",
]

_DIRECTION_AXIS = {"vertical": "z", "lateral": "y"}


@dataclass(frozen=True)
class TrackMatrices:
    """Mass, stiffness and damping matrices of a linear track model and its coordinates."""

    M: np.ndarray  #: kg (kg m^2 for roll), n x n
    K: np.ndarray  #: N/m (N m/rad for roll), n x n
    D: np.ndarray  #: N s/m (N m s/rad for roll), n x n
    dof: tuple[str, ...]  #: coordinate names, see the module docstring

    def index(self, name: str) -> int:
        """Position of a coordinate in the matrices.

        Parameters
        ----------
        name : str
            Coordinate name, e.g. ``"z_r1"`` (see the module docstring).

        Returns
        -------
        int
            Row/column index of the coordinate.

        Raises
        ------
        KeyError
            The model has no such coordinate; the message lists those it has.
        """
        if name not in self.dof:
            raise KeyError(
                f"no coordinate {name!r} in this model (coordinates: {' '.join(self.dof)})"
            )
        return self.dof.index(name)


@dataclass(frozen=True)
class Modes:
    """Eigen-analysis of a linear track model.

    ``frequency_hz`` are the undamped natural frequencies (K phi = w^2 M phi) with their
    mass-normalised shapes; ``damping_ratio`` is the modal damping phi^T D phi / (2 w),
    which ignores the coupling of modes by non-proportional damping and exceeds 1 for
    overdamped modes (the m_0 layer on its dashpot c_0). ``eigenvalues`` are those of the
    damped first-order system (1/s): complex pairs for oscillating modes, real for
    overdamped ones.
    """

    frequency_hz: np.ndarray  #: Hz, ascending
    damping_ratio: np.ndarray  #: -, per undamped mode
    shapes: np.ndarray  #: columns, mass-normalised (phi^T M phi = 1)
    dof: tuple[str, ...]  #: coordinate names, the rows of ``shapes``
    eigenvalues: np.ndarray  #: 1/s, complex, of the damped system, 2n values

    def dominant_dof(self) -> tuple[str, ...]:
        """Per mode, the coordinate holding most of its kinetic energy.

        Returns
        -------
        tuple of str
            One coordinate name per undamped mode, in the order of ``frequency_hz``.
        """
        return tuple(
            self.dof[i] for i in np.argmax(self.shapes**2 * self._mass_diag[:, None], axis=0)
        )

    @property
    def _mass_diag(self) -> np.ndarray:
        # shapes are mass-normalised: M = inv(Phi^T)inv(Phi); its diagonal weights the energy
        inv = np.linalg.inv(self.shapes)
        return np.diag(inv.T @ inv)

    def damped(self) -> tuple[np.ndarray, np.ndarray]:
        """Frequencies and damping ratios of the oscillating modes of the damped system.

        The oscillating modes are the eigenvalues lambda with Im > 0, in ascending |lambda|.

        Returns
        -------
        frequency_hz : numpy.ndarray
            Natural frequency |lambda| / 2 pi (Hz).
        damping_ratio : numpy.ndarray
            Damping ratio -Re(lambda) / |lambda| (-).
        """
        oscillating = self.eigenvalues.imag > 1e-9 * np.abs(self.eigenvalues)
        lam = self.eigenvalues[oscillating]
        lam = lam[np.argsort(np.abs(lam))]
        return np.abs(lam) / (2 * math.pi), -lam.real / np.abs(lam)


def dof_names(active_rails: Sequence[str], layers: int) -> tuple[str, ...]:
    """Coordinate names of the co-running model, in the order of its system matrices.

    Parameters
    ----------
    active_rails : sequence of str
        Rail slots in contact in the zone (``"r1"``...); ordered by slot whatever the order
        given.
    layers : {2, 3}
        Two-layer or three-layer model (the latter adds the m_0 coordinates).

    Returns
    -------
    tuple of str
        Sleeper coordinates, then the rails', then the m_0 layer's (see the module docstring).
    """
    rails = [rail for rail in RAIL_SLOTS if rail in active_rails]
    names = ["y_t", "z_t", "phi_t"] + [f"{axis}_{rail}" for rail in rails for axis in ("y", "z")]
    if layers == 3:
        names += [f"{axis}_m0_{rail}" for rail in rails for axis in ("y", "z")]
    return tuple(names)


def wheel_dof(rail: str, direction: str, layers: int) -> str:
    """Coordinate a wheel loads: the rail mass (two layers) or the m_0 above it (three layers).

    Parameters
    ----------
    rail : str
        Rail slot, ``"r1"`` to ``"r4"``.
    direction : {"vertical", "lateral"}
        Direction of the load.
    layers : {2, 3}
        Two-layer or three-layer model.

    Returns
    -------
    str
        Coordinate name, e.g. ``"z_m0_r2"``.

    Raises
    ------
    ValueError
        For an unknown direction.
    """
    if direction not in DIRECTIONS:
        raise ValueError(f"direction must be one of {', '.join(DIRECTIONS)}, got {direction!r}")
    axis = _DIRECTION_AXIS[direction]
    return f"{axis}_m0_{rail}" if layers == 3 else f"{axis}_{rail}"


def zone_position(zone: Zone) -> float:
    """The position that stands for a zone when no x is given: its midpoint.

    Parameters
    ----------
    zone : Zone
        A zone of the turnout (Table 3).

    Returns
    -------
    float
        Midpoint of the zone, from the switch toe (m).
    """
    return 0.5 * (zone.x_start + zone.x_end)


def assemble_track_matrices(params: CoRunningParameters, x: float) -> TrackMatrices:
    """M, K, D of the co-running cross-section at x, assembled by hand from the parameters.

    Every spring-damper adds k b b^T to K and c b b^T to D, b being the linearised
    extension of the spring per unit coordinate (a lever arm a = y - sleeper_y on the
    sleeper's roll). Positions come from ``params.zone`` (``rail_y``, ``ballast_y``,
    ``sleeper_y``).

    Parameters
    ----------
    params : CoRunningParameters
        Parameter set of the zone containing x.
    x : float
        Position from the switch toe (m) at which position-dependent entries are taken.

    Returns
    -------
    TrackMatrices
        M, K, D and the coordinate names (:func:`dof_names`).
    """
    values, zone = params.at(x), params.zone
    dof = dof_names(params.active_rails, params.layers)
    idx = {name: i for i, name in enumerate(dof)}
    n = len(dof)
    M, K, D = np.zeros((n, n)), np.zeros((n, n)), np.zeros((n, n))

    def spring(b: dict[str, float], k: float, c: float) -> None:
        vec = np.zeros(n)
        for name, value in b.items():
            vec[idx[name]] = value
        K[:] += k * np.outer(vec, vec)
        D[:] += c * np.outer(vec, vec)

    M[0, 0] = M[1, 1] = values["m_t"]
    M[2, 2] = values["J_t"]
    for ballast, y_b in zip((1, 2), zone.ballast_y):
        spring(
            {"z_t": 1.0, "phi_t": y_b - zone.sleeper_y},
            values[f"k_tg{ballast}_z"],
            values[f"c_tg{ballast}_z"],
        )
    spring({"y_t": 1.0}, values["k_tg_y"], values["c_tg_y"])
    for rail in dof_rails(dof):
        j, a = rail[1:], zone.rail_y[rail] - zone.sleeper_y
        i_y, i_z = idx[f"y_{rail}"], idx[f"z_{rail}"]
        M[i_y, i_y] = M[i_z, i_z] = values[f"m_r{j}"]
        spring(
            {f"z_{rail}": 1.0, "z_t": -1.0, "phi_t": -a}, values[f"k_rt{j}_z"], values[f"c_rt{j}_z"]
        )
        spring({f"y_{rail}": 1.0, "y_t": -1.0}, values[f"k_rt{j}_y"], values[f"c_rt{j}_y"])
        if params.layers == 3:
            for axis in ("y", "z"):
                i_m0 = idx[f"{axis}_m0_{rail}"]
                M[i_m0, i_m0] = values["m_0"]
                spring(
                    {f"{axis}_m0_{rail}": 1.0, f"{axis}_{rail}": -1.0},
                    values[f"k_0{j}_{axis}"],
                    values[f"c_0{j}_{axis}"],
                )
    return TrackMatrices(M, K, D, dof)


def dof_rails(dof: Sequence[str]) -> tuple[str, ...]:
    """Rail slots that have coordinates in a list of coordinate names, in slot order.

    Parameters
    ----------
    dof : sequence of str
        Coordinate names, e.g. :attr:`TrackMatrices.dof`.

    Returns
    -------
    tuple of str
        The rail slots (``"r1"``...) with a ``z_<slot>`` coordinate.
    """
    return tuple(rail for rail in RAIL_SLOTS if f"z_{rail}" in dof)


def modes(matrices: TrackMatrices) -> Modes:
    """Undamped eigenfrequencies, modal damping ratios and damped eigenvalues.

    Parameters
    ----------
    matrices : TrackMatrices
        M, K, D of a linear track model.

    Returns
    -------
    Modes
        The eigen-analysis; see :class:`Modes` for the definitions.
    """
    M, K, D = matrices.M, matrices.K, matrices.D
    w2, phi = scipy.linalg.eigh(K, M)
    w = np.sqrt(np.clip(w2, 0.0, None))
    with np.errstate(divide="ignore", invalid="ignore"):
        zeta = np.einsum("ik,ij,jk->k", phi, D, phi) / (2.0 * w)
    lam = scipy.linalg.eigvals(_state_matrix(M, K, D))
    return Modes(w / (2 * math.pi), zeta, phi, matrices.dof, lam[np.argsort(np.abs(lam))])


def _state_matrix(M: np.ndarray, K: np.ndarray, D: np.ndarray) -> np.ndarray:
    n = M.shape[0]
    Minv = np.linalg.inv(M)
    return np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ D]])


def receptance_from_matrices(
    matrices: TrackMatrices, dof: str, frequency_hz: np.ndarray, method: str = "modal"
) -> np.ndarray:
    """Point receptance H(f) = X/F (m/N, complex) at coordinate ``dof``.

    Convention: F e^{i w t} gives X e^{i w t} with (K - w^2 M + i w D) X = F.

    Parameters
    ----------
    matrices : TrackMatrices
        M, K, D of the model.
    dof : str
        Coordinate name (force and displacement there), e.g. ``"z_m0_r2"``.
    frequency_hz : array_like
        Frequencies (Hz).
    method : {"modal", "direct"}
        ``modal``: eigen-decomposition of the first-order system once, then a sum over
        its 2n modes (fast; falls back to ``direct`` if the eigenvectors are nearly
        dependent). ``direct``: one complex linear solve per frequency.

    Returns
    -------
    numpy.ndarray
        Complex receptance (m/N), one value per frequency.

    Raises
    ------
    ValueError
        For an unknown method.
    """
    if method not in ("modal", "direct"):
        raise ValueError(f"method must be 'modal' or 'direct', got {method!r}")
    i_dof, frequency = matrices.index(dof), np.asarray(frequency_hz, dtype=float)
    s = 2j * math.pi * frequency
    if method == "modal":
        H = _modal_receptance(matrices, i_dof, s)
        if H is not None:
            return H
    M, K, D = matrices.M, matrices.K, matrices.D
    Z = K[None, :, :] + s[:, None, None] ** 2 * M[None, :, :] + s[:, None, None] * D[None, :, :]
    rhs = np.zeros((len(frequency), M.shape[0], 1), dtype=complex)
    rhs[:, i_dof, 0] = 1.0
    return np.linalg.solve(Z, rhs)[:, i_dof, 0]


def _modal_receptance(matrices: TrackMatrices, i: int, s: np.ndarray) -> np.ndarray | None:
    """H(s) = sum_k c_k b_k / (s - lambda_k), A = V diag(lambda) V^-1; None if V is singular."""
    M, n = matrices.M, matrices.M.shape[0]
    lam, V = scipy.linalg.eig(_state_matrix(M, matrices.K, matrices.D))
    if np.linalg.cond(V) > 1e10:
        return None
    B = np.zeros(2 * n)
    B[n:] = np.linalg.solve(M, np.eye(n)[:, i])
    residue = V[i, :] * np.linalg.solve(V, B)
    return (1.0 / (s[:, None] - lam[None, :])) @ residue


def co_running_parameters_at(
    turnout: Turnout,
    layers: int,
    x: float | None = None,
    zone: int | None = None,
    source: str = "derived",
    readings: Readings = DEFAULT_READINGS,
) -> tuple[CoRunningParameters, float]:
    """The parameter set and the position used for ``x`` or ``zone`` (its midpoint).

    Parameters
    ----------
    turnout : Turnout
        The turnout.
    layers : {2, 3}
        Two-layer (Fig. 2) or three-layer (Fig. 3) model.
    x : float, optional
        Position from the switch toe (m). Give ``x`` or ``zone``.
    zone : int, optional
        1-based zone index (Table 3); its midpoint is used.
    source : {"derived", "published"}
        Eqs 1-19 on Table 1, or the paper's Table 2.
    readings : Readings
        Readings of the ambiguous equations, for ``source="derived"``.

    Returns
    -------
    params : CoRunningParameters
        Parameter set of the zone.
    x : float
        ``x`` itself, or the midpoint of ``zone`` (m).

    Raises
    ------
    ValueError
        Neither or both of ``x`` and ``zone`` given.
    """
    if (x is None) == (zone is None):
        raise ValueError("give exactly one of x or zone")
    params = co_running_parameters(
        turnout, zone=zone, x=x, layers=layers, source=source, readings=readings
    )
    return params, (float(x) if x is not None else zone_position(params.zone))


def co_running_receptance(
    turnout: Turnout,
    layers: int,
    rail: str,
    direction: str,
    x: float | None = None,
    zone: int | None = None,
    source: str = "derived",
    frequencies: np.ndarray | None = None,
    readings: Readings = DEFAULT_READINGS,
) -> Receptance:
    """Point receptance of a rail of the co-running model (paper Section 3.3, Figs 5, 6).

    Parameters
    ----------
    turnout : Turnout
        The turnout.
    layers : {2, 3}
        Two-layer (force on the rail mass) or three-layer model (force on the m_0 above it).
    rail : {"r1", "r2", "r3", "r4"}
        Must be active at the position (Table 3); ValueError otherwise.
    direction : {"vertical", "lateral"}
        Direction of force and displacement.
    x : float, optional
        Position from the switch toe (m). Give ``x`` or ``zone``.
    zone : int, optional
        1-based zone; the receptance is taken at the zone's midpoint.
    source : {"derived", "published"}
        Eqs 1-19 on Table 1, or the paper's Table 2.
    frequencies : array_like, optional
        Hz; default 400 log-spaced from 1 to 2000 Hz.
    readings : Readings
        Readings of the ambiguous equations, for ``source="derived"``.

    Returns
    -------
    Receptance
        ``model`` "2-layer"/"3-layer"; ``metadata`` holds ``zone``, ``source``, ``layers``,
        ``dof``, ``eigenfrequencies_hz`` and ``damping_ratios`` (undamped modes) and
        ``damped_frequencies_hz``, ``damped_damping_ratios`` (oscillating modes of the
        damped system), see :class:`Modes`.
    """
    params, x_at = co_running_parameters_at(turnout, layers, x, zone, source, readings)
    _check_rail(params, rail, x)
    frequency = log_frequencies() if frequencies is None else np.asarray(frequencies, float)
    matrices = assemble_track_matrices(params, x_at)
    dof = wheel_dof(rail, direction, layers)
    modal = modes(matrices)
    damped_frequency, damped_ratio = modal.damped()
    metadata = {
        "zone": params.zone.index,
        "source": source,
        "layers": layers,
        "dof": dof,
        "turnout": turnout.name,
        "eigenfrequencies_hz": tuple(modal.frequency_hz.tolist()),
        "damping_ratios": tuple(modal.damping_ratio.tolist()),
        "damped_frequencies_hz": tuple(damped_frequency.tolist()),
        "damped_damping_ratios": tuple(damped_ratio.tolist()),
    }
    H = receptance_from_matrices(matrices, dof, frequency)
    return Receptance(frequency, H, rail, direction, x_at, f"{layers}-layer", metadata)


def co_running_modes(
    turnout: Turnout,
    layers: int,
    x: float | None = None,
    zone: int | None = None,
    source: str = "derived",
    readings: Readings = DEFAULT_READINGS,
) -> Modes:
    """Eigen-analysis of the co-running model at x (or at a zone's midpoint).

    Parameters
    ----------
    turnout : Turnout
        The turnout.
    layers : {2, 3}
        Two-layer (Fig. 2) or three-layer (Fig. 3) model.
    x : float, optional
        Position from the switch toe (m). Give ``x`` or ``zone``.
    zone : int, optional
        1-based zone index (Table 3); its midpoint is used.
    source : {"derived", "published"}
        Eqs 1-19 on Table 1, or the paper's Table 2.
    readings : Readings
        Readings of the ambiguous equations, for ``source="derived"``.

    Returns
    -------
    Modes
        Eigenfrequencies, damping ratios and shapes of the cross-section.
    """
    params, x_at = co_running_parameters_at(turnout, layers, x, zone, source, readings)
    return modes(assemble_track_matrices(params, x_at))


def _check_rail(params: CoRunningParameters, rail: str, x: float | None) -> None:
    if rail not in RAIL_SLOTS:
        raise ValueError(f"rail must be one of {', '.join(RAIL_SLOTS)}, got {rail!r}")
    if rail not in params.active_rails:
        zone = params.zone
        where = f"in zone {zone.index} (" if x is None else f"at x = {x:g} m (zone {zone.index}, "
        raise ValueError(
            f"rail {rail} is not active {where}{zone.name}, {zone.x_start:g} m to "
            f"{zone.x_end:g} m; active rails: {' '.join(zone.active_rails)})"
        )
