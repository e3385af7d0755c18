"""A Model Exchange instance of an FMI 2.0 FMU for one-off evaluations at rest (the gain
design's mass matrix): logs kept, cleaned up on every path without masking the error."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from fmpy import calloc, free, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (FMU2Model, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE)

from .errors import ScenarioError
from .fmi2 import release, status_categories, unpack


class ModelExchangeInstance:
    """``with ModelExchangeInstance(path, name) as fmu:`` set_real / initialize /
    get_real by variable name; FMI failures raise ``fmu.Failed``."""

    Failed = FMICallException
    _fmu: Any  # the FMPy model: None outside the with block

    def __init__(self, path: str | Path, name: str):
        self.path, self.name = str(path), name
        self.messages: list[str] = []

    def __enter__(self) -> ModelExchangeInstance:
        md = read_model_description(self.path)
        if md.modelExchange is None:
            raise ScenarioError(
                f"field 'fmus.plant': {Path(self.path).name} has no Model Exchange interface, "
                "which the gain design 'gains.omega' needs; use a plant FMU built with Model "
                "Exchange (the project's dist/Pss3Plant.fmu) or give 'gains.Kp', 'gains.Ki' "
                "and 'gains.Kd'")
        self.refs = {v.name: v.valueReference for v in md.modelVariables}
        self.types = {v.name: v.type for v in md.modelVariables}
        self._unzip: str | None = unpack(self.path)
        self._initialized = False
        self._fmu = None
        try:
            self._fmu = FMU2Model(guid=md.guid, unzipDirectory=self._unzip,
                                  modelIdentifier=md.modelExchange.modelIdentifier,
                                  instanceName=self.name)
            self._callbacks = fmi2CallbackFunctions()
            self._callbacks.logger = fmi2CallbackLoggerTYPE(self._log)
            self._callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
            self._callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
            self._fmu.instantiate(callbacks=self._callbacks)
            categories = status_categories(md)
            if categories:
                self._fmu.setDebugLogging(True, categories)
            self._fmu.setupExperiment(startTime=0.0)
        except BaseException:
            self.__exit__(None, None, None)
            raise
        return self

    def _log(self, _env, _name, _status, category, message) -> None:
        self.messages.append(message.decode("utf-8", "replace") if message else "")

    def reason(self, error: Exception) -> str:
        return self.messages[-1] if self.messages else f"status {getattr(error, 'status', '?')}"

    def set_real(self, names, values) -> None:
        self._fmu.setReal([self.refs[n] for n in names], list(values))

    def set_values(self, values: dict) -> None:
        """Sets {name: value} by each variable's declared type (Real, Integer, Boolean)."""
        for name, value in values.items():
            setter = {"Integer": self._fmu.setInteger, "Enumeration": self._fmu.setInteger,
                      "Boolean": self._fmu.setBoolean}.get(self.types[name], self._fmu.setReal)
            setter([self.refs[name]], [value])

    def get_real(self, names) -> list[float]:
        return list(self._fmu.getReal([self.refs[n] for n in names]))

    def reset(self) -> None:
        """fmi2Reset: the state after instantiation again (its start values), ready for
        the next evaluation."""
        self._fmu.reset()
        self._initialized = False
        self.messages.clear()
        self._fmu.setupExperiment(startTime=0.0)

    def initialize(self) -> None:
        self._fmu.enterInitializationMode()
        self._fmu.exitInitializationMode()
        self._initialized = True
        self._fmu.newDiscreteStates()
        self._fmu.enterContinuousTimeMode()

    def __exit__(self, *_exc) -> None:
        fmu, self._fmu = self._fmu, None
        release(fmu, self._initialized, self._unzip)
        self._unzip = None
