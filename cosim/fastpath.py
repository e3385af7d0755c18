"""The per-step FMI calls of the master through prepared ctypes arrays and prototypes.

FMPy's wrappers build new value-reference and value arrays, convert lists and log on
every call. The step of a chain of FMUs only ever repeats the same calls, so this module
prepares them once: per connected pair one value-reference array per side and one shared
value buffer (fmi2GetReal of the source writes into the buffer that fmi2SetReal of the
target reads, no Python values in between), and per FMU one buffer for the recorded
signals. The C functions are called through their own prototypes with addresses
prepared as plain integers.

Only Real variables take this path; a scenario that connects or records an Integer or
Boolean variable runs on the generic path (FmuInstance.get_values / set_values).
"""

from __future__ import annotations

import ctypes
from ctypes import c_double, c_int, c_size_t, c_uint, c_void_p

import numpy as np

from .errors import FmuError, StepDiscarded

_TRANSFER = ctypes.CFUNCTYPE(c_int, c_void_p, c_void_p, c_size_t, c_void_p)
_DO_STEP = ctypes.CFUNCTYPE(c_int, c_void_p, c_double, c_double, c_int)
_DISCARD = 2


def _function(fmu, name: str, prototype):
    return prototype(ctypes.cast(getattr(fmu._fmu.dll, name), c_void_p).value)


def _refs(fmu, names) -> ctypes.Array | None:
    """Value references of `names`, or None when one of them is not Real."""
    refs = []
    for name in names:
        v = fmu.variables.get(name)
        if v is None:
            raise FmuError(f"{fmu.alias} has no variable '{name}'")
        if v.type != "Real":
            return None
        refs.append(v.valueReference)
    return (c_uint * len(refs))(*refs)


class Transfer:
    """One prepared get (source) + set (target) through a shared buffer."""

    def __init__(self, source, variables, target, inputs):
        self.source, self.target = source, target
        self.src_refs, self.dst_refs = _refs(source, variables), _refs(target, inputs)
        self.ok = self.src_refs is not None and self.dst_refs is not None
        if not self.ok:
            return
        self.buffer = (c_double * len(variables))()
        self.get = _function(source, "fmi2GetReal", _TRANSFER)
        self.set = _function(target, "fmi2SetReal", _TRANSFER)
        self.args_get = (source._fmu.component, ctypes.addressof(self.src_refs),
                         len(variables), ctypes.addressof(self.buffer))
        self.args_set = (target._fmu.component, ctypes.addressof(self.dst_refs),
                         len(variables), ctypes.addressof(self.buffer))
        self.names = (variables, inputs)

    def __call__(self) -> None:
        if self.get(*self.args_get) > 1:
            raise FmuError(f"{self.source.alias}: fmi2GetReal({', '.join(self.names[0])}) "
                           f"failed: {self.source._last_message()}")
        if self.set(*self.args_set) > 1:
            raise FmuError(f"{self.target.alias}: fmi2SetReal({', '.join(self.names[1])}) "
                           f"failed: {self.target._last_message()}")


_SLOPES = ctypes.CFUNCTYPE(c_int, c_void_p, c_void_p, c_size_t, c_void_p, c_void_p)


def _orders(n: int, order: int) -> ctypes.Array:
    """Derivative orders 1..order of n values each, as the value references repeat."""
    return (c_int * (n * order))(*(k for k in range(1, order + 1) for _ in range(n)))


class SlopeTransfer:
    """One prepared fmi2GetRealOutputDerivatives (source, orders 1..order) +
    fmi2SetRealInputDerivatives (target) through a shared buffer: the input derivatives
    over the next step (all of order 1, then all of order 2)."""

    ok = True

    def __init__(self, source, variables, target, inputs, order):
        self.source, self.target = source, target
        self.src_refs = _refs(source, tuple(variables) * order)
        self.dst_refs = _refs(target, tuple(inputs) * order)
        n = len(variables) * order
        self.orders = _orders(len(variables), order)
        self.buffer = (c_double * n)()
        self.get = _function(source, "fmi2GetRealOutputDerivatives", _SLOPES)
        self.set = _function(target, "fmi2SetRealInputDerivatives", _SLOPES)
        self.args_get = (source._fmu.component, ctypes.addressof(self.src_refs), n,
                         ctypes.addressof(self.orders), ctypes.addressof(self.buffer))
        self.args_set = (target._fmu.component, ctypes.addressof(self.dst_refs), n,
                         ctypes.addressof(self.orders), ctypes.addressof(self.buffer))
        self.names = (variables, inputs)

    def __call__(self, _t: float = 0.0) -> None:
        if self.get(*self.args_get) > 1:
            raise FmuError(f"{self.source.alias}: fmi2GetRealOutputDerivatives("
                           f"{', '.join(self.names[0])}) failed: "
                           f"{self.source._last_message()}")
        if self.set(*self.args_set) > 1:
            raise FmuError(f"{self.target.alias}: fmi2SetRealInputDerivatives("
                           f"{', '.join(self.names[1])}) failed: "
                           f"{self.target._last_message()}")


class HistorySlope:
    """The derivatives through the last samples (cosim.slopes.History) of the values a
    value Transfer just moved, set as the target's input derivatives."""

    def __init__(self, transfer: Transfer, history):
        self.transfer, self.history = transfer, history
        n, order = len(transfer.names[0]), history.order
        self.values = np.frombuffer(transfer.buffer, dtype=np.float64)
        self.orders = _orders(n, order)
        self.refs = (c_uint * (n * order))(*(list(transfer.dst_refs) * order))
        self.set = _function(transfer.target, "fmi2SetRealInputDerivatives", _SLOPES)
        self.args = (transfer.target._fmu.component, ctypes.addressof(self.refs), n * order,
                     ctypes.addressof(self.orders), history.out.ctypes.data)

    def __call__(self, t: float) -> None:
        self.history.derivatives(t, self.values)
        if self.set(*self.args) > 1:
            raise FmuError(f"{self.transfer.target.alias}: fmi2SetRealInputDerivatives("
                           f"{', '.join(self.transfer.names[1])}) failed: "
                           f"{self.transfer.target._last_message()}")


class Kernel:
    """Prepared calls of one master over its open FMUs; None from `build` when a
    connected or recorded variable is not Real."""

    def __init__(self, fmus, inputs, recorded_by_fmu, order, slopes=None):
        self.fmus, self.order = fmus, order
        self.transfers = {alias: [Transfer(fmus[src], variables, fmus[alias], targets)
                                  for src, variables, targets in inputs[alias]]
                          for alias in order}
        self.slopes = {alias: [self._slope(alias, *pair) for pair in (slopes or {}).get(alias, [])]
                       for alias in order}
        self.steppers = [(alias, _function(fmus[alias], "fmi2DoStep", _DO_STEP),
                          fmus[alias]._fmu.component) for alias in order]
        self.recorders = []
        width = 0
        for alias, variables in recorded_by_fmu.items():
            refs = _refs(fmus[alias], variables)
            if refs is None:
                self.ok = False
                return
            buffer = np.zeros(len(variables))
            self.recorders.append((_function(fmus[alias], "fmi2GetReal", _TRANSFER),
                                   (fmus[alias]._fmu.component, ctypes.addressof(refs),
                                    len(variables), buffer.ctypes.data), refs, buffer,
                                   slice(width, width + len(variables)), alias))
            width += len(variables)
        self.width = width
        self.ok = all(t.ok for ts in self.transfers.values() for t in ts)

    def set_inputs(self, alias: str) -> None:
        for transfer in self.transfers[alias]:
            transfer()

    def _slope(self, alias, source, variables, targets, history, order):
        if history is None:
            return SlopeTransfer(self.fmus[source], variables, self.fmus[alias], targets,
                                 order)
        # The values are those the pair's value Transfer moved just before in the same
        # propagation (a Transfer of the subset when the pair has other variables too).
        for values in self.transfers[alias]:
            if values.source is self.fmus[source] and values.names == (variables, targets):
                return HistorySlope(values, history)
        values = Transfer(self.fmus[source], variables, self.fmus[alias], targets)
        self.transfers[alias].append(values)
        return HistorySlope(values, history)

    def propagate(self, t: float) -> None:
        """Every FMU's inputs from its sources, in order (the sampled coupling), then
        the input slopes."""
        for alias in self.order:
            for transfer in self.transfers[alias]:
                transfer()
        for alias in self.order:
            for transfer in self.slopes[alias]:
                transfer(t)

    def step_all(self, t: float, h: float, propagate: bool, sampled: bool) -> None:
        """One step of every FMU; `propagate`: the sampled propagation first."""
        if propagate:
            self.propagate(t)
        for alias, do_step, component in self.steppers:
            if not sampled:
                for transfer in self.transfers[alias]:
                    transfer()
                for transfer in self.slopes[alias]:
                    transfer(t)
            status = do_step(component, t, h, 1)
            if status > 1:
                fmu = self.fmus[alias]
                if status == _DISCARD:
                    raise StepDiscarded(alias, t, fmu._last_message())
                raise FmuError(f"{alias}: fmi2DoStep at t = {t:.9g} s failed with status "
                               f"{status}: {fmu._last_message()}")

    def record(self, row: np.ndarray) -> None:
        for get, args, _refs_alive, buffer, columns, alias in self.recorders:
            if get(*args) > 1:
                raise FmuError(f"{alias}: fmi2GetReal of the recorded signals failed: "
                               f"{self.fmus[alias]._last_message()}")
            row[columns] = buffer
