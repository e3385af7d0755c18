"""Finite differences at initialization: which initial unknowns of an FMU move when one
known is moved in Initialization Mode, through FMPy (FMI 2.0 and FMI 3.0).

The knowns at initialization are the inputs, the variables with initial="exact"
(parameters, start values of states) and the independent variable (the start time; a
variable of FMI 3.0 only): FMI 2.0 section 3.2.3 (InitialUnknowns), FMI 3.0 section
2.4.8 (InitialUnknown). An unknown "moves" when any bit of any of its values
changes: a value the FMU does not compute from the known is reproduced exactly."""

import math
import shutil

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave

# Relative step of a Real known (of 1e-3 where it is 0): large enough to move every
# dependent value, small enough to keep every configuration valid (the robot still
# assembles, the inertia stays positive definite).
STEP = 1e-3


def _same(a, b):
    return a == b or (isinstance(a, float) and math.isnan(a) and math.isnan(b))


class InitialProbe:
    """One FMU (path) extracted to `directory`, instantiated afresh per evaluation."""

    def __init__(self, path, directory, fmi3):
        self.fmi3 = fmi3
        self.directory = extract(path, unzipdir=str(directory))
        md = read_model_description(self.directory)
        self.description = md
        cls = FMU3Slave if fmi3 else FMU2Slave
        self.fmu = cls(guid=md.guid, unzipDirectory=self.directory,
                       modelIdentifier=md.coSimulation.modelIdentifier)
        self.by_name = {v.name: v for v in md.modelVariables}
        # The independent variable (FMI 3.0 "time") is moved through the start time.
        self.knowns = [v for v in md.modelVariables
                       if v.causality in ("input", "independent")
                       or (v.initial == "exact" and v.variability != "constant")]
        self.unknowns = [u.variable for u in md.initialUnknowns]

    def close(self):
        self.fmu.freeLibrary()
        shutil.rmtree(self.directory, ignore_errors=True)

    def declared(self):
        """{unknown name: set of known names, or None (depends on all)}."""
        return {u.variable.name: (None if u.dependencies is None
                                  else {d.name for d in u.dependencies})
                for u in self.description.initialUnknowns}

    def _size(self, v):
        return v.shape[0] if self.fmi3 and v.shape else 1

    def _call(self, kind, operation, v, *args):
        suffix = {"Real": "Real", "Float64": "Float64", "Integer": "Integer",
                  "Int32": "Int32", "Boolean": "Boolean"}[v.type]
        return getattr(self.fmu, f"{operation}{suffix}")([v.valueReference], *args)

    def _set(self, v, values):
        self._call(v.type, "set", v, list(values))

    def _get(self, v):
        if self.fmi3:
            return tuple(self._call(v.type, "get", v, self._size(v)))
        return tuple(self._call(v.type, "get", v))

    def start(self, v):
        """The start values of the known v (a list, one per element)."""
        start = 0.0 if v.causality == "independent" else v.start
        if isinstance(start, str):
            start = start.split()
        values = start if isinstance(start, (list, tuple)) else [start] * self._size(v)
        parse = {"Boolean": lambda s: str(s).lower() in ("true", "1"),
                 "Integer": int, "Int32": int}.get(v.type, float)
        return [parse(s) if s is not None else parse(0) for s in values]

    def evaluate(self, assignments):
        """The initial unknowns' values in Initialization Mode after setting
        `assignments` ({variable name: list of values}; the independent variable's
        value is the start time, 0 by default); None when the FMU refuses."""
        independent = {v.name for v in self.knowns if v.causality == "independent"}
        start = next((values[0] for name, values in assignments.items()
                      if name in independent), 0.0)
        self.fmu.instantiate()
        try:
            if self.fmi3:
                self.fmu.enterInitializationMode(startTime=start)
            else:
                self.fmu.setupExperiment(startTime=start)
                self.fmu.enterInitializationMode()
            for name, values in assignments.items():
                if name not in independent:
                    self._set(self.by_name[name], values)
            return {v.name: self._get(v) for v in self.unknowns}
        except Exception:  # noqa: BLE001 - any refusal of the FMU: not evaluable
            return None
        finally:
            # The instance only: FMPy's freeInstance also unloads the library.
            free = self.fmu.fmi3FreeInstance if self.fmi3 else self.fmu.fmi2FreeInstance
            free(self.fmu.component)

    def moved(self, config):
        """{unknown: set of knowns that move it} under the configuration `config`
        ({name: values}, FMI 3.0 names: arrays whole), and the knowns whose move the
        FMU refused there."""
        base_assignments = self._expand(config)
        base = self.evaluate(base_assignments)
        assert base is not None, f"the configuration {config} is refused"
        moved = {name: set() for name in base}
        refused = set()
        for known in self.knowns:
            values = base_assignments.get(known.name, self.start(known))
            for i in range(len(values)):
                changed = list(values)
                changed[i] = _perturbed(known, values[i])
                result = self.evaluate({**base_assignments, known.name: changed})
                if result is None:
                    refused.add(known.name)
                    continue
                for name, value in result.items():
                    if not all(_same(a, b) for a, b in zip(value, base[name])):
                        moved[name].add(known.name)
        return moved, refused

    def _expand(self, config):
        """`config` by variable name: FMI 2.0 splits arrays into elements."""
        if self.fmi3:
            return {name: list(values) for name, values in config.items()}
        out = {}
        for name, values in config.items():
            if name in self.by_name:
                out[name] = list(values)
            else:
                for i, value in enumerate(values, start=1):
                    out[f"{name}[{i}]"] = [value]
        return out


def _perturbed(v, value):
    if v.type == "Boolean":
        return not value
    if v.type in ("Integer", "Int32"):
        candidates = [int(x) for x in (v.max, v.min) if x is not None]
        return next((c for c in candidates if c != value), value + 1)
    return value + STEP * (abs(value) or 1e-3)
