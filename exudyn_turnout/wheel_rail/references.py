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

from exudyn_turnout.wheel_rail.creep_table import creep_table, table_creep_forces
from exudyn_turnout.wheel_rail.geometry import (
    FLANGE_DIRECTION,
    WheelGrid,
    prepare_rail,
    prepare_wheel,
    search_candidates,
    surface_derivatives,
)
from exudyn_turnout.wheel_rail.hertz import (
    curvature_sums,
    effective_modulus,
    hertz_constant,
    hertz_contact,
)
from exudyn_turnout.wheel_rail.kp_creep import StripPatch, fastsim_patch, kp_strips
from exudyn_turnout.wheel_rail.nonhertz import hertz_fits, kik_piotrowski, normal_gap_function
from exudyn_turnout.wheel_rail.profiles import ProfileFormatError, read_slices
from exudyn_turnout.wheel_rail.sections import (
    lateral_grid,
    slice_sections,
    wheel_drop,
    wheel_envelope,
)

__all__ = [
    "ReferencePatch",
    "ReferenceCase",
    "read_reference_output",
    "GeometryResult",
    "geometry_at_reference",
    "compare_all",
    "PatchResult",
    "ContactResult",
    "contact_at_reference",
    "REFERENCE_FILES",
]

#: The packaged CONTACT reference outputs compared (``reference_outputs/<name>.ref_out``).
REFERENCE_FILES = ("wing_brute", "cross_brute", "cross+wing", "cw_interrupt")

_MM = 1e-3


@dataclass(frozen=True)
class ReferencePatch:
    """One contact patch of a CONTACT case, SI units (CONTACT writes mm, N, N/mm^2)."""

    x_contact: float  #: m, contact point along the track relative to the wheel (XCP(TR))
    y_contact_rail: float  #: m, contact point on the rail profile (YCP(R))
    z_contact_rail: float  #: m, its height (-ZCP(R))
    y_contact_wheel: float  #: m, contact point on the wheel profile (YCP(W))
    normal_force: float  #: N, FN
    fx: float  #: N, longitudinal tangential force FX (CONTACT's sign)
    fs: float  #: N, lateral tangential force FS, in the contact plane (CONTACT's sign)
    approach: float  #: m, APPROACH of the bodies at the patch
    p_max: float  #: Pa, PMAX
    cksi: float  #: -, longitudinal creepage CKSI
    ceta: float  #: -, lateral creepage CETA
    cphi: float  #: 1/m, spin creepage CPHI (CONTACT: 1/mm)
    length: float  #: m, extent along x of the contact elements (columns x DX)
    width: float  #: m, extent along s of the contact elements (rows x DS)
    area: float  #: m^2, number of elements in contact x DX x DS
    n_elements: int  #: -, NCON, elements in contact


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
    prescribed: str = "position"  #: "position" (Z given) or "force" (FZ given)
    dx: float = 0.0  #: m, CONTACT's element size along x (DX)
    ds: float = 0.0  #: m, CONTACT's element size along s (DS)
    friction: float = 0.3  #: -, CONTACT's FSTAT
    shear_modulus: float = 8.2e10  #: Pa, CONTACT's G (its input: N/mm^2)
    poisson: float = 0.28  #: -, CONTACT's NU
    #: every patch of the case (CONTACT's order); the fields above repeat the first one
    patches: tuple[ReferencePatch, ...] = ()


def _numbers(line: str) -> list[float]:
    return [float(v) for v in re.findall(r"[-+]?\d*\.?\d+(?:[eE][-+]?\d+)?", line)]


_MAP_ROW = re.compile(r"^\s+(\d+)\s+([.oS*|PE -]+)$")


def _contact_map(lines: list[str], start: int) -> tuple[int, int, int]:
    """Columns (x) and rows (s) spanned by the contact elements of a "FORM OF THE CONTACT"
    map, and their number (adhesion ``*`` and slip ``S``)."""
    rows: list[str] = []
    i = start + 1
    while i < len(lines) and _MAP_ROW.match(lines[i]):
        body = lines[i].split(None, 1)[1]
        if " . " in body or " * " in body or " S " in body:  # a wide map, one char per cell
            body = body[0::2]
        rows.append(body)
        i += 1
    cells = [(r, c) for r, row in enumerate(rows) for c, ch in enumerate(row) if ch in "*S"]
    if not cells:
        return 0, 0, 0
    rows_spanned, columns_spanned = (max(v) - min(v) + 1 for v in zip(*cells, strict=True))
    return columns_spanned, rows_spanned, len(cells)


def read_reference_output(path: str | Path) -> list[ReferenceCase]:
    """Read the cases of a CONTACT ``.ref_out`` file, every patch of each.

    Per patch: contact reference location, FN, FX, FS, APPROACH, PMAX, the creepages CKSI,
    CETA, CPHI, and the patch's extent from the "FORM OF THE CONTACT" map (rows: s with
    step DS; columns: x with step DX, the map's ``X -->`` axis).

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
    patch: dict[str, Any] = {}
    rail = ""
    step = (0.0, 0.0)
    material: dict[str, float] = {}
    for i, line in enumerate(lines):
        text = line.strip()
        if text.startswith("Case"):
            _finish(current, patch, cases, path, rail, step, material)
            current, patch = {"case": int(_numbers(text)[0]), "patches": []}, {}
        elif text.startswith("RAIL PROFILE"):
            rail = text.split('"')[1]
        elif text.startswith("DX ") and "DS" in text:
            values = _numbers(lines[i + 1])
            step = (values[0] * _MM, values[1] * _MM)
        elif text.startswith("NU ") and " G " in text:
            values = _numbers(lines[i + 1])
            material = {"poisson": values[0], "shear_modulus": values[1] * 1e6}
        elif text.startswith("FSTAT"):
            material["friction"] = _numbers(lines[i + 1])[0]
        elif text.startswith("VERTICAL PROBLEM WITH PRESCRIBED"):
            current["prescribed"] = "force" if "FORCE" in text else "position"
        elif text.startswith("S_WS"):
            current["position"] = _numbers(lines[i + 1])
        elif text.startswith("----- DATA FOR CONTACT PATCH"):
            if patch:
                current["patches"].append(patch)
            patch = {}
        elif text.startswith("XCP(TR)"):
            patch["xcp_tr"] = _numbers(lines[i + 1])
        elif text.startswith("XCP(W)"):
            patch["xcp_w"] = _numbers(lines[i + 1])
        elif text.startswith("CHI ") and "CKSI" in text:
            patch["kinematics"] = _numbers(lines[i + 1])
        elif text.startswith("FN ") and "FX" in text:
            patch["forces"] = _numbers(lines[i + 1])
        elif text.startswith("FN/G"):
            patch["ratios"] = _numbers(lines[i + 1])
        elif text.startswith("FORM OF THE CONTACT"):
            patch["map"] = _contact_map(lines, i)
    _finish(current, patch, cases, path, rail, step, material)
    if not cases:
        raise ProfileFormatError(f"{path.name}: no complete CONTACT case found")
    return cases


_PATCH_KEYS = ("xcp_tr", "xcp_w", "kinematics", "forces", "ratios")


def _patch(raw: dict[str, Any], step: tuple[float, float]) -> ReferencePatch:
    tr, wh, kin, forces, ratios = (raw[k] for k in _PATCH_KEYS)
    columns, rows, count = raw.get("map", (0, 0, 0))
    return ReferencePatch(
        x_contact=tr[0] * _MM,
        y_contact_rail=tr[4] * _MM,
        z_contact_rail=-tr[5] * _MM,
        y_contact_wheel=wh[1] * _MM,
        normal_force=forces[0],
        fx=forces[1],
        fs=forces[2],
        approach=ratios[3] * _MM,
        p_max=ratios[4] * 1e6,
        cksi=kin[3],
        ceta=kin[4],
        cphi=kin[5] / _MM,
        length=columns * step[0],
        width=rows * step[1],
        area=count * step[0] * step[1],
        n_elements=count,
    )


def _finish(current, patch, cases, path, rail, step, material) -> None:
    """Close a case: keep it when its position and at least one whole patch were read."""
    if not current:
        return
    raw = list(current.get("patches", [])) + ([patch] if patch else [])
    patches = tuple(_patch(p, step) for p in raw if all(k in p for k in _PATCH_KEYS))
    if "position" not in current or not patches:
        return
    pos, first = current["position"], patches[0]
    cases.append(
        ReferenceCase(
            source=str(path),
            case=current["case"],
            rail_file=rail,
            s=pos[0] * _MM,
            y=pos[1] * _MM,
            wheel_height=-pos[2] * _MM,
            x_contact=first.x_contact,
            y_contact_rail=first.y_contact_rail,
            z_contact_rail=first.z_contact_rail,
            y_contact_wheel=first.y_contact_wheel,
            approach=first.approach,
            normal_force=first.normal_force,
            prescribed=current.get("prescribed", "position"),
            dx=step[0],
            ds=step[1],
            patches=patches,
            **material,
        )
    )


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
    grid, enveloped, derivatives = _section(case, wheel, profiles_dir, envelope_step, reach,
                                            nominal_radius, interpolation)  # fmt: skip
    found = search_candidates(
        prepare_rail(enveloped.z[0], derivatives.slope[0], derivatives.curvature[0], grid),
        prepare_wheel(wheel, 0.0),
        shift=case.y,
        lift=case.wheel_height,
        max_candidates=1,
    )
    return _geometry(found, 0, grid, enveloped, nominal_radius)


def _section(case, wheel, profiles_dir, envelope_step, reach, nominal_radius, interpolation):
    """The lateral grid, the rigid-wheel envelope of the slices at S, and its derivatives."""
    slices = read_slices(Path(profiles_dir) / Path(case.rail_file).name)
    grid = lateral_grid(-0.08, 0.30, wheel.s[1] - wheel.s[0])
    offsets = np.arange(-reach, reach + 0.5 * envelope_step, envelope_step)
    sections = slice_sections(slices, grid, x=case.s + offsets, interpolation=interpolation)
    enveloped = wheel_envelope(
        sections, np.array([case.s]), nominal_radius, reach=reach, step=envelope_step
    )
    return grid, enveloped, surface_derivatives(enveloped)


def _geometry(found, k, grid, enveloped, nominal_radius) -> GeometryResult:
    """Candidate k of a search as a :class:`GeometryResult` (x from the envelope)."""
    index = int(round((found.y_rail[k] - grid[0]) / (grid[1] - grid[0])))
    x_offset = enveloped.x_offset
    assert x_offset is not None  # wheel_envelope records where along x each height is met
    dx = float(x_offset[0, index])
    return GeometryResult(
        x_contact=dx,
        y_contact_rail=float(found.y_rail[k]),
        z_contact_rail=float(found.z_rail[k] + wheel_drop(dx, nominal_radius)),
        y_contact_wheel=float(found.s_wheel[k]),
        approach=-float(found.gap[k]),
        angle=float(found.angle[k]),
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
    for name in REFERENCE_FILES:
        for case in read_reference_output(folder / "reference_outputs" / f"{name}.ref_out"):
            ours = geometry_at_reference(
                case, wheel, folder / "profiles", interpolation=interpolation
            )
            rows.append((f"{name}#{case.case}", case, ours))
    return rows


@dataclass(frozen=True)
class PatchResult:
    """Our normal and tangential contact at a CONTACT case, by one method (SI)."""

    #: m, where the normal force acts on the rail profile (Hertz: the contact point; KP:
    #: the patch's force centre, moved from it along the tangent)
    y_contact_rail: float
    z_contact_rail: float  #: m, its height
    approach: float  #: m, penetration that carries CONTACT's FN
    force_at_geometry: float  #: N, normal force at our undeformed interpenetration
    p_max: float  #: Pa, peak pressure at CONTACT's FN
    length: float  #: m, patch extent along x at CONTACT's FN
    width: float  #: m, patch extent along the lateral tangent at CONTACT's FN
    area: float  #: m^2, contact area at CONTACT's FN
    a: float  #: m, semi-axis for the creep law (rolling direction)
    b: float  #: m, semi-axis for the creep law (lateral)
    fx: float  #: N, longitudinal creep force at CONTACT's creepages (kernel's law, on wheel)
    fs: float  #: N, lateral creep force at CONTACT's creepages (the kernel's law, on the wheel)


@dataclass(frozen=True)
class ContactResult:
    """Geometry, Hertz and Kik-Piotrowski at one CONTACT case (patch 1)."""

    geometry: GeometryResult  #: our contact point (the candidate nearest CONTACT's)
    hertz: PatchResult  #: Hertz with the point's curvature sums (floored as in the tables)
    semi_hertz: PatchResult  #: Kik-Piotrowski on the point's gap function
    hertz_fits: bool  #: the tables' criterion (:func:`.nonhertz.hertz_fits`)
    #: N, Kik-Piotrowski force of every candidate in interpenetration (our patches)
    patch_forces: tuple[float, ...]
    kp_strips: StripPatch  #: KP's patch at CONTACT's FN, strip by strip
    #: N, (FX, FS) of FASTSIM on the KP strips (:func:`.kp_creep.fastsim_patch`, parabolic
    #: pressure) at CONTACT's creepages, FN, mu, G and nu
    strip_creep: tuple[float, float]
    #: m, where along x the rigid wheel meets the rail's line under each KP strip (the
    #: envelope's x offset): the skew a 3-D patch would have, which KP's 2-D patch has not
    kp_skew: np.ndarray


def _solve_penetration(force: float, evaluate) -> float:
    """Penetration at which ``evaluate(delta)`` (increasing) equals ``force`` (bisection)."""
    low, high = 1e-8, 2e-3
    for _ in range(60):
        mid = float(np.sqrt(low * high))
        if evaluate(mid) < force:
            low = mid
        else:
            high = mid
    return float(np.sqrt(low * high))


def contact_at_reference(
    case: ReferenceCase,
    wheel: WheelGrid,
    profiles_dir: str | Path,
    envelope_step: float = 2.5e-4,
    reach: float = 0.1,
    nominal_radius: float = 0.46,
    step: float = 2e-5,
    window: float = 0.02,
) -> ContactResult:
    """Our normal contact (Hertz and Kik-Piotrowski) and creep forces at a CONTACT case.

    The geometry is that of :func:`geometry_at_reference`; the candidate nearest
    CONTACT's first patch is compared.  Its position is the point of deepest
    interpenetration; KP's patch position is where its normal force acts (the strips'
    force-weighted mean along the tangent), which is what CONTACT's reference location
    agrees with (validation/contact_vs_contact.md).  Hertz uses the point's curvature
    sums (floored like the tables'), Kik-Piotrowski the undeformed normal gap along the
    lateral tangent (:func:`.nonhertz.normal_gap_function`, sampled at ``step``).  Both
    are evaluated at CONTACT's FN; the creep forces are the passage kernel's law, the FASTSIM table
    (:func:`.creep_table.table_creep_forces`, Poisson's ratio 0.28 as all the packaged
    cases) at CONTACT's creepages CKSI, CETA, CPHI with its FN, friction and G.  FASTSIM
    on KP's patch strip by strip (:func:`.kp_creep.fastsim_patch`) is given beside them.

    Parameters
    ----------
    case : ReferenceCase
        The reference case.
    wheel : WheelGrid
        The S1002 wheel, gridded.
    profiles_dir : str or Path
        Folder holding the slice files.
    envelope_step, reach, nominal_radius : float
        m, see :func:`geometry_at_reference`.
    step, window : float
        m, sample step and half-width of the gap function.

    Returns
    -------
    ContactResult
    """
    grid, enveloped, derivatives = _section(case, wheel, profiles_dir, envelope_step, reach,
                                            nominal_radius, "auto")  # fmt: skip
    rail = prepare_rail(enveloped.z[0], derivatives.slope[0], derivatives.curvature[0], grid)
    prepared = prepare_wheel(wheel, 0.0, 0.0, (FLANGE_DIRECTION,))
    found = search_candidates(rail, prepared, shift=case.y, lift=case.wheel_height)
    k = int(np.argmin(np.abs(found.y_rail - case.y_contact_rail)))
    geometry = _geometry(found, k, grid, enveloped, nominal_radius)
    gaps = normal_gap_function(
        rail, prepared, np.full(found.gap.shape, case.y), found.y_rail, found.z_rail,
        found.angle, step=step, window=window, lift=case.wheel_height,
    )  # fmt: skip
    modulus = effective_modulus(2.0 * case.shear_modulus * (1.0 + case.poisson), case.poisson)
    a_raw = 0.5 * np.cos(found.angle) / found.radius
    b_raw = 0.5 * (np.nan_to_num(found.curvature_wheel) + np.nan_to_num(found.curvature_rail))
    a_sum, b_sum = curvature_sums(
        found.radius, found.angle, found.curvature_wheel, found.curvature_rail
    )
    patch = case.patches[0]
    force = patch.normal_force

    table = creep_table()  # the kernel's creep law (FASTSIM, tabulated)

    def creep(a: float, b: float) -> tuple[float, float]:
        forces = table_creep_forces(
            table, patch.cksi, patch.ceta, patch.cphi, a, b, force, case.friction,
            shear_modulus=case.shear_modulus,
        )  # fmt: skip
        return float(forces.longitudinal), float(forces.lateral)

    constant = float(hertz_constant(a_sum[k], b_sum[k], modulus))
    ellipse = hertz_contact(a_sum[k], b_sum[k], force, modulus)
    a_h, b_h = float(ellipse.a), float(ellipse.b)
    hertz = PatchResult(
        y_contact_rail=geometry.y_contact_rail,
        z_contact_rail=geometry.z_contact_rail,
        approach=(force / constant) ** (2.0 / 3.0),
        force_at_geometry=constant * max(geometry.approach, 0.0) ** 1.5,
        p_max=float(ellipse.p0),
        length=2.0 * a_h,
        width=2.0 * b_h,
        area=float(np.pi * a_h * b_h),
        a=a_h,
        b=b_h,
        fx=creep(a_h, b_h)[0],
        fs=creep(a_h, b_h)[1],
    )

    def kp(delta: float, row: int = k):
        return kik_piotrowski(gaps[row : row + 1], step, a_sum[row], delta, modulus)

    delta = _solve_penetration(force, lambda d: float(kp(d).normal_force[0]))
    solved = kp(delta)
    a_kp, b_kp = float(solved.a[0]), float(solved.b[0])
    shift = float(solved.t_centre[0])
    semi = PatchResult(
        y_contact_rail=geometry.y_contact_rail + shift * float(np.cos(found.angle[k])),
        z_contact_rail=geometry.z_contact_rail + shift * float(np.sin(found.angle[k])),
        approach=delta,
        force_at_geometry=float(kp(geometry.approach).normal_force[0])
        if geometry.approach > 0.0
        else 0.0,
        p_max=float(solved.p_max[0]),
        length=2.0 * float(solved.half_length[0]),
        width=float(solved.t_high[0] - solved.t_low[0]),
        area=float(solved.area[0]),
        a=a_kp,
        b=b_kp,
        fx=creep(a_kp, b_kp)[0],
        fs=creep(a_kp, b_kp)[1],
    )
    strips = kp_strips(gaps[k], step, float(a_sum[k]), delta, modulus)
    under = geometry.y_contact_rail + strips.t * float(np.cos(found.angle[k]))
    x_offset = enveloped.x_offset
    assert x_offset is not None  # wheel_envelope records where along x each height is met
    skew = np.interp(under, grid, x_offset[0])
    strip_creep = fastsim_patch(
        patch.cksi, patch.ceta, patch.cphi, strips, case.friction, case.shear_modulus,
        case.poisson, normal_force=force,
    )  # fmt: skip
    fits = bool(hertz_fits(gaps[k : k + 1], step, a_raw[k], b_raw[k], modulus)[0])
    forces = tuple(
        float(kp(-float(found.gap[j]), j).normal_force[0])
        for j in range(len(found.gap))
        if found.gap[j] < 0.0
    )
    return ContactResult(geometry, hertz, semi, fits, forces, strips, strip_creep, skew)
