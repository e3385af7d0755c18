"""The scalar-only FMI 3.0 variant (dist/fmi3-scalar/, issue 21): every FMI 2.0 scalar
an FMI 3.0 scalar with the same name and value reference, served by the same binary
under its own instantiationToken. Truths: the FMI 2.0 description (names, references,
units, starts, bounds), the FMI 3.0 array build and the FMI 2.0 build (simulations)."""

import ctypes
from xml.etree import ElementTree

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

from conftest import DIST, MODELS, fmu3, fmu3_path, fmu_path
from test_fmi3 import AGREEMENT, simulate
from test_fmi3_calls import ERROR, dependencies, initialize, last_message
from test_importers import reference_cases


def scalar_path(model):
    path = DIST / "fmi3-scalar" / f"{model}.fmu"
    if not path.exists():
        pytest.fail(f"{path} is missing: run scripts/build-fmus.sh first")
    return str(path)


@pytest.mark.parametrize("model", MODELS)
def test_every_fmi2_scalar_is_the_same_fmi3_scalar(model):
    # Expected: the FMI 2.0 description, variable by variable, and no array (the
    # plant's event indicators, no FMI 2.0 variable, are scalars too).
    assert validate_fmu(scalar_path(model)) == []
    md2 = read_model_description(fmu_path(model))
    md3 = read_model_description(scalar_path(model))
    scalars = {v.name: v for v in md3.modelVariables}
    for v in md2.modelVariables:
        s = scalars[v.name]
        assert s.valueReference == v.valueReference, v.name
        assert s.shape is None or s.shape == (), v.name
        assert (s.causality, s.variability, s.unit) == (v.causality, v.variability,
                                                         v.unit), v.name
        assert (s.start, s.min, s.max) == (v.start, v.min, v.max), v.name
    arrays = [v.name for v in md3.modelVariables if v.shape not in (None, ())]
    assert arrays == []
    assert md3.numberOfContinuousStates == md2.numberOfContinuousStates
    assert md3.numberOfEventIndicators == md2.numberOfEventIndicators
    assert md3.guid == md2.guid + "-scalar"


@pytest.mark.parametrize("model", MODELS)
def test_per_scalar_get_and_set_with_one_value_each(model, tmp_path):
    # Expected: each Float64 scalar reads its FMI 2.0 start value with nValues = 1, and a
    # set parameter reads back; the array build refuses nValues = 1 for the same
    # reference (its variable there is the whole array).
    md2 = read_model_description(fmu_path(model))
    fmu = fmu3(scalar_path(model), tmp_path / "scalar")
    fmu.enterInitializationMode()
    checked = 0
    for v in md2.modelVariables:
        if v.type != "Real" or v.start is None:
            continue
        assert fmu.getFloat64([v.valueReference], 1) == [float(v.start)], (v.name,
                                                                          last_message(fmu))
        if v.causality == "parameter" and v.variability == "tunable":
            fmu.setFloat64([v.valueReference], [float(v.start) + 0.25])
            assert fmu.getFloat64([v.valueReference], 1) == [float(v.start) + 0.25]
        checked += 1
    assert checked > 0
    fmu.freeInstance()
    arrays = fmu3(fmu3_path(model), tmp_path / "arrays")
    sizes = {v.valueReference: v.shape for v in arrays.description.modelVariables}
    vr = next(r for r, shape in sizes.items() if shape not in (None, ()))
    refs = (ctypes.c_uint32 * 1)(vr)
    values = (ctypes.c_double * 1)()
    status = arrays.dll.fmi3GetFloat64(arrays.component, refs, 1, values, 1)
    assert status == ERROR


@pytest.mark.parametrize("model, case_dir, interface", reference_cases())
def test_scalar_variant_equals_the_array_build_and_fmi2(model, case_dir, interface):
    # Expected: the same binary and model code behind three descriptions; the scalar
    # variant takes the FMI 2.0 names as they are. Model Exchange reads the event
    # indicators (scalars here). Every reference case of every model.
    md3 = read_model_description(fmu3_path(model))
    time2, fmi2, _, _ = simulate(fmu_path(model), None, case_dir, model, interface, False)
    time3, fmi3, _, _ = simulate(fmu3_path(model), md3, case_dir, model, interface, True)
    times, scalar, _, _ = simulate(scalar_path(model), None, case_dir, model, interface,
                                   False)
    assert np.array_equal(times, time3) and np.array_equal(times, time2)
    worst = max(max(np.max(np.abs(scalar[s] - fmi3[s])), np.max(np.abs(scalar[s] - fmi2[s])))
                for s in scalar)
    print(f"{model}/{case_dir.name}/{interface}: scalar vs array/FMI 2.0 {worst:.3g}")
    assert worst <= AGREEMENT


@pytest.mark.parametrize("model", MODELS)
def test_ecos_runs_the_scalar_variant_like_the_fmi2_build(model):
    # Expected: ecos (FMI Library) stepping the scalar variant reads, after every step,
    # what it reads from the FMI 2.0 build (same binary; that run equals FMPy:
    # test_importers_alone.py). It cannot address the array build's elements
    # ("No real property fmu::u[1]"), the reason for this variant.
    from importer_runs import run_fmu_ecos
    md = read_model_description(fmu_path(model))
    experiment = md.defaultExperiment
    h = float(experiment.stepSize)
    steps = round((float(experiment.stopTime) - float(experiment.startTime)) / h)
    outputs = [v.name for v in md.modelVariables if v.causality == "output" and v.type == "Real"]
    expected = run_fmu_ecos(fmu_path(model), outputs, steps, h, {})
    rows = run_fmu_ecos(scalar_path(model), outputs, steps, h, {})
    assert np.ptp(expected[:, 1:], axis=0).max() > 0  # the outputs move
    assert np.abs(rows - expected).max() <= AGREEMENT


@pytest.mark.parametrize("model", MODELS)
def test_runtime_dependencies_are_those_of_the_description(model, tmp_path):
    # Expected: fmi3GetVariableDependencies of the scalar view (computed at run time
    # from the instance's table) lists, for every output and state derivative, the value
    # references of the description's `dependencies` (written by the build crate), all
    # with element index 0 (scalars); without `dependencies`, every known (the inputs
    # and the states).
    fmu = fmu3(scalar_path(model), tmp_path)
    names = {v.valueReference: v.name for v in fmu.description.modelVariables}
    root = ElementTree.parse(tmp_path / "modelDescription.xml").getroot()
    variables = fmu.description.modelVariables
    knowns = sorted([v.valueReference for v in variables if v.causality == "input"]
                    + [v.derivative.valueReference for v in variables if v.derivative])
    unknowns = [u for u in root.find("ModelStructure")
                if u.tag in ("Output", "ContinuousStateDerivative")]
    assert unknowns
    for u in unknowns:
        listed = u.attrib.get("dependencies")
        declared = knowns if listed is None else sorted(int(r) for r in listed.split())
        found = dependencies(fmu, names[int(u.attrib["valueReference"])])
        assert sorted(vr for _, vr, _, _ in found) == declared, u.attrib
        assert {(i, k) for i, _, k, _ in found} <= {(0, 0)}
    fmu.freeInstance()


def test_each_event_indicator_scalar_reads_its_element_of_the_array(tmp_path):
    # Expected: the array build's eventIndicators (nValues = 6) after initialization at
    # the defaults, element k in the scalar eventIndicators[k].
    arrays = fmu3(fmu3_path("Pss3Plant"), tmp_path / "arrays")
    scalars = fmu3(scalar_path("Pss3Plant"), tmp_path / "scalar")
    initialize(arrays)
    initialize(scalars)
    expected = arrays.getFloat64([arrays.vr["eventIndicators"]], 6)
    assert any(expected)
    for k, z in enumerate(expected):
        assert scalars.getFloat64([scalars.vr[f"eventIndicators[{k + 1}]"]], 1) == [z]
    arrays.freeInstance()
    scalars.freeInstance()
