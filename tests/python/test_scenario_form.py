"""Hand-written closed-loop scenarios (robofmu.closed_loop): units, the Euler-rate and gain
conversions against the Rust side, and multi-segment motions through the planner FMU."""

from __future__ import annotations

import math
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from robofmu.master import Master  # noqa: E402
from robofmu.report import read_csv, vector  # noqa: E402
from robofmu.scenario import ScenarioError, load_scenario, parse_document  # noqa: E402

NAMES = ["regulation", "path1_cubic", "path1_quintic", "three_axis_cubic",
         "three_axis_quintic"]


def test_the_regulation_resolves_to_its_former_plain_form():
    # Truth: tests/scenarios/regulation_plain.toml, written by the Rust tools
    # (`robofmu closed-loop boundary` and `design-gains`, gains rounded to 6 decimals).
    plain = load_scenario(ROOT / "tests" / "scenarios" / "regulation_plain.toml")
    human = load_scenario(ROOT / "scenarios" / "regulation.toml")
    assert human.parameters["planner"] == plain.parameters["planner"]
    assert human.parameters["plant"] == plain.parameters["plant"]
    for key, value in plain.parameters["pid"].items():
        assert human.parameters["pid"][key] == pytest.approx(value, rel=1e-6, abs=1e-12)
    assert sorted(map(str, human.connections)) == sorted(map(str, plain.connections))
    assert human.record == plain.record and human.steps == plain.steps


@pytest.mark.parametrize("name", NAMES)
def test_boundary_conditions_are_the_rust_references(name):
    # Truth: the Rust reference CSV's planner rows at t0 and tf, computed by the Rust
    # library's Euler-rate conversion (pss3::rotation) from the same file.
    ref = read_csv(ROOT / "tests" / "closed_loop_references" / name / f"{name}_ref.csv")
    p = load_scenario(ROOT / "scenarios" / f"{name}.toml").parameters["planner"]
    for row, end in ((0, "0"), (-1, "f")):
        for i in (1, 2, 3):
            assert p[f"q{end}[{i}]"] == pytest.approx(ref[f"planner.q[{i}]"][row], abs=1e-14)
            assert p[f"qdot{end}[{i}]"] == pytest.approx(ref[f"planner.qdot[{i}]"][row],
                                                         abs=1e-14)
            if p["order"] == 5:
                assert p[f"qddot{end}[{i}]"] == pytest.approx(
                    ref[f"planner.qddot[{i}]"][row], abs=1e-14)


def document(name: str) -> dict:
    return tomllib.loads((ROOT / "scenarios" / f"{name}.toml").read_text())


@pytest.mark.parametrize("path, value, field", [
    (("gains", "omega"), 30, "gains.omega"),
    (("gains", "omega"), "30 rad", "gains.omega"),
    (("motion", "profile"), "septic", "motion.profile"),
    (("start", "angles"), "3, -2 deg", "start.angles"),
    (("stop_time",), "1 parsec", "stop_time"),
])
def test_quantities_without_their_unit_are_refused(path, value, field):
    data = document("regulation")
    node = data
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value
    with pytest.raises(ScenarioError, match=field.replace(".", r"\.")):
        parse_document(data, ROOT / "scenarios")


def test_degrees_and_radians_state_the_same_motion():
    data = document("three_axis_quintic")
    data["motion"]["waypoints"][1]["angles"] = ", ".join(
        repr(math.radians(a)) for a in (4, -5, 145)) + " rad"
    data["motion"]["waypoints"][1]["omega"] = ", ".join(
        repr(math.degrees(w)) for w in (0.03, 0.02, 0.08)) + " deg/s"
    a = parse_document(data, ROOT / "scenarios").parameters["planner"]
    b = load_scenario(ROOT / "scenarios" / "three_axis_quintic.toml").parameters["planner"]
    assert a == pytest.approx(b, rel=1e-14, abs=1e-15)


def multi_segment(profile: str) -> dict:
    data = document("three_axis_quintic")
    data["motion"]["profile"] = profile
    first, last = data["motion"]["waypoints"]
    middle = {"time": "1 s", "angles": "0, -1, 140 deg", "omega": "0.05, -0.02, 0.1 rad/s",
              "omega_dot": "0.02, 0.01, 0 rad/s^2"}
    data["motion"]["waypoints"] = [first, middle, last]
    return data


@pytest.mark.parametrize("profile", ["cubic", "quintic"])
def test_multi_segment_motions_pass_every_waypoint_continuously(profile):
    # Truth: the waypoint's angles and its base-frame omega (converted by the
    # planner-independent E^-1) at t = 1 s; velocity continuity shows as a
    # first-difference of q equal to q_dot h to O(h^2) on both sides of the waypoint.
    from robofmu.design import euler_rates
    scenario = parse_document(multi_segment(profile), ROOT / "scenarios")
    assert [s.step for s in scenario.schedule] == [1000]
    r = Master(scenario).run()
    q, qdot = vector(r.columns, "planner", "q"), vector(r.columns, "planner", "qdot")
    angles = np.radians([0.0, -1.0, 140.0])
    assert np.abs(q[1000] - angles).max() < 1e-15
    assert np.abs(qdot[1000] - euler_rates(angles, [0.05, -0.02, 0.1])).max() < 1e-15
    h = scenario.step_size
    for k in (999, 1000):
        assert np.abs((q[k + 1] - q[k]) / h - 0.5 * (qdot[k] + qdot[k + 1])).max() < 1e-6
    # Sample 1000 is the first segment at its end; the second segment, extrapolated
    # back from samples 1001..1003 (quadratically, error O(h^3)), must meet it.
    qddot = vector(r.columns, "planner", "qddot")
    right = 3.0 * qddot[1001] - 3.0 * qddot[1002] + qddot[1003]
    jump = np.abs(right - qddot[1000]).max()
    # Quintic: acceleration continuous; cubic: it jumps (the cubic cannot match it).
    assert (jump < 1e-6) if profile == "quintic" else (jump > 1e-2), jump
    theta = vector(r.columns, "plant", "theta")
    assert math.degrees(np.abs(theta - q).max()) < 0.05  # the loop tracks it


# Every mass and inertia of the plant (the off-diagonal inertias are 0 by default).
MASSES = ["platformMass", "legMass", "legTransverseInertia", "sliderMass",
          "platformInertia[1,1]", "platformInertia[2,2]", "platformInertia[3,3]"]


def _pid_gains(document) -> list[float]:
    pid = parse_document(document, ROOT / "scenarios").parameters["pid"]
    return [pid[f"{k}[{i}]"] for k in ("Kp", "Ki", "Kd") for i in (1, 2, 3)]


def test_the_gain_design_uses_the_scenarios_plant_as_the_closed_form_says():
    # Truth: the rigid-body dynamics are homogeneous in mass: every mass and inertia
    # doubled doubles M and so the Euler-angle mass matrix M_x (gravity is subtracted by
    # the design, friction vanishes at rest), and the triple-pole gains Kp = 3 m w^2,
    # Ki = m w^3, Kd = 3 m w are linear in m: every gain doubles.
    from fmpy import read_model_description
    md = read_model_description(str(ROOT / "dist" / "Pss3Plant.fmu"))
    start = {v.name: float(v.start) for v in md.modelVariables if v.name in MASSES}
    document = tomllib.loads((ROOT / "scenarios" / "regulation.toml").read_text())
    nominal = _pid_gains(document)
    document["plant"] = {name: 2.0 * value for name, value in start.items()}
    doubled = _pid_gains(document)
    assert doubled == pytest.approx([2.0 * g for g in nominal], rel=1e-9)
    # The design assumes another plant only when told: gains.design_plant (empty: the
    # FMU's defaults) gives the nominal gains back for the doubled plant.
    document["gains"]["design_plant"] = {}
    assert _pid_gains(document) == pytest.approx(nominal, rel=1e-12)


def test_a_sweep_drawing_plant_parameters_designs_on_the_base_plant():
    # Truth: sweeps/demo_gains.toml draws plant.legMass at random (the robot's
    # uncertainty): each run's gains are those of the base scenario's plant at its omega.
    from robofmu.sweep.spec import document_for, load_spec
    spec = load_spec(ROOT / "sweeps" / "demo_gains.toml")
    run = spec.runs[0]
    document = document_for(spec, run)
    assert document["gains"]["design_plant"] == {}
    assert document["plant"]["legMass"] != "0.9467 kg"
    base = tomllib.loads((ROOT / "scenarios" / "regulation.toml").read_text())
    base["gains"]["omega"] = document["gains"]["omega"]
    assert _pid_gains(document) == pytest.approx(_pid_gains(base), rel=1e-12)
