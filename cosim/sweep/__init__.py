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
from dataclasses import dataclass
from pathlib import Path

from .plots import plot_sweep
from .runner import FmuStore, execute, read_fmus, run_on_worker, worker_plugin
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

    def throughput(self) -> float:
        """Runs per second between the first and the last completed run (leaves out
        the cluster's start-up and the workers' first imports)."""
        t = self.completed_at
        return (len(t) - 1) / (t[-1] - t[0]) if len(t) > 1 and t[-1] > t[0] else 0.0


def reachable_on(plant_fmu: Path):
    """A filter of workspace targets: the plant FMU initialises at the pose (rad) with
    every actuator within its stroke."""
    from .reach import reachable
    return lambda pose: reachable(plant_fmu, pose)


def _client(scheduler: str | None, workers: int | None):
    from distributed import Client, LocalCluster
    if scheduler is not None:
        return Client(scheduler), None
    cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1,
                           processes=True, dashboard_address=None)
    return Client(cluster), cluster


def _run_serial(todo, fmus, blobs, record):
    store = FmuStore(blobs)
    store.setup()
    for rid, values, document in todo:
        record(rid, values, execute(store, document, fmus))


def _run_dask(todo, fmus, blobs, record, scheduler, workers, retries):
    from distributed import as_completed
    client, cluster = _client(scheduler, workers)
    try:
        client.register_plugin(worker_plugin(blobs))
        futures = {client.submit(run_on_worker, document, fmus, key=f"cosim-run-{rid}",
                                 pure=False, retries=retries): (rid, values)
                   for rid, values, document in todo}
        for future in as_completed(futures):
            rid, values = futures[future]
            try:
                outcome = future.result()
            except Exception as e:  # worker lost too often (KilledWorker), or a bug
                outcome = {"status": "failed", "reason": f"{type(e).__name__}: {e}"}
            record(rid, values, outcome)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def run_sweep(spec: Spec, out: Path, scheduler: str | None = None,
              workers: int | None = None, resume: bool = False, progress: bool = True,
              retries: int = 2, plots: bool = True) -> SweepOutcome:
    """Runs every run of `spec` not done yet; workers=0 runs serially in-process."""
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

    def record(rid, values, outcome):
        table.append(rid, values_row(spec, values), outcome)
        completed_at.append(time.perf_counter())
        bar.update(outcome["status"] == "ok")

    try:
        if workers == 0 and scheduler is None:
            _run_serial(todo, fmus, blobs, record)
        elif todo:
            _run_dask(todo, fmus, blobs, record, scheduler, workers, retries)
    finally:
        table.close()
    written = []
    if plots:
        header, rows = read_table(table.path)
        axes = [c for c, v in zip(header[3:], _kinds(spec)) if v != "random"]
        written = plot_sweep(header, rows, axes, any(v.kind == "random" for v in spec.varied),
                             out, spec.name)
    return SweepOutcome(table.path, written, len(todo), len(spec.runs) - len(todo),
                        bar.failed, time.perf_counter() - started, completed_at)


def _kinds(spec: Spec) -> list[str]:
    kinds = []
    for v in spec.varied:
        kinds += [v.kind] * (3 if v.kind == "workspace" else 1)
    return kinds
