"""The conversions of a hand-written closed-loop scenario, done when it is loaded:

- base-frame angular velocity and acceleration -> Euler-angle rates and accelerations,
  for R = Rz(thz) Ry(thy) Rx(thx): omega = E(th) th_dot with
  E = [[cz cy, -sz, 0], [sz cy, cz, 0], [-sy, 0, 1]] (the same map as the Rust
  library's pss3::rotation, which the Rust reference uses on the same file);
- PID gains by the triple-pole rule (Kd = 3 m w, Kp = 3 m w^2, Ki = m w^3: the rule
  "pid" of robofmu/closed_loop.toml, which the Rust reference's closed_loop::gains
  reads too): m per Euler axis is the largest diagonal entry of the
  Euler-angle mass matrix M_x over the design poses. M_x is measured on the plant FMU
  itself with the scenario's plant parameters (Model Exchange, at rest):
  th_ddot = M_x^-1 (u - G_x), linear in the generalized force u, so three unit forces
  give the columns of M_x^-1 exactly.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .controllers import rule_gains
from .errors import ScenarioError
from .model_exchange import ModelExchangeInstance

EULER_SINGULAR_COS = 1e-9


class PlantRefused(ScenarioError):
    """The plant FMU refuses the design's parameters or pose; `reason` is its own line."""

    def __init__(self, message: str, reason: str):
        super().__init__(message)
        self.reason = reason


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
        angles = ", ".join(f"{math.degrees(x):.6g}" for x in th)
        raise ScenarioError(f"the Euler angles ({angles}) deg are singular (thy = +-90 deg)")
    thx_dot = (cz * omega[0] + sz * omega[1]) / cy
    return [thx_dot, -sz * omega[0] + cz * omega[1], omega[2] + sy * thx_dot]


def euler_accelerations(th, rates, omega_dot) -> list[float]:
    """th_ddot = E^-1 (omega_dot - E_dot th_dot)."""
    rhs = np.asarray(omega_dot) - euler_rate_matrix_dot(th, rates) @ np.asarray(rates)
    return euler_rates(th, [float(x) for x in rhs])


def triple_pole_gains(inertia: float, bandwidth: float) -> tuple[float, float, float]:
    """(Kp, Ki, Kd) placing a triple pole at -bandwidth for m s^3 + Kd s^2 + Kp s + Ki."""
    return rule_gains("pid", inertia, bandwidth)  # robofmu/closed_loop.toml


def design_gains(plant_fmu: Path, poses, bandwidth: float,
                 plant: dict | None = None) -> list[tuple[float, float, float]]:
    """(Kp, Ki, Kd) per Euler axis for the largest inertia over `poses` (rad) of the
    plant FMU with the parameters `plant` ({name: SI value}; default: its own)."""
    check_bandwidth(bandwidth, poses)
    parameters = tuple(sorted((plant or {}).items()))
    inertia = np.zeros(3)
    for at_pose in euler_inertias(str(plant_fmu), [tuple(p) for p in poses], parameters):
        inertia = np.maximum(inertia, at_pose)
    return [triple_pole_gains(float(m), bandwidth) for m in inertia]


def check_bandwidth(bandwidth: float, poses) -> None:
    """ScenarioError unless the design rule has a positive bandwidth and poses."""
    if not (math.isfinite(bandwidth) and bandwidth > 0.0) or not poses:
        raise ScenarioError(f"field 'gains.omega' must be positive, got {bandwidth}")


# (plant FMU, pose, parameters) -> diagonal of M_x: a plant is linearised once per pose.
_INERTIA: dict[tuple, np.ndarray] = {}
MAX_CACHED = 256


def euler_inertias(plant_fmu: str, poses: list[tuple[float, float, float]],
                   parameters: tuple = ()) -> list[np.ndarray]:
    """Diagonal of M_x at each pose (rad), from the plant FMU at rest (Model Exchange)
    with `parameters` ((name, value) pairs) set: one instance for every pose not
    computed before (fmi2Reset between poses). A pose the plant refuses raises
    ScenarioError with the plant's own reason."""
    keys = [(plant_fmu, tuple(pose), parameters) for pose in poses]
    todo = [key for key in dict.fromkeys(keys) if key not in _INERTIA]
    if len(_INERTIA) + len(todo) > MAX_CACHED:
        _INERTIA.clear()
    if todo:
        with ModelExchangeInstance(plant_fmu, "design") as fmu:
            for k, key in enumerate(todo):
                if k:
                    fmu.reset()
                _INERTIA[key] = _inertia_at(fmu, key[1], parameters)
    return [_INERTIA[key] for key in keys]


def euler_inertia(plant_fmu: str, pose: tuple[float, float, float],
                  parameters: tuple = ()) -> np.ndarray:
    """euler_inertias at one pose."""
    return euler_inertias(plant_fmu, [pose], parameters)[0]


def _inertia_at(fmu, pose, parameters: tuple) -> np.ndarray:
    try:
        fmu.set_values(dict(parameters))
        return _euler_inertia(fmu, pose)
    except fmu.Failed as e:
        deg = ", ".join(f"{math.degrees(x):.6g}" for x in pose)
        raise PlantRefused(f"field 'gains': the plant cannot be linearised at the "
                           f"design pose ({deg}) deg: {fmu.reason(e)}; choose design "
                           "poses inside the workspace", fmu.reason(e)) from None


def _euler_inertia(fmu, pose) -> np.ndarray:
    fmu.set_real([f"theta0[{i}]" for i in (1, 2, 3)], list(pose))
    fmu.set_real([f"omega0[{i}]" for i in (1, 2, 3)], [0.0, 0.0, 0.0])
    fmu.initialize()
    u_refs = [f"generalizedForceCommand[{i}]" for i in (1, 2, 3)]
    gravity = fmu.get_real([f"gravityCompensation[{i}]" for i in (1, 2, 3)])
    acc_refs = [f"der(omega[{i}])" for i in (1, 2, 3)]

    def euler_acceleration(u) -> np.ndarray:
        fmu.set_real(u_refs, list(u))
        # At rest E_dot th_dot = 0, so th_ddot = E^-1 omega_dot.
        return np.array(euler_rates(pose, fmu.get_real(acc_refs)))

    base = euler_acceleration(gravity)
    inverse = np.column_stack([euler_acceleration(np.array(gravity) + e) - base
                               for e in np.eye(3)])
    if not np.all(np.isfinite(inverse)) or abs(np.linalg.det(inverse)) == 0.0:
        raise ScenarioError("field 'gains': the plant's mass matrix is singular at a design "
                            "pose; choose design poses inside the workspace")
    return np.diag(np.linalg.inv(inverse))
