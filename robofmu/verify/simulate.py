"""The FMU run: FMPy's simulate_fmu with the case's experiment, start values and
inputs, recording the variables behind the reference's columns. The case is checked
against the FMU first (bad input, exit 2); an FMI call that fails is RunFailed."""

from __future__ import annotations

import contextlib
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from fmpy import extract, read_model_description, simulate_fmu

from ..fmi2 import remove_extracted
from .case import Case
from .errors import RunFailed, VerifyError
from .names import Names

INTERFACE_NAMES = {"cs": "CoSimulation", "me": "ModelExchange"}


@dataclass
class Run:
    """A simulation result: time and one series per reference column; ``messages``:
    the FMU's log messages ("[STATUS] text"), the last ones kept."""

    time: np.ndarray
    series: dict[str, np.ndarray]
    messages: list[str] = field(default_factory=list)


STATUS = ["OK", "WARNING", "DISCARD", "ERROR", "FATAL", "PENDING"]
KEPT_MESSAGES = 20


class _Log:
    """The FMU's log messages, the last ones kept, to tell why the FMU ended a run.

    As FMI 3.0 logger callback (environment, status, category, message) it is given to
    FMPy. FMI 2.0 FMUs keep FMPy's own logger, which prints "[STATUS] message" lines:
    FMPy routes an FMI 2.0 logger of ours through a proxy that keeps the last one given
    in a global of its C library, which would point at a freed callback once this run is
    over (the next FMPy run in the process crashed). So the run's stdout comes here as
    a file (``write``): everything goes on to stderr, the "[STATUS] ..." lines are kept."""

    def __init__(self):
        self.messages: list[str] = []
        self._line = ""

    def _keep(self, text: str) -> None:
        self.messages = (self.messages + [text.strip()])[-KEPT_MESSAGES:]

    def __call__(self, *args):
        status, message = args[-3], args[-1]
        text = message.decode("utf-8", "replace") if isinstance(message, bytes) else str(message)
        label = STATUS[status] if isinstance(status, int) and 0 <= status < len(STATUS) else status
        self._keep(f"[{label}] {text}")

    def write(self, text: str) -> int:
        sys.stderr.write(text)
        self._line += text
        *lines, self._line = self._line.split("\n")
        for line in lines:
            if any(line.startswith(f"[{label}] ") for label in STATUS):
                self._keep(line)
        return len(text)

    def flush(self) -> None:
        sys.stderr.flush()


def read_description(fmu: Path):
    if not Path(fmu).is_file():
        raise VerifyError(fmu, "FMU", "no such file", "give the path of an .fmu file")
    try:
        return read_model_description(str(fmu), validate=False)
    except Exception as e:  # FMPy raises plain exceptions for a broken archive or XML
        raise VerifyError(fmu, "modelDescription.xml", f"cannot be read ({e})",
                          "give an FMI 2.0 or 3.0 FMU") from None


def choose_interface(fmu: Path, description, wanted: str | None) -> str:
    """"CoSimulation" or "ModelExchange": `wanted` (cs/me) or the first supported."""
    supported = [name for name, part in (("CoSimulation", description.coSimulation),
                                         ("ModelExchange", description.modelExchange))
                 if part is not None]
    if not supported:
        raise VerifyError(fmu, "modelDescription.xml", "the FMU has neither Co-Simulation "
                          "nor Model Exchange", "give an FMU with one of them")
    if wanted is None:
        return supported[0]
    name = INTERFACE_NAMES[wanted]
    if name not in supported:
        raise VerifyError(fmu, "--interface", f"the FMU does not support {name}",
                          f"use --interface {'cs' if wanted == 'me' else 'me'}")
    return name


def _check(case: Case, names: Names, fmu: Path) -> None:
    for signal in case.signals():
        if names.locate(signal) is None:
            raise VerifyError(case.reference.path, f"column '{signal}'",
                              f"{fmu.name} has no such variable",
                              "remove the column or name a variable of the FMU")
    for name in case.start_values:
        if names.locate(name) is None:
            raise VerifyError(fmu, f"start value '{name}'", "the FMU has no such variable",
                              "check the name in case.json start_values or --start")
    if case.inputs is None:
        return
    for column in case.inputs.columns:
        found = names.locate(column)
        if found is None or found[0].causality != "input":
            inputs = sorted(v.name for v in names.variables.values() if v.causality == "input")
            raise VerifyError(case.inputs.path, f"column '{column}'",
                              f"is not an input of {fmu.name}",
                              f"use the FMU's inputs ({', '.join(inputs) or 'none'})")


def simulate(fmu: Path, description, case: Case, interface: str) -> Run:
    """Runs the FMU over the case's experiment through FMPy."""

    names = Names(description)
    _check(case, names, Path(fmu))
    inputs = None if case.inputs is None else names.input_signals(case.inputs.time,
                                                                  case.inputs.columns)
    # Extracted here: simulate_fmu removes the folder it extracts only when the run ends
    # well.
    unzipped = extract(str(fmu))
    log = _Log()
    try:
        # FMPy prints its warnings (an input the file leaves out, ...): to stderr, so
        # that stdout holds the verdicts only.
        with contextlib.redirect_stdout(log):
            result = simulate_fmu(
                unzipped, validate=False, fmi_type=interface, start_time=case.start,
                stop_time=case.stop, output_interval=case.output_interval,
                step_size=case.step if interface == "CoSimulation" and case.step > 0 else None,
                relative_tolerance=case.rel_tol,
                set_stop_time=case.options is None or case.options.stop_time_defined,
                start_values=names.start_values(case.start_values),
                input=inputs, output=names.outputs(case.signals()),
                logger=log if description.fmiVersion.startswith("3.") else None)
    except Exception as e:  # FMPy raises plain exceptions for a failed FMI call
        said = f" (its log: {log.messages[-1]})" if log.messages else ""
        raise RunFailed(f"{fmu}: the {interface} run failed: {e}{said}") from e
    finally:
        remove_extracted(unzipped)
    return Run(np.asarray(result["time"], float),
               {s: names.column(result, s) for s in case.signals()}, log.messages)
