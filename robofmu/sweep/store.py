"""The sweep's table: one CSV row per run, appended and flushed as the run completes.

CSV rather than Parquet: a Parquet file is written whole (or as one file per row
group), so a sweep killed half way would lose its rows or leave many small files;
an appended CSV line is on disk the moment the run ends, --resume reads it back with
the standard library, and floats are written with repr, so the values read back are
the values computed (bit for bit). pandas/pyarrow would add 100 MB to the environment
for no gain at these sizes (thousands of rows).
"""

from __future__ import annotations

import csv
import math
import sys
import time
from pathlib import Path

from .runner import METRICS
from .spec import Spec


def columns(spec: Spec) -> list[str]:
    """run_id, status, reason, the varied values (unit in the name), the metrics."""
    names = ["run_id", "status", "reason"]
    for v in spec.varied:
        unit = f" [{v.unit}]" if v.unit else ""
        if v.kind == "workspace":
            names += [f"{v.path}[{i}]{unit}" for i in (1, 2, 3)]
        else:
            names.append(f"{v.path}{unit}")
    return names + METRICS


def values_row(spec: Spec, values: dict) -> list:
    row = []
    for v in spec.varied:
        value = values[v.path]
        row += list(value) if isinstance(value, list) else [value]
    return row


class Table:
    """The CSV of one sweep; `done` holds the run ids already completed."""

    def __init__(self, path: Path, header: list[str], resume: bool):
        self.path, self.header = path, header
        self.done: set[str] = set()
        path.parent.mkdir(parents=True, exist_ok=True)
        if resume and path.exists():
            rows = _complete_rows(path, header)
            self.done = {r[0] for r in rows[1:] if len(r) == len(header) and r[1] == "ok"}
            self.file = open(path, "a", newline="")
            if not rows:
                csv.writer(self.file).writerow(header)
        else:
            self.file = open(path, "w", newline="")
            csv.writer(self.file).writerow(header)
        self.file.flush()
        self.writer = csv.writer(self.file)

    def append(self, run_id: str, values: list, outcome: dict) -> None:
        metrics = [outcome.get(m, "") for m in METRICS]
        self.writer.writerow([run_id, outcome["status"], outcome.get("reason", ""),
                              *values, *metrics])
        self.file.flush()

    def close(self) -> None:
        self.file.close()


def _complete_rows(path: Path, header: list[str]) -> list[list[str]]:
    """The table's rows without a torn last line: a sweep killed while writing leaves
    a line without its newline, which is cut off here (the file too, so that the next
    row starts on a line of its own) and its run made again. A file that is not this
    SPEC's table is refused and left as it is."""
    data = path.read_bytes()
    end = data.rfind(b"\n") + 1
    refuse = f"{path}: not a table of this SPEC ({{}}); run without --resume or choose " \
             "another --out"
    try:
        rows = list(csv.reader(data[:end].decode().splitlines(keepends=True)))
        data.decode()
    except (UnicodeDecodeError, csv.Error) as e:
        raise ValueError(refuse.format(e)) from None
    if (rows and rows[0] != header) or (not rows and data):
        raise ValueError(refuse.format("its columns differ"))
    if end < len(data):
        with open(path, "rb+") as f:
            f.truncate(end)
    return rows


def read_table(path: Path) -> tuple[list[str], list[dict]]:
    """Header and rows (numbers as floats where they parse)."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))

    def value(text):
        try:
            return float(text)
        except ValueError:
            return text
    return rows[0], [dict(zip(rows[0], map(value, r))) for r in rows[1:]]


class Progress:
    """A terminal line: runs done / failed of total, rate, redrawn at most 10 times a
    second."""

    def __init__(self, total: int, skipped: int, stream=sys.stderr, enabled: bool = True):
        self.total, self.skipped, self.stream, self.enabled = total, skipped, stream, enabled
        self.done = self.failed = 0
        self.started = time.perf_counter()
        self.shown = -math.inf

    def update(self, ok: bool) -> None:
        self.done += 1
        self.failed += not ok
        now = time.perf_counter()
        if self.enabled and (now - self.shown > 0.1 or self.done == self.total):
            self.shown = now
            rate = self.done / max(now - self.started, 1e-9)
            width, fraction = 30, self.done / max(self.total, 1)
            bar = "#" * int(width * fraction) + "." * (width - int(width * fraction))
            end = "\n" if self.done == self.total else ""
            self.stream.write(f"\r[{bar}] {self.done}/{self.total} runs, {self.failed} "
                              f"failed, {rate:.2f} runs/s"
                              f"{f' ({self.skipped} done before)' if self.skipped else ''}"
                              f"{end}")
            self.stream.flush()
