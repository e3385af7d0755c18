"""The case file (``case.json``): start values, event times and tolerances, each
checked; a mistake names the file, the key and the fix. Format: docs/verify.md."""

from __future__ import annotations

import json
import math
from pathlib import Path

from . import tolerance
from .errors import VerifyError

CASE_KEYS = ("start_values", "event_times", "tolerances")
INTERFACES = ("CoSimulation", "ModelExchange")


def read_case_file(path: Path) -> dict:
    try:
        data = json.loads(path.read_text())
    except OSError as e:
        raise VerifyError(path, "", f"cannot be read ({e.strerror})", "check the path") from None
    except (ValueError, UnicodeDecodeError) as e:
        raise VerifyError(path, "", f"is not JSON ({e})", "fix the syntax") from None
    if not isinstance(data, dict):
        raise VerifyError(path, "", "is not a JSON object", "write {\"tolerances\": {...}}")
    unknown = sorted(set(data) - set(CASE_KEYS))
    if unknown:
        raise VerifyError(path, unknown[0], "unknown key",
                          f"use only {', '.join(CASE_KEYS)} (docs/verify.md)")
    return data


def start_values(path: Path | str, data) -> dict[str, object]:
    if not isinstance(data, dict):
        raise VerifyError(path, "start_values", "is not an object",
                          "write {\"NAME\": VALUE, ...}")
    for name, value in data.items():
        if not isinstance(value, (bool, int, float, str)) or (
                isinstance(value, float) and not math.isfinite(value)):
            raise VerifyError(path, f"start_values.{name}", f"{value!r} is not a value",
                              "give a finite number, true/false or a string")
    return dict(data)


def event_times(path: Path | str, data) -> list[float]:
    if not isinstance(data, list) or not all(
            isinstance(t, (int, float)) and not isinstance(t, bool) and math.isfinite(t)
            for t in data):
        raise VerifyError(path, "event_times", "is not a list of times",
                          "write [t1, t2, ...] in seconds")
    return [float(t) for t in data]


def _rule_table(path: Path | str, where: str, data) -> dict[str, tolerance.Rule]:
    if not isinstance(data, dict):
        raise VerifyError(path, where, "is not an object", "write {\"SIGNAL\": TOLERANCE}")
    rules = {}
    for signal, spec in data.items():
        try:
            rules[signal] = tolerance.from_json(spec)
        except ValueError as e:
            raise VerifyError(path, f"{where}.{signal}", str(e), "give a number (absolute), "
                              "{\"abs\": A, \"rel\": R} or \"cross-check\"") from None
    return rules


def tolerances(path: Path | str, data) -> dict[str | None, dict[str, tolerance.Rule]]:
    """{"SIGNAL": SPEC} for every interface, or {"CoSimulation": {...}, ...}."""
    if isinstance(data, dict) and data and all(k in INTERFACES for k in data):
        return {k: _rule_table(path, f"tolerances.{k}", v) for k, v in data.items()}
    if isinstance(data, dict) and any(k in INTERFACES for k in data):
        raise VerifyError(path, "tolerances", "mixes interface names and signal names",
                          "key it by interface (CoSimulation, ModelExchange) or by signal")
    return {None: _rule_table(path, "tolerances", data)}
