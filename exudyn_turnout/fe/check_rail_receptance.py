"""The check rail's lateral receptance at its gauge corner in the FE: what the co-running uses.

The co-running check rail (slot r3) stands for the FE check rail on its L-bracket
(:mod:`~exudyn_turnout.fe.check_rail`). Three numbers per position x along it describe its
lateral point receptance H(f) at the gauge corner (where the back of a wheel's flange bears
on its face, ``contact_depth`` below its top), in the torsion-aware FE (the rail rolls on
its bracket, as in the FE passages):

- the static stiffness ``1 / |H(f_static)|`` (1 Hz, as the paper's Fig. 1);
- the frequency of the check rail's lateral resonance on its bracket: the largest |H| in a
  search band above the ballast's rigid-body motion and below the lateral pinned-pinned
  frequency (``resonance_band``, default 60-500 Hz);
- the dynamic stiffness there, ``1 / max |H|`` (how deep the resonance is: its damping).

:func:`check_rail_lateral_points` computes them; the turnout file stores them under
``[check_rail.co_running]`` (:func:`co_running_section_toml` writes that block), and
:mod:`exudyn_turnout.corunning.check_rail` derives the co-running check rail's pad
stiffness, damping and participating mass from them (the FE is not run during a passage,
as the paper's K_sh(x) of Eq 14 is an FE result stored as a fit).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from exudyn_turnout.fe.frf import load_height, sweep_vectors
from exudyn_turnout.fe.layout import load_layout
from exudyn_turnout.fe.mesh import FEOptions, build_mesh
from exudyn_turnout.fe.model import assemble
from exudyn_turnout.fe.torsion import UIC60_SECTION, RailTorsionSection
from exudyn_turnout.inputs.check_rail import CheckRailLateral
from exudyn_turnout.inputs.turnout import Turnout

__all__ = [
    "RESONANCE_BAND",
    "check_rail_positions",
    "check_rail_lateral_points",
    "check_rail_receptance",
    "co_running_section_toml",
]

#: Hz, band searched for the check rail's lateral resonance on its bracket: above the
#: sleepers' rigid-body motion on the ballast (< ~50 Hz, the dynamic stiffness there is the
#: ballast's damping) and below the check rail's lateral pinned-pinned frequency (~600 Hz
#: for a 60E1-like section over 0.6 m bays: the co-running models have no discrete supports).
RESONANCE_BAND = (60.0, 500.0)


def check_rail_positions(
    turnout: Turnout, rail_id: str, overhang_step: float = 0.15
) -> list[float]:
    """Where the co-running check rail takes the FE's values: its sleepers and free ends.

    At every sleeper under the rail, as the paper's Fig. 1 and its fits (Eqs 10, 14) take
    the static stiffness at the sleepers (mid-bay the FE adds the bay's bending, and near
    the pinned-pinned frequency a resonance the co-running models cannot have); and on the
    overhang between the rail's free end and its first (last) sleeper, every
    ``overhang_step``, 1 cm inside the end: there the rail is a cantilever, much softer.

    Parameters
    ----------
    turnout : Turnout
        With ``[layout]`` (``sleeper_x0``) and the rail.
    rail_id : str
        Layout rail id.
    overhang_step : float
        m.

    Returns
    -------
    list of float
        m, increasing.
    """
    rail = load_layout(turnout).rail(rail_id)
    x0 = float(turnout.raw.get("layout", {}).get("sleeper_x0", 0.0))
    spacing = turnout.sleeper.spacing
    first = x0 + spacing * np.ceil((rail.x_from - x0) / spacing - 1e-9)
    sleepers = [round(float(x), 9) for x in np.arange(first, rail.x_to + 1e-9, spacing)]
    if not sleepers:
        return [round(0.5 * (rail.x_from + rail.x_to), 9)]
    start = np.arange(rail.x_from + 0.01, sleepers[0] - 0.05, overhang_step)
    end = np.arange(rail.x_to - 0.01, sleepers[-1] + 0.05, -overhang_step)
    points = [round(float(x), 9) for x in (*start, *sleepers, *end)]
    return sorted(set(points))


def check_rail_receptance(
    turnout: Turnout,
    rail_id: str,
    xs: Sequence[float],
    frequencies: np.ndarray,
    options: FEOptions | None = None,
    section: RailTorsionSection = UIC60_SECTION,
) -> np.ndarray:
    """Lateral point receptance (m/N) of an FE check rail at its gauge corner, torsion-aware.

    Parameters
    ----------
    turnout : Turnout
        With a ``[layout]`` holding ``rail_id``.
    rail_id : str
        Layout rail id of the check rail (e.g. ``"check_diverging"``).
    xs : sequence of float
        m, positions along it (made FE nodes).
    frequencies : numpy.ndarray
        Hz.
    options : FEOptions, optional
        FE discretisation (default ``FEOptions()``, the report's mesh).
    section : RailTorsionSection
        The rail's torsion section (gives the gauge corner's height).

    Returns
    -------
    numpy.ndarray
        Complex H, shape (len(frequencies), len(xs)).
    """
    mesh = build_mesh(
        turnout, load_layout(turnout), options or FEOptions(), points={rail_id: list(xs)}
    )
    model = assemble(turnout, mesh, "lateral", torsion=section)
    z = load_height(section, "head")
    B = np.column_stack([model.head_vector(rail_id, float(x), z) for x in xs])
    return sweep_vectors(model, B, np.asarray(frequencies, float))


def check_rail_lateral_points(
    turnout: Turnout,
    rail_id: str,
    xs: Sequence[float],
    options: FEOptions | None = None,
    f_static: float = 1.0,
    band: tuple[float, float] = RESONANCE_BAND,
    n_band: int = 160,
) -> CheckRailLateral:
    """Static stiffness, lateral resonance and its depth of an FE check rail along x.

    Parameters
    ----------
    turnout : Turnout
    rail_id : str
        Layout rail id of the check rail.
    xs : sequence of float
        m, increasing positions along it.
    options : FEOptions, optional
        FE discretisation (default ``FEOptions()``).
    f_static : float
        Hz, the static stiffness is 1 / |H(f_static)| (the paper's Fig. 1 takes 1 Hz).
    band : (float, float)
        Hz, band searched for the resonance (:data:`RESONANCE_BAND`).
    n_band : int
        Log-spaced frequencies in the band (160: 1.9 % steps over 60-500 Hz).

    Returns
    -------
    CheckRailLateral
        One value per x; ``rail`` is ``rail_id``.
    """
    f_band = np.geomspace(band[0], band[1], n_band)
    f = np.concatenate(([f_static], f_band))
    H = np.abs(check_rail_receptance(turnout, rail_id, xs, f, options))
    peak = np.argmax(H[1:], axis=0)
    return CheckRailLateral(
        rail=rail_id,
        x=tuple(float(x) for x in xs),
        static_stiffness=tuple(float(v) for v in 1.0 / H[0]),
        resonance_frequency=tuple(float(f_band[i]) for i in peak),
        resonance_stiffness=tuple(float(1.0 / H[1 + i, j]) for j, i in enumerate(peak)),
    )


def co_running_section_toml(points: CheckRailLateral) -> str:
    """The ``[check_rail.co_running]`` block of a turnout file holding these FE points.

    Parameters
    ----------
    points : CheckRailLateral

    Returns
    -------
    str
        TOML text (4 significant digits), with a comment naming how it was made.
    """

    def row(values: Sequence[float], fmt: str) -> str:
        return "[" + ", ".join(format(v, fmt) for v in values) + "]"

    return "\n".join(
        [
            "[check_rail.co_running]",
            "# FE (torsion-aware, L-bracket) lateral receptance of the check rail at its gauge",
            "# corner: exudyn_turnout.fe.check_rail_receptance.check_rail_lateral_points",
            "# (python validation/check_rail_support.py --toml prints this block).",
            f'rail = "{points.rail}"',
            f"x = {row(points.x, '.6g')}  # m",
            f"static_stiffness = {row(points.static_stiffness, '.4g')}  # N/m, 1/|H(1 Hz)|",
            f"resonance_frequency = {row(points.resonance_frequency, '.4g')}  # Hz",
            f"resonance_stiffness = {row(points.resonance_stiffness, '.4g')}  # N/m, 1/max|H|",
            "",
        ]
    )
