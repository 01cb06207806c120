"""FE elements (Timoshenko beam and bar of order p) and the closed forms they are checked with.

Reference values and their sources:
- rigid-body motions (w = const; w = x, psi = 1) store no strain energy (any beam element);
- a beam element's translational mass is rho A L (consistent mass);
- simply supported Timoshenko beam, mode n: frequency equation (5) of
  exudyn_turnout.fe.analytic (Timoshenko 1921; e.g. Han, Benaroya & Wei, JSV 225 (1999)
  935, simply supported case); its Euler-Bernoulli limit (n pi / L)^2 sqrt(EI / rhoA) / 2pi;
- UIC60 (stock rail of Table 1) on a 0.6 m span: Euler-Bernoulli 1408.6 Hz, Timoshenko
  with kappa = 0.4, G = E / 2.6: 1058.9 Hz (SPEC: "Euler-Bernoulli puts the pinned-pinned
  resonance ~35% too high": 1408.6 / 1058.9 = 1.33);
- the infinite beam's static stiffness in the Euler-Bernoulli limit is Eq 2 of the paper.
"""

import math

import numpy as np
import pytest
import scipy.linalg as la

from exudyn_turnout.corunning import equations as eq
from exudyn_turnout.fe import analytic as an
from exudyn_turnout.fe import timoshenko as tim
from exudyn_turnout.fe.model import rail_section


@pytest.fixture(scope="module")
def stock(turnout):
    return {
        k: float(np.ravel(v)[0])
        for k, v in rail_section(turnout, "stock", np.array([0.0]), "vertical").items()
    }


@pytest.mark.parametrize("p", [1, 2, 4, 6])
def test_lagrange_partition_of_unity(p):
    N, dN = tim.lagrange_shape_functions(p, np.linspace(0, 1, 7))
    assert np.allclose(N.sum(axis=1), 1.0) and np.allclose(dN.sum(axis=1), 0.0)
    nodes, _ = tim.lagrange_shape_functions(p, np.linspace(0, 1, p + 1))
    assert np.allclose(nodes, np.eye(p + 1))


@pytest.mark.parametrize("p", [2, 4])
def test_beam_rigid_body_motions_store_no_energy(p, stock):
    L = np.array([0.3])
    K = tim.beam_stiffness(p, L, stock["EI"], stock["kGA"])[0]
    x = np.linspace(0, 0.3, p + 1)
    translation = np.ravel(np.column_stack([np.ones(p + 1), np.zeros(p + 1)]))
    rotation = np.ravel(np.column_stack([x, np.ones(p + 1)]))  # w = x, psi = w' = 1
    scale = np.abs(K).max()
    assert np.abs(K @ translation).max() < 1e-9 * scale
    assert np.abs(K @ rotation).max() < 1e-9 * scale


def test_translational_mass_is_rho_a_l(stock):
    M = tim.beam_mass(4, np.array([0.3]), stock["rhoA"], stock["rhoI"])[0]
    w = np.ravel(np.column_stack([np.ones(5), np.zeros(5)]))
    assert w @ M @ w == pytest.approx(stock["rhoA"] * 0.3, rel=1e-12)


def test_bar_matrices():
    K = tim.bar_stiffness(3, np.array([2.0]), 5.0)[0]
    M = tim.bar_mass(3, np.array([2.0]), 7.0)[0]
    assert np.allclose(K @ np.ones(4), 0.0) and np.ones(4) @ M @ np.ones(4) == pytest.approx(14.0)


def _simply_supported(p, n_el, span, s):
    L = np.full(n_el, span / n_el)
    K = tim.beam_stiffness(p, L, s["EI"], s["kGA"])
    M = tim.beam_mass(p, L, s["rhoA"], s["rhoI"])
    n = 2 * (p * n_el + 1)
    KK, MM = np.zeros((n, n)), np.zeros((n, n))
    for e in range(n_el):
        d = np.arange(2 * p * e, 2 * p * e + 2 * (p + 1))
        KK[np.ix_(d, d)] += K[e]
        MM[np.ix_(d, d)] += M[e]
    free = [i for i in range(n) if i not in (0, n - 2)]  # w = 0 at both ends, psi free
    return np.sqrt(la.eigh(KK[np.ix_(free, free)], MM[np.ix_(free, free)], eigvals_only=True)) / (
        2 * math.pi
    )


def test_pinned_pinned_modes_of_two_quartic_elements(stock):
    """Two quartic elements per span: modes 1, 2 within 1e-4 of the closed form."""
    f = _simply_supported(4, 2, 0.6, stock)
    for n in (1, 2):
        exact = an.simply_supported_timoshenko_frequency(
            0.6, stock["EI"], stock["kGA"], stock["rhoA"], stock["rhoI"], n
        )
        assert f[n - 1] == pytest.approx(exact, rel=1e-4)


def test_pinned_pinned_closed_form_values(stock):
    f_t = an.simply_supported_timoshenko_frequency(
        0.6, stock["EI"], stock["kGA"], stock["rhoA"], stock["rhoI"]
    )
    f_eb = an.simply_supported_euler_frequency(0.6, stock["EI"], stock["rhoA"])
    assert f_eb == pytest.approx(1408.6, abs=0.1) and f_t == pytest.approx(1058.9, abs=0.1)
    limit = an.simply_supported_timoshenko_frequency(
        0.6, stock["EI"], stock["kGA"] * 1e8, stock["rhoA"], 1e-12
    )
    assert limit == pytest.approx(f_eb, rel=1e-6)


def test_infinite_beam_static_limit_is_eq2(turnout, stock):
    s = an.two_layer_support(0.0, 120e6, 25e3, 164.5, 25e6, 200e3, 0.6)
    H = an.infinite_timoshenko_receptance(
        0.0, stock["EI"], stock["kGA"] * 1e8, stock["rhoA"], stock["rhoI"], s
    )
    assert 1 / abs(H) == pytest.approx(
        eq.static_track_stiffness(stock["EI"], float(s.real)), rel=1e-6
    )
