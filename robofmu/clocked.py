"""The master's run of a scenario with clocked FMUs (``[sample_period]``: an FMI 3.0
FMU whose periodic input clock the master ticks) or FMUs in Model Exchange
(``[model_exchange]``, integrated by robofmu.integrated), beside co-simulation FMUs, in
sampled coupling; a loop in Python (robofmu.master's native loop serves the scenarios
without either, unchanged).

Time: the sample period P of each clocked FMU is read as the exact fraction c / r of
its decimal (0.001 s = 1/1000) and must be the interval the FMU reports for its clock
(fmi3GetIntervalFraction, else fmi3GetIntervalDecimal, in Initialization Mode) and a
whole number m of communication steps. Communication point k is

    t_k = start + (k c) / (r m)

from integers (one rounding, so no drift: with 1 ms, t at k = 10^6 is 1000.0
exactly), and tick j of the clock falls on point j m at start + (j c) / r, the time
the FMU computes for its tick j.

Each step k, as robofmu.master's sampled coupling: at t_k the outputs are propagated
through the scenario's order; a clocked FMU whose tick falls on t_k gets its inputs
first, then, in Event Mode, fmi3SetClock and fmi3UpdateDiscreteStates (its clocked
outputs change there), then fmi3EnterStepMode, before the FMUs after it read its
outputs (a clocked FMU in Model Exchange: fmi3EnterEventMode, the clock, the update,
then Continuous-Time Mode). The row of t_k is recorded, and every FMU steps to t_k+1;
a clocked co-simulation FMU's step that ends at its next tick returns there asking for
Event Mode (it was instantiated with eventModeUsed and earlyReturnAllowed) and enters
it. Inputs are held
over each step (no input derivatives: a clocked output is piecewise constant). A step
an FMU discards or ends early (not at a tick) ends the run with the FMU's reason.
"""

from __future__ import annotations

import time
from fractions import Fraction
from pathlib import Path

import numpy as np

from .errors import CosimError, FmuError, ScenarioError, StepDiscarded
from .fmu_check import describe
from .instances import close_all
from .integrated import Rk4Instance
from .preflight import check_interval, clock_of


def exact_period(period: float) -> Fraction:
    """`period` (s) as the fraction of its shortest decimal (0.001 -> 1/1000): the
    interval the FMU ticks when its period parameter is that decimal."""
    return Fraction(repr(period))


def grid(start: float, step: Fraction, count: int) -> np.ndarray:
    """t_k = start + (k n) / d for k in 0..count-1 (n / d = `step`): each from
    integers, one rounding."""
    n, d = step.numerator, step.denominator
    return np.array([start + (k * n) / d for k in range(count)])


class ClockedRun:
    """One run of a scenario with sample periods, over robofmu.master.Master's
    parameters, plan switches and instance handling."""

    def __init__(self, master):
        self.master = master
        s = self.scenario = master.scenario
        self.steps = s.steps
        self.clocks: dict[str, str] = {}  # alias -> its clock's name
        self.every: dict[str, int] = {}  # alias -> communication steps per tick
        periods = {alias: exact_period(p) for alias, p in s.sample_period.items()}
        for alias, period in s.sample_period.items():
            self.every[alias] = round(period / s.step_size)
            self.clocks[alias] = clock_of(describe(Path(s.fmus[alias]), f"fmus.{alias}"),
                                          alias, period).name
        # The communication step: a period over its steps per tick, the same for each.
        steps = {period / self.every[alias] for alias, period in periods.items()}
        if len(steps) > 1:
            raise ScenarioError("field 'sample_period': the periods "
                                f"{sorted(map(str, s.sample_period.values()))} s are not "
                                "exact multiples of one step; make each a multiple of "
                                "the smallest")
        self.times = grid(s.start_time, steps.pop() if steps else exact_period(s.step_size),
                          self.steps + 1)
        self.own = set(self.clocks) | set(s.model_exchange)  # instances made here
        self.t: list[float] = self.times.tolist()  # as Python floats, for the FMU calls

    def _open(self) -> dict:
        from .fmi3 import Fmu3Instance, is_fmi3  # lazily: FMPy's FMI 3.0 layer
        m, s, fmus = self.master, self.scenario, {}
        try:
            for alias in s.order:
                path = Path(s.fmus[alias])
                if alias in self.clocks and alias not in s.model_exchange:
                    if not is_fmi3(path):
                        raise ScenarioError(f"field 'sample_period.{alias}': {path} is not an "
                                            "FMI 3.0 FMU; name its FMI 3.0 build (such as "
                                            "fmi3/ComputedTorque)")
                    fmus[alias] = Fmu3Instance(alias, path, s.start_time, s.stop_time,
                                               clocked=True)
                elif alias in s.model_exchange:
                    if not is_fmi3(path):
                        raise ScenarioError(f"field 'model_exchange.{alias}': {path} is not an "
                                            "FMI 3.0 FMU; name its FMI 3.0 build (such as "
                                            "fmi3/Pss3Plant)")
                    fmus[alias] = Rk4Instance(alias, path, s.start_time, s.stop_time)
                else:
                    fmus[alias] = m.open_fmu(alias, path, s)
        except BaseException:
            for fmu in fmus.values():
                fmu.close()
            raise
        return fmus

    def _exchange(self, alias: str) -> None:
        for source, variables, inputs in self.master.inputs[alias]:
            self.fmus[alias].set_values(inputs, self.fmus[source].get_values(variables))

    def _propagate(self, k: int) -> None:
        """The sampled propagation at t_k, ticking the clocks that tick there."""
        for alias in self.scenario.order:
            self._exchange(alias)
            every = self.every.get(alias)
            if every is not None and k % every == 0:
                fmu = self.fmus[alias]
                if isinstance(fmu, Rk4Instance):  # Model Exchange: Event Mode at the tick
                    fmu.enter_event_mode()
                    fmu.tick(self.clocks[alias], self.t[k])
                    fmu.resume()
                    continue
                if k > 0 and not self.in_event_mode[alias]:
                    raise FmuError(f"{alias}: its step to the tick at t = {self.t[k]!r} s "
                                   "ended without asking for Event Mode; the FMU does not "
                                   "tick where sample_period says")
                fmu.tick(self.clocks[alias], self.t[k])
                fmu.enter_step_mode()
                self.in_event_mode[alias] = False

    def _record(self, row: np.ndarray) -> None:
        for alias, (first, names) in self.record_slices.items():
            row[first:first + len(names)] = self.fmus[alias].get_values(names)

    def _step(self, k: int) -> None:
        t, h = self.t[k], self.t[k + 1] - self.t[k]
        for alias in self.scenario.order:
            fmu = self.fmus[alias]
            if isinstance(fmu, Rk4Instance):  # to t_k+1 exactly: a tick's time
                fmu.advance(t, self.t[k + 1])
                continue
            if alias not in self.clocks:
                fmu.do_step(t, h)
                continue
            event, reached = fmu.step_to(t, h)
            if (k + 1) % self.every[alias] == 0:
                if not event or reached != self.t[k + 1]:
                    raise FmuError(f"{alias}: its step from t = {t!r} s reached "
                                   f"{reached!r} s without asking for Event Mode at the "
                                   f"tick t = {self.t[k + 1]!r} s")
                fmu.enter_event_mode()
                self.in_event_mode[alias] = True

    def run(self, contiguous: bool):
        from .master import Arrays, _close_fmu  # the master imports this module lazily
        m, s = self.master, self.scenario
        switches = {switch.step: switch for switch in s.schedule}
        names = [str(sig) for sig in m.recorded]
        self.record_slices, first = {}, 0
        for alias, variables in m.recorded_by_fmu.items():
            self.record_slices[alias] = (first, variables)
            first += len(variables)
        columns = [f"{alias}.{v}" for alias, variables in m.recorded_by_fmu.items()
                   for v in variables]
        rows = np.empty((len(self.times), len(columns)))
        self.in_event_mode = dict.fromkeys(self.clocks, True)  # after initialization
        self.fmus = m.fmus = self._open()
        try:
            for alias, values in s.parameters.items():
                m._initialize(alias, values)
            for alias in s.order:
                self.fmus[alias].enter_initialization()
            for alias, clock in self.clocks.items():
                check_interval(self.fmus[alias], alias, clock, s.sample_period[alias])
            for alias in s.order:  # consistent inputs at the start, in order
                self._exchange(alias)
            for alias in s.order:
                self.fmus[alias].exit_initialization()
            started = time.perf_counter()
            for k in range(self.steps + 1):
                if k in switches:
                    m._switch_plan(switches[k])
                self._propagate(k)
                self._record(rows[k])
                if k < self.steps:
                    self._step(k)
                if m.progress is not None and (k % max(1, self.steps // 100) == 0
                                               or k == self.steps):
                    m.progress(k / self.steps)
            m.loop_seconds = time.perf_counter() - started
        except BaseException as e:
            shared = m.close_fmu is _close_fmu  # else the caller's pool (a sweep) keeps them
            for alias, fmu in self.fmus.items():  # after a failed run nothing stays shared
                if alias in self.own or shared:
                    fmu.close()
                else:
                    m.close_fmu(fmu)  # the pool's: it discards them
            if shared:
                close_all()
            if isinstance(e, StepDiscarded):
                raise CosimError(f"{e} (this loop, for clocked and Model Exchange FMUs, "
                                 "does not retry a discarded step; use a smaller "
                                 "step_size)") from None
            raise
        for alias, fmu in self.fmus.items():
            fmu.close() if alias in self.own else m.close_fmu(fmu)
        data = dict(zip(columns, np.ascontiguousarray(rows.T) if contiguous else rows.T))
        return Arrays(names=names, time=self.times, columns={n: data[n] for n in names},
                      discards=[])
