"""Errors of the co-simulation master (free of FMPy so the master logic stands alone)."""


class ScenarioError(ValueError):
    """A scenario file that cannot be run; the message names the field."""


class CosimError(RuntimeError):
    """The co-simulation cannot go on; the message names the FMU, the call and the time."""


class FmuError(CosimError):
    """An FMI call failed; the message names the FMU instance, the call and the FMU's log."""


class StepDiscarded(Exception):
    """doStep returned fmi2Discard: the step was rejected and the state is unchanged."""

    def __init__(self, alias: str, time: float, reason: str):
        super().__init__(f"{alias} discarded the step at t = {time:.9g} s: {reason}")
        self.alias, self.time, self.reason = alias, time, reason
