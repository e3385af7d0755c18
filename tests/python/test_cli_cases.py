"""The cases of issue 19 for a single run, each against an independent truth: the FMU's
own log line in errors (the plant logs a Discard's reason only when its status category
is on), cleanup that does not mask the first error and leaves no extracted folder, units
checked against the FMU's declared unit, the workspace check along the interpolated
path, the units sidecar, and plots that do not magnify round-off."""

from __future__ import annotations

import json
import math
import sys
import tempfile
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from robofmu.errors import CosimError  # noqa: E402
from robofmu.master import Master  # noqa: E402
from robofmu.scenario import ScenarioError, load_scenario, parse_document  # noqa: E402
from hostile_cases import ROOT, base, edit, plain  # noqa: E402

HEAVY_INERTIA = {"platformMass": "2.5 kg", "platformInertia[1,1]": "0.03 kg m^2",
                 "platformInertia[2,2]": "0.03 kg m^2",
                 "platformInertia[3,3]": "0.057 kg m^2"}


@pytest.fixture
def private_temp(tmp_path, monkeypatch):
    temp = tmp_path / "temp"
    temp.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(temp))
    return temp


def test_a_refused_call_carries_the_fmus_log_line_and_cleanup_leaves_nothing(private_temp):
    # Truth: the plant's own check (I_xx + I_yy >= I_zz about the centre of mass; with
    # 2.5 kg and the default inertia about P, 2 (0.011824 - 2.5 * 0.01955^2) < 0.022886).
    doc = edit(plain(), "parameters/plant/platformMass", 2.5)
    scenario = parse_document(doc, ROOT, preflight=False)  # straight to the master
    with pytest.raises(CosimError) as error:
        Master(scenario).run()
    message = str(error.value)
    assert "triangle inequality" in message and "logged no reason" not in message
    assert "Terminate" not in message  # cleanup did not replace the first error
    assert not list(private_temp.iterdir())  # every extracted FMU folder removed


def test_the_gain_design_at_a_pose_the_plant_refuses_names_the_plants_reason(private_temp):
    from robofmu.design import euler_inertia
    plant = str(ROOT / "dist" / "Pss3Plant.fmu")
    with pytest.raises(ScenarioError, match="cannot reach its platform joint"):
        euler_inertia(plant, (0.0, math.radians(30.0), math.radians(138.0)))
    assert not list(private_temp.iterdir())


def test_units_are_checked_against_the_declared_unit(tmp_path):
    def plant_parameters(values):
        path = tmp_path / "s.json"
        path.write_text(json.dumps(edit(base(), "plant", values)))
        return load_scenario(path).parameters["plant"]
    # Truth: 9.81 m/s^2 is the FMU's declared default of g (modelDescription start).
    assert plant_parameters({"g": "9.81 m/s^2"})["g"] == 9.81
    assert plant_parameters({"g": 9.81})["g"] == 9.81
    with pytest.raises(ScenarioError, match=r"'plant.g'.*a length.*m/s2"):
        plant_parameters({"g": "9810 mm"})
    got = plant_parameters({**HEAVY_INERTIA, "legMass": "950 g"})
    assert got["platformMass"] == 2.5 and got["legMass"] == pytest.approx(0.95, rel=1e-15)
    assert got["platformInertia[3,3]"] == 0.057


def test_the_documented_heavier_platform_runs(tmp_path, capsys):
    from robofmu.cli import main
    path = tmp_path / "heavy.json"
    path.write_text(json.dumps(edit(base(), "plant", HEAVY_INERTIA)))
    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--quiet",
                 "--no-plots"]) == 0
    units = json.loads((tmp_path / "out" / "h.units.json").read_text())
    # Truth: the units the plant's and planner's modelDescription declare.
    assert units["time"] == "s" and units["plant.theta[1]"] == "rad"
    assert units["plant.force[1]"] == "N" and units["planner.qddot[1]"] == "rad/s2"
    assert units["pid.u[1]"] == "1"  # the PID declares no unit
    header = (tmp_path / "out" / "h.csv").read_text().splitlines()[0]
    assert header.split(",")[0] == '"time"' and set(units) == {
        n.strip('"') for n in header.split(",")}


def test_a_path_between_reachable_waypoints_that_leaves_the_workspace_is_refused(tmp_path):
    # Two reachable waypoints, a fast roll rate at both ends: the quintic overshoots
    # between them. Truth of reachability: the plant's inverse kinematics (l within
    # [strokeMin, strokeMax]); the waypoints alone pass the same check.
    doc = edit(base(), "motion/waypoints/0/omega", "3, 0, 0 rad/s")
    doc = edit(doc, "motion/waypoints/1/omega", "-3, 0, 0 rad/s")
    doc = edit(doc, "stop_time", "0.5 s")
    doc = edit(doc, "motion/waypoints/1/time", "0.5 s")
    doc = edit(doc, "motion/waypoints/1/angles", "0, 0, 138 deg")
    path = tmp_path / "overshoot.json"
    path.write_text(json.dumps(doc))
    with pytest.raises(ScenarioError) as error:
        load_scenario(path)
    message = str(error.value)
    import re
    when = re.search(r"at t = ([0-9.e-]+) s", message)
    assert "'motion.waypoints'" in message and when, message
    assert 0.0 < float(when.group(1)) < 0.5  # between the waypoints
    assert "actuator" in message and "stroke" in message
    for k in (0, 1):  # each waypoint alone is inside the workspace
        point = doc["motion"]["waypoints"][k]
        single = edit(doc, "motion/waypoints", [dict(point), dict(point)])
        single = edit(single, "motion/waypoints/0/time", "0 s")
        single = edit(single, "motion/waypoints/1/time", "0.5 s")
        single = edit(single, "motion/waypoints/0/omega", "0, 0, 0 rad/s")
        single = edit(single, "motion/waypoints/1/omega", "0, 0, 0 rad/s")
        assert parse_document(single, tmp_path, preflight=True).steps == 500


def test_plots_do_not_magnify_round_off():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from robofmu.report import coincide_note, steady_axis
    fig, (flat, real) = plt.subplots(2)
    noise = 1e-14 * np.sin(np.linspace(0.0, 10.0, 100))
    flat.plot(noise)
    steady_axis(flat, noise, "deg")
    low, high = flat.get_ylim()
    assert high - low == pytest.approx(2e-6)  # the panel spans MIN_SPAN either side
    signal = np.linspace(0.0, 0.5, 100)
    real.plot(signal)
    before = real.get_ylim()
    steady_axis(real, signal, "deg")
    assert real.get_ylim() == before  # a real deviation keeps the autoscale
    plt.close(fig)
    assert "coincides" in coincide_note(signal, signal + 1e-6, "deg", 0.5)
    assert coincide_note(signal, signal + 0.01, "deg", 0.5) == ""


def test_a_simulation_that_fails_is_exit_1_with_the_fmus_reason(tmp_path, capsys):
    # Absurd gains from a small offset: the plant's integrator cannot follow and the
    # plant discards the first step, saying why (its log line, category logStatusDiscard).
    from robofmu.cli import main
    doc = edit(plain(), "parameters/plant/theta0[1]", 0.01)
    for i in (1, 2, 3):
        doc = edit(doc, f"parameters/pid/Kp[{i}]", 1e12)
    path = tmp_path / "boom.json"
    path.write_text(json.dumps(doc))
    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--quiet"]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"cosim: {path}: the simulation failed")
    assert "plant discarded the step at t = 0 s" in err and "fmi2DoStep" in err
    assert "logged no reason" not in err


def test_one_help_lists_every_command_and_each_command_has_its_own(capsys):
    from robofmu.cli import COMMANDS, main
    assert main(["--help"]) == 0
    text = capsys.readouterr().out
    assert all(f"    {name}" in text for name in COMMANDS) and len(COMMANDS) == 11
    for name in COMMANDS:
        assert main([name, "--help"]) == 0
        assert f"usage: cosim {name}" in capsys.readouterr().out


def test_every_document_the_harness_points_to_exists():
    # Messages and help texts send users to docs/NAME.md: each such file must exist
    # (truth: the repository's docs/ folder); a renamed document left a dead pointer.
    import re
    named = {m for p in (ROOT / "robofmu").rglob("*.py")
             for m in re.findall(r"docs/[\w.-]+\.md", p.read_text())}
    assert len(named) >= 3
    assert sorted(n for n in named if not (ROOT / n).is_file()) == []


def test_demo_errors_are_one_line_with_the_exit_code_of_the_contract(tmp_path, capsys,
                                                                    monkeypatch):
    # A bundled scenario that is missing (the user's checkout is incomplete) is a user
    # error: exit 2 and one line 'cosim: FILE: ...' (the contract of robofmu/cli.py); the
    # demo said 'demo: ...' and exited 1, like a failed simulation.
    import robofmu.demo
    from robofmu.cli import main
    monkeypatch.setattr(robofmu.demo, "SCENARIOS", ["no_such_scenario"])
    assert main(["demo", "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and err[0].startswith("cosim: ") and "no_such_scenario.toml" in err[0]


def test_a_flat_recorded_signal_is_not_labelled_in_newtons(tmp_path, monkeypatch):
    # NAME_signals.png draws any FMU's signals (planner angles in rad here): a panel
    # constant to round-off was noted "constant to within ... N". Truth: the panel's
    # signals are the planner's, whose unit is rad, not N.
    import matplotlib
    matplotlib.use("Agg")
    import robofmu.outputs
    from robofmu.outputs import plot_signals
    notes = []
    original = robofmu.outputs.steady_axis  # robofmu.report's, imported where it is used
    monkeypatch.setattr(robofmu.outputs, "steady_axis",
                        lambda ax, values, unit: notes.append(unit) or original(ax, values,
                                                                               unit))
    t = [0.0, 0.5, 1.0]
    path = plot_signals({"time": t, "planner.q[1]": [0.1, 0.1, 0.1 + 1e-9]},
                        ["planner.q[1]"], "flat", tmp_path)
    assert path.is_file() and notes == ["SI units"]
