"""``cosim verify FMU`` with no case: every experiment the FMU carries (FMI-LS-REF), and
a broken archive refused in one line.

Truths: the reference cases of tests/references/ (each from its own independent truth:
cross-check.txt and scripts/make_references.py say which), which the FMUs carry byte
for byte (test_lsref.py); an edited copy raises Pss3Plant's theta[3] by 1e-3 rad, ten
times its tolerance, from T_WRONG on, so that theta[3] alone fails, first at T_WRONG (the
result is sampled every 1 ms as the reference); the Planner's defaults case is the
reference of its DefaultExperiment (0 to 2.5 s, step 0.01 s: modelDescription.xml)."""

import hashlib
import json
import xml.etree.ElementTree as ET
import zipfile

import pytest
from junitparser import JUnitXml

from conftest import DIST, MODELS, REFERENCES
from verify_cli import verify

FOLDER = "extra/org.fmi-standard.fmi-ls-ref"
MANIFEST = f"{FOLDER}/fmi-ls-manifest.xml"
PATH1_REF = f"{FOLDER}/path1/Pss3Plant_ref.csv"
T_WRONG = 1.235
ET.register_namespace("fmi-ls", "http://fmi-standard.org/fmi-ls-manifest")


def entries(fmu):
    with zipfile.ZipFile(fmu) as z:
        return {name: z.read(name) for name in z.namelist()}


def write(fmu, files):
    with zipfile.ZipFile(fmu, "w", zipfile.ZIP_DEFLATED) as z:
        for name, data in files.items():
            z.writestr(name, data)
    return fmu


def with_checksum(files, path):
    """The manifest's SHA-256 of `path` set to that of its (edited) bytes."""
    root = ET.fromstring(files[MANIFEST])
    for related in root.iter("Related"):
        if f"{FOLDER}/{related.get('source')}" == path:
            related.find(".//Checksum").set("value", hashlib.sha256(files[path]).hexdigest())
    files[MANIFEST] = ET.tostring(root, xml_declaration=True, encoding="UTF-8")
    return files


def raise_theta3(csv: bytes) -> bytes:
    lines = csv.decode().splitlines()
    column = lines[0].split(",").index('"theta[3]"')
    out = [lines[0]]
    for line in lines[1:]:
        fields = line.split(",")
        if float(fields[0]) >= T_WRONG - 1e-12:
            fields[column] = repr(float(fields[column]) + 1e-3)
        out.append(",".join(fields))
    return ("\n".join(out) + "\n").encode()


def reports(out):
    return {p.parent.name: json.loads(p.read_text()) for p in out.glob("*/verify.json")}


def test_pss3plant_passes_every_experiment_it_carries(tmp_path):
    # The must-show: `cosim verify dist/Pss3Plant.fmu`, no other argument but
    # where to write.
    out, junit = tmp_path / "out", tmp_path / "junit.xml"
    outcome = verify(DIST / "Pss3Plant.fmu", "--out", out, "--junit", junit)
    print(outcome.out, outcome.err)
    assert outcome.code == 0, outcome.err
    found = reports(out)
    assert sorted(found) == sorted(p.name for p in (REFERENCES / "Pss3Plant").iterdir())
    assert all(r["passed"] and len(r["signals"]) == 6 for r in found.values())
    assert outcome.out.count("PASS ") == 12 and "FAIL" not in outcome.out
    assert outcome.out.splitlines()[-1].startswith(f"{DIST / 'Pss3Plant.fmu'}: 2 of 2 experiments passed")
    suites = list(JUnitXml.fromfile(str(junit)))
    assert len(suites) == 2 and sum(s.tests for s in suites) == 12
    assert sum(s.failures + s.errors for s in suites) == 0


@pytest.mark.parametrize("variant", ["", "fmi3", "fmi3-scalar"])
@pytest.mark.parametrize("model", MODELS)
def test_every_fmu_passes_its_own_experiments(model, variant, tmp_path):
    outcome = verify(DIST / variant / f"{model}.fmu", "--out", tmp_path / "out")
    assert outcome.code == 0, outcome.out + outcome.err
    assert sorted(reports(tmp_path / "out")) == sorted(
        p.name for p in (REFERENCES / model).iterdir())


def test_an_edited_reference_value_fails_naming_signal_and_time(tmp_path):
    files = entries(DIST / "Pss3Plant.fmu")
    files[PATH1_REF] = raise_theta3(files[PATH1_REF])
    fmu = write(tmp_path / "Pss3Plant.fmu", with_checksum(files, PATH1_REF))
    outcome = verify(fmu, "--out", tmp_path / "out")
    print(outcome.out)
    assert outcome.code == 1, outcome.err
    failing = [line for line in outcome.out.splitlines() if line.startswith("FAIL")]
    assert len(failing) == 1 and failing[0].startswith("FAIL theta[3]:")
    assert f"leaves its band at t = {T_WRONG:g} s" in failing[0]
    assert "1 of 2 experiments passed" in outcome.out.splitlines()[-1]
    found = reports(tmp_path / "out")
    assert not found["path1"]["passed"] and found["from_default_pose"]["passed"]
    assert (tmp_path / "out" / "path1" / "theta_3.png").is_file()


def refused(tmp_path, files, *words):
    """Exit 2, one line on stderr naming each of `words`, nothing written."""
    fmu = write(tmp_path / "copy.fmu", files)
    before = sorted(tmp_path.rglob("*"))
    outcome = verify(fmu, "--out", tmp_path / "out")
    assert outcome.code == 2, outcome.out + outcome.err
    lines = outcome.err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in outcome.err, outcome.err
    for word in words:
        assert word in lines[0], lines[0]
    assert outcome.out == "" and sorted(tmp_path.rglob("*")) == before
    return lines[0]


def test_a_removed_file_is_refused_in_one_line(tmp_path):
    files = entries(DIST / "Pss3Plant.fmu")
    del files[f"{FOLDER}/path1/Pss3Plant_input.csv"]
    refused(tmp_path, files, "path1/Pss3Plant_input.csv", "is missing from the archive",
            "repackage the FMU")


def test_an_edited_file_with_its_old_checksum_is_refused_in_one_line(tmp_path):
    files = entries(DIST / "Pss3Plant.fmu")
    files[PATH1_REF] = raise_theta3(files[PATH1_REF])
    refused(tmp_path, files, PATH1_REF, "SHA-256", "changed after packaging")


def test_a_wrong_checksum_is_refused_in_one_line(tmp_path):
    files = entries(DIST / "Pss3Plant.fmu")
    manifest = files[MANIFEST].decode()
    digest = hashlib.sha256(files[PATH1_REF]).hexdigest()
    files[MANIFEST] = manifest.replace(digest, "0" * 64).encode()
    refused(tmp_path, files, PATH1_REF, "is not the manifest's 0000000000000000")


def test_a_reference_column_naming_no_variable_is_refused(tmp_path):
    # A column no variable has: refused, naming the file inside the FMU and the column.
    files = result_only(tmp_path)
    path = f"{FOLDER}/Planner_out.csv"
    files[path] = files[path].replace(b'"qdot[3]"', b'"qdot[4]"', 1)
    refused(tmp_path, files, path, "column 'qdot[4]'", "has no such variable")
    # In our FMU the experiment's tolerances name the renamed column first: refused too.
    files = entries(DIST / "Pss3Plant.fmu")
    files[PATH1_REF] = files[PATH1_REF].replace(b'"omega[3]"', b'"omega[4]"', 1)
    refused(tmp_path, with_checksum(files, PATH1_REF), "validation.exp",
            "tolerances.omega[3]", "the reference has no such column")


def test_an_experiment_the_fmu_cannot_run_is_refused(tmp_path):
    files = entries(DIST / "Pss3Plant.fmu")
    path = f"{FOLDER}/validation.exp"
    files[path] = files[path].replace(b"<TransientSimulation", b"<SteadyState/><Ignored")
    refused(tmp_path, with_checksum(files, path), "validation.exp", "SteadyState",
            "TransientSimulation experiments only")


def test_an_fmu_without_experiments_is_refused(tmp_path):
    files = {n: d for n, d in entries(DIST / "Pss3Plant.fmu").items()
             if not n.startswith("extra/")}
    refused(tmp_path, files, "carries no experiments", "give a case folder")


def result_only(tmp_path):
    """Planner.fmu as Reference-FMUs 0.0.41 ship theirs: a manifest naming one `result`
    CSV (the defaults case's reference), no experiment, no checksum."""
    files = {n: d for n, d in entries(DIST / "Planner.fmu").items()
             if not n.startswith("extra/")}
    files[f"{FOLDER}/Planner_out.csv"] = (REFERENCES / "Planner" / "defaults"
                                          / "Planner_ref.csv").read_bytes()
    files[MANIFEST] = (
        b'<?xml version="1.0" encoding="UTF-8"?>\n<fmiReferences '
        b'xmlns:fmi-ls="http://fmi-standard.org/fmi-ls-manifest" '
        b'fmi-ls:fmi-ls-name="org.fmi-standard.fmi-ls-ref" fmi-ls:fmi-ls-version="1.0.0-alpha.1" '
        b'fmi-ls:fmi-ls-description="Layered Standard providing information on related files '
        b'included in an FMU.">\n  <Related type="text/csv" source="Planner_out.csv" '
        b'role="result"/>\n</fmiReferences>\n')
    return files


def test_an_fmu_carrying_only_a_result_is_verified_against_its_default_experiment(tmp_path):
    files = result_only(tmp_path)
    fmu = write(tmp_path / "Planner.fmu", files)
    outcome = verify(fmu, "--out", tmp_path / "out")
    print(outcome.out)
    assert outcome.code == 0, outcome.err
    (report,) = reports(tmp_path / "out").values()
    assert report["experiment"]["stop"] == 2.5 and report["experiment"]["step"] == 0.01
    assert report["passed"] and len(report["signals"]) == 9
    # Without a DefaultExperiment: the reference's span (0 to 2.5 s) and its interval.
    description = files["modelDescription.xml"].decode()
    start = description.index("<DefaultExperiment")
    stripped = dict(files, **{"modelDescription.xml": (
        description[:start] + description[description.index("/>", start) + 2:]).encode()})
    outcome = verify(write(tmp_path / "Planner.fmu", stripped), "--out", tmp_path / "out1")
    assert outcome.code == 0, outcome.err
    (report,) = reports(tmp_path / "out1").values()
    assert report["experiment"]["stop"] == 2.5 and report["passed"]
    assert report["experiment"]["step"] == pytest.approx(0.01, rel=1e-12)
    # The same FMU with q[1] off by 0.5 rad from 1 s on (60 % of the samples, beyond the
    # band's 10 %) fails on q[1] alone.
    csv = files[f"{FOLDER}/Planner_out.csv"].decode().splitlines()
    for k in range(1, len(csv)):
        fields = csv[k].split(",")
        if float(fields[0]) >= 1.0 - 1e-12:
            fields[1] = repr(float(fields[1]) + 0.5)
        csv[k] = ",".join(fields)
    files[f"{FOLDER}/Planner_out.csv"] = ("\n".join(csv) + "\n").encode()
    outcome = verify(write(tmp_path / "Planner.fmu", files), "--out", tmp_path / "out2")
    failing = [line for line in outcome.out.splitlines() if line.startswith("FAIL")]
    assert outcome.code == 1 and len(failing) == 1 and failing[0].startswith("FAIL q[1]:")
