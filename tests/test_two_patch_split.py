"""Normal-force split between wing rail and nose: passage tables vs the exact 3-D solution.

At one wheel position in the UK crossing's wing rail -> nose transfer (slices
``uk_crossing.slcs``, S1002 wheel, CONTACT's lateral convention, Y = 0, no yaw), the
static wheel load of the packaged vehicle: the exact half-space solution
(``exact_normal.solve_normal``) on the 3-D gap spanning both rails, on a grid coarser than
the page's, is the reference; the passage's contact table and kernel
(``validation/two_patch_split.py``, which builds both from library functions) must give
the same split within the contact issue's 10 % and carry the load with the two patches.
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest

from exudyn_turnout.inputs.vehicle_model import load_vehicle_model

SCRIPT = Path(__file__).resolve().parents[1] / "validation" / "two_patch_split.py"

#: m, the rigid transfer at Y = 0: where the rigid S1002 wheel touches nose and wing rail
#: at once on the 3-D surfaces (validation/two_patch_split.md: u = 0.2519 m); the nose
#: carries about half the load here
U_TRANSFER = 0.252
#: m, the reference's elements: twice the page's (0.5 x 0.25 mm).  Nose share at this u:
#: 0.498 here, 0.494 on the page's grid, and halving that moved it by 0.03 percentage
#: points (validation/two_patch_split.md)
COARSE = (1e-3, 5e-4)


@pytest.fixture(scope="module")
def split():
    spec = importlib.util.spec_from_file_location("two_patch_split", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclasses look their module up there
    spec.loader.exec_module(module)
    yield module
    sys.modules.pop(spec.name, None)


@pytest.fixture(scope="module")
def solved(split, tmp_path_factory):
    load = float(load_vehicle_model().static_wheel_load)
    packed = split.crossing_table(cache_dir=tmp_path_factory.mktemp("tables"))
    reference, solution = split.reference_split(U_TRANSFER, 0.0, load, *COARSE)
    tables = split.table_split(packed, U_TRANSFER, 0.0, load)
    return load, packed, reference, solution, tables


def test_reference_has_two_separate_patches_that_carry_the_load(solved):
    load, _packed, reference, solution, _tables = solved
    # two contact regions, one on each rail (the flangeway between them is ~ 0.05 m wide)
    assert reference.regions == 2
    assert reference.nose > 0.1 * load and reference.wing > 0.1 * load
    # equilibrium: the two patches' forces are the prescribed total
    assert reference.nose + reference.wing == pytest.approx(load, rel=1e-9)
    p = solution.pressure
    assert p.sum() * solution.dx * solution.dy == pytest.approx(load, rel=1e-9)
    # the grid grew until the contact does not touch its edges
    assert not (p[0].any() or p[-1].any() or p[:, 0].any() or p[:, -1].any())


def test_tables_split_the_load_within_ten_percent_of_the_reference(solved):
    _load, _packed, reference, _solution, tables = solved
    r, s = reference.share, tables.share
    # the contact issue's criterion, per patch: |share_tables - share_ref| <= 10 % of the
    # reference's share (measured at this u: tables 0.470 against 0.498 here, -5.6 % of
    # the nose's share, +5.5 % of the wing's; on the slice positions alone, before the
    # transfer nodes, 0.469, -5.7 / +5.6 %)
    assert abs(s - r) <= 0.1 * r
    assert abs((1.0 - s) - (1.0 - r)) <= 0.1 * (1.0 - r)
    # where the patches act: the tables' force centres (the per-node KP force centre on the
    # 2-D section) within 0.5 mm of the exact pressure's on the nose, 1 mm on the wing rail
    # (measured: 0.01 and 0.25 mm; 0.01 and 0.47 mm on the slice positions alone)
    assert tables.y_nose == pytest.approx(reference.y_nose, abs=5e-4)
    assert tables.y_wing == pytest.approx(reference.y_wing, abs=1e-3)


def test_tables_two_patches_are_the_kernels_vertical_force(split, solved):
    load, packed, _reference, _solution, tables = solved
    # vertical equilibrium: the kernel's generalised vertical force on the wheelset at the
    # solved height is the load, and the nose's and the wing's rows add up to it
    q = np.array([0.0, tables.height, 0.0, 0.0, 0.0, 0.0, 0.0])
    forces = np.zeros(q.size)
    details = np.zeros((packed.n_bodies * packed.n_candidates, len(split.DETAIL_FIELDS)))
    constants = np.array([0.0, split.NOMINAL_RADIUS, 0.3, 8.0e10, 0.0, 0.0])
    split.contact_forces(
        U_TRANSFER, q, np.zeros_like(q), np.zeros(4), packed.values, packed.blendable,
        packed.x, packed.layout, packed.bounds, constants, forces, details,
    )  # fmt: skip
    assert forces[1] == pytest.approx(load, rel=1e-5)
    assert tables.nose + tables.wing == pytest.approx(forces[1], rel=1e-9)
    assert tables.nose > 0.1 * load and tables.wing > 0.1 * load


def test_nose_share_late_in_the_transfer_within_0_05(split, solved):
    # late in the transfer, where the tables on the slice positions alone (one 19.7 mm
    # cell from 0.2484 to 0.2680 m) met the nose late: with the transfer nodes
    # (section_nodes.transfer_nodes) the nose share is within the page's 0.05 of the
    # reference (measured on this coarse grid: 0.836 against 0.878; on the slice
    # positions alone 0.805, 0.073 off; the page: 0.072 off before, within 0.05 at 20 / 20
    # points after)
    load, packed, *_ = solved
    u = 0.2554
    reference, _solution = split.reference_split(u, 0.0, load, *COARSE)
    tables = split.table_split(packed, u, 0.0, load)
    assert 0.5 < reference.share < 1.0
    assert abs(tables.share - reference.share) <= 0.05
