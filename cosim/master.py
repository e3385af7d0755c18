"""Fixed-step co-simulation of a chain of FMUs, in the scenario's (Gauss-Seidel) order.

Each communication step k advances every FMU from t_k = start + k h to t_k + h, in the
scenario's order, with two couplings:

- "sampled" (default): at t_k the outputs are propagated through the chain in order
  (each FMU's inputs are set from its sources' outputs at t_k, so an FMU with direct
  feedthrough, such as the PID, answers for t_k), then every FMU steps with its inputs
  held over the step. Every FMU sees all its inputs at the same instant t_k: the
  semantics of a sampled-data (digital) controller with zero-order hold.
- "gauss-seidel": classic sequential stepping; before an FMU steps, its inputs take the
  current outputs of their sources, which are already at t_k + h when the source comes
  earlier in the order. A source that is a function of time (the planner) then leads
  by one step: the loop tracks q(t + h) instead of q(t), an O(h) artefact.

Time is an integer step count, so t_k never accumulates rounding. A step that an FMU
discards is retried as two half steps, down to the scenario's max_step_halvings, with
every FMU rolled back to the start of the step.
"""

from __future__ import annotations

import csv
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from .errors import CosimError, StepDiscarded
from .scenario import Scenario, Signal


@dataclass
class Result:
    """Recorded signals: ``time`` and one column per signal name."""

    names: list[str]
    time: list[float]
    columns: dict[str, list[float]]
    discards: list[str]

    def write_csv(self, path: Path) -> None:
        """Cross-check CSV: quoted names on the first line, time first."""
        path.parent.mkdir(parents=True, exist_ok=True)
        with open(path, "w", newline="") as f:
            out = csv.writer(f, quoting=csv.QUOTE_NONNUMERIC, lineterminator="\n")
            out.writerow(["time", *self.names])
            for k, t in enumerate(self.time):
                out.writerow([t, *(self.columns[n][k] for n in self.names)])


def _open_fmu(alias, path, scenario):
    from .fmu import FmuInstance
    return FmuInstance(alias, path, scenario.start_time, scenario.stop_time)


class Master:
    """Runs one scenario. ``open_fmu(alias, path, scenario)`` creates the instances
    (FMPy by default; tests pass stand-ins with the same methods)."""

    def __init__(self, scenario: Scenario, open_fmu: Callable = _open_fmu,
                 progress: Callable[[float], None] | None = None):
        self.scenario = scenario
        self.open_fmu = open_fmu
        self.progress = progress
        # Per target FMU and source FMU: the source variables and the target inputs, so
        # that each pair is one get and one set call per step.
        self.inputs: dict[str, list[tuple[str, tuple[str, ...], tuple[str, ...]]]] = {}
        for alias in scenario.order:
            by_source: dict[str, tuple[list[str], list[str]]] = {}
            for c in scenario.connections:
                if c.target.alias == alias:
                    sources, targets = by_source.setdefault(c.source.alias, ([], []))
                    sources.append(c.source.variable)
                    targets.append(c.target.variable)
            self.inputs[alias] = [(src, tuple(a), tuple(b)) for src, (a, b) in by_source.items()]
        recorded = [c.source for c in scenario.connections] + list(scenario.record)
        self.recorded: list[Signal] = list(dict.fromkeys(recorded))
        self.recorded_by_fmu: dict[str, tuple[str, ...]] = {}
        for sig in self.recorded:
            self.recorded_by_fmu[sig.alias] = self.recorded_by_fmu.get(sig.alias, ()) + (
                sig.variable,)
        self.discards: list[str] = []

    def _time(self, numerator: int, denominator: int) -> float:
        s = self.scenario
        return s.start_time + numerator * s.step_size / denominator

    def _set_inputs(self, alias: str) -> None:
        for source, variables, inputs in self.inputs[alias]:
            self.fmus[alias].set_values(inputs, self.fmus[source].get_values(variables))

    def _advance(self, numerator: int, denominator: int, halvings_left: int) -> None:
        """Advances every FMU from t(numerator/denominator) by step_size/denominator."""
        t = self._time(numerator, denominator)
        h = self.scenario.step_size / denominator
        saved = ({a: f.get_state() for a, f in self.fmus.items()} if halvings_left > 0 else None)
        sampled = self.scenario.coupling == "sampled"
        try:
            if sampled:
                for alias in self.scenario.order:
                    self._set_inputs(alias)
            for alias in self.scenario.order:
                if not sampled:
                    self._set_inputs(alias)
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
            for alias, state in (saved or {}).items():
                self.fmus[alias].free_state(state)

    def _record(self, result: Result, t: float) -> None:
        result.time.append(t)
        for alias, variables in self.recorded_by_fmu.items():
            for variable, value in zip(variables, self.fmus[alias].get_values(variables)):
                result.columns[f"{alias}.{variable}"].append(value)

    def run(self) -> Result:
        s = self.scenario
        self.fmus = {}
        names = [str(sig) for sig in self.recorded]
        result = Result(names=names, time=[], columns={n: [] for n in names}, discards=self.discards)
        try:
            for alias in s.order:
                self.fmus[alias] = self.open_fmu(alias, s.fmus[alias], s)
            for alias, values in s.parameters.items():
                for name, value in values.items():
                    self.fmus[alias].set_value(name, value)
            for alias in s.order:
                self.fmus[alias].enter_initialization()
            for alias in s.order:  # consistent inputs at the start time, in order
                self._set_inputs(alias)
            for alias in s.order:
                self.fmus[alias].exit_initialization()
            self._record(result, self._time(0, 1))
            for k in range(s.steps):
                self._advance(k, 1, s.max_step_halvings)
                self._record(result, self._time(k + 1, 1))
                if self.progress is not None:
                    self.progress((k + 1) / s.steps)
        finally:
            for fmu in self.fmus.values():
                fmu.close()
        return result


def text_progress(stream=sys.stderr, width: int = 40) -> Callable[[float], None]:
    """A progress bar on a terminal line, redrawn only when it changes."""
    last = [-1]

    def show(fraction: float) -> None:
        filled = int(fraction * width)
        if filled != last[0]:
            last[0] = filled
            end = "\n" if fraction >= 1.0 else ""
            stream.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {100 * fraction:5.1f}%{end}")
            stream.flush()

    return show
