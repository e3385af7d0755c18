"""A fixed parameter set again after initialization (what gemseo-fmu does in step mode
for every variable of a study, issue 45): every FMU, both standards (FMI 3.0 with its
array and its scalar-only view), every interface and every mode after initialization
where the setter is legal, every fixed parameter (Real/Float64, Integer/Int32,
Boolean; the models have no String variables).

Expected (the rule of docs/reliability.md, "A fixed parameter set again"):
- the value it holds, bit for bit: Warning and a log line naming the variable and the
  rule;
- a different value (one ulp off, -0.0 for 0.0, NaN, the other integer or boolean, one
  element of an array): Error with the message of a refused set
  ("... cannot be set in <mode>");
- after both, the instance's serialized FMU state equals the one taken before, byte for
  byte (the independent truth: the FMU's own earlier state), and outputs after steps
  equal those of a twin instance that was never set again."""

import math
from ctypes import byref, c_bool, c_double, c_int, c_int32, c_size_t, c_uint32, c_void_p

import pytest
from fmpy import extract, read_model_description
from fmpy.fmi2 import (FMU2Model, FMU2Slave, calloc, fmi2CallbackAllocateMemoryTYPE,
                       fmi2CallbackFreeMemoryTYPE, fmi2CallbackFunctions,
                       fmi2CallbackLoggerTYPE, free)

from conftest import DIST, MODELS, ROOT, fmu3, fmu3_path, fmu_path
from test_fmi3_calls import ERROR, OK, initialize, last_message

WARNING = 1

RULE = "accepted without effect"


def refusal(name, mode):
    """The message of a refused set, unchanged by issue 45."""
    return f'"{name}" (causality parameter, variability fixed) cannot be set in {mode}'


def different(value):
    """A value that is not `value` bit for bit: one ulp up (a Real), -0.0 for 0.0, the
    next integer, the other boolean."""
    if isinstance(value, bool):
        return not value
    if isinstance(value, int):
        return value + 1
    if value == 0.0 and math.copysign(1.0, value) > 0:
        return -0.0
    return math.nextafter(value, math.inf)


def fixed_parameters(description):
    return [v for v in description.modelVariables
            if v.causality == "parameter" and v.variability == "fixed"]


# ---------------------------------------------------------------- FMI 2.0 -----------

class Host2:
    """One FMI 2.0 instance through FMPy's classes, with its log kept and the setters
    called raw (FMPy raises on fmi2Error; the status is what is checked here)."""

    TYPES = {"Real": ("fmi2SetReal", "fmi2GetReal", c_double),
             "Integer": ("fmi2SetInteger", "fmi2GetInteger", c_int),
             "Boolean": ("fmi2SetBoolean", "fmi2GetBoolean", c_int)}

    def __init__(self, directory, description, interface):
        self.lines = []

        def log(_env, _name, status, category, message):
            self.lines.append((status, category.decode(), message.decode()))

        self.callbacks = fmi2CallbackFunctions()
        self.callbacks.logger = fmi2CallbackLoggerTYPE(log)
        self.callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        self.callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        cls, node = ((FMU2Slave, description.coSimulation) if interface == "CS"
                     else (FMU2Model, description.modelExchange))
        self.fmu = cls(guid=description.guid, unzipDirectory=directory,
                       modelIdentifier=node.modelIdentifier, instanceName="reset")
        self.fmu.instantiate(callbacks=self.callbacks, loggingOn=True)

    def reach(self, mode):
        fmu = self.fmu
        fmu.setupExperiment(startTime=0.0)
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        if mode == "StepComplete":
            fmu.doStep(0.0, 0.01)
        elif mode == "ContinuousTimeMode":
            fmu.enterContinuousTimeMode()

    def raw(self, name, vr, values):
        f = getattr(self.fmu.dll, name)
        f.restype = c_int
        vrs = (c_uint32 * len(vr))(*vr)
        return f(c_void_p(self.fmu.component), vrs, c_size_t(len(vr)), values)

    def get(self, v):
        setter, getter, ctype = self.TYPES[v.type]
        out = (ctype * 1)()
        assert self.raw(getter, [v.valueReference], out) == OK
        return bool(out[0]) if v.type == "Boolean" else out[0]

    def set(self, v, value):
        _, _, ctype = self.TYPES[v.type]
        return self.raw(self.TYPES[v.type][0], [v.valueReference], (ctype * 1)(value))

    def state(self):
        state = self.fmu.getFMUstate()
        data = bytes(self.fmu.serializeFMUstate(state))
        self.fmu.freeFMUstate(state)
        return data


def has_real_fixed(model):
    """Whether the model has a fixed Real parameter (the only type whose setter is legal
    in Continuous-Time Mode); from the checked-in description."""
    description = read_model_description(str(ROOT / "modelDescription" / f"{model}.xml"))
    return any(v.type == "Real" for v in fixed_parameters(description))


def fmi2_cases():
    return [pytest.param(model, interface, mode, id=f"{model}-{interface}-{mode}")
            for model in MODELS
            for interface, modes in (("CS", ["StepComplete"]),
                                     ("ME", ["EventMode", "ContinuousTimeMode"]))
            for mode in modes
            if mode != "ContinuousTimeMode" or has_real_fixed(model)]


@pytest.fixture(scope="module")
def unpacked2(tmp_path_factory):
    folders = {}
    for model in MODELS:
        directory = extract(fmu_path(model), unzipdir=str(tmp_path_factory.mktemp(model)))
        folders[model] = (directory, read_model_description(directory))
    return folders


@pytest.mark.parametrize("model,interface,mode", fmi2_cases())
def test_fmi2_fixed_parameter_set_again(unpacked2, model, interface, mode):
    directory, description = unpacked2[model]
    host = Host2(directory, description, interface)
    host.reach(mode)
    checked = 0
    for v in fixed_parameters(description):
        if mode == "ContinuousTimeMode" and v.type != "Real":
            continue  # fmi2SetInteger/Boolean are illegal there (FMI 2.0 3.2.3)
        before = host.state()
        value = host.get(v)
        assert host.set(v, value) == WARNING, host.lines[-1:]
        status, category, line = host.lines[-1]
        assert (status, category) == (WARNING, "logStatusWarning")
        assert f'"{v.name}"' in line and RULE in line and mode in line, line
        assert host.state() == before
        assert host.set(v, different(value)) == ERROR
        assert refusal(v.name, mode) in host.lines[-1][2], host.lines[-1]
        assert host.state() == before
        assert host.get(v) == value
        host.fmu.reset()
        host.reach(mode)
        if v.type == "Real":  # NaN never holds: refused as a change
            assert host.set(v, math.nan) == ERROR
            assert refusal(v.name, mode) in host.lines[-1][2], host.lines[-1]
            host.fmu.reset()
            host.reach(mode)
        checked += 1
    assert checked > 0
    host.fmu.freeInstance()


@pytest.mark.parametrize("model", MODELS)
def test_fmi2_outputs_after_unchanged_sets_equal_a_twin(unpacked2, model):
    # Every fixed parameter set again before each of 20 steps: the outputs equal those
    # of a twin instance that was never set again, bit for bit.
    directory, description = unpacked2[model]
    hosts = [Host2(directory, description, "CS") for _ in range(2)]
    outputs = [v.valueReference for v in description.modelVariables
               if v.causality == "output" and v.type == "Real"]
    fixed = fixed_parameters(description)
    for host in hosts:
        host.reach("StepComplete")
    values = [hosts[0].get(v) for v in fixed]
    for k in range(1, 21):
        for v, value in zip(fixed, values):
            assert hosts[0].set(v, value) == WARNING
        for host in hosts:
            host.fmu.doStep(0.01 * k, 0.01)
        assert hosts[0].fmu.getReal(outputs) == hosts[1].fmu.getReal(outputs)
    for host in hosts:
        host.fmu.freeInstance()


# ---------------------------------------------------------------- FMI 3.0 -----------

FMI3_TYPES = {"Float64": ("fmi3SetFloat64", "fmi3GetFloat64", c_double),
              "Int32": ("fmi3SetInt32", "fmi3GetInt32", c_int32),
              "Boolean": ("fmi3SetBoolean", "fmi3GetBoolean", c_bool)}


def size(v):
    """Elements of `v` at the default sizes: a dimension is its start or, sized by a
    structural parameter (`<Dimension valueReference>`), that parameter's start."""
    return math.prod(int(d.start if d.start is not None else d.variable.start)
                     for d in v.dimensions)


def raw3(fmu, name, v, values):
    """The setter or getter `name` of `v` through FMPy's ctypes function: its status."""
    vr = (c_uint32 * 1)(v.valueReference)
    return getattr(fmu.dll, name)(fmu.component, vr, 1, values, len(values))


def get3(fmu, v):
    _, getter, ctype = FMI3_TYPES[v.type]
    out = (ctype * size(v))()
    assert raw3(fmu, getter, v, out) == OK
    return [bool(x) for x in out] if v.type == "Boolean" else list(out)


def set3(fmu, v, values):
    setter, _, ctype = FMI3_TYPES[v.type]
    return raw3(fmu, setter, v, (ctype * len(values))(*values))


def state3(fmu):
    state = fmu.getFMUState()
    data = fmu.serializeFMUState(state)
    assert fmu.dll.fmi3FreeFMUState(fmu.component, byref(state)) == OK
    return data


def fmi3_cases():
    return [pytest.param(folder, model, interface, mode,
                         id=f"{folder}-{model}-{interface}-{mode}")
            for folder in ("fmi3", "fmi3-scalar")
            for model in MODELS
            for interface, modes in (("CS", ["StepMode"]),
                                     ("CS+events", ["EventMode", "StepMode"]),
                                     ("ME", ["EventMode", "ContinuousTimeMode"]))
            for mode in modes
            if mode != "ContinuousTimeMode" or has_real_fixed(model)]


def reach3(fmu, interface, mode):
    initialize(fmu)
    if interface == "CS" or (interface == "CS+events" and mode == "StepMode"):
        if interface == "CS+events":
            assert fmu.enterStepMode() == OK
        fmu.doStep(0.0, 0.01)
    elif mode == "ContinuousTimeMode":
        assert fmu.enterContinuousTimeMode() == OK


def instantiate3(path, directory, interface):
    """FMPy's FMU3Model (ME) or FMU3Slave (CS, CS+events: eventModeUsed) of `path`,
    every log category on."""
    events = {} if interface == "ME" else {"eventModeUsed": interface == "CS+events"}
    fmu = fmu3(path, directory, model_exchange=interface == "ME", **events)
    assert fmu.dll.fmi3SetDebugLogging(fmu.component, True, 0, None) == OK
    return fmu


@pytest.mark.parametrize("folder,model,interface,mode", fmi3_cases())
def test_fmi3_fixed_parameter_set_again(tmp_path, folder, model, interface, mode):
    path = fmu3_path(model) if folder == "fmi3" else str(DIST / folder / f"{model}.fmu")
    fmu = instantiate3(path, tmp_path / model, interface)
    reach3(fmu, interface, mode)
    checked = 0
    for v in fixed_parameters(fmu.description):
        if mode == "ContinuousTimeMode" and v.type != "Float64":
            continue  # fmi3SetInt32/Boolean are illegal there (FMI 3.0 3.3)
        before = state3(fmu)
        values = get3(fmu, v)
        assert set3(fmu, v, values) == WARNING, fmu.lines[-1:]
        status, category, line = fmu.lines[-1]
        assert (status, category) == (WARNING, "logStatusWarning")
        assert f'"{v.name}"' in line and RULE in line and mode in line, line
        assert state3(fmu) == before
        # One element off (the last of an array): the whole call is refused.
        changed = values[:-1] + [different(values[-1])]
        assert set3(fmu, v, changed) == ERROR
        assert refusal(v.name, mode) in last_message(fmu), last_message(fmu)
        assert state3(fmu) == before
        assert get3(fmu, v) == values
        assert fmu.reset() == OK
        reach3(fmu, interface, mode)
        checked += 1
    assert checked > 0
    fmu.freeInstance()


@pytest.mark.parametrize("model", MODELS)
def test_fmi3_outputs_after_unchanged_sets_equal_a_twin(tmp_path, model):
    # Every fixed parameter set again before each of 20 steps: the outputs equal those
    # of a twin instance that was never set again, bit for bit.
    twins = [instantiate3(fmu3_path(model), tmp_path / f"{model}{k}", "CS") for k in range(2)]
    outputs = [v for v in twins[0].description.modelVariables
               if v.causality == "output" and v.type == "Float64"]
    fixed = fixed_parameters(twins[0].description)
    for fmu in twins:
        reach3(fmu, "CS", "StepMode")
    values = [get3(twins[0], v) for v in fixed]
    for k in range(1, 21):
        for v, value in zip(fixed, values):
            assert set3(twins[0], v, value) == WARNING
        for fmu in twins:
            fmu.doStep(0.01 * k, 0.01)
        read = [[get3(fmu, v) for v in outputs] for fmu in twins]
        assert read[0] == read[1]
    for fmu in twins:
        fmu.freeInstance()
