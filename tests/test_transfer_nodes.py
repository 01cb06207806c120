"""x nodes where two rails share a wheel (``section_nodes.transfer_nodes``).

The contact tables interpolate each rail's contact linearly between x nodes, and the load
split of two rails sharing a wheel follows the difference d of their first-touch heights
(validation/two_patch_split.md: 0.56 percentage points of the nose's share per um at
54.5 kN).  ``transfer_nodes`` halves a cell while the two rails are within 0.2 mm of first
touch (or change order) and d departs from linear by more than 2 um at its middle.
"""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_turnout.wheel_rail.section_nodes import (
    TRANSFER_MIN_STEP,
    TRANSFER_NEAR,
    TRANSFER_TOLERANCE,
    first_touch_heights,
    transfer_nodes,
    wheel_heights,
)

#: lateral shifts of the synthetic wheel (m)
SHIFTS = np.linspace(-0.004, 0.004, 5)


def _heights(x: float) -> np.ndarray:
    """Synthetic first-touch heights (m) of two rails, (2, n_shifts).

    Rail 0 (wing) stays level; rail 1 (nose) rises along x on a parabola, crossing the wing
    at x = 0.25 + 2 s (s the shift): d'' = 2 /m, so linear interpolation is within 2 um on
    cells up to sqrt(8 * 2e-6 / 2) = 2.8 mm.  On [1, 2] it bends as a cubic while it stays
    3.7 - 6.3 mm below the wing (no transfer).
    """
    wing = np.zeros_like(SHIFTS)
    t = x - 0.25 - 2.0 * SHIFTS
    nose = 0.02 * t + 1.0 * t**2 if x < 1.0 else -0.005 + 0.01 * (x - 1.5) ** 3 + 0.0 * SHIFTS
    return np.stack((wing, nose))


def _interpolation_error(nodes: np.ndarray, xs: np.ndarray) -> float:
    """Largest |linear interpolation of d on ``nodes`` - d| (m) where |d| <= near."""
    d_nodes = np.array([_heights(v)[1] - _heights(v)[0] for v in nodes])
    worst = 0.0
    for x in xs:
        d = _heights(x)[1] - _heights(x)[0]
        blend = np.array([np.interp(x, nodes, d_nodes[:, k]) for k in range(len(SHIFTS))])
        shared = np.abs(d) <= TRANSFER_NEAR
        if shared.any():
            worst = max(worst, float(np.max(np.abs(blend - d)[shared])))
    return worst


def test_transfer_is_refined_until_linear_within_tolerance():
    nodes = np.array([0.0, 0.5])
    xs = np.linspace(0.0, 0.5, 2001)
    before = _interpolation_error(nodes, xs)
    # the parabola on one 0.5 m cell: the error is mm, far above 2 um
    assert before > 100 * TRANSFER_TOLERANCE
    extra = transfer_nodes(_heights, nodes)
    refined = np.sort(np.concatenate((nodes, extra)))
    # the middle of every cell is checked; on a parabola the largest error of a cell is at
    # its middle, so the tolerance bounds the whole cell
    assert _interpolation_error(refined, xs) <= TRANSFER_TOLERANCE
    assert np.min(np.diff(refined)) >= TRANSFER_MIN_STEP - 1e-12
    # fine cells (the parabola needs < 2.8 mm) only where the rails share the wheel: the
    # transfer lies at x = 0.25 +- 8 mm and d leaves +-0.2 mm within ~25 mm of it; outside,
    # the coarser halvings that lead there
    short = np.diff(refined) < 0.004
    assert np.all((refined[:-1][short] > 0.2) & (refined[1:][short] < 0.3))
    assert short.sum() > 0


def test_region_without_transfer_gets_no_nodes():
    # on [1, 2] d bends (the middle of [1, 1.5] lies 0.5 mm off its ends' mean) but stays
    # 3.7 - 6.3 mm (> 0.2 mm) below zero
    assert len(transfer_nodes(_heights, np.array([1.0, 1.5, 2.0]))) == 0
    # the same bend 5 mm higher, where it crosses the wing: refined
    raised = transfer_nodes(lambda x: _heights(x) + [[0.0], [0.005]], np.array([1.0, 1.5, 2.0]))
    assert len(raised) > 0


def test_one_rail_gets_no_nodes():
    assert len(transfer_nodes(lambda x: _heights(x)[1:], np.array([0.0, 0.5]))) == 0


def test_first_touch_heights_flat_wheel_is_highest_point_per_rail():
    # a flat wheel (height 0 everywhere) first touches each rail at its highest point
    y = np.round(np.arange(0.0, 0.1, 1e-4), 6)
    z = np.full_like(y, np.nan)
    z[(y > 0.01) & (y < 0.03)] = -0.001  # gauge-side head (nose)
    z[(y > 0.05) & (y < 0.08)] = np.linspace(-0.002, -0.0005, np.count_nonzero(y > 0.05) - 200)[
        : np.count_nonzero((y > 0.05) & (y < 0.08))
    ]
    wheel_s = np.arange(-0.2, 0.2, 1e-4)
    wheel_z = np.zeros_like(wheel_s)
    over = wheel_heights(y, wheel_s, wheel_z, 0.05, np.array([0.0]))
    h = first_touch_heights(z, over, -0.010)
    assert h.shape == (2, 1)
    assert h[0, 0] == pytest.approx(-0.001)
    assert h[1, 0] == pytest.approx(np.nanmax(z[y > 0.04]))
    # one head: the gauge-side rail is absent
    only = np.where(y > 0.04, z, np.nan)
    h1 = first_touch_heights(only, over, -0.010)
    assert np.isnan(h1[0, 0]) and h1[1, 0] == pytest.approx(np.nanmax(z[y > 0.04]))


def test_first_touch_heights_coned_wheel_closed_form():
    # a wheel coned 1:20 over a flat rail 20 mm wide: first touch at the rail's edge
    # nearest the wheel's lowest point; closed form -|s - y_edge| / 20 below the rail
    y = np.round(np.arange(0.0, 0.1, 1e-4), 6)
    z = np.where((y >= 0.04) & (y <= 0.06), 0.0, np.nan)
    wheel_s = np.round(np.arange(-0.2, 0.2, 1e-4), 6)
    wheel_z = np.abs(wheel_s) / 20.0
    shifts = np.array([0.0, 0.015, -0.02])
    h = first_touch_heights(z, wheel_heights(y, wheel_s, wheel_z, 0.05, shifts))
    taping = 0.05 + shifts
    distance = np.clip(np.maximum(0.04 - taping, taping - 0.06), 0.0, None)
    assert h[0] == pytest.approx(-distance / 20.0, abs=1e-9)


def _pair_error(body_a, body_b, lo: float, hi: float) -> float:
    """Largest error (m) of the two bodies' tables' d (first-touch heights linear between
    each body's nodes) against d of the exact sections every 1 mm, where |d| <= near."""
    from exudyn_turnout.inputs.turnout import load_turnout
    from exudyn_turnout.wheel_rail import turnout_sections as ts
    from exudyn_turnout.wheel_rail.turnout_design import rail_geometry

    context = ts._context(rail_geometry(load_turnout()), False)

    def touch(body, x):
        return ts._first_touch(context, ts._body_heights(context, body.segments, x), None)[0]

    xs = np.arange(lo, hi, 1e-3)
    d = np.array([touch(body_b, x) - touch(body_a, x) for x in xs])
    tables = []
    for body in (body_a, body_b):
        nodes = body.sections.x[(body.sections.x >= lo - 0.05) & (body.sections.x <= hi + 0.05)]
        at = np.array([touch(body, x) for x in nodes])
        tables.append(np.stack([np.interp(xs, nodes, at[:, k]) for k in range(at.shape[1])], 1))
    error = np.abs(tables[1] - tables[0] - d)
    shared = (np.abs(d) <= TRANSFER_NEAR) & np.isfinite(error)
    return float(np.max(error[shared]))


def test_packaged_switch_toe_transfer_is_followed():
    # the stock rail -> blade transfer at the toe of the packaged UIC60 1:15 switch, where
    # the flange meets the blade as it widens: on the nodes of the section tolerance alone
    # (10 mm min_step) the tables' d was up to 390 um off the exact sections' here
    # (measured with the nodes before the transfer nodes, near x = 0.057 m, shift +7.5 mm);
    # with them 5.9 um, what remains the 0.1 mm lateral grid's steps of the blade's planed
    # edge (p95 over the whole switch 1.0 um)
    from exudyn_turnout.inputs.turnout import load_turnout
    from exudyn_turnout.wheel_rail.turnout_sections import route_rail_bodies

    bodies = {b.name: b for b in route_rail_bodies(load_turnout(), "through")}
    stock = bodies["right wheel on right stock rail"]
    blade = bodies["right wheel on switch blade, closure and wing rail"]
    assert _pair_error(stock, blade, 0.0, 0.15) <= 10e-6


def test_slices_segment_gets_nodes_in_its_transfer_only():
    # the packaged turnout with its crossing nose replaced by the UK crossing slices (both
    # heads in one section): on the slice positions alone the wing rail -> nose transfer lay
    # in one 19.7 mm cell (u = 0.2484 - 0.2680 m, validation/two_patch_split.md); the
    # transfer nodes split it, while behind the transfer (u = 0.33 - 0.40 m, the nose
    # alone carries) the nodes stay the slice positions
    import copy
    from dataclasses import replace

    from exudyn_turnout.inputs.turnout import load_turnout
    from exudyn_turnout.wheel_rail.data import profile_path
    from exudyn_turnout.wheel_rail.profiles import read_slices
    from exudyn_turnout.wheel_rail.turnout_sections import route_rail_bodies

    turnout = load_turnout()
    raw = copy.deepcopy(turnout.raw)
    x0 = 46.8
    raw["routes"]["through"]["contacts"][2]["sections"] = [
        {"kind": "slices", "file": "uk_crossing.slcs", "x0": x0, "x": ["nose_tip - 0.1", 51.0]}
    ]
    nose = route_rail_bodies(replace(turnout, raw=raw), "through")[2]
    u = nose.sections.x - x0
    slices = read_slices(profile_path("uk_crossing.slcs")).u
    cell = u[(u > 0.2484 + 1e-4) & (u < 0.2680 - 1e-4)]
    assert len(cell) >= 3
    assert np.max(np.diff(np.concatenate(([0.2484], cell, [0.2680])))) <= 0.005
    behind = u[(u > 0.33) & (u < 0.40)]
    assert len(behind) > 0
    assert all(np.min(np.abs(slices - v)) < 1e-6 for v in behind)
