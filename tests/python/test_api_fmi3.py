"""FMI 3.0 FMUs of anyone's in robofmu.System: a third-party FMI 3.0 co-simulation FMU
compiled here from a few lines of C (examples/integrator3/: Float64 arrays u[2] and
y[2], Float64, Int32 and Boolean parameters) driven by our PID as FMI 2.0, as FMI 3.0
(the bundled "fmi3/PID" added as it is) and through simulate(fmi3=True), against the
closed form; a clock and what it clocks left out (the FMU runs without them); and the
one-line errors for what the master does not run (a clock or a clocked variable
connected without a sample period, Model Exchange only, arrays of two dimensions, types
it cannot pass)."""

from __future__ import annotations

import importlib.util
import re
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

import robofmu  # noqa: E402

H, GAIN, KP, Y0, SETPOINTS = 0.01, 2.0, -5.0, (0.25, 0.0), (1.0, -0.5)


@pytest.fixture(scope="module")
def integrator3(tmp_path_factory) -> Path:
    # By its path: test_api.py imports examples/integrator/build_fmu.py as build_fmu.
    spec = importlib.util.spec_from_file_location(
        "build_integrator3", ROOT / "examples" / "integrator3" / "build_fmu.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.build(tmp_path_factory.mktemp("integrator3") / "Integrator3.fmu")


def system(pid: str, plant: Path, **plant_parameters) -> robofmu.System:
    """Our PID's axes 1 and 2 as P controllers of the two integrators."""
    s = robofmu.System(stop_time=1.0, step_size="10 ms")
    gains = {f"{k}[{i}]": v for i in (1, 2) for k, v in (("Kp", KP), ("Ki", 0.0), ("Kd", 0.0))}
    s.add("pid", pid, parameters={**gains, "setpoint[1]": SETPOINTS[0],
                                  "setpoint[2]": SETPOINTS[1]})
    s.add("plant", plant, parameters={"gain": GAIN, "y0[1]": "250 mm", "sign": -1,
                                      **plant_parameters})
    for i in (1, 2):
        s.connect(f"plant.y[{i}]", f"pid.measurement[{i}]")
        s.connect(f"pid.u[{i}]", f"plant.u[{i}]")
    return s


@pytest.mark.parametrize("pid, fmi3", [("PID", False), ("fmi3/PID", False), ("PID", True)])
def test_a_third_party_fmi3_fmu_with_our_pid_follows_the_closed_form(integrator3, pid, fmi3):
    # Closed form: y' = sign gain u with u = Kp (s - y) sampled at t_k and held (sampled
    # coupling, the integrator steps exactly): y_k = s - (1 - h sign gain Kp)^k (s - y0),
    # here 1 - h (-1) 2 (-5) = 0.9 on both axes.
    result = robofmu.simulate(system(pid, integrator3), fmi3=fmi3)
    k = np.arange(101)
    for i in (1, 2):
        s, y0 = SETPOINTS[i - 1], Y0[i - 1]
        np.testing.assert_allclose(result[f"plant.y[{i}]"],
                                   s - (1 - H * -1 * GAIN * KP) ** k * (s - y0),
                                   rtol=0, atol=1e-12)
    assert result.unit("plant.y[1]") == "m"


def test_a_boolean_parameter_of_a_third_party_fmi3_fmu_is_set(integrator3):
    # frozen = true: y' = 0 whatever u, so y stays y0 (the FMU's own rule).
    result = robofmu.simulate(system("PID", integrator3, frozen=True))
    assert np.all(result["plant.y[1]"] == 0.25) and np.all(result["plant.y[2]"] == 0.0)


def test_an_fmi3_fmu_with_a_clock_runs_without_it(integrator3, tmp_path):
    # The clock and the variable it clocks are left out of the scalar view; the rest
    # runs as the FMU without them (the same closed form as above, y_k on axis 1).
    plant = _variant(integrator3, tmp_path / "Clocked.fmu",
                     lambda x: x.replace("</ModelVariables>", CLOCK + CLOCKED + "</ModelVariables>"))
    result = robofmu.simulate(system("PID", plant))
    s, y0 = SETPOINTS[0], Y0[0]
    np.testing.assert_allclose(result["plant.y[1]"],
                               s - (1 - H * -1 * GAIN * KP) ** np.arange(101) * (s - y0),
                               rtol=0, atol=1e-12)


def _variant(fmu: Path, out: Path, edit) -> Path:
    """`fmu` with its modelDescription.xml changed by `edit` (the binary kept)."""
    with zipfile.ZipFile(fmu) as source, zipfile.ZipFile(out, "w") as target:
        for item in source.infolist():
            data = source.read(item)
            if item.filename == "modelDescription.xml":
                data = edit(data.decode()).encode()
            target.writestr(item, data)
    return out


CLOCK = '<Clock name="tick" valueReference="7" causality="input" intervalVariability="triggered"/>'
FLOAT32 = '<Float32 name="z" valueReference="8" causality="output" variability="continuous"/>'
CLOCKED = ('<Float64 name="held" valueReference="9" causality="output" variability="discrete" '
           'clocks="7"/>')


@pytest.mark.parametrize("edit, field, message", [
    (lambda x: x.replace("</ModelVariables>", CLOCK + CLOCKED + "</ModelVariables>"),
     "connections[4].from", "plant.tick is an input clock, which the master ticks itself; "
     "give plant a sample period (field 'sample_period.plant'"),
    (lambda x: x.replace("</ModelVariables>", CLOCK + CLOCKED + "</ModelVariables>"),
     "connections[4].from", "plant.held is clocked (by tick): it has a value only at that "
     "clock's ticks; give plant a sample period"),
    (lambda x: re.sub(r"<CoSimulation ", "<ModelExchange ", x), "fmus.plant",
     "does not support co-simulation (FMI 3.0 Model Exchange only)"),
    (lambda x: x.replace('<Dimension start="2"/>', '<Dimension start="2"/><Dimension start="1"/>'),
     "fmus.plant", "declares u as an array of shape (2, 1); only arrays of one dimension"),
    (lambda x: x.replace("</ModelVariables>", FLOAT32 + "</ModelVariables>"),
     "connections[4].from", "plant.z is of type Float32, which the master cannot pass"),
    (lambda x: x, "parameters.plant.sign", "2 is outside the range [-1, 1] that plant.sign"),
    (lambda x: x, "parameters.plant.sign", "plant.sign is an integer; write a whole number"),
    (lambda x: x, "parameters.plant.frozen", "plant.frozen is a Boolean; write true or false"),
])
def test_what_the_master_does_not_run_is_one_line(integrator3, tmp_path, edit, field, message):
    plant = _variant(integrator3, tmp_path / "Variant.fmu", edit)
    parameters = {"parameters.plant.sign": {"sign": 2 if "range" in message else 1.5},
                  "parameters.plant.frozen": {"frozen": 1}}.get(field, {})
    s = system("PID", plant, **parameters)
    connected = ("z" if "Float32" in message else "tick" if "plant.tick" in message else
                 "held" if "plant.held" in message else None)
    if connected is not None:
        s.connect(f"plant.{connected}", "pid.measurement[3]")
    with pytest.raises(robofmu.ScenarioError) as caught:
        robofmu.simulate(s)
    text = str(caught.value)
    assert f"field '{field}'" in text and message in text and "\n" not in text, text
