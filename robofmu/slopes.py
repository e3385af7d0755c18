"""Input derivatives for input_extrapolation = "linear" (order 1) and "quadratic"
(order 2): which output derivatives an FMU really serves, which input derivatives it
really takes, and the derivatives through the last samples where a source serves none.

An FMU declares maxOutputDerivativeOrder for all its outputs, but some answer
fmi2Error for some of them (an error that ends the instance); FMI 2.0 declares no
highest order of input derivatives at all (canInterpolateInputs says only that there
is one). Before a master passes derivatives it asks a throwaway instance, initialised
at its start values: the source for orders 1..n of each connected output, the target
to take orders 1..n of each connected input. The answers are cached per FMU file and
variable list, so a sweep asks once per process. Each signal then takes the highest
order that its source serves (or its history gives), its target takes and the
scenario asks for.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np
from fmpy import read_model_description

from .errors import CosimError
from .instances import give_back, open_instance


def _probe(path: str, call) -> bool:
    """`call` on a shared instance of the FMU (robofmu.instances) in initialisation
    mode; False when the FMU refuses (the instance is reset before its next use)."""
    try:
        fmu = open_instance("probe", Path(path), 0.0, 1.0)
    except Exception:  # noqa: BLE001 - any failure: no derivatives (the run reports it)
        return False
    try:
        fmu.enter_initialization()
        return call(fmu)
    except CosimError:
        return False
    except BaseException:
        fmu.close()
        raise
    finally:
        give_back(fmu)


def _outputs(names: tuple[str, ...], order: int):
    def call(fmu) -> bool:
        fmu.exit_initialization()
        fmu.get_output_derivatives(names, order)
        return True
    return call


def _inputs(names: tuple[str, ...], order: int):
    def call(fmu) -> bool:
        fmu.set_input_derivatives(names, [0.0] * (order * len(names)), order)
        return True
    return call


def _highest(path: str, names: tuple[str, ...], order: int, probe) -> dict[str, int]:
    """Per name, the highest order in 0..order for which `probe(names, order)` passes
    (orders 1..k all pass when k does: both calls take every order up to k at once)."""
    if order >= 1 and _probe(path, probe(names, order)):
        return dict.fromkeys(names, order)
    found = {}
    for name in names:
        found[name] = next((k for k in range(order, 0, -1)
                            if _probe(path, probe((name,), k))), 0)
    return found


@lru_cache(maxsize=64)
def _feedthrough(path: str) -> frozenset[str]:
    """The outputs of the FMU at `path` that depend on an input at the same instant (its
    ModelStructure; an output without a dependency list depends on every input)."""
    try:
        md = read_model_description(path)
    except Exception:  # noqa: BLE001 - unreadable here: the run's own checks report it
        return frozenset()
    inputs = any(v.causality == "input" for v in md.modelVariables)
    return frozenset(o.variable.name for o in md.outputs
                     if (inputs if o.dependencies is None
                         else any(d.causality == "input" for d in o.dependencies)))


@lru_cache(maxsize=256)
def served(path: str, names: tuple[str, ...], order: int) -> dict[str, int]:
    """Per name, the highest output derivative order (at most `order`, 0: none) the FMU
    at `path` returns; 0 for an output with direct feedthrough (`_feedthrough`; FMI 3.0
    scalars `x[k]` by their array `x`): its derivative at a communication point follows
    its inputs as they were set, not as they move over the next step, so the signal's
    history gives the better slope (the PID's u: a P term on a moving measurement)."""
    through = _feedthrough(path)
    smooth = tuple(n for n in names if n not in through and n.split("[")[0] not in through)
    found = _highest(path, smooth, order, _outputs) if smooth else {}
    return {n: found.get(n, 0) for n in names}


@lru_cache(maxsize=256)
def accepted(path: str, names: tuple[str, ...], order: int) -> dict[str, int]:
    """Per input name, the highest input derivative order (at most `order`) the FMU at
    `path` takes."""
    return _highest(path, names, order, _inputs)


class History:
    """Derivatives of connected outputs whose FMU gives none, from their values at the
    last communication points: those at t_k of the polynomial through the last
    order + 1 points (Newton's divided differences, any spacing: a retried step halves
    it). Order 1: (x_k - x_{k-1}) / (t_k - t_{k-1}). Order 2: with
    d1 = (x_k - x_{k-1}) / (t_k - t_{k-1}), d1' the same one point back and
    d2 = (d1 - d1') / (t_k - t_{k-2}): x' = d1 + d2 (t_k - t_{k-1}), x'' = 2 d2.
    While fewer points are known the order is lower (zero at the first point); at a
    time already seen (a step retried after a discard) the last derivatives.

    The state lives in numpy arrays that the native loop (crates/tools/cosim-kernel) reads and
    updates in place with the same operations in the same order: `past` (order rows:
    the values at the last points, newest first), `times` (their times), `count` (how
    many are known, at most order) and `out` (order rows: the derivatives)."""

    def __init__(self, order: int, n: int):
        self.order = order
        self.past = np.zeros((order, n))
        self.state = np.zeros(order + 1)  # [count, t of past[0], t of past[1], ...]
        self.out = np.zeros((order, n))

    def derivatives(self, t: float, values: np.ndarray) -> np.ndarray:
        """The derivatives at t of the signal now `values`; updates the history."""
        count = int(self.state[0])
        if count > 0 and t <= self.state[1]:
            return self.out
        self.out[:] = 0.0
        if count >= 1:
            d1 = (values - self.past[0]) / (t - self.state[1])
            self.out[0] = d1
            if self.order >= 2 and count >= 2:
                back = (self.past[0] - self.past[1]) / (self.state[1] - self.state[2])
                d2 = (d1 - back) / (t - self.state[2])
                self.out[0] = d1 + d2 * (t - self.state[1])
                self.out[1] = 2.0 * d2
        self.past[1:] = self.past[:-1].copy()
        self.state[2:] = self.state[1:-1].copy()
        self.past[0] = values
        self.state[1] = t
        self.state[0] = min(count + 1, self.order)
        return self.out

    def seed(self, t0: float, h: float, points: list[np.ndarray]) -> None:
        """Past points before t0 from the values at t0, t0 + h, ... t0 + order h (a
        start-up run of `order` steps): those of the polynomial through them at
        t0 - h, ..., t0 - order h, so that the derivatives at t0 are the polynomial's.
        A multistep start-up: without it the first steps extrapolate with a lower
        order and their error dominates the run's."""
        x = points
        if self.order == 1:
            back = [x[0] - (x[1] - x[0])]
        else:  # the parabola through x0, x1, x2 at -h and -2h
            back = [3.0 * x[0] - 3.0 * x[1] + x[2], 6.0 * x[0] - 8.0 * x[1] + 3.0 * x[2]]
        for k, value in enumerate(back):
            self.past[k] = value
            self.state[k + 1] = t0 - (k + 1) * h
        self.state[0] = self.order
