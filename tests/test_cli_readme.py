"""The README's command-line block lists, for every command, exactly the options of its
``--help`` (the same set; the README is the source a new user reads first)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from exudyn_turnout.cli.main import main

README = Path(__file__).resolve().parents[1] / "README.md"


def _synopsis() -> dict[str, set[str]]:
    """Command words -> the options the README's block gives them."""
    block = re.search(r"## Command line\n\n```text\n(.*?)```", README.read_text(), re.S)
    assert block, "README: no command-line block"
    commands: dict[str, set[str]] = {}
    words = None
    for line in block.group(1).splitlines():
        if line.startswith("exudyn-turnout "):
            head = line[len("exudyn-turnout ") :].split()
            words = tuple(w for w in head[:2] if re.fullmatch(r"[a-z]+", w))
            if words and words[0] in ("frf", "params", "simulate", "fit", "validate", "study"):
                words = words[:1]
            commands[" ".join(words)] = set()
        assert words is not None
        commands[" ".join(words)] |= set(re.findall(r"(?<![\w-])--[a-z][a-z-]*", line))
    commands.pop("", None)
    return commands


def _help_options(words: list[str], capsys) -> set[str]:
    """The options ``--help`` lists (its option lines, not options named in prose)."""
    assert main([*words, "--help"]) == 0
    text = capsys.readouterr().out
    found = re.findall(r"^\s{2}(?:-\w(?: \S+)?, )?(--[a-z][a-z-]*)", text, re.M)
    return set(found) - {"--help"}


@pytest.mark.parametrize("words", sorted(_synopsis()))
def test_readme_synopsis_has_the_options_of_help(words, capsys):
    readme = _synopsis()[words] - {"--version"}
    helped = _help_options(words.split(), capsys)
    assert readme == helped, (
        f"{words}: only in README {sorted(readme - helped)}, only in --help "
        f"{sorted(helped - readme)}"
    )
