"""Input extrapolation for FMI 3.0 instances through the intermediate update
(input_extrapolation = "linear" or "quadratic"; FMI 3.0 has no input derivatives in
co-simulation).

An FMU that provides intermediate update calls the importer back at points inside a
communication step (our plant and PID: 9 inner points of 10 equal sub-intervals); at
each, the inputs declared intermediateUpdate="true" may be set. The master's
derivatives (robofmu.master) are applied there, at the middle of the sub-interval that
starts: u = u(t_k) + u'_k s + u''_k s^2 / 2 with s = tau + d/2 - t_k, d the length of
the sub-interval before. Over a step the input is a staircase that integrates the
ramp the FMI 2.0 build integrates exactly (a parabola to within d^2 u'' / 24 a
sub-interval), on every sub-interval but the first (held at u(t_k)).
"""

from __future__ import annotations

import zipfile
from pathlib import Path
from xml.etree import ElementTree


def flagged_inputs(path: Path) -> set[str]:
    """Names of the variables declared intermediateUpdate="true" (FMPy 0.3.32 does not
    read the attribute: the XML itself)."""
    with zipfile.ZipFile(path) as archive:
        root = ElementTree.fromstring(archive.read("modelDescription.xml"))
    variables = root.find("ModelVariables")
    return {v.get("name", "") for v in (variables if variables is not None else [])
            if v.get("intermediateUpdate") == "true"}


class IntermediateInputs:
    """The derivatives of one FMI 3.0 instance's inputs, applied at its intermediate points."""

    def __init__(self, instance, flagged: set[str]):
        self.instance, self.flagged = instance, flagged
        self.slopes: dict[str, tuple[float, float]] = {}
        self.start = self.last = 0.0
        self.base: list[float] = []
        self.failure: Exception | None = None

    def set_derivatives(self, names, values, order: int) -> None:
        """Derivatives of orders 1..order of the inputs `names` for the next step (all
        of order 1, then all of order 2; inputs not declared intermediateUpdate are
        held)."""
        n = len(names)
        for k, name in enumerate(names):
            if self.instance.variable_of(name) in self.flagged:
                second = float(values[n + k]) if order >= 2 else 0.0
                self.slopes[name] = (float(values[k]), second)

    def begin(self, t: float) -> None:
        """A step starts at t: the inputs' values there are the ramps' origins."""
        self.start = self.last = t
        self.failure = None
        self.base = self.instance.get_written(tuple(self.slopes))

    def callback(self, _env, time, set_requested, _get_allowed, _finished,
                 _can_return_early, _early_requested, _early_time) -> None:
        if not set_requested or not self.slopes or self.failure is not None:
            return
        try:
            # The value at the middle of the sub-interval that starts here, taken as long
            # as the one before it (the midpoint rule: the staircase integrates the ramp
            # exactly on every sub-interval but the first).
            ds = time - self.start + 0.5 * (time - self.last)
            self.last = time
            self.instance.set_values(tuple(self.slopes), [
                u + d1 * ds + d2 * ds * ds / 2 for u, (d1, d2) in zip(self.base,
                                                                     self.slopes.values())])
        except Exception as e:  # noqa: BLE001 - an exception cannot cross the C callback
            self.failure = e
