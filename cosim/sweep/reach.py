"""Whether the platform can take an orientation: the plant FMU initialised at the pose,
every actuator length within its stroke [strokeMin, strokeMax]."""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from ..errors import CosimError


@lru_cache(maxsize=4096)
def _reachable(plant_fmu: str, pose: tuple[float, float, float]) -> bool:
    from ..fmu import FmuInstance
    fmu = FmuInstance("plant", Path(plant_fmu), 0.0, 1.0)
    try:
        fmu.set_values(("theta0[1]", "theta0[2]", "theta0[3]"), list(pose))
        fmu.enter_initialization()
        fmu.exit_initialization()
        lengths = fmu.get_values(("l[1]", "l[2]", "l[3]"))
        low, high = fmu.get_values(("strokeMin", "strokeMax"))
    except CosimError:
        return False
    finally:
        fmu.close()
    return all(low <= x <= high for x in lengths)


def reachable(plant_fmu: Path, pose) -> bool:
    """`pose`: Euler angles (rad)."""
    return _reachable(str(plant_fmu), tuple(float(x) for x in pose))
