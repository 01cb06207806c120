"""Readers for Simpack profiles and CONTACT slice files (exudyn_turnout.wheel_rail.profiles)."""

import numpy as np
import pytest

from exudyn_turnout.wheel_rail.data import profile_path
from exudyn_turnout.wheel_rail.profiles import (
    ProfileFormatError,
    read_plain_profile,
    read_profile,
    read_simpack_profile,
    read_slices,
)
from exudyn_turnout.wheel_rail.sections import gauge_point, place_rail


def test_s1002_wheel_is_read_in_metres_field_side_positive_z_up():
    wheel = read_simpack_profile(profile_path("MBench_S1002_v3.prw"))
    assert wheel.kind == "wheel"
    # S1002 flange height 28 mm above the taping line (EN 13715, profile S1002)
    assert -wheel.z.min() == pytest.approx(0.028, abs=2e-4)
    # the flange (lowest point) is on the gauge side (negative y) after Simpack's mirror.y
    assert wheel.y[np.argmin(wheel.z)] == pytest.approx(-0.0549, abs=5e-4)
    # taping line at the origin; flange back 70 mm to the gauge side (EN 13715)
    assert np.interp(0.0, wheel.y[::-1], wheel.z[::-1]) == pytest.approx(0.0, abs=5e-5)
    assert wheel.y.min() == pytest.approx(-0.070, abs=1e-3)
    # the tread falls away towards the field side (radius decreases: z rises)
    assert wheel.z[np.argmax(wheel.y)] > 0.002


def test_manchester_uic60_head_width_and_reference_point():
    rail = read_simpack_profile(profile_path("MBench_UIC60_v3.prr"))
    assert rail.kind == "rail"
    # the file's comment says its reference point is not Simpack's standard: it is the
    # highest point of the already inclined rail, so the top is at y = 0, z = 0
    assert "reference point not SIMPACK standard" in rail.comment
    assert rail.y[np.argmax(rail.z)] == pytest.approx(0.0, abs=1e-3)
    assert rail.z.max() == pytest.approx(0.0, abs=1e-6)
    # 60E1 (UIC60) head width 72 mm (EN 13674-1), measured at the gauge-point depth
    depth = rail.z.max() - 0.014
    crossing = rail.y[np.abs(rail.z - depth) < 3e-4]
    assert crossing.max() - crossing.min() == pytest.approx(0.072, abs=1.5e-3)
    # placed: gauge point at half the gauge, top at 0, independent of the reference point
    placed = place_rail(rail, gauge=1.435)
    assert gauge_point(placed) == pytest.approx(0.7175, abs=1e-9)
    assert placed.z.max() == pytest.approx(0.0, abs=1e-12)


def test_slice_sets_positions_and_profiles():
    nose = read_slices(profile_path("cross_nose.slcs"))
    assert len(nose.profiles) == 21
    assert nose.u[0] == pytest.approx(-0.1) and nose.u[-1] == pytest.approx(0.1)
    assert nose.features.shape == (21, 5)
    uk = read_slices(profile_path("uk_crossing.slcs"))  # u in m (U_SCALE 1000 mm/usr)
    assert len(uk.profiles) == 148
    assert uk.u[0] == pytest.approx(-75.0) and uk.u[-1] == pytest.approx(50.0)
    # plain-text slices in metres, detected as such: a rail head about 70-80 mm wide
    first = uk.profiles[0]
    assert 0.06 < np.ptp(first.y) < 0.2


def test_plain_profile_units(tmp_path):
    path = tmp_path / "rail.txt"
    path.write_text("% y z in mm\n" + "\n".join(f"{y} {0.001 * y * y}" for y in range(-30, 31)))
    in_mm = read_plain_profile(path)
    assert in_mm.y.max() == pytest.approx(0.030)
    assert in_mm.z.min() == pytest.approx(-0.0009)  # file z down -> negated
    assert read_profile(path, length_unit="mm").y.max() == pytest.approx(0.030)
    with pytest.raises(ProfileFormatError, match="rail.txt: consecutive profile points"):
        read_profile(path, length_unit="m")  # 1 m steps: the wrong unit is caught


@pytest.mark.parametrize(
    "content, problem",
    [
        ("header.begin\n type = 0\nheader.end\nspline.begin\n point.begin\n1 2\n", "only 1"),
        ("spline.begin\n point.begin\n1 x\n point.end\nspline.end\n", "not a number"),
        ("foo.begin\n", "unknown block"),
        (
            "header.begin\n type = 7\nheader.end\nspline.begin\npoint.begin\n"
            + "".join(f"{i} 0\n" for i in range(9))
            + "point.end\nspline.end\n",
            "header type",
        ),
    ],
)
def test_bad_simpack_files_raise_one_clear_error(tmp_path, content, problem):
    path = tmp_path / "bad.prr"
    path.write_text(content)
    with pytest.raises(ProfileFormatError, match=problem) as info:
        read_simpack_profile(path)
    assert str(info.value).startswith("bad.prr: ")
    assert isinstance(info.value, ValueError)


def test_missing_and_bad_slice_files(tmp_path):
    with pytest.raises(ProfileFormatError, match="nothere.prw: file not found"):
        read_simpack_profile(tmp_path / "nothere.prw")
    slcs = tmp_path / "set.slcs"
    slcs.write_text("0 1\n2\n0 0 0\n1\n0.0 'a.prr'\n10.0 'missing.prr'\n")
    (tmp_path / "a.prr").write_text(
        "spline.begin\nunits.len.f = 1000.\npoint.begin\n"
        + "".join(f"{i} 0\n" for i in range(9))
        + "point.end\n"
    )
    with pytest.raises(ProfileFormatError, match="set.slcs: slice 'missing.prr'"):
        read_slices(slcs)
    slcs.write_text("0 1\n2\n0 0 0\n1\n10.0 'a.prr'\n0.0 'a.prr'\n")
    with pytest.raises(ProfileFormatError, match="not strictly increasing"):
        read_slices(slcs)
