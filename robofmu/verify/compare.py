"""The verdict of each signal: its samples against the band of its tolerance rule.

Samples are the result's, inside the experiment (up to the time the FMU ended the run,
when it ended it early); those within 1e-9 s (relative to the time scale) of an event
time of the case file are left out (a jump is right on both sides). At a time the
reference writes twice (an event), a result sample is compared with the value before
the jump when the result records the instant twice and it is the first of them, with the
value after it when it is the last, and with either when the result has one sample
there (events.sides)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .case import Case
from .errors import RunFailed
from .events import EITHER, LEFT, RIGHT, interp, sides
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
    reference: np.ndarray  # the reference each sample was compared with
    limits: Limits
    outside_mask: np.ndarray  # the samples outside the band

    def line(self) -> str:
        """The one-line verdict a person reads."""
        where = f"max |error| {self.max_error:.3g} at t = {self.max_error_time:.6g} s"
        text = f"{'PASS' if self.passed else 'FAIL'} {self.signal}: {where}; tolerance {self.tolerance}"
        if self.first_exit is not None:
            share = 100.0 * self.outside / self.samples
            text += (f"; leaves its band at t = {self.first_exit:.6g} s "
                     f"({self.outside} of {self.samples} samples outside, {share:.3g} %)")
        return text


@dataclass
class EarlyEnd:
    """The FMU ended the run at `time`, before StopTime; `reason`: its last log message."""

    time: float
    stop: float
    reason: str | None
    allowed: bool

    def line(self) -> str:
        said = f": {self.reason}" if self.reason else " (the FMU logged no reason)"
        verdict = "ENDED" if self.allowed else "FAIL"
        text = (f"{verdict} run: the FMU ended the run at t = {self.time:.6g} s, before "
                f"StopTime {self.stop:g} s{said}; the signals are judged up to {self.time:.6g} s")
        return text + ("" if self.allowed else " (--allow-early-end accepts this)")


def _slack(case: Case) -> float:
    return EVENT_SLACK * max(1.0, abs(case.start), abs(case.stop))


def kept_samples(case: Case, time: np.ndarray, stop: float) -> np.ndarray:
    """The samples that are judged: from StartTime to `stop`, away from the case file's
    events."""
    scale = _slack(case)
    keep = (time >= case.start - scale) & (time <= stop + scale)
    for t_event in case.event_times:
        keep &= np.abs(time - t_event) > scale
    return keep


def judge(case: Case, run: Run, interface: str, signal: str, stop: float) -> Verdict:
    keep = kept_samples(case, run.time, stop)
    t, y = run.time[keep], run.series[signal][keep]
    ref_t, ref_y = case.reference.time, case.reference.columns[signal]
    rule = case.rule(interface, signal)
    side = sides(t)
    before, after = (rule.limits(t, ref_t, ref_y, case.start, stop, s) for s in (LEFT, RIGHT))
    ref_before, ref_after = interp(t, ref_t, ref_y, LEFT), interp(t, ref_t, ref_y, RIGHT)
    use_before = (side == LEFT) | ((side == EITHER) & (np.abs(y - ref_before) < np.abs(y - ref_after)))
    out_before = (y < before.lower) | (y > before.upper)
    out_after = (y < after.lower) | (y > after.upper)
    outside = np.where(side == LEFT, out_before,
                       np.where(side == RIGHT, out_after, out_before & out_after))
    reference = np.where(use_before, ref_before, ref_after)
    limits = Limits(np.where(use_before, before.lower, after.lower),
                    np.where(use_before, before.upper, after.upper),
                    after.plot_time, after.plot_lower, after.plot_upper)
    error = np.abs(y - reference)
    worst = int(np.argmax(error))
    return Verdict(
        signal=signal, rule=rule,
        tolerance=rule.describe(ref_t, ref_y, case.start, stop),
        passed=bool(rule.passes(outside)), max_error=float(error[worst]),
        max_error_time=float(t[worst]),
        first_exit=float(t[np.argmax(outside)]) if outside.any() else None,
        outside=int(outside.sum()), samples=int(len(t)), time=t, value=y,
        reference=reference, limits=limits, outside_mask=outside)


def early_end(case: Case, run: Run) -> EarlyEnd | None:
    """The run's early end, or None when it reached StopTime. RunFailed when it does
    not start at StartTime or ends before its first step."""
    scale = _slack(case)
    if len(run.time) < 2 or run.time[0] > case.start + scale:
        ended = f"ended at t = {run.time[-1]:g} s " if len(run.time) else ""
        raise RunFailed(f"the result {ended}covers less than one step from StartTime "
                        f"{case.start:g} s (it has {len(run.time)} samples)")
    if run.time[-1] >= case.stop - scale:
        return None
    reason = run.messages[-1] if run.messages else None
    return EarlyEnd(float(run.time[-1]), case.stop, reason, case.allow_early_end)


def judge_all(case: Case, run: Run, interface: str) -> tuple[list[Verdict], EarlyEnd | None]:
    """Every signal's verdict, over the interval the run covers, and its early end."""
    end = early_end(case, run)
    stop = case.stop if end is None else end.time
    return [judge(case, run, interface, s, stop) for s in case.signals()], end
