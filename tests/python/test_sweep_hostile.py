"""Hostile input to `cosim sweep` (issue 19): malformed SPECs, scenarios, tables and
arguments. Each must end with exit status 2 and one line on stderr naming the field (or
argparse's usage error for a malformed option), with no traceback, and write nothing
outside --out (the tree around it is compared before and after)."""

from __future__ import annotations

import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from robofmu.cli import main as cosim  # noqa: E402
from hostile_cases import ABSOLUTE_NAME  # noqa: E402

SCENARIO = ROOT / "scenarios" / "regulation.toml"
HEAD = f'scenario = "{SCENARIO}"\n'
GRID = "[grid.'gains.omega']\nvalues = [10]\nunit = \"rad/s\"\n"
RANDOM = ("[random.'plant.legMass']\ndistribution = \"uniform\"\nlow = 0.8\nhigh = 0.9\n"
          "unit = \"kg\"\n")

# (id, SPEC text (str) or bytes, extra arguments, text the message must contain)
CASES = [
    ("empty", "", [], "field 'scenario'"),
    ("not-toml", "scenario = [", [], "cannot read the SPEC"),
    ("non-utf8", b"scenario = \"\xff\xfe\"\n", [], "cannot read the SPEC"),
    ("scenario-number", "scenario = 5\n" + GRID, [], "field 'scenario'"),
    ("scenario-missing", "scenario = \"nowhere.toml\"\n" + GRID, [], "field 'scenario'"),
    ("scenario-garbage", "scenario = \"garbage.toml\"\n" + GRID, [], "field 'scenario'"),
    ("unknown-field", HEAD + "repeat = 3\n" + GRID, [], "unknown field 'repeat'"),
    ("name-escapes", HEAD + "name = \"../evil\"\n" + GRID, [], "field 'name'"),
    ("name-absolute", HEAD + f"name = {ABSOLUTE_NAME!r}\n" + GRID, [], "field 'name'"),
    ("name-number", HEAD + "name = 7\n" + GRID, [], "field 'name'"),
    ("grid-number", HEAD + "grid = 3\n", [], "field 'grid'"),
    ("grid-entry-number", HEAD + "[grid]\n'gains.omega' = 5\n", [], "grid.gains.omega"),
    ("steps-zero", HEAD + "[grid.'gains.omega']\nfrom = 1\nto = 2\nsteps = 0\n", [],
     "grid.gains.omega.steps"),
    ("steps-float", HEAD + "[grid.'gains.omega']\nfrom = 1\nto = 2\nsteps = 1e12\n", [],
     "grid.gains.omega.steps"),
    ("steps-huge", HEAD + "[grid.'gains.omega']\nfrom = 1\nto = 2\nsteps = 1000000000\n",
     [], "grid.gains.omega.steps"),
    ("values-empty", HEAD + "[grid.'gains.omega']\nvalues = []\n", [],
     "grid.gains.omega.values"),
    ("values-strings", HEAD + "[grid.'gains.omega']\nvalues = [\"a\"]\n", [],
     "grid.gains.omega.values"),
    ("values-nan", HEAD + "[grid.'gains.omega']\nvalues = [nan]\n", [],
     "grid.gains.omega.values"),
    ("values-inf", HEAD + "[grid.'gains.omega']\nvalues = [inf]\n", [],
     "grid.gains.omega.values"),
    ("values-bool", HEAD + "[grid.'gains.omega']\nvalues = [true]\n", [],
     "grid.gains.omega.values"),
    ("from-text", HEAD + "[grid.'gains.omega']\nfrom = \"ten\"\nto = 2\nsteps = 2\n", [],
     "grid.gains.omega.from"),
    ("unit-number", HEAD + "[grid.'gains.omega']\nvalues = [10]\nunit = 5\n", [],
     "grid.gains.omega.unit"),
    ("unit-unknown", HEAD + "[grid.'gains.omega']\nvalues = [10]\nunit = \"parsec\"\n", [],
     "gains.omega"),
    ("path-malformed", HEAD + "[grid.'gains..omega']\nvalues = [10]\n", [], "gains..omega"),
    ("path-index-out", HEAD + "[grid.'motion.waypoints[7].time']\nvalues = [1]\n", [],
     "motion.waypoints[7].time"),
    ("random-no-seed", HEAD + "samples = 2\n" + RANDOM, [], "field 'seed'"),
    ("seed-negative", HEAD + "seed = -1\nsamples = 2\n" + RANDOM, [], "field 'seed'"),
    ("seed-huge", HEAD + f"seed = {2 ** 63 + 5}\nsamples = 2\n" + RANDOM, [],
     "field 'seed'"),
    ("seed-float", HEAD + "seed = 1.5\nsamples = 2\n" + RANDOM, [], "field 'seed'"),
    ("samples-1e8", HEAD + "seed = 1\nsamples = 1e8\n" + RANDOM, [], "field 'samples'"),
    ("samples-int-huge", HEAD + "seed = 1\nsamples = 100000000\n" + RANDOM, [],
     "field 'samples'"),
    ("samples-zero", HEAD + "seed = 1\nsamples = 0\n" + RANDOM, [], "field 'samples'"),
    ("samples-without-random", HEAD + "samples = 3\n" + GRID, [], "samples"),
    ("distribution-unknown", HEAD + "seed = 1\nsamples = 2\n[random.'plant.legMass']\n"
     "distribution = \"cauchy\"\n", [], "random.plant.legMass.distribution"),
    ("sd-negative", HEAD + "seed = 1\nsamples = 2\n[random.'plant.legMass']\n"
     "distribution = \"normal\"\nmean = 1\nsd = -1\n", [], "random.plant.legMass.sd"),
    ("uniform-reversed", HEAD + "seed = 1\nsamples = 2\n[random.'plant.legMass']\n"
     "distribution = \"uniform\"\nlow = 2\nhigh = 1\n", [], "random.plant.legMass.high"),
    ("truncation-empty", HEAD + "seed = 1\nsamples = 2\n[random.'plant.legMass']\n"
     "distribution = \"normal\"\nmean = 0\nsd = 1\nmin = 100\nmax = 100.0001\n", [],
     "random.plant.legMass"),
    ("product-huge", HEAD + "[grid.'gains.omega']\nfrom = 1\nto = 2\nsteps = 2000\n"
     "[grid.'plant.legMass']\nfrom = 1\nto = 2\nsteps = 2000\n", [], "1000000"),
    ("workspace-no-path", HEAD + "[workspace]\nthx = {values = [0]}\n", [],
     "workspace.path"),
    ("workspace-unknown", HEAD + "[workspace]\npath = \"motion.waypoints[1].angles\"\n"
     "spin = 3\n", [], "workspace.spin"),
    ("workspace-axis-number", HEAD + "[workspace]\npath = \"motion.waypoints[1].angles\"\n"
     "thx = 3\nthy = {values = [0]}\nthz = {values = [0]}\n", [], "workspace.thx"),
    ("workspace-huge", HEAD + "[workspace]\npath = \"motion.waypoints[1].angles\"\n"
     "thx = {from = 0, to = 1, steps = 100}\nthy = {from = 0, to = 1, steps = 100}\n"
     "thz = {from = 0, to = 1, steps = 100}\n", [], "workspace"),
    ("fmu-dir-empty", HEAD + GRID, ["--fmu-dir", "{tmp}/nothing"], "fmus.planner"),
    ("fmu-not-zip", HEAD + GRID, ["--fmu-dir", "{tmp}/text"], "fmus.planner"),
    ("fmu-not-zip-workspace", HEAD + "[workspace]\npath = \"motion.waypoints[1].angles\"\n"
     "thx = {values = [0]}\nthy = {values = [0]}\nthz = {values = [138]}\n",
     ["--fmu-dir", "{tmp}/text"], "fmus.planner"),
    ("fmu-zip-without-description", HEAD + GRID, ["--fmu-dir", "{tmp}/zips"],
     "fmus.planner"),
    ("workers-negative", HEAD + GRID, ["--workers", "-1"], "--workers"),
    ("workers-huge", HEAD + GRID, ["--workers", "100000"], "--workers"),
    ("batch-zero", HEAD + GRID, ["--batch", "0"], "--batch"),
    ("scheduler-and-workers", HEAD + GRID, ["--scheduler", "tcp://127.0.0.1:1",
                                            "--workers", "2"], "--scheduler"),
    ("out-is-a-file", HEAD + GRID, ["--out", "{tmp}/a-file"], "--out"),
]
ARGPARSE = [("workers-text", ["--workers", "many"]), ("batch-float", ["--batch", "1.5"]),
            ("unknown-option", ["--turbo"])]


def tree(path: Path) -> dict:
    return {str(p.relative_to(path)): p.stat().st_size for p in sorted(path.rglob("*"))
            if "out" not in p.relative_to(path).parts[:1]}


def prepared(tmp_path: Path, text, name="hostile") -> Path:
    (tmp_path / "garbage.toml").write_bytes(b"\x00\x01 not a scenario [[[")
    (tmp_path / "a-file").write_text("x")
    for folder in ("text", "zips"):
        (tmp_path / folder).mkdir()
    for model in ("Planner", "PID", "Pss3Plant"):
        (tmp_path / "text" / f"{model}.fmu").write_text("not a zip archive")
        with zipfile.ZipFile(tmp_path / "zips" / f"{model}.fmu", "w") as archive:
            archive.writestr("binaries/readme.txt", "no modelDescription.xml")
    spec = tmp_path / f"{name}.toml"
    spec.write_bytes(text if isinstance(text, bytes) else text.encode())
    return spec


def main(argv: list[str]) -> int:
    """`cosim sweep ARGV`, through the command table (its one-line errors, exit codes)."""
    return cosim(["sweep", *argv])


@pytest.mark.parametrize("case, text, extra, field", CASES, ids=[c[0] for c in CASES])
def test_malformed_sweep_input_is_one_line_naming_the_field(tmp_path, capsys, case, text,
                                                            extra, field):
    spec = prepared(tmp_path, text)
    extra = [a.replace("{tmp}", str(tmp_path)) for a in extra]
    out = ["--out", str(tmp_path / "out")] if "--out" not in extra else []
    before = tree(tmp_path)
    status = main([str(spec), *out, "--quiet", *(["--workers", "0"]
                                                  if "--workers" not in extra and
                                                  "--scheduler" not in extra else []),
                   *extra])
    err = capsys.readouterr().err
    assert status == 2, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("cosim: ") and field in lines[0], err
    assert "Traceback" not in err
    assert tree(tmp_path) == before


@pytest.mark.parametrize("case, extra", ARGPARSE, ids=[c[0] for c in ARGPARSE])
def test_malformed_options_are_usage_errors(tmp_path, capsys, case, extra):
    spec = prepared(tmp_path, HEAD + GRID)
    before = tree(tmp_path)
    status = main([str(spec), "--out", str(tmp_path / "out"), *extra])
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    # the sweep's parser names `cosim sweep`; an unknown option is the top parser's
    assert status == 2 and len(lines) == 1 and lines[0].startswith("cosim: cosim")
    assert lines[0].endswith(" --help'") and "Traceback" not in err
    assert tree(tmp_path) == before


def test_resume_refuses_a_table_of_another_spec_or_not_a_table(tmp_path, capsys):
    spec = prepared(tmp_path, HEAD + GRID, name="t")
    (tmp_path / "out").mkdir()
    for content in (b"run_id,other\n", b"\xff\xfe\x00garbage"):
        (tmp_path / "out" / "t.csv").write_bytes(content)
        status = main([str(spec), "--out", str(tmp_path / "out"), "--workers", "0",
                       "--resume", "--quiet"])
        err = capsys.readouterr().err.strip().splitlines()
        assert status == 2 and len(err) == 1 and "t.csv" in err[0] and "--resume" in err[0]
