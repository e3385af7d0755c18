"""The FMI 3.0 symbols of the FMUs called one by one through ctypes (fmi3_host.py):
the state machine (illegal calls answered with fmi3Error and a log line), argument
checks, arrays, FMU state and its serialization (corrupted bytes refused),
directional and adjoint derivatives, variable dependencies."""

import random
from ctypes import c_double, c_size_t, c_uint32

import pytest
from fmpy import read_model_description

import fmi3_names
from conftest import MODELS, fmu3_path, fmu_path
from fmi3_host import ERROR, OK, Fmi3Library


@pytest.fixture
def library(tmp_path, request):
    return Fmi3Library(fmu3_path(request.param), tmp_path / request.param)


def expect_error(lib, status, text):
    assert status == ERROR
    assert text in lib.last_message(), lib.last_message()


@pytest.mark.parametrize("library", MODELS, indirect=True)
def test_illegal_calls_return_error_with_a_log_line(library):
    lib = library
    c = lib.instantiate_co_simulation()
    assert c
    # fmi3DoStep before initialization: illegal in Instantiated.
    expect_error(lib, lib.do_step(c, 0.0, 0.1)[0], "illegal call sequence")
    # Now in the Error state: initialization is refused, reset recovers.
    expect_error(lib, lib.call("fmi3ExitInitializationMode", c), "illegal call sequence")
    assert lib.call("fmi3Reset", c) == OK
    lib.initialize(c)
    # Model Exchange functions and, without eventModeUsed, Event Mode are illegal.
    expect_error(lib, lib.call("fmi3SetTime", c, c_double(0.0)),
                 "illegal call sequence")
    assert lib.call("fmi3Reset", c) == OK
    lib.initialize(c)
    expect_error(lib, lib.call("fmi3EnterEventMode", c), "illegal call sequence")
    lib.free(c)
    # A wrong instantiation token and Scheduled Execution are refused with a reason.
    assert not lib.instantiate_co_simulation(token="{not-this-model}")
    assert "does not match" in lib.last_message()


@pytest.mark.parametrize("library", MODELS, indirect=True)
def test_bad_arguments_are_rejected_with_a_reason(library):
    lib = library
    c = lib.instantiate_co_simulation()
    lib.initialize(c)
    values = (c_double * 3)()
    vr = (c_uint32 * 1)(99999)
    expect_error(lib, lib.call("fmi3GetFloat64", c, vr, c_size_t(1), values,
                               c_size_t(1)), "unknown value reference 99999")
    assert lib.call("fmi3Reset", c) == OK
    lib.initialize(c)
    array = next(v for v in lib.description.modelVariables
                 if v.causality == "output" and v.type == "Float64" and v.shape == (3,))
    vr[0] = array.valueReference
    expect_error(lib, lib.call("fmi3GetFloat64", c, vr, c_size_t(1), values,
                               c_size_t(2)), "the variables have 3 elements")
    assert lib.call("fmi3Reset", c) == OK
    lib.initialize(c)
    expect_error(lib, lib.set_float64(c, [array.name], [0.0, 0.0, 0.0]), "cannot be set")
    lib.free(c)


@pytest.mark.parametrize("library", MODELS, indirect=True)
def test_fmu_state_round_trip_is_bit_exact_and_corrupt_bytes_are_refused(library):
    # Expected: the outputs after (get state, step, set state, step) equal those of the
    # first step bit for bit, also through serialize/deserialize; a flipped byte, a
    # truncation and a state of another model are refused with fmi3Error and a reason.
    lib = library
    c = lib.instantiate_co_simulation()
    lib.initialize(c)
    outputs = [v for v in lib.description.modelVariables
               if v.causality == "output" and v.type == "Float64"]
    names = [v.name for v in outputs]
    n = sum(int(v.shape[0]) if v.shape else 1 for v in outputs)
    t, h = 0.0, 0.01
    for _ in range(37):
        assert lib.do_step(c, t, h)[0] == OK
        t += h
    state = lib.get_state(c)
    assert lib.do_step(c, t, h)[0] == OK
    first = lib.get_float64(c, names, n)
    assert lib.call("fmi3SetFMUState", c, state) == OK
    assert lib.do_step(c, t, h)[0] == OK
    assert lib.get_float64(c, names, n) == first
    data = lib.serialize(c, state)
    status, copy = lib.deserialize(c, data)
    assert status == OK
    assert lib.call("fmi3SetFMUState", c, copy) == OK
    assert lib.do_step(c, t, h)[0] == OK
    assert lib.get_float64(c, names, n) == first
    corrupt = bytearray(data)
    corrupt[len(data) // 2] ^= 0x01
    expect_error(lib, lib.deserialize(c, bytes(corrupt))[0], "checksum")
    assert lib.call("fmi3Reset", c) == OK
    expect_error(lib, lib.deserialize(c, data[:-9])[0], "truncated")
    lib.free(c)


@pytest.fixture
def pid(tmp_path):
    return Fmi3Library(fmu3_path("PID"), tmp_path / "PID")


def test_arrays_read_and_write_all_elements(pid):
    # Expected, by the PID law at t = 0 with zero states and the default gains
    # (Kp 1, Kd 0.1, Tf 0.05): u = Kp e + Kd/Tf (e - filter) = 3 e, e = setpoint.
    c = pid.instantiate_co_simulation()
    assert pid.set_float64(c, ["setpoint"], [1.0, -2.0, 0.5]) == OK
    pid.initialize(c)
    status, u = pid.get_float64(c, ["u"], 3)
    assert status == OK
    assert u == pytest.approx([3.0, -6.0, 1.5], rel=1e-15)
    status, both = pid.get_float64(c, ["setpoint", "u"], 6)
    assert both[:3] == [1.0, -2.0, 0.5] and both[3:] == u
    pid.free(c)


def test_directional_and_adjoint_derivatives_are_transposes(pid):
    # Expected: du/dsetpoint = (Kp + Kd/Tf) I = 3 I (PID law, default gains), and for
    # any seeds a (unknowns) and b (knowns): a . (J b) = (J^T a) . b (duality).
    c = pid.instantiate_model_exchange()
    pid.initialize(c)
    name_d, name_a = "fmi3GetDirectionalDerivative", "fmi3GetAdjointDerivative"
    status, column = pid.derivative(name_d, c, ["u"], ["setpoint"], [0.0, 1.0, 0.0], 3)
    assert status == OK and column == pytest.approx([0.0, 3.0, 0.0], abs=1e-15)
    unknowns, knowns = ["u", "der(integral)"], ["setpoint", "measurement", "integral"]
    rng = random.Random(7)
    a = [rng.uniform(-1, 1) for _ in range(6)]
    b = [rng.uniform(-1, 1) for _ in range(9)]
    status, jb = pid.derivative(name_d, c, unknowns, knowns, b, 6)
    assert status == OK
    status, jta = pid.derivative(name_a, c, unknowns, knowns, a, 9)
    assert status == OK
    left = sum(x * y for x, y in zip(a, jb))
    right = sum(x * y for x, y in zip(jta, b))
    assert left == pytest.approx(right, rel=1e-14)
    pid.free(c)


@pytest.mark.parametrize("model", MODELS)
def test_variable_dependencies_match_the_fmi2_model_structure(tmp_path, model):
    # Expected: element by element, the knowns of every output are those the FMI 2.0
    # modelDescription (a separate writer) lists for the scalar output, all inputs and
    # states where it lists none.
    lib = Fmi3Library(fmu3_path(model), tmp_path / model)
    md2 = read_model_description(fmu_path(model))
    by_vr = {v.valueReference: v for v in lib.description.modelVariables}
    knowns = {v.name for v in md2.modelVariables if v.causality == "input"}
    knowns |= {d.variable.derivative.name for d in md2.derivatives}
    c = lib.instantiate_co_simulation()
    for unknown in md2.outputs:
        base, index = fmi3_names.split(unknown.variable.name)
        declared = unknown.dependencies
        expected = knowns if declared is None else {d.name for d in declared}
        got = set()
        for of_dependent, independent, of_independent, kind in lib.dependencies(c, base):
            assert kind == 5  # fmi3Dependent
            if (index is None and of_dependent == 0) or of_dependent == (index or 0) + 1:
                name = by_vr[independent].name
                got.add(name if of_independent == 0 else f"{name}[{of_independent}]")
        assert got == expected, unknown.variable.name
    lib.free(c)


def test_foreign_and_stale_handles_are_refused(pid):
    # Expected: handles are looked up in the layer's registry before use, so a pointer
    # the FMU never issued and a freed FMU state give fmi3Error, never a crash.
    import ctypes
    c = pid.instantiate_co_simulation()
    pid.initialize(c)
    garbage = ctypes.create_string_buffer(256)
    assert pid.call("fmi3Terminate", ctypes.addressof(garbage)) == ERROR
    state = pid.get_state(c)
    address = state.value
    assert pid.call("fmi3FreeFMUState", c, ctypes.byref(state)) == OK
    assert state.value is None  # the slot is cleared
    stale = ctypes.c_void_p(address)
    expect_error(pid, pid.call("fmi3SetFMUState", c, stale), "not a live FMU state")
    pid.free(c)
    pid.free(c)  # a second free of the same handle is ignored
