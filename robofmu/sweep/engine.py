"""Where a sweep's runs execute: serially in this process, or as batches of runs on a
Dask cluster (a LocalCluster started here, or an existing one by its scheduler's
address).

With a LocalCluster, this process makes the first run itself (loading every FMU) and,
while the cluster starts (worker processes importing, FMUs unpacked and loaded by the worker plugin), more
runs on the instances it has (see _meanwhile); the rest is submitted as tasks of
`auto_batch` runs once the workers are ready, so the start-up is not lost time and one
worker is not slower than serial. Results are written by the caller's `record`
in this process as the tasks complete.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
from concurrent.futures import ThreadPoolExecutor

from ..errors import require
from ..units import quantity
from . import scratch
from .runner import FmuStore, execute, run_on_worker, warm, worker_plugin

RUN_STEP_S = 2e-5  # CPU per closed-loop step of the three FMUs (cosim bench sweep: ~20 ms/run)
TASK_S = 0.25  # shortest target length of a task
CLIENT_TASK_S = 0.0125  # this process's CPU per task (client, scheduler; cosim bench sweep)
TASKS_PER_WORKER = 4  # at least, so that the last tasks balance over the workers


def task_seconds(workers: int) -> float:
    """Target task length: W workers finishing tasks of length T hand this process W/T
    tasks a second; it keeps up with a quarter of its time while T >= 4 W CLIENT_TASK_S."""
    return max(TASK_S, 4 * workers * CLIENT_TASK_S)


def auto_batch(runs: int, workers: int, steps: int) -> int:
    """Runs per task: as many as fit task_seconds, and few enough that every worker gets
    TASKS_PER_WORKER tasks (the load balances at the end of the sweep)."""
    by_length = int(task_seconds(workers) / max(steps * RUN_STEP_S, 1e-9))
    by_balance = runs // (TASKS_PER_WORKER * max(workers, 1))
    return max(1, min(by_length, by_balance))


def _steps(todo) -> int:
    """Communication steps of a run (of the first: the runs of a sweep differ in
    parameters, rarely in length); an estimate for auto_batch only."""
    document = todo[0][2]

    def seconds(key, default):
        value = document.get(key, default)
        return float(value) if isinstance(value, (int, float)) else quantity(value, "time", key)
    try:  # the times alone: resolving the whole document needs its FMUs (their folder)
        span = seconds("stop_time", 0.0) - seconds("start_time", 0.0)
        return max(1, round(span / seconds("step_size", 1e-3)))
    except Exception:  # noqa: BLE001 - an estimate; the run itself reports a problem
        return 1000


def run_serial(todo, fmus, blobs, record, ready) -> None:
    store = FmuStore(blobs)
    store.setup()
    warm(store, fmus)
    ready()
    try:
        for rid, values, document in todo:
            record(rid, values, execute(store, document, fmus))
    finally:
        store.close()


def _client(scheduler, workers: int | None):
    """`scheduler`: None (a LocalCluster of `workers`), an address, or a Client of the
    caller's (used as it is, left open)."""
    from distributed import Client, LocalCluster  # lazy: 0.4 s (see _worker_processes)
    if isinstance(scheduler, Client):
        return scheduler, None
    if scheduler is not None:
        return Client(scheduler, set_as_default=False), None
    cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1,
                           processes=True, dashboard_address=":0")
    return Client(cluster, set_as_default=False), cluster


def _start(scheduler, workers, blobs, fmus):
    """Client, cluster (or None) and worker count, every worker warm."""
    client, cluster = _client(scheduler, workers)
    try:
        client.register_plugin(worker_plugin(blobs, fmus))
        return client, cluster, max(1, len(client.scheduler_info()["workers"]))
    except BaseException:
        _close(client, cluster, scheduler)
        raise


def _close(client, cluster, scheduler=None) -> None:
    if client is not scheduler:  # a Client the caller passed stays open
        client.close()
    if cluster is not None:
        cluster.close()


def _loaded(store: FmuStore, fmus: dict[str, str]) -> bool:
    """Every FMU has an idle instance: a run opens no new one."""
    return all(store.pool.idle.get((alias, str(store.path(digest))))
               for alias, digest in fmus.items())


def _meanwhile(todo, store, fmus, record, starting) -> int:
    """Runs in this process until the cluster is ready; how many were made. Only runs
    that open no FMU: FMPy loads an FMU's library with the process's working directory
    changed to the FMU's binaries folder for a moment, and a worker process started in
    that moment would be told to start there (a folder removed later)."""
    made = 0
    while not starting.done() and made < len(todo) and _loaded(store, fmus):
        rid, values, document = todo[made]
        record(rid, values, execute(store, document, fmus))
        made += 1
    return made


PRELOAD = ["distributed", "numpy", "fmpy", "robofmu.sweep.runner",
           "robofmu.sweep.worker_signals"]  # the last: workers leave Ctrl-C to the sweep


def _worker_processes():
    """Configuration under which a LocalCluster's worker processes are forked from a
    server that imported PRELOAD once (forkserver) instead of each new interpreter
    importing them (spawn, Dask's default): 2.3 s instead of 3.8 s to two warm
    workers (medians of 4 interleaved starts on the loaded 2-core machine). Also
    for workers a nanny restarts, so it holds for the whole sweep."""
    # dask and distributed lazily: 0.4 s of start-up (benches/bench_startup.py) that a
    # serial sweep (--workers 0) and `cosim sweep --help` do not pay.
    import dask
    # distributed first: its import adds its defaults to Dask's configuration, which
    # the configuration set below would otherwise drop again when it is restored.
    from distributed.utils import get_mp_context
    if "forkserver" not in multiprocessing.get_all_start_methods():
        return contextlib.nullcontext()
    config = dask.config.set({"distributed.worker.multiprocessing-method": "forkserver"})
    get_mp_context().set_forkserver_preload(PRELOAD)  # before the server starts
    return config


def run_dask(todo, fmus, blobs, record, scheduler, workers, retries, batch, ready) -> None:
    require("distributed", "sweep", "a sweep on Dask", "run it serially (--workers 0)")
    with _worker_processes():
        _run_dask(todo, fmus, blobs, record, scheduler, workers, retries, batch, ready)


def _run_dask(todo, fmus, blobs, record, scheduler, workers, retries, batch, ready) -> None:
    # The first run before the cluster starts: it loads every FMU (and probes their
    # slopes) in this process while no worker process is being started (_meanwhile).
    # With --scheduler (an existing cluster, maybe reached from a login node) every run
    # goes to the cluster: there is no start-up to fill.
    store, made = FmuStore(blobs), 0
    try:
        if scheduler is None:
            warm(store, fmus)
            rid, values, document = todo[0]
            record(rid, values, execute(store, document, fmus))
            made = 1
        with ThreadPoolExecutor(1, thread_name_prefix="cosim-cluster-start") as pool:
            starting = pool.submit(_start, scheduler, workers, blobs, fmus)
            try:
                if scheduler is None:
                    made += _meanwhile(todo[made:], store, fmus, record, starting)
            finally:
                client, cluster, count = starting.result()
    finally:
        store.close()
    try:
        rest = todo[made:]
        size = batch or auto_batch(len(rest), count, _steps(todo))
        ready(size)
        if rest:
            _gather(client, rest, fmus, record, retries, size)
    finally:
        _close(client, cluster, scheduler)
        scratch.reclaim()  # the folders of workers that died during the sweep


def _gather(client, todo, fmus, record, retries, size) -> None:
    from distributed import as_completed  # lazy: 0.4 s (see _worker_processes)
    values_of = {rid: values for rid, values, _ in todo}
    chunks = [todo[i:i + size] for i in range(0, len(todo), size)]
    futures = {client.submit(run_on_worker, [(rid, doc) for rid, _, doc in chunk], fmus,
                             key=f"cosim-runs-{chunk[0][0]}-{len(chunk)}", pure=False,
                             retries=retries): chunk
               for chunk in chunks}
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
