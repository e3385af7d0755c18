"""The 3-PSS robot's drawn points, from the plant FMU's own parameters.

The parameters (lp, ld, gamma, lb, alpha, beta, a, strokeMin, strokeMax) are the start
values in the Pss3Plant FMU's modelDescription.xml, with the overrides a scenario or the
user gives; only the three-fold layout of the mechanism (docs/3pss-model.md, "Mechanism
and frames") is written here. Everything is SI: m and rad.

    h_i = lb (sin beta cos(alpha + k_i), sin beta sin(alpha + k_i), cos beta)
    u_i = (cos c_i, sin c_i, 0),  b_i = ld (cos(gamma + m_i), sin(gamma + m_i), 0)
    R = Rz(thz) Ry(thy) Rx(thx),  P = (0, 0, lp)
    l_i = d_i.u_i - sqrt((d_i.u_i)^2 - |d_i|^2 + a^2),  d_i = P + R b_i - h_i
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

# Azimuths of the slider joints k_i, of the platform joints m_i and of the actuator
# axes c_i, deg (docs/3pss-model.md; the same order as the plant's legs 1, 2, 3).
SLIDER_AZIMUTH_DEG = (-120.0, 0.0, 120.0)
PLATFORM_AZIMUTH_DEG = (0.0, 120.0, -120.0)
ACTUATOR_AZIMUTH_DEG = (0.0, 120.0, -120.0)

# The plant's parameter names, as in its modelDescription.xml.
PARAMETERS = ("lp", "ld", "gamma", "lb", "alpha", "beta", "a", "strokeMin", "strokeMax")


class CannotAssemble(ValueError):
    """A leg cannot reach its platform joint at the given orientation."""

    def __init__(self, leg: int):
        super().__init__(f"leg {leg} cannot reach the platform at this orientation")
        self.leg = leg


@dataclass(frozen=True)
class Robot:
    """The fixed vectors of one parameter set (arrays of shape (3, 3): one row per leg)."""

    params: dict[str, float]
    pivot: np.ndarray    # P in {A}
    h: np.ndarray        # slider joints at l = 0, in {A}
    u: np.ndarray        # actuator unit directions, in {A}
    b: np.ndarray        # platform joints relative to P, in {B}

    @property
    def leg_length(self) -> float:
        return self.params["a"]

    @property
    def stroke(self) -> tuple[float, float]:
        return self.params["strokeMin"], self.params["strokeMax"]


def robot(params: dict[str, float]) -> Robot:
    """The fixed vectors for `params` (a dict holding every name in PARAMETERS)."""
    p = {name: float(params[name]) for name in PARAMETERS}
    k = np.radians(SLIDER_AZIMUTH_DEG) + p["alpha"]
    h = p["lb"] * np.column_stack([np.sin(p["beta"]) * np.cos(k), np.sin(p["beta"]) * np.sin(k),
                                   np.full(3, np.cos(p["beta"]))])
    c = np.radians(ACTUATOR_AZIMUTH_DEG)
    u = np.column_stack([np.cos(c), np.sin(c), np.zeros(3)])
    m = np.radians(PLATFORM_AZIMUTH_DEG) + p["gamma"]
    b = p["ld"] * np.column_stack([np.cos(m), np.sin(m), np.zeros(3)])
    return Robot(params=p, pivot=np.array([0.0, 0.0, p["lp"]]), h=h, u=u, b=b)


def rotation(theta) -> np.ndarray:
    """R = Rz(thz) Ry(thy) Rx(thx) for Euler angles (thx, thy, thz), rad."""
    (cx, cy, cz), (sx, sy, sz) = np.cos(theta), np.sin(theta)
    rx = np.array([[1.0, 0.0, 0.0], [0.0, cx, -sx], [0.0, sx, cx]])
    ry = np.array([[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]])
    rz = np.array([[cz, -sz, 0.0], [sz, cz, 0.0], [0.0, 0.0, 1.0]])
    return rz @ ry @ rx


@dataclass(frozen=True)
class Pose:
    """Every point drawn for one orientation, in {A} (rows: legs 1, 2, 3)."""

    theta: np.ndarray      # Euler angles, rad
    rotation: np.ndarray   # R
    l: np.ndarray          # actuator displacements, m (inverse kinematics of theta)
    sliders: np.ndarray    # slider joints M_i = h_i + l_i u_i
    platform: np.ndarray   # platform joints P + R b_i


def platform_joints(rob: Robot, theta) -> np.ndarray:
    """Platform joints P + R b_i in {A} for orientation `theta`."""
    return rob.pivot + rob.b @ rotation(theta).T


def pose(rob: Robot, theta) -> Pose:
    """The robot assembled at `theta` by the closed-form inverse kinematics."""
    theta = np.asarray(theta, dtype=float)
    rot = rotation(theta)
    platform = rob.pivot + rob.b @ rot.T
    # Absurd parameters (ld = 1e300) overflow to inf/nan here: no warning, the check below
    # refuses them with the one-line error.
    with np.errstate(over="ignore", invalid="ignore"):
        d = platform - rob.h
        along = np.einsum("ij,ij->i", d, rob.u)
        discriminant = along**2 - np.einsum("ij,ij->i", d, d) + rob.leg_length**2
    if not np.all(discriminant >= 0.0):
        raise CannotAssemble(int(np.argmin(discriminant >= 0.0)) + 1)
    l = along - np.sqrt(discriminant)
    return Pose(theta=theta, rotation=rot, l=l, sliders=rob.h + l[:, None] * rob.u,
                platform=platform)


def rails(rob: Robot) -> np.ndarray:
    """Each actuator's usable travel: segments (3, 2, 3) from strokeMin to strokeMax."""
    lo, hi = rob.stroke
    return np.stack([rob.h + lo * rob.u, rob.h + hi * rob.u], axis=1)
