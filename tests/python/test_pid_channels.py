"""The N-channel PID through FMPy 0.3.32: the FMI 3.0 PID set to six channels by its
structural parameter `nChannels` (FMU3Slave: enterConfigurationMode, setUInt64,
exitConfigurationMode) and stepped 100 times with every per-channel array at six
elements, measurements moving each step and two channels limited.

Expected values: the three-channel FMU run twice, the FMI 2.0 PID (dist/PID.fmu, whose
channel count is fixed at three and which no resize reaches) with the gains, limits and
inputs of channels 1-3, then of channels 4-6: each of the six outputs must equal its
channel's in those runs to 1e-12 at every step (the channels are independent), and so
must the output derivatives of orders 1 and 2 at the end. FMPy's
simulate_fmu sets start values in Instantiated (fmpy/simulation.py, apply_start_values),
where FMI 3.0 does not let a structural parameter be set: the FMU refuses it there with a
line naming Configuration Mode; the six-channel Model Exchange instance has twelve
continuous states, and the clocked output uSampled six elements."""

import math
from ctypes import c_double, c_int32, c_uint32

import pytest
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

from conftest import fmu3, fmu3_path, fmu_path, refused

N = 6
STEPS = 100
H = 0.01
PARAMETERS = {
    "Kp": [1.0, 2.0, 0.5, 1.5, 3.0, 0.8],
    "Ki": [0.5, 0.1, 1.0, 0.2, 0.7, 0.3],
    "Kd": [0.1, 0.05, 0.2, 0.0, 0.1, 0.3],
    "Tf": [0.05, 0.02, 0.1, 0.05, 0.03, 0.08],
    "uMin": [-1.0, -1.0, -0.3, -2.0, -0.5, -1.0],
    "uMax": [1.0, 1.0, 0.3, 2.0, 0.5, 1.0],
}
LIMITED = [False, False, True, False, True, False]
SETPOINT = [1.0, 0.5, -0.25, 0.8, -1.0, 0.3]


def measurement(k, t):
    """Channel k's measurement at time t: a different slow wave per channel."""
    return 0.4 * math.sin(0.7 * (k + 1) * t + k)


def six_channels(tmp_path):
    """u of the six-channel FMI 3.0 PID at each step, and its output derivatives of
    orders 1 and 2 at the end (the array through FMPy's ctypes function)."""
    fmu = fmu3(fmu3_path("PID"), tmp_path / "fmi3")
    vr = fmu.vr
    fmu.enterConfigurationMode()
    fmu.setUInt64([vr["nChannels"]], [N])
    fmu.exitConfigurationMode()
    for name, values in PARAMETERS.items():
        fmu.setFloat64([vr[name]], values)
    fmu.setBoolean([vr["limitOutput"]], LIMITED)
    fmu.setFloat64([vr["setpoint"]], SETPOINT)
    fmu.enterInitializationMode(startTime=0.0)
    fmu.exitInitializationMode()
    assert list(fmu.getUInt64([vr["nChannels"]])) == [N]
    # The clocked output is sized by the channel count too (zero before a tick).
    assert list(fmu.getFloat64([vr["uSampled"]], N)) == [0.0] * N
    outputs, t = [], 0.0
    for _ in range(STEPS):
        fmu.setFloat64([vr["measurement"]], [measurement(k, t) for k in range(N)])
        fmu.doStep(t, H)
        t += H
        outputs.append(list(fmu.getFloat64([vr["u"]], N)))
    slopes = []
    for order in (1, 2):
        values = (c_double * N)()
        fmu.fmi3GetOutputDerivatives(fmu.component, (c_uint32 * 1)(vr["u"]), 1,
                                     (c_int32 * 1)(order), values, N)
        slopes.append(list(values))
    fmu.terminate()
    fmu.freeInstance()
    return outputs, slopes


def three_channels(tmp_path, first):
    """u of the FMI 2.0 PID (three channels) set to channels first..first+2, and its
    output derivatives of orders 1 and 2 at the end."""
    directory = extract(fmu_path("PID"), unzipdir=str(tmp_path / f"fmi2-{first}"))
    description = read_model_description(directory)
    vr = {v.name: v.valueReference for v in description.modelVariables}
    fmu = FMU2Slave(guid=description.guid, unzipDirectory=directory,
                    modelIdentifier=description.coSimulation.modelIdentifier)
    fmu.instantiate()
    channels = range(first, first + 3)

    def refs(name):
        return [vr[f"{name}[{c + 1}]"] for c in range(3)]

    for name, values in PARAMETERS.items():
        fmu.setReal(refs(name), [values[k] for k in channels])
    fmu.setBoolean(refs("limitOutput"), [LIMITED[k] for k in channels])
    fmu.setReal(refs("setpoint"), [SETPOINT[k] for k in channels])
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    outputs, t = [], 0.0
    for _ in range(STEPS):
        fmu.setReal(refs("measurement"), [measurement(k, t) for k in channels])
        fmu.doStep(t, H)
        t += H
        outputs.append(list(fmu.getReal(refs("u"))))
    slopes = [fmu.getRealOutputDerivatives(refs("u"), [order] * 3) for order in (1, 2)]
    fmu.terminate()
    fmu.freeInstance()
    return outputs, slopes


def test_six_channels_equal_the_three_channel_fmu_run_twice(tmp_path):
    six, slopes = six_channels(tmp_path)
    (low, low_slopes), (high, high_slopes) = three_channels(tmp_path, 0), three_channels(tmp_path, 3)
    truth = [a + b for a, b in zip(low, high)]
    assert len(six) == len(truth) == STEPS
    worst = max(abs(x - y) for row, ref in zip(six, truth) for x, y in zip(row, ref))
    assert worst <= 1e-12, worst
    # The output derivatives of all six channels, orders 1 and 2.
    for order in range(2):
        expected = low_slopes[order] + high_slopes[order]
        assert max(abs(x - y) for x, y in zip(slopes[order], expected)) <= 1e-12
    assert any(abs(x) > 1e-3 for x in slopes[0]), slopes
    # The limits bind on the limited channels: the test exercises them.
    assert any(abs(row[2]) == pytest.approx(0.3) for row in six)


def test_structural_parameter_outside_configuration_mode_and_model_exchange(tmp_path):
    fmu = fmu3(fmu3_path("PID"), tmp_path / "instantiated")
    vr = fmu.vr["nChannels"]
    # What simulate_fmu does with start_values={"nChannels": 6}: set in Instantiated.
    assert refused(fmu.setUInt64, [vr], [N]) == 3  # fmi3Error
    assert any("Configuration Mode" in line for _, _, line in fmu.lines), fmu.lines
    fmu.freeInstance()
    me = fmu3(fmu3_path("PID"), tmp_path / "me", model_exchange=True)
    me.enterConfigurationMode()
    me.setUInt64([me.vr["nChannels"]], [N])
    me.exitConfigurationMode()
    me.enterInitializationMode(startTime=0.0)
    me.exitInitializationMode()
    assert me.getNumberOfContinuousStates() == 2 * N
    me.terminate()
    me.freeInstance()
