"""Events in the FMI cross-check files: a time written on two (or more) rows is a jump;
the first row holds the value just before it (the left limit), the last the value just
after it (the right limit). These functions read a signal with such rows on both sides
and tell which side each sample of a result stands for."""

from __future__ import annotations

import numpy as np

LEFT, RIGHT, EITHER = -1, 1, 0


def interp(t, xp: np.ndarray, fp: np.ndarray, side: int = RIGHT) -> np.ndarray:
    """`fp(xp)` read as linear between its rows at the times `t`: at a repeated time,
    the value after the jump (RIGHT) or before it (LEFT); before the first time the
    first value, after the last the last (as numpy.interp)."""
    t = np.asarray(t, dtype=float)
    if side == RIGHT:
        k = np.searchsorted(xp, t, side="right") - 1  # the last row at or before t
        k = np.clip(k, 0, len(xp) - 2)
    else:
        k = np.searchsorted(xp, t, side="left")  # the first row at or after t
        k = np.clip(k - 1, 0, len(xp) - 2)
    x0, x1 = xp[k], xp[k + 1]
    y0, y1 = fp[k], fp[k + 1]
    span = x1 - x0
    with np.errstate(invalid="ignore", divide="ignore"):
        w = np.where(span > 0, (t - x0) / np.where(span > 0, span, 1.0), 1.0)
    w = np.clip(w, 0.0, 1.0)
    return y0 + w * (y1 - y0)


def sides(time: np.ndarray) -> np.ndarray:
    """For each sample of a result: LEFT when the next sample has the same time (the
    value before an event the importer recorded), RIGHT when the previous one has (the
    value after it), else EITHER (one sample at the instant: before or after is right)."""
    side = np.full(len(time), EITHER)
    same = np.diff(time) == 0
    side[:-1][same] = LEFT
    side[1:][same] = RIGHT
    side[1:-1][same[1:] & same[:-1]] = EITHER  # inside a run of three or more
    return side
