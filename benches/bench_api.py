"""Whole runs of the library against a C host that makes the same FMI calls directly:
``python benches/bench_api.py [--runs 10] [--sweep 400]`` (a benchmark, not a test; the
figures are in docs/performance.md).

The C host (benches/c_host/c_host.c, compiled here with `cc`) dlopens the FMI 2.0
binaries of the unzipped bundled FMUs and runs the regulation scenario's coupling
(planner -> PID -> plant, 1000 steps of 1 ms, sampled coupling, the scenario's start
values as robofmu resolves them) with direct calls: per step every doStep, then one
fmi2GetReal and one fmi2SetReal per connected pair of FMUs. Both sides run with
input_extrapolation = "hold", so that they make the same FMI calls (robofmu's default,
"quadratic", adds the input derivatives; its figure is printed too). A whole run is
timed on both sides: loading, instantiation, initialisation, the steps, freeing.

Printed, each the median of --runs: robofmu.simulate(PATH) / C host (and the
process's first such call, before any instance is shared or any answer cached);
robofmu.simulate(loaded scenario) / C host; and a serial sweep of --sweep regulation
runs (robofmu.run_sweep) / --sweep C-host runs, in wall time and in CPU time (this
process's against the C host's, which the load of other jobs moves less than the wall
time: the two are measured one after the other). The machine's load average is printed
with them: measure on a quiet machine."""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import fmpy
from fmpy import extract, read_model_description

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import robofmu  # noqa: E402

HOST = ROOT / "benches" / "c_host" / "c_host.c"
TYPES = {"Real": "r", "Integer": "i", "Enumeration": "i", "Boolean": "b"}


def compile_host(work: Path) -> Path:
    exe = work / "c_host"
    headers = Path(fmpy.__file__).parent / "c-code"
    subprocess.run(["cc", "-O2", f"-I{headers}", "-o", str(exe), str(HOST), "-ldl"], check=True)
    return exe


def write_plan(scenario: robofmu.Scenario, work: Path) -> Path:
    """The C host's plan of the scenario's resolved form (see c_host.c's main)."""
    plan = scenario.resolved()
    order = plan.order
    lines = [str(len(order))]
    refs = {}
    for alias in order:
        md = read_model_description(str(plan.fmus[alias]))
        refs[alias] = {v.name: v for v in md.modelVariables}
        folder = extract(str(plan.fmus[alias]), unzipdir=str(work / alias))
        lines.append(f"{folder} {md.coSimulation.modelIdentifier} {md.guid}")
    starts = []
    for alias, values in plan.parameters.items():
        for name, value in values.items():
            v = refs[alias][name]
            starts.append(f"{order.index(alias)} {TYPES[v.type]} {v.valueReference} "
                          f"{float(value)!r}")
    lines += [str(len(starts)), *starts]
    groups = []
    for alias in order:  # per target in order, per source: one get and one set (robofmu.master)
        by_source: dict[str, list[tuple[int, int]]] = {}
        for c in plan.connections:
            if c.target.alias == alias:
                by_source.setdefault(c.source.alias, []).append(
                    (refs[c.source.alias][c.source.variable].valueReference,
                     refs[alias][c.target.variable].valueReference))
        for source, pairs in by_source.items():
            groups.append(f"{order.index(alias)} {order.index(source)} {len(pairs)} "
                          + " ".join(f"{a} {b}" for a, b in pairs))
    lines += [str(len(groups)), *groups, f"{plan.start_time!r} {plan.stop_time!r} {plan.step_size!r}"]
    path = work / "plan.txt"
    path.write_text("\n".join(lines) + "\n")
    return path


def children_cpu() -> float:
    """CPU seconds (user + system) of the finished child processes so far."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def host_runs(exe: Path, plan: Path, runs: int) -> tuple[list[float], list[float]]:
    said = subprocess.run([str(exe), str(plan), str(runs)], check=True, capture_output=True,
                          text=True).stdout.split("\n")
    times = [float(x) for x in said[:runs]]
    last = [float(x) for x in said[runs].split()[1:]]
    return times, last


def median_wall(call, runs: int) -> float:
    walls = []
    for _ in range(runs):
        started = time.perf_counter()
        call()
        walls.append(time.perf_counter() - started)
    return statistics.median(walls)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=10)
    parser.add_argument("--sweep", type=int, default=400)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="bench-api-") as scratch:
        work = Path(scratch)
        text = robofmu.example("regulation").read_text()
        path = work / "regulation.toml"
        path.write_text(text.replace('step_size = "1 ms"',
                                     'step_size = "1 ms"\ninput_extrapolation = "hold"'))
        started = time.perf_counter()
        robofmu.simulate(path)  # the first run in this process: nothing shared or cached yet
        cold = time.perf_counter() - started
        scenario = robofmu.load(path)
        exe = compile_host(work)
        plan = write_plan(scenario, work)
        host_runs(exe, plan, 3)  # warm: the libraries in the page cache
        robofmu.simulate(scenario)
        host, last = host_runs(exe, plan, args.runs)
        ours = robofmu.simulate(scenario)
        u = [float(ours[f"pid.u[{i}]"][-1]) for i in (1, 2, 3)]
        difference = max(abs(a - b) for a, b in zip(u, last))
        c_run = statistics.median(host)
        from_path = median_wall(lambda: robofmu.simulate(path), args.runs)
        loaded = median_wall(lambda: robofmu.simulate(scenario), args.runs)
        default = robofmu.load("regulation")
        quadratic = median_wall(lambda: robofmu.simulate(default), args.runs)
        spec = work / "sweep.toml"
        spec.write_text(f'scenario = "{path}"\nname = "bench"\n[grid.\'gains.omega\']\n'
                        f'from = 20\nto = 40\nsteps = {args.sweep}\nunit = "rad/s"\n')
        started, cpu = time.perf_counter(), time.process_time()
        outcome = robofmu.run_sweep(spec, work / "out")
        sweep_wall, sweep_cpu = time.perf_counter() - started, time.process_time() - cpu
        host_cpu = children_cpu()
        host_sweep, _ = host_runs(exe, plan, args.sweep)
        host_cpu = children_cpu() - host_cpu
        load = os.getloadavg()
    print(f"machine load average (1, 5 min): {load[0]:.2f}, {load[1]:.2f} on "
          f"{os.cpu_count()} CPUs")
    print(f"C host, whole run: {1e3 * c_run:.2f} ms (median of {args.runs}); its last "
          f"pid.u equals robofmu's within {difference:.1e}")
    print(f"simulate(path):      {1e3 * from_path:8.2f} ms = {from_path / c_run:5.2f} x the C host")
    print(f"  (the process's first, nothing shared yet: {1e3 * cold:.2f} ms = "
          f"{cold / c_run:.2f} x)")
    print(f"simulate(scenario):  {1e3 * loaded:8.2f} ms = {loaded / c_run:5.2f} x the C host")
    print(f"  (default quadratic extrapolation: {1e3 * quadratic:.2f} ms = "
          f"{quadratic / c_run:.2f} x)")
    print(f"serial sweep of {outcome.runs} runs ({outcome.failed} failed): {sweep_wall:.2f} s = "
          f"{sweep_wall / sum(host_sweep):5.2f} x {args.sweep} C-host runs "
          f"({sum(host_sweep):.2f} s)")
    print(f"  (CPU time, which the other jobs' load moves less: {sweep_cpu:.2f} s = "
          f"{sweep_cpu / host_cpu:.2f} x the C host's {host_cpu:.2f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
