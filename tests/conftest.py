"""Shared fixtures: the packaged turnout, loaded once; headless matplotlib."""

import os

import pytest

os.environ.setdefault("MPLBACKEND", "Agg")
# One BLAS thread per test process (set before numpy loads OpenBLAS): the suite runs on
# pytest-xdist workers, one per core, and OpenBLAS's own threads on top of them oversubscribe
# the cores. Measured on 2 cores (the exact-theory and detailed-contact tests, -n 0, load ~2):
# 59.9 s wall / 26.3 s user with OpenBLAS's default threads, 24.5 s / 12.7 s with one.
for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

from exudyn_turnout.inputs.turnout import load_turnout  # noqa: E402


@pytest.fixture(scope="session")
def turnout():
    """The packaged UIC60-760-1:15 turnout (data/uic60_760_1_15.toml)."""
    return load_turnout()
