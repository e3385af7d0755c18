"""The master's stepping loop in native code (crates/cosim-kernel, built by cargo into
target/release/libcosim_kernel.so and bundled in the wheel for the platform it was built
on, or the library named by COSIM_KERNEL_LIBRARY).

NativeKernel takes the calls cosim.fastpath prepared (function pointers, instance
handles, value references, buffers) into a C plan, and makes whole runs of steps in one
call: per step every FMU's fmi2DoStep, the sampled propagation at the next point
(values, then slopes) and the recorded row, in the order of the Python kernel, so the
results are the same bit for bit. Without the library the master uses cosim.fastpath.
"""

from __future__ import annotations

import ctypes
import os
import platform
import sys
from ctypes import POINTER, Structure, c_double, c_int, c_size_t, c_uint64, c_void_p
from functools import lru_cache
from pathlib import Path

import numpy as np

from .errors import CosimError, FmuError, StepDiscarded
from .fastpath import HistorySlope, Kernel, SlopeTransfer

ROOT = Path(__file__).resolve().parent.parent
KINDS = ("fmi2GetReal", "fmi2SetReal", "fmi2DoStep", "fmi2GetRealOutputDerivatives",
         "fmi2SetRealInputDerivatives", "fmi2GetReal (recorded signals)")


class _Exchange(Structure):
    _fields_ = [("get", c_void_p), ("source", c_void_p), ("source_refs", c_void_p),
                ("set", c_void_p), ("target", c_void_p), ("target_refs", c_void_p),
                ("n", c_size_t), ("buffer", c_void_p)]


class _Slope(Structure):
    _fields_ = [("get", c_void_p), ("source", c_void_p), ("source_refs", c_void_p),
                ("set", c_void_p), ("target", c_void_p), ("target_refs", c_void_p),
                ("n", c_size_t), ("orders", c_void_p), ("slopes", c_void_p),
                ("values", c_void_p), ("previous", c_void_p), ("state", c_void_p)]


class _Stepper(Structure):
    _fields_ = [("do_step", c_void_p), ("component", c_void_p)]


class _Recorder(Structure):
    _fields_ = [("get", c_void_p), ("component", c_void_p), ("refs", c_void_p),
                ("n", c_size_t), ("column", c_size_t)]


class _Plan(Structure):
    _fields_ = [("exchanges", c_void_p), ("n_exchanges", c_size_t), ("slopes", c_void_p),
                ("n_slopes", c_size_t), ("steppers", c_void_p), ("n_steppers", c_size_t),
                ("recorders", c_void_p), ("n_recorders", c_size_t), ("width", c_size_t),
                ("start", c_double), ("h", c_double)]


class _Failure(Structure):
    _fields_ = [("kind", c_int), ("index", c_size_t), ("status", c_int), ("step", c_uint64)]


# The kernel bundled in the wheel for this machine (hatch_build.py: kernel_platform, KERNEL).
PLATFORM = f"{sys.platform}-{platform.machine().lower()}"
LIBRARY_NAME = {"linux": "libcosim_kernel.so", "darwin": "libcosim_kernel.dylib",
                "win32": "cosim_kernel.dll"}.get(sys.platform, "libcosim_kernel.so")


def library_path() -> Path:
    """COSIM_KERNEL_LIBRARY, else the wheel's kernel for this platform, else the
    checkout's build (target/release/)."""
    if "COSIM_KERNEL_LIBRARY" in os.environ:
        return Path(os.environ["COSIM_KERNEL_LIBRARY"])
    bundled = Path(__file__).resolve().parent / "_native" / PLATFORM / LIBRARY_NAME
    return bundled if bundled.is_file() else ROOT / "target" / "release" / LIBRARY_NAME


@lru_cache(maxsize=1)
def library():
    """The kernel library, or None when it is not there (said once, on stderr: the
    Python loop then runs, with the same results)."""
    path = library_path()
    if not path.is_file():
        print(f"cosim: no native stepping loop for {PLATFORM} ({path.name} not built); "
              "using the Python loop (same results, slower)", file=sys.stderr)
        return None
    lib = ctypes.CDLL(str(path))
    lib.cosim_kernel_run.argtypes = [POINTER(_Plan), c_uint64, c_uint64, c_int, c_void_p,
                                     POINTER(_Failure)]
    lib.cosim_kernel_run.restype = c_int
    lib.cosim_kernel_propagate.argtypes = [POINTER(_Plan), c_double, POINTER(_Failure)]
    lib.cosim_kernel_propagate.restype = c_int
    return lib


def _address(x) -> int:
    return x if isinstance(x, int) else ctypes.cast(x, c_void_p).value or 0  # NULL: 0


def _array(kind, items) -> tuple:
    array = (kind * max(len(items), 1))(*items)
    return array, len(items)


class NativeKernel(Kernel):
    """cosim.fastpath.Kernel whose propagation and runs of steps are native calls."""

    def __init__(self, fmus, inputs, recorded_by_fmu, order, slopes, start, h):
        super().__init__(fmus, inputs, recorded_by_fmu, order, slopes)
        if not self.ok:
            return
        self.lib = library()
        self.exchanges = [t for alias in order for t in self.transfers[alias]]
        self.slope_calls = [x for alias in order for x in self.slopes[alias]]
        self.history = [(np.zeros(len(x.values)), np.zeros(2)) if isinstance(x, HistorySlope)
                        else None for x in self.slope_calls]
        self.steppers_c = _array(_Stepper, [_Stepper(_address(f), _address(c))
                                            for _, f, c in self.steppers])
        self.exchanges_c = _array(_Exchange, [self._exchange(t) for t in self.exchanges])
        self.slopes_c = _array(_Slope, [self._slope_c(x, h) for x, h in
                                        zip(self.slope_calls, self.history)])
        self.recorders_c = _array(_Recorder, [
            _Recorder(_address(get), _address(args[0]), args[1], args[2], columns.start)
            for get, args, _refs, _buffer, columns, _alias in self.recorders])
        self.plan = _Plan(ctypes.addressof(self.exchanges_c[0]), self.exchanges_c[1],
                          ctypes.addressof(self.slopes_c[0]), self.slopes_c[1],
                          ctypes.addressof(self.steppers_c[0]), self.steppers_c[1],
                          ctypes.addressof(self.recorders_c[0]), self.recorders_c[1],
                          self.width, start, h)
        self.failure = _Failure()

    @staticmethod
    def _exchange(t) -> _Exchange:
        return _Exchange(_address(t.get), _address(t.args_get[0]), t.args_get[1],
                         _address(t.set), _address(t.args_set[0]), t.args_set[1],
                         t.args_get[2], t.args_get[3])

    @staticmethod
    def _slope_c(x, history) -> _Slope:
        if isinstance(x, SlopeTransfer):
            component, refs, n, orders, buffer = x.args_get
            target, target_refs = x.args_set[0], x.args_set[1]
            return _Slope(_address(x.get), _address(component), refs, _address(x.set),
                          _address(target), target_refs, n, orders, buffer, None, None, None)
        target, target_refs, n, orders, slopes = x.args
        previous, state = history
        return _Slope(None, None, None, _address(x.set), _address(target), target_refs, n,
                      orders, slopes, x.values.ctypes.data, previous.ctypes.data,
                      state.ctypes.data)

    def propagate(self, t: float) -> None:
        if self.lib.cosim_kernel_propagate(ctypes.byref(self.plan), t,
                                           ctypes.byref(self.failure)):
            self._raise()

    def run_steps(self, start: int, stop: int, rows: np.ndarray, propagate_first: bool) -> None:
        """Steps start..stop; row k + 1 of `rows` after step k."""
        if self.lib.cosim_kernel_run(ctypes.byref(self.plan), start, stop,
                                     int(propagate_first), rows.ctypes.data,
                                     ctypes.byref(self.failure)):
            self._raise()

    def _raise(self) -> None:
        f = self.failure
        t = self.plan.start + f.step * self.plan.h
        if f.kind == 2:
            alias = self.steppers[f.index][0]
            message = self.fmus[alias]._last_message()
            if f.status == 2:
                d = StepDiscarded(alias, t, message)
                raise CosimError(f"{d} (no step halvings left; raise max_step_halvings to "
                                 "retry with smaller steps)")
            raise FmuError(f"{alias}: fmi2DoStep at t = {t:.9g} s failed with status "
                           f"{f.status}: {message}")
        call = {0: self.exchanges, 1: self.exchanges, 3: self.slope_calls,
                4: self.slope_calls}.get(f.kind)
        if call is None:  # a recorder
            alias = self.recorders[f.index][5]
        else:
            item = call[f.index]
            item = getattr(item, "transfer", item)
            alias = (item.source if f.kind in (0, 3) else item.target).alias
        raise FmuError(f"{alias}: {KINDS[f.kind]} failed at t = {t:.9g} s: "
                       f"{self.fmus[alias]._last_message()}")
