"""The library API of robofmu, re-exported at the package's top level (``import robofmu``).

- :func:`load` reads a scenario file or a bundled example into a :class:`Scenario`,
  whose fields can be changed in code (:meth:`Scenario.set`) with the file's checks,
  units and messages;
- :class:`System` builds a co-simulation of any FMI 2.0 co-simulation FMUs in code (the
  plain scenario form: FMUs, parameters, connections, coupling, extrapolation);
- :func:`simulate` runs either (or a scenario file) and returns a :class:`Result` of
  numpy arrays;
- :func:`fmu` and :func:`example` give the bundled FMUs and example scenarios;
- :func:`run_sweep`, :func:`write_ssp`, :func:`write_container`, :func:`verify_fmu`
  and :func:`write_animation` are the commands ``cosim sweep|ssp|container|verify|animate``
  as functions.

Errors are the classes of :mod:`robofmu.errors`: :class:`ScenarioError` (a
``ValueError``: bad input, the one-line message ``cosim`` prints, naming the file or
field and the fix), :class:`SimulationError` (a ``RuntimeError``: a run that failed)
and :class:`MissingExtra` (a ``RuntimeError``: an optional dependency to install).
"""

from __future__ import annotations

import argparse
import copy
import math
import os
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from . import bundle
from .errors import CosimError, ScenarioError, SimulationError, require
from .scenario import Scenario as Plan
from .scenario import parse_document, read_document

if TYPE_CHECKING:
    import pandas

__all__ = ["Result", "Scenario", "System", "SweepResult", "VerifyResult", "example", "fmu",
           "load", "run_sweep", "simulate", "verify_fmu", "write_animation",
           "write_container", "write_ssp"]

#: A file name as the API takes it.
PathLike = str | os.PathLike[str]
#: A parameter value: SI number, boolean, or a string with a unit ("40 rad/s").
Value = float | int | bool | str


def fmu(name: str) -> Path:
    """The bundled FMU `name` (``"Pss3Plant"``, ``"PID"``, ``"Planner"``, ...; ``fmi3/``
    or ``fmi3-scalar/`` in front for the FMI 3.0 builds): what ``cosim fmus --path NAME``
    prints. ScenarioError for a name that is not bundled."""
    path = bundle.fmu(name)
    if path is None:
        raise ScenarioError(f"fmu: {name!r} is not a bundled FMU ({bundle.where_fmus_come_from()}); "
                            "name one of those")
    return path


def example(name: str) -> Path:
    """The bundled example scenario `name` (``"regulation"``, ``"path1_quintic"``, ...)
    or reference case (``"Pss3Plant/path1"``, a folder for :func:`verify_fmu`): what
    ``cosim examples --path NAME`` prints. ScenarioError for an unknown name."""
    path = bundle.scenarios().get(name) or bundle.references().get(name)
    if path is None:
        raise ScenarioError(f"example: {name!r} is not a bundled example scenario (examples: "
                            f"{', '.join(bundle.scenarios()) or 'none'}) or reference case "
                            "('cosim examples' lists them); name one of those")
    return path


def _scenario_file(path_or_name: PathLike) -> Path:
    """A scenario file, or a bundled example by name."""
    text = os.fspath(path_or_name)
    path = Path(text)
    if path.suffix in (".toml", ".json") or path.exists() or os.sep in text or "/" in text:
        return path
    return example(text)


class Scenario:
    """A scenario read into one object: the document as written (:attr:`document`, in a
    person's units where the file uses them) and its validated, resolved form (SI, every
    FMU checked). :meth:`set` changes a field of the document with the same checks,
    units and messages as the file. Made by :func:`load` or :meth:`System.scenario`."""

    def __init__(self, document: dict[str, Any], base_dir: Path,
                 fmu_dir: PathLike | None = None, source: Path | None = None) -> None:
        self._document = copy.deepcopy(document)
        self._base_dir = Path(base_dir)
        self._fmu_dir = None if fmu_dir is None else Path(fmu_dir)
        self.source = source
        self._plan = self._resolve(self._document)

    def _resolve(self, document: dict[str, Any]) -> Plan:
        try:
            return parse_document(copy.deepcopy(document), self._base_dir, self._fmu_dir,
                                  preflight=True)
        except ScenarioError as e:
            raise ScenarioError(f"{self._where()}{e}") from None
        except RecursionError:
            raise ScenarioError(f"{self._where()}is nested too deeply to read") from None

    def _where(self) -> str:
        return f"{self.source}: " if self.source is not None else ""

    @property
    def document(self) -> dict[str, Any]:
        """A copy of the scenario document (as the file states it)."""
        return copy.deepcopy(self._document)

    @property
    def name(self) -> str:
        """The scenario's name (its output files are named after it)."""
        return self._plan.name

    @property
    def start_time(self) -> float:
        """Start time, s."""
        return self._plan.start_time

    @property
    def stop_time(self) -> float:
        """Stop time, s."""
        return self._plan.stop_time

    @property
    def step_size(self) -> float:
        """Communication step, s."""
        return self._plan.step_size

    @property
    def fmus(self) -> dict[str, Path]:
        """Alias -> the FMU file it runs."""
        return dict(self._plan.fmus)

    @property
    def parameters(self) -> dict[str, dict[str, float | int | bool]]:
        """Alias -> the start values set before initialisation (SI, resolved: a
        closed-loop scenario's designed gains included)."""
        return copy.deepcopy(self._plan.parameters)

    @property
    def connections(self) -> list[tuple[str, str]]:
        """("alias.output", "alias.input") of every connection."""
        return [(str(c.source), str(c.target)) for c in self._plan.connections]

    def get(self, field_path: str) -> Any:
        """The document's value at `field_path` ("gains.omega",
        "motion.waypoints[1].angles"); ScenarioError when there is none."""
        from .sweep.spec import SpecError, get_path
        try:
            return copy.deepcopy(get_path(self._document, field_path))
        except SpecError as e:
            raise ScenarioError(f"{self._where()}{e}") from None

    def set(self, field_path: str, value: Any) -> None:
        """Sets the document's field `field_path` ("gains.omega", "stop_time",
        "parameters.pid.kp") to `value` as the file would write it ("40 rad/s" where the
        file takes a quantity), and validates the scenario again: ScenarioError with the
        file's message (the scenario unchanged) when the value is refused."""
        from .sweep.spec import SpecError, set_path
        document = copy.deepcopy(self._document)
        try:
            set_path(document, field_path, value)
        except SpecError as e:
            raise ScenarioError(f"{self._where()}{e}") from None
        self._plan = self._resolve(document)
        self._document = document

    def resolved(self) -> Plan:
        """A copy of the validated plain form (SI) that the master runs."""
        return copy.deepcopy(self._plan)

    def __repr__(self) -> str:
        return (f"robofmu.Scenario({self.name!r}, fmus={list(self._plan.fmus)}, "
                f"stop_time={self.stop_time!r}, step_size={self.step_size!r})")


def load(path_or_name: PathLike, fmu_dir: PathLike | None = None) -> Scenario:
    """Reads a scenario file (.toml or .json), or the bundled example of that name
    (:func:`example`), validated against its FMUs as ``cosim check`` does. FMU paths are
    relative to the file's folder, or looked up by file name in `fmu_dir`."""
    path = _scenario_file(path_or_name)
    try:
        document = read_document(path)
    except ScenarioError as e:
        raise ScenarioError(f"{path}: {e}") from None
    return Scenario(document, path.parent, fmu_dir, source=path)


def _seconds(value: float | str, what: str) -> float:
    """A time given in s or as "value unit" (e.g. "2 s", "1 ms")."""
    from .units import quantity
    if isinstance(value, str):
        return quantity(value, "time", what)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ScenarioError(f"{what}: must be a finite number of seconds or a string like "
                            f"\"1 ms\", got {value!r}")
    return float(value)


class System:
    """A co-simulation of FMUs built in code, without a scenario file (the plain
    scenario form): any FMI 2.0 or FMI 3.0 co-simulation FMU, ours or anyone's (an
    element of an FMI 3.0 array is named ``"alias.x[1]"``), or the FMI 3.0 builds of
    ours in place of their FMI 2.0 files with ``simulate(..., fmi3=True)``.

    >>> system = System(stop_time=1.0, step_size="1 ms")  # doctest: +SKIP
    >>> system.add("pid", fmu("PID"), parameters={"kp[1]": 100.0})  # doctest: +SKIP
    >>> system.connect("source.y", "pid.setpoint[1]")  # doctest: +SKIP

    `coupling` ("sampled" or "gauss-seidel"), `input_extrapolation` ("hold",
    "linear", "quadratic") and `max_step_halvings` are the scenario fields of the same
    names (docs/user-guide.md). The FMUs are taken in the order they were added (the
    scenario's `order`): add an FMU whose outputs depend on its inputs (a controller)
    before the FMUs it feeds, so that they step with its output at t_k."""

    def __init__(self, stop_time: float | str, step_size: float | str = 0.001,
                 start_time: float | str = 0.0, *, name: str = "system",
                 coupling: str = "sampled", input_extrapolation: str = "quadratic",
                 max_step_halvings: int = 0) -> None:
        self._head: dict[str, Any] = {
            "name": name, "start_time": _seconds(start_time, "start_time"),
            "stop_time": _seconds(stop_time, "stop_time"),
            "step_size": _seconds(step_size, "step_size"), "coupling": coupling,
            "input_extrapolation": input_extrapolation, "max_step_halvings": max_step_halvings}
        self._fmus: dict[str, str] = {}
        self._parameters: dict[str, dict[str, Value]] = {}
        self._connections: list[dict[str, str]] = []
        self._record: list[str] = []
        self._sample_period: dict[str, float] = {}
        self._model_exchange: dict[str, str] = {}

    def add(self, alias: str, fmu_file: PathLike,
            parameters: Mapping[str, Value] | None = None, *,
            sample_period: float | str | None = None,
            model_exchange: str | None = None) -> System:
        """Adds the FMU `fmu_file` (a path, or a bundled FMU's name such as "PID") as
        `alias`, with start values `parameters` (variable -> SI value or "value unit");
        `sample_period` (s or "value unit"): the master ticks its periodic input clock
        at that period; `model_exchange` ("rk4"): the master integrates it in Model
        Exchange (the scenario fields sample_period.ALIAS and model_exchange.ALIAS)."""
        if alias in self._fmus:
            raise ScenarioError(f"fmus.{alias}: the alias is used twice; give each FMU its "
                                "own alias")
        text = os.fspath(fmu_file)
        self._fmus[alias] = text if bundle.is_name(text) else str(Path(text).absolute())
        if sample_period is not None:
            self._sample_period[alias] = _seconds(sample_period, f"sample_period.{alias}")
        if model_exchange is not None:
            self._model_exchange[alias] = model_exchange
        for variable, value in (parameters or {}).items():
            self.set(f"{alias}.{variable}", value)
        return self

    def connect(self, source: str, target: str) -> System:
        """Connects the output `source` ("alias.variable") to the input `target`."""
        self._connections.append({"from": source, "to": target})
        return self

    def set(self, name: str, value: Value) -> System:
        """Sets the start value of "alias.variable" (SI, or "value unit")."""
        alias, _, variable = name.partition(".")
        if alias not in self._fmus or not variable:
            raise ScenarioError(f"parameters: {name!r} must be \"alias.variable\" of an added "
                                f"FMU (added: {', '.join(self._fmus) or 'none'}); add the FMU "
                                "first")
        self._parameters.setdefault(alias, {})[variable] = value
        return self

    def record(self, *signals: str) -> System:
        """Records these "alias.variable" signals too (every connected output is
        recorded anyway)."""
        self._record += signals
        return self

    def document(self) -> dict[str, Any]:
        """The system as a plain-form scenario document (SI numbers)."""
        parameters = {alias: {variable: _si_value(alias, variable, value, self._fmus[alias])
                              for variable, value in values.items()}
                      for alias, values in self._parameters.items()}
        return {**self._head, "fmus": dict(self._fmus), "order": list(self._fmus),
                "parameters": parameters, "connections": list(self._connections),
                "record": list(self._record),
                **({"sample_period": dict(self._sample_period)} if self._sample_period else {}),
                **({"model_exchange": dict(self._model_exchange)} if self._model_exchange
                   else {})}

    def scenario(self) -> Scenario:
        """The system validated against its FMUs (ScenarioError naming what is wrong)."""
        return Scenario(self.document(), Path.cwd())


def _fmu_path(text: str) -> Path:
    if bundle.is_name(text):
        return fmu(text)
    return Path(text)


def _si_value(alias: str, variable: str, value: Value, fmu_file: str | Path) -> Value:
    """`value` for FMU variable `alias.variable`: a number or boolean as it is, a
    "value unit" string converted to the unit the FMU declares for the variable."""
    if not isinstance(value, str):
        return value
    from .fmu_check import describe, missing, unit_of
    from .units import UNITS, _split, exponents
    where = f"parameters.{alias}.{variable}"
    path = _fmu_path(fmu_file) if isinstance(fmu_file, str) else fmu_file
    md = describe(path, f"fmus.{alias}")
    v = {x.name: x for x in md.modelVariables}.get(variable)
    if v is None:
        raise ScenarioError(f"field '{where}': {missing(md, alias, variable)}; see the "
                            "FMU reference (docs/fmus.md) for the names")
    number, unit = _split(value.strip(), where)
    try:
        amount = float(number)
    except ValueError:
        raise ScenarioError(f"field '{where}': cannot read a number in {value!r}") from None
    declared = unit_of(md, v)
    factor, dimension = UNITS[unit]
    if declared is None:
        raise ScenarioError(f"field '{where}': {alias}.{variable} declares no unit, so "
                            f"{value!r} cannot be converted; give the number alone")
    name, exps, fmu_factor, offset = declared
    if exps is None:
        if name != unit:
            raise ScenarioError(f"field '{where}': {alias}.{variable} is in '{name}' (no SI "
                                f"definition), got '{unit}'; give the value in {name}")
        return amount
    if exps != exponents(dimension):
        raise ScenarioError(f"field '{where}': {alias}.{variable} is in '{name}', got '{unit}' "
                            f"({dimension}); give the value in {name} or a unit of its kind")
    return (amount * factor - offset) / fmu_factor


class Result:
    """The recorded signals of one run, as numpy arrays: :attr:`time` and
    ``result["alias.variable"]`` (SI, or the unit :meth:`unit` names)."""

    def __init__(self, time: npt.NDArray[np.float64], columns: dict[str, npt.NDArray[np.float64]],
                 units: dict[str, str], discards: list[str], name: str) -> None:
        #: Communication points, s.
        self.time = time
        self._columns = columns
        self._units = units
        #: One line per step an FMU discarded and the master retried.
        self.discards = discards
        #: The scenario's name.
        self.name = name

    @property
    def names(self) -> list[str]:
        """The recorded signals, "alias.variable", in the order of the CSV."""
        return list(self._columns)

    def __getitem__(self, name: str) -> npt.NDArray[np.float64]:
        if name == "time":
            return self.time
        try:
            return self._columns[name]
        except KeyError:
            raise KeyError(f"{name!r} was not recorded (recorded: {', '.join(self._columns)}); "
                           "connect it or add it to the record") from None

    def __contains__(self, name: object) -> bool:
        return name == "time" or name in self._columns

    def __iter__(self) -> Iterator[str]:
        return iter(["time", *self._columns])

    def __len__(self) -> int:
        return 1 + len(self._columns)

    def unit(self, name: str) -> str:
        """The unit of `name` as its FMU declares it ("1": none declared)."""
        self[name]  # KeyError for a name not recorded
        return self._units.get(name, "1")

    def to_pandas(self) -> pandas.DataFrame:
        """A DataFrame indexed by time, one column per signal (needs pandas:
        ``pip install 'robofmu[pandas]'``)."""
        pd = require("pandas", "pandas", "Result.to_pandas")
        frame = pd.DataFrame(dict(self._columns), index=pd.Index(self.time, name="time"))
        frame.attrs["units"] = dict(self._units)
        return frame

    def to_csv(self, path: PathLike) -> Path:
        """Writes the CSV `cosim run` writes (quoted names, time first, SI) to `path`."""
        from .master import Result as Table
        out = Path(path)
        Table(self.names, self.time.tolist(), {n: c.tolist() for n, c in self._columns.items()},
              self.discards).write_csv(out)
        return out

    def __repr__(self) -> str:
        return f"robofmu.Result({self.name!r}, {len(self.time)} points, signals={self.names})"


Target = Scenario | System | str | os.PathLike[str]


def _plan_of(target: Target, fmu_dir: PathLike | None) -> Plan:
    if isinstance(target, Scenario):
        return target.resolved()
    if isinstance(target, System):
        return target.scenario().resolved()
    if isinstance(target, (str, os.PathLike)):
        return load(target, fmu_dir).resolved()
    raise ScenarioError(f"simulate: {target!r} is not a scenario, a System or a scenario "
                        "file; pass one of those")


def _override(plan: Plan, parameters: Mapping[str, Value]) -> None:
    """Sets "alias.variable" start values of `plan`, checked as a scenario's are."""
    from .fmu_check import check_value, describe
    for name, value in parameters.items():
        alias, _, variable = name.partition(".")
        if alias not in plan.fmus or not variable:
            raise ScenarioError(f"parameters: {name!r} must be \"alias.variable\" of one of "
                                f"the FMUs ({', '.join(plan.fmus)})")
        si = _si_value(alias, variable, value, plan.fmus[alias])
        md = describe(plan.fmus[alias], f"fmus.{alias}")
        plan.parameters.setdefault(alias, {})[variable] = check_value(
            md, alias, variable, si, f"parameters.{alias}.{variable}")


def simulate(target: Target, parameters: Mapping[str, Value] | None = None, *,
             fmu_dir: PathLike | None = None, fmi3: bool = False,
             progress: bool = False) -> Result:
    """Simulates `target` (a :class:`Scenario`, a :class:`System`, a scenario file or a
    bundled example's name) and returns its recorded signals.

    `parameters`: "alias.variable" -> value (SI, or "value unit" converted to the unit
    the FMU declares), set on top of the scenario's; checked against the variable's
    type and min/max. `fmi3`: run the FMI 3.0 builds of the FMUs (dist/fmi3/).
    ScenarioError for bad input, SimulationError when the run fails."""
    from .master import run_arrays, text_progress
    from .outputs import column_units
    plan = _plan_of(target, fmu_dir)
    if parameters:
        _override(plan, parameters)
    try:
        table = run_arrays(plan, fmi3=fmi3, progress=text_progress() if progress else None)
    except CosimError as e:
        raise SimulationError(f"{plan.name}: the simulation failed: {e}") from e
    return Result(table.time, table.columns, column_units(plan, table.names),
                  list(table.discards), plan.name)


@dataclass
class SweepResult:
    """The outcome of :func:`run_sweep`: the table written (one row per run) and the counts."""

    table: Path
    plots: list[Path]
    runs: int
    failed: int
    wall_s: float
    reasons: dict[str, int] = field(default_factory=dict)

    def rows(self) -> list[dict[str, str]]:
        """The table's rows (column -> text), as written."""
        from .sweep.store import read_table
        return read_table(self.table)[1]


def run_sweep(spec: PathLike, out: PathLike, *, client: Any = None, scheduler: str | None = None,
          workers: int | None = 0, resume: bool = False, plots: bool = False,
          fmu_dir: PathLike | None = None, progress: bool = False) -> SweepResult:
    """Runs the sweep SPEC (docs/sweeps.md) into the folder `out`. By default serially in
    this process (``workers=0``); `workers=N` on a local Dask cluster, `scheduler` on a
    running one, `client` on an existing ``dask.distributed.Client`` (how Dask reaches
    SLURM or Kubernetes clusters). Dask needs ``pip install 'robofmu[sweep]'``; `plots`
    needs ``'robofmu[plots]'``."""
    from .sweep import SpecError, sweep_file
    if client is not None and scheduler is not None:
        raise ScenarioError("run_sweep: give client or scheduler, not both")
    if client is not None or scheduler is not None or workers != 0:
        require("distributed", "sweep", "run_sweep on Dask")
    if plots:
        require("matplotlib", "plots", "run_sweep(plots=True)")
    spec_path, folder = Path(spec), Path(out)
    fmus = None if fmu_dir is None else Path(fmu_dir)
    if folder.exists() and not folder.is_dir():
        raise ScenarioError(f"run_sweep: out: {folder} is not a directory; give a directory")
    remote = client if client is not None else scheduler
    try:
        _, outcome = sweep_file(spec_path, folder, fmus, scheduler=remote,
                                workers=None if remote is not None else workers,
                                resume=resume, progress=progress, plots=plots)
    except SpecError as e:
        raise ScenarioError(str(e)) from None
    return SweepResult(outcome.table, list(outcome.plots), outcome.runs, outcome.failed,
                       outcome.wall_s, dict(outcome.reasons))


def _source(target: Target) -> Path | None:
    """The scenario file `target` was read from, if any (named in messages)."""
    if isinstance(target, Scenario):
        return target.source
    if isinstance(target, (str, os.PathLike)):
        return _scenario_file(target)
    return None


def write_ssp(target: Target, path: PathLike, fmu_dir: PathLike | None = None) -> Path:
    """Writes `target` (scenario, System or file) as an SSP 1.0 archive at `path` (a
    .ssp file)."""
    from .ssp import check_archive_path, write_ssp as write
    out = Path(path)
    check_archive_path(out)
    write(_plan_of(target, fmu_dir), out, _source(target))
    return out


def write_container(target: Target, path: PathLike, fmu_dir: PathLike | None = None) -> Path:
    """Writes `target` as one container FMU at `path` (a .fmu file), built by the
    fmu-manipulation-toolbox (``pip install 'robofmu[container]'``)."""
    from .container import build_container, check_container_path
    require("fmu_manipulation_toolbox", "container", "write_container")
    out = Path(path)
    check_container_path(out)
    build_container(_plan_of(target, fmu_dir), out, _source(target))
    return out


def _arguments(command: str, first: str, **values: Any) -> argparse.Namespace:
    """The arguments of ``cosim COMMAND FIRST`` (the command table's parser: every
    option's default), then `values`."""
    from .cli import build_parser
    args = build_parser(command).parse_args([command, "--", first])
    for key, value in values.items():
        setattr(args, key, value)
    return args


@dataclass
class VerifyResult:
    """The verdict of :func:`verify_fmu`: whether every signal passed, the JSON report
    written and the lines ``cosim verify`` prints (one per signal)."""

    passed: bool
    report: Path
    lines: list[str]


def verify_fmu(fmu_file: PathLike, case: PathLike | None, out: PathLike, *,
           interface: str | None = None, step: float | None = None) -> VerifyResult:
    """Runs the FMU `fmu_file` (FMI 2.0 or 3.0) on the reference case folder `case`
    (``cosim verify FMU CASE --out OUT``: docs/verify.md) and judges every reference
    column against its tolerance; the report and the plots of failing signals go to the
    folder `out`. ScenarioError (a VerifyError) for bad input, SimulationError when the
    FMU cannot be simulated."""
    from .verify.cli import write_files
    from .verify.errors import RunFailed
    from .verify.runner import REPORT, verify_case
    args = _arguments("verify", os.fspath(fmu_file), fmu=Path(fmu_file), out=Path(out),
                      case=None if case is None else Path(case), interface=interface,
                      step=step)
    if args.fmu.is_dir():
        raise ScenarioError(f"verify_fmu: {args.fmu} is a folder; name an .fmu file (a "
                            "cross-check tree is verified by 'cosim verify TREE')")
    try:
        result = verify_case(args.fmu, args.case, args, args.interface, args.out)
        write_files(dict(result.files), args.out, result.signals)
        if result.error is not None:
            raise RunFailed(result.error)
    except RunFailed as e:
        raise SimulationError(str(e)) from None
    return VerifyResult(result.status == "passed", args.out / REPORT, list(result.lines))


def write_animation(csv: PathLike, out: PathLike, *, scenario: PathLike | None = None,
            fmu_file: PathLike | None = None, frames: int = 40, fps: float = 10.0,
            size: int = 360) -> list[Path]:
    """Draws the robot of a run's CSV (``cosim run``'s, or :meth:`Result.to_csv`'s)
    moving, as NAME.gif in the folder `out` (``cosim animate``: docs/animation.md); the
    plant's geometry from `scenario`, else `fmu_file`, else the bundled Pss3Plant.
    Returns the files written; ScenarioError (an AnimateError) for bad input."""
    from .animate.make import make_animation
    plant = fmu_file if fmu_file is not None else (fmu("Pss3Plant") if scenario is None
                                                   else None)
    return make_animation(Path(csv), Path(out), fmu=None if plant is None else Path(plant),
                          scenario=None if scenario is None else Path(scenario),
                          frames=frames, fps=fps, size=size)[1]
