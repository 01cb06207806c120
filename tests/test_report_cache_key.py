"""The report's FE cache keys cover every file a passage executes (issue 21).

The key hashes whole stage folders of the package (:func:`exudyn_turnout.report.cache.
code_files`), never a hand-kept list of modules, so a module added or moved inside a stage
is covered without anyone remembering it.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

#: Package folders whose modules do not change a passage's result: the report (it consumes
#: results; its few modules that run or store a cached result are in the key anyway,
#: ``report.cache.REPORT_RESULT_MODULES``), the command line (it parses arguments and calls
#: the report) and the plotting (it draws results). Their modules may be imported along with
#: a passage but compute none of its numbers.
NOT_RESULTS = ("report", "cli", "plotting")


def _tiny_fe_passage() -> None:
    """The smallest FE passages of the package, as the report runs them: the single
    wheelset and the full vehicle, 0.2 m of the through route each (about 15 s).

    The one place of the test that calls the passage API (to adapt when it changes).
    """
    import exudyn_turnout as et

    settings = et.PassageSettings(route="through", speed_kmh=100, x_start=46.6, x_end=46.8)
    turnout = et.load_turnout()
    for vehicle in ("wheelset", "manchester"):
        et.simulate_passage(turnout, settings, vehicle, track="fe")


#: Run in a fresh interpreter: the FE passage, then every loaded module's file as JSON.
_CHILD = """
import json, runpy, sys
runpy.run_path(sys.argv[1])["_tiny_fe_passage"]()
print(json.dumps({n: getattr(m, "__file__", None) for n, m in list(sys.modules.items())
                  if n == "exudyn_turnout" or n.startswith("exudyn_turnout.")}))
"""


@pytest.mark.slow
def test_fe_passage_key_covers_every_module_the_passage_executes():
    """Every package module loaded by an FE passage (in a fresh interpreter, so nothing else
    of a test session counts) is a file of the FE passage's cache key.

    Except the modules of ``report/``, ``cli/`` and ``plotting/`` (:data:`NOT_RESULTS`): they
    do not change a result. The report consumes the passage's result and keys it (a change
    there cannot alter the numbers it caches), the command line only parses arguments and
    calls the report, and plotting only draws results; none of them is called by the passage.
    """
    import exudyn_turnout
    from exudyn_turnout.report.cache import RESULT_STAGES, code_files

    root = Path(exudyn_turnout.__file__).resolve().parent
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(root.parent)] + sys.path))
    child = subprocess.run(
        [sys.executable, "-c", _CHILD, __file__],
        capture_output=True,
        text=True,
        env=env,
        timeout=600,
        check=False,
    )
    assert child.returncode == 0, child.stderr[-3000:]
    loaded = json.loads(child.stdout.strip().splitlines()[-1])
    # it did run an FE passage: FE and passage modules were loaded
    assert any(n.startswith("exudyn_turnout.fe.") for n in loaded)
    assert any(n.startswith("exudyn_turnout.passage.") for n in loaded)
    files = {Path(f).resolve() for f in loaded.values() if f}
    assert all(f.is_relative_to(root) for f in files), "another copy of the package was loaded"
    relevant = {f for f in files if f.relative_to(root).parts[0] not in NOT_RESULTS}
    covered = {f.resolve() for f in code_files(RESULT_STAGES)}
    missing = sorted(str(f.relative_to(root)) for f in relevant - covered)
    assert not missing, f"executed in an FE passage but not in its cache key: {missing}"


def test_code_files_hash_stage_folders_recursively(tmp_path):
    """Nested folders of a stage, top-level modules and profile data are covered; other stages
    and data that do not change results are not; a byte changes the fingerprint."""
    from exudyn_turnout.report.cache import code_files, code_fingerprint

    made = [
        "__init__.py",
        "receptance.py",
        "passage/__init__.py",
        "passage/vehicle/builder.py",
        "passage/contact/deep/element.py",
        "fe/model.py",
        "report/markdown.py",
        "plotting/curves.py",
        "data/uic.toml",
        "data/wheel_rail/profiles/uk_crossing/x.txt",
        "data/wheel_rail/reference_outputs/a.ref_out",
        "data/wheel_rail/NOTICE.md",
        "passage/__pycache__/x.cpython-311.pyc",
    ]
    for name in made:
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(name)
    got = {f.relative_to(tmp_path).as_posix() for f in code_files(("passage", "fe"), tmp_path)}
    assert got == {
        "__init__.py",
        "receptance.py",
        "passage/__init__.py",
        "passage/vehicle/builder.py",
        "passage/contact/deep/element.py",
        "fe/model.py",
        "data/uic.toml",
        "data/wheel_rail/profiles/uk_crossing/x.txt",
    }
    key = code_fingerprint(("passage", "fe"), tmp_path)
    assert key == code_fingerprint(("passage", "fe"), tmp_path)
    (tmp_path / "passage/contact/deep/element.py").write_text("changed")
    changed = code_fingerprint(("passage", "fe"), tmp_path)
    (tmp_path / "passage/contact/deep/new.py").write_text("")
    added = code_fingerprint(("passage", "fe"), tmp_path)
    (tmp_path / "report/markdown.py").write_text("changed")  # not a result's code
    assert len({key, changed, added}) == 3
    assert added == code_fingerprint(("passage", "fe"), tmp_path)


def test_fe_passage_cache_key_follows_the_code(turnout, monkeypatch):
    """The FE passage's key is the key of the code of :data:`RESULT_STAGES`: another code
    fingerprint gives another key."""
    import exudyn_turnout as et
    import exudyn_turnout.report.passages as rp

    settings = et.PassageSettings(route="through", x_start=46.0, x_end=47.0, contact="profile")
    config = rp.ReportConfig(vehicle="wheelset")
    key = rp.fe_passage_cache_key(turnout, settings, config)
    monkeypatch.setattr(rp, "code_fingerprint", lambda stages: "0" * 64)
    assert rp.fe_passage_cache_key(turnout, settings, config) != key


def _imported_files(files, root: Path) -> set[Path]:
    """Files of the package imported anywhere (also inside functions) by ``files``."""
    import ast

    out = set()
    for f in files:
        if f.suffix != ".py":
            continue
        for node in ast.walk(ast.parse(f.read_text(encoding="utf-8"))):
            names = []
            if isinstance(node, ast.ImportFrom) and node.module:
                names = [node.module] + [f"{node.module}.{a.name}" for a in node.names]
            elif isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            for name in names:
                if name != "exudyn_turnout" and not name.startswith("exudyn_turnout."):
                    continue
                path = root.joinpath(*name.split(".")[1:])
                for candidate in (path.with_suffix(".py"), path / "__init__.py"):
                    if candidate.is_file():
                        out.add(candidate.resolve())
    return out


def test_key_code_imports_only_code_of_the_key():
    """Every package module that the code of the cache key imports (at the top or in a
    function) is itself in the key, but for ``report/``, ``cli/`` and ``plotting/`` (see
    :data:`NOT_RESULTS`): the key of every FE result (receptance, stiffness, passage) cannot
    miss a module by a static import either (a narrower key of inputs/ and fe/ for the FE
    receptance did: the package's ``__init__`` imports ``corunning/parameters.py``)."""
    import exudyn_turnout
    from exudyn_turnout.report import cache

    root = Path(exudyn_turnout.__file__).resolve().parent
    covered = {f.resolve() for f in cache.code_files(cache.RESULT_STAGES)}
    imported = _imported_files(covered, root)
    relevant = {f for f in imported if f.relative_to(root).parts[0] not in NOT_RESULTS}
    missing = sorted(str(f.relative_to(root)) for f in relevant - covered)
    assert not missing, f"imported by the key's code but not in the key: {missing}"
    assert len(imported) > 20  # the walk found the package's imports
