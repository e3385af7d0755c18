"""``cosim verify FMU [CASE] [options]``: exit 0 when every reference column is within
its tolerance, 1 when one is not (or the FMU run fails, or the FMU ends the run before
StopTime without --allow-early-end), 2 on bad input. ``cosim verify FMU`` without CASE
and --reference: every experiment the FMU carries (FMI-LS-REF, robofmu.verify.own).
``cosim verify TREE``: every case of an FMI cross-check tree (robofmu.verify.tree)."""

from __future__ import annotations

import argparse
import re
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

from ..errors import output_path
from . import junit
from .errors import COMMAND_LINE, RunFailed, VerifyError
from .files import write_all
from .own import own_experiments
from .plot import plot_name
from .runner import REPORT, run_case, verify_case
from .simulate import choose_interface, read_description
from .tree import verify_tree


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.description = ("Run an FMU through FMPy and compare it with reference results, "
                          "or every case of an FMI cross-check tree (docs/verify.md).")
    parser.add_argument("fmu", type=Path, metavar="FMU|TREE",
                        help="the FMU (FMI 2.0 or 3.0), or a folder in the FMI cross-check "
                        "layout (fmus/<FMI version>/<cs|me>/<platform>/<tool>/<version>/"
                        "<Model>/) to verify every case of it")
    parser.add_argument("case", type=Path, nargs="?",
                        help="case folder: <Model>_ref.csv, <Model>_ref.opt, optional "
                        "<Model>_in.csv and case.json; without it and --reference, every "
                        "experiment the FMU carries (FMI-LS-REF)")
    parser.add_argument("--reference", type=Path, help="reference CSV (instead of the case's)")
    parser.add_argument("--input", type=Path, help="input CSV (instead of the case's)")
    parser.add_argument("--start", action="append", metavar="NAME=VALUE",
                        help="a start value (repeatable; over the case file's)")
    parser.add_argument("--tolerance", action="append", metavar="NAME=ABS[,REL]",
                        help="a signal's tolerance: ABS, ABS,REL (x range) or cross-check; "
                        "NAME * for every signal without one (repeatable)")
    parser.add_argument("--interface", choices=["cs", "me"],
                        help="Co-Simulation or Model Exchange (default: cs when supported); "
                        "in a tree: run only the cases of this interface")
    parser.add_argument("--step", type=float,
                        help="communication step and output interval in s (default: the "
                        "case's StepSize; StepSize 0: docs/verify.md)")
    parser.add_argument("--allow-early-end", action="store_true",
                        help="pass a case whose FMU ends the run before StopTime when its "
                        "signals are within tolerance up to that time")
    parser.add_argument("--jobs", type=int, default=1,
                        help="cases run at once in a tree, each in its own process "
                        "(default: 1)")
    parser.add_argument("--out", type=output_path, default=Path("results/verify"),
                        help=f"folder for {REPORT} and the PNG of each failing signal; for "
                        "a tree, the results tree (default: results/verify)")
    parser.add_argument("--junit", type=output_path, help="also write JUnit XML to this file")
    parser.add_argument("--html", type=output_path, help="a tree: also write the results page "
                        "(FMU x importer x platform, each case's numbers, plots and files) "
                        "to this file")


def write_files(files: dict[Path, bytes], out: Path, signals) -> None:
    """Writes `files`, then removes the PNG an earlier run wrote for a signal of this case
    that this run did not plot (only `<signal>.png` names that verify itself writes)."""
    write_cases(files, [(out, signals)])


def write_cases(files: dict[Path, bytes], cases: list[tuple[Path, list[str]]]) -> None:
    """`write_files` for several cases (each its folder and its signals)."""
    try:
        write_all(files)
    except OSError as e:
        raise VerifyError(e.filename or cases[0][0], "--out/--junit",
                          f"cannot be written ({e.strerror})",
                          "give a writable folder; nothing was written") from None
    for out, signals in cases:
        for signal in signals:
            stale = out / plot_name(signal)
            try:
                if stale not in files and stale.is_file():
                    stale.unlink()
            except OSError as e:
                raise VerifyError(stale, "--out", f"an earlier run's plot cannot be removed "
                                  f"({e.strerror})", "remove it by hand") from None


def _folder(name: str, taken: set[str]) -> str:
    """A folder name for an experiment: its name with only letters, digits, '.', '_'
    and '-' (others '_'), made unique."""
    folder = re.sub(r"[^A-Za-z0-9._-]+", "_", name).strip("._") or "experiment"
    unique, k = folder, 2
    while unique in taken:
        unique, k = f"{folder}_{k}", k + 1
    taken.add(unique)
    return unique


def _verify_own(args) -> int:
    """Every experiment the FMU carries, each as a case in OUT/<experiment>/."""
    if args.input is not None:
        raise VerifyError(COMMAND_LINE, "--input", "needs a case folder or --reference",
                          "give one, or leave --input out to run the FMU's own experiments")
    description = read_description(args.fmu)
    interface = choose_interface(args.fmu, description, args.interface)
    taken: set[str] = set()
    results = []
    for own in own_experiments(args.fmu, description, args):
        out = args.out / _folder(own.case.name, taken)
        results.append((out, run_case(args.fmu, description, interface, own.case, out)))
    files: dict[Path, bytes] = {}
    for _, result in results:
        files.update(result.files)
    if args.junit is not None:
        files[args.junit] = junit.document([ET.fromstring(r.suite) for _, r in results])
    write_cases(files, [(out, r.signals) for out, r in results])
    for out, result in results:
        for line in result.lines:
            print(line)
        print(f"{result.summary} -> {out / REPORT}")
    passed = sum(r.status == "passed" for _, r in results)
    print(f"{args.fmu}: {passed} of {len(results)} experiments passed -> {args.out}")
    return 0 if passed == len(results) else 1


def _verify(args) -> int:
    if args.step is not None and not args.step > 0:
        raise VerifyError(COMMAND_LINE, "--step", f"{args.step:g} is not positive",
                          "give the step in seconds, e.g. --step 0.001")
    if args.jobs < 1:
        raise VerifyError(COMMAND_LINE, "--jobs", f"{args.jobs} is not positive",
                          "give the number of cases to run at once, e.g. --jobs 2")
    if args.fmu.is_dir():
        return verify_tree(args)
    if args.html is not None:
        raise VerifyError(COMMAND_LINE, "--html", "is written for a tree only",
                          "give a cross-check tree, or leave --html out")
    if args.case is None and args.reference is None:
        return _verify_own(args)
    result = verify_case(args.fmu, args.case, args, args.interface, args.out)
    files = dict(result.files)
    if args.junit is not None:
        files[args.junit] = junit.document([ET.fromstring(result.suite)])
    write_files(files, args.out, result.signals)
    if result.error is not None:
        raise RunFailed(result.error)
    for line in result.lines:
        print(line)
    print(f"{result.summary} -> {args.out / REPORT}")
    return 0 if result.status == "passed" else 1


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
