"""Loops written directly on FMPy's FMI 2.0 Co-Simulation API (not on robofmu.master), the
second implementation the importers of test_importers_*.py are compared with. They step
on the importer's own time grid (GRIDS): libcosim counts integer nanoseconds and passes
t_k = (k h_ns) / 1e9 and t_{k+1} - t_k; ecos passes h itself and accumulates t. The
step size's last bit matters: where it exceeds 1 ms by one ulp (as libcosim's and FMPy
simulate_fmu's differences do) the plant's integrator (maxStep 1 ms) takes two substeps
instead of one, a difference of up to 4e-5 rad/s in thetaDot (within the integrator's
tolerance, far above 1e-12).

run_jacobi: the closed loop of a scenario with the Jacobi coupling that libcosim's and ecos's
fixed-step algorithms use, written directly on FMPy's FMI 2.0 Co-Simulation API (not on
robofmu.master): the second implementation the importers are compared with.

Initialization: every FMU gets its parameters, enters initialization mode, then the
connections are propagated in the scenario's order (inputs at the start time equal the
sources' outputs there) and every FMU leaves initialization mode. Step k: every FMU steps
from t_k to t_k + h with the inputs it holds (its sources' outputs at t_k, computed when
those sources finished the previous step), then every connection is transferred. So an
FMU with direct feedthrough (the PID) steps with inputs one step old: u over
[t_k, t_k + h] is the PID's answer for the inputs of t_{k-1}.
"""

from __future__ import annotations

import shutil

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

SETTERS = {"Real": "setReal", "Integer": "setInteger", "Boolean": "setBoolean",
           "Enumeration": "setInteger"}


class Slave:
    def __init__(self, alias: str, path):
        md = read_model_description(str(path))
        self.variables = {v.name: v for v in md.modelVariables}
        self.unzipped = extract(str(path))
        self.fmu = FMU2Slave(guid=md.guid, unzipDirectory=self.unzipped,
                             modelIdentifier=md.coSimulation.modelIdentifier,
                             instanceName=alias)
        self.fmu.instantiate()

    def vr(self, name: str) -> int:
        return self.variables[name].valueReference

    def set(self, name: str, value) -> None:
        variable = self.variables[name]
        getattr(self.fmu, SETTERS[variable.type])([variable.valueReference], [value])

    def free(self) -> None:
        self.fmu.terminate()
        self.fmu.freeInstance()
        shutil.rmtree(self.unzipped, ignore_errors=True)


def libcosim_grid(steps: int, h: float) -> list[tuple[float, float]]:
    """(t_k, step size) of libcosim's steps from 0: integer nanoseconds as doubles."""
    nanos = round(h * 1e9)
    times = [k * nanos / 1e9 for k in range(steps + 1)]
    return [(times[k], times[k + 1] - times[k]) for k in range(steps)]


def ecos_grid(steps: int, h: float) -> list[tuple[float, float]]:
    """(t_k, step size) of ecos's steps from 0: h itself, t accumulated."""
    grid, t = [], 0.0
    for _ in range(steps):
        grid.append((t, h))
        t += h
    return grid


GRIDS = {"libcosim": libcosim_grid, "ecos": ecos_grid}


def run_jacobi(scenario, signals: list[str], grid: list[tuple[float, float]],
               exchange=None) -> np.ndarray:
    """Rows (time, *signals) at t_0 .. t_N of the Jacobi loop over `grid` (pairs
    (t_k, step size), from the scenario's start time 0); `signals` are "alias.variable"
    Real outputs. `exchange(links)` passes the values after every step (default
    `transfer`: all read, then all set; `transfer_in_turn`: one connection after the
    other)."""
    exchange = exchange or transfer
    slaves = {alias: Slave(alias, path) for alias, path in scenario.fmus.items()}
    try:
        links = [(slaves[c.source.alias], slaves[c.source.alias].vr(c.source.variable),
                  slaves[c.target.alias], slaves[c.target.alias].vr(c.target.variable))
                 for c in scenario.connections]
        initialize(scenario, slaves, links)
        probes = [(slaves[alias], slaves[alias].vr(name))
                  for alias, name in (s.split(".", 1) for s in signals)]
        rows = np.empty((len(grid) + 1, len(signals) + 1))
        rows[0] = [scenario.start_time] + read(probes)
        for k, (t, h) in enumerate(grid):
            for slave in slaves.values():
                slave.fmu.doStep(currentCommunicationPoint=t, communicationStepSize=h)
            exchange(links)
            rows[k + 1] = [t + h] + read(probes)
        return rows
    finally:
        for slave in slaves.values():
            slave.free()


def initialize(scenario, slaves: dict, links) -> None:
    """Parameters set, initialization mode, connections propagated in the scenario's
    order, initialization mode left."""
    for alias, slave in slaves.items():
        slave.fmu.setupExperiment(startTime=scenario.start_time)
        for name, value in scenario.parameters.get(alias, {}).items():
            slave.set(name, value)
        slave.fmu.enterInitializationMode()
    for alias in scenario.order:
        transfer([link for link in links if link[2] is slaves[alias]])
    for slave in slaves.values():
        slave.fmu.exitInitializationMode()


def transfer(links) -> None:
    """Every connection's source output copied to its target input (Real signals)."""
    values = [source.fmu.getReal([vr])[0] for source, vr, _, _ in links]
    for (_, _, target, vr), value in zip(links, values):
        target.fmu.setReal([vr], [value])


def transfer_in_turn(links) -> None:
    """Each connection's source output copied to its target input before the next is
    read (the container FMU's scheme)."""
    for source, out, target, into in links:
        target.fmu.setReal([into], source.fmu.getReal([out]))


def read(probes) -> list[float]:
    return [slave.fmu.getReal([vr])[0] for slave, vr in probes]


def run_alone(path, outputs: list[str], grid: list[tuple[float, float]],
              start: dict[str, float]) -> np.ndarray:
    """One FMU alone (Real start values `start`, no inputs set afterwards): rows (time,
    *outputs) after each step of `grid` (pairs (t_k, step size) from 0)."""
    slave = Slave("fmu", path)
    try:
        slave.fmu.setupExperiment(startTime=0.0)
        for name, value in start.items():
            slave.set(name, value)
        slave.fmu.enterInitializationMode()
        slave.fmu.exitInitializationMode()
        probes = [(slave, slave.vr(name)) for name in outputs]
        rows = np.empty((len(grid), len(outputs) + 1))
        for k, (t, h) in enumerate(grid):
            slave.fmu.doStep(currentCommunicationPoint=t, communicationStepSize=h)
            rows[k] = [t + h] + read(probes)
        return rows
    finally:
        slave.free()
