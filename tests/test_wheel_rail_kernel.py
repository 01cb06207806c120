"""The compiled profile contact kernel (wheel_rail/kernel.py) against the package's reference
implementations and against closed forms.

References:
- table geometry: :func:`exudyn_turnout.wheel_rail.tables.lookup_values` (tested against
  CONTACT's reference outputs in test_wheel_rail_contact_references.py);
- creep: the kernel's law, the FASTSIM table (:func:`exudyn_turnout.wheel_rail.creep_table.
  table_creep_forces`), or Polach's (:func:`exudyn_turnout.wheel_rail.creep.
  polach_creep_forces`, Polach 1999), and their small-creepage limit, Kalker's linear
  theory F_x = -G a b C11 xi (Kalker 1967);
- normal force: the node's law N_ref (delta / DELTA_REF)^n (wheel_rail/nonhertz.py; Hertz
  F = C_H delta^1.5 with the tabulated C_H where Hertz fits, Johnson 1985, Eq 4.39-4.41);
- generalised forces: at v = 0 without damping the normal forces derive from the potential
  U = sum 2/5 C_H delta^2.5, so Q = -dU/dq (finite differences).
"""

from __future__ import annotations

import numpy as np
import pytest

from exudyn_turnout.wheel_rail import kernel, packed_tables
from exudyn_turnout.wheel_rail.creep import kalker_coefficients, polach_creep_forces
from exudyn_turnout.wheel_rail.data import s1002_wheel, standard_track, uic60_rail
from exudyn_turnout.wheel_rail.geometry import WheelsetSetup
from exudyn_turnout.wheel_rail.node_laws import (
    centre_point,
    node_centre,
    node_normal_forces,
    node_offset,
)
from exudyn_turnout.wheel_rail.sections import (
    CrossingDesign,
    SectionGrid,
    crossing_sections,
    lateral_grid,
)
from exudyn_turnout.wheel_rail.tables import (
    build_contact_table,
    lookup,
    lookup_values,
    normal_force,
)

SETUP = WheelsetSetup()
N_Q = 11  # y_w, z_w, phi, psi, beta, y_s, z_s, then left rail (7, 8), right rail (9, 10)
G = 8.1e10  # Pa, steel


@pytest.fixture(scope="module")
def wheel():
    return s1002_wheel(SETUP)


@pytest.fixture(scope="module")
def plain(wheel, tmp_path_factory):
    track = standard_track(SETUP, np.array([-10.0, 70.0]))
    table = build_contact_table(
        wheel, track, SETUP.taping_line, cache_dir=tmp_path_factory.mktemp("tables")
    )
    return packed_tables.pack_tables([table, table], [1, -1], [(7, 8), (9, 10)], [(-10, 70)] * 2)


@pytest.fixture(scope="module")
def crossing_table(wheel, tmp_path_factory):
    """Wing rail and nose as one surface over the nose tip: two-point contact, cells whose
    nodes hold different contact points (the nearest-node branch of the lookup)."""
    design = CrossingDesign(nose_tip=0.0)
    grid = lateral_grid(SETUP.taping_line - 0.11, SETUP.taping_line + 0.09, SETUP.grid_step)
    x = np.linspace(-0.2, 0.6, 17)
    rails = crossing_sections(design, uic60_rail(SETUP), x, grid, gauge=SETUP.gauge)
    z = np.fmax(rails["wing"].z, rails["nose"].z)
    sections = SectionGrid(x=x, y=grid, z=z, name="wing and nose")
    return build_contact_table(
        wheel, sections, SETUP.taping_line, cache_dir=tmp_path_factory.mktemp("tables")
    )


def _evaluate(packed, x, q, q_t=None, constants=(0.0, 0.46, 0.4, G, 0.0, 0.0)):
    forces = np.zeros(N_Q)
    details = np.zeros((packed.n_bodies * packed.n_candidates, len(kernel.DETAIL_FIELDS)))
    kernel.contact_forces(
        float(x),
        np.asarray(q, float),
        np.zeros(N_Q) if q_t is None else np.asarray(q_t, float),
        np.zeros(4),
        packed.values,
        packed.blendable,
        packed.x,
        packed.layout,
        packed.bounds,
        np.asarray(constants, float),
        forces,
        details,
    )
    return forces, details


def _column(name: str) -> int:
    return kernel.DETAIL_FIELDS.index(name)


def _slide(table, x: float, shift: float, c: int) -> float:
    """1 / (rho_w + rho_r) of slot c at (x, shift) as the kernel has it: per node from the
    table's lateral curvatures (both convex, else 0), bilinear between the cell's nodes."""
    names = list(table.fields)
    k_w = np.nan_to_num(table.values[..., c, names.index("curvature_wheel")])
    k_r = np.nan_to_num(table.values[..., c, names.index("curvature_rail")])
    convex = (table.values[..., c, 0] < 0.5) & (k_w > 0.0) & (k_r > 0.0)
    node = np.where(convex, k_w * k_r / np.where(convex, k_w + k_r, 1.0), 0.0)
    ix = min(max(int(np.searchsorted(table.x, x, side="right")) - 1, 0), len(table.x) - 2)
    tx = min(max((x - table.x[ix]) / (table.x[ix + 1] - table.x[ix]), 0.0), 1.0)
    position = (shift - table.shift[0]) / (table.shift[1] - table.shift[0])
    js = int(position)
    ts = position - js
    v00, v10, v01, v11 = node[ix, js], node[ix + 1, js], node[ix, js + 1], node[ix + 1, js + 1]
    return float(v00 + tx * (v10 - v00) + ts * ((v01 - v00) + tx * (v11 - v10 - v01 + v00)))


def test_kernel_geometry_equals_table_lookup(crossing_table):
    """In cells whose nodes hold the same contact points, positions, angle and gap of every
    candidate equal lookup_values (bilinear)."""
    packed = packed_tables.pack_tables([crossing_table], [-1], [(7, 8)], [(-1.0, 1.0)])
    rng = np.random.default_rng(3)
    fields = crossing_table.fields
    step = crossing_table.shift[1] - crossing_table.shift[0]
    checked = moved = exact = 0
    for _ in range(300):
        x, shift, lift = rng.uniform(-0.2, 0.6), rng.uniform(-0.011, 0.011), -1e-4
        ix = min(max(np.searchsorted(crossing_table.x, x, side="right") - 1, 0), 15)
        js = int((shift - crossing_table.shift[0]) / step)
        if not crossing_table.blendable[ix, js]:
            continue
        q = np.zeros(N_Q)
        q[0], q[1] = -shift, lift  # right wheel: shift = -(y_w - y_rail)
        _, details = _evaluate(packed, x, q)
        reference = lookup_values(crossing_table, [x], [shift], [lift])[0]
        for c in range(crossing_table.values.shape[2]):
            gap = reference[c, fields.index("gap")]
            if gap >= 0.5:
                continue
            checked += 1
            row = details[c]
            # positions: the deepest point moved to the node's force centre at the kernel's
            # penetration and angle, onto the rail surface along the normal (.nonhertz)
            centre = node_centre(
                reference[c, fields.index("patch_centre")],
                reference[c, fields.index("patch_centre_exponent")],
                row[_column("delta")],
            )
            offset = node_offset(
                reference[c, fields.index("patch_offset_c2")],
                reference[c, fields.index("patch_offset_c3")],
                centre,
            )
            gamma = row[_column("angle")]
            along, up = centre_point(centre, offset, np.sin(gamma), np.cos(gamma))
            assert row[_column("y_rail")] == pytest.approx(reference[c, 1] + along, abs=1e-11)
            assert row[_column("z_rail")] == pytest.approx(reference[c, 2] + up, abs=1e-11)
            assert row[_column("s_wheel")] == pytest.approx(reference[c, 3] + along, abs=1e-11)
            assert row[_column("radius")] == pytest.approx(reference[c, 5], abs=1e-12)
            # the kernel's angle is atan2 of the interpolated (sin, cos), the table's the
            # interpolated angle: equal to O(D^3) for a cell whose angle changes by D
            # (0.09 rad: ~1e-5 rad)
            assert row[_column("angle")] == pytest.approx(reference[c, 4], abs=2e-5)
            # the gap is carried to the lift with the normalised cos(angle); interpolated
            # (sin, cos) of nodes whose angles differ by D have length cos(D / 2), and
            # lookup_values uses them as they are: 1 - cos(D / 2) ~ D^2 / 8 < 1e-3 for the
            # < 0.09 rad a cell's angle changes here, times |lift| = 1e-4 m.  Where the rail
            # varies along x (the nose's ramp) the contact lies at the minimum along x of the
            # wheel's parabola (no yaw: lead**2 / (2 r / cos(gamma))) and profile term
            # (sin(gamma)^2 lead^4 / (8 r^2 (rho_w + rho_r))) plus the rail's gap,
            # x_offset ahead (along_x.lead_along_x, tests/test_wheel_rail_lead_table.py): the
            # table's gap there plus the parabola, never more than the table's gap at x
            lead = row[_column("x_offset")]
            radius_x = row[_column("radius")] / np.cos(gamma)
            assert -row[_column("delta")] <= gap + 1e-7
            ix_lead = min(max(np.searchsorted(crossing_table.x, x + lead, side="right") - 1, 0), 15)
            assert crossing_table.x[0] <= x + lead <= crossing_table.x[-1]  # on the rail
            if crossing_table.blendable[ix_lead, js]:  # at zero lift: the kernel carries
                # the minimum's gap to the lift with the angle at x
                # (x_offset is the patch's force centre, along_x.patch_along_x: the gap there
                # is no smaller than at the deepest point, equal where the patch is the
                # parabola's)
                there = lookup_values(crossing_table, [x + lead], [shift], [0.0])[0]
                at_centre = (
                    there[c, fields.index("gap")]
                    + lead**2 / (2.0 * radius_x)
                    + np.sin(gamma) ** 2
                    * _slide(crossing_table, x, shift, c)
                    / (8.0 * row[_column("radius")] ** 2)
                    * lead**4
                    + np.cos(gamma) * lift
                )
                assert -row[_column("delta")] <= at_centre + 1e-9
                exact += -row[_column("delta")] == pytest.approx(at_centre, abs=1e-9)
                moved += lead != 0.0
    assert checked > 50
    assert moved > 5  # the nose's ramp moves some contacts along x
    assert exact > 0.5 * checked  # most patches are the parabola's: the centre is the deepest


def test_lookup_normal_force_is_the_kernels(crossing_table):
    """tables.normal_force (the lookup path) and the kernel's normal force are one law
    (node_laws.node_normal_force): equal to round-off in cells whose nodes hold the same
    contact points (both bilinear), on the crossing, where semi-Hertzian nodes exist; and
    both put the contact at the same force centre.  The kernel's search along x is off
    (the tables' slope bound set to 0): its contact at x, as the lookup's."""
    table = crossing_table
    assert np.any(table.field("semi_hertzian") > 0.0)
    packed = packed_tables.pack_tables([table], [-1], [(7, 8)], [(-1.0, 1.0)])
    packed.bounds[:, 4] = 0.0
    rng = np.random.default_rng(7)
    step = table.shift[1] - table.shift[0]
    checked = semi = 0
    for _ in range(300):
        x, shift, lift = rng.uniform(-0.2, 0.6), rng.uniform(-0.011, 0.011), -2e-4
        ix = min(max(np.searchsorted(table.x, x, side="right") - 1, 0), len(table.x) - 2)
        js = int((shift - table.shift[0]) / step)
        if not table.blendable[ix, js]:
            continue
        q = np.zeros(N_Q)
        q[0], q[1] = -shift, lift  # right wheel: shift = -(y_w - y_rail)
        _, details = _evaluate(packed, x, q)
        found = lookup(table, [x], [shift], [lift])
        expected = normal_force(found)[0]
        raw = lookup_values(table, [x], [shift], [lift])[0]
        for c in range(table.values.shape[2]):
            if not found.valid[0, c]:
                continue
            row = details[c]
            # the same law of the same fields at the kernel's penetration: to round-off
            law = node_normal_forces(
                found.patch_force[0, c : c + 1],
                found.force_exponent[0, c : c + 1],
                np.array([row[_column("delta")]]),
            )[0]
            assert row[_column("normal")] == pytest.approx(law, rel=1e-12, abs=1e-9)
            # the lookup's own penetration differs by < 1e-7 m (its gap is carried to the
            # lift with the interpolated, unnormalised cos, see the test above): n 1e-7 /
            # delta < 2e-3 of the force at delta >= 0.1 mm
            assert row[_column("normal")] == pytest.approx(expected[c], rel=2e-3, abs=1e-6)
            # positions: the same, to the penetrations' and angles' differences (the lookup
            # takes cos of the interpolated angle, the kernel the normalised interpolated
            # (sin, cos)): < 0.3 um for centres of a few mm
            assert row[_column("y_rail")] == pytest.approx(found.y_rail[0, c], abs=3e-7)
            if expected[c] > 0.0:
                checked += 1
                semi += raw[c, table.fields.index("semi_hertzian")] > 0.0
    assert checked > 20 and semi > 0


def test_forces_are_continuous_where_contact_points_jump(crossing_table):
    """Over the nose tip the contact passes from wing rail to nose (cells whose nodes hold
    different points).  A nearest-node lookup makes the force jump at every cell edge there;
    the kernel's blend keeps it continuous inside a cell and nearly so across edges, and at
    a node it gives that node's own contacts."""
    packed = packed_tables.pack_tables([crossing_table], [-1], [(7, 8)], [(-1.0, 1.0)])
    xs, shifts = crossing_table.x, crossing_table.shift
    mixed = np.argwhere(~crossing_table.blendable[:-1, :-1])
    assert len(mixed) > 20
    q = np.zeros(N_Q)
    q[1] = -3e-4  # pressed 0.3 mm down: both rails near contact, ~100-300 kN

    def vertical(x, shift):
        q[0] = -shift
        return _evaluate(packed, x, q)[0][1]

    eps = 1e-9
    jumps, loads = [], []
    for ix, js in mixed[:: max(1, len(mixed) // 60)]:
        x_mid, s_mid = 0.5 * (xs[ix] + xs[ix + 1]), shifts[js] + 0.5 * (shifts[1] - shifts[0])
        for x, shift, dx, ds in (
            (xs[ix], s_mid, eps, 0.0),
            (xs[ix + 1], s_mid, eps, 0.0),
            (x_mid, shifts[js], 0.0, 1e-12),
            (x_mid, shifts[js + 1], 0.0, 1e-12),
        ):
            jumps.append(abs(vertical(x + dx, shift + ds) - vertical(x - dx, shift - ds)))
            loads.append(abs(vertical(x, shift)))
    # Edges between a blended and a bilinear cell differ by the convexity of F(delta) over
    # one 0.2 mm shift step: below 1 % of the force (a nearest-node lookup: up to 100 %)
    assert max(j / max(f, 1e4) for j, f in zip(jumps, loads)) < 0.01
    ix, js = mixed[0]
    q[0], q[1] = -shifts[js], 0.0
    _, details = _evaluate(packed, xs[ix], q)
    node = crossing_table.values[ix, js]
    for c in range(node.shape[0]):
        if node[c, 0] < 0.5:
            assert -details[c, _column("delta")] == pytest.approx(node[c, 0], abs=1e-12)


def test_plain_track_at_rest_lateral_force_is_n_tan_gamma(plain):
    """Issue 12 check: at rest on straight plain track each wheel's lateral force is
    N tan(contact angle) of its real contact point, below 2 kN, and the two cancel."""
    from scipy.optimize import brentq

    load = 54_546.0  # N per wheel: 44 482 kg x 9.81 / 8 (Manchester vehicle, Iwnicki 1998)
    q = np.zeros(N_Q)

    def excess(z):
        q[1] = z
        return _evaluate(plain, 5.0, q)[0][1] - 2.0 * load

    brentq(excess, -1e-3, 0.0, xtol=1e-14)
    forces, details = _evaluate(plain, 5.0, q)
    loaded = details[details[:, _column("normal")] > 0]
    assert len(loaded) == 2
    for row in loaded:
        angle = row[_column("angle")]
        assert abs(row[_column("Fy")]) == pytest.approx(row[_column("Fz")] * np.tan(angle), 1e-9)
        assert abs(row[_column("Fy")]) < 2e3
        assert row[_column("Fz")] == pytest.approx(load, rel=1e-6)
    assert forces[0] == pytest.approx(0.0, abs=1e-6)  # the two wheels' lateral forces cancel
    assert forces[7] == pytest.approx(-forces[9], rel=1e-12)


def test_normal_forces_derive_from_the_hertz_potential(plain):
    """At v = 0 the generalised forces on y, z and roll are -dU/dq of U = N delta / (n + 1)
    (the node's law N = k delta^n; Hertz: 2/5 C_H delta^2.5):
    checks the lateral lever arm, the roll lever arm and the sign conventions together."""

    def potential(q):
        _, details = _evaluate(plain, 5.0, q)
        total = 0.0
        for k in range(plain.n_bodies):
            for c in range(plain.n_candidates):
                row = details[k * plain.n_candidates + c]
                delta = row[_column("delta")]
                if delta > 0 and row[_column("normal")] > 0:
                    # the node's law N = k delta^n (Hertz: n = 1.5) has the potential
                    # N delta / (n + 1); n from the stiffness dN/d(delta) = n N / delta
                    n = row[_column("stiffness")] * delta / row[_column("normal")]
                    total += row[_column("normal")] * delta / (n + 1.0)
        return total

    # On the tread.  Towards the flange root (y ~ 5 mm) the contact angle changes by ~0.1
    # rad per 0.2 mm shift step and the lateral force from the node's angle departs from the
    # secant slope of the tabulated gap by up to ~17 % (kernel docstring): not a check of
    # the conventions there, so not tested there.
    for y in (0.0012, -0.0037):
        q = np.zeros(N_Q)
        q[0], q[1], q[2] = y, -8e-5, 2e-5  # penetrations of a static wheel load's order
        forces, _ = _evaluate(plain, 5.0, q)
        for i, step in ((1, 1e-9), (2, 1e-9), (0, 1e-8)):
            plus, minus = q.copy(), q.copy()
            plus[i] += step
            minus[i] -= step
            derivative = (potential(plus) - potential(minus)) / (2 * step)
            # Lateral: the table gives the contact angle at 0.2 mm steps of shift and
            # interpolates it, while the gap's slope is the secant over the step; they agree
            # to ~1 % where the angle changes fast with the shift
            tolerance = 0.02 if i == 0 else 1e-3
            assert forces[i] == pytest.approx(-derivative, rel=tolerance, abs=1.0), (y, i)


def test_polach_scalar_equals_the_vectorised_model():
    rng = np.random.default_rng(7)
    for _ in range(100):
        xi, eta = rng.normal(0, 3e-3, 2)
        spin = rng.normal(0, 1.0)
        a, b = rng.uniform(2e-3, 9e-3, 2)
        Q, mu = rng.uniform(1e3, 1.5e5), rng.uniform(0.1, 0.5)
        c = kalker_coefficients(np.array([a]), np.array([b]), 0.28)
        reference = polach_creep_forces(xi, eta, spin, a, b, Q, mu, G, 0.28)
        fx, fy = kernel.polach_scalar(xi, eta, spin, a, b, Q, mu, G, c.c11[0], c.c22[0], c.c23[0])
        assert fx == pytest.approx(float(reference.longitudinal), rel=1e-10, abs=1e-9)
        assert fy == pytest.approx(float(reference.lateral), rel=1e-10, abs=1e-9)


def test_small_longitudinal_creepage_gives_kalkers_linear_force(plain):
    """A spin perturbation rate that leaves xi = -1e-5 on both wheels gives, far below
    saturation, F_x = -G a b C11 xi (Kalker's linear theory).  Far below: mu = 100, for the
    wheels' spin on their coned treads (about -0.07 1/m) slips part of a patch at mu = 0.4
    and lowers F_x by 8.5 % there (the full theory's, not the linear one's)."""
    q = np.zeros(N_Q)
    q[1] = -2.5e-4  # 68 um into both rails (the wheel first touches 0.18 mm down)
    q_t = np.zeros(N_Q)
    v, r0 = 27.0, 0.46
    constants = (v, r0, 100.0, G, 0.0, 0.0)
    _, details = _evaluate(plain, 5.0, q, q_t, constants=constants)
    r = details[details[:, _column("normal")] > 0, _column("radius")].mean()
    # beta_t: xi = -1e-5 (r = 0.45991 m: beta_t = 0 would leave xi = 1 - r / r0 ~ 2e-4)
    q_t[4] = (1.0 + 1e-5) * v / r - v / r0
    _, details = _evaluate(plain, 5.0, q, q_t, constants=constants)
    loaded = details[details[:, _column("normal")] > 0]
    assert len(loaded) == 2
    for row in loaded:
        a, b = row[_column("a")], row[_column("b")]
        c11 = kalker_coefficients(np.array([a]), np.array([b]), 0.28).c11[0]
        xi = row[_column("xi")]
        r = row[_column("radius")]
        assert xi == pytest.approx(1.0 - (v / r0 + q_t[4]) * r / v, rel=1e-9)
        # 5e-3: the kernel's C11 is its table nodes' (bilinear between ellipses of other a / b)
        # and the creep table's linear limit; measured +0.33 % (the test had no loaded row
        # before 2026-12: the wheel 0.12 mm down did not touch)
        assert row[_column("Fx")] == pytest.approx(-G * a * b * c11 * xi, rel=5e-3)


def test_select_rebinds_coordinates_without_copying(plain):
    chosen = plain.select([1], [(7, 8)])
    assert chosen.n_bodies == 1 and chosen.layout[0, 6] == -1 and chosen.layout[0, 7] == 7
    assert chosen.values is plain.values


def test_a_diverged_state_gives_nan_forces_not_a_crash(plain):
    """NaN coordinates (a diverged solver step) must not index the tables out of range."""
    q = np.zeros(N_Q)
    q[0] = np.nan
    forces, _ = _evaluate(plain, 5.0, q)
    assert np.all(np.isnan(forces))
    forces, _ = _evaluate(plain, np.nan, np.zeros(N_Q))
    assert np.all(np.isnan(forces))


def test_normal_force_and_semi_axes_follow_the_node_law(crossing_table):
    """At a table node the kernel's normal force, stiffness and semi-axes are the node's
    law (wheel_rail/nonhertz.py), for Hertz and for semi-Hertzian nodes alike (the search
    along x off: the tables' slope bound set to 0, the contact at the node)."""
    from exudyn_turnout.wheel_rail.node_laws import DELTA_REF

    packed = packed_tables.pack_tables([crossing_table], [-1], [(7, 8)], [(-1.0, 1.0)])
    packed.bounds[:, 4] = 0.0
    fields = {name: k for k, name in enumerate(crossing_table.fields)}
    values = crossing_table.values
    kinds = set()
    for ix in range(0, len(crossing_table.x), 3):
        for js in range(0, len(crossing_table.shift), 7):
            q = np.zeros(N_Q)
            q[0], q[1] = -crossing_table.shift[js], -1e-4
            _, details = _evaluate(packed, crossing_table.x[ix], q)
            for c in range(values.shape[2]):
                node = values[ix, js, c]
                delta = -(node[fields["gap"]] + np.cos(node[fields["angle"]]) * -1e-4)
                if node[0] >= 0.5 or delta <= 0.0:
                    continue
                ratio = delta / DELTA_REF
                force = node[fields["patch_force"]] * ratio ** node[fields["patch_force_exponent"]]
                row = details[c]
                assert row[_column("normal")] == pytest.approx(force, rel=1e-9)
                stiffness = node[fields["patch_force_exponent"]] * force / delta
                assert row[_column("stiffness")] == pytest.approx(stiffness, rel=1e-9)
                a = node[fields["patch_a"]] * ratio ** node[fields["patch_a_exponent"]]
                b = node[fields["patch_b"]] * ratio ** node[fields["patch_b_exponent"]]
                assert row[_column("a")] == pytest.approx(a, rel=1e-9)
                assert row[_column("b")] == pytest.approx(b, rel=1e-9)
                assert row[_column("semi_hertzian")] == pytest.approx(node[fields["semi_hertzian"]])
                kinds.add(round(float(node[fields["semi_hertzian"]]), 6))
    # Hertz nodes, fully semi-Hertzian nodes and blended ones were all checked
    assert min(kinds) == 0.0 and max(kinds) == 1.0 and len(kinds) > 2


@pytest.mark.parametrize("creep_law", ["fastsim", "polach"])
def test_creep_forces_are_the_selected_law_at_the_rows_creepages(wheel, creep_law):
    """The flange contact of a yawed, sliding wheelset: every row's (F_x, F_t) is
    the selected law (the FASTSIM table, or Polach's) at the row's creepages, semi-axes and
    normal force (at a table node: a row blended from several nodes holds the nodes' mean
    creepages and axes but the sum of their forces); the two laws differ there (spin on
    the flange)."""
    from exudyn_turnout.wheel_rail.creep_table import creep_table, table_creep_forces

    track = standard_track(SETUP, np.array([-10.0, 70.0]))
    table = build_contact_table(wheel, track, SETUP.taping_line)
    packed = packed_tables.pack_tables(
        [table, table], [1, -1], [(7, 8), (9, 10)], [(-10, 70)] * 2, creep_law=creep_law
    )
    q = np.zeros(N_Q)
    # at a table node (x and shift), so that each row is one node's contact point
    x = float(table.x[len(table.x) // 2])
    shift = float(table.shift[np.argmin(np.abs(table.shift - 0.0065))])
    q[0], q[1], q[3] = shift, 7e-4, 4e-3  # on the left flange (~100 kN), yawed
    q_t = np.zeros(N_Q)
    q_t[0], q_t[4] = 0.05, 0.3
    mu, v = 0.35, 20.0
    _, details = _evaluate(packed, x, q, q_t, constants=(v, 0.46, mu, G, 0.0, 0.0))
    rows = details[details[:, _column("normal")] > 0]
    assert len(rows) >= 1 and np.max(np.abs(rows[:, _column("spin")])) > 0.5  # a flange
    args = [rows[:, _column(n)] for n in ("xi", "eta", "spin", "a", "b", "normal")]
    if creep_law == "fastsim":
        expected = table_creep_forces(creep_table(), *args, mu, G)
        other = polach_creep_forces(*args, mu, G, 0.28)
    else:
        expected = polach_creep_forces(*args, mu, G, 0.28)
        other = table_creep_forces(creep_table(), *args, mu, G)
    scale = mu * rows[:, _column("normal")]
    assert np.all(np.abs(rows[:, _column("Fx")] - expected.longitudinal) <= 1e-9 * scale)
    assert np.all(np.abs(rows[:, _column("Ft")] - expected.lateral) <= 1e-9 * scale)
    difference = np.hypot(
        expected.longitudinal - other.longitudinal, expected.lateral - other.lateral
    )
    assert difference.max() > 0.01 * mu * rows[:, _column("normal")].max()
