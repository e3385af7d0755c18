"""Output derivatives of the real .fmu files through FMPy: fmi2GetRealOutputDerivatives
(FMU2Slave.getRealOutputDerivatives) and fmi3GetOutputDerivatives (FMU3Slave
.getOutputDerivatives for scalars, the ctypes host of fmi3_host.py for arrays and bad
arguments), against the textbook planner polynomial and central differences of the
plant's outputs along its co-simulation trajectory."""

import shutil

import pytest
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave

from conftest import fmu3_path, fmu_path
from fmi3_host import ERROR, OK, Fmi3Library


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
    # Expected: Planner and Pss3Plant provide order 2 (planner: every output; plant:
    # theta, yaw, pitch, roll, l), the PID none (the attribute left out: default 0).
    for model, order in [("Planner", 2), ("Pss3Plant", 2), ("PID", 0)]:
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


def plant_trajectory_errors(fmu, pairs, get, derivatives, delta):
    """Largest |derivative - central difference| / (1 + |difference|) per (name, order)
    pair over three points of the plant's trajectory (CS steps of `delta` around
    each); `get` reads values, `derivatives` the output derivatives of the pairs."""
    names = [n for n, _ in pairs]
    worst = [0.0] * len(pairs)
    t = 0.0
    for point in (0.02, 0.05, 0.1):
        fmu.doStep(t, point - delta - t)
        before = get(names)
        fmu.doStep(point - delta, delta)
        at, d = get(names), derivatives(pairs)
        fmu.doStep(point, delta)
        after = get(names)
        t = point + delta
        for i, (_, order) in enumerate(pairs):
            if order == 1:
                difference = (after[i] - before[i]) / (2 * delta)
            else:
                difference = (after[i] - 2 * at[i] + before[i]) / delta**2
            worst[i] = max(worst[i], abs(d[i] - difference) / (1 + abs(difference)))
    return worst


# A tilted plant moving under constant actuator forces, integrator tolerance 1e-12
# (the values of fmus/pss3-plant/tests/output_derivatives.rs).
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


@pytest.mark.parametrize("delta, order, tolerance", [(1e-5, 1, 3e-7), (1e-4, 2, 1e-5)])
def test_fmi2_plant_derivatives_match_central_differences(tmp_path, delta, order, tolerance):
    # Expected: central differences of the outputs over CS steps of delta (truncation
    # delta^2/6 |y'''|, delta^2/12 |y''''| dominate; see the Rust test of the same
    # trajectory for the tolerances).
    fmu, description, directory = open_slave(tmp_path, "Pss3Plant")
    vr = refs(description)
    start_moving_plant(fmu, vr, fmi3=False)
    names = ["theta[1]", "theta[2]", "theta[3]", "yaw", "pitch", "roll", "l[1]", "l[2]",
             "l[3]"]
    if order == 1:
        names += ["omega[1]", "omega[2]", "omega[3]", "lDot[1]", "lDot[2]", "lDot[3]",
                  "thetaDot[1]", "thetaDot[2]", "thetaDot[3]"]
    pairs = [(n, order) for n in names]
    errors = plant_trajectory_errors(
        fmu, pairs, lambda ns: fmu.getReal([vr[n] for n in ns]),
        lambda ps: fmu.getRealOutputDerivatives([vr[n] for n, _ in ps], [o for _, o in ps]),
        delta)
    assert max(errors) < tolerance, dict(zip(names, errors))
    close(fmu, directory)


def test_fmi2_refusals_are_errors(tmp_path):
    # Not exact (omegaDot), not an output (a parameter), order 3: fmi2Error.
    fmu, description, directory = open_slave(tmp_path, "Pss3Plant")
    vr = refs(description)
    for name, order in [("omegaDot[1]", 1), ("tolerance", 1), ("theta[1]", 3)]:
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
    lib = Fmi3Library(fmu3_path("Planner"), tmp_path / "Planner3")
    c = lib.instantiate_co_simulation()
    lib.initialize(c)
    assert lib.do_step(c, 0.0, 0.75)[0] == OK
    yield lib, c
    lib.free(c)


def test_fmi3_arrays_are_serialized_pair_by_pair(planner3):
    # Expected: for (q, 1), (qdot, 2): qdot[1..3] then the jerk[1..3] of `quintic` at
    # t = 0.75 s; and (q, 1) equals the output qdot read with fmi3GetFloat64.
    lib, c = planner3
    status, values = lib.output_derivatives(c, ["q", "qdot"], [1, 2], 6)
    assert status == OK
    dq = [0.5, -0.3, 0.8]
    assert values[:3] == pytest.approx([quintic(d, 2.0, 0.75)[1] for d in dq], rel=1e-12)
    assert values[3:] == pytest.approx([quintic(d, 2.0, 0.75)[3] for d in dq], rel=1e-12)
    assert lib.get_float64(c, ["qdot"], 3) == (OK, values[:3])


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
    lib, c = planner3
    status, _ = lib.output_derivatives(c, names, orders, n_values)
    assert status == ERROR
    assert message in lib.last_message(), lib.last_message()


def test_fmi3_pid_provides_none(tmp_path):
    lib = Fmi3Library(fmu3_path("PID"), tmp_path / "PID3")
    c = lib.instantiate_co_simulation()
    lib.initialize(c)
    assert lib.do_step(c, 0.0, 0.01)[0] == OK
    output = next(v for v in lib.description.modelVariables
                  if v.causality == "output" and v.type == "Float64")
    size = output.shape[0] if output.shape else 1
    status, _ = lib.output_derivatives(c, [output.name], [1], size)
    assert status == ERROR
    assert "provides no output derivatives" in lib.last_message(), lib.last_message()
    lib.free(c)
