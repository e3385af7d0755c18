"""Limits a scenario may declare (``[limits]``), judged against the run's metrics::

    [limits]
    max_tracking_error = "0.5 deg"   # largest |planned - plant| Euler angle, any axis
    rms_tracking_error = "0.1 deg"   # RMS over the run of the error vector's norm
    max_force = "60 N"               # largest |actuator force|, any actuator

A run that exceeds a declared limit ends with exit code 1 (`cosim run`)."""

from __future__ import annotations

from .errors import ScenarioError
from .units import quantity

# limit -> (dimension, metric key in robofmu.report.Metrics.si(), human unit)
LIMITS = {
    "max_tracking_error": ("angle", "max_error", "deg"),
    "rms_tracking_error": ("angle", "rms_error", "deg"),
    "max_force": ("force", "peak_force", "N"),
}


def parse_limits(raw) -> dict[str, float]:
    """{limit: SI value} of a [limits] table."""
    if not isinstance(raw, dict):
        raise ScenarioError("field 'limits' must be a table of name = \"value unit\"")
    limits = {}
    for name, text in raw.items():
        if name not in LIMITS:
            raise ScenarioError(f"unknown field 'limits.{name}'; the limits are "
                                f"{', '.join(LIMITS)}")
        value = quantity(text, LIMITS[name][0], f"limits.{name}")
        if value <= 0.0:
            raise ScenarioError(f"field 'limits.{name}' must be positive, got {text!r}")
        limits[name] = value
    return limits


CLOSED_LOOP_COLUMNS = [f"{a}.{v}[{i}]" for a, v in (("planner", "q"), ("plant", "theta"),
                                                     ("plant", "force"), ("planner", "qddot"),
                                                     ("plant", "omegaDot")) for i in (1, 2, 3)]


def check_measurable(scenario) -> None:
    """Declared limits need the closed-loop signals recorded (connected or `record`)."""
    recorded = ({str(c.source) for c in scenario.connections}
                | {str(r) for r in scenario.record})
    missing = sorted(set(CLOSED_LOOP_COLUMNS) - recorded)
    if scenario.limits and missing:
        raise ScenarioError(f"field 'limits': the limits need the closed-loop signals, and "
                            f"{missing[0]} is not recorded; add it to 'record' or remove "
                            "'limits'")


def judge(limits: dict[str, float], measured: dict[str, float]) -> list[tuple]:
    """(limit, measured SI, limit SI, human unit, passed) per declared limit."""
    rows = []
    for name, bound in limits.items():
        _, key, unit = LIMITS[name]
        value = measured[key]
        rows.append((name, value, bound, unit, value <= bound))
    return rows
