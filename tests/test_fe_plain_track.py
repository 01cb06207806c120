"""Discretely supported plain track (two stock rails on 2.5 m sleepers, Table 1).

Reference values and their sources:
- pinned-pinned resonance: the mode of the periodically supported rail with a node at
  every support has the frequency of a simply supported Timoshenko beam of one span
  (Thompson, Railway Noise and Vibration, 2009, sec. 3.5; closed form: frequency
  equation (5) of exudyn_turnout.fe.analytic): 1058.9 Hz vertical, 543.9 Hz lateral for
  UIC60 on 0.6 m; the peak of the mid-span receptance must lie within 3% of it and move
  down when the spacing grows (0.55 m -> 1212.8 Hz, 0.65 m -> 931.8 Hz, same formula);
- Eq 2: K_st = 6.3694e7 N/m (continuous support, Euler-Bernoulli); the discrete FE is
  lower by the Timoshenko shear deflection (4.3%, test_fe_continuous.py) and the
  discrete, flexible sleepers (~3%): between 5% and 10% lower;
- mesh convergence (criterion: <= 0.5 dB): halving the element lengths changes the
  receptance by < 0.5 dB below 2 kHz; reflections (same criterion): doubling the
  plain-track extension before the absorbing ends changes it by < 0.5 dB;
- the condensed solve is exact: equal to the direct solve of the full system.
"""

import dataclasses

import numpy as np
import pytest

from exudyn_turnout.corunning.parameters import reference_support
from exudyn_turnout.fe.analytic import simply_supported_timoshenko_frequency
from exudyn_turnout.fe.frf import point_receptances, sweep, sweep_points
from exudyn_turnout.fe.layout import plain_track_layout
from exudyn_turnout.fe.mesh import FEOptions, build_mesh
from exudyn_turnout.fe.model import assemble, rail_section
from exudyn_turnout.fe.solver import condense, default_keep, solve_full

F = np.geomspace(20.0, 2000.0, 40)
DEFAULT_OPTIONS = FEOptions()


def _model(turnout, direction, options=DEFAULT_OPTIONS, spacing=None, points=(0.3,)):
    if spacing is not None:
        turnout = dataclasses.replace(
            turnout, sleeper=dataclasses.replace(turnout.sleeper, spacing=spacing)
        )
    mesh = build_mesh(turnout, plain_track_layout(), options, points={"right": list(points)})
    return assemble(turnout, mesh, direction)


def _f_pp(turnout, direction, span):
    s = {
        k: float(np.ravel(v)[0])
        for k, v in rail_section(turnout, "stock", np.array([0.0]), direction).items()
    }
    return simply_supported_timoshenko_frequency(span, s["EI"], s["kGA"], s["rhoA"], s["rhoI"])


def _peak(turnout, direction, spacing):
    model = _model(turnout, direction, spacing=spacing, points=(spacing / 2,))
    f_pp = _f_pp(turnout, direction, spacing)
    f = np.geomspace(0.8 * f_pp, 1.25 * f_pp, 120)
    H = sweep(model, "right", spacing / 2, f)
    return f[np.argmax(np.abs(H))], f_pp


@pytest.mark.parametrize("direction", ["vertical", "lateral"])
def test_pinned_pinned_peak_at_the_simply_supported_frequency(turnout, direction):
    f_peak, f_pp = _peak(turnout, direction, 0.6)
    assert f_pp == pytest.approx(1058.9 if direction == "vertical" else 543.9, abs=0.1)
    assert f_peak == pytest.approx(f_pp, rel=0.03)


def test_pinned_pinned_moves_down_when_spacing_grows(turnout):
    peaks = [_peak(turnout, "vertical", s) for s in (0.55, 0.65)]
    assert peaks[0][0] > 1058.9 * 1.03 and peaks[1][0] < 1058.9 / 1.03
    for f_peak, f_pp in peaks:
        assert f_peak == pytest.approx(f_pp, rel=0.03)


def test_static_stiffness_below_eq2(turnout):
    model = _model(turnout, "vertical")
    K = 1 / np.abs(point_receptances(model, [("right", 0.0), ("right", 0.3)], 1.0))
    K_eq2 = reference_support(turnout).K_st_z
    assert K_eq2 == pytest.approx(6.3694e7, rel=1e-4)
    assert 0.90 * K_eq2 < K[1] < K[0] < 0.95 * K_eq2  # above a sleeper stiffer than mid-span


def _level_change(turnout, direction, coarse, fine):
    points = [("right", 0.0), ("right", 0.3)]
    a = sweep_points(_model(turnout, direction, coarse), points, F)
    b = sweep_points(_model(turnout, direction, fine), points, F)
    return np.abs(20 * np.log10(np.abs(b / a))).max()


@pytest.mark.parametrize("direction", ["vertical", "lateral"])
def test_mesh_convergence_halving_elements(turnout, direction):
    """Default element lengths against halved ones (shorter model ends: the mesh is compared)."""
    coarse = FEOptions(extension=6.0, absorbing_length=12.0)
    fine = dataclasses.replace(
        coarse,
        element_length=coarse.element_length / 2,
        sleeper_element_length=coarse.sleeper_element_length / 2,
    )
    assert _level_change(turnout, direction, coarse, fine) < 0.5


@pytest.mark.parametrize("direction", ["vertical", "lateral"])
def test_no_reflections_when_extension_doubles(turnout, direction):
    default = FEOptions()
    assert (
        _level_change(
            turnout,
            direction,
            default,
            dataclasses.replace(default, extension=2 * default.extension),
        )
        < 0.5
    )


@pytest.mark.parametrize("direction", ["vertical", "lateral"])
def test_condensed_solve_equals_full_solve(turnout, direction):
    model = _model(turnout, direction)
    b = model.point_vector("right", 0.3)
    system = condense(model, np.union1d(default_keep(model), np.nonzero(b)[0]))
    bk = system.restrict(b).astype(complex)
    for f in (1.0, 700.0, 1900.0):
        w = 2 * np.pi * f
        assert bk @ system.solve(w, bk) == pytest.approx(b @ solve_full(model, w, b), rel=1e-9)


def test_point_must_be_a_node(turnout):
    model = _model(turnout, "vertical")
    with pytest.raises(ValueError, match="no node at x = 0.31"):
        model.point_vector("right", 0.31)
