"""The vehicle: one wheelset under its share of bogie and car body (Manchester benchmark).

Kept apart from the track and the contact so that the full Manchester vehicle can later
replace it. The model lives in the track's cross-section plane, Exudyn's global X-Y
plane: X = lateral y (positive left), Y = vertical z (up), rotation about Z = roll
(positive lifts the left wheel); yaw is one more coordinate owned by the contact element.

::

              sprung mass m_s (y, z)            share of car body and bogie frame
             |             |
         k_y,k_z,c_z   k_y,k_z,c_z              primary suspension, per axlebox,
             |             |                    at +-d from the wheelset centre
        ==o==+=============+==o==               wheelset m_w, J_roll (y, z, roll), J_yaw
          |<------ 2 b ------>|                 contact points at +-b
"""
from __future__ import annotations

from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from .contact import ContactLaw, load_contact_law
from .turnout import _Reader, read_toml

__all__ = ["Vehicle", "VehicleHandles", "load_vehicle", "default_vehicle_path", "add_vehicle", "GRAVITY"]

GRAVITY = 9.81  #: m/s^2


@dataclass(frozen=True)
class Vehicle:
    m_w: float  #: kg, wheelset mass
    J_roll: float  #: kg m^2
    J_yaw: float  #: kg m^2
    r0: float  #: m, nominal rolling radius
    b: float  #: m, lateral semi-distance of the contact points
    m_s: float  #: kg, sprung mass carried by this wheelset
    k_x: float  #: N/m, primary longitudinal stiffness per axlebox
    k_y: float  #: N/m, primary lateral stiffness per axlebox
    k_z: float  #: N/m, primary vertical stiffness per axlebox
    c_y: float  #: N s/m
    c_z: float  #: N s/m
    d: float  #: m, lateral semi-spacing of the axleboxes
    contact: ContactLaw
    source: str

    @property
    def static_wheel_load(self) -> float:
        """(m_w + m_s) g / 2 (N), each wheel's share on straight level track."""
        return (self.m_w + self.m_s) * GRAVITY / 2.0

    @property
    def k_roll(self) -> float:
        """Primary roll stiffness 2 k_z d^2 (N m/rad) of the wheelset against the sprung point."""
        return 2.0 * self.k_z * self.d**2

    @property
    def k_yaw(self) -> float:
        """Primary yaw stiffness 2 k_x d^2 (N m/rad) against the (non-yawing) sprung mass."""
        return 2.0 * self.k_x * self.d**2


def default_vehicle_path() -> Path:
    return Path(str(resources.files("exudyn_turnout") / "data" / "manchester_wheelset.toml"))


def load_vehicle(path: str | Path | None = None) -> Vehicle:
    """Load and validate a vehicle file (default: the packaged Manchester benchmark wheelset).

    Every number must be finite and > 0 (dampings >= 0) and within a plausibility bound:
    masses <= 1e6 kg, inertias <= 1e7 kg m^2, wheel radius 0.1..2 m, semi-spacings <= 5 m,
    stiffnesses <= 1e12 N/m, dampings <= 1e10 N s/m; contact: C_H <= 1e14 N/m^1.5,
    creep coefficients and N_ref <= 1e10 N, mu <= 2, conicity <= 1, flange clearance <= 0.1 m.

    Parameters
    ----------
    path : str or Path, optional
        TOML vehicle file.

    Returns
    -------
    Vehicle

    Raises
    ------
    TurnoutFileError
        The file cannot be read, or a field is missing or out of range (the message names
        the file and the field).
    """
    path = Path(path) if path is not None else default_vehicle_path()
    data = read_toml(path)
    r = _Reader(path.name, data)
    w, p = "wheelset", "primary_suspension"
    k, c = 1e12, 1e10
    radius = r.number(f"{w}.wheel_radius", upper=2.0)
    if radius < 0.1:
        raise r.fail(f"{w}.wheel_radius", f"must be >= 0.1 m (a railway wheel), got {radius:g}")
    contact_bounds = {"C_H": (True, 1e14), "damping": (False, c), "f11_ref": (True, 1e10),
                      "f22_ref": (True, 1e10), "N_ref": (True, 1e10), "mu": (True, 2.0),
                      "conicity": (True, 1.0), "flange_stiffness": (True, k),
                      "flange_damping": (False, c), "flange_clearance": (True, 0.1)}
    for name, (positive, upper) in contact_bounds.items():
        r.number(f"contact.{name}", positive, upper=upper)
    return Vehicle(
        r.number(f"{w}.mass", upper=1e6), r.number(f"{w}.roll_inertia", upper=1e7),
        r.number(f"{w}.yaw_inertia", upper=1e7), radius,
        r.number(f"{w}.contact_semi_spacing", upper=5.0), r.number("sprung_mass.mass", upper=1e6),
        r.number(f"{p}.k_x", upper=k), r.number(f"{p}.k_y", upper=k), r.number(f"{p}.k_z", upper=k),
        r.number(f"{p}.c_y", positive=False, upper=c),
        r.number(f"{p}.c_z", positive=False, upper=c),
        r.number(f"{p}.semi_spacing", upper=5.0),
        load_contact_law(data, str(path)), str(path))


@dataclass(frozen=True)
class VehicleHandles:
    """Exudyn indices of the vehicle items."""

    wheelset_node: int  #: NodeRigidBody2D (y, z, roll)
    wheelset_body: int
    sprung_node: int  #: NodePoint2D (y, z)
    sprung_body: int
    yaw_node: int  #: NodeGenericODE2, one coordinate; its inertia sits in the contact element
    gravity_loads: tuple[int, ...]


def add_vehicle(mbs, vehicle: Vehicle, ground_body: int, z_w0: float = 0.0, z_s0: float = 0.0) -> VehicleHandles:
    """Add the wheelset, its sprung mass, the primary suspension and gravity.

    Parameters
    ----------
    mbs : exudyn.MainSystem
    vehicle : Vehicle
    ground_body : int
        Unused for now (the sprung mass is free); kept so a car body can be attached later.
    z_w0, z_s0 : float
        Initial vertical displacements (m) of wheelset and sprung mass (a guess for the
        static solver: the Hertz springs need closed contact to have stiffness).
    """
    from exudyn import itemInterface as ii

    del ground_body
    n_w = mbs.AddNode(ii.NodeRigidBody2D(referenceCoordinates=[0.0, 0.0, 0.0], initialCoordinates=[0.0, z_w0, 0.0]))
    o_w = mbs.AddObject(ii.ObjectRigidBody2D(mass=vehicle.m_w, inertia=vehicle.J_roll, nodeNumber=n_w))
    n_s = mbs.AddNode(ii.NodePoint2D(referenceCoordinates=[0.0, 0.0], initialCoordinates=[0.0, z_s0]))
    o_s = mbs.AddObject(ii.ObjectMassPoint2D(mass=vehicle.m_s, nodeNumber=n_s))
    n_yaw = mbs.AddNode(ii.NodeGenericODE2(referenceCoordinates=[0.0], initialCoordinates=[0.0],
                                           initialCoordinates_t=[0.0], numberOfODE2Coordinates=1))
    m_s = mbs.AddMarker(ii.MarkerNodePosition(nodeNumber=n_s))
    for side in (1.0, -1.0):
        # Force-free at rest: the axlebox marker sits at y = side * d, the sprung point at
        # y = 0, so the spring's unstretched offset is p_sprung - p_box = (-side * d, 0).
        # Without it each spring would carry k_y d of lateral tension, which acts on the
        # wheelset as a roll stiffness of -2 k_y d^2 instead of the intended +2 k_z d^2.
        m_box = mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=o_w,
                                                    localPosition=[side * vehicle.d, 0.0, 0.0]))
        mbs.AddObject(ii.CartesianSpringDamper(
            markerNumbers=[m_box, m_s], stiffness=[vehicle.k_y, vehicle.k_z, 0.0],
            damping=[vehicle.c_y, vehicle.c_z, 0.0], offset=[-side * vehicle.d, 0.0, 0.0]))
    loads = tuple(mbs.AddLoad(ii.LoadMassProportional(markerNumber=mbs.AddMarker(ii.MarkerBodyMass(bodyNumber=o)),
                                                      loadVector=[0.0, -GRAVITY, 0.0]))
                  for o in (o_w, o_s))
    return VehicleHandles(n_w, o_w, n_s, o_s, n_yaw, loads)
