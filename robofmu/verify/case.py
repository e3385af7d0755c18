"""The case: reference, inputs, experiment, start values, event times and tolerances,
from a folder in the FMI cross-check layout (``<Model>_ref.csv``, ``<Model>_ref.opt``,
optional ``<Model>_in.csv`` or ``<Model>_input.csv`` and ``case.json``) and the command
line's options, which take precedence. The case file's format: docs/verify.md."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import casefile, tolerance
from .errors import COMMAND_LINE, VerifyError
from .table import Options, Table, read_options, read_table
from ..scenario import MAX_STEPS

CASE_FILE = "case.json"
ANY = "*"  # the tolerance of every signal that has none of its own
DEFAULT_REL_TOL = 1e-6


@dataclass
class Case:
    """What to run and how to judge it; ``rules`` by interface, then by signal."""

    name: str
    reference: Table
    inputs: Table | None
    start: float
    stop: float
    step: float  # 0: variable step (the rules' StepSize 0)
    rel_tol: float
    start_values: dict[str, object] = field(default_factory=dict)
    event_times: list[float] = field(default_factory=list)
    rules: dict[str | None, dict[str, tolerance.Rule]] = field(default_factory=dict)
    options: Options | None = None  # the _ref.opt file's, when the case has one
    allow_early_end: bool = False

    @property
    def output_interval(self) -> float | None:
        """The output interval: the step, else OutputIntervalLength, else None (FMPy
        chooses: docs/verify.md)."""
        if self.step > 0:
            return self.step
        if self.options is not None and self.options.output_interval:
            return self.options.output_interval
        return None

    def signals(self) -> list[str]:
        return list(self.reference.columns)

    def rule(self, interface: str, signal: str):
        """The signal's rule: its own, else "*", else the FMI cross-check band rule; one
        given for this interface before one for every interface."""
        for name in (signal, ANY):
            for key in (interface, None):
                if name in self.rules.get(key, {}):
                    return self.rules[key][name]
        return tolerance.CrossCheckBand()


def _model_files(folder: Path | None, reference: Path | None) -> tuple[str, Path | None]:
    """The model's name and its reference: the folder's one <Model>_ref.csv, or with
    --reference, the folder's one <Model>_ref.opt (no folder: the file's name)."""
    if folder is None:  # load_case: then --reference is given
        assert reference is not None
        return reference.stem.removesuffix("_ref"), None
    suffix = "_ref.csv" if reference is None else "_ref.opt"
    found = sorted(folder.glob(f"*{suffix}"))
    if len(found) != 1:
        what = "no" if not found else f"{len(found)}"
        raise VerifyError(folder, f"<Model>{suffix}", f"{what} such files found",
                          f"put exactly one <Model>{suffix} in the case folder")
    return found[0].name[: -len(suffix)], (found[0] if reference is None else None)


def _input_file(folder: Path, model: str) -> Path | None:
    found = [p for p in (folder / f"{model}_in.csv", folder / f"{model}_input.csv")
             if p.exists()]
    if len(found) > 1:
        raise VerifyError(folder, found[1].name, f"both {found[0].name} and {found[1].name} "
                          "exist", "keep one input file")
    return found[0] if found else None


def _experiment(folder: Path | None, model: str, reference: Table, step: float | None):
    """(start, stop, step, relative tolerance, options): the _ref.opt file's, --step
    over its StepSize; without a folder, the reference's span and median interval."""
    if folder is None:
        intervals = np.diff(reference.time)
        median = float(np.median(intervals[intervals > 0]))
        return reference.time[0], reference.time[-1], step or median, DEFAULT_REL_TOL, None
    options_path = folder / f"{model}_ref.opt"
    if not options_path.exists():
        raise VerifyError(options_path, "", "is missing", "write StartTime, StopTime, "
                          "StepSize and RelTol lines (FMI cross-check _ref.opt)")
    o = read_options(options_path)
    return o.start, o.stop, step or o.step, o.rel_tol, o


def _check_coverage(case: Case) -> None:
    t = case.reference.time
    slack = 1e-9 * max(1.0, abs(case.start), abs(case.stop))
    if t[0] > case.start + slack or t[-1] < case.stop - slack:
        raise VerifyError(case.reference.path, "column 'time'",
                          f"the reference covers {t[0]:g} to {t[-1]:g} s, the experiment "
                          f"{case.start:g} to {case.stop:g} s",
                          "extend the reference or shorten the experiment (StartTime, StopTime)")


def _check_step(step: float, case: Case, source, field: str) -> None:
    """At least one step and at most MAX_STEPS over the experiment: a step longer than
    the experiment would compare the start alone, a tiny one would never end."""
    span = case.stop - case.start
    steps = span / step
    if not (math.isfinite(step) and 1.0 - 1e-9 <= steps <= MAX_STEPS):
        raise VerifyError(source, field, f"a step of {step:g} s makes {steps:.3g} steps "
                          f"of the {span:g} s experiment",
                          f"give a step from {span / MAX_STEPS:.3g} to {span:g} s")


def _check_rule_names(case: Case, source: Path | str, field: str = "tolerances.") -> None:
    for rules in case.rules.values():
        for signal in rules:
            if signal != ANY and signal not in case.reference.columns:
                raise VerifyError(source, f"{field}{signal}",
                                  "the reference has no such column",
                                  f"use one of {', '.join(case.signals())} or remove it")


def load_case(folder: Path | None, options) -> Case:
    """The case of `folder` (or None) with the command line's `options` applied:
    reference, input, step, start (NAME=VALUE list), tolerance (NAME=SPEC list)."""
    if folder is not None and not Path(folder).is_dir():
        raise VerifyError(folder, "CASE", "is not a folder", "give the case folder "
                          "(<Model>_ref.csv, <Model>_ref.opt, ...) or --reference FILE")
    if folder is None and options.reference is None:
        raise VerifyError(COMMAND_LINE, "CASE", "no case folder and no --reference",
                          "give a case folder or --reference FILE")
    folder = None if folder is None else Path(folder)
    model, reference_path = _model_files(folder, options.reference)
    reference_file = options.reference or reference_path
    assert reference_file is not None  # _model_files: the folder's, or --reference
    reference = read_table(reference_file)
    input_path = options.input or (_input_file(folder, model) if folder else None)
    data = {}
    case_path = folder / CASE_FILE if folder else None
    if case_path is not None and case_path.exists():
        data = casefile.read_case_file(case_path)
    source = case_path if case_path is not None else COMMAND_LINE  # where a value is wrong
    start, stop, step, rel_tol, opt = _experiment(folder, model, reference, options.step)
    case = Case(
        name=f"{folder.parent.name}/{folder.name}" if folder else model,
        reference=reference, inputs=read_table(input_path) if input_path else None,
        start=float(start), stop=float(stop), step=float(step), rel_tol=float(rel_tol),
        start_values=casefile.start_values(source, data.get("start_values", {})),
        event_times=casefile.event_times(source, data.get("event_times", [])),
        rules=casefile.tolerances(source, data.get("tolerances", {})),
        options=opt, allow_early_end=bool(getattr(options, "allow_early_end", False)))
    opt_path = folder / f"{model}_ref.opt" if folder else COMMAND_LINE
    check_case(case, opt_path, options, "StepSize" if folder else "--step", source)
    apply_options(case, options)
    return case


def check_case(case: Case, experiment: Path | str, options, step_field: str = "StepSize",
               rules: Path | str | None = None) -> None:
    """The reference covers the experiment, the step makes a sane number of steps, every
    rule names a column; `experiment` and `rules` are where a mistake is (`rules`
    defaults to `experiment`)."""
    _check_coverage(case)
    if options.step is not None:
        _check_step(case.step, case, COMMAND_LINE, "--step")
    elif case.step > 0:
        _check_step(case.step, case, experiment, step_field)
    elif case.output_interval is not None:
        _check_step(case.output_interval, case, experiment, "OutputIntervalLength")
    _check_rule_names(case, experiment if rules is None else rules)


def _pair(text: str, option: str) -> tuple[str, str]:
    name, sep, value = text.partition("=")
    if not sep or not name.strip():
        raise VerifyError(COMMAND_LINE, option, f"'{text}' is not NAME=VALUE",
                          f"write {option} NAME=VALUE")
    return name.strip(), value.strip()


def parse_value(text: str):
    """A start value from the command line: true/false, an integer, a number or text."""
    if text.lower() in ("true", "false"):
        return text.lower() == "true"
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def apply_options(case: Case, options) -> None:
    """--start NAME=VALUE and --tolerance NAME=SPEC (for every interface)."""
    for text in options.start or []:
        name, value = _pair(text, "--start")
        case.start_values[name] = parse_value(value)
    overrides = {}
    for text in options.tolerance or []:
        name, value = _pair(text, "--tolerance")
        try:
            overrides[name] = tolerance.from_text(value)
        except ValueError as e:
            raise VerifyError(COMMAND_LINE, f"--tolerance {name}", str(e),
                              "write NAME=ABS, NAME=ABS,REL or NAME=cross-check") from None
    probe = Case(case.name, case.reference, None, 0, 1, 1, 1, rules={None: overrides})
    _check_rule_names(probe, COMMAND_LINE, "--tolerance ")
    for rules in case.rules.values():
        for name in overrides:
            rules.pop(name, None)
    case.rules.setdefault(None, {}).update(overrides)
