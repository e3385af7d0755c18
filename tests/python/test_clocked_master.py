"""Our master ticks a clocked FMU (robofmu.clocked): the sampled computed-torque law of
ComputedTorque's FMI 3.0 build (input clock `sampleClock`, clocked output `uSampled`)
on the FMI 3.0 plant in Co-Simulation, through a scenario's `sample_period`.

Expected values: the zero-order-hold law from a second formulation, computed here from
the plant's recorded outputs at the ticks (test_clocked_controller.Reference: the
continuous form of the same FMU in Model Exchange used as a function, the sampled
error integral advanced by Ts der(integral) in Python), held between ticks: every
recorded `uSampled` equal to it to 1e-12 N m. Tick times: k counter / resolution from
integers, against numpy's k / 1000 (each one rounding); the bad inputs of the new field:
one line naming the file and the field, exit 2."""

from __future__ import annotations

import sys
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


def scenario(tmp_path: Path, step: float = 0.001, stop: float = 0.2, period="0.001",
             ct: str = "fmi3/ComputedTorque", extra: str = "") -> Path:
    """The loop ct -> plant, ct ticked every `period` s (the text of the field)."""
    path = tmp_path / "sampled.toml"
    path.write_text(f'name = "sampled"\nstop_time = {stop}\nstep_size = {step}\n'
                    f'order = ["ct", "plant"]\n{extra}\n'
                    f'[fmus]\nct = "{ct}"\nplant = "fmi3/Pss3Plant"\n\n'
                    f'[sample_period]\nct = {period}\n\n' + CONNECTIONS)
    return path


@pytest.mark.parametrize("step, stop", [(0.001, 0.2), (0.0005, 0.1)])
def test_the_sampled_law_equals_the_zero_order_hold_reference(tmp_path, step, stop):
    result = run_arrays(load_scenario(scenario(tmp_path, step, stop)))
    every = round(0.001 / step)  # communication steps per tick
    assert len(result.time) == round(stop / step) + 1
    reference = Reference(tmp_path)
    worst, held = 0.0, None
    for k in range(len(result.time)):
        if k % every == 0:  # a tick: the law at the plant's outputs now
            theta = [result.columns[f"plant.theta[{i}]"][k] for i in AXES]
            rate = [result.columns[f"plant.thetaDot[{i}]"][k] for i in AXES]
            held = reference.tick(theta, rate)
        got = [result.columns[f"ct.uSampled[{i}]"][k] for i in AXES]
        worst = max(worst, *(abs(a - b) for a, b in zip(got, held)))
    print(f"step {step} s: max |uSampled - zero-order hold| = {worst:.3g} N m")
    assert worst <= 1e-12, worst
    # The loop moved (the comparison is not one of zeros) and the output is held: with
    # two steps per tick, each odd row repeats the tick's value before it.
    assert abs(result.columns["plant.theta[1]"][-1]) > 1e-5
    u = result.columns["ct.uSampled[3]"]
    assert np.abs(u).max() > 1.0
    if every == 2:
        assert np.array_equal(u[1::2], u[0:-1:2]) and np.all(u[2::2] != u[1::2])


def test_ticks_are_exact_after_a_million_periods_and_the_fmu_takes_the_clock_there(tmp_path):
    # Truth: k / 1000 rounded once (numpy divides each integer k, IEEE); a sum of 10^6
    # periods is 1.7e-8 s off, which the FMU refuses as no tick.
    times = grid(0.0, Fraction(1, 1000), 0, 1_000_001)
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
    ({"extra": 'coupling = "gauss-seidel"'}, "field 'coupling': a scenario with sample_period "
                                             "runs with coupling = \"sampled\""),
])
def test_a_bad_sample_period_is_one_line(tmp_path, capsys, change, message):
    path = scenario(tmp_path, stop=0.01, **change)
    assert cosim(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"cosim: {path}: "), err
    assert message in err, err
