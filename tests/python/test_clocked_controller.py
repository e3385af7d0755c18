"""The sampled computed-torque law as an FMI 3.0 clocked partition, driven by FMPy's
low-level classes (FMU3Slave, FMU3Model: their setClock, getIntervalFraction,
updateDiscreteStates, enterEventMode and doStep calls), closing the loop with the FMI
3.0 plant (Pss3Plant in Co-Simulation, stepped at 1 ms) from the start pose towards
the FMU's default setpoint (0.5, -0.5 and 1 deg away).

The controller ticks every 1 ms on its input clock `sampleClock`: in Co-Simulation with
clock information (eventModeUsed, earlyReturnAllowed) and in Model Exchange (the test
sets the time to each tick; the plant stays in Co-Simulation). Expected values: the
zero-order-hold law computed here from a second formulation, the continuous form of
the same FMU in Model Exchange used as a function: at tick k its output `u` at the
sampled inputs and the error integral I_k set as its continuous state, and
I_k+1 = I_k + Ts der(integral) (the exact integral of the held error over one period,
robofmu_dynamics::computed_torque::sampled). The clocked output `uSampled` must equal
that recursion to 1e-12 N m at every tick, in both interfaces; the ticks fall on
k counter / resolution exactly (the interval read as the fraction 1/1000)."""

from ctypes import c_double, c_int, c_uint64

import pytest
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi3 import FMU3Model, FMU3Slave, fmi3ValueReference

from conftest import fmu3_path

TICKS = 200  # 0.2 s at 1 ms
PERIOD = 1e-3


def open_fmu(tmp_path, model, cls, name):
    directory = extract(fmu3_path(model), unzipdir=str(tmp_path / name))
    description = read_model_description(directory)
    interface = description.coSimulation if cls is FMU3Slave else description.modelExchange
    fmu = cls(guid=description.guid, unzipDirectory=directory,
              modelIdentifier=interface.modelIdentifier)
    vr = {v.name: v.valueReference for v in description.modelVariables}
    return fmu, vr


class Reference:
    """The zero-order-hold law from the continuous form (see the module docstring)."""

    def __init__(self, tmp_path):
        self.fmu, self.vr = open_fmu(tmp_path, "ComputedTorque", FMU3Model, "reference")
        self.fmu.instantiate()
        self.fmu.enterInitializationMode(startTime=0.0)
        self.fmu.exitInitializationMode()
        self.fmu.enterContinuousTimeMode()
        self.integral = [0.0, 0.0, 0.0]

    def tick(self, theta, theta_dot):
        """u_k at the sampled measurement and I_k; I_k+1 for the next tick."""
        self.fmu.setFloat64([self.vr["measurement"]], theta)
        self.fmu.setFloat64([self.vr["measuredRate"]], theta_dot)
        self.fmu.setContinuousStates((c_double * 3)(*self.integral), 3)
        u = self.fmu.getFloat64([self.vr["u"]], 3)
        rate = self.fmu.getFloat64([self.vr["der(integral)"]], 3)
        self.integral = [i + PERIOD * r for i, r in zip(self.integral, rate)]
        return u


def open_plant(tmp_path):
    plant, vr = open_fmu(tmp_path, "Pss3Plant", FMU3Slave, "plant")
    plant.instantiate()
    plant.enterInitializationMode(startTime=0.0)
    plant.exitInitializationMode()
    return plant, vr


def interval_fraction(fmu, clock):
    counters, resolutions, qualifiers = (c_uint64 * 1)(), (c_uint64 * 1)(), (c_int * 1)()
    fmu.getIntervalFraction((fmi3ValueReference * 1)(clock), counters, resolutions, qualifiers)
    return counters[0], resolutions[0], qualifiers[0]


def to_next_tick(ctrl, t, k):
    """Takes the controller from tick k at time t to Event Mode at tick k + 1 (its
    time, returned, is (k + 1) counter / resolution); in Co-Simulation the step must end
    exactly there and ask for Event Mode."""
    next_tick = (k + 1) / 1000
    if isinstance(ctrl, FMU3Slave):
        ctrl.enterStepMode()
        event, _terminate, early, last = ctrl.doStep(t, PERIOD)
        assert (event, early, last) == (True, False, next_tick), k
    else:
        ctrl.enterContinuousTimeMode()
        ctrl.setTime(next_tick)
    ctrl.enterEventMode()
    return next_tick


def run_loop(tmp_path, interface):
    """Ticks the clocked controller on the plant for TICKS periods; the largest
    |uSampled - reference| over the ticks, and the controller's time after the last."""
    cls = FMU3Slave if interface == "CoSimulation" else FMU3Model
    ctrl, vr = open_fmu(tmp_path, "ComputedTorque", cls, f"ctrl_{interface}")
    if cls is FMU3Slave:
        ctrl.instantiate(eventModeUsed=True, earlyReturnAllowed=True)
    else:
        ctrl.instantiate()
    clock = vr["sampleClock"]
    ctrl.setFloat64([vr["samplePeriod"]], [PERIOD])
    ctrl.enterInitializationMode(startTime=0.0)
    # A fixed clock's interval, read in Initialization Mode: 1/1000 s, changed (2).
    assert interval_fraction(ctrl, clock) == (1, 1000, 2)
    ctrl.exitInitializationMode()  # Event Mode at t = 0, tick 0
    plant, pvr = open_plant(tmp_path)
    reference = Reference(tmp_path)
    worst, t = 0.0, 0.0
    for k in range(TICKS):
        theta = plant.getFloat64([pvr["theta"]], 3)
        theta_dot = plant.getFloat64([pvr["thetaDot"]], 3)
        ctrl.setFloat64([vr["measurement"]], theta)
        ctrl.setFloat64([vr["measuredRate"]], theta_dot)
        ctrl.setClock([clock], [True])
        ctrl.updateDiscreteStates()
        u = ctrl.getFloat64([vr["uSampled"]], 3)
        expected = reference.tick(theta, theta_dot)
        worst = max(worst, *(abs(a - b) for a, b in zip(u, expected)))
        plant.setFloat64([pvr["generalizedForceCommand"]], u)
        plant.doStep(t, PERIOD)
        t = to_next_tick(ctrl, t, k)
    return worst, ctrl, vr, t, plant, pvr


@pytest.mark.parametrize("interface", ["CoSimulation", "ModelExchange"])
def test_clocked_computed_torque_follows_the_zero_order_hold_law(tmp_path, interface):
    worst, ctrl, vr, t, plant, pvr = run_loop(tmp_path, interface)
    print(f"{interface}: max |uSampled - reference| = {worst:.3g} N m")
    assert worst <= 1e-12, worst
    # The loop moved: the plant left its start pose towards the setpoint (so the
    # comparison is not one of zeros), and the held output is not the continuous one.
    theta = plant.getFloat64([pvr["theta"]], 3)
    assert abs(theta[0]) > 1e-5, theta
    held = ctrl.getFloat64([vr["uSampled"]], 3)
    assert any(abs(x) > 1e-3 for x in held), held
    if interface == "CoSimulation":
        # Restartable early return: a step of 2.5 ms returns early at the next tick,
        # and the step after it starts from there.
        ctrl.setClock([vr["sampleClock"]], [True])
        ctrl.updateDiscreteStates()
        ctrl.enterStepMode()
        event, _terminate, early, last = ctrl.doStep(t, 2.5e-3)
        assert (event, early, last) == (True, True, (TICKS + 1) / 1000)
        ctrl.enterEventMode()
        ctrl.setClock([vr["sampleClock"]], [True])
        ctrl.updateDiscreteStates()
        ctrl.enterStepMode()
        assert ctrl.doStep(last, 0.5e-3)[3] == last + 0.5e-3


def test_ticks_are_exact_after_a_million_periods_and_only_ticks_are_accepted(tmp_path):
    """Tick 10^6 of the 1/1000 s clock is t = 1000 s exactly (10^6 counter /
    resolution); a time summed from 10^6 periods (1.7e-8 s off) is no tick and
    fmi3SetClock refuses it with fmi3Error (3), as it refuses a clock set outside Event
    Mode."""
    summed = sum([PERIOD] * 1_000_000)
    assert abs(summed - 1000.0) > 1e-9
    for t, accepted in [(1000.0, True), (summed, False)]:
        ctrl, vr = open_fmu(tmp_path, "ComputedTorque", FMU3Model, f"me_{accepted}")
        ctrl.instantiate()
        ctrl.enterInitializationMode(startTime=0.0)
        ctrl.exitInitializationMode()
        ctrl.enterContinuousTimeMode()
        ctrl.setTime(t)
        ctrl.enterEventMode()
        if accepted:
            ctrl.setClock([vr["sampleClock"]], [True])
            ctrl.updateDiscreteStates()
            ctrl.enterContinuousTimeMode()
            with pytest.raises(FMICallException) as refused:
                ctrl.setClock([vr["sampleClock"]], [True])  # Continuous-Time Mode
            assert refused.value.status == 3
        else:
            with pytest.raises(FMICallException) as refused:
                ctrl.setClock([vr["sampleClock"]], [True])
            assert refused.value.status == 3


def test_the_fmus_that_return_early_at_ticks_declare_it():
    # Expected from the FMI 3.0 standard (CoSimulation attribute mightReturnEarlyFromDoStep:
    # an FMU may return early only where it declares it): the clocked controllers end a
    # step at a tick when earlyReturnAllowed (the CoSimulation tests above), the plant at
    # an end-stop contact; the Planner never returns early.
    for model, early in [("ComputedTorque", True), ("PID", True), ("Pss3Plant", True),
                         ("Planner", False)]:
        co_simulation = read_model_description(fmu3_path(model)).coSimulation
        assert co_simulation.mightReturnEarlyFromDoStep is early, model
