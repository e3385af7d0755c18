"""JUnit XML: one test suite per case (the FMU, interface and case), one test case per
signal with a failure element (message = the one-line verdict) for a signal outside its
tolerance, one test case "run" failed when the FMU ended the run early (not allowed),
one test case in error when the run failed or the case was rejected."""

from __future__ import annotations

import xml.etree.ElementTree as ET

from .compare import EarlyEnd, Verdict


def suite(name: str, classname: str, verdicts: list[Verdict], seconds: float,
          end: EarlyEnd | None = None) -> ET.Element:
    node = ET.Element("testsuite", name=name, errors="0", skipped="0", time=f"{seconds:.3f}")
    failures = 0
    for v in verdicts:
        case = ET.SubElement(node, "testcase", name=v.signal, classname=classname, time="0")
        if not v.passed:
            failures += 1
            failure = ET.SubElement(case, "failure", message=v.line(), type="tolerance")
            failure.text = v.line()
        else:
            ET.SubElement(case, "system-out").text = v.line()
    tests = len(verdicts)
    if end is not None:
        tests += 1
        case = ET.SubElement(node, "testcase", name="run", classname=classname, time="0")
        if end.allowed:
            ET.SubElement(case, "system-out").text = end.line()
        else:
            failures += 1
            ET.SubElement(case, "failure", message=end.line(), type="early end").text = end.line()
    node.set("tests", str(tests))
    node.set("failures", str(failures))
    return node


def error_suite(name: str, classname: str, message: str, kind: str = "run") -> ET.Element:
    """A case that could not be judged: one test case in error."""
    node = ET.Element("testsuite", name=name, tests="1", failures="0", errors="1",
                      skipped="0", time="0")
    case = ET.SubElement(node, "testcase", name="simulation", classname=classname, time="0")
    ET.SubElement(case, "error", message=message, type=kind).text = message
    return node


def document(suites: list[ET.Element], seconds: float | None = None) -> bytes:
    root = ET.Element("testsuites", name="cosim verify")
    for key in ("tests", "failures", "errors"):
        root.set(key, str(sum(int(s.get(key, "0")) for s in suites)))
    if seconds is not None:
        root.set("time", f"{seconds:.3f}")
    root.extend(suites)
    ET.indent(root)
    return ET.tostring(root, encoding="utf-8", xml_declaration=True) + b"\n"
