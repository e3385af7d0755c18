"""cosim verify on a wrong reference: exit 1, the signal and the first time it leaves its
band named, a PNG of it, JUnit XML that a JUnit parser (junitparser) reads, JSON.

Truth: the path-1 reference (tests/references/Pss3Plant/path1, from the library's
kinematics) with theta[3] raised by 1e-3 rad, ten times its tolerance of 1e-4 rad, from
the sample at T_WRONG on; the FMU is within 1e-5 rad of the unchanged reference, so
theta[3] first leaves its band at the first result sample at or after T_WRONG (the
result is sampled every 1 ms, as the reference) and every other signal passes."""

import json
import shutil
import tempfile

import numpy as np
import pytest
from junitparser import Error, Failure, JUnitXml

from conftest import DIST, REFERENCES
from verify_cli import verify, verify_process

T_WRONG = 1.235
SIGNALS = ["theta[1]", "theta[2]", "theta[3]", "omega[1]", "omega[2]", "omega[3]"]


def wrong_case(tmp_path):
    case = tmp_path / "path1"
    shutil.copytree(REFERENCES / "Pss3Plant" / "path1", case)
    reference = case / "Pss3Plant_ref.csv"
    lines = reference.read_text().splitlines()
    header = lines[0].split(",")
    column = header.index('"theta[3]"')
    out = [lines[0]]
    for line in lines[1:]:
        fields = line.split(",")
        if float(fields[0]) >= T_WRONG - 1e-12:
            fields[column] = repr(float(fields[column]) + 1e-3)
        out.append(",".join(fields))
    reference.write_text("\n".join(out) + "\n")
    return case


@pytest.mark.parametrize("interface", ["cs", "me"])
def test_wrong_reference_fails_and_says_where(interface, tmp_path):
    out, junit = tmp_path / "out", tmp_path / "junit" / "verify.xml"
    outcome = verify(DIST / "Pss3Plant.fmu", wrong_case(tmp_path), "--interface", interface,
                     "--out", out, "--junit", junit)
    print(outcome.out)
    assert outcome.code == 1, outcome.err
    failing = [line for line in outcome.out.splitlines() if line.startswith("FAIL")]
    assert len(failing) == 1 and failing[0].startswith("FAIL theta[3]:")
    assert f"leaves its band at t = {T_WRONG:g} s" in failing[0]
    assert sum(line.startswith("PASS") for line in outcome.out.splitlines()) == 5
    # JSON: the same verdicts in numbers.
    report = json.loads((out / "verify.json").read_text())
    assert report["passed"] is False
    by_name = {s["signal"]: s for s in report["signals"]}
    assert sorted(by_name) == sorted(SIGNALS)
    wrong = by_name["theta[3]"]
    assert wrong["first_exit_time"] == pytest.approx(T_WRONG, abs=1e-9)
    assert wrong["max_error"] == pytest.approx(1e-3, abs=1e-4)
    assert all(by_name[s]["passed"] for s in SIGNALS if s != "theta[3]")
    # PNG: the failing signal only, a readable image.
    assert sorted(p.name for p in out.glob("*.png")) == ["theta_3.png"] == [
        wrong["plot"].rsplit("/", 1)[-1]]
    from matplotlib.image import imread
    image = imread(out / "theta_3.png")
    assert image.shape[0] > 100 and image.shape[1] > 100
    # JUnit: one suite, one test case per signal, the wrong one failed with its verdict.
    xml = JUnitXml.fromfile(str(junit))
    suites = list(xml)
    assert len(suites) == 1 and suites[0].tests == 6 and suites[0].failures == 1
    results = {case.name: case.result for case in suites[0]}
    assert sorted(results) == sorted(SIGNALS)
    failure = results["theta[3]"]
    assert len(failure) == 1 and isinstance(failure[0], Failure)
    assert "theta[3]" in failure[0].message and f"t = {T_WRONG:g} s" in failure[0].message
    assert all(results[s] == [] for s in SIGNALS if s != "theta[3]")


def test_a_passing_run_removes_the_plots_of_an_earlier_failing_one(tmp_path):
    # Truth: wrong_case fails theta[3] only (its PNG is written); the unchanged path-1
    # reference passes every signal, so after it no plot of a signal of this case remains
    # in --out, while a file verify never writes stays.
    out = tmp_path / "out"
    out.mkdir()
    (out / "notes.png").write_bytes(b"the user's own file")
    wrong = verify(DIST / "Pss3Plant.fmu", wrong_case(tmp_path), "--out", out)
    assert wrong.code == 1 and (out / "theta_3.png").is_file(), wrong.err
    right = verify(DIST / "Pss3Plant.fmu", REFERENCES / "Pss3Plant" / "path1", "--out", out)
    assert right.code == 0, right.err
    assert sorted(p.name for p in out.iterdir()) == ["notes.png", "verify.json"]
    assert (out / "notes.png").read_bytes() == b"the user's own file"
    assert json.loads((out / "verify.json").read_text())["passed"] is True


def test_exit_codes_of_the_command(tmp_path):
    # The command as a process: 0 on the right reference, 1 on the wrong one.
    fmu = DIST / "Pss3Plant.fmu"
    right = verify_process(fmu, REFERENCES / "Pss3Plant" / "path1", "--out", tmp_path / "a")
    wrong = verify_process(fmu, wrong_case(tmp_path), "--out", tmp_path / "b")
    assert (right.code, wrong.code) == (0, 1), right.err + wrong.err
    assert "Traceback" not in right.err + wrong.err


def test_band_rule_from_the_command_line_rejects_a_halved_signal(tmp_path):
    # The cross-check example (test_cross_check.py): the planner with q[3] of the
    # reference doubled (so the result is half of it) is outside the 10 % band for most
    # samples; the other signals, under the same rule, pass.
    case = tmp_path / "defaults"
    shutil.copytree(REFERENCES / "Planner" / "defaults", case)
    (case / "case.json").unlink()
    reference = case / "Planner_ref.csv"
    data = np.genfromtxt(reference, delimiter=",", names=True, deletechars="")
    names = [n.strip('"') for n in data.dtype.names]
    data[data.dtype.names[names.index("q[3]")]] *= 2.0
    reference.write_text(",".join(f'"{n}"' for n in names) + "\n" + "\n".join(
        ",".join(repr(float(v)) for v in row) for row in data) + "\n")
    outcome = verify(DIST / "Planner.fmu", case, "--tolerance", "*=cross-check",
                     "--out", tmp_path / "out")
    assert outcome.code == 1
    assert [line.split(":")[0] for line in outcome.out.splitlines()
            if line.startswith("FAIL")] == ["FAIL q[3]"]
    assert "FMI cross-check band" in outcome.out


def test_a_run_the_fmu_refuses_is_a_failure_with_reports(tmp_path):
    # Truth: the PID refuses empty output limits (uMin >= uMax) when initialization ends
    # (fmus/pid); saturation's uMax[1] is 3. A verification that cannot run fails
    # (exit 1), and says so in JSON and as a JUnit error.
    out, junit = tmp_path / "out", tmp_path / "junit.xml"
    outcome = verify(DIST / "PID.fmu", REFERENCES / "PID" / "saturation", "--start", "uMin[1]=5",
                     "--out", out, "--junit", junit)
    assert outcome.code == 1
    assert outcome.err.strip().splitlines()[-1].startswith("cosim: ")
    assert "run failed" in outcome.err and "Traceback" not in outcome.err
    report = json.loads((out / "verify.json").read_text())
    assert report["passed"] is False and "fmi2ExitInitializationMode" in report["error"]
    assert report["signals"] == []
    suite, = list(JUnitXml.fromfile(str(junit)))
    assert (suite.tests, suite.errors) == (1, 1)
    case, = list(suite)
    assert isinstance(case.result[0], Error)


def test_reference_option_replaces_the_folders(tmp_path):
    # The folder's experiment, inputs and case file with the wrong reference given by
    # --reference: theta[3] fails where it was changed.
    wrong = wrong_case(tmp_path) / "Pss3Plant_ref.csv"
    outcome = verify(DIST / "Pss3Plant.fmu", REFERENCES / "Pss3Plant" / "path1",
                     "--reference", wrong, "--out", tmp_path / "out")
    assert outcome.code == 1
    assert [line.split(":")[0] for line in outcome.out.splitlines()
            if line.startswith("FAIL")] == ["FAIL theta[3]"]


def test_event_times_leave_out_the_instant_of_a_jump(tmp_path):
    # The planner's default move ends at tf = 2 s, where its acceleration jumps to 0;
    # a reference may hold either side there. Its qddot[1] at exactly 2 s set to the
    # other side's value (here 1.0 off) fails with no event declared (first exit 2 s),
    # and passes with event_times [2.0], where that one sample is not judged.
    case = tmp_path / "defaults"
    shutil.copytree(REFERENCES / "Planner" / "defaults", case)
    edit = case / "Planner_ref.csv"
    lines = edit.read_text().splitlines()
    column = lines[0].split(",").index('"qddot[1]"')
    for k, line in enumerate(lines[1:], start=1):
        fields = line.split(",")
        if float(fields[0]) == 2.0:
            fields[column] = repr(float(fields[column]) + 1.0)
            lines[k] = ",".join(fields)
    edit.write_text("\n".join(lines) + "\n")
    spec = json.loads((case / "case.json").read_text())
    results = {}
    for events in ([], [2.0]):
        spec["event_times"] = events
        (case / "case.json").write_text(json.dumps(spec))
        out = tmp_path / f"out{len(events)}"
        results[len(events)] = (verify(DIST / "Planner.fmu", case, "--out", out),
                                json.loads((out / "verify.json").read_text()))
    (bare, bare_report), (declared, declared_report) = results[0], results[1]
    assert bare.code == 1 and declared.code == 0
    wrong = {s["signal"]: s for s in bare_report["signals"]}["qddot[1]"]
    assert wrong["first_exit_time"] == 2.0 and wrong["samples_outside"] == 1
    # 0 to 2.5 s every 10 ms: 251 samples, one left out.
    assert [s["samples"] for s in bare_report["signals"]] == [251] * 9
    assert [s["samples"] for s in declared_report["signals"]] == [250] * 9


def test_a_refused_run_leaves_no_extracted_fmu(tmp_path, monkeypatch):
    # FMPy's simulate_fmu removes the folder it extracted only when the run succeeds.
    # Truth: the temporary folder (tempfile's, where fmpy.extract unpacks) is empty
    # after a run the PID refuses (uMin >= uMax, as above) and after one that passes.
    temp = tmp_path / "temp"
    temp.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(temp))
    refused = verify(DIST / "PID.fmu", REFERENCES / "PID" / "saturation", "--start",
                     "uMin[1]=5", "--out", tmp_path / "a")
    assert refused.code == 1 and list(temp.iterdir()) == []
    passed = verify(DIST / "PID.fmu", REFERENCES / "PID" / "saturation", "--out", tmp_path / "b")
    assert passed.code == 0 and list(temp.iterdir()) == []
