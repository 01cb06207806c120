"""Point receptance of the FE turnout model by a direct frequency-domain solve.

H(f) = b^T Z(omega)^-1 b with b the element shape functions of the loaded rail at x (a
unit point force and the deflection under it), Z = K + iG + i omega D - omega^2 M of
one bending plane, solved with the exact condensation of
:mod:`exudyn_turnout.fe.solver` and sparse LU at every frequency. The result is a
:class:`~exudyn_turnout.receptance.Receptance` (model "FE"), the object and CSV columns
of the co-running models, so the curves compare directly.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import asdict

import numpy as np
from numpy.typing import ArrayLike

from exudyn_turnout.fe.layout import Layout, load_layout
from exudyn_turnout.fe.mesh import FEOptions, build_mesh
from exudyn_turnout.fe.model import PlaneModel, assemble
from exudyn_turnout.fe.solver import condense, default_keep
from exudyn_turnout.fe.torsion import UIC60_SECTION, RailTorsionSection
from exudyn_turnout.inputs.turnout import RAIL_SLOTS, Turnout
from exudyn_turnout.receptance import Receptance, log_frequencies

__all__ = [
    "sweep",
    "sweep_points",
    "sweep_vectors",
    "point_receptances",
    "resolve_rail",
    "load_height",
    "fe_receptance",
]

_DEFAULT_OPTIONS = FEOptions()


def sweep(model: PlaneModel, rail_id: str, x: float, frequencies: ArrayLike) -> np.ndarray:
    """Point receptance of one rail node over a range of frequencies.

    Parameters
    ----------
    model : PlaneModel
        The assembled vertical or lateral model.
    rail_id : str
        Layout rail id.
    x : float
        Position from the switch toe (m); must be a rail node (build the mesh with
        ``points={rail_id: [x]}``).
    frequencies : array_like
        Frequencies (Hz).

    Returns
    -------
    numpy.ndarray
        Complex receptance H (m/N), one value per frequency.
    """
    return sweep_points(model, [(rail_id, x)], frequencies)[:, 0]


def sweep_points(
    model: PlaneModel, points: Sequence[tuple[str, float]], frequencies: ArrayLike
) -> np.ndarray:
    """Point receptances of many rail nodes, one factorisation per frequency for all points.

    Parameters
    ----------
    model : PlaneModel
        The assembled vertical or lateral model.
    points : sequence of (str, float)
        Rail ids and positions (m) of rail nodes.
    frequencies : array_like
        Frequencies (Hz).

    Returns
    -------
    numpy.ndarray
        Complex receptances (m/N), shape (n_frequencies, n_points).
    """
    B = np.column_stack([model.point_vector(rail_id, x) for rail_id, x in points])
    return sweep_vectors(model, B, frequencies)


def sweep_vectors(model: PlaneModel, B: np.ndarray, frequencies: ArrayLike) -> np.ndarray:
    """Receptances b^T Z^-1 b of general load/response vectors, one factorisation per frequency.

    Parameters
    ----------
    model : PlaneModel
        The assembled model.
    B : numpy.ndarray
        (n_dof, m) vectors b, each both the load and the response (e.g.
        :meth:`~exudyn_turnout.fe.model.PlaneModel.head_vector`); the DOFs they touch
        are kept in the condensation.
    frequencies : array_like
        Frequencies (Hz).

    Returns
    -------
    numpy.ndarray
        Complex receptances (m/N or per unit of b), shape (n_frequencies, m).
    """
    B = np.asarray(B, float).reshape(model.n_dof, -1)
    system = condense(model, np.union1d(default_keep(model), np.nonzero(B.any(axis=1))[0]))
    Bk = system.restrict(B).astype(complex)
    return np.array(
        [
            np.einsum("ij,ij->j", Bk, system.solve(2 * np.pi * frequency, Bk))
            for frequency in np.asarray(frequencies, float)
        ]
    )


def point_receptances(
    model: PlaneModel, points: Sequence[tuple[str, float]], frequency_hz: float
) -> np.ndarray:
    """Point receptances (m/N, complex) at many (rail_id, x) nodes, one factorisation.

    Parameters
    ----------
    model : PlaneModel
        The assembled vertical or lateral model.
    points : sequence of (str, float)
        Rail ids and positions (m) of rail nodes.
    frequency_hz : float
        Frequency (Hz).

    Returns
    -------
    numpy.ndarray
        Complex receptance (m/N) of each point.
    """
    B = np.column_stack([model.point_vector(rail_id, x) for rail_id, x in points])
    system = condense(model, np.union1d(default_keep(model), np.nonzero(B.any(axis=1))[0]))
    B = system.restrict(B).astype(complex)
    return np.einsum("ij,ij->j", B, system.solve(2 * np.pi * frequency_hz, B))


def resolve_rail(layout: Layout, rail: str, x: float, route: str = "through") -> str:
    """Layout rail id of a co-running slot (r1..r4), or a layout rail id checked at x.

    Parameters
    ----------
    layout : Layout
        The turnout layout.
    rail : str
        Co-running slot ``"r1"``..``"r4"`` or a layout rail id.
    x : float
        Position from the switch toe (m).
    route : {"through", "diverging"}
        Slot mapping to use for a slot.

    Returns
    -------
    str
        The layout rail id.

    Raises
    ------
    ValueError
        Unknown rail, or the rail is not present at x.
    """
    if rail in RAIL_SLOTS:
        return layout.slot_rail(rail, x, route)
    rail_ids = [layout_rail.id for layout_rail in layout.rails]
    if rail not in rail_ids:
        raise ValueError(
            f"rail must be one of {', '.join(RAIL_SLOTS)} or a layout rail "
            f"({', '.join(rail_ids)}), got {rail!r}"
        )
    found = layout.rail(rail)
    if not found.x_from <= x <= found.x_to:
        raise ValueError(
            f"rail {rail} is not present at x = {x:g} m "
            f"(it runs from {found.x_from:g} to {found.x_to:g} m)"
        )
    return rail


def load_height(section: RailTorsionSection, height: str | float) -> float:
    """Height of a lateral load above the rail's shear centre (m).

    Parameters
    ----------
    section : RailTorsionSection
        Rail section.
    height : {"head", "shear_centre"} or float
        ``"head"``: the gauge corner (``contact_depth`` below the rail top);
        ``"shear_centre"``: 0; a number: metres above the rail foot's underside.

    Returns
    -------
    float
        z above the shear centre (m).

    Raises
    ------
    ValueError
        An unknown name, or a height outside the rail.
    """
    if height == "head":
        return section.gauge_corner_height
    if height == "shear_centre":
        return 0.0
    if isinstance(height, str):
        raise ValueError(f"height must be 'head', 'shear_centre' or metres, got {height!r}")
    if not 0.0 <= float(height) <= section.height:
        raise ValueError(
            f"height must be within the rail (0 to {section.height:g} m above the foot), "
            f"got {height!r}"
        )
    return float(height) - section.shear_centre_height


def fe_receptance(
    turnout: Turnout,
    rail: str,
    direction: str,
    x: float,
    frequencies: ArrayLike | None = None,
    route: str = "through",
    options: FEOptions = _DEFAULT_OPTIONS,
    layout: Layout | None = None,
    torsion: RailTorsionSection | bool = True,
    height: str | float = "head",
) -> Receptance:
    """Point receptance of the FE turnout model at one rail position.

    Parameters
    ----------
    turnout : Turnout
        With a ``[layout]`` section (or give ``layout``).
    rail : str
        Co-running slot "r1".."r4" (mapped to a rail by ``layout.slots``) or a layout
        rail id such as "straight".
    direction : {"vertical", "lateral"}
        Bending plane: the vertical or the lateral model.
    x : float
        Position from the switch toe (m).
    frequencies : array_like, optional
        Hz; default :func:`~exudyn_turnout.receptance.log_frequencies` (400, 1-2000 Hz).
    route : {"through", "diverging"}
        Slot mapping to use.
    options : FEOptions
        Discretisation, rail damping and model ends.
    layout : Layout, optional
        Default :func:`~exudyn_turnout.fe.layout.load_layout` of the turnout.
    torsion : RailTorsionSection or bool
        Lateral only: rail torsion (:mod:`~exudyn_turnout.fe.torsion`); True (default)
        the 60E1 section :data:`~exudyn_turnout.fe.torsion.UIC60_SECTION`, False the
        planar lateral model (force and response at the rail, no roll).
    height : {"head", "shear_centre"} or float
        Lateral with torsion only: where the lateral force acts and the displacement is
        taken (:func:`load_height`); default the gauge corner of the rail head.

    Returns
    -------
    Receptance
        model "FE", ``metadata`` with the rail id, the DOF count, the options and, for
        the lateral plane, the torsion section and the load height above the shear centre.

    Raises
    ------
    ValueError
        The rail is not present at x, x is outside the model, or a bad height.
    """
    layout = layout or load_layout(turnout)
    rail_id = resolve_rail(layout, rail, float(x), route)
    frequency = log_frequencies() if frequencies is None else np.asarray(frequencies, float)
    section = (UIC60_SECTION if torsion is True else torsion) or None
    if direction != "lateral":
        section = None
    z = load_height(section, height) if section is not None else 0.0
    model = assemble(
        turnout,
        build_mesh(turnout, layout, options, points={rail_id: [float(x)]}),
        direction,
        torsion=section,
    )
    H = sweep_vectors(model, model.head_vector(rail_id, float(x), z)[:, None], frequency)[:, 0]
    metadata = {
        "rail_id": rail_id,
        "route": route,
        "n_dof": model.n_dof,
        "options": asdict(options),
    }
    if direction == "lateral":
        metadata["torsion"] = asdict(section) if section is not None else None
        metadata["height_above_shear_centre_m"] = z
    return Receptance(frequency, H, rail, direction, float(x), "FE", metadata)
