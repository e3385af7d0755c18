"""The JSON report: the run and one entry per signal."""

from __future__ import annotations

import json
import math

from .case import Case
from .compare import Verdict


def _number(value):
    return None if value is None or not math.isfinite(value) else value


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


def json_report(fmu: str, fmi_version: str, interface: str, case: Case,
                verdicts: list[Verdict], plots: dict[str, str], error: str | None = None) -> bytes:
    """The report; `error`: why the run failed (then no signal was judged)."""
    document = {
        "fmu": fmu,
        "fmi_version": fmi_version,
        "interface": interface,
        "case": case.name,
        "experiment": {"start": case.start, "stop": case.stop, "step": case.step,
                       "relative_tolerance": case.rel_tol},
        "passed": error is None and all(v.passed for v in verdicts),
        "error": error,
        "signals": [signal_entry(v, plots.get(v.signal)) for v in verdicts],
    }
    return (json.dumps(document, indent=2) + "\n").encode()
