"""The workspace check of a closed-loop plan, before any simulation: the plant FMU
initialised at a pose gives the actuator lengths l[1..3] by its inverse kinematics, and
the pose is reachable when every length lies in [strokeMin, strokeMax]. This is the one
implementation of the check (robofmu/sweep/reach.py uses it too); one instance is reset
between poses: ~30 us a pose.

The plan is sampled at every communication step (at most MAX_SAMPLES poses, evenly
spread, plus every waypoint) by running the planner FMU alone with the scenario's
parameters and plan switches, its steps made by the native stepping loop
(robofmu.loop) as in a run.

Both are the bulk of reading a closed-loop scenario (1001 poses and 1000 planner steps
for the regulation), so their calls go to the FMU's own C functions on arrays prepared
once (FMPy's per-call wrappers cost most of a pose); a pose where any call fails is made
again through robofmu.fmi2, whose error carries the FMU's reason for the message."""

from __future__ import annotations

import math
from collections.abc import Callable
from ctypes import c_double, c_int, c_uint
from pathlib import Path
from types import SimpleNamespace
from typing import TYPE_CHECKING, Any

import numpy as np

from .errors import CosimError, ScenarioError
from .fmi2 import FmuInstance
from .instances import give_back, open_instance
from .fmu_check import start_value, variables
from .loop import Loop
from .preflight import _reason

if TYPE_CHECKING:
    from .scenario import Scenario

MAX_SAMPLES = 20000
# Lengths within this of a stroke end count as inside: a path that runs exactly to the
# end of the stroke (path1) computes its length to round-off.
STROKE_TOLERANCE = 1e-9  # m
ANGLES = tuple(f"theta0[{i}]" for i in (1, 2, 3))
LENGTHS = tuple(f"l[{i}]" for i in (1, 2, 3))


def deg(pose) -> str:
    return "(" + ", ".join(f"{math.degrees(x):.4g}" for x in pose) + ") deg"


class Workspace:
    """One plant instance with the scenario's plant parameters; `problem(pose)` is None
    for a reachable pose, else the reason (the actuator leaving its stroke, or the
    plant's own refusal)."""

    def __init__(self, plant_fmu: Path, parameters: dict):
        self.parameters = {k: v for k, v in parameters.items()
                           if not k.startswith(("theta0[", "omega0["))}
        self.fmu = open_instance("plant", Path(plant_fmu), 0.0, 1.0)
        self.fresh = True
        self._direct: _DirectPose | None
        try:
            self._direct = _DirectPose(self.fmu, self.parameters)
        except _NotDirect:
            self._direct = None
        except BaseException:
            self.fmu.close()
            raise

    def __enter__(self) -> Workspace:
        return self

    def __exit__(self, *_exc) -> None:
        give_back(self.fmu)  # robofmu.instances: reset before its next use

    def problem(self, pose) -> str | None:
        found = None if self._direct is None else self._direct.lengths(pose, self.fresh)
        self.fresh = False
        if found is not None:
            return _outside(found[:3], found[3], found[4])
        return self._problem_through_fmpy(pose)

    def _problem_through_fmpy(self, pose) -> str | None:
        fmu = self.fmu
        try:
            if not self.fresh:
                fmu.reset(0.0, 1.0)
            self.fresh = False
            for name, value in self.parameters.items():
                fmu.set_value(name, value)
            fmu.set_values(ANGLES, list(pose))
            fmu.enter_initialization()
            fmu.exit_initialization()
            lengths = fmu.get_values(LENGTHS)
            low, high = fmu.get_values(("strokeMin", "strokeMax"))
        except CosimError as e:
            return f"the plant refuses it: {_reason(e)}"
        return _outside(lengths, low, high)


def _outside(lengths, low: float, high: float) -> str | None:
    for i, x in enumerate(lengths):
        if not low - STROKE_TOLERANCE <= x <= high + STROKE_TOLERANCE:
            return (f"actuator {i + 1} would need length {1000 * x:.4f} mm, outside its "
                    f"stroke [{1000 * low:.4f}, {1000 * high:.4f}] mm")
    return None


class _NotDirect(Exception):
    """The instance is not an FMI 2.0 one with Real angles and lengths."""


_C_TYPES: dict[str, tuple[Any, Callable[[Any], Any]]] = {
    "Real": (c_double, float), "Integer": (c_int, int), "Boolean": (c_int, bool)}
_WARNING = 1  # fmi2Warning: the worst status that is not a failure (as FMPy counts)


class _DirectPose:
    """Workspace.problem's FMI calls on the FMU's own C functions: fmi2Reset and
    fmi2SetupExperiment (t = 0..1, as robofmu.instances sets up the experiment), the
    parameters (one call per type), the angles, fmi2Enter/ExitInitializationMode and one
    fmi2GetReal of the lengths and the stroke ends."""

    def __init__(self, fmu, parameters: dict):
        if type(fmu) is not FmuInstance:
            raise _NotDirect
        names = tuple(parameters)
        try:
            angles = fmu._groups(ANGLES)
            read = fmu._groups((*LENGTHS, "strokeMin", "strokeMax"))
            groups = fmu._groups(names)
        except CosimError:
            raise _NotDirect from None  # the FMPy path names what is missing
        if [kind for kind, _, _ in angles + read] != ["Real", "Real"]:
            raise _NotDirect
        self.fmu, slave = fmu, fmu._fmu
        dll, self.component = slave.dll, slave.component
        self.reset, self.setup = dll.fmi2Reset, dll.fmi2SetupExperiment
        self.enter = dll.fmi2EnterInitializationMode
        self.exit = dll.fmi2ExitInitializationMode
        self.set_real, self.get_real = dll.fmi2SetReal, dll.fmi2GetReal
        self.parameters = []
        for kind, positions, refs in groups:
            ctype, convert = _C_TYPES[kind]
            self.parameters.append((getattr(dll, f"fmi2Set{kind}"), (c_uint * len(refs))(*refs),
                                    len(refs), (ctype * len(refs))(
                                        *(convert(parameters[names[k]]) for k in positions))))
        self.angle_refs = (c_uint * 3)(*angles[0][2])
        self.angles = (c_double * 3)()
        self.read_refs = (c_uint * 5)(*read[0][2])
        self.read = (c_double * 5)()

    def lengths(self, pose, fresh: bool) -> list[float] | None:
        """[l1, l2, l3, strokeMin, strokeMax] at `pose`; None when a call fails."""
        c = self.component
        if not fresh and (self.reset(c) > _WARNING
                          or self.setup(c, 0, 0.0, 0.0, 1, 1.0) > _WARNING):
            return None
        self.fmu._initialized = False
        for setter, refs, n, values in self.parameters:
            if setter(c, refs, n, values) > _WARNING:
                return None
        self.angles[:] = [float(x) for x in pose]
        if (self.set_real(c, self.angle_refs, 3, self.angles) > _WARNING
                or self.enter(c) > _WARNING or self.exit(c) > _WARNING):
            return None
        self.fmu._initialized = True
        if self.get_real(c, self.read_refs, 5, self.read) > _WARNING:
            return None
        return self.read[:]


def is_closed_loop_plant(scenario: Scenario) -> bool:
    if "plant" not in scenario.fmus or "planner" not in scenario.fmus:
        return False
    plant = variables(scenario.fmus["plant"])
    planner = variables(scenario.fmus["planner"])
    return all(n in plant for n in (*ANGLES, *LENGTHS, "strokeMin", "strokeMax")) and all(
        f"q[{i}]" in planner for i in (1, 2, 3))


def planned_poses(scenario: Scenario) -> list[tuple[float, list[float]]]:
    """(time, planned angles) at the communication points (strided to MAX_SAMPLES)."""
    s = scenario
    stride = max(1, math.ceil(s.steps / MAX_SAMPLES))
    switches = {w.step: w for w in s.schedule}
    keep = set(range(0, s.steps + 1, stride)) | {s.steps} | set(switches)
    names = tuple(f"q[{i}]" for i in (1, 2, 3))
    rows = np.empty((s.steps + 1, len(names)))
    fmu = open_instance("planner", s.fmus["planner"], s.start_time, s.stop_time)
    try:
        for name, value in s.parameters.get("planner", {}).items():
            fmu.set_value(name, value)
        fmu.enter_initialization()
        fmu.exit_initialization()
        timing = SimpleNamespace(start_time=s.start_time, step_size=s.step_size,
                                 coupling="sampled", max_step_halvings=0)
        loop = Loop({"planner": fmu}, {"planner": []}, {"planner": names}, ["planner"], {},
                    timing)
        loop.record(rows[0], s.start_time)
        k = 0
        while True:
            if k in switches:
                t = s.start_time + k * s.step_size
                fmu.reset(t, s.stop_time)
                for name, value in switches[k].parameters.items():
                    fmu.set_value(name, value)
                fmu.enter_initialization()
                fmu.exit_initialization()
                loop.record(rows[k], t)
            if k == s.steps:
                break
            stop = min([b for b in switches if b > k] + [s.steps])
            loop.run_steps(k, stop, rows, False)  # row j + 1 after step j
            k = stop
    except BaseException:
        fmu.close()
        raise
    give_back(fmu)
    return [(s.start_time + k * s.step_size, rows[k].tolist()) for k in sorted(keep)
            if k <= s.steps]


def check_poses(plant_fmu: Path, parameters: dict, poses, fields) -> None:
    """Raises ScenarioError at the first unreachable pose. `poses`: (label, time or None,
    angles) with label the scenario field to blame."""
    with Workspace(plant_fmu, parameters) as ws:
        for field, t, pose in poses:
            reason = ws.problem(pose)
            if reason is not None:
                when = "" if t is None else f"at t = {t:.6g} s "
                raise ScenarioError(f"field '{field}': {when}the pose {deg(pose)} is outside "
                                    f"the workspace: {reason}; {fields}")


def check_plan(scenario: Scenario, where: dict) -> int:
    """The start pose and the whole planned path against the workspace; returns the
    number of poses checked. `where`: field names for the messages ("start", "plan")."""
    plant = scenario.parameters.get("plant", {})
    start = [plant.get(n, start_value(scenario.fmus["plant"], n)) for n in ANGLES]
    poses = [(where["start"], scenario.start_time, start)]
    poses += [(where["plan"], t, q) for t, q in planned_poses(scenario)]
    check_poses(scenario.fmus["plant"], plant, poses,
                "move the waypoints (or the start) inside the workspace or shorten the motion")
    return len(poses)
