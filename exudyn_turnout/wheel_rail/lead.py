"""Lead of the contact point of a yawed wheel: where along the track it meets the rail.

A wheel is a surface of revolution about its axle; a rail (at one section) is a prismatic
surface along the track X.  Without yaw they touch in the vertical plane through the axle.
With the wheelset yawed by psi (about the vertical, positive turning left), the point of
the wheel that touches the rail is where the wheel's surface normal has no X component.

Derivation (this package; checked against an independent 3-D search of the gap between the
yawed surface of revolution and a prismatic rail in ``tests/test_wheel_rail_lead.py``).  In
the wheel's frame a point of the circle of radius r(y') at angle theta from its lowest
point is ``(r sin(theta), y', -r cos(theta))`` and the surface normal is proportional to
``(sin(theta), -dr/dy', -cos(theta))``.  Its track X component after the yaw is
``sin(theta) cos(psi) + (dr/dy') sin(psi)``; it vanishes at

    sin(theta) = -(dr/dy') tan(psi) = s tan(gamma) tan(psi),

with the kernel's conventions (:mod:`.kernel`: side s = +1 left, -1 right; contact angle
gamma > 0 tilting the normal towards the track centre, so ``dr/dy' = -s tan(gamma)`` in
track Y).  The contact point then lies

- ``x_lead = r sin(theta)`` ahead of the axle (in the wheel's frame): a flange contact
  (gamma = 70 deg) of a wheelset yawed by 5 mrad leads by 6.3 mm, the back of the flange
  against a check rail (|gamma| = 84 deg) by 22 mm;
- ``r (1 - cos(theta))`` higher than the profile's point, so the yawed wheel reaches
  ``r (1 - cos(theta)) cos(gamma)`` further towards the rail along the normal (the normal
  gap closes by that much): 15 um and 54 um in the two examples.

There the wheel's material moves vertically at ``-Omega x_lead`` (Omega = v / r0 the
wheel's rate of turning) while the rail does not: in the contact plane, whose lateral
tangent is ``(0, cos(gamma), s sin(gamma))``, this adds ``-s sin(gamma) Omega x_lead / v``
to the lateral creepage, and with the yaw term ``-psi cos(gamma)`` the lateral creepage of
the yaw becomes ``-psi / cos(gamma)`` to first order (``r / r0 = 1``), the form of the
flange contact's lateral creepage when the contact is taken where it lies (Garg &
Dukkipati, Dynamics of Railway Vehicle Systems, 1984, write a flanging wheel's lateral
creepage with 1 / cos of the contact angle).  The spin creepage is unchanged to first
order (the turning of a surface of revolution about its own axis is tangent to it).

Stage: pure numpy.
"""

from __future__ import annotations

import numpy as np

__all__ = ["MAX_LEAD_SINE", "contact_lead"]

#: |sin(theta)| is capped here: beyond it the touching point would lie r (1 - cos(theta)) >
#: 14 mm above the lowest point of its wheel circle (r = 0.46 m), higher than a rail's head
#: reaches into a flange's root, i.e. outside the profiles' extent (a check rail's face at
#: 84 deg reaches the cap at a yaw of 26 mrad, a 70 deg flange at 91 mrad).
MAX_LEAD_SINE = 0.25


def contact_lead(radius, angle, side, yaw) -> tuple[np.ndarray, np.ndarray]:
    """Lead of the contact point of a yawed wheel and the normal gap it closes.

    Parameters
    ----------
    radius : float or numpy.ndarray
        m, rolling radius of the contact point.
    angle : float or numpy.ndarray
        rad, contact angle (positive: normal force on the wheel towards the track centre).
    side : float or numpy.ndarray
        +1 for the left wheel, -1 for the right.
    yaw : float or numpy.ndarray
        rad, wheelset yaw relative to the rail (about the vertical, positive to the left).

    Returns
    -------
    x_lead : numpy.ndarray
        m, contact point ahead of the axle, ``r sin(theta)`` with
        ``sin(theta) = s tan(gamma) tan(psi)`` (capped at :data:`MAX_LEAD_SINE`).
    closing : numpy.ndarray
        m, how much nearer the rail the yawed wheel is along the contact normal,
        ``r (1 - cos(theta)) cos(gamma)`` (subtract it from the normal gap).
    """
    radius = np.asarray(radius, float)
    angle = np.asarray(angle, float)
    sine = np.clip(
        np.asarray(side, float) * np.tan(angle) * np.tan(np.asarray(yaw, float)),
        -MAX_LEAD_SINE,
        MAX_LEAD_SINE,
    )
    rise = sine * sine / (1.0 + np.sqrt(1.0 - sine * sine))  # 1 - cos(theta)
    return radius * sine, radius * rise * np.cos(angle)
