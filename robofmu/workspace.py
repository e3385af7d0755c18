"""The workspace check of a closed-loop plan, before any simulation: the plant FMU
initialised at a pose gives the actuator lengths l[1..3] by its inverse kinematics, and
the pose is reachable when every length lies in [strokeMin, strokeMax]. This is the one
implementation of the check (robofmu/sweep/reach.py uses it too); one instance is reset
between poses: ~30 us a pose.

The plan is sampled at every communication step (at most MAX_SAMPLES poses, evenly
spread, plus every waypoint) by running the planner FMU alone with the scenario's
parameters and plan switches."""

from __future__ import annotations

import math
from pathlib import Path

from typing import TYPE_CHECKING

from .errors import CosimError, ScenarioError
from .instances import give_back, open_instance
from .fmu_check import start_value, variables
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

    def __enter__(self) -> Workspace:
        return self

    def __exit__(self, *_exc) -> None:
        give_back(self.fmu)  # robofmu.instances: reset before its next use

    def problem(self, pose) -> str | None:
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
        for i, x in enumerate(lengths):
            if not low - STROKE_TOLERANCE <= x <= high + STROKE_TOLERANCE:
                return (f"actuator {i + 1} would need length {1000 * x:.4f} mm, outside its "
                        f"stroke [{1000 * low:.4f}, {1000 * high:.4f}] mm")
        return None


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
    poses = []
    fmu = open_instance("planner", s.fmus["planner"], s.start_time, s.stop_time)
    try:
        for name, value in s.parameters.get("planner", {}).items():
            fmu.set_value(name, value)
        fmu.enter_initialization()
        fmu.exit_initialization()
        for k in range(s.steps + 1):
            t = s.start_time + k * s.step_size
            if k in switches:
                fmu.reset(t, s.stop_time)
                for name, value in switches[k].parameters.items():
                    fmu.set_value(name, value)
                fmu.enter_initialization()
                fmu.exit_initialization()
            if k in keep:
                poses.append((t, fmu.get_values(names)))
            if k < s.steps:
                fmu.do_step(t, s.step_size)
    except BaseException:
        fmu.close()
        raise
    give_back(fmu)
    return poses


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
