"""Wheel/rail contact from real profiles: readers, sections, geometry, Hertz, creep, tables.

Self-contained (numpy/scipy; no exudyn): the passage simulation plugs in through
:func:`tables.build_contact_table` and :func:`tables.lookup`.  Conventions (every module):
SI units; a profile's lateral axis y points towards the field side, z up; rails placed in
*side coordinates* (y from the track centre line, the same for left and right rail); contact
angles positive when the normal force on the wheel points towards the track centre.

Modules: :mod:`.profiles` (Simpack .prw/.prr, CONTACT .slcs readers), :mod:`.sections`
(gridded rail sections along x, placement, slices, switch/crossing design sections, rigid
wheel envelope), :mod:`.geometry` (candidate contact points, wheelset equilibrium,
equivalent conicity, flange angle, Nadal), :mod:`.hertz` (exact Hertz ellipse, C_H),
:mod:`.creep` (Kalker coefficients, Polach's creep forces with spin), :mod:`.fastsim` and
:mod:`.creep_table` (Kalker's FASTSIM and its table, the kernel's default creep law),
:mod:`.nonhertz` (Kik-Piotrowski normal contact where Hertz does not fit),
:mod:`.node_laws` (the tables' per-node laws: normal force, force centre, contact point on
the rail), :mod:`.tables` (cached tables, vectorised lookup), :mod:`.transfer` (load transfer
and dips),
:mod:`.references` (CONTACT reference outputs), :mod:`.data` (packaged data); a turnout's
rail bodies: :mod:`.turnout_design` (``[wheel_rail]`` design data and formulas),
:mod:`.turnout_segments` (the ``sections`` lists), :mod:`.section_nodes` (x grids),
:mod:`.turnout_sections` (bodies and their contact tables), :mod:`.handovers` (load transfer,
rest heights at hand-overs); figures in :mod:`exudyn_turnout.plotting.wheel_rail` (this
package never imports matplotlib).
"""

from exudyn_turnout.wheel_rail.creep import (
    CreepForces,
    KalkerCoefficients,
    kalker_coefficients,
    polach_creep_forces,
)
from exudyn_turnout.wheel_rail.geometry import (
    Candidates,
    WheelGrid,
    WheelsetContact,
    WheelsetSetup,
    equivalent_conicity,
    find_candidates,
    flange_angle,
    grid_wheel,
    nadal_limit,
    solve_wheelset,
    surface_derivatives,
)
from exudyn_turnout.wheel_rail.hertz import (
    HertzContact,
    curvature_sums,
    effective_modulus,
    hertz_constant,
    hertz_contact,
)
from exudyn_turnout.wheel_rail.profiles import (
    Profile,
    ProfileFormatError,
    SliceSet,
    read_plain_profile,
    read_profile,
    read_simpack_profile,
    read_slices,
)
from exudyn_turnout.wheel_rail.sections import (
    CrossingDesign,
    SectionGrid,
    SwitchDesign,
    crossing_sections,
    lateral_grid,
    place_rail,
    plain_rail_sections,
    slice_sections,
    switch_sections,
    wheel_envelope,
)
from exudyn_turnout.wheel_rail.tables import (
    ContactLookup,
    ContactTable,
    TableSettings,
    build_contact_table,
    default_cache_dir,
    lookup,
    normal_force,
)
from exudyn_turnout.wheel_rail.transfer import DipSummary, WheelPath, dip_summary, wheel_path

__all__ = [
    "CreepForces",
    "KalkerCoefficients",
    "kalker_coefficients",
    "polach_creep_forces",
    "Candidates",
    "WheelGrid",
    "WheelsetContact",
    "WheelsetSetup",
    "equivalent_conicity",
    "find_candidates",
    "flange_angle",
    "grid_wheel",
    "nadal_limit",
    "solve_wheelset",
    "surface_derivatives",
    "HertzContact",
    "curvature_sums",
    "effective_modulus",
    "hertz_constant",
    "hertz_contact",
    "Profile",
    "ProfileFormatError",
    "SliceSet",
    "read_plain_profile",
    "read_profile",
    "read_simpack_profile",
    "read_slices",
    "CrossingDesign",
    "SectionGrid",
    "SwitchDesign",
    "crossing_sections",
    "lateral_grid",
    "place_rail",
    "plain_rail_sections",
    "slice_sections",
    "switch_sections",
    "wheel_envelope",
    "ContactLookup",
    "ContactTable",
    "TableSettings",
    "build_contact_table",
    "default_cache_dir",
    "lookup",
    "normal_force",
    "DipSummary",
    "WheelPath",
    "dip_summary",
    "wheel_path",
]
