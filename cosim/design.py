"""The conversions of a hand-written closed-loop scenario, done when it is loaded:

- base-frame angular velocity and acceleration -> Euler-angle rates and accelerations,
  for R = Rz(thz) Ry(thy) Rx(thx): omega = E(th) th_dot with
  E = [[cz cy, -sz, 0], [sz cy, cz, 0], [-sy, 0, 1]] (the same map as the Rust
  library's pss3::rotation, which the Rust reference uses on the same file);
- PID gains by the triple-pole rule (Kd = 3 m w, Kp = 3 m w^2, Ki = m w^3, the Rust
  closed_loop::gains design): m per Euler axis is the largest diagonal entry of the
  Euler-angle mass matrix M_x over the design poses. M_x is measured on the nominal
  plant FMU itself (Model Exchange, at rest): th_ddot = M_x^-1 (u - G_x), linear in the
  generalized force u, so three unit forces give the columns of M_x^-1 exactly.
"""

from __future__ import annotations

import math
from functools import lru_cache
from pathlib import Path

import numpy as np

from .scenario import ScenarioError

EULER_SINGULAR_COS = 1e-9


def euler_rate_matrix(th) -> np.ndarray:
    sy, cy = math.sin(th[1]), math.cos(th[1])
    sz, cz = math.sin(th[2]), math.cos(th[2])
    return np.array([[cz * cy, -sz, 0.0], [sz * cy, cz, 0.0], [-sy, 0.0, 1.0]])


def euler_rate_matrix_dot(th, rates) -> np.ndarray:
    sy, cy = math.sin(th[1]), math.cos(th[1])
    sz, cz = math.sin(th[2]), math.cos(th[2])
    yd, zd = rates[1], rates[2]
    return np.array([[-cz * sy * yd - sz * cy * zd, -cz * zd, 0.0],
                     [-sz * sy * yd + cz * cy * zd, -sz * zd, 0.0],
                     [-cy * yd, 0.0, 0.0]])


def euler_rates(th, omega) -> list[float]:
    """th_dot = E^-1 omega (written out as the Rust library does, same rounding)."""
    sy, cy = math.sin(th[1]), math.cos(th[1])
    sz, cz = math.sin(th[2]), math.cos(th[2])
    if abs(cy) < EULER_SINGULAR_COS:
        raise ScenarioError(f"Euler angles {np.degrees(th)} deg are singular (thy = +-90 deg)")
    thx_dot = (cz * omega[0] + sz * omega[1]) / cy
    return [thx_dot, -sz * omega[0] + cz * omega[1], omega[2] + sy * thx_dot]


def euler_accelerations(th, rates, omega_dot) -> list[float]:
    """th_ddot = E^-1 (omega_dot - E_dot th_dot)."""
    rhs = np.asarray(omega_dot) - euler_rate_matrix_dot(th, rates) @ np.asarray(rates)
    return euler_rates(th, [float(x) for x in rhs])


def triple_pole_gains(inertia: float, bandwidth: float) -> tuple[float, float, float]:
    """(Kp, Ki, Kd) placing a triple pole at -bandwidth for m s^3 + Kd s^2 + Kp s + Ki."""
    m, w = inertia, bandwidth
    return 3.0 * m * w * w, m * w * w * w, 3.0 * m * w


def design_gains(plant_fmu: Path, poses, bandwidth: float) -> list[tuple[float, float, float]]:
    """(Kp, Ki, Kd) per Euler axis for the largest inertia over `poses` (rad)."""
    if not (math.isfinite(bandwidth) and bandwidth > 0.0) or not poses:
        raise ScenarioError(f"field 'gains.omega' must be positive, got {bandwidth}")
    inertia = np.zeros(3)
    for pose in poses:
        inertia = np.maximum(inertia, euler_inertia(str(plant_fmu), tuple(pose)))
    return [triple_pole_gains(float(m), bandwidth) for m in inertia]


@lru_cache(maxsize=256)
def euler_inertia(plant_fmu: str, pose: tuple[float, float, float]) -> np.ndarray:
    """Diagonal of M_x at `pose` (rad), from the plant FMU at rest (Model Exchange)."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Model

    md = read_model_description(plant_fmu)
    refs = {v.name: v.valueReference for v in md.modelVariables}
    unzip = extract(plant_fmu)
    fmu = FMU2Model(guid=md.guid, unzipDirectory=unzip,
                    modelIdentifier=md.modelExchange.modelIdentifier, instanceName="design")
    fmu.instantiate()
    try:
        fmu.setupExperiment(startTime=0.0)
        fmu.setReal([refs[f"theta0[{i}]"] for i in (1, 2, 3)], list(pose))
        fmu.setReal([refs[f"omega0[{i}]"] for i in (1, 2, 3)], [0.0, 0.0, 0.0])
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        fmu.newDiscreteStates()
        fmu.enterContinuousTimeMode()
        u_refs = [refs[f"generalizedForceCommand[{i}]"] for i in (1, 2, 3)]
        gravity = fmu.getReal([refs[f"gravityCompensation[{i}]"] for i in (1, 2, 3)])
        acc_refs = [refs[f"der(omega[{i}])"] for i in (1, 2, 3)]

        def euler_acceleration(u) -> np.ndarray:
            fmu.setReal(u_refs, list(u))
            # At rest E_dot th_dot = 0, so th_ddot = E^-1 omega_dot.
            return np.array(euler_rates(pose, fmu.getReal(acc_refs)))

        base = euler_acceleration(gravity)
        inverse = np.column_stack([euler_acceleration(np.array(gravity) + e) - base
                                   for e in np.eye(3)])
    finally:
        fmu.terminate()
        fmu.freeInstance()
    return np.diag(np.linalg.inv(inverse))
