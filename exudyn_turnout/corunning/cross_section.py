"""The springs of the co-running cross-section (Figs 2, 3): pure data, no Exudyn.

The Exudyn builder (:mod:`exudyn_turnout.corunning.track`) adds one ``CartesianSpringDamper`` per
item of :func:`cross_section_springs`, and the model drawing
(:mod:`exudyn_turnout.plotting.model`) draws the same list, so the figure shows what is built.
"""

from __future__ import annotations

from dataclasses import dataclass

from exudyn_turnout.corunning.parameters import CoRunningParameters
from exudyn_turnout.inputs.turnout import RAIL_SLOTS

__all__ = ["CrossSectionSpring", "cross_section_springs"]


@dataclass(frozen=True)
class CrossSectionSpring:
    """One spring-damper of the cross-section: its ends and entry names (y, z)."""

    name: str  #: "ballast_z1", "ballast_z2", "ballast_y", "pad_rj" or "layer_rj"
    sleeper_y: float | None  #: m, attachment on the sleeper (from its centre); None: not on it
    ground_y: float | None  #: m, attachment on the ground; None: not on it
    nodes: tuple[str, ...]  #: names of node ends ("r1", "m0_r1")
    k: tuple[str | None, str | None]  #: entry names for y and z stiffness
    c: tuple[str | None, str | None]  #: entry names for y and z damping


def cross_section_springs(params: CoRunningParameters) -> list[CrossSectionSpring]:
    """Every spring-damper of a zone's cross-section, in the order the builder adds them.

    Parameters
    ----------
    params : CoRunningParameters
        The zone's parameter set (its zone gives rail, ballast and sleeper positions).

    Returns
    -------
    list of CrossSectionSpring
        The two vertical ballast springs, the lateral ballast spring, then per active rail
        its pad and, for three layers, its extra layer.
    """
    zone, out = params.zone, []
    for ballast, y_b in zip((1, 2), zone.ballast_y):
        out.append(
            CrossSectionSpring(
                f"ballast_z{ballast}",
                y_b - zone.sleeper_y,
                y_b,
                (),
                (None, f"k_tg{ballast}_z"),
                (None, f"c_tg{ballast}_z"),
            )
        )
    out.append(
        CrossSectionSpring("ballast_y", 0.0, zone.sleeper_y, (), ("k_tg_y", None), ("c_tg_y", None))
    )
    for rail in (r for r in RAIL_SLOTS if r in params.active_rails):
        j = rail[1:]
        out.append(
            CrossSectionSpring(
                f"pad_{rail}",
                zone.rail_y[rail] - zone.sleeper_y,
                None,
                (rail,),
                (f"k_rt{j}_y", f"k_rt{j}_z"),
                (f"c_rt{j}_y", f"c_rt{j}_z"),
            )
        )
        if params.layers == 3:
            out.append(
                CrossSectionSpring(
                    f"layer_{rail}",
                    None,
                    None,
                    (rail, f"m0_{rail}"),
                    (f"k_0{j}_y", f"k_0{j}_z"),
                    (f"c_0{j}_y", f"c_0{j}_z"),
                )
            )
    return out
