"""One run of a sweep, as a worker executes it: FMUs shipped by content, instances
loaded once per worker and reused across runs (fmi2Reset), metrics of the run.

FMUs reach the workers without a shared file system: the client reads each FMU once
and registers a Dask worker plugin holding the bytes; every worker (also one that joins
later, or a restarted one) writes them into its own local directory when the plugin is
set up. A task carries only the run's scenario document and its values.

Reuse: FMI 2.0 fmi2Reset returns an instance to its state after instantiation, with
every variable at its start value. tests/python/test_sweep.py shows that a run on a
reset instance, after a run with other parameters, is bit for bit the run on a fresh
instance for our three FMUs, so the pool resets instead of re-instantiating (which
also extracts the FMU and loads its library: milliseconds per run).
"""

from __future__ import annotations

import hashlib
import math
import shutil
import time
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import CosimError
from ..instances import new_instance
from ..master import Master
from ..scenario import ScenarioError, Signal, fmu_file, parse_document
from . import scratch
from .spec import SpecError

FORCE_LIMIT_N = 400.0
SETTLING_BAND = 0.02  # settling: the error stays within 2 % of its initial value
METRICS = ["rms_error_deg", "max_error_deg", "peak_force_n", "force_limit_hit",
           "end_stop_hit", "settling_time_s", "discards", "wall_s"]


class InstancePool:
    """Open FMU instances per (alias, FMU file), reused across runs after fmi2Reset."""

    def __init__(self):
        self.idle: dict[tuple[str, str], list] = {}
        self.opened = 0
        self.loops: dict = {}  # the last run's prepared stepping loop (Master.loops)

    def open(self, alias, path, scenario):
        idle = self.idle.get((alias, str(path)))
        if idle:
            fmu = idle.pop()
            fmu.reset(scenario.start_time, scenario.stop_time)
            return fmu
        self.opened += 1
        fmu = new_instance(alias, path, scenario.start_time, scenario.stop_time)
        fmu.pool_key = (alias, str(path))
        return fmu

    def release(self, fmu) -> None:
        self.idle.setdefault(fmu.pool_key, []).append(fmu)

    def discard(self, fmu) -> None:
        """An instance that failed is not reused (nor a loop prepared over it)."""
        self.loops.clear()
        fmu.close()


class FmuStore:
    """FMU bytes by content digest, written into a local folder on first use."""

    def __init__(self, blobs: dict[str, bytes]):
        self.blobs = blobs
        self.folder: Path | None = None
        self.pool = InstancePool()

    def setup(self) -> None:
        self.folder = scratch.make()
        for digest, data in self.blobs.items():
            (self.folder / f"{digest}.fmu").parent.mkdir(exist_ok=True)
            (self.folder / f"{digest}.fmu").write_bytes(data)

    def ready(self) -> Path:
        """The folder of the FMUs, written on first use."""
        if self.folder is None:
            self.setup()
        assert self.folder is not None  # setup made it
        return self.folder

    def path(self, digest: str) -> Path:
        return self.ready() / f"{digest}.fmu"

    def close(self) -> None:
        """Frees the idle instances and removes the FMU files."""
        self.pool.loops.clear()
        for fmus in self.pool.idle.values():
            for fmu in fmus:
                fmu.close()
        self.pool.idle.clear()
        if self.folder is not None:
            shutil.rmtree(self.folder, ignore_errors=True)
            self.folder = None


def read_fmus(document: dict, base: Path, fmu_dir: Path | None) -> tuple[dict, dict]:
    """(alias -> digest, digest -> bytes) of a scenario document's FMUs."""
    by_alias, blobs = {}, {}
    for alias, name in document.get("fmus", {}).items():
        path = fmu_file(alias, str(name), base, fmu_dir)
        try:
            data = Path(path).read_bytes()
        except OSError as e:
            raise SpecError(f"field 'fmus.{alias}' of the scenario: cannot read {path} "
                            f"({e.strerror or e}); build the FMUs (scripts/build-fmus.sh) "
                            "or give --fmu-dir") from None
        digest = hashlib.sha256(data).hexdigest()[:20]
        by_alias[alias], blobs[digest] = digest, data
        build = Path(path).parent / "fmi3" / Path(path).name
        if "sample_period" in document and build.is_file():
            # The closed-loop form's sampled law runs in the FMI 3.0 build beside the
            # controller's file (robofmu.closed_loop): kept beside its copy here too.
            blobs[f"fmi3/{digest}"] = build.read_bytes()
    return by_alias, blobs


def execute(store: FmuStore, document: dict, fmus: dict[str, str]) -> dict:
    """Runs one scenario document with the store's FMUs; the metrics, or the failure."""
    started = time.perf_counter()
    local = dict(document, fmus={a: str(store.path(d)) for a, d in fmus.items()})
    pool = store.pool
    try:
        scenario = parse_document(local, store.ready())
        # Recorded: what the metrics read (the scenario's record list is checked above;
        # a sweep keeps metrics, not signals), the connected outputs anyway.
        scenario.record = [Signal("plant", f"{n}[{i}]") for n in ("force", "stopForce")
                           for i in (1, 2, 3)]
        used: list = []
        master = Master(scenario, open_fmu=pool.open, close_fmu=used.append,
                        loops=pool.loops)
        try:
            result = master.run_arrays(contiguous=False)
        except BaseException:
            for fmu in used:
                pool.discard(fmu)
            raise
        for fmu in used:
            pool.release(fmu)
    except (CosimError, ScenarioError) as e:
        return {"status": "failed", "reason": str(e).replace("\n", " ")}
    row = metrics(result)
    row["wall_s"] = time.perf_counter() - started
    return {"status": "ok", "reason": "", **row}


def metrics(result) -> dict:
    """Tracking error (deg), peak actuator force and limits, settling time, discards."""
    def vec(alias: str, n: str) -> np.ndarray:
        return np.column_stack([np.asarray(result.columns[f"{alias}.{n}[{i}]"], dtype=float)
                                for i in (1, 2, 3)])

    q = vec("planner", "q")
    error = q - vec("plant", "theta")
    axis_error = np.abs(error).max(axis=1)
    peak_force = float(np.abs(vec("plant", "force")).max())
    settling = math.nan
    if np.all(q == q[0]) and axis_error[0] > 0.0:  # regulation: the setpoint holds
        last_outside = np.nonzero(axis_error > SETTLING_BAND * axis_error[0])[0][-1]
        if last_outside + 1 < len(result.time):  # else: never settled
            settling = float(result.time[last_outside + 1] - result.time[0])
    return {
        "rms_error_deg": math.degrees(float(np.sqrt(np.mean(np.sum(error ** 2, axis=1))))),
        "max_error_deg": math.degrees(float(axis_error.max())),
        "peak_force_n": peak_force,
        "force_limit_hit": int(peak_force > FORCE_LIMIT_N),
        "end_stop_hit": int(bool(np.any(vec("plant", "stopForce") != 0.0))),
        "settling_time_s": settling,
        "discards": len(result.discards),
    }


_STORE_NAME = "cosim-fmu-store"


def warm(store: FmuStore, fmus: dict[str, str]) -> None:
    """Unpacks every FMU and loads its library once (one idle instance per alias in
    the pool), so that a worker's first run costs what its later runs cost."""
    for alias, digest in fmus.items():
        try:
            fmu = store.pool.open(alias, store.path(digest), _WARM_EXPERIMENT)
        except Exception:  # noqa: BLE001 - best effort: each run reports the reason
            continue
        store.pool.release(fmu)


class _Experiment:
    start_time, stop_time = 0.0, 1.0


_WARM_EXPERIMENT = _Experiment()


def execute_batch(store: FmuStore, batch: list[tuple[str, dict]],
                  fmus: dict[str, str]) -> list[tuple[str, dict]]:
    """Several runs in one task: (run id, outcome) of each."""
    return [(rid, execute(store, document, fmus)) for rid, document in batch]


def worker_plugin(blobs: dict[str, bytes], fmus: dict[str, str]):
    """A Dask worker plugin that gives every worker the FMUs, unpacked and loaded
    (warm), and an instance pool."""
    # lazy: distributed is 0.4 s of start-up (benches/bench_startup.py) that serial runs skip
    from distributed.diagnostics.plugin import WorkerPlugin

    class FmuPlugin(WorkerPlugin):
        name = _STORE_NAME

        def __init__(self, blobs, fmus):
            self.blobs, self.fmus = blobs, fmus

        def setup(self, worker):
            self.store = FmuStore(self.blobs)
            self.store.setup()
            warm(self.store, self.fmus)

        def teardown(self, worker):
            self.store.close()

    return FmuPlugin(blobs, fmus)


def run_on_worker(batch: list[tuple[str, dict]], fmus: dict[str, str]) -> list:
    """The task function: a batch of runs on a Dask worker with the plugin's store."""
    from distributed import get_worker  # lazy: 0.4 s (see worker_plugin)
    plugin: Any = get_worker().plugins[_STORE_NAME]  # worker_plugin's FmuPlugin
    return execute_batch(plugin.store, batch, fmus)
