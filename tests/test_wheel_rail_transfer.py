"""Load transfer wing rail -> nose and the dip of the wheel's path, from geometry alone.

Crossing: the real UK crossing 56E1-R245-1:9.25 of the multibody S&C benchmark (VSD 61(3),
2023), CONTACT's slices (packaged, Apache-2.0).  The wheel (S1002) is placed at its nominal
position: taping line 70 mm + 1360 / 2 mm from the track centre, the rail's gauge point
(14 mm below its top, at the start of the slice set) at 1435 / 2 mm.
"""

import numpy as np
import pytest

from exudyn_turnout.wheel_rail.data import profile_path, s1002_wheel
from exudyn_turnout.wheel_rail.geometry import WheelsetSetup
from exudyn_turnout.wheel_rail.profiles import read_slices
from exudyn_turnout.wheel_rail.sections import (
    gauge_point,
    lateral_grid,
    slice_sections,
    wheel_envelope,
)
from exudyn_turnout.wheel_rail.transfer import dip_summary, wheel_path

SETUP = WheelsetSetup()


@pytest.fixture(scope="module")
def paths():
    slices = read_slices(profile_path("uk_crossing.slcs"))
    grid = lateral_grid(-0.08, 0.12)
    sections = slice_sections(slices, grid)
    taping = gauge_point(slices.profiles[3]) + SETUP.taping_line - 0.5 * SETUP.gauge
    x = np.arange(0.0, 0.5, 0.01)
    enveloped = wheel_envelope(sections, x, SETUP.nominal_radius, reach=0.08, step=0.004)
    wheel = s1002_wheel(SETUP)
    return {shift: wheel_path(enveloped, wheel, taping, shift) for shift in (-0.003, 0.0, 0.003)}


def test_load_passes_from_wing_rail_to_nose_with_a_dip(paths):
    centred = dip_summary(paths[0.0])
    assert paths[0.0].carrier[0] == 1 and paths[0.0].carrier[-1] == 0  # wing, then nose
    assert 0.1 < centred.transfer_x < 0.45
    # a dip, not a step: the path falls and rises again by a fraction of a millimetre or more
    assert 2e-4 < centred.depth < 3e-3
    assert centred.falling_slope > 1e-3 and centred.rising_slope > 1e-3
    # around the transfer both rails are close: the other rail's gap is small there
    near = np.abs(paths[0.0].x - centred.transfer_x) <= 0.02
    assert np.nanmin(paths[0.0].second_gap[near]) < 1e-3


def test_transfer_point_moves_with_the_lateral_offset(paths):
    transfer = {shift: dip_summary(path).transfer_x for shift, path in paths.items()}
    # towards the field side the tread meets the widening nose earlier (nose widens
    # towards the field side at 1:9.25)
    assert transfer[0.003] < transfer[0.0] < transfer[-0.003]
