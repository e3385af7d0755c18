"""The closed loop as FMPy's own container FMU (fmpy.container_fmu, FMPy's Rust runtime
shipped in the wheel), built from our FMI 3.0 PID and plant (the scalar-only view, whose
variable names are the scenario's) and run by FMPy's simulate_fmu: what a user who builds
a system in FMPy gets (issue 45). The regulation scenario's planner is constant (a plan
from a pose to the same pose; tested below), so the PID's setpoint inputs hold its start
values.

The container steps every component from t_k with the inputs it holds, then transfers
the connections one after another in the configuration's order (FMPy's
native/container-fmu, `doFixedStep` and `updateConnections`), reading each source when
its connection comes: the PID's inputs of t_{k+1} are set before its output is read for
the plant, so the plant applies the PID's answer to the current inputs (not a Jacobi
scheme: libcosim and ecos read every source first). Its time is accumulated step by
step (ecos's grid). Two truths:
- the same scheme written on FMPy's FMI 2.0 API (`sequential_loop` below, with the
  initialization of fmpy_loops.py): plant angles and rates equal to 1e-12 (same
  binaries; the FMI 2.0 and FMI 3.0 front-ends share the model code);
- our master (robofmu.master, sampled coupling with extrapolated inputs) within a
  tolerance derived as in test_importers_ssp.py: the scheme's difference from the
  master is first order in h, so its deviation at h is about twice the deviation at
  h/2; the tolerance is 2.5 times the deviation of the sequential loop from the master
  at h/2.

FMI 2.0 is not offered by FMPy's container path: test_fmi2_container_fails names how it
fails (docs/interoperability.md, "FMPy's container FMU")."""

from __future__ import annotations

import dataclasses
import json
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.container_fmu import Configuration
from fmpy.container_fmu.cli import create_container_fmu
from fmpy.container_fmu.config import Component, Connection
from fmpy.model_description import CoSimulation, DefaultExperiment, ModelDescription, ModelVariable

from conftest import DIST
from fmpy_loops import ecos_grid, run_jacobi, transfer_in_turn

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from robofmu.master import Master  # noqa: E402
from robofmu.scenario import load_scenario  # noqa: E402

SIGNALS = [f"plant.{name}[{i}]" for name in ("theta", "thetaDot") for i in (1, 2, 3)]
FMI3_TYPES = {"Float64": "Float64", "Int32": "Int32", "Boolean": "Boolean",
              "Real": "Float64", "Integer": "Int32"}


def text(value) -> str:
    """A start value as the container's configuration holds it (parsed by its runtime)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    return repr(value) if isinstance(value, float) else str(value)


def pid_and_plant(scenario):
    """The scenario without its planner, whose outputs are constant in the regulation
    scenario (its start and end poses are equal, its rates zero): the PID's setpoint
    inputs get the planner's start values instead, as start values."""
    planner = scenario.parameters["planner"]
    held = {"q": "q0", "qdot": "qdot0"}
    setpoints = {}
    for c in scenario.connections:
        if c.source.alias == "planner":
            name, index = c.source.variable.split("[")
            setpoints[c.target.variable] = planner[f"{held[name]}[{index}"]
    kept = ("pid", "plant")
    parameters = {alias: dict(scenario.parameters[alias]) for alias in kept}
    parameters["pid"].update(setpoints)
    return dataclasses.replace(
        scenario, fmus={alias: scenario.fmus[alias] for alias in kept}, order=list(kept),
        parameters=parameters,
        connections=[c for c in scenario.connections if c.source.alias in kept])


def configuration(scenario, fmi_version: str, folder: Path) -> Configuration:
    """The container of the scenario's FMUs (from `folder`), its connections, its
    parameters (and held inputs) as container parameters (inputs) with their values as
    start values, and the plant's angles and rates as outputs."""
    components, variables = {}, {}
    for alias in scenario.order:
        filename = folder / scenario.fmus[alias].name
        md = read_model_description(str(filename))
        components[alias] = Component(name=alias, filename=filename, modelDescription=md)
        variables[alias] = {v.name: v for v in md.modelVariables}
    md = ModelDescription(fmiVersion=fmi_version, modelName=f"{scenario.name}_container",
                          instantiationToken="{6b9f7d1c-45a0-4c3e-9a51-0c6c2b2f4a45}")
    md.coSimulation = CoSimulation(modelIdentifier="container_fmu",
                                   fixedInternalStepSize=scenario.step_size)
    md.defaultExperiment = DefaultExperiment(startTime="0", stopTime=repr(scenario.stop_time),
                                             stepSize=repr(scenario.step_size))
    mappings: dict = {}
    if fmi_version.startswith("3"):
        time = ModelVariable(name="time", type="Float64", causality="independent",
                             variability="continuous")
        md.modelVariables.append(time)
    for alias, assignments in scenario.parameters.items():
        for name, value in assignments.items():
            inner = variables[alias][name]
            given = ("input", "continuous", None) if inner.causality == "input" else (
                "parameter", inner.variability, "exact")
            v = ModelVariable(name=f"{alias}.{name}", type=FMI3_TYPES[inner.type]
                              if fmi_version.startswith("3") else inner.type,
                              causality=given[0], variability=given[1], initial=given[2])
            v.start = text(value)
            md.modelVariables.append(v)
            mappings[v] = [(components[alias], inner)]
    for signal in SIGNALS:
        alias, name = signal.split(".", 1)
        inner = variables[alias][name]
        v = ModelVariable(name=signal, type=inner.type, causality="output",
                          variability="continuous", initial="calculated")
        md.modelVariables.append(v)
        mappings[v] = [(components[alias], inner)]
    connections = [Connection(startElement=components[c.source.alias],
                              startConnectors=[variables[c.source.alias][c.source.variable]],
                              endElement=components[c.target.alias],
                              endConnectors=[variables[c.target.alias][c.target.variable]])
                   for c in scenario.connections]
    return Configuration(parallelDoStep=False, modelDescription=md,
                         components=list(components.values()), connections=connections,
                         variableMappings=mappings)


def build(scenario, fmi_version: str, folder: Path, out: Path) -> Path:
    unzipdir = out / "unzipped"
    unzipdir.mkdir(parents=True, exist_ok=True)
    filename = out / f"{scenario.name}_container.fmu"
    create_container_fmu(configuration(scenario, fmi_version, folder), unzipdir, filename)
    return filename


def run_alone_rows(scenario, signals) -> np.ndarray:
    return sequential_loop(scenario, ecos_grid(scenario.steps, scenario.step_size), signals)


def sequential_loop(scenario, grid, signals=SIGNALS) -> np.ndarray:
    """Rows (time, *signals) at t_0 .. t_N of the container's scheme on FMPy's FMI 2.0
    API: every FMU steps, then each connection is transferred in turn."""
    return run_jacobi(scenario, signals, grid, exchange=transfer_in_turn)


def master_rows(scenario) -> np.ndarray:
    result = Master(scenario).run()
    return np.column_stack([result.time] + [result.columns[s] for s in SIGNALS])


@pytest.fixture(scope="module")
def regulation():
    return load_scenario(ROOT / "scenarios" / "regulation.toml")


def test_the_planner_is_constant_in_the_regulation_scenario(regulation):
    # Why the container may hold PID and plant only: the planner's outputs equal its
    # start values at every step (its plan from a pose to the same pose).
    planner = dataclasses.replace(regulation, fmus={"planner": regulation.fmus["planner"]},
                                  order=["planner"], connections=[],
                                  parameters={"planner": regulation.parameters["planner"]})
    names = [f"planner.{n}[{i}]" for n in ("q", "qdot") for i in (1, 2, 3)]
    rows = run_alone_rows(planner, names)
    start = regulation.parameters["planner"]
    expected = [start[f"{n}0[{i}]"] for n in ("q", "qdot") for i in (1, 2, 3)]
    assert (rows[:, 1:] == np.array(expected)).all()


def test_fmi3_container_equals_its_scheme_and_the_master(regulation, tmp_path):
    scenario = pid_and_plant(regulation)
    container = build(scenario, "3.0", DIST / "fmi3-scalar", tmp_path)
    result = simulate_fmu(str(container), stop_time=scenario.stop_time,
                          step_size=scenario.step_size, output=SIGNALS)
    rows = np.column_stack([result["time"]] + [result[s] for s in SIGNALS])
    assert len(rows) == scenario.steps + 1
    loop = sequential_loop(scenario, ecos_grid(scenario.steps, scenario.step_size))
    assert np.abs(rows[:, 0] - loop[:, 0]).max() < 1e-12
    error = np.abs(rows[:, 1:] - loop[:, 1:]).max(axis=0)
    worst = int(np.argmax(error))
    assert error[worst] <= 1e-12, f"{SIGNALS[worst]}: {error[worst]:.3g}"
    # Our master, within the coupling tolerance.
    half = dataclasses.replace(scenario, step_size=scenario.step_size / 2)
    loop_half = sequential_loop(half, ecos_grid(half.steps, half.step_size))
    master_half = master_rows(dataclasses.replace(regulation, step_size=half.step_size))
    tolerance = 2.5 * np.abs(loop_half[:, 1:] - master_half[:, 1:]).max(axis=0)
    deviation = np.abs(rows[:, 1:] - master_rows(regulation)[:, 1:]).max(axis=0)
    for name, d, tol in zip(SIGNALS, deviation, tolerance):
        assert d <= tol, f"{name}: {d:.3g} > {tol:.3g}"
    # The coupling is felt and shrinks as a first-order error does.
    assert (deviation >= 0.2 * tolerance).all(), deviation / tolerance
    # The parameters reached the FMUs: the loop regulates to the target (0, 0, 138) deg
    # from (3, -2, 136) deg, where the FMUs' defaults would not.
    assert np.abs(rows[-1, 1:4] - np.radians([0.0, 0.0, 138.0])).max() < 1e-3


def test_fmi2_container_fails(regulation, tmp_path, capsys):
    # FMPy 0.3.32 writes an FMI 2.0 container without complaint, but its runtime cannot
    # run it: (1) each connection of the configuration carries the FMI 2.0 type name of
    # its start connector ("Real"), which the runtime's configuration reader does not
    # know (it names the FMI 3.0 types), so fmi2Instantiate fails; (2) with those names
    # made "Float64" by hand it runs, but every value reference answers for the variable
    # before it: the runtime keeps value reference 0 for the container's time and maps
    # reference k to its (k-1)-th variable, while an FMI 2.0 container has no time
    # variable and FMPy numbers its variables from 0.
    # The container's log is read from FMPy's default logger (it prints each message):
    # simulate_fmu(logger=...) of an FMI 2.0 FMU hands FMPy's native logger proxy, one
    # per process, a ctypes callback that dies with the call, and a later FMU's log line
    # in this process then jumps into freed memory (seen as a segmentation fault in
    # test_output_derivatives.py under load).
    container = build(pid_and_plant(regulation), "2.0", DIST, tmp_path)
    capsys.readouterr()
    with pytest.raises(Exception, match="Failed to instantiate"):
        simulate_fmu(str(container), stop_time=0.01, step_size=regulation.step_size,
                     output=SIGNALS)
    printed = capsys.readouterr().out
    assert "unknown variant `Real`" in printed, printed
    unzipped = tmp_path / "unzipped"
    config = unzipped / "resources" / "container.json"
    data = json.loads(config.read_text())
    for c in data["connections"]:
        c["variableType"] = {"Real": "Float64", "Integer": "Int32"}.get(c["variableType"],
                                                                        c["variableType"])
    config.write_text(json.dumps(data))
    patched = Path(shutil.make_archive(str(tmp_path / "patched"), "zip", root_dir=unzipped))
    result = simulate_fmu(str(patched), stop_time=0.01, step_size=regulation.step_size,
                          output=SIGNALS)
    # plant.theta[1] reads the variable before it (the parameter omega0[3] = 0), and
    # plant.theta[2] reads theta[1], which starts at 3 deg.
    assert result["plant.theta[1]"][0] == 0.0
    assert result["plant.theta[2]"][0] == pytest.approx(np.radians(3.0), abs=1e-12)
