"""Export a scenario as an SSP 1.0 archive (System Structure and Parameterization), so
that other tools can run the closed loop without our master.

The archive holds SystemStructure.ssd and the FMUs under resources/. Each component
carries its own parameters: one ParameterBinding with an inline ParameterSet named
"scenario" whose names are the FMU's variable names (the form libcosim, ecos and
OMSimulator apply; a system-level set with names "component.variable" is not written:
libcosim and ecos ignore it, and one copy of each value cannot disagree with another).
The communication step size is written where the importers look for it
(robofmu.ssp_annotations). Connector kinds and types come from each FMU's
modelDescription.xml. docs/interoperability.md says which tool reads what.
"""

from __future__ import annotations

import argparse
import zipfile
from pathlib import Path
from xml.etree import ElementTree as ET

from fmpy import read_model_description
from fmpy.ssp.ssd import ParameterSet, read_ssd

from .errors import output_path
from .run import fmu_dir
from .scenario import Scenario, ScenarioError, load_scenario, schedule_field
from .ssp_annotations import default_experiment, system_annotations
from .ssp_annotations import tag as _tag

# The name of every component's parameter set: ecos applies a set only when the caller
# names it (EcosSimulation.init(parameter_set=PARAMETER_SET)); libcosim takes a
# component's first set when none is named.
PARAMETER_SET = "scenario"
# How each importer applies the bindings (`cosim ssp --help`, and the SSD's description).
# SSP 1.0 applies every ParameterBinding and has no default or selectable set, so no
# form of the archive makes ecos apply one without its name (docs/interoperability.md).
IMPORTERS = f"""The scenario's parameters are bound in each component, in one parameter set
named "{PARAMETER_SET}"; the importers apply it with:
  libcosim: CosimExecution.from_ssp_file(PATH) (applied as loaded)
  ecos:     EcosSimulation(...).init(parameter_set="{PARAMETER_SET}") (a plain init()
            applies none: the FMUs run at their start values)
  FMPy:     simulate_ssp(PATH, ..., parameter_set=robofmu.ssp.fmpy_parameter_set(PATH))
            (simulate_ssp ignores the bindings of the SSD)"""
NO_SCHEDULE = ("a multi-segment motion (a sequence of plans) has no SSP form: SSP parameters "
               "are fixed for the whole run; export one segment at a time (a copy of the "
               "scenario with two of its waypoints, the first as start), or run the whole "
               "motion with 'cosim run'")


def _variables(path: Path) -> dict:
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


def _parameter_bindings(assignments: dict, variables: dict, alias: str) -> ET.Element:
    """A component's ParameterBindings: one inline set, names relative to the FMU."""
    bindings = ET.Element(_tag("ssd", "ParameterBindings"))
    binding = ET.SubElement(bindings, _tag("ssd", "ParameterBinding"))
    values = ET.SubElement(binding, _tag("ssd", "ParameterValues"))
    pset = ET.SubElement(values, _tag("ssv", "ParameterSet"), version="1.0", name=PARAMETER_SET)
    params = ET.SubElement(pset, _tag("ssv", "Parameters"))
    for name, value in assignments.items():
        p = ET.SubElement(params, _tag("ssv", "Parameter"), name=name)
        p.append(_value_element(_type_of(variables, alias, name), value))
    return bindings


def resources(fmus: dict[str, Path]) -> dict[str, str]:
    """The archive path of each alias's FMU: resources/NAME.fmu, one entry per file (two
    aliases of one file share it); another file of a name already taken goes under
    resources/ALIAS/."""
    taken: dict[str, Path] = {}
    found = {}
    for alias, path in fmus.items():
        name = f"resources/{path.name}"
        if taken.setdefault(name, path.resolve()) != path.resolve():
            name = f"resources/{alias}/{path.name}"
        found[alias] = name
    return found


def system_structure(scenario: Scenario, variables: dict[str, dict]) -> ET.ElementTree:
    """The SystemStructure.ssd document of `scenario`; `variables[alias]` maps each
    FMU's variable names to FMPy's ScalarVariable objects."""
    root = ET.Element(_tag("ssd", "SystemStructureDescription"), version="1.0", name=scenario.name,
                      description=" ".join(IMPORTERS.split()))
    system = ET.SubElement(root, _tag("ssd", "System"), name=scenario.name)
    elements = ET.SubElement(system, _tag("ssd", "Elements"))
    used: dict[str, dict[str, str]] = {alias: {} for alias in scenario.order}
    sources = resources(scenario.fmus)
    for c in scenario.connections:
        used[c.source.alias][c.source.variable] = "output"
        used[c.target.alias][c.target.variable] = "input"
    for sig in scenario.record:
        used[sig.alias].setdefault(sig.variable, "output")
    for alias in scenario.order:
        component = ET.SubElement(elements, _tag("ssd", "Component"), name=alias,
                                  type="application/x-fmu-sharedlibrary",
                                  source=sources[alias])
        connectors = ET.SubElement(component, _tag("ssd", "Connectors"))
        for name, kind in used[alias].items():
            _type_of(variables[alias], alias, name)
            causality = variables[alias][name].causality
            if causality != kind:
                raise ScenarioError(f"{alias}.{name} is a {causality}, not an {kind}")
            connector = ET.SubElement(connectors, _tag("ssd", "Connector"), name=name, kind=kind)
            ET.SubElement(connector, _tag("ssc", _type_of(variables[alias], alias, name)))
        if scenario.parameters.get(alias):
            component.append(_parameter_bindings(scenario.parameters[alias], variables[alias], alias))
    connections = ET.SubElement(system, _tag("ssd", "Connections"))
    for c in scenario.connections:
        ET.SubElement(connections, _tag("ssd", "Connection"),
                      startElement=c.source.alias, startConnector=c.source.variable,
                      endElement=c.target.alias, endConnector=c.target.variable)
    system.append(system_annotations(scenario.step_size))
    root.append(default_experiment(scenario.start_time, scenario.stop_time, scenario.step_size))
    return ET.ElementTree(root)


def check_archive_path(path: Path, option: str = "path") -> None:
    """ScenarioError (naming `option`, the argument that gave `path`) unless `path` can
    be the archive: a file whose name ends with .ssp."""
    if path.suffix != ".ssp" or path.is_dir():
        raise ScenarioError(f"{option}: {path}: the SSP archive is a file whose name ends "
                            "with .ssp; name such a file")


def no_schedule(scenario: Scenario, source: Path | None, problem: str) -> None:
    """ScenarioError `problem` when `scenario` has plan switches, naming the field of its
    file `source` that holds them (when it was read from a file)."""
    if scenario.schedule:  # the hand-written form's waypoints, or the plain form's switches
        where = "" if source is None else f"{source}: field '{schedule_field(source)}': "
        raise ScenarioError(where + problem)


def write_ssp(scenario: Scenario, path: Path, source: Path | None = None) -> None:
    """Writes the SSP archive of `scenario` (read from the file `source`, if any: named
    in the message of a scenario that has no SSP form) to `path`."""
    no_schedule(scenario, source, NO_SCHEDULE)
    variables = {alias: _variables(p) for alias, p in scenario.fmus.items()}
    tree = system_structure(scenario, variables)
    ET.indent(tree)
    root = tree.getroot()
    assert root is not None  # system_structure builds the document from its root
    path.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("SystemStructure.ssd", ET.tostring(root, encoding="unicode",
                                                      xml_declaration=True))
        written = set()
        for alias, name in resources(scenario.fmus).items():
            if name not in written:
                z.write(scenario.fmus[alias], name)
                written.add(name)


def fmpy_parameter_set(path: Path):
    """The bindings of an SSP written by write_ssp as the one FMPy ParameterSet that
    FMPy's simulate_ssp(parameter_set=...) takes (it applies no binding of the SSD
    itself), with names "component.variable"."""
    merged = ParameterSet(name=PARAMETER_SET)
    for component in read_ssd(str(path)).system.elements:
        for binding in component.parameterBindings:
            for parameter_set in binding.parameterValues:
                for p in parameter_set.parameters:
                    p.name = f"{component.name}.{p.name}"
                    merged.parameters.append(p)
    return merged


def add_arguments(parser) -> None:
    """``cosim ssp SCENARIO --out X.ssp``."""
    parser.epilog = IMPORTERS
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.add_argument("scenario", type=Path, help="scenario file (.toml or .json)")
    parser.add_argument("--out", type=output_path, required=True, help="SSP file to write (.ssp)")
    parser.add_argument("--fmu-dir", type=Path, help="find the FMUs by file name here")


def run(args) -> int:
    check_archive_path(args.out, "--out")
    scenario = load_scenario(args.scenario, fmu_dir(args.fmu_dir))
    write_ssp(scenario, args.out, args.scenario)
    print(f"wrote {args.out}")
    return 0
