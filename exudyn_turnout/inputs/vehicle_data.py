"""The railway vehicle as data: bodies, suspensions, bumpstop, and the static loads they give.

The frozen :class:`VehicleModel` a vehicle file is read into
(:func:`exudyn_turnout.inputs.vehicle_model.load_vehicle_model`) and its parts, in SI
units. One layout describes

- a full vehicle: a car body on two bogies, two wheelsets per bogie (``bogies = 2``), or
- single wheelsets, each under its own sprung share (``bogies = 0``, a :class:`SprungMass`,
  no car body, no secondary suspension): the package's fast study model
  (:func:`single_wheelset_share` derives it from a full vehicle).

Axes: x forward, y left, z up; heights above the rail top; x of every body relative to the
vehicle reference, the front wheelset at x = 0 (the others behind it, x < 0).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

__all__ = [
    "GRAVITY",
    "BodyData",
    "WheelsetData",
    "SuspensionData",
    "BumpStop",
    "SprungMass",
    "VehicleModel",
    "full_vehicle_parts",
    "car_body_shares",
    "single_wheelset_share",
]

GRAVITY = 9.81  #: m/s^2, as the package's single-wheelset model (vehicle.GRAVITY)


@dataclass(frozen=True)
class BodyData:
    """A rigid body kind (car body or bogie frame) and where its copies sit."""

    mass: float  #: kg, each
    roll_inertia: float  #: kg m^2, Jx about the longitudinal axis through the CoG
    pitch_inertia: float  #: kg m^2, Jy about the lateral axis
    yaw_inertia: float  #: kg m^2, Jz about the vertical axis
    cog_height: float  #: m above the rail top
    x: tuple[float, ...]  #: m, longitudinal position of each copy (front wheelset at 0)


@dataclass(frozen=True)
class WheelsetData:
    """The wheelsets: one kind, several positions."""

    mass: float  #: kg, each
    roll_inertia: float  #: kg m^2, Jx
    spin_inertia: float  #: kg m^2, Jy about the axle
    yaw_inertia: float  #: kg m^2, Jz
    wheel_radius: float  #: m, nominal rolling radius r0 (= axle height above the rail)
    back_to_back: float  #: m, flange back distance
    contact_semi_spacing: float  #: m, lateral semi-distance of the nominal contact points
    x: tuple[float, ...]  #: m, position of each wheelset, x[0] = 0 (front), then decreasing
    bogie: tuple[int, ...]  #: 0-based bogie index of each wheelset, -1: none

    @property
    def cog_height(self) -> float:
        """Height (m) of the axle above the rail: the wheel radius."""
        return self.wheel_radius


@dataclass(frozen=True)
class SuspensionData:
    """One suspension element (per axlebox or per bogie side), acting along x, y, z."""

    k_x: float  #: N/m, longitudinal stiffness
    k_y: float  #: N/m, lateral stiffness
    k_z: float  #: N/m, vertical stiffness
    c_x: float  #: N s/m, longitudinal damping
    c_y: float  #: N s/m, lateral damping
    c_z: float  #: N s/m, vertical damping
    semi_spacing: float  #: m, lateral semi-spacing of the two elements of a body
    height: float  #: m above the rail top, where the element acts


@dataclass(frozen=True)
class BumpStop:
    """Lateral bumpstop between car body and bogie: free within +-clearance, then a table."""

    clearance: float  #: m, free play each side
    height: float  #: m above the rail, where it acts (at the bogie centre's x)
    displacement: tuple[float, ...]  #: m, increasing, all > clearance
    force: tuple[float, ...]  #: N at those displacements, non-decreasing, >= 0

    def ramps(self) -> tuple[tuple[float, ...], tuple[float, ...]]:
        """Breakpoints u_i (m) and slope increments s_i (N/m) of the characteristic.

        F(u) = sign(u) sum_i s_i max(|u| - u_i, 0): the table (with (clearance, 0) in front),
        linear in between and extrapolated with the last slope, as a sum of ramps; written
        with abs, max and sign only, so it serves Python and Exudyn symbolic functions.

        Returns
        -------
        tuple of tuple of float
            (breakpoints, slope increments), the same length.
        """
        u = (self.clearance,) + self.displacement
        f = (0.0,) + self.force
        slopes = [(f[i + 1] - f[i]) / (u[i + 1] - u[i]) for i in range(len(u) - 1)]
        slopes.append(slopes[-1])  # extrapolation beyond the table: the last slope
        increments = [slopes[0]] + [slopes[i] - slopes[i - 1] for i in range(1, len(u) - 1)]
        return u[:-1], tuple(increments)

    def lateral_force(self, u: float) -> float:
        """Force (N) at relative lateral displacement u (m); odd in u, 0 within the clearance.

        Parameters
        ----------
        u : float
            Relative lateral displacement car body minus bogie at the bumpstop (m).

        Returns
        -------
        float
            Restoring force magnitude with the sign of u (N).
        """
        points, increments = self.ramps()
        a = abs(u)
        return math.copysign(sum(s * max(a - p, 0.0) for p, s in zip(points, increments)), u)


@dataclass(frozen=True)
class SprungMass:
    """Share of bogie and car body carried by one wheelset (single-wheelset model)."""

    mass: float  #: kg, per wheelset
    height: float  #: m above the rail, where the point mass sits (primary springs reach it)


@dataclass(frozen=True)
class VehicleModel:
    """A vehicle file's content, SI units (the two layouts: :mod:`.vehicle_data`)."""

    name: str
    description: str
    reference: str  #: literature source of the data
    wheelset: WheelsetData
    primary: SuspensionData  #: per axlebox
    car_body: BodyData | None  #: None for the single-wheelset layout
    bogie: BodyData | None  #: None for the single-wheelset layout
    secondary: SuspensionData | None  #: per bogie side
    secondary_yaw_stiffness: float  #: N m/rad per bogie, bogie vs car body about z
    anti_roll_stiffness: float  #: N m/rad per bogie, anti-roll bar (relative roll)
    bumpstop: BumpStop | None  #: lateral, one per bogie
    sprung_mass: SprungMass | None  #: per wheelset, single-wheelset layout only
    source: str  #: file name the model was read from ("" if built in code)

    @property
    def n_wheelsets(self) -> int:
        """Number of wheelsets."""
        return len(self.wheelset.x)

    @property
    def n_bogies(self) -> int:
        """Number of bogies (0 in the single-wheelset layout)."""
        return 0 if self.bogie is None else len(self.bogie.x)

    @property
    def total_mass(self) -> float:
        """Mass (kg) of the whole vehicle (for a single wheelset: wheelset + sprung share)."""
        m = self.n_wheelsets * self.wheelset.mass
        if self.car_body is not None:
            m += self.car_body.mass * len(self.car_body.x)
        if self.bogie is not None:
            m += self.bogie.mass * self.n_bogies
        if self.sprung_mass is not None:
            m += self.sprung_mass.mass * self.n_wheelsets
        return m

    @property
    def unsprung_mass_per_wheel(self) -> float:
        """Unsprung mass (kg) per wheel: half a wheelset."""
        return 0.5 * self.wheelset.mass

    def wheelset_loads(self) -> tuple[float, ...]:
        """Static vertical load (N) of each wheelset on level track, by the lever rule.

        The car body's weight goes to the two bogies in inverse proportion to their
        distance from its CoG, each bogie's load (its share plus its weight) to its two
        wheelsets the same way, plus each wheelset's own weight (statics, first principles).

        Returns
        -------
        tuple of float
            One load per wheelset (N), in the order of ``wheelset.x``.
        """
        wheelset = self.wheelset
        loads = [wheelset.mass * GRAVITY] * self.n_wheelsets
        if self.sprung_mass is not None:
            return tuple(load + self.sprung_mass.mass * GRAVITY for load in loads)
        body, bogie, _ = full_vehicle_parts(self)
        x_bogies = bogie.x
        x_body = body.x[0]
        shares = car_body_shares(x_body, x_bogies)
        for j, share in enumerate(shares):
            bogie_load = share * body.mass * GRAVITY + bogie.mass * GRAVITY
            mine = [i for i, b in enumerate(wheelset.bogie) if b == j]
            x0, x1 = wheelset.x[mine[0]], wheelset.x[mine[1]]
            loads[mine[0]] += bogie_load * (x_bogies[j] - x1) / (x0 - x1)
            loads[mine[1]] += bogie_load * (x0 - x_bogies[j]) / (x0 - x1)
        return tuple(loads)

    def static_wheel_loads(self) -> tuple[float, ...]:
        """Static wheel load (N) of each wheelset on straight level track: half its load.

        Returns
        -------
        tuple of float
            One value per wheelset (both wheels carry the same on level track).
        """
        return tuple(0.5 * q for q in self.wheelset_loads())

    @property
    def static_wheel_load(self) -> float:
        """Mean static wheel load (N): total weight / (2 n_wheelsets)."""
        return self.total_mass * GRAVITY / (2 * self.n_wheelsets)


def full_vehicle_parts(model: VehicleModel) -> tuple[BodyData, BodyData, SuspensionData]:
    """The car body, the bogie kind and the secondary suspension of a full vehicle.

    Parameters
    ----------
    model : VehicleModel
        A full vehicle (with bogies).

    Returns
    -------
    tuple
        (car body, bogie, secondary suspension).

    Raises
    ------
    ValueError
        The model is a single-wheelset layout (no car body, bogies or secondary suspension).
    """
    if model.car_body is None or model.bogie is None or model.secondary is None:
        raise ValueError(f"{model.name}: has no car body and bogies (single-wheelset layout)")
    return model.car_body, model.bogie, model.secondary


def car_body_shares(x_body: float, x_bogies: tuple[float, ...]) -> tuple[float, float]:
    """Shares of the car body's weight on bogie 1 and bogie 2 (lever rule, sum 1).

    Parameters
    ----------
    x_body : float
        m, the car body's CoG along x.
    x_bogies : tuple of float
        m, the two bogie centres along x.

    Returns
    -------
    tuple of float
        (share on bogie 1, share on bogie 2).
    """
    span = x_bogies[0] - x_bogies[1]
    return (x_body - x_bogies[1]) / span, (x_bogies[0] - x_body) / span


def single_wheelset_share(model: VehicleModel, index: int = 0) -> VehicleModel:
    """The single-wheelset study model of a full vehicle: one wheelset under its sprung share.

    The sprung mass is the wheelset's static load / g minus its own mass (lever rule; for
    the Manchester vehicle 32000 / 4 + 2615 / 2 = 9307.5 kg), at the primary springs'
    height, on the same primary suspension.

    Parameters
    ----------
    model : VehicleModel
        A full vehicle (with bogies), or a single-wheelset model (returned unchanged).
    index : int
        Which wheelset's share (0: the front one).

    Returns
    -------
    VehicleModel
        One wheelset at x = 0 with a ``sprung_mass`` and no car body, bogies, secondary
        suspension or bumpstop.
    """
    if model.sprung_mass is not None:
        return model
    share = model.wheelset_loads()[index] / GRAVITY - model.wheelset.mass
    wheelset = replace(model.wheelset, x=(0.0,), bogie=(-1,))
    return replace(
        model,
        name=f"{model.name}, wheelset {index + 1} with its sprung share",
        wheelset=wheelset,
        car_body=None,
        bogie=None,
        secondary=None,
        secondary_yaw_stiffness=0.0,
        anti_roll_stiffness=0.0,
        bumpstop=None,
        sprung_mass=SprungMass(share, model.primary.height),
    )
