"""A vehicle's whole contact object in one compiled call: wheel/rail contacts, bumpstops,
co-running track springs.

:class:`~exudyn_turnout.passage.contact.vehicle_contacts.VehicleContacts` is the force
function of one Exudyn ``ObjectGenericODE2``. At speed (no static holds) this module
evaluates it in one numba call per residual instead of several Python calls:

- per wheelset its position x (x0 + v t, or x0 frozen, clamped to the contact tables'
  range), the route's curvature at x (the element's piecewise-linear table, the same
  formula), the kernel :func:`~exudyn_turnout.wheel_rail.kernel.contact_forces` on the
  wheelset's coordinates, and the curving load -m v^2 kappa on wheelset and sprung mass
  (track-following frame);
- the linear bumpstops between car body and bogies (straight track), the law of
  :func:`~exudyn_turnout.passage.vehicle.builder.linear_bumpstop_functions`;
- the co-running tracks' springs (:func:`~exudyn_turnout.corunning.track_kernel.spring_forces`;
  the laws' values, which depend on t only, once per time: the Newton iterations of a step
  share t).

The forces equal those of the Python path, bit for bit. Every small array lives in one
float and one integer buffer (read through views): a numba call costs ~0.1-0.2 us per
argument, and this one takes seven. Exudyn's coordinate lists are packed into the buffer
with one ``struct`` call and the forces go back as a list: both are what Exudyn's Python
interface moves fastest (measured on a 107-coordinate object: a numpy array returned costs
~3 us more per call than a list, two numpy slice assignments ~3 us more than the packing).
"""

from __future__ import annotations

import math
import operator
import struct
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numba
import numpy as np

from exudyn_turnout.corunning.track_kernel import (
    KERNEL_ARRAYS,
    TrackForce,
    applied_spring_forces,
    law_values,
)
from exudyn_turnout.passage.contact.profile import ProfileContactElement
from exudyn_turnout.wheel_rail.kernel import contact_forces

__all__ = ["CompiledResidual", "PACKED_NAMES", "residual_kernel", "record_kernel"]

#: the packed arrays: (name, kind), kind "f" in the float buffer, "i" in the integer one; a
#: kernel reads array j through the header row j (offset, shape): _residual's indices are
#: the positions in this tuple
_PACKED = (
    ("q", "f"),
    ("q_t", "f"),
    ("out", "f"),
    ("motion", "f"),
    ("irregularity", "f"),
    ("constants", "f"),
    ("work", "f"),
    ("details", "f"),
    ("bounds", "f"),
    ("curvature_x", "f"),
    ("curvature_v", "f"),
    ("stop_coefficient", "f"),
    ("stop_points", "f"),
    ("stop_increments", "f"),
    ("track_values", "f"),
    ("arms", "f"),
    ("tracks", "f"),
    ("poly_c", "f"),
    ("poly_f", "f"),
    ("law_a", "f"),
    ("ramps", "f"),
    ("spans", "i"),
    ("sizes", "i"),
    ("layout", "i"),
    ("stop_index", "i"),
    ("stop_count", "i"),
    ("scalars", "i"),  # the contacts' end: the stops' start, zeroed from there on
    ("ends", "i"),
    ("laws", "i"),
    ("track_poly", "i"),
    ("poly_n", "i"),
    ("law_i", "i"),
    ("body_loads", "f"),  # N, the curving loads on this vector (empty on straight track)
    ("stop_shift", "f"),  # m, q_geo of the bumpstops' coordinates (zero on straight track)
    ("law_time", "f"),  # s, the time of track_values (NaN: none yet)
)


@numba.njit(cache=True)
def _curvature(xs, values, x):  # pragma: no cover (compiled)
    """The profile element's ``_interp``: piecewise linear, held beyond the ends."""
    i = np.searchsorted(xs, x, side="right")
    if i <= 0:
        return values[0]
    if i >= xs.shape[0]:
        return values[-1]
    x0, x1 = xs[i - 1], xs[i]
    return values[i - 1] + (values[i] - values[i - 1]) * (x - x0) / (x1 - x0)


@numba.njit(cache=True)
def _all_forces(
    t,
    q,
    q_t,
    out,
    motion,
    spans,
    curvature_x,
    curvature_v,
    irregularity,
    constants,
    work,
    details,
    sizes,
    values,
    blendable,
    xs,
    layout,
    bounds,
):  # pragma: no cover (compiled)
    """Contact forces of every wheelset into ``out`` (assigned on the wheelsets' spans)."""
    for k in range(spans.shape[0]):
        x0, v, lo, hi, frozen = motion[k, 0], motion[k, 1], motion[k, 2], motion[k, 3], motion[k, 4]
        x = x0 if frozen != 0.0 else x0 + v * t
        x = min(max(x, lo), hi)
        kappa = _curvature(curvature_x, curvature_v, x)
        constants[k, 5] = kappa
        a, b = spans[k, 0], spans[k, 1]
        n = b - a
        u, u_t, f = work[k, 0, :n], work[k, 1, :n], work[k, 2, :n]
        for j in range(n):
            u[j] = q[a + j]
            u_t[j] = q_t[a + j]
        n_bodies, n_rows = sizes[k, 0], sizes[k, 1]
        contact_forces(
            x,
            u,
            u_t,
            irregularity[k],
            values,
            blendable,
            xs,
            layout[k, :n_bodies],
            bounds[k, :n_bodies],
            constants[k],
            f,
            details[k, :n_rows],
        )
        for j in range(n):
            out[a + j] = f[j]
        a_y = v**2 * kappa
        if a_y != 0.0:
            out[a] += -(motion[k, 5] * a_y)
            out[a + 5] += -(motion[k, 6] * a_y)


@numba.njit(cache=True)
def _view1(buf, header, j):  # pragma: no cover (compiled)
    o = header[j, 0]
    return buf[o : o + header[j, 1]]


@numba.njit(cache=True)
def _view2(buf, header, j):  # pragma: no cover (compiled)
    # as_strided, not reshape: a reshape costs ~20 ns (a call into numba's helper), a
    # residual takes ~20 2-D views; the 3-D ones (work, details, layout, bounds) stay
    # reshaped, C-contiguous: the contact kernel's loops over them are faster (measured:
    # the residual ~0.4 us faster than with all views strided)
    o, a, b = header[j, 0], header[j, 1], header[j, 2]
    s = buf.itemsize
    return np.lib.stride_tricks.as_strided(buf[o : o + a * b], shape=(a, b), strides=(b * s, s))


@numba.njit(cache=True)
def _view3(buf, header, j):  # pragma: no cover (compiled)
    o, a, b, c = header[j, 0], header[j, 1], header[j, 2], header[j, 3]
    return buf[o : o + a * b * c].reshape((a, b, c))


@numba.njit(cache=True)
def _stop_forces(
    q, out, start, index, coefficient, count, points, increments, shift
):  # pragma: no cover (compiled)
    """Add the linear bumpstops' forces (builder.linear_bumpstop_functions) on q - shift
    to ``out``."""
    for r in range(index.shape[0]):
        u = 0.0
        for j in range(count[r]):
            i = index[r, j]
            u += coefficient[r, j] * (q[start + i] - shift[i])
        a = abs(u)
        if a > points[0]:
            f = 0.0
            for p in range(points.shape[0]):
                if a > points[p]:
                    f += increments[p] * (a - points[p])
            f = math.copysign(f, u)
            for j in range(count[r]):
                out[start + index[r, j]] -= coefficient[r, j] * f


@numba.njit(cache=True)
def _record(t, work, details, record):  # pragma: no cover (compiled)
    """Store the contacts' forces and detail rows of time t in ``record`` (one row per time,
    the later call of a time overwriting: Newton's last call is at the accepted state; a
    time earlier than the last row's, a step tried again smaller, rewinds to it)."""
    n = record.shape[0] - 1
    r = int(record[0, 0])
    if record[0, 1] != 0.0:
        return
    if r < 1 or t > record[r, 0]:
        r += 1
    else:
        while r > 1 and record[r - 1, 0] >= t:
            r -= 1
    if r > n:  # more times than rows (smaller steps than planned): recording given up
        record[0, 1] = 1.0
        return
    record[0, 0] = r
    row = record[r]
    row[0] = t
    j = 1
    for k in range(work.shape[0]):
        for i in range(work.shape[2]):
            row[j] = work[k, 2, i]
            j += 1
        for a in range(details.shape[1]):
            for b in range(details.shape[2]):
                row[j] = details[k, a, b]
                j += 1


@numba.njit(cache=True)
def _residual(t, fbuf, ibuf, header, values, blendable, xs, record):  # pragma: no cover
    """The whole contact object's forces at time t (module docstring), into ``out``; with a
    ``record`` of more than one row the contacts' forces and details too (:func:`_record`),
    each time's once: a call's are pending (``record[0, 2:4]``: flag, time) until a call at
    another time stores them (the last call of a time is the one kept; Newton's iterations
    share t) or :meth:`CompiledResidual.recorded` does."""
    q, q_t, out = _view1(fbuf, header, 0), _view1(fbuf, header, 1), _view1(fbuf, header, 2)
    recording = record.shape[0] > 1
    if recording and record[0, 2] != 0.0 and record[0, 3] != t:  # before work is overwritten
        _record(record[0, 3], _view3(fbuf, header, 6), _view3(fbuf, header, 7), record)
        record[0, 2] = 0.0
    _all_forces(
        t,
        q,
        q_t,
        out,
        _view2(fbuf, header, 3),
        _view2(ibuf, header, 21),
        _view1(fbuf, header, 9),
        _view1(fbuf, header, 10),
        _view2(fbuf, header, 4),
        _view2(fbuf, header, 5),
        _view3(fbuf, header, 6),
        _view3(fbuf, header, 7),
        _view2(ibuf, header, 22),
        values,
        blendable,
        xs,
        _view3(ibuf, header, 23),
        _view3(fbuf, header, 8),
    )
    start = _view1(ibuf, header, 26)[0]
    for j in range(start, out.shape[0]):  # the stops and the track's own coordinates
        out[j] = 0.0
    _stop_forces(
        q,
        out,
        start,
        _view2(ibuf, header, 24),
        _view2(fbuf, header, 11),
        _view1(ibuf, header, 25),
        _view1(fbuf, header, 12),
        _view1(fbuf, header, 13),
        _view1(fbuf, header, 33),
    )
    values, law_time = _view1(fbuf, header, 14), _view1(fbuf, header, 34)
    if law_time[0] != t:  # the springs' laws depend on t only: once per time
        law_values(
            t,
            _view2(fbuf, header, 16),
            _view2(ibuf, header, 29),
            _view2(fbuf, header, 17),
            _view1(ibuf, header, 30),
            _view2(fbuf, header, 18),
            _view2(ibuf, header, 31),
            _view1(fbuf, header, 19),
            _view2(fbuf, header, 20),
            values,
        )
        law_time[0] = t
    applied_spring_forces(
        q,
        q_t,
        out,
        values,
        _view3(ibuf, header, 27),
        _view2(fbuf, header, 15),
        _view2(ibuf, header, 28),
    )
    body = _view1(fbuf, header, 32)
    for j in range(body.shape[0]):
        out[j] += body[j]
    if recording:
        record[0, 2], record[0, 3] = 1.0, t


class CompiledResidual:
    """The hot path of a vehicle's contact object (module docstring).

    Parameters
    ----------
    elements : sequence of ProfileContactElement
        The wheelsets' elements (``WheelsetContactElement``: with the clamps ``x_clamp``,
        ``x_clamp_end`` and a ``frozen`` flag), all on one route (:meth:`serves`).
    spans : sequence of (int, int)
        Each element's coordinates in the force vector.
    n : int
        Size of the force vector.
    stops : dict, optional
        The bumpstops' :func:`~exudyn_turnout.passage.vehicle.builder.linear_bumpstop_arrays`,
        their coordinates following the last element's.
    track : TrackForce, optional
        The co-running tracks' springs on the force vector's indices.
    curved : bool
        Body loads and the bumpstops' q_geo are given per time (:meth:`prepare`).
    """

    def __init__(
        self,
        elements: Sequence[ProfileContactElement],
        spans: Sequence[tuple[int, int]],
        n: int,
        stops: Mapping[str, np.ndarray] | None = None,
        track: TrackForce | None = None,
        curved: bool = False,
    ):
        self.elements = tuple(elements)
        first, n_el = self.elements[0], len(self.elements)
        n_bodies = [el.tables.layout.shape[0] for el in self.elements]
        n_rows = [el._details.shape[0] for el in self.elements]
        layout = np.zeros((n_el, max(n_bodies), 9), dtype=np.int64)
        bounds = np.zeros((n_el, max(n_bodies), first.tables.bounds.shape[1]))
        for k, el in enumerate(self.elements):
            layout[k, : n_bodies[k]] = el.tables.layout
            bounds[k, : n_bodies[k]] = el.tables.bounds
        motion = [
            [
                el.x0,
                el.v,
                getattr(el, "x_clamp", -math.inf),
                getattr(el, "x_clamp_end", math.inf),
                1.0 if getattr(el, "frozen", False) else 0.0,
                el.vehicle.m_w,
                el.vehicle.m_s,
            ]
            for el in self.elements
        ]
        stop = dict(stops) if stops is not None else {}
        arrays: dict[str, np.ndarray] = {
            "q": np.zeros(n),
            "q_t": np.zeros(n),
            "out": np.zeros(n),
            "motion": np.array(motion, dtype=float),
            "irregularity": np.zeros((n_el, 4)),
            "constants": np.array([el._constants for el in self.elements]),
            "work": np.zeros((n_el, 3, max(el.n for el in self.elements))),
            "details": np.zeros((n_el, max(n_rows), first._details.shape[1])),
            "bounds": bounds,
            "curvature_x": np.asarray(first._curvature_x, float),
            "curvature_v": np.asarray(first._curvature_v, float),
            "stop_coefficient": stop.get("coefficient", np.zeros((0, 0))),
            "stop_points": stop.get("points", np.zeros(1)),
            "stop_increments": stop.get("increments", np.zeros(1)),
            "spans": np.array(spans, dtype=np.int64).reshape(-1, 2),
            "sizes": np.array([n_bodies, n_rows], dtype=np.int64).T.copy(),
            "layout": layout,
            "stop_index": stop.get("index", np.zeros((0, 0), dtype=np.int64)),
            "stop_count": stop.get("count", np.zeros(0, dtype=np.int64)),
            "scalars": np.array([max(b for _, b in spans)], dtype=np.int64),
        }
        springs = track.arrays if track is not None else _no_springs()
        arrays.update({k: springs[k] for k in KERNEL_ARRAYS})
        arrays["track_values"] = np.zeros(len(springs["law_a"]))
        arrays["body_loads"] = np.zeros(n if curved else 0)
        arrays["stop_shift"] = np.zeros(n - max(b for _, b in spans))  # from the stops' start
        arrays["law_time"] = np.full(1, math.nan)
        self._fbuf, self._ibuf, self._header, views = _pack(arrays)
        self.q, self.q_t, self.out = views["q"], views["q_t"], views["out"]
        # Exudyn's two lists go into q and q_t (adjacent at the buffer's start) in one
        # struct call: ~1.8 us against ~5 us for two numpy slice assignments
        if self._header[0, 0] != 0 or self._header[1, 0] != n:
            raise AssertionError("q and q_t must lead the float buffer")
        self._states = struct.Struct(f"={2 * n}d")
        self._bytes = self._fbuf.data.cast("B")
        self._motion, self._irregularity = views["motion"], views["irregularity"]
        self._body_loads, self._stop_shift = views["body_loads"], views["stop_shift"]
        self._frozen = tuple(m[4] != 0.0 for m in motion)
        #: reads every element's ``frozen`` flag, where all have one (None: getattr)
        self._frozen_getter = (
            operator.attrgetter("frozen")
            if all(isinstance(getattr(el, "frozen", None), bool) for el in self.elements)
            else None
        )
        self._irregular = [
            (k, el) for k, el in enumerate(self.elements) if el.irregularity is not None
        ]
        self._tables = (first.tables.values, first.tables.blendable, first.tables.x)
        self._work, self._details = views["work"], views["details"]
        #: the run's record (:meth:`start_record`); one row: nothing recorded
        self._record = [np.zeros((1, 2))]

    @staticmethod
    def serves(elements: Sequence[ProfileContactElement]) -> bool:
        """Whether the elements can share one call: one route and the same packed tables.

        Parameters
        ----------
        elements : sequence of ProfileContactElement

        Returns
        -------
        bool
        """
        first = elements[0]
        return all(
            isinstance(el, ProfileContactElement)
            and el.route is first.route
            and el.tables.values is first.tables.values
            and el.tables.blendable is first.tables.blendable
            and el.tables.x is first.tables.x
            for el in elements
        )

    def prepare(
        self, t: float, loads: np.ndarray | None = None, shift: np.ndarray | None = None
    ) -> None:
        """Read the elements' ``frozen`` flags and irregularities at time t (once per t).

        Parameters
        ----------
        t : float
            s.
        loads : numpy.ndarray, optional
            N, the body loads on the force vector at t (``curved``).
        shift : numpy.ndarray, optional
            m, q_geo of the bumpstops' coordinates at t (``curved``).
        """
        if loads is not None:
            self._body_loads[:] = loads
        if shift is not None:
            self._stop_shift[: len(shift)] = shift
        frozen = self._frozen_flags()
        if frozen != self._frozen:
            self._frozen = frozen
            self._motion[:, 4] = frozen
        for k, el in self._irregular:
            self._irregularity[k] = el.irregularity.at(el.x_at(t))

    def _frozen_flags(self) -> tuple:
        """The elements' ``frozen`` flags (False where an element has none)."""
        if self._frozen_getter is not None:  # every element has the flag: one C loop
            return tuple(map(self._frozen_getter, self.elements))
        return tuple(bool(getattr(el, "frozen", False)) for el in self.elements)

    def __call__(self, t: float, q_list, q_t_list) -> np.ndarray:
        """The force vector at time t for Exudyn's coordinate and velocity lists.

        Parameters
        ----------
        t : float
            s.
        q_list, q_t_list : sequence of float
            The object's coordinates and velocities.

        Returns
        -------
        list of float
            The force vector (Exudyn reads a list ~3 us faster than a numpy array).
        """
        self._states.pack_into(self._bytes, 0, *q_list, *q_t_list)
        _residual(t, self._fbuf, self._ibuf, self._header, *self._tables, self._record[0])
        return self.out.tolist()

    def start_record(self, times: int) -> None:
        """Record, from now on, the contacts' forces and detail rows at up to ``times``
        distinct times (a run's steps and its start): what the output columns are made of,
        without evaluating the contacts again after the run (:meth:`recorded`).

        Parameters
        ----------
        times : int
            Rows to keep (a run that takes more times gives its record up).
        """
        width = 1 + self._work.shape[0] * (self._work.shape[2] + self._details[0].size)
        # row 0: rows used, given up, a call pending and its time (_residual)
        record = np.zeros((int(times) + 1, max(width, 4)))
        self._record[0] = record

    def recorded(self, t: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]] | None:
        """The recorded forces and detail rows of every element at the times ``t``, and stop
        recording; None where a time is missing (or the record was given up).

        Parameters
        ----------
        t : numpy.ndarray
            s, the times wanted (a run's sensor times), increasing.

        Returns
        -------
        list of (forces, details) or None
            Per element: (len(t), element size) generalised contact forces (the kernel's,
            without the curving load) and (len(t), rows, fields) detail rows, as
            :func:`~exudyn_turnout.wheel_rail.kernel.contact_history` returns them (views of
            the record where every step was stored).
        """
        record, self._record[0] = self._record[0], np.zeros((1, 2))
        if record.shape[0] > 1 and record[0, 2] != 0.0:  # the last call's, pending
            _record(record[0, 3], self._work, self._details, record)
            record[0, 2] = 0.0
        rows = int(record[0, 0])
        if record.shape[0] < 2 or record[0, 1] != 0.0 or rows < 1:
            return None
        times = record[1 : rows + 1, 0]
        t = np.asarray(t, float)
        if np.array_equal(times, t):  # a row per stored time (every step stored): views
            data = record[1 : rows + 1, 1:]
        else:
            at = np.searchsorted(times, t)
            if np.any(at >= rows) or not np.array_equal(times[np.minimum(at, rows - 1)], t):
                return None
            data = record[1 + at, 1:]
        n_max = self._work.shape[2]
        shape = self._details.shape[1:]
        size = n_max + shape[0] * shape[1]
        out = []
        for k, el in enumerate(self.elements):
            block = data[:, k * size : (k + 1) * size]
            details = block[:, n_max:].reshape(len(t), *shape)[:, : el._details.shape[0]]
            out.append((block[:, : el.n], details))
        return out

    def bound(self) -> Callable[[float, Sequence[float], Sequence[float]], list]:
        """:meth:`__call__` as a closure over the buffers: the same forces, without the
        attribute look-ups of every call (the hot path of a run's ~60,000 calls).

        Returns
        -------
        callable(t, q_list, q_t_list) -> list of float
        """
        pack, data, tolist = self._states.pack_into, self._bytes, self.out.tolist
        fbuf, ibuf, header = self._fbuf, self._ibuf, self._header
        values, blendable, xs = self._tables
        record = self._record

        def call(t: float, q_list: Sequence[float], q_t_list: Sequence[float]) -> list:
            pack(data, 0, *q_list, *q_t_list)
            _residual(t, fbuf, ibuf, header, values, blendable, xs, record[0])
            return tolist()

        return call

    def force_function(
        self, choose: Callable[[float], bool], other: Callable
    ) -> Callable[[Any, float, int, Sequence[float], Sequence[float]], list]:
        """An Exudyn ``forceUserFunction`` whose compiled path is inline: :meth:`bound`'s
        forces where ``choose(t)`` (asked once per time, Newton's iterations share t) says
        the compiled path serves t, else ``other``'s. One Python frame per residual call
        (the hot path of a run's ~54,000 calls).

        Parameters
        ----------
        choose : callable(t) -> bool
            Prepares time t (:meth:`prepare`) and says whether the compiled path serves it.
        other : callable(mbs, t, item_number, q_list, q_t_list) -> list
            The forces where it does not.

        Returns
        -------
        callable(mbs, t, item_number, q_list, q_t_list) -> list of float
        """
        pack, data, tolist = self._states.pack_into, self._bytes, self.out.tolist
        fbuf, ibuf, header = self._fbuf, self._ibuf, self._header
        values, blendable, xs = self._tables
        record = self._record
        chosen = [math.nan, False]  #: the last time, and whether the compiled path serves it

        def force(mbs, t: float, item_number: int, q_list, q_t_list) -> list:
            if t != chosen[0]:
                chosen[0], chosen[1] = t, choose(t)
            if chosen[1]:
                pack(data, 0, *q_list, *q_t_list)
                _residual(t, fbuf, ibuf, header, values, blendable, xs, record[0])
                return tolist()
            return other(mbs, t, item_number, q_list, q_t_list)

        return force


def _no_springs() -> dict[str, np.ndarray]:
    """Empty spring arrays (no compiled track)."""
    return {
        "ends": np.zeros((0, 2, 4), dtype=np.int64),
        "arms": np.zeros((0, 2)),
        "laws": np.zeros((0, 4), dtype=np.int64),
        "tracks": np.zeros((0, 4)),
        "track_poly": np.zeros((0, 2), dtype=np.int64),
        "poly_c": np.zeros((0, 1)),
        "poly_n": np.zeros(0, dtype=np.int64),
        "poly_f": np.zeros((0, 5)),
        "law_i": np.zeros((0, 4), dtype=np.int64),
        "law_a": np.zeros(0),
        "ramps": np.zeros((0, 3)),
    }


def _pack(
    arrays: Mapping[str, np.ndarray],
) -> tuple[np.ndarray, np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """Float buffer, integer buffer, header (offset, shape padded to 3) and the views."""
    sizes = {"f": 0, "i": 0}
    header = np.zeros((len(_PACKED), 4), dtype=np.int64)
    for j, (name, kind) in enumerate(_PACKED):
        a = arrays[name]
        header[j, 0] = sizes[kind]
        header[j, 1 : 1 + a.ndim] = a.shape
        sizes[kind] += a.size
    fbuf, ibuf = np.zeros(max(sizes["f"], 1)), np.zeros(max(sizes["i"], 1), dtype=np.int64)
    views = {}
    for j, (name, kind) in enumerate(_PACKED):
        a = arrays[name]
        buf = fbuf if kind == "f" else ibuf
        view = buf[header[j, 0] : header[j, 0] + a.size].reshape(a.shape)
        view[...] = a
        views[name] = view
    return fbuf, ibuf, header, views


#: the packed arrays' names in the order of the header's rows (for compiled callers that
#: read the buffers: :mod:`~exudyn_turnout.passage.corunning_track.stepper`)
PACKED_NAMES = tuple(name for name, _ in _PACKED)

#: the whole force object's compiled residual ``(t, fbuf, ibuf, header, values, blendable,
#: xs, record)``, for compiled callers (the stepper calls it from numba)
residual_kernel = _residual

#: the record of one time's contact forces and details ``(t, work, details, record)`` (what
#: the residual stores at each call), for compiled callers that record once per time
record_kernel = _record
