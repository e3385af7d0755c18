"""``cosim verify FMU [CASE] [options]``: exit 0 when every reference column is within
its tolerance, 1 when one is not (or the FMU run fails), 2 on bad input."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from ..errors import output_path
from .case import load_case
from .compare import judge_all
from .errors import COMMAND_LINE, RunFailed, VerifyError
from .files import write_all
from .junit import junit_error, junit_report
from .plot import plot_name, plot_png
from .report import json_report
from .simulate import choose_interface, read_description, simulate

REPORT = "verify.json"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.description = ("Run an FMU through FMPy and compare it with reference results "
                          "(docs/verify.md).")
    parser.add_argument("fmu", type=Path, help="the FMU (FMI 2.0 or 3.0)")
    parser.add_argument("case", type=Path, nargs="?",
                        help="case folder: <Model>_ref.csv, <Model>_ref.opt, optional "
                        "<Model>_in.csv and case.json")
    parser.add_argument("--reference", type=Path, help="reference CSV (instead of the case's)")
    parser.add_argument("--input", type=Path, help="input CSV (instead of the case's)")
    parser.add_argument("--start", action="append", metavar="NAME=VALUE",
                        help="a start value (repeatable; over the case file's)")
    parser.add_argument("--tolerance", action="append", metavar="NAME=ABS[,REL]",
                        help="a signal's tolerance: ABS, ABS,REL (x range) or cross-check; "
                        "NAME * for every signal without one (repeatable)")
    parser.add_argument("--interface", choices=["cs", "me"],
                        help="Co-Simulation or Model Exchange (default: cs when supported)")
    parser.add_argument("--step", type=float,
                        help="communication step and output interval in s (default: the "
                        "case's StepSize)")
    parser.add_argument("--out", type=output_path, default=Path("results/verify"),
                        help=f"folder for {REPORT} and the PNG of each failing signal "
                        "(default: results/verify)")
    parser.add_argument("--junit", type=output_path, help="also write JUnit XML to this file")


def _title(args, interface, case) -> str:
    return f"{args.fmu.name} ({interface}) against {case.name}"


def _outputs(args, description, interface, case, verdicts, seconds) -> dict[Path, bytes]:
    """Every file to write, by path, made before any is written."""
    files, plots = {}, {}
    for v in verdicts:
        if not v.passed:
            path = args.out / plot_name(v.signal)
            files[path] = plot_png(case, v, _title(args, interface, case))
            plots[v.signal] = str(path)
    files[args.out / REPORT] = json_report(str(args.fmu), description.fmiVersion, interface,
                                           case, verdicts, plots)
    if args.junit is not None:
        files[args.junit] = junit_report(_title(args, interface, case),
                                         f"{args.fmu.stem}.{interface}", verdicts, seconds)
    return files


def _failure_outputs(args, description, interface, case, error: str) -> dict[Path, bytes]:
    """The reports of a run that failed: the error, no verdicts."""
    files = {args.out / REPORT: json_report(str(args.fmu), description.fmiVersion, interface,
                                            case, [], {}, error)}
    if args.junit is not None:
        files[args.junit] = junit_error(_title(args, interface, case),
                                        f"{args.fmu.stem}.{interface}", error)
    return files


def _write(files: dict[Path, bytes], out: Path, signals) -> None:
    """Writes `files`, then removes the PNG an earlier run wrote for a signal of this case
    that this run did not plot (only `<signal>.png` names that verify itself writes)."""
    try:
        write_all(files)
    except OSError as e:
        raise VerifyError(e.filename or out, "--out/--junit",
                          f"cannot be written ({e.strerror})",
                          "give a writable folder; nothing was written") from None
    for signal in signals:
        stale = out / plot_name(signal)
        try:
            if stale not in files and stale.is_file():
                stale.unlink()
        except OSError as e:
            raise VerifyError(stale, "--out", f"an earlier run's plot cannot be removed "
                              f"({e.strerror})", "remove it by hand") from None


def _verify(args) -> int:
    if args.step is not None and not args.step > 0:
        raise VerifyError(COMMAND_LINE, "--step", f"{args.step:g} is not positive",
                          "give the step in seconds, e.g. --step 0.001")
    description = read_description(args.fmu)
    interface = choose_interface(args.fmu, description, args.interface)
    case = load_case(args.case, args)
    started = time.perf_counter()
    try:
        verdicts = judge_all(case, simulate(args.fmu, description, case, interface), interface)
    except RunFailed as e:
        _write(_failure_outputs(args, description, interface, case, str(e)), args.out,
               case.reference.columns)
        raise
    _write(_outputs(args, description, interface, case, verdicts,
                    time.perf_counter() - started), args.out, case.reference.columns)
    for v in verdicts:
        print(v.line())
    failed = sum(not v.passed for v in verdicts)
    print(f"{args.fmu.name} {description.fmiVersion} {interface} against {case.name}: "
          f"{len(verdicts) - failed} of {len(verdicts)} signals within tolerance "
          f"-> {args.out / REPORT}")
    return 1 if failed else 0


def run(args: argparse.Namespace) -> int:
    try:
        return _verify(args)
    except VerifyError as e:
        if getattr(args, "debug", False):
            raise
        print(f"cosim: {e}", file=sys.stderr)
        return 2
    except RunFailed as e:
        if getattr(args, "debug", False):
            raise
        print(f"cosim: {e}", file=sys.stderr)
        return 1
