"""A minimal ctypes host of the FMI 3.0 symbols of an FMU's shared library, for the
call-level tests: every function returns its status, the log lines are kept."""

import ctypes
from ctypes import (CFUNCTYPE, POINTER, byref, c_bool, c_char_p, c_double, c_int, c_size_t,
                    c_uint8, c_uint32, c_void_p)
from pathlib import Path

from fmpy import extract, read_model_description

OK, WARNING, DISCARD, ERROR, FATAL = range(5)

LOG_MESSAGE = CFUNCTYPE(None, c_void_p, c_int, c_char_p, c_char_p)
# fmi3IntermediateUpdateCallback: environment, intermediateUpdateTime,
# intermediateVariableSetRequested, intermediateVariableGetAllowed,
# intermediateStepFinished, canReturnEarly, *earlyReturnRequested, *earlyReturnTime.
INTERMEDIATE_UPDATE = CFUNCTYPE(None, c_void_p, c_double, c_bool, c_bool, c_bool, c_bool,
                                POINTER(c_bool), POINTER(c_double))


class Fmi3Library:
    """The shared library of an FMI 3.0 FMU, extracted to `directory`."""

    def __init__(self, fmu, directory):
        root = Path(extract(fmu, unzipdir=str(directory)))
        self.description = read_model_description(str(root))
        identifier = self.description.modelExchange.modelIdentifier
        self.dll = ctypes.CDLL(str(root / "binaries" / "x86_64-linux" / f"{identifier}.so"))
        self.lines = []
        self._callbacks = []

        def log(_env, status, category, message):
            self.lines.append((status, category.decode(), message.decode()))

        self._log = LOG_MESSAGE(log)
        self.vr = {v.name: v.valueReference for v in self.description.modelVariables}

    def last_message(self):
        return self.lines[-1][2] if self.lines else ""

    def call(self, name, instance, *args):
        """fmi3<name>(instance, args...): its status."""
        function = getattr(self.dll, name)
        function.restype = c_int
        return function(c_void_p(instance), *args)

    def instantiate_co_simulation(self, event_mode_used=False, token=None,
                                  intermediate_update=None, early_return_allowed=False):
        """`intermediate_update`: a Python function with the arguments of
        INTERMEDIATE_UPDATE (kept alive with the library)."""
        f = self.dll.fmi3InstantiateCoSimulation
        f.restype = c_void_p
        token = (token or self.description.guid).encode()
        callback = INTERMEDIATE_UPDATE(intermediate_update) if intermediate_update else None
        self._callbacks.append(callback)  # alive as long as the library
        return f(b"test", token, None, c_bool(False), c_bool(False),
                 c_bool(event_mode_used), c_bool(early_return_allowed), None,
                 c_size_t(0), None, self._log, callback)

    def instantiate_model_exchange(self):
        f = self.dll.fmi3InstantiateModelExchange
        f.restype = c_void_p
        return f(b"test", self.description.guid.encode(), None, c_bool(False),
                 c_bool(False), None, self._log)

    def initialize(self, instance, start=0.0):
        assert self.call("fmi3EnterInitializationMode", instance, c_bool(False),
                         c_double(0.0), c_double(start), c_bool(False), c_double(0.0)) == OK
        assert self.call("fmi3ExitInitializationMode", instance) == OK

    def get_float64(self, instance, names, n_values):
        vrs = (c_uint32 * len(names))(*[self.vr[n] for n in names])
        values = (c_double * n_values)()
        status = self.call("fmi3GetFloat64", instance, vrs, c_size_t(len(names)),
                           values, c_size_t(n_values))
        return status, list(values)

    def set_float64(self, instance, names, values):
        vrs = (c_uint32 * len(names))(*[self.vr[n] for n in names])
        array = (c_double * len(values))(*values)
        return self.call("fmi3SetFloat64", instance, vrs, c_size_t(len(names)),
                         array, c_size_t(len(values)))

    def output_derivatives(self, instance, names, orders, n_values):
        """fmi3GetOutputDerivatives of the variables `names` with `orders`: status and
        the n_values values (arrays serialized element by element, pair by pair)."""
        vrs = (c_uint32 * len(names))(*[self.vr[n] for n in names])
        order_array = (c_int * len(orders))(*orders)
        values = (c_double * n_values)()
        status = self.call("fmi3GetOutputDerivatives", instance, vrs, c_size_t(len(names)),
                           order_array, values, c_size_t(n_values))
        return status, list(values)

    def do_step(self, instance, t, h):
        event, terminate, early = c_bool(), c_bool(), c_bool()
        last = c_double()
        status = self.call("fmi3DoStep", instance, c_double(t), c_double(h),
                           c_bool(True), byref(event), byref(terminate), byref(early),
                           byref(last))
        self.early_return = early.value
        return status, event.value, last.value

    def get_state(self, instance):
        state = c_void_p()
        assert self.call("fmi3GetFMUState", instance, byref(state)) == OK
        return state

    def serialize(self, instance, state):
        size = c_size_t()
        assert self.call("fmi3SerializedFMUStateSize", instance, state,
                         byref(size)) == OK
        data = (c_uint8 * size.value)()
        assert self.call("fmi3SerializeFMUState", instance, state, data,
                         size) == OK
        return bytes(data)

    def deserialize(self, instance, data):
        state = c_void_p()
        buffer = (c_uint8 * len(data))(*data)
        status = self.call("fmi3DeserializeFMUState", instance, buffer,
                           c_size_t(len(data)), byref(state))
        return status, state

    def derivative(self, name, instance, unknowns, knowns, seed, n_out):
        u = (c_uint32 * len(unknowns))(*[self.vr[n] for n in unknowns])
        k = (c_uint32 * len(knowns))(*[self.vr[n] for n in knowns])
        s = (c_double * len(seed))(*seed)
        out = (c_double * n_out)()
        status = self.call(name, instance, u, c_size_t(len(unknowns)), k,
                           c_size_t(len(knowns)), s, c_size_t(len(seed)), out,
                           c_size_t(n_out))
        return status, list(out)

    def dependencies(self, instance, name):
        n = c_size_t()
        vr = c_uint32(self.vr[name])
        assert self.call("fmi3GetNumberOfVariableDependencies", instance, vr,
                         byref(n)) == OK
        of_dependent = (c_size_t * n.value)()
        independents = (c_uint32 * n.value)()
        of_independents = (c_size_t * n.value)()
        kinds = (c_int * n.value)()
        assert self.call("fmi3GetVariableDependencies", instance, vr,
                         of_dependent, independents, of_independents, kinds, n) == OK
        return list(zip(of_dependent, independents, of_independents, kinds))

    def free(self, instance):
        self.dll.fmi3FreeInstance.restype = None
        self.dll.fmi3FreeInstance(c_void_p(instance))

