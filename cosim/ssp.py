"""Export a scenario as an SSP 1.0 archive (System Structure and Parameterization), so
that other tools can run the closed loop without our master.

The archive holds SystemStructure.ssd and the FMUs under resources/. Parameters are one
system-level ParameterSet with names "component.variable" (the form FMPy's
``simulate_ssp(parameter_set=...)`` applies); connector kinds and types come from each
FMU's modelDescription.xml.
"""

from __future__ import annotations

import sys
import zipfile
from pathlib import Path
from xml.etree import ElementTree as ET

from .scenario import Scenario, ScenarioError, load_scenario

NS = {
    "ssd": "http://ssp-standard.org/SSP1/SystemStructureDescription",
    "ssc": "http://ssp-standard.org/SSP1/SystemStructureCommon",
    "ssv": "http://ssp-standard.org/SSP1/SystemStructureParameterValues",
}
for _prefix, _uri in NS.items():
    ET.register_namespace(_prefix, _uri)


def _tag(prefix: str, name: str) -> str:
    return f"{{{NS[prefix]}}}{name}"


def _variables(path: Path) -> dict:
    from fmpy import read_model_description
    return {v.name: v for v in read_model_description(str(path)).modelVariables}


def _type_of(variables: dict, alias: str, name: str) -> str:
    try:
        return variables[name].type
    except KeyError:
        raise ScenarioError(f"FMU '{alias}' has no variable '{name}'") from None


def _value_element(kind: str, value) -> ET.Element:
    if kind == "Real":
        return ET.Element(_tag("ssv", "Real"), value=repr(float(value)))
    if kind in ("Integer", "Enumeration"):
        return ET.Element(_tag("ssv", "Integer"), value=str(int(value)))
    if kind == "Boolean":
        return ET.Element(_tag("ssv", "Boolean"), value="true" if value else "false")
    raise ScenarioError(f"parameters of type {kind} cannot be exported")


def system_structure(scenario: Scenario, variables: dict[str, dict]) -> ET.ElementTree:
    """The SystemStructure.ssd document of `scenario`; `variables[alias]` maps each
    FMU's variable names to FMPy's ScalarVariable objects."""
    root = ET.Element(_tag("ssd", "SystemStructureDescription"), version="1.0", name=scenario.name)
    system = ET.SubElement(root, _tag("ssd", "System"), name=scenario.name)
    elements = ET.SubElement(system, _tag("ssd", "Elements"))
    used: dict[str, dict[str, str]] = {alias: {} for alias in scenario.order}
    for c in scenario.connections:
        used[c.source.alias][c.source.variable] = "output"
        used[c.target.alias][c.target.variable] = "input"
    for sig in scenario.record:
        used[sig.alias].setdefault(sig.variable, "output")
    for alias in scenario.order:
        component = ET.SubElement(elements, _tag("ssd", "Component"), name=alias,
                                  type="application/x-fmu-sharedlibrary",
                                  source=f"resources/{scenario.fmus[alias].name}")
        connectors = ET.SubElement(component, _tag("ssd", "Connectors"))
        for name, kind in used[alias].items():
            _type_of(variables[alias], alias, name)
            causality = variables[alias][name].causality
            if causality != kind:
                raise ScenarioError(f"{alias}.{name} is a {causality}, not an {kind}")
            connector = ET.SubElement(connectors, _tag("ssd", "Connector"), name=name, kind=kind)
            ET.SubElement(connector, _tag("ssc", _type_of(variables[alias], alias, name)))
    connections = ET.SubElement(system, _tag("ssd", "Connections"))
    for c in scenario.connections:
        ET.SubElement(connections, _tag("ssd", "Connection"),
                      startElement=c.source.alias, startConnector=c.source.variable,
                      endElement=c.target.alias, endConnector=c.target.variable)
    if scenario.parameters:
        bindings = ET.SubElement(system, _tag("ssd", "ParameterBindings"))
        binding = ET.SubElement(bindings, _tag("ssd", "ParameterBinding"))
        values = ET.SubElement(binding, _tag("ssd", "ParameterValues"))
        pset = ET.SubElement(values, _tag("ssv", "ParameterSet"), version="1.0", name="scenario")
        params = ET.SubElement(pset, _tag("ssv", "Parameters"))
        for alias, assignments in scenario.parameters.items():
            for name, value in assignments.items():
                p = ET.SubElement(params, _tag("ssv", "Parameter"), name=f"{alias}.{name}")
                p.append(_value_element(_type_of(variables[alias], alias, name), value))
    ET.SubElement(root, _tag("ssd", "DefaultExperiment"),
                  startTime=repr(scenario.start_time), stopTime=repr(scenario.stop_time))
    # The schema orders a System's children: ParameterBindings, Elements, Connections.
    system[:] = sorted(system, key=lambda e: ["ParameterBindings", "Elements", "Connections"]
                       .index(e.tag.split("}")[1]))
    return ET.ElementTree(root)


def write_ssp(scenario: Scenario, path: Path) -> None:
    """Writes the SSP archive of `scenario` to `path`."""
    if scenario.schedule:
        raise ScenarioError("a multi-segment motion (a sequence of plans) has no SSP form: "
                            "SSP parameters are fixed for the whole run")
    variables = {alias: _variables(p) for alias, p in scenario.fmus.items()}
    tree = system_structure(scenario, variables)
    ET.indent(tree)
    path.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("SystemStructure.ssd", ET.tostring(tree.getroot(), encoding="unicode",
                                                      xml_declaration=True))
        for fmu in scenario.fmus.values():
            z.write(fmu, f"resources/{fmu.name}")


def add_arguments(parser) -> None:
    """``cosim ssp SCENARIO --out X.ssp``."""
    parser.add_argument("scenario", type=Path, help="scenario file (.toml or .json)")
    parser.add_argument("--out", type=Path, required=True, help="SSP file to write (.ssp)")
    parser.add_argument("--fmu-dir", type=Path, help="find the FMUs by file name here")


def run(args) -> int:
    from .run import fmu_dir
    if args.out.suffix != ".ssp" or args.out.is_dir():
        raise ScenarioError(f"--out: {args.out}: the SSP archive is a file whose name ends "
                            "with .ssp; name such a file")
    scenario = load_scenario(args.scenario, fmu_dir(args.fmu_dir))
    try:
        write_ssp(scenario, args.out)
    except ScenarioError as e:
        raise ScenarioError(f"{args.scenario}: field 'motion.waypoints': {e}") from None
    print(f"wrote {args.out}")
    return 0
