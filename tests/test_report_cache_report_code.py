"""The report's FE cache key covers the report code on the path of a cached value.

A cached FE passage is run by ``report.passages.run_passage`` through
``report.passage_api.run_track_passage`` (which picks the vehicle and makes the FE
options) and stored and read back by ``report.cache``: a change in them can change what the
cache returns, so their bytes are part of every key (report/cache.py,
``REPORT_RESULT_MODULES``). The rest of ``report/`` only reads results and stays out.
"""

from __future__ import annotations

import inspect
from pathlib import Path

import numpy as np
import pytest

import exudyn_turnout
from exudyn_turnout.report import cache, passage_api, passages

ROOT = Path(exudyn_turnout.__file__).resolve().parent


def test_the_functions_that_compute_or_store_a_cached_value_are_in_the_key():
    covered = {f.resolve() for f in cache.code_files(cache.RESULT_STAGES)}
    for function in (
        passages.run_passage,
        passages.fe_passage_cache_key,
        passage_api.run_track_passage,
        passage_api.fe_passage_options,
        cache.ResultCache.save,
        cache.ResultCache.load,
    ):
        source = Path(inspect.getsourcefile(function) or "").resolve()
        assert source in covered, f"{function.__qualname__} ({source.name}) is not in the key"


def test_report_result_modules_exist_and_nothing_else_of_report():
    covered = {f.resolve().relative_to(ROOT).as_posix() for f in cache.code_files()}
    report = {name for name in covered if name.startswith("report/")}
    assert report == set(cache.REPORT_RESULT_MODULES)
    assert all((ROOT / name).is_file() for name in cache.REPORT_RESULT_MODULES)


def test_a_byte_in_a_report_result_module_changes_the_fingerprint(tmp_path):
    for name in ("report/passages.py", "report/markdown.py", "fe/model.py"):
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(name)
    key = cache.code_fingerprint(("fe",), tmp_path)
    (tmp_path / "report/markdown.py").write_text("edited")  # reads results only
    assert cache.code_fingerprint(("fe",), tmp_path) == key
    (tmp_path / "report/passages.py").write_text("edited")  # runs the cached passage
    assert cache.code_fingerprint(("fe",), tmp_path) != key


def test_an_unusable_cache_location_warns_and_the_run_goes_on(tmp_path):
    """A cache directory under a file (as XDG_CACHE_HOME set to a file) cannot be made:
    saving warns once and stores nothing, loading finds nothing; no exception (issue 25)."""
    blocker = tmp_path / "a_file"
    blocker.write_text("not a directory")
    store = cache.ResultCache(blocker / "exudyn_turnout")
    key = cache.input_key("x", 1)
    with pytest.warns(UserWarning, match=r"FE result cache .*a_file.* not usable.*without it"):
        store.save(key, {"H": np.ones(3)}, {"computed": "now"})
    assert store.load(key) is None
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a_file"]


def test_a_usable_cache_round_trips(tmp_path):
    store = cache.ResultCache(tmp_path / "c")
    key = cache.input_key("y", 2)
    store.save(key, {"H": np.arange(3.0)}, {"computed": "now"})
    arrays, meta = store.load(key)
    assert np.array_equal(arrays["H"], [0.0, 1.0, 2.0]) and meta == {"computed": "now"}
