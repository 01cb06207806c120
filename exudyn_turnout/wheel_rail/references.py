"""CONTACT reference outputs (``.ref_out``) and our geometry at the same wheel positions.

CONTACT (Vollebregt & Kalker, open-source version; packaged outputs, see the data folder's
NOTICE.md) solves the full elastic, non-Hertzian contact of an S1002 wheel on a rail given
by slices, for a prescribed wheel position (S along the track, Y lateral, Z vertical) or
force.  Its output gives, per contact patch, the contact reference point on the rail
(XCP, YCP, ZCP), and the approach.  CONTACT's z axis points down and its rail is the right
rail with y towards the field side; :class:`ReferenceCase` converts to this package's
conventions (metres, z up).  :func:`geometry_at_reference` evaluates our undeformed-distance
geometry at the same wheel position.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from exudyn_turnout.wheel_rail.geometry import WheelGrid, find_candidates, surface_derivatives
from exudyn_turnout.wheel_rail.profiles import ProfileFormatError, read_slices
from exudyn_turnout.wheel_rail.sections import lateral_grid, slice_sections, wheel_envelope

__all__ = [
    "ReferenceCase",
    "read_reference_output",
    "GeometryResult",
    "geometry_at_reference",
    "compare_all",
]

_MM = 1e-3


@dataclass(frozen=True)
class ReferenceCase:
    """One case of a CONTACT reference output, in metres, z up (first contact patch)."""

    source: str  #: the .ref_out file
    case: int  #: case number in the file
    rail_file: str  #: slice file named by CONTACT (relative to the .inp's folder)
    s: float  #: m, wheel position along the track (slice coordinate u)
    y: float  #: m, lateral wheel position (towards the field side)
    wheel_height: float  #: m, height of the wheel profile origin (CONTACT's -Z_WS)
    x_contact: float  #: m, contact point along the track relative to the wheel (XCP(TR))
    y_contact_rail: float  #: m, contact point on the rail profile (YCP(R))
    z_contact_rail: float  #: m, its height (-ZCP(R))
    y_contact_wheel: float  #: m, contact point on the wheel profile (YCP(W))
    approach: float  #: m, approach of the bodies
    normal_force: float  #: N, FN


def _numbers(line: str) -> list[float]:
    return [float(v) for v in re.findall(r"[-+]?\d*\.?\d+(?:[eE][-+]?\d+)?", line)]


def read_reference_output(path: str | Path) -> list[ReferenceCase]:
    """Read the cases of a CONTACT ``.ref_out`` file.

    Parameters
    ----------
    path : str or Path
        The reference output.

    Returns
    -------
    list of ReferenceCase

    Raises
    ------
    ProfileFormatError
        If the file has no complete case.
    """
    path = Path(path)
    try:
        lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    except FileNotFoundError:
        raise ProfileFormatError(f"{path.name}: file not found") from None
    cases: list[ReferenceCase] = []
    current: dict[str, Any] = {}
    rail = ""
    for i, line in enumerate(lines):
        text = line.strip()
        if text.startswith("Case"):
            current = {"case": int(_numbers(text)[0])}
        elif text.startswith("RAIL PROFILE"):
            rail = text.split('"')[1]
        elif text.startswith("S_WS"):
            current["position"] = _numbers(lines[i + 1])
        elif text.startswith("XCP(TR)") and "xcp_tr" not in current:
            current["xcp_tr"] = _numbers(lines[i + 1])
        elif text.startswith("XCP(W)") and "xcp_w" not in current:
            current["xcp_w"] = _numbers(lines[i + 1])
        elif text.startswith("FN ") and "forces" not in current:
            current["forces"] = _numbers(lines[i + 1])
        elif text.startswith("FN/G") and "approach" not in current:
            current["approach"] = _numbers(lines[i + 1])[3]
            if all(k in current for k in ("position", "xcp_tr", "xcp_w", "forces")):
                pos, tr, wh = current["position"], current["xcp_tr"], current["xcp_w"]
                cases.append(
                    ReferenceCase(
                        source=str(path),
                        case=current["case"],
                        rail_file=rail,
                        s=pos[0] * _MM,
                        y=pos[1] * _MM,
                        wheel_height=-pos[2] * _MM,
                        x_contact=tr[0] * _MM,
                        y_contact_rail=tr[4] * _MM,
                        z_contact_rail=-tr[5] * _MM,
                        y_contact_wheel=wh[1] * _MM,
                        approach=current["approach"] * _MM,
                        normal_force=current["forces"][0],
                    )
                )
    if not cases:
        raise ProfileFormatError(f"{path.name}: no complete CONTACT case found")
    return cases


@dataclass(frozen=True)
class GeometryResult:
    """Our undeformed-distance geometry at a reference case's wheel position (SI, z up)."""

    x_contact: float  #: m, where along the track the wheel meets the rail (envelope)
    y_contact_rail: float  #: m, lateral position of the deepest point on the rail
    z_contact_rail: float  #: m, rail surface height there
    y_contact_wheel: float  #: m, lateral position on the wheel profile
    approach: float  #: m, largest undeformed interpenetration (normal)
    angle: float  #: rad, contact angle


def geometry_at_reference(
    case: ReferenceCase,
    wheel: WheelGrid,
    profiles_dir: str | Path,
    envelope_step: float = 2.5e-4,
    reach: float = 0.1,
    nominal_radius: float = 0.46,
    interpolation: str = "auto",
) -> GeometryResult:
    """Evaluate our geometry at the wheel position of a CONTACT case.

    CONTACT places the rail profile at RAILY0 = 750 mm and the wheel profile origin at
    FBDIST / 2 - FBPOS = 680 + 70 = 750 mm for Y = 0 in the packaged inputs, so the two
    profile origins coincide at Y = 0 and ``taping_line = 0`` in the rail profile's frame.

    Parameters
    ----------
    case : ReferenceCase
        The reference case.
    wheel : WheelGrid
        The S1002 wheel, gridded.
    profiles_dir : str or Path
        Folder holding the slice files (the case's ``../profiles/`` names are resolved by
        their file name).
    envelope_step : float
        m, step of the longitudinal search of the rigid-wheel envelope.
    reach : float
        m, extent of that search.
    nominal_radius : float
        m, wheel radius (CONTACT's NOMRAD: 460 mm).
    interpolation : str
        Of the slices along the track (:data:`.sections.SLICE_INTERPOLATIONS`), evaluated
        at every position of the longitudinal search.

    Returns
    -------
    GeometryResult
        The touching point with the largest interpenetration.
    """
    slices = read_slices(Path(profiles_dir) / Path(case.rail_file).name)
    grid = lateral_grid(-0.08, 0.30, wheel.s[1] - wheel.s[0])
    offsets = np.arange(-reach, reach + 0.5 * envelope_step, envelope_step)
    sections = slice_sections(slices, grid, x=case.s + offsets, interpolation=interpolation)
    enveloped = wheel_envelope(
        sections, np.array([case.s]), nominal_radius, reach=reach, step=envelope_step
    )
    derivatives = surface_derivatives(enveloped)
    found = find_candidates(
        enveloped.z[0],
        derivatives.slope[0],
        derivatives.curvature[0],
        grid,
        wheel,
        0.0,
        shift=case.y,
        lift=case.wheel_height,
        max_candidates=1,
    )
    index = int(round((found.y_rail[0] - grid[0]) / (grid[1] - grid[0])))
    x_offset = enveloped.x_offset
    assert x_offset is not None  # wheel_envelope records where along x each height is met
    dx = float(x_offset[0, index])
    return GeometryResult(
        x_contact=dx,
        y_contact_rail=float(found.y_rail[0]),
        z_contact_rail=float(found.z_rail[0]) + dx * dx / (2 * nominal_radius),
        y_contact_wheel=float(found.s_wheel[0]),
        approach=-float(found.gap[0]),
        angle=float(found.angle[0]),
    )


def compare_all(
    wheel: WheelGrid, data_folder: str | Path, interpolation: str = "auto"
) -> list[tuple]:
    """Every packaged reference case with our geometry next to it.

    Parameters
    ----------
    wheel : WheelGrid
        The S1002 wheel.
    data_folder : str or Path
        The packaged ``data/wheel_rail`` folder.
    interpolation : str
        Of the slices along the track (:data:`.sections.SLICE_INTERPOLATIONS`).

    Returns
    -------
    list of (str, ReferenceCase, GeometryResult)
        Named ``"<file>#<case>"``.
    """
    folder = Path(data_folder)
    rows = []
    for name in ("wing_brute", "cross_brute", "cross+wing", "cw_interrupt"):
        for case in read_reference_output(folder / "reference_outputs" / f"{name}.ref_out"):
            ours = geometry_at_reference(
                case, wheel, folder / "profiles", interpolation=interpolation
            )
            rows.append((f"{name}#{case.case}", case, ours))
    return rows
