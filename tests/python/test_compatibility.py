"""The importers that scripts/compatibility.py adds to the compatibility folder besides
cosim verify: our master (robofmu.master.Master, the FMU with its inputs from a CSV
source) and the container runtime (the FMU alone in a container FMU of
fmu-manipulation-toolbox, run by FMPy), and libcosim's refusal of FMI 3.0. The PID and
the plant, per FMI version (the release runs every FMU: test_release.py); each verdict
in its own process, as at release.

Truths: the PID's reference is its closed-form response to its constant default inputs
(tests/references/PID/defaults, scripts/make_references.py), computed without running
the FMU; a copy of the case whose reference u[2] is shifted by 0.5 from t = 1 s must fail
in each importer (the FMI cross-check band around the reference is its running minimum
and maximum widened by 10 % of its range: u[2] ranges over 0.93 (1.5 to 0.57), so the
band reaches 0.093 beyond it, and the shifted half lies outside), so that a verdict is
not a constant. libcosim's refusal is its own error message ("Unsupported FMI
version"), for our FMU and for a third-party FMI 3.0 FMU: a container FMU written by
fmu-manipulation-toolbox (its modelDescription.xml and its binary are the toolbox's)."""

import csv
import re
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
sys.path.insert(0, str(ROOT))

import compatibility  # noqa: E402

REFUSED = "refused (Unsupported feature: Unsupported FMI version)"


@pytest.fixture(scope="module")
def folders(tmp_path_factory):
    """The PID's Co-Simulation folders: FMI 2.0 and FMI 3.0 (arrays)."""
    out = tmp_path_factory.mktemp("compatibility")
    laid = compatibility.lay_out(out, compatibility.version(), models=["PID", "Pss3Plant"])
    cs = {f"{f.parts[-1]} {f.parts[-6]}": f for f in laid
          if f.parts[-5] == "cs" and f.parts[-3] == "robofmu"}
    assert sorted(cs) == ["PID 2.0", "PID 3.0", "Pss3Plant 2.0", "Pss3Plant 3.0"]
    return {**cs, **{k.split()[1]: f for k, f in cs.items() if k.startswith("PID ")}}


@pytest.mark.parametrize("fmi_version", ["2.0", "3.0"])
def test_master_runs_the_plant_as_fmpy_does(folders, fmi_version):
    # Second importer: FMPy's simulate_fmu on the same FMU, inputs (the plant's
    # time-varying actuator forces of its defaults case) and grid; it sets the inputs
    # interpolated at each communication point and holds them over the step, as the
    # master is asked to. The plant's outputs are states (no feedthrough), so both record
    # the same values: equal to rounding (measured 1.3e-15).
    from fmpy import simulate_fmu

    case, rows = compatibility.master_run(folders[f"Pss3Plant {fmi_version}"])
    fmu = folders[f"Pss3Plant {fmi_version}"] / "Pss3Plant.fmu"
    inputs = case.inputs
    signals = np.zeros(len(inputs.time), dtype=[("time", float)] + [
        (name, float) for name in inputs.columns])
    signals["time"] = inputs.time
    for name, column in inputs.columns.items():
        signals[name] = column
    if fmi_version == "3.0":  # FMPy takes an FMI 3.0 array as one field
        from robofmu.verify.names import Names
        from fmpy import read_model_description
        signals = Names(read_model_description(str(fmu))).input_signals(
            inputs.time, inputs.columns)
    result = simulate_fmu(str(fmu), fmi_type="CoSimulation", start_time=case.start,
                          stop_time=case.stop, step_size=case.step,
                          output_interval=case.step, input=signals)
    assert rows.shape[0] == len(result) == 2001
    for j, signal in enumerate(case.signals(), 1):
        name, _, index = signal.partition("[")
        theirs = (result[signal] if fmi_version == "2.0"
                  else result[name][:, int(index[:-1]) - 1])
        assert np.max(np.abs(rows[:, j] - theirs)) < 1e-12, signal


@pytest.mark.parametrize("importer, folder", [
    ("master", "2.0"), ("master", "3.0"), ("container", "2.0"),
    ("container", "Pss3Plant 3.0")])  # the PID's FMI 3.0 arrays: the test below
def test_importer_passes(folders, importer, folder):
    assert compatibility.verdict_of(importer, folders[folder]) == "passed"


def test_the_container_refuses_the_pid_s_resizable_arrays(folders):
    # Expected: fmu-manipulation-toolbox 2.0's container builder refuses a port whose
    # size is a structural parameter (its embedded.py raises FMUError); the FMI 3.0 PID's
    # arrays are sized by nChannels (vr 90). The verdict carries the toolbox's reason.
    assert compatibility.verdict_of("container", folders["3.0"]) == (
        "refused (Port 'setpoint' depends on structuralParameter '90' which is not "
        "supported)")


@pytest.mark.parametrize("importer", ["master", "container"])
def test_importer_fails_an_edited_reference(folders, importer, tmp_path):
    case = tmp_path / "PID"
    shutil.copytree(folders["2.0"], case)
    reference = case / "PID_ref.csv"
    with reference.open() as f:
        rows = list(csv.reader(f))
    column = rows[0].index("u[2]")
    for row in rows[1:]:
        if float(row[0]) >= 1.0:
            row[column] = repr(float(row[column]) + 0.5)
    with reference.open("w", newline="") as f:
        csv.writer(f, quoting=csv.QUOTE_NONNUMERIC, lineterminator="\n").writerows(
            [rows[0]] + [[float(v) for v in row] for row in rows[1:]])
    assert compatibility.verdict_of(importer, case).startswith("failed")


def test_libcosim_runs_fmi2_and_refuses_fmi3_ours_and_a_third_party_one(folders, tmp_path):
    from fmu_manipulation_toolbox.container import FMUContainer

    assert compatibility.verdict_of("libcosim", folders["2.0"]) == "passed"
    assert compatibility.verdict_of("libcosim", folders["3.0"]) == REFUSED
    # The toolbox's FMI 3.0 container of the FMI 2.0 PID, in a copy of the case.
    work = tmp_path / "work"
    work.mkdir()
    shutil.copy(folders["2.0"] / "PID.fmu", work / "PID.fmu")
    container = FMUContainer("PID_container", work, fmi_version=3)
    container.get_fmu("PID.fmu")
    container.add_output("PID.fmu", "u[1]", "u1")
    container.add_implicit_rule(auto_input=False, auto_output=False, auto_link=False)
    container.make_fmu("container.fmu", step_size=1e-3)
    case = tmp_path / "PID"
    shutil.copytree(folders["3.0"], case)
    shutil.copy(work / "container.fmu", case / "PID.fmu")
    assert compatibility.verdict_of("libcosim", case) == REFUSED


def test_fmi3_array_csvs_name_the_variables_and_read_as_the_case(folders):
    # The guide's CSV rules: "All variable names are exactly the same as defined in the
    # modelDescription.xml" and arrays "serialized as for start values ... with space (` `)
    # as separator". Truth: FMPy's reading of the FMU's variables, and the case's own
    # files (one column per element), read by the same reader.
    from fmpy import read_model_description

    from robofmu.verify.table import read_table

    case = ROOT / "tests" / "references" / "PID" / "defaults"
    folder = folders["3.0"]
    variables = {v.name: v for v in read_model_description(str(folder / "PID.fmu")).modelVariables}
    for written, original in (("PID_ref.csv", "PID_ref.csv"), ("PID_in.csv", "PID_input.csv")):
        header = (folder / written).read_text().splitlines()[0].split(",")
        names = [name.strip('"') for name in header[1:]]
        assert names and all(variables[n].dimensions for n in names), names
        ours, theirs = read_table(folder / written), read_table(case / original)
        assert (ours.time == theirs.time).all()
        assert sorted(ours.columns) == sorted(theirs.columns)
        assert all((ours.columns[n] == theirs.columns[n]).all() for n in theirs.columns)


@pytest.mark.parametrize("text, said", [
    ('"time","u"\n0,1 2 3\n1,4 5\n', "line 3, column 'u': has 2 elements, the column's first row 3"),
    ('"time","u","u[1]"\n0,1 2,3\n1,4 5,6\n', "line 1: names an array's element twice"),
    ('"time","u"\n0 1,1\n1,2\n', "line 2, column 'time': holds more than one number"),
])
def test_a_broken_array_column_is_one_line(text, said):
    from robofmu.verify.errors import VerifyError
    from robofmu.verify.table import read_table

    with pytest.raises(VerifyError, match=re.escape(said)):
        read_table(Path("x.csv"), text)


def test_the_results_page_shows_each_importers_verdict(folders):
    # The page of the compatibility folder (compatibility.results_page, the one
    # scripts/compatibility.py writes) with libcosim's and ecos's verdicts on the PID, run
    # here: its matrix, read by Python's HTML parser, must show them in their importers'
    # columns with their versions (libcosim's refusal of FMI 3.0 with its reason), beside
    # cosim's verdict, and every link must resolve. Truth: the verdicts the importers
    # returned (as Readme.txt records them).
    from importlib.metadata import version

    from page_matrix import matrix, unresolved

    out = folders["2.0"].parents[6]
    tool = compatibility.version()
    others = [(folders[v], "libcosim", compatibility.verdict_of("libcosim", folders[v]))
              for v in ("2.0", "3.0")]
    others.append((folders["2.0"], "ecos", compatibility.verdict_of("ecos", folders["2.0"])))
    assert [said for _, _, said in others] == ["passed", REFUSED, "passed"]
    cosim = {"/".join(folders[v].parts[-6:]): "passed" for v in ("2.0", "3.0")}
    page = out / "index.html"
    page.write_bytes(compatibility.results_page(out, tool, cosim, {}, others))
    rows = matrix(page)
    libcosim = f"libcosim (libcosimpy {version('libcosimpy')})"
    ecos = f"ecos (ecospy {version('ecospy')})"
    fmi2 = rows[f"PID.fmu (FMI 2.0, robofmu {tool}), linux64"]
    fmi3 = rows[f"PID.fmu (FMI 3.0, robofmu {tool}), x86_64-linux"]
    assert fmi2[libcosim] == "cs passed" and fmi2[ecos] == "cs passed"
    assert fmi3[libcosim] == f"cs {REFUSED}" and fmi3[ecos] == ""
    assert fmi2[f"cosim {tool} (FMPy {version('fmpy')})"] == "cs passed\nme not run"
    assert unresolved(page) == []
