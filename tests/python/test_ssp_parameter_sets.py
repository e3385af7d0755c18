"""The parameter set of an SSP written by `cosim ssp`, applied by the call each importer's
user writes first, as `cosim ssp --help` and the SSD's own description tell it (issue 45).

SSP 1.0 (and the 1.1 schema FMPy ships) applies every ParameterBinding of a component:
"all of the parameters found will be used to parametrize the component" (the
ParameterBinding documentation of SystemStructureDescription.xsd); a ParameterSet's name
is required but selects nothing, and there is no default set to mark. The importers
differ: libcosim applies the bindings as loaded; ecos keeps each named set aside and
applies one only when EcosSimulation.init names it (ecos's ssp_loader: a plain init()
applies none); FMPy's simulate_ssp reads no binding and takes a ParameterSet object.
No form of the archive changes that, so the set's name and the calls are written where a
user looks first (the help and the SSD's description).

Expected value of every run: the regulation scenario ends at its target (0, 0, 138) deg
(our master ends there to 1e-9 rad); at the FMUs' start values the planner's default
targets (0.5, -0.3, 0.8) rad leave it 0.28 rad away."""

from __future__ import annotations

import subprocess
import sys
import zipfile
from pathlib import Path
from xml.etree import ElementTree as ET

import numpy as np
import pytest
from fmpy.ssp.simulation import simulate_ssp

from importer_runs import run_ecos, run_libcosim

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from robofmu.scenario import load_scenario  # noqa: E402
from robofmu.ssp import IMPORTERS, PARAMETER_SET, fmpy_parameter_set, write_ssp  # noqa: E402

ANGLES = [f"plant.theta[{i}]" for i in (1, 2, 3)]
TARGET = np.radians([0.0, 0.0, 138.0])


@pytest.fixture(scope="module")
def regulation(tmp_path_factory):
    scenario = load_scenario(ROOT / "scenarios" / "regulation.toml")
    ssp = tmp_path_factory.mktemp("ssp") / "regulation.ssp"
    write_ssp(scenario, ssp)
    return scenario, ssp


def off_target(final) -> float:
    return float(np.abs(np.asarray(final) - TARGET).max())


def test_help_and_description_name_the_set_and_each_importers_call(regulation):
    _, ssp = regulation
    help_text = subprocess.run([sys.executable, "-m", "robofmu", "ssp", "--help"], cwd=ROOT,
                               capture_output=True, text=True, check=True).stdout
    with zipfile.ZipFile(ssp) as z:
        description = ET.fromstring(z.read("SystemStructure.ssd")).get("description")
    for text in (" ".join(help_text.split()), description):
        assert f'parameter set named "{PARAMETER_SET}"' in text
        assert "CosimExecution.from_ssp_file(PATH)" in text
        assert f'init(parameter_set="{PARAMETER_SET}")' in text
        assert "parameter_set=robofmu.ssp.fmpy_parameter_set(PATH)" in text
    assert description == " ".join(IMPORTERS.split())


def test_libcosim_applies_the_set_as_loaded(regulation):
    scenario, ssp = regulation
    rows = run_libcosim(str(ssp), ANGLES, scenario.steps)  # CosimExecution.from_ssp_file
    assert off_target(rows[-1, 1:]) < 1e-6


def test_ecos_applies_the_set_when_init_names_it(regulation):
    scenario, ssp = regulation
    named = run_ecos(str(ssp), ANGLES, scenario.steps, scenario.step_size,
                     parameter_set=PARAMETER_SET)
    assert off_target(named[-1, 1:]) < 1e-6
    plain = run_ecos(str(ssp), ANGLES, scenario.steps, scenario.step_size, parameter_set=None)
    assert off_target(plain[-1, 1:]) > 0.1


def test_fmpy_simulate_ssp_applies_the_set_it_is_given(regulation):
    scenario, ssp = regulation
    run = {"start_time": 0.0, "stop_time": scenario.stop_time, "step_size": scenario.step_size}
    given = simulate_ssp(str(ssp), parameter_set=fmpy_parameter_set(ssp), **run)
    assert off_target([given[name][-1] for name in ANGLES]) < 1e-6
    plain = simulate_ssp(str(ssp), **run)
    assert off_target([plain[name][-1] for name in ANGLES]) > 0.1
