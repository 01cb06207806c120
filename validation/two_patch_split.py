"""The normal-force split between wing rail and nose: passage tables vs the exact 3-D solution.

Writes two_patch_split.md.  Run: ``python validation/two_patch_split.py`` (a few minutes on
one core; ``--quick`` for a coarse sweep).

Geometry: the real UK crossing 56E1-R245-1:9.25 (``uk_crossing.slcs``, CONTACT's
distribution, Apache-2.0; see exudyn_turnout/data/wheel_rail/NOTICE.md), the S1002 wheel
of every packaged CONTACT case (``MBench_S1002_v3.prw``, r = 0.46 m), placed as in CONTACT's
inputs (``reference_outputs/*.inp``): the wheel profile's origin at the slices' lateral
position Y, no roll, no yaw, the wheel's height the height of its profile origin (CONTACT's
-Z).  The wheel rolls from the wing rail (field side, y > 0) onto the nose (gauge side);
where both carry it there are two contact patches.

Per longitudinal position u of the wheel centre, at a fixed total vertical load W, normal
solutions of both patches, each at the wheel height that carries W (vertical equilibrium):

- **reference**: the exact half-space solution (``wheel_rail/exact_normal.solve_normal``,
  Boussinesq influence coefficients, Polonsky-Keer CG with FFT) on the undeformed gap of
  the 3-D surfaces (``wheel_rail/reference_normal.surface_gap``, ``"spline"`` surfaces: the
  slices joined by CONTACT's interpolating spline and interpolated along u, the wheel a
  body of revolution) on one horizontal grid that spans both rails, so both patches and
  their elastic interaction are solved together.  This solver reproduces CONTACT's
  approach within 1.8 % on its five packaged cases (validation/detailed_vs_contact.md).
  Force prescribed: its approach is the wheel's descent below first touch;
- **tables**: what the passage computes: the slice set's sections on the x nodes the
  passage's ``slices`` segments get (``section_nodes`` with the default ``[wheel_rail]``
  tolerance and steps at the slice positions, then ``transfer_nodes`` where the two rails
  share the wheel), the rigid wheel's envelope along x
  (``wheel_envelope``, reach 0.1 m), the contact table of the 2-D sections
  (``build_contact_table``, default settings but the shift range, see
  :data:`TABLE_SHIFTS`), and the compiled kernel (``kernel.contact_forces``, v = 0: no
  creep) on it for the wheelset at lateral position Y and height z; its per-candidate rows
  give the normal force of every contact (the per-node law: Hertz where the ellipse fits,
  Kik-Piotrowski's power law where it does not).  The wheel height is solved (brentq) for
  the sum of the vertical forces = W;
- **tables, 2 mm x nodes** (diagnostic): the same table, law and kernel on the slice set's
  sections every 2 mm along u instead of the passage's nodes;
- **tables, slice nodes only** (before -> after): the passage's tables on the nodes it
  had before ``transfer_nodes`` (the slice positions alone);
- **KP, 2-D section** (diagnostic): Kik-Piotrowski on each contact of the 2-D section
  exactly at u (:func:`kp_split`; no table, no Hertz).

The sweep covers the rigid transfer (:func:`rigid_transfer`) +- 12 mm every 0.5 mm, at
two lateral positions for the static wheel load and at Y = 0 for CONTACT's 10 kN; the
reference's element size is checked once at half of it.

Patches are told apart by the flangeway between the two rail heads of the section at u
(:func:`split_position`): contact on the gauge side of it is the nose's, on the field side
the wing rail's.  The reference also counts its separate contact regions
(``scipy.ndimage.label``, 8-connected).  "Within 10 %": per patch
``|share_tables - share_ref| <= 0.1 share_ref``; "within 0.05": ``|share_tables -
share_ref| <= 0.05``.  Pitch of the contact planes: the grid is horizontal and the gap
vertical, for both patches (the nose's contact lies ~5 mm ahead of the axle: a normal
pitched by 0.011 rad, cos = 0.99994); the kernel's vertical force likewise ignores the
pitch.
"""

from __future__ import annotations

import os

for _name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

import argparse  # noqa: E402
import dataclasses  # noqa: E402
import functools  # noqa: E402
import math  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from dataclasses import dataclass  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
from scipy import ndimage  # noqa: E402
from scipy.optimize import brentq  # noqa: E402

from exudyn_turnout.inputs.vehicle_model import load_vehicle_model  # noqa: E402
from exudyn_turnout.wheel_rail.data import profile_path, s1002_wheel  # noqa: E402
from exudyn_turnout.wheel_rail.exact_normal import solve_normal  # noqa: E402
from exudyn_turnout.wheel_rail.geometry import (  # noqa: E402
    FLANGE_DIRECTION,
    prepare_rail,
    prepare_wheel,
    search_candidates,
    surface_derivatives,
)
from exudyn_turnout.wheel_rail.hertz import MIN_CURVATURE_SUM, effective_modulus  # noqa: E402
from exudyn_turnout.wheel_rail.kernel import DETAIL_FIELDS, contact_forces  # noqa: E402
from exudyn_turnout.wheel_rail.nonhertz import kik_piotrowski, normal_gap_function  # noqa: E402
from exudyn_turnout.wheel_rail.packed_tables import PackedTables, pack_tables  # noqa: E402
from exudyn_turnout.wheel_rail.profiles import read_slices  # noqa: E402
from exudyn_turnout.wheel_rail.reference_normal import (  # noqa: E402
    GAP_SAMPLE_STEP,
    GAP_SAMPLE_WINDOW,
    NOMINAL_RADIUS,
    CaseGeometry,
    surface_gap,
)
from exudyn_turnout.wheel_rail.references import ReferenceCase  # noqa: E402
from exudyn_turnout.wheel_rail.section_nodes import (  # noqa: E402
    first_touch_heights,
    section_nodes,
    transfer_nodes,
    wheel_heights,
)
from exudyn_turnout.wheel_rail.sections import (  # noqa: E402
    SectionGrid,
    lateral_grid,
    slice_heights,
    slice_surface,
    wheel_envelope,
)
from exudyn_turnout.wheel_rail.tables import TableSettings, build_contact_table  # noqa: E402
from exudyn_turnout.wheel_rail.transfer import rail_runs  # noqa: E402
from exudyn_turnout.wheel_rail.turnout_design import RailGeometry  # noqa: E402
from exudyn_turnout.wheel_rail.turnout_sections import (  # noqa: E402
    HEAD_THRESHOLD,
    TRANSFER_SHIFTS,
)

OUT = Path(__file__).with_suffix(".md")
SLICE_FILE = "uk_crossing.slcs"
#: steel, as the tables' defaults (TableSettings: E = 210 GPa, nu = 0.3)
MODULUS = effective_modulus(TableSettings().young, TableSettings().poisson)
#: m, shifts of the table (the passage's step 0.2 mm; a node's values do not depend on the
#: range, so a narrower one than the passage's +-12 mm gives the same nodes, 5x faster)
TABLE_SHIFTS = (-0.008, 0.004)
#: m, the table's x range (u of the slices), around the transfer
TABLE_X = (0.05, 0.55)
#: m, x range of the diagnostic table on uniform nodes (:func:`crossing_table`)
FINE_X = (0.2, 0.34)
#: m, its node spacing
FINE_STEP = 0.002
#: the third method's name on the page (:func:`kp_split`)
KP_NAME = "KP, 2-D section"
#: the fourth method's name: the passage's tables on the nodes it had before the transfer
#: nodes (the slice positions alone), for the comparison before -> after
OLD_NAME = "tables, slice nodes only"
#: m, element size of the reference along x and y (halved once at one u: see the page)
DX, DY = 5e-4, 2.5e-4
#: m, first window of the reference grid: x from the wheel centre, y on the slices
X_WINDOW = (-0.02, 0.025)
Y_WINDOW = (-0.048, 0.065)
#: m, the grid keeps the elements whose undeformed gap is below this (both heads)
GAP_LEVEL = 1e-3
#: the loads' sources, N: the packaged vehicle's static wheel load (M g / 8) and
#: CONTACT's FN of its packaged cases (about 10 kN)
CONTACT_FN = 1.0e4
#: m, lateral wheel positions: CONTACT's Y = 0 (every packaged case) and -2.5 mm, where
#: the passage puts a centred wheelset on this slice set (its gauge point, y = -35.0 mm, at
#: gauge / 2 = 717.5 mm and the taping line at 750 mm: 32.5 - 35.0 = -2.5 mm)
PASSAGE_Y = -0.0025
POSITIONS = (0.0, PASSAGE_Y)
#: m, the sweep covers the rigid transfer +- this (both patches carry within +-10 mm)
SWEEP_HALF_WIDTH = 0.012


@dataclass(frozen=True)
class Split:
    """One method's normal solution of both patches at one wheel position (SI)."""

    nose: float  #: N, vertical force on the nose
    wing: float  #: N, vertical force on the wing rail
    height: float  #: m, wheel height (profile origin, CONTACT's -Z) carrying the load
    approach: float  #: m, descent of the wheel below its first touch
    y_nose: float  #: m, lateral force centre of the nose patch (slice frame; NaN: none)
    y_wing: float  #: m, the same on the wing rail
    regions: int  #: separate contact regions (reference; tables: loaded candidates)
    #: m, height of the wheel at which the nose first touches it (rigid surfaces; NaN: none)
    touch_nose: float = math.nan
    touch_wing: float = math.nan  #: m, the same for the wing rail

    @property
    def share(self) -> float:
        """The nose's share of the total vertical force (-)."""
        return self.nose / (self.nose + self.wing)


def _case(u: float, y: float, height: float) -> ReferenceCase:
    """A CONTACT-style wheel position on the UK crossing (fields surface_gap reads)."""
    return ReferenceCase(
        source="", case=0, rail_file=SLICE_FILE, s=u, y=y, wheel_height=height,
        x_contact=0.0, y_contact_rail=0.0, z_contact_rail=0.0, y_contact_wheel=0.0,
        approach=0.0, normal_force=0.0,
    )  # fmt: skip


#: surface_gap's frame: lateral tangent = the slices' y (contact angle 0, origin y = 0)
_FRAME = CaseGeometry(
    gap=np.zeros(1), table_gap=np.zeros(1), a_sum=0.0, a_raw=0.0, b_raw=0.0, angle=0.0,
    y_rail=0.0, z_rail=0.0, interpenetration=0.0, x_offset=0.0, wheel_y=np.zeros(1),
    wheel_z=np.zeros(1),
)  # fmt: skip


@functools.lru_cache(maxsize=1)
def _surface():
    """The slice set as the passage's sections see it (slice frame, 0.1 mm grid)."""
    slices = read_slices(profile_path(SLICE_FILE))
    y = lateral_grid(-0.08, 0.12, RailGeometry().grid_step)
    return slices, slice_surface(slices, y)


def split_position(u: float) -> float:
    """The middle of the flangeway between nose and wing rail in the section at u.

    Parameters
    ----------
    u : float
        m, position along the slices.

    Returns
    -------
    float
        m, lateral position (slice frame): the nose lies below it, the wing rail above.
    """
    _slices, surface = _surface()
    z = slice_heights(surface, np.array([u]))[0]
    top = float(np.nanmax(z))
    runs = rail_runs(z, top - 0.010)
    y = surface.y
    # the two heads a wheel at the slices' y = -40 ... +60 mm can touch
    heads = [r for r in runs if y[r.stop - 1] > -0.04 and y[r.start] < 0.06]
    if len(heads) < 2:
        raise ValueError(f"u = {u} m: no flangeway between two heads")
    return 0.5 * float(y[heads[0].stop - 1] + y[heads[1].start])


def reference_split(
    u: float, y: float, load: float, dx: float = DX, dy: float = DY
) -> tuple[Split, object]:
    """Exact normal solution on the 3-D gap spanning both rails, at total vertical load.

    Parameters
    ----------
    u, y : float
        m, wheel position along the slices and lateral position (CONTACT's S and Y).
    load : float
        N, total vertical load.
    dx, dy : float
        m, element size.

    Returns
    -------
    (Split, NormalSolution)
        The split, and the solution (its ``x``, ``y`` on the 3-D grid: x from the wheel
        centre, y in the slice frame).
    """
    pdir = profile_path(SLICE_FILE).parent
    x_lo, x_hi = X_WINDOW
    y_lo, y_hi = Y_WINDOW
    for _ in range(4):
        x = np.arange(x_lo, x_hi + 0.5 * dx, dx)
        t = np.arange(y_lo, y_hi + 0.5 * dy, dy)
        h = surface_gap(_case(u, y, 0.0), _FRAME, pdir, x, t)
        lowest = float(np.min(h))
        near = h - lowest < GAP_LEVEL
        rows = np.flatnonzero(near.any(axis=1))
        cols = np.flatnonzero(near.any(axis=0))
        rows = slice(max(rows[0] - 2, 0), min(rows[-1] + 3, len(x)))
        cols = slice(max(cols[0] - 2, 0), min(cols[-1] + 3, len(t)))
        solved = solve_normal(h[rows, cols] - lowest, dx, dy, MODULUS, force=load)
        inside = solved.pressure > 0.0
        edge = inside[0].any() or inside[-1].any() or inside[:, 0].any() or inside[:, -1].any()
        if not edge:
            break
        x_lo, x_hi = x_lo - 0.01, x_hi + 0.01
        y_lo, y_hi = y_lo - 0.01, y_hi + 0.01
    xs, ts = x[rows], t[cols]
    p = solved.pressure
    split = split_position(u)
    on_nose = ts < split
    element = dx * dy
    nose = float(p[:, on_nose].sum()) * element
    wing = float(p[:, ~on_nose].sum()) * element
    column = p.sum(axis=0)

    def centre(mask):
        total = float(column[mask].sum())
        return float(np.sum(column[mask] * ts[mask]) / total) if total > 0.0 else math.nan

    regions = int(ndimage.label(inside, structure=np.ones((3, 3)))[1])
    result = Split(
        nose=nose, wing=wing, height=-lowest - solved.approach, approach=solved.approach,
        y_nose=centre(on_nose), y_wing=centre(~on_nose), regions=regions,
        touch_nose=-float(h[:, t < split].min()), touch_wing=-float(h[:, t >= split].min()),
    )  # fmt: skip
    return result, dataclasses.replace(solved, x=xs, y=ts)


def crossing_table(
    cache_dir: str | Path | None = None, x_step: float | None = None, transfer: bool = True
) -> PackedTables:
    """The passage's contact table of the UK crossing slices, packed for the kernel.

    Sections at the x nodes a ``slices`` segment gets (:mod:`.turnout_sections`: the
    slice positions as break points, ``section_nodes`` with the default ``[wheel_rail]``
    tolerance and minimum step, then ``transfer_nodes`` where nose and wing rail share the
    wheel), the rigid wheel's envelope (default reach and step), the
    table of the S1002 wheel with its profile origin as the taping line (so the table's
    shift is CONTACT's Y and its lift CONTACT's -Z).

    Parameters
    ----------
    cache_dir : str or Path, optional
        Table cache (default: the package's).
    x_step : float, optional
        m, instead of the passage's nodes, uniform nodes this far apart over
        :data:`FINE_X` (a diagnostic: the same sections, law and kernel, finer along x).
    transfer : bool
        Add the transfer nodes (False: the slice positions' nodes alone, as the passage
        had them before ``transfer_nodes``).

    Returns
    -------
    PackedTables
        One body, side +1, its lateral and vertical coordinates at q[5], q[6].
    """
    geometry = RailGeometry()
    slices, surface = _surface()
    if x_step is None:
        a, b = TABLE_X
        points = sorted({a, b} | {float(v) for v in slices.u if a <= v <= b})
        x, z = section_nodes(
            lambda v: slice_heights(surface, np.array([v]))[0],
            points,
            geometry.section_tolerance,
            geometry.min_step,
            slice(0, len(surface.y)),
            geometry.grid_step,
        )
        # the passage's nodes where nose and wing rail share the wheel (turnout_sections:
        # the S1002 wheel over the running rails' shift range, here in the slice frame,
        # where the passage's centred wheelset stands at Y = -2.5 mm)
        wheel = s1002_wheel()
        low, high, step = TRANSFER_SHIFTS
        shifts = PASSAGE_Y + low + step * np.arange(int(round((high - low) / step)) + 1)
        over = wheel_heights(surface.y, wheel.s, wheel.z, 0.0, shifts)
        extra = np.zeros(0)
        if transfer:
            extra = transfer_nodes(
                lambda v: first_touch_heights(
                    slice_heights(surface, np.array([v]))[0], over, HEAD_THRESHOLD
                ),
                x,
            )
        x = np.sort(np.concatenate((x, extra)))
        z = slice_heights(surface, x)
        nodes = x
    else:
        a, b = FINE_X
        reach = geometry.envelope_reach
        x = np.arange(a - reach, b + reach + 0.5 * x_step, x_step)
        z = slice_heights(surface, x)
        nodes = np.arange(a, b + 0.5 * x_step, x_step)
    sections = SectionGrid(x=x, y=surface.y, z=z, name="uk_crossing slices")
    enveloped = wheel_envelope(
        sections, nodes, NOMINAL_RADIUS, geometry.envelope_reach, geometry.envelope_step
    )
    settings = TableSettings(shift_min=TABLE_SHIFTS[0], shift_max=TABLE_SHIFTS[1])
    table = build_contact_table(s1002_wheel(), enveloped, 0.0, settings, cache_dir)
    return pack_tables([table], [1], [(5, 6)], [(-np.inf, np.inf)], ["uk_crossing"], MODULUS)


def kernel_rows(packed: PackedTables, u: float, y: float, height: float) -> np.ndarray:
    """The kernel's per-candidate rows for the wheel at (u, y, height), no creep.

    Parameters
    ----------
    packed : PackedTables
        From :func:`crossing_table`.
    u, y, height : float
        m, wheel position (CONTACT's S, Y, -Z).

    Returns
    -------
    numpy.ndarray
        (n_candidates, len(DETAIL_FIELDS)) rows of ``kernel.contact_forces``.
    """
    q = np.array([y, height, 0.0, 0.0, 0.0, 0.0, 0.0])
    forces = np.zeros(q.size)
    details = np.zeros((packed.n_bodies * packed.n_candidates, len(DETAIL_FIELDS)))
    constants = np.array([0.0, NOMINAL_RADIUS, 0.3, 8.0e10, 0.0, 0.0])  # v = 0: no creep
    contact_forces(
        u, q, np.zeros_like(q), np.zeros(4), packed.values, packed.blendable, packed.x,
        packed.layout, packed.bounds, constants, forces, details,
    )  # fmt: skip
    return details


_NORMAL, _FZ, _Y_RAIL, _DELTA, _ANGLE, _FOUND = (
    DETAIL_FIELDS.index(n) for n in ("normal", "Fz", "y_rail", "delta", "angle", "found")
)


def table_split(packed: PackedTables, u: float, y: float, load: float) -> Split:
    """The kernel's split at the wheel height whose vertical forces sum to ``load``.

    Parameters
    ----------
    packed : PackedTables
        From :func:`crossing_table`.
    u, y : float
        m, wheel position along the slices and lateral position.
    load : float
        N, total vertical load.

    Returns
    -------
    Split
    """

    def total(height: float) -> float:
        return float(kernel_rows(packed, u, y, height)[:, _FZ].sum())

    high = 0.01  # m: above both rails (the slices' tops are below 4 mm)
    low = high - 0.001
    while total(low) < load:
        low -= 0.001
    height = brentq(lambda h: total(h) - load, low, high, xtol=1e-14)
    rows = kernel_rows(packed, u, y, height)
    split = split_position(u)
    loaded = rows[:, _NORMAL] > 0.0
    nose_rows = loaded & (rows[:, _Y_RAIL] < split)
    wing_rows = loaded & (rows[:, _Y_RAIL] >= split)

    def centre(mask):
        f = rows[mask, _FZ]
        return float(np.sum(f * rows[mask, _Y_RAIL]) / f.sum()) if f.sum() > 0 else math.nan

    # descent below first touch: the deepest candidate's normal penetration, vertical
    found = rows[:, _FOUND] > 0.0
    descent = np.where(found, rows[:, _DELTA] / np.cos(rows[:, _ANGLE]), -np.inf)
    nose_found = found & (rows[:, _Y_RAIL] < split)
    wing_found = found & (rows[:, _Y_RAIL] >= split)
    return Split(
        nose=float(rows[nose_rows, _FZ].sum()), wing=float(rows[wing_rows, _FZ].sum()),
        height=height, approach=float(descent.max()), y_nose=centre(nose_rows),
        y_wing=centre(wing_rows), regions=int(np.count_nonzero(loaded)),
        touch_nose=height + float(descent[nose_found].max()) if nose_found.any() else math.nan,
        touch_wing=height + float(descent[wing_found].max()) if wing_found.any() else math.nan,
    )  # fmt: skip


def kp_split(u: float, y: float, load: float) -> Split:
    """Kik-Piotrowski on each candidate of the 2-D section at u, in vertical equilibrium.

    The section exactly at u (the slice set interpolated along u, enveloped by the rigid
    wheel with the passage's reach and step), its candidates (``search_candidates``), each
    one's lateral gap function (``normal_gap_function``, every 0.02 mm) and KP's force at
    its penetration (``kik_piotrowski``, A = cos(gamma) / (2 r) floored as the tables);
    no table, no node interpolation, no Hertz.

    Parameters
    ----------
    u, y : float
        m, wheel position along the slices and lateral position.
    load : float
        N, total vertical load.

    Returns
    -------
    Split
        ``regions``: candidates carrying load.
    """
    geometry = RailGeometry()
    _slices, surface = _surface()
    reach, step = geometry.envelope_reach, geometry.envelope_step
    x = u + np.arange(-reach, reach + 0.5 * step, step)
    sections = SectionGrid(x=x, y=surface.y, z=slice_heights(surface, x), name="at u")
    enveloped = wheel_envelope(sections, np.array([u]), NOMINAL_RADIUS, reach, step)
    derivatives = surface_derivatives(enveloped)
    rail = prepare_rail(enveloped.z[0], derivatives.slope[0], derivatives.curvature[0], surface.y)
    wheel = prepare_wheel(_wheel(), 0.0, 0.0, (FLANGE_DIRECTION,))
    found = search_candidates(rail, wheel, shift=y, lift=0.0)
    n = len(found.gap)
    gaps = normal_gap_function(
        rail, wheel, np.full(n, y), found.y_rail, found.z_rail, found.angle,
        step=GAP_SAMPLE_STEP, window=GAP_SAMPLE_WINDOW,
    )  # fmt: skip
    cosine = np.cos(found.angle)
    a_sum = np.maximum(0.5 * cosine / found.radius, MIN_CURVATURE_SUM)

    def vertical(height: float) -> np.ndarray:
        delta = -(found.gap + cosine * height)
        out = np.zeros(n)
        pressed = delta > 0.0
        if pressed.any():
            patch = kik_piotrowski(
                gaps[pressed], GAP_SAMPLE_STEP, a_sum[pressed], delta[pressed], MODULUS
            )
            out[pressed] = patch.normal_force * cosine[pressed]
        return out

    top = float(np.max(-found.gap / cosine))  # first touch
    low = top - 0.001
    while vertical(low).sum() < load:
        low -= 0.001
    height = brentq(lambda h: vertical(h).sum() - load, low, top, xtol=1e-14)
    forces = vertical(height)
    split = split_position(u)
    on_nose = found.y_rail < split

    def centre(mask):
        f = forces[mask]
        return float(np.sum(f * found.y_rail[mask]) / f.sum()) if f.sum() > 0 else math.nan

    return Split(
        nose=float(forces[on_nose].sum()), wing=float(forces[~on_nose].sum()),
        height=height, approach=top - height, y_nose=centre(on_nose),
        y_wing=centre(~on_nose), regions=int(np.count_nonzero(forces)),
        touch_nose=float(np.max(-found.gap[on_nose] / cosine[on_nose]))
        if on_nose.any() else math.nan,
        touch_wing=float(np.max(-found.gap[~on_nose] / cosine[~on_nose]))
        if (~on_nose).any() else math.nan,
    )  # fmt: skip


@functools.lru_cache(maxsize=1)
def _wheel():
    return s1002_wheel()


def rigid_transfer(y: float, u_range=(0.15, 0.4), step: float = 0.005) -> float:
    """u where the rigid wheel touches nose and wing rail at once (3-D gap, linear in u).

    Parameters
    ----------
    y : float
        m, lateral wheel position.
    u_range : (float, float)
        m, where to look.
    step : float
        m, scan step.

    Returns
    -------
    float
        m.
    """
    pdir = profile_path(SLICE_FILE).parent
    x = np.arange(X_WINDOW[0], X_WINDOW[1] + 0.5e-3, 1e-3)
    t = np.arange(Y_WINDOW[0], Y_WINDOW[1] + 0.5e-3, 2.5e-4)
    us = np.arange(u_range[0], u_range[1] + 0.5 * step, step)
    difference = []
    for u in us:
        h = surface_gap(_case(float(u), y, 0.0), _FRAME, pdir, x, t).min(axis=0)
        split = split_position(float(u))
        difference.append(float(h[t < split].min() - h[t >= split].min()))
    d = np.array(difference)
    k = int(np.flatnonzero((d[:-1] > 0.0) & (d[1:] <= 0.0))[0])
    return float(us[k] - d[k] * (us[k + 1] - us[k]) / (d[k + 1] - d[k]))


def half_point(u: np.ndarray, share: np.ndarray) -> float:
    """u where the nose's share first reaches 50 % (linear between points; NaN: never).

    Parameters
    ----------
    u, share : numpy.ndarray
        m and -, the sweep.

    Returns
    -------
    float
        m.
    """
    above = np.flatnonzero((share[:-1] < 0.5) & (share[1:] >= 0.5))
    if above.size == 0:
        return math.nan
    k = int(above[0])
    return float(u[k] + (0.5 - share[k]) * (u[k + 1] - u[k]) / (share[k + 1] - share[k]))


def _fmt(value: float, scale: float = 1e3, digits: int = 2) -> str:
    return "-" if not math.isfinite(value) else f"{value * scale:.{digits}f}"


def _within(tab: float, ref: float) -> tuple[bool, bool]:
    """(both patches' shares within 10 % of the reference's, nose share within 0.05)."""
    ten = abs(tab - ref) <= 0.1 * ref and abs(tab - ref) <= 0.1 * (1.0 - ref)
    return ten, abs(tab - ref) <= 0.05


def _law_error(touches: dict, shares: dict, name: str, mask: np.ndarray) -> float:
    """Largest nose-share difference at the reference's first-touch difference.

    The tables' share interpolated over their own first-touch difference (nose minus wing)
    at the reference's: what is left when both methods see the same rigid geometry, i.e.
    the normal law (2-D KP / Hertz per patch, no elastic interaction) alone.
    """
    d_tab = np.array(touches[name])
    share = np.array(shares[name])
    finite = np.isfinite(d_tab)
    order = np.argsort(d_tab[finite])
    d_ref = np.array(touches["ref"])[mask]
    at = np.interp(d_ref, d_tab[finite][order], share[finite][order])
    return float(np.max(np.abs(at - np.array(shares["ref"])[mask]))) if mask.any() else 0.0


def _range(u: np.ndarray, share: np.ndarray) -> str:
    both = (share > 0.0) & (share < 1.0)
    return f"{u[both].min():.4f} - {u[both].max():.4f}" if both.any() else "-"


def sweep(methods: dict, y: float, load: float, us, lines: list) -> dict:
    """One lateral position and load: the page's rows into ``lines``; summary numbers.

    ``methods``: name -> ``f(u, y, load) -> Split``; the first is the passage's tables,
    then the 2 mm table and KP on the 2-D section.
    """
    names = list(methods)
    lines += [
        "| u (m) | regions ref | nose share ref | tables | diff (pp) | diff (% of ref) | "
        f"{' | '.join(names[1:])} | nose - wing first touch ref / "
        f"{' / '.join(names)} (um) | "
        "approach ref / tables (um) | y nose ref / tables (mm) | y wing ref / tables (mm) |",
        "|---|---|---|---|---|---|" + "---|" * (len(names) - 1) + "---|---|---|---|",
    ]
    shares: dict[str, list[float]] = {"ref": [], **{n: [] for n in names}}
    touches: dict[str, list[float]] = {"ref": [], **{n: [] for n in names}}
    both = []
    approaches: dict[str, list[float]] = {"ref": [], **{n: [] for n in names}}
    for u in us:
        ref, _solution = reference_split(float(u), y, load)
        splits = {n: method(float(u), y, load) for n, method in methods.items()}
        for split in (ref, *splits.values()):  # vertical equilibrium of every method
            if abs(split.nose + split.wing - load) > 1e-6 * load:
                raise RuntimeError(f"u = {u}: {split} does not carry {load} N")
        tab = splits[names[0]]
        r, s = ref.share, tab.share
        shares["ref"].append(r)
        touches["ref"].append(ref.touch_nose - ref.touch_wing)
        for n, split in splits.items():
            shares[n].append(split.share)
            touches[n].append(split.touch_nose - split.touch_wing)
        both.append(ref.nose > 0.0 and ref.wing > 0.0)
        approaches["ref"].append(ref.approach)
        for n, split in splits.items():
            approaches[n].append(split.approach)
        relative = f"{(s - r) / r * 100:+.1f}" if r > 0 else "-"
        touch = [_fmt(m.touch_nose - m.touch_wing, 1e6, 1) for m in (ref, *splits.values())]
        others = " | ".join(f"{splits[n].share:.3f}" for n in names[1:])
        lines.append(
            f"| {u:.4f} | {ref.regions} | {r:.3f} | {s:.3f} | {(s - r) * 100:+.1f} | "
            f"{relative} | {others} | {' / '.join(touch)} | "
            f"{ref.approach * 1e6:.1f} / {tab.approach * 1e6:.1f} | "
            f"{_fmt(ref.y_nose)} / {_fmt(tab.y_nose)} | {_fmt(ref.y_wing)} / {_fmt(tab.y_wing)} |"
        )
    u_arr = np.asarray(us, float)
    mask = np.array(both)
    ref_share = np.array(shares["ref"])
    summary: dict = {"points": int(mask.sum()), "u50_ref": half_point(u_arr, ref_share)}
    summary["two_ref"] = _range(u_arr, ref_share)
    if len(names) > 2:  # the 2 mm table's and KP's first-touch differences (same section)
        gap = np.abs(np.array(touches[names[1]]) - np.array(touches[names[2]]))
        summary["fine_kp"] = float(np.nanmax(gap))
    d_ref = np.array(touches["ref"])
    middle = mask & (ref_share > 0.1) & (ref_share < 0.9)
    summary["slope"] = (
        float(np.polyfit(d_ref[middle], ref_share[middle], 1)[0]) if middle.sum() >= 2 else math.nan
    )
    # one rail alone (in both methods): a method's approach over the exact one, - 1
    exact = np.array(approaches["ref"])
    summary["stiffness"] = {}
    for n in names:
        ratios = np.array(approaches[n]) / exact - 1.0
        share = np.array(shares[n])
        summary["stiffness"][n] = {
            rail: (float(ratios[only].min()), float(ratios[only].max()))
            for rail, only in (
                ("wing", (ref_share == 0.0) & (share == 0.0)),
                ("nose", (ref_share == 1.0) & (share == 1.0)),
            )
            if only.any()
        }
    share_any = np.array([np.array(v) for v in shares.values()])
    moving = np.flatnonzero(np.any((share_any > 0.0) & (share_any < 1.0), axis=0))
    low, high = max(int(moving.min()) - 2, 0), min(int(moving.max()) + 2, len(u_arr) - 1)
    summary["shown"] = (float(u_arr[low]), float(u_arr[high]))
    for n in names:
        share = np.array(shares[n])
        within = [_within(a, b) for a, b in zip(share[mask], ref_share[mask])]
        summary[n] = {
            "ok10": sum(w[0] for w in within),
            "ok05": sum(w[1] for w in within),
            "worst": float(np.max(np.abs(share[mask] - ref_share[mask]))) if within else 0.0,
            "u50": half_point(u_arr, share),
            "law": _law_error(touches, shares, n, mask),
            "geometry": float(np.max(np.abs(np.array(touches[n])[mask] - d_ref[mask])))
            if mask.any()
            else 0.0,
            "two": _range(u_arr, share),
        }
    return summary


def _convergence(y: float, load: float) -> list[str]:
    """The reference at half the element size, at the rigid transfer."""
    u = rigid_transfer(y)
    coarse, _ = reference_split(u, y, load)
    fine, _ = reference_split(u, y, load, 0.5 * DX, 0.5 * DY)
    return [
        f"Element size, reference at Y = {y * 1e3:+.1f} mm, W = {load / 1e3:.1f} kN, "
        f"u = {u:.4f} m: nose share {coarse.share:.4f} at {DX * 1e3:g} x {DY * 1e3:g} mm, "
        f"{fine.share:.4f} at half of it ({(fine.share - coarse.share) * 100:+.2f} pp); "
        f"approach {coarse.approach * 1e6:.2f} / {fine.approach * 1e6:.2f} um.",
    ]


def _explanation(summaries: list, tables: dict, fine_name: str) -> list[str]:
    """The "why" section, from the sweep's numbers."""
    y, load, first = summaries[0]
    passage = tables["tables"]
    u50 = first["u50_ref"]
    packed = tables["tables"]
    at = table_split(packed, u50, y, load)
    rows = kernel_rows(packed, u50, y, at.height)
    semi = rows[rows[:, _NORMAL] > 0.0, DETAIL_FIELDS.index("semi_hertzian")]
    geometry = ", ".join(
        f"{s[OLD_NAME]['geometry'] * 1e6:.1f} / {s['tables']['geometry'] * 1e6:.1f} / "
        f"{s[fine_name]['geometry'] * 1e6:.1f} um (Y = {yy * 1e3:+.1f} mm, {w / 1e3:.1f} kN)"
        for yy, w, s in summaries
    )
    old = tables[OLD_NAME]
    k_old = int(np.searchsorted(old.x, u50))
    old_cell = (float(old.x[k_old - 1]), float(old.x[k_old]))
    inside = passage.x[(passage.x > old_cell[0] - 1e-9) & (passage.x < old_cell[1] + 1e-9)]
    slopes = ", ".join(
        f"{s['slope'] * 1e-6 * 100:.2f} percentage points per um at {w / 1e3:.1f} kN "
        f"(Y = {yy * 1e3:+.1f} mm)"
        for yy, w, s in summaries
        if math.isfinite(s["slope"])
    )

    def stiffness(method: str) -> str:
        return "; ".join(
            f"Y = {yy * 1e3:+.1f} mm, {w / 1e3:.1f} kN: "
            + ", ".join(
                f"{name} alone {lo * 100:+.1f} ... {hi * 100:+.1f} %"
                for name, (lo, hi) in s["stiffness"][method].items()
            )
            for yy, w, s in summaries
        )

    return [
        "## Why the tables differ",
        "",
        "The split follows the difference of the rails' first-touch heights d (nose minus "
        "wing): the reference's nose share changes by "
        f"{slopes} of d in the transfer (a linear fit between 10 and 90 %).  An error of d "
        "weighs more the smaller the approach, i.e. the smaller the load.",
        "",
        "- **Geometry along x (the passage's x nodes).**  The largest error of d where the "
        f"reference has two patches, {OLD_NAME} / passage tables / {fine_name}: "
        f"{geometry}.  On the slice positions alone (``section_nodes`` takes them as break "
        "points and adds none between them: midway the section differs from the blend of "
        "its ends by less than the 0.2 mm section tolerance) the transfer at "
        f"Y = {y * 1e3:+.1f} mm (u50 = {u50:.4f} m) lies inside one table cell, "
        f"{old_cell[0]:.4f} - {old_cell[1]:.4f} m "
        f"({(old_cell[1] - old_cell[0]) * 1e3:.1f} mm), where the kernel interpolates each "
        "rail's contact linearly along x, while on the 3-D surface (the slices interpolated "
        "along u at constant y, shape-preserving cubic) the rails' first-touch heights do "
        "not vary linearly between the slices: those tables meet the nose late and keep "
        "load on the wing rail over the second half of the transfer.  The passage now adds "
        "x nodes where two rails share the wheel (``section_nodes.transfer_nodes``: a cell "
        "is halved while, for the rigid S1002 wheel at some shift of the tables' +-12 mm, "
        "nose and wing rail are both within 0.2 mm of first touch and the difference of "
        "their first-touch heights departs from linear by more than 2 um at its middle, "
        f"down to 1 mm): {len(inside)} nodes in that cell, "
        f"{(float(np.max(np.diff(inside))) if len(inside) > 1 else 0.0) * 1e3:.1f} mm apart "
        f"at most ({len(passage.x)} nodes over {TABLE_X[0]:g} - {TABLE_X[1]:g} m instead of "
        f"{len(old.x)}).  On 2 mm nodes (the same interpolated surface sampled densely) the "
        "same law and kernel follow d within the last numbers; what remains there is the "
        "2-D section (wheel envelope of the polygon slices) against the 3-D spline "
        "surfaces.  Which of the two is the crossing between two slices the data do not "
        "say: the slices are its only description, and CONTACT interpolates them along u "
        "in its own way (by features).",
        "- **Normal law.**  At the reference's own d (the tables' share interpolated over "
        "their d), the largest difference of the nose share is the last column of the "
        "summary: that part is the law's.  Here both patches are Hertz nodes (weight of "
        "the KP law at u50: "
        + ", ".join(f"{v:.2f}" for v in semi)
        + "): the tables' law per patch, without the elastic interaction of the two "
        "patches (the exact solution has it: a force F on a half-space lowers the surface "
        "by F / (pi E* r), about 1 um at the 68 mm between the patches).  "
        f"'{KP_NAME}' sees the geometry of the {FINE_STEP * 1e3:g} mm table (the section "
        "exactly at u; their first-touch differences d agree within "
        f"{max(s['fine_kp'] for _y, _w, s in summaries) * 1e6:.1f} um) with "
        "Kik-Piotrowski's law instead of Hertz's: the two differ by the law alone.  Where "
        "one rail carries alone (in both methods), the approach against the exact one, "
        f"tables: {stiffness('tables')}; {KP_NAME}: {stiffness(KP_NAME)}.  The exact "
        "approach on the wing rail alone changes along u between two slices (the 3-D "
        "surface there is the slices' interpolation along u at constant y, the wing rail's "
        "crown moving sideways at 1:9.25 through it); on the slice positions alone the "
        "tables', linear between the slices, hardly "
        f"({OLD_NAME}: {stiffness(OLD_NAME)}); the transfer nodes follow it in part.",
        "",
        "Nothing was tuned: the tables are the passage's (default section tolerance, "
        "envelope and law).",
    ]


def main(argv: list[str] | None = None) -> int:
    """Write the page."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="coarse sweep (2 mm steps)")
    parser.add_argument("--out", type=Path, default=OUT, help="page to write")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    static = float(load_vehicle_model().static_wheel_load)
    fine_name = f"tables, {FINE_STEP * 1e3:g} mm x nodes"
    tables = {
        "tables": crossing_table(),
        fine_name: crossing_table(x_step=FINE_STEP),
        OLD_NAME: crossing_table(transfer=False),
    }
    passage_x = tables["tables"].x
    methods = {
        name: functools.partial(table_split, packed)
        for name, packed in tables.items()
        if name != OLD_NAME
    }
    methods[KP_NAME] = kp_split
    methods[OLD_NAME] = functools.partial(table_split, tables[OLD_NAME])
    step = 0.002 if args.quick else 0.0005
    lines = [
        "# Normal-force split between wing rail and nose: passage tables vs exact 3-D",
        "",
        "Written by `python validation/two_patch_split.py` (methods in its docstring).  "
        f"UK crossing 56E1-R245-1:9.25 slices, S1002 wheel (r = {NOMINAL_RADIUS} m), no roll "
        "or yaw, CONTACT's lateral convention (wheel profile origin at the slices' Y).  "
        "Reference: exact half-space normal contact on the 3-D gap spanning both rails "
        f"({DX * 1e3:g} x {DY * 1e3:g} mm elements); tables: the passage's contact table of "
        "the 2-D sections and its kernel; "
        f"{fine_name}: the same on uniform x nodes {FINE_STEP * 1e3:g} mm apart (a "
        f"diagnostic); {KP_NAME}: Kik-Piotrowski on each contact of the 2-D section "
        f"exactly at u (no table); {OLD_NAME}: the passage's tables on the nodes it had "
        "before x nodes were added where two rails share the wheel (the slice positions "
        "alone).  Every method at the wheel height that carries the load "
        f"(E* = {MODULUS / 1e9:.1f} GPa).",
        "",
        "Loads: the static wheel load of the packaged vehicle "
        f"(M g / 8 = {static / 1e3:.1f} kN: what a passage's wheel carries over the "
        f"crossing) and CONTACT's FN of its packaged cases ({CONTACT_FN / 1e3:.0f} kN).  "
        "Nose share = vertical force on the nose / total; diff in percentage points and in % "
        "of the reference share; first touch: the wheel height at which each rail alone "
        "touches the rigid wheel, nose minus wing (> 0: the nose is met first); approach = "
        "descent of the wheel below its first touch; y: lateral force centre of each patch "
        "in the slices' frame (the nose on the gauge side, y < 0).  The passage's x nodes "
        "here: "
        + ", ".join(f"{v:.4f}" for v in passage_x[(passage_x > 0.2) & (passage_x < 0.31)])
        + " m.",
        "",
    ]
    summaries = []
    cases = [(y, static) for y in POSITIONS] + [(0.0, CONTACT_FN)]
    for y, load in cases:
        centre = rigid_transfer(y)
        count = int(round(SWEEP_HALF_WIDTH / step))
        us = np.round(centre + step * np.arange(-count, count + 1), 5)
        summary_lines: list[str] = []
        summary = sweep(methods, y, load, us, summary_lines)
        # the page shows the transfer and 2 points either side of it
        keep = [k for k, u in enumerate(us) if summary["shown"][0] <= u <= summary["shown"][1]]
        lines += [
            f"## Y = {y * 1e3:+.1f} mm, W = {load / 1e3:.1f} kN",
            "",
            f"Rigid transfer (both rails touch the rigid wheel, 3-D gap): u = {centre:.4f} m.",
            "",
            *summary_lines[:2],
            *(summary_lines[2 + k] for k in keep),
            "",
        ]
        summaries.append((y, load, summary))
    lines += [
        "## Summary",
        "",
        "Points: u where the reference has load on both rails.  Within 10 %: both patches' "
        "shares within 10 % of the reference's; within 0.05: the nose share within 0.05 of "
        "it; worst: the largest difference of the nose share there.  u50: where the nose "
        "carries 50 % (linear between points).",
        "",
        "| Y (mm) | W (kN) | two patches u (m): ref / tables | points | tables: within 10 % / "
        "0.05, worst | u50 ref / tables (m) | u50 shift (mm) | "
        f"{fine_name}: within 10 % / 0.05, worst | u50 shift (mm) | {KP_NAME}: within 10 % / "
        "0.05, worst | u50 shift (mm) | worst at the reference's first-touch difference: "
        f"tables / 2 mm / KP | {OLD_NAME}: within 10 % / 0.05, worst | u50 shift (mm) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for y, load, s in summaries:
        t, f, k, o = s["tables"], s[fine_name], s[KP_NAME], s[OLD_NAME]
        lines.append(
            f"| {y * 1e3:+.1f} | {load / 1e3:.1f} | {s['two_ref']} / {t['two']} | "
            f"{s['points']} | {t['ok10']} / {t['ok05']}, {t['worst']:.3f} | "
            f"{s['u50_ref']:.4f} / {t['u50']:.4f} | {(t['u50'] - s['u50_ref']) * 1e3:+.2f} | "
            f"{f['ok10']} / {f['ok05']}, {f['worst']:.3f} | "
            f"{(f['u50'] - s['u50_ref']) * 1e3:+.2f} | "
            f"{k['ok10']} / {k['ok05']}, {k['worst']:.3f} | "
            f"{(k['u50'] - s['u50_ref']) * 1e3:+.2f} | "
            f"{t['law']:.3f} / {f['law']:.3f} / {k['law']:.3f} | "
            f"{o['ok10']} / {o['ok05']}, {o['worst']:.3f} | "
            f"{(o['u50'] - s['u50_ref']) * 1e3:+.2f} |"
        )
    lines += ["", *_explanation(summaries, tables, fine_name), "", *_convergence(*cases[0])]
    lines += ["", f"Total run time {time.perf_counter() - start:.0f} s.", ""]
    args.out.write_text("\n".join(lines), encoding="utf-8")
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
