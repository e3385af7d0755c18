#!/usr/bin/env python3
"""Writes the Rust reference of every hand-written closed-loop scenario in scenarios/
(planner -> PID -> 3-PSS plant): the loop as one continuous-time ODE
(`robofmu closed-loop reference`, Dop853 at 1e-11, every 10 ms), to
tests/closed_loop_references/<name>/<name>_ref.csv with its options file.

The scenarios are written by hand in a person's units (docs/user-guide.md); the Python
harness alone resolves them (units, Euler-rate boundary conditions, triple-pole gains,
workspace) and writes their expanded SI form to tests/scenarios/expanded/<name>.toml
(`cosim check --expanded`), which the Rust reference reads.

Run after `cargo build --release` and scripts/setup-venv.sh:
    .venv/bin/python scripts/make_scenarios.py [name ...]
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ROBOFMU = ROOT / "target" / "release" / "robofmu"
SCENARIOS = ROOT / "scenarios"
EXPANDED = ROOT / "tests" / "scenarios" / "expanded"
REFERENCES = ROOT / "tests" / "closed_loop_references"
# Scenarios with plant parameters the reference does not model (it uses the default plant).
HARNESS_ONLY = {"heavy_platform"}


def main(names: list[str]) -> None:
    for name in names or sorted(p.stem for p in SCENARIOS.glob("*.toml")
                                if p.stem not in HARNESS_ONLY):
        expanded = EXPANDED / f"{name}.toml"
        subprocess.run([sys.executable, "-m", "robofmu", "check", str(SCENARIOS / f"{name}.toml"),
                        "--expanded", str(expanded)], check=True, cwd=ROOT)
        reference = REFERENCES / name / f"{name}_ref.csv"
        reference.parent.mkdir(parents=True, exist_ok=True)
        subprocess.run([str(ROBOFMU), "closed-loop", "reference", "--scenario",
                        str(expanded), "--out", str(reference),
                        "--every", "10", "--tolerance", "1e-11"], check=True)


if __name__ == "__main__":
    main(sys.argv[1:])
