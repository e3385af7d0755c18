"""The JSON report: the run and one entry per signal."""

from __future__ import annotations

import json
import math

from .case import Case
from .compare import EarlyEnd, Verdict


def _number(value):
    return None if value is None or not math.isfinite(value) else value


def passed(verdicts: list[Verdict], error: str | None, end: EarlyEnd | None) -> bool:
    return (error is None and all(v.passed for v in verdicts)
            and (end is None or end.allowed))


def signal_entry(verdict: Verdict, plot: str | None) -> dict:
    return {
        "signal": verdict.signal,
        "passed": verdict.passed,
        "rule": verdict.rule.to_json(),
        "tolerance": verdict.tolerance,
        "max_error": _number(verdict.max_error),
        "max_error_time": verdict.max_error_time,
        "first_exit_time": verdict.first_exit,
        "samples_outside": verdict.outside,
        "samples": verdict.samples,
        "plot": plot,
    }


def _experiment(case: Case) -> dict:
    options = case.options
    return {"start": case.start, "stop": case.stop, "step": case.step,
            "variable_step": case.step == 0, "output_interval": case.output_interval,
            "relative_tolerance": case.rel_tol,
            "absolute_tolerance": None if options is None else options.abs_tol,
            "solver_type": None if options is None else options.solver_type,
            "stop_time_defined": True if options is None else options.stop_time_defined,
            "ignored_options": [] if options is None else options.ignored}


def json_report(fmu: str, fmi_version: str, interface: str, case: Case,
                verdicts: list[Verdict], plots: dict[str, str], error: str | None = None,
                end: EarlyEnd | None = None) -> bytes:
    """The report; `error`: why the run failed (then no signal was judged); `end`: the
    FMU ended the run before StopTime."""
    ended = None if end is None else {"time": end.time, "reason": end.reason,
                                      "allowed": end.allowed}
    document = {
        "fmu": fmu,
        "fmi_version": fmi_version,
        "interface": interface,
        "case": case.name,
        "experiment": _experiment(case),
        "passed": passed(verdicts, error, end),
        "error": error,
        "ended_early": ended,
        "signals": [signal_entry(v, plots.get(v.signal)) for v in verdicts],
    }
    return (json.dumps(document, indent=2) + "\n").encode()
