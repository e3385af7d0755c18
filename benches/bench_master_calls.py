"""Instructions per communication step of the master against the FMU calls it makes
(callgrind: counts, not times, so the figure does not depend on the machine's load).

    python benches/bench_master_calls.py [--steps 50,1050] [--scenario regulation]

For each input_extrapolation (hold, linear, quadratic) and each of two run lengths it runs the
master under callgrind and counts every instruction of the process and, apart, the
inclusive cost of every call from outside the FMUs' libraries into them (the FMU calls
alone: the FMU's own work with what it calls, libm and the allocator included). The
difference between the two run lengths removes start-up and initialisation; per step:
the master's total, the FMU calls alone, their ratio. Python's string hashing is fixed
(PYTHONHASHSEED=0): with random seeds the interpreter's dictionary work differs from
run to run by some million instructions, tens of thousands a step over 200 steps.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RUN = """
import sys, tomllib
sys.path.insert(0, {root!r})
from pathlib import Path
from robofmu.master import Master
from robofmu.scenario import parse_document
path = Path({scenario!r})
document = tomllib.loads(path.read_text())
document["stop_time"] = "{stop} s"
document["input_extrapolation"] = {mode!r}
Master(parse_document(document, path.parent)).run()
"""


FMU_LIBRARIES = ("/Pss3Plant.so", "/PID.so", "/Planner.so")


def _name(rest: str, table: dict) -> str:
    """A compressed callgrind name: "(id) name" defines, "(id)" refers."""
    rest = rest.strip()
    if rest.startswith("("):
        key, _, name = rest.partition(")")
        if name.strip():
            table[key] = name.strip()
        return table.get(key, "")
    return rest


def fmu_call_cost(path: Path) -> int:
    """Inclusive instructions of the calls from outside the FMU libraries into them."""
    objects: dict = {}
    current = callee = pending = None
    total = 0
    is_fmu = lambda ob: (ob or "").endswith(FMU_LIBRARIES)
    for line in path.read_text().splitlines():
        if line.startswith("ob="):
            current = _name(line[3:], objects)
        elif line.startswith("cob="):
            callee = _name(line[4:], objects)
        elif line.startswith("calls="):
            pending, callee = (callee if callee is not None else current), None
        elif pending is not None and line[:1] in "0123456789+-*":
            if is_fmu(pending) and not is_fmu(current):
                total += int(line.split()[1])
            pending = None
    return total


def instructions(mode: str, steps: int, scenario: Path, work: Path) -> tuple[int, int]:
    """(every instruction, the FMU calls') of a run of `steps` steps."""
    out = work / f"cg.{mode}.{steps}"
    code = RUN.format(root=str(ROOT), scenario=str(scenario), stop=steps * 1e-3, mode=mode)
    subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}",
                    sys.executable, "-c", code], check=True, capture_output=True,
                   env={**os.environ, "PYTHONHASHSEED": "0"})
    summary = re.search(r"^summary:\s+(\d+)", out.read_text(), re.MULTILINE)
    return int(summary.group(1)), fmu_call_cost(out)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--steps", default="50,1050")
    parser.add_argument("--scenario", default="regulation")
    args = parser.parse_args(argv)
    short, long = (int(x) for x in args.steps.split(","))
    scenario = ROOT / "scenarios" / f"{args.scenario}.toml"
    print(f"{args.scenario}: instructions per step (callgrind, runs of {long} - {short} steps)")
    with tempfile.TemporaryDirectory() as work:
        for mode in ("hold", "linear", "quadratic"):
            (t0, f0), (t1, f1) = (instructions(mode, n, scenario, Path(work))
                                  for n in (short, long))
            total, fmu = (t1 - t0) / (long - short), (f1 - f0) / (long - short)
            print(f"  {mode:>6}: master {total / 1e3:8.1f} k, FMU calls {fmu / 1e3:8.1f} k, "
                  f"master/FMU calls {total / fmu:5.2f}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
