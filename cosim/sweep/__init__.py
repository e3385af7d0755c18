"""Sweeps and Monte Carlo of a closed-loop scenario on Dask distributed.

Python API::

    from cosim.sweep import load_spec, run_sweep
    spec = load_spec("sweeps/gains.toml")
    outcome = run_sweep(spec, Path("results"))          # LocalCluster, 1 worker per core
    outcome = run_sweep(spec, out, scheduler="tcp://host:8786")   # an existing cluster
    outcome = run_sweep(spec, out, workers=0)           # serially, in this process

The table (out/<name>.csv) gets one row per run as the run completes; plots are
written next to it at the end. See cosim.sweep.spec for the SPEC format.
"""

from __future__ import annotations

import os
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

from .plots import plot_sweep
from .runner import FmuStore, execute, read_fmus, run_on_worker, warm, worker_plugin
from .spec import Spec, SpecError, document_for, load_spec, run_id
from .store import Progress, Table, columns, read_table, values_row

__all__ = ["Spec", "SpecError", "SweepOutcome", "load_spec", "run_sweep", "reachable_on"]


@dataclass
class SweepOutcome:
    table: Path
    plots: list[Path]
    runs: int  # runs made now
    skipped: int  # done before (--resume)
    failed: int
    wall_s: float
    completed_at: list[float]  # perf_counter() as each row was written
    reasons: Counter = field(default_factory=Counter)  # failure reason -> runs
    batch: int = 1  # runs per task
    ready_s: float = 0.0  # from the start to the workers being ready (cluster start-up)
    started_at: float = 0.0  # perf_counter() at the start of run_sweep

    def throughput(self) -> float:
        """Runs per second from the workers being ready to the last completed run
        (leaves out the cluster's start-up and the workers' warm-up)."""
        t = self.completed_at
        span = t[-1] - self.started_at - self.ready_s if t else 0.0
        return len(t) / span if span > 0 else 0.0


def reachable_on(plant_fmu: Path):
    """A filter of workspace targets: the plant FMU initialises at the pose (rad) with
    every actuator within its stroke."""
    from .reach import reachable
    return lambda pose: reachable(plant_fmu, pose)


def _client(scheduler: str | None, workers: int | None):
    from distributed import Client, LocalCluster
    if scheduler is not None:
        return Client(scheduler, set_as_default=False), None
    cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1,
                           processes=True, dashboard_address=None)
    return Client(cluster, set_as_default=False), cluster


def _run_serial(todo, fmus, blobs, record, ready):
    store = FmuStore(blobs)
    store.setup()
    warm(store, fmus)
    ready()
    for rid, values, document in todo:
        record(rid, values, execute(store, document, fmus))


def _batches(todo: list, size: int) -> list[list]:
    return [todo[i:i + size] for i in range(0, len(todo), size)]


def _run_dask(todo, fmus, blobs, record, scheduler, workers, retries, batch, ready):
    from distributed import as_completed
    client, cluster = _client(scheduler, workers)
    try:
        client.register_plugin(worker_plugin(blobs, fmus))  # every worker warm
        count = max(1, len(client.scheduler_info()["workers"]))
        size = batch or auto_batch(len(todo), count, _steps(todo))
        ready(size)
        values_of = {rid: values for rid, values, _ in todo}
        futures = {client.submit(run_on_worker, [(rid, doc) for rid, _, doc in chunk], fmus,
                                 key=f"cosim-runs-{chunk[0][0]}-{len(chunk)}", pure=False,
                                 retries=retries): chunk
                   for chunk in _batches(todo, size)}
        # The sweep's own client and loop: never a client the caller made current (a
        # `with Client(...)` around run_sweep); as_completed would otherwise track these
        # futures on that client's event loop, and a result lost with a killed worker
        # would be waited for again on this one ("bound to a different event loop").
        for future in as_completed(futures, loop=client.loop):
            try:
                outcomes = future.result()
            except Exception as e:  # worker lost too often (KilledWorker), or a bug
                reason = f"{type(e).__name__}: {e}"
                outcomes = [(rid, {"status": "failed", "reason": reason})
                            for rid, _, _ in futures[future]]
            for rid, outcome in outcomes:
                record(rid, values_of[rid], outcome)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


RUN_STEP_S = 6e-5  # a closed-loop step of the three FMUs on the worker (cosim bench sweep)
TASK_S = 0.5  # target length of one task: the scheduler's ~1 ms per task is then 0.2 %
TASKS_PER_WORKER = 4  # at least, so that the last tasks balance over the workers


def auto_batch(runs: int, workers: int, steps: int) -> int:
    """Runs per task: as many as fit TASK_S, and few enough that every worker gets
    TASKS_PER_WORKER tasks (the load balances at the end of the sweep)."""
    by_length = int(TASK_S / max(steps * RUN_STEP_S, 1e-9))
    by_balance = runs // (TASKS_PER_WORKER * max(workers, 1))
    return max(1, min(by_length, by_balance))


def _steps(todo) -> int:
    """Communication steps of a run (of the first; the runs of a sweep differ in
    parameters only, rarely in length)."""
    from ..scenario import parse_document
    if not todo:
        return 1
    try:
        return parse_document(todo[0][2], Path(".")).steps
    except Exception:  # noqa: BLE001 - an estimate only; the run reports the problem
        return 1000


def run_sweep(spec: Spec, out: Path, scheduler: str | None = None,
              workers: int | None = None, resume: bool = False, progress: bool = True,
              retries: int = 2, plots: bool = True, batch: int | None = None
              ) -> SweepOutcome:
    """Runs every run of `spec` not done yet; workers=0 runs serially in-process;
    `batch`: runs per Dask task (None: sized by auto_batch)."""
    import time
    started = time.perf_counter()
    header = columns(spec)
    table = Table(out / f"{spec.name}.csv", header, resume)
    fmus, blobs = read_fmus(spec.document, spec.scenario.parent, spec.fmu_dir)
    todo = []
    for values in spec.runs:
        rid = run_id(values)
        if rid not in table.done:
            todo.append((rid, values, document_for(spec, values)))
    bar = Progress(len(todo), len(spec.runs) - len(todo), enabled=progress)
    completed_at: list[float] = []
    reasons: Counter = Counter()
    setup = {"ready_s": 0.0, "batch": 1}

    def record(rid, values, outcome):
        table.append(rid, values_row(spec, values), outcome)
        completed_at.append(time.perf_counter())
        if outcome["status"] != "ok":
            reasons[outcome.get("reason", "")] += 1
        bar.update(outcome["status"] == "ok")

    def ready(size: int = 1) -> None:
        setup["ready_s"], setup["batch"] = time.perf_counter() - started, size

    try:
        if workers == 0 and scheduler is None:
            _run_serial(todo, fmus, blobs, record, ready)
        elif todo:
            _run_dask(todo, fmus, blobs, record, scheduler, workers, retries, batch, ready)
    finally:
        table.close()
    written = []
    if plots:
        header, rows = read_table(table.path)
        axes = [c for c, v in zip(header[3:], _kinds(spec)) if v != "random"]
        written = plot_sweep(header, rows, axes, any(v.kind == "random" for v in spec.varied),
                             out, spec.name)
    return SweepOutcome(table.path, written, len(todo), len(spec.runs) - len(todo),
                        bar.failed, time.perf_counter() - started, completed_at, reasons,
                        setup["batch"], setup["ready_s"], started)


def _kinds(spec: Spec) -> list[str]:
    kinds = []
    for v in spec.varied:
        kinds += [v.kind] * (3 if v.kind == "workspace" else 1)
    return kinds
