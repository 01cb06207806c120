"""The co-running track's spring-dampers as one compiled force (no Exudyn).

:func:`~exudyn_turnout.corunning.track.add_co_running_track` builds each spring of
:func:`~exudyn_turnout.corunning.cross_section.cross_section_springs` as an Exudyn
``CartesianSpringDamper`` whose stiffness and damping follow the wheelset's position x
through a symbolic user function. This module evaluates the same springs of one or more
co-running tracks in one numba-compiled call instead, for an Exudyn ``ObjectGenericODE2``
that holds the tracks' coordinates (the masses stay Exudyn's bodies):

- every entry a spring uses is evaluated at its track's x = x0 + v t with the operations
  of :class:`~exudyn_turnout.corunning.track.EntryLaw` (Eqs 10, 11, 14, 15, Table 2's ramps,
  fitted tables), in the same order;
- every spring acts along the global lateral and vertical axes between its two ends as a
  ``CartesianSpringDamper`` does: ground, a point of the sleeper at lever arm a from its
  centre (rigid-body kinematics, exact in the roll phi: lateral y_t + a (cos phi - 1),
  vertical z_t + a sin phi), or a rail or m_0 node; the force k d + c d_t (d the second end's
  displacement minus the first's) pulls the first end and pushes the second; on the
  sleeper it adds the moment a cos(phi) F_z - a sin(phi) F_y;
- the Jacobian for Newton's method is the linear one, the K(x) and D(x) of
  :func:`~exudyn_turnout.corunning.modal.assemble_track_matrices` (the roll's geometric
  terms, of relative size phi, left out: they change the iteration, not its solution).

Coordinates are displacements from the reference configuration, which is force-free.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numba
import numpy as np

from exudyn_turnout.corunning.cross_section import cross_section_springs
from exudyn_turnout.corunning.fitted import TableEntry
from exudyn_turnout.corunning.parameters import CoRunningParameters, reference_support
from exudyn_turnout.inputs.turnout import Entry, Polynomial

__all__ = [
    "TrackPlacement",
    "TrackForce",
    "track_force",
    "spring_forces",
    "law_values",
    "applied_spring_forces",
    "KERNEL_ARRAYS",
]

#: names of :attr:`TrackForce.arrays` in the order :func:`spring_forces` takes them
KERNEL_ARRAYS = (
    "ends",
    "arms",
    "laws",
    "tracks",
    "track_poly",
    "poly_c",
    "poly_n",
    "poly_f",
    "law_i",
    "law_a",
    "ramps",
)

# marker kinds of a spring end
_GROUND, _NODE, _SLEEPER = 0, 1, 2
# entry kinds of a law
_CONST, _RAMPS, _DELTA_Z, _DELTA_Y = 0, 1, 2, 3


@dataclass(frozen=True)
class TrackPlacement:
    """One co-running track in the force vector: its parameters, motion and coordinates."""

    params: CoRunningParameters  #: the zone's parameter set (2 or 3 layers)
    x0: float  #: m, position at t = 0 (where the laws are evaluated: x = x0 + v t)
    v: float  #: m/s, speed (0: laws frozen at x0)
    #: coordinate name (:func:`~exudyn_turnout.corunning.modal.dof_names`) -> index in the
    #: force vector
    index: Mapping[str, int]


@numba.njit(cache=True)
def _support(x, poly_c, poly_n, poly_f, p):  # pragma: no cover (compiled)
    """Delta(x) of Eqs 11, 15 as EntryLaw's _support_factor computes it."""
    lo, hi, plain = poly_f[p, 0], poly_f[p, 1], poly_f[p, 2]
    inv_plain, inv_k = poly_f[p, 3], poly_f[p, 4]
    xc = min(max(x, lo), hi)
    n = poly_n[p]
    acc = poly_c[p, n - 1]
    for i in range(n - 2, -1, -1):
        acc = acc * xc + poly_c[p, i]
    ratio = inv_k * acc
    if math.isnan(plain):
        return ratio
    w = min(max((x - plain) * inv_plain, 0.0), 1.0)
    return (1.0 - w) + w * ratio


@numba.njit(cache=True)
def law_values(
    t, tracks, track_poly, poly_c, poly_n, poly_f, law_i, law_a, ramps, values
):  # pragma: no cover (compiled)
    """Every law's value at its track's x = x0 + v t (into ``values``; compiled).

    They depend on t only: a caller evaluating several residuals at one t (the Newton
    iterations of a step) computes them once and applies them with
    :func:`applied_spring_forces`.

    Parameters
    ----------
    t : float
        s; each track's x = x0 + v t.
    tracks, track_poly, poly_c, poly_n, poly_f, law_i, law_a, ramps : numpy.ndarray
        :attr:`TrackForce.arrays` of those names.
    values : numpy.ndarray
        SI units, one per law (:attr:`TrackForce.laws`), overwritten.
    """
    n_tracks = tracks.shape[0]
    delta = np.empty((n_tracks, 2))
    for k in range(n_tracks):
        x = tracks[k, 0] + tracks[k, 1] * t
        delta[k, 0] = _support(x, poly_c, poly_n, poly_f, track_poly[k, 0])
        delta[k, 1] = _support(x, poly_c, poly_n, poly_f, track_poly[k, 1])
    for j in range(law_i.shape[0]):
        k, kind = law_i[j, 0], law_i[j, 1]
        if kind == 0:
            values[j] = law_a[j]
        elif kind == 1:
            x = tracks[k, 0] + tracks[k, 1] * t
            s = (x - tracks[k, 2]) * tracks[k, 3]
            acc = law_a[j]
            for r in range(law_i[j, 2], law_i[j, 3]):
                acc = acc + ramps[r, 2] * min(max((s - ramps[r, 0]) * ramps[r, 1], 0.0), 1.0)
            values[j] = acc
        elif kind == 2:
            values[j] = law_a[j] * delta[k, 0]
        else:
            values[j] = law_a[j] * delta[k, 1]


@numba.njit(cache=True)
def _end_motion(q, q_t, ends, arms, s, e):  # pragma: no cover (compiled)
    """Displacement (y, z) and velocity (y, z) of end e of spring s; cos, sin of the roll."""
    kind, iy, iz, ip = ends[s, e, 0], ends[s, e, 1], ends[s, e, 2], ends[s, e, 3]
    if kind == 1:
        return q[iy], q[iz], q_t[iy], q_t[iz], 1.0, 0.0
    if kind == 2:
        a = arms[s, e]
        c, sn = math.cos(q[ip]), math.sin(q[ip])
        return (
            q[iy] + a * (c - 1.0),
            q[iz] + a * sn,
            q_t[iy] - a * sn * q_t[ip],
            q_t[iz] + a * c * q_t[ip],
            c,
            sn,
        )
    return 0.0, 0.0, 0.0, 0.0, 1.0, 0.0


@numba.njit(cache=True)
def spring_forces(
    t,
    q,
    q_t,
    out,
    values,
    ends,
    arms,
    laws,
    tracks,
    track_poly,
    poly_c,
    poly_n,
    poly_f,
    law_i,
    law_a,
    ramps,
):  # pragma: no cover (compiled)
    """Add every spring's generalised forces at time t to ``out`` (compiled).

    Parameters
    ----------
    t : float
        s; each track's x = x0 + v t.
    q, q_t : numpy.ndarray
        Coordinates and velocities of the force vector.
    out : numpy.ndarray
        The force vector, added to.
    values : numpy.ndarray
        Scratch for the laws' values (one per law).
    ends, arms, laws, tracks, track_poly, poly_c, poly_n, poly_f, law_i, law_a, ramps
        :attr:`TrackForce.arrays` (:data:`KERNEL_ARRAYS`).
    """
    law_values(t, tracks, track_poly, poly_c, poly_n, poly_f, law_i, law_a, ramps, values)
    applied_spring_forces(q, q_t, out, values, ends, arms, laws)


@numba.njit(cache=True)
def applied_spring_forces(q, q_t, out, values, ends, arms, laws):  # pragma: no cover (compiled)
    """Add every spring's generalised forces, its laws' values given, to ``out`` (compiled).

    Parameters
    ----------
    q, q_t : numpy.ndarray
        Coordinates and velocities of the force vector.
    out : numpy.ndarray
        The force vector, added to.
    values : numpy.ndarray
        The laws' values at the time (:func:`law_values`).
    ends, arms, laws : numpy.ndarray
        :attr:`TrackForce.arrays` of those names.
    """
    for s in range(ends.shape[0]):
        y0, z0, vy0, vz0, c0, s0 = _end_motion(q, q_t, ends, arms, s, 0)
        y1, z1, vy1, vz1, c1, s1 = _end_motion(q, q_t, ends, arms, s, 1)
        f_y, f_z = 0.0, 0.0
        if laws[s, 0] >= 0:
            f_y += values[laws[s, 0]] * (y1 - y0)
        if laws[s, 2] >= 0:
            f_y += values[laws[s, 2]] * (vy1 - vy0)
        if laws[s, 1] >= 0:
            f_z += values[laws[s, 1]] * (z1 - z0)
        if laws[s, 3] >= 0:
            f_z += values[laws[s, 3]] * (vz1 - vz0)
        for e in range(2):
            sign = 1.0 if e == 0 else -1.0  # pulls the first end, pushes the second
            kind, iy, iz, ip = ends[s, e, 0], ends[s, e, 1], ends[s, e, 2], ends[s, e, 3]
            if kind == 0:
                continue
            out[iy] += sign * f_y
            out[iz] += sign * f_z
            if kind == 2:
                a = arms[s, e]
                c, sn = (c0, s0) if e == 0 else (c1, s1)
                out[ip] += sign * (a * c * f_z - a * sn * f_y)


@numba.njit(cache=True)
def _add_jacobian(
    t,
    f_q,
    f_q_t,
    out,
    values,
    ends,
    arms,
    laws,
    tracks,
    track_poly,
    poly_c,
    poly_n,
    poly_f,
    law_i,
    law_a,
    ramps,
):  # pragma: no cover (compiled)
    """Add f_q K(x) + f_q_t D(x) (linear in the coordinates) to ``out``."""
    law_values(t, tracks, track_poly, poly_c, poly_n, poly_f, law_i, law_a, ramps, values)
    index = np.empty(4, np.int64)
    coef = np.empty(4)
    for s in range(ends.shape[0]):
        for direction in range(2):
            factor = 0.0
            if laws[s, direction] >= 0:
                factor += f_q * values[laws[s, direction]]
            if laws[s, 2 + direction] >= 0:
                factor += f_q_t * values[laws[s, 2 + direction]]
            if factor == 0.0:
                continue
            m = 0
            for e in range(2):
                sign = -1.0 if e == 0 else 1.0  # d = second end - first end
                kind = ends[s, e, 0]
                if kind == 0:
                    continue
                index[m], coef[m] = ends[s, e, 1 + direction], sign
                m += 1
                if kind == 2 and direction == 1:  # z_t + a phi
                    index[m], coef[m] = ends[s, e, 3], sign * arms[s, e]
                    m += 1
            for i in range(m):
                for j in range(m):
                    out[index[i], index[j]] += factor * coef[i] * coef[j]


class TrackForce:
    """The springs of one or more co-running tracks as one compiled force (module docstring).

    Build with :func:`track_force`. The arrays are numba's inputs; the methods add to a
    caller's force vector or Jacobian, indices those of the placements.
    """

    def __init__(
        self,
        arrays: dict[str, np.ndarray],
        springs: tuple[tuple[int, str], ...],
        laws: tuple[tuple[int, str], ...],
    ):
        self._arrays = arrays
        #: (track, spring name) of each spring, in kernel order
        self.springs = springs
        #: (track, entry name) of every law, in the order of :meth:`law_values`
        self.laws = laws
        self._values = np.zeros(len(arrays["law_a"]))
        self._args = tuple(arrays[k] for k in KERNEL_ARRAYS)

    @property
    def arrays(self) -> dict[str, np.ndarray]:
        """The kernel's input arrays by name (:data:`KERNEL_ARRAYS`; do not modify)."""
        return dict(self._arrays)

    def add_forces(self, t: float, q: np.ndarray, q_t: np.ndarray, out: np.ndarray) -> None:
        """Add the springs' generalised forces (N, N m on a roll) at time t to ``out``.

        Parameters
        ----------
        t : float
            s; each track's x = x0 + v t.
        q, q_t : numpy.ndarray
            Coordinates and velocities (float arrays) of the force vector.
        out : numpy.ndarray
            The force vector (right-hand side), added to.
        """
        spring_forces(t, q, q_t, out, self._values, *self._args)

    def add_jacobian(self, t: float, f_q: float, f_q_t: float, out: np.ndarray) -> None:
        """Add f_q K(x) + f_q_t D(x) at time t to ``out`` (the left-hand side's Jacobian).

        Parameters
        ----------
        t : float
            s.
        f_q, f_q_t : float
            Factors of the stiffness and damping matrices.
        out : numpy.ndarray
            (n, n) matrix in the force vector's indices, added to.
        """
        _add_jacobian(t, f_q, f_q_t, out, self._values, *self._args)

    def law_values(self, t: float) -> np.ndarray:
        """The value of every entry the springs use at time t (for checks).

        Parameters
        ----------
        t : float
            s.

        Returns
        -------
        numpy.ndarray
            SI units, in the order of :attr:`laws`.
        """
        values = np.zeros_like(self._values)
        a = self._arrays
        law_values(
            t,
            a["tracks"],
            a["track_poly"],
            a["poly_c"],
            a["poly_n"],
            a["poly_f"],
            a["law_i"],
            a["law_a"],
            a["ramps"],
            values,
        )
        return values


def _polynomial_row(profile: Polynomial, inv_k: float) -> tuple[list[float], list[float]]:
    plain = profile.plain_track_end
    return list(profile.coefficients), [
        profile.x_min,
        profile.x_max,
        math.nan if plain is None else plain,
        math.nan if plain is None else 1.0 / (profile.x_min - plain),
        inv_k,
    ]


def _law(entry: Entry) -> tuple[int, float, list]:
    """(kind, a, ramps) of an entry, ramps as (s_i, 1/ds_i, dv_i) in EntryLaw's order."""
    if entry.kind == "Delta_z":
        return _DELTA_Z, entry.a, []
    if entry.kind == "Delta_y":
        return _DELTA_Y, entry.a, []
    if entry.kind == "ramp":  # a + (b - a) clamp(s): one ramp from s = 0 with slope 1
        return _RAMPS, entry.a, [(0.0, 1.0, entry.b - entry.a)]
    if isinstance(entry, TableEntry):
        v0, ramps = entry.ramps()
        return _RAMPS, v0, [tuple(r) for r in ramps]
    return _CONST, entry.a, []


class _Builder:
    """Rows of the kernel's arrays, track after track."""

    def __init__(self) -> None:
        self.ends: list = []
        self.arms: list = []
        self.laws: list = []
        self.springs: list = []
        self.tracks: list = []
        self.track_poly: list = []
        self.poly_c: list = []
        self.poly_f: list = []
        self.law_i: list = []
        self.law_a: list = []
        self.ramps: list = []
        self.law_names: list = []

    def add(self, k: int, place: TrackPlacement) -> None:
        params, index = place.params, place.index
        zone = params.zone
        self.tracks.append([place.x0, place.v, zone.x_start, 1.0 / (zone.x_end - zone.x_start)])
        reference = reference_support(params.turnout)
        rows = []
        for profile, K_st in (
            (params.turnout.K_sw, reference.K_st_z),
            (params.turnout.K_sh, reference.K_st_y),
        ):
            coefficients, floats = _polynomial_row(profile, 1.0 / K_st)
            rows.append(len(self.poly_c))
            self.poly_c.append(coefficients)
            self.poly_f.append(floats)
        self.track_poly.append(rows)
        law_of: dict[str, int] = {}
        sleeper = (_SLEEPER, index["y_t"], index["z_t"], index["phi_t"])
        for spring in cross_section_springs(params):
            row, lever = [], []
            if spring.ground_y is not None:
                row.append((_GROUND, 0, 0, 0))
                lever.append(0.0)
            if spring.sleeper_y is not None:
                row.append(sleeper)
                lever.append(spring.sleeper_y)
            for end in spring.nodes:
                row.append((_NODE, index[f"y_{end}"], index[f"z_{end}"], 0))
                lever.append(0.0)
            self.ends.append(row)
            self.arms.append(lever)
            self.laws.append([self._law(k, params, n, law_of) for n in spring.k + spring.c])
            self.springs.append((k, spring.name))

    def _law(
        self, k: int, params: CoRunningParameters, name: str | None, law_of: dict[str, int]
    ) -> int:
        if name is None:
            return -1
        if name not in law_of:
            kind, a, entry_ramps = _law(params.entries[name])
            law_of[name] = len(self.law_a)
            self.law_i.append([k, kind, len(self.ramps), len(self.ramps) + len(entry_ramps)])
            self.law_a.append(a)
            self.ramps.extend(entry_ramps)
            self.law_names.append((k, name))
        return law_of[name]

    def arrays(self) -> dict[str, np.ndarray]:
        width = max(len(c) for c in self.poly_c)
        return {
            "ends": np.array(self.ends, dtype=np.int64).reshape(-1, 2, 4),
            "arms": np.array(self.arms, dtype=float).reshape(-1, 2),
            "laws": np.array(self.laws, dtype=np.int64).reshape(-1, 4),
            "tracks": np.array(self.tracks, dtype=float).reshape(-1, 4),
            "track_poly": np.array(self.track_poly, dtype=np.int64).reshape(-1, 2),
            "poly_c": np.array([c + [0.0] * (width - len(c)) for c in self.poly_c], dtype=float),
            "poly_n": np.array([len(c) for c in self.poly_c], dtype=np.int64),
            "poly_f": np.array(self.poly_f, dtype=float).reshape(-1, 5),
            "law_i": np.array(self.law_i, dtype=np.int64).reshape(-1, 4),
            "law_a": np.array(self.law_a, dtype=float),
            "ramps": np.array(self.ramps, dtype=float).reshape(-1, 3),
        }


def track_force(placements: Sequence[TrackPlacement]) -> TrackForce:
    """The springs of the given co-running tracks as one :class:`TrackForce`.

    Parameters
    ----------
    placements : sequence of TrackPlacement
        The tracks: parameter sets, x0 and v, and where their coordinates sit in the
        force vector (every coordinate of the track's
        :func:`~exudyn_turnout.corunning.modal.dof_names`).

    Returns
    -------
    TrackForce
        Its springs in :func:`~exudyn_turnout.corunning.cross_section.cross_section_springs`
        order, track after track.

    Raises
    ------
    KeyError
        A coordinate of a track is missing from its index.
    """
    builder = _Builder()
    for k, place in enumerate(placements):
        builder.add(k, place)
    return TrackForce(builder.arrays(), tuple(builder.springs), tuple(builder.law_names))
