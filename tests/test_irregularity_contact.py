"""Track irregularities enter the profile contact as the rail's own geometry would.

Issue 15's check: a dipped joint of total angle 2 alpha (Jenkins et al., Railway Engineering
Journal 3(1) 1974: each rail end dips with slope alpha towards the joint) given as an
irregularity gives the same contact forces as the same dip written into the rail's cross
sections (the contact table then holds the dipped rail). The two paths differ only in where
the dip enters: the kernel's lift (irregularity) or the tabulated gap (geometry), which the
table interpolates linearly between its x nodes (10 mm here).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from exudyn_turnout.inputs.irregularity import dipped_joint
from exudyn_turnout.inputs.vehicle import load_vehicle
from exudyn_turnout.passage.contact import profile as profile_contact
from exudyn_turnout.passage.run import simulate_passage
from exudyn_turnout.passage.settings import PassageError, PassageSettings

JOINT_X = 55.5  # m, on the plain track after the crossing (zone 3)
ANGLE = 0.006  # rad, 2 alpha: a moderate dipped joint (depth 1.5 mm over 1 m)
LENGTH = 1.0  # m


def _dipped_route_contact(turnout, vehicle, tmp_path):
    """The through route's contact with the right rail after the crossing dipped."""
    from exudyn_turnout.wheel_rail.packed_tables import pack_tables
    from exudyn_turnout.wheel_rail.sections import SectionGrid
    from exudyn_turnout.wheel_rail.tables import build_contact_table
    from exudyn_turnout.wheel_rail.turnout_sections import route_contact_tables

    wheel, setup = profile_contact.wheel_and_setup(turnout, vehicle)
    pairs = list(route_contact_tables(turnout, "through", wheel, setup))
    dip = dipped_joint(JOINT_X, ANGLE, LENGTH, rail="right")
    for k, (body, _table) in enumerate(pairs):
        if body.wheel == "right" and body.x_from <= JOINT_X <= body.x_to:
            x = np.unique(
                np.concatenate(
                    (
                        [body.x_from, body.x_to],
                        np.arange(JOINT_X - 0.6, JOINT_X + 0.6001, 0.01),
                    )
                )
            )
            plain = body.sections.z[0]
            z = plain[None, :] + dip.at_array(x)[1][:, None]  # right rail, vertical
            sections = SectionGrid(x=x, y=body.sections.y, z=z, name="dipped plain rail")
            dipped = build_contact_table(wheel, sections, setup.taping_line, cache_dir=tmp_path)
            pairs[k] = (replace(body, sections=sections), dipped)
            break
    else:
        raise AssertionError("no right-wheel body at the joint")
    bodies = [b for b, _ in pairs]
    packed = pack_tables(
        [t for _, t in pairs],
        [1 if b.wheel == "left" else -1 for b in bodies],
        [(0, 0)] * len(bodies),
        [(b.x_from, b.x_to) for b in bodies],
        names=[b.name for b in bodies],
    )
    return profile_contact.RouteContact(
        packed, tuple(b.wheel for b in bodies), tuple(b.rail for b in bodies), 0.0
    )


def test_dipped_joint_as_irregularity_equals_the_dip_in_the_rail(turnout, tmp_path, monkeypatch):
    vehicle = load_vehicle()
    settings = PassageSettings(layers=3, x_start=54.0, x_end=57.0)
    by_irregularity = simulate_passage(
        turnout,
        replace(settings, irregularity=dipped_joint(JOINT_X, ANGLE, LENGTH, "right")),
        vehicle="wheelset",
    )
    dipped = _dipped_route_contact(turnout, vehicle, tmp_path)
    monkeypatch.setattr(profile_contact, "route_contact", lambda *args, **kwargs: dipped)
    by_geometry = simulate_passage(turnout, settings, vehicle="wheelset")
    a, b = by_irregularity.columns, by_geometry.columns
    smooth = np.abs(a["x_m"] - JOINT_X) < 1.0
    peak_a = a["Fz_right_N"][smooth].max()
    peak_b = b["Fz_right_N"][smooth].max()
    assert peak_a > 1.3 * by_irregularity.summary["static_wheel_load_N"]  # a real impact
    # Same forces: the peak within 1 %, the histories within 2 % of the peak (the table
    # interpolates the dipped gap linearly between its 10 mm x nodes, the irregularity is
    # exact at the wheel's x).  At the dip's ends (slope changes of alpha = 3 mrad) the
    # table's path puts the contact on the slope change while it lies within r alpha = 1.4
    # mm ahead of the axle (along_x.lead_along_x: the wheel's radius), the irregularity at
    # the wheel's own x: there the histories are shifted by 1.4 mm (2.4 kN apart on their
    # steep flanks, measured), their extremes within 0.5 % of the peak (80 N measured)
    assert peak_a == pytest.approx(peak_b, rel=0.01)
    x = a["x_m"]
    ends = [JOINT_X - 0.5 * LENGTH, JOINT_X + 0.5 * LENGTH]
    near_ends = (np.abs(x - ends[0]) < 0.1) | (np.abs(x - ends[1]) < 0.1)
    assert np.max(np.abs(a["Fz_right_N"] - b["Fz_right_N"])[~near_ends]) < 0.02 * peak_b
    for end in ends:
        near = np.abs(x - end) < 0.1
        for extreme in (np.max, np.min):
            assert extreme(a["Fz_right_N"][near]) == pytest.approx(
                extreme(b["Fz_right_N"][near]), abs=0.005 * peak_b
            )
    assert np.max(np.abs(a["Fz_left_N"] - b["Fz_left_N"])) < 0.02 * peak_b


def test_irregularity_needs_the_profile_contact(turnout):
    settings = PassageSettings(
        x_start=54.0, x_end=55.0, contact="height-table", irregularity=dipped_joint(54.5, 0.006)
    )
    with pytest.raises(PassageError, match="irregularities need the profile contact"):
        simulate_passage(turnout, settings, vehicle="wheelset")


def test_cli_irregularity(tmp_path, capsys):
    import json

    from exudyn_turnout.cli.main import main

    spec = "joint:x=54.5,angle=0.006,length=1"
    out = tmp_path / "run"
    argv = ["simulate", "--vehicle", "wheelset", "--x-start", "54", "--x-end", "55", "--no-plot"]
    argv += ["--out", str(out)]
    assert main(argv + ["--irregularity", spec]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["settings"]["irregularity"] == spec
    assert summary["provenance"]["settings"]["irregularity"] == spec
    capsys.readouterr()
    assert main(argv + ["--irregularity", "dip:x=abc,depth=0.001,length=1"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--irregularity" in err
