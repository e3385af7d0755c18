"""The SSP 1.0 namespaces and the tool annotations that carry the communication step size.

SSP 1.0 has no element for a co-simulation step size; the importers read it from their
own annotations, which the standard allows (ssc:Annotation holds any one element of
another namespace, and a tool skips the types it does not know):

- libcosim (Open Simulation Platform): ssd:DefaultExperiment / ssd:Annotations /
  ssc:Annotation type="com.opensimulationplatform" / osp:Algorithm /
  osp:FixedStepAlgorithm baseStepSize (its ssp_parser.cpp; without it, and without a
  step size from the caller, libcosim 0.11.2 crashes);
- OMSimulator: ssd:System / ssd:Annotations / ssc:Annotation type="org.openmodelica" /
  oms:Annotations / oms:SimulationInformation / oms:FixedStepMaster with description
  (the master, "oms-ma"), stepSize and relativeTolerance, the three attributes its
  reader takes (SystemWC::importFromSSD_SimulationInformation) and its own SSP export
  writes. A missing relativeTolerance reads as 0, which OMSimulator then passes to every
  FMU as a defined tolerance (fmi2SetupExperiment(toleranceDefined = true, 0)); the
  FMUs here refuse that (docs/interoperability.md), so it is always written;
- ecos and FMPy take the step size from the caller only.

libcosim and ecos match element names with their prefixes (boost property_tree,
pugixml), so the prefixes below are part of the format, not a choice.
"""

from __future__ import annotations

from xml.etree import ElementTree as ET

NS = {
    "ssd": "http://ssp-standard.org/SSP1/SystemStructureDescription",
    "ssc": "http://ssp-standard.org/SSP1/SystemStructureCommon",
    "ssv": "http://ssp-standard.org/SSP1/SystemStructureParameterValues",
    "osp": "http://opensimulationplatform.com/SSP/OSPAnnotations",
    "oms": "https://raw.githubusercontent.com/OpenModelica/OMSimulator/master/schema/oms.xsd",
}
for _prefix, _uri in NS.items():
    ET.register_namespace(_prefix, _uri)


def tag(prefix: str, name: str) -> str:
    return f"{{{NS[prefix]}}}{name}"


def _annotations(kind: str) -> tuple[ET.Element, ET.Element]:
    """ssd:Annotations holding one ssc:Annotation of type `kind`; returns both."""
    annotations = ET.Element(tag("ssd", "Annotations"))
    annotation = ET.SubElement(annotations, tag("ssc", "Annotation"), type=kind)
    return annotations, annotation


def default_experiment(start_time: float, stop_time: float, step_size: float) -> ET.Element:
    """ssd:DefaultExperiment with libcosim's fixed-step algorithm annotation."""
    experiment = ET.Element(tag("ssd", "DefaultExperiment"), startTime=repr(start_time),
                            stopTime=repr(stop_time))
    annotations, annotation = _annotations("com.opensimulationplatform")
    algorithm = ET.SubElement(annotation, tag("osp", "Algorithm"))
    ET.SubElement(algorithm, tag("osp", "FixedStepAlgorithm"), baseStepSize=repr(step_size))
    experiment.append(annotations)
    return experiment


# The relative tolerance written for OMSimulator: its own default (System.h), what it
# would use had the SSP not set one. The FMUs here take no tolerance from the importer
# (fixed-step models; the plant's integrator has its own parameter), so the value only
# has to be one they accept: a positive number.
RELATIVE_TOLERANCE = 1e-4


def system_annotations(step_size: float) -> ET.Element:
    """The ssd:Annotations of a system with OMSimulator's fixed-step master."""
    annotations, annotation = _annotations("org.openmodelica")
    info = ET.SubElement(ET.SubElement(annotation, tag("oms", "Annotations")),
                         tag("oms", "SimulationInformation"))
    ET.SubElement(info, tag("oms", "FixedStepMaster"), description="oms-ma",
                  stepSize=repr(step_size), relativeTolerance=repr(RELATIVE_TOLERANCE))
    return annotations
