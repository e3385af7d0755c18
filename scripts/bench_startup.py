"""Start-up wall time of the `cosim` command line: `cosim --help`, `cosim run --help` and
`cosim sweep --help`, each a fresh interpreter, runs interleaved, medians printed
(``python scripts/bench_startup.py [--runs 10]``). The figures behind the imports kept
lazy in cosim/ (CHANGELOG.md)."""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time

COMMANDS = {
    "cosim --help": ["--help"],
    "cosim run --help": ["run", "--help"],
    "cosim sweep --help": ["sweep", "--help"],
}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--runs", type=int, default=10, help="runs per command (default 10)")
    args = parser.parse_args()
    times: dict[str, list[float]] = {label: [] for label in COMMANDS}
    for _ in range(args.runs):
        for label, argv in COMMANDS.items():
            start = time.perf_counter()
            subprocess.run([sys.executable, "-m", "cosim", *argv], check=True,
                           stdout=subprocess.DEVNULL)
            times[label].append(time.perf_counter() - start)
    for label, values in times.items():
        print(f"{label:22s} median {1e3 * statistics.median(values):6.0f} ms "
              f"(min {1e3 * min(values):.0f}, max {1e3 * max(values):.0f}, "
              f"{args.runs} runs)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
