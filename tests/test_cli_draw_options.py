"""``draw passage`` refuses a bad ``--scale`` or x range before running (one line, exit 2).

Before, ``--scale -1`` drew the displacements upside down with exit 0, and a reversed x range
ran into the passage and ended as a failed run (exit 3) instead of bad input (exit 2).
"""

from __future__ import annotations

import pytest

from exudyn_turnout.cli.main import main


@pytest.mark.parametrize(
    "options, message",
    [
        (["--scale", "-1"], "--scale must be > 0"),
        (["--scale", "0"], "--scale must be > 0"),
        (["--x-start", "50", "--x-end", "40"], "with --x-start < --x-end"),
        (["--x-start", "-50", "--x-end", "1"], "must lie within the turnout (-5 to 60 m)"),
        (["--x-end", "70"], "must lie within the turnout (-5 to 60 m)"),
    ],
)
def test_bad_passage_options(tmp_path, capsys, options, message):
    out = tmp_path / "p.gif"
    assert main(["draw", "passage", *options, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0], err
    assert not out.exists()
