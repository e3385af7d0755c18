"""Sweeps on Dask (robofmu.sweep): a 2-worker LocalCluster against the same runs made
serially, a killed worker, --resume, failures, malformed SPECs, the metrics, and the
instance reuse (fmi2Reset) the workers rely on.

Cost: about 30 s on 2 cores (two LocalCluster start-ups, 4 + 8 closed-loop runs of
1000 steps on the cluster, a few serial runs)."""

from __future__ import annotations

import csv
import math
import os
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from robofmu.master import Master  # noqa: E402
from robofmu.scenario import load_scenario  # noqa: E402
from robofmu.sweep import SpecError, load_spec, run_sweep  # noqa: E402
from robofmu.sweep.runner import InstancePool  # noqa: E402

BASE = '''scenario = "{scenario}"
name = "{name}"
'''
GRID_AND_DRAWS = BASE + '''seed = 3
samples = {samples}
[grid.'gains.omega']
values = {omegas}
unit = "rad/s"
[random.'plant.platformMass']
distribution = "uniform"
low = 0.75
high = 0.85
unit = "kg"
'''


def write_spec(tmp_path, text: str, name: str = "small", **fields) -> Path:
    spec = tmp_path / f"{name}.toml"
    spec.write_text(text.format(scenario=ROOT / "scenarios" / "regulation.toml", name=name,
                                **fields))
    return spec


def rows(path: Path) -> dict[str, dict]:
    """run_id -> row, without the wall time (the only column that may differ)."""
    with open(path, newline="") as f:
        return {r["run_id"]: {k: v for k, v in r.items() if k != "wall_s"}
                for r in csv.DictReader(f)}


def test_reset_instances_give_the_runs_of_fresh_instances():
    # Truth: a fresh instantiation. fmi2Reset must bring back every start value, so a
    # run after another run with other parameters is the fresh run bit for bit.
    pool = InstancePool()
    other = load_scenario(ROOT / "scenarios" / "regulation.toml")
    other.parameters["plant"]["platformMass"] = 0.85
    other.parameters["pid"]["Kp[1]"] = 900.0
    used = []
    Master(other, open_fmu=pool.open, close_fmu=used.append).run()
    for fmu in used:
        pool.release(fmu)
    scenario = load_scenario(ROOT / "scenarios" / "three_axis_quintic.toml")
    reused = Master(scenario, open_fmu=pool.open, close_fmu=pool.release).run()
    fresh = Master(scenario).run()
    assert pool.opened == 3  # the second run reused all three instances
    assert reused.columns == fresh.columns


def test_two_worker_cluster_gives_the_serial_results(tmp_path):
    spec = load_spec(write_spec(tmp_path, GRID_AND_DRAWS, samples=2, omegas="[10, 30]"))
    serial = run_sweep(spec, tmp_path / "serial", workers=0, progress=False)
    dask = run_sweep(spec, tmp_path / "dask", workers=2, progress=False)
    assert (serial.runs, serial.failed, dask.runs, dask.failed) == (4, 0, 4, 0)
    assert rows(serial.table) == rows(dask.table)
    assert [p.name for p in dask.plots] == ["small_grid.png"]  # 2 draws: no histogram


class KillOnce:
    """A worker plugin that ends its worker process the moment a task starts executing
    there, once per cluster (the marker file is created exclusively): a deterministic
    kill -9 in the middle of a run, with no thread racing the sweep."""

    name = "kill-once"

    def __init__(self, marker: str):
        self.marker = marker

    def setup(self, worker):
        pass

    def teardown(self, worker):
        pass

    def transition(self, key, start, finish, **kwargs):
        if finish == "executing" and str(key).startswith("cosim-runs-"):
            try:
                os.close(os.open(self.marker, os.O_CREAT | os.O_EXCL | os.O_WRONLY))
            except FileExistsError:
                return
            os._exit(9)


def test_a_killed_workers_runs_are_retried(tmp_path, monkeypatch):
    # Truth: the serial runs. A worker dies in the middle of its first task; the
    # scheduler gives the task to the restarted (or the other) worker and the table is
    # the serial table. The sweep runs inside a `with Client(...)` of the caller's own,
    # which once made as_completed track the sweep's futures on the caller's event loop
    # (a result lost with the worker was then awaited on the sweep's loop: "bound to a
    # different event loop", issue 19): the futures must be tracked on the sweep's loop.
    # The killed worker ran no clean-up: its folder of FMU files (robofmu.sweep.scratch)
    # must be gone after the sweep all the same, and so every worker's.
    import tempfile

    import distributed
    from distributed import Client, LocalCluster
    from distributed.diagnostics.plugin import WorkerPlugin
    spec = load_spec(write_spec(tmp_path, GRID_AND_DRAWS, samples=4, omegas="[10, 30]"))
    serial = run_sweep(spec, tmp_path / "serial", workers=0, progress=False, plots=False)
    marker = tmp_path / "killed"
    loops = []
    original = distributed.as_completed

    def tracked(futures, loop=None, **kwargs):
        loops.append(loop)
        return original(futures, loop=loop, **kwargs)

    monkeypatch.setattr(distributed, "as_completed", tracked)
    plugin = type("KillOncePlugin", (KillOnce, WorkerPlugin), {})(str(marker))
    scratch = Path(tempfile.gettempdir())
    folders_before = set(scratch.glob("cosim-fmus-*"))
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=":0") as cluster, Client(cluster) as client:
        client.register_plugin(plugin)
        outcome = run_sweep(spec, tmp_path / "dask", scheduler=cluster.scheduler_address,
                            progress=False, plots=False, batch=2)
        assert loops and loops[0] is not None and loops[0] is not client.loop
    assert marker.exists() and outcome.failed == 0 and outcome.runs == 8
    assert rows(outcome.table) == rows(serial.table)
    assert set(scratch.glob("cosim-fmus-*")) <= folders_before


def test_resume_runs_only_what_is_missing(tmp_path):
    spec = load_spec(write_spec(tmp_path, GRID_AND_DRAWS, samples=1, omegas="[10, 20, 30]"))
    full = run_sweep(spec, tmp_path / "full", workers=0, progress=False, plots=False)
    partial = tmp_path / "partial" / "small.csv"
    partial.parent.mkdir()
    lines = full.table.read_text().splitlines(keepends=True)
    # Header, one run and half of the next run's line: a sweep killed while writing.
    partial.write_text("".join(lines[:2]) + lines[2][:len(lines[2]) // 2])
    again = run_sweep(spec, tmp_path / "partial", workers=0, resume=True, progress=False,
                      plots=False)
    assert (again.runs, again.skipped) == (2, 1)  # the torn run is made again
    assert rows(partial) == rows(full.table)
    assert len(partial.read_text().splitlines()) == 4  # the torn line is gone


def test_a_failing_run_is_recorded_with_its_reason(tmp_path):
    # A plant whose spherical joint P sits at the base (lp = 0, within the declared
    # min = 0 but refused by the model: it must be positive): the run fails with the
    # plant's reason, the sweep goes on.
    text = BASE + "[grid.'plant.lp']\nvalues = [0.0, 0.632187]\nunit = \"m\"\n"
    outcome = run_sweep(load_spec(write_spec(tmp_path, text)), tmp_path, workers=0,
                        progress=False, plots=False)
    by_lp = {r["plant.lp [m]"]: r for r in rows(outcome.table).values()}
    assert outcome.failed == 1
    assert by_lp["0.0"]["status"] == "failed" and "lp" in by_lp["0.0"]["reason"]
    assert by_lp["0.632187"]["status"] == "ok"


def test_settling_time_follows_the_triple_pole_closed_form(tmp_path):
    # Truth: the loop's error with a triple pole at -w from an initial offset e0 at rest
    # (integral zero) is e0 (1 + w t - (w t)^2) e^(-w t); its last exit from the 2 %
    # band is at w t = 7.889. The co-simulation adds the zero-order hold (half a step,
    # w h / 2 = 0.005 at w = 10 rad/s, 0.015 at 30) and the neglected coupling: 1.5 %.
    s_band = brentq(lambda s: (s * s - s - 1.0) * math.exp(-s) - 0.02, 3.0, 20.0)
    text = BASE + "[grid.'gains.omega']\nvalues = [10, 30]\nunit = \"rad/s\"\n"
    outcome = run_sweep(load_spec(write_spec(tmp_path, text)), tmp_path, workers=0,
                        progress=False, plots=False)
    for row in rows(outcome.table).values():
        w = float(row["gains.omega [rad/s]"])
        assert abs(float(row["settling_time_s"]) * w / s_band - 1.0) < 0.015, row
        # Regulation from a 3 deg error: the largest error is the initial one.
        assert abs(float(row["max_error_deg"]) - 3.0) < 1e-9
        assert row["force_limit_hit"] == "0" and row["end_stop_hit"] == "0"


@pytest.mark.parametrize("text, field", [
    (BASE + "[grid.'gains.omega']\nfrom = 10\nto = 60\nsteps = 0\nunit = \"rad/s\"\n",
     "grid.gains.omega.steps"),
    (BASE + "seed = 1\nsamples = 2\n[random.'plant.platformMass']\n"
            "distribution = \"lognormal\"\n", "random.plant.platformMass.distribution"),
    (BASE + "seed = 1\nsamples = 2\n[random.'plant.platformMass']\n"
            "distribution = \"normal\"\nmean = 0.8\n", "random.plant.platformMass.sd"),
    (BASE + "[grid.'gains.omega']\nvalues = [10]\nunit = \"rad\"\n", "gains.omega"),
    (BASE + "[grid.'gains.omega']\nvalues = [10]\n", "gains.omega"),
    (BASE + "samples = 3\n[grid.'gains.omega']\nvalues = [10]\nunit = \"rad/s\"\n",
     "samples"),
    (BASE + "repeat = 3\n", "repeat"),
    (BASE, "nothing varies"),
])
def test_malformed_specs_are_refused_naming_the_field(tmp_path, text, field):
    with pytest.raises(SpecError, match=field.replace(".", r"\.")):
        load_spec(write_spec(tmp_path, text))


def test_workspace_targets_outside_the_reachable_set_are_left_out(tmp_path):
    # Truth: the plant FMU's inverse kinematics at the pose. At thx = 10 deg actuator 3
    # would be 157.8 mm long, beyond the 152 mm stroke end; at 60 deg leg 3 cannot reach
    # its platform joint; at 0 deg all three are within the stroke.
    from robofmu.sweep import reachable_on
    text = BASE + ("[workspace]\npath = \"motion.waypoints[1].angles\"\nunit = \"deg\"\n"
                   "[workspace.thx]\nvalues = [0, 10, 60]\n[workspace.thy]\nvalues = [0]\n"
                   "[workspace.thz]\nvalues = [138]\n")
    spec = load_spec(write_spec(tmp_path, text),
                     reachable=reachable_on(ROOT / "dist" / "Pss3Plant.fmu"))
    assert [run["motion.waypoints[1].angles"] for run in spec.runs] == [[0.0, 0.0, 138.0]]


def test_the_sweep_reachability_is_the_workspace_check_at_the_stroke_end():
    # Truth: robofmu/workspace.py's Workspace.problem, the one implementation, which counts
    # a length within STROKE_TOLERANCE of a stroke end as inside. Bisecting thx between
    # 0 deg (reachable) and 10 deg (actuator 3 beyond its stroke) gives a pose whose
    # length lies past strokeMax by less than that tolerance: the sweep must keep it.
    from robofmu.sweep.reach import reachable
    from robofmu.workspace import LENGTHS, STROKE_TOLERANCE, Workspace
    plant = ROOT / "dist" / "Pss3Plant.fmu"
    pose = lambda thx: (thx, 0.0, math.radians(138.0))  # noqa: E731
    inside, outside = 0.0, math.radians(10.0)
    with Workspace(plant, {}) as ws:
        assert ws.problem(pose(inside)) is None and ws.problem(pose(outside)) is not None
        for _ in range(80):
            middle = 0.5 * (inside + outside)
            if middle in (inside, outside):
                break
            if ws.problem(pose(middle)) is None:
                inside = middle
            else:
                outside = middle
        ws.problem(pose(inside))
        longest = max(ws.fmu.get_values(LENGTHS))
        stroke_max = ws.fmu.get_values(("strokeMax",))[0]
    assert stroke_max < longest <= stroke_max + STROKE_TOLERANCE
    assert reachable(plant, pose(inside)) is True
    assert reachable(plant, pose(outside)) is False


def test_the_command_refuses_a_malformed_spec_by_field(tmp_path):
    import subprocess
    spec = write_spec(tmp_path, BASE + "[grid.'gains.omega']\nfrom = 10\nto = 60\n")
    run = subprocess.run([sys.executable, "-m", "robofmu", "sweep", str(spec), "--out",
                          str(tmp_path)], cwd=ROOT, capture_output=True, text=True)
    assert run.returncode == 2
    assert "field 'grid.gains.omega.steps' must be a positive integer" in run.stderr
    assert not (tmp_path / "small.csv").exists()


def test_random_draws_are_seeded_truncated_and_follow_their_distribution():
    # Truth: the distributions' moments. Normal(0.8, 0.1) truncated to [0.7, 1.0]:
    # mean 0.8 + 0.1 (phi(-1) - phi(2)) / (Phi(2) - Phi(-1)) = 0.8288; uniform(1, 3):
    # mean 2, variance 1/3. Bounds: 5 standard errors of the mean over 4000 draws.
    from scipy.stats import norm, truncnorm
    from robofmu.sweep.spec import random_draws
    tables = {"a": {"distribution": "normal", "mean": 0.8, "sd": 0.1, "min": 0.7,
                    "max": 1.0},
              "b": {"distribution": "uniform", "low": 1.0, "high": 3.0}}
    draws = random_draws(tables, 11, 4000)
    assert draws == random_draws(tables, 11, 4000) != random_draws(tables, 12, 4000)
    a, b = (np.array(column) for column in zip(*draws))
    assert a.min() >= 0.7 and a.max() <= 1.0
    expected = 0.8 + 0.1 * (norm.pdf(-1) - norm.pdf(2)) / (norm.cdf(2) - norm.cdf(-1))
    assert expected == pytest.approx(truncnorm(-1, 2, 0.8, 0.1).mean(), rel=1e-12)
    sd = truncnorm(-1, 2, 0.8, 0.1).std()
    assert abs(a.mean() - expected) < 5 * sd / np.sqrt(len(a))
    assert abs(b.mean() - 2.0) < 5 * np.sqrt(1 / 3 / len(b))
    assert abs(b.var() - 1 / 3) < 0.03


def test_auto_batch_fits_the_task_length_and_keeps_every_worker_busy():
    # Closed form: runs per task = min(T(W) / (steps RUN_STEP_S), runs / (4 W)), at
    # least 1, with the task length T(W) = max(TASK_S, 4 W CLIENT_TASK_S).
    from robofmu.sweep.engine import CLIENT_TASK_S, RUN_STEP_S, TASK_S, auto_batch
    run_s = 1000 * RUN_STEP_S
    assert auto_batch(100000, 2, 1000) == int(TASK_S / run_s)
    assert auto_batch(100000, 16, 1000) == int(4 * 16 * CLIENT_TASK_S / run_s)
    assert auto_batch(64, 16, 1000) == 1  # 64 runs / (4 x 16 workers)
    assert auto_batch(400, 2, 1000) == min(int(TASK_S / run_s), 50)
    assert auto_batch(3, 8, 10 ** 9) == 1


def test_grid_plots_show_the_spread_of_the_draws(tmp_path):
    # Truth: numpy's median and percentiles of each grid point's draws, computed here
    # apart; below 10 draws the band is the range. No histogram of a few draws.
    from robofmu.sweep.plots import plot_sweep, spread
    rng = np.random.default_rng(5)
    rows = [{"status": "ok", "w": w, "rms_error_deg": float(w + rng.normal())}
            for w in (1.0, 2.0) for _ in range(30)]
    rows += [{"status": "ok", "w": 3.0, "rms_error_deg": v} for v in (1.0, 5.0, 2.0)]
    stats = spread(rows, ["w"], "rms_error_deg")
    for w in (1.0, 2.0):
        x = np.array([r["rms_error_deg"] for r in rows if r["w"] == w])
        assert stats[(w,)] == pytest.approx((np.median(x), *np.percentile(x, [10, 90]), 30))
    assert stats[(3.0,)] == (2.0, 1.0, 5.0, 3)
    written = plot_sweep(["run_id", "status", "reason", "w"], rows, ["w"], True, tmp_path, "s")
    assert [p.name for p in written] == ["s_grid.png"]  # 3 draws at w = 3: no histogram


def test_the_command_exits_1_with_the_reasons_of_failed_runs(tmp_path, capsys):
    # lp = 0: the plant refuses it (its own reason in the table's 'reason' column); the
    # command says how many runs failed and why, exit status 1.
    from robofmu.cli import main
    text = BASE + "[grid.'plant.lp']\nvalues = [0.0, 0.632187]\nunit = \"m\"\n"
    spec = write_spec(tmp_path, text)
    status = main(["sweep", str(spec), "--out", str(tmp_path), "--workers", "0", "--quiet"])
    err = capsys.readouterr().err.splitlines()
    reason = next(r["reason"] for r in rows(tmp_path / "small.csv").values()
                  if r["status"] == "failed")
    assert status == 1
    assert "1 of 2 runs failed" in err[0]
    assert err[1] == f"  1 x {reason}" and reason.startswith("plant")


def test_a_reused_stepping_loop_gives_the_runs_of_a_fresh_one():
    # Truth: a fresh master (its own instances and loop). A sweep worker keeps the
    # prepared loop of the last run (Master.loops) and reuses it over the same instances
    # for a run with other parameter values: bit for bit the fresh run.
    pool = InstancePool()
    runs, loops = [], []
    for kp in (900.0, 1200.0):
        scenario = load_scenario(ROOT / "scenarios" / "regulation.toml")
        scenario.input_extrapolation = "hold"  # no input derivatives: the loop is kept
        scenario.parameters["pid"]["Kp[1]"] = kp
        used: list = []
        master = Master(scenario, open_fmu=pool.open, close_fmu=used.append, loops=pool.loops)
        runs.append(master.run())
        for fmu in used:
            pool.release(fmu)
        loops += list(pool.loops.values())
        assert runs[-1].columns == Master(scenario).run().columns, kp
    assert pool.opened == 3 and len(loops) == 2 and loops[0] is loops[1]
    assert runs[0].columns["pid.u[1]"] != runs[1].columns["pid.u[1]"]
