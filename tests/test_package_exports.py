"""Every name the package offers at its top (``exudyn_turnout.__all__``, imported lazily)
resolves: a lazy entry pointing at a module that no longer defines the name fails here
rather than in a user's import or the documentation build."""

import importlib

import pytest

import exudyn_turnout

PACKAGES = [
    "exudyn_turnout",
    "exudyn_turnout.passage",
    "exudyn_turnout.wheel_rail",
    "exudyn_turnout.corunning",
    "exudyn_turnout.fe",
    "exudyn_turnout.inputs",
    "exudyn_turnout.studies",
    "exudyn_turnout.report",
]


@pytest.mark.parametrize("name", exudyn_turnout.__all__)
def test_top_level_name_resolves(name):
    assert getattr(exudyn_turnout, name) is not None


@pytest.mark.parametrize("package", PACKAGES)
def test_every_listed_name_of_a_package_resolves(package):
    module = importlib.import_module(package)
    missing = [n for n in getattr(module, "__all__", []) if not hasattr(module, n)]
    assert not missing
