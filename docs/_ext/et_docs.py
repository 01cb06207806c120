"""Pages of the documentation that are made from the package at build time.

Three generators, none of which runs anything slow:

- :func:`api_pages`: one page per package of the pipeline and one per module (the API
  reference). Each public name (listed in an ``__all__``) is documented once, on the page
  of the module that defines it, and listed by its package page in a summary table;
- :func:`example_pages`: one page per script in ``examples/`` (its docstring and its
  source; the scripts are not run: they take minutes);
- :func:`cli_reference`: the ``--help`` text of every ``exudyn-turnout`` command, from the
  parsers themselves (through :func:`exudyn_turnout.cli.main.main`).

This module imports neither Sphinx nor docutils at its top, so that the tests can call
the generators (``tests/test_docs_pages.py``); :func:`setup` registers them with Sphinx.
"""

from __future__ import annotations

import ast
import contextlib
import importlib
import importlib.util
import inspect
import io
import os
import pkgutil
import re
from functools import cache
from pathlib import Path

__all__ = [
    "ROOT",
    "STAGES",
    "api_pages",
    "cli_commands",
    "cli_reference",
    "example_pages",
    "plain_text_docstring",
    "public_names",
    "setup",
    "write_pages",
]

#: The repository (the folder holding ``docs/``, ``examples/`` and the package).
ROOT = Path(__file__).resolve().parents[2]

#: Packages and top-level modules of the API reference, in the order of the pipeline, each
#: with the line its page is titled with.
STAGES = {
    "exudyn_turnout": "the front door",
    "exudyn_turnout.inputs": "stage 1: turnout file, plan, routes, vehicle files",
    "exudyn_turnout.wheel_rail": "wheel/rail profiles, sections, contact geometry",
    "exudyn_turnout.corunning": "stages 2-3: Eqs 1-19, co-running parameters and tracks",
    "exudyn_turnout.receptance": "stage 4: receptance (FRF) data",
    "exudyn_turnout.fe": "stage 5: the FE reference of the turnout",
    "exudyn_turnout.passage": "stage 6: the passage, a vehicle through the turnout",
    "exudyn_turnout.studies": "studies: many passages from one file",
    "exudyn_turnout.report": "stage 7: the validation report",
    "exudyn_turnout.plotting": "figures",
    "exudyn_turnout.provenance": "provenance of every output",
}


# --- API reference ------------------------------------------------------------------------


@cache
def _source(modname: str) -> tuple[Path, ast.Module] | None:
    spec = importlib.util.find_spec(modname)
    if spec is None or spec.origin is None or not spec.origin.endswith(".py"):
        return None
    path = Path(spec.origin)
    return path, ast.parse(path.read_text(encoding="utf-8"))


def _absolute(modname: str, is_package: bool, node: ast.ImportFrom) -> str:
    if not node.level:
        return node.module or ""
    parts = modname.split(".")
    base = parts if is_package else parts[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


@cache
def _definer(modname: str, name: str) -> str | None:
    """The module whose source defines ``name`` as found in ``modname``, following imports."""
    found = _source(modname)
    if found is None:
        return None
    path, tree = found
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            if node.name == name:
                return modname
        elif isinstance(node, ast.Assign):
            for target in node.targets:
                if isinstance(target, ast.Name) and target.id == name:
                    return modname
        elif isinstance(node, ast.AnnAssign):
            if isinstance(node.target, ast.Name) and node.target.id == name:
                return modname
        elif isinstance(node, ast.ImportFrom):
            for alias in node.names:
                if (alias.asname or alias.name) == name:
                    source = _absolute(modname, path.name == "__init__.py", node)
                    if not source.startswith("exudyn_turnout"):
                        return None
                    inner = _definer(source, alias.name)
                    if inner is not None:
                        return inner
                    # a module imported by name (from package import module)
                    return None
    return None


@cache
def _modules() -> tuple[str, ...]:
    """Every module of the package but ``__main__`` and ``cli`` (see the CLI page)."""
    import exudyn_turnout

    names = ["exudyn_turnout"]
    for info in pkgutil.walk_packages(exudyn_turnout.__path__, "exudyn_turnout."):
        last = info.name.rsplit(".", 1)[-1]
        if last.startswith("_") or info.name.startswith("exudyn_turnout.cli"):
            continue
        names.append(info.name)
    return tuple(sorted(names))


def _is_package(modname: str) -> bool:
    return hasattr(importlib.import_module(modname), "__path__")


def public_names(modname: str) -> list[str]:
    """The names of a module's ``__all__`` (empty without one)."""
    return list(getattr(importlib.import_module(modname), "__all__", []))


@cache
def _canonical() -> dict[str, dict[str, str]]:
    """For every module: its public names -> the module whose page documents them."""
    modules = _modules()
    result: dict[str, dict[str, str]] = {}
    for modname in modules:
        module = importlib.import_module(modname)
        homes = {}
        for name in public_names(modname):
            home = _definer(modname, name)
            if home is None:  # e.g. the front door's names imported on first use
                obj = getattr(module, name)
                owner = getattr(obj, "__module__", None)
                if isinstance(owner, str) and owner in modules and hasattr(obj, "__qualname__"):
                    home = owner
                else:
                    lazy = getattr(module, "_LAZY", {}).get(name)
                    home = _definer(lazy, name) if lazy else None
            homes[name] = home if home in modules else modname
        result[modname] = homes
    return result


def _title(text: str, underline: str = "=") -> list[str]:
    return [text, underline * len(text), ""]


def _first_paragraph(text: str | None) -> str:
    """The first paragraph of a docstring as one line of reStructuredText."""
    lines = []
    for line in (text or "").strip().splitlines():
        if not line.strip():
            break
        lines.append(line.strip())
    summary = " ".join(plain_text_docstring(lines))
    return summary[:-1] if summary.endswith("::") else summary


def _data_comment(modname: str, name: str) -> str:
    """The ``#:`` comment of a module-level name (above its assignment or after it)."""
    found = _source(modname)
    if found is None:
        return ""
    path, tree = found
    source = path.read_text(encoding="utf-8").splitlines()
    for node in tree.body:
        targets = getattr(node, "targets", None) or [getattr(node, "target", None)]
        if any(isinstance(t, ast.Name) and t.id == name for t in targets):
            line = source[node.lineno - 1]
            if "#: " in line:
                return line.split("#: ", 1)[1].strip()
            comments = []
            k = node.lineno - 2
            while k >= 0 and source[k].lstrip().startswith("#:"):
                comments.insert(0, source[k].lstrip()[2:].strip())
                k -= 1
            return _first_paragraph("\n".join(comments))
    return ""


def _summary(full: str) -> str:
    modname, _, name = full.rpartition(".")
    if full in _modules():
        return _first_paragraph(importlib.import_module(full).__doc__)
    obj = getattr(importlib.import_module(modname), name)
    if isinstance(obj, type) or callable(obj):
        return _first_paragraph(inspect.getdoc(obj))
    return _data_comment(modname, name)


def _table(role: str, names: list[str]) -> list[str]:
    """A two-column table: each object linked, with the first paragraph of its docstring."""
    lines = [".. list-table::", "   :widths: 30 70", ""]
    for full in names:
        lines += [f"   * - :py:{role}:`~{full}`", f"     - {_summary(full) or ' '}"]
    return lines + [""]


def _documented_here(modname: str) -> list[str]:
    names = set()
    for homes in _canonical().values():
        names.update(name for name, home in homes.items() if home == modname)
    return sorted(names, key=lambda n: (n.lower(), n))


def _module_page(modname: str, tagline: str | None = None) -> str:
    members = _documented_here(modname)
    lines = _title(f"``{modname}``" + (f": {tagline}" if tagline else ""))
    lines += [f".. automodule:: {modname}", "   :no-members:", ""]
    if members:
        lines += _title("Contents", "-")
        lines += _table("obj", [f"{modname}.{name}" for name in members])
        for name in members:
            lines += [f".. autoany:: {modname}.{name}", ""]
    return "\n".join(lines) + "\n"


def _children(package: str) -> list[str]:
    prefix = package + "."
    return [m for m in _modules() if m.startswith(prefix) and "." not in m[len(prefix) :]]


def _package_page(package: str, tagline: str | None = None) -> str:
    lines = _title(f"``{package}``" + (f": {tagline}" if tagline else ""))
    lines += [f".. automodule:: {package}", "   :no-members:", ""]
    homes = _canonical()[package]
    if homes:
        lines += _title("Public names", "-")
        offer = (
            "``import exudyn_turnout as et``"
            if package == "exudyn_turnout"
            else (f"``from {package} import ...``")
        )
        lines += [
            f"What {offer} offers (its ``__all__``), each linked to the module that defines it.",
            "",
        ]
        ordered = sorted(homes.items(), key=lambda item: (item[0].lower(), item[0]))
        lines += _table("obj", [f"{home}.{name}" for name, home in ordered])
    here = _documented_here(package)
    if here:
        lines += _title("Defined in the package itself", "-")
        for name in here:
            lines += [f".. autoany:: {package}.{name}", ""]
    children = [] if package == "exudyn_turnout" else _children(package)
    if children:
        lines += _title("Modules", "-")
        lines += _table("mod", children)
        lines += [".. toctree::", "   :hidden:", ""]
        lines += [f"   {child}" for child in children]
        lines += [""]
    return "\n".join(lines) + "\n"


def api_pages() -> dict[str, str]:
    """The API reference: file name (under ``api/generated/``) -> reStructuredText.

    Returns
    -------
    dict
        One page per stage of :data:`STAGES` and one per module or package below them.
    """
    pages = {}
    for modname in _modules():
        stage = STAGES.get(modname)
        if _is_package(modname):
            pages[f"{modname}.rst"] = _package_page(modname, stage)
        else:
            pages[f"{modname}.rst"] = _module_page(modname, stage)
    return pages


# --- Examples -----------------------------------------------------------------------------


def _examples() -> list[Path]:
    return sorted((ROOT / "examples").glob("*.py"))


def example_pages() -> dict[str, str]:
    """The gallery: file name (under ``examples/generated/``) -> reStructuredText.

    Returns
    -------
    dict
        One page per ``examples/*.py``: its docstring, the data file of the same name if
        there is one (``monte_carlo_study.toml``), and its source.
    """
    pages = {}
    for script in _examples():
        tree = ast.parse(script.read_text(encoding="utf-8"))
        doc = ast.get_docstring(tree) or ""
        first, _, rest = doc.partition("\n")
        lines = _title(f"``{script.name}``")
        lines += [first.strip(), rest, ""]
        lines += [
            ".. note::",
            "",
            "   Not run when the documentation is built (a run takes minutes): run it yourself",
            f"   from the repository, ``python examples/{script.name} --help`` for its options.",
            "",
        ]
        rel = os.path.relpath(script, ROOT / "docs" / "examples" / "generated")
        for data in sorted(script.parent.glob(script.stem + ".*")):
            if data.suffix in (".toml", ".csv"):
                data_rel = os.path.relpath(data, ROOT / "docs" / "examples" / "generated")
                lines += _title(f"``{data.name}``", "-")
                lines += [
                    f".. literalinclude:: {data_rel}",
                    f"   :language: {'toml' if data.suffix == '.toml' else 'text'}",
                    "",
                ]
        lines += _title("Source", "-")
        lines += [f".. literalinclude:: {rel}", "   :language: python", "   :linenos:", ""]
        pages[f"{script.stem}.rst"] = "\n".join(lines) + "\n"
    return pages


# --- Command line -------------------------------------------------------------------------


def _help(argv: list[str]) -> str:
    from exudyn_turnout.cli.main import main

    out = io.StringIO()
    saved = {k: os.environ.get(k) for k in ("COLUMNS", "NO_COLOR", "PYTHON_COLORS")}
    os.environ.update(COLUMNS="90", NO_COLOR="1", PYTHON_COLORS="0")
    try:
        with contextlib.redirect_stdout(out):
            main([*argv, "--help"])
    finally:
        for key, value in saved.items():
            if value is None:
                os.environ.pop(key, None)
            else:
                os.environ[key] = value
    return out.getvalue()


_SUBCOMMANDS = re.compile(r"^positional arguments:\n\s+\{([\w,-]+)\}\s*$", re.MULTILINE)


def cli_commands(argv: tuple[str, ...] = ()) -> list[tuple[tuple[str, ...], str]]:
    """Every command of ``exudyn-turnout`` with its help text, the program itself first.

    Parameters
    ----------
    argv : tuple of str
        The command to start from (default: the program).

    Returns
    -------
    list of (tuple of str, str)
        (command words, ``--help`` output), depth first in the parsers' order.
    """
    text = _help(list(argv))
    found = [(argv, text)]
    match = _SUBCOMMANDS.search(text)
    if match:
        for sub in match.group(1).split(","):
            found += cli_commands((*argv, sub))
    return found


def cli_reference() -> str:
    """The command-line reference as reStructuredText (one section per command).

    Returns
    -------
    str
    """
    lines = []
    for words, text in cli_commands():
        title = " ".join(("exudyn-turnout", *words))
        lines += _title(f"``{title}``", "-" if words else "-")
        lines += [".. code-block:: text", ""]
        lines += [("   " + line).rstrip() for line in text.rstrip().splitlines()]
        lines += [""]
    return "\n".join(lines) + "\n"


# --- Docstrings as plain text ------------------------------------------------------------

_SPANS = re.compile(r"(``.+?``|`[^`]*`)")
_UNDERLINE = re.compile(r"^\s*([-=~^\"'`#*+])\1{2,}\s*$")


def plain_text_docstring(lines: list[str]) -> list[str]:
    """Read what a docstring writes as plain text the way a reader of ``help()`` does.

    The package's docstrings are written for ``help()`` and the source as much as for this
    site. Two plain-text habits of theirs are not reStructuredText, and are read here as
    they are meant (the docstrings themselves stay as they are):

    - ``|H|``, ``|F_x xi|``: an absolute value, not a substitution reference (docutils
      would stop on an undefined substitution): every ``|`` outside inline literals,
      literal blocks, directives and grid tables is escaped;
    - a section title whose underline is shorter than the title: the underline is drawn
      to the title's length.

    Parameters
    ----------
    lines : list of str
        The docstring's lines (as autodoc and napoleon hand them on).

    Returns
    -------
    list of str
        The same number of lines.
    """
    out = list(lines)
    block_indent = None  # indent of the line that opened a literal block or a directive
    in_table = False
    for i, line in enumerate(out):
        stripped = line.strip()
        indent = len(line) - len(line.lstrip())
        if block_indent is not None:
            if not stripped or indent > block_indent:
                continue
            block_indent = None
        if not stripped:
            in_table = False
            continue
        if stripped.startswith(("+-", "+=")):
            in_table = True
        if in_table:
            continue
        if _UNDERLINE.match(line) and i > 0 and out[i - 1].strip():
            title = out[i - 1].rstrip()
            if not _UNDERLINE.match(title) and len(stripped) < len(title.strip()):
                out[i] = " " * indent + stripped[0] * len(title.strip())
            continue
        if stripped.startswith(".. ") or stripped.endswith("::"):
            block_indent = indent
        if "|" in line and not stripped.startswith(".. "):
            parts = _SPANS.split(line)
            for k in range(0, len(parts), 2):  # the text between literals and roles
                parts[k] = re.sub(r"(?<!\\)\|", r"\\|", parts[k])
            out[i] = "".join(parts)
    return out


def _nearest(modname: str | None, classname: str | None, matches: list) -> list:
    """Of several targets of one name, the one nearest the referring module, if one is.

    Parameters
    ----------
    modname, classname : str or None
        Where the reference stands.
    matches : list of (str, object)
        The targets found (full name, entry).

    Returns
    -------
    list
        The one nearest target (most leading name parts in common with the referring
        module and class); none when two are equally near: the word stays plain text
        rather than a link to an unrelated object.
    """
    here = [*(modname or "").split("."), *((classname or "").split(".") if classname else [])]

    def shared(full: str) -> int:
        n = 0
        for a, b in zip(here, full.split(".")):
            if a != b:
                break
            n += 1
        return n

    scores = [shared(name) for name, _ in matches]
    best = max(scores)
    nearest = [m for m, s in zip(matches, scores) if s == best]
    return nearest if len(nearest) == 1 else []


# --- Sphinx -------------------------------------------------------------------------------


def write_pages(docs: Path) -> None:
    """Write the generated pages under ``docs`` (only files whose text changed).

    Parameters
    ----------
    docs : Path
        The documentation's source folder.
    """
    for folder, pages in (
        (docs / "api" / "generated", api_pages()),
        (docs / "examples" / "generated", example_pages()),
    ):
        folder.mkdir(parents=True, exist_ok=True)
        for stale in set(p.name for p in folder.glob("*.rst")) - set(pages):
            (folder / stale).unlink()
        for name, text in pages.items():
            path = folder / name
            if not path.exists() or path.read_text(encoding="utf-8") != text:
                path.write_text(text, encoding="utf-8")


def setup(app):
    """Sphinx extension: generate the pages, add ``autoany`` and ``cli-reference``.

    Parameters
    ----------
    app : sphinx.application.Sphinx

    Returns
    -------
    dict
    """
    from docutils import nodes
    from docutils.statemachine import StringList
    from sphinx.util.docutils import SphinxDirective

    class CliReference(SphinxDirective):
        """``.. cli-reference::``: the help of every command, from the parsers."""

        def run(self):
            node = nodes.section()
            node.document = self.state.document
            text = StringList(cli_reference().splitlines(), source="cli-reference")
            self.state.nested_parse(text, self.content_offset, node, match_titles=True)
            return node.children

    class AutoAny(SphinxDirective):
        """``.. autoany:: module.name``: the autodoc directive that fits the object."""

        required_arguments = 1

        def run(self):
            target = self.arguments[0]
            modname, _, name = target.rpartition(".")
            obj = getattr(importlib.import_module(modname), name)
            if isinstance(obj, type):
                kind = "autoexception" if issubclass(obj, BaseException) else "autoclass"
                options = (
                    [] if issubclass(obj, BaseException) else ["   :members:", "   :undoc-members:"]
                )
                if obj.__bases__ != (object,):
                    options.append("   :show-inheritance:")
            elif callable(obj) and hasattr(obj, "__code__") or _is_numba(obj):
                kind, options = "autofunction", []
            else:
                kind, options = "autodata", []
            text = StringList([f".. {kind}:: {target}", *options, ""], source=target)
            node = nodes.section()
            node.document = self.state.document
            self.state.nested_parse(text, self.content_offset, node)
            return node.children

    def generate(app):
        write_pages(Path(app.srcdir))

    def process_docstring(app, what, name, obj, options, lines):
        lines[:] = plain_text_docstring(lines)

    # Docstrings name modules and classes relative to their package (":mod:`.geometry`",
    # a type hint ``Contact``); Sphinx looks such a name up as a suffix over the whole
    # project and warns when two objects end in it. The nearest one to the referring
    # module is meant; a tie is left unlinked (see _nearest).
    from sphinx.domains.python import PythonDomain

    find_obj = PythonDomain.find_obj

    def find_nearest(self, env, modname, classname, name, type, searchmode=0):
        matches = find_obj(self, env, modname, classname, name, type, searchmode)
        if len(matches) > 1:
            matches = _nearest(modname, classname, matches)
        return matches

    if not getattr(find_obj, "_et_docs", False):
        find_nearest._et_docs = True
        PythonDomain.find_obj = find_nearest

    def resolve_reexport(app, env, node, contnode):
        """``exudyn_turnout.load_turnout``: a name offered by a package but documented in
        its defining module (``exudyn_turnout.inputs.turnout.load_turnout``) links there."""
        if node.get("refdomain") != "py":
            return None
        domain = env.get_domain("py")
        target = node.get("reftarget", "")
        modname, _, name = target.rpartition(".")
        home = _canonical().get(modname, {}).get(name)
        if home is not None and home != modname:
            return domain.resolve_xref(
                env, node["refdoc"], app.builder, node["reftype"], f"{home}.{name}", node, contnode
            )
        # ":func:`simulate_passage`" written in a module that does not define it: the one
        # object of that name nearest the referring module (none if two are as near)
        if "." in target or target.startswith("_"):
            return None
        matches = domain.find_obj(
            env, node.get("py:module"), node.get("py:class"), target, node["reftype"], 1
        )
        if len(matches) != 1:
            return None
        return domain.resolve_xref(
            env, node["refdoc"], app.builder, node["reftype"], matches[0][0], node, contnode
        )

    app.connect("missing-reference", resolve_reexport)
    app.add_directive("cli-reference", CliReference)
    app.add_directive("autoany", AutoAny)
    app.connect("builder-inited", generate)
    app.connect("autodoc-process-docstring", process_docstring, priority=600)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}


def _is_numba(obj) -> bool:
    return type(obj).__module__.startswith("numba") and hasattr(obj, "py_func")
