"""The gridded wheel kept in the table cache, and the contact tables' lazy cell coefficients.

Reference values: :func:`exudyn_turnout.wheel_rail.geometry.grid_wheel` and
:func:`exudyn_turnout.wheel_rail.tables.cell_coefficients` themselves (the cache and the
lazy property must return exactly what they compute).
"""

import subprocess
import sys
import warnings

import numpy as np
import pytest

from exudyn_turnout.passage.contact.route_cache import wheel_grid
from exudyn_turnout.wheel_rail.data import profile_path
from exudyn_turnout.wheel_rail.geometry import grid_wheel
from exudyn_turnout.wheel_rail.profiles import ProfileFormatError, read_profile
from exudyn_turnout.wheel_rail.tables import (
    TableSettings,
    build_contact_table,
    cell_coefficients,
)

STEP, RADIUS = 1e-4, 0.46  # m, the packaged turnout's grid step and the Manchester wheel
WHEEL = "MBench_S1002_v3.prw"  # the packaged Manchester benchmark wheel


def _same(a, b) -> None:
    for name in ("s", "z", "slope", "curvature"):
        left, right = getattr(a, name), getattr(b, name)
        assert left.dtype == right.dtype and left.shape == right.shape
        np.testing.assert_array_equal(left, right)  # NaN where NaN, bit for bit elsewhere
    assert a.nominal_radius == b.nominal_radius


@pytest.fixture(scope="module")
def direct():
    return grid_wheel(read_profile(profile_path(WHEEL), kind="wheel"), STEP, RADIUS)


def test_cached_wheel_grid_equals_computed_and_is_read_back(direct, tmp_path, monkeypatch):
    first = wheel_grid(profile_path(WHEEL), STEP, RADIUS, tmp_path)
    assert len(list(tmp_path.glob("wheel_grid_*.npz"))) == 1
    _same(direct, first)

    def refuse(*args, **kwargs):
        raise AssertionError("computed again although cached")

    monkeypatch.setattr("exudyn_turnout.wheel_rail.geometry.grid_wheel", refuse)
    _same(direct, wheel_grid(profile_path(WHEEL), STEP, RADIUS, tmp_path))
    monkeypatch.undo()
    # another radius is another entry
    other = wheel_grid(profile_path(WHEEL), STEP, 0.5, tmp_path)
    assert other.nominal_radius == 0.5
    assert len(list(tmp_path.glob("wheel_grid_*.npz"))) == 2


@pytest.mark.parametrize("damage", ["truncate", "garbage", "tampered"])
def test_damaged_wheel_grid_entry_is_computed_again(direct, tmp_path, damage):
    wheel_grid(profile_path(WHEEL), STEP, RADIUS, tmp_path)
    (path,) = tmp_path.glob("wheel_grid_*.npz")
    if damage == "tampered":
        with np.load(path) as data:
            content = {k: data[k] for k in data.files}
        content["slope"] = content["slope"] + 1e-3
        np.savez(path, **content)
    else:
        data = path.read_bytes()
        path.write_bytes(data[: len(data) // 2] if damage == "truncate" else b"x" * 999)
    with pytest.warns(RuntimeWarning, match=f"wheel-grid cache .*{path.name}.*computed again"):
        _same(direct, wheel_grid(profile_path(WHEEL), STEP, RADIUS, tmp_path))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # whole again: read quietly
        _same(direct, wheel_grid(profile_path(WHEEL), STEP, RADIUS, tmp_path))


def test_edited_profile_file_is_another_entry(direct, tmp_path):
    edited = tmp_path / "wheel.prw"
    edited.write_bytes(profile_path(WHEEL).read_bytes())
    _same(direct, wheel_grid(edited, STEP, RADIUS, tmp_path / "cache"))
    edited.write_bytes(edited.read_bytes() + b"\n")  # same profile, other bytes
    _same(direct, wheel_grid(edited, STEP, RADIUS, tmp_path / "cache"))
    assert len(list((tmp_path / "cache").glob("wheel_grid_*.npz"))) == 2


def test_missing_profile_file_raises_as_before(tmp_path):
    with pytest.raises(ProfileFormatError, match="no_such.prw: file not found"):
        wheel_grid(tmp_path / "no_such.prw", STEP, RADIUS, tmp_path)


def test_unusable_cache_location_computes(direct, tmp_path):
    blocker = tmp_path / "not_a_directory"
    blocker.write_text("a file where the cache should be")
    with pytest.warns(RuntimeWarning, match="running without a cache"):
        got = wheel_grid(profile_path(WHEEL), STEP, RADIUS, blocker)
    _same(direct, got)


def test_a_cached_wheel_grid_needs_no_scipy_signal(tmp_path):
    """scipy.signal (the Savitzky-Golay filter) costs ~0.5 s to import: a warm run skips it."""
    code = (
        "import sys\n"
        "from exudyn_turnout.passage.contact.profile import wheel_and_setup\n"
        "from exudyn_turnout.inputs.turnout import load_turnout\n"
        "from exudyn_turnout.inputs.vehicle import load_vehicle\n"
        f"wheel_and_setup(load_turnout(), load_vehicle('wheelset'), {str(tmp_path)!r})\n"
        "print('scipy.signal' in sys.modules)\n"
    )
    runs = [
        subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
        for _ in range(2)
    ]
    assert [r.stdout.strip() for r in runs] == ["True", "False"]  # built, then read back


def test_contact_table_coefficients_are_computed_on_first_use(tmp_path):
    from exudyn_turnout.wheel_rail.sections import SectionGrid

    wheel = grid_wheel(read_profile(profile_path(WHEEL), kind="wheel"), STEP, RADIUS)
    y = np.round(np.arange(-0.04, 0.04, STEP), 10)
    z = -0.5 * y**2 / 0.3  # a round rail head, radius 0.3 m
    sections = SectionGrid(x=np.array([0.0, 1.0]), y=y, z=np.vstack([z, z]), name="head")
    settings = TableSettings(shift_min=-0.004, shift_max=0.004, shift_step=1e-3)
    table = build_contact_table(wheel, sections, 0.0, settings, cache_dir=tmp_path)
    assert "_coefficients" not in table.__dict__  # not built with the table
    expected = cell_coefficients(table.values, table.blendable, table.shift)
    np.testing.assert_array_equal(table.coefficients, expected)
    assert table.coefficients is table.coefficients  # kept
