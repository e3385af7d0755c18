"""Runs an SSP archive (or one FMU) in libcosim (libcosimpy) and ecos (ecospy), the two
independent SSP importers from PyPI, and returns the trajectories of chosen outputs
after every communication step, in the form tests/python/jacobi.py returns them
(rows: time, *signals; here rows 1..N, after each step)."""

from __future__ import annotations

import numpy as np

PARAMETER_SET = "scenario"  # robofmu.ssp.PARAMETER_SET, the name ecos must be given


def quiet() -> None:
    """Both libraries log every FMI call by default; warnings and errors stay."""
    from ecospy.lib import EcosLib
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    log_output_level(CosimLogLevel.WARNING)
    EcosLib.set_log_level("warn")


def run_libcosim(ssp: str, signals: list[str], steps: int,
                 step_size: float | None = None) -> np.ndarray:
    """libcosim's fixed-step (Jacobi) algorithm; the step size comes from the SSP's
    annotation unless `step_size` (s) is given. libcosim counts time in integer
    nanoseconds."""
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimObserver import CosimObserver
    quiet()
    nanos = None if step_size is None else round(step_size * 1e9)
    execution = CosimExecution.from_ssp_file(ssp, nanos)
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)
    probes = []
    for signal in signals:
        alias, name = signal.split(".", 1)
        index = execution.slave_index_from_instance_name(alias)
        refs = {v.name.decode(): v.reference for v in execution.slave_variables(index)}
        probes.append((index, refs[name]))
    rows = np.empty((steps, len(signals) + 1))
    for k in range(steps):
        if not execution.step(1):
            raise RuntimeError(f"libcosim: step {k} failed")
        rows[k, 0] = execution.status().current_time * 1e-9
        rows[k, 1:] = [observer.last_real_values(i, [r])[0] for i, r in probes]
    return rows


def run_ecos(ssp: str, signals: list[str], steps: int, step_size: float,
             parameter_set: str | None = PARAMETER_SET) -> np.ndarray:
    """ecos's fixed-step (Jacobi) algorithm with `parameter_set` applied at init (ecos
    applies none unless it is named); ecos takes the step size from the caller only."""
    from ecospy.EcosSimulation import EcosSimulation
    quiet()
    ids = [signal.replace(".", "::", 1) for signal in signals]
    rows = np.empty((steps, len(signals) + 1))
    with EcosSimulation(ssp_path=ssp, step_size=step_size) as sim:
        if not sim.init(parameter_set=parameter_set):
            raise RuntimeError("ecos: init failed")
        for k in range(steps):
            rows[k, 0] = sim.step(1)
            rows[k, 1:] = [sim.get_real(i) for i in ids]
        sim.terminate()
    return rows


def run_fmu_libcosim(fmu: str, outputs: list[str], steps: int, step_size: float,
                     start: dict[str, float]) -> np.ndarray:
    """One FMU alone (no connections; Real start values `start`, the rest as declared)
    in libcosim."""
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave
    quiet()
    execution = CosimExecution.from_step_size(round(step_size * 1e9))
    index = execution.add_local_slave(CosimLocalSlave(fmu_path=fmu, instance_name="fmu"))
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)
    refs = {v.name.decode(): v.reference for v in execution.slave_variables(index)}
    wanted = [refs[name] for name in outputs]
    for name, value in start.items():
        execution.real_initial_value(index, refs[name], value)
    rows = np.empty((steps, len(outputs) + 1))
    for k in range(steps):
        if not execution.step(1):
            raise RuntimeError(f"libcosim: step {k} of {fmu} failed")
        rows[k, 0] = execution.status().current_time * 1e-9
        rows[k, 1:] = observer.last_real_values(index, wanted)
    return rows


def run_fmu_ecos(fmu: str, outputs: list[str], steps: int, step_size: float,
                 start: dict[str, float]) -> np.ndarray:
    """One FMU alone (no connections; Real start values `start`, the rest as declared)
    in ecos (as a parameter set, applied during initialization)."""
    from ecospy.EcosSimulation import EcosSimulation
    from ecospy.EcosSimulationStructure import EcosSimulationStructure
    quiet()
    structure = EcosSimulationStructure()
    structure.add_model("fmu", fmu)
    if start:
        structure.add_parameter_set("start", {f"fmu::{k}": v for k, v in start.items()})
    rows = np.empty((steps, len(outputs) + 1))
    with EcosSimulation(structure=structure, step_size=step_size) as sim:
        if not sim.init(parameter_set="start" if start else None):
            raise RuntimeError(f"ecos: init of {fmu} failed")
        for k in range(steps):
            rows[k, 0] = sim.step(1)
            rows[k, 1:] = [sim.get_real(f"fmu::{name}") for name in outputs]
        sim.terminate()
    return rows
