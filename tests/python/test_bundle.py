"""Bundled FMUs by name (robofmu.bundle, scenario FMU entries without .fmu) and the
commands that list them. Truth: the files under dist/ that scripts/build-fmus.sh writes
(in a checkout the bundle is the repository's dist/, tests/references/, scenarios/)."""

from pathlib import Path

import pytest

from robofmu import bundle
from robofmu.cli import main
from robofmu.errors import ScenarioError
from robofmu.scenario import fmu_file, parse_document, read_document

ROOT = Path(__file__).resolve().parents[2]


def test_the_bundle_of_a_checkout_is_dist_and_its_names_carry_the_variant():
    assert not bundle.installed()
    found = bundle.fmus()
    expected = {("" if folder == "." else f"{folder}/") + p.stem: p.resolve()
                for folder in (".", "fmi3", "fmi3-scalar")
                for p in (ROOT / "dist" / folder).glob("*.fmu")}
    assert {n: p.resolve() for n, p in found.items()} == expected and len(found) == 12
    assert bundle.fmu("fmi3/Pss3Plant") == ROOT / "dist" / "fmi3" / "Pss3Plant.fmu"
    assert bundle.fmu("Pss3Plant.fmu") is None
    assert set(bundle.references()) >= {"PID/defaults", "Pss3Plant/path1"}
    assert bundle.scenarios()["regulation"] == ROOT / "scenarios" / "regulation.toml"


def test_a_scenario_names_bundled_fmus_and_a_wrong_name_is_refused_by_field(tmp_path):
    data = read_document(ROOT / "scenarios" / "regulation.toml")
    assert data["fmus"]["plant"] == "Pss3Plant"
    # Away from the repository: the names still find dist/'s files.
    scenario = parse_document(data, tmp_path)
    assert Path(scenario.fmus["plant"]) == ROOT / "dist" / "Pss3Plant.fmu"
    # --fmu-dir: the name's file there.
    assert fmu_file("plant", "fmi3/Pss3Plant", tmp_path, tmp_path / "mine") == \
        tmp_path / "mine" / "fmi3" / "Pss3Plant.fmu"
    with pytest.raises(ScenarioError) as error:
        parse_document(dict(data, fmus=dict(data["fmus"], plant="Pss3")), tmp_path)
    message = str(error.value)
    assert message.startswith("field 'fmus.plant': 'Pss3' is not a bundled FMU (bundled: ")
    assert "fmi3/Pss3Plant" in message and message.endswith("or a path to an .fmu file")


def test_fmus_and_examples_print_paths_other_tools_can_use(capsys):
    assert main(["fmus", "--path", "PID"]) == 0
    assert capsys.readouterr().out == f"{ROOT / 'dist' / 'PID.fmu'}\n"
    assert main(["examples", "--path", "Pss3Plant/path1"]) == 0
    assert capsys.readouterr().out == f"{ROOT / 'tests' / 'references' / 'Pss3Plant' / 'path1'}\n"
    assert main(["fmus"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 12 and all(" version " in line for line in lines)
    assert main(["fmus", "--path", "Nope"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("cosim: --path: 'Nope' is not a bundled FMU") and err.count("\n") == 1


def test_without_the_native_kernel_one_line_names_the_platform_and_nothing_runs(tmp_path):
    # The master has one stepping loop, the native kernel (docs/co-simulation-master.md):
    # a wheel on a platform it ships no kernel for must say so in one line, not fall back
    # to another loop and not trace back.
    import os
    import subprocess
    import sys

    from robofmu.loop import PLATFORM
    env = dict(os.environ, COSIM_KERNEL_LIBRARY=str(tmp_path / "no_such_kernel.so"))
    run = subprocess.run([sys.executable, "-m", "robofmu", "run",
                          str(ROOT / "scenarios" / "regulation.toml"), "--quiet", "--no-plots",
                          "--out", str(tmp_path / "out")], capture_output=True, text=True, env=env)
    assert run.returncode != 0
    assert run.stderr.count("\n") == 1, run.stderr
    assert run.stderr.startswith("cosim: ") and f"no stepping loop for {PLATFORM}: " in run.stderr
    assert "COSIM_KERNEL_LIBRARY" in run.stderr  # the way out
    assert not (tmp_path / "out" / "regulation.csv").exists()
