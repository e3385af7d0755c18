"""Runs ``cosim verify`` for the tests: the one place that says how the command is
invoked (in process, as the console script would, with its exit code and output).

Until the harness's dispatcher (cosim/cli.py) registers the subcommand, the command is
the package's own entry, ``python -m cosim.verify``. After that, switch here only:
``main(argv)`` -> the dispatcher's main with ``["verify", *argv]``, COMMAND ->
``[sys.executable, "-m", "cosim", "verify"]``, and ``shell`` returns its argument."""

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

from cosim.verify.__main__ import main  # noqa: E402

# The same command in a child process (exit code and stderr as a user sees them).
COMMAND = [sys.executable, "-m", "cosim.verify"]


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
    """A documented command line as the tests run it. Until the harness's dispatcher
    (cosim/cli.py) registers the verify subcommand, `cosim verify` is run as the
    package's module; after that, return `command` unchanged."""
    return command.replace("cosim verify", f"{sys.executable} -m cosim.verify")
