"""cosim verify reads the FMI cross-check files as the cross-check rules write them
(FMI-CROSS-CHECK-RULES.md of modelica/fmi-cross-check; docs/verify.md quotes them):
each convention as a small case, on our PID FMU's defaults case (tests/references/PID/
defaults, the reference from the PID's closed form) or on hand-written signals.

Truths: the rules' text (what each file may hold); FMPy 0.3.32's own readers and its
cross-check band (fmpy.util.read_ref_opt_file, fmpy.cross_check.validate_signal) on the
same data; closed-form signals with a jump for the events."""

import json
import shutil

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.util import read_ref_opt_file

from conftest import DIST, REFERENCES
from verify_cli import verify

from robofmu.verify import compare
from robofmu.verify.case import Case
from robofmu.verify.simulate import Run
from robofmu.verify.table import Table, read_options, read_table
from robofmu.verify.tolerance import CrossCheckBand, Deviation

PID = DIST / "PID.fmu"
# FMPy 0.3.32 imports its band filters from scipy.ndimage.filters, deprecated in SciPy 1.17.
pytestmark = pytest.mark.filterwarnings(
    "ignore:Please import .* from the `scipy.ndimage` namespace:DeprecationWarning")


def pid_case(tmp_path, opt_lines=None):
    case = tmp_path / "PID"
    shutil.copytree(REFERENCES / "PID" / "defaults", case)
    if opt_lines is not None:
        (case / "PID_ref.opt").write_text("\n".join(opt_lines) + "\n")
    return case


def test_every_option_key_of_the_rules_with_their_comments(tmp_path):
    # The rules' own _ref.opt example, keys and "// ..." comments as written there (the
    # OutputIntervalLength line of the 4.1 rules has no value), with the PID's numbers.
    lines = ["// required elements:", "StartTime, 0.0         // in seconds",
             "StopTime, 2.0          // in seconds",
             "StepSize, 0.01         // in seconds, 0.0 means variable step solver",
             "RelTol, 1e-8", "// optional elements:", "AbsTol, 2",
             "SolverType, FixedStep  // see implementation notes for a list of predefined types",
             "OutputIntervalLength   // reference data provided with this time spacing in seconds",
             "StopTimeDefined, 1", "", "Tolerance, 1e-3"]
    case = pid_case(tmp_path, lines)
    options = read_options(case / "PID_ref.opt")
    assert (options.start, options.stop, options.step, options.rel_tol) == (0.0, 2.0, 0.01, 1e-8)
    assert (options.abs_tol, options.solver_type, options.output_interval) == (2.0, "FixedStep", None)
    assert options.stop_time_defined and options.ignored == ["Tolerance"]
    out = tmp_path / "out"
    outcome = verify(PID, case, "--out", out)
    assert outcome.code == 0, outcome.out + outcome.err
    experiment = outcome.report(out)["experiment"]
    assert experiment["absolute_tolerance"] == 2.0 and experiment["ignored_options"] == ["Tolerance"]
    assert experiment["solver_type"] == "FixedStep" and experiment["stop_time_defined"] is True


def test_step_size_zero_is_a_variable_step_run_with_fmpys_output_points(tmp_path):
    # "StepSize, 0.01 // in seconds, 0.0 means variable step solver" (the rules). The
    # output points are FMPy's choice (simulate_fmu without step or output interval):
    # for Co-Simulation the FMU's defaultExperiment stepSize, doubled until at most 1000
    # intervals fill the experiment.
    case = pid_case(tmp_path, ["StartTime, 0", "StopTime, 2", "StepSize, 0", "RelTol, 1e-8"])
    out = tmp_path / "out"
    outcome = verify(PID, case, "--out", out, "--junit", out / "junit.xml")
    assert outcome.code == 0, outcome.out + outcome.err
    report = outcome.report(out)
    assert report["experiment"]["variable_step"] is True
    step = float(read_model_description(str(PID)).defaultExperiment.stepSize)
    while 2.0 / step > 1000:
        step *= 2
    assert report["signals"][0]["samples"] == round(2.0 / step) + 1
    # FMPy's own reader takes the same file (StepSize 0 is allowed there too).
    assert read_ref_opt_file(str(case / "PID_ref.opt"))["StepSize"] == 0


def test_output_interval_length_sets_the_points_of_a_variable_step_run(tmp_path):
    case = pid_case(tmp_path, ["StartTime, 0", "StopTime, 2", "StepSize, 0", "RelTol, 1e-8",
                               "OutputIntervalLength, 0.02"])
    out = tmp_path / "out"
    outcome = verify(PID, case, "--out", out)
    assert outcome.code == 0, outcome.out + outcome.err
    assert outcome.report(out)["signals"][0]["samples"] == 101  # 2 s / 0.02 s + 1


@pytest.mark.parametrize("header", [
    '"time","u[1]","u[2]","u[3]"',              # the rules: names in double quotes
    'time,u[1],u[2],u[3]',                      # unquoted (FMPy writes and reads both)
    '"time" ,"u[1]" ,"u[2]" ,"u[3]" ',          # a space after each quoted name
    ' "time", "u[1]", "u[2]", "u[3]"',          # a space before each
    '\ufeff"Time","u[1]","u[2]","u[3]"',        # a byte-order mark, Time capitalized
])
def test_header_variants_exporters_write(header, tmp_path):
    case = pid_case(tmp_path)
    reference = case / "PID_ref.csv"
    lines = reference.read_text().splitlines()
    reference.write_text("\n".join([header] + lines[1:]) + "\n", encoding="utf-8")
    table = read_table(reference)
    assert list(table.columns) == ["u[1]", "u[2]", "u[3]"]
    out = tmp_path / "out"
    outcome = verify(PID, case, "--out", out)
    assert outcome.code == 0, outcome.out + outcome.err


def jump_reference(tmp_path):
    """y = t before t = 1 s, t + 1 from it on: written as the rules write an event, the
    time 1 on two rows (the value before, then after)."""
    path = tmp_path / "jump_ref.csv"
    rows = ["time,y"] + [f"{t:g},{t:g}" for t in np.arange(0, 1.0, 0.1)]
    rows += ["1,1", "1,2"] + [f"{t:g},{t + 1:g}" for t in np.arange(1.1, 2.05, 0.1)]
    path.write_text("\n".join(rows) + "\n")
    return read_table(path)


def judge(reference: Table, t, y, rule):
    case = Case("jump", reference, None, 0.0, 2.0, 0.1, 1e-6, rules={None: {"y": rule}})
    verdicts, end = compare.judge_all(case, Run(np.asarray(t, float), {"y": np.asarray(y, float)}),
                                      "CoSimulation")
    assert end is None
    return verdicts[0]


def test_a_repeated_time_is_an_event_judged_on_both_sides(tmp_path):
    reference = jump_reference(tmp_path)
    assert reference.event_times() == [1.0]
    exact = Deviation(1e-9)
    grid = np.linspace(0, 2, 21)
    truth = lambda t: t + (t >= 1)  # noqa: E731
    # An importer that records the event: two samples at 1 s, before and after.
    t2 = np.sort(np.concatenate([grid, [1.0]]))
    y2 = truth(t2)
    y2[np.argmax(t2 == 1.0)] = 1.0  # the first sample at 1 s: the value before the jump
    assert judge(reference, t2, y2, exact).passed
    # The two samples swapped (after first, then before) are wrong on both.
    swapped = y2.copy()
    k = int(np.argmax(t2 == 1.0))
    swapped[k], swapped[k + 1] = swapped[k + 1], swapped[k]
    verdict = judge(reference, t2, swapped, exact)
    assert not verdict.passed and verdict.outside == 2 and verdict.first_exit == 1.0
    # One sample at 1 s: before or after the jump are both right, between is not.
    for value, ok in ((1.0, True), (2.0, True), (1.5, False)):
        y1 = truth(grid)
        y1[10] = value
        verdict = judge(reference, grid, y1, exact)
        assert verdict.passed == ok and verdict.max_error == pytest.approx(0.0 if ok else 0.5)


def test_the_band_at_an_event_against_fmpys(tmp_path):
    # FMPy's validate_signal on the same event reference keeps the first of the repeated
    # rows, so it reads the jump as a ramp from (1, 1) to (1.1, 2.1): the true result
    # (2 at 1 s, 2.01 at 1.01 s, ...) then lies above its band for a few samples from the event on.
    # cosim verify reads the jump as a jump. Elsewhere both find the same outliers: a
    # result 0.4 above the truth from 1.5 s on (the band is 10 % of the range 3, 0.3).
    from fmpy.cross_check import validate_signal
    reference = jump_reference(tmp_path)
    t = np.linspace(0, 2, 201)
    y = t + (t >= 1) + 0.4 * (t >= 1.5)
    _, _, _, fmpy_outside = validate_signal(t, y, reference.time, reference.columns["y"], 0.0, 2.0)
    verdict = judge(reference, t, y, CrossCheckBand())
    after_event = (t >= 1.0) & (t < 1.1)
    assert fmpy_outside[after_event].sum() == 5 and not verdict.outside_mask[after_event].any()
    assert (verdict.outside_mask[~after_event] == fmpy_outside[~after_event]).all()
    assert verdict.outside == 51  # 1.5 s to 2 s every 0.01 s
    assert not verdict.passed  # 51 of 201 samples outside: more than 10 %


def pid_u(t, e):
    """The PID's defaults (Kp 1, Ki 0.5, Kd 0.1, Tf 0.05) on a constant error e from a
    zero state, by Laplace inversion (as scripts/make_references.py writes the PID cases):
    u = Kp e + Ki e t + Kd e / Tf exp(-t / Tf)."""
    return 1.0 * e + 0.5 * e * t + 0.1 * e / 0.05 * np.exp(-t / 0.05)


def write_pid_reference(case, t_jump):
    """The closed form of the three channels every 0.01 s, u[1] with 0.5 added from
    t_jump on, the time t_jump on two rows (before and after the jump)."""
    t = np.round(np.arange(0, 201) * 0.01, 12)
    before, after = t[t <= t_jump], t[t > t_jump]
    rows = [(ti, 0.0) for ti in before] + [(t_jump, 0.5)] + [(ti, 0.5) for ti in after]
    lines = ['"time","u[1]","u[2]","u[3]"'] + [
        ",".join(repr(float(x)) for x in (ti, pid_u(ti, 1.0) + ff, pid_u(ti, 0.5),
                                          pid_u(ti, -0.25)))
        for ti, ff in rows]
    (case / "PID_ref.csv").write_text("\n".join(lines) + "\n")


def feedforward_step_case(tmp_path):
    """The PID's defaults with feedforward[1] stepping from 0 to 0.5 at 1 s, written as
    the rules write an event: time 1 on two rows, in the input and in the reference
    (the feedforward adds to u[1] directly: u[1] = pid_u + feedforward)."""
    case = pid_case(tmp_path)
    inputs = case / "PID_input.csv"
    header, first, last = inputs.read_text().splitlines()
    column = header.split(",").index('"feedforward[1]"')

    def row(time, feedforward, line):
        fields = line.split(",")
        fields[0], fields[column] = repr(time), repr(feedforward)
        return ",".join(fields)
    inputs.write_text("\n".join([header, row(0.0, 0.0, first), row(1.0, 0.0, first),
                                 row(1.0, 0.5, last), row(2.0, 0.5, last)]) + "\n")
    write_pid_reference(case, 1.0)
    return case


@pytest.mark.parametrize("interface", ["cs", "me"])
def test_an_input_event_applies_its_value_after_the_event(interface, tmp_path):
    # The rules' CSV example writes an input step as a repeated time; the value after
    # the event applies from the event on (FMPy: Input.findEvents, apply(after_event)).
    # Within the case's tolerances (Co-Simulation 1e-9, exact but for round-off; Model
    # Exchange 1e-5, CVode at RelTol 1e-8) of the closed form with the jump at 1 s.
    case = feedforward_step_case(tmp_path)
    assert read_table(case / "PID_input.csv").event_times() == [1.0]
    assert read_table(case / "PID_ref.csv").event_times() == [1.0]
    outcome = verify(PID, case, "--interface", interface, "--out", tmp_path / "out")
    print(outcome.out)
    assert outcome.code == 0, outcome.out + outcome.err
    # Not trivially passing: against a reference whose jump comes one output step
    # early (0.99 s) the result fails u[1] at 1 s by the jump's 0.5.
    write_pid_reference(case, 0.99)
    early = verify(PID, case, "--interface", interface, "--out", tmp_path / "early")
    failing = [line for line in early.out.splitlines() if line.startswith("FAIL")]
    assert early.code == 1 and len(failing) == 1, early.out
    assert failing[0].startswith("FAIL u[1]: max |error| 0.5 at t = 1 s")


def test_an_fmu_that_ends_the_run_early(tmp_path, monkeypatch):
    # The FMU's run stops at 1 s of the 2 s experiment (as Reference-FMUs' Stair asks to
    # terminate at 9 s of 10): every signal judged up to 1 s, a FAIL line saying so with
    # the FMU's last log message, every signal plotted, JUnit's "run" test case failed;
    # --allow-early-end passes it.
    from robofmu.verify import runner
    real = runner.simulate

    def ends_at_one_second(*args):
        run = real(*args)
        keep = run.time <= 1.0 + 1e-12
        return Run(run.time[keep], {k: v[keep] for k, v in run.series.items()},
                   ["[OK] counter reached its limit, terminating"])
    monkeypatch.setattr(runner, "simulate", ends_at_one_second)
    case, out = pid_case(tmp_path), tmp_path / "out"
    outcome = verify(PID, case, "--out", out, "--junit", out / "junit.xml")
    print(outcome.out)
    assert outcome.code == 1
    end_line = [line for line in outcome.out.splitlines() if line.startswith("FAIL run:")]
    assert end_line == ["FAIL run: the FMU ended the run at t = 1 s, before StopTime 2 s: "
                        "[OK] counter reached its limit, terminating; the signals are judged "
                        "up to 1 s (--allow-early-end accepts this)"]
    assert sum(line.startswith("PASS u[") for line in outcome.out.splitlines()) == 3
    report = outcome.report(out)
    assert report["passed"] is False and report["ended_early"]["time"] == 1.0
    assert all(s["samples"] == 101 for s in report["signals"])  # 0 to 1 s every 0.01 s
    assert sorted(p.name for p in out.glob("*.png")) == ["u_1.png", "u_2.png", "u_3.png"]
    from junitparser import Failure, JUnitXml
    suite, = list(JUnitXml.fromfile(str(out / "junit.xml")))
    results = {c.name: c.result for c in suite}
    assert isinstance(results["run"][0], Failure) and results["u[1]"] == []
    allowed = verify(PID, case, "--out", tmp_path / "allowed", "--allow-early-end")
    assert allowed.code == 0 and "ENDED run:" in allowed.out
    assert json.loads((tmp_path / "allowed" / "verify.json").read_text())["passed"] is True
