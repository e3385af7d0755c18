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
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .fmu_check import describe
from .instances import close_all, give_back, open_instance
from .loop import Loop
from .scenario import Scenario, ScenarioError, Signal, extrapolation_order
from .slopes import History, accepted, served


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


@dataclass
class Arrays:
    """A run's recorded signals as numpy arrays (what Result holds as lists)."""

    names: list[str]
    time: np.ndarray
    columns: dict[str, np.ndarray]
    discards: list[str]


def _open_fmu(alias, path, scenario):
    return open_instance(alias, path, scenario.start_time, scenario.stop_time)


def _close_fmu(fmu) -> None:
    give_back(fmu)  # robofmu.instances: the next run or check resets it


class Master:
    """Runs one scenario. ``open_fmu(alias, path, scenario)`` creates the instances
    (FMPy by default; tests pass stand-ins with the same methods) and
    ``close_fmu(instance)`` ends them (a sweep worker's pool keeps them for the next
    run). The steps are made by the one stepping loop, robofmu.loop (native code)."""

    def __init__(self, scenario: Scenario, open_fmu: Callable = _open_fmu,
                 progress: Callable[[float], None] | None = None,
                 close_fmu: Callable = _close_fmu, loops: dict | None = None):
        self.scenario = scenario
        self.loops = loops  # a sweep worker's prepared loop, reused (_prepared_loop)
        self.open_fmu = open_fmu
        self.close_fmu = close_fmu
        self.progress = progress
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

    def _slope_pairs(self) -> dict[str, list]:
        """Per target FMU, the connections that pass input derivatives (orders 1..n,
        n from input_extrapolation) where the target interpolates inputs
        (canInterpolateInputs), each signal at the highest order that the scenario asks
        for and the target takes: the source's output derivatives where it serves them
        (at most the order it serves), else the derivatives through the source's last
        values (History)."""
        pairs: dict[str, list] = {alias: [] for alias in self.scenario.order}
        order = extrapolation_order(self.scenario.input_extrapolation)
        if order == 0:
            return pairs
        for alias in self.scenario.order:
            if not getattr(self.fmus[alias], "can_interpolate_inputs", False):
                continue
            for source, variables, inputs in self.inputs[alias]:
                pairs[alias] += self._split(alias, source, variables, inputs, order)
        return pairs

    def _split(self, alias, source, variables, inputs, order) -> list:
        """(source, variables, inputs, None, k) for the served derivatives of order
        1..k, (..., History, k) for the rest of the Real variables of one connected
        pair, one entry per kind and order."""
        fmu, target = self.fmus[source], self.fmus[alias]
        is_real = getattr(fmu, "is_real", lambda _name: True)  # test doubles: all Real
        real = [k for k, v in enumerate(variables) if is_real(v)]
        names = tuple(variables[k] for k in real)
        taken = getattr(target, "max_input_derivative_order", None)
        if taken is None:  # FMI 2.0 declares none: ask the FMU
            taken = accepted(str(self.scenario.fmus[alias]), tuple(inputs[k] for k in real),
                             order)
            taken = [taken[inputs[k]] for k in real]
        else:
            taken = [min(order, taken)] * len(real)
        served_order = (served(str(self.scenario.fmus[source]), names, order)
                        if getattr(fmu, "max_output_derivative_order", 0) >= 1 else {})
        kinds: dict[tuple, list[int]] = {}
        for k, want in zip(real, taken):
            own = min(want, served_order.get(variables[k], 0))
            if want > 0:
                kinds.setdefault((own == 0, own or want), []).append(k)
        parts = []
        for (history, n), keep in sorted(kinds.items()):  # the served ones first
            parts.append((source, tuple(variables[k] for k in keep),
                          tuple(inputs[k] for k in keep),
                          History(n, len(keep)) if history else None, n))
        return parts

    def _prepared_loop(self) -> Loop:
        """The stepping loop's plan over this run's instances: the one `loops` keeps
        when the last run had the same instances, couplings, recorded signals and
        experiment and no input derivatives (a sweep's runs differ in parameter values
        only), else a new one (kept there for the next run)."""
        s = self.scenario
        if self.loops is None or any(self.slopes.values()):
            return Loop(self.fmus, self.inputs, self.recorded_by_fmu, s.order, self.slopes, s)
        key = (tuple((a, id(f)) for a, f in self.fmus.items()), repr(self.inputs),
               repr(self.recorded_by_fmu), tuple(s.order), s.coupling, s.start_time,
               s.step_size, s.max_step_halvings)
        loop = self.loops.get(key)
        if loop is not None and all(loop.fmus[a] is f for a, f in self.fmus.items()):
            loop.renew()
            return loop
        loop = Loop(self.fmus, self.inputs, self.recorded_by_fmu, s.order, self.slopes, s)
        self.loops.clear()
        self.loops[key] = loop
        return loop

    def _start_up(self, rows: np.ndarray, loop: Loop) -> None:
        """The multistep start-up of the derivatives through past values (History) of
        order 2: the first steps would extrapolate with a lower order (no past points
        yet), and with sampled coupling their error dominates a run's (the regulation
        at 1 ms: 4.6e-5 rad without, 1.4e-6 rad with). Two passes of the first `order`
        steps from the initial state (their rows are written again later), each ending
        with every FMU rolled back and the histories seeded with the points before t_0
        of the polynomial through what the pass saw at t_0..t_order (the second pass
        starts from the first one's seed). Needs FMU states (canGetAndSetFMUstate) of
        every FMU and no plan switch in those steps; otherwise the start is of lower
        order."""
        s = self.scenario
        histories = [p[3] for pairs in self.slopes.values() for p in pairs
                     if p[3] is not None and p[3].order >= 2]
        order = max((h.order for h in histories), default=0)
        if (not histories or s.steps <= order
                or any(switch.step <= order for switch in s.schedule)
                or not all(getattr(f, "can_get_state", False) for f in self.fmus.values())):
            return
        discards = len(loop.discards)
        for _ in range(2):
            points = [[h.past[0].copy()] for h in histories]
            saved = {a: f.get_state() for a, f in self.fmus.items()}
            try:
                for k in range(order):
                    loop.run_steps(k, k + 1, rows, False)
                    for h, p in zip(histories, points):
                        p.append(h.past[0].copy())
                for alias, state in saved.items():
                    self.fmus[alias].set_state(state)
            finally:
                for alias, state in saved.items():
                    self.fmus[alias].free_state(state)
            for h, p in zip(histories, points):
                h.seed(s.start_time, s.step_size, p)
            loop.propagate(s.start_time)
        del loop.discards[discards:]

    def _initialize(self, alias: str, parameters: dict) -> None:
        fmu = self.fmus[alias]
        set_each = getattr(fmu, "set_each", None)  # robofmu.fmi2: without FMPy's wrappers
        if set_each is not None:
            set_each(list(parameters), list(parameters.values()))
            return
        for name, value in parameters.items():
            fmu.set_value(name, value)

    def _switch_plan(self, switch) -> None:
        """A plan switch of a multi-segment motion: the (stateless) FMU is reset and
        initialised with the next segment's parameters, its experiment starting now."""
        fmu = self.fmus[switch.alias]
        fmu.reset(self._time(switch.step, 1), self.scenario.stop_time)
        self._initialize(switch.alias, switch.parameters)
        fmu.enter_initialization()
        fmu.exit_initialization()

    def _run_steps(self, rows: np.ndarray, switches: dict, loop: Loop) -> None:
        """The stepping loop (robofmu.loop), split at plan switches and for progress."""
        s, k = self.scenario, 0
        chunk = max(1, s.steps // 100) if self.progress is not None else s.steps
        while k < s.steps:
            switched = k in switches
            if switched:
                self._switch_plan(switches[k])
            stop = min([b for b in switches if b > k] + [s.steps, k + chunk])
            loop.run_steps(k, stop, rows, propagate_first=switched)
            k = stop
            if self.progress is not None:
                self.progress(k / s.steps)

    def run(self) -> Result:
        a = self.run_arrays()
        return Result(names=a.names, time=a.time.tolist(),
                      columns={n: a.columns[n].tolist() for n in a.names}, discards=a.discards)

    def run_arrays(self, contiguous: bool = True) -> Arrays:
        """The run, its signals as arrays: one contiguous array per signal, or (not
        `contiguous`: a sweep's run, which reads them once) the columns of the rows."""
        s = self.scenario
        if s.sample_period or s.model_exchange:  # the Python loop of robofmu.clocked
            from .clocked import ClockedRun
            return ClockedRun(self).run(contiguous)
        self.fmus = {}
        switches = {switch.step: switch for switch in s.schedule}
        try:
            for alias in s.order:
                self.fmus[alias] = self.open_fmu(alias, s.fmus[alias], s)
            for alias, values in s.parameters.items():
                self._initialize(alias, values)
            for alias in s.order:
                self.fmus[alias].enter_initialization()
            self.slopes = self._slope_pairs()
            loop = self._prepared_loop()
            names = [f"{alias}.{v}" for alias, v in loop.columns]
            rows = np.empty((s.steps + 1, len(names)))
            for index in range(len(s.order)):  # consistent inputs at the start, in order
                loop.set_inputs(index, s.start_time)
            for alias in s.order:
                self.fmus[alias].exit_initialization()
            if s.coupling == "sampled":  # the slopes of the first step (values are set)
                loop.propagate(s.start_time)
                self._start_up(rows, loop)
            loop.record(rows[0], s.start_time)
            loop_started = time.perf_counter()
            self._run_steps(rows, switches, loop)
            self.loop_seconds = time.perf_counter() - loop_started
            self.discards = loop.discards
        except BaseException:
            if self.close_fmu is _close_fmu:  # after a failed run nothing stays shared
                for fmu in self.fmus.values():
                    fmu.close()
                self.fmus = {}
                close_all()
            raise
        finally:
            for fmu in self.fmus.values():
                self.close_fmu(fmu)
        # t_k = start + k h as _time computes it (k h / 1 is k h), for every k at once.
        times = s.start_time + np.arange(s.steps + 1) * s.step_size
        order = [str(sig) for sig in self.recorded]
        columns = dict(zip(names, np.ascontiguousarray(rows.T) if contiguous else rows.T))
        return Arrays(names=order, time=times, columns={n: columns[n] for n in order},
                      discards=self.discards)


def run_scenario(scenario: Scenario, *, fmi3: bool = False,
                 progress: Callable[[float], None] | None = None,
                 option: str = "fmi3") -> Result:
    """One run of a validated scenario (what ``cosim run`` makes): with `fmi3`, of the
    FMI 3.0 builds of its FMUs (dist/fmi3/<Model>.fmu beside each), ScenarioError
    naming `option` (the argument that asked for them) when one is missing. CosimError
    as the master raises it when the run fails."""
    return _master(scenario, fmi3, progress, option).run()


def run_arrays(scenario: Scenario, *, fmi3: bool = False,
               progress: Callable[[float], None] | None = None,
               option: str = "fmi3") -> Arrays:
    """As run_scenario, the signals as numpy arrays (what robofmu.simulate makes)."""
    return _master(scenario, fmi3, progress, option).run_arrays()


def _master(scenario: Scenario, fmi3: bool, progress: Callable[[float], None] | None,
            option: str) -> Master:
    from .fmi3 import fmi3_path, is_fmi3, open_fmi3  # lazily: FMPy's FMI 3.0 layer
    if not fmi3:
        return Master(scenario, progress=progress)
    for alias, path in scenario.fmus.items():
        if not is_fmi3(path) and not fmi3_path(path).is_file():
            raise ScenarioError(f"{option}: {fmi3_path(path)} (the FMI 3.0 build of "
                                f"fmus.{alias}) does not exist; build it with bash "
                                f"scripts/build-fmus.sh or run without {option}")
    return Master(scenario, open_fmu=open_fmi3, progress=progress)


class _Described:
    """What Master._slope_pairs reads of an FMI 2.0 instance, from its model description."""

    def __init__(self, path: Path):
        md = describe(path, "fmus")
        self.variables = {v.name: v for v in md.modelVariables}
        self.can_interpolate_inputs = bool(md.coSimulation.canInterpolateInputs)
        self.max_output_derivative_order = int(md.coSimulation.maxOutputDerivativeOrder or 0)

    def is_real(self, name: str) -> bool:
        return self.variables[name].type == "Real"


def warm_probes(scenario: Scenario) -> None:
    """Makes now the input-derivative probes that the first run of `scenario` would make
    (slopes.accepted and served, cached per FMU file), while no instance is held: they
    borrow the scenario's shared instances (robofmu.instances) instead of instantiating
    the FMUs a second time during the run."""
    master = Master(scenario)
    master.fmus = {alias: _Described(path) for alias, path in scenario.fmus.items()}
    master._slope_pairs()


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
