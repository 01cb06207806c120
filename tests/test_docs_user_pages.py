"""The hand-written pages a new user reads agree with the code (``docs/*.rst``, formats).

- every ``exudyn-turnout ...`` command shown names a real command and only its options;
- the API reference's stage labels carry the numbers of the pipeline page's stages;
- the turnout page documents every section of a turnout file and every key of the
  check rail's tables (``[check_rail]``, ``[check_rail.support]``,
  ``[check_rail.co_running]``), as the readers know them;
- the getting-started page is in the table of contents.
"""

from __future__ import annotations

import importlib.util
import re
import shlex
from pathlib import Path

import pytest

from exudyn_turnout.inputs.check_rail import CHECK_RAIL_KEYS, CO_RUNNING_MODELS
from exudyn_turnout.inputs.turnout import SECTIONS

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
#: the pages written by hand (the API and gallery pages are generated)
PAGES = sorted(p for p in DOCS.rglob("*.rst") if "generated" not in p.parts)


def _load_et_docs():
    spec = importlib.util.spec_from_file_location("et_docs", DOCS / "_ext" / "et_docs.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


et_docs = _load_et_docs()


@pytest.fixture(scope="module")
def commands() -> dict[tuple[str, ...], str]:
    return dict(et_docs.cli_commands())


def _shown_commands() -> list[tuple[str, str]]:
    """(page, command line) of every ``exudyn-turnout`` command in a literal or code block."""
    out = []
    for page in PAGES:
        text = page.read_text(encoding="utf-8")
        # inline literals may wrap over lines: join the paragraph's lines first
        joined = re.sub(r"\n[ \t]*", " ", text)
        for match in re.finditer(r"``(exudyn-turnout [^`]+)``", joined):
            out.append((page.name, match.group(1)))
        for line in text.splitlines():
            stripped = line.strip()
            if stripped.startswith("exudyn-turnout "):
                out.append((page.name, stripped))
    return out


def test_pages_show_commands():
    shown = _shown_commands()
    assert len(shown) >= 10, shown
    assert any("quickstart" in page for page, _ in shown)


@pytest.mark.parametrize("page, line", _shown_commands())
def test_every_shown_command_exists_with_its_options(commands, page, line):
    words = shlex.split(line.replace("...", ""))[1:]
    command: tuple[str, ...] = ()
    for word in words:
        if (*command, word) in commands:
            command = (*command, word)
        else:
            break
    assert command or not words or words[0].startswith("-"), f"{page}: {line}"
    help_text = commands[command]
    if "..." in line and not command:  # "exudyn-turnout ... --turnout FILE": some command
        help_text = "\n".join(commands.values())
    for option in re.findall(r"(?<![\w-])--[a-z][a-z0-9-]*", line):
        assert re.search(rf"(?<![\w-]){re.escape(option)}\b", help_text), (
            f"{page}: `{line}`: exudyn-turnout {' '.join(command)} has no {option}"
        )


def test_api_stage_labels_follow_the_pipeline_page():
    pipeline = (DOCS / "pipeline.rst").read_text(encoding="utf-8")
    headings = dict(re.findall(r"^(\d)\. (.+)\n-+$", pipeline, re.M))
    assert sorted(headings) == [str(i) for i in range(1, 8)], headings
    numbered = 0
    for label in et_docs.STAGES.values():
        found = re.match(r"stages? (\d)(?:-(\d))?: (.*)", label)
        if not found:
            continue
        numbered += 1
        first, last, text = found.groups()
        for n in range(int(first), int(last or first) + 1):
            words = {w for w in re.findall(r"[a-z]+", headings[str(n)].lower()) if len(w) > 2}
            assert words & set(re.findall(r"[a-z]+", text.lower())), (label, headings[str(n)])
    assert numbered >= 6


def test_turnout_page_documents_every_section_and_check_rail_key():
    page = (DOCS / "formats" / "turnout.rst").read_text(encoding="utf-8")
    for section in SECTIONS:
        assert f"``[{section}" in page or f"``[[{section}" in page, section
    for table in ("check_rail.support", "check_rail.co_running"):
        assert f"``[{table}]``" in page, table
    support = ("height", "k_roll", "c_roll")
    co_running = ("rail", "x", "static_stiffness", "resonance_frequency")
    co_running += ("resonance_stiffness", "model")
    plain = tuple(k for k in CHECK_RAIL_KEYS if k not in ("support", "co_running"))
    assert len(plain) == len(CHECK_RAIL_KEYS) - 2  # the two tables are checked above
    for key in plain + support + co_running:
        assert f"``{key}``" in page, key
    for model in CO_RUNNING_MODELS:
        assert f'``"{model}"``' in page, model


def test_support_keys_on_the_page_are_the_readers():
    """The support keys the page lists are the fields the reader accepts (no more)."""
    from exudyn_turnout.inputs.check_rail import CheckRailSupport, support_from_section

    fields = set(CheckRailSupport.__dataclass_fields__)
    assert fields == {"height", "k_roll", "c_roll"}
    with pytest.raises(ValueError, match="is not a field"):
        support_from_section({"support": {"roll": 1.0}})


def test_getting_started_is_in_the_contents():
    index = (DOCS / "index.rst").read_text(encoding="utf-8")
    toctree = index.split(".. toctree::", 1)[1]
    assert re.search(r"^\s+quickstart$", toctree, re.M)
    assert (DOCS / "quickstart.rst").is_file()


def test_examples_index_describes_every_example():
    index = (DOCS / "examples" / "index.rst").read_text(encoding="utf-8")
    for script in sorted((ROOT / "examples").glob("*.py")):
        assert f":doc:`generated/{script.stem}`" in index, script.name
