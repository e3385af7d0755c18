"""Checks of a parsed scenario against its FMUs before any simulation: every parameter
against the variable's type and range, every connection and recorded signal against the
variables, and every FMU initialised alone with its parameters (a parameter set the FMU
refuses is reported with the FMU's own reason, blamed on the scenario's field)."""

from __future__ import annotations

from collections.abc import Callable
from fractions import Fraction
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING

from .errors import CosimError, ScenarioError
from .instances import give_back, open_instance
from .fmu_check import check_value, describe, missing
from .limits import check_measurable

if TYPE_CHECKING:
    from .scenario import Scenario


#: The types a connection passes (FMI 3.0 Float64 and Int32 read as Real and Integer).
PASSED = ("Real", "Integer", "Enumeration", "Boolean")


def initialize_alone(path: Path, alias: str, parameters: dict, field: str,
                     initializing: Callable | None = None) -> None:
    """Sets `parameters` on an instance of the FMU (robofmu.instances: the one the run
    will use), initialises it (calling `initializing(instance)` in Initialization Mode)
    and reads its outputs; ScenarioError with the FMU's reason when it refuses."""
    md = describe(path, f"fmus.{alias}")
    outputs = tuple(v.name for v in md.modelVariables if v.causality == "output"
                    and v.type in ("Real", "Integer", "Boolean"))
    try:
        fmu = open_instance(alias, Path(path), 0.0, 1.0)
    except CosimError as e:
        raise ScenarioError(f"field 'fmus.{alias}': the FMU cannot be instantiated: "
                            f"{_reason(e)}; rebuild it (bash scripts/build-fmus.sh)") from None
    try:
        for name, value in parameters.items():
            fmu.set_value(name, value)
        fmu.enter_initialization()
        if initializing is not None:
            initializing(fmu)
        fmu.exit_initialization()
        fmu.get_values(outputs)
    except CosimError as e:
        fmu.close()
        raise ScenarioError(f"field '{field}': {alias} refuses these parameters: "
                            f"{_reason(e)}; change them") from None
    except BaseException:
        fmu.close()
        raise
    give_back(fmu)


def clock_of(md, alias: str, period: float):
    """The one periodic input clock of the FMU of `alias` (scalar view `md`) that
    sample_period.ALIAS = `period` ticks, or ScenarioError naming that field."""
    where = f"field 'sample_period.{alias}'"
    clocks = [v for v, clock in getattr(md, "clocked", {}).values() if v.name == clock]
    inputs = [v for v in clocks if v.causality == "input"
              and v.intervalVariability in ("constant", "fixed", "tunable")]
    if md.fmiVersion != "3.0" or not clocks:
        raise ScenarioError(f"{where}: {alias} declares no clock (an FMI {md.fmiVersion} FMU "
                            f"without one); remove {where[7:-1]} or name an FMI 3.0 FMU with "
                            "a periodic input clock, such as fmi3/ComputedTorque")
    if len(inputs) != 1 or len(clocks) != 1:
        raise ScenarioError(f"{where}: {alias} declares the clocks "
                            f"{', '.join(v.name for v in clocks)}; the master ticks an FMU of "
                            "one periodic input clock only")
    if not md.coSimulation.hasEventMode:
        raise ScenarioError(f"{where}: {alias} declares no Event Mode in co-simulation "
                            "(hasEventMode), where the master ticks its clock; name an FMU "
                            "that has one")
    clock = inputs[0]
    if clock.intervalDecimal is not None and float(clock.intervalDecimal) != period:
        raise ScenarioError(f"{where}: {alias}.{clock.name} ticks every "
                            f"{float(clock.intervalDecimal):g} s (its intervalDecimal), not "
                            f"{period:g} s; write sample_period.{alias} = "
                            f"{float(clock.intervalDecimal):g}")
    return clock


def check_interval(fmu, alias: str, clock: str, period: float) -> None:
    """The interval of the instance's clock (Initialization Mode) is sample_period.ALIAS
    = `period` exactly (as fractions where the FMU gives one), else ScenarioError."""
    interval = fmu.interval(clock)
    if isinstance(interval, tuple):
        seconds, same = interval[0] / interval[1], Fraction(*interval) == Fraction(repr(period))
    else:
        seconds = float(interval)
        same = seconds == period
    if not same:
        raise ScenarioError(f"field 'sample_period.{alias}': {alias}.{clock} ticks every "
                            f"{seconds!r} s with the scenario's parameters, not {period!r} s; "
                            f"write sample_period.{alias} = {seconds!r} or set the FMU's "
                            f"period parameter (ours: parameters.{alias}.samplePeriod)")


def check_clock(md, alias: str, period: float) -> dict:
    """The clocked variables of `alias` that a scenario may connect and record when
    its clock ticks (clock_of checks the clock)."""
    clock = clock_of(md, alias, period).name
    return {name: v for name, (v, c) in md.clocked.items() if c == clock and name != clock}


def _reason(error: Exception) -> str:
    """The FMU's log line of an FmuError, without the '[category] fmi2Call: ' prefix and
    the plant's 'invalid parameters: ' preamble."""
    text = str(error).rsplit("] ", 1)[-1]
    if text.startswith("fmi") and ": " in text:
        text = text.split(": ", 1)[1]
    return text.removeprefix("invalid parameters: ")


def check(scenario: Scenario, fields: dict | None = None) -> None:
    """All checks above; `fields` maps an alias to the scenario field its parameters
    come from (default 'parameters.ALIAS')."""
    fields = fields or {}
    check_measurable(scenario)
    mds = {alias: describe(path, f"fmus.{alias}") for alias, path in scenario.fmus.items()}
    for alias, values in scenario.parameters.items():
        where = fields.get(alias, f"parameters.{alias}")
        for name, value in values.items():
            values[name] = check_value(mds[alias], alias, name, value, f"{where}.{name}")
    for k, switch in enumerate(scenario.schedule):
        for name, value in switch.parameters.items():
            switch.parameters[name] = check_value(
                mds[switch.alias], switch.alias, name, value,
                f"plan_switches[{k}].parameters.{name}")
    names = {alias: {v.name: v for v in md.modelVariables} for alias, md in mds.items()}
    for alias in scenario.model_exchange:
        if mds[alias].fmiVersion != "3.0" or mds[alias].modelExchange is None:
            raise ScenarioError(f"field 'model_exchange.{alias}': {alias} is no FMI 3.0 FMU "
                                "with Model Exchange; name one (such as fmi3/Pss3Plant) or "
                                f"remove model_exchange.{alias}")
    for alias, period in scenario.sample_period.items():  # ticked: its clocked outputs run
        names[alias].update(check_clock(mds[alias], alias, period))
    def absent(signal) -> str:
        return missing(mds[signal.alias], signal.alias, signal.variable,
                       signal.alias in scenario.sample_period)

    for k, c in enumerate(scenario.connections):
        for side, signal in (("from", c.source), ("to", c.target)):
            v = names[signal.alias].get(signal.variable)
            if v is None:
                raise ScenarioError(f"field 'connections[{k}].{side}': "
                                    f"{absent(signal)}")
            if v.type not in PASSED:
                raise ScenarioError(f"field 'connections[{k}].{side}': {signal} is of type "
                                    f"{v.type}, which the master cannot pass; connect a Real "
                                    "(FMI 3.0: Float64), Integer (Int32) or Boolean variable")
            if side == "to" and v.causality != "input":
                raise ScenarioError(f"field 'connections[{k}].to': {signal} is not an input "
                                    f"({v.causality}); connect to an input")
    for k, signal in enumerate(scenario.record):
        if signal.variable not in names[signal.alias]:
            raise ScenarioError(f"field 'record[{k}]': "
                                f"{absent(signal)}")
    for alias in scenario.order:
        initializing = None
        if alias in scenario.sample_period:  # the FMU's clock interval: the scenario's
            tick = scenario.sample_period[alias]
            initializing = partial(check_interval, alias=alias, period=tick,
                                   clock=clock_of(mds[alias], alias, tick).name)
        initialize_alone(scenario.fmus[alias], alias, scenario.parameters.get(alias, {}),
                         fields.get(alias, f"parameters.{alias}"), initializing)
    if scenario.sample_period or scenario.model_exchange:
        return  # robofmu.clocked's runs hold their inputs: no input derivatives to probe
    from .master import warm_probes  # lazily: the master reads scenarios (this module's user)
    warm_probes(scenario)
