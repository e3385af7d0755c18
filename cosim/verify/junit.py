"""JUnit XML: one test suite for the run, one test case per signal, a failure element
(message = the one-line verdict) for a signal outside its tolerance."""

from __future__ import annotations

import xml.etree.ElementTree as ET

from .compare import Verdict


def junit_report(suite: str, classname: str, verdicts: list[Verdict], seconds: float) -> bytes:
    failures = sum(not v.passed for v in verdicts)
    root = ET.Element("testsuites", name="cosim verify", tests=str(len(verdicts)),
                      failures=str(failures), errors="0", time=f"{seconds:.3f}")
    node = ET.SubElement(root, "testsuite", name=suite, tests=str(len(verdicts)),
                         failures=str(failures), errors="0", skipped="0", time=f"{seconds:.3f}")
    for v in verdicts:
        case = ET.SubElement(node, "testcase", name=v.signal, classname=classname, time="0")
        if not v.passed:
            failure = ET.SubElement(case, "failure", message=v.line(), type="tolerance")
            failure.text = v.line()
        else:
            ET.SubElement(case, "system-out").text = v.line()
    ET.indent(root)
    return ET.tostring(root, encoding="utf-8", xml_declaration=True) + b"\n"


def junit_error(suite: str, classname: str, message: str) -> bytes:
    """A run that failed before any signal could be judged: one test case in error."""
    root = ET.Element("testsuites", name="cosim verify", tests="1", failures="0", errors="1")
    node = ET.SubElement(root, "testsuite", name=suite, tests="1", failures="0", errors="1",
                         skipped="0")
    case = ET.SubElement(node, "testcase", name="simulation", classname=classname, time="0")
    ET.SubElement(case, "error", message=message, type="run").text = message
    ET.indent(root)
    return ET.tostring(root, encoding="utf-8", xml_declaration=True) + b"\n"
