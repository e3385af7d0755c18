"""The master's stepping loop: one loop, in native code (crates/tools/cosim-kernel, built by
cargo into target/release/; or shipped inside the package; or the library named by
COSIM_KERNEL_LIBRARY).

`Loop` prepares every call of a step once and hands the kernel a C plan; the kernel
makes whole runs of steps in one call: per step every FMU's step (sampled or
Gauss-Seidel coupling; a discarded step retried in halves from the saved FMU states),
the sampled propagation at the next point (values, then input derivatives) and the
recorded row. Each call of the plan is, per FMU and call:

- an FMI 2.0 FMPy instance (robofmu.fmi2.FmuInstance) on Real variables: the FMU's own
  C function (fmi2GetReal, fmi2SetReal, fmi2DoStep, fmi2GetRealOutputDerivatives,
  fmi2SetRealInputDerivatives, fmi2Get/Set/FreeFMUstate) with its instance handle,
  value references and a buffer prepared here: per connected pair one value-reference
  array per side and one shared buffer (the source's get writes where the target's set
  reads), no Python in between;
- anything else (an FMI 3.0 instance, robofmu.fmi3; Integer or Boolean variables; a
  stand-in of the tests; an FMU without FMU states): a C callback with the same
  signature into the instance's Python methods (get_values, set_values, do_step,
  get_output_derivatives, set_input_derivatives, get/set/free_state). An exception
  there is kept and raised as it is when the kernel stops.
"""

from __future__ import annotations

import ctypes
import os
import platform
import sys
from ctypes import (CFUNCTYPE, POINTER, Structure, c_double, c_int, c_size_t, c_uint,
                    c_uint64, c_void_p)
from functools import lru_cache
from pathlib import Path

import numpy as np

from .errors import CosimError, FmuError, StepDiscarded
from .fmi2 import FmuInstance

ROOT = Path(__file__).resolve().parent.parent
LIBRARY = ("cosim_kernel.dll" if sys.platform == "win32" else
           "libcosim_kernel.dylib" if sys.platform == "darwin" else "libcosim_kernel.so")
KINDS = ("fmi2GetReal", "fmi2SetReal", "fmi2DoStep", "fmi2GetRealOutputDerivatives",
         "fmi2SetRealInputDerivatives", "fmi2GetReal (recorded signals)", "fmi2GetFMUstate",
         "fmi2SetFMUstate")
_GET, _SET, _DO_STEP, _GET_DERIVATIVES, _SET_DERIVATIVES, _RECORD, _GET_STATE, _SET_STATE = \
    range(8)
_OK, _DISCARD, _ERROR = 0, 2, 3

_TRANSFER = CFUNCTYPE(c_int, c_void_p, c_void_p, c_size_t, c_void_p)
_DERIVATIVES = CFUNCTYPE(c_int, c_void_p, c_void_p, c_size_t, c_void_p, c_void_p)
_STEP = CFUNCTYPE(c_int, c_void_p, c_double, c_double, c_int)
_STATE_POINTER = CFUNCTYPE(c_int, c_void_p, c_void_p)
_STATE_VALUE = CFUNCTYPE(c_int, c_void_p, c_void_p)
_DISCARDED = CFUNCTYPE(None, c_void_p, c_size_t, c_double, c_double)


class _Exchange(Structure):
    _fields_ = [("get", c_void_p), ("source", c_void_p), ("source_refs", c_void_p),
                ("set", c_void_p), ("target", c_void_p), ("target_refs", c_void_p),
                ("n", c_size_t), ("buffer", c_void_p)]


class _Slope(Structure):
    _fields_ = [("get", c_void_p), ("source", c_void_p), ("source_refs", c_void_p),
                ("set", c_void_p), ("target", c_void_p), ("target_refs", c_void_p),
                ("n", c_size_t), ("orders", c_void_p), ("slopes", c_void_p),
                ("order", c_size_t), ("values", c_void_p), ("past", c_void_p),
                ("state", c_void_p)]


class _Stepper(Structure):
    _fields_ = [("do_step", c_void_p), ("component", c_void_p), ("get_state", c_void_p),
                ("set_state", c_void_p), ("free_state", c_void_p),
                ("first_exchange", c_size_t), ("n_exchanges", c_size_t),
                ("first_slope", c_size_t), ("n_slopes", c_size_t)]


class _Recorder(Structure):
    _fields_ = [("get", c_void_p), ("component", c_void_p), ("refs", c_void_p),
                ("n", c_size_t), ("column", c_size_t), ("buffer", c_void_p)]


class _Plan(Structure):
    _fields_ = [("exchanges", c_void_p), ("n_exchanges", c_size_t), ("slopes", c_void_p),
                ("n_slopes", c_size_t), ("steppers", c_void_p), ("n_steppers", c_size_t),
                ("recorders", c_void_p), ("n_recorders", c_size_t), ("width", c_size_t),
                ("start", c_double), ("h", c_double), ("gauss_seidel", c_int),
                ("halvings", ctypes.c_uint32), ("discarded", c_void_p), ("context", c_void_p)]


class _Failure(Structure):
    _fields_ = [("kind", c_int), ("index", c_size_t), ("status", c_int), ("time", c_double)]


# The folder of the kernel the wheel bundles for this machine (hatch_build.py's rule).
PLATFORM = f"{sys.platform}-{platform.machine().lower()}"


def library_path() -> Path:
    """The kernel library: the one COSIM_KERNEL_LIBRARY names, else the one the wheel
    ships for this platform (robofmu/_native/<platform>/), else the one cargo builds in
    this checkout."""
    named = os.environ.get("COSIM_KERNEL_LIBRARY")
    if named:
        return Path(named)
    shipped = Path(__file__).resolve().parent / "_native" / PLATFORM / LIBRARY
    return shipped if shipped.is_file() else ROOT / "target" / "release" / LIBRARY


@lru_cache(maxsize=1)
def library():
    """The kernel library; CosimError when it is not built."""
    path = library_path()
    if not path.is_file():
        raise CosimError(f"no stepping loop for {PLATFORM}: {path} is not there; in a "
                         "checkout run scripts/build-fmus.sh (or cargo build --release -p "
                         "robofmu-cosim-kernel), or name the library in COSIM_KERNEL_LIBRARY")
    lib = ctypes.CDLL(str(path))
    lib.cosim_kernel_run.argtypes = [POINTER(_Plan), c_uint64, c_uint64, c_int, c_void_p,
                                     POINTER(_Failure)]
    lib.cosim_kernel_run.restype = c_int
    lib.cosim_kernel_propagate.argtypes = [POINTER(_Plan), c_double, POINTER(_Failure)]
    lib.cosim_kernel_propagate.restype = c_int
    lib.cosim_kernel_inputs.argtypes = [POINTER(_Plan), c_size_t, c_double, POINTER(_Failure)]
    lib.cosim_kernel_inputs.restype = c_int
    lib.cosim_kernel_record.argtypes = [POINTER(_Plan), c_void_p, c_double, POINTER(_Failure)]
    lib.cosim_kernel_record.restype = c_int
    return lib


def _address(x) -> int | None:
    return x if x is None or isinstance(x, int) else ctypes.cast(x, c_void_p).value


def _array(kind, items) -> tuple:
    return (kind * max(len(items), 1))(*items), len(items)


class Loop:
    """The prepared calls of one run over its open instances and the kernel's plan.
    `inputs[alias]`: (source, source variables, inputs) per connected pair; `slopes`:
    robofmu.master's derivative pairs; `recorded_by_fmu`: the recorded variables.
    `columns`: (alias, variable) of each column of a recorded row, in order."""

    def __init__(self, fmus, inputs, recorded_by_fmu, order, slopes, scenario):
        self.fmus, self.order = fmus, order
        self.lib = library()
        self.error: BaseException | None = None  # what a callback raised
        self.discards: list[str] = []
        self._alive: list = []  # buffers, arrays and callbacks the plan points to
        self._states: dict[int, tuple] = {}
        self._next_state = 1
        self.direct = {alias: type(fmu) is FmuInstance for alias, fmu in fmus.items()}
        self.exchanges, exchanges_c, steppers_c = [], [], []
        buffers: list[tuple[str, str, tuple, object]] = []  # (source, target, variables, buffer)
        self.slope_items, slopes_c = [], []
        for alias in order:
            first, first_slope = len(exchanges_c), len(slopes_c)
            moved = {}
            for source, variables, targets in inputs[alias]:
                exchange, buffer = self._exchange(source, variables, alias, targets)
                moved[(source, tuple(variables), tuple(targets))] = buffer
                exchanges_c.append(exchange)
                self.exchanges.append((source, alias))
                buffers.append((source, alias, tuple(variables), buffer))
            for source, variables, targets, history, order_k in slopes.get(alias, []):
                key = (source, tuple(variables), tuple(targets))
                if history is not None and key not in moved:  # a subset of a pair
                    exchange, moved[key] = self._exchange(source, variables, alias, targets)
                    exchanges_c.append(exchange)
                    self.exchanges.append((source, alias))
                    buffers.append((source, alias, tuple(variables), moved[key]))
                slopes_c.append(self._slope(source, variables, alias, targets, history,
                                            order_k, moved.get(key)))
                self.slope_items.append((source, alias))
            steppers_c.append(self._stepper(alias, first, len(exchanges_c) - first,
                                            first_slope, len(slopes_c) - first_slope))
        copied = (self._exchanged(buffers, {target for _, target in self.slope_items})
                  if scenario.coupling == "sampled" else {})
        self.recorders, recorders_c, self.columns = [], [], []
        for alias, variables in recorded_by_fmu.items():
            read = tuple(v for v in variables if (alias, v) not in copied)
            if read:
                recorders_c.append(self._recorder(alias, read, len(self.columns)))
                self.recorders.append(alias)
                self.columns += [(alias, v) for v in read]
        for alias, variables in recorded_by_fmu.items():
            for v in variables:
                if (alias, v) in copied:
                    recorders_c.append(_Recorder(None, None, None, 1, len(self.columns),
                                                 copied[(alias, v)]))
                    self.recorders.append(alias)
                    self.columns.append((alias, v))
        width = self.width = len(self.columns)
        arrays = [_array(_Exchange, exchanges_c), _array(_Slope, slopes_c),
                  _array(_Stepper, steppers_c), _array(_Recorder, recorders_c)]
        self._alive += arrays
        self.on_discard = _DISCARDED(self._discarded)
        pointers = []
        for array, n in arrays:
            pointers += [ctypes.addressof(array), n]
        self.plan = _Plan(*pointers, width, scenario.start_time, scenario.step_size,
                          int(scenario.coupling != "sampled"), scenario.max_step_halvings,
                          _address(self.on_discard), None)
        self.failure = _Failure()

    # -- preparing the calls ------------------------------------------------------------

    def _keep(self, x):
        self._alive.append(x)
        return x

    def _refs(self, alias, names):
        """Value references of Real `names` of a direct instance, else None."""
        if not self.direct[alias]:
            return None
        fmu, refs = self.fmus[alias], []
        for name in names:
            v = fmu.variables.get(name)
            if v is None:
                raise FmuError(f"{alias} has no variable '{name}'")
            if v.type != "Real":
                return None
            refs.append(v.valueReference)
        return self._keep((c_uint * len(refs))(*refs))

    def _function(self, alias, name) -> int | None:
        return ctypes.cast(getattr(self.fmus[alias]._fmu.dll, name), c_void_p).value

    def _handle(self, alias):
        return self.fmus[alias]._fmu.component if self.direct[alias] else None

    def _callback(self, prototype, body, failing=_ERROR) -> int | None:
        """A C callback that runs `body(*args)`; an exception is kept for run() and the
        kernel told `failing`."""
        def call(*args):
            try:
                return body(*args)
            except StepDiscarded as e:
                self.error = e
                return _DISCARD
            except BaseException as e:  # noqa: BLE001 - nothing may cross the C callback
                self.error = e
                return failing
        return _address(self._keep(prototype(call)))

    def _getter(self, alias, names):
        """(function, handle, refs) that read Real values of `names` into a buffer."""
        refs = self._refs(alias, names)
        if refs is not None:
            return (self._function(alias, "fmi2GetReal"), self._handle(alias),
                    ctypes.addressof(refs))
        fmu = self.fmus[alias]

        def get(_c, _refs, n, values):
            (c_double * n).from_address(values)[:] = fmu.get_values(names)
            return _OK
        return self._callback(_TRANSFER, get), None, None

    def _setter(self, alias, names):
        refs = self._refs(alias, names)
        if refs is not None:
            return (self._function(alias, "fmi2SetReal"), self._handle(alias),
                    ctypes.addressof(refs))
        fmu = self.fmus[alias]

        def set_(_c, _refs, n, values):
            fmu.set_values(names, list((c_double * n).from_address(values)))
            return _OK
        return self._callback(_TRANSFER, set_), None, None

    def _exchange(self, source, variables, target, inputs):
        variables, inputs = tuple(variables), tuple(inputs)
        buffer = self._keep((c_double * len(variables))())
        get = self._getter(source, variables)
        set_ = self._setter(target, inputs)
        return (_Exchange(get[0], _address(get[1]), get[2], set_[0], _address(set_[1]),
                          set_[2], len(variables), ctypes.addressof(buffer)), buffer)

    def _slope(self, source, variables, target, inputs, history, order, buffer):
        variables, inputs = tuple(variables), tuple(inputs)
        n = len(variables) * order
        orders = self._keep((c_int * n)(*(k for k in range(1, order + 1)
                                          for _ in variables)))
        refs = self._refs(target, inputs * order)
        if refs is not None:
            set_ = (self._function(target, "fmi2SetRealInputDerivatives"),
                    self._handle(target), ctypes.addressof(refs))
        else:
            fmu = self.fmus[target]

            def set_derivatives(_c, _refs, count, _orders, values):
                fmu.set_input_derivatives(inputs, list((c_double * count).from_address(values)),
                                          order)
                return _OK
            set_ = (self._callback(_DERIVATIVES, set_derivatives), None, None)
        if history is not None:
            values = np.frombuffer(buffer, dtype=np.float64)
            self._keep(values)
            return _Slope(None, None, None, set_[0], _address(set_[1]), set_[2], n,
                          ctypes.addressof(orders), history.out.ctypes.data, history.order,
                          values.ctypes.data, history.past.ctypes.data,
                          history.state.ctypes.data)
        out = self._keep((c_double * n)())
        src_refs = self._refs(source, variables * order)
        if src_refs is not None:
            get = (self._function(source, "fmi2GetRealOutputDerivatives"),
                   self._handle(source), ctypes.addressof(src_refs))
        else:
            fmu = self.fmus[source]

            def get_derivatives(_c, _refs, count, _orders, values):
                (c_double * count).from_address(values)[:] = \
                    fmu.get_output_derivatives(variables, order)
                return _OK
            get = (self._callback(_DERIVATIVES, get_derivatives), None, None)
        return _Slope(get[0], _address(get[1]), get[2], set_[0], _address(set_[1]), set_[2],
                      n, ctypes.addressof(orders), ctypes.addressof(out), 0, None, None, None)

    def _stepper(self, alias, first, count, first_slope, n_slopes) -> _Stepper:
        fmu = self.fmus[alias]
        if self.direct[alias]:
            do_step = self._function(alias, "fmi2DoStep")
        else:
            def step(_c, t, h, _no_set_prior):
                fmu.do_step(t, h)
                return _OK
            do_step = self._callback(_STEP, step)
        if self.direct[alias] and fmu.can_get_state:
            states = [self._function(alias, f"fmi2{verb}FMUstate")
                      for verb in ("Get", "Set", "Free")]
        else:
            states = self._bridged_states(fmu)
        return _Stepper(do_step, _address(self._handle(alias)), *states, first, count,
                        first_slope, n_slopes)

    def _bridged_states(self, fmu) -> list[int | None]:
        """get/set/free_state of a Python adapter as FMI 2.0's state calls: the state
        crosses the kernel as a key of self._states."""
        def get(_c, pointer):
            key, self._next_state = self._next_state, self._next_state + 1
            self._states[key] = fmu.get_state()
            c_void_p.from_address(pointer).value = key
            return _OK

        def set_(_c, key):
            fmu.set_state(self._states[key])
            return _OK

        def free(_c, pointer):
            fmu.free_state(self._states.pop(c_void_p.from_address(pointer).value))
            return _OK
        return [self._callback(_STATE_POINTER, get), self._callback(_STATE_VALUE, set_),
                self._callback(_STATE_POINTER, free)]

    def _recorder(self, alias, variables, column) -> _Recorder:
        get, handle, refs = self._getter(alias, tuple(variables))
        return _Recorder(get, _address(handle), refs, len(variables), column, None)

    @staticmethod
    def _exchanged(buffers, slope_targets) -> dict[tuple[str, str], int]:
        """(alias, variable) -> address of the value in an exchange buffer, for the
        outputs that a sampled propagation reads when nothing will change them before
        the row is recorded: the exchange reading them comes after every value exchange
        into their FMU and no input derivatives are passed to it. The row then copies
        what an fmi2GetReal at recording would return, without the call."""
        last_into: dict[str, int] = {}
        for i, (_, target, _, _) in enumerate(buffers):
            last_into[target] = i
        copied: dict[tuple[str, str], int] = {}
        for i, (source, _, variables, buffer) in enumerate(buffers):
            if last_into.get(source, -1) > i or source in slope_targets:
                continue
            base = ctypes.addressof(buffer)
            for k, v in enumerate(variables):
                copied.setdefault((source, v), base + k * ctypes.sizeof(c_double))
        return copied

    def renew(self) -> None:
        """Ready for another run over the same instances (the plan unchanged; every
        buffer is written by the run's propagation before it is read)."""
        self.error = None
        self.discards = []
        self._states.clear()
        self._next_state = 1

    # -- running --------------------------------------------------------------------------

    def _discarded(self, _context, index, t, h) -> None:
        """A discarded step about to be retried: its message kept (robofmu.master)."""
        alias = self.order[index]
        d = self.error if isinstance(self.error, StepDiscarded) else \
            StepDiscarded(alias, t, self.fmus[alias]._last_message())
        self.error = None
        self.discards.append(f"{d}; retrying with h = {h / 2:.9g} s")

    def _check(self, status: int) -> None:
        if status:
            self._raise()
        self.error = None

    def set_inputs(self, index: int, t: float) -> None:
        """Input values of the index-th FMU from its sources (initialization)."""
        self._check(self.lib.cosim_kernel_inputs(ctypes.byref(self.plan), index, t,
                                                 ctypes.byref(self.failure)))

    def propagate(self, t: float) -> None:
        """The sampled propagation at t (values, then input derivatives)."""
        self._check(self.lib.cosim_kernel_propagate(ctypes.byref(self.plan), t,
                                                    ctypes.byref(self.failure)))

    def record(self, row: np.ndarray, t: float) -> None:
        """The recorded signals now into `row`."""
        self._check(self.lib.cosim_kernel_record(ctypes.byref(self.plan), row.ctypes.data, t,
                                                 ctypes.byref(self.failure)))

    def run_steps(self, start: int, stop: int, rows: np.ndarray, propagate_first: bool) -> None:
        """Steps start..stop; row k + 1 of `rows` after step k."""
        self._check(self.lib.cosim_kernel_run(ctypes.byref(self.plan), start, stop,
                                              int(propagate_first), rows.ctypes.data,
                                              ctypes.byref(self.failure)))

    def _raise(self) -> None:
        f, error = self.failure, self.error
        self.error = None
        if f.kind == _DO_STEP and f.status == _DISCARD:
            alias = self.order[f.index]
            d = error if isinstance(error, StepDiscarded) else \
                StepDiscarded(alias, f.time, self.fmus[alias]._last_message())
            raise CosimError(f"{d} (no step halvings left; raise max_step_halvings to "
                             "retry with smaller steps)")
        if error is not None:
            raise error
        if f.kind == _DO_STEP:
            alias = self.order[f.index]
            raise FmuError(f"{alias}: fmi2DoStep at t = {f.time:.9g} s failed with status "
                           f"{f.status}: {self.fmus[alias]._last_message()}")
        if f.kind in (_GET, _SET):
            alias = self.exchanges[f.index][f.kind]
        elif f.kind in (_GET_DERIVATIVES, _SET_DERIVATIVES):
            alias = self.slope_items[f.index][f.kind - _GET_DERIVATIVES]
        elif f.kind == _RECORD:
            alias = self.recorders[f.index]
        else:
            alias = self.order[f.index]
        raise FmuError(f"{alias}: {KINDS[f.kind]} failed at t = {f.time:.9g} s: "
                       f"{self.fmus[alias]._last_message()}")
