"""Every public function and class has a numpydoc docstring (python-control's rule).

Public: the names in a module's ``__all__`` that the module defines, and their public
methods. A function's docstring has a ``Parameters`` section naming every parameter (but
``self``/``cls``), and a ``Returns`` (or ``Yields``) section unless it returns None. A
class has a docstring. Read from the source with ``ast``: nothing is imported.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "exudyn_turnout"


def _all_names(tree: ast.Module) -> list[str]:
    """Names of ``__all__ = [...]`` and every later ``__all__ += [...]``."""
    names: list[str] = []
    for node in tree.body:
        if isinstance(node, ast.Assign):
            targets = node.targets
        elif isinstance(node, ast.AugAssign):
            targets = [node.target]
        else:
            continue
        if any(isinstance(t, ast.Name) and t.id == "__all__" for t in targets):
            if isinstance(node.value, (ast.List, ast.Tuple)):
                names += [e.value for e in node.value.elts if isinstance(e, ast.Constant)]
    return names


def _sections(doc: str) -> dict[str, str]:
    """numpydoc sections: title -> body text."""
    out, title, lines = {}, None, doc.splitlines()
    for i, line in enumerate(lines):
        if i + 1 < len(lines) and re.fullmatch(r"\s*-{3,}\s*", lines[i + 1]) and line.strip():
            title = line.strip()
            out[title] = ""
        elif title is not None and not re.fullmatch(r"\s*-{3,}\s*", line):
            out[title] += line + "\n"
    return out


def _parameter_names(fn: ast.FunctionDef) -> list[str]:
    args = fn.args
    names = [a.arg for a in args.posonlyargs + args.args + args.kwonlyargs]
    names += [f"*{args.vararg.arg}"] if args.vararg else []
    names += [f"**{args.kwarg.arg}"] if args.kwarg else []
    return [n for n in names if n not in ("self", "cls")]


def _returns_none(fn: ast.FunctionDef) -> bool:
    if fn.returns is not None:
        return isinstance(fn.returns, ast.Constant) and fn.returns.value is None
    return not any(isinstance(n, ast.Return) and n.value is not None for n in ast.walk(fn))


def _problems(fn: ast.FunctionDef, where: str) -> list[str]:
    doc = ast.get_docstring(fn)
    if not doc:
        return [f"{where}: no docstring"]
    out = []
    sections = _sections(doc)
    names = _parameter_names(fn)
    if names:
        body = sections.get("Parameters", "")
        documented = set()
        for line in body.splitlines():
            if line and not line.startswith((" " * 8, "\t")):
                head = line.split(":")[0]
                documented.update(n.strip() for n in head.split(","))
        missing = [n for n in names if n.lstrip("*") not in {d.lstrip("*") for d in documented}]
        if missing:
            out.append(f"{where}: Parameters section lacks {', '.join(missing)}")
    if not _returns_none(fn) and not {"Returns", "Yields"} & set(sections):
        out.append(f"{where}: no Returns section")
    return out


def _public_items():
    for path in sorted(PACKAGE.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        names = set(_all_names(tree))
        module = path.relative_to(PACKAGE).as_posix()
        for node in tree.body:
            if getattr(node, "name", None) in names:
                yield module, node


ITEMS = list(_public_items())


@pytest.mark.parametrize("module,node", ITEMS, ids=[f"{m}:{n.name}" for m, n in ITEMS])
def test_public_api_has_numpydoc(module, node):
    where = f"{module}:{node.name}"
    problems = []
    if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
        problems += _problems(node, where)
    elif isinstance(node, ast.ClassDef):
        if not ast.get_docstring(node):
            problems.append(f"{where}: class without docstring")
        for item in node.body:
            if isinstance(item, ast.FunctionDef) and not item.name.startswith("_"):
                is_property = any(
                    isinstance(d, ast.Name) and d.id == "property" for d in item.decorator_list
                )
                if is_property:
                    if not ast.get_docstring(item):
                        problems.append(f"{where}.{item.name}: property without docstring")
                else:
                    problems += _problems(item, f"{where}.{item.name}")
    assert not problems, "\n".join(problems)


def test_every_module_declares_its_public_api():
    missing = []
    for path in sorted(PACKAGE.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        has_public = any(
            isinstance(n, (ast.FunctionDef, ast.ClassDef)) and not n.name.startswith("_")
            for n in tree.body
        )
        if has_public and not _all_names(tree):
            missing.append(path.relative_to(PACKAGE).as_posix())
    assert not missing, f"modules without __all__: {missing}"
