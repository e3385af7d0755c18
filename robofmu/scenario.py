"""Scenario files: loading and validation.

Schema (TOML shown; JSON has the same structure)::

    name = "tracking-quintic"          # used for output file names
    start_time = 0.0                   # s (optional, default 0)
    stop_time = 2.0                    # s, > start_time
    step_size = 0.001                  # s, communication step, > 0 (optional, default 1 ms)
    order = ["planner", "pid", "plant"]  # Gauss-Seidel order; every FMU once
    max_step_halvings = 0              # Discard retries with h/2, h/4, ... (optional)
    coupling = "sampled"               # or "gauss-seidel" (optional, default "sampled")
    controller = "pid"                 # or "computed-torque": the closed loop's controller,
                                       # for the Rust reference (optional, default "pid")
    input_extrapolation = "quadratic"  # or "linear", "hold" (or the order 2, 1, 0): input
                                       # derivatives up to that order where the FMUs allow

    [fmus]                             # alias -> FMU path (relative to this file), or
    planner = "Planner"                # the name of a bundled FMU (cosim fmus lists them)

    [parameters.planner]               # start values set before initialisation
    "tf" = 2.0

    [[connections]]                    # output -> input, both "alias.variable"
    from = "planner.q[1]"
    to = "pid.setpoint[1]"

    record = ["plant.theta[1]"]        # extra signals to record (optional)

    [sample_period]                    # alias -> s: the master ticks that FMU's periodic
    ct = 0.001                         # input clock (FMI 3.0) every so many seconds, a
                                       # whole number of steps (robofmu.clocked)
    [model_exchange]                   # alias -> method: an FMI 3.0 FMU in Model Exchange,
    plant = "rk4"                      # integrated by the master (robofmu.integrated)

A malformed scenario raises ScenarioError naming the offending field.

A closed-loop scenario can also be written in a person's units (waypoints in degrees,
base-frame angular velocities, gains by a design rule): a file with a [motion] table is
resolved into the form above by robofmu.closed_loop when it is loaded.
"""

from __future__ import annotations

import json
import math
import os
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from . import bundle, preflight as checks
from .closed_loop import FIELDS, WHERE, is_closed_loop, resolve
from .controllers import kind_of
from .errors import ScenarioError
from .limits import parse_limits
from .notes import say
from .schedule import PlanSwitch
from .workspace import check_plan, is_closed_loop_plant

__all__ = ["PlanSwitch", "Scenario", "ScenarioError", "Signal", "Connection",
           "fmu_file", "load_scenario", "parse_document", "parse_scenario"]


COUPLINGS = ("sampled", "gauss-seidel")
INTEGRATORS = ("rk4",)  # model_exchange: the master's methods (robofmu.integrated)
EXTRAPOLATIONS = ("hold", "linear", "quadratic")  # index: the order of the input derivatives
DEFAULT_STEP = 0.001  # s
MAX_STEPS = 1_000_000  # communication steps of one run (the results are held in memory)
MAX_SIGNALS = 1000  # connections and recorded signals
MAX_FILE_BYTES = 1_000_000
NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.-]{0,99}")
ALIAS = re.compile(r"[A-Za-z_][A-Za-z0-9_]{0,99}")  # "alias.variable"; file names of exports
REPOSITORY_DIST = Path(__file__).resolve().parent.parent / "dist"


@dataclass(frozen=True)
class Signal:
    """A variable of one FMU instance, written "alias.variable"."""

    alias: str
    variable: str

    def __str__(self) -> str:
        return f"{self.alias}.{self.variable}"


@dataclass(frozen=True)
class Connection:
    source: Signal
    target: Signal


@dataclass
class Scenario:
    name: str
    fmus: dict[str, Path]
    order: list[str]
    start_time: float
    stop_time: float
    step_size: float
    parameters: dict[str, dict[str, float | int | bool]] = field(default_factory=dict)
    connections: list[Connection] = field(default_factory=list)
    record: list[Signal] = field(default_factory=list)
    max_step_halvings: int = 0
    coupling: str = "sampled"
    input_extrapolation: str = "quadratic"
    # Plan switches of a multi-segment motion (PlanSwitch), in order.
    schedule: list = field(default_factory=list)
    # Limits the run is judged against (robofmu.limits), SI.
    limits: dict = field(default_factory=dict)
    description: str | None = None
    # The closed loop's controller ("pid" or "computed-torque", robofmu.controllers): read
    # by the Rust reference from the expanded form.
    controller: str = "pid"
    # alias -> sample period (s) of an FMU whose input clock the master ticks
    # (robofmu.clocked).
    sample_period: dict[str, float] = field(default_factory=dict)
    # alias -> the method ("rk4") by which the master integrates an FMU in Model
    # Exchange (robofmu.integrated).
    model_exchange: dict[str, str] = field(default_factory=dict)

    @property
    def steps(self) -> int:
        """Number of communication steps from start to stop time."""
        return round((self.stop_time - self.start_time) / self.step_size)


# What a TOML/JSON reader calls the Python types of a document.
KIND_NAMES = {str: "a string", float: "a finite number", int: "an integer", bool: "a boolean",
              dict: "a table", list: "a list"}


def _require(data: dict, key: str, kind, where: str = ""):
    if key not in data:
        raise ScenarioError(f"missing field '{where}{key}'")
    value = data[key]
    if kind is float and isinstance(value, int) and not isinstance(value, bool):
        value = float(value)
    if not isinstance(value, kind) or (kind is float and not math.isfinite(value)):
        kinds = kind if isinstance(kind, tuple) else (kind,)
        name = " or ".join(KIND_NAMES.get(k, k.__name__) for k in kinds)
        raise ScenarioError(f"field '{where}{key}' must be {name}, got {value!r}")
    return value


def _signal(text, where: str, aliases) -> Signal:
    if not isinstance(text, str) or "." not in text:
        raise ScenarioError(f"field '{where}' must be \"alias.variable\", got {text!r}")
    alias, variable = text.split(".", 1)
    if alias not in aliases:
        raise ScenarioError(f"field '{where}' names unknown FMU '{alias}' (known: {sorted(aliases)})")
    if not variable:
        raise ScenarioError(f"field '{where}' has an empty variable name")
    return Signal(alias, variable)


def parse_scenario(data: dict, base_dir: Path) -> Scenario:
    """Validates a scenario given as a parsed TOML/JSON document."""
    if not isinstance(data, dict):
        raise ScenarioError("a scenario must be a table/object at the top level")
    known = {"name", "description", "start_time", "stop_time", "step_size", "order", "fmus",
             "parameters", "connections", "record", "max_step_halvings", "coupling", "limits",
             "plan_switches", "input_extrapolation", "controller", "sample_period", "model_exchange"}
    unknown = sorted(set(data) - known, key=str)
    if unknown:
        raise ScenarioError(f"unknown field '{unknown[0]}'; the fields are {sorted(known)}")
    name = _require(data, "name", str)
    if "description" in data:
        _require(data, "description", str)
    if not NAME.fullmatch(name):
        raise ScenarioError(f"field 'name' must be a plain file name (letters, digits, '_', "
                            f"'-', '.'; at most 100; no '/'), got {name!r}; it names the "
                            "output files under --out")
    fmus_raw = _require(data, "fmus", dict)
    if not fmus_raw:
        raise ScenarioError("field 'fmus' must name at least one FMU")
    for alias in fmus_raw:
        if not ALIAS.fullmatch(alias):
            raise ScenarioError(f"field 'fmus': the alias {alias!r} must be a name of letters, "
                                "digits and '_' (not starting with a digit; at most 100): it "
                                "names the FMU's signals and files; rename it")
    fmus = {alias: base_dir / _require(fmus_raw, alias, str, "fmus.") for alias in fmus_raw}
    order = _require(data, "order", list)
    if not all(isinstance(a, str) for a in order) or sorted(order) != sorted(fmus):
        raise ScenarioError(f"field 'order' must list every FMU of 'fmus' exactly once, got {order}")
    start = _require(data, "start_time", float) if "start_time" in data else 0.0
    stop = _require(data, "stop_time", float)
    step = _require(data, "step_size", float) if "step_size" in data else DEFAULT_STEP
    if step <= 0.0:
        raise ScenarioError(f"field 'step_size' must be positive, got {step}")
    if stop <= start:
        raise ScenarioError(f"field 'stop_time' ({stop}) must be after 'start_time' ({start})")
    steps = (stop - start) / step
    if steps > MAX_STEPS:
        raise ScenarioError(f"field 'step_size': {stop - start:g} s in steps of {step:g} s are "
                            f"{steps:.3g} steps, more than the {MAX_STEPS:,} a run may have; "
                            "use a larger step_size or a shorter run")
    if abs(steps - round(steps)) > 1e-9 * max(1.0, steps):
        raise ScenarioError(f"field 'step_size' ({step}) must divide stop - start ({stop - start})")
    params_raw = data.get("parameters", {})
    if not isinstance(params_raw, dict):
        raise ScenarioError("field 'parameters' must be a table of FMU aliases")
    parameters = {}
    for alias, values in params_raw.items():
        if alias not in fmus:
            raise ScenarioError(f"field 'parameters.{alias}' names unknown FMU '{alias}'")
        if not isinstance(values, dict):
            raise ScenarioError(f"field 'parameters.{alias}' must be a table of name = value")
        for var, value in values.items():
            if not isinstance(value, (int, float, bool)) or (
                    isinstance(value, float) and not math.isfinite(value)):
                raise ScenarioError(f"field 'parameters.{alias}.{var}' must be a finite number "
                                    f"or boolean, got {value!r}")
        parameters[alias] = dict(values)
    connections = []
    raw_connections = data.get("connections", [])
    if not isinstance(raw_connections, list) or len(raw_connections) > MAX_SIGNALS:
        raise ScenarioError(f"field 'connections' must be a list of at most {MAX_SIGNALS} "
                            "{from, to} tables")
    targets = set()
    for k, c in enumerate(raw_connections):
        where = f"connections[{k}]"
        if not isinstance(c, dict) or set(c) != {"from", "to"}:
            raise ScenarioError(f"field '{where}' must have exactly the keys 'from' and 'to'")
        conn = Connection(_signal(c["from"], f"{where}.from", fmus), _signal(c["to"], f"{where}.to", fmus))
        if conn.target in targets:
            raise ScenarioError(f"field '{where}.to': input {conn.target} is connected twice")
        targets.add(conn.target)
        connections.append(conn)
    record_raw = data.get("record", [])
    if not isinstance(record_raw, list) or len(record_raw) > MAX_SIGNALS:
        raise ScenarioError(f"field 'record' must be a list of at most {MAX_SIGNALS} "
                            "\"alias.variable\"")
    record = [_signal(s, f"record[{k}]", fmus) for k, s in enumerate(record_raw)]
    halvings = data.get("max_step_halvings", 0)
    if not isinstance(halvings, int) or isinstance(halvings, bool) or not 0 <= halvings <= 20:
        raise ScenarioError(f"field 'max_step_halvings' must be an integer in 0..20, got {halvings!r}")
    coupling = data.get("coupling", "sampled")
    if coupling not in COUPLINGS:
        raise ScenarioError(f"field 'coupling' must be one of {COUPLINGS}, got {coupling!r}")
    extrapolation = data.get("input_extrapolation", "quadratic")
    if type(extrapolation) is int and 0 <= extrapolation < len(EXTRAPOLATIONS):
        extrapolation = EXTRAPOLATIONS[extrapolation]
    if extrapolation not in EXTRAPOLATIONS:
        raise ScenarioError(f"field 'input_extrapolation' must be one of {EXTRAPOLATIONS} "
                            f"or the order 0, 1 or 2, got {extrapolation!r}")
    return Scenario(controller=kind_of(data), name=name,
                    sample_period=_sample_periods(data.get("sample_period", {}), fmus, step,
                                                  coupling, halvings),
                    model_exchange=_model_exchange(data.get("model_exchange", {}), fmus,
                                                   coupling, halvings), fmus=fmus, order=list(order),
                    start_time=start, stop_time=stop,
                    step_size=step, parameters=parameters, connections=connections,
                    record=record, max_step_halvings=halvings, coupling=coupling,
                    input_extrapolation=extrapolation, description=data.get("description"),
                    limits=parse_limits(data.get("limits", {})),
                    schedule=_plan_switches(data.get("plan_switches", []), fmus, round(steps)))


def _sample_periods(raw, fmus, step: float, coupling: str,
                    halvings: int) -> dict[str, float]:
    """``[sample_period]``: alias -> the period (s) at which the master ticks the FMU's
    input clock, a whole number of communication steps."""
    if not isinstance(raw, dict):
        raise ScenarioError("field 'sample_period' must be a table of alias = period in s, "
                            "such as sample_period = { ct = 0.001 }")
    periods = {}
    for alias in raw:
        where = f"sample_period.{alias}"
        if alias not in fmus:
            raise ScenarioError(f"field '{where}' names unknown FMU '{alias}' (known: "
                                f"{sorted(fmus)})")
        period = raw[alias]
        if (isinstance(period, bool) or not isinstance(period, (int, float))
                or not math.isfinite(period) or period <= 0.0):
            raise ScenarioError(f"field '{where}' must be a positive number of seconds "
                                f"(such as 0.001), got {period!r}")
        period = float(period)
        steps = period / step
        if round(steps) < 1 or abs(steps - round(steps)) > 1e-9 * steps:
            raise ScenarioError(f"field '{where}': {period:g} s is not a whole number of "
                                f"communication steps of {step:g} s (step_size); make it a "
                                "multiple of step_size")
        periods[alias] = period
    if periods and (coupling != "sampled" or halvings):
        raise ScenarioError("field 'sample_period': a scenario with clocks runs with "
                            "coupling = \"sampled\" and no max_step_halvings; remove those "
                            "fields")
    return periods


def _model_exchange(raw, fmus, coupling: str, halvings: int) -> dict[str, str]:
    """``[model_exchange]``: alias -> the method ("rk4") by which the master integrates
    that FMU in Model Exchange."""
    if not isinstance(raw, dict):
        raise ScenarioError("field 'model_exchange' must be a table of alias = method, such "
                            "as model_exchange = { plant = \"rk4\" }")
    for alias, method in raw.items():
        if alias not in fmus:
            raise ScenarioError(f"field 'model_exchange.{alias}' names unknown FMU '{alias}' "
                                f"(known: {sorted(fmus)})")
        if method not in INTEGRATORS:
            raise ScenarioError(f"field 'model_exchange.{alias}' must be one of {INTEGRATORS} "
                                f"(the master's integration methods), got {method!r}")
    if raw and (coupling != "sampled" or halvings):
        raise ScenarioError("field 'model_exchange': an FMU in Model Exchange runs with "
                            "coupling = \"sampled\" and no max_step_halvings; remove those "
                            "fields")
    return dict(raw)


def extrapolation_order(name: str) -> int:
    """The order of the input derivatives of input_extrapolation `name` (hold: 0)."""
    return EXTRAPOLATIONS.index(name)


def _plan_switches(raw, fmus, steps: int) -> list[PlanSwitch]:
    """``[[plan_switches]]`` (step, alias, parameters): the expanded form of a
    multi-segment motion, in increasing steps inside the run."""
    if not isinstance(raw, list) or len(raw) > MAX_SIGNALS:
        raise ScenarioError(f"field 'plan_switches' must be a list of at most {MAX_SIGNALS} "
                            "{step, alias, parameters} tables")
    switches, last = [], 0
    for k, item in enumerate(raw):
        where = f"plan_switches[{k}]"
        if not isinstance(item, dict) or set(item) != {"step", "alias", "parameters"}:
            raise ScenarioError(f"field '{where}' must have exactly the keys 'step', 'alias' "
                                "and 'parameters'")
        step = item["step"]
        if not isinstance(step, int) or isinstance(step, bool) or not last < step < steps:
            raise ScenarioError(f"field '{where}.step' must be an integer after the previous "
                                f"switch's and before the last step ({steps}), got {step!r}")
        if item["alias"] not in fmus:
            raise ScenarioError(f"field '{where}.alias' names unknown FMU {item['alias']!r}")
        values = item["parameters"]
        if not isinstance(values, dict) or not all(
                isinstance(v, (int, float, bool)) and not (
                    isinstance(v, float) and not math.isfinite(v)) for v in values.values()):
            raise ScenarioError(f"field '{where}.parameters' must be a table of finite "
                                "numbers or booleans")
        switches.append(PlanSwitch(step, item["alias"], dict(values)))
        last = step
    return switches


def _bundled_fmu(alias: str, name: str, fmu_dir) -> Path:
    """The FMU a scenario names without a path: `name`.fmu in `fmu_dir` (fmi3/ in front
    kept), else the bundled one (the wheel's; in a checkout, dist/'s)."""
    if fmu_dir is not None:
        return (Path(fmu_dir) / f"{name}.fmu").absolute()
    path = bundle.fmu(name)
    if path is None:
        raise ScenarioError(f"field 'fmus.{alias}': '{name}' is not a bundled FMU "
                            f"({bundle.where_fmus_come_from()}); name one of those or a "
                            "path to an .fmu file")
    return path


def fmu_file(alias: str, entry: str, base_dir: Path, fmu_dir=None) -> Path:
    """The file a scenario's FMU entry names: a bundled FMU's name (_bundled_fmu), else a
    path by file name in `fmu_dir`, else relative to the scenario's folder `base_dir`
    (for readers of the raw document, such as the sweeps; no fallback to dist/)."""
    if bundle.is_name(entry):
        return _bundled_fmu(alias, entry, fmu_dir)
    return Path(fmu_dir) / Path(entry).name if fmu_dir is not None else Path(base_dir) / entry


def _find_fmus(data: dict, base_dir: Path, fmu_dir) -> dict:
    """The document with its FMU paths found: a name without .fmu among the bundled
    FMUs (_bundled_fmu); a path by file name in `fmu_dir`, else relative to the
    scenario, else (a file that is not there) by file name in the repository's dist/
    when this package runs from a checkout."""
    if not isinstance(data, dict) or not isinstance(data.get("fmus"), dict):
        return data
    found = {}
    for alias, f in data["fmus"].items():
        if not isinstance(f, str) or not f:
            found[alias] = f  # parse_scenario names the field
            continue
        if bundle.is_name(f):  # "Pss3Plant", "fmi3/PID": a bundled FMU (robofmu.bundle)
            found[alias] = str(_bundled_fmu(alias, f, fmu_dir))
            continue
        path = (Path(fmu_dir) / Path(f).name if fmu_dir is not None else base_dir / f).absolute()
        fallback = REPOSITORY_DIST / Path(f).name
        if fmu_dir is None and not path.exists() and fallback.is_file():
            say(f"field 'fmus.{alias}': {os.path.normpath(path)} is not there; running the repository's "
                f"{fallback} instead (found by file name in its dist/); give the right "
                "path or --fmu-dir DIR to run your own FMU")
            path = fallback
        found[alias] = str(path)
    return dict(data, fmus=found)


def parse_document(data: dict, base_dir: Path, fmu_dir: str | Path | None = None,
                   preflight: bool = False) -> Scenario:
    """A plain or hand-written (closed-loop) scenario document, validated; with
    `preflight` (the default of load_scenario, not here: a sweep's runs report what the
    FMUs refuse as failed runs), also against its FMUs (robofmu.preflight) and, for the
    closed loop, the start pose, the waypoints and the whole plan against the workspace
    (robofmu.workspace)."""
    data = _find_fmus(data, base_dir, fmu_dir)
    if not is_closed_loop(data):
        scenario = parse_scenario(data, base_dir)
        fields, where = {}, {"start": "parameters.plant", "plan": "parameters.planner"}
    else:
        plain, schedule = resolve(data, base_dir, preflight)
        scenario = parse_scenario(plain, base_dir)
        scenario.schedule = schedule
        fields, where = FIELDS, dict(WHERE, start="start.angles" if "angles" in data.get(
            "start", {}) else "motion.waypoints[0].angles")
    if preflight:
        checks.check(scenario, fields)
        if is_closed_loop_plant(scenario):
            check_plan(scenario, where)
    return scenario


def read_document(path: Path) -> dict:
    """The parsed TOML/JSON file; ScenarioError (naming the file) for anything unreadable."""
    if path.suffix not in (".toml", ".json"):
        raise ScenarioError("scenario files are .toml or .json; name such a file")
    try:
        if not path.is_file():
            raise ScenarioError("is not a file" if path.exists() else "does not exist")
        if path.stat().st_size > MAX_FILE_BYTES:
            raise ScenarioError(f"is larger than {MAX_FILE_BYTES:,} bytes; a scenario is a "
                                "short text file")
        text = path.read_bytes().decode("utf-8")
        if path.suffix == ".toml":
            return tomllib.loads(text)
        return json.loads(text)
    except UnicodeDecodeError as e:
        raise ScenarioError(f"is not UTF-8 text (byte {e.start}); save it as UTF-8") from None
    except (tomllib.TOMLDecodeError, json.JSONDecodeError) as e:
        raise ScenarioError(f"not valid {path.suffix[1:].upper()}: {e}") from None
    except RecursionError:
        raise ScenarioError("is nested too deeply to read") from None
    except OSError as e:
        raise ScenarioError(f"cannot be read: {e.strerror}") from None


def schedule_field(path: Path) -> str:
    """The field that holds the plan switches of the scenario file `path` (already loaded):
    'plan_switches' in the plain form, 'motion.waypoints' in the hand-written one."""
    return "plan_switches" if "plan_switches" in read_document(Path(path)) else \
        "motion.waypoints"


def load_scenario(path: str | Path, fmu_dir: str | Path | None = None,
                  preflight: bool = True) -> Scenario:
    """Reads and validates a .toml or .json scenario file. FMU paths are relative to the
    file's folder, or, with `fmu_dir`, looked up by file name in `fmu_dir`."""
    path = Path(path)
    try:
        data = read_document(path)
        return parse_document(data, path.parent, fmu_dir, preflight)
    except ScenarioError as e:
        raise ScenarioError(f"{path}: {e}") from None
    except RecursionError:
        raise ScenarioError(f"{path}: is nested too deeply to read") from None
