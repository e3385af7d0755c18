"""Wall time of closed-loop scenarios through the FMUs: the median of several runs.
``python -m cosim.bench [--runs 5] [scenario ...]`` (names under scenarios/)."""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

from .bench_container import print_container_lines
from .master import Master
from .scenario import load_scenario

ROOT = Path(__file__).resolve().parent.parent


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m cosim.bench", description=__doc__)
    parser.add_argument("scenarios", nargs="*", default=["three_axis_quintic"])
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args(argv)
    for name in args.scenarios:
        scenario = load_scenario(ROOT / "scenarios" / f"{name}.toml")
        for coupling in ("sampled", "gauss-seidel"):
            scenario.coupling = coupling
            walls = []
            for _ in range(args.runs):
                started = time.perf_counter()
                Master(scenario).run()
                walls.append(time.perf_counter() - started)
            median = statistics.median(walls)
            print(f"{name} ({coupling}): {scenario.steps} steps of {scenario.step_size} s, "
                  f"median {median:.3f} s over {args.runs} runs "
                  f"({1e6 * median / scenario.steps:.0f} us per step; min {min(walls):.3f} s, "
                  f"max {max(walls):.3f} s)")
    print_container_lines(ROOT / "scenarios" / f"{args.scenarios[0]}.toml", args.runs)
    return 0


if __name__ == "__main__":
    sys.exit(main())
