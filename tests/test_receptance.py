"""Receptance and modes of the co-running model (exudyn_turnout.corunning.modal), numpy only.

Reference values are not copied from anywhere: each test checks the receptance against
an independent statement of linear vibration theory about this model,
- at f -> 0 the receptance is the static compliance (K^-1)_ii, and for the two-layer
  rail 1/k_rt plus the point compliance of the sleeper on its two ballast springs;
- the extra layer sits in series (k_0 || c_0 between rail and m_0, paper Fig. 3);
- above the rail-on-pad resonance a mass dominates (|H| -> 1/(m_r w^2)), while in the
  three-layer model the dashpot c_0 (Eq 12) dominates up to many kHz (|H| -> 1/(c_0 w)).
Parameters: the packaged turnout, derived set (Eqs 1-19).
"""

import math

import numpy as np
import pytest

from exudyn_turnout.corunning.modal import (
    TrackMatrices,
    assemble_track_matrices,
    co_running_modes,
    co_running_parameters_at,
    co_running_receptance,
    modes,
    receptance_from_matrices,
)

#: (zone, x): zone 1 on the switch rail's plateau region, zone 2 on the crossing nose.
POSITIONS = [(1, 20.0), (2, 47.0)]
AXIS = {"vertical": "z", "lateral": "y"}


def _matrices(turnout, layers, x):
    params, _ = co_running_parameters_at(turnout, layers, x=x)
    return params.at(x), assemble_track_matrices(params, x)


@pytest.mark.parametrize("zone,x", POSITIONS)
@pytest.mark.parametrize("layers", [2, 3])
@pytest.mark.parametrize("direction", ["vertical", "lateral"])
def test_lowest_frequency_is_static_compliance(turnout, zone, x, layers, direction):
    """H(1 mHz) = (K^-1)_ii; |H(1 Hz)| (the paper's 'static' value) within 0.5 %.

    Tolerances: at 1 mHz the damping terms shift H by w c/k <= 2 pi 1e-3 * 0.01 s = 6e-5
    (imaginary part, first order; ballast c/k = 0.01 s is the largest ratio) and the real
    part by its square. At 1 Hz, w c_tg/k_tg = 0.063 changes |H| by about its square.
    """
    r = co_running_receptance(turnout, layers, "r2", direction, x=x, frequencies=[1e-3, 1.0])
    _, m = _matrices(turnout, layers, x)
    C = np.linalg.inv(m.K)[m.index(r.metadata["dof"]), m.index(r.metadata["dof"])]
    assert r.H[0].real == pytest.approx(C, rel=1e-7)
    assert abs(r.H[0].imag) < 1e-4 * C
    assert abs(r.H[1]) == pytest.approx(C, rel=5e-3)


@pytest.mark.parametrize("zone,x", POSITIONS)
def test_two_layer_static_compliance_by_hand(turnout, zone, x):
    """Rail pad in series with the sleeper on two ballast springs (lever arms from the zone).

    Vertical: 1/k_rt2,z + [1 a] S^-1 [1 a]^T, S the 2x2 heave/roll stiffness of the sleeper
    on k_tg1,z, k_tg2,z at distances a_1, a_2 from its centre, a = y_r2 - y_sleeper.
    Lateral: 1/k_rt2,y + 1/k_tg,y. Round-off only: rel 1e-9.
    """
    v, _ = _matrices(turnout, 2, x)
    z = turnout.zone(zone)
    a1, a2 = (y - z.sleeper_y for y in z.ballast_y)
    k1, k2, a = v["k_tg1_z"], v["k_tg2_z"], z.rail_y["r2"] - z.sleeper_y
    S = np.array([[k1 + k2, k1 * a1 + k2 * a2], [k1 * a1 + k2 * a2, k1 * a1**2 + k2 * a2**2]])
    sleeper = np.array([1.0, a]) @ np.linalg.solve(S, np.array([1.0, a]))
    f = [1e-4]
    H_z = co_running_receptance(turnout, 2, "r2", "vertical", x=x, frequencies=f).H[0]
    H_y = co_running_receptance(turnout, 2, "r2", "lateral", x=x, frequencies=f).H[0]
    assert H_z.real == pytest.approx(1 / v["k_rt2_z"] + sleeper, rel=1e-9)
    assert H_y.real == pytest.approx(1 / v["k_rt2_y"] + 1 / v["k_tg_y"], rel=1e-9)


@pytest.mark.parametrize("zone,x", POSITIONS)
@pytest.mark.parametrize("direction", ["vertical", "lateral"])
def test_three_layer_is_two_layer_plus_extra_layer_in_series(turnout, zone, x, direction):
    """Below 50 Hz, H_3 = H_2 + 1/(k_0 + i w c_0); below 5 Hz, Re(H_3 - H_2) = 1/k_0.

    Tolerances: the m_0 inertia is left out of the series formula; it is 2.5 kg on each
    active rail against 109-409 kg rails and k_0 >= 2.6e8 N/m, measured <= 0.14 % up to
    20 Hz and 1.2 % at 50 Hz (the crossing rail's lateral resonance is at 57 Hz), so 0.2 %
    and 2 %. Re 1/(k_0 + i w c_0) = (1/k_0)/(1 + (w c_0/k_0)^2): c_0/k_0 <= 2.7e-3 s gives
    <= 0.8 % at 5 Hz, so 1 %.
    """
    f = np.geomspace(0.5, 50.0, 40)
    w = 2 * math.pi * f
    H2 = co_running_receptance(turnout, 2, "r2", direction, x=x, frequencies=f).H
    H3 = co_running_receptance(turnout, 3, "r2", direction, x=x, frequencies=f).H
    v, _ = _matrices(turnout, 3, x)
    k0, c0 = v[f"k_02_{AXIS[direction]}"], v[f"c_02_{AXIS[direction]}"]
    error = np.abs(H3 - (H2 + 1 / (k0 + 1j * w * c0))) / np.abs(H3)
    assert np.all(error[f <= 20] < 2e-3)
    assert np.all(error < 2e-2)
    low = f <= 5
    np.testing.assert_allclose((H3[low] - H2[low]).real * k0, 1.0, rtol=1e-2)


def _slope(f, H):
    return np.polyfit(np.log(f), np.log(np.abs(H)), 1)[0]


@pytest.mark.parametrize("zone,x", POSITIONS)
def test_high_frequency_two_layer_mass_line(turnout, zone, x):
    """Two layers, 1-5 kHz: log-log slope -2 (within 0.06), and |H| m_r w^2 -> 1 at 5 kHz.

    Band and tolerance: above the pad resonance (<= 320 Hz here) |H| = 1/|k - w^2 m + i w c|;
    k_rt/(m_r w^2) is <= 0.1 at 1 kHz, which steepens the fitted slope by < 0.06. At
    5 kHz k_rt/(m_r w^2) < 4e-3 and c_rt/(m_r w) < 0.03, so |H| m_r w^2 within 1 %.
    """
    f = np.geomspace(1000.0, 5000.0, 60)
    r = co_running_receptance(turnout, 2, "r2", "vertical", x=x, frequencies=f)
    v, _ = _matrices(turnout, 2, x)
    assert _slope(f, r.H) == pytest.approx(-2.0, abs=0.06)
    assert abs(r.H[-1]) * v["m_r2"] * (2 * math.pi * f[-1]) ** 2 == pytest.approx(1.0, rel=1e-2)


@pytest.mark.parametrize("zone,x", POSITIONS)
def test_high_frequency_three_layer_dashpot_line(turnout, zone, x):
    """Three layers, 1-5 kHz: log-log slope -1 (within 0.05) and |H| c_0 w = 1 within 7 %.

    Band and tolerance: w c_0 exceeds k_0 above k_0/(2 pi c_0) <= 300 Hz; the rail
    behind the layer adds |1/(w^2 m_r)|, at most c_0/(w m_r) = 0.35 of the dashpot term at
    1 kHz, and m_0 adds w m_0 / c_0 <= 0.33 at 5 kHz (in quadrature), so |H| c_0 w stays
    within 1 +- 0.07 and the fitted slope within 0.05 of -1 (measured -1.014 and -1.013).
    """
    f = np.geomspace(1000.0, 5000.0, 60)
    r = co_running_receptance(turnout, 3, "r2", "vertical", x=x, frequencies=f)
    v, _ = _matrices(turnout, 3, x)
    assert _slope(f, r.H) == pytest.approx(-1.0, abs=0.05)
    np.testing.assert_allclose(np.abs(r.H) * v["c_02_z"] * 2 * math.pi * f, 1.0, rtol=0.07)


def test_modal_and_direct_solutions_agree_to_5000_hz(turnout):
    """Modal superposition of the first-order system = a linear solve per frequency.

    Both are exact for a diagonalisable system; the difference is round-off in the
    eigenvectors (condition number checked internally): rel 1e-8.
    """
    _, m = _matrices(turnout, 3, 47.0)
    f = np.geomspace(0.1, 5000.0, 300)
    for dof in ("z_m0_r2", "y_m0_r3", "z_r1"):
        H_modal = receptance_from_matrices(m, dof, f, method="modal")
        H_direct = receptance_from_matrices(m, dof, f, method="direct")
        np.testing.assert_allclose(H_modal, H_direct, rtol=1e-8)


def test_modes_of_proportionally_damped_system():
    """D = beta K: zeta_k = beta w_k / 2, and the damped eigenvalues give the same w_k, zeta_k.

    Two masses (1 kg, 2 kg) on springs 1e6, 2e6 N/m (ground-m1, m1-m2); beta = 1e-4 s.
    Undamped frequencies from the 2x2 characteristic equation by hand; rel 1e-10.
    """
    M = np.diag([1.0, 2.0])
    K = np.array([[3e6, -2e6], [-2e6, 2e6]])
    beta = 1e-4
    md = modes(TrackMatrices(M, K, beta * K, ("a", "b")))
    # det(K - w^2 M) = 0: 2 w^4 - (2*3e6 + 2e6) w^2 + (3e6*2e6 - 4e12) = 0
    w2 = np.roots([2.0, -8e6, 2e12])
    w = np.sqrt(np.sort(w2))
    np.testing.assert_allclose(md.frequency_hz, w / (2 * math.pi), rtol=1e-10)
    np.testing.assert_allclose(md.damping_ratio, beta * w / 2, rtol=1e-10)
    f_d, zeta_d = md.damped()
    np.testing.assert_allclose(f_d, w / (2 * math.pi), rtol=1e-10)
    np.testing.assert_allclose(zeta_d, beta * w / 2, rtol=1e-10)


def test_receptance_metadata_and_rail_pad_resonance(turnout):
    """The |H| peak above 100 Hz of the crossing rail (zone 2) is a damped eigenfrequency.

    Rail on pad: sqrt(k_rt2,z / m_r2) / 2 pi = sqrt(4.53e8 / 409) / 2 pi = 167 Hz (Table 2
    masses and stiffness); the peak lies within 10 % of the nearest damped eigenfrequency
    (a damped peak is not exactly at the eigenfrequency).
    """
    f = np.geomspace(100.0, 1000.0, 2000)
    r = co_running_receptance(turnout, 2, "r2", "vertical", zone=2, frequencies=f)
    assert (r.model, r.rail, r.direction, r.metadata["zone"]) == ("2-layer", "r2", "vertical", 2)
    assert r.x == pytest.approx(0.5 * (44.29 + 51.0))
    peak = f[np.argmax(np.abs(r.H))]
    assert peak == pytest.approx(167.0, rel=0.1)
    nearest = min(r.metadata["damped_frequencies_hz"], key=lambda fd: abs(fd - peak))
    assert peak == pytest.approx(nearest, rel=0.1)
    assert len(r.metadata["eigenfrequencies_hz"]) == 3 + 2 * 4


def test_co_running_modes_count_and_order(turnout):
    """Zone 1, three layers: 3 sleeper + 2 x 3 rails + 2 x 3 m_0 = 15 modes, ascending."""
    md = co_running_modes(turnout, 3, x=20.0)
    assert len(md.frequency_hz) == 15 and np.all(np.diff(md.frequency_hz) >= 0)
    assert set(md.dominant_dof()) <= set(md.dof)


def test_inactive_rail_is_an_error(turnout):
    with pytest.raises(
        ValueError, match=r"rail r3 is not active in zone 1 .*active rails: r1 r2 r4"
    ):
        co_running_receptance(turnout, 3, "r3", "vertical", zone=1)
    with pytest.raises(ValueError, match="exactly one of x or zone"):
        co_running_receptance(turnout, 3, "r2", "vertical")
    with pytest.raises(ValueError, match="direction"):
        co_running_receptance(turnout, 3, "r2", "up", x=20.0)
