"""An FMI 3.0 FMU in Model Exchange that the master integrates itself (a scenario's
``model_exchange = { ALIAS = "rk4" }``, run by robofmu.clocked's loop): the classic
fourth-order Runge-Kutta method, one step of the communication step h from t_k to
t_k+1 with the inputs held over it (the values set at t_k),

    x_k+1 = x_k + h / 6 (k1 + 2 k2 + 2 k3 + k4),

each stage fmi3SetTime, fmi3SetContinuousStates and fmi3GetContinuousStateDerivatives;
then the time and the state of t_k+1 set, fmi3CompletedIntegratorStep. A state event
(an event indicator changing sign over the step) is located by bisection of the step's
size (40 halvings: the first RK4 step from t_k whose end shows the change): the FMU
steps there, passes through Event Mode (fmi3UpdateDiscreteStates until its discrete
states settle) and the rest of the step is integrated from the state it reports; an
event the FMU asks for after a step (time or step events) is handled at the step's
end."""

from __future__ import annotations

from ctypes import c_double
from pathlib import Path

import numpy as np

from .errors import FmuError
from .fmi3 import Fmu3Instance

class Rk4Instance(Fmu3Instance):
    """The Model Exchange instance of an FMI 3.0 FMU, addressed as Fmu3Instance, whose
    do_step integrates one RK4 step."""

    def __init__(self, alias: str, path: Path, start_time: float, stop_time: float):
        super().__init__(alias, path, start_time, stop_time, model_exchange=True)
        self._x = np.empty(0)
        self._z = np.empty(0)

    def exit_initialization(self) -> None:
        """Initialization Mode -> Event Mode -> Continuous-Time Mode, the discrete
        states settled; the state and event indicators at the start."""
        super().exit_initialization()
        n = self._call("fmi3GetNumberOfContinuousStates",
                       self._fmu.getNumberOfContinuousStates)
        m = self._call("fmi3GetNumberOfEventIndicators", self._fmu.getNumberOfEventIndicators)
        self._buffer = (c_double * max(n, 1))()
        self._indicators = (c_double * max(m, 1))()
        self._n, self._m = n, m
        self._settle("at the start")

    def _settle(self, when: str) -> None:
        """In Event Mode: the discrete states updated until they settle, then
        Continuous-Time Mode with the state and event indicators read again."""
        for _ in range(100):
            update = self._call("fmi3UpdateDiscreteStates", self._fmu.updateDiscreteStates)
            if update[1]:
                raise FmuError(f"{self.alias}: fmi3UpdateDiscreteStates asks to terminate "
                               f"{when}: {self._last_message()}")
            if not update[0]:
                break
        else:
            raise FmuError(f"{self.alias}: its discrete states do not settle {when} (100 "
                           "updates)")
        self.resume()

    def resume(self) -> None:
        """Event Mode -> Continuous-Time Mode, the state and event indicators read again
        (after an event, or a tick of its clock: robofmu.clocked)."""
        self._call("fmi3EnterContinuousTimeMode", self._fmu.enterContinuousTimeMode)
        self._call("fmi3GetContinuousStates",
                   lambda: self._fmu.getContinuousStates(self._buffer, self._n))
        self._x = np.array(self._buffer[:self._n])
        self._z = self._event_indicators()

    def _event_indicators(self) -> np.ndarray:
        self._call("fmi3GetEventIndicators",
                   lambda: self._fmu.getEventIndicators(self._indicators, self._m))
        return np.array(self._indicators[:self._m])

    def _set(self, t: float, x: np.ndarray) -> None:
        self._call("fmi3SetTime", lambda: self._fmu.setTime(t))
        self._buffer[:self._n] = x.tolist()
        self._call("fmi3SetContinuousStates",
                   lambda: self._fmu.setContinuousStates(self._buffer, self._n))

    def _derivatives(self, t: float, x: np.ndarray) -> np.ndarray:
        self._set(t, x)
        self._call("fmi3GetContinuousStateDerivatives",
                   lambda: self._fmu.getContinuousStateDerivatives(self._buffer, self._n))
        return np.array(self._buffer[:self._n])

    def _rk4(self, t: float, x: np.ndarray, h: float) -> np.ndarray:
        """One RK4 step of size h from (t, x); the FMU left at t + h and the result."""
        k1 = self._derivatives(t, x)
        k2 = self._derivatives(t + h / 2, x + h / 2 * k1)
        k3 = self._derivatives(t + h / 2, x + h / 2 * k2)
        k4 = self._derivatives(t + h, x + h * k3)
        x = x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        self._set(t + h, x)
        return x

    def _crossed(self, z: np.ndarray) -> bool:
        return bool(np.any(np.signbit(z) != np.signbit(self._z)))

    def do_step(self, time: float, step: float) -> None:
        self.advance(time, time + step)

    def advance(self, time: float, end: float) -> None:
        """RK4 from `time` to `end` in one step, or, where an event indicator changes
        sign over it, to the first change (bisection of the step's size, 40 halvings),
        Event Mode there, and the rest of the step after it."""
        x0 = self._x
        x = self._rk4(time, x0, end - time)
        z = self._event_indicators()
        at = end
        if self._crossed(z):
            low, high = 0.0, end - time  # no change after low, a change after high
            for _ in range(40):
                middle = (low + high) / 2
                self._rk4(time, x0, middle)
                if self._crossed(self._event_indicators()):
                    high = middle
                else:
                    low = middle
            at = time + high
            x = self._rk4(time, x0, high)
            z = self._event_indicators()
        enter_event_mode, terminate = self._call(
            "fmi3CompletedIntegratorStep", self._fmu.completedIntegratorStep)
        if terminate:
            raise FmuError(f"{self.alias}: after the RK4 step from t = {time!r} s the FMU asks "
                           f"to terminate: {self._last_message()}")
        crossed = self._crossed(z)
        self._x, self._z = x, z
        if enter_event_mode or crossed:
            self._call("fmi3EnterEventMode", self._fmu.enterEventMode)
            self._settle(f"at t = {at!r} s")
        if at < end:
            self.advance(at, end)
