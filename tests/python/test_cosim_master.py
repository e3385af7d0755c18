"""The co-simulation master's stepping logic, with pure-Python stand-in FMUs whose
results have closed forms (no FMPy or FMU needed)."""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from robofmu.errors import CosimError, StepDiscarded  # noqa: E402
from robofmu.master import Master  # noqa: E402
from robofmu.scenario import ScenarioError, load_scenario, parse_scenario  # noqa: E402


class Ramp:
    """Output y = t at the FMU's current time."""

    def __init__(self, alias):
        self.alias, self.t, self.steps = alias, 0.0, []

    def set_value(self, name, value):
        raise AssertionError(f"Ramp has no input {name}")

    def get_value(self, name):
        assert name == "y"
        return self.t

    def get_values(self, names):
        return [self.get_value(n) for n in names]

    def set_values(self, names, values):
        for n, v in zip(names, values):
            self.set_value(n, v)

    def do_step(self, t, h):
        assert t == pytest.approx(self.t, abs=1e-15), "steps must be contiguous"
        self.steps.append(h)
        self.t = t + h

    def get_state(self):
        return {"t": self.t}

    def set_state(self, s):
        self.t = s["t"]

    def free_state(self, s):
        pass

    enter_initialization = exit_initialization = close = lambda self: None


class Integrator(Ramp):
    """x' = u with u held over the step (x += u h); discards steps longer than h_max."""

    def __init__(self, alias, h_max=1.0):
        super().__init__(alias)
        self.x, self.u, self.h_max = 0.0, 0.0, h_max

    def set_value(self, name, value):
        assert name == "u"
        self.u = value

    def get_value(self, name):
        return {"x": self.x, "u": self.u}[name]

    def do_step(self, t, h):
        if h > self.h_max + 1e-15:
            raise StepDiscarded(self.alias, t, f"step {h} longer than {self.h_max}")
        super().do_step(t, h)
        self.x += self.u * h

    def get_state(self):
        return {"t": self.t, "x": self.x, "u": self.u}

    def set_state(self, s):
        self.t, self.x, self.u = s["t"], s["x"], s["u"]


def scenario(**over):
    data = {"name": "chain", "stop_time": 1.0, "step_size": 0.1, "order": ["ramp", "int"],
            "fmus": {"ramp": "r.fmu", "int": "i.fmu"},
            "connections": [{"from": "ramp.y", "to": "int.u"}], "record": ["int.x"]}
    data.update(over)
    return parse_scenario(data, Path("."))


def run(s, h_max=1.0):
    made = {}

    def open_fmu(alias, _path, _s):
        made[alias] = Ramp(alias) if alias == "ramp" else Integrator(alias, h_max)
        return made[alias]

    return Master(s, open_fmu=open_fmu).run(), made


def test_gauss_seidel_order_feeds_the_advanced_output():
    # Closed form: the integrator steps after the ramp, so over step k it holds
    # u = t_{k+1} = (k+1) h; x_N = h^2 N (N+1) / 2 = 0.55 for h = 0.1, N = 10.
    result, _ = run(scenario(coupling="gauss-seidel"))
    assert result.columns["int.x"][-1] == pytest.approx(0.55, abs=1e-14)
    # Jacobi order would give h^2 N (N-1) / 2 = 0.45: the reversed order must.
    reversed_result, _ = run(scenario(order=["int", "ramp"], coupling="gauss-seidel"))
    assert reversed_result.columns["int.x"][-1] == pytest.approx(0.45, abs=1e-14)


def test_sampled_coupling_feeds_every_input_at_the_step_start():
    # Closed form: the inputs of step k are the outputs at t_k = k h, whatever the
    # order: u = k h and x_N = h^2 N (N-1) / 2 = 0.45.
    for order in (["ramp", "int"], ["int", "ramp"]):
        result, _ = run(scenario(order=order))
        assert result.columns["int.x"][-1] == pytest.approx(0.45, abs=1e-14)


def test_sampled_rows_record_the_inputs_the_next_step_holds():
    # Closed form: with sampled coupling the integrator holds u = t_k = k h over step k;
    # row k records the values exchanged at t_k, so int.u equals ramp.y = k h on every
    # row (recording after the step but before the propagation gave int.u = (k-1) h).
    result, _ = run(scenario(record=["int.x", "int.u"]))
    h = 0.1
    assert result.columns["int.u"] == pytest.approx([k * h for k in range(11)], abs=1e-15)
    assert result.columns["int.u"] == result.columns["ramp.y"]
    # x at row k integrates the inputs of rows 0..k-1: x_k = h^2 k (k-1) / 2.
    assert result.columns["int.x"] == pytest.approx(
        [h * h * k * (k - 1) / 2 for k in range(11)], abs=1e-14)


class SlopedIntegrator(Integrator):
    """x' = u with u(t_k + s) = u + u' s over the step (canInterpolateInputs)."""

    can_interpolate_inputs = True
    max_input_derivative_order = 1

    def __init__(self, alias, h_max=1.0):
        super().__init__(alias, h_max)
        self.slope = 0.0

    def set_input_derivatives(self, names, values, order):
        assert names == ("u",) and order == 1
        self.slope = values[0]

    def do_step(self, t, h):
        super().do_step(t, h)
        self.x += self.slope * h * h / 2


def test_linear_extrapolation_integrates_a_ramp_exactly():
    # Closed form: the ramp gives no derivatives, so its slope comes from its last two
    # samples: 0 over the first step (no history), then exactly 1. x_N = integral of t
    # minus the first step's missing h^2/2: N^2 h^2 / 2 - h^2 / 2 = 0.495 (hold: 0.45).
    made = {}

    def open_fmu(alias, _path, _s):
        made[alias] = Ramp(alias) if alias == "ramp" else SlopedIntegrator(alias)
        return made[alias]

    result = Master(scenario(input_extrapolation="linear"), open_fmu=open_fmu).run()
    assert result.columns["int.x"][-1] == pytest.approx(0.495, abs=1e-14)
    held = Master(scenario(input_extrapolation="hold"), open_fmu=open_fmu).run()
    assert held.columns["int.x"][-1] == pytest.approx(0.45, abs=1e-14)


def test_time_is_an_integer_step_count():
    # 0.1 added ten times is 0.9999999999999999; t_k = k h must be exact at the end.
    result, _ = run(scenario())
    assert len(result.time) == 11 and result.time[0] == 0.0 and result.time[-1] == 1.0
    assert result.names == ["ramp.y", "int.x"]


def test_discarded_steps_are_retried_with_halved_steps_after_rollback():
    # h = 0.1 with h_max = 0.03 needs two halvings (h/4 = 0.025); every FMU then takes
    # M = 40 substeps and x = (h/4)^2 M (M+1) / 2 = 0.5125 (same closed form as above).
    s = scenario(max_step_halvings=2, coupling="gauss-seidel")
    result, made = run(s, h_max=0.03)
    assert result.columns["int.x"][-1] == pytest.approx(0.5125, abs=1e-14)
    assert made["ramp"].t == pytest.approx(1.0, abs=1e-14)
    assert len(result.time) == 11
    assert "int discarded the step at t = 0" in result.discards[0]


def test_discard_without_halvings_left_is_a_clear_error():
    with pytest.raises(CosimError, match=r"int discarded the step at t = 0 s: step 0.05 longer"):
        run(scenario(max_step_halvings=1), h_max=0.03)


def test_result_csv_is_in_cross_check_format(tmp_path):
    result, _ = run(scenario())
    result.write_csv(tmp_path / "out.csv")
    lines = (tmp_path / "out.csv").read_text().splitlines()
    assert lines[0] == '"time","ramp.y","int.x"'
    assert lines[-1].split(",")[0] == "1.0"


@pytest.mark.parametrize("change, field", [
    ({"step_size": 0.3}, "step_size"),
    ({"step_size": -0.1}, "step_size"),
    ({"stop_time": "2"}, "stop_time"),
    ({"order": ["ramp"]}, "order"),
    ({"connections": [{"from": "ramp.y", "to": "pid.u"}]}, "connections[0].to"),
    ({"connections": [{"from": "ramp", "to": "int.u"}]}, "connections[0].from"),
    ({"connections": [{"from": "ramp.y", "to": "int.u"}] * 2}, "connections[1].to"),
    ({"parameters": {"int": {"k": float("nan")}}}, "parameters.int.k"),
    ({"record": ["nothing.x"]}, "record[0]"),
    ({"max_step_halvings": -1}, "max_step_halvings"),
    ({"coupling": "jacobi"}, "coupling"),
    ({"stepsize": 0.1}, "stepsize"),
])
def test_malformed_scenarios_name_the_field(change, field):
    with pytest.raises(ScenarioError, match=re.escape(f"'{field}")):
        scenario(**change)


def test_scenario_files_load_from_toml_and_json(tmp_path):
    data = {"name": "x", "stop_time": 1.0, "step_size": 0.5, "order": ["a"], "fmus": {"a": "a.fmu"}}
    (tmp_path / "s.json").write_text(json.dumps(data))
    (tmp_path / "s.toml").write_text(
        'name = "x"\nstop_time = 1.0\nstep_size = 0.5\norder = ["a"]\n[fmus]\na = "a.fmu"\n')
    for name in ("s.json", "s.toml"):
        s = load_scenario(tmp_path / name, preflight=False)  # no FMU files here
        assert s.steps == 2 and s.fmus["a"] == tmp_path / "a.fmu"
    del data["step_size"]
    assert parse_scenario(data, tmp_path).step_size == 0.001  # the documented default
    (tmp_path / "bad.toml").write_text("name = ")
    with pytest.raises(ScenarioError, match="not valid TOML"):
        load_scenario(tmp_path / "bad.toml")



def test_ssp_structure_passes_the_ssp_schema(tmp_path):
    # Truth: FMPy's reader validates SystemStructure.ssd against the SSP 1.0 XSD.
    from types import SimpleNamespace as Var
    pytest.importorskip("fmpy")
    from fmpy.ssp.ssd import read_ssd
    from robofmu.ssp import system_structure
    s = scenario(parameters={"int": {"gain": 2.0, "n": 3}})
    variables = {"ramp": {"y": Var(type="Real", causality="output")},
                 "int": {"u": Var(type="Real", causality="input"),
                         "x": Var(type="Real", causality="output"),
                         "gain": Var(type="Real", causality="parameter"),
                         "n": Var(type="Integer", causality="parameter")}}
    tree = system_structure(s, variables)
    ssp = tmp_path / "chain.ssp"
    import xml.etree.ElementTree as ET
    import zipfile
    with zipfile.ZipFile(ssp, "w") as z:
        z.writestr("SystemStructure.ssd", ET.tostring(tree.getroot(), encoding="unicode"))
    ssd = read_ssd(str(ssp), validate=True)
    names = [(c.startElement, c.startConnector, c.endElement, c.endConnector)
             for c in ssd.system.connections]
    assert names == [("ramp", "y", "int", "u")]
    assert ssd.system.parameterBindings == []  # bound per component (robofmu.ssp)
    ramp, integrator = ssd.system.elements
    assert ramp.parameterBindings == []
    params = integrator.parameterBindings[0].parameterValues[0].parameters
    assert [(p.name, p.type, p.value) for p in params] == [("gain", "Real", "2.0"),
                                                            ("n", "Integer", "3")]
    variables["int"]["u"] = Var(type="Real", causality="parameter")
    with pytest.raises(ScenarioError, match="int.u is a parameter, not an input"):
        system_structure(s, variables)
