"""Every repository path, module and script the README (and CONTRIBUTING.md) names exists.

README.md names files a new user opens or runs: backticked repository paths
(``exudyn_turnout/...py``, ``validation/...md``, ``benchmarks/...py``, ``examples/...py``,
``tests/...py``, ``docs/...``), paths relative to the package (``passage/run.py``, the
layout section's way of naming a module), dotted modules (``exudyn_turnout.report.settings``),
relative links (``[...](validation/report/report.md)``) and commands
``python validation/X.py``. A file renamed or removed without the README following fails
here, with the name. CONTRIBUTING.md is held to the same (its paths and package paths).
Reads files only (no imports of the package): well under 2 s.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
CONTRIBUTING = ROOT / "CONTRIBUTING.md"
PACKAGE = ROOT / "exudyn_turnout"
#: top-level folders of the repository whose paths the README names
TOP = ("exudyn_turnout", "validation", "benchmarks", "examples", "tests", "docs")
#: paths the README names that a command writes, not the repository (the docs' build)
WRITTEN = ("docs/_build/",)


def _backticked(text: str) -> list[str]:
    """Inline code spans of a markdown text (fenced blocks left out)."""
    text = re.sub(r"```.*?```", "", text, flags=re.S)
    return re.findall(r"`([^`\n]+)`", text.replace("\n", " "))


def repo_paths(text: str) -> list[str]:
    """Backticked repository paths (a ``*`` glob allowed), link targets and scripts.

    Parameters
    ----------
    text : str
        A markdown text (README.md).

    Returns
    -------
    list of str
        Paths relative to the repository root, in order of appearance, without repeats.
    """
    found = []
    top = "|".join(TOP)
    for span in _backticked(text):
        for word in span.split():
            if re.fullmatch(rf"(?:{top})/[\w./*<>+-]*", word) and "<" not in word:
                found.append(word.rstrip("."))
    for target in re.findall(r"\]\(([^)#\s]+)\)", text):
        if "://" not in target:
            found.append(target)
    for script in re.findall(rf"\bpython (?:-m \S+ )?((?:{top})/[\w./-]+\.py)\b", text):
        found.append(script)  # "python validation/<script>.py", a placeholder, is left out
    return [p for p in dict.fromkeys(found) if not p.startswith(WRITTEN)]


def package_relative_paths(text: str) -> list[str]:
    """Backticked ``<sub-package>/<module>.py`` or ``<sub-package>/``: paths in the package.

    Parameters
    ----------
    text : str
        A markdown text (README.md).

    Returns
    -------
    list of str
        Paths relative to ``exudyn_turnout/``, without repeats.
    """
    subpackages = {p.name for p in PACKAGE.iterdir() if (p / "__init__.py").is_file()}
    found = []
    for span in _backticked(text):
        head = span.split("/", 1)[0]
        if head in subpackages and re.fullmatch(r"[\w/]+(?:\.py|/)", span):
            found.append(span)
    return list(dict.fromkeys(found))


def dotted_modules(text: str) -> list[str]:
    """Backticked dotted names ``exudyn_turnout.a.b`` (a call's arguments cut off).

    Parameters
    ----------
    text : str
        A markdown text (README.md).

    Returns
    -------
    list of str
        The dotted names, without repeats.
    """
    found = []
    for span in _backticked(text):
        match = re.match(r"(exudyn_turnout(?:\.\w+)+)", span)
        if match:
            found.append(match.group(1))
    return list(dict.fromkeys(found))


def _exists(path: str) -> bool:
    if "*" in path:
        return any(ROOT.glob(path))
    return (ROOT / path).exists()


def _resolves(dotted: str) -> bool:
    """A module or package, or a module's (or package's ``__init__``) top-level name."""
    parts = dotted.split(".")
    base = ROOT.joinpath(*parts)
    if base.with_suffix(".py").is_file() or (base / "__init__.py").is_file():
        return True
    owner = ROOT.joinpath(*parts[:-1])
    source = owner.with_suffix(".py") if owner.with_suffix(".py").is_file() else None
    if source is None and (owner / "__init__.py").is_file():
        source = owner / "__init__.py"
    if source is None:
        return False
    name = re.escape(parts[-1])
    pattern = rf"^(?:def|class) {name}\b|^{name}\b\s*[:=]|\b{name}\b.*# re-export|\"{name}\""
    return re.search(pattern, source.read_text(encoding="utf-8"), re.M) is not None


TEXT = README.read_text(encoding="utf-8")
#: (file, path) of every repository and package path README.md and CONTRIBUTING.md name
NAMED = [
    (doc.name, path)
    for doc in (README, CONTRIBUTING)
    for path in repo_paths(doc.read_text(encoding="utf-8"))
]
PACKAGE_NAMED = [
    (doc.name, path)
    for doc in (README, CONTRIBUTING)
    for path in package_relative_paths(doc.read_text(encoding="utf-8"))
]


def test_the_readme_names_paths():
    # the README at the time of writing names more than 40 repository paths, 6 scripts
    # run with python and 8 dotted modules: a parser finding none would pass vacuously
    assert len(repo_paths(TEXT)) >= 40
    assert len(package_relative_paths(TEXT)) >= 5
    assert len(dotted_modules(TEXT)) >= 5


def test_the_parsers_on_a_known_text():
    text = (
        "see `validation/a.md` and `exudyn_turnout/x/y.py`, run `python benchmarks/b.py "
        "--quick`; [r](validation/report/report.md), [d](#dev), `passage/run.py`, "
        "`exudyn_turnout.report.settings`, `exudyn_turnout.studies.run_study(s, e)`, "
        "open `docs/_build/html/index.html`\n"
        "```bash\npython examples/in_a_fence.py\n```\n"
    )
    assert repo_paths(text) == [
        "validation/a.md",
        "exudyn_turnout/x/y.py",
        "benchmarks/b.py",
        "validation/report/report.md",
        "examples/in_a_fence.py",
    ]
    assert package_relative_paths(text) == ["passage/run.py"]
    assert dotted_modules(text) == [
        "exudyn_turnout.report.settings",
        "exudyn_turnout.studies.run_study",
    ]


@pytest.mark.parametrize("doc, path", NAMED)
def test_repository_path_exists(doc, path):
    assert _exists(path), f"{doc} names {path}, which the repository does not have"


@pytest.mark.parametrize("doc, path", PACKAGE_NAMED)
def test_package_path_exists(doc, path):
    assert (PACKAGE / path).exists(), f"{doc} names {path}: no exudyn_turnout/{path}"


@pytest.mark.parametrize("dotted", dotted_modules(TEXT))
def test_dotted_name_resolves(dotted):
    assert _resolves(dotted), f"README.md names {dotted}: no such module or top-level name"


def test_every_python_command_runs_an_existing_script():
    # the fenced blocks too: "python validation/report.py" is in one
    scripts = re.findall(r"\bpython ((?:validation|benchmarks|examples)/[\w./-]+\.py)", TEXT)
    assert len(scripts) >= 5, scripts
    missing = sorted({s for s in scripts if not (ROOT / s).is_file()})
    assert not missing, f"README.md runs scripts that do not exist: {missing}"
