"""The package's import rules, read from the source (no module is imported here).

- only the Exudyn builders import exudyn;
- only plotting and figure modules import matplotlib;
- ``fe/`` never imports ``corunning/`` (the FE reference stays independent of the model it
  judges);
- nothing imports ``cli/`` or ``report/`` from below (they are the top of the pipeline);
- no star imports.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "exudyn_turnout"

#: Modules allowed to import exudyn: they build Exudyn systems.
EXUDYN_BUILDERS = {
    "corunning/track.py",
    "passage/vehicle.py",
    "passage/contact_element.py",
    "passage/simulate.py",
    "passage/vehicle_builder.py",
    "passage/full_vehicle_passage.py",
    "passage/fe_passage.py",
    "passage/hunting.py",
    "passage/fe_vehicle_passage.py",
    "passage/vehicle_analysis.py",
}
#: The one module allowed to import matplotlib (the figure modules get it from there).
FIGURE_MODULES = {"plotting/backend.py"}
#: Top-level stages, in pipeline order; a stage may not import a later stage of this list
#: unless listed in ALLOWED_UPWARD.
STAGES = ("inputs", "wheel_rail", "corunning", "fe", "passage", "studies", "report", "cli")


def _modules() -> dict[str, ast.Module]:
    return {
        p.relative_to(PACKAGE).as_posix(): ast.parse(p.read_text(encoding="utf-8"))
        for p in sorted(PACKAGE.rglob("*.py"))
    }


def _imports(name: str, tree: ast.Module) -> set[str]:
    """Absolute dotted names imported by module ``name`` (relative imports resolved)."""
    parts = ["exudyn_turnout"] + name[:-3].split("/")
    if parts[-1] == "__init__":
        parts = parts[:-1]
        package = parts
    else:
        package = parts[:-1]
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[: len(package) - node.level + 1]
                stem = ".".join(base + ([node.module] if node.module else []))
            else:
                stem = node.module or ""
            out.add(stem)
            out.update(f"{stem}.{alias.name}" for alias in node.names)
    return out


def _stage(dotted: str) -> str | None:
    parts = dotted.split(".")
    if len(parts) >= 2 and parts[0] == "exudyn_turnout" and parts[1] in STAGES:
        return parts[1]
    return None


MODULES = _modules()


def test_layout_has_the_stages():
    for stage in STAGES:
        assert (PACKAGE / stage / "__init__.py").exists(), stage


@pytest.mark.parametrize("name", sorted(MODULES))
def test_only_builders_import_exudyn(name):
    uses = any(i == "exudyn" or i.startswith("exudyn.") for i in _imports(name, MODULES[name]))
    assert not uses or name in EXUDYN_BUILDERS, f"{name} imports exudyn"


@pytest.mark.parametrize("name", sorted(MODULES))
def test_only_figure_modules_import_matplotlib(name):
    uses = any(i.split(".")[0] == "matplotlib" for i in _imports(name, MODULES[name]))
    assert not uses or name in FIGURE_MODULES, f"{name} imports matplotlib"


@pytest.mark.parametrize("name", sorted(MODULES))
def test_no_star_imports(name):
    for node in ast.walk(MODULES[name]):
        if isinstance(node, ast.ImportFrom):
            assert all(alias.name != "*" for alias in node.names), name


@pytest.mark.parametrize("name", sorted(n for n in MODULES if n.startswith("fe/")))
def test_fe_never_imports_corunning(name):
    bad = {i for i in _imports(name, MODULES[name]) if _stage(i) == "corunning"}
    assert not bad, f"{name} imports {sorted(bad)}"


@pytest.mark.parametrize("name", sorted(MODULES))
def test_nothing_below_imports_cli_or_report(name):
    own = name.split("/")[0]
    if own in ("cli", "report") or name in ("__init__.py", "__main__.py"):
        return
    bad = {i for i in _imports(name, MODULES[name]) if _stage(i) in ("cli", "report")}
    assert not bad, f"{name} imports {sorted(bad)}"


@pytest.mark.parametrize("name", sorted(MODULES))
def test_stages_import_only_earlier_stages(name):
    own = name.split("/")[0]
    if own not in STAGES:
        return
    for i in _imports(name, MODULES[name]):
        other = _stage(i)
        if other is not None and other != own:
            assert STAGES.index(other) < STAGES.index(own), f"{name} imports {i}"


def test_importing_the_figure_modules_does_not_import_matplotlib():
    """matplotlib comes in through plotting/backend.py when a figure is drawn (fast CLI)."""
    import subprocess
    import sys

    code = (
        "import sys, exudyn_turnout.plotting, exudyn_turnout.plotting.studies, "
        "exudyn_turnout.plotting.wheel_rail; print('matplotlib' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
