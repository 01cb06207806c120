"""Equivalent co-running track parameters for a zone or any position x (paper Section 3).

Three sources:

``derived``
    computed from the turnout's Table 1 properties with Eqs 1-19
    (:mod:`exudyn_turnout.corunning.equations`) under a set of :class:`Readings`; the check
    rail's (slot r3's) lateral entries and mass are derived from the FE check rail on its
    L-bracket when the file has ``[check_rail.co_running]``
    (:mod:`exudyn_turnout.corunning.check_rail`, ``check_rail="bracket"``), or from Eqs
    1-19 like a running rail (``check_rail="table1"``, the paper's; the comparison with
    Table 2 uses it);
``published``
    the paper's Table 2, as stored in the turnout file;
``fitted``
    the derived set with the entries fitted to the FE receptance
    (:mod:`exudyn_turnout.corunning.fit`) in their place, carried by the turnout
    (``turnout.fitted``, attached by :func:`exudyn_turnout.corunning.fitted.with_fitted`).

Policy for the default readings (:data:`DEFAULT_READINGS`): where an equation as printed
is dimensionally inconsistent or ambiguous, use the reading that reproduces Table 2 (the
set the paper validated against its FE model); where the reading that reproduces Table 2
is an arithmetic slip against textbook physics (the shear modulus in Eq 12), keep the
physics and report the difference. :data:`AS_PRINTED` evaluates every equation literally.
The comparison with Table 2 is in :mod:`exudyn_turnout.corunning.comparison`.

Entries that depend on position are :class:`~exudyn_turnout.inputs.turnout.Entry` objects of
kind ``Delta_z``, ``Delta_y`` (coefficient times the factor of Eq 11 / 15) or ``ramp``
(Table 2's ranges, linear over the zone); masses are constant within a zone, as in the
paper.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from exudyn_turnout.corunning import equations as eq
from exudyn_turnout.corunning.check_rail import (
    bracket_entries,
    check_rail_lateral,
    check_rail_model,
)
from exudyn_turnout.inputs.turnout import (
    PARAMETER_NAMES,
    RAIL_SLOTS,
    Entry,
    Polynomial,
    RailType,
    Turnout,
    Zone,
)

__all__ = [
    "Readings",
    "DEFAULT_READINGS",
    "AS_PRINTED",
    "TABLE2_READINGS",
    "RailSupport",
    "CoRunningParameters",
    "rail_support",
    "reference_rail_type",
    "reference_support",
    "delta_z",
    "delta_y",
    "co_running_parameters",
    "SOURCES",
]

SOURCES = ("derived", "published", "fitted")
_EXTRA_LAYER = ("k_0", "c_0", "m_0")


@dataclass(frozen=True)
class Readings:
    """How to read the equations whose printed form is ambiguous (see the module doc)."""

    eq5: str = "reciprocal"  #: "reciprocal" or "printed" (see equations.sleeper_effective_length)
    eq12_shear_modulus: str = "E/(2(1+nu))"  #: or "E(1+nu)/2"
    eq16_rail_mass: str = "per_effective_length"  #: or "printed"
    eq18_sleeper_share: str = "per_rail"  #: "per_rail" (L_t/n) or "printed" (whole L_t)


#: Readings used by ``source="derived"`` unless told otherwise.
DEFAULT_READINGS = Readings()
#: Every equation exactly as printed.
AS_PRINTED = Readings("printed", "E/(2(1+nu))", "printed", "printed")
#: The readings under which Table 2 reproduces (used to back the explanations).
TABLE2_READINGS = Readings("reciprocal", "E(1+nu)/2", "per_effective_length", "per_rail")


@dataclass(frozen=True)
class RailSupport:
    """Equivalent support of one rail type (Eqs 1-5, 13), both directions, SI units."""

    rail_type: RailType  #: the type whose section and pads are used
    L_t: float  #: m, sleeper length used in Eqs 4, 5, 13
    k_b_z: float  #: N/m, Eq 3 or 4
    c_b_z: float  #: N s/m, Eq 3 or 4 with d_b,z
    k_s_z: float  #: N/m^2, Eq 2
    K_st_z: float  #: N/m, Eq 2
    L_eff_r_z: float  #: m, Eq 1
    k_b_y: float  #: N/m, Eq 13
    c_b_y: float  #: N s/m, Eq 13 with d_b,y
    k_s_y: float  #: N/m^2, Eq 2 lateral
    K_st_y: float  #: N/m, Eq 2 lateral
    L_eff_r_y: float  #: m, Eq 1 lateral
    L_eff_s: float  #: -, Eq 5


def _section(rail: RailType, quantity: str) -> float:
    table = getattr(rail, quantity)
    if not table.is_constant:
        raise ValueError(f"rail type {rail.name!r} has a varying {quantity}; give it equivalent_to")
    return table.value[0]


def rail_support(
    turnout: Turnout, type_name: str, readings: Readings = DEFAULT_READINGS
) -> RailSupport:
    """Equivalent support stiffness and effective lengths of a rail type (Eqs 1-5, 13).

    A rail type with ``equivalent_to`` (the switch rail) takes the values of that type
    (Section 3.1.1); its Delta factor is applied by :func:`co_running_parameters`.

    Parameters
    ----------
    turnout : Turnout
        The turnout (Table 1 properties of rails, pads, sleepers and ballast).
    type_name : str
        Name of a rail type of the turnout file (``"stock"``, ``"switch"``, ``"crossing"``...).
    readings : Readings
        Readings of the ambiguous equations (Eq 5 is the one used here).

    Returns
    -------
    RailSupport
        Equivalent ballast, support stiffness, static stiffness and effective lengths of the
        rail type in both directions.
    """
    rail = turnout.rail_types[type_name]
    if rail.equivalent_to:
        rail = turnout.rail_types[rail.equivalent_to]
    L_t, n = rail.sleeper_length, rail.rails_per_sleeper  # Table 1 column of this rail type
    sleeper, ballast, L_s = turnout.sleeper, turnout.ballast, turnout.sleeper.spacing
    EI_s = sleeper.youngs_modulus * sleeper.I
    L_eff_s = eq.sleeper_effective_length(L_t, ballast.s_b_z, EI_s, readings.eq5)
    if rail.support == "middle":
        k_b_z, c_b_z = (
            eq.ballast_stiffness_middle(ballast.s_b_z, L_eff_s),
            eq.ballast_stiffness_middle(ballast.d_b_z, L_eff_s),
        )
    else:
        k_b_z, c_b_z = (
            eq.ballast_stiffness_edge(ballast.s_b_z, L_t, n),
            eq.ballast_stiffness_edge(ballast.d_b_z, L_t, n),
        )
    k_b_y, c_b_y = (
        eq.lateral_ballast_stiffness(ballast.s_b_y, L_t),
        eq.lateral_ballast_stiffness(ballast.d_b_y, L_t),
    )
    E = rail.youngs_modulus
    k_s_z = eq.continuous_support_stiffness(rail.pad.k_z, k_b_z, L_s)
    k_s_y = eq.continuous_support_stiffness(rail.pad.k_y, k_b_y, L_s)
    K_st_z = eq.static_track_stiffness(E * _section(rail, "I_z"), k_s_z)
    K_st_y = eq.static_track_stiffness(E * _section(rail, "I_y"), k_s_y)
    return RailSupport(
        rail,
        L_t,
        k_b_z,
        c_b_z,
        k_s_z,
        K_st_z,
        eq.effective_length_rail(K_st_z, k_s_z),
        k_b_y,
        c_b_y,
        k_s_y,
        K_st_y,
        eq.effective_length_rail(K_st_y, k_s_y),
        L_eff_s,
    )


def reference_rail_type(turnout: Turnout) -> str:
    """Name of the plain-track rail type (``[turnout] reference_rail_type``, default "stock").

    Parameters
    ----------
    turnout : Turnout
        The turnout whose file names the reference rail type.

    Returns
    -------
    str
        A key of ``turnout.rail_types``.

    """
    return turnout.reference_rail_type  # validated by the loader


def reference_support(turnout: Turnout) -> RailSupport:
    """Support of the reference (plain-track) rail: K_st,z and K_st,y of Eqs 11 and 15.

    Parameters
    ----------
    turnout : Turnout
        The turnout.

    Returns
    -------
    RailSupport
        :func:`rail_support` of :func:`reference_rail_type` under the default readings.
    """
    return rail_support(turnout, reference_rail_type(turnout))


def _support_factor(profile: Polynomial, K_st: float, x: float) -> float:
    """Eq 11 / 15 ratio K(x) / K_st, plain track (1) ahead of the profile's range.

    Eqs 10 and 14 are FE fits from the switch toe on (x >= x_min). Ahead of the toe there
    is no switch rail: the track is plain and the factor is 1 (the paper's zone 1 starts
    5 m before the toe, Table 3, but its stiffness "continuously varied as a function of
    the rail position" has nothing to vary there). If the file gives ``plain_track_end``,
    the factor is 1 up to it and blends linearly to Eq 10's / 14's toe value at x_min, so
    that the co-running springs do not change stepwise under a loaded rail; without it the
    toe value is held (the earlier behaviour, which softened plain track by up to 34 %).
    """
    if profile.plain_track_end is None or x >= profile.x_min:
        return eq.stiffness_ratio(profile(x), K_st)
    if x <= profile.plain_track_end:
        return 1.0
    at_toe = eq.stiffness_ratio(profile(profile.x_min), K_st)
    weight = (x - profile.plain_track_end) / (profile.x_min - profile.plain_track_end)
    return 1.0 + weight * (at_toe - 1.0)


def delta_z(turnout: Turnout, x: float) -> float:
    """Eq 11: Delta_z(x) = K_sw(x) / K_st,z, K_sw from Eq 10, K_st,z of the reference rail (Eq 2).

    Plain track (1) ahead of the toe: see :func:`_support_factor`.

    Parameters
    ----------
    turnout : Turnout
        The turnout, with the switch rail's vertical stiffness fit K_sw (Eq 10).
    x : float
        Position from the switch toe (m).

    Returns
    -------
    float
        Vertical stiffness ratio Delta_z (-).
    """
    return _support_factor(turnout.K_sw, reference_support(turnout).K_st_z, x)


def delta_y(turnout: Turnout, x: float) -> float:
    """Eq 15: Delta_y(x) = K_sh(x) / K_st,y, K_sh from Eq 14, K_st,y of the reference rail (Eq 2).

    Plain track (1) ahead of the toe: see :func:`_support_factor`.

    Parameters
    ----------
    turnout : Turnout
        The turnout, with the switch rail head's lateral stiffness fit K_sh (Eq 14).
    x : float
        Position from the switch toe (m).

    Returns
    -------
    float
        Lateral stiffness ratio Delta_y (-).
    """
    return _support_factor(turnout.K_sh, reference_support(turnout).K_st_y, x)


@dataclass(frozen=True)
class CoRunningParameters:
    """A co-running parameter set of one zone: entries as functions of x, SI units.

    ``entries`` maps the names of :data:`~exudyn_turnout.inputs.turnout.PARAMETER_NAMES` to
    :class:`~exudyn_turnout.inputs.turnout.Entry`; ``constants`` holds intermediate values
    (``K_st_z``, ``L_eff_r_z``, ...). Use :meth:`at` for numbers at a position.
    """

    turnout: Turnout
    zone: Zone
    layers: int  #: 2 or 3
    source: str  #: "derived", "published" or "fitted"
    entries: Mapping[str, Entry]
    constants: Mapping[str, float] = field(default_factory=dict)

    @property
    def active_rails(self) -> tuple[str, ...]:
        """Rail slots (``"r1"``...) in contact with a wheel in this zone (Table 3)."""
        return self.zone.active_rails

    def at(self, x: float) -> dict[str, float]:
        """All entries, the constants and ``Delta_z``, ``Delta_y`` evaluated at a position.

        Parameters
        ----------
        x : float
            Position from the switch toe (m), inside the zone.

        Returns
        -------
        dict of str to float
            Parameter name to value (SI units).

        Raises
        ------
        ValueError
            x is outside the zone.
        """
        if not self.zone.contains(x):
            raise ValueError(
                f"x = {x:g} m is outside zone {self.zone.index} "
                f"({self.zone.x_start:g} m to {self.zone.x_end:g} m)"
            )
        Delta_z, Delta_y = delta_z(self.turnout, x), delta_y(self.turnout, x)
        zone_fraction = (x - self.zone.x_start) / (self.zone.x_end - self.zone.x_start)
        out = {
            name: entry.value(Delta_z, Delta_y, zone_fraction)
            for name, entry in self.entries.items()
        }
        out.update(self.constants)
        out.update(Delta_z=Delta_z, Delta_y=Delta_y)
        return out

    def depends_on_x(self, name: str) -> bool:
        """Whether an entry varies with position within the zone.

        Parameters
        ----------
        name : str
            Parameter name, a key of ``entries``.

        Returns
        -------
        bool
            True for Delta_z, Delta_y and ramp entries, False for constants.
        """
        return self.entries[name].kind != "const"


def _factor(kind: str | None, coefficient: float) -> Entry:
    return Entry(kind or "const", coefficient)


def _rail_entries(turnout: Turnout, zone: Zone, slot: str, readings: Readings) -> dict[str, Entry]:
    j = slot[1:]
    rail_type = turnout.rail_types[zone.rail_types[slot]]
    support = rail_support(turnout, rail_type.name, readings)
    base, L_s, x = support.rail_type, turnout.sleeper.spacing, zone.mass_at_x
    factor_z, factor_y = rail_type.vertical_factor, rail_type.lateral_factor
    k_rt_z = eq.pad_stiffness(base.pad.k_z, support.L_eff_r_z, L_s)
    k_rt_y = eq.pad_stiffness(base.pad.k_y, support.L_eff_r_y, L_s)
    G = eq.shear_modulus(base.youngs_modulus, base.poisson, readings.eq12_shear_modulus)
    c_0 = eq.extra_layer_damping(_section(base, "area"), G, base.density, base.shear_coefficient)
    m_r = eq.rail_mass(
        _section(base, "area"), base.density, support.L_eff_r_z, L_s, readings.eq16_rail_mass
    )
    if factor_z and x is not None:  # Eq 17 at the zone's mass position
        m_r = eq.switch_rail_mass(
            _section(base, "area"),
            base.density,
            support.L_eff_r_z,
            delta_z(turnout, x),
            L_s,
            readings.eq16_rail_mass,
        )
    layer = turnout.extra_layer
    return {
        f"k_rt{j}_z": _factor(factor_z, k_rt_z),
        f"c_rt{j}_z": _factor(factor_z, eq.pad_damping(base.pad.c_z, support.L_eff_r_z, L_s)),
        f"k_0{j}_z": _factor(factor_z, layer.k_0_z_over_k_rt_z * k_rt_z),
        f"c_0{j}_z": Entry("const", c_0),
        f"k_rt{j}_y": _factor(factor_y, k_rt_y),
        f"c_rt{j}_y": _factor(factor_y, eq.pad_damping(base.pad.c_y, support.L_eff_r_y, L_s)),
        f"k_0{j}_y": _factor(factor_y, layer.k_0_y_over_k_rt_y * k_rt_y),
        f"c_0{j}_y": Entry("const", c_0),
        f"m_r{j}": Entry("const", m_r),
    }


def _sleeper_entries(turnout: Turnout, zone: Zone, readings: Readings) -> dict[str, Entry]:
    # the rail type that governs k_tg1, k_tg_y, m_t and J_t (Zone.ballast_rail_type)
    governing_type = turnout.rail_types[zone.ballast_rail_type]
    governing = rail_support(turnout, governing_type.name, readings)
    other_type = zone.rail_types.get("r4", reference_rail_type(turnout))
    other = rail_support(turnout, other_type, readings)
    sleeper, L_s, x = turnout.sleeper, turnout.sleeper.spacing, zone.mass_at_x
    if governing.rail_type.support == "middle":
        m_t = eq.crossing_sleeper_mass(
            sleeper.area,
            sleeper.density,
            governing.L_eff_s,
            governing.L_eff_r_z,
            L_s,
        )
    else:
        n = (
            governing.rail_type.rails_per_sleeper
            if readings.eq18_sleeper_share == "per_rail"
            else 1
        )
        d_y = delta_y(turnout, x) if (governing_type.lateral_factor and x is not None) else 1.0
        m_t = eq.sleeper_mass(
            sleeper.area,
            sleeper.density,
            governing.L_t,
            governing.L_eff_r_z,
            d_y,
            L_s,
            n,
        )
    factor_z, factor_y = governing_type.vertical_factor, governing_type.lateral_factor
    return {
        "k_tg1_z": _factor(
            factor_z,
            eq.ballast_spring_stiffness(governing.k_b_z, governing.L_eff_r_z, L_s),
        ),
        "c_tg1_z": _factor(
            factor_z,
            eq.ballast_spring_damping(governing.c_b_z, governing.L_eff_r_z, L_s),
        ),
        "k_tg2_z": Entry("const", eq.ballast_spring_stiffness(other.k_b_z, other.L_eff_r_z, L_s)),
        "c_tg2_z": Entry("const", eq.ballast_spring_damping(other.c_b_z, other.L_eff_r_z, L_s)),
        "k_tg_y": _factor(
            factor_y,
            eq.ballast_spring_stiffness(governing.k_b_y, governing.L_eff_r_y, L_s),
        ),
        "c_tg_y": _factor(
            factor_y,
            eq.ballast_spring_damping(governing.c_b_y, governing.L_eff_r_y, L_s),
        ),
        "m_0": Entry("const", turnout.extra_layer.m_0),
        "m_t": Entry("const", m_t),
        "J_t": Entry(
            "const",
            eq.sleeper_roll_inertia(m_t, governing.rail_type.sleeper_length, sleeper.height),
        ),
    }


def _check_rail_slots(turnout: Turnout, zone: Zone) -> tuple[str, ...]:
    """Active slots of the zone whose rail type is a check rail's (slot r3's, Table 3)."""
    types = {z.rail_types["r3"] for z in turnout.zones if "r3" in z.active_rails}
    return tuple(r for r in zone.active_rails if r == "r3" and zone.rail_types[r] in types)


def _bracket(
    turnout: Turnout, zone: Zone, layers: int, entries: dict[str, Entry]
) -> dict[str, Entry]:
    """The check rail's lateral entries and mass from the FE bracket (corunning.check_rail)."""
    lateral = check_rail_lateral(turnout)
    assert lateral is not None  # check_rail_model("bracket") checked it
    k_tg_y = entries["k_tg_y"]

    def k_tg_y_at(x: float) -> float:
        s = (x - zone.x_start) / (zone.x_end - zone.x_start)
        return k_tg_y.value(delta_z(turnout, x), delta_y(turnout, x), s)

    out = dict(entries)
    for slot in _check_rail_slots(turnout, zone):
        out.update(
            bracket_entries(
                lateral,
                zone,
                layers,
                k_tg_y_at,
                turnout.extra_layer.k_0_y_over_k_rt_y,
                turnout.extra_layer.m_0,
                slot,
            )
        )
    return out


def _derived(
    turnout: Turnout, zone: Zone, readings: Readings, layers: int = 3, check_rail: str = "table1"
) -> tuple[dict[str, Entry], dict[str, float]]:
    entries: dict[str, Entry] = {}
    for slot in RAIL_SLOTS:
        if slot in zone.rail_types:
            entries.update(_rail_entries(turnout, zone, slot, readings))
    entries.update(_sleeper_entries(turnout, zone, readings))
    if check_rail == "bracket":
        entries = _bracket(turnout, zone, layers, entries)
    reference = reference_support(turnout)
    governing = rail_support(turnout, zone.ballast_rail_type, readings)
    constants = {
        "K_st_z": reference.K_st_z,
        "K_st_y": reference.K_st_y,
        "L_eff_r_z": reference.L_eff_r_z,
        "L_eff_r_y": reference.L_eff_r_y,
        "L_eff_s": governing.L_eff_s,
    }
    ordered = {n: entries[n] for n in PARAMETER_NAMES if n in entries}
    return ordered, constants


def _with_fitted_entries(
    turnout: Turnout, zone: Zone, layers: int, entries: dict[str, Entry]
) -> dict[str, Entry]:
    """The derived entries with the zone's fitted ones in their place (``source="fitted"``)."""
    fitted = turnout.fitted.get(zone.index)
    if not fitted:
        raise ValueError(
            f"{turnout.source}: no fitted parameters for zone {zone.index} "
            "(fit with exudyn-turnout fit, pass the file with --parameters)"
        )
    fitted_layers = 3 if "m_0" in fitted else 2
    if fitted_layers != layers:
        raise ValueError(
            f"the fitted parameters of zone {zone.index} are for the {fitted_layers}-layer "
            f"model, not {layers} layers"
        )
    return {name: fitted.get(name, entry) for name, entry in entries.items()}


def co_running_parameters(
    turnout: Turnout,
    zone: int | None = None,
    x: float | None = None,
    layers: int = 3,
    source: str = "derived",
    readings: Readings = DEFAULT_READINGS,
    check_rail: str | None = None,
) -> CoRunningParameters:
    """Co-running parameter set of a zone, or of the zone containing x.

    Parameters
    ----------
    turnout : Turnout
        From :func:`~exudyn_turnout.inputs.turnout.load_turnout`.
    zone : int, optional
        1-based zone index (Table 3). Give ``zone`` or ``x``.
    x : float, optional
        Position from the switch toe (m); the zone containing it is used.
    layers : {2, 3}
        Two-layer (Fig. 2) or three-layer (Fig. 3) model; two layers drop m_0, k_0, c_0.
    source : {"derived", "published", "fitted"}
        Eqs 1-19 on Table 1, the paper's Table 2, or the derived set with the entries
        fitted to the FE receptance in their place (``turnout.fitted``, see
        :func:`exudyn_turnout.corunning.fitted.with_fitted`).
    readings : Readings
        Readings of the ambiguous equations, for ``source="derived"`` (and the entries a
        fitted set does not hold).
    check_rail : {"bracket", "table1"}, optional
        The check rail's (slot r3's) lateral entries and mass for ``source="derived"`` (and
        the entries a fitted set does not hold): ``"bracket"`` derived from the FE check
        rail on its L-bracket (:mod:`exudyn_turnout.corunning.check_rail`), ``"table1"``
        Eqs 1-19 on Table 1 like a running rail (the paper's). Default: ``"bracket"`` when
        the file has ``[check_rail.co_running]``, else ``"table1"``. Not used by
        ``source="published"`` (Table 2 as printed).

    Returns
    -------
    CoRunningParameters
        Call ``.at(x)`` for numbers.
    """
    if (zone is None) == (x is None):
        raise ValueError("give exactly one of zone or x")
    if layers not in (2, 3):
        raise ValueError(f"layers must be 2 or 3, got {layers}")
    if source not in SOURCES:
        raise ValueError(f"source must be one of {', '.join(SOURCES)}, got {source!r}")
    if zone is not None:
        zone_data = turnout.zone(zone)
    else:
        assert x is not None  # exactly one of zone and x, checked above
        zone_data = turnout.zone_at(float(x))
    constants: dict[str, float]
    if source == "published":
        if zone_data.index not in turnout.published:
            raise ValueError(
                f"{turnout.source}: no published parameters for zone {zone_data.index}"
            )
        entries, constants = dict(turnout.published[zone_data.index]), {}
    else:
        model = check_rail_model(turnout, check_rail)
        entries, constants = _derived(turnout, zone_data, readings, layers, model)
    if source == "fitted":
        entries = _with_fitted_entries(turnout, zone_data, layers, entries)
    if layers == 2:
        entries = {
            name: entry for name, entry in entries.items() if not name.startswith(_EXTRA_LAYER)
        }
    return CoRunningParameters(turnout, zone_data, layers, source, entries, constants)
