"""The one error the animation reports to a user: FILE: FIELD: problem; what to do."""

from __future__ import annotations

from ..errors import ScenarioError

COMMAND_LINE = "command line"


class AnimateError(ScenarioError):
    """A user mistake (bad file, field or argument); the CLI prints it and exits 2."""

    def __init__(self, where: str, field: str, problem: str):
        super().__init__(f"{where}: {field}: {problem}")
