"""The FMI 3.0 symbols of the FMUs called one by one through FMPy's FMU3Slave and
FMU3Model (their ctypes functions where a status matters): the state machine (illegal
calls answered with fmi3Error and a log line), argument checks, arrays, FMU state and
its serialization (corrupted bytes refused), directional and adjoint derivatives,
variable dependencies."""

import ctypes
import random
from ctypes import byref, c_double, c_int, c_size_t, c_uint32

import pytest
from fmpy import read_model_description

import fmi3_names
from conftest import MODELS, fmu3, fmu3_path, fmu_path, refused

OK, ERROR = 0, 3


@pytest.fixture
def library(tmp_path, request):
    return fmu3(fmu3_path(request.param), tmp_path / request.param)


def last_message(fmu):
    return fmu.lines[-1][2] if fmu.lines else ""


def expect_error(fmu, status, text):
    assert status == ERROR
    assert text in last_message(fmu), last_message(fmu)


def initialize(fmu):
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()


def outputs(fmu):
    """The Float64 outputs: value references and their number of elements."""
    variables = [v for v in fmu.description.modelVariables
                 if v.causality == "output" and v.type == "Float64"]
    return [v.valueReference for v in variables], sum(int(v.shape[0]) if v.shape else 1
                                                       for v in variables)


@pytest.mark.parametrize("library", MODELS, indirect=True)
def test_illegal_calls_return_error_with_a_log_line(library, tmp_path):
    fmu = library
    # fmi3DoStep before initialization: illegal in Instantiated.
    expect_error(fmu, refused(fmu.doStep, 0.0, 0.1), "illegal call sequence")
    # Now in the Error state: initialization is refused, reset recovers.
    expect_error(fmu, fmu.dll.fmi3ExitInitializationMode(fmu.component), "illegal call sequence")
    assert fmu.reset() == OK
    initialize(fmu)
    # Model Exchange functions and, without eventModeUsed, Event Mode are illegal.
    expect_error(fmu, fmu.dll.fmi3SetTime(fmu.component, 0.0), "illegal call sequence")
    assert fmu.reset() == OK
    initialize(fmu)
    expect_error(fmu, fmu.dll.fmi3EnterEventMode(fmu.component), "illegal call sequence")
    fmu.freeInstance()
    # A wrong instantiation token is refused with a reason.
    lines = []
    with pytest.raises(Exception, match="Failed to instantiate"):
        fmu3(fmu3_path(fmu.description.modelName), tmp_path / "token", guid="{not-this-model}",
             lines=lines)
    assert "does not match" in lines[-1][2]


@pytest.mark.parametrize("library", MODELS, indirect=True)
def test_bad_arguments_are_rejected_with_a_reason(library):
    fmu = library
    c = fmu.component
    initialize(fmu)
    values = (c_double * 3)()
    vr = (c_uint32 * 1)(99999)
    expect_error(fmu, fmu.dll.fmi3GetFloat64(c, vr, 1, values, 1),
                 "unknown value reference 99999")
    assert fmu.reset() == OK
    initialize(fmu)
    array = next(v for v in fmu.description.modelVariables
                 if v.causality == "output" and v.type == "Float64" and v.shape == (3,))
    vr[0] = array.valueReference
    expect_error(fmu, fmu.dll.fmi3GetFloat64(c, vr, 1, values, 2),
                 "the variables have 3 elements")
    assert fmu.reset() == OK
    initialize(fmu)
    expect_error(fmu, refused(fmu.setFloat64, [array.valueReference], [0.0, 0.0, 0.0]),
                 "cannot be set")
    fmu.freeInstance()


def deserialize(fmu, data):
    """fmi3DeserializeFMUState of `data`: the status and the new state."""
    state = ctypes.c_void_p()
    buffer = (ctypes.c_uint8 * len(data))(*data)
    return fmu.dll.fmi3DeserializeFMUState(fmu.component, buffer, len(data), byref(state)), state


@pytest.mark.parametrize("library", MODELS, indirect=True)
def test_fmu_state_round_trip_is_bit_exact_and_corrupt_bytes_are_refused(library):
    # Expected: the outputs after (get state, step, set state, step) equal those of the
    # first step bit for bit, also through serialize/deserialize; a flipped byte, a
    # truncation and a state of another model are refused with fmi3Error and a reason.
    fmu = library
    initialize(fmu)
    vrs, n = outputs(fmu)
    t, h = 0.0, 0.01
    for _ in range(37):
        fmu.doStep(t, h)
        t += h
    state = fmu.getFMUState()
    fmu.doStep(t, h)
    first = fmu.getFloat64(vrs, n)
    fmu.setFMUState(state)
    fmu.doStep(t, h)
    assert fmu.getFloat64(vrs, n) == first
    data = fmu.serializeFMUState(state)
    status, copy = deserialize(fmu, data)
    assert status == OK
    fmu.setFMUState(copy)
    fmu.doStep(t, h)
    assert fmu.getFloat64(vrs, n) == first
    corrupt = bytearray(data)
    corrupt[len(data) // 2] ^= 0x01
    expect_error(fmu, deserialize(fmu, bytes(corrupt))[0], "checksum")
    assert fmu.reset() == OK
    expect_error(fmu, deserialize(fmu, data[:-9])[0], "truncated")
    fmu.freeInstance()


@pytest.fixture
def pid(tmp_path):
    return fmu3(fmu3_path("PID"), tmp_path / "PID")


def test_arrays_read_and_write_all_elements(pid):
    # Expected, by the PID law at t = 0 with zero states and the default gains
    # (Kp 1, Kd 0.1, Tf 0.05): u = Kp e + Kd/Tf (e - filter) = 3 e, e = setpoint.
    pid.setFloat64([pid.vr["setpoint"]], [1.0, -2.0, 0.5])
    initialize(pid)
    u = pid.getFloat64([pid.vr["u"]], 3)
    assert u == pytest.approx([3.0, -6.0, 1.5], rel=1e-15)
    both = pid.getFloat64([pid.vr["setpoint"], pid.vr["u"]], 6)
    assert both[:3] == [1.0, -2.0, 0.5] and both[3:] == u
    pid.freeInstance()


def test_directional_and_adjoint_derivatives_are_transposes(tmp_path):
    # Expected: du/dsetpoint = (Kp + Kd/Tf) I = 3 I (PID law, default gains), and for
    # any seeds a (unknowns) and b (knowns): a . (J b) = (J^T a) . b (duality).
    pid = fmu3(fmu3_path("PID"), tmp_path / "PID", model_exchange=True)
    initialize(pid)
    vr = pid.vr
    column = pid.getDirectionalDerivative([vr["u"]], [vr["setpoint"]], [0.0, 1.0, 0.0], 3)
    assert column == pytest.approx([0.0, 3.0, 0.0], abs=1e-15)
    unknowns = [vr["u"], vr["der(integral)"]]
    knowns = [vr["setpoint"], vr["measurement"], vr["integral"]]
    rng = random.Random(7)
    a = [rng.uniform(-1, 1) for _ in range(6)]
    b = [rng.uniform(-1, 1) for _ in range(9)]
    jb = pid.getDirectionalDerivative(unknowns, knowns, b, 6)
    jta = pid.getAdjointDerivative(unknowns, knowns, a, 9)
    left = sum(x * y for x, y in zip(a, jb))
    right = sum(x * y for x, y in zip(jta, b))
    assert left == pytest.approx(right, rel=1e-14)
    pid.freeInstance()



def test_computed_torque_derivatives_in_both_interfaces_and_the_adjoint(tmp_path):
    # Expected: ComputedTorque's u is affine in the planned acceleration (u = M_x a +
    # terms of the measured motion, no limits by default), so the difference of u over
    # a unit change of setpointAcceleration[2] is the column M_x e_2 to rounding; a
    # Co-Simulation instance gives the same column (one implementation behind both
    # interfaces); for any seeds a and b, a . (J b) = (J^T a) . b (duality) over every
    # unknown and known.
    columns = []
    for model_exchange in (True, False):
        ct = fmu3(fmu3_path("ComputedTorque"), tmp_path / f"CT{model_exchange}",
                  model_exchange=model_exchange)
        initialize(ct)
        vr = ct.vr
        columns.append(ct.getDirectionalDerivative([vr["u"]], [vr["setpointAcceleration"]],
                                                   [0.0, 1.0, 0.0], 3))
        u0 = ct.getFloat64([vr["u"]], 3)
        ct.setFloat64([vr["setpointAcceleration"]], [0.0, 1.0, 0.0])
        difference = [a - b for a, b in zip(ct.getFloat64([vr["u"]], 3), u0)]
        assert columns[-1] == pytest.approx(difference, rel=1e-12, abs=1e-14)
        assert max(abs(x) for x in difference) > 1e-3
        if model_exchange:
            unknowns = [vr["u"], vr["der(integral)"]]
            knowns = [vr[n] for n in ("setpoint", "setpointRate", "setpointAcceleration",
                                      "measurement", "measuredRate", "integral")]
            rng = random.Random(11)
            a = [rng.uniform(-1, 1) for _ in range(6)]
            b = [rng.uniform(-1, 1) for _ in range(18)]
            jb = ct.getDirectionalDerivative(unknowns, knowns, b, 6)
            jta = ct.getAdjointDerivative(unknowns, knowns, a, 18)
            left = sum(x * y for x, y in zip(a, jb))
            right = sum(x * y for x, y in zip(jta, b))
            assert left == pytest.approx(right, rel=1e-12)
        ct.freeInstance()
    assert columns[0] == pytest.approx(columns[1], rel=1e-14)

def dependencies(fmu, name):
    """fmi3GetVariableDependencies of `name`: (element of the dependent, independent,
    element of the independent, kind) tuples. Through the ctypes functions: FMPy's
    getNumberOfVariableDependencies passes the type c_size_t, not a value."""
    n, vr = c_size_t(), fmu.vr[name]
    assert fmu.dll.fmi3GetNumberOfVariableDependencies(fmu.component, vr, byref(n)) == OK
    of_dependent = (c_size_t * n.value)()
    independents = (c_uint32 * n.value)()
    of_independents = (c_size_t * n.value)()
    kinds = (c_int * n.value)()
    assert fmu.dll.fmi3GetVariableDependencies(fmu.component, vr, of_dependent, independents,
                                               of_independents, kinds, n) == OK
    return list(zip(of_dependent, independents, of_independents, kinds))


@pytest.mark.parametrize("model", MODELS)
def test_variable_dependencies_match_the_fmi2_model_structure(tmp_path, model):
    # Expected: element by element, the knowns of every output are those the FMI 2.0
    # modelDescription (a separate writer) lists for the scalar output, all inputs and
    # states where it lists none.
    fmu = fmu3(fmu3_path(model), tmp_path / model)
    md2 = read_model_description(fmu_path(model))
    by_vr = {v.valueReference: v for v in fmu.description.modelVariables}
    knowns = {v.name for v in md2.modelVariables if v.causality == "input"}
    knowns |= {d.variable.derivative.name for d in md2.derivatives}
    for unknown in md2.outputs:
        base, index = fmi3_names.split(unknown.variable.name)
        declared = unknown.dependencies
        expected = knowns if declared is None else {d.name for d in declared}
        got = set()
        for of_dependent, independent, of_independent, kind in dependencies(fmu, base):
            assert kind == 5  # fmi3Dependent
            if (index is None and of_dependent == 0) or of_dependent == (index or 0) + 1:
                name = by_vr[independent].name
                got.add(name if of_independent == 0 else f"{name}[{of_independent}]")
        assert got == expected, unknown.variable.name
    fmu.freeInstance()


def test_foreign_and_stale_handles_are_refused(pid):
    # Expected: handles are looked up in the layer's registry before use, so a pointer
    # the FMU never issued and a freed FMU state give fmi3Error, never a crash.
    c = pid.component
    initialize(pid)
    garbage = ctypes.create_string_buffer(256)
    assert pid.dll.fmi3Terminate(ctypes.addressof(garbage)) == ERROR
    state = pid.getFMUState()
    address = state.value
    assert pid.dll.fmi3FreeFMUState(c, byref(state)) == OK
    assert state.value is None  # the slot is cleared
    stale = ctypes.c_void_p(address)
    expect_error(pid, pid.dll.fmi3SetFMUState(c, stale), "not a live FMU state")
    pid.dll.fmi3FreeInstance(c)
    pid.dll.fmi3FreeInstance(c)  # a second free of the same handle is ignored
