"""The FMI 3.0 FMUs (dist/fmi3/) through FMPy: validation, the default experiments,
the agreement of the FMI 2.0 and FMI 3.0 builds of each model on the reference cases
(tests/references) on both interfaces (the same model code behind two front-ends: they
must agree to 1e-12; each build against the references themselves:
test_verify_references.py); Co-Simulation event mode at the plant's end stops."""

import json

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.validation import validate_fmu

import fmi3_names
from conftest import INTERFACES, MODELS, fmu3_path, fmu_path
from robofmu.fmi3 import scalar_names
from test_importers import read_options, read_signals, reference_cases

# The FMI 2.0 and FMI 3.0 builds call the same model code with the same arguments in
# the same order, so they agree to rounding; 1e-12 is the bound.
AGREEMENT = 1e-12


@pytest.mark.parametrize("model", MODELS)
def test_validate_fmu_finds_no_problems(model):
    assert validate_fmu(fmu3_path(model)) == []


@pytest.mark.parametrize("model", MODELS)
def test_every_three_vector_is_one_array(model):
    # Expected: each FMI 2.0 family x[1], x[2], x[3] is the FMI 3.0 array x of
    # dimension 3 with the same type, causality and unit.
    md2 = read_model_description(fmu_path(model))
    md3 = read_model_description(fmu3_path(model))
    arrays = {v.name: v for v in md3.modelVariables}
    for v in md2.modelVariables:
        base, index = fmi3_names.split(v.name)
        if index is None:
            continue
        array = arrays[base]
        assert array.shape == (3,), base
        assert array.causality == v.causality and array.unit == v.unit, base
        assert {"Real": "Float64", "Integer": "Int32"}.get(v.type, v.type) == array.type
    assert md3.numberOfContinuousStates == md2.numberOfContinuousStates
    assert md3.numberOfEventIndicators == md2.numberOfEventIndicators



@pytest.mark.parametrize("model", MODELS)
def test_the_harness_finds_every_fmi2_scalar_in_the_fmi3_arrays(model):
    # Truth: the FMI 2.0 build's description of the same table, each scalar's array
    # and element parsed from its name here (a derivative's from its state's name), the
    # harness's from the FMI 3.0 <Dimension> elements. FMI 3.0 adds time, the event
    # indicators, the clocked partitions (FMI 2.0 has no clocks) and the structural
    # parameters (FMI 2.0 has none) only.
    md2 = read_model_description(fmu_path(model))
    names = scalar_names(read_model_description(fmu3_path(model)).modelVariables)
    for v in md2.modelVariables:
        state = v.derivative
        base, index = fmi3_names.split(state.name if state is not None else v.name)
        expected = f"der({base})" if state is not None else base
        variable, element = names[v.name]
        assert (variable.name, element) == (expected, index), v.name
    indicators = {f"eventIndicators[{k}]" for k in range(1, md2.numberOfEventIndicators + 1)}
    added = {"time"} | indicators | CLOCKED.get(model, set()) | STRUCTURAL.get(model, set())
    assert set(names) - {v.name for v in md2.modelVariables} == added


# The variables of each FMU's clocked partition: its clock, the clock's period
# parameter and its clocked outputs (docs/profiles.md, Dynamics Controller).
CLOCKED = {
    "ComputedTorque": {"sampleClock", "samplePeriod", "uSampled[1]", "uSampled[2]", "uSampled[3]"},
    "PID": {"sampleClock", "samplePeriod", "uSampled[1]", "uSampled[2]", "uSampled[3]"},
}
# The structural parameters of each FMU (FMI 3.0 only; docs/profiles.md, resizable
# parameter arrays).
STRUCTURAL = {"PID": {"nChannels"}}


def simulate(path, description, case, model, interface, fmi3):
    """One reference case through FMPy; FMI 3.0 names translated to the arrays."""
    case_dir = case
    options = read_options(case_dir / f"{model}_ref.opt")
    spec = json.loads((case_dir / "case.json").read_text())
    reference = np.genfromtxt(case_dir / f"{model}_ref.csv", delimiter=",", names=True,
                              deletechars="")
    signals = [n.strip('"') for n in reference.dtype.names[1:]]
    inputs_file = case_dir / f"{model}_input.csv"
    inputs = read_signals(inputs_file) if inputs_file.exists() else None
    start = spec["start_values"]
    output = signals
    if fmi3:
        start = fmi3_names.start_values(start, description)
        inputs = None if inputs is None else fmi3_names.input_signals(inputs, description)
        output = fmi3_names.output_names(signals)
    result = simulate_fmu(
        path,
        fmi_type=interface,
        start_time=options["StartTime"],
        stop_time=options["StopTime"],
        output_interval=options["StepSize"],
        step_size=options["StepSize"] if interface == "CoSimulation" else None,
        relative_tolerance=options["RelTol"],
        start_values=start,
        input=inputs,
        output=output,
    )
    series = {s: (fmi3_names.column(result, s) if fmi3 else result[s]) for s in signals}
    return result["time"], series, reference, spec


@pytest.mark.parametrize("model,case_dir,interface", reference_cases())
def test_both_builds_agree_on_every_reference_case(model, case_dir, interface):
    md3 = read_model_description(fmu3_path(model))
    time2, fmi2, _, _ = simulate(fmu_path(model), None, case_dir, model, interface, False)
    time3, fmi3, _, _ = simulate(fmu3_path(model), md3, case_dir, model, interface, True)
    assert np.array_equal(time2, time3)
    # The verdict against the reference: test_verify_references.py (cosim verify).
    worst = 0.0
    for signal in fmi3:
        worst = max(worst, np.max(np.abs(fmi3[signal] - fmi2[signal])))
    print(f"{model}/{case_dir.name}/{interface}: FMI 2.0 vs 3.0 max difference {worst:.3g}")
    assert worst <= AGREEMENT


@pytest.mark.parametrize("interface", INTERFACES)
@pytest.mark.parametrize("model", ["Planner", "PID"])  # Pss3Plant: the cases above
def test_default_experiment_runs_with_no_options(model, interface):
    # Expected: as for FMI 2.0 (test_importers.py): the planner at rest at its default
    # targets qf = (0.5, -0.3, 0.8) rad, the PID's closed form at t = 2 s.
    result = simulate_fmu(fmu3_path(model), fmi_type=interface)
    experiment = read_model_description(fmu3_path(model)).defaultExperiment
    assert result["time"][-1] == pytest.approx(float(experiment.stopTime))
    last = result[-1]
    if model == "Planner":
        assert last["q"] == pytest.approx([0.5, -0.3, 0.8], abs=1e-12)
        assert list(last["qdot"]) == [0.0, 0.0, 0.0]
    else:
        e = np.array([1.0, 0.5, -0.25])
        expected = e + 0.5 * e * 2.0 + 0.1 * e / 0.05 * np.exp(-40.0)
        assert last["u"] == pytest.approx(expected, abs=1e-6)


def test_co_simulation_event_mode_marks_every_end_stop_contact():
    # Expected: with eventModeUsed, fmi3DoStep reports eventHandlingNeeded exactly at
    # the steps where an end-stop contact (atStop) changed; FMPy then passes through
    # Event Mode and records the instant twice. Same run as the FMI 2.0 end-stop test
    # (test_pss3_plant.py): rolling down into the lower stops and bouncing off.
    md3 = read_model_description(fmu3_path("Pss3Plant"))
    start = fmi3_names.start_values(
        {"theta0[2]": 0.003, "theta0[3]": 2.4, "omega0[1]": 0.01, "omega0[3]": -0.3}, md3)
    result = simulate_fmu(fmu3_path("Pss3Plant"), fmi_type="CoSimulation", stop_time=1.0,
                          step_size=1e-3, output_interval=1e-3, start_values=start,
                          output=["atStop"], use_event_mode=True)
    time = result["time"]
    flags = result["atStop"]
    repeated = time[1:][np.diff(time) == 0]
    changed = time[1:][np.any(np.diff(flags, axis=0) != 0, axis=1)]
    print(f"{len(repeated)} events at {np.round(repeated, 3)} s")
    assert len(repeated) >= 6  # three actuators, each into and out of its stop
    assert np.array_equal(np.unique(repeated), np.unique(changed))


def test_co_simulation_returns_early_at_the_end_stop_contacts():
    # Expected: with earlyReturnAllowed, a step in which a contact begins or ends
    # stops just after it: there an actuator displacement l[i] equals the contact edge,
    # strokeMin -+ 1 nm (hysteresis, fmus/pss3-plant), to within the bisection's
    # 2^-30 of the 1 ms step times |lDot| (< 1e-12 m), where the 1 ms grid alone is off
    # by up to |lDot| h = 3e-4 m. Independent truth: the stroke parameter.
    md3 = read_model_description(fmu3_path("Pss3Plant"))
    stroke_min = float({v.name: v for v in md3.modelVariables}["strokeMin"].start)
    start = fmi3_names.start_values(
        {"theta0[2]": 0.003, "theta0[3]": 2.4, "omega0[1]": 0.01, "omega0[3]": -0.3}, md3)
    result = simulate_fmu(fmu3_path("Pss3Plant"), fmi_type="CoSimulation", stop_time=1.0,
                          step_size=1e-3, output_interval=1e-3, start_values=start,
                          output=["l", "atStop"], use_event_mode=True,
                          early_return_allowed=True)
    time = result["time"]
    off_grid = np.abs(time * 1e3 - np.round(time * 1e3)) > 1e-6
    assert off_grid.sum() >= 6  # three actuators, each into and out of its stop
    distance = np.min(np.abs(np.abs(result["l"][off_grid] - stroke_min) - 1e-9), axis=1)
    print(f"{off_grid.sum()} early returns, largest distance to the contact edge "
          f"{distance.max():.2e} m")
    assert distance.max() < 1e-10
