"""cosim verify on bad input: exit 2, one line on stderr naming the file, the field or
column and the fix, no traceback, and nothing written (the --out folder is not made).
Each case is the path-1 case (tests/references/Pss3Plant/path1) with one mistake."""

import json
import shutil

import pytest

from conftest import DIST, REFERENCES
from verify_cli import verify, verify_process

REF, INPUT, CASE = "Pss3Plant_ref.csv", "Pss3Plant_input.csv", "case.json"
OPT = "Pss3Plant_ref.opt"


def edit_lines(path, change):
    lines = path.read_text().splitlines()
    path.write_text("\n".join(change(lines)) + "\n")


def edit_case(path, change):
    data = json.loads(path.read_text())
    change(data)
    path.write_text(json.dumps(data))


def swap_rows(lines):
    lines[3], lines[4] = lines[4], lines[3]
    return lines


def set_field(row, column, text):
    def change(lines):
        fields = lines[row].split(",")
        fields[column] = text
        lines[row] = ",".join(fields)
        return lines
    return change


def rename_column(old, new):
    return lambda lines: [lines[0].replace(f'"{old}"', f'"{new}"')] + lines[1:]


def drop_omega_3(data):
    for rules in data["tolerances"].values():
        del rules["omega[3]"]


def cut_after(seconds):
    return lambda lines: lines[:1] + [x for x in lines[1:] if float(x.split(",")[0]) <= seconds]


MISTAKES = {
    # name: (file, edit, words the message must contain); file: [(file, edit), ...]
    # where one mistake needs two edits
    "unsorted times": (REF, swap_rows, [REF, "line 5, column 'time'", "goes back", "sort"]),
    # A time written twice is an event (test_verify_conventions.py), not a mistake.
    "negative step": (OPT, lambda x: [("StepSize, -0.001" if line.startswith("StepSize") else line)
                                      for line in x], [OPT, "StepSize", "negative", "0 for a variable-step"]),
    "option given twice": (OPT, lambda x: x + ["RelTol, 1e-3"], [OPT, "RelTol", "given twice"]),
    "option without its value": (OPT, lambda x: [("StopTime," if line.startswith("StopTime") else line)
                                                 for line in x], [OPT, "StopTime", "missing"]),
    "reference ends early": (REF, cut_after(1.5), [REF, "column 'time'", "covers 0 to 1.5 s",
                                                   "experiment 0 to 2 s"]),
    "reference starts late": (REF, lambda x: x[:1] + x[3:], [REF, "covers 0.002 to 2 s"]),
    "unknown column": ([(REF, rename_column("omega[3]", "omega[4]")), (CASE, drop_omega_3)],
                       None, [REF, "column 'omega[4]'", "no such variable"]),
    "column missing for a tolerance": (
        CASE, lambda d: d["tolerances"]["CoSimulation"].update({"phi[1]": 1e-4}),
        [CASE, "tolerances.phi[1]", "no such column"]),
    "short row": (REF, set_field(7, slice(1, None), "1.0"), [REF, "line 8", "fields"]),
    "NaN": (REF, set_field(9, 2, "nan"), [REF, "line 10, column 'theta[2]'", "not finite"]),
    "not a number": (REF, set_field(9, 2, "2.x"), [REF, "line 10, column 'theta[2]'",
                                                     "not a number"]),
    "input that is an output": (INPUT, rename_column("actuatorForce[3]", "theta[1]"),
                                [INPUT, "column 'theta[1]'", "not an input", "actuatorForce"]),
    "input the FMU lacks": (INPUT, rename_column("actuatorForce[3]", "actuatorForce[4]"),
                            [INPUT, "column 'actuatorForce[4]'", "not an input"]),
    "unknown case key": (CASE, lambda d: d.update({"tolerance": {}}),
                         [CASE, "tolerance: unknown key", "start_values, event_times, tolerances"]),
    "bad tolerance": (CASE, lambda d: d["tolerances"]["ModelExchange"].update({"theta[1]": -1}),
                      [CASE, "tolerances.ModelExchange.theta[1]", "not negative"]),
    "unknown start value": (CASE, lambda d: d["start_values"].update({"theta1": 0.1}),
                            ["Pss3Plant.fmu", "start value 'theta1'", "no such variable"]),
    "no signal column": (REF, lambda x: [line.split(",")[0] for line in x],
                         [REF, "line 1", "no signal column"]),
    "first column not time": (REF, rename_column("time", "t"), [REF, "column 1 't'", "time"]),
}


def broken_case(tmp_path, name):
    case = tmp_path / "path1"
    shutil.copytree(REFERENCES / "Pss3Plant" / "path1", case)
    file, change, _ = MISTAKES[name]
    for file, change in (file if isinstance(file, list) else [(file, change)]):
        (edit_case if file == CASE else edit_lines)(case / file, change)
    return case


def assert_user_error(outcome, words, out):
    assert outcome.code == 2, (outcome.out, outcome.err)
    lines = outcome.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("cosim: "), outcome.err
    assert "; " in lines[0] and "Traceback" not in outcome.err
    for word in words:
        assert word in lines[0], (word, lines[0])
    assert outcome.out == ""
    assert not out.exists()


@pytest.mark.parametrize("name", sorted(MISTAKES))
def test_bad_case_is_refused_with_one_line(name, tmp_path):
    out = tmp_path / "out"
    outcome = verify(DIST / "Pss3Plant.fmu", broken_case(tmp_path, name), "--out", out,
                     "--junit", out / "junit.xml")
    print(outcome.err)
    assert_user_error(outcome, MISTAKES[name][2], out)


@pytest.mark.parametrize("args,words", [
    (["--tolerance", "theta[1]=tight"], ["--tolerance theta[1]", "ABS,REL"]),
    (["--tolerance", "psi=1e-3"], ["command line: --tolerance psi", "no such column"]),
    (["--start", "theta0[1]"], ["--start", "NAME=VALUE"]),
    (["--start", "nothing=1"], ["start value 'nothing'"]),
    (["--step", "0"], ["--step", "not positive"]),
    # A step longer than the experiment compared the start alone and passed; an infinite
    # one too; a tiny one ran without end (the path-1 experiment lasts 2 s).
    (["--step", "100"], ["command line: --step", "steps of the", "give a step from"]),
    (["--step", "inf"], ["command line: --step", "give a step from"]),
    (["--step", "1e-300"], ["command line: --step", "give a step from"]),
    (["--reference", "missing.csv"], ["missing.csv", "cannot be read"]),
])
def test_bad_option_is_refused_with_one_line(args, words, tmp_path):
    out = tmp_path / "out"
    outcome = verify(DIST / "Pss3Plant.fmu", REFERENCES / "Pss3Plant" / "path1", *args,
                     "--out", out)
    assert_user_error(outcome, words, out)


def test_missing_fmu_reference_and_options_file(tmp_path):
    out = tmp_path / "out"
    assert_user_error(verify(tmp_path / "X.fmu", REFERENCES / "PID" / "defaults", "--out", out),
                      ["X.fmu", "no such file"], out)
    case = tmp_path / "case"
    shutil.copytree(REFERENCES / "PID" / "defaults", case)
    (case / "PID_ref.opt").unlink()
    assert_user_error(verify(DIST / "PID.fmu", case, "--out", out), ["PID_ref.opt", "missing"],
                      out)
    (case / "PID_ref.csv").unlink()
    assert_user_error(verify(DIST / "PID.fmu", case, "--out", out),
                      ["<Model>_ref.csv", "no such files"], out)


def test_a_step_size_that_would_never_end_is_refused(tmp_path):
    # StepSize 1e-300 of a 2 s experiment: 2e300 steps, a run without end.
    out, case = tmp_path / "out", tmp_path / "case"
    shutil.copytree(REFERENCES / "PID" / "defaults", case)
    edit_lines(case / "PID_ref.opt", lambda lines: [
        "StepSize, 1e-300" if line.startswith("StepSize") else line for line in lines])
    assert_user_error(verify(DIST / "PID.fmu", case, "--out", out),
                      ["PID_ref.opt: StepSize", "give a step from"], out)


def test_bad_input_as_a_process_has_no_traceback(tmp_path):
    out = tmp_path / "out"
    outcome = verify_process(DIST / "Pss3Plant.fmu", broken_case(tmp_path, "NaN"), "--out", out)
    assert_user_error(outcome, [REF, "not finite"], out)


def test_outputs_are_written_all_or_nothing(tmp_path):
    # The JUnit file cannot be made (its folder is a file): the run was right, but the
    # report folder and its PNG/JSON must not appear half-made; exit 2 names the file.
    blocker = tmp_path / "file"
    blocker.write_text("not a folder\n")
    out = tmp_path / "out" / "nested"
    outcome = verify(DIST / "PID.fmu", REFERENCES / "PID" / "defaults", "--out", out,
                     "--junit", blocker / "junit.xml")
    assert outcome.code == 2 and "junit.xml" in outcome.err and "nothing was written" in outcome.err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]


def test_a_junit_path_that_is_a_folder_writes_nothing(tmp_path):
    # --junit names an existing folder: the rename over it would fail after verify.json
    # was renamed into place. Truth: nothing is written, no temporary file is left, and
    # the message names the user's path (not a temporary name).
    folder = tmp_path / "junit"
    folder.mkdir()
    out = tmp_path / "out"
    outcome = verify(DIST / "PID.fmu", REFERENCES / "PID" / "defaults", "--out", out,
                     "--junit", folder)
    assert outcome.code == 2, outcome.err
    assert f"cosim: {folder}: --out/--junit:" in outcome.err and "nothing was written" in outcome.err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["junit"]
    assert list(folder.iterdir()) == []


def test_a_tree_without_cases_and_a_tree_with_a_case_folder_are_refused(tmp_path):
    # A folder as FMU|TREE is a cross-check tree: one with no case is bad input, and a
    # tree gives each case its own files, so CASE (or --reference) with it is too.
    empty, out = tmp_path / "empty", tmp_path / "out"
    empty.mkdir()
    assert_user_error(verify(empty, "--out", out), [str(empty), "TREE", "holds no case",
                                                    "cross-check tree"], out)
    assert_user_error(verify(empty, REFERENCES / "PID" / "defaults", "--out", out),
                      ["command line: CASE/--reference/--input", "leave them out"], out)
    assert_user_error(verify(empty, "--jobs", "0", "--out", out), ["--jobs", "not positive"],
                      out)
