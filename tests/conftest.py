"""Shared fixtures: the packaged turnout, loaded once; the plain track's packed contact
tables; headless matplotlib."""

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


@pytest.fixture(scope="session")
def plain_packed(tmp_path_factory):
    """S1002 on plain UIC60 1:40 track, x -10..70 m, packed for the kernel: left wheel's
    body bound to rail coordinates (7, 8), the right's to (9, 10)."""
    import numpy as np

    from exudyn_turnout.wheel_rail import packed_tables
    from exudyn_turnout.wheel_rail.data import s1002_wheel, standard_track
    from exudyn_turnout.wheel_rail.geometry import WheelsetSetup
    from exudyn_turnout.wheel_rail.tables import build_contact_table

    setup = WheelsetSetup()
    track = standard_track(setup, np.array([-10.0, 70.0]))
    table = build_contact_table(
        s1002_wheel(setup), track, setup.taping_line, cache_dir=tmp_path_factory.mktemp("plain")
    )
    return packed_tables.pack_tables([table, table], [1, -1], [(7, 8), (9, 10)], [(-10, 70)] * 2)
