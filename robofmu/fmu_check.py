"""What the scenario's FMUs declare, read once per file, with user errors that name the
scenario field: the file (exists, a zip, FMI 2.0 or 3.0 co-simulation with a binary
for this platform; FMI 3.0 read as its scalar view), its variables, their units (as SI
base-unit exponents) and ranges."""

from __future__ import annotations

import copy
import math
import os
import platform
import stat
import zipfile
from pathlib import Path
from typing import Any

from fmpy import read_model_description
from fmpy.model_description import ModelDescription

from .errors import ScenarioError

BASE_UNITS = ("kg", "m", "s", "rad")
OTHER_BASE_UNITS = ("A", "K", "mol", "cd")
INT32 = (-2 ** 31, 2 ** 31 - 1)
BINARY_DIR = {("Linux", "x86_64"): "linux64", ("Darwin", "x86_64"): "darwin64",
              ("Darwin", "arm64"): "darwin64", ("Windows", "AMD64"): "win64"}
FMI3_BINARY_DIR = {("Linux", "x86_64"): "x86_64-linux", ("Linux", "aarch64"): "aarch64-linux",
                   ("Darwin", "x86_64"): "x86_64-darwin", ("Darwin", "arm64"): "aarch64-darwin",
                   ("Windows", "AMD64"): "x86_64-windows"}


def _describe(path: str):
    if not zipfile.is_zipfile(path):
        raise ValueError("is not an FMU (not a zip archive)")
    with zipfile.ZipFile(path) as z:
        names = set(z.namelist())
    if "modelDescription.xml" not in names:
        raise ValueError("is not an FMU (no modelDescription.xml in the archive)")
    try:
        md = read_model_description(path, validate=False)
    except Exception as e:  # noqa: BLE001 - any malformed XML is the file's fault
        raise ValueError(f"has an unreadable modelDescription.xml ({e})") from None
    if md.fmiVersion not in ("2.0", "3.0"):
        raise ValueError(f"is an FMI {md.fmiVersion} FMU; FMI 2.0 and 3.0 are supported")
    if md.coSimulation is None:
        raise ValueError("does not support co-simulation (FMI "
                         f"{md.fmiVersion} Model Exchange only)")
    if md.fmiVersion == "2.0":
        folder = BINARY_DIR.get((platform.system(), platform.machine()), "linux64")
    else:
        folder = FMI3_BINARY_DIR.get((platform.system(), platform.machine()), "x86_64-linux")
    wanted = f"binaries/{folder}/{md.coSimulation.modelIdentifier}"
    if not any(n.startswith(wanted + ".") for n in names):
        raise ValueError(f"has no binary for this platform ({wanted}.*)")
    return md if md.fmiVersion == "2.0" else scalar_view(md)


#: The FMI 3.0 types the master passes and sets, as the FMI 2.0 types of the scalar view.
FMI3_TYPES = {"Float64": "Real", "Int32": "Integer", "Boolean": "Boolean"}


class ScalarView(ModelDescription):
    """An FMI 3.0 model description as its scalar view (scalar_view), and what the view
    leaves out: `clocked` maps the scalar name of each clock and clocked variable to
    (its scalar variable, the name of its clock)."""

    clocked: dict[str, tuple[Any, str]]


def _scalars(v) -> list:
    """One variable per scalar of `v` (FMI 3.0 type names turned into FMI 2.0 ones)."""
    starts = str(v.start).split() if v.start is not None else None
    elements = [None] if not v.shape else list(range(int(v.shape[0])))
    scalars = []
    for k in elements:
        scalar = copy.copy(v)
        scalar.shape = ()
        scalar.type = FMI3_TYPES.get(v.type, v.type)
        if k is not None:  # as robofmu.fmi3.scalar_names: der(x[1]) of an array state x
            state = v.derivative.name if v.derivative is not None else None
            element = f"{state or v.name}[{k + 1}]"
            scalar.name = f"der({element})" if state else element
            if starts is not None:
                scalar.start = starts[k] if len(starts) == len(elements) else starts[0]
        scalars.append(scalar)
    return scalars


def scalar_view(md) -> ScalarView:
    """An FMI 3.0 model description as the scenario checks read FMI 2.0 ones: one
    variable per scalar (`x[1]`..`x[n]` of a one-dimensional array `x`, the names
    robofmu.fmi3 addresses), Float64, Int32 and Boolean as Real, Integer and Boolean
    (other types keep their FMI 3.0 name, which no check accepts). Clocks and the
    variables they clock are left out (kept in the view's `clocked`: the master reads
    them only where a scenario ticks the clock, robofmu.clocked). ValueError for what
    the master cannot run: arrays of more than one dimension or of a size set by a
    structural parameter."""
    scalars: list = []
    clocked: dict[str, tuple[Any, str]] = {}
    for v in md.modelVariables:
        if v.shape and (len(v.shape) != 1 or not isinstance(v.shape[0], int)):
            raise ValueError(f"declares {v.name} as an array of shape {v.shape}; only arrays "
                             "of one dimension of fixed size are supported")
        if v.type == "Clock" or v.clocks:
            clock = v.name if v.type == "Clock" else v.clocks[0].name
            clocked.update((s.name, (s, clock)) for s in _scalars(v))
            continue
        scalars += _scalars(v)
    view = ScalarView()
    for kind in type(md).__mro__:
        for slot in getattr(kind, "__slots__", ()):
            if slot != "__weakref__" and hasattr(md, slot):
                setattr(view, slot, getattr(md, slot))
    view.modelVariables = scalars
    view.clocked = clocked
    return view


def missing(md, alias: str, name: str, ticked: bool = False) -> str:
    """Why `alias` has no variable `name` in the scalar view `md`: none of that name,
    or a clock or a clocked variable (left out), with how to run it (`ticked`: the
    scenario ticks the clock already)."""
    clocked = getattr(md, "clocked", {}).get(name)
    if clocked is None:
        return f"{alias} has no variable '{name}'"
    clock = clocked[1]
    if ticked:
        return (f"{alias}.{name} is the input clock that sample_period.{alias} ticks, which "
                "has no value to pass; connect or record the variables it clocks")
    what = ("is an input clock, which the master ticks itself" if clock == name else
            f"is clocked (by {clock}): it has a value only at that clock's ticks")
    return (f"{alias}.{name} {what}; give {alias} a sample period (field "
            f"'sample_period.{alias}', docs/co-simulation-master.md) to run it")


def describe(path: Path, field: str):
    """The model description of the FMU at `path`, or ScenarioError naming `field`."""
    path = Path(path)
    try:
        status = os.stat(path)
    except FileNotFoundError:
        raise ScenarioError(f"field '{field}': {path} does not exist; build the FMUs "
                            "(bash scripts/build-fmus.sh) or pass --fmu-dir DIR") from None
    except OSError as e:
        raise ScenarioError(f"field '{field}': cannot read {path}: {e.strerror}") from None
    if not stat.S_ISREG(status.st_mode):
        raise ScenarioError(f"field '{field}': {path} is not a file; name an .fmu file")
    # The file itself, however it is named, as it is now (a rewritten FMU is read again).
    key = (status.st_dev, status.st_ino, status.st_mtime_ns, status.st_size)
    md = _DESCRIBED.get(key)
    if md is not None:
        return md
    try:
        md = _describe(str(path))
    except ValueError as e:
        raise ScenarioError(f"field '{field}': {path} {e}; name an FMI 2.0 or 3.0 "
                            "co-simulation FMU (bash scripts/build-fmus.sh builds ours in "
                            "dist/)") from None
    except OSError as e:
        raise ScenarioError(f"field '{field}': cannot read {path}: {e.strerror}") from None
    if len(_DESCRIBED) >= 32:
        del _DESCRIBED[next(iter(_DESCRIBED))]
    _DESCRIBED[key] = md
    return md


#: describe's model descriptions by file (device, inode, modification time, size).
_DESCRIBED: dict[tuple[int, int, int, int], Any] = {}


def variable_names(md) -> frozenset[str]:
    """The names of a described FMU's variables (kept with describe's descriptions)."""
    kept = _NAMES.get(id(md))
    if kept is None or kept[0] is not md:
        if len(_NAMES) >= 32:
            del _NAMES[next(iter(_NAMES))]
        kept = _NAMES[id(md)] = (md, frozenset(v.name for v in md.modelVariables))
    return kept[1]


_NAMES: dict[int, tuple[Any, frozenset[str]]] = {}


def variables(path: Path) -> dict:
    return {v.name: v for v in describe(path, "fmus").modelVariables}


def start_value(path: Path, name: str) -> float:
    return float(variables(path)[name].start)


def unit_of(md, variable) -> tuple[str, tuple[int, ...] | None, float, float] | None:
    """(unit name, exponents over BASE_UNITS + OTHER_BASE_UNITS, factor, offset) of a
    variable's declared unit; None when it declares none."""
    name = variable.unit or (variable.declaredType.unit if variable.declaredType else None)
    if not name:
        return None
    for unit in md.unitDefinitions or []:
        if unit.name == name and unit.baseUnit is not None:
            b = unit.baseUnit
            exps = tuple(int(getattr(b, k, 0) or 0) for k in BASE_UNITS + OTHER_BASE_UNITS)
            return name, exps, float(getattr(b, "factor", 1.0) or 1.0), float(
                getattr(b, "offset", 0.0) or 0.0)
    return name, None, 1.0, 0.0


def check_value(md, alias: str, name: str, value, field: str):
    """`value` (SI, already converted) for variable `name`: declared, settable, of its
    type, integer in range, within min/max. Returns the value to set."""
    v = {x.name: x for x in md.modelVariables}.get(name)
    if v is None:
        raise ScenarioError(f"field '{field}': {missing(md, alias, name)}; see the "
                            "FMU reference (docs/fmus.md) for the names")
    if v.causality not in ("parameter", "input") or v.variability == "constant":
        raise ScenarioError(f"field '{field}': {alias}.{name} is {v.causality} "
                            f"({v.variability}) and cannot be set; set a parameter or input")
    kind = v.type
    if kind == "Boolean":
        if not isinstance(value, bool):
            raise ScenarioError(f"field '{field}': {alias}.{name} is a Boolean; write true "
                                f"or false, not {value!r}")
        return value
    if isinstance(value, bool):
        raise ScenarioError(f"field '{field}': {alias}.{name} is a {kind}; write a number, "
                            f"not {value!r}")
    if kind in ("Integer", "Enumeration"):
        if not isinstance(value, int):
            raise ScenarioError(f"field '{field}': {alias}.{name} is an integer; write a whole "
                                f"number, not {value!r}")
        low, high = INT32
        if not low <= value <= high:
            raise ScenarioError(f"field '{field}': {value} does not fit a 32-bit integer "
                                f"[{low}, {high}]; write a value in range")
    elif kind == "Real":
        if not isinstance(value, (int, float)) or not math.isfinite(value):
            raise ScenarioError(f"field '{field}': {alias}.{name} must be a finite number, "
                                f"got {value!r}")
        value = float(value)
    else:
        raise ScenarioError(f"field '{field}': {alias}.{name} is of type {kind}, which "
                            "scenarios cannot set")
    low = _bound(v.min if v.min is not None else getattr(v.declaredType, "min", None))
    high = _bound(v.max if v.max is not None else getattr(v.declaredType, "max", None))
    if (low is not None and value < low) or (high is not None and value > high):
        span = f"[{-math.inf if low is None else low:g}, {math.inf if high is None else high:g}]"
        raise ScenarioError(f"field '{field}': {value!r} is outside the range {span} that "
                            f"{alias}.{name} declares; write a value in range")
    return value


def _bound(text):
    if text is None:
        return None
    try:
        return float(text)
    except (TypeError, ValueError):
        return None
