"""The SSP export (robofmu.ssp) against the SSP 1.0 schema and the places the importers read.

Truths: the standard's XSDs (SystemStructureDescription.xsd and the schemas it imports,
the copies FMPy ships under fmpy/ssp/schema, BSD-licensed, not copied here) through
xmlschema, a validator independent of FMPy's reader; and the element paths that libcosim
(ssp_parser.cpp), ecos (ssp.cpp) and OMSimulator (its own SSP export) read, with the
prefixes those parsers match literally."""

from __future__ import annotations

import sys
import zipfile
from pathlib import Path
from xml.etree import ElementTree as ET

import fmpy
import pytest
import xmlschema

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from robofmu.scenario import load_scenario  # noqa: E402
from robofmu.ssp import PARAMETER_SET, write_ssp  # noqa: E402
from robofmu.ssp_annotations import NS  # noqa: E402

SCHEMA = Path(fmpy.__file__).parent / "ssp" / "schema" / "SystemStructureDescription.xsd"
# Every scenario with one plan (a multi-segment motion has no SSP form), with either
# controller.
SCENARIOS = ["regulation", "path1_cubic", "path1_quintic", "three_axis_cubic",
             "three_axis_quintic", "path1_cubic_ct", "three_axis_quintic_ct"]


@pytest.fixture(scope="module")
def schema():
    return xmlschema.XMLSchema(str(SCHEMA))


def exported(name: str, tmp_path: Path):
    scenario = load_scenario(ROOT / "scenarios" / f"{name}.toml")
    ssp = tmp_path / f"{name}.ssp"
    write_ssp(scenario, ssp)
    with zipfile.ZipFile(ssp) as z:
        text = z.read("SystemStructure.ssd").decode("utf-8")
        names = set(z.namelist())
    return scenario, text, names


@pytest.mark.parametrize("name", SCENARIOS)
def test_export_is_valid_ssp_1_0(name, tmp_path, schema):
    scenario, text, names = exported(name, tmp_path)
    schema.validate(text)
    assert names == {"SystemStructure.ssd"} | {f"resources/{p.name}" for p in scenario.fmus.values()}
    # The validator does reject: a System with its Elements after its Connections.
    root = ET.fromstring(text)
    system = root.find("ssd:System", NS)
    system[:] = list(reversed(system[:]))
    assert not schema.is_valid(ET.tostring(root, encoding="unicode"))


@pytest.mark.parametrize("name", SCENARIOS)
def test_every_parameter_is_bound_in_its_component(name, tmp_path):
    scenario, text, _ = exported(name, tmp_path)
    root = ET.fromstring(text)
    system = root.find("ssd:System", NS)
    assert system.find("ssd:ParameterBindings", NS) is None  # one copy of each value
    for component in system.iterfind("ssd:Elements/ssd:Component", NS):
        sets = component.findall(
            "ssd:ParameterBindings/ssd:ParameterBinding/ssd:ParameterValues/ssv:ParameterSet", NS)
        expected = scenario.parameters.get(component.get("name"), {})
        if not expected:
            assert sets == []
            continue
        assert [s.get("name") for s in sets] == [PARAMETER_SET]
        bound = {}
        for p in sets[0].iterfind("ssv:Parameters/ssv:Parameter", NS):
            (value,) = list(p)
            text_value = value.get("value")
            bound[p.get("name")] = {"true": True, "false": False}.get(text_value, text_value)
        assert set(bound) == set(expected)
        for key, value in expected.items():
            if isinstance(value, bool):
                assert bound[key] is value, key
            else:
                assert float(bound[key]) == value, key


@pytest.mark.parametrize("name", ["regulation", "three_axis_cubic"])
def test_step_size_and_tolerance_are_where_libcosim_and_omsimulator_read_them(name, tmp_path):
    scenario, text, _ = exported(name, tmp_path)
    root = ET.fromstring(text)
    osp = root.findall("ssd:DefaultExperiment/ssd:Annotations/ssc:Annotation"
                       "[@type='com.opensimulationplatform']/osp:Algorithm/"
                       "osp:FixedStepAlgorithm", NS)
    assert [float(e.get("baseStepSize")) for e in osp] == [scenario.step_size]
    oms = root.findall("ssd:System/ssd:Annotations/ssc:Annotation[@type='org.openmodelica']/"
                       "oms:Annotations/oms:SimulationInformation/oms:FixedStepMaster", NS)
    assert [float(e.get("stepSize")) for e in oms] == [scenario.step_size]
    # OMSimulator's reader (SystemWC::importFromSSD_SimulationInformation) takes
    # description, stepSize and relativeTolerance from this element; a missing
    # relativeTolerance reads as 0 and reaches every FMU as a defined tolerance 0,
    # which they refuse (issue 36): it must be there and positive.
    assert [e.get("description") for e in oms] == ["oms-ma"]
    assert [float(e.get("relativeTolerance")) > 0 for e in oms] == [True]
    experiment = root.find("ssd:DefaultExperiment", NS)
    assert float(experiment.get("stopTime")) == scenario.stop_time
    # libcosim and ecos match prefixed names ("ssd:Component", "osp:Algorithm"): the
    # document must spell them with exactly these prefixes.
    for prefix in ("ssd", "ssc", "ssv", "osp", "oms"):
        assert f"<{prefix}:" in text and f'xmlns:{prefix}="{NS[prefix]}"' in text, prefix


def test_each_component_source_holds_its_own_fmu_once(tmp_path):
    # Two aliases of one file and a different file of the same name (a copy of the PID
    # renamed Planner.fmu). Truth: the bytes of each alias's file on disk; a zip entry
    # written twice would be a second, shadowed copy (zipfile warns "Duplicate name").
    other = tmp_path / "other" / "Planner.fmu"
    other.parent.mkdir()
    other.write_bytes((ROOT / "dist" / "PID.fmu").read_bytes())
    scenario = load_scenario(ROOT / "scenarios" / "regulation.toml")
    scenario.fmus = {"planner": ROOT / "dist" / "Planner.fmu",
                     "again": ROOT / "dist" / "Planner.fmu", "pid": other}
    scenario.order, scenario.connections, scenario.record = list(scenario.fmus), [], []
    scenario.parameters = {}
    ssp = tmp_path / "x.ssp"
    write_ssp(scenario, ssp)
    with zipfile.ZipFile(ssp) as z:
        names = z.namelist()
        root = ET.fromstring(z.read("SystemStructure.ssd"))
        sources = {c.get("name"): c.get("source")
                   for c in root.iterfind("ssd:System/ssd:Elements/ssd:Component", NS)}
        assert len(names) == len(set(names)) == 3
        for alias, path in scenario.fmus.items():
            assert z.read(sources[alias]) == path.read_bytes(), alias
    assert sources["planner"] == sources["again"] != sources["pid"]
