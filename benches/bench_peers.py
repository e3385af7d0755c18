"""Our master against the two SSP importers from PyPI, libcosim (libcosimpy) and ecos
(ecospy), on the same SSP export of one scenario, in one run:

    python benches/bench_peers.py [--runs 5] [--scenario three_axis_quintic]

Each master runs the scenario's whole run at its step h: ours (robofmu.master.Master,
input_extrapolation hold, linear and quadratic, and quadratic at 4 h) from the
scenario, libcosim and ecos
(their fixed-step algorithms, Jacobi schemes without input extrapolation) from the SSP
archive robofmu.ssp writes for it. Time: wall time of a whole run, loading and
instantiation included, nothing read back during the run (libcosim: one step(N)
call, ecos: one step(N) call), runs interleaved, median and minimum over the runs.
Error: the largest |theta - theta_ref| over the axes and the communication points,
theta_ref from our master at h / 16 with quadratic extrapolation; the importers'
trajectories come from separate runs that read theta after every step (the time
runs read nothing).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from robofmu.master import Master  # noqa: E402
from robofmu.scenario import load_scenario  # noqa: E402
from robofmu.ssp import PARAMETER_SET, write_ssp  # noqa: E402

THETA = [f"plant.theta[{i}]" for i in (1, 2, 3)]


def quiet() -> None:
    """Both libraries log every FMI call by default; warnings and errors stay."""
    from ecospy.lib import EcosLib
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    log_output_level(CosimLogLevel.WARNING)
    EcosLib.set_log_level("warn")


def ours(scenario, extrapolation: str, coarse: int = 1):
    """Our master; with `coarse` at coarse times the scenario's step."""
    scenario = replace(scenario, input_extrapolation=extrapolation,
                       step_size=coarse * scenario.step_size)

    def run(read: bool):
        result = Master(scenario).run()
        return np.column_stack([result.columns[s] for s in THETA])[1:] if read else None
    return run


def libcosim(ssp: Path, scenario):
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimObserver import CosimObserver

    def run(read: bool):
        execution = CosimExecution.from_ssp_file(str(ssp), round(scenario.step_size * 1e9))
        if not read:
            if not execution.step(scenario.steps):
                raise RuntimeError("libcosim: a step failed")
            return None
        observer = CosimObserver.create_last_value()
        execution.add_observer(observer)
        index = execution.slave_index_from_instance_name("plant")
        refs = {v.name.decode(): v.reference for v in execution.slave_variables(index)}
        wanted = [refs[s.split(".", 1)[1]] for s in THETA]
        rows = np.empty((scenario.steps, 3))
        for k in range(scenario.steps):
            if not execution.step(1):
                raise RuntimeError(f"libcosim: step {k} failed")
            rows[k] = observer.last_real_values(index, wanted)
        return rows
    return run


def ecos(ssp: Path, scenario):
    from ecospy.EcosSimulation import EcosSimulation

    def run(read: bool):
        ids = [s.replace(".", "::", 1) for s in THETA]
        with EcosSimulation(ssp_path=str(ssp), step_size=scenario.step_size) as sim:
            if not sim.init(parameter_set=PARAMETER_SET):
                raise RuntimeError("ecos: init failed")
            if not read:
                sim.step(scenario.steps)
                sim.terminate()
                return None
            rows = np.empty((scenario.steps, 3))
            for k in range(scenario.steps):
                sim.step(1)
                rows[k] = [sim.get_real(i) for i in ids]
            sim.terminate()
            return rows
    return run


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--scenario", default="three_axis_quintic")
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args(argv)
    quiet()
    scenario = load_scenario(ROOT / "scenarios" / f"{args.scenario}.toml")
    fine = replace(scenario, step_size=scenario.step_size / 16, input_extrapolation="quadratic")
    result = Master(fine).run()
    reference = np.column_stack([result.columns[s] for s in THETA])[16::16]
    with tempfile.TemporaryDirectory() as work:
        ssp = Path(work) / f"{scenario.name}.ssp"
        write_ssp(scenario, ssp)
        masters = {"ours, hold": ours(scenario, "hold"),
                   "ours, linear": ours(scenario, "linear"),
                   "ours, quadratic (default)": ours(scenario, "quadratic"),
                   "ours, quadratic, 4 h": ours(scenario, "quadratic", 4),
                   "libcosim (libcosimpy)": libcosim(ssp, scenario),
                   "ecos (ecospy)": ecos(ssp, scenario)}
        errors = {}
        for name, run in masters.items():
            rows = run(True)
            every = len(reference) // len(rows)  # 4 for the run at 4 h
            errors[name] = float(np.abs(rows - reference[every - 1::every]).max())
        times: dict[str, list[float]] = {name: [] for name in masters}
        for _ in range(args.runs):  # interleaved: the machine's load hits all alike
            for name, run in masters.items():
                started = time.perf_counter()
                run(False)
                times[name].append(time.perf_counter() - started)
    print(f"{scenario.name}: {scenario.steps} steps of {1e3 * scenario.step_size:g} ms, whole "
          f"runs (instantiation included), {args.runs} interleaved runs; error: max |theta - "
          f"theta_ref| (rad), theta_ref from our master at h/16, quadratic")
    print(f"  {'master':28s} {'median (s)':>10} {'min (s)':>8} {'error (rad)':>12}")
    for name in masters:
        print(f"  {name:28s} {statistics.median(times[name]):10.3f} {min(times[name]):8.3f} "
              f"{errors[name]:12.2e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
