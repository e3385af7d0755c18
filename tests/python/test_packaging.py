"""The harness as an installed package: `pip install` of pyproject.toml (from a copy of
the sources, without touching the working tree), the `cosim` console command, and the
FMUs found by their bundled names, from the scenario's folder or from --fmu-dir. About 10 s.
scripts/test-wheel.sh installs the built wheel into a fresh venv, as a user does."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

from conftest import package_source

from robofmu.loop import library_path

ROOT = Path(__file__).resolve().parents[2]


def test_installed_console_command_runs_a_scenario_anywhere(tmp_path):
    source = package_source(tmp_path / "src")
    prefix = tmp_path / "prefix"
    # --no-deps --no-build-isolation: the dependencies are this venv's (no download).
    # --ignore-installed: pip would otherwise first uninstall the editable install of
    # this venv (scripts/setup-venv.sh), the same distribution.
    subprocess.run([sys.executable, "-m", "pip", "install", "--quiet", "--no-deps",
                    "--ignore-installed",
                    "--no-build-isolation", "--disable-pip-version-check", "--prefix",
                    str(prefix), str(source)], check=True, capture_output=True)
    command = prefix / "bin" / "cosim"
    site = next(prefix.glob("lib/python*/site-packages"))
    # The master's stepping loop is this checkout's build, as the FMUs are (the
    # package ships no binaries).
    env = {"PYTHONPATH": str(site), "PATH": "/usr/bin:/bin",
           "COSIM_KERNEL_LIBRARY": str(library_path())}
    work = tmp_path / "elsewhere"
    work.mkdir()
    # A scenario away from the repository: FMUs by file name from --fmu-dir ...
    shutil.copy(ROOT / "scenarios" / "regulation.toml", work / "regulation.toml")
    run = subprocess.run([str(command), "run", "regulation.toml", "--out", "out", "--quiet",
                          "--fmu-dir", str(ROOT / "dist")], cwd=work, env=env,
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "1000 steps" in run.stdout and (work / "out" / "regulation.csv").exists()
    # ... and relative to the scenario's own folder (scenarios/../dist) by default.
    run = subprocess.run([str(command), "run", str(ROOT / "scenarios" / "regulation.toml"),
                          "--out", "out2", "--quiet"], cwd=work, env=env,
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    imported = subprocess.run([str(Path(sys.executable)), "-c",
                               "import robofmu, sys; print(robofmu.__file__)"], cwd=work,
                              env=env, capture_output=True, text=True)
    assert imported.stdout.startswith(str(site)), imported.stdout
    # A copied scenario naming the bundled FMUs (plant = "Pss3Plant") finds them in the
    # installed package (robofmu/data/fmus) ...
    run = subprocess.run([str(command), "run", "regulation.toml", "--out", "out3", "--quiet"],
                         cwd=work, env=env, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "1000 steps" in run.stdout and (work / "out3" / "regulation.csv").exists()
    # ... but one naming files by path, ../dist/Planner.fmu, finds no ../dist (and an
    # installed copy has no repository dist/): a user error naming the field, the file
    # and the build command.
    text = (work / "regulation.toml").read_text()
    for model in ("Planner", "PID", "Pss3Plant"):
        text = text.replace(f'"{model}"', f'"../dist/{model}.fmu"')
    (work / "regulation.toml").write_text(text)
    run = subprocess.run([str(command), "run", "regulation.toml", "--quiet"], cwd=work,
                         env=env, capture_output=True, text=True)
    assert run.returncode == 2, run.stderr
    assert ("field 'fmus.planner'" in run.stderr and "Planner.fmu" in run.stderr
            and "scripts/build-fmus.sh" in run.stderr and "--fmu-dir" in run.stderr)
    assert run.stderr.count("\n") == 1 and "Traceback" not in run.stderr
