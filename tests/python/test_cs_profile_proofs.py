"""Two features of the FMI feature profiles (docs/profiles.md) proven on Co-Simulation
instances of the FMI 3.0 FMUs, through FMPy's FMU3Slave and FMU3Model:

- directional derivatives called on a Co-Simulation instance (fmi3GetDirectionalDerivative
  in Step Mode, FMU3Slave.getDirectionalDerivative) equal those of a Model Exchange
  instance at the same state and inputs (the PID), central differences of the outputs in
  the inputs on the same instance (both FMUs), and the PID's closed form;
- a variable communication step size: a run whose steps are random between 1e-4 and
  1e-2 s gives, at the times it shares with a fixed-step run, the fixed-step run's values
  (the PID: both equal to the closed form of its step response, which its steps follow
  exactly for held inputs; the plant: within its integrator's tolerance)."""

import math
import random
from ctypes import c_double

import pytest

from conftest import fmu3, fmu3_path
from test_fmi3_calls import initialize

# The PID's defaults (Kp 1, Ki 0.5, Kd 0.1, Tf 0.05 s, setpoints 1, 0.5 and -0.25,
# measurements 0): the step response from the zero state, u = e (Kp + Ki t + Kd/Tf
# exp(-t/Tf)), and du/dy = -(Kp + Kd/Tf) on the error path.
KP, KI, KD, TF = 1.0, 0.5, 0.1, 0.05
ERRORS = [1.0, 0.5, -0.25]


def pid_closed_form(t):
    return [e * (KP + KI * t + KD / TF * math.exp(-t / TF)) for e in ERRORS]


def column(fmu, unknown, known, element, size=3):
    """Column `element` of d unknown / d known (arrays of `size` elements each)."""
    seed = [1.0 if k == element else 0.0 for k in range(size)]
    return fmu.getDirectionalDerivative([fmu.vr[unknown]], [fmu.vr[known]], seed, size)


def central(fmu, unknown, known, element, h, size=3):
    """Central difference of `unknown` in element `element` of the input `known`, the
    input put back afterwards."""
    base = fmu.getFloat64([fmu.vr[known]], size)
    values = []
    for sign in (1, -1):
        moved = list(base)
        moved[element] += sign * h
        fmu.setFloat64([fmu.vr[known]], moved)
        values.append(fmu.getFloat64([fmu.vr[unknown]], size))
    fmu.setFloat64([fmu.vr[known]], base)
    return [(a - b) / (2 * h) for a, b in zip(*values)]


def test_pid_directional_derivatives_on_a_co_simulation_instance(tmp_path):
    # Expected: the Model Exchange instance's, at the CS instance's state (integral and
    # filter read from it, set as continuous states) and inputs; central differences
    # (u is linear in the inputs: exact up to rounding, 1e-9); the closed form
    # du/dy = -(Kp + Kd/Tf) on the diagonal, 0 off it (the channels are independent).
    cs = fmu3(fmu3_path("PID"), tmp_path / "cs")
    initialize(cs)
    cs.setFloat64([cs.vr["measurement"]], [0.1, -0.2, 0.3])
    t = 0.0
    for h in (0.01, 0.003, 0.02):
        cs.doStep(t, h)
        t += h
    me = fmu3(fmu3_path("PID"), tmp_path / "me", model_exchange=True)
    initialize(me)
    me.enterContinuousTimeMode()
    me.setFloat64([me.vr["measurement"]], [0.1, -0.2, 0.3])
    states = cs.getFloat64([cs.vr["integral"], cs.vr["filter"]], 6)
    assert any(x != 0.0 for x in states)
    me.setContinuousStates((c_double * 6)(*states), 6)
    assert me.getFloat64([me.vr["u"]], 3) == cs.getFloat64([cs.vr["u"]], 3)
    for known in ("measurement", "setpoint", "feedforward"):
        for element in range(3):
            got = column(cs, "u", known, element)
            assert got == column(me, "u", known, element), (known, element)
            assert got == pytest.approx(central(cs, "u", known, element, 1e-4),
                                        rel=1e-9, abs=1e-9), (known, element)
    for element in range(3):
        expected = [-(KP + KD / TF) if k == element else 0.0 for k in range(3)]
        assert column(cs, "u", "measurement", element) == pytest.approx(expected, rel=1e-14)
    cs.freeInstance()
    me.freeInstance()


def test_plant_directional_derivatives_on_a_co_simulation_instance(tmp_path):
    # Expected: central differences of the outputs with direct feedthrough of the
    # generalized force (omegaDot, thetaDot's rate is a state: 0) on the same
    # instance, at a moving state; omegaDot is affine in the force (the dynamics are
    # linear in it), so the difference is exact up to rounding (1e-7 relative).
    cs = fmu3(fmu3_path("Pss3Plant"), tmp_path / "plant")
    cs.setFloat64([cs.vr["omega0"]], [0.3, -0.5, 0.8])
    initialize(cs)
    cs.setFloat64([cs.vr["generalizedForceCommand"]], [0.5, -0.2, 0.1])
    t = 0.0
    for h in (0.01, 0.004):
        cs.doStep(t, h)
        t += h
    for unknown in ("omegaDot", "theta"):
        for element in range(3):
            got = column(cs, unknown, "generalizedForceCommand", element)
            fd = central(cs, unknown, "generalizedForceCommand", element, 1e-3)
            assert got == pytest.approx(fd, rel=1e-7, abs=1e-9), (unknown, element)
            if unknown == "theta":
                assert got == [0.0, 0.0, 0.0]  # a state: no direct feedthrough
            else:
                assert any(abs(x) > 1e-3 for x in got)
    cs.freeInstance()


def random_steps(seed, stop, grid):
    """Steps between 1e-4 and 1e-2 s that land on every multiple of `grid` up to
    `stop` (the last step of each grid interval takes what is left of it)."""
    rng = random.Random(seed)
    steps = []
    for _ in range(round(stop / grid)):
        left = grid
        while left > 1e-2 + 1e-4 or left > 2e-4 and rng.random() < 0.8:
            h = rng.uniform(1e-4, min(1e-2, left - 1e-4))
            steps.append(h)
            left -= h
        steps.append(left)
    return steps


def run(fmu, steps, names, sizes):
    """(time, values of `names`) after each step, the time summed as a master sums it."""
    t, out = 0.0, []
    for h in steps:
        fmu.doStep(t, h)
        t += h
        out.append((t, fmu.getFloat64([fmu.vr[n] for n in names], sizes)))
    return out


def test_pid_variable_steps_give_the_fixed_step_values_and_the_closed_form(tmp_path):
    # Expected: the closed form of the step response at every step's end (the PID's step
    # is exact for held inputs, whatever its size), to 1e-12; at the shared times
    # (every 20 ms), the fixed-step run's values to 1e-12.
    steps = random_steps(43, 0.4, 0.02)
    assert min(steps) >= 1e-4 - 1e-15 and max(steps) <= 1e-2 + 1e-4 and len(steps) > 80
    runs = []
    for name, sequence in (("variable", steps), ("fixed", [0.02] * 20)):
        fmu = fmu3(fmu3_path("PID"), tmp_path / name)
        initialize(fmu)
        runs.append(run(fmu, sequence, ["u"], 3))
        fmu.freeInstance()
    variable, fixed = runs
    for t, u in variable:
        assert u == pytest.approx(pid_closed_form(t), rel=1e-12, abs=1e-12), t
    shared = {round(t, 9): u for t, u in variable}
    for t, u in fixed:
        assert shared[round(t, 9)] == pytest.approx(u, rel=1e-12, abs=1e-12), t


def test_plant_variable_steps_give_the_fixed_step_values(tmp_path):
    # Expected: at the shared times (every 10 ms over 0.1 s) the fixed-step run's
    # angles and rates, within the integrator's tolerance (1e-10 here): 1e-8 rad and
    # rad/s.
    steps = random_steps(7, 0.1, 0.01)
    runs = []
    for name, sequence in (("variable", steps), ("fixed", [0.01] * 10)):
        fmu = fmu3(fmu3_path("Pss3Plant"), tmp_path / name)
        fmu.setFloat64([fmu.vr["omega0"]], [0.3, -0.5, 0.8])
        fmu.setFloat64([fmu.vr["tolerance"]], [1e-10])
        initialize(fmu)
        fmu.setFloat64([fmu.vr["generalizedForceCommand"]], [0.5, -0.2, 0.1])
        runs.append(run(fmu, sequence, ["theta", "omega"], 6))
        fmu.freeInstance()
    variable, fixed = runs
    shared = {round(t, 9): x for t, x in variable}
    worst = max(abs(a - b) for t, x in fixed for a, b in zip(shared[round(t, 9)], x))
    print(f"plant: max difference variable vs fixed steps {worst:.3g}")
    assert worst <= 1e-8, worst
    assert fixed[-1][1] != fixed[0][1]  # it moved
