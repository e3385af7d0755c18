"""The tolerance rules a signal can be checked with.

- ``Deviation(abs, rel)``: every sample within ``abs + rel * R`` of the reference,
  interpolated linearly at the sample's time, where R = max - min of the reference over
  the experiment. ``Deviation(1e-4)`` is an absolute tolerance, ``Deviation(0, 0.01)``
  one of 1 % of the signal's range.
- ``CrossCheckBand()``: the FMI cross-check's rule, as FMPy 0.3.32 implements it
  (fmpy.cross_check.validate_signal and validate_result): the reference is resampled
  linearly on 1000 equidistant times from start to stop; the band is the running
  minimum and maximum over 21 of those samples (centred, cut at the ends), widened by
  10 % of the resampled reference's range (a constant reference: by 10 % of its value,
  0.5 when it is 0); its limits are interpolated linearly at the result's times. The
  signal passes when at most 10 % of its samples lie outside.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

from .events import LEFT, RIGHT, interp

BAND_SAMPLES = 1000
BAND_WINDOW = 21
BAND_WIDTH = 0.1
BAND_OUTSIDE = 0.1
CROSS_CHECK = "cross-check"


@dataclass(frozen=True)
class Limits:
    """A rule's band: ``lower``/``upper`` at the result's times, ``plot_time`` with
    ``plot_lower``/``plot_upper`` to draw it."""

    lower: np.ndarray
    upper: np.ndarray
    plot_time: np.ndarray
    plot_lower: np.ndarray
    plot_upper: np.ndarray


def reference_range(ref_t, ref_y, start: float, stop: float) -> float:
    """max - min of the reference, linearly interpolated, over [start, stop]."""
    inside = ref_y[(ref_t >= start) & (ref_t <= stop)]
    ends = [interp(start, ref_t, ref_y, RIGHT), interp(stop, ref_t, ref_y, LEFT)]
    values = np.concatenate([inside, ends])
    return float(values.max() - values.min())


@dataclass(frozen=True)
class Deviation:
    """|result - reference| <= abs + rel * range at every sample."""

    abs: float
    rel: float = 0.0

    def width(self, ref_t, ref_y, start, stop) -> float:
        return self.abs + self.rel * reference_range(ref_t, ref_y, start, stop)

    def limits(self, t, ref_t, ref_y, start, stop, side=RIGHT) -> Limits:
        w = self.width(ref_t, ref_y, start, stop)
        at_t = interp(t, ref_t, ref_y, side)
        keep = (ref_t >= start) & (ref_t <= stop)
        return Limits(at_t - w, at_t + w, ref_t[keep], ref_y[keep] - w, ref_y[keep] + w)

    def passes(self, outside: np.ndarray) -> bool:
        return not outside.any()

    def describe(self, ref_t, ref_y, start, stop) -> str:
        if self.rel == 0:
            return f"{self.abs:g} (absolute)"
        w = self.width(ref_t, ref_y, start, stop)
        absolute = f"{self.abs:g} + " if self.abs else ""
        return f"{w:.3g} ({absolute}{self.rel:g} x range)"

    def to_json(self) -> dict:
        return {"rule": "deviation", "abs": self.abs, "rel": self.rel}


def _running(values: np.ndarray, reduce) -> np.ndarray:
    half = BAND_WINDOW // 2
    padded = np.pad(values, half, mode="edge")
    return reduce(sliding_window_view(padded, BAND_WINDOW), axis=1)


@dataclass(frozen=True)
class CrossCheckBand:
    """The FMI cross-check band rule (module docstring)."""

    def limits(self, t, ref_t, ref_y, start, stop, side=RIGHT) -> Limits:
        grid = np.linspace(start, stop, BAND_SAMPLES)
        y = interp(grid, ref_t, ref_y, side)
        low, high = float(y.min()), float(y.max())
        if low == high:
            w = 0.5 if low == 0 else abs(low) * BAND_WIDTH
        else:
            w = (high - low) * BAND_WIDTH
        lower, upper = _running(y, np.min) - w, _running(y, np.max) + w
        return Limits(np.interp(t, grid, lower), np.interp(t, grid, upper), grid, lower, upper)

    def passes(self, outside: np.ndarray) -> bool:
        return outside.sum() <= BAND_OUTSIDE * len(outside)

    def describe(self, ref_t, ref_y, start, stop) -> str:
        return "FMI cross-check band (at most 10 % of the samples outside)"

    def to_json(self) -> dict:
        return {"rule": CROSS_CHECK}


def _check(value, what: str) -> float:
    """A non-negative finite number, or ValueError saying what is wrong."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"{what} must be a number")
    if not math.isfinite(value) or value < 0:
        raise ValueError(f"{what} must be finite and not negative")
    return float(value)


Rule = Deviation | CrossCheckBand  # a signal's tolerance rule


def from_json(spec) -> Rule:
    """A rule from the case file: a number (absolute), {"abs": A, "rel": R} (either may
    be left out, 0 then) or "cross-check". ValueError names what is wrong."""
    if spec == CROSS_CHECK:
        return CrossCheckBand()
    if isinstance(spec, dict):
        unknown = sorted(set(spec) - {"abs", "rel"})
        if unknown or not spec:
            raise ValueError(f"unknown keys {unknown}" if unknown else "empty object")
        return Deviation(_check(spec.get("abs", 0.0), "abs"), _check(spec.get("rel", 0.0), "rel"))
    return Deviation(_check(spec, "the tolerance"))


def from_text(text: str) -> Rule:
    """A rule from the command line: "ABS", "ABS,REL" or "cross-check"."""
    if text.strip() == CROSS_CHECK:
        return CrossCheckBand()
    parts = text.split(",")
    if len(parts) > 2:
        raise ValueError("give ABS or ABS,REL")
    try:
        numbers = [float(p) for p in parts]
    except ValueError:
        raise ValueError(f"'{text}' is not ABS, ABS,REL or cross-check") from None
    return Deviation(*[_check(n, w) for n, w in zip(numbers, ("ABS", "REL"))])
