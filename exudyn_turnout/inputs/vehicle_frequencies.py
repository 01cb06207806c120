"""Hand calculations of a vehicle's natural frequencies on rigid (or elastic) track.

The ``*_frequency`` functions are first-principles references for the Exudyn model of the
full vehicle (``tests/test_full_vehicle.py``, ``validation/vehicle_modes.py``). Each states
its source and its assumptions (which neighbours are held, which springs act in series);
:func:`hand_frequencies` collects them. Pure arithmetic on a
:class:`~exudyn_turnout.inputs.vehicle_data.VehicleModel`.
"""

from __future__ import annotations

import math

import numpy as np

from exudyn_turnout.inputs.vehicle_data import (
    GRAVITY,
    VehicleModel,
    car_body_shares,
    full_vehicle_parts,
)

__all__ = [
    "series",
    "sway_frequencies",
    "carbody_bounce_frequency",
    "carbody_pitch_frequency",
    "carbody_yaw_frequency",
    "carbody_sway_frequencies",
    "bogie_bounce_frequency",
    "bogie_pitch_frequency",
    "bogie_sway_frequencies",
    "wheelset_bounce_frequency",
    "hand_frequencies",
]


def series(*stiffnesses: float) -> float:
    """Stiffness of springs in series, 1 / sum(1 / k_i) (first principles; inf allowed).

    Parameters
    ----------
    *stiffnesses : float
        Stiffnesses (any consistent unit); ``math.inf`` is a rigid link.

    Returns
    -------
    float
        The series stiffness (same unit as the inputs).
    """
    return 1.0 / sum(1.0 / k for k in stiffnesses)


def _hz(k: float, m: float) -> float:
    return math.sqrt(k / m) / (2.0 * math.pi)


def sway_frequencies(
    mass: float, roll_inertia: float, k_lateral: float, lever: float, k_roll: float
) -> tuple[float, float]:
    """Coupled lateral-roll (sway) frequencies of a rigid body on springs, 2x2 (Hz).

    First principles (as Garg & Dukkipati, Dynamics of Railway Vehicle Systems, 1984,
    ch. 7, lateral/roll model of a car body): coordinates y (lateral, at the CoG) and phi
    (roll, positive lifting the left side); the lateral springs act at ``lever`` above the
    CoG (negative: below), where the lateral displacement is y - lever phi, so
    ``K = [[k, -k e], [-k e, k e^2 + k_roll]]``, ``M = diag(m, J)``.

    Parameters
    ----------
    mass : float
        kg.
    roll_inertia : float
        kg m^2 about the longitudinal axis through the CoG.
    k_lateral : float
        N/m, total lateral stiffness.
    lever : float
        m, height of the lateral springs relative to the CoG.
    k_roll : float
        N m/rad, roll stiffness from the vertical springs (and anti-roll bars), including
        the gravitational term (negative for a body standing on springs below its CoG).

    Returns
    -------
    tuple of float
        (lower sway, upper sway) frequencies in Hz.
    """
    k = np.array(
        [[k_lateral, -k_lateral * lever], [-k_lateral * lever, k_lateral * lever**2 + k_roll]]
    )
    w2 = np.linalg.eigvalsh(k / np.sqrt(np.outer([mass, roll_inertia], [mass, roll_inertia])))
    lo, hi = np.sqrt(np.clip(w2, 0.0, None)) / (2.0 * math.pi)
    return float(lo), float(hi)


def _wheelsets_of(model: VehicleModel, j: int) -> list[int]:
    return [i for i, b in enumerate(model.wheelset.bogie) if b == j]


def _primary_vertical(model: VehicleModel, k_track_z: float) -> float:
    """Vertical stiffness (N/m) of one axlebox spring in series with its wheel's track spring."""
    return series(model.primary.k_z, k_track_z)


def _per_bogie_vertical(model: VehicleModel, k_track_z: float) -> float:
    """Vertical stiffness (N/m) under the car body at one bogie: secondary in series with the
    bogie's four axlebox springs (each in series with its track spring); bogie mass neglected."""
    _, _, secondary = full_vehicle_parts(model)
    return series(2.0 * secondary.k_z, 4.0 * _primary_vertical(model, k_track_z))


def carbody_bounce_frequency(model: VehicleModel, k_track_z: float = math.inf) -> float:
    """Car body bounce (Hz): f = sqrt(K / m) / 2 pi.

    K: per bogie the two secondary springs in series with the four axlebox springs (each in
    series with the wheel's track spring ``k_track_z``), summed over the bogies; the bogie
    mass is neglected (quasi-static series: Iwnicki (ed.), Handbook of Railway Vehicle
    Dynamics, 2006, ch. 5 "Suspension components", the suspension stages of a bogie vehicle
    in series; first principles). Bounce and pitch uncouple for a car body midway between
    the bogies.

    Parameters
    ----------
    model : VehicleModel
        A full vehicle.
    k_track_z : float
        N/m, vertical support stiffness under each wheel (default: rigid).

    Returns
    -------
    float
        Hz.
    """
    car_body, _, _ = full_vehicle_parts(model)
    return _hz(model.n_bogies * _per_bogie_vertical(model, k_track_z), car_body.mass)


def carbody_pitch_frequency(model: VehicleModel, k_track_z: float = math.inf) -> float:
    """Car body pitch (Hz): K = sum_bogies (K_b a_b^2 + 2 k_x2 e^2) + m g e, J = Jy.

    K_b as in :func:`carbody_bounce_frequency`, a_b the bogie centre's distance from the
    car body's CoG; e = height of the secondary springs minus the CoG height (< 0): pitch
    moves the springs' ends longitudinally by e theta against the bogies (the car body's
    longitudinal position is held by the moving frame), and m g e is the gravitational term
    of a body standing on vertical springs below its CoG (first principles; Garg &
    Dukkipati 1984, ch. 7).

    Parameters
    ----------
    model : VehicleModel
        A full vehicle.
    k_track_z : float
        N/m, vertical support stiffness under each wheel (default: rigid).

    Returns
    -------
    float
        Hz.
    """
    car_body, bogie, secondary = full_vehicle_parts(model)
    e = secondary.height - car_body.cog_height
    k = sum(
        _per_bogie_vertical(model, k_track_z) * (x_bogie - car_body.x[0]) ** 2
        + 2.0 * secondary.k_x * e**2
        for x_bogie in bogie.x
    )
    return _hz(k + car_body.mass * GRAVITY * e, car_body.pitch_inertia)


def carbody_yaw_frequency(model: VehicleModel) -> float:
    """Car body yaw on the secondary suspension, bogies held (Hz).

    K = sum over bogies of 2 k_y a_b^2 (lateral springs at the bogie centre's distance a_b
    from the CoG) + 2 k_x b^2 (longitudinal springs at the lateral semi-spacing b) +
    the secondary yaw stiffness; J = Jz (first principles; Garg & Dukkipati 1984, ch. 7).

    Parameters
    ----------
    model : VehicleModel
        A full vehicle.

    Returns
    -------
    float
        Hz.
    """
    car_body, bogie, secondary = full_vehicle_parts(model)
    k = sum(
        2.0 * secondary.k_y * (x_bogie - car_body.x[0]) ** 2
        + 2.0 * secondary.k_x * secondary.semi_spacing**2
        + model.secondary_yaw_stiffness
        for x_bogie in bogie.x
    )
    return _hz(k, car_body.yaw_inertia)


def carbody_sway_frequencies(
    model: VehicleModel, k_track_z: float = math.inf, bogies_held: bool = False
) -> tuple[float, float]:
    """Car body lower and upper sway (coupled lateral-roll), 2x2 (Hz).

    :func:`sway_frequencies` with: lateral springs 2 k_y2 per bogie at the secondary
    height (in series with the bogie's four primary k_y1 unless ``bogies_held``); roll
    stiffness per bogie (2 k_z2 b2^2 + anti-roll bar) in series with the primary roll
    stiffness 4 k_z1 b1^2 (unless ``bogies_held``); gravitational term m g e with
    e = secondary height - CoG height (< 0). Bogie masses neglected (quasi-static series).

    Parameters
    ----------
    model : VehicleModel
        A full vehicle.
    k_track_z : float
        N/m, vertical support stiffness under each wheel (default: rigid).
    bogies_held : bool
        True: the textbook model on the secondary suspension alone.

    Returns
    -------
    tuple of float
        (lower, upper) in Hz.
    """
    car_body, _, secondary = full_vehicle_parts(model)
    primary = model.primary
    k_lat = 2.0 * secondary.k_y
    k_roll = 2.0 * secondary.k_z * secondary.semi_spacing**2 + model.anti_roll_stiffness
    if not bogies_held:
        k_lat = series(k_lat, 4.0 * primary.k_y)
        k_roll = series(k_roll, 4.0 * _primary_vertical(model, k_track_z) * primary.semi_spacing**2)
    e = secondary.height - car_body.cog_height
    return sway_frequencies(
        car_body.mass,
        car_body.roll_inertia,
        model.n_bogies * k_lat,
        e,
        model.n_bogies * k_roll + car_body.mass * GRAVITY * e,
    )


def bogie_bounce_frequency(model: VehicleModel, k_track_z: float = math.inf) -> float:
    """Bogie frame bounce with car body held (Hz): K = 4 k_z1 (series track) + 2 k_z2.

    First principles: the car body is ~12x heavier and bounces at ~1 Hz, far below, so it
    acts as held; the axlebox springs stand on the wheelsets on the track springs.

    Parameters
    ----------
    model : VehicleModel
        A full vehicle.
    k_track_z : float
        N/m, vertical support stiffness under each wheel (default: rigid).

    Returns
    -------
    float
        Hz.
    """
    _, bogie, secondary = full_vehicle_parts(model)
    k = 4.0 * _primary_vertical(model, k_track_z) + 2.0 * secondary.k_z
    return _hz(k, bogie.mass)


def bogie_pitch_frequency(model: VehicleModel, k_track_z: float = math.inf, j: int = 0) -> float:
    """Bogie frame pitch, car body and wheelsets held longitudinally (Hz).

    K = sum over its axleboxes of k_z1 a^2 (a: axle distance from the bogie centre)
    + 4 k_x1 h1^2 + 2 k_x2 h2^2 (longitudinal springs at heights h1, h2 relative to the
    bogie CoG) + the gravitational terms sum F_i h_i of the preloaded vertical springs;
    J = Jy (first principles).

    Parameters
    ----------
    model : VehicleModel
        A full vehicle.
    k_track_z : float
        N/m, vertical support stiffness under each wheel (default: rigid).
    j : int
        Bogie index.

    Returns
    -------
    float
        Hz.
    """
    _, bogie, secondary = full_vehicle_parts(model)
    primary = model.primary
    h1, h2 = primary.height - bogie.cog_height, secondary.height - bogie.cog_height
    kz = _primary_vertical(model, k_track_z)
    k = sum(2.0 * kz * (model.wheelset.x[i] - bogie.x[j]) ** 2 for i in _wheelsets_of(model, j))
    k += 4.0 * primary.k_x * h1**2 + 2.0 * secondary.k_x * h2**2 + _bogie_gravity_term(model, j)
    return _hz(k, bogie.pitch_inertia)


def _bogie_gravity_term(model: VehicleModel, j: int) -> float:
    """sum_i F_i h_i (N m/rad) of the preloaded vertical springs on bogie j: primary forces up
    at h1, secondary forces down at h2 (relative to the bogie CoG): the geometric stiffness
    of rotating a body under vertical point loads (first principles)."""
    car_body, bogie, secondary = full_vehicle_parts(model)
    share = car_body_shares(car_body.x[0], bogie.x)[j] * car_body.mass * GRAVITY
    h1 = model.primary.height - bogie.cog_height
    h2 = secondary.height - bogie.cog_height
    return (share + bogie.mass * GRAVITY) * h1 - share * h2


def bogie_sway_frequencies(
    model: VehicleModel, k_track_z: float = math.inf, k_track_y: float = math.inf, j: int = 0
) -> tuple[float, float]:
    """Bogie frame lower and upper sway (coupled lateral-roll), car body held (Hz).

    For the Manchester bogie the lower mode is ~80 % roll (kinetic energy), the upper ~80 %
    lateral (the lateral springs act 0.14 m below and 0.23 m above the CoG).

    :func:`sway_frequencies` with lateral springs 4 k_y1 at the primary height (each
    wheelset's pair in series with its two track springs ``k_track_y``) and 2 k_y2 at the
    secondary height (their combined lever about the CoG), roll stiffness
    4 k_z1 b1^2 (series track) + 2 k_z2 b2^2 + anti-roll bar + the gravitational term
    (first principles; car body ~33x the bogie's roll inertia: held).

    Parameters
    ----------
    model : VehicleModel
        A full vehicle.
    k_track_z, k_track_y : float
        N/m, vertical and lateral support stiffness under each wheel (default: rigid).
    j : int
        Bogie index.

    Returns
    -------
    tuple of float
        (lower, upper) in Hz.
    """
    _, bogie, secondary = full_vehicle_parts(model)
    primary = model.primary
    h1, h2 = primary.height - bogie.cog_height, secondary.height - bogie.cog_height
    k1 = 2.0 * series(2.0 * primary.k_y, 2.0 * k_track_y)  # two wheelsets
    k2 = 2.0 * secondary.k_y
    k_lat = k1 + k2
    lever = (k1 * h1 + k2 * h2) / k_lat
    # the lateral springs' own roll stiffness beyond k_lat lever^2 (two levers)
    extra = k1 * h1**2 + k2 * h2**2 - k_lat * lever**2
    k_roll = (
        4.0 * _primary_vertical(model, k_track_z) * primary.semi_spacing**2
        + 2.0 * secondary.k_z * secondary.semi_spacing**2
        + model.anti_roll_stiffness
        + _bogie_gravity_term(model, j)
        + extra
    )
    return sway_frequencies(bogie.mass, bogie.roll_inertia, k_lat, lever, k_roll)


def wheelset_bounce_frequency(model: VehicleModel, k_track_z: float) -> float:
    """Wheelset bounce on the track springs and the primary suspension, bogie held (Hz).

    K = 2 k_track_z + 2 k_z1, m = wheelset mass (first principles).

    Parameters
    ----------
    model : VehicleModel
        Any vehicle (full or single-wheelset); its wheelset and primary suspension are used.
    k_track_z : float
        N/m, vertical support stiffness under each wheel.

    Returns
    -------
    float
        Hz.
    """
    return _hz(2.0 * k_track_z + 2.0 * model.primary.k_z, model.wheelset.mass)


def hand_frequencies(
    model: VehicleModel, k_track_z: float = math.inf, k_track_y: float = math.inf
) -> dict[str, float]:
    """All hand-calculated natural frequencies of a full vehicle (Hz), keyed by mode name.

    Keys: ``carbody_bounce``, ``carbody_pitch``, ``carbody_yaw``, ``carbody_lower_sway``,
    ``carbody_upper_sway``, ``bogie_bounce``, ``bogie_pitch``, ``bogie_lower_sway``,
    ``bogie_upper_sway`` and, for finite ``k_track_z``, ``wheelset_bounce``.

    Parameters
    ----------
    model : VehicleModel
        A full vehicle.
    k_track_z, k_track_y : float
        N/m, vertical and lateral support stiffness under each wheel (default: rigid).

    Returns
    -------
    dict of str to float
        Mode name -> frequency (Hz).
    """
    lower, upper = carbody_sway_frequencies(model, k_track_z)
    b_lower, b_upper = bogie_sway_frequencies(model, k_track_z, k_track_y)
    out = {
        "carbody_bounce": carbody_bounce_frequency(model, k_track_z),
        "carbody_pitch": carbody_pitch_frequency(model, k_track_z),
        "carbody_yaw": carbody_yaw_frequency(model),
        "carbody_lower_sway": lower,
        "carbody_upper_sway": upper,
        "bogie_bounce": bogie_bounce_frequency(model, k_track_z),
        "bogie_pitch": bogie_pitch_frequency(model, k_track_z),
        "bogie_lower_sway": b_lower,
        "bogie_upper_sway": b_upper,
    }
    if math.isfinite(k_track_z):
        out["wheelset_bounce"] = wheelset_bounce_frequency(model, k_track_z)
    return out
