"""Issue 24 and 23 on the FE track: the Cholesky factor, the moving window, the steady start."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import scipy.sparse.linalg as sla

from exudyn_turnout.passage.fe_track.options import FEPassageOptions
from exudyn_turnout.passage.fe_track.planes import (
    CholeskyFactor,
    build_fe_planes,
    dof_positions,
    generalized_alpha,
    window_dofs,
)
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageSettings


@pytest.fixture(scope="module")
def planes(turnout):
    return build_fe_planes(turnout)


def test_cholesky_solves_as_superlu(planes):
    """CHOLMOD's solve of the vertical step matrix equals SuperLU's (the factor it replaced)
    to round-off (reference: scipy's splu with its own ordering, relative 1e-10)."""
    ga, h = generalized_alpha(0.8), 1e-4
    m = planes.vertical
    A = (m.M + ga.gamma_eff * h * planes.D_vertical + ga.beta_eff * h * h * m.K).tocsc()
    b = np.random.default_rng(1).standard_normal((m.n_dof, 2))
    x = CholeskyFactor(A).solve(b)
    reference = sla.splu(A).solve(b)
    assert np.max(np.abs(x - reference)) < 1e-10 * np.max(np.abs(reference))


def test_window_holds_the_dofs_in_range_and_absorbs_only_at_cuts(planes):
    x = dof_positions(planes.lateral)
    assert np.all(np.isfinite(x))
    mesh = planes.vertical.mesh
    dofs, eta = window_dofs(x, [(mesh.x_min, 20.0)], (mesh.x_min, mesh.x_max), 4.0, 0.5)
    inside = x[dofs]
    assert inside.min() >= mesh.x_min and inside.max() <= 20.0
    # no absorber at the model's own end, the full eta_max at the cut (quadratic ramp)
    assert np.all(eta[inside < 15.9] == 0.0)
    assert eta[np.argmax(inside)] == pytest.approx(0.5 * ((inside.max() - 16.0) / 4.0) ** 2)


@pytest.mark.slow
def test_window_gives_the_whole_models_forces(turnout):
    """A 20 m window (cut every 0.2 m, so several cuts in the run) gives the whole FE model's
    wheel forces over 0.4 m of the crossing (reference: the same run on the whole model;
    the window's own convergence table is validation/fe_window_convergence.md)."""
    settings = PassageSettings(x_start=45.0, x_end=45.4)
    runs = {}
    for name, length in (("whole", None), ("window", 20.0)):
        options = FEPassageOptions(window_length=length, window_shift=0.2)
        runs[name] = simulate_passage(
            turnout, settings, track="fe", fe_options=options, vehicle="wheelset"
        )
    assert "cuts" in runs["window"].summary["fe_window"]
    assert runs["whole"].summary["fe_window"] == "whole model"
    for key in ("Fz_right_N", "Fz_left_N", "Fy_right_N", "Fy_left_N"):
        a, b = runs["whole"].columns[key], runs["window"].columns[key]
        assert np.max(np.abs(a - b)) < 0.01 * np.max(np.abs(a)) + 1.0, key


@pytest.mark.slow
def test_full_vehicle_starts_in_steady_curving_on_the_diverging_route(turnout):
    """Issue 23: inside the 760 m curve at 80 km/h the FE full vehicle starts in steady
    curving (it started at rest at y = 0.14 mm and swung to 6.8 mm, issue 23): the leading
    wheelset flanges at y of several mm from t = 0 and does not swing."""
    settings = PassageSettings(route="diverging", speed_kmh=80.0, x_start=30.0, x_end=30.1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = simulate_passage(turnout, settings, "manchester", track="fe")
    assert result.summary["start"].startswith("steady curving at 80 km/h, R = 760 m")
    assert isinstance(result.summary["start_residual"], float)
    y = result.columns["y_ws1_m"]
    assert y[0] > 4e-3  # flanging (the co-running leading wheelset: 6.3 mm, issue 23)
    assert np.max(np.abs(y - y[0])) < 1e-4  # no swing
