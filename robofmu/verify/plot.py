"""The PNG of a failing signal: the reference with its band, the result, the samples
outside the band marked, the first time it leaves the band and, when the FMU ended the
run early, that time; the signal's unit (from the FMU) on the axes."""

from __future__ import annotations

import io
import re

import numpy as np

from ..errors import require
from .case import Case
from .compare import EarlyEnd, Verdict


def plot_name(signal: str) -> str:
    """A file name for a signal: `theta[1]` -> `theta_1.png`."""
    return re.sub(r"[^\w.-]+", "_", signal).strip("_") + ".png"


def _label(name: str, unit: str | None) -> str:
    return f"{name} [{unit}]" if unit else f"{name} [-]"


def _signal_panel(axes, case: Case, verdict: Verdict, outside, unit) -> None:
    limits = verdict.limits
    axes.fill_between(limits.plot_time, limits.plot_lower, limits.plot_upper, color="0.85",
                      label=f"band: {verdict.tolerance}")
    ref = case.reference
    inside = (ref.time >= case.start) & (ref.time <= case.stop)
    axes.plot(ref.time[inside], ref.columns[verdict.signal][inside], color="0.3", lw=1,
              label="reference")
    axes.plot(verdict.time, verdict.value, color="tab:blue", lw=1, label="result")
    axes.plot(verdict.time[outside], verdict.value[outside], "x", color="tab:red", ms=3,
              label=f"outside the band ({int(np.sum(outside))} samples)")
    axes.set_ylabel(_label(verdict.signal, unit))


def _deviation_panel(axes, verdict: Verdict, outside, unit) -> None:
    """The same around the reference (result - reference): a narrow band stays visible."""
    ref = verdict.reference
    limits = verdict.limits
    axes.fill_between(verdict.time, limits.lower - ref, limits.upper - ref, color="0.85")
    axes.axhline(0.0, color="0.3", lw=1)
    deviation = verdict.value - ref
    axes.plot(verdict.time, deviation, color="tab:blue", lw=1)
    axes.plot(verdict.time[outside], deviation[outside], "x", color="tab:red", ms=3)
    axes.set_ylabel(_label("result - reference", unit))
    axes.set_xlabel("time [s]")


def plot_png(case: Case, verdict: Verdict, title: str, unit: str | None = None,
             end: EarlyEnd | None = None) -> bytes:
    # lazy: matplotlib.figure is 0.3 s of start-up (benches/bench_startup.py), paid by plots only
    matplotlib = require("matplotlib", "plots", "the plots of cosim verify")
    matplotlib.use("Agg")
    from matplotlib.figure import Figure
    figure = Figure(figsize=(8, 6.5), dpi=100, layout="constrained")
    top, bottom = figure.subplots(2, 1, sharex=True, height_ratios=[3, 2])
    outside = verdict.outside_mask
    _signal_panel(top, case, verdict, outside, unit)
    _deviation_panel(bottom, verdict, outside, unit)
    if verdict.first_exit is not None:
        for axes in (top, bottom):
            axes.axvline(verdict.first_exit, color="tab:red", ls="--", lw=1,
                         label=f"first exit t = {verdict.first_exit:.6g} s")
    if end is not None:  # the whole experiment shown: the part the run never reached
        for axes in (top, bottom):
            axes.set_xlim(case.start, case.stop)
            axes.axvline(end.time, color="0.2", ls=":", lw=1.5,
                         label=f"the FMU ended the run, t = {end.time:.6g} s")
    top.set_title(f"{title}\n{verdict.signal}: {'PASS' if verdict.passed else 'FAIL'}",
                  fontsize=10)
    top.legend(fontsize=8, loc="best")
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png")
    return buffer.getvalue()
