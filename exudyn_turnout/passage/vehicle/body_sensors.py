"""Sensors of the full vehicle's bodies during a passage, and their columns after it.

The run loops (co-running track and FE track) call :func:`add_body_sensors` once per built
system and :func:`recorded_body_columns` once per run segment: three Exudyn sensors on the
linear vehicle's suspension element (its coordinates, velocities and accelerations: every
body's, in one vector each), read after the run and turned into the columns of
:func:`~exudyn_turnout.passage.vehicle.body_outputs.body_columns`. The accelerations are the
integrator's (generalized-alpha's q_tt), not differences of stored displacements. Cost: ~3 us
per stored step for the three sensors (measured on a 35-coordinate element, 20,000 steps,
against a full-vehicle step of ~230 us CPU).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import SensorBody

from exudyn_turnout.passage.vehicle.body_outputs import body_columns
from exudyn_turnout.passage.vehicle.handles import VehicleBuild

__all__ = ["SENSORS_KEY", "GEOMETRY_STEP", "add_body_sensors", "recorded_body_columns"]

#: ``mbs.variables`` key of the sensors (the build, the sensor numbers, the body loads).
SENSORS_KEY = "exudyn_turnout.passage.vehicle.body_sensors"

#: m, central-difference step of the track-following frame's rate (as the body loads' table).
GEOMETRY_STEP = 0.01


def add_body_sensors(mbs: Any, build: VehicleBuild, loads: Any = None) -> None:
    """Add the body sensors to a system that is not yet assembled (nothing for a vehicle
    without a car body or not in the linear representation).

    Parameters
    ----------
    mbs : exudyn.MainSystem
    build : VehicleBuild
        The vehicle, linear representation.
    loads : BodyLoads, optional
        The run's track-following frame (route curvature, x at t = 0, speed); None: a
        straight route at rest.
    """
    if build.car_body is None or "suspension" not in build.items:
        return
    kinds = (
        exu.OutputVariableType.Coordinates,
        exu.OutputVariableType.Coordinates_t,
        exu.OutputVariableType.Coordinates_tt,
    )
    sensors = tuple(
        int(
            mbs.AddSensor(
                SensorBody(
                    bodyNumber=build.items["suspension"],
                    storeInternal=True,
                    writeToFile=False,
                    outputVariableType=kind,
                )
            )
        )
        for kind in kinds
    )
    mbs.variables[SENSORS_KEY] = (build, sensors, loads)


def recorded_body_columns(
    mbs: Any, t: np.ndarray, stored_data: Callable[[int], np.ndarray] | None = None
) -> dict[str, np.ndarray]:
    """The body columns at the times ``t`` of a finished run (empty without sensors).

    Parameters
    ----------
    mbs : exudyn.MainSystem
        After its SolveDynamic.
    t : numpy.ndarray
        s, the run's own times (from its start), one per output row; each is matched to the
        nearest stored sensor sample (the sensors store every step or every output step).
    stored_data : callable(sensor) -> numpy.ndarray, optional
        A sensor's samples (default ``mbs.GetSensorStoredData``; a run of the compiled
        stepper gives its own).

    Returns
    -------
    dict
        :func:`~exudyn_turnout.passage.vehicle.body_outputs.body_columns`, one value per
        time.
    """
    entry = mbs.variables.get(SENSORS_KEY)
    if entry is None:
        return {}
    build, sensors, loads = entry
    read = mbs.GetSensorStoredData if stored_data is None else stored_data
    stored = [np.asarray(read(s), float) for s in sensors]
    times = stored[0][:, 0]
    t = np.asarray(t, float)
    rows = np.clip(np.searchsorted(times, t), 1, len(times) - 1)
    rows = np.where(np.abs(times[rows - 1] - t) <= np.abs(times[rows] - t), rows - 1, rows)
    q, q_t, q_tt = (a[rows, 1:] for a in stored)
    kwargs: dict[str, Any] = {}
    if loads is not None and loads.curved and not loads.frozen:
        x_front = loads.x_f0 + loads.v * t
        h = GEOMETRY_STEP
        kwargs["q_geo"] = loads.geometries(x_front)
        ahead, behind = loads.geometries(x_front + h), loads.geometries(x_front - h)
        kwargs["q_geo_t"] = (ahead - behind) * (loads.v / (2 * h))
        # the car body's frame (the reference's, last column): its centripetal and angular
        # accelerations, as its curving and Euler loads in the run
        lateral, yaw = loads.frame_accelerations(x_front)
        kwargs["centripetal"], kwargs["frame_yaw_acceleration"] = lateral[:, -1], yaw[:, -1]
    return body_columns(build, q, q_t, q_tt, **kwargs)
