"""One case from files to verdicts: the FMU run, every signal judged, and every file
to write (made in memory first; written all or nothing by the caller)."""

from __future__ import annotations

import time
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import junit
from .case import Case, load_case
from .compare import judge_all
from .errors import RunFailed
from .names import Names
from .plot import plot_name, plot_png
from .report import json_report, passed
from .simulate import choose_interface, read_description, simulate

REPORT = "verify.json"


@dataclass
class CaseResult:
    """A verified case: ``status`` passed or failed; ``lines`` what to print; ``files``
    by path; ``suite`` its JUnit test suite (XML text)."""

    status: str
    lines: list[str]
    summary: str
    files: dict[Path, bytes]
    suite: bytes
    signals: list[str] = field(default_factory=list)
    error: str | None = None  # why the run failed


def result_csv(run, signals: list[str]) -> bytes:
    """The result as the cross-check's CSV: quoted names, time first, one row a sample."""
    header = ",".join(f'"{name}"' for name in ["time", *signals])
    rows = np.column_stack([run.time] + [run.series[s] for s in signals])
    lines = [header] + [",".join(repr(float(x)) for x in row) for row in rows]
    return ("\n".join(lines) + "\n").encode()


def verify_case(fmu: Path, case_dir: Path | None, options, wanted: str | None, out: Path,
                name: str | None = None, out_csv: str | None = None,
                plot_all: bool = False) -> CaseResult:
    """Runs and judges one case; VerifyError on bad input (nothing made)."""
    description = read_description(fmu)
    interface = choose_interface(fmu, description, wanted)
    case = load_case(case_dir, options)
    if name is not None:
        case.name = name
    return run_case(fmu, description, interface, case, out, out_csv, plot_all)


def run_case(fmu: Path, description, interface: str, case: Case, out: Path,
             out_csv: str | None = None, plot_all: bool = False) -> CaseResult:
    """Runs and judges a loaded case; VerifyError when it does not fit the FMU.
    `plot_all`: a plot of every signal (for the results page), not only the failing."""
    title = f"{fmu.name} ({interface}) against {case.name}"
    classname = f"{fmu.stem}.{interface}"
    head = f"{fmu.name} {description.fmiVersion} {interface} against {case.name}"
    started = time.perf_counter()
    try:
        run = simulate(fmu, description, case, interface)
        verdicts, end = judge_all(case, run, interface)
    except RunFailed as e:
        files = {out / REPORT: json_report(str(fmu), description.fmiVersion, interface, case,
                                           [], {}, str(e))}
        return CaseResult("failed", [], f"{head}: the run failed: {e}", files,
                          ET.tostring(junit.error_suite(title, classname, str(e))),
                          case.signals(), str(e))
    seconds = time.perf_counter() - started
    names = Names(description)
    files, plots = {}, {}
    for v in verdicts:
        # A failing signal's plot; every signal's when the FMU ended the run early or
        # the results page shows them all.
        if plot_all or not v.passed or (end is not None and not end.allowed):
            path = out / plot_name(v.signal)
            files[path] = plot_png(case, v, title, names.unit(v.signal), end)
            plots[v.signal] = str(path)
    files[out / REPORT] = json_report(str(fmu), description.fmiVersion, interface, case,
                                      verdicts, plots, end=end)
    if out_csv is not None:
        files[out / out_csv] = result_csv(run, case.signals())
    ok = passed(verdicts, None, end)
    lines = [v.line() for v in verdicts] + ([end.line()] if end is not None else [])
    within = sum(v.passed for v in verdicts)
    summary = (f"{head}: {within} of {len(verdicts)} signals within tolerance"
               + ("" if end is None else f", run ended by the FMU at t = {end.time:.6g} s"))
    return CaseResult("passed" if ok else "failed", lines, summary, files,
                      ET.tostring(junit.suite(title, classname, verdicts, seconds, end)),
                      case.signals())
