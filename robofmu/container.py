"""A scenario as one container FMU, built and run by a second FMI implementation: the
fmu-manipulation-toolbox (PyPI), whose compiled runtime loads and steps the embedded FMUs.

``cosim container SCENARIO --out X.fmu`` writes a co-simulation FMU 2.0 that
holds the scenario's FMUs, connections, start values (the scenario's parameters),
communication step and start/stop time (its default experiment), so that
``fmpy simulate X.fmu`` with no options runs the closed loop.

Coupling: the toolbox's "sequential" mode. Each internal step, every embedded FMU in turn
takes its inputs from the container's buffer, steps, and writes its outputs back. The
FMUs whose connected outputs depend on their inputs (direct feedthrough: the PID) step
last, the others (planner, plant) first. The plant then steps with the PID output
computed from the planner's and the plant's values at the start of the step, as with our
master's "sampled" coupling; the only difference is that the PID integrates over
[t, t + h] the error sampled at t + h instead of t (see tests/python/test_container.py for
what that changes). The toolbox's default "parallel" mode is a Jacobi scheme: the plant
would step with a PID output computed from inputs one step old. The container has no
rollback: the scenario's coupling and max_step_halvings are our master's options only.

The connected signals are the container's locals, named "alias.variable" as in our
master's results (the toolbox lower-cases the alias); every output of the embedded FMUs
is also a container output, under its variable name (prefixed with the FMU alias where two FMUs share a name).
"""

from __future__ import annotations

import argparse
import logging
import re
import shutil
import sys
import tempfile
from pathlib import Path

from fmpy import read_model_description

from .errors import output_path
from .run import fmu_dir
from .scenario import Scenario, load_scenario
from .ssp import no_schedule

TOOLBOX_LOGGER = "fmu_manipulation_toolbox"


def feedthrough_aliases(scenario: Scenario) -> set[str]:
    """FMUs with a connected output that depends on one of their inputs, by the
    modelDescription's ModelStructure (no `dependencies` attribute: on every input)."""
    connected = {(c.source.alias, c.source.variable) for c in scenario.connections}
    result = set()
    for alias, path in scenario.fmus.items():
        md = read_model_description(str(path))
        has_inputs = any(v.causality == "input" for v in md.modelVariables)
        for output in md.outputs:
            if (alias, output.variable.name) not in connected:
                continue
            dependencies = output.dependencies
            if (has_inputs and dependencies is None) or any(
                    d.causality == "input" for d in dependencies or []):
                result.add(alias)
    return result


def stepping_order(scenario: Scenario) -> list[str]:
    """The scenario's order with the feedthrough FMUs moved to the end."""
    last = feedthrough_aliases(scenario)
    return ([a for a in scenario.order if a not in last]
            + [a for a in scenario.order if a in last])


def start_value_text(value) -> str | bool:
    """A scenario parameter in the form the toolbox's add_start_value takes."""
    if isinstance(value, bool):
        return value
    return repr(float(value)) if isinstance(value, float) else str(value)


def exposed_ports(scenario: Scenario) -> dict[str, dict[tuple[str, str], str]]:
    """The container's ports: every output of the embedded FMUs and every input that no
    connection feeds, by causality, (alias, variable) -> name: the variable's name, or
    "alias_variable" where another FMU has a port of the same name."""
    fed = {(c.target.alias, c.target.variable) for c in scenario.connections}
    ports: dict[str, list] = {"output": [], "input": []}
    for alias, path in scenario.fmus.items():
        for v in read_model_description(str(path)).modelVariables:
            if v.causality == "output" or (v.causality == "input" and (alias, v.name) not in fed):
                ports[v.causality].append((alias, v.name))
    count: dict[str, int] = {}
    for _, name in ports["output"] + ports["input"]:
        count[name] = count.get(name, 0) + 1
    return {causality: {(alias, name): name if count[name] == 1 else f"{alias}_{name}"
                        for alias, name in found}
            for causality, found in ports.items()}


def _describe(container, scenario: Scenario) -> None:
    for alias in stepping_order(scenario):
        container.get_fmu(f"{alias}.fmu")
    for c in scenario.connections:
        container.add_link(f"{c.source.alias}.fmu", c.source.variable,
                           f"{c.target.alias}.fmu", c.target.variable)
    ports = exposed_ports(scenario)
    for (alias, variable), name in ports["output"].items():
        container.add_output(f"{alias}.fmu", variable, name)
    # The inputs that no connection feeds (the plant's disturbance torque, ...) are the
    # container's inputs, with the embedded FMU's start value.
    for (alias, variable), name in ports["input"].items():
        container.add_input(name, f"{alias}.fmu", variable)
    for alias, values in scenario.parameters.items():
        for variable, value in values.items():
            container.add_start_value(f"{alias}.fmu", variable, start_value_text(value))
    container.add_implicit_rule(auto_input=False, auto_output=False, auto_link=False)
    container.start_time = scenario.start_time
    container.stop_time = scenario.stop_time


class ContainerError(RuntimeError):
    """The toolbox refused the description or logged an error while building."""


class _Collector(logging.Handler):
    def __init__(self):
        super().__init__(logging.WARNING)
        self.records: list[logging.LogRecord] = []

    def emit(self, record):
        self.records.append(record)


NO_SCHEDULE = ("a multi-segment motion has no container form (the container has no plan "
               "switches); use two waypoints")


def check_container_path(out: Path, option: str = "path") -> None:
    """ContainerError (naming `option`, the argument that gave `out`) unless `out` can be
    the container: a file whose name ends with .fmu."""
    if out.suffix != ".fmu" or out.is_dir():
        raise ContainerError(f"{option}: {out}: the container is a file whose name ends "
                             "with .fmu; name such a file")


def build_container(scenario: Scenario, out: Path, source: Path | None = None) -> list[str]:
    """Writes the scenario (read from the file `source`, if any: named in the message of
    a scenario that has no container form) as a container FMU at `out` (a .fmu path).
    Returns the toolbox's warnings; raises ContainerError on any error it logs."""
    no_schedule(scenario, source, NO_SCHEDULE)
    try:  # lazy: an optional dependency (the wheel's extra 'container'), 0.04 s to import
        from fmu_manipulation_toolbox.container import FMUContainer, FMUContainerError
    except ImportError:
        raise ContainerError("cosim container needs fmu-manipulation-toolbox, which the wheel "
                             "leaves optional; pip install 'robofmu[container]'") from None
    out = Path(out)
    check_container_path(out)
    logger = logging.getLogger(TOOLBOX_LOGGER)
    collector, propagate = _Collector(), logger.propagate
    logger.addHandler(collector)
    logger.propagate = False
    try:
        with tempfile.TemporaryDirectory(prefix="cosim-container-") as scratch:
            work = Path(scratch)
            # Embedded FMUs are named after their file: one file per alias, so that the
            # container's variables read "alias.variable".
            for alias, path in scenario.fmus.items():
                shutil.copyfile(path, work / f"{alias}.fmu")
            container = FMUContainer(re.sub(r"\W", "_", out.stem), work)
            _describe(container, scenario)
            container.make_fmu(out.name, step_size=scenario.step_size, sequential=True)
            errors = [r.getMessage() for r in collector.records if r.levelno >= logging.ERROR]
            if errors:
                raise ContainerError("; ".join(errors))
            out.parent.mkdir(parents=True, exist_ok=True)
            shutil.move(str(work / out.name), out)
    except FMUContainerError as e:
        raise ContainerError(str(e)) from e
    finally:
        logger.removeHandler(collector)
        logger.propagate = propagate
    return [r.getMessage() for r in collector.records if r.levelno < logging.ERROR]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """``cosim container SCENARIO --out X.fmu``."""
    parser.add_argument("scenario", type=Path, help="scenario file (.toml or .json)")
    parser.add_argument("--out", type=output_path, required=True, help="container FMU to write (.fmu)")
    parser.add_argument("--fmu-dir", type=Path, help="find the FMUs by file name here")


def run(args: argparse.Namespace) -> int:
    check_container_path(args.out, "--out")
    scenario = load_scenario(args.scenario, fmu_dir(args.fmu_dir))
    warnings = build_container(scenario, args.out, args.scenario)
    for line in warnings:
        print(f"fmu-manipulation-toolbox: {line}", file=sys.stderr)
    print(f"{args.out}: {scenario.name} as a container FMU ({', '.join(stepping_order(scenario))} "
          f"stepped in sequence every {scenario.step_size} s); run it with: fmpy simulate {args.out}")
    return 0
