"""The frames of an animation: a few samples of the run, each with the robot's points,
the planned platform (the ghost) and the end stops touched since the previous frame."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import AnimateError
from .geometry import CannotAssemble, Pose, Robot, platform_joints, pose, rotation
from .motion import Motion

# An actuator within this distance of strokeMin or strokeMax, or past it, is at the end
# stop, m (the plant's spring end stops let it run slightly past the stroke).
STOP_TOLERANCE = 1e-6


@dataclass(frozen=True)
class Frame:
    """One picture: its row in the run, the time, the robot, the planned platform joints and its rotation
    (None without a planner) and, per actuator, -1 lower stop, +1 upper stop, 0 free."""

    row: int
    time: float
    pose: Pose
    ghost: np.ndarray | None
    ghost_rotation: np.ndarray | None
    stops: np.ndarray


def frame_rows(samples: int, frames: int) -> np.ndarray:
    """Rows of `frames` pictures spread evenly over `samples` rows, first and last
    included (fewer when the run has fewer rows)."""
    return np.unique(np.round(np.linspace(0, samples - 1, min(frames, samples))).astype(int))


def _assemble(rob: Robot, motion: Motion, row: int) -> Pose:
    try:
        return pose(rob, motion.theta[row])
    except CannotAssemble as e:
        raise AnimateError(motion.source, f"line {row + 2}", f"{e}; the plant parameters "
                           "do not match the run: pass its scenario with --scenario") from None


def _displacements(rob: Robot, motion: Motion) -> np.ndarray:
    """The actuator displacements of every row: the plant's own, else by kinematics."""
    if motion.l is not None:
        return motion.l
    return np.array([_assemble(rob, motion, k).l for k in range(len(motion.time))])


def stop_flags(rob: Robot, motion: Motion, rows: np.ndarray) -> np.ndarray:
    """(frames, 3): the end stop each actuator touched in the rows since the previous
    frame (the lower one wins a tie, which needs a stroke of zero)."""
    lo, hi = rob.stroke
    l = _displacements(rob, motion)
    lower = l <= lo + STOP_TOLERANCE
    upper = l >= hi - STOP_TOLERANCE
    if motion.at_stop is not None:
        lower |= motion.at_stop < 0
        upper |= motion.at_stop > 0
    flags = np.zeros((len(rows), 3), dtype=int)
    starts = np.concatenate([[rows[0]], rows[:-1] + 1])
    for j, (first, last) in enumerate(zip(starts, rows)):
        span = slice(first, last + 1)
        flags[j] = np.where(lower[span].any(axis=0), -1, np.where(upper[span].any(axis=0), 1, 0))
    return flags


def make_frames(rob: Robot, motion: Motion, frames: int) -> list[Frame]:
    """`frames` pictures of `motion` (fewer when it has fewer samples)."""
    rows = frame_rows(len(motion.time), frames)
    flags = stop_flags(rob, motion, rows)
    out = []
    for row, stops in zip(rows, flags):
        planned = None if motion.planned is None else motion.planned[row]
        out.append(Frame(
            row=int(row), time=float(motion.time[row]), pose=_assemble(rob, motion, row),
            ghost=None if planned is None else platform_joints(rob, planned),
            ghost_rotation=None if planned is None else rotation(planned), stops=stops))
    return out
