"""The corpus of hostile inputs of tests/python/test_hostile_cli.py: malformed scenario
files and arguments for `cosim run/check/ssp/container/bench`, each with the exit code
and the text its one-line message must hold (the field, or the argument)."""

from __future__ import annotations

import copy
import json
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DIST = ROOT / "dist"


def base() -> dict:
    """A valid closed-loop scenario of 50 steps (the file is written as JSON)."""
    return {"name": "h", "stop_time": "0.05 s", "step_size": "1 ms",
            "fmus": {"planner": str(DIST / "Planner.fmu"), "pid": str(DIST / "PID.fmu"),
                     "plant": str(DIST / "Pss3Plant.fmu")},
            "motion": {"profile": "quintic", "waypoints": [
                {"time": "0 s", "angles": "0, 0, 138 deg"},
                {"time": "0.05 s", "angles": "0.5, -0.5, 138.5 deg"}]},
            "gains": {"omega": "30 rad/s"}}


def plain() -> dict:
    """A valid plain scenario: the planner's ramp regulated by the PID on the plant."""
    q0 = [0.0, 0.0, 2.4085543677521746]
    conn = [("planner", "q", "pid", "setpoint"), ("planner", "qdot", "pid", "setpointRate"),
            ("plant", "theta", "pid", "measurement"),
            ("plant", "thetaDot", "pid", "measuredRate"),
            ("plant", "gravityCompensation", "pid", "feedforward"),
            ("pid", "u", "plant", "generalizedForceCommand")]
    return {"name": "p", "stop_time": 0.02, "step_size": 0.001,
            "order": ["planner", "pid", "plant"],
            "fmus": {"planner": str(DIST / "Planner.fmu"), "pid": str(DIST / "PID.fmu"),
                     "plant": str(DIST / "Pss3Plant.fmu")},
            "parameters": {"planner": {"order": 5, "t0": 0.0, "tf": 0.02,
                                       **{f"q0[{i + 1}]": q0[i] for i in range(3)},
                                       **{f"qf[{i + 1}]": q0[i] for i in range(3)}},
                           "pid": {f"{k}[{i}]": v for i in (1, 2, 3)
                                   for k, v in (("Kp", 50.0), ("Ki", 10.0), ("Kd", 5.0),
                                                ("Tf", 0.0), ("useRateInputs", True))},
                           "plant": {f"theta0[{i + 1}]": q0[i] for i in range(3)}},
            "connections": [{"from": f"{a}.{x}[{i}]", "to": f"{b}.{y}[{i}]"}
                            for a, x, b, y in conn for i in (1, 2, 3)]}


def edit(doc: dict, path: str, value) -> dict:
    """A copy of `doc` with the dotted `path` (list indices as numbers) set to `value`,
    or removed when `value` is DELETE."""
    doc = copy.deepcopy(doc)
    keys = [int(k) if k.isdigit() else k for k in path.split("/")]
    target = doc
    for k in keys[:-1]:
        target = target[k]
    if value is DELETE:
        del target[keys[-1]]
    else:
        target[keys[-1]] = value
    return doc


DELETE = object()
B = base
WP = "motion/waypoints"

# An absolute path on this machine (the temp directory's), never written into the source.
ABSOLUTE_NAME = str(Path(tempfile.gettempdir()).resolve() / "cosim-hostile-abs")

# (id, document or raw bytes, exit code, text the message holds)
DOCUMENTS = [
    ("top-level list", [1, 2], 2, "top level"),
    ("unknown field", edit(B(), "colour", "red"), 2, "'colour'"),
    ("name with ../", edit(B(), "name", "../escape"), 2, "'name'"),
    ("name absolute", edit(B(), "name", ABSOLUTE_NAME), 2, "'name'"),
    ("name empty", edit(B(), "name", ""), 2, "'name'"),
    ("name a number", edit(B(), "name", 5), 2, "'name'"),
    ("name with NUL", edit(B(), "name", "a\u0000b"), 2, "'name'"),
    ("name a dot", edit(B(), "name", ".."), 2, "'name'"),
    ("fmus missing", edit(B(), "fmus", DELETE), 2, "'fmus'"),
    ("fmus a list", edit(B(), "fmus", ["a.fmu"]), 2, "'fmus'"),
    ("fmu missing file", edit(B(), "fmus/plant", "nowhere/Nothing.fmu"), 2, "'fmus.plant'"),
    ("fmu is a directory", edit(B(), "fmus/plant", str(DIST)), 2, "'fmus.plant'"),
    ("fmu not a zip", edit(B(), "fmus/plant", str(ROOT / "README.md")), 2, "'fmus.plant'"),
    ("fmu FMI 3.0 in 2.0 slot", edit(B(), "fmus/plant", str(DIST / "fmi3" / "Pss3Plant.fmu")),
     2, "'fmus.plant'"),
    ("fmu the wrong model", edit(B(), "fmus/plant", str(DIST / "PID.fmu")), 2, "plant"),
    ("fmu a number", edit(B(), "fmus/plant", 5), 2, "'fmus.plant'"),
    ("fmu extra alias", edit(B(), "fmus/extra", str(DIST / "PID.fmu")), 2, "'fmus'"),
    ("stop_time missing", edit(B(), "stop_time", DELETE), 2, "'stop_time'"),
    ("stop_time in deg", edit(B(), "stop_time", "2 deg"), 2, "'stop_time'"),
    ("stop_time negative", edit(B(), "stop_time", "-1 s"), 2, "'stop_time'"),
    ("stop_time bare number", edit(B(), "stop_time", 2), 2, "'stop_time'"),
    ("stop_time a list", edit(B(), "stop_time", ["1 s"]), 2, "'stop_time'"),
    ("1e12 steps", edit(edit(B(), "stop_time", "1e9 s"), f"{WP}/1/time", "1e9 s"), 2,
     "'step_size'"),
    ("stop_time 1e308 s", edit(edit(B(), "stop_time", "1e308 s"), f"{WP}/1/time", "1e308 s"), 2,
     "'step_size'"),
    ("name of 101 characters", edit(B(), "name", "n" * 101), 2, "'name'"),
    ("step_size subnormal", edit(B(), "step_size", "1e-320 s"), 2, "'step_size'"),
    ("step_size zero", edit(B(), "step_size", "0 s"), 2, "'step_size'"),
    ("step_size 1e-300", edit(B(), "step_size", "1e-300 s"), 2, "'step_size'"),
    ("step_size nan", edit(B(), "step_size", "nan s"), 2, "'step_size'"),
    ("step_size inf", edit(B(), "step_size", "inf s"), 2, "'step_size'"),
    ("step_size not dividing", edit(B(), "step_size", "3 ms"), 2, "'step_size'"),
    ("profile missing", edit(B(), "motion/profile", DELETE), 2, "'motion.profile'"),
    ("profile unknown", edit(B(), "motion/profile", "septic"), 2, "'motion.profile'"),
    ("motion a string", edit(B(), "motion", "fast"), 2, "'motion'"),
    ("one waypoint", edit(B(), WP, [B()["motion"]["waypoints"][0]]), 2, "'motion.waypoints'"),
    ("waypoints a string", edit(B(), WP, "0, 0, 138 deg"), 2, "'motion.waypoints'"),
    ("waypoints of numbers", edit(B(), WP, [1, 2]), 2, "'motion.waypoints[0]'"),
    ("waypoint without angles", edit(B(), f"{WP}/1/angles", DELETE), 2,
     "'motion.waypoints[1].angles'"),
    ("waypoint unknown key", edit(B(), f"{WP}/1/speed", "1 m/s"), 2, "'motion.waypoints[1]"),
    ("angles two values", edit(B(), f"{WP}/1/angles", "1, 2 deg"), 2,
     "'motion.waypoints[1].angles'"),
    ("angles not numbers", edit(B(), f"{WP}/1/angles", "a, b, c deg"), 2,
     "'motion.waypoints[1].angles'"),
    ("angles unknown unit", edit(B(), f"{WP}/1/angles", "1, 2, 3 furlong"), 2,
     "'motion.waypoints[1].angles'"),
    ("angles without unit", edit(B(), f"{WP}/1/angles", "1, 2, 3"), 2,
     "'motion.waypoints[1].angles'"),
    ("angles in metres", edit(B(), f"{WP}/1/angles", "1, 2, 3 m"), 2,
     "'motion.waypoints[1].angles'"),
    ("angles a list", edit(B(), f"{WP}/1/angles", [0, 0, 138]), 2,
     "'motion.waypoints[1].angles'"),
    ("angles a list of strings", edit(B(), f"{WP}/1/angles", ["0 deg", "0 deg", "138 deg"]), 2,
     "'motion.waypoints[1].angles'"),
    ("angles nan", edit(B(), f"{WP}/1/angles", "nan, 0, 138 deg"), 2,
     "'motion.waypoints[1].angles'"),
    ("angles huge", edit(B(), f"{WP}/1/angles", "1e308, 0, 138 deg"), 2,
     "'motion.waypoints[1].angles'"),
    ("omega with wrong unit", edit(B(), f"{WP}/1/omega", "0, 0, 1 rad"), 2,
     "'motion.waypoints[1].omega'"),
    ("waypoint times reversed", edit(B(), f"{WP}/1/time", "0 s"), 2,
     "'motion.waypoints[1].time'"),
    ("waypoint time in deg", edit(B(), f"{WP}/1/time", "1 deg"), 2,
     "'motion.waypoints[1].time'"),
    ("unreachable waypoint (10 deg about x)", edit(B(), f"{WP}/1/angles", "10, 0, 138 deg"), 2,
     "'motion.waypoints[1].angles'"),
    ("unreachable waypoint (30 deg about y)", edit(B(), f"{WP}/1/angles", "0, 30, 138 deg"), 2,
     "'motion.waypoints[1].angles'"),
    ("singular waypoint (thy = 90 deg)", edit(B(), f"{WP}/1/angles", "0, 90, 138 deg"), 2,
     "motion.waypoints[1]"),
    ("unreachable start", edit(B(), "start", {"angles": "0, -25, 138 deg"}), 2,
     "'start.angles'"),
    ("start unknown key", edit(B(), "start", {"pose": "0, 0, 138 deg"}), 2, "'start.pose'"),
    ("start a number", edit(B(), "start", 3), 2, "'start'"),
    ("gains missing", edit(B(), "gains", DELETE), 2, "'gains'"),
    ("gains omega negative", edit(B(), "gains/omega", "-30 rad/s"), 2, "'gains.omega'"),
    ("gains omega zero", edit(B(), "gains/omega", "0 rad/s"), 2, "'gains.omega'"),
    ("gains omega and Kp", edit(B(), "gains/Kp", "1, 1, 1 N m/rad"), 2, "'gains.Kp'"),
    ("gains Kp alone", edit(B(), "gains", {"Kp": "1, 1, 1 N m/rad"}), 2, "'gains'"),
    ("gains Kp in N", edit(B(), "gains", {"Kp": "1, 1, 1 N", "Ki": "0, 0, 0 N m/(rad s)",
                                          "Kd": "0, 0, 0 N m s/rad"}), 2, "'gains.Kp'"),
    ("design pose unreachable", edit(B(), "gains/design_poses", ["20, 0, 138 deg"]), 2,
     "'gains.design_poses[0]'"),
    ("design poses a string", edit(B(), "gains/design_poses", "0, 0, 138 deg"), 2,
     "'gains.design_poses'"),
    ("design poses empty", edit(B(), "gains/design_poses", []), 2, "'gains.design_poses'"),
    ("plant mass in deg", edit(B(), "plant", {"platformMass": "1 deg"}), 2,
     "'plant.platformMass'"),
    ("plant g in mm", edit(B(), "plant", {"g": "9810 mm"}), 2, "'plant.g'"),
    ("plant friction in deg", edit(B(), "plant", {"sliderFriction": "3 deg"}), 2,
     "'plant.sliderFriction'"),
    ("plant mass 2.5 kg alone (triangle inequality)", edit(B(), "plant",
                                                          {"platformMass": "2.5 kg"}), 2,
     "triangle inequality"),
    ("plant mass negative", edit(B(), "plant", {"platformMass": "-1 kg"}), 2, "'plant"),
    ("plant mass a boolean", edit(B(), "plant", {"platformMass": True}), 2,
     "'plant.platformMass'"),
    ("plant length overflow", edit(B(), "plant", {"lp": "1e400 m"}), 2, "'plant.lp'"),
    ("plant enum out of range", edit(B(), "plant", {"endStopMode": 3}), 2,
     "'plant.endStopMode'"),
    ("plant integer 1.5", edit(B(), "plant", {"endStopMode": 1.5}), 2, "'plant.endStopMode'"),
    ("plant integer wraps in C", edit(B(), "plant", {"endStopMode": 4294967297}), 2,
     "'plant.endStopMode'"),
    ("plant unknown variable", edit(B(), "plant", {"nosuch": 1.0}), 2, "'plant.nosuch'"),
    ("plant start angle beside start", edit(B(), "plant", {"theta0[1]": 0.1}), 2,
     "'plant.theta0[1]': the start state is the field 'start'"),
    ("plant start rate beside start", edit(B(), "plant", {"omega0[3]": "1 rad/s"}), 2,
     "'plant.omega0[3]'"),
    ("plant start from actuators", edit(B(), "plant", {"initFromActuators": True}), 2,
     "'plant.initFromActuators'"),
    ("plant output set", edit(B(), "plant", {"theta[1]": 0.0}), 2, "'plant.theta[1]'"),
    ("plant unit on unitless", edit(B(), "plant", {"legComFraction": "0.5 m"}), 2,
     "'plant.legComFraction'"),
    ("plant a list", edit(B(), "plant", [1, 2]), 2, "'plant'"),
    ("plant value a table", edit(B(), "plant", {"g": {"value": 9.81}}), 2, "'plant.g'"),
    ("record a string", edit(B(), "record", "plant.theta[1]"), 2, "'record'"),
    ("record of numbers", edit(B(), "record", [1, 2]), 2, "'record[0]'"),
    ("record unknown variable", edit(B(), "record", ["plant.nosuch"]), 2, "'record[0]'"),
    ("record unknown FMU", edit(B(), "record", ["nosuch.x"]), 2, "'record[0]'"),
    ("record 2000 signals", edit(B(), "record", ["plant.l[1]"] * 2000), 2, "'record'"),
    ("coupling unknown", edit(B(), "coupling", "jacobi"), 2, "'coupling'"),
    ("halvings 100", edit(B(), "max_step_halvings", 100), 2, "'max_step_halvings'"),
    ("halvings 1.5", edit(B(), "max_step_halvings", 1.5), 2, "'max_step_halvings'"),
    ("limit in deg for force", edit(B(), "limits", {"max_force": "50 deg"}), 2,
     "'limits.max_force'"),
    ("limit unknown", edit(B(), "limits", {"max_speed": "1 m/s"}), 2, "'limits.max_speed'"),
    ("limit negative", edit(B(), "limits", {"max_force": "-1 N"}), 2, "'limits.max_force'"),
    ("limits a list", edit(B(), "limits", ["1 N"]), 2, "'limits'"),
    ("limits without the closed-loop signals", edit(edit(B(), "record", []), "limits",
                                                    {"max_force": "1 N"}), 2, "'limits'"),
    ("plain: plan switch integer 3.7", edit(plain(), "plan_switches", [
        {"step": 10, "alias": "planner", "parameters": {"order": 3.7}}]), 2,
     "'plan_switches[0].parameters.order'"),
    ("plain: plan switch after the end", edit(plain(), "plan_switches", [
        {"step": 10 ** 9, "alias": "planner", "parameters": {}}]), 2,
     "'plan_switches[0].step'"),
    ("plain: plan switch of a string", edit(plain(), "plan_switches", ["x"]), 2,
     "'plan_switches[0]'"),
    ("plain: order mismatch", edit(plain(), "order", ["planner", "pid"]), 2, "'order'"),
    ("plain: order of numbers", edit(plain(), "order", [1, 2, 3]), 2, "'order'"),
    ("plain: integer wraps in C", edit(plain(), "parameters/planner/order", 4294967301), 2,
     "'parameters.planner.order'"),
    ("plain: integer 3.7", edit(plain(), "parameters/planner/order", 3.7), 2,
     "'parameters.planner.order'"),
    ("plain: integer below min", edit(plain(), "parameters/planner/order", 1), 2,
     "'parameters.planner.order'"),
    ("plain: boolean as 1", edit(plain(), "parameters/plant/initFromActuators", 1), 2,
     "'parameters.plant.initFromActuators'"),
    # An alias is a file name in the container's and the SSP's exports: "../x" wrote
    # x.fmu outside the container's work folder (outside --out).
    ("plain: alias a path", edit(plain(), "fmus", {"../../x": str(DIST / "PID.fmu")}), 2,
     "alias '../../x'"),
    ("plain: alias with a dot", edit(plain(), "fmus", {"a.b": str(DIST / "PID.fmu")}), 2,
     "alias 'a.b'"),
    ("plain: description a number", edit(plain(), "description", 3), 2, "'description'"),
    ("description a table", edit(B(), "description", {"a": 1}), 2, "'description'"),
    ("plain: parameter a string", edit(plain(), "parameters/pid/Kp[1]", "50"), 2,
     "'parameters.pid.Kp[1]'"),
    ("plain: parameter nan", edit(plain(), "parameters/pid/Kp[1]", float("nan")), 2,
     "'parameters.pid.Kp[1]'"),
    ("plain: connection to an output", edit(plain(), "connections/0/to", "plant.theta[1]"), 2,
     "'connections[0]"),
    ("plain: connection from nothing", edit(plain(), "connections/0/from", "planner.zzz"), 2,
     "'connections[0].from'"),
    ("plain: connections of strings", edit(plain(), "connections", ["a -> b"]), 2,
     "'connections[0]'"),
    ("plain: connected twice", edit(plain(), "connections/1/to", "pid.setpoint[1]"), 2,
     "'connections[1].to'"),
    ("plain: unreachable start", edit(plain(), "parameters/plant/theta0[2]", 0.5), 2,
     "'parameters.plant'"),
    ("plain: unreachable plan", edit(plain(), "parameters/planner/qf[1]", 0.3), 2,
     "'parameters.planner'"),
]

RAW = [
    ("empty file", b"", ".toml", 2, "'name'"),
    ("not UTF-8", b"name = \"\xff\xfe\"\n", ".toml", 2, "UTF-8"),
    ("binary garbage", bytes(range(256)) * 4, ".toml", 2, "h.toml"),
    ("TOML syntax", b"name = \n", ".toml", 2, "TOML"),
    ("TOML nested 100000 deep", b"a = " + b"[" * 100000 + b"]" * 100000 + b"\n", ".toml", 2,
     "h.toml"),
    ("JSON nested 100000 deep", b"[" * 100000 + b"]" * 100000, ".json", 2, "h.json"),
    ("JSON syntax", b"{\"name\": }", ".json", 2, "JSON"),
    ("JSON NaN stop_time", json.dumps(edit(plain(), "stop_time", float("nan"))).encode(),
     ".json", 2, "'stop_time'"),
    ("TOML inf stop_time", b"name = \"x\"\nstop_time = inf\norder = []\n[fmus]\n", ".toml", 2,
     "h.toml"),
    ("2 MB file", b"# " + b"x" * 2_000_000 + b"\n", ".toml", 2, "bytes"),
    ("wrong suffix", b"name = \"x\"\n", ".yaml", 2, ".toml or .json"),
]
