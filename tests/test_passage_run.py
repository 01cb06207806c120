"""The passage's door (passage/run.py) and its track interface (passage/track.py)."""

from __future__ import annotations

import inspect

import pytest

from exudyn_turnout.passage.run import track_of, vehicle_of
from exudyn_turnout.passage.settings import PassageError, PassageSettings
from exudyn_turnout.passage.track import TrackImplementation


def _positional(function) -> list[str]:
    return [
        p.name
        for p in inspect.signature(function).parameters.values()
        if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD) and p.name != "self"
    ]


@pytest.mark.parametrize("run", ["simulate_wheelset", "simulate_vehicle"])
def test_every_track_offers_the_interface_with_its_signature(run):
    """The door calls both track implementations positionally: their parameters must be the
    protocol's, in its order (keyword-only extras, e.g. reused FE planes, are allowed)."""
    from exudyn_turnout.passage import corunning_track, fe_track

    want = _positional(getattr(TrackImplementation, run))
    for implementation in (corunning_track, fe_track):
        assert _positional(getattr(implementation, run)) == want, implementation.__name__


def test_the_track_is_the_one_source_of_truth():
    settings = PassageSettings(layers=3)
    assert track_of(settings, "2-layer") == ("2-layer", PassageSettings(layers=2))
    assert track_of(PassageSettings(layers=2), None)[0] == "2-layer"
    track, unchanged = track_of(settings, "fe")
    assert track == "fe" and unchanged == settings
    with pytest.raises(PassageError, match="track must be one of 2-layer, 3-layer, fe"):
        track_of(settings, "4-layer")


def test_vehicles_by_name():
    from exudyn_turnout.inputs.vehicle import Vehicle
    from exudyn_turnout.inputs.vehicle_model import VehicleModel

    # the default is the full Manchester vehicle (issue 24: the paper's figures show its front
    # axle); the single wheelset by name
    assert isinstance(vehicle_of(None), VehicleModel)
    assert isinstance(vehicle_of("wheelset"), Vehicle)
    manchester = vehicle_of("manchester")
    assert isinstance(manchester, VehicleModel) and len(manchester.wheelset.x) == 4
    with pytest.raises(PassageError, match="unknown packaged vehicle 'tgv'"):
        vehicle_of("tgv")
