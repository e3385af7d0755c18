"""Our master ticks a clocked FMU (robofmu.clocked): the sampled computed-torque law of
ComputedTorque's FMI 3.0 build (input clock `sampleClock`, clocked output `uSampled`)
on the FMI 3.0 plant in Co-Simulation, through a scenario's `sample_period`; the plant
and the controller in Model Exchange (robofmu.integrated); the closed-loop form's
`sample_period` with computed torque on a motion and with the sampled PID on the
regulation (its law written again in numpy); robofmu.System and a sweep.

Expected values: the zero-order-hold law from a second formulation, computed here from
the plant's recorded outputs at the ticks (test_clocked_controller.Reference: the
continuous form of the same FMU in Model Exchange used as a function, the sampled
error integral advanced by Ts der(integral) in Python), held between ticks: every
recorded `uSampled` equal to it to 1e-12 N m. Tick times: k counter / resolution from
integers, against numpy's k / 1000 (each one rounding); the bad inputs of the new field:
one line naming the file and the field, exit 2."""

from __future__ import annotations

import shutil
import sys
from ctypes import c_double
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException
from fmpy.fmi3 import FMU3Model

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from robofmu.cli import main as cosim  # noqa: E402
from robofmu.clocked import grid  # noqa: E402
from robofmu.master import run_arrays  # noqa: E402
from robofmu.scenario import load_scenario  # noqa: E402
from test_clocked_controller import Reference, open_fmu  # noqa: E402

AXES = (1, 2, 3)
CONNECTIONS = "".join(
    f'[[connections]]\nfrom = "plant.{out}[{i}]"\nto = "ct.{into}[{i}]"\n'
    for out, into in (("theta", "measurement"), ("thetaDot", "measuredRate")) for i in AXES
) + "".join(f'[[connections]]\nfrom = "ct.uSampled[{i}]"\n'
            f'to = "plant.generalizedForceCommand[{i}]"\n' for i in AXES)


# The setpoint of thz 1 deg from the plant's start (theta0[3] = 2.439784063985299 rad),
# the others the FMU's (0.5 and -0.5 deg): the loop moves and no actuator reaches an
# end stop (the FMU's default thz, 17 deg away, drops the platform onto the lower stops).
SETPOINT = (0.008726646259971648, -0.008726646259971648, 2.457237)


def scenario(tmp_path: Path, step: float = 0.001, stop: float = 0.2, period="0.001",
             ct: str = "fmi3/ComputedTorque", extra: str = "", name: str = "sampled",
             plant: str = "fmi3/Pss3Plant", ct_parameters: str = "") -> Path:
    """The loop ct -> plant, ct ticked every `period` s (the text of the field)."""
    path = tmp_path / f"{name}.toml"
    path.write_text(f'name = "{name}"\nstop_time = {stop}\nstep_size = {step}\n'
                    f'order = ["ct", "plant"]\n{extra}\n'
                    f'[fmus]\nct = "{ct}"\nplant = "{plant}"\n\n'
                    f'[parameters.ct]\n"setpoint[3]" = {SETPOINT[2]}\n{ct_parameters}\n'
                    f'[sample_period]\nct = {period}\n\n' + CONNECTIONS)
    return path


def zero_order_hold_error(tmp_path: Path, result, every: int) -> float:
    """The largest |uSampled - the zero-order-hold law| over the rows: the law at the
    plant's recorded outputs every `every` rows (the ticks), held in between."""
    folder = tmp_path / f"reference{len(list(tmp_path.glob('reference*')))}"
    folder.mkdir()  # each its own copy of the FMU: the last one's library stays loaded
    reference = Reference(folder)
    reference.fmu.setFloat64([reference.vr["setpoint"]], list(SETPOINT))
    worst, held = 0.0, None
    for k in range(len(result.time)):
        if k % every == 0:  # a tick: the law at the plant's outputs now
            theta = [result.columns[f"plant.theta[{i}]"][k] for i in AXES]
            rate = [result.columns[f"plant.thetaDot[{i}]"][k] for i in AXES]
            held = reference.tick(theta, rate)
        got = [result.columns[f"ct.uSampled[{i}]"][k] for i in AXES]
        worst = max(worst, *(abs(a - b) for a, b in zip(got, held)))
    return worst


@pytest.mark.parametrize("step, stop, plant", [(0.001, 0.2, "fmi3/Pss3Plant"),
                                               (0.0005, 0.1, "fmi3/Pss3Plant"),
                                               (0.001, 0.05, "Pss3Plant")])
def test_the_sampled_law_equals_the_zero_order_hold_reference(tmp_path, step, stop, plant):
    # Also beside the FMI 2.0 plant (an FMI 2.0 FMU in the same loop).
    result = run_arrays(load_scenario(scenario(tmp_path, step, stop, plant=plant)))
    every = round(0.001 / step)  # communication steps per tick
    assert len(result.time) == round(stop / step) + 1
    worst = zero_order_hold_error(tmp_path, result, every)
    print(f"step {step} s: max |uSampled - zero-order hold| = {worst:.3g} N m")
    assert worst <= 1e-12, worst
    # The loop moved (the comparison is not one of zeros) and the output is held: with
    # two steps per tick, each odd row repeats the tick's value before it.
    assert abs(result.columns["plant.theta[1]"][-1]) > 1e-4
    u = result.columns["ct.uSampled[3]"]
    assert np.abs(u).max() > 1.0
    if every == 2:
        assert np.array_equal(u[1::2], u[0:-1:2]) and np.all(u[2::2] != u[1::2])


def test_the_plant_and_the_controller_in_model_exchange(tmp_path):
    # The plant integrated by the master (RK4 at 1 ms, robofmu.integrated) against the
    # plant's own integrator in Co-Simulation (Dormand-Prince 5(4) at its tolerance): a
    # second formulation of the same motion. Measured: 1.2e-13 rad and 1.9e-11 rad/s
    # over 0.2 s (a motion of 0.02 rad at up to 0.2 rad/s); the sampled law is still the
    # reference's to 1e-12.
    co = run_arrays(load_scenario(scenario(tmp_path)))
    me = run_arrays(load_scenario(scenario(tmp_path, name="me",
                                           extra='model_exchange = { plant = "rk4" }')))
    for signal, bound in (("theta", 1e-11), ("thetaDot", 1e-9)):
        for i in AXES:
            name = f"plant.{signal}[{i}]"
            assert np.abs(me.columns[name] - co.columns[name]).max() < bound, name
    assert zero_order_hold_error(tmp_path, me, 1) <= 1e-12
    # The clocked controller in Model Exchange too (Clocked Model Exchange: Event Mode,
    # fmi3SetClock and fmi3UpdateDiscreteStates at each tick, its continuous state
    # integrated between): the same loop, its output the reference's.
    both = run_arrays(load_scenario(scenario(
        tmp_path, name="both", extra='model_exchange = { plant = "rk4", ct = "rk4" }')))
    assert zero_order_hold_error(tmp_path, both, 1) <= 1e-12
    for name in me.names:
        assert np.array_equal(both.columns[name], me.columns[name]), name


def test_ticks_are_exact_after_a_million_periods_and_the_fmu_takes_the_clock_there(tmp_path):
    # Truth: k / 1000 rounded once (numpy divides each integer k, IEEE); a sum of 10^6
    # periods is 1.7e-8 s off, which the FMU refuses as no tick.
    times = grid(0.0, Fraction(1, 1000), 1_000_001)
    assert times[-1] == 1000.0
    assert np.array_equal(times, np.arange(1_000_001) / 1000)
    assert abs(sum([0.001] * 1_000_000) - 1000.0) > 1e-9
    ctrl, vr = open_fmu(tmp_path, "ComputedTorque", FMU3Model, "me")
    ctrl.instantiate()
    ctrl.enterInitializationMode(startTime=0.0)
    ctrl.exitInitializationMode()
    ctrl.enterContinuousTimeMode()
    ctrl.setTime(float(times[-1]))
    ctrl.enterEventMode()
    ctrl.setClock([vr["sampleClock"]], [True])  # tick 10^6: accepted
    ctrl.updateDiscreteStates()
    ctrl.enterContinuousTimeMode()
    ctrl.setTime(sum([0.001] * 1_000_001))
    ctrl.enterEventMode()
    with pytest.raises(FMICallException):
        ctrl.setClock([vr["sampleClock"]], [True])


def test_a_run_far_from_zero_ticks_on_the_fmus_grid(tmp_path):
    # Start 999.995 s: the master's points start + k / 1000 are the FMU's ticks (it
    # refuses a clock off its tick by more than 1e-12 s, a few ulps there).
    path = scenario(tmp_path, stop=1000.005, extra="start_time = 999.995")
    result = run_arrays(load_scenario(path))
    assert np.array_equal(result.time, 999.995 + np.arange(11) / 1000)


@pytest.mark.parametrize("change, message", [
    ({"period": "0.0015"}, "field 'sample_period.ct': 0.0015 s is not a whole number of "
                           "communication steps of 0.001 s (step_size); make it a multiple"),
    ({"period": "0.002"}, "field 'sample_period.ct': ct.sampleClock ticks every 0.001 s with "
                          "the scenario's parameters, not 0.002 s; write sample_period.ct = "
                          "0.001 or set the FMU's period parameter"),
    ({"period": '"1 ms"'}, "field 'sample_period.ct' must be a positive number of seconds "
                           "(such as 0.001), got '1 ms'"),
    ({"period": "-0.001"}, "field 'sample_period.ct' must be a positive number of seconds"),
    ({"ct": "ComputedTorque"}, "field 'sample_period.ct': ct declares no clock (an FMI 2.0 FMU "
                               "without one); remove sample_period.ct or name an FMI 3.0 FMU"),
    ({"extra": 'coupling = "gauss-seidel"'}, "field 'sample_period': a scenario with clocks "
                                             "runs with coupling = \"sampled\" and no "
                                             "max_step_halvings"),
    ({"extra": 'model_exchange = { plant = "rk4" }', "plant": "Pss3Plant"},
     "field 'model_exchange.plant': plant is no FMI 3.0 FMU with Model Exchange"),
    ({"extra": 'model_exchange = { plant = "euler" }'},
     "field 'model_exchange.plant' must be one of ('rk4',) (the master's integration methods)"),
])
def test_a_bad_sample_period_is_one_line(tmp_path, capsys, change, message):
    path = scenario(tmp_path, stop=0.01, **change)
    assert cosim(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"cosim: {path}: "), err
    assert message in err, err


def test_a_system_built_in_code_runs_the_same_clocked_loop(tmp_path):
    # robofmu.System's sample_period and model_exchange are the scenario's fields: the
    # same run as the file's, bit for bit.
    import robofmu
    system = robofmu.System(stop_time=0.05, step_size="1 ms")
    system.add("ct", "fmi3/ComputedTorque", {"setpoint[3]": SETPOINT[2]}, sample_period="1 ms")
    system.add("plant", "fmi3/Pss3Plant", model_exchange="rk4")
    for out, into in (("theta", "measurement"), ("thetaDot", "measuredRate")):
        for i in AXES:
            system.connect(f"plant.{out}[{i}]", f"ct.{into}[{i}]")
    for i in AXES:
        system.connect(f"ct.uSampled[{i}]", f"plant.generalizedForceCommand[{i}]")
    result = robofmu.simulate(system)
    path = scenario(tmp_path, stop=0.05, extra='model_exchange = { plant = "rk4" }')
    expected = run_arrays(load_scenario(path))
    for name in expected.names:
        assert np.array_equal(result[name], expected.columns[name]), name


def test_the_expanded_form_keeps_the_clock_and_the_integration(tmp_path):
    # cosim check --expanded writes the plain form the Rust tools and a rerun read.
    path = scenario(tmp_path, stop=0.01, extra='model_exchange = { plant = "rk4" }')
    out = tmp_path / "expanded.toml"
    assert cosim(["check", str(path), "--expanded", str(out)]) == 0
    again = load_scenario(out)
    assert again.sample_period == {"ct": 0.001} and again.model_exchange == {"plant": "rk4"}


def test_a_discarded_step_ends_the_run_in_one_line(tmp_path, capsys):
    # Absurd gains: the plant's integrator cannot follow and discards the first step.
    gains = "".join(f'"Kp[{i}]" = 1e12\n' for i in AXES) + '"setpoint[1]" = 0.3\n'
    path = scenario(tmp_path, stop=0.01, ct_parameters=gains)
    assert cosim(["run", str(path), "--out", str(tmp_path / "out"), "--quiet"]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"cosim: {path}: the simulation failed")
    assert "plant discarded the step at t = 0 s" in err and "does not retry" in err, err


def test_the_closed_loop_form_runs_the_sampled_law_on_a_motion(tmp_path):
    # path1_cubic_ct (planner -> ct -> plant, 2 s) with sample_period = "1 ms": the
    # controller's FMI 3.0 build ticked, uSampled to the plant. Truth: the zero-order-hold
    # law from the continuous form of the same FMU (Model Exchange, the resolved
    # scenario's parameters), at the recorded planner and plant outputs of each tick,
    # the integral advanced by Ts der(integral); to 1e-12 N m. The sampled loop tracks
    # within 1e-6 deg of the planner (measured 1.8e-7 deg; the continuous law 1.8e-11
    # deg; the Rust sampled reference, tests/sampled_loop.rs, 2e-7 deg from its
    # continuous loop).
    from robofmu.fmi3 import Fmu3Instance
    text = (ROOT / "scenarios" / "path1_cubic_ct.toml").read_text()
    path = tmp_path / "sampled_path1_ct.toml"
    path.write_text(text.replace('step_size = "1 ms"', 'step_size = "1 ms"\nsample_period = "1 ms"'))
    s = load_scenario(path, fmu_dir=ROOT / "dist")
    assert s.sample_period == {"ct": 0.001} and s.fmus["ct"].parent.name == "fmi3"
    result = run_arrays(s)
    law = Fmu3Instance("law", s.fmus["ct"], 0.0, 2.0, model_exchange=True)
    try:
        law.set_values(tuple(s.parameters["ct"]), list(s.parameters["ct"].values()))
        law.enter_initialization()
        law.exit_initialization()
        law._fmu.enterContinuousTimeMode()
        integral, worst = [0.0, 0.0, 0.0], 0.0
        inputs = [(f"planner.{a}[{i}]", f"{b}[{i}]") for a, b in (
            ("q", "setpoint"), ("qdot", "setpointRate"), ("qddot", "setpointAcceleration"))
            for i in AXES] + [(f"plant.{a}[{i}]", f"{b}[{i}]") for a, b in (
                ("theta", "measurement"), ("thetaDot", "measuredRate")) for i in AXES]
        outputs = tuple(f"u[{i}]" for i in AXES) + tuple(f"der(integral[{i}])" for i in AXES)
        for k in range(len(result.time)):
            law.set_values(tuple(b for _, b in inputs),
                           [result.columns[a][k] for a, _ in inputs])
            law._fmu.setContinuousStates((c_double * 3)(*integral), 3)
            values = law.get_values(outputs)
            got = [result.columns[f"ct.uSampled[{i}]"][k] for i in AXES]
            worst = max(worst, *(abs(a - b) for a, b in zip(got, values[:3])))
            integral = [x + 0.001 * r for x, r in zip(integral, values[3:])]
    finally:
        law.close()
    assert worst <= 1e-12, worst
    error = max(np.abs(result.columns[f"planner.q[{i}]"] - result.columns[f"plant.theta[{i}]"]).max()
                for i in AXES)
    assert 1e-9 < np.degrees(error) < 1e-6, np.degrees(error)


@pytest.mark.parametrize("value, build, message", [
    ('"1 kg"', "fmi3", "field 'sample_period' must be a time, got unit 'kg'"),
    ('"1 ms"', "fmi3-scalar", "field 'sample_period': the controller's FMI 3.0 build"),
    ('"1 ms"', None, "field 'sample_period': the sampled law runs in the FMI 3.0 build"),
])
def test_a_bad_sample_period_of_the_closed_loop_form_is_one_line(tmp_path, capsys, value,
                                                                 build, message):
    # The FMUs by name from a folder (--fmu-dir) whose fmi3/ holds the PID's FMI 3.0
    # build, or its scalar-only build (no clocks), or nothing.
    folder = tmp_path / "fmus"
    (folder / "fmi3").mkdir(parents=True)
    for model in ("Planner", "PID", "Pss3Plant"):
        shutil.copy(ROOT / "dist" / f"{model}.fmu", folder)
    if build is not None:
        shutil.copy(ROOT / "dist" / build / "PID.fmu", folder / "fmi3")
    path = tmp_path / "regulation.toml"
    path.write_text(f"sample_period = {value}\n"
                    + (ROOT / "scenarios" / "regulation.toml").read_text())
    assert cosim(["check", str(path), "--fmu-dir", str(folder)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"cosim: {path}: {message}"), err


def test_a_sweep_runs_the_sampled_closed_loop(tmp_path):
    # The sweep keeps the controller's FMI 3.0 build beside its copy of the FMI 2.0
    # file: the sampled run's metrics, the same as one run of the scenario's.
    import csv

    from robofmu.report import metrics
    from robofmu.sweep import load_spec, run_sweep
    text = (ROOT / "scenarios" / "path1_cubic_ct.toml").read_text()
    path = tmp_path / "sampled.toml"
    path.write_text(text.replace('step_size = "1 ms"', 'step_size = "1 ms"\nsample_period = "1 ms"'))
    spec = tmp_path / "spec.toml"
    spec.write_text(f'scenario = "{path}"\nname = "sampled"\n'
                    "[grid.'gains.omega']\nvalues = [30]\nunit = \"rad/s\"\n")
    outcome = run_sweep(load_spec(spec), tmp_path / "out", workers=0, progress=False,
                        plots=False)
    with open(outcome.table, newline="") as f:
        (row,) = list(csv.DictReader(f))
    assert row["status"] == "ok", row["reason"]
    single = run_arrays(load_scenario(path))
    expected = metrics({"time": single.time, **single.columns}).rms_error_deg
    assert float(row["rms_error_deg"]) == pytest.approx(expected, rel=1e-12)
    assert 1e-9 < expected < 1e-6  # sampled: the continuous law tracks to 1e-11 deg


@pytest.mark.parametrize("fmi3", [False, True])
def test_the_sampled_pid_on_the_regulation_equals_its_zero_order_hold_law(tmp_path, fmi3):
    # scenarios/regulation.toml (PID, gains by the design rule, Tf = 0 with rate inputs,
    # no output limits) with sample_period = "1 ms": the PID's FMI 3.0 build ticked, the
    # planner and the plant FMI 2.0, or (fmi3) their FMI 3.0 builds.
    # Truth: the zero-order-hold PID in numpy from the recorded planner and plant
    # outputs at the ticks (crates/fmu/control/src/sampled.rs's recursion written
    # again): u_k = Kp e_k + Ki I_k + Kd (qdot_k - thetaDot_k) + g_k with
    # e_k = q_k - theta_k, I_0 = 0, I_k+1 = I_k + Ts e_k; to 1e-12 N m.
    text = (ROOT / "scenarios" / "regulation.toml").read_text()
    path = tmp_path / "sampled_regulation.toml"
    path.write_text('sample_period = "1 ms"\n' + text)
    s = load_scenario(path)
    p = s.parameters["pid"]
    assert s.sample_period == {"pid": 0.001}
    assert all(p[f"Tf[{i}]"] == 0.0 and p[f"useRateInputs[{i}]"] for i in AXES)
    assert not any(p.get(f"limitOutput[{i}]", False) for i in AXES)
    c = run_arrays(s, fmi3=fmi3).columns
    worst = 0.0
    for i in AXES:
        e = c[f"planner.q[{i}]"] - c[f"plant.theta[{i}]"]
        integral = np.concatenate(([0.0], np.cumsum(0.001 * e[:-1])))
        u = (p[f"Kp[{i}]"] * e + p[f"Ki[{i}]"] * integral
             + p[f"Kd[{i}]"] * (c[f"planner.qdot[{i}]"] - c[f"plant.thetaDot[{i}]"])
             + c[f"plant.gravityCompensation[{i}]"])
        worst = max(worst, np.abs(c[f"pid.uSampled[{i}]"] - u).max())
    print(f"sampled PID: max |uSampled - zero-order hold| = {worst:.3g} N m")
    assert worst <= 1e-12, worst
    # The loop regulates: from 3 deg off to within 0.05 deg at the end.
    error = max(abs(c[f"planner.q[{i}]"][-1] - c[f"plant.theta[{i}]"][-1]) for i in AXES)
    assert np.degrees(error) < 0.05


def test_plan_switches_in_the_clocked_loop(tmp_path):
    # scenarios/three_axis_waypoints.toml (two segments: the planner reset and given
    # the next segment's parameters at the interior waypoint) with the sampled PID:
    # within the zero-order hold's deviation of the continuous PID in the native loop
    # (measured 2.6e-7 rad; tests/sampled_loop.rs: 1e-5 deg on its three-axis motion).
    text = (ROOT / "scenarios" / "three_axis_waypoints.toml").read_text()
    path = tmp_path / "sampled_waypoints.toml"
    path.write_text('sample_period = "1 ms"\n' + text)
    sampled = load_scenario(path)
    assert len(sampled.schedule) == 1
    continuous = run_arrays(load_scenario(ROOT / "scenarios" / "three_axis_waypoints.toml"))
    result = run_arrays(sampled)
    apart = max(np.abs(result.columns[f"plant.theta[{i}]"]
                       - continuous.columns[f"plant.theta[{i}]"]).max() for i in AXES)
    assert 1e-9 < apart < 1e-6, apart
