"""The co-running track's springs as one compiled force (exudyn_turnout.corunning.track_kernel).

References: the co-running cross-section of the paper (Section 3, Figs 2, 3) assembled by
hand in exudyn_turnout.corunning.modal.assemble_track_matrices; Eqs 10, 11, 14, 15 and
Table 2's ramps through CoRunningParameters.at; the symbolic-spring builder
exudyn_turnout.corunning.track (mechanism "symbolic") as the Exudyn reference. Exudyn runs
headless and quiet in tmp_path.
"""

import dataclasses

import numpy as np
import pytest

from exudyn_turnout.corunning.fitted import TableEntry
from exudyn_turnout.corunning.modal import assemble_track_matrices, dof_names
from exudyn_turnout.corunning.parameters import co_running_parameters
from exudyn_turnout.corunning.track_kernel import TrackPlacement, track_force


def _force(params, x0, v):
    dof = dof_names(params.active_rails, params.layers)
    index = {name: i for i, name in enumerate(dof)}
    return track_force([TrackPlacement(params, x0, v, index)]), len(dof)


@pytest.mark.parametrize("source", ["derived", "published"])
@pytest.mark.parametrize("layers", [2, 3])
@pytest.mark.parametrize("zone", [1, 2, 3])
def test_matrices_and_laws_equal_the_parameter_set(turnout, source, layers, zone):
    """K(x), D(x) of the kernel equal the hand assembly, every law CoRunningParameters.at(x).

    Same operations in another order (Horner vs powers, sums of the springs): rel 1e-12.
    """
    params = co_running_parameters(turnout, zone=zone, layers=layers, source=source)
    z = params.zone
    v = 30.0
    force, n = _force(params, z.x_start, v)
    for x in np.linspace(z.x_start, z.x_end - 1e-6, 7):
        t = (x - z.x_start) / v
        hand = assemble_track_matrices(params, x)
        K, D = np.zeros((n, n)), np.zeros((n, n))
        force.add_jacobian(t, 1.0, 0.0, K)
        force.add_jacobian(t, 0.0, 1.0, D)
        assert np.max(np.abs(K - hand.K)) <= 1e-12 * np.max(np.abs(hand.K))
        assert np.max(np.abs(D - hand.D)) <= 1e-12 * np.max(np.abs(hand.D))
        expected = params.at(float(x))
        for (_, name), value in zip(force.laws, force.law_values(t)):
            assert value == pytest.approx(expected[name], rel=1e-12)


def test_fitted_tables_follow_the_zone_position(turnout):
    """A fitted table entry (piecewise linear in the zone position s) gives its values."""
    params = co_running_parameters(turnout, zone=2, layers=3)
    table = TableEntry.of((0.0, 0.5, 1.0), (1e8, 3e8, 2e8))
    params = dataclasses.replace(params, entries={**params.entries, "k_rt1_z": table})
    z = params.zone
    force, _ = _force(params, z.x_start, 1.0)
    i = [name for _, name in force.laws].index("k_rt1_z")
    for s, expected in ((0.0, 1e8), (0.25, 2e8), (0.5, 3e8), (0.75, 2.5e8), (1.0, 2e8)):
        t = s * (z.x_end - z.x_start)
        assert force.law_values(t)[i] == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("layers", [2, 3])
def test_force_free_in_the_reference_configuration(turnout, layers):
    """Zero coordinates and velocities: no force. A small displacement: -K q (first order).

    The roll enters exactly (sin, cos); at 1e-6 rad its second-order terms are ~1e-6 of the
    linear force: rel 1e-5. A velocity gives -D q_t exactly (linear in it): rel 1e-12.
    """
    for zone in turnout.zones:
        params = co_running_parameters(turnout, zone=zone.index, layers=layers)
        force, n = _force(params, 0.5 * (zone.x_start + zone.x_end), 0.0)
        out = np.zeros(n)
        force.add_forces(0.0, np.zeros(n), np.zeros(n), out)
        assert np.all(out == 0.0)
        hand = assemble_track_matrices(params, 0.5 * (zone.x_start + zone.x_end))
        q = 1e-6 * np.random.default_rng(zone.index).standard_normal(n)
        out[:] = 0.0
        force.add_forces(0.0, q, np.zeros(n), out)
        assert np.max(np.abs(out + hand.K @ q)) <= 1e-5 * np.max(np.abs(hand.K @ q))
        out[:] = 0.0
        force.add_forces(0.0, np.zeros(n), q, out)
        assert np.max(np.abs(out + hand.D @ q)) <= 1e-12 * np.max(np.abs(hand.D @ q))


def test_compiled_track_in_exudyn_equals_symbolic_springs(turnout, tmp_path, monkeypatch):
    """A step load (100 kN down, 20 kN lateral) on the r2 wheel node of zone 1 (x from 2 m at
    100 m/s, Delta_z(x) changing): coordinate histories of the compiled mechanism and the
    symbolic springs agree. Both converge Newton to 1e-4 N with other Jacobians (numerical
    for the symbolic springs, the linear one here): rel 1e-6 of the largest displacement;
    the springs frozen at x0 differ by more (the check can fail)."""
    exu = pytest.importorskip("exudyn")
    from exudyn.itemInterface import LoadForceVector, SensorNode

    from exudyn_turnout.corunning.track import add_co_running_track, simulation_settings

    monkeypatch.chdir(tmp_path)
    params = co_running_parameters(turnout, zone=1, layers=3)

    def run(mechanism):
        mbs = exu.SystemContainer().AddSystem()
        handles = add_co_running_track(mbs, params, 2.0, 100.0, mechanism=mechanism)
        mbs.AddLoad(
            LoadForceVector(markerNumber=handles.wheel_markers["r2"], loadVector=[2e4, -1e5, 0])
        )
        nodes = [handles.sleeper_node, handles.rail_nodes["r2"], handles.layer_nodes["r2"]]
        sensors = [
            mbs.AddSensor(
                SensorNode(
                    nodeNumber=node,
                    storeInternal=True,
                    writeToFile=False,
                    outputVariableType=exu.OutputVariableType.Coordinates,
                )
            )
            for node in nodes
        ]
        mbs.Assemble()
        was = exu.config.printToConsole
        exu.config.printToConsole = False
        try:
            mbs.SolveDynamic(simulation_settings(300 * 5e-5, 5e-5))
        finally:
            exu.config.printToConsole = was
        return np.hstack([mbs.GetSensorStoredData(s)[:, 1:] for s in sensors]), handles

    compiled, handles = run("compiled")
    symbolic, _ = run("symbolic")
    constant, _ = run("constant")
    assert handles.connectors == {} and handles.force_object is not None
    assert "pad_r2" in handles.position_dependent
    scale = np.max(np.abs(symbolic))
    assert np.max(np.abs(compiled - symbolic)) <= 1e-6 * scale
    assert np.max(np.abs(constant - symbolic)) > 1e-3 * scale
    assert list(tmp_path.iterdir()) == []
