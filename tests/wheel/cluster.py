"""A sweep through the public API on a real Dask cluster: one `dask scheduler` and two
`dask worker` processes, each started as its own process in its own empty folder, in
the environment where only the wheel is installed (run by scripts/test-wheel.sh with
that venv's python; no checkout on any path). robofmu.run_sweep gets an existing
dask.distributed.Client; the FMUs reach the workers from the client (the sweep's worker
plugin carries their bytes: the client reads them from a folder only it is given); the
table equals the serial sweep's, run for run and column for column (wall time aside).

Everything binds to 127.0.0.1; every wait is bounded; the three processes are killed
(their whole process groups) at the end, also on failure.

    python cluster.py CHECKOUT     CHECKOUT: the repository, which must be on no path
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import robofmu

START_TIMEOUT_S = 90.0


def start(args: list[str], folder: Path, env: dict[str, str]) -> subprocess.Popen[bytes]:
    """A process in its own empty folder and process group; its output to a log beside, its
    temporary files (the sweep's FMU folder on a worker) in a folder beside, removed with
    the rest: a worker killed at the end runs no clean-up."""
    assert not any(folder.iterdir()), f"{folder} is not empty"
    log = (folder.parent / f"{folder.name}.log").open("wb")
    tmp = folder.parent / f"{folder.name}-tmp"
    tmp.mkdir()
    return subprocess.Popen(args, cwd=folder, env=dict(env, TMPDIR=str(tmp)), stdout=log,
                            stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                            start_new_session=True)


def stop(processes: list[subprocess.Popen[bytes]]) -> None:
    """SIGTERM to each process group, SIGKILL to what is left after 10 s."""
    for p in processes:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGTERM)
    deadline = time.monotonic() + 10.0
    for p in processes:
        try:
            p.wait(timeout=max(0.1, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            pass
        try:
            os.killpg(p.pid, signal.SIGKILL)  # also a worker process the nanny started
        except ProcessLookupError:
            pass
        p.wait(timeout=10.0)


def worker_facts(dask_worker: Any) -> dict[str, object]:
    """Run on each worker (client.run): where it runs, what it imports, which FMU files
    its sweep plugin holds."""
    plugins = dask_worker.plugins
    stores = [p.store for p in plugins.values() if hasattr(p, "store")]
    files = sorted(f.name for s in stores if s.folder is not None for f in s.folder.iterdir())
    return {"cwd": os.getcwd(), "path": list(sys.path), "robofmu": robofmu.__file__,
            "executable": sys.executable, "fmus": files}


def main(checkout: Path) -> None:
    from distributed import Client, get_task_stream

    started = time.perf_counter()
    root = Path(tempfile.mkdtemp(prefix="robofmu-cluster-"))
    folders = {name: root / name for name in ("scheduler", "worker1", "worker2", "client")}
    for folder in folders.values():
        folder.mkdir()
    bin_dir = Path(sys.executable).parent
    env = {"PATH": f"{bin_dir}:/usr/bin:/bin", "HOME": str(root), "LANG": "C.UTF-8",
           "DASK_DISTRIBUTED__WORKER__DAEMON": "False"}
    scheduler_file = root / "scheduler.json"
    processes: list[subprocess.Popen[bytes]] = []
    try:
        processes.append(start([str(bin_dir / "dask"), "scheduler", "--host", "127.0.0.1",
                                "--port", "0", "--dashboard-address", "127.0.0.1:0",
                                "--scheduler-file", str(scheduler_file)],
                               folders["scheduler"], env))
        for name in ("worker1", "worker2"):
            processes.append(start([str(bin_dir / "dask"), "worker", "--scheduler-file",
                                    str(scheduler_file), "--host", "127.0.0.1",
                                    "--dashboard-address", "127.0.0.1:0", "--nworkers", "1",
                                    "--nthreads", "1", "--local-directory", ".",
                                    "--name", name], folders[name], env))
        deadline = time.monotonic() + START_TIMEOUT_S
        while not scheduler_file.exists():
            if time.monotonic() > deadline or processes[0].poll() is not None:
                raise SystemExit(f"cluster: the scheduler did not start; see {root}/scheduler.log")
            time.sleep(0.1)
        address = json.loads(scheduler_file.read_text())["address"]
        assert address.startswith("tcp://127.0.0.1:"), address

        # The client's FMUs: copies of the bundled ones in a folder only the client is given.
        fmu_dir = folders["client"] / "fmus"
        fmu_dir.mkdir()
        for name in ("Planner", "PID", "Pss3Plant"):
            shutil.copy(robofmu.fmu(name), fmu_dir / f"{name}.fmu")
        digests = {hashlib.sha256((fmu_dir / f"{n}.fmu").read_bytes()).hexdigest()[:20]
                   for n in ("Planner", "PID", "Pss3Plant")}
        spec = folders["client"] / "sweep.toml"
        spec.write_text(f"""\
scenario = {json.dumps(str(robofmu.example("regulation")))}
name = "cluster"
seed = 11
samples = 2

[grid.'gains.omega']
from = 20
to = 40
steps = 3
unit = "rad/s"

[random.'plant.legMass']
distribution = "normal"
mean = 0.9467
sd = 0.09467
min = 0.75
max = 1.15
unit = "kg"
""")
        serial = robofmu.run_sweep(spec, folders["client"] / "serial", fmu_dir=fmu_dir)

        with Client(address, timeout=START_TIMEOUT_S) as client:
            client.wait_for_workers(2, timeout=START_TIMEOUT_S)
            with get_task_stream(client) as stream:
                on_cluster = robofmu.run_sweep(spec, folders["client"] / "cluster",
                                               client=client, fmu_dir=fmu_dir)
            # Every run went to the workers: the tasks of the sweep (a batch of runs each).
            tasks = [t for t in stream.data if str(t["key"]).startswith("cosim-runs-")]
            ran = sum(int(str(t["key"]).rsplit("-", 1)[1]) for t in tasks)
            assert ran == 6, stream.data
            print(f"cluster: {len(tasks)} tasks of the sweep ran on "
                  f"{len({t['worker'] for t in tasks})} of the 2 workers, {ran} runs in all")
            facts = client.run(worker_facts)
        assert len(facts) == 2, facts
        venv = Path(sys.prefix).resolve()
        for worker, fact in facts.items():
            cwd = Path(str(fact["cwd"])).resolve()
            assert cwd.parent == root.resolve() and cwd.name.startswith("worker"), (worker, cwd)
            assert Path(str(fact["robofmu"])).resolve().is_relative_to(venv), (worker, fact)
            assert Path(str(fact["executable"])).parent.resolve() == bin_dir.resolve(), fact
            path = [str(p) for p in fact["path"]]
            on_path = [p for p in path if p and Path(p).resolve().is_relative_to(checkout)]
            assert not on_path, f"{worker}: the checkout is on sys.path: {on_path}"
            # The FMUs it ran: the client's bytes (named by their digest), written by the plugin.
            held = {f.removesuffix(".fmu") for f in fact["fmus"]}
            assert held == digests, (worker, held, digests)
            print(f"cluster: {worker}: cwd {cwd.name}/, robofmu from the wheel's venv, "
                  f"{len(path)} sys.path entries, none in the checkout; FMUs {sorted(held)}")

        assert serial.runs == on_cluster.runs == 6 and serial.failed == on_cluster.failed == 0
        a, b = serial.rows(), on_cluster.rows()
        key = "run_id"
        assert [r[key] for r in a] == [r[key] for r in b] or sorted(r[key] for r in a) == sorted(
            r[key] for r in b), (a, b)
        by_run = {r[key]: r for r in b}
        compared = 0
        for row in a:
            other = by_run[row[key]]
            for column, value in row.items():
                if column != "wall_s":
                    assert other[column] == value, (row[key], column, value, other[column])
                    compared += 1
        rms = [float(r["rms_error_deg"]) for r in a]
        assert all(0.0 < x < 3.0 for x in rms), rms
        print(f"cluster: 6 runs on 2 dask workers = the serial sweep ({compared} values equal; "
              f"RMS error {min(rms):.4f}..{max(rms):.4f} deg), "
              f"{time.perf_counter() - started:.1f} s with the cluster's start")
    finally:
        stop(processes)
        shutil.rmtree(root, ignore_errors=True)


if __name__ == "__main__":
    main(Path(sys.argv[1]).resolve())
