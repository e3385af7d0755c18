"""A test oracle, never run by the harness: the master's stepping loop written out in
Python over the instances' own methods (FmuInstance / Fmu3Instance get_values,
set_values, do_step, get_output_derivatives, set_input_derivatives, get/set/free_state:
FMPy's wrappers), in the order robofmu.loop's native kernel makes the same calls. It is
what the master's loop was before it became one native loop (robofmu/master.py's
`_run_python` with FMPy calls); tests compare the master with it bit for bit.
"""

from __future__ import annotations

import numpy as np

from robofmu.errors import CosimError, StepDiscarded
from robofmu.master import Master, Result


class ReferenceMaster(Master):
    """robofmu.master.Master with the stepping loop in plain Python."""

    def _set_inputs(self, alias: str) -> None:
        for source, variables, inputs in self.inputs[alias]:
            self.fmus[alias].set_values(inputs, self.fmus[source].get_values(variables))

    def _set_slopes(self, alias: str, t: float) -> None:
        for source, variables, inputs, history, order in self.slopes[alias]:
            fmu = self.fmus[source]
            if history is None:
                derivatives = fmu.get_output_derivatives(variables, order)
            else:
                derivatives = history.derivatives(t, np.array(fmu.get_values(variables)))
                derivatives = derivatives.ravel()
            self.fmus[alias].set_input_derivatives(inputs, derivatives, order)

    def _propagate(self, t: float) -> None:
        for alias in self.scenario.order:
            self._set_inputs(alias)
        for alias in self.scenario.order:
            self._set_slopes(alias, t)

    def _advance(self, numerator: int, denominator: int, halvings_left: int,
                 inputs_set: bool = False) -> None:
        t = self._time(numerator, denominator)
        h = self.scenario.step_size / denominator
        saved = ({a: f.get_state() for a, f in self.fmus.items()} if halvings_left > 0 else None)
        sampled = self.scenario.coupling == "sampled"
        try:
            if sampled and not inputs_set:
                self._propagate(t)
            for alias in self.scenario.order:
                if not sampled:
                    self._set_inputs(alias)
                    self._set_slopes(alias, t)
                self.fmus[alias].do_step(t, h)
        except StepDiscarded as d:
            if saved is None:
                raise CosimError(f"{d} (no step halvings left; raise max_step_halvings "
                                 "to retry with smaller steps)") from None
            self.discards.append(f"{d}; retrying with h = {h / 2:.9g} s")
            for alias, state in saved.items():
                self.fmus[alias].set_state(state)
            self._advance(2 * numerator, 2 * denominator, halvings_left - 1)
            self._advance(2 * numerator + 1, 2 * denominator, halvings_left - 1)
        finally:
            for state_alias, state in (saved or {}).items():
                self.fmus[state_alias].free_state(state)

    def _record(self, rows: np.ndarray, k: int) -> None:
        column = 0
        for alias, variables in self.recorded_by_fmu.items():
            values = self.fmus[alias].get_values(variables)
            rows[k, column:column + len(values)] = values
            column += len(values)

    def _step(self, k: int, rows: np.ndarray, inputs_set: bool) -> None:
        self._advance(k, 1, self.scenario.max_step_halvings, inputs_set=inputs_set)
        if self.scenario.coupling == "sampled":
            self._propagate(self._time(k + 1, 1))
        self._record(rows, k + 1)

    def _start_up(self, rows: np.ndarray) -> None:
        # Master._start_up's passes, each step as _step makes it.
        s = self.scenario
        histories = [p[3] for pairs in self.slopes.values() for p in pairs
                     if p[3] is not None and p[3].order >= 2]
        if (not histories or s.steps <= 2 or any(w.step <= 2 for w in s.schedule)
                or not all(getattr(f, "can_get_state", False) for f in self.fmus.values())):
            return
        discards = len(self.discards)
        for _ in range(2):
            points = [[h.past[0].copy()] for h in histories]
            saved = {a: f.get_state() for a, f in self.fmus.items()}
            for k in range(2):
                self._step(k, rows, True)
                for h, p in zip(histories, points):
                    p.append(h.past[0].copy())
            for alias, state in saved.items():
                self.fmus[alias].set_state(state)
                self.fmus[alias].free_state(state)
            for h, p in zip(histories, points):
                h.seed(s.start_time, s.step_size, p)
            self._propagate(s.start_time)
        del self.discards[discards:]

    def run(self) -> Result:
        s = self.scenario
        self.fmus, self.discards = {}, []
        names = [f"{alias}.{v}" for alias, vs in self.recorded_by_fmu.items() for v in vs]
        rows = np.empty((s.steps + 1, len(names)))
        switches = {switch.step: switch for switch in s.schedule}
        try:
            for alias in s.order:
                self.fmus[alias] = self.open_fmu(alias, s.fmus[alias], s)
            for alias, values in s.parameters.items():
                self._initialize(alias, values)
            for alias in s.order:
                self.fmus[alias].enter_initialization()
            self.slopes = self._slope_pairs()
            for alias in s.order:
                self._set_inputs(alias)
            for alias in s.order:
                self.fmus[alias].exit_initialization()
            if s.coupling == "sampled":
                self._propagate(s.start_time)
                self._start_up(rows)
            self._record(rows, 0)
            for k in range(s.steps):
                switched = k in switches
                if switched:
                    self._switch_plan(switches[k])
                self._step(k, rows, not switched)
        finally:
            for fmu in self.fmus.values():
                self.close_fmu(fmu)
        times = [self._time(k, 1) for k in range(s.steps + 1)]
        order = [str(sig) for sig in self.recorded]
        columns = {name: rows[:, j].tolist() for j, name in enumerate(names)}
        return Result(names=order, time=times, columns={n: columns[n] for n in order},
                      discards=self.discards)
