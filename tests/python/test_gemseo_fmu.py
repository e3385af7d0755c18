"""Our FMUs in gemseo-fmu 3.1.1 (design of experiments and MDO on FMUs, built on FMPy
0.3.19), run in its own venv (.venv-gemseo, scripts/setup-gemseo-venv.sh) through
gemseo_runs.py (issue 45).

- A DOE (gemseo's full-factorial sampling) over the plant's fixed parameters theta0[1]
  and legMass, FMI 2.0 and the FMI 3.0 scalar-only variant: each sample equals a plain
  FMPy run (simulate_fmu of this venv's FMPy 0.3.32 with the sample as start values) to
  1e-10 (measured: 0, bit for bit). gemseo-fmu sets every variable of the study before
  initialization and again in step mode with the same value; the FMUs accept the second
  set with Warning (docs/reliability.md, "A fixed parameter set again").
- A system of gemseo-fmu's do-step disciplines (PID + plant, TimeSteppingSystem, coupled
  by names) reaches the regulation target of scenarios/regulation.toml: (0, 0, 138) deg
  from (3, -2, 136) deg, within 1e-6 rad after 1 s (measured 4.2e-11), with the
  scenario's gains and rate inputs. This needs the FMI 3.0 scalar variant: gemseo-fmu
  takes every FMI 2.0 variable for a Real, and the PID's Boolean parameter
  useRateInputs[i] cannot be an input (test_fmi2_boolean_parameters_need_fmi3)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from fmpy import simulate_fmu

from conftest import DIST

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from robofmu.scenario import load_scenario  # noqa: E402

PYTHON = ROOT / ".venv-gemseo" / "bin" / "python"
RUNNER = Path(__file__).with_name("gemseo_runs.py")
# A step that is a power of two: every t_k = k h is exact in both FMPy versions.
STEP = 2.0 ** -7
FINAL = 0.25
DESIGN = {"theta0[1]": [-0.05, 0.05], "legMass": [0.8, 1.1]}
OUTPUTS = ["theta[1]", "theta[2]", "theta[3]"]
VARIANTS = {"fmi2": DIST / "Pss3Plant.fmu", "fmi3-scalar": DIST / "fmi3-scalar" / "Pss3Plant.fmu"}


def gemseo(request: dict, tmp_path: Path) -> dict:
    """gemseo_runs.py on `request` in the gemseo-fmu venv: its result."""
    if not PYTHON.exists():
        pytest.fail(f"{PYTHON} is missing: run scripts/setup-gemseo-venv.sh first")
    ask, answer = tmp_path / "request.json", tmp_path / "result.json"
    ask.write_text(json.dumps(request))
    run = subprocess.run([str(PYTHON), str(RUNNER), str(ask), str(answer)], cwd=tmp_path,
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    return json.loads(answer.read_text())


@pytest.mark.parametrize("variant", sorted(VARIANTS))
def test_doe_over_fixed_parameters_equals_plain_fmpy(variant, tmp_path):
    fmu = str(VARIANTS[variant])
    result = gemseo({"study": "doe", "fmu": fmu, "design": DESIGN, "outputs": OUTPUTS,
                     "final_time": FINAL, "time_step": STEP, "samples": 4}, tmp_path)
    rows = result["rows"]
    corners = {(r["inputs"]["theta0[1]"], r["inputs"]["legMass"]) for r in rows}
    assert corners == {(a, b) for a in DESIGN["theta0[1]"] for b in DESIGN["legMass"]}
    finals = set()
    for row in rows:
        plain = simulate_fmu(fmu, start_values=row["inputs"], stop_time=FINAL,
                             output_interval=STEP, output=OUTPUTS)
        for name in OUTPUTS:
            ours = np.array(row["outputs"][name])
            assert ours.shape == plain[name].shape
            assert np.abs(ours - plain[name]).max() <= 1e-10, (row["inputs"], name)
        finals.add(round(row["outputs"]["theta[1]"][-1], 12))
    # The parameters reach the model: each corner ends elsewhere.
    assert len(finals) == 4


def system_request(fmus: Path, rate_inputs: bool) -> dict:
    """PID + plant as gemseo-fmu do-step disciplines with the regulation scenario's
    parameters; the planner's constant target is the PID's setpoint."""
    scenario = load_scenario(ROOT / "scenarios" / "regulation.toml")
    pid = dict(scenario.parameters["pid"])
    if not rate_inputs:
        pid = {k: v for k, v in pid.items() if not k.startswith("useRateInputs")}
    plant = scenario.parameters["plant"]
    axes = (1, 2, 3)
    target = {f"setpoint[{i}]": scenario.parameters["planner"][f"q0[{i}]"] for i in axes}

    def rename(pairs):
        return {f"{fmu}[{i}]": f"{shared}_{i}" for fmu, shared in pairs for i in axes}

    return {
        "study": "system", "final_time": scenario.stop_time,
        "time_step": scenario.step_size,
        "components": {
            "pid": {"fmu": str(fmus / "PID.fmu"),
                    "inputs": [*target, *pid] + [f"{n}[{i}]" for n in (
                        "measurement", "measuredRate", "feedforward") for i in axes],
                    "outputs": [f"u[{i}]" for i in axes],
                    "names": rename([("measurement", "theta"), ("measuredRate", "thetaDot"),
                                     ("feedforward", "g"), ("u", "u")])},
            "plant": {"fmu": str(fmus / "Pss3Plant.fmu"),
                      "inputs": [*plant] + [f"generalizedForceCommand[{i}]" for i in axes],
                      "outputs": [f"{n}[{i}]" for n in ("theta", "thetaDot",
                                                        "gravityCompensation") for i in axes],
                      "names": rename([("theta", "theta"), ("thetaDot", "thetaDot"),
                                       ("gravityCompensation", "g"),
                                       ("generalizedForceCommand", "u")])},
        },
        "values": {**target, **pid, **plant},
        "record": [f"theta_{i}" for i in axes],
        "target": [target[f"setpoint[{i}]"] for i in axes],
    }


def test_pid_and_plant_system_reaches_the_regulation_target(tmp_path):
    request = system_request(DIST / "fmi3-scalar", rate_inputs=True)
    result = gemseo(request, tmp_path)
    final = np.array([result[name][-1] for name in request["record"]])
    start = np.array([result[name][0] for name in request["record"]])
    assert np.abs(start - request["target"]).max() > 0.03  # 3 and 2 deg away
    assert np.abs(final - request["target"]).max() < 1e-6, final - request["target"]


def test_fmi2_boolean_parameters_need_fmi3(tmp_path):
    # gemseo-fmu 3.1.1 wraps every FMI 2.0 variable as a Real (RealVariable: float
    # values, fmi2SetReal): a Boolean input such as the PID's useRateInputs[i] fails
    # when the discipline is created, on its start value ("false" is not a float), so
    # the scenario's PID (rate inputs, Tf = 0) cannot be built from the FMI 2.0 FMUs.
    # Workaround: the FMI 3.0 scalar variant (dist/fmi3-scalar), where gemseo-fmu uses
    # the typed getters and setters (the test above).
    request = system_request(DIST, rate_inputs=True)
    with pytest.raises(AssertionError, match="could not convert string to float"):
        gemseo(request, tmp_path)


def test_fmi3_arrays_need_the_scalar_variant(tmp_path):
    # gemseo-fmu 3.1.1 leaves the start values of an FMI 3.0 array as strings: the
    # plant's theta0 (array of 3) as an input fails at the first set ("must be real
    # number, not numpy.str_"). Workaround: dist/fmi3-scalar, whose theta0[1] is a
    # scalar (the DOE above).
    request = {"study": "run", "fmu": str(DIST / "fmi3" / "Pss3Plant.fmu"),
               "inputs": ["theta0"], "outputs": ["theta"], "final_time": 2 * STEP,
               "time_step": STEP}
    with pytest.raises(AssertionError, match="must be real number, not numpy.str_"):
        gemseo(request, tmp_path)

