"""robofmu: robot FMUs (3-PSS spherical parallel robot, PID, planner, computed torque)
and their co-simulation harness, as a library and as the ``cosim`` command.

>>> import robofmu
>>> scenario = robofmu.load("regulation")            # a bundled example, or a file
>>> scenario.set("gains.omega", "40 rad/s")          # any field, checked as in the file
>>> result = robofmu.simulate(scenario)
>>> result.time, result["plant.theta[1]"]            # numpy arrays (SI)

The names below are the public API (robofmu.api; docs/python-api.md). Errors:
:class:`ScenarioError` (a ``ValueError``: bad input), :class:`SimulationError` (a
``RuntimeError``: a run that failed), :class:`MissingExtra` (a ``RuntimeError``: an
optional dependency to install). The command line is ``cosim COMMAND`` (robofmu/cli.py),
also ``python -m robofmu COMMAND``.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from .api import (Result, Scenario, SweepResult, System, VerifyResult, example, fmu, load,
                      run_sweep, simulate, verify_fmu, write_animation, write_container,
                      write_ssp)
    from .errors import CosimError, MissingExtra, ScenarioError, SimulationError

__all__ = ["CosimError", "MissingExtra", "Result", "Scenario", "ScenarioError",
           "SimulationError", "SweepResult", "System", "VerifyResult", "example", "fmu", "load",
           "run_sweep", "simulate", "verify_fmu", "write_animation", "write_container",
           "write_ssp"]

_ERRORS = {"CosimError", "MissingExtra", "ScenarioError", "SimulationError"}


def __getattr__(name: str) -> Any:
    """The API's names, imported on first use: the ``cosim`` command line starts without
    importing numpy and FMPy for commands that do not need them."""
    if name in __all__:
        module = importlib.import_module(".errors" if name in _ERRORS else ".api", __name__)
        return getattr(module, name)
    raise AttributeError(f"module 'robofmu' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
