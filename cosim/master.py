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

Recorded moment: row k holds every recorded signal at t_k as it is exchanged over the
step from t_k. With "sampled", that is after the inputs of t_k are set (row 0 after
initialization, row k > 0 after step k - 1 and the propagation at t_k that step k uses),
so a recorded output is the value its targets hold over [t_k, t_k + h] (pid.u is the
control the plant receives); the propagation is the one the next step needs anyway, so
recording costs no extra FMU calls. With "gauss-seidel", row k + 1 is read after every
FMU has made step k: each output there is the value passed on during that step.

Time is an integer step count, so t_k never accumulates rounding. A step that an FMU
discards is retried as two half steps, down to the scenario's max_step_halvings, with
every FMU rolled back to the start of the step.
"""

from __future__ import annotations

import csv
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any
from collections.abc import Callable

import numpy as np

from .errors import CosimError, StepDiscarded
from .scenario import Scenario, Signal
from .slopes import History, served


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


def _close_fmu(fmu) -> None:
    fmu.close()


class Master:
    """Runs one scenario. ``open_fmu(alias, path, scenario)`` creates the instances
    (FMPy by default; tests pass stand-ins with the same methods) and
    ``close_fmu(instance)`` ends them (a sweep worker's pool keeps them for the next
    run). With ``fast`` (default) the per-step calls of FMPy instances go through the
    prepared ctypes calls of cosim.fastpath; the results are the same bit for bit."""

    def __init__(self, scenario: Scenario, open_fmu: Callable = _open_fmu,
                 progress: Callable[[float], None] | None = None,
                 close_fmu: Callable = _close_fmu, fast: bool = True, native: bool = True):
        self.scenario = scenario
        self.open_fmu = open_fmu
        self.close_fmu = close_fmu
        self.progress = progress
        self.fast = fast
        self.native = native  # the native loop (cosim.native) where it applies
        # cosim.fastpath.Kernel, or cosim.native.NativeKernel (which has run_steps)
        self.kernel: Any = None
        self.loop_seconds = float("nan")  # wall time of the stepping loop (recording included)
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
        if self.kernel is not None:
            self.kernel.set_inputs(alias)
            return
        for source, variables, inputs in self.inputs[alias]:
            self.fmus[alias].set_values(inputs, self.fmus[source].get_values(variables))

    def _set_slopes(self, alias: str, t: float) -> None:
        for source, variables, inputs, history in self.slopes[alias]:
            fmu = self.fmus[source]
            if history is None:
                slopes = fmu.get_output_slopes(variables)
            else:
                slopes = history.slopes(t, np.array(fmu.get_values(variables)))
            self.fmus[alias].set_input_slopes(inputs, slopes)

    def _propagate(self, t: float) -> None:
        """Sampled coupling at time t: every FMU's inputs from its sources' current
        outputs, in order, then (linear extrapolation) the slopes, from outputs that now
        all answer for the inputs just set."""
        if self.kernel is not None:
            self.kernel.propagate(t)
            return
        for alias in self.scenario.order:
            self._set_inputs(alias)
        for alias in self.scenario.order:
            self._set_slopes(alias, t)

    def _slope_pairs(self) -> dict[str, list]:
        """Per target FMU, the connections that pass slopes with input_extrapolation =
        "linear", where the target interpolates inputs (canInterpolateInputs): the
        source's output derivatives where it serves them (cosim.slopes), else the slope
        through the outputs at the last two communication points (History)."""
        pairs: dict[str, list] = {alias: [] for alias in self.scenario.order}
        if self.scenario.input_extrapolation != "linear":
            return pairs
        for alias in self.scenario.order:
            if not getattr(self.fmus[alias], "can_interpolate_inputs", False):
                continue
            for source, variables, inputs in self.inputs[alias]:
                pairs[alias] += self._split(source, variables, inputs)
        return pairs

    def _split(self, source, variables, inputs) -> list:
        """(source, variables, inputs, None) for the served slopes, (..., History) for
        the rest of the Real variables of one connected pair."""
        fmu = self.fmus[source]
        is_real = getattr(fmu, "is_real", lambda _name: True)  # test doubles: all Real
        real = [k for k, v in enumerate(variables) if is_real(v)]
        ok = (served(str(self.scenario.fmus[source]), tuple(variables[k] for k in real))
              if getattr(fmu, "max_output_derivative_order", 0) >= 1 else frozenset())
        parts = []
        for keep, history in (([k for k in real if variables[k] in ok], None),
                              ([k for k in real if variables[k] not in ok], History())):
            if keep:
                parts.append((source, tuple(variables[k] for k in keep),
                              tuple(inputs[k] for k in keep), history))
        return parts

    def _advance(self, numerator: int, denominator: int, halvings_left: int,
                 inputs_set: bool = False) -> None:
        """Advances every FMU from t(numerator/denominator) by step_size/denominator;
        `inputs_set`: the sampled propagation at that time is done already."""
        t = self._time(numerator, denominator)
        h = self.scenario.step_size / denominator
        saved = ({a: f.get_state() for a, f in self.fmus.items()} if halvings_left > 0 else None)
        sampled = self.scenario.coupling == "sampled"
        try:
            if self.kernel is not None:
                self.kernel.step_all(t, h, sampled and not inputs_set, sampled)
            else:
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
            for alias, state in (saved or {}).items():
                self.fmus[alias].free_state(state)

    def _record(self, rows: np.ndarray, k: int) -> None:
        if self.kernel is not None:
            self.kernel.record(rows[k])
            return
        column = 0
        for alias, variables in self.recorded_by_fmu.items():
            values = self.fmus[alias].get_values(variables)
            rows[k, column:column + len(values)] = values
            column += len(values)

    def _initialize(self, alias: str, parameters: dict) -> None:
        for name, value in parameters.items():
            self.fmus[alias].set_value(name, value)

    def _switch_plan(self, switch) -> None:
        """A plan switch of a multi-segment motion: the (stateless) FMU is reset and
        initialised with the next segment's parameters, its experiment starting now."""
        fmu = self.fmus[switch.alias]
        fmu.reset(self._time(switch.step, 1), self.scenario.stop_time)
        self._initialize(switch.alias, switch.parameters)
        fmu.enter_initialization()
        fmu.exit_initialization()

    def _build_kernel(self) -> None:
        self.kernel = None
        from .fmu import FmuInstance
        # The prepared ctypes calls are FMI 2.0 calls on FMI 2.0 scalar names: FMI 3.0
        # instances (cosim.fmi3) and test doubles go through their own methods.
        if self.fast and all(type(f) is FmuInstance for f in self.fmus.values()):
            from .fastpath import Kernel
            from .native import NativeKernel, library
            s = self.scenario
            kernel: Kernel | NativeKernel
            if self.native and self._native_applies() and library() is not None:
                kernel = NativeKernel(self.fmus, self.inputs, self.recorded_by_fmu, s.order,
                                      self.slopes, s.start_time, s.step_size)
            else:
                kernel = Kernel(self.fmus, self.inputs, self.recorded_by_fmu, s.order,
                                self.slopes)
            self.kernel = kernel if kernel.ok else None

    def _native_applies(self) -> bool:
        """The native loop makes whole runs of steps: sampled coupling, no step retried
        (a retry needs the state saved before every step)."""
        return self.scenario.coupling == "sampled" and self.scenario.max_step_halvings == 0

    def _run_python(self, rows: np.ndarray, switches: dict) -> None:
        s = self.scenario
        sampled = s.coupling == "sampled"
        for k in range(s.steps):
            switched = k in switches
            if switched:
                self._switch_plan(switches[k])
            self._advance(k, 1, s.max_step_halvings, inputs_set=not switched)
            if sampled:  # the inputs at t_{k+1}: recorded now, used by step k + 1
                self._propagate(self._time(k + 1, 1))
            self._record(rows, k + 1)
            if self.progress is not None:
                self.progress((k + 1) / s.steps)

    def _run_native(self, rows: np.ndarray, switches: dict) -> None:
        """The stepping loop in native calls, split at plan switches and for progress."""
        s, k = self.scenario, 0
        chunk = max(1, s.steps // 100) if self.progress is not None else s.steps
        while k < s.steps:
            switched = k in switches
            if switched:
                self._switch_plan(switches[k])
            stop = min([b for b in switches if b > k] + [s.steps, k + chunk])
            self.kernel.run_steps(k, stop, rows, propagate_first=switched)
            k = stop
            if self.progress is not None:
                self.progress(k / s.steps)

    def run(self) -> Result:
        s = self.scenario
        self.fmus = {}
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
            self._build_kernel()
            for alias in s.order:  # consistent inputs at the start time, in order
                self._set_inputs(alias)
            for alias in s.order:
                self.fmus[alias].exit_initialization()
            if s.coupling == "sampled":  # the slopes of the first step (values are set)
                self._propagate(s.start_time)
            self._record(rows, 0)
            loop_started = time.perf_counter()
            if hasattr(self.kernel, "run_steps"):
                self._run_native(rows, switches)
            else:
                self._run_python(rows, switches)
            self.loop_seconds = time.perf_counter() - loop_started
        finally:
            self.kernel = None
            for fmu in self.fmus.values():
                self.close_fmu(fmu)
        times = [self._time(k, 1) for k in range(s.steps + 1)]
        order = [str(sig) for sig in self.recorded]
        columns = {name: rows[:, j].tolist() for j, name in enumerate(names)}
        return Result(names=order, time=times, columns={n: columns[n] for n in order},
                      discards=self.discards)


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
