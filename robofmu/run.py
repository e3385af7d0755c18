"""``cosim run SCENARIO [--out DIR] [--fmu-dir DIR] [--quiet] [--fmi3] [--no-plots]``:
one simulation of a scenario, validated first (``cosim check``), with its CSV, units,
plots and metrics summary under --out (see robofmu.outputs). Exit 1 when a limit the
scenario declares is exceeded."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from .errors import output_path, require
from .master import run_scenario, text_progress
from .outputs import write_outputs
from .report import sig
from .scenario import ScenarioError, load_scenario


def add_common(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("scenario", type=Path, help="scenario file (.toml or .json)")
    parser.add_argument("--fmu-dir", type=Path,
                        help="find the FMUs by file name here (default: relative to the "
                        "scenario, else the repository's dist/)")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_common(parser)
    parser.add_argument("--out", type=output_path, default=Path("results"),
                        help="directory for the results (default: results)")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
    parser.add_argument("--fmi3", action="store_true",
                        help="run the FMI 3.0 builds (dist/fmi3/<Model>.fmu) of the FMUs")
    parser.add_argument("--no-plots", action="store_true", help="CSV and summary only")


def output_dir(out: Path) -> Path:
    """--out, refused when it exists and is not a directory."""
    if out.exists() and not out.is_dir():
        raise ScenarioError(f"--out: {out} exists and is not a directory; name a directory")
    return out


def fmu_dir(path: Path | None) -> Path | None:
    if path is not None and not path.is_dir():
        raise ScenarioError(f"--fmu-dir: {path} is not a directory; name the folder that "
                            "holds the .fmu files")
    return path


def run(args: argparse.Namespace) -> int:
    if not args.no_plots:
        require("matplotlib", "plots", "the plots of cosim run", "run with --no-plots")
    out = output_dir(args.out)
    scenario = load_scenario(args.scenario, fmu_dir(args.fmu_dir))
    progress = None if args.quiet else text_progress()
    started = time.perf_counter()
    result = run_scenario(scenario, fmi3=args.fmi3, progress=progress, option="--fmi3")
    wall = time.perf_counter() - started
    for line in result.discards:
        print(f"cosim: {line}")
    summary = write_outputs(scenario, result, out, plots=not args.no_plots)
    print(f"{scenario.name}: {scenario.steps} steps of {scenario.step_size} s in {wall:.3f} s "
          f"wall time -> {out}/")
    human = summary.get("metrics_human", {})
    if human:
        print(f"  RMS tracking error {sig(human['rms_error_deg'])} deg (of |q - theta| over "
              f"the 3 angles), max {sig(human['max_error_deg'])} deg (one angle), peak "
              f"|actuator force| "
              f"{sig(human['peak_force_N'])} N")
    for row in summary["limits"]:
        verdict = "ok" if row["passed"] else "EXCEEDED"
        print(f"  limit {row['limit']}: {row['measured']:.6g} {row['unit']} <= "
              f"{row['bound']:.6g} {row['unit']}: {verdict}")
    if not summary["passed"]:
        print(f"cosim: {args.scenario}: field 'limits': the run exceeded a declared limit "
              "(see above and the _summary.json)", file=sys.stderr)
        return 1
    return 0
