"""Input slopes for input_extrapolation = "linear": which output derivatives an FMU
really serves, and the slope through the last two samples where it serves none.

An FMU declares maxOutputDerivativeOrder for all its outputs, but some answer
fmi2Error for some of them (an error that ends the instance). Before a master passes
slopes from an FMU it asks a throwaway instance, initialised at its start values,
for the first derivative of each connected output; the answer is cached per FMU
file and variable list, so a sweep asks once per process.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np

from .errors import CosimError


def _probe(path: str, names: tuple[str, ...]) -> bool:
    from .fmu import FmuInstance
    try:
        fmu = FmuInstance("probe", Path(path), 0.0, 1.0)
    except Exception:  # noqa: BLE001 - any failure: no slopes (the run reports it)
        return False
    try:
        fmu.enter_initialization()
        fmu.exit_initialization()
        fmu.get_output_slopes(names)
        return True
    except CosimError:
        return False
    finally:
        fmu.close()


@lru_cache(maxsize=256)
def served(path: str, names: tuple[str, ...]) -> frozenset[str]:
    """The names among `names` whose first derivative the FMU at `path` returns."""
    if _probe(path, names):
        return frozenset(names)
    return frozenset(n for n in names if _probe(path, (n,)))


class History:
    """The slope of a connected output through its values at the last two
    communication points, (x_k - x_{k-1}) / (t_k - t_{k-1}): linear extrapolation over
    the next step for an output whose FMU gives no derivatives. Zero at the first
    point; at a time already seen (a step retried after a discard) the last slope."""

    def __init__(self):
        self.t: float | None = None
        self.values: np.ndarray | None = None
        self.last: np.ndarray | None = None

    def slopes(self, t: float, values: np.ndarray) -> np.ndarray:
        if self.t is None or self.values is None:
            self.last = np.zeros_like(values)
        elif t > self.t:
            self.last = (values - self.values) / (t - self.t)
        else:
            assert self.last is not None  # set with self.t
            return self.last
        self.t, self.values = t, values.copy()
        return self.last
