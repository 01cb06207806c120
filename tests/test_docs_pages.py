"""The documentation's sources (``docs/``), checked without Sphinx (CI builds the site).

Every public name has its page, every example its gallery page, every command its
``--help``; the example of every file-format page is read by the package's own loader;
and the two ways the site reads docstrings (plain-text ``|H|``, the nearest of two targets)
do what ``docs/_ext/et_docs.py`` says.
"""

from __future__ import annotations

import importlib.util
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"


def _load_et_docs():
    spec = importlib.util.spec_from_file_location("et_docs", DOCS / "_ext" / "et_docs.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


et_docs = _load_et_docs()


@pytest.fixture(scope="module")
def api_pages():
    return et_docs.api_pages()


def test_every_stage_and_module_has_a_page(api_pages):
    """Each stage of the API index and each module below it (but ``cli``) gets a page."""
    index = (DOCS / "api" / "index.rst").read_text(encoding="utf-8")
    for stage in et_docs.STAGES:
        assert f"{stage}.rst" in api_pages
        assert f"generated/{stage}\n" in index, f"{stage} missing from docs/api/index.rst"
    import pkgutil

    import exudyn_turnout

    for info in pkgutil.walk_packages(exudyn_turnout.__path__, "exudyn_turnout."):
        last = info.name.rsplit(".", 1)[-1]
        if last.startswith("_") or info.name.startswith("exudyn_turnout.cli"):
            continue
        assert f"{info.name}.rst" in api_pages, info.name


def test_every_public_name_is_documented_once_and_listed(api_pages):
    """Every ``__all__`` name of every package and module is documented on exactly one page
    (its defining module's) and a package's page lists all of its ``__all__``."""
    documented: dict[str, str] = {}
    for page, text in api_pages.items():
        for target in re.findall(r"^\.\. autoany:: (\S+)$", text, re.M):
            assert target not in documented, f"{target} on {page} and {documented[target]}"
            documented[target] = page
    by_name: dict[str, set[str]] = {}
    for target in documented:
        module, _, name = target.rpartition(".")
        by_name.setdefault(name, set()).add(module)
    for page, text in api_pages.items():
        modname = page.removesuffix(".rst")
        for name in et_docs.public_names(modname):
            homes = by_name.get(name, set())
            assert homes, f"{modname}.{name}: documented nowhere"
            if page != "exudyn_turnout.rst" and not hasattr(
                importlib.import_module(modname), "__path__"
            ):
                continue
            # a package's page lists its names in the table, linked to where they live
            assert any(f":py:obj:`~{home}.{name}`" in text for home in homes), (
                f"{modname}: {name} missing from its page's table"
            )


def test_every_example_has_a_gallery_page():
    pages = et_docs.example_pages()
    scripts = sorted((ROOT / "examples").glob("*.py"))
    assert scripts
    for script in scripts:
        text = pages[f"{script.stem}.rst"]
        assert f"examples/{script.name}\n" in text  # literalinclude of its source
        assert "Not run when the documentation is built" in text
        first = text.split("\n")[3]
        assert first.strip(), f"{script.name}: no docstring"
    study_page = pages["monte_carlo_study.rst"]
    assert "examples/monte_carlo_study.toml" in study_page


def test_every_command_has_its_help():
    commands = dict(et_docs.cli_commands())
    for words in [(), ("params",), ("simulate",), ("fe", "frf"), ("draw", "section"), ("fit",)]:
        assert commands[words].startswith("usage: exudyn-turnout"), words
    assert ("fe",) in commands and ("study",) in commands
    reference = et_docs.cli_reference()
    assert "``exudyn-turnout draw passage``" in reference


def test_literal_includes_exist():
    """Every file a hand-written page includes is there (the site would fail on it too)."""
    pages = [p for p in DOCS.rglob("*.rst") if "generated" not in p.parts]
    assert pages
    for page in pages:
        for target in re.findall(r"^\.\. literalinclude:: (\S+)$", page.read_text(), re.M):
            assert (page.parent / target).is_file(), f"{page.relative_to(DOCS)}: {target}"


def _check_vehicle(path):
    from exudyn_turnout.inputs.vehicle_model import load_vehicle_model

    vehicle = load_vehicle_model(path)
    assert vehicle.sprung_mass is not None and vehicle.car_body is None


def _check_study(path):
    from exudyn_turnout.studies import load_study

    # 2 speeds x 2 paired rows x 3 seeds, as the file's comment says
    assert len(load_study(path).cases()) == 12


def _check_irregularity(path):
    from exudyn_turnout.inputs.irregularity import irregularity_from_csv, irregularity_from_spec

    irregularity = irregularity_from_csv(path)
    assert irregularity.x[0] == -5.0 and irregularity.x[-1] == 60.0
    assert irregularity_from_spec(f"{path};dip:x=30,depth=0.001,length=1") is not None


#: docs/formats/examples/<file> -> how the package reads it
FORMAT_EXAMPLES = {
    "wheelset_vehicle_model.toml": _check_vehicle,
    "study.toml": _check_study,
    "irregularity.csv": _check_irregularity,
}


def test_format_examples_are_read_by_the_package():
    """Each example file of the file-format pages is read by the package's loader, and is
    shown on a page."""
    folder = DOCS / "formats" / "examples"
    files = sorted(p.name for p in folder.iterdir())
    assert files == sorted(FORMAT_EXAMPLES), "a new example needs its loader here"
    pages = "".join(p.read_text() for p in (DOCS / "formats").glob("*.rst"))
    for name, check in FORMAT_EXAMPLES.items():
        check(folder / name)
        assert f"examples/{name}" in pages, f"{name} is on no page"


def test_packaged_files_shown_by_the_format_pages_load():
    """The packaged files the format pages show are read by their loaders."""
    import exudyn_turnout as et
    from exudyn_turnout.corunning.fitted import load_fitted
    from exudyn_turnout.inputs.turnout import default_turnout_path
    from exudyn_turnout.wheel_rail.data import profile_path
    from exudyn_turnout.wheel_rail.profiles import read_profile, read_slices

    turnout = et.load_turnout()
    fitted = default_turnout_path().with_name("uic60_760_1_15_fitted.toml")
    assert load_fitted(turnout, fitted) is not None
    et.load_vehicle("wheelset")
    et.load_vehicle_model("manchester")
    assert read_profile(profile_path("MBench_S1002_v3.prw"), kind="wheel").kind == "wheel"
    assert read_slices(profile_path("cross_nose.slcs")) is not None


def test_plain_text_docstring():
    """``|H|`` is escaped outside literals; literal blocks, inline literals and grid tables
    are left alone; a short title underline is drawn to the title's length."""
    lines = [
        "The level |H| in dB, ``a|b`` stays::",
        "",
        "    |x| in a literal block",
        "",
        "back |y|",
        "Title here",
        "-----",
        "",
        "+---+---+",
        "| a | b |",
        "+---+---+",
    ]
    out = et_docs.plain_text_docstring(lines)
    assert out[0] == r"The level \|H\| in dB, ``a|b`` stays::"
    assert out[2] == "    |x| in a literal block"
    assert out[4] == r"back \|y\|"
    assert out[6] == "----------"
    assert out[8:] == lines[8:]
    assert len(out) == len(lines)


def test_nearest_target():
    """Of two objects with one name, the one in the referring module's package wins; a tie
    links to neither."""
    matches = [("exudyn_turnout.inputs.geometry", 0), ("exudyn_turnout.wheel_rail.geometry", 1)]
    nearest = et_docs._nearest("exudyn_turnout.wheel_rail.tables", None, matches)
    assert nearest == [matches[1]]
    assert et_docs._nearest("exudyn_turnout.fe.mesh", None, matches) == []
