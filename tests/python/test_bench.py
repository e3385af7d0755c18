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
    run = subprocess.run([sys.executable, "-m", "cosim.bench", "--runs", "1",
                          "--sweep-runs", "0", "regulation"], cwd=ROOT, check=True,
                         capture_output=True, text=True)
    lines = run.stdout.strip().splitlines()
    loops = [re.fullmatch(r"\s+(.+?)\s+([0-9.]+) us", line) for line in lines[1:-1]]
    times = {m.group(1): float(m.group(2)) for m in loops if m}
    assert sorted(times) == ["ctypes loop (no recording)", "master", "master (FMPy calls)",
                             "minimal FMPy loop"]
    # The container section (cosim.bench_container) sits between the loops and the ratio.
    assert any(line.startswith("container/master ratio: ") for line in lines[:-1])
    ratio = float(re.fullmatch(r"master/minimal ratio: ([0-9.]+)", lines[-1]).group(1))
    assert abs(ratio - times["master"] / times["minimal FMPy loop"]) < 0.01 + 0.01 * ratio
