"""Rail torsion in the lateral FE model, its closed form, and the rail-head contact operator.

Reference values and their sources:
- the closed form of an infinite rail in coupled lateral bending and torsion
  (exudyn_turnout.fe.analytic, derived in its docstring) reduces to the Timoshenko
  closed form of the same module when nothing couples (shear centre at the foot, centroid
  at the shear centre, load at the shear centre): identical to round-off;
- a string on an elastic foundation (St Venant torsion GJ on a roll foundation k, no
  warping) under a point torque: phi(0) / T = 1 / (2 sqrt(GJ k)) (e.g. Hetenyi, *Beams on
  Elastic Foundation*, 1946, the tensioned-string analogue; GJ phi'' - k phi = -T delta);
- the warping/St Venant stiffness ratio (E C_w / G J_t) k^2 of the free torsional wave:
  0.55 at 500 Hz and 2.2 at 1 kHz with the 60E1 data (arithmetic of the torsion
  module's formula, stated in its docstring);
- the package FE (the turnout assembly, one rail, sleepers 0.1 m apart at the same support
  per unit length, rigid sleepers) against the closed form on the smeared support:
  criterion 0.1 dB at 20-2000 Hz (measured 0.004 dB, validation/fe_lateral_torsion.md;
  0.1 m supports put the pinned-pinned frequency above 19 kHz);
- with all eccentricities zero the torsion model's lateral receptance at the shear centre
  is the planar model's (roll decouples exactly);
- the condensation stays exact with torsion DOFs: equal to the full sparse solve;
- reciprocity of the rail-head operator: u_head . F = f_vertical . q_vertical +
  f_lateral . q_lateral (virtual work), and a rigid roll phi moves a point at (y, z) by
  (-z phi, y phi) (kinematics T1 of exudyn_turnout.fe.torsion).
"""

import dataclasses

import numpy as np
import pytest
import scipy.sparse.linalg as sla

from exudyn_turnout.fe import analytic as an
from exudyn_turnout.fe.continuous import lateral_torsion_closed_form, refined_supports
from exudyn_turnout.fe.frf import fe_receptance, load_height, sweep_vectors
from exudyn_turnout.fe.layout import plain_track_layout, single_rail_layout
from exudyn_turnout.fe.mesh import FEOptions, build_mesh
from exudyn_turnout.fe.model import assemble, rail_section
from exudyn_turnout.fe.rail_head import element_at, rail_head_point
from exudyn_turnout.fe.torsion import UIC60_SECTION, RailTorsionSection, warping_ratio

#: short plain-track model (as tests/test_fe_passage.py): ends 4 m + 4 m absorbing.
SHORT = FEOptions(extension=4.0, absorbing_length=4.0)


def _lateral_section(turnout):
    return {
        k: float(np.ravel(v)[0])
        for k, v in rail_section(turnout, "stock", np.array([0.0]), "lateral").items()
    }


@pytest.fixture(scope="module")
def plain_models(turnout):
    mesh = build_mesh(turnout, plain_track_layout(length=4.0), SHORT, points={"right": [0.3]})
    return (
        assemble(turnout, mesh, "vertical"),
        assemble(turnout, mesh, "lateral", torsion=UIC60_SECTION),
    )


def test_closed_form_uncoupled_limit_is_the_timoshenko_closed_form(turnout):
    s = _lateral_section(turnout)
    w = 2 * np.pi * np.array([1.0, 200.0, 900.0, 1900.0])
    support = an.two_layer_support(w, 25e6, 10e3, 329.0, 25e6, 250e3, 0.6)
    coupled = an.infinite_rail_lateral_torsion_receptance(
        w,
        s["EI"],
        s["kGA"],
        s["rhoA"],
        s["rhoI"],
        1.7e5,
        0.0,
        0.0,
        0.28,
        0.0,
        support,
        0.0,
        3.7e5 * (1 + 0.01j),
        0.0,
    )
    planar = an.infinite_timoshenko_receptance(w, s["EI"], s["kGA"], s["rhoA"], s["rhoI"], support)
    assert np.abs(coupled / planar - 1).max() < 1e-9


def test_string_on_elastic_foundation_under_a_torque():
    GJ, k = 1.66e5, 3.75e5
    phi = an.infinite_point_response(
        np.array([[GJ + 0j]]), np.zeros((1, 1)), np.array([[k * (1 + 1e-9j)]]), np.array([1.0])
    )[0]
    assert phi == pytest.approx(1 / (2 * np.sqrt(GJ * k)), rel=1e-6)


def test_warping_matters_above_500_hz(turnout):
    rail = turnout.rail_types["stock"]
    G = rail.youngs_modulus / (2 * (1 + rail.poisson))
    ratio = warping_ratio(
        UIC60_SECTION, [500.0, 1000.0], rail.youngs_modulus, G, rail.density, 7.67e-3
    )
    assert ratio == pytest.approx([0.55, 2.2], rel=0.03)


def test_warping_penalty_reaches_the_vlasov_limit(turnout):
    f = np.geomspace(20.0, 2000.0, 12)
    z = UIC60_SECTION.gauge_corner_height
    base = lateral_torsion_closed_form(turnout, UIC60_SECTION, f, z, eta=0.01)
    stiff = dataclasses.replace(UIC60_SECTION, warping_penalty=1e4)
    tenfold = lateral_torsion_closed_form(turnout, stiff, f, z, eta=0.01)
    assert np.abs(20 * np.log10(np.abs(tenfold / base))).max() < 0.01


def test_package_fe_matches_the_closed_form_on_refined_supports(turnout):
    """Within 0.1 dB, 20-2000 Hz, at the shear centre and at the gauge corner."""
    f = np.array([20.0, 150.0, 500.0, 1000.0, 2000.0])
    refined = refined_supports(turnout, 0.1)
    mesh = build_mesh(refined, single_rail_layout(), FEOptions(), points={"rail": [0.0]})
    model = assemble(refined, mesh, "lateral", torsion=UIC60_SECTION)
    heights = (0.0, UIC60_SECTION.gauge_corner_height)
    B = np.column_stack([model.head_vector("rail", 0.0, z) for z in heights])
    H = sweep_vectors(model, B, f)
    for j, z in enumerate(heights):
        closed = lateral_torsion_closed_form(turnout, UIC60_SECTION, f, z, eta=0.01)
        assert np.abs(20 * np.log10(np.abs(H[:, j] / closed))).max() < 0.1


def test_no_eccentricity_reproduces_the_planar_model(turnout):
    mesh = build_mesh(turnout, plain_track_layout(length=4.0), SHORT, points={"right": [0.3]})
    centred = dataclasses.replace(UIC60_SECTION, shear_centre_height=0.0, centroid_height=0.0)
    f = [1.0, 400.0, 1500.0]
    planar = assemble(turnout, mesh, "lateral")
    coupled = assemble(turnout, mesh, "lateral", torsion=centred)
    H_planar = sweep_vectors(planar, planar.point_vector("right", 0.3)[:, None], f)
    H_coupled = sweep_vectors(coupled, coupled.head_vector("right", 0.3, 0.0)[:, None], f)
    assert np.abs(H_coupled / H_planar - 1).max() < 1e-9
    assert coupled.n_dof > planar.n_dof == coupled.torsion_dof_offset


def test_vertical_plane_ignores_torsion(turnout):
    mesh = build_mesh(turnout, plain_track_layout(length=2.0), SHORT)
    a, b = assemble(turnout, mesh, "vertical"), assemble(turnout, mesh, "vertical", UIC60_SECTION)
    assert b.torsion is None and (a.K != b.K).nnz == 0 and (a.M != b.M).nnz == 0


def test_condensed_solve_exact_with_torsion(plain_models):
    lateral = plain_models[1]
    b = lateral.head_vector("right", 0.3, UIC60_SECTION.gauge_corner_height)
    for f in (1.0, 700.0, 1900.0):
        w = 2 * np.pi * f
        full = b @ sla.splu(lateral.dynamic_stiffness(w).tocsc()).solve(b.astype(complex))
        assert sweep_vectors(lateral, b[:, None], [f])[0, 0] == pytest.approx(full, rel=1e-9)


def test_rail_head_reciprocity_and_kinematics(plain_models):
    vertical, lateral = plain_models
    rng = np.random.default_rng(1)
    element, xi = element_at(vertical, "right", 0.437)
    assert 0.0 < xi < 1.0  # inside an element, not at a node
    point = rail_head_point(vertical, lateral, "right", 0.437, y=-0.012, z=0.1)
    q_v, q_l = rng.normal(size=vertical.n_dof), rng.normal(size=lateral.n_dof)
    F_y, F_z = 2.3e4, -7.1e4
    f_v, f_l = point.loads(F_y, F_z)
    u_y, u_z = point.displacement(q_v, q_l)
    assert u_y * F_y + u_z * F_z == pytest.approx(f_v @ q_v + f_l @ q_l, rel=1e-12)
    roll = np.zeros(lateral.n_dof)
    roll[lateral.roll_dof(np.arange(len(vertical.mesh.node_x)))] = 1.0
    roll[lateral.roll_dof(lateral.rail_elem_nodes.ravel())] = 1.0
    assert point.displacement(np.zeros(vertical.n_dof), roll) == pytest.approx((-0.1, -0.012))


def test_rail_head_load_at_a_node_is_the_head_vector(plain_models):
    vertical, lateral = plain_models
    z = UIC60_SECTION.gauge_corner_height
    _, f_l = rail_head_point(vertical, lateral, "right", 0.3, z=z).loads(1.0, 0.0)
    assert np.allclose(f_l, lateral.head_vector("right", 0.3, z), atol=1e-12)


def test_bad_section_and_height(turnout):
    with pytest.raises(ValueError, match="J_t must be > 0"):
        RailTorsionSection(J_t=-1.0)
    with pytest.raises(ValueError, match="height must be 'head'"):
        load_height(UIC60_SECTION, "top")
    with pytest.raises(ValueError, match="within the rail"):
        fe_receptance(
            turnout, "right", "lateral", 0.3, [1.0], layout=plain_track_layout(), height=0.5
        )


def test_two_flange_formulas_for_a_symmetric_i_section():
    """Equal flanges: shear centre midway, C_w = I_y h^2 / 4 with I_y = 2 I_f (Timoshenko &
    Gere 1961, doubly symmetric I-beam)."""
    from exudyn_turnout.fe.torsion import two_flange_shear_centre, two_flange_warping_constant

    assert two_flange_shear_centre(0.14, 2e-6, 2e-6) == pytest.approx(0.07)
    assert two_flange_warping_constant(0.14, 2e-6, 2e-6) == pytest.approx(4e-6 * 0.14**2 / 4)
