"""The turnout as data: the frozen dataclasses a turnout file is read into.

:class:`Turnout` and its parts (rail types with their pads, sleepers, ballast, the third
layer, the support-stiffness polynomials of Eqs 10 and 14, the zones of Table 3, the
co-running entries of Table 2), the rail slots :data:`RAIL_SLOTS` and the entry names
:data:`PARAMETER_NAMES`. SI units. Reading and validating a file is
:func:`exudyn_turnout.inputs.turnout.load_turnout`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = [
    "Table1D",
    "Polynomial",
    "RailPad",
    "RailType",
    "Sleeper",
    "Ballast",
    "ExtraLayer",
    "Zone",
    "Entry",
    "Turnout",
    "RAIL_SLOTS",
    "PARAMETER_NAMES",
]

#: Rail slots of the co-running model: r1 stock, r2 switch/crossing nose, r3 check, r4 stock.
RAIL_SLOTS = ("r1", "r2", "r3", "r4")


def _names() -> tuple[str, ...]:
    """Names of the co-running entries, in Table 2 order (vertical, lateral, masses)."""
    out = []
    for d in ("z", "y"):
        out += [f"{p}{j}_{d}" for j in range(1, 5) for p in ("k_0", "c_0")]
        out += [f"{p}{j}_{d}" for j in range(1, 5) for p in ("k_rt", "c_rt")]
        out += ["k_tg1_z", "c_tg1_z", "k_tg2_z", "c_tg2_z"] if d == "z" else ["k_tg_y", "c_tg_y"]
    return tuple(out) + ("m_0", "m_t", "m_r1", "m_r2", "m_r3", "m_r4", "J_t")


#: Entry names of a co-running parameter set (API, CSV and JSON use these).
PARAMETER_NAMES = _names()


@dataclass(frozen=True)
class Table1D:
    """A quantity tabulated along x, linear in between, held outside the table."""

    x: tuple[float, ...]  #: m, increasing
    value: tuple[float, ...]  #: in the unit of the quantity

    def __call__(self, x: float) -> float:
        return float(np.interp(x, self.x, self.value))

    @property
    def is_constant(self) -> bool:
        """True if every tabulated value is the same."""
        return len(set(self.value)) == 1


@dataclass(frozen=True)
class Polynomial:
    """K(x) = sum(c_i x^i) on [x_min, x_max], held at the end values outside (Eqs 10, 14)."""

    coefficients: tuple[float, ...]  #: N/m, N/m^2, N/m^3 ... ascending powers of x
    x_min: float  #: m
    x_max: float  #: m
    #: m; at and before this x the track is plain (its Delta factor is 1); between it and
    #: x_min the factor blends linearly (see parameters.delta_z). None: held from x_min.
    plain_track_end: float | None = None

    def __call__(self, x: float) -> float:
        x_clamped = min(max(x, self.x_min), self.x_max)
        return float(sum(c * x_clamped**i for i, c in enumerate(self.coefficients)))


@dataclass(frozen=True)
class RailPad:
    """Rail pad under one rail type (Table 1)."""

    k_z: float  #: N/m, vertical pad stiffness k_p,z
    c_z: float  #: N s/m, vertical pad damping c_p,z
    k_y: float  #: N/m, lateral pad stiffness k_p,y
    c_y: float  #: N s/m, lateral pad damping c_p,y


@dataclass(frozen=True)
class RailType:
    """One column of the paper's Table 1 (rail and the pad under it)."""

    name: str  #: key in Turnout.rail_types, e.g. "stock"
    density: float  #: kg/m^3, rho_r
    youngs_modulus: float  #: Pa, E_r
    shear_coefficient: float  #: kappa (-)
    poisson: float  #: nu (-)
    area: Table1D  #: m^2, A_r along x
    I_z: Table1D  #: m^4, vertical bending inertia along x
    I_y: Table1D  #: m^4, lateral bending inertia along x
    sleeper_length: float  #: m, L_t of Table 1 for this rail type
    support: str  #: "edge" (Eq 4) or "middle" (Eq 3) of the sleeper
    rails_per_sleeper: int  #: n in Eq 4
    pad: RailPad  #: the pad under this rail type
    vertical_factor: str | None  #: "Delta_z" or None
    lateral_factor: str | None  #: "Delta_y" or None
    equivalent_to: str | None  #: rail type whose co-running values this one scales


@dataclass(frozen=True)
class Sleeper:
    """Sleepers (bearers) of the turnout (Table 1)."""

    density: float  #: kg/m^3, rho_s
    youngs_modulus: float  #: Pa, E_s
    area: float  #: m^2, A_s
    I: float  #: m^4, I_s (vertical bending)
    spacing: float  #: m, L_s
    length: Table1D  #: m, sleeper (bearer) length along x

    @property
    def height(self) -> float:
        """Height h_t (m) of the rectangle with the sleeper's A_s and I_s: sqrt(12 I_s / A_s)."""
        return math.sqrt(12.0 * self.I / self.area)


@dataclass(frozen=True)
class Ballast:
    """Ballast per unit sleeper length (Table 1)."""

    s_b_z: float  #: N/m^2, vertical stiffness per unit sleeper length
    d_b_z: float  #: N s/m^2, vertical damping per unit length
    s_b_y: float  #: N/m^2, lateral stiffness per unit length
    d_b_y: float  #: N s/m^2, lateral damping per unit length


@dataclass(frozen=True)
class ExtraLayer:
    """The third layer of the three-layer model (Section 3.1.1)."""

    m_0: float  #: kg, dummy mass of the third layer
    k_0_z_over_k_rt_z: float  #: k_0j,z / k_rtj,z (-)
    k_0_y_over_k_rt_y: float  #: k_0j,y / k_rtj,y (-)


@dataclass(frozen=True)
class Zone:
    """A simulation zone (Table 3): masses constant, active rails fixed."""

    index: int  #: 1-based
    name: str  #: description, e.g. "switch panel"
    x_start: float  #: m
    x_end: float  #: m
    active_rails: tuple[str, ...]  #: rail slots a wheel can load in this zone (Table 3)
    rail_types: Mapping[str, str]  #: slot -> rail type name
    ballast_rail_type: str  #: rail type governing k_tg1, k_tg_y, m_t, J_t
    mass_at_x: float | None  #: m; masses from Eqs 17/18 at this x, None: Delta = 1
    rail_y: Mapping[str, float]  #: m, lateral position of each rail slot (y positive left)
    ballast_y: tuple[float, float]  #: m, lateral positions of the k_tg1 and k_tg2 springs
    sleeper_y: float  #: m, lateral position of the sleeper's centre of mass

    def contains(self, x: float) -> bool:
        """True if x lies in the zone, ends included.

        Parameters
        ----------
        x : float
            Position from the switch toe (m).

        Returns
        -------
        bool
            x_start <= x <= x_end.
        """
        return self.x_start <= x <= self.x_end


@dataclass(frozen=True)
class Entry:
    """One co-running entry as a function of x: a, a*Delta_z, a*Delta_y or a ramp a -> b."""

    kind: str  #: "const", "Delta_z", "Delta_y" or "ramp"
    a: float  #: value, coefficient, or ramp start value (SI)
    b: float = math.nan  #: ramp end value (SI), only for kind "ramp"

    def value(self, delta_z: float, delta_y: float, s: float) -> float:
        """Value at Delta_z, Delta_y and relative zone position s in [0, 1].

        Parameters
        ----------
        delta_z, delta_y : float
            Delta_z(x), Delta_y(x).
        s : float
            Relative position in the zone (ramps).

        Returns
        -------
        float
            The entry's value (SI): a, a Delta_z, a Delta_y, or a + (b - a) s with s
            clamped to [0, 1].
        """
        if self.kind == "Delta_z":
            return self.a * delta_z
        if self.kind == "Delta_y":
            return self.a * delta_y
        if self.kind == "ramp":
            return self.a + (self.b - self.a) * min(max(s, 0.0), 1.0)
        return self.a

    def describe(self) -> str:
        """The entry as Table 2 prints it ("369e6 * Delta_z", "448e6 - 453e6", ...).

        Returns
        -------
        str
            The coefficient or range in 4 significant digits, with its Delta factor.
        """
        if self.kind in ("Delta_z", "Delta_y"):
            return f"{self.a:.4g} * {self.kind}"
        if self.kind == "ramp":
            return f"{self.a:.4g} - {self.b:.4g}"
        return f"{self.a:.4g}"


@dataclass(frozen=True)
class Turnout:
    """A turnout definition in SI units (the file it is read from: :mod:`.turnout`)."""

    name: str  #: short name from the file, e.g. "UIC60-760-1:15"
    description: str  #: free text from the file
    source: str  #: file the definition was read from
    rail_types: Mapping[str, RailType]  #: Table 1 columns by name
    sleeper: Sleeper  #: Table 1 sleeper properties
    ballast: Ballast  #: Table 1 ballast properties
    K_sw: Polynomial  #: Eq 10, switch-rail vertical support stiffness (N/m)
    K_sh: Polynomial  #: Eq 14, lateral support stiffness (N/m)
    extra_layer: ExtraLayer  #: m_0 and the k_0 ratios of the three-layer model
    zones: tuple[Zone, ...]  #: Table 3, contiguous, in increasing x
    published: Mapping[int, Mapping[str, Entry]]  #: zone index -> Table 2 entries
    raw: Mapping[str, Any]  #: the parsed file, for sections later modules read
    #: the plain-track rail type: its K_st (Eq 2) is Eqs 11 and 15's denominator
    reference_rail_type: str = "stock"
    #: m, where peaks "at the switch" / "at the crossing" are taken: name -> (x_from, x_to);
    #: defaults: switch 0-10 m from the toe, crossing the last zone that is not plain track
    regions: Mapping[str, tuple[float, float]] = field(default_factory=dict)
    #: zone index -> co-running entries fitted to the FE receptance (``source="fitted"``),
    #: attached by :func:`exudyn_turnout.corunning.fitted.with_fitted`; empty when loaded
    fitted: Mapping[int, Mapping[str, Entry]] = field(default_factory=dict)

    @property
    def x_min(self) -> float:
        """m, start of the first zone."""
        return self.zones[0].x_start

    @property
    def x_max(self) -> float:
        """m, end of the last zone."""
        return self.zones[-1].x_end

    def zone(self, index: int) -> Zone:
        """Zone by 1-based index; :class:`KeyError` naming the valid range otherwise.

        Parameters
        ----------
        index : int
            1-based zone index (Table 3).

        Returns
        -------
        Zone
            The zone.
        """
        if not 1 <= index <= len(self.zones):
            raise KeyError(
                f"zone {index} does not exist in {self.name} (zones 1..{len(self.zones)})"
            )
        return self.zones[index - 1]

    def zone_at(self, x: float) -> Zone:
        """The zone containing x (the later zone on a boundary); ValueError outside.

        Parameters
        ----------
        x : float
            Position from the switch toe (m).

        Returns
        -------
        Zone
            The zone containing x.
        """
        if not self.x_min <= x <= self.x_max:
            raise ValueError(
                f"x = {x:g} m is outside the turnout {self.name} "
                f"({self.x_min:g} m to {self.x_max:g} m)"
            )
        for zone in reversed(self.zones):
            if zone.contains(x):
                return zone
        raise AssertionError("zones are contiguous by validation")
