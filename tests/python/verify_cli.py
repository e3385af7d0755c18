"""Runs ``cosim verify`` for the tests: the one place that says how the command is
invoked (in process, as the console script would, with its exit code and output).

The command runs through the harness's dispatcher (robofmu/cli.py), in process and as
``python -m robofmu verify``."""

from __future__ import annotations

import contextlib
import io
import json
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from robofmu.cli import main as dispatch  # noqa: E402

# The same command in a child process (exit code and stderr as a user sees them).
COMMAND = [sys.executable, "-m", "robofmu", "verify"]


def main(argv) -> int:
    """``cosim verify ARGV...`` through the harness's dispatcher (robofmu/cli.py)."""
    return dispatch(["verify", *argv])


@dataclass
class Outcome:
    code: int
    out: str
    err: str

    def report(self, out_dir: Path) -> dict:
        return json.loads((Path(out_dir) / "verify.json").read_text())


def verify(*args) -> Outcome:
    """``cosim verify ARGS...`` in this process."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main([str(a) for a in args])
        except SystemExit as e:  # argparse's usage errors
            code = e.code
    return Outcome(code, out.getvalue(), err.getvalue())


def verify_process(*args, cwd=ROOT) -> Outcome:
    """``cosim verify ARGS...`` as a child process."""
    done = subprocess.run(COMMAND + [str(a) for a in args], cwd=cwd, capture_output=True,
                          text=True)
    return Outcome(done.returncode, done.stdout, done.stderr)


def shell(command: str) -> str:
    """A documented command line as the tests run it: `cosim verify` through this
    interpreter's dispatcher (`python -m robofmu verify`, the console script's function)."""
    return command.replace("cosim verify", f"{sys.executable} -m robofmu verify")
