"""The published parameter set equals the paper's Table 2 exactly.

Source of every value: Shih, Ambur & Dixon (2023), Vehicle System Dynamics 61(3),
Table 2 "Three-layer track properties for the present co-running track", typed here a
second time, independently of the turnout file, so that a transcription error in either
shows up. Cells: a number, "<coef> Dz" / "<coef> Dy" for coef * Delta_z / Delta_y, and
"a-b" for Table 2's ranges.
"""

import pytest

from exudyn_turnout.corunning.parameters import co_running_parameters

TABLE2 = """
k_01_z 369e6 | 369e6 | 369e6
c_01_z 315e3 | 315e3 | 315e3
k_02_z 369e6 Dz | 448e6-453e6 | 448e6
c_02_z 315e3 | 946e3 | 315e3
k_03_z 369e6 | 369e6 | 369e6
c_03_z 315e3 | 315e3 | 315e3
k_04_z 369e6 | 369e6 | 369e6
c_04_z 315e3 | 315e3 | 315e3
k_rt1_z 369e6 | 369e6 | 369e6
c_rt1_z 77e3 | 77e3 | 77e3
k_rt2_z 369e6 Dz | 448e6-453e6 | 448e6
c_rt2_z 77e3 Dz | 94e3 | 93e3
k_rt3_z 369e6 | 369e6 | 369e6
c_rt3_z 77e3 | 77e3 | 77e3
k_rt4_z 369e6 | 369e6 | 369e6
c_rt4_z 77e3 | 77e3 | 77e3
k_tg1_z 77e6 Dz | 93e6-134e6 | 93e6
c_tg1_z 77e4 Dz | 93e4-134e4 | 93e4
k_tg2_z 77e6 | 77e6 | 77e6
c_tg2_z 77e4 | 77e4 | 77e4
k_01_y 280e6 Dy | 280e6 Dy | 280e6 Dy
c_01_y 315e3 | 315e3 | 315e3
k_02_y 280e6 Dy | 265e6 | 280e6 Dy
c_02_y 315e3 | 946e3 | 315e3
k_03_y 280e6 Dy | 1075e6 | 280e6 Dy
c_03_y 315e3 | 315e3 | 315e3
k_04_y 280e6 Dy | 280e6 Dy | 280e6 Dy
c_04_y 315e3 | 315e3 | 315e3
k_rt1_y 56e6 Dy | 56e6 Dy | 56e6 Dy
c_rt1_y 22e3 Dy | 22e3 Dy | 22e3 Dy
k_rt2_y 56e6 Dy | 53e6 | 56e6 Dy
c_rt2_y 22e3 Dy | 21e3 | 22e3 Dy
k_rt3_y 215e6 | 215e6 | 215e6
c_rt3_y 45e3 | 45e3 | 45e3
k_rt4_y 56e6 Dy | 56e6 Dy | 56e6 Dy
c_rt4_y 22e3 Dy | 22e3 Dy | 22e3 Dy
k_tg_y 56e6 Dy | 86e6 | 56e6 Dy
c_tg_y 56e4 Dy | 86e4 | 56e4 Dy
m_0 2.5 | 2.5 | 2.5
m_t 500 | 881 | 500
m_r1 111 | 111 | 111
m_r2 111 | 409 | 111
m_r3 111 | 111 | 111
m_r4 111 | 111 | 111
J_t 265 | 1213 | 265
"""


def _cells():
    for line in TABLE2.strip().splitlines():
        name, rest = line.split(" ", 1)
        for zone, cell in enumerate(rest.split("|"), start=1):
            yield zone, name, cell.strip()


def _expected(cell):
    if "-" in cell:
        a, b = cell.split("-")
        return "ramp", float(a), float(b)
    if cell.endswith(("Dz", "Dy")):
        return {"Dz": "Delta_z", "Dy": "Delta_y"}[cell[-2:]], float(cell[:-2]), None
    return "const", float(cell), None


@pytest.mark.parametrize("zone,name,cell", list(_cells()))
def test_published_entry_equals_table2(turnout, zone, name, cell):
    entry = co_running_parameters(turnout, zone=zone, source="published").entries[name]
    kind, a, b = _expected(cell)
    assert (entry.kind, entry.a) == (kind, a)
    if b is not None:
        assert entry.b == b


def test_published_set_has_every_table2_entry_and_no_other(turnout):
    names = {name for _, name, _ in _cells()}
    for zone in (1, 2, 3):
        assert set(co_running_parameters(turnout, zone=zone, source="published").entries) == names


def test_two_layer_published_drops_extra_layer(turnout):
    entries = co_running_parameters(turnout, zone=1, layers=2, source="published").entries
    assert not [n for n in entries if n.startswith(("k_0", "c_0", "m_0"))]
    assert "k_rt1_z" in entries and "m_t" in entries


def test_ramp_is_linear_over_the_zone(turnout):
    """Table 2 zone 2 k_rt2,z "448e6 - 453e6", read as linear from zone start to end."""
    p = co_running_parameters(turnout, zone=2, source="published")
    z = p.zone
    assert p.at(z.x_start)["k_rt2_z"] == pytest.approx(448e6)
    assert p.at(z.x_end)["k_rt2_z"] == pytest.approx(453e6)
    assert p.at(0.5 * (z.x_start + z.x_end))["k_rt2_z"] == pytest.approx(450.5e6)
