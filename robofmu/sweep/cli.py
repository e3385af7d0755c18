"""``cosim sweep SPEC [--out DIR] [--scheduler ADDRESS | --workers N] [--batch N]
[--resume] [--fmu-dir DIR] [--quiet]``: runs a sweep (see robofmu.sweep.spec).

Exit status: 0 every run ok, 1 some runs failed (a summary of their reasons on
stderr), 2 a user error (SPEC, argument or table; one line naming the field)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..errors import output_path, require
from . import SpecError, sweep_file
from .spec import MAX_RUNS


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("spec", type=Path, help="sweep specification (.toml)")
    parser.add_argument("--out", type=output_path, default=Path("results"),
                        help="directory for the table and plots (default: results)")
    parser.add_argument("--scheduler", help="address of an existing Dask scheduler, e.g. "
                        "tcp://host:8786 (default: a LocalCluster with one worker process "
                        "per core)")
    parser.add_argument("--workers", type=int, default=None,
                        help="LocalCluster workers (default: one per core; 0: serially "
                        "in this process)")
    parser.add_argument("--batch", type=int, default=None,
                        help="runs per Dask task (default: sized automatically)")
    parser.add_argument("--resume", action="store_true",
                        help="skip the runs the table already holds as ok")
    parser.add_argument("--fmu-dir", type=Path,
                        help="find the FMUs by file name here instead of relative to the "
                        "scenario")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")


def _check_arguments(args) -> None:
    if args.workers is not None and not 0 <= args.workers <= 1024:
        raise SpecError(f"--workers: {args.workers} is out of range; give 0 (serial) to "
                        "1024 workers")
    if args.batch is not None and not 1 <= args.batch <= MAX_RUNS:
        raise SpecError(f"--batch: {args.batch} is out of range; give 1 to {MAX_RUNS} runs "
                        "per task or leave it out")
    if args.scheduler is not None and args.workers is not None:
        raise SpecError("--scheduler and --workers: give one of them (the scheduler's "
                        "cluster has its own workers)")
    if args.out.exists() and not args.out.is_dir():
        raise SpecError(f"--out: {args.out} is not a directory; give a directory")


def run(args: argparse.Namespace) -> int:
    require("matplotlib", "plots", "the plots of cosim sweep")
    try:
        _check_arguments(args)
        spec, outcome = sweep_file(args.spec, args.out, args.fmu_dir, scheduler=args.scheduler,
                                   workers=args.workers, resume=args.resume,
                                   progress=not args.quiet, batch=args.batch)
    except (SpecError, ValueError, OSError) as e:
        print(f"cosim: {_one_line(e)}", file=sys.stderr)
        return 2
    print(f"{spec.name}: {outcome.runs} runs ({outcome.failed} failed, {outcome.skipped} "
          f"done before) in {outcome.wall_s:.1f} s -> {outcome.table}"
          + "".join(f", {p}" for p in outcome.plots))
    if outcome.failed:
        print(f"cosim: {args.spec}: {outcome.failed} of {outcome.runs} runs failed; the "
              f"reasons (column 'reason' of {outcome.table}):", file=sys.stderr)
        for reason, count in outcome.reasons.most_common(5):
            print(f"  {count} x {reason}", file=sys.stderr)
        if len(outcome.reasons) > 5:
            print(f"  ... and {len(outcome.reasons) - 5} other reasons", file=sys.stderr)
        return 1
    return 0


def _one_line(error: Exception) -> str:
    text = " ".join(str(error).split())
    return text if len(text) <= 400 else text[:397] + "..."
