"""CONTACT-style post-processing of a passage (passage/post_contact.py).

The passage's contact rebuilt at a recorded sample must be the passage's own (same normal
force, same contact position), and our exact contact on a plain-rail tread contact, where
Hertz's assumptions hold, must give Hertz's solution.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from exudyn_turnout.passage import simulate_passage
from exudyn_turnout.passage.post_contact import (
    ELEMENTS_ACROSS,
    contact_stems,
    post_contact,
    rebuild_contact,
)
from exudyn_turnout.passage.results import PassageResult
from exudyn_turnout.passage.settings import PassageSettings

RIGHT_STOCK = "cp_right_r1_right_wheel_on_right_stock_rail_0"


def _record(
    stem: str, x: float, y_w: float, z_w: float, normal: float, xi: float = 0.0, yaw: float = 0.0
):
    """A one-sample result of the right wheel on the through route's right stock rail."""

    def one(v):
        return np.array([v])

    columns = {
        "t_s": one(0.0),
        "x_m": one(x),
        "y_wheelset_m": one(y_w),
        "z_wheelset_m": one(z_w),
        "roll_wheelset_rad": one(0.0),
        "yaw_wheelset_rad": one(yaw),
        "y_rail_r1_m": one(0.0),
        "z_rail_r1_m": one(0.0),
        f"{stem}_N_N": one(normal),
        f"{stem}_Fx_N": one(0.0),
        f"{stem}_Ft_N": one(0.0),
        f"{stem}_y_rail_m": one(0.0),
        f"{stem}_x_m": one(0.0),
        f"{stem}_xi_1": one(xi),
        f"{stem}_eta_1": one(0.0),
        f"{stem}_spin_1pm": one(0.0),
    }
    return PassageResult(PassageSettings(route="through"), columns, {})


@pytest.mark.filterwarnings("ignore::UserWarning")  # a start inside the crossing region
def test_rebuilds_the_passage_contact_on_the_wing_rail(turnout):
    """The kernel on the recorded coordinates gives the recorded force and position, and
    the exact patch's force centre lies within 0.5 mm of the recorded contact on the rail
    (issue 22's tolerance for contact positions against CONTACT)."""
    result = simulate_passage(
        turnout, PassageSettings(layers=3, x_start=46.4, x_end=46.6), vehicle="wheelset"
    )
    stem = "cp_right_r2_right_wheel_on_switch_blade_closure_and_wing_rail_0"
    assert stem in contact_stems(result, "right")
    i = len(result.columns["x_m"]) - 1
    recorded = result.columns[f"{stem}_N_N"][i]
    assert recorded > 20e3  # the wheel runs on the wing rail here
    found = post_contact(turnout, result, stem, i)
    # the passage's own contact, evaluated again: the same numbers (damping 0 in the vehicle)
    assert found.rebuilt_normal == pytest.approx(recorded, rel=1e-9)
    assert found.y_rail_rebuilt == pytest.approx(result.columns[f"{stem}_y_rail_m"][i], abs=1e-12)
    assert found.normal == recorded
    # the 3-D gap at the recorded positions: its interpenetration is the passage's
    # penetration within 5 % (the tables' 2-D enveloped sections against the 3-D surfaces)
    assert found.interpenetration == pytest.approx(found.approach, rel=0.05)
    assert abs(found.y_rail_exact - found.y_rail) < 5e-4
    assert found.exact_fx * found.fx > 0.0  # the same creepages, the same sign


def test_plain_rail_tread_contact_is_hertz(turnout):
    """Right wheel on the plain stock rail before the switch (x = -3 m), wheelset 3 mm to
    the right (the contact on the gauge side of the crown, where the table's node is pure
    Hertz), 20 kN.  Reference: Hertz's solution of the node's curvatures, which the
    passage's law is there (its approach, semi-axes and p0 = 3 N / (2 pi a b)).
    Tolerances: approach and the force at the passage's approach 1 %, p_max 5 % (the
    rail's lateral curvature varies across the 9 x 5 mm patch, UIC60's crown R300 falling
    to R80 towards the gauge side, and Hertz takes the point's; measured +3.4 %), the
    patch's extent 2 elements (the exact extent counts whole elements of 1/26 of it)."""
    x, y_w = -3.0, -3e-3

    def excess(z_w: float) -> float:
        record = _record(RIGHT_STOCK, x, y_w, z_w, 1.0)
        return rebuild_contact(turnout, record, RIGHT_STOCK, 0).normal - 20e3

    z_w = brentq(excess, -2e-3, 2e-3, xtol=1e-11)
    found = post_contact(turnout, _record(RIGHT_STOCK, x, y_w, z_w, 20e3, xi=1e-4), RIGHT_STOCK, 0)
    assert found.semi_hertzian == 0.0  # the node's law is Hertz's
    assert found.rebuilt_normal == pytest.approx(20e3, rel=1e-6)
    assert found.exact_approach == pytest.approx(found.approach, rel=0.01)
    assert found.exact_normal_at_approach == pytest.approx(20e3, rel=0.01)
    assert found.exact_p_max == pytest.approx(found.p_max, rel=0.05)
    assert abs(found.exact_length - found.length) <= 2 * found.length / ELEMENTS_ACROSS
    assert abs(found.exact_width - found.width) <= 2 * found.width / ELEMENTS_ACROSS
    assert abs(found.y_rail_exact - found.y_rail_rebuilt) < 1e-4
    # longitudinal creepage alone, in the linear range (xi = 1e-4): F_x = -G a b C11 xi
    # (Kalker) on both the exact patch and the Hertz ellipse: they agree within 3 %
    assert found.exact_fx < 0.0
    assert found.exact_fx == pytest.approx(found.ellipse_fx, rel=0.03)
    # Hertz's gap on plain rail: the exact solution on the 2-D slice is the 3-D one (the
    # slice does not vary along x), and KP is near Hertz (its own method error: up to ~5 %
    # on CONTACT's cases, validation/normal_vs_contact.md)
    assert found.exact_2d_approach == pytest.approx(found.exact_approach, rel=0.02)
    assert found.exact_2d_width == pytest.approx(found.exact_width, rel=0.1)
    assert found.kp_normal_at_approach == pytest.approx(20e3, rel=0.1)
    assert math.isfinite(found.exact_fs)


@pytest.mark.parametrize("yaw", [5e-3, -5e-3])
def test_yawed_flange_contact_leads_as_the_closed_form(turnout, yaw):
    """Right wheel in flange contact (wheelset 7 mm to the right, contact angle 70 deg) on
    the plain stock rail, yawed by 5 mrad, 30 kN.  The exact patch on the yawed body of
    revolution (this module's own 3-D gap) lies ahead of the axle where the passage's
    closed form of the lead puts it (``wheel_rail/lead.py``: r s tan(gamma) tan(psi), 6.4 mm
    here, itself checked against an independent 3-D search in test_wheel_rail_lead.py),
    within 0.5 mm (issue 22's tolerance for contact positions)."""
    x, y_w = -3.0, -7e-3

    def excess(z_w: float) -> float:
        record = _record(RIGHT_STOCK, x, y_w, z_w, 1.0, yaw=yaw)
        return rebuild_contact(turnout, record, RIGHT_STOCK, 0).normal - 30e3

    z_w = brentq(excess, -3e-3, 3e-3, xtol=1e-11)
    record = _record(RIGHT_STOCK, x, y_w, z_w, 30e3, yaw=yaw)
    found = post_contact(turnout, record, RIGHT_STOCK, 0)
    assert math.degrees(found.angle) > 60.0  # flange contact
    lead = rebuild_contact(turnout, record, RIGHT_STOCK, 0).x_contact
    assert abs(lead) > 5e-3 and math.copysign(1.0, lead) == -math.copysign(1.0, yaw)
    assert found.x_contact_exact == pytest.approx(lead, abs=5e-4)


def test_bad_requests_are_one_line_errors(turnout):
    """An unknown contact, a sample without load, a sample outside the run."""
    record = _record(RIGHT_STOCK, -3.0, 0.0, 0.0, 0.0)
    with pytest.raises(ValueError, match="carries no load"):
        post_contact(turnout, record, RIGHT_STOCK, 0)
    with pytest.raises(ValueError, match="outside"):
        rebuild_contact(turnout, record, RIGHT_STOCK, 5)
    with pytest.raises(ValueError, match="no rail body"):
        rebuild_contact(turnout, record, "cp_right_r1_no_such_rail_0", 0)
