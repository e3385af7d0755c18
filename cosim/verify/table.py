"""Readers of the FMI cross-check files: a CSV of signals (quoted names on the first
line, ``time`` first) and the experiment options (``<Model>_ref.opt``)."""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .errors import VerifyError

OPTION_KEYS = ("StartTime", "StopTime", "StepSize", "RelTol")


@dataclass
class Table:
    """Signals sampled at strictly increasing times."""

    path: Path
    time: np.ndarray
    columns: dict[str, np.ndarray]


def _read_rows(path: Path) -> list[list[str]]:
    try:
        with open(path, newline="") as f:
            return [row for row in csv.reader(f) if row]
    except OSError as e:
        raise VerifyError(path, "", f"cannot be read ({e.strerror})",
                          "check the path") from None
    except (UnicodeDecodeError, csv.Error) as e:
        raise VerifyError(path, "", f"is not a CSV text file ({e})",
                          "write it as comma-separated text") from None


def _header(path: Path, rows: list[list[str]]) -> list[str]:
    if len(rows) < 3:
        raise VerifyError(path, "", "needs a header and at least two rows of samples",
                          "write the names on the first line and one row per time")
    names = [name.strip() for name in rows[0]]
    if len(names) < 2:
        raise VerifyError(path, "line 1", "has no signal column after time",
                          "add one column per signal")
    if names[0] != "time":
        raise VerifyError(path, f"column 1 '{names[0]}'", "the first column must be time",
                          "name it time and put the sample times there")
    seen = set()
    for name in names:
        if not name or name in seen:
            raise VerifyError(path, f"column '{name}'", "is empty or repeated",
                              "give every column one unique name")
        seen.add(name)
    return names


def _number(path: Path, line: int, name: str, text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise VerifyError(path, f"line {line}, column '{name}'", f"'{text}' is not a number",
                          "write a decimal number") from None
    if not math.isfinite(value):
        raise VerifyError(path, f"line {line}, column '{name}'", f"{text} is not finite",
                          "give a finite number (no NaN or inf)")
    return value


def _check_times(path: Path, time: np.ndarray) -> None:
    steps = np.diff(time)
    if np.all(steps > 0):
        return
    k = int(np.argmax(steps <= 0))
    kind = "repeats" if steps[k] == 0 else "goes back to"
    raise VerifyError(path, f"line {k + 3}, column 'time'",
                      f"time {kind} {time[k + 1]:g} s after {time[k]:g} s on the line before",
                      "sort the rows by strictly increasing time (declare a jump as an "
                      "event_times entry of the case file, not as a repeated time)")


def read_table(path: Path) -> Table:
    """The signals of a CSV file, checked: names, numbers, finite, increasing times."""
    path = Path(path)
    rows = _read_rows(path)
    names = _header(path, rows)
    values = np.empty((len(rows) - 1, len(names)))
    for i, row in enumerate(rows[1:]):
        if len(row) != len(names):
            raise VerifyError(path, f"line {i + 2}", f"has {len(row)} fields, the header "
                              f"{len(names)}", "write one value per column on every line")
        values[i] = [_number(path, i + 2, n, t) for n, t in zip(names, row)]
    _check_times(path, values[:, 0])
    return Table(path, values[:, 0], {n: values[:, j] for j, n in enumerate(names[1:], 1)})


def read_options(path: Path) -> dict[str, float]:
    """StartTime, StopTime, StepSize and RelTol of a cross-check ``_ref.opt`` file."""
    path = Path(path)
    options = {}
    for line, row in enumerate(_read_rows(path), start=1):
        if len(row) != 2 or row[0].strip() not in OPTION_KEYS:
            raise VerifyError(path, f"line {line}", f"'{','.join(row)}' is not an option",
                              f"write 'KEY, VALUE' lines with KEY one of {', '.join(OPTION_KEYS)}")
        options[row[0].strip()] = _number(path, line, row[0].strip(), row[1])
    for key in OPTION_KEYS:
        if key not in options:
            raise VerifyError(path, key, "is missing", f"add a line '{key}, VALUE'")
    if not options["StopTime"] > options["StartTime"] or options["StepSize"] <= 0:
        raise VerifyError(path, "StopTime", "the experiment is empty or its step is not "
                          "positive", "give StartTime < StopTime and StepSize > 0")
    return options
