"""Shared fixtures: the packaged turnout, loaded once; headless matplotlib."""

import os

import pytest

os.environ.setdefault("MPLBACKEND", "Agg")

from exudyn_turnout.inputs.turnout import load_turnout  # noqa: E402


@pytest.fixture(scope="session")
def turnout():
    """The packaged UIC60-760-1:15 turnout (data/uic60_760_1_15.toml)."""
    return load_turnout()
