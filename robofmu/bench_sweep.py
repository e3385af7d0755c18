"""``cosim bench sweep [--runs N] [--workers 0,1,2] [--batch N] [--repeat N]``: sweep
throughput per worker count, the cluster's start-up included and excluded (also
``python -m robofmu.bench sweep ...``).

The sweep is the issue-22 case: the regulation scenario (1 s at 1 ms) with the leg mass
drawn at random, N runs. For each worker count (0: serially in this process; N > 0: a
LocalCluster of N worker processes) it prints the wall time with start-up, runs/s with
start-up (runs / wall) and without (from the workers being ready to the last run), the
speed-up over serial, the parallel efficiency (speed-up / workers) and the runs per
task. Then the per-task overhead budget: the time a task costs the workers beyond its
runs (measured at the largest worker count) and the start-up, from which the last lines
predict the speed-up of a larger cluster (16 workers unless --predict says otherwise).
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import tempfile
from pathlib import Path

from . import bundle
from .scenario import load_scenario
from .sweep import auto_batch, run_sweep
from .sweep.spec import parse_spec

ROOT = Path(__file__).resolve().parent.parent


def add_sweep_options(parser: argparse.ArgumentParser) -> None:
    """The options of `cosim bench sweep` besides --runs (robofmu.bench adds them: the
    command table's `bench` command parses them)."""
    parser.add_argument("--workers", default="0,1,2",
                        help="comma-separated worker counts (0: serial; default 0,1,2)")
    parser.add_argument("--batch", type=int, default=None,
                        help="runs per task (default: sized automatically)")
    parser.add_argument("--repeat", type=int, default=1,
                        help="measure the worker counts this many times, interleaved, and "
                        "print the medians (a machine loaded by others; default 1)")
    parser.add_argument("--predict", type=int, default=16,
                        help="worker count to predict from the budget (default 16)")


def bench_spec(runs: int):
    data = {"scenario": str(bundle.scenarios_dir() / "regulation.toml"), "name": "bench",
            "seed": 1, "samples": runs,
            "random": {"plant.legMass": {"distribution": "normal", "mean": 0.9467,
                                         "sd": 0.09467, "min": 0.75, "max": 1.15,
                                         "unit": "kg"}}}
    return parse_spec(data, ROOT, "bench")


def measure(spec, workers: int, batch: int | None, out: Path) -> dict:
    outcome = run_sweep(spec, out / f"w{workers}", workers=workers, progress=False,
                        plots=False, batch=batch)
    if outcome.failed:
        raise RuntimeError(f"{outcome.failed} runs failed: {outcome.reasons.most_common(1)}")
    return {"workers": workers, "wall": outcome.wall_s, "ready": outcome.ready_s,
            "with": outcome.runs / outcome.wall_s, "without": outcome.throughput(),
            "batch": outcome.batch, "runs": outcome.runs, "cpu": outcome.client_cpu_s}


def budget(rows: list[dict]) -> tuple[float, float, float]:
    """CPU seconds per run (serial row: this process ran them all), CPU seconds of this
    process (client, LocalCluster scheduler, table writer) per task on a cluster (the
    row of the most workers), and the start-up wall time of one worker (1-worker row,
    else the smallest cluster): on a machine with a free core per worker these do not
    depend on the load of the others."""
    serial = next(r for r in rows if r["workers"] == 0)
    cluster = [r for r in rows if r["workers"] > 0]
    t_run = serial["cpu"] / serial["runs"]
    if not cluster:
        return t_run, 0.0, 0.0
    last = max(cluster, key=lambda r: r["workers"])
    per_task = last["cpu"] / -(-last["runs"] // last["batch"])
    return t_run, per_task, min(cluster, key=lambda r: r["workers"])["ready"]


def predict(runs: int, workers: int, t_run: float, per_task: float, startup: float,
            batch: int) -> float:
    """Speed-up over serial with start-up, `workers` on as many free cores: this process
    makes runs while the cluster starts (robofmu.sweep.engine), then the workers share the
    rest plus the last task (the tail), unless this process's work per task (one
    process) takes longer."""
    rest = max(0.0, runs - startup / t_run)
    tasks = math.ceil(rest / batch)
    work = max(rest * t_run / workers + min(batch, rest) * t_run, tasks * per_task)
    wall = min(startup, runs * t_run) + work
    return runs * t_run / wall


def run(args: argparse.Namespace) -> int:
    try:
        counts = [int(x) for x in args.workers.split(",")]
    except ValueError:
        print(f"cosim: --workers: {args.workers!r} is not a comma-separated list of "
              "integers; give e.g. 0,1,2", file=sys.stderr)
        return 2
    if 0 not in counts or min(counts) < 0 or not 1 <= args.runs <= 100000:
        print("cosim: --workers/--runs: give 0 (the serial reference) among the worker "
              "counts and 1 to 100000 runs", file=sys.stderr)
        return 2
    if not 1 <= args.repeat <= 100:
        print("cosim: --repeat: give 1 to 100", file=sys.stderr)
        return 2
    spec = bench_spec(args.runs)
    samples: dict[int, list[dict]] = {w: [] for w in counts}
    with tempfile.TemporaryDirectory() as out:
        for _ in range(args.repeat):
            for workers in counts:
                samples[workers].append(measure(spec, workers, args.batch, Path(out)))
    rows = [{key: statistics.median(r[key] for r in samples[w]) for key in samples[w][0]}
            for w in counts]
    serial = next(r for r in rows if r["workers"] == 0)
    print(f"sweep: {args.runs} runs of regulation (1 s at 1 ms, leg mass random), "
          f"median of {args.repeat} interleaved measurement(s)")
    print(f"{'workers':>8} {'wall s':>8} {'start s':>8} {'runs/s':>8} {'runs/s*':>8} "
          f"{'speed-up':>9} {'eff.':>6} {'eff.*':>6} {'batch':>6}")
    for r in rows:
        w = max(r["workers"], 1)
        up, up_ex = r["with"] / serial["with"], r["without"] / serial["without"]
        print(f"{r['workers']:>8.0f} {r['wall']:8.2f} {r['ready']:8.2f} {r['with']:8.1f} "
              f"{r['without']:8.1f} {up:9.2f} {up / w:6.2f} {up_ex / w:6.2f} {r['batch']:>6.0f}")
    print("(runs/s: with start-up; runs/s*: from the workers being ready; eff.: speed-up "
          "over serial / workers, eff.* without start-up)")
    if max(counts) == 0:
        print("budget: give a worker count above 0 too (the cluster's cost per task and "
              "start-up come from it)")
        return 0
    t_run, per_task, startup = budget(rows)
    n = args.predict
    print(f"budget: {1e3 * t_run:.1f} ms CPU per run; this process {1e3 * per_task:.1f} ms "
          f"CPU per task (client, scheduler, writer); worker start-up {startup:.2f} s")
    for runs in (args.runs, 2000):
        batch = args.batch or auto_batch(runs, n, spec_steps(spec))
        print(f"predicted speed-up at {n} workers, {runs} runs, {batch} runs per task, with "
              f"start-up: {predict(runs, n, t_run, per_task, startup, batch):.1f}")
    return 0


def spec_steps(spec) -> int:
    return load_scenario(spec.scenario).steps

