"""Hand-written closed-loop scenarios (planner -> PID -> 3-PSS plant) in a person's
units, resolved at load time into the FMU parameters of a plain scenario.

Example (every quantity states its unit; see robofmu/units.py for the units)::

    name = "three_axis_quintic"
    stop_time = "2 s"
    step_size = "1 ms"

    [fmus]
    planner = "Planner"
    pid = "PID"
    plant = "Pss3Plant"

    [motion]
    profile = "quintic"                 # or "cubic"; the same for every segment
    [[motion.waypoints]]
    time = "0 s"
    angles = "-5, 3, 132 deg"           # Euler angles thx, thy, thz
    omega = "0.02, -0.03, 0.05 rad/s"   # base frame (optional, default 0)
    omega_dot = "0, 0, 0 rad/s^2"       # base frame (optional, default 0)
    [[motion.waypoints]]
    time = "2 s"
    angles = "4, -5, 145 deg"

    [start]                             # plant start (optional: first waypoint)
    angles = "3, -2, 136 deg"
    omega = "0, 0, 0 rad/s"

    [gains]                             # design rule ...
    omega = "30 rad/s"                  # triple pole at -omega on this scenario's plant
    # design_poses = ["0, 0, 138 deg"]  # optional, see below
    # design_plant = { legMass = "1 kg" }  # optional: the plant the design assumes
    #                                    # (default: the [plant] table below)
    # ... or explicit gains: Kp = "800, 600, 640 N m/rad", Ki = "... N m/(rad s)",
    # Kd = "... N m s/rad"

    [plant]                             # other plant parameters (FMU names, SI or units)
    platformMass = "2.5 kg"             # a heavier platform needs its inertia too:
    "platformInertia[1,1]" = "0.03 kg m^2"   # (the plant checks the triangle inequality)
    "platformInertia[2,2]" = "0.03 kg m^2"
    "platformInertia[3,3]" = "0.057 kg m^2"

    [limits]                            # optional, see robofmu/limits.py
    max_tracking_error = "0.5 deg"

The controller is the PID above or, with ``controller = "computed-torque"``, the
ComputedTorque FMU under the alias ``ct`` with gains by ``[gains] omega`` and its model
of the robot in ``[model]`` (default: the plant's; see robofmu/controllers.py).

Several waypoints make a multi-segment motion: one planner polynomial per segment,
each starting with the angles, rates (and, quintic, accelerations) the previous one
ends with, so velocity (and, quintic, acceleration) is continuous at every waypoint.
The master runs them as a sequence of plans: at each interior waypoint it resets the
planner FMU (a stateless function of time) and loads the next segment's parameters.

Default design poses: the plant start and, per segment, the poses at 0, 1/4, 1/2, 3/4
and 1 of the segment (linear in the angles). These rules exist only here: the Rust
reference (robofmu closed-loop reference) reads the expanded form that
``cosim check SCENARIO --expanded FILE.toml`` writes (robofmu.expand).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from .controllers import LOOPS, Loop, kind_of, model_parameters, pole_placement
from .design import (PlantRefused, check_bandwidth, design_gains, euler_accelerations,
                     euler_rates)
from .errors import CosimError, ScenarioError
from .fmu_check import check_value, describe, unit_of, variable_names
from .preflight import initialize_alone
from .schedule import PlanSwitch
from .units import UNITS, exponents, quantity, quantity_vector, unit_in
from .workspace import check_poses

RECORD = ([f"plant.force[{i}]" for i in (1, 2, 3)] + [f"plant.l[{i}]" for i in (1, 2, 3)]
          + [f"plant.omegaDot[{i}]" for i in (1, 2, 3)]
          + [f"planner.qddot[{i}]" for i in (1, 2, 3)])
PROFILES = {"cubic": 3, "quintic": 5}
KNOWN = {"name", "description", "start_time", "stop_time", "step_size", "fmus", "motion",
         "start", "gains", "plant", "record", "coupling", "max_step_halvings", "limits",
         "input_extrapolation", "controller", "model", "sample_period"}
# The scenario fields the FMUs' parameters come from, and the fields blamed for an
# unreachable pose (robofmu.workspace).
FIELDS = {"planner": "motion", "pid": "gains", "ct": "model", "plant": "plant"}
WHERE = {"plan": "motion.waypoints"}
MAX_WAYPOINTS = 1000


@dataclass(frozen=True)
class Waypoint:
    time: float
    angles: list[float]
    omega: list[float]  # base frame, rad/s
    rates: list[float]
    accelerations: list[float]


def is_closed_loop(data: dict) -> bool:
    return isinstance(data, dict) and "motion" in data


def _table(data: dict, key: str, where: str = "") -> dict:
    value = data.get(key, {})
    if not isinstance(value, dict):
        raise ScenarioError(f"field '{where}{key}' must be a table")
    return value


def _waypoint(raw, k: int) -> Waypoint:
    where = f"motion.waypoints[{k}]"
    if not isinstance(raw, dict):
        raise ScenarioError(f"field '{where}' must be a table")
    unknown = sorted(set(raw) - {"time", "angles", "omega", "omega_dot"})
    if unknown:
        raise ScenarioError(f"unknown field '{where}.{unknown[0]}'")
    for key in ("time", "angles"):
        if key not in raw:
            raise ScenarioError(f"missing field '{where}.{key}'")
    angles = quantity_vector(raw["angles"], "angle", f"{where}.angles", 3)
    omega = quantity_vector(raw.get("omega", "0, 0, 0 rad/s"), "angular velocity",
                            f"{where}.omega", 3)
    omega_dot = quantity_vector(raw.get("omega_dot", "0, 0, 0 rad/s^2"),
                                "angular acceleration", f"{where}.omega_dot", 3)
    try:
        rates = euler_rates(angles, omega)
        accelerations = euler_accelerations(angles, rates, omega_dot)
    except ScenarioError as e:
        raise ScenarioError(f"field '{where}.angles': {e}; keep thy away from +-90 deg") from None
    return Waypoint(quantity(raw["time"], "time", f"{where}.time"), angles, omega, rates,
                    accelerations)


def waypoints(motion: dict) -> tuple[int, list[Waypoint]]:
    profile = motion.get("profile")
    if profile not in PROFILES:
        raise ScenarioError(f"field 'motion.profile' must be one of {sorted(PROFILES)}, "
                            f"got {profile!r}")
    raw = motion.get("waypoints")
    if not isinstance(raw, list) or not 2 <= len(raw) <= MAX_WAYPOINTS:
        raise ScenarioError(f"field 'motion.waypoints' must list 2 to {MAX_WAYPOINTS} "
                            "waypoints ([[motion.waypoints]] tables)")
    points = [_waypoint(p, k) for k, p in enumerate(raw)]
    for k in range(1, len(points)):
        if points[k].time <= points[k - 1].time:
            raise ScenarioError(f"field 'motion.waypoints[{k}].time' must be after the "
                                "previous waypoint's")
    return PROFILES[profile], points


def segment_parameters(order: int, a: Waypoint, b: Waypoint) -> dict:
    p = {"order": order, "t0": a.time, "tf": b.time}
    for i in range(3):
        n = i + 1
        p |= {f"q0[{n}]": a.angles[i], f"qf[{n}]": b.angles[i],
              f"qdot0[{n}]": a.rates[i], f"qdotf[{n}]": b.rates[i]}
        if order == 5:
            p |= {f"qddot0[{n}]": a.accelerations[i], f"qddotf[{n}]": b.accelerations[i]}
    return p


def design_poses(start: list[float], points: list[Waypoint]) -> list[list[float]]:
    poses = [start]
    for a, b in zip(points, points[1:]):
        poses += [[x + (y - x) * s for x, y in zip(a.angles, b.angles)]
                  for s in (0.0, 0.25, 0.5, 0.75, 1.0)]
    return poses


def _design_plant(raw: dict, plant_fmu: Path, plant_values: dict) -> dict:
    """The plant parameters the design rule assumes: `gains.design_plant` (a table like
    `plant`; a sweep that draws plant parameters at random keeps the base scenario's
    there) or else the scenario's own `plant` values."""
    if "design_plant" not in raw:
        return plant_values
    table = _table(raw, "design_plant", "gains.")
    _refuse_start_parameters(table, "gains.design_plant")
    return {k: _plant_value(v, k, plant_fmu, "gains.design_plant")
            for k, v in table.items()}


def _gains(raw: dict, plant_fmu: Path, poses, plant_values: dict,
           preflight: bool) -> list[tuple[float, float, float]]:
    explicit = {"Kp": "stiffness gain", "Ki": "integral gain", "Kd": "damping gain"}
    if "omega" in raw:
        unknown = sorted(set(raw) - {"omega", "design_poses", "design_plant"})
        if unknown:
            raise ScenarioError(f"field 'gains.{unknown[0]}' cannot be combined with the "
                                "design rule 'gains.omega'")
        if "design_poses" in raw:
            listed = raw["design_poses"]
            if not isinstance(listed, list) or not 1 <= len(listed) <= MAX_WAYPOINTS:
                raise ScenarioError("field 'gains.design_poses' must be a list of 1 to "
                                    f"{MAX_WAYPOINTS} angles (\"thx, thy, thz deg\")")
            poses = [quantity_vector(p, "angle", f"gains.design_poses[{k}]", 3)
                     for k, p in enumerate(listed)]
        bandwidth = quantity(raw["omega"], "angular velocity", "gains.omega")
        check_bandwidth(bandwidth, poses)
        design_plant = _design_plant(raw, plant_fmu, plant_values)
        if not preflight:
            # A sweep's run: a plant the FMU refuses fails that run (with the plant's
            # reason), as it would in the run itself, not the whole SPEC.
            try:
                return design_gains(plant_fmu, poses, bandwidth, design_plant)
            except PlantRefused as e:
                raise CosimError(f"plant: {e.reason} (in the gain design)") from None
        if design_plant is not plant_values:
            initialize_alone(plant_fmu, "plant", design_plant, "gains.design_plant")
        check_poses(plant_fmu, design_plant, [(f"gains.design_poses[{k}]", None, p)
                                              for k, p in enumerate(poses)],
                    "design the gains at poses inside the workspace")
        return design_gains(plant_fmu, poses, bandwidth, design_plant)
    if set(raw) != set(explicit):
        raise ScenarioError("field 'gains' needs either 'omega' (design rule) or all of "
                            "'Kp', 'Ki', 'Kd'")
    columns = [quantity_vector(raw[k], dim, f"gains.{k}", 3) for k, dim in explicit.items()]
    return list(zip(*columns))


def _article(noun: str) -> str:
    return ("an " if noun[0] in "aeiou" else "a ") + noun


# A variable each role's FMU must have: a wrong FMU in a slot is named as such.
ROLE_VARIABLES = {"planner": "qf[1]", "plant": "theta0[1]"}


def _check_roles(fmus: dict, base_dir: Path, loop: Loop) -> None:
    roles = ROLE_VARIABLES | {loop.alias: loop.role_variable}
    for alias, f in fmus.items():
        if not isinstance(f, str):
            raise ScenarioError(f"field 'fmus.{alias}' must be a file name (a string)")
        md = describe(base_dir / f, f"fmus.{alias}")
        if md.fmiVersion != "2.0":
            raise ScenarioError(f"field 'fmus.{alias}': {f} is an FMI {md.fmiVersion} FMU "
                                "where the closed-loop form takes the FMI 2.0 file; name "
                                f"{md.modelName} and add --fmi3 to run the FMI 3.0 builds")
        if roles[alias] not in variable_names(md):
            raise ScenarioError(f"field 'fmus.{alias}': {Path(f).name} ({md.modelName}) is "
                                f"not a {alias} FMU (no variable {roles[alias]}); "
                                f"name the {alias} FMU of dist/")


def _plant_value(value, name: str, plant_fmu: Path, table: str = "plant",
                 alias: str = "plant"):
    """A parameter of the FMU `alias` set in the scenario's `table`: a number (SI, in
    the unit the FMU declares) or "value unit", whose unit must have the dimension of
    the unit the FMU declares for `name`."""
    field = f"{table}.{name}"
    md = describe(plant_fmu, f"fmus.{alias}")
    variable = {v.name: v for v in md.modelVariables}.get(name)
    if isinstance(value, str) and variable is not None:
        declared = unit_of(md, variable)
        unit = unit_in(value)
        if unit is None:
            raise ScenarioError(f"field '{field}': no known unit at the end of {value!r}; "
                                f"write \"value unit\" with one of: {', '.join(UNITS)}")
        dimension = UNITS[unit][1]
        if declared is None or declared[1] is None:
            raise ScenarioError(f"field '{field}': {alias}.{name} declares no unit; write a "
                                "plain number")
        if declared[1] != exponents(dimension) or declared[2] != 1.0 or declared[3] != 0.0:
            hint = [u for u, (f, d) in UNITS.items() if f == 1.0 and declared[1:] == (
                exponents(d), 1.0, 0.0)]
            form = f"\"VALUE {hint[0]}\" or " if hint else ""
            raise ScenarioError(f"field '{field}': {value!r} is {_article(dimension)}, but "
                                f"{name} is declared in {declared[0]}; write {form}a plain "
                                f"number in {declared[0]}")
        value = quantity(value, dimension, field)
    return check_value(md, alias, name, value, field)


def _refuse_start_parameters(plant: dict, table: str = "plant") -> None:
    """The plant's start parameters belong to `start`: set under `plant`, they would
    override the start that the workspace check and the gain design used."""
    for name in plant:
        if name.startswith(("theta0[", "omega0[")) or name == "initFromActuators":
            raise ScenarioError(f"field '{table}.{name}': the start state is the field 'start' "
                                "(start.angles, start.omega), which the gain design and "
                                "the workspace check use; set it there")


def _controller(data: dict, kind: str, fmu: Path, plant_fmu: Path, plant_values: dict,
                poses, preflight: bool) -> dict:
    """The controller FMU's parameters: PID gains designed on the plant, or the
    computed-torque gains and model (robofmu.controllers)."""
    if kind == "computed-torque":
        gains = pole_placement(_table(data, "gains"), quantity)
        model = model_parameters(describe(fmu, "fmus.ct"), plant_values,
                                 _table(data, "model"),
                                 lambda v, name: _plant_value(v, name, fmu, "model", "ct"))
        return gains | model
    pid_gains = _gains(_table(data, "gains"), plant_fmu, poses, plant_values, preflight)
    pid: dict[str, float | bool] = {}
    for i, (kp, ki, kd) in enumerate(pid_gains):
        n = i + 1
        pid |= {f"Kp[{n}]": kp, f"Ki[{n}]": ki, f"Kd[{n}]": kd, f"Tf[{n}]": 0.0,
                f"useRateInputs[{n}]": True}
    return pid


def _clocked_build(base_dir: Path, entry: str) -> str:
    """The FMI 3.0 build beside the controller's FMI 2.0 file (dist/fmi3/<Model>.fmu):
    the file whose clocked law sample_period ticks."""
    build = (base_dir / entry).parent / "fmi3" / Path(entry).name
    if not build.is_file():
        raise ScenarioError(f"field 'sample_period': the sampled law runs in the FMI 3.0 "
                            f"build of the controller, {build}, which does not exist; build "
                            "it (bash scripts/build-fmus.sh) or remove sample_period")
    md = describe(build, "sample_period")
    if not getattr(md, "clocked", None) or "samplePeriod" not in variable_names(md):
        raise ScenarioError(f"field 'sample_period': the controller's FMI 3.0 build {build} "
                            f"({md.modelName}) has no sampled law (no clock and samplePeriod "
                            "parameter); remove sample_period or choose a controller that "
                            "has one (controller = \"computed-torque\")")
    return str(build)


def resolve(data: dict, base_dir: Path,
            preflight: bool = True) -> tuple[dict, list[PlanSwitch]]:
    """The plain scenario (as parse_scenario reads it) and the plan switches. With
    `preflight`, the plant's parameters, the start, the waypoints and the design poses
    are checked with the plant FMU before the gain design."""
    unknown = sorted(set(data) - KNOWN)
    if unknown:
        raise ScenarioError(f"unknown field '{unknown[0]}'")
    kind = kind_of(data)
    loop = LOOPS[kind]
    fmus = _table(data, "fmus")
    if set(fmus) != {"planner", loop.alias, "plant"}:
        raise ScenarioError(f"field 'fmus' must name exactly 'planner', '{loop.alias}' and "
                            f"'plant' (controller = \"{kind}\")")
    if "model" in data and kind != "computed-torque":
        raise ScenarioError("field 'model' (the controller's model of the robot) needs "
                            "controller = \"computed-torque\"; remove it for the PID")
    order, points = waypoints(_table(data, "motion"))
    stop_time = quantity(data.get("stop_time"), "time", "stop_time")
    start = quantity(data["start_time"], "time", "start_time") if "start_time" in data else 0.0
    if start < stop_time < points[-1].time:  # else parse_scenario names stop_time
        k = len(points) - 1
        raise ScenarioError(
            f"field 'motion.waypoints[{k}].time': the motion ends at {points[-1].time:g} s, "
            f"after stop_time = {stop_time:g} s (the run would stop before the platform gets "
            f"there); set stop_time to at least {points[-1].time:g} s or end the motion "
            "earlier")
    start_raw = _table(data, "start")
    unknown = sorted(set(start_raw) - {"angles", "omega"})
    if unknown:
        raise ScenarioError(f"unknown field 'start.{unknown[0]}'")
    theta0 = (quantity_vector(start_raw["angles"], "angle", "start.angles", 3)
              if "angles" in start_raw else points[0].angles)
    omega0 = (quantity_vector(start_raw["omega"], "angular velocity", "start.omega", 3)
              if "omega" in start_raw else points[0].omega)
    _check_roles(fmus, base_dir, loop)
    plant_fmu = base_dir / str(fmus["plant"])
    _refuse_start_parameters(_table(data, "plant"))
    plant_values = {k: _plant_value(v, k, plant_fmu) for k, v in _table(data, "plant").items()}
    if preflight:
        initialize_alone(plant_fmu, "plant", plant_values, "plant")
        start_field = "start.angles" if "angles" in start_raw else "motion.waypoints[0].angles"
        check_poses(plant_fmu, plant_values, [(start_field, None, theta0)] + [
            (f"motion.waypoints[{k}].angles", p.time, p.angles) for k, p in enumerate(points)],
                    "move the waypoints (or the start) inside the workspace")
    controller = _controller(data, kind, base_dir / str(fmus[loop.alias]), plant_fmu,
                             plant_values, design_poses(theta0, points), preflight)
    output, sampled = "u", {}
    if "sample_period" in data:  # the controller's clocked law, in its FMI 3.0 build
        period = quantity(data["sample_period"], "time", "sample_period")
        fmus = dict(fmus, **{loop.alias: _clocked_build(base_dir, fmus[loop.alias])})
        controller["samplePeriod"] = period
        output, sampled = "uSampled", {loop.alias: period}
    plant = {f"theta0[{i + 1}]": theta0[i] for i in range(3)}
    plant |= {f"omega0[{i + 1}]": omega0[i] for i in range(3)}
    plant |= plant_values
    start_time = (quantity(data["start_time"], "time", "start_time")
                  if "start_time" in data else 0.0)
    step = quantity(data["step_size"], "time", "step_size") if "step_size" in data else 1e-3
    plain = {"start_time": start_time,
             "stop_time": stop_time,
             "step_size": step, "order": ["planner", loop.alias, "plant"],
             "fmus": dict(fmus),
             "parameters": {"planner": segment_parameters(order, points[0], points[1]),
                            loop.alias: controller, "plant": plant},
             "connections": [{"from": f"{a}.{output if (a, x) == (loop.alias, 'u') else x}[{i}]",
                              "to": f"{b}.{y}[{i}]"}
                             for a, x, b, y in loop.connections for i in (1, 2, 3)],
             "record": data.get("record", RECORD)}
    if sampled:
        plain["sample_period"] = sampled
    for key in ("name", "coupling", "input_extrapolation", "max_step_halvings",
                "description", "limits", "controller"):
        if key in data:
            plain[key] = data[key]
    switches = []
    for a, b in zip(points[1:], points[2:]):
        steps = (a.time - start_time) / step
        if abs(steps - round(steps)) > 1e-9 * max(1.0, steps):
            raise ScenarioError(f"waypoint time {a.time} s is not a communication point")
        switches.append(PlanSwitch(round(steps), "planner", segment_parameters(order, a, b)))
    return plain, switches
