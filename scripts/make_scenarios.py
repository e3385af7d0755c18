#!/usr/bin/env python3
"""Writes the Rust reference of every hand-written closed-loop scenario in scenarios/
(planner -> PID -> 3-PSS plant): the loop as one continuous-time ODE
(`robofmu closed-loop reference`, Dop853 at 1e-11, every 10 ms), to
tests/closed_loop_references/<name>/<name>_ref.csv with its options file.

The scenarios are written by hand in a person's units (cosim/closed_loop.py documents
the form); the Rust reference and the Python harness both resolve them (Euler-rate
boundary conditions, triple-pole gains) when they load them.

Run after `cargo build --release`:  python3 scripts/make_scenarios.py [name ...]
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ROBOFMU = ROOT / "target" / "release" / "robofmu"
SCENARIOS = ROOT / "scenarios"
REFERENCES = ROOT / "tests" / "closed_loop_references"


def main(names: list[str]) -> None:
    for name in names or sorted(p.stem for p in SCENARIOS.glob("*.toml")):
        reference = REFERENCES / name / f"{name}_ref.csv"
        reference.parent.mkdir(parents=True, exist_ok=True)
        subprocess.run([str(ROBOFMU), "closed-loop", "reference", "--scenario",
                        str(SCENARIOS / f"{name}.toml"), "--out", str(reference),
                        "--every", "10", "--tolerance", "1e-11"], check=True)


if __name__ == "__main__":
    main(sys.argv[1:])
