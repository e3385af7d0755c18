"""Whether the platform can take an orientation: the one workspace check of
robofmu/workspace.py (the plant FMU initialised at the pose, every actuator length within
its stroke [strokeMin, strokeMax]), with the FMU's default parameters."""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from ..workspace import Workspace


@lru_cache(maxsize=4096)
def _reachable(plant_fmu: str, pose: tuple[float, float, float]) -> bool:
    with Workspace(Path(plant_fmu), {}) as workspace:
        return workspace.problem(pose) is None


def reachable(plant_fmu: Path, pose) -> bool:
    """`pose`: Euler angles (rad)."""
    return _reachable(str(plant_fmu), tuple(float(x) for x in pose))
