"""Sweeps and Monte Carlo of a closed-loop scenario on Dask distributed.

Python API::

    from robofmu.sweep import load_spec, run_sweep
    spec = load_spec("sweeps/gains.toml")
    outcome = run_sweep(spec, Path("results"))          # LocalCluster, 1 worker per core
    outcome = run_sweep(spec, out, scheduler="tcp://host:8786")   # an existing cluster
    outcome = run_sweep(spec, out, workers=0)           # serially, in this process

The table (out/<name>.csv) gets one row per run as the run completes; plots are
written next to it at the end. See robofmu.sweep.spec for the SPEC format.
"""

from __future__ import annotations

import time
import tomllib
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..scenario import ScenarioError, fmu_file
from .engine import auto_batch, run_dask, run_serial
from .plots import plot_sweep
from .reach import reachable
from .runner import read_fmus
from .spec import Spec, SpecError, document_for, load_spec, run_id
from .store import Progress, Table, columns, read_table, values_row

__all__ = ["Spec", "SpecError", "SweepOutcome", "auto_batch", "load_spec", "run_sweep",
           "reachable_on", "workspace_filter"]


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
    client_cpu_s: float = 0.0  # CPU time of this process (client, scheduler of a
    # LocalCluster, table writer; the runs themselves when serial) after the workers
    # were ready

    def throughput(self) -> float:
        """Runs per second from the workers being ready to the last completed run
        (leaves out the cluster's start-up and the workers' warm-up)."""
        ready = self.started_at + self.ready_s
        after = [t for t in self.completed_at if t >= ready]
        span = after[-1] - ready if after else 0.0
        return len(after) / span if span > 0 else 0.0


def reachable_on(plant_fmu: Path):
    """A filter of workspace targets: the plant FMU initialises at the pose (rad) with
    every actuator within its stroke."""
    return lambda pose: reachable(plant_fmu, pose)


def workspace_filter(spec_path: Path, fmu_dir: Path | None = None):
    """The workspace filter on the plant FMU of the SPEC's base scenario (None when the
    SPEC or its scenario cannot be read: load_spec then reports the problem by field)."""
    try:
        data = tomllib.loads(Path(spec_path).read_text())
        scenario = (Path(spec_path).parent / str(data.get("scenario", ""))).resolve()
        plant = tomllib.loads(scenario.read_text())["fmus"]["plant"]
        if not isinstance(plant, str):
            return None
    except (OSError, KeyError, TypeError, ValueError, tomllib.TOMLDecodeError):
        return None
    try:
        path = fmu_file("plant", plant, scenario.parent, fmu_dir)
    except ScenarioError:
        return None  # not a bundled FMU: load_spec names the field
    return reachable_on(path)


def run_sweep(spec: Spec, out: Path, scheduler: Any = None,
              workers: int | None = None, resume: bool = False, progress: bool = True,
              retries: int = 2, plots: bool = True, batch: int | None = None
              ) -> SweepOutcome:
    """Runs every run of `spec` not done yet; workers=0 runs serially in-process;
    `scheduler`: an address, or a dask.distributed.Client of the caller's (left open);
    `batch`: runs per Dask task (None: sized by auto_batch)."""
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
    setup = {"ready_s": 0.0, "batch": 1, "cpu": time.process_time()}

    def record(rid, values, outcome):
        table.append(rid, values_row(spec, values), outcome)
        completed_at.append(time.perf_counter())
        if outcome["status"] != "ok":
            reasons[outcome.get("reason", "")] += 1
        bar.update(outcome["status"] == "ok")

    def ready(size: int = 1) -> None:
        setup["ready_s"], setup["batch"] = time.perf_counter() - started, size
        setup["cpu"] = time.process_time()

    try:
        if workers == 0 and scheduler is None:
            run_serial(todo, fmus, blobs, record, ready)
        elif todo:
            run_dask(todo, fmus, blobs, record, scheduler, workers, retries, batch, ready)
    finally:
        table.close()
    client_cpu = time.process_time() - setup["cpu"]
    written = []
    if plots:
        header, rows = read_table(table.path)
        axes = [c for c, v in zip(header[3:], _kinds(spec)) if v != "random"]
        written = plot_sweep(header, rows, axes, any(v.kind == "random" for v in spec.varied),
                             out, spec.name, spec.about())
    return SweepOutcome(table.path, written, len(todo), len(spec.runs) - len(todo),
                        bar.failed, time.perf_counter() - started, completed_at, reasons,
                        int(setup["batch"]), setup["ready_s"], started, client_cpu)


def sweep_file(spec_path: Path, out: Path, fmu_dir: Path | None = None,
               **options: Any) -> tuple[Spec, SweepOutcome]:
    """The sweep SPEC file `spec_path` (its workspace targets filtered on its plant FMU)
    run into the folder `out` (run_sweep's `options`): what ``cosim sweep`` and
    robofmu.run_sweep make. SpecError naming the field of a bad SPEC."""
    spec = load_spec(spec_path, fmu_dir, reachable=workspace_filter(spec_path, fmu_dir))
    return spec, run_sweep(spec, out, **options)


def _kinds(spec: Spec) -> list[str]:
    kinds = []
    for v in spec.varied:
        kinds += [v.kind] * (3 if v.kind == "workspace" else 1)
    return kinds
