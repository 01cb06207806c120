"""The wheel envelope kept in the table cache: identical to computing it, damage-proof.

Reference values: :func:`exudyn_turnout.wheel_rail.sections.wheel_envelope` itself (the
cache must return exactly what it computes).
"""

import numpy as np
import pytest

from exudyn_turnout.wheel_rail.sections import SectionGrid, wheel_envelope
from exudyn_turnout.wheel_rail.tables import cached_wheel_envelope

RADIUS, REACH, STEP = 0.46, 0.05, 0.002  # m


@pytest.fixture
def sections():
    """A rail head whose height falls along x (a nose-like ramp) on a 1 mm lateral grid."""
    x = np.linspace(0.0, 0.4, 41)
    y = np.linspace(-0.03, 0.03, 61)
    z = -0.5 * y[None, :] ** 2 / 0.3 - 0.01 * np.clip(x[:, None] - 0.2, 0.0, None)
    return SectionGrid(x=x, y=y, z=z, name="ramp")


def _same(a: SectionGrid, b: SectionGrid) -> None:
    for name in ("x", "y", "z", "x_offset"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    assert a.name == b.name


def test_cached_envelope_equals_computed_and_is_read_back(sections, tmp_path):
    direct = wheel_envelope(sections, sections.x, RADIUS, REACH, STEP)
    first = cached_wheel_envelope(sections, sections.x, RADIUS, REACH, STEP, tmp_path)
    files = list(tmp_path.glob("envelope_*.npz"))
    assert len(files) == 1
    second = cached_wheel_envelope(sections, sections.x, RADIUS, REACH, STEP, tmp_path)
    _same(direct, first)
    _same(direct, second)
    # another radius is another entry
    cached_wheel_envelope(sections, sections.x, 0.5, REACH, STEP, tmp_path)
    assert len(list(tmp_path.glob("envelope_*.npz"))) == 2


@pytest.mark.parametrize("damage", ["truncate", "garbage", "empty"])
def test_damaged_envelope_entry_is_computed_again(sections, tmp_path, damage):
    direct = wheel_envelope(sections, sections.x, RADIUS, REACH, STEP)
    cached_wheel_envelope(sections, sections.x, RADIUS, REACH, STEP, tmp_path)
    (path,) = tmp_path.glob("envelope_*.npz")
    data = path.read_bytes()
    path.write_bytes(
        {"truncate": data[: len(data) // 2], "garbage": b"x" * 999, "empty": b""}[damage]
    )
    _same(direct, cached_wheel_envelope(sections, sections.x, RADIUS, REACH, STEP, tmp_path))
    # and the entry is whole again
    _same(direct, cached_wheel_envelope(sections, sections.x, RADIUS, REACH, STEP, tmp_path))


def test_tampered_envelope_values_fail_the_checksum(sections, tmp_path):
    direct = wheel_envelope(sections, sections.x, RADIUS, REACH, STEP)
    cached_wheel_envelope(sections, sections.x, RADIUS, REACH, STEP, tmp_path)
    (path,) = tmp_path.glob("envelope_*.npz")
    with np.load(path) as data:
        content = {k: data[k] for k in data.files}
    content["z"] = content["z"] + 1e-3
    np.savez(path, **content)
    _same(direct, cached_wheel_envelope(sections, sections.x, RADIUS, REACH, STEP, tmp_path))


def test_unusable_cache_location_computes(sections, tmp_path):
    blocker = tmp_path / "not_a_directory"
    blocker.write_text("a file where the cache should be")
    direct = wheel_envelope(sections, sections.x, RADIUS, REACH, STEP)
    with pytest.warns(RuntimeWarning, match="running without a cache"):
        got = cached_wheel_envelope(sections, sections.x, RADIUS, REACH, STEP, blocker)
    _same(direct, got)
