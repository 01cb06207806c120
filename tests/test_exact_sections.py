"""Exact rail sections between a body's nodes (turnout_sections.exact_sections_between).

A body's sections are blended linearly between its x nodes. On the packaged check rail's
flare (1:67, 15 mm over 1 m to x = 45.29 m, ``[check_rail]`` of
``data/uic60_760_1_15.toml``) the nodes lie 62.5 mm apart, and blending the heights of two
laterally shifted steep faces is not a face in between. ``post_contact`` therefore adds
the rail's exact section every 1 mm around a contact. The reference here is the closed form
of the face's position, ``check_face`` (clearance plus the flare's linear opening).
"""

import numpy as np
import pytest

from exudyn_turnout.wheel_rail.sections import sections_at
from exudyn_turnout.wheel_rail.turnout_design import check_face, rail_geometry
from exudyn_turnout.wheel_rail.turnout_sections import exact_sections_between, route_rail_bodies

LEVEL = -0.015  #: m, a height on the check rail's face (the flange back's contact there)
NODE = 45.2275  #: m, the body's node before the flare's end (45.29 m), 62.5 mm before it


@pytest.fixture(scope="module")
def check_rail(turnout):
    """The diverging route's check-rail body and the turnout's design."""
    body = next(b for b in route_rail_bodies(turnout, "diverging") if b.back_of_flange)
    return body, rail_geometry(turnout)


def _face(y: np.ndarray, z: np.ndarray, level: float) -> float:
    """m, lateral position where the section's face falls through ``level`` (linear)."""
    i = int(np.flatnonzero(np.isfinite(z) & (z > level)).max())
    return float(y[i] + (z[i] - level) / (z[i] - z[i + 1]) * (y[i + 1] - y[i]))


def test_the_flare_nodes_are_where_this_test_expects_them(check_rail):
    """The body's nodes around the flare end (what makes its blend cut the face)."""
    body, _ = check_rail
    x = body.sections.x
    assert np.any(np.isclose(x, NODE)) and np.any(np.isclose(x, 45.29))
    assert not np.any((x > NODE + 1e-9) & (x < 45.29 - 1e-9))


@pytest.mark.parametrize("x", [45.2405, 45.2585, 45.2595, 45.2775])
def test_refined_sections_follow_the_flare_where_the_blend_does_not(turnout, check_rail, x):
    """Between two nodes the refined face moves as check_face's closed form (1:67) and as
    the exact section at x; the body's own blend is a tenth of a millimetre or more off at
    mid-cell."""
    body, geometry = check_rail
    refined = exact_sections_between(turnout, body, 45.2, 45.4)
    y = body.sections.y
    at_node = _face(y, sections_at(refined, np.array([NODE]))[0], LEVEL)
    expected = -(
        check_face(x, body.x_from, body.x_to, geometry.check_rail)
        - check_face(NODE, body.x_from, body.x_to, geometry.check_rail)
    )
    moved = _face(y, sections_at(refined, np.array([x]))[0], LEVEL) - at_node
    # the sections lie on the 0.1 mm lateral grid: a level's crossing interpolated linearly
    # between grid points of the curved face carries up to ~3.5 um (at the body's own exact
    # nodes the face lies 52.4-55.5 um from the closed form at this level), hence 5 um
    assert moved == pytest.approx(expected, abs=5e-6)
    exact = exact_sections_between(turnout, body, x, x)  # the exact section at x itself
    at_x = _face(y, sections_at(exact, np.array([x]))[0], LEVEL) - at_node
    assert moved == pytest.approx(at_x, abs=2e-7)  # 1 mm refinement: within 0.2 um of it
    blended = _face(y, sections_at(body.sections, np.array([x]))[0], LEVEL) - at_node
    if abs(x - 0.5 * (NODE + 45.29)) < 0.005:
        assert abs(blended - expected) > 1e-4


def test_a_range_off_the_body_or_a_single_point(turnout, check_rail):
    """Off the body: the body's own sections; one point: that exact section added."""
    body, _ = check_rail
    assert exact_sections_between(turnout, body, 10.0, 20.0) is body.sections
    single = exact_sections_between(turnout, body, 45.25, 45.25)
    assert len(single.x) == len(body.sections.x) + 1 and np.any(single.x == 45.25)
    again = exact_sections_between(turnout, body, NODE, NODE)  # a node it has: nothing new
    assert len(again.x) == len(body.sections.x)


def test_bad_step_is_a_clear_error(turnout, check_rail):
    """A step that is not positive is refused with one line naming it."""
    body, _ = check_rail
    with pytest.raises(ValueError, match="step must be > 0"):
        exact_sections_between(turnout, body, 45.2, 45.4, step=0.0)
