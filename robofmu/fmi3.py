"""The FMI 3.0 build of a scenario's FMUs behind the interface the master uses
(`FmuInstance` in fmi2.py): the same scalar names (`theta[1]`) on the FMI 3.0 arrays
(`theta`, element 1). Choose it with ``cosim run SCENARIO --fmi3`` or
``Master(scenario, open_fmu=open_fmi3)``; a scenario's ``dist/<Model>.fmu`` is then
read as ``dist/fmi3/<Model>.fmu``.

FMI 3.0 writes whole arrays, and reading is illegal before initialization, so the
instance keeps the values it last wrote (start values first) and completes a partial
write of an array from them."""

from __future__ import annotations

import re
import zipfile
from ctypes import c_double, c_int, c_uint64
from functools import partial
from pathlib import Path
from typing import Any

from fmpy import read_model_description
from fmpy.fmi3 import FMU3Model, FMU3Slave, fmi3ValueReference

from .errors import FmuError
from .fmi2 import LoggedCalls, status_categories, unpack
from .intermediate import IntermediateInputs, flagged_inputs

_FMI3_DISCARD = 2
_CONVERT = {"Float64": float, "Int32": int, "Boolean": bool}


def fmi3_path(path: Path) -> Path:
    """dist/<Model>.fmu -> dist/fmi3/<Model>.fmu (the FMI 3.0 build beside it)."""
    return path.parent / "fmi3" / path.name


def scalar_names(variables) -> dict:
    """FMI 2.0 scalar name -> (FMI 3.0 variable, element index or None), from each
    variable's <Dimension>: an array `x` of n elements holds `x[1]`..`x[n]`, the
    derivative of an array state `x` holds `der(x[1])`..; a scalar keeps its name."""
    names: dict[str, tuple[Any, int | None]] = {}
    for v in variables:
        if not v.shape:
            names[v.name] = (v, None)
            continue
        state = v.derivative.name if v.derivative is not None else None
        for k in range(int(v.shape[0])):  # one dimension: the layer declares no other
            element = f"{state or v.name}[{k + 1}]"
            names[f"der({element})" if state else element] = (v, k)
    return names


def _start(variable) -> list:
    words = str(variable.start).split()
    if variable.type == "Boolean":
        return [w.lower() in ("true", "1") for w in words]
    return [_CONVERT[variable.type](w) for w in words]


class Fmu3Instance(LoggedCalls):
    """A co-simulation instance of an FMI 3.0 FMU, addressed by FMI 2.0 scalar names;
    `clocked`: with Event Mode and early return (the master ticks its input clock,
    robofmu.clocked)."""

    _PREFIX = "fmi3"
    _DISCARD = _FMI3_DISCARD
    _FMU_STATE = "FMUState"

    def __init__(self, alias: str, path: Path, start_time: float, stop_time: float,
                 extrapolate: bool = False, clocked: bool = False,
                 model_exchange: bool = False):
        self.alias = alias
        self.messages: list[str] = []
        self._fmu, self._unzip, self._initialized = None, None, False
        md = read_model_description(str(path))
        interface = md.modelExchange if model_exchange else md.coSimulation
        if interface is None:
            raise FmuError(f"{alias} ({path}) does not support "
                           + ("model exchange" if model_exchange else "co-simulation"))
        self.variables = {v.name: v for v in md.modelVariables}
        self._scalars = scalar_names(md.modelVariables)
        self.can_get_state = bool(interface.canGetAndSetFMUstate)
        # What each array holds now (a write of one element sends the whole array):
        # the start values, again after fmi3Reset.
        self._starts = {v.name: _start(v) for v in md.modelVariables
                        if v.type in _CONVERT and v.start is not None}
        self._written = dict(self._starts)
        self._start_time, self._stop_time = start_time, stop_time
        self._unzip = unpack(path)
        self._path = path
        # Input extrapolation through the intermediate update (robofmu.intermediate).
        self.intermediate = (IntermediateInputs(self, flagged_inputs(path))
                             if extrapolate and not model_exchange
                             and md.coSimulation.providesIntermediateUpdate else None)
        self.can_interpolate_inputs = self.intermediate is not None
        update = self.intermediate.callback if self.intermediate is not None else None
        try:
            if model_exchange:  # robofmu.integrated steps it
                self._fmu = FMU3Model(guid=md.guid, unzipDirectory=self._unzip,
                                      modelIdentifier=interface.modelIdentifier,
                                      instanceName=alias)
                self._call("fmi3InstantiateModelExchange",
                           lambda: self._fmu.instantiate(logMessage=self._log))
            else:
                self._fmu = FMU3Slave(guid=md.guid, unzipDirectory=self._unzip,
                                      modelIdentifier=interface.modelIdentifier,
                                      instanceName=alias)
                self._call("fmi3InstantiateCoSimulation",
                           lambda: self._fmu.instantiate(logMessage=self._log,
                                                         intermediateUpdate=update,
                                                         eventModeUsed=clocked,
                                                         earlyReturnAllowed=clocked))
            categories = status_categories(md)
            if categories:
                self._call("fmi3SetDebugLogging",
                           lambda: self._fmu.setDebugLogging(True, categories))
        except BaseException:
            self.close()
            raise

    def _log(self, _env, status, category, message):
        self._remember(category, message)

    def _locate(self, name: str):
        """(FMI 3.0 variable, element index or None) of an FMI 2.0 scalar name."""
        variable, index = self._scalars.get(name, (None, None))
        if variable is not None and variable.type == "Clock":
            raise FmuError(f"{self.alias}.{name} is an input clock, which the master ticks "
                           f"itself (field 'sample_period.{self.alias}'); connect and record "
                           "the variables it clocks")
        if variable is None or variable.type not in _CONVERT:
            raise FmuError(f"{self.alias} has no variable '{name}' of a supported type")
        return variable, index

    def variable_of(self, name: str) -> str:
        """The name of the FMI 3.0 variable that holds the FMI 2.0 scalar `name`."""
        return self._locate(name)[0].name

    def get_values(self, names: tuple[str, ...]) -> list[float]:
        """Values of `names` (Int32 and Boolean as float), one FMI call per variable."""
        located = [self._locate(name) for name in names]
        arrays = {}
        for variable, _ in located:
            if variable.name not in arrays:
                size = int(variable.shape[0]) if variable.shape else 1
                getter = getattr(self._fmu, "get" + variable.type)
                arrays[variable.name] = self._call(
                    f"fmi3Get{variable.type}({variable.name})",
                    partial(getter, [variable.valueReference], size))
        return [float(arrays[v.name][0 if i is None else i]) for v, i in located]

    def is_real(self, name: str) -> bool:
        return self._locate(name)[0].type == "Float64"

    def get_written(self, names: tuple[str, ...]) -> list[float]:
        """The values last written to the inputs `names`."""
        located = [self._locate(name) for name in names]
        return [float(self._written[v.name][0 if i is None else i]) for v, i in located]

    #: The intermediate update applies derivatives up to the second (robofmu.intermediate).
    max_input_derivative_order = 2

    def set_input_derivatives(self, names: tuple[str, ...], values, order: int) -> None:
        if self.intermediate is None:  # the master asks only where can_interpolate_inputs
            raise FmuError(f"{self.alias}: input derivatives need the intermediate update, "
                           "which this instance does not use")
        self.intermediate.set_derivatives(names, values, order)

    def do_step(self, time: float, step: float) -> None:
        if self.intermediate is None:
            super().do_step(time, step)
            return
        self.intermediate.begin(time)
        super().do_step(time, step)
        if self.intermediate.failure is not None:
            raise FmuError(f"{self.alias}: setting inputs at an intermediate point of the "
                           f"step from t = {time:.9g} s failed: {self.intermediate.failure}")

    def set_values(self, names: tuple[str, ...], values) -> None:
        """Sets `names` to `values`: whole arrays, completed from the last written."""
        changed: dict[str, list] = {}
        for name, value in zip(names, values):
            variable, index = self._locate(name)
            array = changed.setdefault(variable.name, list(self._written[variable.name]))
            array[0 if index is None else index] = _CONVERT[variable.type](value)
        for base, array in changed.items():
            variable = self.variables[base]
            setter = getattr(self._fmu, "set" + variable.type)
            self._call(f"fmi3Set{variable.type}({base})",
                       partial(setter, [variable.valueReference], array))
            self._written[base] = array

    # -- the clocked partition (robofmu.clocked) ---------------------------------------

    def interval(self, clock: str) -> tuple[int, int] | float:
        """The interval of the periodic input clock `clock` (Initialization Mode):
        (counter, resolution) where the clock supports fractions, else seconds."""
        vr = (fmi3ValueReference * 1)(self.variables[clock].valueReference)
        qualifier = (c_int * 1)()
        if self._supports_fraction(clock):
            counter, resolution = (c_uint64 * 1)(), (c_uint64 * 1)()
            self._call(f"fmi3GetIntervalFraction({clock})", lambda: self._fmu.getIntervalFraction(
                vr, counter, resolution, qualifier))
            return counter[0], resolution[0]
        seconds = (c_double * 1)()
        self._call(f"fmi3GetIntervalDecimal({clock})", lambda: self._fmu.getIntervalDecimal(
            vr, seconds, qualifier))
        return seconds[0]

    def _supports_fraction(self, clock: str) -> bool:
        # FMPy 0.3 does not read the attribute: the model description's text says.
        with zipfile.ZipFile(self._path) as z:
            text = z.read("modelDescription.xml").decode("utf-8", "replace")
        tag = re.search(r'<Clock\b[^>]*\bname="' + re.escape(clock) + r'"[^>]*>', text)
        return tag is not None and re.search(r'\bsupportsFraction="(true|1)"', tag[0]) is not None

    def tick(self, clock: str, time: float) -> None:
        """In Event Mode: the clock set and the discrete states updated (the law run)."""
        vr = self.variables[clock].valueReference
        self._call(f"fmi3SetClock({clock}) at t = {time!r} s",
                   lambda: self._fmu.setClock([vr], [True]))
        flags = self._call("fmi3UpdateDiscreteStates", self._fmu.updateDiscreteStates)
        if flags[0] or flags[1]:
            raise FmuError(f"{self.alias}: fmi3UpdateDiscreteStates at t = {time!r} s asks "
                           "for " + ("another update" if flags[0] else "the end of the run") +
                           f", which the master does not serve: {self._last_message()}")

    def enter_step_mode(self) -> None:
        self._call("fmi3EnterStepMode", self._fmu.enterStepMode)

    def enter_event_mode(self) -> None:
        self._call("fmi3EnterEventMode", self._fmu.enterEventMode)

    def step_to(self, time: float, step: float) -> tuple[bool, float]:
        """fmi3DoStep: (event handling needed, the time it reached); FmuError when it
        returns early or asks to terminate (the master's steps end at the ticks)."""
        event, terminate, early, last = self._call(
            f"fmi3DoStep at t = {time!r} s", lambda: self._fmu.doStep(time, step))
        if terminate or early:
            raise FmuError(f"{self.alias}: fmi3DoStep from t = {time!r} s over {step!r} s "
                           + ("asks to terminate" if terminate else
                              f"returned early at t = {last!r} s") +
                           f": {self._last_message()}")
        return bool(event), float(last)

    def enter_initialization(self) -> None:
        self._call("fmi3EnterInitializationMode",
                   lambda: self._fmu.enterInitializationMode(startTime=self._start_time,
                                                             stopTime=self._stop_time))

    def reset(self, start_time: float, stop_time: float) -> None:
        """fmi3Reset: back to the state after instantiation (start values of every
        parameter); the next initialization starts the experiment at `start_time`."""
        self._call("fmi3Reset", self._fmu.reset)
        self._initialized = False
        self._written = dict(self._starts)
        self.messages.clear()
        self._start_time, self._stop_time = start_time, stop_time


def is_fmi3(path: Path) -> bool:
    """The FMU at `path` is an FMI 3.0 FMU itself (anyone's, not the FMI 2.0 file of ours
    whose FMI 3.0 build lies in fmi3/ beside it)."""
    from .fmu_check import describe
    return describe(path, "fmus").fmiVersion == "3.0"


def open_fmi3(alias, path, scenario):
    """The master's `open_fmu` for the FMI 3.0 builds of the scenario's FMUs (an FMI 3.0
    FMU itself as it is, its inputs held)."""
    if is_fmi3(Path(path)):
        return Fmu3Instance(alias, Path(path), scenario.start_time, scenario.stop_time)
    return Fmu3Instance(alias, fmi3_path(Path(path)), scenario.start_time, scenario.stop_time,
                        extrapolate=getattr(scenario, "input_extrapolation", "hold") != "hold")
