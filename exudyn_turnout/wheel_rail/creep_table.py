"""Creep forces from a precomputed table (FASTSIM, or any creep solver), for the kernel.

Why a table.  FASTSIM (:mod:`.fastsim`) on a converged grid costs about 130 microseconds per
contact, far more than the kernel's budget; its forces, however, depend on four numbers
only, so they are computed once, stored, and interpolated.

Normalisation
-------------
With Kalker's coefficients C11, C22, C23 of the ellipse a x b (:mod:`.creep`), the normal
force N and friction mu, the creepages are normalised as

    xi' = G a b C11 xi / (3 mu N),  eta' = G a b C22 eta / (3 mu N),
    phi' = G (a b)^1.5 C23 phi / (3 mu N)

(:func:`normalised_creepages`; xi' is Vermeulen & Johnson's (1964) creepage, which
saturates a pure creepage at xi' = 1).  In these, Kalker's linear theory is
``F / (mu N) = -3 (xi', eta' + phi')`` for every ellipse, and the forces of the simplified
theory (and of the exact one: both are invariant under a common scaling of lengths,
loads and moduli) divided by mu N are functions of the ellipse ratio and (xi', eta',
phi') alone.  The table stores ``f = F / (mu N)`` (so ``|f| <= 1``) over four
coordinates, uniform in each:

- ``tau = ln(a / b)``, :data:`RATIO_RANGE` (a / b from 0.0103 to 96.8, clamped outside:
  patches wide across the rolling direction to the long, narrow ones of the crossing
  nose (a / b 26-29 at the through route's crossing peak, validation/peak_contact.md)
  and the check rail (up to 43); Kalker's coefficients beyond a / b in [0.1, 10] are his
  slender-ellipse asymptotes, :mod:`.creep`).  Until creep-table-6 the axis ended at
  0.05 and 20 and the coefficients at Kalker's end rows (0.1, 10): on the nose's patch
  the normalised creepages, and FASTSIM's flexibilities, were those of a / b = 10, and
  C11, C22, C23 0.62, 0.59, 0.44 of the exact theory's at a / b = 20 (issue 22).  The
  axis was extended by whole node steps, so the old nodes are kept and the table is
  unchanged on a / b in [0.1, 10] (validation/creep_table_resolution.md holds);
- the size of the creepage, ``rho = |(xi', eta', phi')|``, compressed to
  ``u`` in [0, 1] with ``rho = u^2 / (1 - u)`` (u = 1 is full slip, computed at rho =
  :data:`FULL_SLIP`): the saturation (rho ~ 1, u ~ 0.6) gets most of the nodes, and the
  first node above zero lies at rho ~ 1e-3, so that Kalker's linear range is met to
  0.1 % (with ``rho = u / (1 - u)`` it lay at 0.03 and the linear forces were 3 % off);
- the direction of the translational creepage, ``alpha = atan2(eta, xi)`` in
  [0, pi / 2] (the direction of the force in full slip without spin);
- the weight of spin, ``beta = atan2(phi l, |(xi, eta)|)`` in [-pi / 2, pi / 2], with a
  length l (:func:`spin_length`) that moves with the size: in saturation it is the
  patch's ``l_p = |(b cos(alpha), a sin(alpha))|`` (spin slips the material by up to
  ``phi b`` along x and ``phi a`` along y, and this length sets where spin competes with
  the creepage it adds to; measured against the friction-normalised creepages instead,
  the change of f on slender patches was squeezed into a few degrees, and the
  interpolation error was twice as large); at small size it is the length of the
  normalised creepages, ``sqrt(a b) C23 / |(C11 cos(alpha), C22 sin(alpha))|``, so
  that beta is the angle between phi' and |(xi', eta')|, in which Kalker's linear theory
  is a sine and a cosine.  The two are blended geometrically, with weight
  ``w = rho / (rho + 0.3)`` (:attr:`CreepTableSettings.spin_blend`) on the patch's.

Why the blend (issue 22).  A vehicle linearised at free rolling (passage/hunting.py)
reads the forces' slopes at zero translational creepage with spin: pure spin, beta =
+-pi / 2.  With the patch's length alone, the normalised angle is ``atan(K tan)`` of the
patch's with ``K = l_p |(C11 cos, C22 sin)| / (sqrt(a b) C23)`` from 0.2 to 31 (5.3 on
the Manchester vehicle's tread patch, a / b = 0.53): near pure spin the force turns
within a beta of ~1 / K, less than one node step (pi / 32), and the first cell's secant
gave dF_x/dxi 0.81 of FASTSIM's slope and a cross slope dF_y/dxi of 0.22 C11 G a b that
FASTSIM does not have (its f_y is even in xi); the linear critical speed came out
342 km/h against 315 km/h converged (validation/creep_table_resolution.md).

Interpolation: linear in tau and alpha; in rho a cubic Hermite through four nodes whose
slopes are three-point differences (exact for a quadratic, so Kalker's linear theory at
small size is kept; node -1 is node 1 mirrored, f(-rho) = -f(rho); linear in u in the
last cell, to full slip); in beta a Catmull-Rom cubic through four nodes, whose slopes
are central differences.  The forces are thus C1 in rho and beta: the slopes of
linearisations and Newton's Jacobians do not jump at their nodes (tested; they still
do at the nodes of tau and alpha).  beta
continues past +-pi / 2 antiperiodically, ``f(beta +- pi) = -f(beta)`` (past pure spin
the translational creepage reverses: the symmetry below), so the end nodes have central
slopes as well: at pure spin dF_y/dxi is exactly 0 there, as in FASTSIM.  A cubic can
leave the unit disc where the table saturates; the resultant is then scaled back onto
it, so ``|F| <= mu N`` holds for any input (tested).

Symmetries of a patch symmetric in x and y: ``f(-xi, -eta, -phi) = -f(xi, eta, phi)``
and the mirror y -> -y, ``f_x(xi, -eta, -phi) = f_x``, ``f_y(xi, -eta, -phi) = -f_y``;
so only xi >= 0, eta >= 0 are stored.

The interpolation error against direct FASTSIM is measured in
tests/test_wheel_rail_creep_table.py, the slopes in tests/test_creep_table_slopes.py, the
cost per call in benchmarks/bench_creep_table.py.

Cost.  3.9 times Polach's law per call, the multilinear creep-table-4 2.2 times
(benchmarks/bench_creep_table.py, 200,000 random contacts, the least of 5 rounds on 2
shared cores: 0.68, 0.39 and 0.17 microseconds; on a busier moment 2.0, 0.93 and 0.41):
the table is read at 64 nodes instead of 16, in 16 runs of 4 consecutive beta nodes.
A contact kernel call (benchmarks/bench_contact_kernel.py, ~6 microseconds) grows by
about 5 %.  The wider ratio axis of creep-table-6 (59 nodes instead of 39, the same
interpolation) left the cost unchanged within the noise: ``--baseline`` runs (rounds
alternating, creep-table-5 as the baseline) gave 398 / 419 and 403 / 414 ns per call (9
rounds), 1401 / 1435 and 677 / 556 ns (5 rounds, busy moments), ratios 0.95-1.22.

Cache.  The FASTSIM table is built once (22 s of CPU time for creep-table-6's 59 ratio
nodes, 1.5 times creep-table-5's 39; 24-32 s wall on 2 shared cores) and stored as
``.npz`` (17.8 MB) in the cache directory (:func:`.tables.default_cache_dir`), named by
a SHA-256 of its settings, with a SHA-256 of its array; a damaged or unreadable file is
named in one warning and rebuilt, an unwritable directory means running without the
cache (one warning).  The fill runs in chunks of nodes without the GIL: a build is shared
by the thread that needs the table and a helper thread (two cores), and
:func:`start_creep_table` starts it early in a thread of its own (``simulate`` does, beside
the route's contact tables); the values are bit-identical to a fill in one thread, and
the file is written only when complete (under a name of its own, then renamed).
"""

from __future__ import annotations

import functools
import hashlib
import math
import threading
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, fields
from pathlib import Path

import numba
import numpy as np

from exudyn_turnout.wheel_rail.creep import CreepForces, kalker_coefficients
from exudyn_turnout.wheel_rail.fastsim import ellipse_many, kalker_flexibilities
from exudyn_turnout.wheel_rail.tables import default_cache_dir, write_cache_file

__all__ = [
    "FULL_SLIP",
    "RATIO_RANGE",
    "HEADER",
    "CreepTableSettings",
    "CreepTable",
    "normalised_creepages",
    "ratio_coordinate",
    "build_creep_table",
    "creep_table",
    "start_creep_table",
    "table_creep_scalar",
    "table_creep_forces",
    "spin_length",
]

#: Normalised creepage at which the table's full-slip edge (u = 1) is evaluated
FULL_SLIP = 1e6
#: -, range of a / b on the table's ratio axis (clamped outside): creep-table-5's 0.05 ... 20
#: extended by 10 of its node steps ln(400) / 38 at either end (its nodes kept), 0.0103 ... 96.8
RATIO_RANGE = (0.05 * 400.0 ** (-10.0 / 38.0), 20.0 * 400.0 ** (10.0 / 38.0))
#: Length of the header in front of a packed table (:attr:`CreepTable.packed`)
HEADER = 8
_FORMAT = "creep-table-6"


@dataclass(frozen=True)
class CreepTableSettings:
    """Grid of a creep table and the FASTSIM discretisation that fills it."""

    poisson: float = 0.28  #: -, Poisson's ratio of Kalker's coefficients
    n_size: int = 33  #: -, nodes of the compressed size u on [0, 1], rho = u^2 / (1 - u)
    n_alpha: int = 17  #: -, nodes of alpha = atan2(eta, xi) on [0, pi / 2]
    n_beta: int = 33  #: -, nodes of beta (module docstring) on [-pi / 2, pi / 2]
    #: -, nodes of ln(a / b) over RATIO_RANGE (step ln(400) / 38 = 0.158, as creep-table-5's
    #: 39 nodes over 0.05 ... 20, which are among them)
    n_ratio: int = 59
    n_strips: int = 24  #: -, FASTSIM strips across the patch
    n_x: int = 24  #: -, FASTSIM elements along x per strip (and 48, extrapolated)
    #: -, creepage size rho at which the spin angle's length is half way from Kalker's
    #: linear scale to the patch's (:func:`spin_length`)
    spin_blend: float = 0.3
    #: interpolation in beta: Catmull-Rom (True) or linear; not part of the stored values
    cubic_beta: bool = True
    #: interpolation in rho: cubic Hermite (True) or linear; not part of the stored values
    cubic_size: bool = True


@dataclass(frozen=True, eq=False)
class CreepTable:
    """Normalised creep forces ``F / (mu N)`` on the table grid (see the module docstring)."""

    values: np.ndarray  #: -, (n_ratio, n_size, n_alpha, n_beta, 2): f_x, f_y
    ratio_first: float  #: -, first node of the ratio coordinate ln(a / b)
    ratio_step: float  #: -, its step
    settings: CreepTableSettings  #: grid and discretisation
    solver: str  #: name of the solver that filled it
    build_seconds: float  #: s, time to build (0 when loaded from the cache)

    @property
    def packed(self) -> np.ndarray:
        """Header (:data:`HEADER` numbers) and the flat values, the kernel's input.

        Returns
        -------
        numpy.ndarray
            ``[n_ratio, n_size, n_alpha, n_beta, t_first, t_step, cubic, blend, values...]``
            (cubic: + 1 for Catmull-Rom in beta, + 2 for a cubic in rho; else linear).
        """
        n_t, n_x, n_e, n_p = self.values.shape[:4]
        cubic = (1.0 if self.settings.cubic_beta else 0.0) + (
            2.0 if self.settings.cubic_size else 0.0
        )
        blend = self.settings.spin_blend
        header = [n_t, n_x, n_e, n_p, self.ratio_first, self.ratio_step, cubic, blend]
        return np.concatenate((np.array(header, float), self.values.ravel()))


def normalised_creepages(xi, eta, phi, a, b, normal_force, friction, shear_modulus, c11, c22, c23):
    """Creepages normalised by the friction force (module docstring).

    ``xi' = G a b C11 xi / (3 mu N)``, ``eta' = G a b C22 eta / (3 mu N)``,
    ``phi' = G (a b)^1.5 C23 phi / (3 mu N)``: Kalker's linear theory is then
    ``F / (mu N) = -3 (xi', eta' + phi')``; ``xi'`` is the creepage of Vermeulen &
    Johnson (1964).

    Parameters
    ----------
    xi, eta : array_like
        Creepages (-).
    phi : array_like
        1/m, spin creepage.
    a, b : array_like
        m, semi-axes in rolling and lateral direction.
    normal_force : array_like
        N (> 0).
    friction : array_like
        Coefficient of friction.
    shear_modulus : float
        Pa.
    c11, c22, c23 : array_like
        Kalker's coefficients of the ellipse.

    Returns
    -------
    tuple of numpy.ndarray
        (xi', eta', phi'), dimensionless.
    """
    scale = np.asarray(shear_modulus * np.asarray(a) * np.asarray(b), float) / (
        3.0 * np.asarray(friction, float) * np.asarray(normal_force, float)
    )
    root = np.sqrt(np.asarray(a, float) * np.asarray(b, float))
    return (
        scale * np.asarray(c11) * np.asarray(xi),
        scale * np.asarray(c22) * np.asarray(eta),
        scale * root * np.asarray(c23) * np.asarray(phi),
    )


def ratio_coordinate(a, b) -> np.ndarray:
    """The table's ellipse-ratio coordinate ``tau = ln(a / b)``.

    Parameters
    ----------
    a, b : array_like
        m, semi-axes in rolling and lateral direction.

    Returns
    -------
    numpy.ndarray
        tau (0 for a circle).
    """
    return np.log(np.asarray(a, float) / np.asarray(b, float))


def _ratio_axis(n: int) -> np.ndarray:
    """Nodes of ln(a / b) over :data:`RATIO_RANGE`."""
    return np.linspace(math.log(RATIO_RANGE[0]), math.log(RATIO_RANGE[1]), n)


def _axis_creepage(u: np.ndarray) -> np.ndarray:
    """Size rho of the compressed coordinate u, ``u^2 / (1 - u)`` (1: :data:`FULL_SLIP`)."""
    inside = np.abs(u) < 1.0
    safe = np.where(inside, np.abs(u), 0.0)
    return np.where(inside, safe * safe / (1.0 - safe), FULL_SLIP)


def _grid(settings: CreepTableSettings):
    t = _ratio_axis(settings.n_ratio)
    u = np.linspace(0.0, 1.0, settings.n_size)
    alpha = np.linspace(0.0, 0.5 * np.pi, settings.n_alpha)
    beta = np.linspace(-0.5 * np.pi, 0.5 * np.pi, settings.n_beta)
    return t, u, alpha, beta


def _node_creepages(u, alpha, beta, a, b, c11, c22, c23, scale, blend):
    """Creepages (xi, eta, phi) of grid coordinates (module docstring); ``scale`` is
    ``3 mu N / (G a b)``, so that ``xi' = c11 xi / scale``; ``blend`` the size
    :attr:`CreepTableSettings.spin_blend`."""
    rho = _axis_creepage(u)
    xi = np.cos(alpha)
    eta = np.sin(alpha)
    length = spin_length(xi, eta, a, b, c11, c22, c23, rho, blend)
    phi = np.tan(np.clip(beta, -1.5707963, 1.5707963)) / length
    size = np.sqrt((c11 * xi) ** 2 + (c22 * eta) ** 2 + (np.sqrt(a * b) * c23 * phi) ** 2)
    factor = rho * scale / size
    # beta = +-pi / 2 is pure spin: no translational creepage at all.  The clipped tangent
    # above leaves (xi, eta) ~ 3e-8 of the spin's share there, which gave these nodes an
    # f_x up to 9e-8 and an f_y that varied by 8e-8 with alpha; the interpolated force then
    # jumped by ~1e-3 N at zero translational creepage (xi = eta = 0, spin != 0), and
    # Exudyn's forward differences (creepage steps ~1e-11) read slopes 1.5-3x too large.
    spin_only = np.abs(beta) >= 1.5707963
    return (
        np.where(spin_only, 0.0, factor * xi),
        np.where(spin_only, 0.0, factor * eta),
        factor * phi,
    )


@numba.njit(cache=True)
def _spin_length(xi, eta, a, b, c11, c22, c23, rho, blend):  # pragma: no cover (compiled)
    """:func:`spin_length` of one contact (compiled; a plain function, where a ufunc cost
    0.3 s at every import to set up)."""
    plane = math.hypot(xi, eta)
    safe = max(plane, 1e-300)  # not 0: the compiler may divide by it on either branch
    cx = xi / safe if plane > 0.0 else 1.0
    ce = eta / safe
    patch = math.hypot(b * cx, a * ce)
    ratio = patch * math.hypot(c11 * cx, c22 * ce) / (math.sqrt(a * b) * c23)
    weight = 1.0
    if blend > 0.0:
        weight = rho / max(rho + blend, 1e-300)
    return patch * math.exp((weight - 1.0) * math.log(ratio))


@numba.njit(cache=True)
def _spin_lengths(xi, eta, a, b, c11, c22, c23, rho, blend, out):  # pragma: no cover
    for k in range(out.shape[0]):
        out[k] = _spin_length(xi[k], eta[k], a[k], b[k], c11[k], c22[k], c23[k], rho[k],
                              blend[k])  # fmt: skip


def spin_length(xi, eta, a, b, c11, c22, c23, rho, blend):
    """m, the length l of the spin angle ``beta = atan2(phi l, |(xi, eta)|)`` (docstring).

    ``l = l_p K^(w - 1)`` with the patch's length ``l_p = |(b xi, a eta)| / |(xi, eta)|``,
    ``K = l_p |(C11 xi, C22 eta)| / (sqrt(a b) C23 |(xi, eta)|)`` (the ratio of the
    patch's angle to the angle of the friction-normalised creepages) and
    ``w = rho / (rho + blend)``: at small creepage (w -> 0) beta is the angle between the
    normalised creepages, in which Kalker's linear theory is linear; in saturation
    (w -> 1) it is the patch's angle (module docstring).  Compiled (:func:`_spin_length`
    for one contact, in the kernel); arrays are broadcast.

    Parameters
    ----------
    xi, eta : array_like
        Creepages, or their direction (only the direction counts; (0, 0) is taken as x).
    a, b : array_like
        m, semi-axes.
    c11, c22, c23 : array_like
        Kalker's coefficients of the ellipse.
    rho : array_like
        Size of the normalised creepages (module docstring).
    blend : array_like
        The size at which w = 1 / 2 (:attr:`CreepTableSettings.spin_blend`).

    Returns
    -------
    float or numpy.ndarray
        m, l (a float for scalar inputs).
    """
    arrays = np.broadcast_arrays(
        *(np.asarray(v, dtype=float) for v in (xi, eta, a, b, c11, c22, c23, rho, blend))
    )
    shape = arrays[0].shape
    x, e, a_, b_, k11, k22, k23, r, w = (np.array(v, dtype=float).ravel() for v in arrays)
    out = np.empty(x.shape[0])
    _spin_lengths(x, e, a_, b_, k11, k22, k23, r, w, out)
    return out.reshape(shape) if shape else float(out[0])


#: Nodes per chunk of a FASTSIM fill shared between threads (about 0.1 s of one core)
_CHUNK = 4096


def _fastsim_inputs(settings: CreepTableSettings) -> tuple:
    """The FASTSIM inputs of every node, flat, as :func:`.fastsim.fastsim_ellipse` makes them.

    Returns (xi, eta, phi, a, b, N, mu, L1, L2, L3) of the nodes in the table's order
    (C order of ``values[..., 0]``) and ``mu N`` on the grid's shape.
    """
    grid = np.meshgrid(*_grid(settings), indexing="ij")
    a, b, q, mu, g = _physical(grid[0])
    c = kalker_coefficients(a, b, settings.poisson)
    scale = 3.0 * mu * q / (g * a * b)
    xi, eta, phi = _node_creepages(
        grid[1], grid[2], grid[3], a, b, c.c11, c.c22, c.c23, scale, settings.spin_blend
    )
    flat = tuple(np.array(v, dtype=float).ravel() for v in (xi, eta, phi, a, b, q, mu))
    flex = kalker_flexibilities(flat[3], flat[4], g, settings.poisson)
    return flat + tuple(np.ascontiguousarray(f) for f in flex), mu * q


@numba.njit(cache=True, nogil=True)
def _fastsim_chunk(
    xi, eta, phi, a, b, q, mu, flex1, flex2, flex3, n_strips, n_x, out, start, stop
):  # pragma: no cover (compiled; tested through build_creep_table)
    """FASTSIM (:func:`.fastsim.fastsim_ellipse`'s compiled loop) on nodes start ... stop - 1,
    into ``out``; without the GIL, so that threads fill a table together."""
    out[start:stop] = ellipse_many(
        xi[start:stop], eta[start:stop], phi[start:stop], a[start:stop], b[start:stop],
        q[start:stop], mu[start:stop], flex1[start:stop], flex2[start:stop],
        flex3[start:stop], n_strips, n_x,
    )  # fmt: skip


class _Fill:
    """A FASTSIM fill of a table's nodes, in chunks that any thread joining it takes.

    The thread that starts it prepares the nodes' inputs and works through the chunks; a
    thread that needs the table calls :meth:`values`, which takes the chunks still left
    and waits for the others.  The chunks' results go to disjoint slices of one array, so
    the values do not depend on which thread computed what (bit-identical to one thread).
    """

    def __init__(self, settings: CreepTableSettings) -> None:
        self.settings = settings
        self._lock = threading.Condition()
        self._prepared = threading.Event()
        self._next = 0  # the next chunk to take
        self._done = 0  # chunks computed
        self._chunks = 0
        self._inputs: tuple = ()
        self._load: np.ndarray | None = None
        self._out: np.ndarray | None = None
        self.error: BaseException | None = None

    def prepare(self) -> None:
        """Make the nodes' inputs (numpy; the starting thread)."""
        try:
            self._inputs, self._load = _fastsim_inputs(self.settings)
            n = self._inputs[0].size
            self._out = np.zeros((n, 2))
            self._chunks = -(-n // _CHUNK)
        except BaseException as err:
            self.error = err
            raise
        finally:
            self._prepared.set()

    def work(self) -> None:
        """Compute chunks until none is left (any thread)."""
        self._prepared.wait()
        out = self._out
        while self.error is None and out is not None:
            with self._lock:
                chunk = self._next
                if chunk >= self._chunks:
                    return
                self._next += 1
            start = chunk * _CHUNK
            try:
                xi, eta, phi, a, b, q, mu, flex1, flex2, flex3 = self._inputs
                _fastsim_chunk(
                    xi, eta, phi, a, b, q, mu, flex1, flex2, flex3, self.settings.n_strips,
                    self.settings.n_x, out, start, min(start + _CHUNK, out.shape[0]),
                )  # fmt: skip
            except BaseException as err:
                with self._lock:
                    self.error = err
                    self._lock.notify_all()
                raise
            with self._lock:
                self._done += 1
                self._lock.notify_all()

    def values(self) -> np.ndarray:
        """The normalised forces ``F / (mu N)`` on the grid, when every chunk is done.

        Returns
        -------
        numpy.ndarray
            (n_ratio, n_size, n_alpha, n_beta, 2).
        """
        self.work()
        with self._lock:
            while self.error is None and self._done < self._chunks:
                self._lock.wait()
        if self.error is not None:
            raise RuntimeError(f"creep table: the FASTSIM fill failed: {self.error}")
        assert self._out is not None and self._load is not None
        shape = self._load.shape
        forces = (self._out[:, 0].reshape(shape), self._out[:, 1].reshape(shape))
        return np.stack(forces, axis=-1) / self._load[..., None]


def _fastsim_nodes(settings: CreepTableSettings) -> np.ndarray:
    """FASTSIM at every node (the default solver), in the calling thread."""
    fill = _Fill(settings)
    fill.prepare()
    return fill.values()


def _physical(t):
    """A patch with ln(a / b) = t, sqrt(a b) = 5 mm, N = 10 kN, mu = 0.3, G = 81 GPa."""
    ratio = np.exp(np.asarray(t, float))
    root = 5e-3
    a = root * np.sqrt(ratio)
    b = root / np.sqrt(ratio)
    return a, b, np.full_like(a, 1e4), np.full_like(a, 0.3), 8.1e10


def build_creep_table(
    settings: CreepTableSettings = CreepTableSettings(),
    solver: Callable[..., tuple[float, float]] | None = None,
) -> CreepTable:
    """Fill a creep table with FASTSIM (default) or any creep solver.

    Parameters
    ----------
    settings : CreepTableSettings
        Grid and FASTSIM discretisation.
    solver : callable, optional
        ``solver(a, b, xi, eta, phi, N, mu, G, nu) -> (F_x, F_y)`` in N on the wheel, the
        sign convention of :func:`.creep.polach_creep_forces` (e.g. an exact-theory
        solver); called once per node (``n_ratio n_size n_alpha n_beta`` calls) on a patch of
        ``sqrt(a b)`` = 5 mm, N = 10 kN, mu = 0.3, G = 81 GPa.  None: FASTSIM
        (:func:`.fastsim.fastsim_ellipse`), vectorised.  The default grid has 1,092,267
        nodes: an exact-theory solver taking 0.1-1 s per solve (a boundary-element
        solution on 16-24 elements across the patch, one core) would need 30-300 hours;
        a grid of 13 x 17 x 9 x 17 nodes (n_ratio, n_size, n_alpha, n_beta) 1-10 hours.

    Returns
    -------
    CreepTable
    """
    start = time.perf_counter()
    if solver is None:
        values = _fastsim_nodes(settings)
        name = "fastsim"
    else:
        t, u, alpha, beta = _grid(settings)
        values = np.zeros((t.size, u.size, alpha.size, beta.size, 2))
        a, b, q, mu, g = _physical(t)
        c = kalker_coefficients(a, b, settings.poisson)
        for i in range(t.size):
            scale = 3.0 * mu[i] * q[i] / (g * a[i] * b[i])
            for index in np.ndindex(u.size, alpha.size, beta.size):
                xi, eta, phi = _node_creepages(
                    u[index[0]], alpha[index[1]], beta[index[2]], a[i], b[i], c.c11[i],
                    c.c22[i], c.c23[i], scale, settings.spin_blend,
                )  # fmt: skip
                fx, fy = solver(
                    a[i], b[i], float(xi), float(eta), float(phi), q[i], mu[i], g,
                    settings.poisson,
                )  # fmt: skip
                values[(i, *index)] = (fx / (mu[i] * q[i]), fy / (mu[i] * q[i]))
        name = getattr(solver, "__name__", "solver")
    return _bounded_table(values, settings, name, start)


def _bounded_table(
    values: np.ndarray, settings: CreepTableSettings, name: str, start: float
) -> CreepTable:
    """The table of filled values, scaled onto the unit disc where they leave it."""
    t_axis = _ratio_axis(settings.n_ratio)
    # a solver may exceed the disc by round-off; the kernel's bound needs |f| <= 1
    size = np.hypot(values[..., 0], values[..., 1])
    values /= np.maximum(size, 1.0)[..., None]
    return CreepTable(
        values=values,
        ratio_first=float(t_axis[0]),
        ratio_step=float(t_axis[1] - t_axis[0]),
        settings=settings,
        solver=name,
        build_seconds=time.perf_counter() - start,
    )


def _key(settings: CreepTableSettings) -> str:
    # the interpolation flags do not change the values: left out (the text is the one
    # creep-table-5 was first keyed with; creep-table-6 adds the ratio range)
    stored = ", ".join(
        f"{f.name}={getattr(settings, f.name)!r}"
        for f in fields(settings)
        if not f.name.startswith("cubic_")
    )
    text = (
        f"({_FORMAT!r}, CreepTableSettings({stored}, cubic_beta=True), {FULL_SLIP!r}, "
        f"'fastsim-parabolic-3-flexibilities', {RATIO_RANGE!r})"
    )
    return hashlib.sha256(text.encode()).hexdigest()


def _checksum(values: np.ndarray) -> str:
    digest = hashlib.sha256(f"{values.dtype.str}:{values.shape}".encode())
    digest.update(np.ascontiguousarray(values).tobytes())
    return digest.hexdigest()


def _read(path: Path, key: str, settings: CreepTableSettings) -> np.ndarray | None:
    shape = (settings.n_ratio, settings.n_size, settings.n_alpha, settings.n_beta, 2)
    try:
        with open(path, "rb") as handle, np.load(handle, allow_pickle=False) as data:
            values = data["values"]
            if str(data["key"]) != key:
                problem = "belongs to other settings"
            elif values.shape != shape:
                problem = f"has values of shape {values.shape}, expected {shape}"
            elif str(data["checksum"]) != _checksum(values):
                problem = "fails its checksum"
            elif not np.all(np.isfinite(values)) or _largest(values) > 1.0 + 1e-12:
                problem = "holds forces outside the friction disc"
            else:
                return values
    except Exception as err:  # any file numpy cannot read is a damaged cache entry
        problem = f"cannot be read ({type(err).__name__}: {err})".replace("\n", " ")
    warnings.warn(f"creep-table cache {path}: {problem}; the table is rebuilt", RuntimeWarning, 2)
    return None


def _largest(values: np.ndarray) -> float:
    """Largest |f| of a table's values (1: the friction bound)."""
    return float(np.hypot(values[..., 0], values[..., 1]).max())


def _write(path: Path, key: str, values: np.ndarray) -> None:
    content = {"values": values, "key": np.array(key), "checksum": np.array(_checksum(values))}
    write_cache_file(path, content, "creep-table cache")


def _cache_path(settings: CreepTableSettings, cache_dir: str | None) -> tuple[str, Path]:
    """The key of a table and its cache file."""
    key = _key(settings)
    return key, Path(cache_dir or default_cache_dir()) / f"creep_table_{key[:24]}.npz"


class _Background:
    """A table filled and cached by a thread of its own (:func:`start_creep_table`); the
    thread that needs it joins the fill (:meth:`_Fill.work`) and then the thread."""

    def __init__(self, settings: CreepTableSettings, key: str, path: Path) -> None:
        self.fill = _Fill(settings)
        self.table: CreepTable | None = None
        self.thread = threading.Thread(
            target=self._run, args=(key, path), name="creep-table", daemon=True
        )
        self.thread.start()

    def _run(self, key: str, path: Path) -> None:
        start = time.perf_counter()
        try:
            self.fill.prepare()
            table = _bounded_table(self.fill.values(), self.fill.settings, "fastsim", start)
        except BaseException:  # noqa: BLE001 (the joining thread builds it again, or fails)
            return
        _write(path, key, table.values)  # atomic: a killed build leaves no partial file
        self.table = table

    def join(self) -> CreepTable | None:
        """Help fill the table, wait for it; None if the fill failed."""
        try:
            self.fill.work()
        finally:
            self.thread.join()
        return self.table


#: Fills under way in background threads, by cache file (:func:`start_creep_table`)
_RUNNING: dict[str, _Background] = {}
_RUNNING_LOCK = threading.Lock()


def start_creep_table(
    settings: CreepTableSettings = CreepTableSettings(), cache_dir: str | None = None
) -> bool:
    """Start building the FASTSIM creep table in a background thread, unless it is cached.

    For a caller that knows early that it will need the table (the ``simulate`` command,
    before its contact tables are built): the fill runs beside the caller's work without
    the GIL (compiled, ``nogil``), is written to the cache (atomically) when it is done,
    and :func:`creep_table` joins it, taking over the chunks still left.

    Parameters
    ----------
    settings : CreepTableSettings
        Grid and discretisation.
    cache_dir : str, optional
        Cache location (default :func:`.tables.default_cache_dir`).

    Returns
    -------
    bool
        True if the table is being built (now started, or already under way); False if its
        cache file exists (it is read, or rebuilt if damaged, by :func:`creep_table`).
    """
    key, path = _cache_path(settings, cache_dir)
    with _RUNNING_LOCK:
        if str(path) in _RUNNING:
            return True
        if path.is_file():
            return False
        _RUNNING[str(path)] = _Background(settings, key, path)
    return True


@functools.lru_cache(maxsize=4)
def creep_table(
    settings: CreepTableSettings = CreepTableSettings(), cache_dir: str | None = None
) -> CreepTable:
    """The FASTSIM creep table: from memory, from the disk cache, or built and cached.

    A table to build is filled by this thread and a helper thread together (two cores);
    a build started by :func:`start_creep_table` is joined.

    Parameters
    ----------
    settings : CreepTableSettings
        Grid and discretisation.
    cache_dir : str, optional
        Cache location (default :func:`.tables.default_cache_dir`).

    Returns
    -------
    CreepTable
    """
    key, path = _cache_path(settings, cache_dir)
    with _RUNNING_LOCK:
        running = _RUNNING.pop(str(path), None)
    if running is None and path.is_file():
        values = _read(path, key, settings)
        if values is not None:
            t_axis = _ratio_axis(settings.n_ratio)
            return CreepTable(
                values=values,
                ratio_first=float(t_axis[0]),
                ratio_step=float(t_axis[1] - t_axis[0]),
                settings=settings,
                solver="fastsim",
                build_seconds=0.0,
            )
    if running is None:
        running = _Background(settings, key, path)
    table = running.join()
    if table is None:  # the helper failed: once more in this thread, its error raised
        table = build_creep_table(settings)
        _write(path, key, table.values)
    return table


@numba.njit(cache=True)
def _size_node(i, n):  # pragma: no cover (compiled)
    """Size rho of node i of n (:func:`_axis_creepage`; :data:`FULL_SLIP` at the last)."""
    if i >= n - 1:
        return FULL_SLIP
    return i * i / ((n - 1.0) * (n - 1.0 - i))


@numba.njit(cache=True)
def table_creep_scalar(
    packed, offset, xi, eta, phi, a, b, Q, mu, G, c11, c22, c23
):  # pragma: no cover (compiled; tested through table_creep_forces and the kernel)
    """Creep forces of one contact from a packed table (compiled): (F_x, F_y) on the wheel.

    Parameters
    ----------
    packed : numpy.ndarray
        Array holding a :attr:`CreepTable.packed` from index ``offset`` on.
    offset : int
        Index of its header.
    xi, eta : float
        Creepages (-).
    phi : float
        1/m, spin creepage.
    a, b : float
        m, semi-axes in rolling and lateral direction.
    Q : float
        N, normal force.
    mu : float
        Friction coefficient.
    G : float
        Pa, shear modulus.
    c11, c22, c23 : float
        Kalker's coefficients of the ellipse.

    Returns
    -------
    tuple of float
        N, (F_x, F_y); ``|F| <= mu Q``.
    """
    if Q <= 0.0 or a <= 0.0 or b <= 0.0 or mu <= 0.0:
        return 0.0, 0.0
    q_mu = Q * mu
    sign = 1.0
    if xi < 0.0:  # f(-c) = -f(c)
        xi, eta, phi, sign = -xi, -eta, -phi, -1.0
    mirror = 1.0
    if eta < 0.0:  # y -> -y: f_y changes sign
        eta, phi, mirror = -eta, -phi, -1.0
    scale = G * a * b / (3.0 * q_mu)
    cx = scale * c11 * xi
    ce = scale * c22 * eta
    cp = scale * math.sqrt(a * b) * c23 * phi
    n_t = int(packed[offset])
    n_r = int(packed[offset + 1])
    n_a = int(packed[offset + 2])
    n_b = int(packed[offset + 3])
    t_first = packed[offset + 4]
    t_step = packed[offset + 5]
    t = math.log(a / b)
    position = min(max((t - t_first) / t_step, 0.0), n_t - 1.000001)
    it = int(position)
    wt = position - it
    # size, compressed, and the direction of the creepages (module docstring)
    rho = math.sqrt(cx * cx + ce * ce + cp * cp)
    position = 0.5 * (math.sqrt(rho * rho + 4.0 * rho) - rho) * (n_r - 1)  # u of rho
    ir = min(int(position), n_r - 2)
    flags = int(packed[offset + 6] + 0.5)  # 1: cubic in beta, 2: cubic in rho
    # rho: nodes ir - 1 ... ir + 2 with weights v0 ... v3; linear in u in the last cell (to
    # full slip); below it linear in rho, or a cubic Hermite in rho whose node slopes are
    # three-point differences (exact for a quadratic, so Kalker's linear theory is kept);
    # node -1 is node 1 mirrored, f(-rho) = -f(rho) (the creepages reversed)
    r0, r3 = ir - 1, ir + 2
    v0 = v3 = 0.0
    if ir == n_r - 2:
        v2 = position - ir
        v1 = 1.0 - v2
    else:
        low = _size_node(ir, n_r)
        high = _size_node(ir + 1, n_r)
        d1 = high - low
        w = min(max((rho - low) / d1, 0.0), 1.0)
        v1, v2 = 1.0 - w, w
        if flags & 2:
            d0 = low - (_size_node(ir - 1, n_r) if ir > 0 else -_size_node(1, n_r))
            d2 = _size_node(ir + 2, n_r) - high
            w2 = w * w
            h10 = (w2 - 2.0 * w + 1.0) * w * d1  # Hermite's basis times the cell length
            h11 = (w2 - w) * w * d1
            h01 = (3.0 - 2.0 * w) * w2
            a0 = -d1 / (d0 * (d0 + d1))  # slope at low: a0 f0 + a1 f1 + a2 f2
            a2 = d0 / (d1 * (d0 + d1))
            b1 = -d2 / (d1 * (d1 + d2))  # slope at high: b1 f1 + b2 f2 + b3 f3
            b3 = d1 / (d2 * (d1 + d2))
            v0 = h10 * a0
            v1 = 1.0 - h01 - h10 * (a0 + a2) + h11 * b1
            v2 = h01 + h10 * a2 - h11 * (b1 + b3)
            v3 = h11 * b3
    if r0 < 0:
        r0 = 1
        v0 = -v0
    position = math.atan2(eta, xi) * (2.0 / math.pi) * (n_a - 1)
    ia = min(int(position), n_a - 2)
    wa = position - ia
    plane = math.hypot(xi, eta)
    length = _spin_length(xi, eta, a, b, c11, c22, c23, rho, packed[offset + 7])
    position = (math.atan2(phi * length, plane) / math.pi + 0.5) * (n_b - 1)
    ib = min(int(position), n_b - 2)
    wb = position - ib
    # beta: Catmull-Rom through nodes ib - 1 ... ib + 2 (C1, its slopes central differences),
    # or linear (header[6] = 0); beyond +-pi / 2 the nodes continue antiperiodically,
    # f(beta +- pi) = -f(beta) (module docstring), so the ends have central slopes, too
    j0, j1, j2, j3 = ib - 1, ib, ib + 1, ib + 2
    if flags & 1:
        w2_ = wb * wb
        w3_ = w2_ * wb
        w0 = 0.5 * (-w3_ + 2.0 * w2_ - wb)
        w1 = 0.5 * (3.0 * w3_ - 5.0 * w2_ + 2.0)
        w2 = 0.5 * (-3.0 * w3_ + 4.0 * w2_ + wb)
        w3 = 0.5 * (w3_ - w2_)
    else:
        w0, w1, w2, w3 = 0.0, 1.0 - wb, wb, 0.0
    if j0 < 0:
        j0 += n_b - 1
        w0 = -w0
    if j3 > n_b - 1:
        j3 -= n_b - 1
        w3 = -w3
    base = offset + HEADER
    fx = 0.0
    fy = 0.0
    for dt in range(2):
        w_t = wt if dt else 1.0 - wt
        for dr in range(4):
            if dr == 0:
                w_r, jr = w_t * v0, r0
            elif dr == 1:
                w_r, jr = w_t * v1, ir
            elif dr == 2:
                w_r, jr = w_t * v2, ir + 1
            else:
                w_r, jr = w_t * v3, r3
            if w_r == 0.0:
                continue
            for da in range(2):
                w_a = w_r * (wa if da else 1.0 - wa)
                k = base + 2 * (((it + dt) * n_r + jr) * n_a + ia + da) * n_b
                fx += w_a * (
                    w0 * packed[k + 2 * j0] + w1 * packed[k + 2 * j1]
                    + w2 * packed[k + 2 * j2] + w3 * packed[k + 2 * j3]
                )  # fmt: skip
                fy += w_a * (
                    w0 * packed[k + 2 * j0 + 1] + w1 * packed[k + 2 * j1 + 1]
                    + w2 * packed[k + 2 * j2 + 1] + w3 * packed[k + 2 * j3 + 1]
                )  # fmt: skip
    size = math.hypot(fx, fy)
    if size > 1.0:  # the cubics may overshoot near saturation: back onto the disc
        fx /= size
        fy /= size
    return sign * q_mu * fx, sign * mirror * q_mu * fy


@numba.njit(cache=True)
def _many(packed, xi, eta, phi, a, b, q, mu, g, c11, c22, c23):  # pragma: no cover (compiled)
    out = np.zeros((xi.shape[0], 2))
    for k in range(xi.shape[0]):
        fx, fy = table_creep_scalar(
            packed, 0, xi[k], eta[k], phi[k], a[k], b[k], q[k], mu[k], g, c11[k], c22[k], c23[k]
        )
        out[k, 0] = fx
        out[k, 1] = fy
    return out


def table_creep_forces(
    table: CreepTable,
    creep_longitudinal,
    creep_lateral,
    spin,
    a,
    b,
    normal_force,
    friction,
    shear_modulus: float = 8.1e10,
) -> CreepForces:
    """Creep forces interpolated in a creep table (arrays; the kernel's law in Python).

    Parameters
    ----------
    table : CreepTable
        From :func:`creep_table` or :func:`build_creep_table`.
    creep_longitudinal, creep_lateral : array_like
        Creepages xi, eta (-).
    spin : array_like
        1/m, spin creepage.
    a, b : array_like
        m, semi-axes in rolling and lateral direction.
    normal_force : array_like
        N.
    friction : array_like
        Coefficient of friction.
    shear_modulus : float
        Pa.

    Returns
    -------
    CreepForces
        On the wheel, ``|F| <= mu N``.
    """
    arrays = np.broadcast_arrays(
        *(np.asarray(v, float) for v in (creep_longitudinal, creep_lateral, spin, a, b,
                                          normal_force, friction))
    )  # fmt: skip
    shape = arrays[0].shape
    xi, eta, phi, a_, b_, q, mu = (np.array(v, dtype=float).ravel() for v in arrays)
    usable = (a_ > 0.0) & (b_ > 0.0)
    c = kalker_coefficients(
        np.where(usable, a_, 1.0), np.where(usable, b_, 1.0), table.settings.poisson
    )
    out = _many(
        table.packed, xi, eta, phi, a_, b_, q, mu, float(shear_modulus),
        *(np.array(np.broadcast_to(v, xi.shape), dtype=float)
          for v in (c.c11, c.c22, c.c23)),
    )  # fmt: skip
    return CreepForces(longitudinal=out[:, 0].reshape(shape), lateral=out[:, 1].reshape(shape))
