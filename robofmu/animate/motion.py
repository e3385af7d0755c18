"""The motion to animate, read from a result CSV of the co-simulation master.

The CSV (robofmu.master.Result.write_csv) has quoted names on the first line, ``time``
first, then one column per signal ``ALIAS.NAME``. The plant's Euler angles are
``ALIAS.theta[1..3]``; the planned orientation (the ghost) is ``ALIAS.q[1..3]`` of the
planner; end-stop contacts are ``ALIAS.atStop[1..3]`` when the run recorded them.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .errors import AnimateError


@dataclass(frozen=True)
class Motion:
    """One run: times (n,), plant angles (n, 3) and, where recorded, the planned angles
    (n, 3), the actuator displacements the plant reported (n, 3) and its end-stop flags
    (n, 3)."""

    source: str
    plant: str
    time: np.ndarray
    theta: np.ndarray
    planned: np.ndarray | None
    l: np.ndarray | None
    at_stop: np.ndarray | None


def _triple(names: list[str], base: str) -> list[str] | None:
    wanted = [f"{base}[{i}]" for i in (1, 2, 3)]
    return wanted if all(w in names for w in wanted) else None


def _alias_of(names: list[str], suffix: str) -> str | None:
    """The first alias with columns ALIAS.SUFFIX[1..3]."""
    for name in names:
        if name.endswith(f".{suffix}[1]"):
            alias = name[: -len(f".{suffix}[1]")]
            if _triple(names, f"{alias}.{suffix}"):
                return alias
    return None


def _rows(path: Path) -> tuple[list[str], list[list[str]]]:
    if not path.is_file():
        raise AnimateError(str(path), "result CSV", "no such file; give a CSV written by "
                           "'cosim run' (results/NAME.csv)")
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except (UnicodeDecodeError, csv.Error) as e:
        raise AnimateError(str(path), "result CSV", f"not a CSV file ({e}); give a CSV "
                           "written by 'cosim run'") from None
    if not rows or not rows[0] or rows[0][0] != "time":
        raise AnimateError(str(path), "header", "the first column must be 'time'; give "
                           "a CSV written by 'cosim run'")
    if len(rows) < 2:
        raise AnimateError(str(path), "rows", "no samples after the header; give the CSV "
                           "of a run that took at least one step")
    return rows[0], rows[1:]


def _column(path: Path, names, rows, name: str) -> np.ndarray:
    j = names.index(name)
    values = np.empty(len(rows))
    for k, row in enumerate(rows):
        try:
            values[k] = float(row[j])
        except (IndexError, ValueError):
            raise AnimateError(str(path), f"{name}, line {k + 2}", "not a number; give "
                               "the CSV a run wrote, unedited") from None
        if not math.isfinite(values[k]):
            raise AnimateError(str(path), f"{name}, line {k + 2}", f"{row[j]} is not "
                               "finite; animate a run that did not diverge") from None
    return values


def read_motion(path: Path, plant: str | None = None, planner: str | None = None) -> Motion:
    """Reads `path`; `plant` and `planner` are the aliases (default: the first alias with
    theta[1..3], the first with q[1..3])."""
    names, rows = _rows(path)
    plant = plant or _alias_of(names, "theta") or "plant"
    theta_names = _triple(names, f"{plant}.theta")
    if theta_names is None:
        raise AnimateError(str(path), f"{plant}.theta[1]", "no such columns (plant Euler "
                           "angles); record them or name the plant's alias with --plant")
    if planner and _triple(names, f"{planner}.q") is None:
        raise AnimateError(str(path), f"{planner}.q[1]", "no such columns (planned "
                           "angles); name the planner's alias with --planner")
    planner = planner or _alias_of(names, "q")

    def triple(base: str) -> np.ndarray | None:
        found = _triple(names, base)
        if found is None:
            return None
        return np.column_stack([_column(path, names, rows, n) for n in found])

    time = _column(path, names, rows, "time")
    if np.any(np.diff(time) < 0.0):
        raise AnimateError(str(path), "time", "goes backwards; give the CSV a run wrote")
    theta = np.column_stack([_column(path, names, rows, n) for n in theta_names])
    return Motion(source=str(path), plant=plant, time=time, theta=theta,
                  planned=triple(f"{planner}.q") if planner else None,
                  l=triple(f"{plant}.l"), at_stop=triple(f"{plant}.atStop"))
