"""The co-running check rail derived from the FE check rail on its L-bracket (issue 23).

Eqs 1-19 treat a check rail like a running rail: slot r3 becomes a lumped rail mass
(Eq 16, ~109 kg for the UIC60-760-1:15) on a lateral pad (Eq 13 with Table 1's stiff check
pad, 120 MN/m) on the cross-section's sleeper. Its lateral static stiffness at the
gauge corner is then 58 MN/m where the FE check rail on its bracket gives 16-44 MN/m, and
it is 3-5x stiffer than the FE at 100-300 Hz. Here its lateral entries are derived instead
from the FE check rail's lateral receptance at the gauge corner, stored per position x in
the turnout file (``[check_rail.co_running]``, written by
:mod:`exudyn_turnout.fe.check_rail_receptance`): static stiffness K(x), the frequency f_r(x)
of the check rail's lateral resonance on its bracket and the dynamic stiffness K_r(x) =
1 / max |H| there. Step by step (each a pure function below):

1. **Pad stiffness** (:func:`check_rail_pad_stiffness`): in the co-running cross-section
   the lateral load path of a rail is a chain of springs: the extra layer k_0,y (three
   layers), the pad k_rt,y and the sleeper's lateral ballast spring k_tg,y
   (:func:`exudyn_turnout.corunning.modal.assemble_track_matrices`: the lateral springs
   couple no other coordinate). Its static compliance is 1/k_0,y + 1/k_rt,y + 1/k_tg,y;
   with the paper's third-layer rule k_0,y = 5 k_rt,y (Sec. 3.2, ``[extra_layer]``) and
   k_tg,y of Eq 13 (shared with the running rails, unchanged), k_rt,y follows from
   K(x) in closed form. The static stiffness of the co-running check rail is then the
   FE's at every x of the table.
2. **Participating mass** (:func:`check_rail_mass`): the rail mass on its pad resonates at
   f_r: m_r = k_rt,y / (2 pi f_r)^2 (two layers), minus m_0 with three layers (the stiff
   layer, 5 k_rt,y, carries m_0 along at that frequency). The sleeper stands still there
   (its mass, ~900 kg, is 30x the rail's). Masses are constant within a zone, as in the
   paper: the median over the table. The co-running rail is one mass for both directions
   (a 2-D mass point): its vertical value changes too. The check rail carries no vertical
   wheel load (its contact is the back of the flange, lateral only, ``check`` pairs of the
   routes), so it is set for the direction it is loaded in.
3. **Pad damping** (:func:`check_rail_pad_damping`): at the resonance of a mass on a spring
   and dashpot the dynamic stiffness is the dashpot's alone, 2 pi f_r c: c_rt,y = K_r /
   (2 pi f_r). The extra layer's damping c_0,y stays Eq 12's.

Along x the entries are tables in the relative zone position (as fitted sets,
:class:`~exudyn_turnout.corunning.fitted.TableEntry`); the zone's mass is one number.
Where the check rail's FE values are for one route's check rail (``rail``), the co-running
slot r3 uses them on both routes (the co-running parameters do not depend on the route).
"""

from __future__ import annotations

import math
import statistics
from collections.abc import Callable, Mapping

from exudyn_turnout.corunning.fitted import TableEntry
from exudyn_turnout.inputs.check_rail import (
    CO_RUNNING_MODELS,
    CheckRailLateral,
    co_running_model_from_section,
    lateral_from_section,
)
from exudyn_turnout.inputs.turnout import Entry, Turnout, TurnoutFileError, Zone

__all__ = [
    "CHECK_RAIL_MODELS",
    "check_rail_lateral",
    "check_rail_model",
    "check_rail_pad_stiffness",
    "check_rail_mass",
    "check_rail_pad_damping",
    "bracket_entries",
]

#: How the co-running check rail's lateral entries are made: ``"bracket"`` derived from
#: the FE check rail on its L-bracket (this module), ``"table1"`` Eqs 1-19 on Table 1 like
#: a running rail (the paper's). The turnout file chooses with ``[check_rail.co_running]``
#: ``model`` (:data:`exudyn_turnout.inputs.check_rail.CO_RUNNING_MODELS`).
CHECK_RAIL_MODELS = CO_RUNNING_MODELS


def check_rail_lateral(turnout: Turnout) -> CheckRailLateral | None:
    """The file's ``[check_rail.co_running]`` FE values, or None.

    Parameters
    ----------
    turnout : Turnout

    Returns
    -------
    CheckRailLateral or None

    Raises
    ------
    TurnoutFileError
        The section is malformed (the loader checks it too).
    """
    section = turnout.raw.get("check_rail", {})
    try:
        return lateral_from_section(section if isinstance(section, Mapping) else {})
    except ValueError as err:
        raise TurnoutFileError(f"{turnout.source}: check_rail.co_running {err}") from None


def _file_model(turnout: Turnout) -> str | None:
    """The ``model`` key of the file's ``[check_rail.co_running]``, or None."""
    section = turnout.raw.get("check_rail", {})
    try:
        return co_running_model_from_section(section if isinstance(section, Mapping) else {})
    except ValueError as err:
        raise TurnoutFileError(f"{turnout.source}: check_rail.co_running.{err}") from None


def check_rail_model(turnout: Turnout, model: str | None) -> str:
    """The check-rail model to use: the one asked for, or the default.

    Parameters
    ----------
    turnout : Turnout
    model : {"bracket", "table1"} or None
        None: the file's ``[check_rail.co_running]`` ``model`` if it has one, else
        ``"bracket"`` if the file has ``[check_rail.co_running]``, else ``"table1"``.

    Returns
    -------
    str

    Raises
    ------
    ValueError
        An unknown model, or ``"bracket"`` for a file without ``[check_rail.co_running]``.
    """
    if model is None:
        model = _file_model(turnout)
    if model is None:
        return "bracket" if check_rail_lateral(turnout) is not None else "table1"
    if model not in CHECK_RAIL_MODELS:
        raise ValueError(f"check_rail must be one of {', '.join(CHECK_RAIL_MODELS)}, got {model!r}")
    if model == "bracket" and check_rail_lateral(turnout) is None:
        raise ValueError(
            f"{turnout.source} has no [check_rail.co_running] (the FE check rail's lateral "
            "values): use check_rail='table1' or add it (validation/check_rail_support.py)"
        )
    return model


def check_rail_pad_stiffness(
    static_stiffness: float, k_tg_y: float, k_rt_over_k_0: float = 0.0
) -> float:
    """Lateral pad stiffness k_rt,y that gives the co-running rail a static stiffness.

    Springs in series: 1 / K = 1/k_tg,y + (1 + k_rt,y / k_0,y) / k_rt,y.

    Parameters
    ----------
    static_stiffness : float
        N/m, K: the target (the FE check rail's at the gauge corner).
    k_tg_y : float
        N/m, the sleeper's lateral ballast spring (Eq 13).
    k_rt_over_k_0 : float
        -, k_rt,y / k_0,y: 0 for two layers, 1/5 for three (the paper's k_0,y = 5 k_rt,y).

    Returns
    -------
    float
        N/m, (1 + k_rt,y/k_0,y) / (1/K - 1/k_tg,y).

    Raises
    ------
    ValueError
        K >= k_tg,y: no pad on that sleeper reaches it.
    """
    rest = 1.0 / static_stiffness - 1.0 / k_tg_y
    if not rest > 0.0:
        raise ValueError(
            f"the check rail's static stiffness {static_stiffness / 1e6:.4g} MN/m is not below "
            f"the co-running sleeper's lateral ballast spring {k_tg_y / 1e6:.4g} MN/m"
        )
    return (1.0 + k_rt_over_k_0) / rest


def check_rail_mass(
    k_rt_y: float, resonance_frequency: float, layers: int = 2, m_0: float = 0.0
) -> float:
    """Rail mass that resonates on its lateral pad at the FE check rail's frequency.

    Parameters
    ----------
    k_rt_y : float
        N/m, lateral pad stiffness (:func:`check_rail_pad_stiffness`).
    resonance_frequency : float
        Hz, f_r of the FE check rail on its bracket.
    layers : {2, 3}
    m_0 : float
        kg, the extra layer's mass (three layers: it moves with the rail at f_r).

    Returns
    -------
    float
        kg, k_rt,y / (2 pi f_r)^2, less m_0 for three layers.

    Raises
    ------
    ValueError
        The result is not positive.
    """
    m = k_rt_y / (2.0 * math.pi * resonance_frequency) ** 2 - (m_0 if layers == 3 else 0.0)
    if not m > 0.0:
        raise ValueError(f"the check rail's participating mass is not positive ({m:.4g} kg)")
    return m


def check_rail_pad_damping(resonance_stiffness: float, resonance_frequency: float) -> float:
    """Lateral pad damping: at resonance a mass-spring-dashpot's dynamic stiffness is w c.

    Parameters
    ----------
    resonance_stiffness : float
        N/m, 1 / max |H| of the FE check rail at its resonance.
    resonance_frequency : float
        Hz, f_r.

    Returns
    -------
    float
        N s/m, K_r / (2 pi f_r).
    """
    return resonance_stiffness / (2.0 * math.pi * resonance_frequency)


def bracket_entries(
    lateral: CheckRailLateral,
    zone: Zone,
    layers: int,
    k_tg_y: Callable[[float], float],
    k_0_over_k_rt: float,
    m_0: float,
    slot: str = "r3",
) -> dict[str, Entry]:
    """The check rail's lateral entries and mass of a zone, derived from the FE values.

    Parameters
    ----------
    lateral : CheckRailLateral
        The FE check rail's values along x.
    zone : Zone
        The zone where ``slot`` is the check rail; only the values inside it are used.
    layers : {2, 3}
    k_tg_y : callable
        x (m) -> N/m, the zone's lateral ballast spring there (Eq 13, with Eq 15's factor
        if the zone's has one).
    k_0_over_k_rt : float
        -, the third layer's k_0,y / k_rt,y (``[extra_layer]``, the paper's 5).
    m_0 : float
        kg, the extra layer's mass.
    slot : str
        The check rail's slot.

    Returns
    -------
    dict of str to Entry
        ``k_rtj_y``, ``c_rtj_y`` (tables in the relative zone position), ``m_rj`` and, for
        three layers, ``k_0j_y`` (tables).

    Raises
    ------
    ValueError
        No FE position inside the zone, or a step of the derivation fails (named).
    """
    inside = [i for i, x in enumerate(lateral.x) if zone.x_start <= x <= zone.x_end]
    if not inside:
        raise ValueError(
            f"[check_rail.co_running] has no position inside zone {zone.index} "
            f"({zone.x_start:g}-{zone.x_end:g} m)"
        )
    ratio = 1.0 / k_0_over_k_rt if layers == 3 else 0.0
    s = [(lateral.x[i] - zone.x_start) / (zone.x_end - zone.x_start) for i in inside]
    k = [
        check_rail_pad_stiffness(lateral.static_stiffness[i], k_tg_y(lateral.x[i]), ratio)
        for i in inside
    ]
    f_r = [lateral.resonance_frequency[i] for i in inside]
    c = [
        check_rail_pad_damping(lateral.resonance_stiffness[i], lateral.resonance_frequency[i])
        for i in inside
    ]
    m = statistics.median(check_rail_mass(ki, fi, layers, m_0) for ki, fi in zip(k, f_r))

    def table(values: list[float]) -> Entry:
        return TableEntry.of(s, values) if len(values) > 1 else Entry("const", values[0])

    j = slot[1:]
    out = {f"k_rt{j}_y": table(k), f"c_rt{j}_y": table(c), f"m_r{j}": Entry("const", m)}
    if layers == 3:
        out[f"k_0{j}_y"] = table([k_0_over_k_rt * ki for ki in k])
    return out
