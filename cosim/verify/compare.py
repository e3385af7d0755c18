"""The verdict of each signal: its samples against the band of its tolerance rule.

Samples are the result's, inside the experiment; those within 1e-9 s (relative to the
time scale) of an event time of the case are left out (a jump is right on both sides)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .case import Case
from .errors import RunFailed
from .simulate import Run
from .tolerance import Limits, Rule

EVENT_SLACK = 1e-9


@dataclass
class Verdict:
    """One signal: passed or not, where it is worst and where it first leaves its band."""

    signal: str
    rule: Rule
    tolerance: str
    passed: bool
    max_error: float
    max_error_time: float
    first_exit: float | None
    outside: int
    samples: int
    time: np.ndarray
    value: np.ndarray
    limits: Limits

    def line(self) -> str:
        """The one-line verdict a person reads."""
        where = f"max |error| {self.max_error:.3g} at t = {self.max_error_time:.6g} s"
        text = f"{'PASS' if self.passed else 'FAIL'} {self.signal}: {where}; tolerance {self.tolerance}"
        if self.first_exit is not None:
            share = 100.0 * self.outside / self.samples
            text += (f"; leaves its band at t = {self.first_exit:.6g} s "
                     f"({self.outside} of {self.samples} samples outside, {share:.3g} %)")
        return text


def kept_samples(case: Case, time: np.ndarray) -> np.ndarray:
    """The samples that are judged: inside the experiment, away from its events."""
    scale = EVENT_SLACK * max(1.0, abs(case.start), abs(case.stop))
    keep = (time >= case.start - scale) & (time <= case.stop + scale)
    for t_event in case.event_times:
        keep &= np.abs(time - t_event) > scale
    return keep


def judge(case: Case, run: Run, interface: str, signal: str) -> Verdict:
    keep = kept_samples(case, run.time)
    t, y = run.time[keep], run.series[signal][keep]
    ref_t, ref_y = case.reference.time, case.reference.columns[signal]
    rule = case.rule(interface, signal)
    limits = rule.limits(t, ref_t, ref_y, case.start, case.stop)
    outside = (y < limits.lower) | (y > limits.upper)
    error = np.abs(y - np.interp(t, ref_t, ref_y))
    worst = int(np.argmax(error))
    return Verdict(
        signal=signal, rule=rule,
        tolerance=rule.describe(ref_t, ref_y, case.start, case.stop),
        passed=bool(rule.passes(outside)), max_error=float(error[worst]),
        max_error_time=float(t[worst]),
        first_exit=float(t[np.argmax(outside)]) if outside.any() else None,
        outside=int(outside.sum()), samples=int(len(t)), time=t, value=y, limits=limits)


def judge_all(case: Case, run: Run, interface: str) -> list[Verdict]:
    scale = EVENT_SLACK * max(1.0, abs(case.start), abs(case.stop))
    if run.time[0] > case.start + scale or run.time[-1] < case.stop - scale:
        raise RunFailed(f"the result covers {run.time[0]:g} to {run.time[-1]:g} s, not the "
                        f"experiment {case.start:g} to {case.stop:g} s")
    return [judge(case, run, interface, s) for s in case.signals()]
