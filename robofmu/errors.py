"""Errors of the harness (free of FMPy so the master logic stands alone). The library's
documented exceptions: ScenarioError (a ValueError: bad input), CosimError and its
SimulationError (RuntimeErrors: a run that failed) and MissingExtra (a RuntimeError: an
optional dependency to install); each carries the one-line message `cosim` prints."""

import argparse
import importlib
from pathlib import Path
from types import ModuleType


def output_path(text: str) -> Path:
    """The argparse type of an argument naming where to write (--out, --expanded,
    --junit): refuses an empty or blank name, which Path would turn into the current
    directory (files written beside the user's own)."""
    if not text.strip():
        raise argparse.ArgumentTypeError(
            f"{text!r} names nothing; name the directory or file to write")
    return Path(text)


class ScenarioError(ValueError):
    """A scenario file that cannot be run; the message names the field."""


class CosimError(RuntimeError):
    """The co-simulation cannot go on; the message names the FMU, the call and the time."""


class SimulationError(CosimError):
    """A run that failed (an FMU refused a call or diverged); the message names the
    scenario, the FMU, the call and the time."""


class MissingExtra(RuntimeError):
    """An optional dependency that a function needs is not installed; the message names
    the function and the extra to install (``pip install 'robofmu[EXTRA]'``)."""


#: The optional dependencies: top-level module -> the extra that installs it.
EXTRAS = {"matplotlib": "plots", "PIL": "plots", "mpl_toolkits": "plots", "dask": "sweep",
          "distributed": "sweep", "pandas": "pandas", "fmu_manipulation_toolbox": "container"}


def require(module: str, extra: str, needed_by: str,
            alternative: str | None = None) -> ModuleType:
    """The module `module`, or MissingExtra naming `needed_by`, the extra to install and
    the `alternative` that needs no extra."""
    try:
        return importlib.import_module(module)
    except ImportError:
        other = f", or {alternative}" if alternative else ""
        raise MissingExtra(f"{needed_by} needs {module.split('.')[0]}, which robofmu leaves "
                           f"optional; pip install 'robofmu[{extra}]'{other}") from None


class FmuError(CosimError):
    """An FMI call failed; the message names the FMU instance, the call and the FMU's log."""


class StepDiscarded(Exception):
    """doStep returned fmi2Discard: the step was rejected and the state is unchanged."""

    def __init__(self, alias: str, time: float, reason: str):
        super().__init__(f"{alias} discarded the step at t = {time:.9g} s: {reason}")
        self.alias, self.time, self.reason = alias, time, reason
