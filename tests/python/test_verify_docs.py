"""The commands of docs/verify.md run: its `sh` blocks from the repository root, and the
commands of its CI recipes (GitHub Actions `run:`, GitLab CI `script:`) against our PID
FMU, with the one change the document states: the install line (the release's wheel)
installs this checkout from its local sources (no download; the pinned environment has
the dependencies) into a scratch folder, from which the recipe's commands then import
the package."""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from junitparser import JUnitXml

from conftest import package_source
from verify_cli import ROOT, shell

DOC = ROOT / "docs" / "verify.md"
FENCE = re.compile(r"^```(\w*)[^\n]*\n(.*?)^```", re.S | re.M)  # "```text prints": text


def blocks(kind: str) -> list[str]:
    return [body for info, body in FENCE.findall(DOC.read_text()) if info == kind]


def recipe_commands(text: str) -> list[str]:
    """The shell lines of a GitHub Actions workflow or a GitLab CI file."""
    data = yaml.safe_load(text)
    if "jobs" in data:
        steps = [s for job in data["jobs"].values() for s in job["steps"]]
        return [line for s in steps if "run" in s for line in s["run"].splitlines() if line]
    return [line for job in data.values() if isinstance(job, dict) for line in job["script"]]


def bash(command: str, cwd: Path, env: dict) -> subprocess.CompletedProcess:
    return subprocess.run(["bash", "-c", shell(command)], cwd=cwd, env=env,
                          capture_output=True, text=True)


def test_sh_blocks_run():
    env = dict(os.environ, PATH=f"{ROOT / '.venv' / 'bin'}:{os.environ['PATH']}")
    commands = [line for body in blocks("sh") for line in body.splitlines() if line.strip()]
    # Three cases, then a cross-check tree of our FMUs laid out and verified whole (and
    # again with its results page), then an FMU's own experiments.
    assert len(commands) == 7 and commands[3].startswith("bash scripts/cross-check.sh")
    for k, command in enumerate(commands):
        done = bash(command, ROOT, env)
        assert done.returncode == 0, (command, done.stdout, done.stderr)
        if command.startswith("cosim verify"):
            assert "PASS" in done.stdout and "FAIL" not in done.stdout
        summary = done.stdout.splitlines()[-1]
        if k == 4:
            assert " 0 failed, 0 rejected, 0 skipped of " in summary, summary
        if k == 5:
            assert summary.endswith(", results/cross-check/index.html"), summary
        if k == 6:
            assert summary.startswith("dist/Pss3Plant.fmu: 2 of 2 experiments passed"), summary


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """This checkout's package installed from its local path into a scratch folder."""
    scratch = tmp_path_factory.mktemp("release")
    source = package_source(scratch / "source")
    site = scratch / "site"
    subprocess.run([sys.executable, "-m", "pip", "install", "--quiet", "--no-deps",
                    "--no-build-isolation", "--disable-pip-version-check", "--target",
                    str(site), str(source)], check=True, capture_output=True)
    return site


@pytest.mark.parametrize("index,ci", [(0, "GitHub Actions"), (1, "GitLab CI")])
def test_ci_recipe_commands_run_against_a_local_fmu(index, ci, installed, tmp_path):
    commands = recipe_commands(blocks("yaml")[index])
    install = [c for c in commands if "pip install" in c]
    assert len(install) == 1 and re.search(
        r"pip install https://\S+/releases/download/v[\d.]+/robofmu-[\d.]+-py3-none-any\.whl$",
        install[0]), (ci, install)
    checks = [c for c in commands if c not in install]
    assert checks and all(c.startswith("cosim verify ") for c in checks), ci
    # The user's repository: their FMU and references (ours, linked).
    for name in ("dist", "tests"):
        (tmp_path / name).symlink_to(ROOT / name)
    env = dict(os.environ, PYTHONPATH=str(installed),
               PATH=f"{installed / 'bin'}:{ROOT / '.venv' / 'bin'}:{os.environ['PATH']}")
    # The commands import the installed package, not the repository's.
    where = bash("python -c 'import robofmu.verify; print(robofmu.verify.__file__)'", tmp_path, env)
    assert Path(where.stdout.strip()).is_relative_to(installed), where
    for command in checks:
        done = bash(command, tmp_path, env)
        assert done.returncode == 0, (ci, command, done.stdout, done.stderr)
        assert "FAIL" not in done.stdout
    reports = sorted((tmp_path / "results" / "verify").glob("*/junit.xml"))
    assert len(reports) == len(checks)
    for report in reports:
        suite, = list(JUnitXml.fromfile(str(report)))
        assert suite.tests == 3 and suite.failures == 0
