"""Every wheelset's profile contact of a vehicle in one compiled call.

:class:`~exudyn_turnout.passage.contact.vehicle_contacts.VehicleContacts` evaluates the
contact elements of all wheelsets for Exudyn's force function. At speed (no static holds)
this module does it in one numba call instead of one Python call per wheelset: for each
wheelset its position x (x0 + v t, or x0 frozen, clamped to the contact tables' range),
the route's curvature at x (the element's piecewise-linear table, the same formula), the
kernel :func:`~exudyn_turnout.wheel_rail.kernel.contact_forces` on the wheelset's
coordinates, and the curving load -m v^2 kappa on wheelset and sprung mass
(track-following frame). The forces equal the elements' own, bit for bit.
"""

from __future__ import annotations

from collections.abc import Sequence

import numba
import numpy as np

from exudyn_turnout.passage.contact.profile import ProfileContactElement
from exudyn_turnout.wheel_rail.kernel import contact_forces

__all__ = ["CompiledContacts"]


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


class CompiledContacts:
    """The hot path of a vehicle's contact elements (module docstring).

    Parameters
    ----------
    elements : sequence of ProfileContactElement
        The wheelsets' elements (``WheelsetContactElement``: with the clamps ``x_clamp``,
        ``x_clamp_end`` and a ``frozen`` flag), all on one route (:meth:`serves`).
    spans : sequence of (int, int)
        Each element's coordinates in the force vector.
    """

    def __init__(self, elements: Sequence[ProfileContactElement], spans: Sequence[tuple[int, int]]):
        self.elements = tuple(elements)
        first = self.elements[0]
        self.motion = np.array(
            [
                [
                    el.x0,
                    el.v,
                    getattr(el, "x_clamp", -np.inf),
                    getattr(el, "x_clamp_end", np.inf),
                    0.0,
                    el.vehicle.m_w,
                    el.vehicle.m_s,
                ]
                for el in self.elements
            ]
        )
        self.spans = np.array(spans, dtype=np.int64).reshape(-1, 2)
        self.irregularity = np.zeros((len(self.elements), 4))
        self.constants = np.array([el._constants for el in self.elements])
        n_bodies = [el.tables.layout.shape[0] for el in self.elements]
        n_rows = [el._details.shape[0] for el in self.elements]
        layout = np.zeros((len(self.elements), max(n_bodies), 9), dtype=np.int64)
        bounds = np.zeros((len(self.elements), max(n_bodies), 4))
        for k, el in enumerate(self.elements):
            layout[k, : n_bodies[k]] = el.tables.layout
            bounds[k, : n_bodies[k]] = el.tables.bounds
        self._arrays = (
            np.asarray(first._curvature_x, float),
            np.asarray(first._curvature_v, float),
            self.irregularity,
            self.constants,
            np.zeros((len(self.elements), 3, max(el.n for el in self.elements))),
            np.zeros((len(self.elements), max(n_rows), first._details.shape[1])),
            np.array([n_bodies, n_rows], dtype=np.int64).T.copy(),
            first.tables.values,
            first.tables.blendable,
            first.tables.x,
            layout,
            bounds,
        )

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

    def prepare(self, t: float) -> None:
        """Read the elements' ``frozen`` flags and irregularities at time t (once per t).

        Parameters
        ----------
        t : float
            s.
        """
        for k, el in enumerate(self.elements):
            self.motion[k, 4] = 1.0 if getattr(el, "frozen", False) else 0.0
            if el.irregularity is not None:
                self.irregularity[k] = el.irregularity.at(el.x_at(t))

    def add_to(self, t: float, q: np.ndarray, q_t: np.ndarray, out: np.ndarray) -> None:
        """Every wheelset's contact forces and curving load, assigned to its span of ``out``.

        Parameters
        ----------
        t : float
            s.
        q, q_t : numpy.ndarray
            Coordinates and velocities of the force vector.
        out : numpy.ndarray
            The force vector.
        """
        _all_forces(t, q, q_t, out, self.motion, self.spans, *self._arrays)
