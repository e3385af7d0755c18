"""The benchmark's output contract (speed itself is never asserted): every timed loop
is printed and the last line is `master/minimal ratio: X`, X the master's median time
per step over the minimal FMPy loop's, as the README and other tools read it."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_bench_prints_every_loop_and_ends_with_the_ratio():
    run = subprocess.run([sys.executable, "-m", "robofmu.bench", "--runs", "1",
                          "--sweep-runs", "0", "regulation"], cwd=ROOT, check=True,
                         capture_output=True, text=True)
    lines = run.stdout.strip().splitlines()
    loops = [re.fullmatch(r"\s+(.+?)\s+([0-9.]+) us", line) for line in lines[1:-1]]
    times = {m.group(1): float(m.group(2)) for m in loops if m}
    assert sorted(times) == ["master", "master, linear extrapolation",
                             "master, quadratic extrapolation", "minimal FMPy loop"]
    # The container section (robofmu.bench_container) sits between the loops and the ratio.
    assert any(line.startswith("container/master ratio: ") for line in lines[:-1])
    ratio = float(re.fullmatch(r"master/minimal ratio: ([0-9.]+)", lines[-1]).group(1))
    assert abs(ratio - times["master"] / times["minimal FMPy loop"]) < 0.01 + 0.01 * ratio


def test_bench_sweep_prints_throughput_and_efficiency_per_worker_count():
    # Output contract of `cosim bench sweep` (speed not asserted): one row per worker
    # count; the speed-up is runs/s over the serial row's and the efficiency the
    # speed-up per worker, as printed (second formulation from the printed columns).
    run = subprocess.run([sys.executable, "-m", "robofmu.bench", "sweep", "--runs", "6",
                          "--workers", "0,1"], cwd=ROOT, check=True, capture_output=True,
                         text=True)
    lines = run.stdout.strip().splitlines()
    table = [line.split() for line in lines if re.fullmatch(r"\s+[01]\s.*", line)]
    assert [row[0] for row in table] == ["0", "1"]
    serial, one = ([float(x) for x in row[1:]] for row in table)
    wall, start, with_startup, without, speed_up, eff, eff_ex, batch = one
    assert abs(speed_up - with_startup / serial[2]) < 0.01 + 0.02 * speed_up
    assert abs(eff - speed_up) < 0.011 and abs(eff_ex - without / serial[3]) < 0.01 + 0.02 * eff_ex
    assert start <= wall and batch >= 1
    assert any(line.startswith("budget: ") for line in lines)
    assert lines[-1].startswith("predicted speed-up at 16 workers, 2000 runs")
