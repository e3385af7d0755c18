"""Plan switches of a multi-segment motion (shared by the scenario reader and the
closed-loop resolver, robofmu.scenario and robofmu.closed_loop)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class PlanSwitch:
    """At communication step `step`, FMU `alias` is reset and given `parameters`."""

    step: int
    alias: str
    parameters: dict
