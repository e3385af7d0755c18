"""Hostile inputs to `cosim run/check/ssp/container/bench` (corpus: hostile_cases.py):
every one is answered with exit code 2 (1 where the run itself fails), one line
`cosim: ...` naming the file and the field (or the argument), no traceback, nothing
written outside --out, and no FMU instance folder left in the temp directory. The cases
run in this process through robofmu.cli.main (the console script's function); a few run
as subprocesses to see the real exit status. About 40 s."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from robofmu.cli import main  # noqa: E402
from hostile_cases import DIST, DOCUMENTS, RAW, ROOT, base, edit  # noqa: E402


def _tree(folder: Path) -> set[str]:
    return {str(p.relative_to(folder)) for p in folder.rglob("*")}


@pytest.fixture
def sandbox(tmp_path, monkeypatch):
    """cwd = a fresh folder; the temp directory private to the test (FMU extraction
    folders are counted there); returns a function that runs the command line and
    checks the common promises."""
    work, temp = tmp_path / "work", tmp_path / "temp"
    work.mkdir()
    temp.mkdir()
    monkeypatch.chdir(work)
    monkeypatch.setattr(tempfile, "tempdir", str(temp))

    def run(argv, capsys, code, text, names=()):
        before = _tree(work)
        got = main([str(a) for a in argv])
        out, err = capsys.readouterr()
        assert got == code, (got, err)
        lines = err.splitlines()
        if code == 0:
            assert err == "", err
        else:
            assert len(lines) == 1 and lines[0].startswith("cosim: "), err
            assert text in err, err
            for name in names:
                assert name in err, err
        assert "Traceback" not in err + out and "internal error" not in err, err
        new = _tree(work) - before
        assert all(p == "out" or p.startswith("out/") for p in new), new
        assert not list(temp.iterdir()), list(temp.iterdir())  # extracted FMUs removed
        return out, err

    run.work = work
    return run


@pytest.mark.parametrize("label, document, code, text", DOCUMENTS,
                         ids=[c[0] for c in DOCUMENTS])
def test_malformed_scenarios_are_refused_by_field(sandbox, capsys, label, document, code,
                                                  text):
    path = sandbox.work / "h.json"
    path.write_text(json.dumps(document))
    commands = [["check", path], ["run", path, "--out", "out", "--quiet"],
                ["ssp", path, "--out", "out/h.ssp"]]
    if DOCUMENTS.index((label, document, code, text)) % 4 == 0:  # the toolbox is slow
        commands.append(["container", path, "--out", "out/h.fmu"])
    for argv in commands:
        sandbox(argv, capsys, code, text, names=["h.json"])


@pytest.mark.parametrize("label, data, suffix, code, text", RAW, ids=[c[0] for c in RAW])
def test_malformed_files_are_refused(sandbox, capsys, label, data, suffix, code, text):
    path = sandbox.work / f"h{suffix}"
    path.write_bytes(data)
    sandbox(["run", path, "--out", "out", "--quiet"], capsys, code, text, names=[path.name])


# A scenario that `--expanded` must not overwrite (its content checked afterwards).
SELF_TOML = "# the scenario itself\n"


def _arguments(work: Path) -> list[tuple]:
    good = work / "good.json"
    good.write_text(json.dumps(base()))
    (work / "file.txt").write_text("x")
    (work / "d.toml").mkdir()
    (work / "empty").mkdir()
    (work / "fmi2").mkdir()
    os.mkfifo(work / "fifo.toml")  # reading it would block forever
    (work / "loop.toml").symlink_to(work / "loop.toml")
    (work / "self.toml").write_text(SELF_TOML)
    for model in ("Planner", "PID", "Pss3Plant"):
        shutil.copy(DIST / f"{model}.fmu", work / "fmi2")
    waypoints = ROOT / "scenarios" / "three_axis_waypoints.toml"
    return [
        ("missing scenario", ["run", work / "no.toml"], 2, "does not exist"),
        ("scenario is a directory", ["run", work / "d.toml"], 2, "not a file"),
        ("--out is a file", ["run", good, "--out", work / "file.txt"], 2, "--out"),
        ("--fmu-dir missing", ["run", good, "--fmu-dir", work / "nodir"], 2, "--fmu-dir"),
        ("--fmu-dir without FMUs", ["check", good, "--fmu-dir", work / "empty"], 2,
         "'fmus.planner'"),
        ("--fmu-dir a file", ["check", good, "--fmu-dir", work / "file.txt"], 2, "--fmu-dir"),
        ("unknown option", ["run", good, "--bogus"], 2, "--bogus"),
        ("no command", [], 2, "required"),
        ("unknown command", ["frobnicate"], 2, "frobnicate"),
        ("ssp --out not .ssp", ["ssp", good, "--out", "out/x.txt"], 2, "--out"),
        ("ssp of a multi-segment motion", ["ssp", waypoints, "--out", "out/x.ssp"], 2,
         "'motion.waypoints'"),
        ("ssp of a plain multi-segment motion",
         ["ssp", ROOT / "tests" / "scenarios" / "expanded" / "three_axis_waypoints.toml",
          "--out", "out/x.ssp"], 2, "'plan_switches'"),
        ("container of a plain multi-segment motion",
         ["container", ROOT / "tests" / "scenarios" / "expanded" / "three_axis_waypoints.toml",
          "--out", "out/x.fmu"], 2, "'plan_switches'"),
        ("container --out a directory", ["container", good, "--out", work / "empty"], 2,
         "--out"),
        ("container without --out", ["container", good], 2, "--out"),
        ("bench --runs -1", ["bench", "--runs", "-1"], 2, "--runs"),
        ("bench --runs abc", ["bench", "--runs", "abc"], 2, "--runs"),
        ("run without scenario", ["run"], 2, "scenario"),
        ("scenario is a FIFO", ["run", work / "fifo.toml"], 2, "not a file"),
        ("scenario is a symlink loop", ["check", work / "loop.toml"], 2, "loop.toml"),
        ("--debug twice and a subcommand typo", ["--debug", "rnu", "x.toml"], 2, "rnu"),
        # An empty or blank --out would be Path('.'): the results beside the user's
        # files (issue 36); refused by every command that writes, before anything runs.
        *[(f"{command} --out {blank!r}", [command, target, "--out", blank], 2,
           "names nothing")
          for command, target in [("run", good), ("ssp", good), ("container", good),
                                  ("sweep", work / "spec.toml"), ("verify", work / "x.fmu"),
                                  ("animate", work / "x.csv")]
          for blank in ("", " ")],
        ("check --expanded ''", ["check", good, "--expanded", ""], 2, "names nothing"),
        ("verify --junit ''", ["verify", work / "x.fmu", "--junit", ""], 2, "names nothing"),
        ("check --expanded its own scenario",
         ["check", work / "self.toml", "--expanded", work / "." / "self.toml"], 2,
         "is the scenario being checked"),
        ("check --expanded its own scenario through a link",
         ["check", work / "self.toml", "--expanded", work / "link.toml"], 2,
         "is the scenario being checked"),
        ("--fmi3 without the FMI 3.0 builds", ["run", good, "--fmi3", "--fmu-dir", work / "fmi2"],
         2, "--fmi3"),
    ]


def test_hostile_arguments(sandbox, capsys):
    cases = _arguments(sandbox.work)
    (sandbox.work / "link.toml").symlink_to(sandbox.work / "self.toml")
    for label, argv, code, text in cases:
        sandbox(argv, capsys, code, text)
    # `check S --expanded S` refused: the scenario is as it was.
    assert (sandbox.work / "self.toml").read_text() == SELF_TOML
    assert len(cases) + len(DOCUMENTS) + len(RAW) >= 120


def test_a_valid_run_writes_only_under_out(sandbox, capsys):
    path = sandbox.work / "good.json"
    path.write_text(json.dumps(base()))
    out, _ = sandbox(["check", path], capsys, 0, "")
    assert "ok" in out
    sandbox(["run", path, "--out", "out", "--quiet"], capsys, 0, "")
    assert sorted(_tree(sandbox.work / "out")) == [
        "h.csv", "h.units.json", "h_error_forces.png", "h_orientation.png", "h_summary.json"]


def test_a_plant_without_model_exchange_is_a_user_error(sandbox, capsys):
    """The gain design 'gains.omega' evaluates the plant in Model Exchange: a plant FMU
    that declares only Co-Simulation (here dist/Pss3Plant.fmu with the <ModelExchange>
    element cut from its modelDescription.xml) is refused naming the slot and the fix."""
    plant = sandbox.work / "CsOnly.fmu"
    with zipfile.ZipFile(DIST / "Pss3Plant.fmu") as src, zipfile.ZipFile(plant, "w") as dst:
        for item in src.infolist():
            data = src.read(item)
            if item.filename == "modelDescription.xml":
                data = re.sub(rb"<ModelExchange\b.*?(/>|</ModelExchange>)", b"", data,
                              flags=re.S)
                assert b"<ModelExchange" not in data and b"<CoSimulation" in data
            dst.writestr(item, data)
    path = sandbox.work / "cs.json"
    path.write_text(json.dumps(edit(base(), "fmus/plant", str(plant))))
    sandbox(["check", path], capsys, 2, "'fmus.plant'",
            names=["CsOnly.fmu", "Model Exchange", "gains.Kp"])


def test_an_exceeded_limit_is_exit_1_with_the_results_written(sandbox, capsys):
    path = sandbox.work / "limit.json"
    path.write_text(json.dumps(edit(base(), "limits", {"max_force": "1e-9 N"})))
    out, err = sandbox(["run", path, "--out", "out", "--quiet"], capsys, 1, "'limits'",
                       names=["limit.json"])
    assert "EXCEEDED" in out
    summary = json.loads((sandbox.work / "out" / "h_summary.json").read_text())
    assert summary["passed"] is False and summary["limits"][0]["limit"] == "max_force"


def test_the_process_exit_status_and_debug_traceback(tmp_path):
    """The real process: `python -m robofmu` from another directory."""
    bad = tmp_path / "bad.toml"
    bad.write_bytes(b"\xff\xfe")
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    run = subprocess.run([sys.executable, "-m", "robofmu", "run", str(bad)], cwd=tmp_path,
                         env=env, capture_output=True, text=True)
    assert run.returncode == 2 and run.stderr.count("\n") == 1 and "UTF-8" in run.stderr
    debug = subprocess.run([sys.executable, "-m", "robofmu", "--debug", "run", str(bad)],
                           cwd=tmp_path, env=env, capture_output=True, text=True)
    assert debug.returncode == 2 and "Traceback" in debug.stderr
    assert shutil.which("true")  # (the environment ran a process at all)
