"""``python -m cosim sweep SPEC [--out DIR] [--scheduler ADDRESS | --workers N]
[--resume] [--fmu-dir DIR] [--quiet]``: runs a sweep (see cosim.sweep.spec)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from . import SpecError, load_spec, reachable_on, run_sweep


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m cosim sweep", description=__doc__)
    add_arguments(parser)
    return run(parser.parse_args(argv))


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("spec", type=Path, help="sweep specification (.toml)")
    parser.add_argument("--out", type=Path, default=Path("results"),
                        help="directory for the table and plots (default: results)")
    parser.add_argument("--scheduler", help="address of an existing Dask scheduler "
                        "(default: a LocalCluster with one worker process per core)")
    parser.add_argument("--workers", type=int, default=None,
                        help="LocalCluster workers (default: one per core; 0: serially "
                        "in this process)")
    parser.add_argument("--resume", action="store_true",
                        help="skip the runs the table already holds as ok")
    parser.add_argument("--fmu-dir", type=Path,
                        help="find the FMUs by file name here instead of relative to the "
                        "scenario")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")


def run(args: argparse.Namespace) -> int:
    try:
        spec = load_spec(args.spec, args.fmu_dir, reachable=_reachable(args))
        outcome = run_sweep(spec, args.out, scheduler=args.scheduler, workers=args.workers,
                            resume=args.resume, progress=not args.quiet)
    except (SpecError, ValueError, OSError) as e:
        print(f"cosim sweep: {e}", file=sys.stderr)
        return 1
    print(f"{spec.name}: {outcome.runs} runs ({outcome.failed} failed, {outcome.skipped} "
          f"done before) in {outcome.wall_s:.1f} s -> {outcome.table}"
          + "".join(f", {p}" for p in outcome.plots))
    return 0


def _reachable(args):
    """The workspace filter on the base scenario's plant FMU."""
    import tomllib
    data = tomllib.loads(args.spec.read_text())
    scenario = (args.spec.parent / str(data.get("scenario", ""))).resolve()
    try:
        plant = tomllib.loads(scenario.read_text())["fmus"]["plant"]
    except (OSError, KeyError, tomllib.TOMLDecodeError):
        return None  # load_spec reports the scenario's problem by field
    path = (args.fmu_dir / Path(plant).name) if args.fmu_dir else scenario.parent / plant
    return reachable_on(path)


if __name__ == "__main__":
    sys.exit(main())
