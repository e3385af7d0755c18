"""Runs in the gemseo-fmu venv (.venv-gemseo, scripts/setup-gemseo-venv.sh), called by
test_gemseo_fmu.py: `python gemseo_runs.py REQUEST.json RESULT.json`. The request names
the study; the result holds what gemseo-fmu computed, as lists of floats.

- "doe": a design of experiments with gemseo's DOE machinery (sample_disciplines, full
  factorial) over fixed parameters of an FMU wrapped in gemseo-fmu's FMUDiscipline (the
  discipline simulates from 0 to `final_time` at each sample);
- "run": one FMUDiscipline executed at the FMU's start values;
- "system": gemseo-fmu's TimeSteppingSystem of DoStepFMUDiscipline's (PID + plant),
  coupled by names, run to `final_time`.
"""

from __future__ import annotations

import json
import sys

from gemseo import create_design_space, sample_disciplines
from gemseo_fmu.disciplines.do_step_fmu_discipline import DoStepFMUDiscipline
from gemseo_fmu.disciplines.fmu_discipline import FMUDiscipline
from gemseo_fmu.disciplines.time_stepping_system import TimeSteppingSystem
from numpy import array


def doe(request: dict) -> dict:
    inputs = list(request["design"])
    discipline = FMUDiscipline(request["fmu"], input_names=inputs,
                               output_names=request["outputs"],
                               final_time=request["final_time"],
                               time_step=request["time_step"])
    space = create_design_space()
    for name, (lower, upper) in request["design"].items():
        space.add_variable(name, lower_bound=lower, upper_bound=upper)
    dataset = sample_disciplines([discipline], space, request["outputs"],
                                 algo_name="PYDOE_FULLFACT",
                                 n_samples=request["samples"])
    rows = []
    for k in range(len(dataset)):
        sample = {name: float(dataset.get_view(variable_names=name).to_numpy()[k][0])
                  for name in inputs}
        outputs = {name: dataset.get_view(variable_names=name).to_numpy()[k].tolist()
                   for name in request["outputs"]}
        rows.append({"inputs": sample, "outputs": outputs})
    return {"rows": rows, "time": discipline.time.tolist()}


def run(request: dict) -> dict:
    """One FMUDiscipline executed at its default inputs (the FMU's start values)."""
    discipline = FMUDiscipline(request["fmu"], input_names=request["inputs"],
                               output_names=request["outputs"],
                               final_time=request["final_time"],
                               time_step=request["time_step"])
    data = discipline.execute()
    return {name: [float(x) for x in data[name]] for name in request["outputs"]}


def system(request: dict) -> dict:
    disciplines = [
        DoStepFMUDiscipline(spec["fmu"], input_names=spec["inputs"],
                            output_names=spec["outputs"], variable_names=spec["names"],
                            final_time=request["final_time"],
                            time_step=request["time_step"], name=alias)
        for alias, spec in request["components"].items()
    ]
    system = TimeSteppingSystem(disciplines, request["final_time"], request["time_step"],
                                restart=False)
    data = system.execute({name: array([value]) for name, value in request["values"].items()})
    return {name: [float(x) for x in data[name]] for name in request["record"]}


if __name__ == "__main__":
    with open(sys.argv[1]) as f:
        request = json.load(f)
    result = {"doe": doe, "run": run, "system": system}[request["study"]](request)
    with open(sys.argv[2], "w") as f:
        json.dump(result, f)
