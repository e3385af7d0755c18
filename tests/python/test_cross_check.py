"""The FMI cross-check layout written by scripts/cross-check.sh, checked with FMPy's
cross-check tooling (fmpy.cross_check): each FMU simulated the way the cross-check
simulates it (default parameters, the _ref.opt experiment, the _in.csv inputs), its
result validated against the reference (fmpy.cross_check.validate_result: at most 10 %
of the samples outside a band of 10 % of the signal's range around the reference), the
results filed as an importing tool files them, and the whole tree validated by FMPy's
repository rules (validate_vendor_repo: layout, file sizes, modelDescription, options
and CSV files naming existing variables). The script's own verdicts are cosim verify's
with the same band rule (test_verify_rules.py checks that rule against FMPy's)."""

import json
import subprocess
from pathlib import Path

import fmpy
import pytest
from fmpy.cross_check import validate_result
from fmpy.cross_check.validate_vendor_repo import read_csv, validate_repo
from fmpy.util import read_ref_opt_file, write_csv
from junitparser import JUnitXml

from conftest import MODELS

ROOT = Path(__file__).resolve().parents[2]
INTERFACES = {"cs": "CoSimulation", "me": "ModelExchange"}
# FMPy 0.3.32's validate_signal imports from scipy.ndimage.filters, deprecated (still
# there) in SciPy 1.17: a warning about FMPy's import path, not about our FMUs.
pytestmark = pytest.mark.filterwarnings(
    "ignore:Please import .* from the `scipy.ndimage` namespace:DeprecationWarning")


@pytest.fixture(scope="module")
def tree(tmp_path_factory):
    out = tmp_path_factory.mktemp("cross-check")
    subprocess.run(["bash", str(ROOT / "scripts" / "cross-check.sh"), str(out)], check=True,
                   capture_output=True)
    return out


def model_dirs(tree: Path) -> list[Path]:
    return sorted(p.parent for p in (tree / "fmus").glob("2.0/*/linux64/robofmu/*/*/*.fmu"))


def simulate(model_dir: Path):
    """The cross-check's simulation: defaults, the _ref.opt experiment, _in.csv inputs."""
    model = model_dir.name
    options = read_ref_opt_file(str(model_dir / f"{model}_ref.opt"))
    reference = read_csv(str(model_dir / f"{model}_ref.csv"))
    inputs = model_dir / f"{model}_in.csv"
    interface = INTERFACES[model_dir.parts[-5]]
    result = fmpy.simulate_fmu(
        str(model_dir / f"{model}.fmu"), fmi_type=interface, validate=False,
        start_time=options["StartTime"], stop_time=options["StopTime"],
        step_size=options["StepSize"] if interface == "CoSimulation" else None,
        output_interval=options["StepSize"], relative_tolerance=options["RelTol"],
        input=read_csv(str(inputs)) if inputs.exists() else None,
        output=list(reference.dtype.names[1:]))
    return result, reference, options


def test_tree_has_every_model_on_both_interfaces(tree):
    dirs = model_dirs(tree)
    assert sorted((d.parts[-5], d.name) for d in dirs) == sorted(
        (kind, model) for kind in INTERFACES for model in MODELS)
    for d in dirs:
        assert (d / "ReadMe.txt").is_file()
        # The planner alone has no inputs.
        assert (d / f"{d.name}_in.csv").exists() == (d.name != "Planner")


def test_results_validate_and_the_tree_follows_the_repository_rules(tree):
    for model_dir in model_dirs(tree):
        result, reference, options = simulate(model_dir)
        problem = validate_result(result=result, reference=reference,
                                  t_start=options["StartTime"], t_stop=options["StopTime"])
        assert problem is None, (model_dir, problem)
        # File the result as an importing tool (FMPy) files it in the cross-check.
        fmi_version, kind, platform, tool, version, model = model_dir.parts[-6:]
        results = (tree / "results" / fmi_version / kind / platform / "FMPy" /
                   fmpy.__version__ / tool / version / model)
        results.mkdir(parents=True)
        write_csv(str(results / f"{model}_out.csv"), result)
        (results / "passed").touch()
        (results / "ReadMe.txt").write_text("Simulated with FMPy by tests/python/test_cross_check.py.\n")
    fmu_count, result_count, problems = validate_repo(str(tree))
    assert problems == []
    assert (fmu_count, result_count) == (2 * len(MODELS), 2 * len(MODELS))


def test_result_validation_rejects_a_wrong_result(tree):
    # Truth: a planner result with the third axis scaled by 0.5 leaves the 10 % band
    # around the reference for most samples, so the validation must report it; this
    # shows the check above can fail.
    model_dir = next(d for d in model_dirs(tree) if d.name == "Planner")
    result, reference, options = simulate(model_dir)
    result["q[3]"] = 0.5 * result["q[3]"]
    problem = validate_result(result=result, reference=reference,
                              t_start=options["StartTime"], t_stop=options["StopTime"])
    assert problem is not None and "q[3]" in problem


def test_script_verdicts_are_cosim_verify_reports(tree):
    # The script exited 0 (the fixture): every FMU passed; its reports say so per signal,
    # for the reference's every column, under the cross-check band rule.
    for model_dir in model_dirs(tree):
        kind, model = model_dir.parts[-5], model_dir.name
        report_dir = tree / "verify" / "2.0" / kind / model
        report = json.loads((report_dir / "verify.json").read_text())
        reference = read_csv(str(model_dir / f"{model}_ref.csv"))
        assert report["passed"] and report["interface"] == INTERFACES[kind]
        assert [s["signal"] for s in report["signals"]] == list(reference.dtype.names[1:])
        assert all(s["rule"] == {"rule": "cross-check"} for s in report["signals"])
        suite, = list(JUnitXml.fromfile(str(report_dir / "junit.xml")))
        assert (suite.tests, suite.failures) == (len(report["signals"]), 0)


def with_more_cases(tree: Path, to: Path) -> Path:
    """A copy of the tree's fmus/ with the FMI 3.0 builds of the same cases, a case whose
    reference is wrong (the planner's q[3] halved: fails), one whose reference names a
    variable the FMU lacks (rejected) and one for another platform (skipped)."""
    import shutil
    shutil.copytree(tree / "fmus", to / "fmus")
    for model_dir in model_dirs(to):
        fmi3 = Path(str(model_dir).replace("/fmus/2.0/", "/fmus/3.0/"))
        shutil.copytree(model_dir, fmi3)
        shutil.copy(ROOT / "dist" / "fmi3" / f"{model_dir.name}.fmu", fmi3)
    version = model_dirs(to)[0].parts[-2]
    wrong = to / "fmus/2.0/cs/linux64/wrong" / version / "Planner"
    shutil.copytree(to / "fmus/2.0/cs/linux64/robofmu" / version / "Planner", wrong)
    lines = (wrong / "Planner_ref.csv").read_text().splitlines()
    column = lines[0].split(",").index('"q[3]"')
    for k in range(1, len(lines)):
        fields = lines[k].split(",")
        fields[column] = repr(0.5 * float(fields[column]))
        lines[k] = ",".join(fields)
    (wrong / "Planner_ref.csv").write_text("\n".join(lines) + "\n")
    rejected = to / "fmus/2.0/me/linux64/wrong" / version / "PID"
    shutil.copytree(to / "fmus/2.0/me/linux64/robofmu" / version / "PID", rejected)
    text = (rejected / "PID_ref.csv").read_text()
    (rejected / "PID_ref.csv").write_text(text.replace('"u[3]"', '"u[4]"', 1))
    shutil.copytree(to / "fmus/2.0/cs/linux64/robofmu" / version / "PID",
                    to / "fmus/2.0/cs/win64/robofmu" / version / "PID")
    return to


def test_cosim_verify_runs_a_whole_tree(tree, tmp_path):
    # cosim verify TREE with the results into the tree itself (results/ beside fmus/,
    # as an importing tool submits them): one line per case, the summary, one JUnit
    # suite per case, the rules' results layout; checked against FMPy: its cross-check
    # procedure gives the same verdict on every FMI 2.0 case, and its repository check
    # (validate_cross_check_result) re-validates each result we marked passed.
    import shutil
    import sys
    from fmpy.cross_check.validate_vendor_repo import validate_cross_check_result
    from robofmu.verify.tree import tool_version
    xc = with_more_cases(tree, tmp_path)
    done = subprocess.run([sys.executable, "-m", "robofmu", "verify", str(xc), "--out", str(xc),
                           "--jobs", "2"], cwd=ROOT, capture_output=True, text=True)
    print(done.stdout)
    assert done.returncode == 1, done.stderr  # one failed and one rejected case
    lines = done.stdout.splitlines()
    runs = 4 * len(MODELS) + 2
    assert lines[0] == f"{xc}: {runs + 1} cases, {runs} to run here (2 at once), 1 skipped"
    progress = [line for line in lines if line.startswith("[")]
    assert [line.split("]")[0] for line in progress] == [f"[{k}/{runs}" for k in range(1, runs + 1)]
    assert lines[-1].startswith(f"{xc}: {runs - 2} passed, 1 failed, 1 rejected, 1 skipped of "
                                f"{runs + 1} cases in ")
    assert any(line.startswith("SKIPPED  2.0/cs/win64/robofmu/") for line in lines)
    # JUnit: one suite per case run, the failing and the rejected one marked.
    suites = {suite.name: suite for suite in JUnitXml.fromfile(str(xc / "junit.xml"))}
    assert len(suites) == runs
    failing = [name for name, s in suites.items() if s.failures]
    erring = [name for name, s in suites.items() if s.errors]
    assert len(failing) == 1 and "wrong" in failing[0] and "Planner" in failing[0]
    assert len(erring) == 1 and "wrong" in erring[0] and "PID" in erring[0]
    # The results layout: results/<FMI>/<type>/<platform>/cosim/<version>/<tool>/<version>/<Model>.
    results = sorted(p.parent for p in (xc / "results").glob("*/*/*/*/*/*/*/*/README.md"))
    assert len(results) == runs
    for folder in results:
        fmi_version, kind, plat, importer, importer_version, tool, version, model = \
            folder.parts[-8:]
        assert (importer, importer_version, plat) == ("cosim", tool_version(), "linux64")
        markers = [m for m in ("passed", "failed", "rejected") if (folder / m).exists()]
        expected = ("rejected" if (tool, model) == ("wrong", "PID") else
                    "failed" if tool == "wrong" else "passed")
        assert markers == [expected], folder
        assert (folder / f"{model}_out.csv").exists() == (expected != "rejected")
        if fmi_version == "2.0":
            assert validate_cross_check_result(str(folder)) == []
            if expected != "rejected":
                fmu_dir = xc / "fmus" / fmi_version / kind / plat / tool / version / model
                result, reference, options = simulate(fmu_dir)
                fmpy_verdict = validate_result(result=result, reference=reference,
                                               t_start=options["StartTime"],
                                               t_stop=options["StopTime"])
                assert (fmpy_verdict is None) == (expected == "passed"), (folder, fmpy_verdict)
    readme = (xc / "results/2.0/cs/linux64/cosim" / tool_version() / "wrong").glob("*/Planner/README.md")
    folder = next(readme).parent
    text = (folder / "README.md").read_text()
    assert text.startswith("# Planner: failed") and "FAIL q[3]" in text
    assert (folder / "q_3.png").is_file()
    # The wrong case put right and run again, alone (TREE a folder inside the layout):
    # its marker is now passed, and the earlier run's failure marker and plot are gone.
    wrong = next((xc / "fmus/2.0/cs/linux64/wrong").glob("*/Planner"))
    shutil.copy(next((xc / "fmus/2.0/cs/linux64/robofmu").glob("*/Planner/Planner_ref.csv")),
                wrong)
    again = subprocess.run([sys.executable, "-m", "robofmu", "verify", str(wrong.parent),
                            "--out", str(xc)], cwd=ROOT, capture_output=True, text=True)
    assert again.returncode == 0, again.stdout + again.stderr
    assert "1 passed, 0 failed, 0 rejected, 0 skipped of 1 cases" in again.stdout
    assert sorted(p.name for p in folder.iterdir()) == [
        "Planner_out.csv", "README.md", "passed", "verify.json"]
    # --interface picks the cases of one interface; a tree where none runs is refused
    # (exit 2, nothing written), not passed.
    nothing = subprocess.run([sys.executable, "-m", "robofmu", "verify", str(wrong.parent),
                              "--interface", "me", "--out", str(tmp_path / "none")],
                             cwd=ROOT, capture_output=True, text=True)
    assert nothing.returncode == 2 and "none of its 1 cases runs here" in nothing.stderr
    assert "interface cs (--interface me)" in nothing.stderr
    assert not (tmp_path / "none").exists()
