"""The errors of ``cosim verify``: bad input (exit 2) and a run that failed (exit 1)."""

from __future__ import annotations

from ..errors import ScenarioError


COMMAND_LINE = "command line"  # the "file" of a mistake in the options


class VerifyError(ScenarioError):
    """Bad input: the message names the file, the field or column, and the fix."""

    def __init__(self, source: object, field: str, problem: str, fix: str):
        where = f"{source}: {field}" if field else f"{source}"
        super().__init__(f"{where}: {problem}; {fix}")


class RunFailed(RuntimeError):
    """The FMU could not be simulated (an FMI call failed): a verification failure."""
