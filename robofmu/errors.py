"""Errors of the co-simulation master (free of FMPy so the master logic stands alone)."""

import argparse
from pathlib import Path


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


class FmuError(CosimError):
    """An FMI call failed; the message names the FMU instance, the call and the FMU's log."""


class StepDiscarded(Exception):
    """doStep returned fmi2Discard: the step was rejected and the state is unchanged."""

    def __init__(self, alias: str, time: float, reason: str):
        super().__init__(f"{alias} discarded the step at t = {time:.9g} s: {reason}")
        self.alias, self.time, self.reason = alias, time, reason
