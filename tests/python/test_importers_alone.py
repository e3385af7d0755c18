"""Each FMI 2.0 FMU alone (Co-Simulation, its default experiment) in libcosim and ecos,
the two independent importers from PyPI (both built on the FMI Library), against the
same FMU stepped by FMPy (tests/python/fmpy_loops.py, on the importer's time grid): same binary, same calls, so every Real output after every step must agree
to 1e-12 (measured 0, bit for bit)."""

import numpy as np
import pytest
from fmpy import read_model_description

from conftest import MODELS, fmu_path
from fmpy_loops import GRIDS, run_alone
from importer_runs import run_fmu_ecos, run_fmu_libcosim

RUNNERS = {"libcosim": run_fmu_libcosim, "ecos": run_fmu_ecos}
# The plant's defaults are an equilibrium (gravity balanced, no input): a disturbance
# makes it move into its end stops. Planner and PID move with their defaults.
START = {"Pss3Plant": {"disturbanceTorque[1]": 2.0, "disturbanceTorque[2]": -1.0}}


@pytest.mark.parametrize("importer", sorted(RUNNERS))
@pytest.mark.parametrize("model", MODELS)
def test_fmu_alone_equals_fmpy(model, importer):
    fmu = fmu_path(model)
    md = read_model_description(fmu)
    experiment = md.defaultExperiment
    h = float(experiment.stepSize)
    steps = round((float(experiment.stopTime) - float(experiment.startTime)) / h)
    outputs = [v.name for v in md.modelVariables if v.causality == "output" and v.type == "Real"]
    start = START.get(model, {})
    expected = run_alone(fmu, outputs, GRIDS[importer](steps, h), start)
    # Not a constant run: the outputs move (the truth is FMPy's, not the start values).
    assert np.ptp(expected[:, 1:], axis=0).max() > 0.1
    rows = RUNNERS[importer](fmu, outputs, steps, h, start)
    assert np.abs(rows[:, 0] - expected[:, 0]).max() < 1e-12
    error = np.abs(rows[:, 1:] - expected[:, 1:]).max(axis=0)
    worst = int(np.argmax(error))
    assert error[worst] <= 1e-12, f"{outputs[worst]}: {error[worst]:.3g}"
