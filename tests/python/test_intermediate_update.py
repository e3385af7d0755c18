"""FMI 3.0 intermediate update (the FMI 3.0 counterpart of FMI 2.0 input derivatives):
with an intermediateUpdate callback passed to fmi3InstantiateCoSimulation, Pss3Plant
splits each communication step into 10 equal sub-intervals and calls back at the 9
inner points, where the importer reads outputs and sets the continuous inputs
(declared intermediateUpdate="true"). Driven here through FMPy's FMU3Slave (which
takes the callback in `instantiate`), with its ctypes functions for the calls made
from the callback.

The plant is forced with the sinusoids of test_input_derivatives.py (gravity off);
the reference is that test's FMI 2.0 co-simulation with input slopes at h = 1/16 ms
(second order in h: its own error is far below the figures compared here), so no
intermediate update enters the reference."""

import shutil
import zipfile
from xml.etree import ElementTree
from ctypes import byref, c_bool, c_double, c_uint32, c_void_p

import numpy as np
import pytest
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave

from conftest import fmu3, fmu3_path, fmu_path, refused
from test_fmi3_calls import ERROR, initialize, last_message
from test_input_derivatives import AMPLITUDE, OMEGA, PHASE, TIMES, plant_theta

STOP = TIMES[-1]
POINTS = 10  # the plant's INTERMEDIATE_UPDATE_POINTS


def forces(t):
    """The exact actuator forces at time t, N."""
    return [AMPLITUDE[i] * np.cos(OMEGA * t + PHASE[i]) for i in range(3)]


def open_plant(tmp_path, fmi3, name):
    directory = extract(fmu3_path("Pss3Plant") if fmi3 else fmu_path("Pss3Plant"),
                        unzipdir=str(tmp_path / name))
    description = read_model_description(directory)
    cls = FMU3Slave if fmi3 else FMU2Slave
    fmu = cls(guid=description.guid, unzipDirectory=directory,
              modelIdentifier=description.coSimulation.modelIdentifier)
    vr = {v.name: v.valueReference for v in description.modelVariables}
    return fmu, vr, directory


def run_fmi3(tmp_path, h, update_inputs):
    """theta on TIMES from the FMI 3.0 plant at step h with the exact forces set at
    each communication point, and, with `update_inputs`, at each intermediate point
    too (through the callback); without it no callback is passed."""
    fmu, vr, directory = open_plant(tmp_path, True, f"p3_{h}_{update_inputs}")
    failures, points = [], []

    def update(_env, time, set_requested, get_allowed, finished, _can_return_early,
               _early_requested, _early_time):
        try:
            assert set_requested and get_allowed and finished
            points.append(time)
            fmu.setFloat64([vr["actuatorForce"]], forces(time))
        except Exception as e:  # noqa: BLE001 - an exception cannot cross the C callback
            failures.append(e)

    fmu.instantiate(intermediateUpdate=update if update_inputs else None)
    fmu.setFloat64([vr["g"], vr["tolerance"]], [0.0, 1e-12])
    fmu.enterInitializationMode(startTime=0.0)
    fmu.exitInitializationMode()
    n = int(round(STOP / h))
    theta = [fmu.getFloat64([vr["theta"]], 3)]
    for k in range(n):
        fmu.setFloat64([vr["actuatorForce"]], forces(k * h))
        fmu.doStep(k * h, h)
        theta.append(fmu.getFloat64([vr["theta"]], 3))
    fmu.terminate()
    fmu.freeInstance()
    shutil.rmtree(directory, ignore_errors=True)
    assert not failures, failures
    assert len(points) == (POINTS - 1) * n if update_inputs else not points
    grid = np.arange(n + 1) * h
    theta = np.array(theta)
    return np.stack([np.interp(TIMES, grid, theta[:, i]) for i in range(3)], axis=1)


def run_fmi2(tmp_path, h):
    """theta on TIMES from the FMI 2.0 plant with the same exact forces held over each
    step (no slopes)."""
    fmu, vr, directory = open_plant(tmp_path, False, f"p2_{h}")
    fmu.instantiate()
    fmu.setReal([vr["g"], vr["tolerance"]], [0.0, 1e-12])
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    force_vrs = [vr[f"actuatorForce[{i}]"] for i in (1, 2, 3)]
    theta_vrs = [vr[f"theta[{i}]"] for i in (1, 2, 3)]
    n = int(round(STOP / h))
    theta = [fmu.getReal(theta_vrs)]
    for k in range(n):
        fmu.setReal(force_vrs, forces(k * h))
        fmu.doStep(k * h, h)
        theta.append(fmu.getReal(theta_vrs))
    fmu.terminate()
    fmu.freeInstance()
    shutil.rmtree(directory, ignore_errors=True)
    grid = np.arange(n + 1) * h
    theta = np.array(theta)
    return np.stack([np.interp(TIMES, grid, theta[:, i]) for i in range(3)], axis=1)


def test_the_fmi3_descriptions_declare_intermediate_update():
    # Expected: Pss3Plant, PID and ComputedTorque provide it, on their continuous inputs
    # and outputs; the Planner (no continuous inputs) does not.
    for model, provided in [("Pss3Plant", True), ("PID", True), ("ComputedTorque", True),
                            ("Planner", False)]:
        md = read_model_description(fmu3_path(model))
        assert bool(md.coSimulation.providesIntermediateUpdate) is provided, model
    # FMPy 0.3.32 does not read the variable attribute: the XML itself.
    with zipfile.ZipFile(fmu3_path("Pss3Plant")) as z:
        root = ElementTree.fromstring(z.read("modelDescription.xml"))
    flagged = {v.get("name") for v in root.find("ModelVariables")
               if v.get("intermediateUpdate") == "true"}
    assert {"actuatorForce", "torqueCommand", "theta"} <= flagged
    assert "g" not in flagged


def test_without_a_callback_the_fmi3_step_is_the_fmi2_step(tmp_path):
    # Expected: bit for bit the FMI 2.0 co-simulation with the same held inputs (the
    # same core step; a null callback splits nothing).
    h = 2e-3
    assert np.array_equal(run_fmi3(tmp_path, h, False), run_fmi2(tmp_path, h))


@pytest.mark.filterwarnings("ignore")
def test_inputs_set_at_intermediate_points_cut_the_coupling_error(tmp_path, capsys):
    reference = plant_theta(6.25e-5, True)
    errors = {}
    for update in (False, True):
        for h in (4e-3, 2e-3, 1e-3):
            errors[update, h] = np.abs(run_fmi3(tmp_path, h, update) - reference).max()
    with capsys.disabled():
        for (update, h), e in errors.items():
            print(f"\nintermediate update {update}: h = {h}: max |theta error| {e:.3e} rad")
    for update in (False, True):
        # First order in the step either way (the input is held over a step or over a
        # sub-interval): halving h halves the error (ratio 2 within 10 %).
        for h in (4e-3, 2e-3):
            assert 1.8 < errors[update, h] / errors[update, h / 2] < 2.2, (update, h)
    for h in (4e-3, 2e-3, 1e-3):
        # The inputs are held over h / 10 instead of h: the error is ~10 times smaller
        # (measured 9.x; accepted 8 to 12).
        assert 8.0 < errors[False, h] / errors[True, h] < 12.0, h


# Per model: the input set before the step, its values, the output read.
DRIVES = {"Pss3Plant": ("actuatorForce", [30.0, -20.0, 10.0], "theta"),
          "PID": ("measurement", [0.1, 0.2, -0.3], "u"),
          # Near the start pose (roll 122.07 deg), away from the planned angles: the
          # error integral, and with it u, moves over the step.
          "ComputedTorque": ("measurement", [0.01, -0.01, 2.15], "u")}


def start(directory, callback, model="Pss3Plant", early_return_allowed=False):
    """An initialized FMI 3.0 instance (FMPy's FMU3Slave) with `callback`, its input set
    (the plant: gravity on, actuators pushing)."""
    fmu = fmu3(fmu3_path(model), directory, intermediateUpdate=callback,
               earlyReturnAllowed=early_return_allowed)
    initialize(fmu)
    name, values, _ = DRIVES[model]
    fmu.setFloat64([fmu.vr[name]], values)
    return fmu


@pytest.mark.parametrize("model", DRIVES)
def test_reading_at_the_points_gives_the_plain_steps_of_h_over_10(tmp_path, model):
    # Expected: a callback that only reads sees at each inner point what a run without
    # callback sees after plain steps of h / 10 (the same sub-intervals), and the step
    # ends where that run ends (to rounding of the sub-interval ends: 1e-12). Read from
    # the callback through FMPy's ctypes function (its status kept).
    output = DRIVES[model][2]
    seen = []

    def read(_env, time, *_):
        values = (c_double * 3)()
        vr = (c_uint32 * 1)(fmu.vr[output])
        seen.append((time, (fmu.dll.fmi3GetFloat64(fmu.component, vr, 1, values, 3),
                            list(values))))

    fmu = start(tmp_path / "read", read, model)
    fmu.doStep(0.0, 5e-3)
    end = fmu.getFloat64([fmu.vr[output]], 3)
    plain = start(tmp_path / "plain", None, model)
    h = 5e-4
    for k in range(POINTS):
        plain.doStep(k * h, h)
        value = plain.getFloat64([plain.vr[output]], 3)
        if k < POINTS - 1:
            assert seen[k][0] == pytest.approx((k + 1) * h, abs=1e-15)
            assert seen[k][1][0] == 0  # fmi3OK
            assert np.allclose(seen[k][1][1], value, rtol=0, atol=1e-12)
    assert len(seen) == POINTS - 1
    assert np.allclose(end, value, rtol=0, atol=1e-12)
    assert not np.allclose(seen[0][1][1], value, rtol=0, atol=1e-9)  # it moved


@pytest.mark.parametrize("illegal", ["set_parameter", "get_parameter", "do_step",
                                     "terminate", "set_state"])
def test_illegal_calls_from_the_callback_are_errors(tmp_path, illegal):
    # Expected: Intermediate Update Mode allows only fmi3Get* of variables and fmi3Set*
    # of inputs declared intermediateUpdate (FMI 3.0 section 4.2.4): anything else is
    # fmi3Error with a log line, and the step then ends with fmi3Error too.
    statuses = []

    def misbehave(_env, time, *_):
        if statuses:
            return
        c, g, one = plant.component, (c_uint32 * 1)(plant.vr["g"]), (c_double * 1)(1.0)
        if illegal == "set_parameter":
            statuses.append(plant.dll.fmi3SetFloat64(c, g, 1, one, 1))
        elif illegal == "get_parameter":
            statuses.append(plant.dll.fmi3GetFloat64(c, g, 1, one, 1))
        elif illegal == "do_step":
            flag = c_bool()
            statuses.append(plant.dll.fmi3DoStep(c, time, 1e-3, True, byref(flag), byref(flag),
                                                 byref(flag), byref(c_double())))
        elif illegal == "terminate":
            statuses.append(plant.dll.fmi3Terminate(c))
        else:
            statuses.append(plant.dll.fmi3GetFMUState(c, byref(c_void_p())))

    plant = start(tmp_path, misbehave)
    assert refused(plant.doStep, 0.0, 1e-3) == ERROR
    assert statuses == [ERROR]
    messages = [m for _, _, m in plant.lines]
    reason = {"set_parameter": "cannot be set in IntermediateUpdateMode",
              "get_parameter": "not declared intermediateUpdate"}.get(
                  illegal, "not allowed in state IntermediateUpdateMode")
    assert any(reason in m for m in messages), messages
    assert "fmi3DoStep" in last_message(plant)
    plant.freeInstance()


def test_an_instance_freed_by_its_callback_ends_the_step_with_error(tmp_path):
    # Expected: fmi3FreeInstance has no status to refuse with; the step notices that
    # the handle is gone and returns fmi3Error without touching it (no crash).
    def free(_env, *_):
        plant.dll.fmi3FreeInstance(plant.component)

    plant = start(tmp_path, free)
    assert refused(plant.doStep, 0.0, 1e-3) == ERROR
    assert refused(plant.doStep, 1e-3, 1e-3) == ERROR


def test_an_early_return_is_honoured_only_when_allowed(tmp_path):
    # Expected: with earlyReturnAllowed the step ends at the third inner point when
    # the callback asks there (earlyReturn, lastSuccessfulTime = 3 h / 10) and the next
    # step starts from it; without, canReturnEarly is false and the step is whole.
    def ask(_env, time, _set, _get, _finished, can_return_early, requested, at):
        offered.append(can_return_early)
        if len(offered) == 3:
            requested[0] = True
            at[0] = time

    for allowed in (True, False):
        offered = []
        plant = start(tmp_path / str(allowed), ask, early_return_allowed=allowed)
        _, _, early_return, last = plant.doStep(0.0, 1e-2)  # fmi3OK (FMPy raises from Error)
        assert early_return is allowed
        assert last == pytest.approx(3e-3 if allowed else 1e-2, abs=1e-15)
        assert set(offered) == {allowed}
        plant.doStep(last, 1e-3)
        plant.freeInstance()
