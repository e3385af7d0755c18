"""Output derivatives of the real .fmu files through FMPy: fmi2GetRealOutputDerivatives
(FMU2Slave.getRealOutputDerivatives) and fmi3GetOutputDerivatives (FMU3Slave
.getOutputDerivatives for scalars, FMU3Slave's ctypes function for arrays and bad
arguments), against the textbook planner polynomial, central differences of the
plant's and the PID's outputs along their co-simulation trajectories, and the closed
form of the PID's step response."""

import math
import shutil
from ctypes import c_double, c_int, c_uint32

import pytest
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave

from conftest import MODELS, fmu3, fmu3_path, fmu_path
from test_fmi3_calls import ERROR, OK, initialize, last_message


def quintic(dq, duration, tau):
    """q - q0 and its derivatives 1..4 of the rest-to-rest quintic
    q0 + dq (10 s^3 - 15 s^4 + 6 s^5), s = tau / T (textbook closed form)."""
    s = tau / duration
    d = [dq * (10 * s**3 - 15 * s**4 + 6 * s**5),
         dq * (30 * s**2 - 60 * s**3 + 30 * s**4),
         dq * (60 * s - 180 * s**2 + 120 * s**3),
         dq * (60 - 360 * s + 360 * s**2),
         dq * (-360 + 720 * s)]
    return [v / duration**n for n, v in enumerate(d)]


def open_slave(tmp_path, model, fmi3=False):
    """An initialized Co-Simulation slave of the real FMU, its description and unzip
    directory (delete it after freeing the instance)."""
    directory = extract(fmu3_path(model) if fmi3 else fmu_path(model),
                        unzipdir=str(tmp_path / model))
    description = read_model_description(directory)
    cls = FMU3Slave if fmi3 else FMU2Slave
    fmu = cls(guid=description.guid, unzipDirectory=directory,
              modelIdentifier=description.coSimulation.modelIdentifier)
    fmu.instantiate()
    if not fmi3:
        fmu.setupExperiment(startTime=0.0)
    return fmu, description, directory


def close(fmu, directory):
    fmu.terminate()
    fmu.freeInstance()
    shutil.rmtree(directory, ignore_errors=True)


def refs(description):
    return {v.name: v.valueReference for v in description.modelVariables}


def test_descriptions_declare_the_orders():
    # Expected: Planner, Pss3Plant and the PID provide order 2 for every continuous
    # Real output, ComputedTorque none (the attribute left out: default 0).
    for model, order in [("Planner", 2), ("Pss3Plant", 2), ("PID", 2), ("ComputedTorque", 0)]:
        for path in (fmu_path(model), fmu3_path(model)):
            assert read_model_description(path).coSimulation.maxOutputDerivativeOrder == order


def test_fmi2_planner_derivatives_are_the_textbook_polynomial(tmp_path):
    # Default experiment: quintic rest-to-rest from q0 = 0 to qf = (0.5, -0.3, 0.8)
    # over t0 = 0 .. tf = 2 s. Expected: `quintic` at t = 0.75 s.
    fmu, description, directory = open_slave(tmp_path, "Planner")
    vr = refs(description)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    t = 0.0
    for _ in range(3):
        fmu.doStep(t, 0.25)
        t += 0.25
    for axis, dq in enumerate([0.5, -0.3, 0.8], start=1):
        names = [f"q[{axis}]", f"q[{axis}]", f"qdot[{axis}]", f"qdot[{axis}]",
                 f"qddot[{axis}]", f"qddot[{axis}]"]
        got = fmu.getRealOutputDerivatives([vr[n] for n in names], [1, 2, 1, 2, 1, 2])
        want = quintic(dq, 2.0, t)
        expected = [want[1], want[2], want[2], want[3], want[3], want[4]]
        assert got == pytest.approx(expected, rel=1e-12, abs=1e-12)
    close(fmu, directory)


# A tilted plant moving under constant actuator forces, integrator tolerance 1e-12
# (the values of fmus/pss3-plant/tests/output_derivatives.rs). By t = 0.15 s actuator 1
# is in its upper end stop.
PLANT_START = {"theta0": [0.05, -0.04, 2.35], "omega0": [0.3, -0.5, 0.8],
               "actuatorForce": [20.0, -5.0, 12.0], "tolerance": [1e-12]}


def start_moving_plant(fmu, vr, fmi3):
    """Initializes the plant with PLANT_START (FMI 3.0: arrays; FMI 2.0: scalars)."""
    fmu.enterInitializationMode()
    for base, values in PLANT_START.items():
        if fmi3:
            fmu.setFloat64([vr[base]], values)
        elif len(values) == 1:
            fmu.setReal([vr[base]], values)
        else:
            fmu.setReal([vr[f"{base}[{i}]"] for i in range(1, 4)], values)
    fmu.exitInitializationMode()


def output_derivatives(fmu, names, orders, n_values):
    """fmi3GetOutputDerivatives of the variables `names` with `orders` through FMPy's
    ctypes function (FMPy's getOutputDerivatives reads one value per variable): the
    status and the n_values values (arrays serialized element by element, pair by pair)."""
    vrs = (c_uint32 * len(names))(*[fmu.vr[n] for n in names])
    values = (c_double * n_values)()
    status = fmu.dll.fmi3GetOutputDerivatives(fmu.component, vrs, len(names),
                                              (c_int * len(orders))(*orders), values, n_values)
    return status, list(values)


class PlantCalls:
    """The moving plant through FMPy: FMU2Slave (FMI 2.0) or FMU3Slave (FMI 3.0, arrays):
    values and output derivatives of every Real output, element by element."""

    def __init__(self, tmp_path, fmi3):
        self.fmi3 = fmi3
        if fmi3:
            self.fmu = fmu3(fmu3_path("Pss3Plant"), tmp_path / "Pss3Plant3")
            for base, values in PLANT_START.items():
                self.fmu.setFloat64([self.fmu.vr[base]], values)
            initialize(self.fmu)
            variables = self.fmu.description.modelVariables
        else:
            self.fmu, description, self.directory = open_slave(tmp_path, "Pss3Plant")
            self.vr = refs(description)
            start_moving_plant(self.fmu, self.vr, fmi3=False)
            variables = description.modelVariables
        real = ("Float64", "Real")
        self.names = [v.name for v in variables if v.causality == "output" and v.type in real]
        self.sizes = [v.shape[0] if fmi3 and v.shape else 1 for v in variables
                      if v.name in self.names]
        self.elements = [f"{n}[{i}]" if size > 1 else n
                         for n, size in zip(self.names, self.sizes)
                         for i in range(1, size + 1)]

    def values(self):
        if self.fmi3:
            return self.fmu.getFloat64([self.fmu.vr[n] for n in self.names], sum(self.sizes))
        return self.fmu.getReal([self.vr[n] for n in self.names])

    def derivatives(self, order):
        """Every output's derivative of `order`; the status must be OK."""
        orders = [order] * len(self.names)
        if self.fmi3:
            status, values = output_derivatives(self.fmu, self.names, orders, sum(self.sizes))
            assert status == OK, last_message(self.fmu)
            return values
        return self.fmu.getRealOutputDerivatives([self.vr[n] for n in self.names], orders)

    def step(self, t, h):
        self.fmu.doStep(t, h)

    def close(self):
        if self.fmi3:
            self.fmu.freeInstance()
        else:
            close(self.fmu, self.directory)


def central(order, minus, at, plus, step):
    if order == 1:
        return (plus - minus) / (2 * step)
    return (plus - 2 * at + minus) / step**2


def trajectory_mismatches(plant, order, delta):
    """(element, t, derivative, difference, tolerance) where the derivative of `order`
    misses the central difference of step delta along the CS trajectory by more than
    the tolerance: |difference(delta) - difference(2 delta)| (the truncation error of
    difference(delta) is a third of it) plus the values' error (the integrator's,
    tolerance 1e-12, taken as 1e-11 relative) amplified by the difference."""
    amplification = 1 / delta if order == 1 else 4 / delta**2
    mismatches, checked, t = [], 0, 0.0
    for point in (0.02, 0.05, 0.1, 0.15):
        plant.step(t, point - 2 * delta - t)
        y = []
        for k in range(-2, 3):
            y.append(plant.values())
            if k == 0:
                d = plant.derivatives(order)
            if k < 2:
                plant.step(point + k * delta, delta)
        t = point + 2 * delta
        for i, name in enumerate(plant.elements):
            fine = central(order, y[1][i], y[2][i], y[3][i], delta)
            coarse = central(order, y[0][i], y[2][i], y[4][i], 2 * delta)
            tolerance = abs(fine - coarse) + 1e-11 * (1 + abs(y[2][i])) * amplification
            checked += 1
            if abs(d[i] - fine) > tolerance:
                mismatches.append((name, point, d[i], fine, tolerance))
    return mismatches, checked


@pytest.mark.parametrize("fmi3", [False, True], ids=["fmi2", "fmi3"])
@pytest.mark.parametrize("delta, order", [(1e-5, 1), (1e-4, 2)])
def test_plant_derivatives_of_every_output_match_central_differences(tmp_path, fmi3,
                                                                       delta, order):
    # Expected: central differences of every Real output over CS steps of delta along
    # the plant's own trajectory (order 1: delta = 1e-5 s, order 2: 1e-4 s); the
    # tolerance is derived from the step (see trajectory_mismatches).
    plant = PlantCalls(tmp_path, fmi3)
    mismatches, checked = trajectory_mismatches(plant, order, delta)
    plant.close()
    assert mismatches == []
    # 9 vector outputs of 3 elements and 7 scalar ones, at 4 points.
    assert checked == (9 * 3 + 7) * 4


def test_fmi2_refusals_are_errors(tmp_path):
    # Not an output (a parameter), order 3 (above maxOutputDerivativeOrder): fmi2Error.
    fmu, description, directory = open_slave(tmp_path, "Pss3Plant")
    vr = refs(description)
    for name, order in [("tolerance", 1), ("theta[1]", 3), ("omegaDot[1]", 0)]:
        fmu.reset()
        fmu.setupExperiment(startTime=0.0)
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        fmu.doStep(0.0, 0.01)
        with pytest.raises(FMICallException) as info:
            fmu.getRealOutputDerivatives([vr[name]], [order])
        assert info.value.status == 3
    fmu.freeInstance()
    shutil.rmtree(directory, ignore_errors=True)


def test_fmi3_scalar_derivatives_through_fmpy_match_the_fmi2_ones(tmp_path):
    # Expected: the same moving plant, stepped alike, gives the same yaw/pitch/roll
    # rates (orders 1 and 2) through FMI 3.0 as through FMI 2.0, bit for bit (one
    # core behind both front-ends); they are not all zero.
    results = []
    for fmi3 in (False, True):
        fmu, description, directory = open_slave(tmp_path / str(fmi3), "Pss3Plant", fmi3)
        vr = refs(description)
        start_moving_plant(fmu, vr, fmi3)
        for k in range(5):
            fmu.doStep(0.01 * k, 0.01)
        names = ["yaw", "pitch", "roll"]
        getter = fmu.getOutputDerivatives if fmi3 else fmu.getRealOutputDerivatives
        results.append(getter([vr[n] for n in names * 2], [1, 1, 1, 2, 2, 2]))
        close(fmu, directory)
    assert results[0] == results[1]
    assert all(v != 0.0 for v in results[0])


@pytest.fixture
def planner3(tmp_path):
    fmu = fmu3(fmu3_path("Planner"), tmp_path / "Planner3")
    initialize(fmu)
    fmu.doStep(0.0, 0.75)
    yield fmu
    fmu.freeInstance()


def test_fmi3_arrays_are_serialized_pair_by_pair(planner3):
    # Expected: for (q, 1), (qdot, 2): qdot[1..3] then the jerk[1..3] of `quintic` at
    # t = 0.75 s; and (q, 1) equals the output qdot read with fmi3GetFloat64.
    fmu = planner3
    status, values = output_derivatives(fmu, ["q", "qdot"], [1, 2], 6)
    assert status == OK
    dq = [0.5, -0.3, 0.8]
    assert values[:3] == pytest.approx([quintic(d, 2.0, 0.75)[1] for d in dq], rel=1e-12)
    assert values[3:] == pytest.approx([quintic(d, 2.0, 0.75)[3] for d in dq], rel=1e-12)
    assert fmu.getFloat64([fmu.vr["qdot"]], 3) == values[:3]


@pytest.mark.parametrize("names, orders, n_values, message", [
    (["q"], [1], 1, "nValues = 1, but the variables have 3 elements"),
    (["q", "qdot"], [1, 1], 3, "nValues = 3, but the variables have 6 elements"),
    (["t0"], [1], 1, "\"t0\" (value reference 2) is not an output"),
    (["time"], [1], 1, "\"time\" (value reference 0) is not an output"),
    (["q"], [3], 3, "order 3 of \"q[1]\" is outside 1..2"),
    (["qddot"], [0], 3, "order 0 of \"qddot[1]\" is outside 1..2"),
    (["order"], [1], 1, "is a Int32 variable, not Float64"),
])
def test_fmi3_bad_requests_are_errors_with_a_reason(planner3, names, orders, n_values,
                                                    message):
    status, _ = output_derivatives(planner3, names, orders, n_values)
    assert status == ERROR
    assert message in last_message(planner3), last_message(planner3)


# The PID's default experiment (Kp 1, Ki 0.5, Kd 0.1, Tf 0.05 s on every channel, the
# setpoints 1, 0.5 and -0.25, the measurements 0 and held), channel 3 limited to
# [-0.1, 0.1]: its output starts below -0.1 and stays there.
PID_LIMITS = {"limitOutput": True, "uMin": -0.1, "uMax": 0.1}


class PidCalls:
    """The PID through FMPy as PlantCalls: FMU2Slave (FMI 2.0) or FMU3Slave (FMI 3.0,
    the array u), values and output derivatives of u, channel 3 limited."""

    def __init__(self, tmp_path, fmi3):
        self.fmi3 = fmi3
        if fmi3:
            self.fmu = fmu3(fmu3_path("PID"), tmp_path / "PID3")
            for name, value in PID_LIMITS.items():
                setter = self.fmu.setBoolean if name == "limitOutput" else self.fmu.setFloat64
                setter([self.fmu.vr[name]], [False, False, value])
            initialize(self.fmu)
        else:
            self.fmu, description, self.directory = open_slave(tmp_path, "PID")
            self.vr = refs(description)
            for name, value in PID_LIMITS.items():
                setter = self.fmu.setBoolean if name == "limitOutput" else self.fmu.setReal
                setter([self.vr[f"{name}[3]"]], [value])
            self.fmu.enterInitializationMode()
            self.fmu.exitInitializationMode()
        self.elements = ["u[1]", "u[2]", "u[3]"]

    def values(self):
        if self.fmi3:
            return self.fmu.getFloat64([self.fmu.vr["u"]], 3)
        return self.fmu.getReal([self.vr[n] for n in self.elements])

    def derivatives(self, order):
        if self.fmi3:
            status, values = output_derivatives(self.fmu, ["u"], [order], 3)
            assert status == OK, last_message(self.fmu)
            return values
        return self.fmu.getRealOutputDerivatives([self.vr[n] for n in self.elements],
                                                 [order] * 3)

    def step(self, t, h):
        self.fmu.doStep(t, h)

    def close(self):
        if self.fmi3:
            self.fmu.freeInstance()
        else:
            close(self.fmu, self.directory)


@pytest.mark.parametrize("fmi3", [False, True], ids=["fmi2", "fmi3"])
@pytest.mark.parametrize("delta, order", [(1e-5, 1), (1e-4, 2)])
def test_pid_derivatives_match_central_differences_and_the_closed_form(tmp_path, fmi3,
                                                                       delta, order):
    # Expected: (1) central differences of u over CS steps of delta with the inputs
    # held (the PID steps exactly: only the differences' truncation error, bounded as
    # for the plant); (2) the closed form of the step response of channels 1 and 2
    # from the zero state, u = e (Kp + Ki t + Kd/Tf exp(-t/Tf)):
    # u' = e (Ki - Kd/Tf^2 exp(-t/Tf)), u'' = e Kd/Tf^3 exp(-t/Tf); (3) channel 3, held
    # at its lower limit, 0 (its output is constant, its differences 0 too); (4) with
    # a moving input, the input's share.
    pid = PidCalls(tmp_path, fmi3)
    mismatches, checked = trajectory_mismatches(pid, order, delta)
    assert mismatches == [] and checked == 3 * 4
    t = 0.15 + 2 * delta  # where trajectory_mismatches left it
    pid.step(t, 0.05 - 2 * delta)
    t = 0.2
    a = 0.1 * math.exp(-t / 0.05)
    closed = 0.5 - a / 0.05**2 if order == 1 else a / 0.05**3
    got = pid.derivatives(order)
    assert got[:2] == pytest.approx([e * closed for e in (1.0, 0.5)], rel=1e-12)
    assert got[2] == 0.0 and pid.values()[2] == -0.1
    if not fmi3 and order == 1:
        # A measurement moving at 0.2 /s (fmi2SetRealInputDerivatives): the derivative
        # adds du/dy y' = -(Kp + Kd/Tf) 0.2 on channel 1 (robofmu_control::pid_ramp::
        # output_slope: the inputs move with the derivatives set).
        pid.fmu.setRealInputDerivatives([pid.vr["measurement[1]"]], [1], [0.2])
        moving = pid.derivatives(1)
        assert moving[0] == pytest.approx(got[0] - (1.0 + 0.1 / 0.05) * 0.2, rel=1e-12)
        assert moving[1:] == got[1:]
    pid.close()


def test_fmi3_clocked_output_has_no_output_derivatives(tmp_path):
    # uSampled is discrete (clocked): FMI 3.0 defines output derivatives of continuous
    # outputs only, so the call is refused with fmi3Error and a reason.
    fmu = fmu3(fmu3_path("PID"), tmp_path / "PID3")
    initialize(fmu)
    fmu.doStep(0.0, 0.01)
    status, _ = output_derivatives(fmu, ["uSampled"], [1], 3)
    assert status == ERROR
    assert '"uSampled" (value reference 411) is clocked by sampleClock' in last_message(fmu)
    fmu.freeInstance()


@pytest.mark.parametrize("fmi3", [False, True], ids=["fmi2", "fmi3"])
@pytest.mark.parametrize("model", MODELS)
def test_every_output_serves_every_declared_order(tmp_path, model, fmi3):
    # Expected (FMI 2.0 section 4.2.1, FMI 3.0 section 4.2.1.3): the call is allowed
    # for every output up to maxOutputDerivativeOrder, so each (Real output, order)
    # answers OK with finite values after a few steps from the default start.
    path = fmu3_path(model) if fmi3 else fmu_path(model)
    description = read_model_description(path)
    highest = description.coSimulation.maxOutputDerivativeOrder
    outputs = [v for v in description.modelVariables  # continuous ones: not the clocked
               if v.causality == "output" and v.type in ("Real", "Float64") and not v.clocks]
    assert outputs
    if fmi3:
        slave = fmu3(path, tmp_path / model)
        initialize(slave)
        slave.doStep(0.0, 0.01)
        for v, order in [(v, o) for v in outputs for o in range(1, highest + 1)]:
            size = v.shape[0] if v.shape else 1
            status, values = output_derivatives(slave, [v.name], [order], size)
            assert status == OK, (v.name, order, last_message(slave))
            assert all(math.isfinite(x) for x in values), (v.name, order)
        slave.freeInstance()
        return
    fmu, _, directory = open_slave(tmp_path, model)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    fmu.doStep(0.0, 0.01)
    for v, order in [(v, o) for v in outputs for o in range(1, highest + 1)]:
        values = fmu.getRealOutputDerivatives([v.valueReference], [order])
        assert all(math.isfinite(x) for x in values), (v.name, order)
    close(fmu, directory)
