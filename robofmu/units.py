"""Quantities with stated units in hand-written scenarios: ``"5 deg"``, ``"1 ms"``,
``"-5, 3, 132 deg"`` (a vector: numbers separated by commas, one unit at the end).

Values are converted to SI at load time; everything after loading is SI. A bare number
is refused where a unit is expected, so that a scenario always says what it means.
"""

from __future__ import annotations

import math

from .errors import ScenarioError

DEG = math.pi / 180.0

# unit -> (SI factor, dimension). The dimension is checked against what the field expects.
UNITS: dict[str, tuple[float, str]] = {
    "s": (1.0, "time"), "ms": (1e-3, "time"),
    "rad": (1.0, "angle"), "deg": (DEG, "angle"),
    "rad/s": (1.0, "angular velocity"), "deg/s": (DEG, "angular velocity"),
    "rad/s^2": (1.0, "angular acceleration"), "deg/s^2": (DEG, "angular acceleration"),
    "N m/rad": (1.0, "stiffness gain"), "N m/deg": (1.0 / DEG, "stiffness gain"),
    "N m/(rad s)": (1.0, "integral gain"), "N m s/rad": (1.0, "damping gain"),
    "kg": (1.0, "mass"), "g": (1e-3, "mass"), "kg m^2": (1.0, "inertia"),
    "m": (1.0, "length"), "mm": (1e-3, "length"), "N": (1.0, "force"),
    "m/s": (1.0, "velocity"), "mm/s": (1e-3, "velocity"),
    "m/s^2": (1.0, "acceleration"), "N m": (1.0, "torque"),
    "N/m": (1.0, "translational stiffness"), "N s/m": (1.0, "translational damping"),
}

# dimension -> exponents of the SI base units (kg, m, s, rad, A, K, mol, cd), as FMI 2.0
# unit definitions state them (<BaseUnit kg="1" m="2" .../>).
DIMENSIONS: dict[str, tuple[int, ...]] = {
    "time": (0, 0, 1, 0), "angle": (0, 0, 0, 1), "angular velocity": (0, 0, -1, 1),
    "angular acceleration": (0, 0, -2, 1), "stiffness gain": (1, 2, -2, -1),
    "integral gain": (1, 2, -3, -1), "damping gain": (1, 2, -1, -1), "mass": (1, 0, 0, 0),
    "inertia": (1, 2, 0, 0), "length": (0, 1, 0, 0), "force": (1, 1, -2, 0),
    "velocity": (0, 1, -1, 0), "acceleration": (0, 1, -2, 0), "torque": (1, 2, -2, 0),
    "translational stiffness": (1, 0, -2, 0), "translational damping": (1, 0, -1, 0),
}


def exponents(dimension: str) -> tuple[int, ...]:
    """SI base-unit exponents of `dimension`, padded to the eight FMI base units."""
    return DIMENSIONS[dimension] + (0, 0, 0, 0)


def unit_in(text) -> str | None:
    """The unit a "value unit" string ends with (None: no known unit)."""
    if not isinstance(text, str):
        return None
    text = text.strip()
    for unit in sorted(UNITS, key=len, reverse=True):
        if text.endswith(unit) and len(text) > len(unit) and text[-len(unit) - 1] == " ":
            return unit
    return None


def quantity_vector(text, dimension: str, field: str, length: int | None = None) -> list[float]:
    """SI values of ``"x[, y, ...] unit"`` whose unit has `dimension`."""
    if not isinstance(text, str):
        raise ScenarioError(f"field '{field}' must be a string \"value unit\" (e.g. "
                            f"\"{_example(dimension)}\"), got {text!r}")
    numbers, unit = _split(text.strip(), field)
    factor, found = _unit(unit, field)
    if found != dimension:
        raise ScenarioError(f"field '{field}' must be a {dimension}, got unit '{unit}' "
                            f"({found})")
    try:
        values = [float(x) * factor for x in numbers.split(",")]
    except ValueError:
        raise ScenarioError(f"field '{field}': cannot read numbers in {text!r}") from None
    if not all(math.isfinite(v) for v in values):
        raise ScenarioError(f"field '{field}' must be finite, got {text!r}")
    if length is not None and len(values) != length:
        raise ScenarioError(f"field '{field}' must have {length} values, got {len(values)}")
    return values


def quantity(text, dimension: str, field: str) -> float:
    """SI value of ``"x unit"``."""
    return quantity_vector(text, dimension, field, length=1)[0]


def _split(text: str, field: str) -> tuple[str, str]:
    for unit in sorted(UNITS, key=len, reverse=True):
        if text.endswith(unit) and (len(text) == len(unit) or text[-len(unit) - 1] == " "):
            return text[:-len(unit)].strip(), unit
    known = ", ".join(UNITS)
    raise ScenarioError(f"field '{field}': no known unit at the end of {text!r} (units: {known})")


def _unit(unit: str, field: str) -> tuple[float, str]:
    try:
        return UNITS[unit]
    except KeyError:
        raise ScenarioError(f"field '{field}': unknown unit '{unit}'") from None


def _example(dimension: str) -> str:
    unit = next(u for u, (_, d) in UNITS.items() if d == dimension)
    return f"1 {unit}"
