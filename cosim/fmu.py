"""One co-simulation FMU instance behind FMPy's low-level API, with errors that name the
FMU and the FMI call, and the FMU's log messages kept for error reports."""

from __future__ import annotations

from pathlib import Path

from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE, fmi2Discard)
from fmpy import calloc, free

from .errors import FmuError, StepDiscarded




class FmuInstance:
    """A co-simulation instance of an FMI 2.0 FMU, addressed by variable names."""

    def __init__(self, alias: str, path: Path, start_time: float, stop_time: float):
        self.alias = alias
        self.messages: list[str] = []
        md = read_model_description(str(path))
        if md.coSimulation is None:
            raise FmuError(f"{alias} ({path}) does not support co-simulation")
        self.variables = {v.name: v for v in md.modelVariables}
        self.can_get_state = bool(md.coSimulation.canGetAndSetFMUstate)
        self._unzip = extract(str(path))
        self._fmu = FMU2Slave(guid=md.guid, unzipDirectory=self._unzip,
                              modelIdentifier=md.coSimulation.modelIdentifier, instanceName=alias)
        # Keep the ctypes callbacks alive as long as the instance.
        self._callbacks = fmi2CallbackFunctions()
        self._callbacks.logger = fmi2CallbackLoggerTYPE(self._log)
        self._callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        self._callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        self._call("fmi2Instantiate", lambda: self._fmu.instantiate(callbacks=self._callbacks))
        self._call("fmi2SetupExperiment",
                   lambda: self._fmu.setupExperiment(startTime=start_time, stopTime=stop_time))

    def _log(self, _env, _name, status, category, message):
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

    def _variable(self, name: str):
        try:
            return self.variables[name]
        except KeyError:
            raise FmuError(f"{self.alias} has no variable '{name}'") from None

    def set_value(self, name: str, value) -> None:
        v = self._variable(name)
        vr = [v.valueReference]
        if v.type == "Real":
            self._call(f"fmi2SetReal({name})", lambda: self._fmu.setReal(vr, [float(value)]))
        elif v.type in ("Integer", "Enumeration"):
            self._call(f"fmi2SetInteger({name})", lambda: self._fmu.setInteger(vr, [int(value)]))
        elif v.type == "Boolean":
            self._call(f"fmi2SetBoolean({name})", lambda: self._fmu.setBoolean(vr, [bool(value)]))
        else:
            raise FmuError(f"{self.alias}.{name}: variables of type {v.type} are not supported")

    def get_value(self, name: str) -> float:
        v = self._variable(name)
        vr = [v.valueReference]
        if v.type == "Real":
            return self._call(f"fmi2GetReal({name})", lambda: self._fmu.getReal(vr))[0]
        if v.type in ("Integer", "Enumeration"):
            return float(self._call(f"fmi2GetInteger({name})", lambda: self._fmu.getInteger(vr))[0])
        if v.type == "Boolean":
            return float(self._call(f"fmi2GetBoolean({name})", lambda: self._fmu.getBoolean(vr))[0])
        raise FmuError(f"{self.alias}.{name}: variables of type {v.type} are not supported")

    def enter_initialization(self) -> None:
        self._call("fmi2EnterInitializationMode", self._fmu.enterInitializationMode)

    def exit_initialization(self) -> None:
        self._call("fmi2ExitInitializationMode", self._fmu.exitInitializationMode)

    def do_step(self, time: float, step: float) -> None:
        try:
            self._fmu.doStep(currentCommunicationPoint=time, communicationStepSize=step)
        except FMICallException as e:
            if e.status == fmi2Discard:
                raise StepDiscarded(self.alias, time, self._last_message()) from None
            raise FmuError(f"{self.alias}: fmi2DoStep at t = {time:.9g} s failed with status "
                           f"{e.status}: {self._last_message()}") from e

    def get_state(self):
        if not self.can_get_state:
            raise FmuError(f"{self.alias} cannot get and set its FMU state (no rollback)")
        return self._call("fmi2GetFMUstate", self._fmu.getFMUstate)

    def set_state(self, state) -> None:
        self._call("fmi2SetFMUstate", lambda: self._fmu.setFMUstate(state))

    def free_state(self, state) -> None:
        self._call("fmi2FreeFMUstate", lambda: self._fmu.freeFMUstate(state))

    def close(self) -> None:
        """Terminates and frees the instance; safe to call after a failure."""
        try:
            self._fmu.terminate()
        except FMICallException:
            pass
        self._fmu.freeInstance()
