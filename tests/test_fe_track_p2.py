"""P2 force after a dipped joint on the FE track, profile contact (issue 21).

The checks of the legacy vertical-only FE passage (``tests/test_fe_passage.py``:
the former ``passage/fe_track.py``, its own HHT integrator and height-table contact) ported
to the FE passage in use: the same wheelset and profile contact as the co-running passage
on the FE track (``simulate_passage(..., track="fe")`` with ``contact="profile"``, i.e.
:func:`~exudyn_turnout.passage.fe_track.wheelset.simulate_wheelset`), the dip given as a
track irregularity (``PassageSettings.irregularity``). Every run goes through
:func:`_fe_passage`.

Reference values and their sources:

- P2 force after a dip of total angle 2 alpha: Jenkins, Stephenson, Clayton, Morland &
  Lyon, "The effect of track and vehicle parameters on wheel/rail vertical dynamic
  forces", Railway Engineering Journal 3(1) 2-16, 1974 (:func:`jenkins_p2`); the
  dipped-joint shape z = -alpha (L/2 - |s - x|) is
  :func:`~exudyn_turnout.inputs.irregularity.dipped_joint` (same paper);
- its inputs: M_u = m_w / 2 of the Manchester benchmark wheelset (Iwnicki 1998,
  :func:`~exudyn_turnout.inputs.vehicle.load_vehicle`); K_t, M_t, C_t per wheel by Ritz
  reduction of the FE track on its static shape (:func:`equivalent_track`, the same
  reduction as the legacy test); P0 the passage's static wheel load (54546 N).

Numbers found (2 alpha = 9 mrad, 100 km/h, 1/10 of Table 1's ballast damping, h = 1e-4 s,
the dip's entrance eased in, see :func:`eased_dip`): P0 54.55 kN; the P2-band peak
81.86 kN; the force just before the vertex 48.52 kN (P0 less 6.0 kN of suspension
unloading on the 2.5 m of slope), so the vertex adds 33.34 kN; Jenkins' P2 99.45 kN, its
wheel/rail force P0 + M_u / (M_u + M_t) (P2 - P0) 87.78 kN, i.e. an increment of 33.24 kN
(K_t = 60.6 MN/m, M_t = 318 kg, C_t = 37.9 kN s/m per wheel, f2 = 35 Hz, damping term
0.11). The legacy passage (its test's docstring): FE 83.5 kN, 2-mass 87.8 kN, Jenkins
99.5 kN, P0 54.5 kN; measured the same way, its force before the vertex is 50.55 kN (1 m of
slope from a steady start) and its vertex increment 32.94 kN. So the two FE passages agree
on the response to the vertex within 1.2 %; their peaks differ by 1.6 kN because the
sprung mass unloads the wheel for longer here. With the ``joint:`` spec as it is, started
on the slope at rest, the peak is 78.7 kN (start transient, see :func:`eased_dip`).

The plain track: the turnout's file with its ``[layout]`` replaced by 8 m of two stock rails
on 2.5 m sleepers (0.6 m apart, one under the dip's vertex) where the through route runs
on plain track after the crossing (x = 52..60 m; the wheels on slots r1 and r4 only), plus
4 m undamped and 4 m absorbing plain track at each end (:data:`MESH`, as the legacy test):
the legacy test's ``plain_track_layout(length=8.0)`` moved by 56 m (``x_end`` stays the
turnout's 60 m: the route's plan, toe and crossing, is read from it). Checked once: built
at x = -4..4 m, its FE planes have the DOFs, mass matrices and lateral stiffness of
``plain_track_layout(length=8.0)`` exactly and its vertical stiffness within 2e-4 (the
sleepers' shear coefficient: the file's 0.833 instead of the default 5/6).
"""

import copy
import math
from dataclasses import replace

import numpy as np
import pytest
import scipy.sparse.linalg as sla
from scipy.signal import butter, filtfilt

from exudyn_turnout.fe.mesh import FEOptions
from exudyn_turnout.inputs.irregularity import Irregularity, irregularity_from_spec
from exudyn_turnout.inputs.vehicle import load_vehicle
from exudyn_turnout.passage.settings import PassageSettings

#: m, the dip's vertex: above a sleeper, on the plain track after the crossing
X_DIP = 56.0
#: 8 m of plain track + 4 m undamped + 4 m absorbing at each end (the legacy test's mesh)
MESH = FEOptions(extension=4.0, absorbing_length=4.0)
#: m: the dip's entrance (slope eased in over BLEND), then the straight V of Jenkins'
#: dipped joint from X_DIP - STRAIGHT on; the run starts PRE before the entrance
BLEND, STRAIGHT, PRE = 2.0, 0.5, 0.3
#: m, half the length of the equivalent dipped joint (its ends at X_DIP +- HALF)
HALF = STRAIGHT + BLEND / 2
SPEED = 100.0  # km/h


def _fe_passage(turnout, settings, fe_options):
    """The FE passage under test: wheelset, profile contact, FE track (the one line to
    re-point when the passage API moves)."""
    from exudyn_turnout.passage.run import simulate_passage

    return simulate_passage(
        turnout, settings, vehicle="wheelset", track="fe", fe_options=fe_options
    )


def _fe_options():
    """The FE passage options with :data:`MESH`."""
    from exudyn_turnout.passage.fe_track.options import FEPassageOptions

    return FEPassageOptions(mesh=MESH)


def plain_track_turnout(turnout, ballast_damping=1.0):
    """The turnout with its FE ``[layout]`` replaced by plain track at x = 52..60 m.

    Two stock rails at y = +-0.75 m on 2.5 m sleepers of their own track, a sleeper at
    X_DIP; slot r1 is the right rail, r4 the left (the through route's slots there).
    ``ballast_damping`` scales Table 1's d_b,z.
    """
    raw = copy.deepcopy(dict(turnout.raw))
    old = raw["layout"]
    x0, x1 = 52.0, 60.0
    span = [x0, x1]

    def rail(rail_id, y):
        seg = [{"type": "stock", "x": span, "track": "plain"}]
        return {"id": rail_id, "route": "through", "offset": y, "segments": seg}

    raw["layout"] = {
        **{k: old[k] for k in ("gauge", "nose_tip_width", "diverging", "bearers")},
        "x_start": x0,
        "x_end": x1,
        "sleeper_x0": X_DIP,
        "reference_rails": {"switch": "stock_right", "stock": "stock_left"},
        "fits": {k: {"rail": "stock_right", "x": span} for k in ("K_sw", "K_sh")},
        "tracks": {"plain": {"route": "through", "sleeper_length": 2.5}},
        "rails": [rail("stock_left", 0.75), rail("stock_right", -0.75)],
        "slots": {
            "through": {
                "r1": [{"rail": "stock_right", "x": span}],
                "r4": [{"rail": "stock_left", "x": span}],
            }
        },
    }
    ballast = replace(turnout.ballast, d_b_z=ballast_damping * turnout.ballast.d_b_z)
    return replace(turnout, raw=raw, ballast=ballast)


def eased_dip(two_alpha, step=0.005):
    """Jenkins' dipped joint of total angle ``two_alpha`` (rad), vertex at X_DIP, both rails,
    with its entrance eased in: the slope goes from 0 to -alpha over BLEND (raised cosine in
    the slope), so that the wheel runs steadily down the slope when it meets the vertex.

    Why: the passage starts from the static equilibrium at rest; started on the slope (the
    ``joint:`` spec as it is), the wheel lacks the slope's vertical velocity alpha v and
    rings in the P2 band into the vertex (measured: 78.7 kN instead of 81.9 kN). The legacy
    passage started in the steady state on the slope (its wheel descends at alpha v from
    the first step). From X_DIP - STRAIGHT on this is
    ``joint:x=X_DIP,angle=two_alpha,length=2 HALF`` exactly (see the first test).
    """
    alpha = 0.5 * two_alpha
    s_a = X_DIP - STRAIGHT - BLEND
    s = np.union1d(np.arange(s_a, X_DIP + HALF + 0.5 * step, step), [X_DIP, X_DIP + HALF])
    u = np.clip((s - s_a) / BLEND, 0.0, 1.0)
    eased = BLEND * (0.5 * u**2 + (np.cos(2 * np.pi * u) - 1) / (4 * np.pi**2))  # int of slope
    down = -alpha * (eased + np.maximum(s - s_a - BLEND, 0.0))
    z = np.where(s <= X_DIP, down, np.minimum(alpha * (s - X_DIP - HALF), 0.0))
    zero = np.zeros_like(s)
    return Irregularity(s, z, z, zero, zero, source=f"eased dipped joint 2alpha={two_alpha:g}")


def jenkins_p2(P0, two_alpha, v, M_u, M_t, K_t, C_t):
    """Jenkins et al. (1974) P2 force (N) after a dip of total angle 2 alpha (rad) at speed v (m/s).

    P2 = P0 + 2 alpha v sqrt(M_u / (M_u + M_t))
              (1 - C_t pi / (4 sqrt(K_t (M_u + M_t)))) sqrt(K_t M_u)

    M_u unsprung mass per wheel; M_t, K_t, C_t the equivalent track mass, stiffness and
    damping per wheel. Assumptions: a two-mass model (wheel, lumped track on K_t, C_t)
    with a contact stiff compared with K_t, so that after the dip vertex wheel and track
    move together; the vertex is a step 2 alpha v in the wheel's vertical velocity; linear,
    no loss of contact; light damping (the bracket is the first-order damping correction);
    sprung mass and suspension neglected. In that model the formula is the peak force in
    the track spring K_t; the wheel/rail force is M_u / (M_u + M_t) of its dynamic part.
    """
    damping = 1.0 - C_t * math.pi / (4.0 * math.sqrt(K_t * (M_u + M_t)))
    return P0 + two_alpha * v * math.sqrt(M_u / (M_u + M_t)) * damping * math.sqrt(K_t * M_u)


def equivalent_track(turnout, fe_options):
    """K_t, M_t, C_t per wheel: Ritz reduction of the FE track's vertical plane on its static
    shape under both wheels at X_DIP (u = K^-1 (b_r + b_l), K_t = u.K.u / (2 w0^2), etc.),
    with the passage's damping matrix (viscous + structural at ``loss_reference_hz``)."""
    from exudyn_turnout.passage.fe_track.planes import build_fe_planes

    planes = build_fe_planes(turnout, fe_options)
    m = planes.vertical
    b = m.point_vector("stock_right", X_DIP) + m.point_vector("stock_left", X_DIP)
    u = sla.spsolve(m.K.tocsc(), b)
    w0 = u @ m.point_vector("stock_right", X_DIP)
    return tuple(float(u @ (A @ u)) / (2 * w0**2) for A in (m.K, m.M, planes.D_vertical))


def p2_band_peak(columns, cutoff_hz=100.0):
    """Peak after the dip vertex of the right wheel's force low-pass filtered at
    ``cutoff_hz`` (4th-order Butterworth, zero phase): the P2 band, P1 (> 300 Hz) removed."""
    t, x, F = columns["t_s"], columns["x_m"], columns["Fz_right_N"]
    b, a = butter(4, cutoff_hz * 2 * (t[1] - t[0]))
    return float(filtfilt(b, a, F)[x > X_DIP - 0.05].max())


def force_before_vertex(columns):
    """Mean right-wheel force over the sleeper bay before the vertex (N): P0 less the
    suspension's unloading on the slope (Jenkins neglects the sprung mass)."""
    x, F = columns["x_m"], columns["Fz_right_N"]
    return float(F[(x >= X_DIP - 0.6) & (x < X_DIP)].mean())


@pytest.fixture(scope="module")
def light_damping(turnout):
    """The plain track with 1/10 of Table 1's ballast damping (P2 damping ratio ~0.07, as
    the legacy test: with Table 1's d_b,z Jenkins' damping factor turns negative) and the
    FE options; a cache of runs keyed by (2 alpha, time step, FE options)."""
    return plain_track_turnout(turnout, 0.1), _fe_options(), {}


def run_dip(light_damping, two_alpha, h=1e-4, fe_options=None):
    """The passage over :func:`eased_dip` from PRE before its entrance to 0.8 m past the
    vertex (3.6 m, 0.13 s), cached."""
    plain, options, cache = light_damping
    options = fe_options or options
    key = (two_alpha, h, options)
    if key not in cache:
        settings = PassageSettings(
            speed_kmh=SPEED,
            x_start=X_DIP - STRAIGHT - BLEND - PRE,
            x_end=X_DIP + 0.8,
            time_step=h,
            irregularity=eased_dip(two_alpha),
        )
        cache[key] = _fe_passage(plain, settings, options)
    return cache[key]


def test_eased_dip_is_the_dipped_joint_near_the_vertex():
    """From X_DIP - STRAIGHT on, the eased dip is the package's dipped joint (the CLI's
    ``--irregularity joint:...``); the run starts on undisturbed track."""
    spec = irregularity_from_spec(f"joint:x={X_DIP:g},angle=0.009,length={2 * HALF:g}")
    s = np.linspace(X_DIP - STRAIGHT, X_DIP + HALF + 0.5, 301)
    assert eased_dip(9e-3).at_array(s) == pytest.approx(spec.at_array(s), abs=1e-9)
    entrance = eased_dip(9e-3).at_array(np.array([X_DIP - STRAIGHT - BLEND - PRE]))
    assert np.all(entrance == 0.0)


def test_p2_force_after_a_dip_against_jenkins(light_damping):
    """2 alpha = 9 mrad (the crossing's), 100 km/h.

    Tolerances, from the model differences. Jenkins' two-mass model lumps the track into
    one mass on one spring (the Ritz mass of the static shape is one choice; the beam on
    discrete supports has a frequency-dependent one: 20 % more M_t lowers the wheel/rail
    increment, proportional to (M_u / (M_u + M_t))^1.5, by 7 %), neglects the sprung mass
    (the suspension unloads the wheel by 6 kN on the slope before the vertex, 11 % of P0),
    and the 100 Hz low-pass (3 f2) keeps part of the faster track response next to P1.
    Hence, as for the legacy passage, the FE P2-band peak within 12 % of Jenkins'
    wheel/rail force and between 75 % and 100 % of Jenkins' P2 itself (found -6.7 % and
    82 %; legacy -4.9 % and 84 %: the larger gap here is the longer unloading, module
    docstring); and, the unloading taken out by superposition (the increment above the
    mean force over the sleeper bay before the vertex; that mean is uncertain by ~0.5 kN as
    the unloading still drifts), the vertex's increment within 10 % of Jenkins' wheel/rail
    increment M_u / (M_u + M_t) (P2 - P0) (found +0.3 %; the legacy passage -0.9 %).
    """
    plain, options, _ = light_damping
    veh, v, two_alpha = load_vehicle(), SPEED / 3.6, 9e-3
    M_u = veh.m_w / 2
    K_t, M_t, C_t = equivalent_track(plain, options)
    assert C_t * math.pi / (4 * math.sqrt(K_t * (M_u + M_t))) < 0.3  # light damping
    res = run_dip(light_damping, two_alpha)
    P0 = res.summary["static_wheel_load_N"]
    assert P0 == pytest.approx(veh.static_wheel_load, rel=1e-6)
    p2 = jenkins_p2(P0, two_alpha, v, M_u, M_t, K_t, C_t)
    contact_p2 = P0 + M_u / (M_u + M_t) * (p2 - P0)
    fe = p2_band_peak(res.columns)
    print(f"P0 {P0:.0f} N, FE {fe:.0f} N, 2-mass wheel/rail {contact_p2:.0f} N, Jenkins {p2:.0f} N")
    before = force_before_vertex(res.columns)
    print(f"before the vertex {before:.0f} N")
    assert fe == pytest.approx(contact_p2, rel=0.12)
    assert 0.75 * p2 < fe < p2
    assert 0.03 * P0 < P0 - before < 0.2 * P0  # the suspension's unloading on the slope
    assert fe - before == pytest.approx(contact_p2 - P0, rel=0.10)


def test_p2_increment_is_linear_in_dip_angle(light_damping):
    """Linear P2 theory: the dynamic increment above P0 is proportional to 2 alpha v.

    4.5 and 9 mrad, ratio 2 within 3 % (found 27315 / 13594 N = 2.009; the legacy passage
    2.024 for the same angles, its test allowed 5 % for 4 and 9 mrad). Not exactly 2: the
    Hertz spring is nonlinear and P1 leaks slightly into the band; the suspension's
    unloading before the vertex is linear in the angle too.
    """
    P0 = run_dip(light_damping, 9e-3).summary["static_wheel_load_N"]
    inc = [p2_band_peak(run_dip(light_damping, a).columns) - P0 for a in (4.5e-3, 9e-3)]
    print(f"increments {inc[0]:.0f} N, {inc[1]:.0f} N, ratio {inc[1] / inc[0]:.4f}")
    assert inc[1] / inc[0] == pytest.approx(2.0, rel=0.03)


@pytest.mark.slow
def test_p2_peak_converged_in_time_step(light_damping):
    """Halving the time step (1e-4 -> 5e-5 s) moves the P2-band peak after the 9 mrad dip
    by < 0.5 % (found 81861 -> 81853 N, 0.01 %) and the raw peak (P1 included) by < 2 %, the
    legacy test's bound for its raw peak (found 101.3 -> 101.8 kN, 0.5 %)."""
    a, b = (run_dip(light_damping, 9e-3, h) for h in (1e-4, 5e-5))
    assert p2_band_peak(a.columns) == pytest.approx(p2_band_peak(b.columns), rel=5e-3)
    raw = [r.columns["Fz_right_N"][r.columns["x_m"] > X_DIP - 0.05].max() for r in (a, b)]
    print(f"P2 band {p2_band_peak(a.columns):.0f} / {p2_band_peak(b.columns):.0f} N, raw {raw}")
    assert raw[0] == pytest.approx(raw[1], rel=0.02)


@pytest.mark.slow
def test_p2_peak_converged_in_mesh(light_damping):
    """Rail elements of 0.1 m instead of 0.2 m move the P2-band peak by < 1 % (found 81861
    -> 81868 N) and the raw peak by < 2 %, the legacy test's bound for its raw peak (found
    101.3 -> 101.1 kN)."""
    _, options, _ = light_damping
    fine = replace(options, mesh=replace(MESH, element_length=0.1))
    a, b = (run_dip(light_damping, 9e-3, fe_options=o) for o in (options, fine))
    assert p2_band_peak(a.columns) == pytest.approx(p2_band_peak(b.columns), rel=0.01)
    raw = [r.columns["Fz_right_N"][r.columns["x_m"] > X_DIP - 0.05].max() for r in (a, b)]
    print(f"P2 band {p2_band_peak(a.columns):.0f} / {p2_band_peak(b.columns):.0f} N, raw {raw}")
    assert raw[0] == pytest.approx(raw[1], rel=0.02)
