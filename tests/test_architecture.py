"""The package's import rules, read from the source (no module is imported here).

- only the Exudyn builders import exudyn;
- only plotting and figure modules import matplotlib;
- ``fe/`` never imports ``corunning/`` (the FE reference stays independent of the model it
  judges);
- nothing imports ``cli/`` or ``report/`` from below (they are the top of the pipeline);
- no star imports;
- no import circles, imports inside functions counted (one exception: ``Receptance.plot``
  delegating to plotting);
- no private (underscore) name imported from another module;
- the passage's track implementations never import each other, and only the passage's
  dispatch (``passage/run.py``) imports the height-table contact or knows every track.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "exudyn_turnout"

#: Modules allowed to import exudyn: they build Exudyn systems.
EXUDYN_BUILDERS = {
    "corunning/track.py",
    "passage/common.py",  # QuietExudyn: Exudyn's console switches during a solve
    "passage/vehicle/wheelset.py",
    "passage/vehicle/builder.py",
    "passage/vehicle/analysis.py",
    "passage/vehicle/body_sensors.py",
    "passage/vehicle/track_frame.py",
    "passage/vehicle/steady_curving.py",
    "passage/corunning_track/wheelset.py",
    "passage/corunning_track/vehicle.py",
    "passage/corunning_track/vehicle_system.py",
    "passage/corunning_track/relax.py",
    "passage/corunning_track/carry_over.py",
    "passage/corunning_track/stepper.py",  # reads a built system, writes its final state
    "passage/fe_track/wheelset.py",
    "passage/fe_track/vehicle.py",
    "passage/hunting.py",
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


# --- the import graph, imports inside functions counted -----------------------------------

#: Import circles allowed, as sets of modules: ``Receptance.plot`` delegates to plotting,
#: whose receptance figure takes a Receptance (python-control's ``.plot()`` pattern).
ALLOWED_CIRCLES = [{"receptance.py", "plotting/curves.py"}]


def _module_file(dotted: str) -> str | None:
    """The package file of a dotted module name, or None (not a module of the package)."""
    parts = dotted.split(".")
    if parts[0] != "exudyn_turnout":
        return None
    rel = "/".join(parts[1:])
    for candidate in (f"{rel}.py", f"{rel}/__init__.py" if rel else "__init__.py"):
        if candidate in MODULES:
            return candidate
    return None


def _edges(name: str, tree: ast.Module) -> set[str]:
    """Package modules that module ``name`` imports, anywhere in it: ``from pkg import mod``
    is an edge to ``pkg/mod.py`` (not to ``pkg/__init__.py``), ``from mod import name`` one
    to ``mod.py``."""
    parts = ["exudyn_turnout"] + name[:-3].split("/")
    package = parts[:-1] if parts[-1] != "__init__" else parts[:-1]
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            targets = [_module_file(alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            stem = node.module or ""
            if node.level:
                base = package[: len(package) - node.level + 1]
                stem = ".".join(base + ([node.module] if node.module else []))
            targets = [_module_file(f"{stem}.{a.name}") or _module_file(stem) for a in node.names]
        else:
            continue
        out.update(t for t in targets if t is not None and t != name)
    return out


GRAPH = {name: _edges(name, tree) for name, tree in MODULES.items()}


def _strongly_connected(graph: dict[str, set[str]]) -> list[set[str]]:
    """Tarjan's strongly connected components of size > 1 (the import circles)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out: list[set[str]] = []
    counter = [0]

    def visit(v: str) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = set()
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.add(w)
                if w == v:
                    break
            if len(component) > 1:
                out.append(component)

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_circle_finder_finds_a_circle():
    """The checker itself: a -> b -> c -> a is one circle, d hangs off it."""
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert _strongly_connected(graph) == [{"a", "b", "c"}]


def test_no_import_circles():
    circles = [c for c in _strongly_connected(GRAPH) if c not in ALLOWED_CIRCLES]
    assert not circles, f"import circles: {[sorted(c) for c in circles]}"


@pytest.mark.parametrize("name", sorted(MODULES))
def test_no_private_name_imported_from_another_module(name):
    bad = []
    for node in ast.walk(MODULES[name]):
        if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("exudyn_turnout"):
            bad += [
                f"{node.module}.{a.name}"
                for a in node.names
                if a.name.startswith("_") and not a.name.startswith("__")
            ]
    assert not bad, f"{name} imports private names {bad}"


TRACK_IMPLEMENTATIONS = ("passage/corunning_track/", "passage/fe_track/")


@pytest.mark.parametrize("name", sorted(n for n in MODULES if n.startswith(TRACK_IMPLEMENTATIONS)))
def test_track_implementations_do_not_import_each_other(name):
    own = next(t for t in TRACK_IMPLEMENTATIONS if name.startswith(t))
    others = [t for t in TRACK_IMPLEMENTATIONS if t != own]
    bad = {m for m in GRAPH[name] if m.startswith(tuple(others))}
    assert not bad, f"{name} imports {sorted(bad)}"


def test_only_the_dispatch_knows_every_track_and_the_height_table_contact():
    """``passage/run.py`` is the one module importing both tracks and the height-table
    contact; nothing in the passage stage below it imports it."""
    fenced = "passage/contact/height_table.py"
    users = {n for n, edges in GRAPH.items() if fenced in edges}
    assert users == {"passage/run.py"}, users
    both = {
        n
        for n, edges in GRAPH.items()
        if all(any(m.startswith(t) for m in edges) for t in TRACK_IMPLEMENTATIONS)
    }
    assert both == {"passage/run.py"}, both
    below = {n for n in MODULES if n.startswith("passage/") and "passage/run.py" in GRAPH[n]} - {
        "passage/__init__.py"
    }
    assert not below, f"{sorted(below)} import the dispatch"
