"""Readers of the FMI cross-check files: a CSV of signals (names on the first line,
quoted or not, ``time`` first; a time written twice is an event: the first row holds the
value before it, the last the value after it) and the experiment options
(``<Model>_ref.opt``: every key the cross-check rules list). docs/verify.md says which
rule of the cross-check each reading follows."""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .errors import VerifyError

REQUIRED_KEYS = ("StartTime", "StopTime", "StepSize", "RelTol")
# The optional keys: the rules' (AbsTol, SolverType, OutputIntervalLength) and
# StopTimeDefined, which exporters write for the FMI stopTimeDefined argument.
OPTIONAL_KEYS = ("AbsTol", "SolverType", "OutputIntervalLength", "StopTimeDefined")


@dataclass
class Table:
    """Signals sampled at non-decreasing times; a repeated time is an event."""

    path: Path
    time: np.ndarray
    columns: dict[str, np.ndarray]

    def event_times(self) -> list[float]:
        """The times written on more than one row."""
        repeated = self.time[1:][np.diff(self.time) == 0]
        return sorted(set(float(t) for t in repeated))


@dataclass
class Options:
    """A ``_ref.opt`` file: StepSize 0 is a variable-step run; ``output_interval``
    (OutputIntervalLength) None when not given; ``ignored``: keys the rules do not list."""

    start: float
    stop: float
    step: float
    rel_tol: float
    abs_tol: float | None = None
    solver_type: str | None = None
    output_interval: float | None = None
    stop_time_defined: bool = True
    ignored: list[str] | None = None


def _read_rows(path: Path, text: str | None = None) -> list[list[str]]:
    """The rows (of `text` when given, `path` then only names it); "utf-8-sig" drops the
    byte-order mark some exporters write."""
    try:
        with (io.StringIO(text, newline="") if text is not None
              else open(path, newline="", encoding="utf-8-sig")) as f:
            return [row for row in csv.reader(f, skipinitialspace=True)
                    if row and any(field.strip() for field in row)]
    except OSError as e:
        raise VerifyError(path, "", f"cannot be read ({e.strerror})",
                          "check the path") from None
    except (UnicodeDecodeError, csv.Error) as e:
        raise VerifyError(path, "", f"is not a CSV text file ({e})",
                          "write it as comma-separated text") from None


def _name(field: str) -> str:
    """A name of the header as exporters write it: "x", x, "x" (a space after the
    quote) or  "x" (spaces around): the name without spaces and quotes around it."""
    name = field.strip()
    if len(name) >= 2 and name[0] == name[-1] == '"':
        name = name[1:-1].strip()
    return name


def _header(path: Path, rows: list[list[str]]) -> list[str]:
    if len(rows) < 3:
        raise VerifyError(path, "", "needs a header and at least two rows of samples",
                          "write the names on the first line and one row per time")
    names = [_name(field) for field in rows[0]]
    if len(names) < 2:
        raise VerifyError(path, "line 1", "has no signal column after time",
                          "add one column per signal")
    if names[0].lower() != "time":
        raise VerifyError(path, f"column 1 '{names[0]}'", "the first column must be time",
                          "name it time and put the sample times there")
    names[0] = "time"
    seen = set()
    for name in names:
        if not name or name in seen:
            raise VerifyError(path, f"column '{name}'", "is empty or repeated",
                              "give every column one unique name")
        seen.add(name)
    return names


def _number(path: Path, line: int, name: str, text: str) -> float:
    try:
        value = float(text.strip())
    except ValueError:
        raise VerifyError(path, f"line {line}, column '{name}'", f"'{text}' is not a number",
                          "write a decimal number") from None
    if not math.isfinite(value):
        raise VerifyError(path, f"line {line}, column '{name}'", f"{text} is not finite",
                          "give a finite number (no NaN or inf)")
    return value


def _check_times(path: Path, time: np.ndarray) -> None:
    """Times never go back (the rules: "monotonically increasing"; a time written on
    two rows is an event, as in the rules' own example)."""
    steps = np.diff(time)
    if np.all(steps >= 0):
        return
    k = int(np.argmax(steps < 0))
    raise VerifyError(path, f"line {k + 3}, column 'time'",
                      f"time goes back to {time[k + 1]:g} s after {time[k]:g} s on the line "
                      "before", "sort the rows by time (an event is the same time on two "
                      "rows: the value before it, then the value after it)")


def read_table(path: Path, text: str | None = None) -> Table:
    """The signals of a CSV file (or of `text`, read from `path`, such as a file inside
    an FMU), checked: names, numbers, finite, times that never go back."""
    path = Path(path)
    rows = _read_rows(path, text)
    header = _header(path, rows)
    # An array column (the FMI tools list's CSV rules: "Arrays are serialized as for start
    # values in the modelDescription.xml with space as separator"): its elements x[1],
    # x[2], ... as many as its first row holds.
    widths = [max(1, len(field.split())) for field in rows[1][:len(header)]]
    widths += [1] * (len(header) - len(widths))
    if widths[0] != 1:
        raise VerifyError(path, "line 2, column 'time'", "holds more than one number",
                          "write one time per row")
    names = [n if w == 1 else f"{n}[{k}]" for n, w in zip(header, widths)
             for k in range(1, w + 1)]
    if len(set(names)) != len(names):
        raise VerifyError(path, "line 1", "names an array's element twice (a column x[i] "
                          "beside the array column x)", "keep one of them")
    values = np.empty((len(rows) - 1, len(names)))
    for i, row in enumerate(rows[1:]):
        if len(row) != len(header):
            raise VerifyError(path, f"line {i + 2}", f"has {len(row)} fields, the header "
                              f"{len(header)}", "write one value per column on every line")
        values[i] = [v for n, w, t in zip(header, widths, row)
                     for v in _cells(path, i + 2, n, t, w)]
    _check_times(path, values[:, 0])
    return Table(path, values[:, 0], {n: values[:, j] for j, n in enumerate(names[1:], 1)})


def _cells(path: Path, line: int, name: str, text: str, width: int) -> list[float]:
    """The numbers of one field: one, or the `width` elements of an array column."""
    if width == 1:
        return [_number(path, line, name, text)]
    words = text.split()
    if len(words) != width:
        raise VerifyError(path, f"line {line}, column '{name}'", f"has {len(words)} "
                          f"elements, the column's first row {width}", "write every row "
                          "of an array column with its elements separated by spaces")
    return [_number(path, line, name, w) for w in words]


def _option_lines(path: Path):
    """(line number, key, value text) of each option line: "KEY, VALUE", a "// ..."
    comment after it or on a line of its own, blank lines and a key without a value
    (the rules' own "OutputIntervalLength   // ..." line) allowed."""
    try:
        text = path.read_text(encoding="utf-8-sig")
    except OSError as e:
        raise VerifyError(path, "", f"cannot be read ({e.strerror})", "check the path") from None
    except UnicodeDecodeError as e:
        raise VerifyError(path, "", f"is not a text file ({e})", "write KEY, VALUE lines") from None
    for line, raw in enumerate(text.splitlines(), start=1):
        content = raw.split("//", 1)[0].strip()
        if not content:
            continue
        key, _, value = content.partition(",")
        if "," in value:
            raise VerifyError(path, f"line {line}", f"'{content}' has more than one value",
                              "write 'KEY, VALUE'")
        yield line, key.strip().strip('"').strip(), value.strip().strip('"').strip()


def _flag(path: Path, line: int, key: str, text: str) -> bool:
    if text.lower() in ("1", "true"):
        return True
    if text.lower() in ("0", "false"):
        return False
    raise VerifyError(path, f"line {line}, {key}", f"'{text}' is not a flag", "write 0 or 1")


def read_options(path: Path) -> Options:
    """The experiment of a cross-check ``_ref.opt`` file, checked."""
    path = Path(path)
    values: dict[str, tuple[int, str]] = {}
    ignored = []
    for line, key, text in _option_lines(path):
        if key not in REQUIRED_KEYS + OPTIONAL_KEYS:
            ignored.append(key)
            continue
        if key in values:
            raise VerifyError(path, f"line {line}, {key}", f"is given twice (line "
                              f"{values[key][0]} too)", "keep one line per key")
        values[key] = (line, text)
    for key in REQUIRED_KEYS:
        if key not in values or not values[key][1]:
            raise VerifyError(path, key, "is missing", f"add a line '{key}, VALUE' "
                              f"(the rules' required keys: {', '.join(REQUIRED_KEYS)})")

    def number(key):
        line, text = values[key]
        return _number(path, line, key, text)

    options = Options(number("StartTime"), number("StopTime"), number("StepSize"),
                      number("RelTol"), ignored=ignored)
    if "AbsTol" in values and values["AbsTol"][1]:
        options.abs_tol = number("AbsTol")
    if "OutputIntervalLength" in values and values["OutputIntervalLength"][1]:
        options.output_interval = number("OutputIntervalLength")
    if "SolverType" in values and values["SolverType"][1]:
        options.solver_type = values["SolverType"][1]
    if "StopTimeDefined" in values and values["StopTimeDefined"][1]:
        options.stop_time_defined = _flag(path, values["StopTimeDefined"][0],
                                          "StopTimeDefined", values["StopTimeDefined"][1])
    if not options.stop > options.start:
        raise VerifyError(path, "StopTime", f"{options.stop:g} s is not after StartTime "
                          f"{options.start:g} s", "give StartTime < StopTime")
    if options.step < 0:
        raise VerifyError(path, "StepSize", f"{options.step:g} is negative",
                          "give the step in seconds, or 0 for a variable-step run")
    if options.output_interval is not None and options.output_interval < 0:
        raise VerifyError(path, "OutputIntervalLength", f"{options.output_interval:g} is "
                          "negative", "give the output interval in seconds")
    if options.rel_tol < 0:
        raise VerifyError(path, "RelTol", f"{options.rel_tol:g} is negative",
                          "give the relative tolerance, e.g. 1e-5")
    return options
