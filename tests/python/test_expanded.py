"""One implementation of the scenario rules: the hand-written scenarios are resolved by
the harness (robofmu/closed_loop.py, units.py, design.py) and the Rust reference reads
their expanded form, committed in tests/scenarios/expanded/. Truths: (1) the committed
files are what `cosim check --expanded` writes now (every number to 1e-12 relative: the
gain design runs on the plant FMU); (2) the harness runs an expanded file and its
hand-written source to the same bits."""

from __future__ import annotations

import json
import math
import sys
import tomllib
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from robofmu.cli import main  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
EXPANDED = ROOT / "tests" / "scenarios" / "expanded"
NAMES = sorted(p.stem for p in EXPANDED.glob("*.toml"))


def _close(a, b, where: str) -> None:
    if isinstance(a, dict):
        assert set(a) == set(b), where
        for k in a:
            _close(a[k], b[k], f"{where}.{k}")
    elif isinstance(a, list):
        assert len(a) == len(b), where
        for k, (x, y) in enumerate(zip(a, b)):
            _close(x, y, f"{where}[{k}]")
    elif isinstance(a, float):
        assert math.isclose(a, b, rel_tol=1e-12, abs_tol=1e-300), (where, a, b)
    else:
        assert a == b, (where, a, b)


@pytest.mark.parametrize("name", NAMES)
def test_the_committed_expansion_is_the_harness_expansion(name, tmp_path, capsys):
    assert len(NAMES) == 9  # every scenario of scenarios/ but heavy_platform (plant parameters)
    fresh = tmp_path / f"{name}.toml"
    assert main(["check", str(ROOT / "scenarios" / f"{name}.toml"), "--expanded",
                 str(fresh)]) == 0
    got = tomllib.loads(fresh.read_text())
    committed = tomllib.loads((EXPANDED / f"{name}.toml").read_text())
    committed.pop("fmus"), got.pop("fmus")  # paths relative to different folders
    _close(committed, got, name)


def test_an_expanded_multi_segment_run_equals_its_hand_written_source(tmp_path, capsys):
    for source in (ROOT / "scenarios" / "three_axis_waypoints.toml",
                   EXPANDED / "three_axis_waypoints.toml"):
        out = tmp_path / source.parent.name
        assert main(["run", str(source), "--out", str(out), "--quiet", "--no-plots"]) == 0
    a = (tmp_path / "scenarios" / "three_axis_waypoints.csv").read_bytes()
    b = (tmp_path / "expanded" / "three_axis_waypoints.csv").read_bytes()
    assert a == b and len(a) > 100_000


def test_the_description_is_kept_through_the_expansion(tmp_path, capsys):
    # Truth: the text given in the hand-written scenario, unchanged in the expanded form
    # and again in the expansion of that expanded form.
    text = "Three axes, with \"quotes\" and a \\ backslash"
    source = tomllib.loads((ROOT / "scenarios" / "three_axis_waypoints.toml").read_text())
    from robofmu.scenario import fmu_file  # the FMU files the entries name, as absolute paths
    source["fmus"] = {a: str(fmu_file(a, p, ROOT / "scenarios"))
                      for a, p in source["fmus"].items()}
    source["description"] = text
    path = tmp_path / "described.json"
    path.write_text(json.dumps(source))
    first, second = tmp_path / "first.toml", tmp_path / "second.toml"
    assert main(["check", str(path), "--expanded", str(first)]) == 0
    assert main(["check", str(first), "--expanded", str(second)]) == 0
    for expanded in (first, second):
        assert tomllib.loads(expanded.read_text())["description"] == text
