"""FMPy as the importer: validation, default experiments, reference results.

The references under tests/references were computed by scripts/make_references.py
from closed forms with numpy (never by running an FMU); every case is verified through
`cosim verify` in test_verify_references.py. The readers below are shared with
test_fmi3.py."""

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.validation import validate_fmu

from conftest import INTERFACES, MODELS, REFERENCES, fmu_path


@pytest.mark.parametrize("model", MODELS)
def test_validate_fmu_finds_no_problems(model):
    assert validate_fmu(fmu_path(model)) == []


@pytest.mark.parametrize("interface", INTERFACES)
@pytest.mark.parametrize("model", ["Planner", "PID"])  # Pss3Plant: test_pss3_plant.py
def test_default_experiment_runs_with_no_options(model, interface):
    result = simulate_fmu(fmu_path(model), fmi_type=interface)
    experiment = read_model_description(fmu_path(model)).defaultExperiment
    assert result["time"][0] == pytest.approx(float(experiment.startTime))
    assert result["time"][-1] == pytest.approx(float(experiment.stopTime))
    last = result[-1]
    if model == "Planner":
        # Expected: the default targets qf = (0.5, -0.3, 0.8) rad, at rest after tf.
        for axis, qf in enumerate([0.5, -0.3, 0.8], start=1):
            assert last[f"q[{axis}]"] == pytest.approx(qf, abs=1e-12)
            assert last[f"qdot[{axis}]"] == 0.0
    else:
        # Expected: u = Kp e + Ki e t + Kd e/Tf exp(-t/Tf) at t = 2 s with the defaults
        # (Kp 1, Ki 0.5, Kd 0.1, Tf 0.05; e = 1, 0.5, -0.25).
        for channel, e in enumerate([1.0, 0.5, -0.25], start=1):
            expected = e + 0.5 * e * 2.0 + 0.1 * e / 0.05 * np.exp(-40.0)
            assert last[f"u[{channel}]"] == pytest.approx(expected, abs=1e-6)


def reference_cases():
    cases = []
    for model_dir in sorted(REFERENCES.iterdir()):
        for case_dir in sorted(model_dir.iterdir()):
            for interface in INTERFACES:
                cases.append(pytest.param(model_dir.name, case_dir, interface,
                                          id=f"{model_dir.name}-{case_dir.name}-{interface}"))
    return cases


def read_signals(path):
    """A CSV of quoted names (time first) as a structured array with plain names, the
    form FMPy's simulate_fmu takes as input= (interpolated linearly in time)."""
    raw = np.genfromtxt(path, delimiter=",", names=True, deletechars="")
    names = [n.strip('"') for n in raw.dtype.names]
    signals = np.zeros(len(raw), dtype=[(n, np.float64) for n in names])
    for old, new in zip(raw.dtype.names, names):
        signals[new] = raw[old]
    return signals


def read_options(path):
    options = {}
    for line in path.read_text().splitlines():
        key, value = line.split(",")
        options[key.strip()] = float(value)
    return options
