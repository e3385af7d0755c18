"""The FMUs driven call by call through FMPy's low-level classes: FMU-state round
trips and illegal call sequences / bad arguments (errors, never crashes)."""

import ctypes
import shutil

import pytest
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Model, FMU2Slave

from conftest import MODELS, fmu_path


@pytest.fixture
def unpacked(tmp_path, request):
    model = request.param
    directory = extract(fmu_path(model), unzipdir=str(tmp_path / model))
    description = read_model_description(directory)
    yield model, directory, description
    shutil.rmtree(directory, ignore_errors=True)


def slave(directory, description, name="instance"):
    fmu = FMU2Slave(guid=description.guid, unzipDirectory=directory,
                    modelIdentifier=description.coSimulation.modelIdentifier,
                    instanceName=name)
    fmu.instantiate()
    return fmu


def output_refs(description):
    """The Real outputs (read with one fmi2GetReal call)."""
    return [v.valueReference for v in description.modelVariables
            if v.causality == "output" and v.type == "Real"]


@pytest.mark.parametrize("unpacked", MODELS, indirect=True)
def test_fmu_state_round_trip_is_bit_exact(unpacked):
    # Expected: the outputs after (get state, step, set state, step) equal those of the
    # first step bit for bit, also through serialize/deserialize.
    _, directory, description = unpacked
    fmu = slave(directory, description)
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    h = 0.01
    t = 0.0
    for _ in range(37):
        fmu.doStep(t, h)
        t += h
    outputs = output_refs(description)
    state = fmu.getFMUstate()
    fmu.doStep(t, h)
    first = fmu.getReal(outputs)
    fmu.setFMUstate(state)
    fmu.doStep(t, h)
    assert fmu.getReal(outputs) == first
    data = fmu.serializeFMUstate(state)
    copy = fmu.deSerializeFMUstate(data)
    fmu.setFMUstate(copy)
    fmu.doStep(t, h)
    assert fmu.getReal(outputs) == first
    fmu.freeFMUstate(state)
    fmu.freeFMUstate(copy)
    fmu.terminate()
    fmu.freeInstance()


@pytest.mark.parametrize("unpacked", MODELS, indirect=True)
def test_illegal_calls_and_bad_arguments_return_errors(unpacked):
    # Expected: fmi2Error (status 3) for each call, and the process survives.
    _, directory, description = unpacked
    first_output = output_refs(description)[0]

    def expect_error(call):
        with pytest.raises(FMICallException) as info:
            call()
        assert info.value.status == 3

    fmu = slave(directory, description)
    expect_error(lambda: fmu.doStep(0.0, 0.1))           # before initialization
    fmu.reset()
    expect_error(lambda: fmu.getReal([first_output]))      # not readable yet
    fmu.reset()
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    expect_error(lambda: fmu.getReal([987654]))            # unknown value reference
    fmu.reset()
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    expect_error(lambda: fmu.setReal([first_output], [1.0]))   # outputs are not settable
    fmu.reset()
    some_real = next(v.valueReference for v in description.modelVariables
                     if v.type == "Real" and v.causality in ("parameter", "input"))
    expect_error(lambda: fmu.setReal([some_real], [float("nan")]))
    fmu.reset()
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    expect_error(lambda: fmu.doStep(5.0, 0.1))             # wrong communication point
    fmu.freeInstance()

    # A wrong GUID is refused at instantiation.
    bad = FMU2Slave(guid="{00000000-0000-0000-0000-000000000000}", unzipDirectory=directory,
                    modelIdentifier=description.coSimulation.modelIdentifier)
    with pytest.raises(Exception):
        bad.instantiate()


@pytest.mark.parametrize("unpacked", MODELS, indirect=True)
def test_model_exchange_instance_rejects_foreign_calls(unpacked):
    # Expected: fmi2Error (3) for a Co-Simulation call on a Model Exchange instance and
    # for a state vector of the wrong length.
    _, directory, description = unpacked
    fmu = FMU2Model(guid=description.guid, unzipDirectory=directory,
                    modelIdentifier=description.modelExchange.modelIdentifier)
    fmu.instantiate()
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    do_step = fmu.dll.fmi2DoStep
    do_step.argtypes = [ctypes.c_void_p, ctypes.c_double, ctypes.c_double, ctypes.c_int]
    do_step.restype = ctypes.c_int
    assert do_step(fmu.component, 0.0, 0.1, 1) == 3
    fmu.reset()
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    fmu.enterContinuousTimeMode()
    n = description.numberOfContinuousStates
    wrong = (ctypes.c_double * (n + 1))()
    with pytest.raises(FMICallException):
        fmu.setContinuousStates(wrong, n + 1)
    fmu.freeInstance()
