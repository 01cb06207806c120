"""The README's test counts stay true (issue 25: README numbers a test keeps true).

README.md, section "Development", states how many tests the suite has, how many are marked
``slow`` and how many ``-m "not slow"`` runs. This test collects the suite in a fresh
process (``pytest --collect-only -m slow``: one collection gives both counts) and checks
the README's numbers against it within :data:`MARGIN` (at least :data:`MIN_MARGIN`): tests
are added all the time, so an exact count would fail on every new test, while a README off
by more than the margin is stale. The README's own arithmetic (all = slow + not slow) is
checked exactly. Wall-clock times in the README are measurements with their date and
machine, not checked here (no timed assertions).
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"

#: Margin within which the README's counts must match the collected suite: 10 % of the
#: count, at least 5 tests (the slow tests are few).
MARGIN = 0.10
MIN_MARGIN = 5


def readme_counts(text: str) -> dict[str, int]:
    """The test counts the README's "Development" section states.

    Parameters
    ----------
    text : str
        README.md.

    Returns
    -------
    dict
        ``all`` (first "N tests" of the section), ``slow`` ("N tests marked `slow`") and,
        if stated, ``not_slow`` (the count given after ``-m "not slow"``).
    """
    section = re.search(r"^## Development\n(.*?)(?=^## )", text, re.S | re.M)
    assert section, "README.md: no '## Development' section"
    body = section.group(1)
    total = re.search(r"\(?(\d[\d,]*) tests\b", body)
    slow = re.search(r"(\d[\d,]*) tests marked `slow`", body)
    assert total and slow, "README.md, Development: no 'N tests' / 'N tests marked `slow`'"
    out = {"all": int(total.group(1).replace(",", "")), "slow": int(slow.group(1).replace(",", ""))}
    after = body[slow.end() :]
    not_slow = re.search(r"(\d[\d,]*) tests\b", after)
    if not_slow:
        out["not_slow"] = int(not_slow.group(1).replace(",", ""))
    return out


def collected_counts() -> dict[str, int]:
    """(slow, all) tests of the suite, from ``pytest --collect-only -q -m slow``."""
    env = dict(os.environ, PYTHONPATH=str(ROOT), PYTHONDONTWRITEBYTECODE="1")
    proc = subprocess.run(
        [sys.executable, "-m", "pytest", "--collect-only", "-q", "-m", "slow"]
        + ["-p", "no:cacheprovider", "tests"],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )
    last = proc.stdout.strip().splitlines()[-1] if proc.stdout.strip() else ""
    found = re.search(r"(\d+)/(\d+) tests? collected", last)
    assert proc.returncode == 0 and found, (proc.returncode, last, proc.stderr[-2000:])
    return {"slow": int(found.group(1)), "all": int(found.group(2))}


def test_readme_counts_are_parsed():
    # the wording of README.md at 04838fb ("2955 tests", "40 tests marked `slow`", "2915")
    text = (
        "## Development\n\n- Tests: `python -m pytest -n 2 -q` (2955 tests on 2 worker "
        'processes ... `python -m pytest -n 2 -q -m "not slow"` leaves out the 40 tests '
        "marked `slow` (long runs): 2915 tests, but ...\n\n## Validation report\n"
    )
    assert readme_counts(text) == {"all": 2955, "slow": 40, "not_slow": 2915}
    assert readme_counts("## Development\n1,234 tests; 5 tests marked `slow`\n## X\n") == {
        "all": 1234,
        "slow": 5,
    }


def test_readme_arithmetic():
    counts = readme_counts(README.read_text(encoding="utf-8"))
    if "not_slow" in counts:
        assert counts["not_slow"] == counts["all"] - counts["slow"], counts


@pytest.mark.slow
def test_readme_test_counts_match_the_suite():
    stated = readme_counts(README.read_text(encoding="utf-8"))
    got = collected_counts()
    for key in ("all", "slow"):
        assert abs(stated[key] - got[key]) <= max(MARGIN * got[key], MIN_MARGIN), (
            f"README.md states {stated[key]} tests ({key}), the suite has {got[key]}: "
            f"update the Development section"
        )
