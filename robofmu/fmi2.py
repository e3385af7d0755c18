"""One co-simulation FMU instance behind FMPy's low-level API, with errors that name the
FMU and the FMI call, and the FMU's log messages kept for error reports."""

from __future__ import annotations

import shutil
from ctypes import c_double, c_int, c_uint
from functools import partial
from pathlib import Path
from typing import Any

import fmpy
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE, fmi2Discard,
                       fmi2Warning)
from fmpy import calloc, free

from .errors import FmuError, StepDiscarded

# The log categories of the standard for non-OK statuses. An FMU may log a Discard or a
# Warning only when its category is switched on (the plant does): without them, the
# reason of a refused call is lost ("the FMU logged no reason").
STATUS_CATEGORIES = ("logStatusWarning", "logStatusDiscard", "logStatusError",
                     "logStatusFatal", "logStatusPending")


def status_categories(md) -> list[str]:
    """The standard's status log categories that the FMU declares."""
    declared = {getattr(c, "name", c) for c in getattr(md, "logCategories", None) or []}
    return [c for c in STATUS_CATEGORIES if c in declared]


# What an instance on this machine reads of an FMU: its binaries for this platform (FMI
# 2.0's and FMI 3.0's folder names), not those of the other platforms nor extra/ (the
# tools' files, e.g. the LS-REF experiments): a bundled FMU is 7.8 MB, of which it reads
# about 1 MB.
_THIS_PLATFORM = (f"binaries/{fmpy.platform}/", f"binaries/{fmpy.platform_tuple}/")


def _read_here(name: str) -> bool:
    if name.startswith("binaries/"):
        return name.startswith(_THIS_PLATFORM)
    return not name.startswith("extra/")


def unpack(path) -> str:
    """fmpy.extract of the files an instance of the FMU at `path` reads on this machine,
    into a new temporary folder."""
    return str(extract(str(path), include=_read_here))


def remove_extracted(folder) -> None:
    """Removes a folder that fmpy.extract made (None: nothing to do)."""
    if folder:
        shutil.rmtree(folder, ignore_errors=True)


def release(fmu, initialized: bool, unzip) -> None:
    """Terminates `fmu` (an FMPy instance or None) when initialised, frees it and removes
    its extracted folder `unzip`; never raises: a failure while cleaning up must not mask
    the error that led here."""
    if fmu is not None:
        if initialized:
            try:
                fmu.terminate()
            except Exception:  # noqa: BLE001 - cleanup after an earlier failure
                pass
        try:
            if getattr(fmu, "component", None) is not None:
                fmu.freeInstance()
            else:
                fmu.freeLibrary()
        except Exception:  # noqa: BLE001
            pass
    remove_extracted(unzip)


_GETTERS = {"Real": "getReal", "Integer": "getInteger", "Boolean": "getBoolean"}
_SETTERS = {"Real": "setReal", "Integer": "setInteger", "Boolean": "setBoolean"}
_CONVERT = {"Real": float, "Integer": int, "Boolean": bool}
_C_TYPES: dict[str, Any] = {"Real": c_double, "Integer": c_int, "Boolean": c_int}  # fmi2Real, ..


class LoggedCalls:
    """What both FMU adapters (FMI 2.0 here, FMI 3.0 in robofmu.fmi3) share: the last log
    lines of the instance and FMPy calls turned into FmuError with the FMU's reason.
    Subclasses set `alias`, `messages`, `can_get_state` and `_fmu` (an FMPy slave), and
    define `get_values`/`set_values` and the standard's spelling below."""

    alias: str
    messages: list[str]
    can_get_state: bool
    _fmu: Any  # the FMPy slave of the standard; None before it is made and once closed
    _initialized: bool
    _unzip: str | None  # the folder unpack() made; None before and once removed
    #: Prefix of the C function names, status code of Discard, and the standard's
    #: spelling of "FMU state" in function names.
    _PREFIX = "fmi2"
    _DISCARD = fmi2Discard
    _FMU_STATE = "FMUstate"

    def _remember(self, category, message) -> None:
        text = message.decode("utf-8", "replace") if message else ""
        self.messages.append(f"[{(category or b'').decode('utf-8', 'replace')}] {text}")
        del self.messages[:-20]

    def _last_message(self) -> str:
        return self.messages[-1] if self.messages else "(the FMU logged no reason)"

    def _call(self, name: str, fn):
        try:
            return fn()
        except FMICallException as e:
            raise FmuError(f"{self.alias}: {name} failed with status {e.status}: "
                           f"{self._last_message()}") from e
        except Exception as e:  # instantiate raises a plain Exception on NULL
            raise FmuError(f"{self.alias}: {name} failed: {e}; {self._last_message()}") from e

    def get_values(self, names) -> list:
        """The values of the variables `names`, in order (each standard's adapter)."""
        raise NotImplementedError

    def set_values(self, names, values) -> None:
        """Sets the variables `names` to `values` (each standard's adapter)."""
        raise NotImplementedError

    def get_value(self, name: str) -> float:
        return self.get_values((name,))[0]

    def set_value(self, name: str, value) -> None:
        self.set_values((name,), [value])

    def exit_initialization(self) -> None:
        self._call(f"{self._PREFIX}ExitInitializationMode", self._fmu.exitInitializationMode)
        self._initialized = True

    def do_step(self, time: float, step: float) -> None:
        try:
            self._fmu.doStep(currentCommunicationPoint=time, communicationStepSize=step)
        except FMICallException as e:
            if e.status == self._DISCARD:
                raise StepDiscarded(self.alias, time, self._last_message()) from None
            raise FmuError(f"{self.alias}: {self._PREFIX}DoStep at t = {time:.9g} s failed "
                           f"with status {e.status}: {self._last_message()}") from e

    def get_state(self):
        if not self.can_get_state:
            raise FmuError(f"{self.alias} cannot get and set its FMU state (no rollback)")
        return self._state_call("get")()

    def set_state(self, state) -> None:
        self._state_call("set")(state)

    def free_state(self, state) -> None:
        self._state_call("free")(state)

    def _state_call(self, verb: str):
        """FMPy's get/set/free of FMU states, spelt as the standard spells them
        (getFMUstate in FMI 2.0, getFMUState in FMI 3.0), logged as the C function."""
        method = getattr(self._fmu, f"{verb}{self._FMU_STATE}")
        name = f"{self._PREFIX}{verb.capitalize()}{self._FMU_STATE}"
        return lambda *args: self._call(name, lambda: method(*args))

    def close(self) -> None:
        """Terminates (when initialised) and frees the instance and removes its extracted
        folder; safe to call after any failure and more than once, and never raises."""
        fmu, self._fmu = getattr(self, "_fmu", None), None
        release(fmu, getattr(self, "_initialized", False), getattr(self, "_unzip", None))
        self._unzip = None


class FmuInstance(LoggedCalls):
    """A co-simulation instance of an FMI 2.0 FMU, addressed by variable names."""

    #: (file, modification time) where robofmu.instances shares it; None: not shared.
    pool_key: tuple[str, int] | None = None

    def __init__(self, alias: str, path: Path, start_time: float, stop_time: float):
        self.alias = alias
        self.messages: list[str] = []
        self._fmu, self._unzip, self._initialized = None, None, False
        md = read_model_description(str(path))
        if md.coSimulation is None:
            raise FmuError(f"{alias} ({path}) does not support co-simulation")
        self.variables = {v.name: v for v in md.modelVariables}
        self._group_cache: dict = {}
        self._each: dict[str, tuple] = {}  # set_each's prepared call per name
        self.can_get_state = bool(md.coSimulation.canGetAndSetFMUstate)
        self.can_interpolate_inputs = bool(md.coSimulation.canInterpolateInputs)
        self.max_output_derivative_order = int(md.coSimulation.maxOutputDerivativeOrder or 0)
        self._unzip = unpack(path)
        try:
            self._open(md, start_time, stop_time)
        except BaseException:
            self.close()
            raise

    def _open(self, md, start_time: float, stop_time: float) -> None:
        alias = self.alias
        self._fmu = FMU2Slave(guid=md.guid, unzipDirectory=self._unzip,
                              modelIdentifier=md.coSimulation.modelIdentifier, instanceName=alias)
        # Keep the ctypes callbacks alive as long as the instance.
        self._callbacks = fmi2CallbackFunctions()
        self._callbacks.logger = fmi2CallbackLoggerTYPE(self._log)
        self._callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        self._callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        self._call("fmi2Instantiate", lambda: self._fmu.instantiate(callbacks=self._callbacks))
        categories = status_categories(md)
        if categories:
            self._call("fmi2SetDebugLogging",
                       lambda: self._fmu.setDebugLogging(True, categories))
        self._call("fmi2SetupExperiment",
                   lambda: self._fmu.setupExperiment(startTime=start_time, stopTime=stop_time))

    def _log(self, _env, _name, status, category, message):
        self._remember(category, message)

    def _groups(self, names: tuple[str, ...]) -> list[tuple[str, list[int], list[int]]]:
        """(type, positions in `names`, value references) per variable type, cached."""
        groups = self._group_cache.get(names)
        if groups is None:
            by_type: dict[str, tuple[list[int], list[int]]] = {}
            for k, name in enumerate(names):
                v = self.variables.get(name)
                if v is None:
                    raise FmuError(f"{self.alias} has no variable '{name}'")
                kind = "Integer" if v.type == "Enumeration" else v.type
                if kind not in _GETTERS:
                    raise FmuError(f"{self.alias}.{name}: variables of type {v.type} are "
                                   "not supported")
                positions, refs = by_type.setdefault(kind, ([], []))
                positions.append(k)
                refs.append(v.valueReference)
            groups = [(kind, positions, refs) for kind, (positions, refs) in by_type.items()]
            self._group_cache[names] = groups
        return groups

    def get_values(self, names: tuple[str, ...]) -> list[float]:
        """Values of `names` (Integer and Boolean as float), one FMI call per type."""
        out = [0.0] * len(names)
        for kind, positions, refs in self._groups(names):
            getter = getattr(self._fmu, _GETTERS[kind])
            values = self._call(f"fmi2Get{kind}({', '.join(names[k] for k in positions)})",
                                partial(getter, refs))
            for k, value in zip(positions, values):
                out[k] = float(value)
        return out

    def set_values(self, names: tuple[str, ...], values) -> None:
        """Sets `names` to `values`, one FMI call per type."""
        for kind, positions, refs in self._groups(names):
            setter = getattr(self._fmu, _SETTERS[kind])
            convert = _CONVERT[kind]
            typed = [convert(values[k]) for k in positions]
            self._call(f"fmi2Set{kind}({', '.join(names[k] for k in positions)})",
                       partial(setter, refs, typed))

    def set_each(self, names, values) -> None:
        """Sets each of `names` to its value in an FMI call of its own, in order: what
        set_value does name by name (the same calls, statuses and messages), through
        the FMU's C functions without FMPy's wrappers (a sweep run sets every parameter)."""
        for name, value in zip(names, values):
            prepared = self._each.get(name)
            if prepared is None:
                kind = self._groups((name,))[0][0]
                prepared = self._each[name] = (
                    kind, getattr(self._fmu.dll, f"fmi2Set{kind}"), _CONVERT[kind],
                    (c_uint * 1)(self.variables[name].valueReference), (_C_TYPES[kind] * 1)())
            kind, function, convert, ref, typed = prepared
            typed[0] = convert(value)
            status = function(self._fmu.component, ref, 1, typed)
            if status > fmi2Warning:
                raise FmuError(f"{self.alias}: fmi2Set{kind}({name}) failed with status "
                               f"{status}: {self._last_message()}")

    def enter_initialization(self) -> None:
        self._call("fmi2EnterInitializationMode", self._fmu.enterInitializationMode)

    def is_real(self, name: str) -> bool:
        return self.variables[name].type == "Real"

    def get_output_derivatives(self, names: tuple[str, ...], order: int) -> list[float]:
        """Time derivatives of orders 1..order of Real outputs in one
        fmi2GetRealOutputDerivatives call: all of order 1 (in the order of `names`),
        then all of order 2, ..."""
        refs = [self.variables[n].valueReference for n in names]
        orders = [k for k in range(1, order + 1) for _ in refs]
        return self._call(f"fmi2GetRealOutputDerivatives({', '.join(names)}, orders 1..{order})",
                          lambda: self._fmu.getRealOutputDerivatives(refs * order, orders))

    def set_input_derivatives(self, names: tuple[str, ...], values, order: int) -> None:
        """Time derivatives of orders 1..order of Real inputs over the next step
        (fmi2SetRealInputDerivatives), laid out as get_output_derivatives returns them."""
        refs = [self.variables[n].valueReference for n in names]
        orders = [k for k in range(1, order + 1) for _ in refs]
        self._call(f"fmi2SetRealInputDerivatives({', '.join(names)}, orders 1..{order})",
                   lambda: self._fmu.setRealInputDerivatives(refs * order, orders,
                                                             list(values)))

    def reset(self, start_time: float, stop_time: float) -> None:
        """fmi2Reset: back to the state after instantiation (start values of every
        parameter), then the experiment set up again; the instance is reused."""
        self._call("fmi2Reset", self._fmu.reset)
        self._initialized = False
        self.messages.clear()
        self._call("fmi2SetupExperiment",
                   lambda: self._fmu.setupExperiment(startTime=start_time, stopTime=stop_time))
