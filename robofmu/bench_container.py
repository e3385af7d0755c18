"""Wall time per communication step of one scenario three ways, measured in one run:
the container FMU (fmu-manipulation-toolbox's runtime steps the three FMUs; FMPy calls
the container once per step), our master, and a minimal FMPy loop over the same FMUs
(sampled coupling, no recording, no checks). Each is a whole run, FMU extraction and
instantiation included; the median of several runs. Used by ``python -m robofmu.bench``.
"""

from __future__ import annotations

import shutil
import statistics
import tempfile
import time
from pathlib import Path

from fmpy import calloc, extract, free, read_model_description
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE)

from .container import build_container, exposed_ports
from .master import Master
from .scenario import Scenario, load_scenario

_SETTERS = {"Real": "setReal", "Integer": "setInteger", "Boolean": "setBoolean"}
_QUIET = None  # FMI callbacks with a logger that drops the messages, created once


def _quiet_callbacks():
    global _QUIET
    if _QUIET is None:
        _QUIET = fmi2CallbackFunctions()
        _QUIET.logger = fmi2CallbackLoggerTYPE(lambda *_: None)
        _QUIET.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        _QUIET.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
    return _QUIET


def _slave(path: Path, name: str, scenario: Scenario):
    md = read_model_description(str(path))
    unzip = extract(str(path))
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzip,
                    modelIdentifier=md.coSimulation.modelIdentifier, instanceName=name)
    fmu.instantiate(callbacks=_quiet_callbacks())
    fmu.setupExperiment(startTime=scenario.start_time, stopTime=scenario.stop_time)
    variables = {v.name: (v.valueReference, v.type) for v in md.modelVariables}
    return fmu, unzip, variables


def _close(fmu, unzip) -> None:
    fmu.terminate()
    fmu.freeInstance()
    shutil.rmtree(unzip, ignore_errors=True)


def minimal_run(scenario: Scenario) -> dict[str, float]:
    """The loop with nothing but FMPy's FMI calls: parameters, initialisation, then per
    step all inputs from their sources' outputs at t_k, then every FMU steps. Returns the
    connected outputs at the stop time, "alias.variable" -> value."""
    slaves = {a: _slave(p, a, scenario) for a, p in scenario.fmus.items()}
    for alias, values in scenario.parameters.items():
        fmu, _, variables = slaves[alias]
        for name, value in values.items():
            vr, kind = variables[name]
            getattr(fmu, _SETTERS[kind])([vr], [value])
    wires = [(slaves[c.source.alias][0], slaves[c.source.alias][2][c.source.variable][0],
              slaves[c.target.alias][0], slaves[c.target.alias][2][c.target.variable][0])
             for c in scenario.connections]

    def propagate():
        for source, out_vr, target, in_vr in wires:
            target.setReal([in_vr], source.getReal([out_vr]))

    order = [slaves[a][0] for a in scenario.order]
    for fmu in order:
        fmu.enterInitializationMode()
    propagate()
    for fmu in order:
        fmu.exitInitializationMode()
    h = scenario.step_size
    for k in range(scenario.steps):
        propagate()
        for fmu in order:
            fmu.doStep(currentCommunicationPoint=scenario.start_time + k * h,
                       communicationStepSize=h)
    final = {f"{c.source.alias}.{c.source.variable}":
             slaves[c.source.alias][0].getReal([slaves[c.source.alias][2][c.source.variable][0]])[0]
             for c in scenario.connections}
    for fmu, unzip, _ in slaves.values():
        _close(fmu, unzip)
    return final


def container_run(scenario: Scenario, container: Path) -> dict[str, float]:
    """The container stepped by FMPy once per communication step; the signals our
    master records are read after every step. Returns them at the stop time, by the
    container's variable names."""
    fmu, unzip, variables = _slave(container, "container", scenario)
    outputs = exposed_ports(scenario)["output"]
    sources = {(c.source.alias, c.source.variable) for c in scenario.connections}
    recorded = [f"{a}.{v}" if (a, v) in sources else outputs[(a, v)] for a, v in
                dict.fromkeys([(c.source.alias, c.source.variable) for c in scenario.connections]
                              + [(s.alias, s.variable) for s in scenario.record])]
    vrs = [variables[name][0] for name in recorded]
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    h = scenario.step_size
    values = []
    for k in range(scenario.steps):
        fmu.doStep(currentCommunicationPoint=scenario.start_time + k * h, communicationStepSize=h)
        values = fmu.getReal(vrs)
    _close(fmu, unzip)
    return dict(zip(recorded, values))


def _medians_per_step(runs_by_name, scenario: Scenario, runs: int) -> dict[str, float]:
    """Median wall time per step of each run; the runs are interleaved (one of each per
    round) so that a change of the machine's load affects them alike."""
    walls: dict[str, list[float]] = {name: [] for name in runs_by_name}
    for _ in range(runs):
        for name, run in runs_by_name.items():
            started = time.perf_counter()
            run()
            walls[name].append(time.perf_counter() - started)
    return {name: statistics.median(w) / scenario.steps for name, w in walls.items()}


def container_lines(scenario: Scenario, runs: int = 5) -> list[str]:
    """Benchmark lines: container, master and minimal loop, per step, with the ratios."""
    with tempfile.TemporaryDirectory(prefix="cosim-bench-") as work:
        container = Path(work) / f"{scenario.name}.fmu"
        build_container(scenario, container)
        per_step = _medians_per_step({
            "container": lambda: container_run(scenario, container),
            "master": lambda: Master(scenario).run(),
            "minimal": lambda: minimal_run(scenario),
        }, scenario, runs)
    us = {k: 1e6 * v for k, v in per_step.items()}
    return [
        f"{scenario.name}: container FMU (toolbox runtime, sequential) {us['container']:.0f} us "
        f"per step, master {us['master']:.0f} us, minimal FMPy loop {us['minimal']:.0f} us "
        f"(medians of {runs} interleaved whole runs of {scenario.steps} steps)",
        f"container/master ratio: {per_step['container'] / per_step['master']:.2f}; "
        f"container/minimal ratio: {per_step['container'] / per_step['minimal']:.2f}",
    ]


def print_container_lines(scenario_file: Path, runs: int = 5) -> None:
    """Prints the lines for the scenario in `scenario_file` (its coupling order, inputs
    held as the container holds them)."""
    scenario = load_scenario(scenario_file)
    scenario.input_extrapolation = "hold"
    for line in container_lines(scenario, runs):
        print(line, flush=True)
