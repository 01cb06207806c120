"""``fit`` refuses a bad ``--route`` or ``--rails`` before any FE work (one line, exit 2).

Before, ``--route nowhere`` first computed FE receptances and then failed with "no rail of
zone 1 has an FE rail at x = -4.5 m" (naming neither the option nor the route), and
``--rails r3`` for a zone without a check rail failed after its progress line.
"""

from __future__ import annotations

import pytest

from exudyn_turnout.cli.main import main


@pytest.mark.parametrize(
    "options, message",
    [
        (["--route", "nowhere"], "--route nowhere: uic60_760_1_15.toml has no [layout.slots."),
        (["--route", "divergng"], "did you mean 'diverging'?"),
        (["--rails", "r3", "--positions", "10"], "--rails r3: not active in zone 1"),
        (["--rails", "r1", "r3"], "--rails r3: not active in zone 1"),
    ],
)
def test_bad_route_or_rails_before_the_fe(tmp_path, capsys, options, message):
    out = tmp_path / "f.toml"
    assert main(["fit", "--coarse", "--out", str(out), *options]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    # one line: no "zone 1: FE receptances ..." progress line came before the error
    assert len(err) == 1 and message in err[0], err
    assert not out.exists()
