"""Every reference case (tests/references/<Model>/<case>: closed forms and the
library's kinematics, scripts/make_references.py; never an FMU run) through
``cosim verify``, for the FMI 2.0 and FMI 3.0 builds on both interfaces, with the
tolerances of each case.json. The verdicts are cosim verify's; the report's numbers are
checked against the stated tolerances here as well."""

import json

import pytest

from conftest import DIST, INTERFACES, REFERENCES
from verify_cli import verify

BUILDS = {"2.0": DIST, "3.0": DIST / "fmi3"}


def cases():
    found = []
    for version in BUILDS:
        for model_dir in sorted(REFERENCES.iterdir()):
            for case_dir in sorted(model_dir.iterdir()):
                for interface in INTERFACES:
                    label = f"{version}-{model_dir.name}-{case_dir.name}-{interface}"
                    found.append(pytest.param(version, case_dir, interface, id=label))
    return found


@pytest.mark.parametrize("version,case_dir,interface", cases())
def test_reference_case_passes_through_cosim_verify(version, case_dir, interface, tmp_path):
    model = case_dir.parent.name
    fmu = BUILDS[version] / f"{model}.fmu"
    short = {"CoSimulation": "cs", "ModelExchange": "me"}[interface]
    outcome = verify(fmu, case_dir, "--interface", short, "--out", tmp_path)
    print(outcome.out)
    assert outcome.code == 0, outcome.out + outcome.err
    report = outcome.report(tmp_path)
    assert (report["fmi_version"], report["interface"]) == (version, interface)
    experiment = report["experiment"]
    tolerances = json.loads((case_dir / "case.json").read_text())["tolerances"][interface]
    # Every reference column was judged, with the case's absolute tolerance.
    assert sorted(s["signal"] for s in report["signals"]) == sorted(tolerances)
    for signal in report["signals"]:
        assert signal["rule"] == {"rule": "deviation", "abs": tolerances[signal["signal"]],
                                  "rel": 0.0}
        assert signal["passed"] and signal["max_error"] <= tolerances[signal["signal"]]
        # Event instants left out (the planner's t0 and tf) are a few samples only.
        assert signal["samples"] > 0.9 * (experiment["stop"] - experiment["start"]) / experiment["step"]
    assert list((tmp_path).glob("*.png")) == []
