"""Start-up wall time of the `cosim` command line, each run a fresh interpreter, runs
interleaved, medians printed: `cosim --help`, `cosim run --help`, `cosim sweep --help`,
and the import of each module that robofmu/ keeps lazy (the figures named where it does,
and in CHANGELOG.md).

    python benches/bench_startup.py [--runs 10] [--tree DIR ...]

--tree: run the commands in each of these checkouts too (e.g. an older robofmu/ exported
with `git archive REV robofmu | tar -x -C DIR`), interleaved with this one."""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
COMMANDS = {
    "cosim --help": ["-m", "robofmu", "--help"],
    "cosim run --help": ["-m", "robofmu", "run", "--help"],
    "cosim sweep --help": ["-m", "robofmu", "sweep", "--help"],
}
# Kept lazy in robofmu/: the table's command modules (robofmu.cli) and the heavy optional
# packages; `python -c pass` is the interpreter's own start-up.
IMPORTS = {
    "python -c pass": "pass",
    "every command module": "import robofmu.run, robofmu.check, robofmu.sweep.cli, robofmu.ssp, "
                            "robofmu.container, robofmu.bench, robofmu.demo, robofmu.verify.cli, "
                            "robofmu.animate.cli, robofmu.list_fmus, robofmu.list_examples",
    "matplotlib.pyplot": "import matplotlib.pyplot",
    "matplotlib.figure": "import matplotlib.figure",
    "distributed": "import distributed",
    "fmu_manipulation_toolbox": "import fmu_manipulation_toolbox.container",
}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=10, help="runs per case (default 10)")
    parser.add_argument("--tree", type=Path, action="append", default=[],
                        help="another checkout to time the commands in")
    args = parser.parse_args()
    cases = {}
    for tree in [ROOT, *args.tree]:
        tag = "" if tree == ROOT else f" [{tree.name}]"
        cases.update({(label + tag, str(tree)): argv for label, argv in COMMANDS.items()})
    cases.update({(label, str(ROOT)): ["-c", code] for label, code in IMPORTS.items()})
    times: dict[tuple[str, str], list[float]] = {case: [] for case in cases}
    for _ in range(args.runs):
        for (label, cwd), argv in cases.items():
            start = time.perf_counter()
            subprocess.run([sys.executable, *argv], cwd=cwd, check=True,
                           stdout=subprocess.DEVNULL)
            times[(label, cwd)].append(time.perf_counter() - start)
    for (label, _), values in times.items():
        print(f"{label:34s} median {1e3 * statistics.median(values):5.0f} ms "
              f"(min {1e3 * min(values):.0f}, max {1e3 * max(values):.0f}, "
              f"{args.runs} runs)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
