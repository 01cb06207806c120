"""Exudyn co-running track builder (exudyn_turnout.corunning.track), headless and quiet.

References: the co-running cross-section of the paper (Section 3, Figs 2, 3) assembled by hand in
exudyn_turnout.corunning.modal.assemble_track_matrices; the active rails of the paper's Table 3
(zone 1: r1 r2 r4; zone 2: r1-r4; zone 3: r1 r4); Eqs 10, 11, 14, 15 through
CoRunningParameters.at. Every simulation runs in tmp_path as working directory, and the
tests check that Exudyn wrote no file there.
"""

import dataclasses

import numpy as np
import pytest

exu = pytest.importorskip("exudyn")

from exudyn.itemInterface import LoadForceVector, MassPoint2D, NodePoint2D, SensorObject  # noqa: E402

from exudyn_turnout.corunning.modal import assemble_track_matrices  # noqa: E402
from exudyn_turnout.corunning.parameters import co_running_parameters, delta_y, delta_z  # noqa: E402
from exudyn_turnout.corunning.track import (  # noqa: E402
    MECHANISMS,
    EntryLaw,
    add_co_running_track,
    linearized_matrices,
    simulation_settings,
)
from exudyn_turnout.inputs.turnout import Polynomial  # noqa: E402


@pytest.fixture(autouse=True)
def quiet_exudyn_in_tmp(tmp_path, monkeypatch):
    """Exudyn silent, working directory tmp_path; afterwards, no file may have appeared."""
    monkeypatch.chdir(tmp_path)
    was = exu.config.printToConsole
    exu.config.printToConsole = False
    yield
    exu.config.printToConsole = was
    assert list(tmp_path.iterdir()) == [], "Exudyn wrote files into the working directory"


def _system():
    return exu.SystemContainer().AddSystem()


@pytest.mark.parametrize("source", ["derived", "published"])
@pytest.mark.parametrize("layers", [2, 3])
@pytest.mark.parametrize("mechanism", MECHANISMS)
def test_linearized_system_equals_hand_assembly(turnout, source, layers, mechanism):
    """Zone 2 (all four rails, with the check rail r3) at x = 47 m.

    Tolerance: built-in springs linearise exactly (round-off, 1e-12 of the largest
    entry); user-function springs are linearised by Exudyn with finite differences
    (relative step 1e-7), measured 1.3e-8, so 1e-6 of the largest entry.
    """
    params = co_running_parameters(turnout, zone=2, layers=layers, source=source)
    mbs = _system()
    handles = add_co_running_track(mbs, params, 47.0, 30.0, mechanism=mechanism)
    mbs.Assemble()
    exudyn_mkd = linearized_matrices(mbs, handles)
    hand = assemble_track_matrices(params, 47.0)
    assert exudyn_mkd.dof == hand.dof
    tol = 1e-12 if mechanism == "constant" else 1e-6
    for a, b in ((exudyn_mkd.M, hand.M), (exudyn_mkd.K, hand.K), (exudyn_mkd.D, hand.D)):
        assert np.max(np.abs(a - b)) <= tol * np.max(np.abs(b))
    if mechanism != "constant":  # zone 2 has x-dependent entries in both sources (Delta_y, ramps)
        assert handles.position_dependent


@pytest.mark.parametrize(
    "zone,rails", [(1, ("r1", "r2", "r4")), (2, ("r1", "r2", "r3", "r4")), (3, ("r1", "r4"))]
)
@pytest.mark.parametrize("layers", [2, 3])
def test_only_active_rails_get_coordinates(turnout, zone, rails, layers):
    """Table 3: an inactive rail has no node, no marker and no coordinate in the system."""
    params = co_running_parameters(turnout, zone=zone, layers=layers)
    mbs = _system()
    x0 = turnout.zone(zone).x_start
    handles = add_co_running_track(mbs, params, x0)
    mbs.Assemble()
    assert tuple(handles.rail_nodes) == rails
    assert tuple(handles.wheel_markers) == rails
    expected = 3 + 2 * len(rails) * (layers - 1)
    assert mbs.systemData.ODE2Size() == expected == len(handles.dof)
    inactive = {"r1", "r2", "r3", "r4"} - set(rails)
    assert not [d for d in handles.dof if d[-2:] in inactive]
    assert sorted(handles.coordinate_indices(mbs).values()) == list(range(expected))
    wheel = handles.layer_markers if layers == 3 else handles.rail_markers
    assert handles.wheel_markers == wheel


@pytest.mark.parametrize("source", ["derived", "published"])
@pytest.mark.parametrize("zone", [1, 2, 3])
def test_entry_law_equals_parameter_set(turnout, source, zone):
    """The expressions used in the user functions give CoRunningParameters.at(x).

    Evaluated as floats (Python path) and as Exudyn symbolic expressions of a variable x
    (the value the fast path reads). Different operation order (Horner vs powers): rel 1e-12.
    """
    params = co_running_parameters(turnout, zone=zone, layers=3, source=source)
    law = EntryLaw.of(params)
    x_symbol = exu.symbolic.Real("x_test", 0.0)
    names = [n for n in params.entries if params.depends_on_x(n)]
    expressions = {n: law.value(params.entries[n], x_symbol, exu.symbolic) for n in names}
    z = params.zone
    for x in np.linspace(z.x_start, z.x_end, 17):
        x_symbol.SetValue(float(x))
        expected = params.at(float(x))
        for n in names:
            assert law.value(params.entries[n], float(x)) == pytest.approx(expected[n], rel=1e-12)
            assert expressions[n].Evaluate() == pytest.approx(expected[n], rel=1e-12)


def _simulate(params, mechanism, x0=2.0, v=100.0, carrier=False, steps=300, h=5e-5):
    """Step load (100 kN down, 20 kN lateral) on the r2 wheel marker; connector force histories.

    ``carrier``: x read from the coordinate of a free mass point moving at v (x = x0 + q).
    """
    mbs = _system()
    x_coordinate = None
    if carrier:
        node = mbs.AddNode(NodePoint2D(initialVelocities=[v, 0.0]))
        mbs.AddObject(MassPoint2D(nodeNumber=node, mass=1.0))
        x_coordinate = (int(node), 0)
    handles = add_co_running_track(
        mbs, params, x0, v, mechanism=mechanism, x_coordinate=x_coordinate
    )
    mbs.AddLoad(
        LoadForceVector(markerNumber=handles.wheel_markers["r2"], loadVector=[2e4, -1e5, 0.0])
    )
    sensors = {
        name: mbs.AddSensor(
            SensorObject(
                objectNumber=c,
                outputVariableType=exu.OutputVariableType.Force,
                storeInternal=True,
                writeToFile=False,
            )
        )
        for name, c in handles.connectors.items()
    }
    mbs.Assemble()
    mbs.SolveDynamic(simulation_settings(steps * h, h))
    return {name: mbs.GetSensorStoredData(s)[:, 1:] for name, s in sensors.items()}, handles


def _difference(a, b):
    """Largest force difference over all connectors, relative to the largest force."""
    scale = max(np.max(np.abs(f)) for f in b.values())
    return max(np.max(np.abs(a[n] - b[n])) for n in b) / scale


def _unit_delta_turnout(turnout):
    """The turnout with K_sw = K_st,z and K_sh = K_st,y everywhere: Delta_z = Delta_y = 1."""
    K_st_z = turnout.K_sw(0.0) / delta_z(turnout, 0.0)
    K_st_y = turnout.K_sh(0.0) / delta_y(turnout, 0.0)
    return dataclasses.replace(
        turnout, K_sw=Polynomial((K_st_z,), 0.0, 22.0), K_sh=Polynomial((K_st_y,), 0.0, 60.0)
    )


def test_unit_delta_user_functions_equal_constant_springs(turnout):
    """With Delta = 1 everywhere, x-dependent springs give the constant-spring response.

    Zone 1, three layers, derived (its entries are Delta_z / Delta_y multiples). The
    spring values differ only by a * (1/K_st) * K_st round-off, but Exudyn differentiates
    user-function springs numerically for Newton's Jacobian, so the two runs converge
    differently within Newton's relative tolerance 1e-8 (measured 4.7e-9): rel 1e-7.
    """
    unit = _unit_delta_turnout(turnout)
    params = co_running_parameters(unit, zone=1, layers=3)
    assert delta_z(unit, 10.0) == pytest.approx(1.0, rel=1e-14)
    constant, _ = _simulate(params, "constant")
    for mechanism in ("symbolic", "python"):
        forces, handles = _simulate(params, mechanism)
        assert "pad_r2" in handles.position_dependent
        assert _difference(forces, constant) < 1e-7


def test_python_and_symbolic_paths_agree_on_the_switch(turnout):
    """Real Delta_z(x): x from 2 m to 3.5 m in 15 ms; Python and symbolic forces agree.

    Both evaluate the same expressions in double precision: rel 1e-9 of the peak force.
    They differ from springs frozen at x0 by > 0.5 % (Delta_z rises by 4 % over the run),
    which shows the comparison can fail.
    """
    params = co_running_parameters(turnout, zone=1, layers=3)
    symbolic, _ = _simulate(params, "symbolic")
    python, _ = _simulate(params, "python")
    constant, _ = _simulate(params, "constant")
    assert _difference(python, symbolic) < 1e-9
    assert _difference(constant, symbolic) > 5e-3


def test_position_read_from_a_coordinate(turnout):
    """x = x0 + q of a free mass moving at 100 m/s, read at each step start.

    Python and symbolic paths read the same value: rel 1e-9. Against x0 + v t inside the
    step the read value lags by one step (v h = 5 mm, Delta_z changes 1.5e-4 of itself),
    so the forces agree within 1e-3. The last value read is x0 + v (t_end - h).
    """
    params = co_running_parameters(turnout, zone=1, layers=3)
    steps, h = 300, 5e-5
    symbolic, handles = _simulate(params, "symbolic", carrier=True, steps=steps, h=h)
    python, _ = _simulate(params, "python", carrier=True, steps=steps, h=h)
    moving, _ = _simulate(params, "symbolic", steps=steps, h=h)
    assert _difference(python, symbolic) < 1e-9
    assert _difference(symbolic, moving) < 1e-3
    assert handles._position[0] == pytest.approx(2.0 + 100.0 * (steps - 1) * h, rel=1e-9)


def test_bad_mechanism_and_position(turnout):
    params = co_running_parameters(turnout, zone=1, layers=2)
    with pytest.raises(ValueError, match="mechanism"):
        add_co_running_track(_system(), params, 10.0, mechanism="fast")
    with pytest.raises(ValueError, match="outside zone 1"):
        add_co_running_track(_system(), params, 50.0)
