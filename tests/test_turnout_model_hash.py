"""``turnout_model_sha256`` covers every section the FE and co-running models are built from.

The hash (corunning/fitted.py) ties a fitted parameter file to the turnout it was fitted to.
It must change with any value of :data:`MODEL_SECTIONS` (the check rail's L-bracket in the
FE and the co-running check rail among them) and must not change with comments, layout of
the text or the sections the models do not read (its docstring).
"""

from __future__ import annotations

import copy
import dataclasses
import hashlib
import json
import re
from typing import Any

import pytest

from exudyn_turnout.corunning.fitted import MODEL_SECTIONS, read_fitted, turnout_model_sha256
from exudyn_turnout.inputs.turnout import default_turnout_path, load_turnout

FITTED = default_turnout_path().with_name("uic60_760_1_15_fitted.toml")


def _bump(value: Any) -> Any:
    """The first number found in ``value`` (depth first) changed by 1 %: a copy."""
    if isinstance(value, bool):
        return not value
    if isinstance(value, (int, float)):
        return value * 1.01 + 1
    if isinstance(value, str):
        return value + "x"
    if isinstance(value, list):
        return [_bump(value[0])] + value[1:]
    if isinstance(value, dict):
        key = sorted(value)[0]
        return {**value, key: _bump(value[key])}
    raise TypeError(type(value))


def _with(turnout, path: str, value: Any):
    raw = copy.deepcopy(dict(turnout.raw))
    head, _, sub = path.partition(".")
    if sub:
        raw[head] = {**raw[head], sub: value}
    else:
        raw[head] = value
    return dataclasses.replace(turnout, raw=raw)


def _get(turnout, path: str) -> Any:
    head, _, sub = path.partition(".")
    return turnout.raw[head][sub] if sub else turnout.raw[head]


def test_check_rail_tables_are_model_sections():
    assert "check_rail.support" in MODEL_SECTIONS
    assert "check_rail.co_running" in MODEL_SECTIONS


@pytest.mark.parametrize("section", MODEL_SECTIONS)
def test_every_model_section_changes_the_hash(section):
    turnout = load_turnout()
    base = turnout_model_sha256(turnout)
    changed = _with(turnout, section, _bump(_get(turnout, section)))
    assert turnout_model_sha256(changed) != base


def test_each_check_rail_field_changes_the_hash():
    turnout = load_turnout()
    base = turnout_model_sha256(turnout)
    for sub in ("support", "co_running"):
        table = _get(turnout, f"check_rail.{sub}")
        for key in table:
            edited = _with(turnout, f"check_rail.{sub}", {**table, key: _bump(table[key])})
            assert turnout_model_sha256(edited) != base, (sub, key)
        added = _with(turnout, f"check_rail.{sub}", {**table, "model": "table1"})
        assert turnout_model_sha256(added) != base


@pytest.mark.parametrize(
    "path",
    ["routes", "regions", "report", "wheel_rail", "published", "turnout"],
)
def test_other_sections_keep_the_hash(path):
    turnout = load_turnout()
    changed = _with(turnout, path, _bump(_get(turnout, path)))
    assert turnout_model_sha256(changed) == turnout_model_sha256(turnout)


def test_check_rail_contact_fields_keep_the_hash():
    turnout = load_turnout()
    check = dict(turnout.raw["check_rail"])
    for key in ("clearance", "flare_length", "flare_opening", "flare_shape"):
        edited = {**check, key: _bump(check[key])}
        changed = dataclasses.replace(turnout, raw={**turnout.raw, "check_rail": edited})
        assert turnout_model_sha256(changed) == turnout_model_sha256(turnout), key


def test_comments_and_whitespace_keep_the_hash(tmp_path):
    text = default_turnout_path().read_text()
    # drop every full-line comment, pad every "key = value" with spaces, add blank lines
    edited = "\n".join(
        "" if line.lstrip().startswith("#") else re.sub(r"^(\w+) = ", r"\1   =   ", line)
        for line in text.splitlines()
    )
    assert edited != text
    path = tmp_path / "uic60_760_1_15.toml"
    path.write_text("# a new comment\n\n" + edited + "\n\n")
    assert turnout_model_sha256(load_turnout(path)) == turnout_model_sha256(load_turnout())


def test_a_file_edit_of_the_support_changes_the_hash(tmp_path):
    text = default_turnout_path().read_text()
    assert text.count("k_roll = 0.5e6") == 1
    path = tmp_path / "uic60_760_1_15.toml"
    path.write_text(text.replace("k_roll = 0.5e6", "k_roll = 0.6e6"))
    assert turnout_model_sha256(load_turnout(path)) != turnout_model_sha256(load_turnout())


def test_a_turnout_without_check_rail_tables_keeps_its_former_hash():
    """Without the sub-tables the hash is the one of the seven top-level sections alone (the
    definition before the check-rail tables were added, commit 58cdefc)."""
    turnout = load_turnout()
    check = {k: v for k, v in turnout.raw["check_rail"].items() if k == "clearance"}
    bare = dataclasses.replace(turnout, raw={**turnout.raw, "check_rail": check})
    former = {name: bare.raw.get(name) for name in MODEL_SECTIONS if "." not in name}
    text = json.dumps(former, sort_keys=True, separators=(",", ":"), default=repr)
    assert turnout_model_sha256(bare) == hashlib.sha256(text.encode("utf-8")).hexdigest()


def test_packaged_fitted_file_matches_the_packaged_turnout():
    turnout = load_turnout()
    fitted = read_fitted(FITTED, turnout)
    assert fitted.provenance["turnout_model_sha256"] == turnout_model_sha256(turnout)
