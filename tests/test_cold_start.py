"""A first run's builds (issue 24, cold main job): the creep table filled in a background
thread beside the contact tables, and the line that says so.

The reference for the background fill is the fill in one thread (``build_creep_table``)
and direct FASTSIM (:func:`.fastsim.fastsim_ellipse`), which the table's nodes are: the
values must be bit-identical, whichever thread computed which chunk.
"""

from __future__ import annotations

import io
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

from exudyn_turnout.cli import passage as cli_passage
from exudyn_turnout.cli.passage import StatusLine
from exudyn_turnout.wheel_rail import creep_table as ct
from exudyn_turnout.wheel_rail.fastsim import fastsim_ellipse

SMALL = ct.CreepTableSettings(n_size=9, n_alpha=5, n_beta=9, n_ratio=7)


@pytest.fixture(autouse=True)
def _fresh_memory():
    ct.creep_table.cache_clear()
    yield
    ct.creep_table.cache_clear()


def _direct_fastsim(settings):
    """The table's nodes by direct FASTSIM (the fill of creep-table-5 before threads)."""
    grid = np.meshgrid(*ct._grid(settings), indexing="ij")
    a, b, q, mu, g = ct._physical(grid[0])
    c = ct.kalker_coefficients(a, b, settings.poisson)
    scale = 3.0 * mu * q / (g * a * b)
    xi, eta, phi = ct._node_creepages(
        grid[1], grid[2], grid[3], a, b, c.c11, c.c22, c.c23, scale, settings.spin_blend
    )
    f = fastsim_ellipse(xi, eta, phi, a, b, q, mu, g, settings.poisson, settings.n_strips,
                        settings.n_x)  # fmt: skip
    values = np.stack((f.longitudinal, f.lateral), axis=-1) / (mu * q)[..., None]
    return values / np.maximum(np.hypot(values[..., 0], values[..., 1]), 1.0)[..., None]


def test_fill_in_chunks_by_two_threads_is_bit_identical(tmp_path, monkeypatch):
    monkeypatch.setattr(ct, "_CHUNK", 97)  # 3,969 nodes: 41 chunks, shared out
    direct = _direct_fastsim(SMALL)
    assert np.array_equal(ct.build_creep_table(SMALL).values, direct)  # one thread
    assert ct.start_creep_table(SMALL, str(tmp_path)) is True
    assert ct.start_creep_table(SMALL, str(tmp_path)) is True  # under way: not twice
    assert len([t for t in threading.enumerate() if t.name == "creep-table"]) >= 1
    table = ct.creep_table(SMALL, str(tmp_path))  # joins the fill
    assert np.array_equal(table.values, direct) and table.build_seconds > 0.0
    assert not [t for t in threading.enumerate() if t.name == "creep-table"]
    files = list(tmp_path.glob("creep_table_*"))
    assert [f.suffix for f in files] == [".npz"]  # written, no temporary left
    assert ct.start_creep_table(SMALL, str(tmp_path)) is False  # cached now
    ct.creep_table.cache_clear()
    loaded = ct.creep_table(SMALL, str(tmp_path))
    assert loaded.build_seconds == 0.0 and np.array_equal(loaded.values, direct)


def test_background_fill_without_anyone_joining_writes_the_cache(tmp_path):
    assert ct.start_creep_table(SMALL, str(tmp_path)) is True
    with ct._RUNNING_LOCK:
        running = ct._RUNNING.pop(str(next(iter(ct._RUNNING))))
    running.thread.join(60.0)
    assert running.table is not None
    table = ct.creep_table(SMALL, str(tmp_path))
    assert table.build_seconds == 0.0  # read from the file the thread wrote
    assert np.array_equal(table.values, running.table.values)


def test_a_failed_background_fill_is_built_again_by_the_caller(tmp_path, monkeypatch):
    prepare = ct._Fill.prepare

    def fails_in_the_helper(self):
        if threading.current_thread().name == "creep-table":
            self.error = RuntimeError("helper thread failed")
            self._prepared.set()
            raise self.error
        prepare(self)

    monkeypatch.setattr(ct._Fill, "prepare", fails_in_the_helper)
    assert ct.start_creep_table(SMALL, str(tmp_path)) is True
    table = ct.creep_table(SMALL, str(tmp_path))
    assert np.array_equal(table.values, _direct_fastsim(SMALL))
    assert len(list(tmp_path.glob("creep_table_*.npz"))) == 1


def test_a_killed_build_leaves_no_file_that_is_read(tmp_path):
    """The process is killed while its background fill runs (the default grid: seconds):
    no cache file exists afterwards (written only when complete, then renamed)."""
    code = (
        "import sys, time\n"
        "from exudyn_turnout.wheel_rail import creep_table as ct\n"
        "assert ct.start_creep_table(ct.CreepTableSettings(), sys.argv[1])\n"
        "print('started', flush=True)\n"
        "time.sleep(600)\n"
    )
    child = subprocess.Popen(
        [sys.executable, "-c", code, str(tmp_path)], stdout=subprocess.PIPE, text=True
    )
    try:
        assert child.stdout is not None and child.stdout.readline().strip() == "started"
        time.sleep(0.5)
    finally:
        child.kill()
        child.wait(30)
    assert not list(tmp_path.glob("creep_table_*.npz"))


def test_first_run_line_names_the_builds(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    started = []
    monkeypatch.setattr(ct, "start_creep_table", lambda: started.append(1) or True)
    line = cli_passage._start_cold_builds("through")
    assert started == [1]
    assert line is not None and line.startswith(
        "building the contact tables of the through route and the creep table"
    )
    assert "first run only, cached in " + str(tmp_path) in line
    cache = tmp_path / "exudyn_turnout" / "wheel_rail"
    cache.mkdir(parents=True)
    (cache / "contact_table_0123.npz").write_bytes(b"")
    monkeypatch.setattr(ct, "start_creep_table", lambda: False)
    assert cli_passage._start_cold_builds("through") is None  # both cached
    log, quiet = io.StringIO(), io.StringIO()
    StatusLine(log).notice("building the creep table")
    StatusLine(quiet, quiet=True).notice("building the creep table")
    assert log.getvalue() == "building the creep table\n" and quiet.getvalue() == ""
