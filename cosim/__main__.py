"""Command line: ``python -m cosim SCENARIO [--out DIR] [--fmu-dir DIR] [--quiet]``;
``python -m cosim sweep SPEC ...`` (see cosim.sweep.cli); ``python -m cosim container
SCENARIO --out X.fmu`` writes the scenario as a container FMU (see cosim.container)."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from .errors import CosimError
from .fmi3 import open_fmi3
from .master import Master, text_progress
from .scenario import ScenarioError, load_scenario


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] == ["sweep"]:
        from .sweep.cli import main as sweep
        return sweep(argv[1:])
    if argv[:1] == ["container"]:
        from .container import main as container_main
        return container_main(argv[1:])
    parser = argparse.ArgumentParser(prog="python -m cosim", description=__doc__)
    parser.add_argument("scenario", type=Path, help="scenario file (.toml or .json)")
    parser.add_argument("--out", type=Path, default=Path("results"),
                        help="directory for the result CSV (default: results)")
    parser.add_argument("--fmu-dir", type=Path,
                        help="find the FMUs by file name here instead of relative to the "
                        "scenario")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
    parser.add_argument("--fmi3", action="store_true",
                        help="run the FMI 3.0 builds (dist/fmi3/<Model>.fmu) of the FMUs")
    args = parser.parse_args(argv)
    try:
        scenario = load_scenario(args.scenario, args.fmu_dir)
        progress = None if args.quiet else text_progress()
        started = time.perf_counter()
        options = {"open_fmu": open_fmi3} if args.fmi3 else {}
        result = Master(scenario, progress=progress, **options).run()
        wall = time.perf_counter() - started
    except (ScenarioError, CosimError) as e:
        print(f"cosim: {e}", file=sys.stderr)
        return 1
    out = args.out / f"{scenario.name}.csv"
    result.write_csv(out)
    for line in result.discards:
        print(f"cosim: {line}", file=sys.stderr)
    print(f"{scenario.name}: {scenario.steps} steps of {scenario.step_size} s in {wall:.3f} s "
          f"wall time -> {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
