"""The contact elements of a vehicle's wheelsets: each wheelset's profile contact clamped to
the turnout and frozen for the steady-state solve, all of them as one Exudyn force
function with a block Jacobian, and each wheelset's output columns."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from exudyn_turnout.corunning.track_kernel import TrackForce
from exudyn_turnout.passage.contact.profile import (
    STATIC_LATERAL_STIFFNESS,
    STATIC_SPIN_STIFFNESS,
    ProfileContactElement,
)
from exudyn_turnout.passage.contact.vehicle_kernel import CompiledResidual

__all__ = [
    "WheelsetContactElement",
    "VehicleContacts",
    "wheelset_columns",
]

#: relative step of the contact Jacobian's forward differences (Exudyn's default
#: ``numericalDifferentiation.relativeEpsilon``)
_JACOBIAN_EPSILON = 1e-7

#: smallest coordinate size scaling that step (Exudyn's ``minimumCoordinateSize``)
_JACOBIAN_MINIMUM_SIZE = 0.01


class WheelsetContactElement(ProfileContactElement):
    """The profile contact element with its position clamped to the turnout's start and,
    for a solve at speed, frozen (x = x0 whatever t)."""

    x_clamp = -math.inf
    x_clamp_end = math.inf  #: m, largest position (the turnout's end: plain track beyond)
    frozen = False
    hold_spin = False

    def x_at(self, t: float) -> float:
        """Position (m) of the wheelset at time t, at least ``x_clamp``; x0 if frozen.

        Parameters
        ----------
        t : float
            s.

        Returns
        -------
        float
            m.
        """
        x = self.x0 if self.frozen else self.x0 + self.v * t
        return min(max(x, self.x_clamp), self.x_clamp_end)

    def columns(self, t: np.ndarray, q: np.ndarray, q_t: np.ndarray) -> dict[str, np.ndarray]:
        """Output columns (see the parent), at the clamped position.

        Parameters
        ----------
        t : numpy.ndarray
            s.
        q, q_t : numpy.ndarray
            Stored element coordinates and velocities.

        Returns
        -------
        dict
        """
        x = np.clip(self.x0 + self.v * np.asarray(t, float), self.x_clamp, self.x_clamp_end)
        return super().columns((x - self.x0) / self.v, q, q_t)

    def __call__(self, mbs, t, item_number, q, q_t):
        """Exudyn ``forceUserFunction`` (the parent's); frozen at speed (the steady-state
        solve, velocities zero) the spin perturbation is held by a spring, as at rest."""
        forces = super().__call__(mbs, t, item_number, q, q_t)
        if self.hold_spin and self.v > 0.0:
            forces[4] -= STATIC_SPIN_STIFFNESS * q[4]
        return forces

    def _generalised_forces(self, x: float, q: np.ndarray, q_t: np.ndarray) -> np.ndarray:
        """:meth:`__call__`'s forces at x, after ``_prepare(x)``: q, q_t float arrays; the
        element's buffer is returned (overwritten by the next call)."""
        self._call(x, q, q_t)
        forces = self._forces
        if self.v > 0.0:
            a_y = self.v**2 * self._kappa
            forces[0] -= self.vehicle.m_w * a_y
            forces[5] -= self.vehicle.m_s * a_y
            if self.hold_spin:
                forces[4] -= STATIC_SPIN_STIFFNESS * q[4]
        else:
            forces[0] -= STATIC_LATERAL_STIFFNESS * q[0]
            forces[4] -= STATIC_SPIN_STIFFNESS * q[4]
        return forces

    @classmethod
    def of(
        cls, element: ProfileContactElement, x_clamp: float, x_clamp_end: float = math.inf
    ) -> WheelsetContactElement:
        """The element ``element`` as a wheelset's contact, clamped to [x_clamp, x_clamp_end].

        Parameters
        ----------
        element : ProfileContactElement
            The wheelset's contact element (its state is shared, not copied).
        x_clamp, x_clamp_end : float
            m, the turnout's start and end: the contact tables' range.

        Returns
        -------
        WheelsetContactElement
        """
        out = cls.__new__(cls)
        out.__dict__.update(element.__dict__)
        out.x_clamp = x_clamp
        out.x_clamp_end = x_clamp_end
        return out


class VehicleContacts:
    """All wheelsets' contact elements as one Exudyn force function (one ObjectGenericODE2).

    One Python call per residual evaluation instead of one per wheelset; positions,
    curvature, irregularity and the curving loads -m_w v^2 kappa prepared once per time (the
    Newton iterations of a step share t). The forces are those of each element's own
    ``__call__``, bit for bit; the wheelsets' blocks do not couple (the numerical Jacobian
    is block diagonal).

    ``stops``: on straight track the vehicle's bumpstops (``vehicle_builder``'s force and
    Jacobian functions on car body and bogies, ``size`` coordinates, and optionally their
    ``linear_bumpstop_arrays`` for the compiled path) ride along on the object's
    coordinates after the contacts': one Python call fewer per residual evaluation.

    At speed without holds the whole object is one compiled call
    (:class:`~exudyn_turnout.passage.contact.vehicle_kernel.CompiledResidual`).

    ``track``: the co-running tracks' springs
    (:class:`~exudyn_turnout.corunning.track_kernel.TrackForce`, one compiled call) ride
    along too, on indices of this object's vector (their rail or m_0 nodes shared with the
    contacts, the others in ``n_track`` coordinates after the stops').
    """

    def __init__(
        self,
        elements: list[WheelsetContactElement],
        stops: tuple | None = None,
        track: TrackForce | None = None,
        n_track: int = 0,
        body_loads: tuple | None = None,
    ):
        self.elements = list(elements)
        ends = np.cumsum([el.n for el in self.elements])
        self.spans = [(int(b - el.n), int(b)) for el, b in zip(self.elements, ends)]
        self.n_contacts = int(ends[-1])  #: coordinates of the contact elements, first
        self.stops = stops  #: (size, force, jacobian) of the bumpstops, or None
        #: end of the bumpstops' coordinates (the track's own ones follow)
        self.n_stops_end = self.n_contacts + (int(stops[0]) if stops is not None else 0)
        self.track = track  #: the tracks' springs, or None
        self.n = self.n_stops_end + int(n_track)
        #: (BodyLoads, index in this vector of each of its coordinates): the curving loads,
        #: and the bumpstops acting on q - q_geo; None on straight track
        self.body_loads = body_loads
        self._t_loads = math.nan
        self._loads = np.zeros(self.n)  #: N, the body loads at _t_loads on this vector
        self._shift = np.zeros(self.n_stops_end - self.n_contacts)  #: m, q_geo of the stops
        self._out = np.zeros(self.n)
        self._bias = np.zeros(self.n)  #: N, the curving loads (subtracted as in __call__)
        self._t = math.nan
        self._x = [0.0] * len(self.elements)
        self._moving = False  #: all at speed without holds: forces = kernel + bias
        self._a_y = [0.0] * len(self.elements)  #: m/s^2, the curving accelerations in _bias
        self._biased = False  #: any curving load (x + 0.0 == x: skipped on straight track)
        #: the whole object in one compiled call (profile elements at speed, no holds)
        self._compiled = (
            CompiledResidual(
                self.elements,
                self.spans,
                self.n,
                None if stops is None else stops[3],
                track,
                body_loads is not None,
            )
            if CompiledResidual.serves(self.elements) and (stops is None or len(stops) > 3)
            else None
        )
        self._t_fast = math.nan
        self._fast = False
        self._running = all(el.v > 0.0 for el in self.elements)  #: no static element

    def _fast_at(self, t: float) -> bool:
        """Whether the compiled path serves time t (all at speed, no holds); prepares it."""
        self._t_fast = t
        compiled = self._compiled
        if compiled is None or not self._running:
            self._fast = False
            return False
        for el in self.elements:
            if el.hold_spin:
                self._fast = False
                return False
        self._fast = True
        if self.body_loads is None:  # straight track: nothing on the vector changes with t
            compiled.prepare(t)
        else:
            compiled.prepare(t, *self._body_loads_at(t))
        return True

    def _body_loads_at(self, t: float) -> tuple[np.ndarray, np.ndarray] | tuple[()]:
        """The body loads on this vector and the stops' q_geo at t (nothing on straight
        track)."""
        if self.body_loads is None:
            return ()
        if t != self._t_loads:
            loads, index = self.body_loads
            self._t_loads = t
            self._loads[index] = loads(None, t, 0, None, None)
            self._shift[:] = loads.geometry_at(t)[: len(self._shift)]
        return self._loads, self._shift

    def _new_time(self, t: float) -> None:
        self._t = t
        self._moving = True
        for k, (el, (a, _)) in enumerate(zip(self.elements, self.spans)):
            x = el.x_at(t)
            el._prepare(x)
            el._cached_t = t
            self._x[k] = x
            if el.v > 0.0 and not el.hold_spin:
                a_y = el.v**2 * el._kappa
                if a_y != self._a_y[k]:  # changes in curves only
                    self._a_y[k] = a_y
                    self._bias[a] = -(el.vehicle.m_w * a_y)
                    self._bias[a + 5] = -(el.vehicle.m_s * a_y)
                    self._biased = bool(np.any(self._bias))
            else:
                self._moving = False

    def _python_forces(self, t: float, q: np.ndarray, q_t: np.ndarray, out: np.ndarray) -> None:
        """The contacts' forces element by element (static holds, x frozen, v = 0)."""
        if t != self._t:
            self._new_time(t)
        if self._moving:  # x - c == x + (-c) exactly
            for el, x, (a, b) in zip(self.elements, self._x, self.spans):
                el._call(x, q[a:b], q_t[a:b])
                out[a:b] = el._forces
            if self._biased:
                out[: self.n_contacts] += self._bias[: self.n_contacts]
        else:
            for el, x, (a, b) in zip(self.elements, self._x, self.spans):
                out[a:b] = el._generalised_forces(x, q[a:b], q_t[a:b])

    def __call__(self, mbs, t, item_number, q_list, q_t_list):
        if self._fast if t == self._t_fast else self._fast_at(t):
            return self._compiled(t, q_list, q_t_list)  # the hot path: equal to the rest
        q, q_t = np.array(q_list, dtype=float), np.array(q_t_list, dtype=float)
        out = self._out
        self._python_forces(t, q, q_t, out)
        curved = self._body_loads_at(t)
        if self.stops is not None:
            c, e = self.n_contacts, self.n_stops_end
            u = list(q[c:e] - curved[1]) if curved else q_list[c:e]  # q - q_geo in a curve
            out[c:e] = self.stops[1](mbs, t, item_number, u, q_t_list[c:e])
        if self.track is not None:
            out[self.n_stops_end :] = 0.0
            self.track.add_forces(t, q, q_t, out)
        if curved:
            out += curved[0]
        return out.tolist()  # Exudyn reads a list faster than a numpy array

    def start_record(self, times: int) -> None:
        """Record the contacts' forces and detail rows during the coming run (the compiled
        path's :meth:`CompiledResidual.start_record
        <exudyn_turnout.passage.contact.vehicle_kernel.CompiledResidual.start_record>`;
        nothing without it).

        Parameters
        ----------
        times : int
            The run's steps and its start.
        """
        if self._compiled is not None:
            self._compiled.start_record(times)

    def recorded(self, t: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]] | None:
        """Per element, the recorded (forces, details) at the times ``t``, or None
        (:meth:`CompiledResidual.recorded
        <exudyn_turnout.passage.contact.vehicle_kernel.CompiledResidual.recorded>`).

        Parameters
        ----------
        t : numpy.ndarray
            s, the run's sensor times.

        Returns
        -------
        list of (numpy.ndarray, numpy.ndarray) or None
        """
        return None if self._compiled is None else self._compiled.recorded(t)

    def last_forces(self) -> list[np.ndarray] | None:
        """Per element, its generalised contact forces (the kernel's, without the curving
        load) at the compiled path's last call: during a run, before a step, those of the
        step's start (the check rail's watch,
        :class:`~exudyn_turnout.passage.check_rail_steps.CheckRailStop`). Views, overwritten by the
        next call; None where the compiled path did not serve the last call.

        Returns
        -------
        list of numpy.ndarray or None
        """
        if self._compiled is None or not self._fast:
            return None
        work = self._compiled._work
        return [work[k, 2, : el.n] for k, el in enumerate(self.elements)]

    def force_function(self) -> Callable:
        """The object's Exudyn ``forceUserFunction``: :meth:`__call__`, with the compiled
        path inline (:meth:`CompiledResidual.force_function
        <exudyn_turnout.passage.contact.vehicle_kernel.CompiledResidual.force_function>`) and
        the choice of path made once per time. The same forces as :meth:`__call__`, bit for bit.

        Returns
        -------
        callable(mbs, t, item_number, q_list, q_t_list) -> list of float
        """
        if self._compiled is None:
            return self.__call__
        return self._compiled.force_function(self._fast_at, self.__call__)

    def jacobian(self, t: float, q: np.ndarray, q_t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """-df/dq and -df/dq_t of the contact forces f (the left-hand side's Jacobians), by
        forward differences per wheelset (its block; the blocks do not couple); without the
        track's springs (:meth:`jacobian_function` adds them).

        The steps are Exudyn's own numerical differentiation's (relative 1e-7 of the
        coordinate, at least 1e-7 x 0.01). The dummy sprung-mass columns (5, 6) are zero:
        nothing acts on them (m_s = 0).

        Parameters
        ----------
        t : float
            s.
        q, q_t : numpy.ndarray
            The object's coordinates and velocities.

        Returns
        -------
        jac_q, jac_q_t : numpy.ndarray
            (n, n), N/m and N s/m.
        """
        if t != self._t:
            self._new_time(t)
        jac_q, jac_q_t = np.zeros((self.n, self.n)), np.zeros((self.n, self.n))
        for el, x, (a, b) in zip(self.elements, self._x, self.spans):
            u, u_t = np.array(q[a:b], dtype=float), np.array(q_t[a:b], dtype=float)
            f0 = el._generalised_forces(x, u, u_t).copy()
            for vector, jac in ((u, jac_q), (u_t, jac_q_t)):
                for j in range(b - a):
                    if j in (5, 6):
                        continue
                    value = vector[j]
                    eps = _JACOBIAN_EPSILON * max(abs(value), _JACOBIAN_MINIMUM_SIZE)
                    vector[j] = value + eps
                    f1 = el._generalised_forces(x, u, u_t)
                    vector[j] = value
                    jac[a:b, a + j] = (f0 - f1) / eps
        if self.stops is not None:  # their tangent stiffness (at q - q_geo); no damping
            c, e = self.n_contacts, self.n_stops_end
            curved = self._body_loads_at(t)
            u = q[c:e] - curved[1] if curved else q[c:e]
            jac_q[c:e, c:e] = self.stops[2](None, t, 0, u, q_t[c:e], 1.0, 0.0)
        return jac_q, jac_q_t

    def jacobian_function(self, mbs, t, item_number, q, q_t, f_q, f_q_t):
        """Exudyn ``jacobianUserFunction``: f_q (-df/dq) + f_q_t (-df/dq_t); the object's
        own stiffness (the dummies' springs) Exudyn adds itself.

        Parameters
        ----------
        mbs : exudyn.MainSystem
        t : float
            s.
        item_number : int
        q, q_t : sequence of float
            The object's coordinates and velocities.
        f_q, f_q_t : float
            Exudyn's factors of the position and velocity Jacobians.

        Returns
        -------
        numpy.ndarray
            (n, n).
        """
        jac_q, jac_q_t = self.jacobian(t, np.asarray(q, float), np.asarray(q_t, float))
        out = f_q * jac_q + f_q_t * jac_q_t
        if self.track is not None:  # the springs' K(x), D(x)
            self.track.add_jacobian(t, f_q, f_q_t, out)
        return out


def wheelset_columns(
    element: ProfileContactElement,
    t: np.ndarray,
    q: np.ndarray,
    q_t: np.ndarray,
    label: str,
    columns: dict[str, np.ndarray] | None = None,
) -> dict[str, np.ndarray]:
    """Per wheel forces and wheelset coordinates of one wheelset, named ``..._<label>_...``.

    Parameters
    ----------
    element : ProfileContactElement
        The wheelset's contact element.
    t : numpy.ndarray
        s, times from the segment's start.
    q, q_t : numpy.ndarray
        Its element coordinates and velocities (samples x element size).
    label : str
        E.g. "ws2".
    columns : dict, optional
        ``element.columns(t, q, q_t)`` if the caller has it already (not computed twice).

    Returns
    -------
    dict
        ``Fz_<label>_<wheel>_N``, ``Fy_<label>_<wheel>_N``, per rail slot
        ``Fz_<label>_<wheel>_<rail>_N``, ``Fy_...``, and ``y_<label>_m``, ``z_<label>_m``,
        ``roll_<label>_rad``, ``yaw_<label>_rad``.
    """
    cols = element.columns(t, q, q_t) if columns is None else columns
    out = {}
    for name, values in cols.items():
        if name.startswith(("Fz_", "Fy_")):
            out[f"{name[:3]}{label}_{name[3:]}"] = values
    for k, name in enumerate(("y", "z", "roll", "yaw")):
        out[f"{name}_{label}_{'m' if k < 2 else 'rad'}"] = q[:, k]
    return out
