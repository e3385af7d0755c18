"""The evidence every FMU carries (FMI-LS-REF, crates/build/fmi-build/src/lsref.rs): its
manifest and experiments files against the standards' schemas, every file it lists
against its SHA-256, and every case of tests/references/ inside it byte for byte.

Truths: the XSDs of FMI-LS-REF and MA-HS-Experiments (tests/schemas/, verbatim, with the
FMI 3.0 schemas they import read from FMPy's copies) through xmlschema, a validator that
shares no code with the packager; hashlib's SHA-256; the files of tests/references/."""

import hashlib
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path, PurePosixPath

import fmpy
import pytest
import xmlschema

from conftest import DIST, MODELS, REFERENCES, ROOT

SCHEMAS = ROOT / "tests" / "schemas"
FMI3 = Path(fmpy.__file__).parent / "schema" / "fmi3"
# The URLs the two schemas import the FMI 3.0 schemas from: read from FMPy's copies.
FMI_STANDARD = "https://raw.githubusercontent.com/modelica/fmi-standard/main/schema/"
URIS = {FMI_STANDARD + name: str(FMI3 / name)
        for name in ("fmi3Annotation.xsd", "fmi3LayeredStandardManifest.xsd")}
FOLDER = "extra/org.fmi-standard.fmi-ls-ref"
MANIFEST = f"{FOLDER}/fmi-ls-manifest.xml"
VARIANTS = ["", "fmi3", "fmi3-scalar"]
FMUS = [pytest.param(DIST / variant / f"{model}.fmu", id=f"{variant or 'fmi2'}/{model}")
        for variant in VARIANTS for model in MODELS]


@pytest.fixture(scope="module")
def manifest_schema():
    return xmlschema.XMLSchema(str(SCHEMAS / "fmi3LayeredStandardReferenceManifest.xsd"),
                               uri_mapper=URIS, allow="local")


@pytest.fixture(scope="module")
def experiments_schema():
    # The MA-HS-Experiments schema imports fmi3Annotation.xsd with xs:import although
    # neither has a target namespace (XSD 1.0 wants xs:include there): xmlschema builds it
    # leniently with fmi3Annotation.xsd as a second source of the same (absent) namespace,
    # and this known defect must be the schema's only error.
    schema = xmlschema.XMLSchema(
        [str(SCHEMAS / "maHarmonizedSpecificationExperiments.xsd"), str(FMI3 / "fmi3Annotation.xsd")],
        uri_mapper=URIS, allow="local", validation="lax")
    errors = [str(e) for e in schema.all_errors]
    assert len(errors) == 1 and "'namespace' attribute is not present on the import" in errors[0]
    return schema


def entries(fmu: Path) -> dict[str, bytes]:
    if not fmu.exists():
        pytest.fail(f"{fmu} is missing: run scripts/build-fmus.sh first")
    with zipfile.ZipFile(fmu) as z:
        return {name: z.read(name) for name in z.namelist()}


def resolve(source: str) -> str:
    """The archive path of a manifest's relative source."""
    parts: list[str] = []
    for part in PurePosixPath(FOLDER, source).parts:
        if part == "..":
            parts.pop()
        else:
            parts.append(part)
    return "/".join(parts)


def test_there_are_twelve_fmus():
    # Expected: 4 models (one modelDescription/<Model>.xml each) x 3 variants.
    assert len(FMUS) == 12


@pytest.mark.parametrize("fmu", FMUS)
def test_manifest_and_experiments_are_valid_and_every_file_matches_its_checksum(
        fmu, manifest_schema, experiments_schema):
    files = entries(fmu)
    manifest = files[MANIFEST]
    manifest_schema.validate(manifest.decode())
    root = ET.fromstring(manifest)
    roles, names = [], []
    for related in root.iter("Related"):
        path = resolve(related.attrib["source"])
        assert path in files, f"{fmu}: {path} is listed but missing"
        checksum = related.find("Annotations/Annotation[@type='org.robofmu.checksum']/Checksum")
        assert checksum is not None and checksum.attrib["algorithm"] == "SHA-256"
        assert checksum.attrib["value"] == hashlib.sha256(files[path]).hexdigest(), path
        roles.append(related.attrib["role"])
        if related.attrib["role"].startswith("experiment"):
            experiments_schema.validate(files[path].decode())
            names += [e.attrib["name"] for e in ET.fromstring(files[path]).iter("Experiment")]
    assert roles.count("experiment/smoke-test") == 1
    assert roles.count("experiment/validation") == 1
    assert "document" in roles and "result" in roles
    # The page has a section per experiment; the FMU's main page links it.
    page = files["documentation/fmi-ls-ref.html"].decode()
    assert sorted(names) == sorted(p.name for p in (REFERENCES / fmu.stem).iterdir())
    for name in names:
        assert f"<h2>{name}: " in page
    assert 'href="fmi-ls-ref.html"' in files["documentation/index.html"].decode()


@pytest.mark.parametrize("model", MODELS)
def test_every_case_is_carried_as_an_experiment_with_the_same_files(model):
    # Expected: each case folder of tests/references/<Model>/ is one experiment; its
    # reference and input are the folder's files, byte for byte; the defaults case (the
    # folder holding cross-check.txt) is the smoke test with the FMU's DefaultExperiment.
    files = entries(DIST / f"{model}.fmu")
    smoke = ET.fromstring(files[f"{FOLDER}/smoke-test.exp"])
    validation = ET.fromstring(files[f"{FOLDER}/validation.exp"])
    experiments = {e.attrib["name"]: (e, kind) for kind, doc in (("smoke", smoke),
                   ("validation", validation)) for e in doc.iter("Experiment")}
    cases = sorted(p for p in (REFERENCES / model).iterdir() if p.is_dir())
    assert sorted(experiments) == [c.name for c in cases]
    description = fmpy.read_model_description(str(DIST / f"{model}.fmu"))
    default = description.defaultExperiment
    for case in cases:
        experiment, kind = experiments[case.name]
        assert kind == ("smoke" if (case / "cross-check.txt").exists() else "validation")
        reference = experiment.find("References").attrib["source"]
        assert files[f"{FOLDER}/{reference}"] == (case / f"{model}_ref.csv").read_bytes()
        inputs = [p for p in case.glob(f"{model}_in*.csv")]
        stimuli = experiment.find("Stimuli")
        assert (stimuli is None) == (not inputs)
        if inputs:
            assert files[f"{FOLDER}/{stimuli.attrib['source']}"] == inputs[0].read_bytes()
        settings = experiment.find("TransientSimulation").attrib
        options = dict(line.split(",") for line in
                       (case / f"{model}_ref.opt").read_text().splitlines() if line.strip())
        assert float(settings["stopTime"]) == float(options["StopTime"])
        assert float(settings["stepSize"]) == float(options["StepSize"])
        assert float(experiment.attrib["tolerance"]) == float(options["RelTol"])
        if kind == "smoke":
            assert float(settings["stopTime"]) == float(default.stopTime)
            assert float(settings["startTime"]) == float(default.startTime)


def test_the_schemas_refuse_what_the_standards_do_not_allow(manifest_schema,
                                                            experiments_schema):
    # Expected: the schemas' own rules (a role outside FMI-LS-REF's list, a manifest
    # without fmi-ls-version, an experiment without its analysis type, a tolerance that is
    # no number) make our files invalid: the validation above can fail.
    files = entries(DIST / "PID.fmu")
    manifest = files[MANIFEST].decode()
    assert not manifest_schema.is_valid(manifest.replace('role="result"', 'role="results"'))
    assert not manifest_schema.is_valid(manifest.replace(
        'fmi-ls:fmi-ls-version="1.0.0-alpha.1" ', ""))
    smoke = files[f"{FOLDER}/smoke-test.exp"].decode()
    assert not experiments_schema.is_valid(smoke.replace("TransientSimulation", "Transient"))
    assert not experiments_schema.is_valid(smoke.replace('tolerance="1e-8"', 'tolerance="x"'))
