"""The sampled PID law as an FMI 3.0 clocked partition of the PID FMU, driven by FMPy's
low-level classes as the computed-torque law is in test_clocked_controller.py (whose
helpers this file uses): FMU3Slave with eventModeUsed and earlyReturnAllowed
(Co-Simulation with clock information) and FMU3Model (Model Exchange), the loop closed
on the FMI 3.0 plant (Pss3Plant in Co-Simulation, stepped at 1 ms) from its start pose
towards setpoints 0.5, -0.5 and 1 deg away.

The three channels take the law's three paths: channel 1 the filtered error with a
feedforward, channel 2 the rate inputs (the plant's Euler-angle rates, filtered),
channel 3 a tight output limit that the loop hits (conditional integration).

Expected values: the zero-order-hold recursion written here from the law's equations
(docs/profiles.md, `robofmu_control::sampled`), not from the FMU: at tick k, with
e = r - y and w the filter's input (e, or setpointRate - measuredRate),
  u_raw = Kp e + Ki I + D + ff, D = Kd (e - x) / Tf (D = Kd x on the rate path),
  u = u_raw clamped to [uMin, uMax] where limited,
  I <- I + Ts e unless the output is at a limit and Ki e pushes it further out,
  x <- w + (x - w) exp(-Ts / Tf),
the exact solution over one period of the continuous law for inputs held. The
clocked output `uSampled` must equal it to 1e-12 at every tick, in both interfaces."""

import math

import pytest
from fmpy.fmi3 import FMU3Model, FMU3Slave

from test_clocked_controller import interval_fraction, open_fmu, open_plant, to_next_tick

TICKS = 200  # 0.2 s at 1 ms
PERIOD = 1e-3
OFFSET = [math.radians(d) for d in (0.5, -0.5, 1.0)]
GAINS = {"Kp": [40.0, 30.0, 40.0], "Ki": [20.0, 10.0, 20.0], "Kd": [2.0, 3.0, 2.0],
         "Tf": [0.01, 0.02, 0.01], "uMin": [-1.0, -1.0, -0.02], "uMax": [1.0, 1.0, 0.02]}
LIMITED = [False, False, True]
RATES = [False, True, False]
FEEDFORWARD = [0.01, 0.0, 0.0]


class ZeroOrderHold:
    """The sampled PID of the module docstring, channel by channel."""

    def __init__(self):
        self.integral = [0.0] * 3
        self.filter = [0.0] * 3

    def tick(self, setpoint, y, y_rate):
        u = []
        for c in range(3):
            kp, ki, kd, tf = (GAINS[n][c] for n in ("Kp", "Ki", "Kd", "Tf"))
            e = setpoint[c] - y[c]
            w = -y_rate[c] if RATES[c] else e  # setpointRate 0
            d = kd * self.filter[c] if RATES[c] else kd * (e - self.filter[c]) / tf
            raw = kp * e + ki * self.integral[c] + d + FEEDFORWARD[c]
            lo, hi = GAINS["uMin"][c], GAINS["uMax"][c]
            out = min(max(raw, lo), hi) if LIMITED[c] else raw
            stopped = LIMITED[c] and ((raw >= hi and ki * e > 0) or (raw <= lo and ki * e < 0))
            if not stopped:
                self.integral[c] += PERIOD * e
            self.filter[c] = w + (self.filter[c] - w) * math.exp(-PERIOD / tf)
            u.append(out)
        return u


def run_pid_loop(tmp_path, interface):
    """Ticks the clocked PID on the plant for TICKS periods: the largest |uSampled -
    reference|, whether channel 3 hit its limit, the controller and the time after the
    last tick."""
    cls = FMU3Slave if interface == "CoSimulation" else FMU3Model
    plant, pvr = open_plant(tmp_path)
    target = [a + b for a, b in zip(plant.getFloat64([pvr["theta"]], 3), OFFSET)]
    ctrl, vr = open_fmu(tmp_path, "PID", cls, f"pid_{interface}")
    if cls is FMU3Slave:
        ctrl.instantiate(eventModeUsed=True, earlyReturnAllowed=True)
    else:
        ctrl.instantiate()
    for name, values in GAINS.items():
        ctrl.setFloat64([vr[name]], values)
    ctrl.setBoolean([vr["limitOutput"]], LIMITED)
    ctrl.setBoolean([vr["useRateInputs"]], RATES)
    ctrl.setFloat64([vr["setpoint"]], target)
    ctrl.setFloat64([vr["feedforward"]], FEEDFORWARD)
    clock = vr["sampleClock"]
    ctrl.enterInitializationMode(startTime=0.0)
    # The fixed clock's interval, read in Initialization Mode: 1/1000 s, changed (2).
    assert interval_fraction(ctrl, clock) == (1, 1000, 2)
    ctrl.exitInitializationMode()  # Event Mode at t = 0, tick 0
    reference = ZeroOrderHold()
    worst, saturated, t = 0.0, False, 0.0
    for k in range(TICKS):
        theta = plant.getFloat64([pvr["theta"]], 3)
        theta_dot = plant.getFloat64([pvr["thetaDot"]], 3)
        ctrl.setFloat64([vr["measurement"]], theta)
        ctrl.setFloat64([vr["measuredRate"]], theta_dot)
        ctrl.setClock([clock], [True])
        ctrl.updateDiscreteStates()
        u = ctrl.getFloat64([vr["uSampled"]], 3)
        expected = reference.tick(target, theta, theta_dot)
        worst = max(worst, *(abs(a - b) for a, b in zip(u, expected)))
        saturated |= abs(u[2]) == GAINS["uMax"][2]
        plant.setFloat64([pvr["generalizedForceCommand"]], u)
        plant.doStep(t, PERIOD)
        t = to_next_tick(ctrl, t, k)
    moved = [abs(a - b) for a, b in zip(plant.getFloat64([pvr["theta"]], 3), target)]
    return worst, saturated, moved, ctrl, vr, t


@pytest.mark.parametrize("interface", ["CoSimulation", "ModelExchange"])
def test_clocked_pid_follows_the_zero_order_hold_law(tmp_path, interface):
    worst, saturated, moved, ctrl, vr, t = run_pid_loop(tmp_path, interface)
    print(f"{interface}: max |uSampled - reference| = {worst:.3g}; distance to the "
          f"setpoints after 0.2 s {moved}")
    assert worst <= 1e-12, worst
    # Channel 3 hit its limit (the conditional integration was exercised), and the
    # loop moved every angle towards its setpoint (the comparison is not of zeros).
    assert saturated
    assert all(m < abs(o) for m, o in zip(moved, OFFSET)), moved
    # The continuous output is not the sampled one (two laws, not one value).
    u = ctrl.getFloat64([vr["u"]], 3)
    assert u != ctrl.getFloat64([vr["uSampled"]], 3)
    # FMU states carry the sampled law (its state and held outputs; the layer its
    # period): serialized at tick 200, ticked, restored from the bytes and ticked
    # again, uSampled is the same bit for bit (without the law's state the second
    # tick would start from the state after the first).
    data = ctrl.serializeFMUState(ctrl.getFMUState())
    ctrl.setClock([vr["sampleClock"]], [True])
    ctrl.updateDiscreteStates()
    first = ctrl.getFloat64([vr["uSampled"]], 3)
    ctrl.setFMUState(ctrl.deserializeFMUState(data))
    ctrl.setClock([vr["sampleClock"]], [True])
    ctrl.updateDiscreteStates()
    assert ctrl.getFloat64([vr["uSampled"]], 3) == first
    if interface == "CoSimulation":
        # Restartable early return: a step of 2.5 ms returns early at the next tick,
        # and the step after it starts from there.
        ctrl.enterStepMode()
        event, _terminate, early, last = ctrl.doStep(t, 2.5e-3)
        assert (event, early, last) == (True, True, (TICKS + 1) / 1000)
        ctrl.enterEventMode()
        ctrl.setClock([vr["sampleClock"]], [True])
        ctrl.updateDiscreteStates()
        ctrl.enterStepMode()
        assert ctrl.doStep(last, 0.5e-3)[3] == last + 0.5e-3
