"""The library API (`import robofmu`): a bundled scenario loaded, changed and simulated
into numpy arrays, a System of a third-party FMU (compiled here from
examples/integrator/) and our PID, and bad input raising the documented exceptions with
one-line messages. Each expected value says where it comes from."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "examples" / "integrator"))

import robofmu  # noqa: E402
from build_fmu import build  # noqa: E402
from robofmu.master import Master  # noqa: E402
from robofmu.scenario import load_scenario  # noqa: E402


@pytest.fixture(scope="module")
def integrator(tmp_path_factory) -> Path:
    return build(tmp_path_factory.mktemp("integrator") / "Integrator.fmu")


def test_public_names_are_listed_and_documented():
    # dir() lists the API; each public name has a docstring (the API reference).
    assert set(robofmu.__all__) <= set(dir(robofmu))
    for name in robofmu.__all__:
        assert getattr(robofmu, name).__doc__, name


def test_bundled_paths_are_what_the_command_prints(capsys):
    # Second source: `cosim fmus --path` and `cosim examples --path` (robofmu.cli).
    from robofmu.cli import main
    assert main(["fmus", "--path", "PID"]) == 0
    assert Path(capsys.readouterr().out.strip()) == robofmu.fmu("PID")
    assert main(["examples", "--path", "regulation"]) == 0
    assert Path(capsys.readouterr().out.strip()) == robofmu.example("regulation")


def test_changed_gain_simulates_as_the_changed_file_runs(tmp_path):
    scenario = robofmu.load("regulation")
    before = scenario.parameters["pid"]
    scenario.set("gains.omega", "40 rad/s")
    after = scenario.parameters["pid"]
    # The design rule (docs/closed-loop.md): Kp = 3 J w^2, Ki = J w^3, Kd = 3 J w for the
    # same inertia J: from 30 to 40 rad/s the gains scale by (4/3)^2, (4/3)^3, 4/3.
    for gain, power in (("Kp", 2), ("Ki", 3), ("Kd", 1)):
        for i in (1, 2, 3):
            assert after[f"{gain}[{i}]"] == pytest.approx(
                before[f"{gain}[{i}]"] * (4 / 3) ** power, rel=1e-12)
    result = robofmu.simulate(scenario)
    assert isinstance(result.time, np.ndarray) and isinstance(result["plant.theta[1]"], np.ndarray)
    # The communication points: k * 1 ms, k = 0..1000 (regulation.toml).
    np.testing.assert_allclose(result.time, np.arange(1001) * 1e-3, rtol=0, atol=1e-15)
    # Second formulation: the same change written into a copy of the file, run by the
    # master the command line uses.
    text = robofmu.example("regulation").read_text().replace('omega = "30 rad/s"',
                                                             'omega = "40 rad/s"')
    copy = tmp_path / "regulation.toml"
    copy.write_text(text)
    table = Master(load_scenario(copy)).run()
    assert result.names == table.names
    for name in table.names:
        np.testing.assert_array_equal(result[name], np.asarray(table.columns[name]))
    assert result.unit("plant.theta[1]") == "rad" and result.unit("time") == "s"


def test_parameters_take_units_and_are_converted_to_the_fmus(tmp_path):
    # "1000 g" and 1.0 (SI, kg) set the same start value (the unit table: g = 1e-3 kg).
    base = robofmu.load("regulation")
    runs = [robofmu.simulate(base, parameters={"plant.legMass": v}) for v in ("1000 g", 1.0)]
    np.testing.assert_array_equal(runs[0]["plant.theta[1]"], runs[1]["plant.theta[1]"])
    plain = robofmu.simulate(base)
    assert not np.array_equal(plain["plant.theta[1]"], runs[0]["plant.theta[1]"])


def test_a_run_the_fmu_refuses_raises_simulation_error():
    # 2.5 kg with the default inertia: the plant's own check (triangle inequality of the
    # principal moments about the centre of mass) refuses it at initialisation.
    with pytest.raises(robofmu.SimulationError) as caught:
        robofmu.simulate("regulation", parameters={"plant.platformMass": "2.5 kg"})
    assert isinstance(caught.value, RuntimeError)
    assert str(caught.value).startswith("regulation: the simulation failed: plant: ")
    assert "triangle inequality" in str(caught.value) and "\n" not in str(caught.value)


def test_result_writes_the_csv_cosim_run_writes(tmp_path):
    from robofmu.report import read_csv
    result = robofmu.simulate("regulation")
    path = result.to_csv(tmp_path / "out" / "r.csv")
    columns = read_csv(path)
    np.testing.assert_array_equal(np.asarray(columns["time"]), result.time)
    np.testing.assert_array_equal(np.asarray(columns["pid.u[1]"]), result["pid.u[1]"])


def test_system_of_a_third_party_fmu_and_our_pid(integrator):
    # A P controller on an integrator: y' = g u, u = Kp (1 - y) sampled at t_k and held
    # (sampled coupling; the integrator steps exactly): y_k = 1 - (1 - h g Kp)^k (1 - y0).
    h, g, kp, y0 = 0.01, 2.0, 5.0, 0.25
    # The PID (direct feedthrough) first: the sampled coupling propagates the outputs at
    # t_k in the order the FMUs were added, so the plant then steps with u(t_k).
    system = robofmu.System(stop_time=1.0, step_size="10 ms")
    system.add("pid", "PID", parameters={"Kp[1]": kp, "Ki[1]": 0.0, "Kd[1]": 0.0,
                                          "setpoint[1]": 1.0})
    system.add("plant", integrator, parameters={"gain": g, "y0": "250 mm"})
    system.connect("plant.y", "pid.measurement[1]")
    system.connect("pid.u[1]", "plant.u")
    result = robofmu.simulate(system)
    k = np.arange(101)
    np.testing.assert_allclose(result["plant.y"], 1 - (1 - h * g * kp) ** k * (1 - y0),
                               rtol=0, atol=1e-12)
    assert result.unit("plant.y") == "m" and result.unit("pid.u[1]") in ("1", "N m")


@pytest.mark.parametrize("make, message", [
    (lambda i: robofmu.simulate("regulation", parameters={"pid.Kq[1]": 1.0}),
     "field 'parameters.pid.Kq[1]': pid has no variable 'Kq[1]'"),
    (lambda i: robofmu.simulate("regulation", parameters={"plant.platformMass": "3 m"}),
     "field 'parameters.plant.platformMass': plant.platformMass is in 'kg', got 'm'"),
    (lambda i: robofmu.simulate(robofmu.System(1.0).add("p", i, parameters={"y0": 2.0})),
     "field 'parameters.p.y0': 2.0 is outside the range [-1, 1] that p.y0 declares"),
    (lambda i: robofmu.simulate(robofmu.System(1.0).add("p", i).connect("p.y", "p.v")),
     "field 'connections[0].to': p has no variable 'v'"),
    (lambda i: robofmu.simulate(robofmu.System(1.0).add("p", ROOT / "README.md")),
     "field 'fmus.p'"),
    (lambda i: robofmu.load("no_such_example"),
     "example: 'no_such_example' is not a bundled example scenario"),
    (lambda i: robofmu.load("regulation").set("gains.omega", "40 m/s"),
     "field 'gains.omega' must be a angular velocity"),
])
def test_bad_input_raises_the_documented_error(integrator, make, message):
    with pytest.raises(robofmu.ScenarioError) as caught:
        make(integrator)
    text = str(caught.value)
    assert isinstance(caught.value, ValueError)
    assert message in text and "\n" not in text, text


def test_a_refused_change_leaves_the_scenario_as_it_was():
    scenario = robofmu.load("regulation")
    with pytest.raises(robofmu.ScenarioError):
        scenario.set("stop_time", "-1 s")
    assert scenario.stop_time == 1.0 and scenario.get("stop_time") == "1 s"


HIDDEN = """
import sys
sys.modules[{module!r}] = None
sys.path.insert(0, {root!r})
import robofmu
try:
    {call}
except robofmu.MissingExtra as e:
    assert isinstance(e, RuntimeError)
    print(e)
"""


@pytest.mark.parametrize("module, call, message", [
    ("pandas", "robofmu.simulate('regulation').to_pandas()",
     "Result.to_pandas needs pandas, which robofmu leaves optional; pip install "
     "'robofmu[pandas]'"),
    ("distributed", "robofmu.run_sweep('sweeps/demo_gains.toml', 'results/x', workers=2)",
     "run_sweep on Dask needs distributed, which robofmu leaves optional; pip install "
     "'robofmu[sweep]'"),
    ("matplotlib", "robofmu.run_sweep('sweeps/demo_gains.toml', 'results/x', plots=True)",
     "run_sweep(plots=True) needs matplotlib, which robofmu leaves optional; pip install "
     "'robofmu[plots]'"),
    ("fmu_manipulation_toolbox", "robofmu.write_container('regulation', 'results/x.fmu')",
     "write_container needs fmu_manipulation_toolbox, which robofmu leaves optional; pip "
     "install 'robofmu[container]'"),
])
def test_a_missing_extra_is_named_in_one_line(tmp_path, module, call, message):
    # The module hidden (sys.modules[name] = None makes its import fail), run in a fresh
    # interpreter from an empty folder: nothing is written there.
    run = subprocess.run([sys.executable, "-c", HIDDEN.format(module=module, root=str(ROOT),
                                                                call=call)],
                         cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0 and run.stdout == message + "\n", run.stderr
    assert list(tmp_path.iterdir()) == []


def test_the_command_names_a_missing_extra_in_one_line(tmp_path):
    # `cosim run` with its plots and matplotlib hidden: exit 2 (a user error), one line.
    code = (f"import sys; sys.modules['matplotlib'] = None; sys.path.insert(0, {str(ROOT)!r}); "
            "from robofmu.cli import main; "
            f"sys.exit(main(['run', {str(ROOT / 'scenarios' / 'regulation.toml')!r}, "
            "'--out', 'out', '--quiet']))")
    run = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True,
                         text=True, timeout=120)
    assert run.returncode == 2 and run.stdout == "", run.stderr
    assert run.stderr == ("cosim: the plots of cosim run needs matplotlib, which robofmu "
                          "leaves optional; pip install 'robofmu[plots]', or run with "
                          "--no-plots\n")
    assert list(tmp_path.iterdir()) == []


def test_the_commands_as_functions(tmp_path):
    # verify_fmu: the bundled reference case passes (as `cosim verify` in test-wheel.sh).
    verdict = robofmu.verify_fmu(robofmu.fmu("Pss3Plant"), robofmu.example("Pss3Plant/path1"),
                                 tmp_path / "verify")
    assert verdict.passed and verdict.report.is_file() and len(verdict.lines) == 6
    # write_ssp: an SSP archive with the system structure and the three FMUs.
    import zipfile
    ssp = robofmu.write_ssp("regulation", tmp_path / "r.ssp")
    with zipfile.ZipFile(ssp) as archive:
        assert "SystemStructure.ssd" in archive.namelist()
        assert sum(n.endswith(".fmu") for n in archive.namelist()) == 3
    # write_animation of a result's CSV: the GIF `cosim animate` writes.
    csv = robofmu.simulate("regulation").to_csv(tmp_path / "regulation.csv")
    written = robofmu.write_animation(csv, tmp_path / "anim", frames=3, size=96)
    assert [p.name for p in written] == ["regulation.gif"] and written[0].stat().st_size > 0


def test_a_serial_sweep_through_the_api(tmp_path):
    # A grid of two gains on the regulation; each row's RMS error is the one simulate
    # gives for that gain (second path: the Scenario API and the metrics `cosim run`
    # reports, robofmu.report.metrics).
    from robofmu.report import metrics
    spec = tmp_path / "gains.toml"
    spec.write_text(f'scenario = "{robofmu.example("regulation")}"\nname = "g"\n'
                    "[grid.'gains.omega']\nvalues = [20, 40]\nunit = \"rad/s\"\n")
    outcome = robofmu.run_sweep(spec, tmp_path / "out")
    assert (outcome.runs, outcome.failed) == (2, 0) and outcome.table.is_file()
    rows = outcome.rows()
    for row, omega in zip(rows, (20, 40)):
        scenario = robofmu.load("regulation")
        scenario.set("gains.omega", f"{omega} rad/s")
        run = robofmu.simulate(scenario)
        expected = metrics({name: run[name] for name in run})
        assert float(row["rms_error_deg"]) == pytest.approx(expected.rms_error_deg, rel=1e-9)
