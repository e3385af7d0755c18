"""scripts/make_references.py reproduces every file it writes under tests/references
byte for byte (the references are regenerated, never edited by hand): its arithmetic is
exact or correctly rounded, so the bytes do not depend on the machine's CPU, BLAS or
numpy's SIMD paths (see the script's docstring for what differed before)."""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_regeneration_reproduces_the_checked_in_references_byte_for_byte(tmp_path):
    subprocess.run([sys.executable, str(ROOT / "scripts" / "make_references.py"),
                    "--out", str(tmp_path)], check=True)
    written = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*") if p.is_file())
    # Planner 3 cases x 3 files, PID 3 x 3 (+ 1 input CSV), ComputedTorque 1 x 3.
    assert len(written) == 22, written
    differing = [str(p) for p in written
                 if (tmp_path / p).read_bytes() != (ROOT / "tests" / "references" / p).read_bytes()]
    assert differing == []
